"""Independent reference values for the dynamics problems (numpy only).

Run:  python tests/data/independent/dynamics.py

Each ``case_*`` function returns {objective_id: value} for one problem of problems/, in that
objective's unit (vectors as [x, y, z] in the objective's frame, symbolic objectives as
sympy-syntax strings). The solver writes Newton-Euler balances about each body's mass centre
with the reactions as unknowns; every value here comes by another route: Lagrange's equations
from hand-written T and V, moments about a fixed pin with the parallel-axis theorem applied by
hand, whole-system balances, polar acceleration formulas. Nothing here imports mechgrade or
sympy.
"""

import numpy as np

DEG = np.pi / 180.0


def case_pendulum_pin_reaction():
    m, L, g, th, w = 2.0, 1.2, 9.81, 40 * DEG, 3.0
    I_O = m * L**2 / 12 + m * (L / 2) ** 2  # parallel axis by hand: m L^2 / 3
    alpha = -m * g * (L / 2) * np.sin(th) / I_O  # moments about the fixed pin
    r = np.array([L / 2 * np.sin(th), -L / 2 * np.cos(th)])  # G from O
    a_G = alpha * np.array([-r[1], r[0]]) - w**2 * r
    R = m * a_G - m * np.array([0.0, -g])
    e_rod_up = np.array([-np.sin(th), np.cos(th)])  # B.y
    return {"alpha": alpha, "pin_force": [R[0], R[1], 0.0],
            "pin_force_along_rod": float(R @ e_rod_up),
            "eom_symbolic": "-3*g*sin(theta)/(2*L)"}


def case_atwood_machine():
    m1, m2, g = 3.0, 5.0, 9.81
    a = (m2 - m1) * g / (m1 + m2)  # the whole string-and-blocks system
    T = m1 * (g + a)  # block 1 alone
    return {"a1": a, "tension": T, "a1_symbolic": "g*(m2 - m1)/(m1 + m2)",
            "tension_symbolic": "2*m1*m2*g/(m1 + m2)"}


def case_block_on_turntable():
    m, r, g, w, alpha = 0.5, 0.3, 9.81, 4.0, 2.0
    a_r, a_t = -r * w**2, r * alpha  # polar components of the acceleration
    F = m * np.array([a_r, a_t])  # friction is the only horizontal force
    N = m * g
    return {"friction_B": [F[0], F[1], 0.0], "normal": N,
            "mu_needed": float(np.hypot(*F) / N),
            "mu_needed_symbolic": "r*sqrt(phid**4 + phidd**2)/g"}


def case_block_sliding_down_incline():
    m, g, beta, mu = 4.0, 9.81, 30 * DEG, 0.25
    N = m * g * np.cos(beta)
    F = -mu * N  # opposes the downhill slip
    return {"accel": g * np.sin(beta) + F / m, "normal": N, "friction": [F, 0.0, 0.0],
            "accel_symbolic": "g*(sin(beta) - mu_k*cos(beta)*sign(xd))"}


def case_two_mass_spring_chain():
    m1, m2, k1, k2, L1, L2, c = 2.0, 1.0, 100.0, 50.0, 0.5, 0.8, 4.0
    x1, x2, v1, v2 = 0.6, 1.5, 0.5, -0.2
    # Lagrange with V = k1 (x1-L1)^2/2 + k2 (x2-x1-L2)^2/2 and Rayleigh D = c (v2-v1)^2/2
    dV = np.array([k1 * (x1 - L1) - k2 * (x2 - x1 - L2), k2 * (x2 - x1 - L2)])
    dD = np.array([-c * (v2 - v1), c * (v2 - v1)])
    a = -(dV + dD) / np.array([m1, m2])
    return {"a1": a[0], "a2": a[1], "spring2_on_block1": [k2 * (x2 - x1 - L2), 0.0, 0.0],
            "spring1_energy": k1 * (x1 - L1) ** 2 / 2, "ke2": m2 * v2**2 / 2,
            "damper_power": -c * (v2 - v1) ** 2, "momentum": [m1 * v1, 0.0, 0.0],
            **_chain_modes(m1, m2, k1, k2), **_chain_damping(m1, m2, k1, k2, c)}


def case_cart_pendulum_spring_modes():
    M, m, L, k, x0, g = 2.0, 0.5, 0.8, 50.0, 1.0, 9.81
    x, th, w = 1.1, 20 * DEG, 1.5  # the cart's speed (0.4 m/s) enters no answer
    # Lagrange with T = (M+m) x'^2/2 + m L x' th' cos th + m L^2 th'^2/2,
    # V = k (x-x0)^2/2 - m g L cos th: a 2x2 linear system in x'' and th''
    mass = np.array([[M + m, m * L * np.cos(th)], [m * L * np.cos(th), m * L * L]])
    rhs = np.array([m * L * np.sin(th) * w**2 - k * (x - x0), -m * g * L * np.sin(th)])
    xdd, thdd = np.linalg.solve(mass, rhs)
    # the bob's acceleration along the rod (toward the pin): -x'' sin th + L th'^2
    tension = m * (-xdd * np.sin(th) + L * w**2) + m * g * np.cos(th)
    # small oscillations about x = x0, th = 0: mass and stiffness matrices at rest there,
    # the generalized eigenproblem through the Cholesky factor of the mass matrix
    mass0 = np.array([[M + m, m * L], [m * L, m * L * L]])
    stiff0 = np.diag([k, m * g * L])
    chol = np.linalg.cholesky(mass0)
    inverse = np.linalg.inv(chol)
    w2 = np.linalg.eigvalsh(inverse @ stiff0 @ inverse.T)
    return {"cart_acceleration": xdd, "alpha": thdd, "rod_force": tension,
            "omega_1": np.sqrt(w2[0]), "omega_2": np.sqrt(w2[1])}


def _chain_damping(m1, m2, k1, k2, c):
    # the damper between the blocks is not proportional damping: the quadratic eigenproblem
    # (l^2 M + l C + K) phi = 0 as the pencil [[C, M], [M, 0]] l z = [[-K, 0], [0, M]] z
    M = np.diag([m1, m2])
    K = np.array([[k1 + k2, -k2], [-k2, k2]])
    C = c * np.array([[1.0, -1.0], [-1.0, 1.0]])
    Z = np.zeros((2, 2))
    roots = np.linalg.eigvals(np.linalg.solve(np.block([[C, M], [M, Z]]),
                                              np.block([[-K, Z], [Z, M]])))
    upper = sorted((r for r in roots if r.imag > 0), key=abs)
    return {"zeta_1": -upper[0].real / abs(upper[0]), "zeta_2": -upper[1].real / abs(upper[1])}


def _chain_modes(m1, m2, k1, k2):
    # M x'' + K x = 0 about the equilibrium, K from V's second derivatives by hand;
    # numpy's symmetric generalized eigenproblem through M^(-1/2) K M^(-1/2)
    M = np.diag([m1, m2])
    K = np.array([[k1 + k2, -k2], [-k2, k2]])
    root = np.diag(1 / np.sqrt(np.diag(M)))
    w2, u = np.linalg.eigh(root @ K @ root)
    shapes = root @ u
    ratio = shapes[1] / shapes[0]
    return {"omega_1": np.sqrt(w2[0]), "omega_2": np.sqrt(w2[1]), "mode_1_ratio": ratio[0],
            "mode_2_ratio": ratio[1]}


def case_ruina_9_19_falling_ladder():
    m, L, g, th0, th = 10.0, 4.0, 9.81, 80 * DEG, 60 * DEG
    # Lagrange: T = m L^2 thd^2 / 6 (centre speed L thd / 2 plus spin), V = m g L sin(th) / 2;
    # energy from rest at th0 (theta decreases)
    thd = -np.sqrt(3 * g * (np.sin(th0) - np.sin(th)) / L)
    thdd = -(m * g * L / 2 * np.cos(th)) / (m * L**2 / 3)
    # the reactions are the only horizontal / the vertical forces besides gravity
    xdd = -L / 2 * (np.sin(th) * thdd + np.cos(th) * thd**2)
    ydd = L / 2 * (np.cos(th) * thdd - np.sin(th) * thd**2)
    # symbolic forms with g, L > 0 split out: the comparison samples signed symbols; the
    # ladder's angle from +x is pi - theta, so omega_z = -theta'
    rate = "sqrt(3)*sqrt(g)*sqrt(sin(theta0) - sin(theta))/sqrt(L)"
    return {"G_path_radius": "L/2", "eom_thetaddot": "-3*g*cos(theta)/(2*L)",
            "thetadot_of_theta": "-" + rate, "omega_z_of_theta": rate,
            "N1_wall": "m*cos(theta)*(3*g*sin(theta) - 2*L*thetad**2)/4",
            "N2_floor": "m*(g + 3*g*sin(theta)**2 - 2*L*thetad**2*sin(theta))/4",
            # by hand: L thd^2 = 3 g (sin th0 - sin th) put into the two reactions above
            "N1_wall_of_theta": "3*m*g*cos(theta)*(3*sin(theta) - 2*sin(theta0))/4",
            "N2_floor_of_theta": "m*g*(1 + 9*sin(theta)**2 - 6*sin(theta)*sin(theta0))/4",
            "thetaddot_now": thdd, "reactions_now": [m * xdd, m * (ydd + g), 0.0]}


def case_ruina_9_21_wheel_incline():
    m, M, r, g, th = 1.0, 2.0, 0.1, 9.81, 30 * DEG
    mass = m + 2 * M
    # Lagrange in x with phi' = -x'/r: (mass + I/r^2) x'' = mass g sin(th), I = m r^2/2 + M R^2;
    # a = 0.2 g  =>  I/r^2 = mass (sin(th)/0.2 - 1)
    I = mass * (np.sin(th) / 0.2 - 1) * r**2
    R = np.sqrt((I - m * r**2 / 2) / M)
    a = 0.2 * g
    return {"aG_symbolic": "(m + 2*M)*g*sin(theta)/(m + 2*M + (m*r**2/2 + M*R**2)/r**2)",
            "R_min": R,
            "contact_force": [mass * a - mass * g * np.sin(th), mass * g * np.cos(th), 0.0]}

def case_ruina_9_20_ladder_energy():
    # energy: m g (L/2) (sin th0 - sin th) = (m L^2 / 6) thd^2, v_G = (L/2) |thd|
    th0, th = 80 * DEG, 45 * DEG  # with g = L = 1
    thd2 = 3 * (np.sin(th0) - np.sin(th))
    return {"vG_over_sqrt_gL": 0.5 * np.sqrt(thd2),
            "eom_thetaddot": "-3*g*cos(theta)/(2*L)",
            # written with g, L > 0 split out: the comparison samples signed symbols
            "vG_symbolic": "sqrt(3)*sqrt(g)*sqrt(L)*sqrt(sin(theta0) - sin(theta))/2",
            # N1 = m x_G'' with L thd^2 = 3 g (sin th0 - sin th)
            "N1_wall": "3*m*g*cos(theta)*(3*sin(theta) - 2*sin(theta0))/4",
            # where the wall lets go: N1 = m x_G'' from the centre's acceleration, with the
            # rate from energy and theta'' from Lagrange, bisected below the release angle
            "theta_wall_lost": "asin(2*sin(theta0)/3)",
            "theta_wall_lost_deg": _wall_lost(th0) / DEG,
            "vG_wall_lost": 0.5 * np.sqrt(3 * (np.sin(th0) - np.sin(_wall_lost(th0))))}


def _wall_lost(th0, g=1.0, L=1.0):
    """The angle below th0 where the ladder's wall reaction m x_G'' first vanishes."""
    def wall(th):
        thd = -np.sqrt(3 * g * (np.sin(th0) - np.sin(th)) / L)
        thdd = -3 * g * np.cos(th) / (2 * L)
        return -L / 2 * (np.sin(th) * thdd + np.cos(th) * thd**2)  # x_G'' (m = 1)

    return _bisect(wall, th0 - 1e-9, 0.0)


def case_ruina_9_23_ball_impulse_momentum():
    m, r, g, v0 = 1.0, 0.1, 9.8, 5.0
    I = 2 * m * r**2 / 5

    def rolling(mu):
        # angular impulse about the contact point is zero: m v0 r = m v r + I v / r
        v = m * v0 * r / (m * r + I / r)
        t = (v0 - v) / (mu * g)  # linear impulse of the friction force
        return t, v, v0 * t - mu * g * t**2 / 2

    t, v, x = rolling(0.12)
    return {"t_star": t, "v_at_t_star": v, "omega_at_t_star_z": -v / r,
            "distance_to_pure_rolling": x, "t_star_if_mu_0p2": rolling(0.2)[0]}


def case_ladder_wall_lift_off():
    m, L, g, th0 = 12.0, 4.0, 9.81, 80 * DEG
    # N1 = (3/4) m g cos(th) (3 sin th - 2 sin th0) (Sample 9.19) vanishes at sin th = 2/3 sin th0
    th = np.arcsin(2 * np.sin(th0) / 3)
    thd = -np.sqrt(3 * g * (np.sin(th0) - np.sin(th)) / L)  # energy from rest
    N2 = m * (g + 3 * g * np.sin(th) ** 2 - 2 * L * thd**2 * np.sin(th)) / 4
    return {"theta_wall_contact_lost_deg": th / DEG, "thetad_at_lift_off": thd,
            "floor_reaction": N2, "energy_at_lift_off": m * g * L / 2 * np.sin(th0)}


def case_damped_pendulum_vibration():
    m, L, g, c = 1.5, 0.8, 9.81, 0.6
    # about the pin: (m L^2/3) th'' = -(m g L/2) sin th - c L^2 th' (the horizontal dashpot
    # at the tip stretches at -L th' near th = 0): linearised k = 3g/(2L), c_eff = 3c/m
    wn = np.sqrt(3 * g / (2 * L))
    zeta = 3 * c / m / (2 * wn)
    # symbolic forms with g, L > 0 split out: the comparison samples signed symbols
    return {"omega_n": wn, "zeta": zeta,
            "damped_period": 2 * np.pi / (wn * np.sqrt(1 - zeta**2)),
            "omega_n_symbolic": "sqrt(6)*sqrt(g)/(2*sqrt(L))",
            "zeta_symbolic": "sqrt(6)*sqrt(L)*c/(2*sqrt(g)*m)"}


def case_ruina_9_26_billiard_cue():
    m, r, d, v = 0.2, 0.03, 0.01, 1.0
    P = m * v  # linear impulse = change of linear momentum
    # angular impulse about the centre: the cue above the centre spins the ball clockwise
    omega = -P * d / (2 * m * r**2 / 5)
    return {"omega_z": omega, "impulse": P, "omega_symbolic": "-5*d*v/(2*r**2)"}


def case_rod_strikes_ledge():
    m, L, v0, e = 3.0, 1.2, 4.0, 0.5
    # P = m (vG' + v0); (m L^2/12) w' = -(L/2) P; end A: vG' - (L/2) w' = e v0
    # => vG' + 3 (vG' + v0) = e v0
    vG = (e * v0 - 3 * v0) / 4
    P = m * (vG + v0)
    w = -(L / 2) * P / (m * L**2 / 12)
    return {"vG_after": vG, "omega_after": w, "impulse": [0.0, P, 0.0],
            "omega_symbolic": "-3*v0*(1 + e)/(2*L)"}


def case_yo_yo_unwinding():
    m, k, r, g, yd = 0.2, 0.03, 0.01, 9.81, -0.5
    # about the string point S (the instantaneous centre, moving with G's acceleration
    # parallel to GS = 0): (m k^2 + m r^2) phi'' = m g r, y'' = r phi''
    a = -g * r**2 / (k**2 + r**2)
    T = m * (g + a)
    return {"accel": a, "tension": T, "tension_symbolic": "m*g*k**2/(k**2 + r**2)",
            "spin_momentum": [0.0, 0.0, m * k**2 * yd / r]}


def case_car_braking_weight_transfer():
    m, g, h, a, b, mu = 1200.0, 9.81, 0.55, 1.1, 1.5, 0.8
    # moments about the rear contact (the car does not pitch): N_F (a + b) - m g b = m a_x h
    ax = -mu * g  # all wheels slide: friction mu (N_F + N_R) = mu m g
    NF = (m * g * b - m * ax * h) / (a + b)
    return {"decel": ax, "front_normal": NF, "rear_normal": m * g - NF,
            "front_share_symbolic": "m*g*(b + mu*h*sign(xd))/(a + b)"}


def case_block_slides_on_cart():
    m, M, mu, g, v0 = 2.0, 8.0, 0.3, 9.81, 5.0
    # momentum of block + cart is conserved (friction is internal, the floor smooth);
    # the relative speed falls at mu g (1 + m/M); energy: mu m g d = KE lost
    v = m * v0 / (m + M)
    rate = mu * g * (1 + m / M)
    lost = m * v0**2 / 2 - (m + M) * v**2 / 2
    return {"t_slide": v0 / rate, "t_slide_symbolic": "v0/(mu*g*(1 + m/M))", "common_speed": v, "slide_distance": lost / (mu * m * g),
            "energy_lost": lost, "friction_on_block": [-mu * m * g, 0.0, 0.0],
            "cart_acceleration": mu * m * g / M}


def case_flywheel_speed_drop():
    m, M, T, w0 = 500.0, 1500.0, 0.2, 300 * 2 * np.pi / 60
    # angular impulse about the axle: I (w0 - w1) = M T with w1 = 0.9 w0; I = m R^2 / 2
    I = M * T / (0.1 * w0)
    w1 = 0.9 * w0
    return {"R_needed": np.sqrt(2 * I / m), "speed_after": w1 * 60 / (2 * np.pi),
            "energy_taken": I * (w0**2 - w1**2) / 2,  # = the punch's work M * angle
            "turns_during_stroke": (w0 + w1) / 2 * T / DEG}


def case_ruina_9_24_momentum_projection():
    # e_n . i = -sin(theta), e_n . j = cos(theta), e_t . i = cos(theta), e_t . j = sin(theta);
    # before: m2 (-v0 j); after: m1 v1p i + m2 (v2t e_t + v2n e_n)
    return {"en_equation_residual": "-m2*v0*cos(theta) + m1*v1p*sin(theta) - m2*v2n",
            "et_equation_residual": "-m2*v0*sin(theta) - m1*v1p*cos(theta) - m2*v2t"}


def case_ruina_9_25_units_matrix():
    v0, th, m1, m2 = 20.0, 60 * DEG, 20.0, 5.0  # ft/s, lbm: the equations are homogeneous
    # the book's scaled system: rows divided by m1, by m2, and the given v2t = -v0 sin(theta)
    A = np.array([[-np.sin(th), 0.0, m2 / m1],
                  [m1 / m2 * np.cos(th), 1.0, 0.0],
                  [0.0, 1.0, 0.0]])
    b = np.array([-m2 / m1 * v0 * np.cos(th), -v0 * np.sin(th), -v0 * np.sin(th)])
    v1p, v2t, v2n = np.linalg.solve(A, b)
    e_t, e_n = np.array([np.cos(th), np.sin(th)]), np.array([-np.sin(th), np.cos(th)])
    v2 = v2t * e_t + v2n * e_n
    return {"v1p": v1p, "v2t": v2t, "v2n": v2n, "v2_N": [v2[0], v2[1], 0.0]}


def case_rod_struck_on_ice():
    m, L, J = 1.5, 1.2, 3.0
    # linear impulse: m vG = J; angular impulse about G: (m L^2/12) w = (L/2) J
    vG = J / m
    w = (L / 2) * J / (m * L**2 / 12)
    # the point at rest: vG + w x r = 0 along the rod, r = -vG / w (behind the centre)
    return {"vG_after": [0.0, vG, 0.0], "omega_after": w, "vB_after": [0.0, vG - w * L / 2, 0.0],
            "point_at_rest": [-vG / w, 0.0, 0.0], "omega_symbolic": "6*J/(m*L)"}


def case_ruina_9_22_marble_bowling_ball():
    v0, mu, g, r, R = 3.0, 0.1, 9.81, 0.01, 0.16

    def rolling(radius, mass):
        # angular momentum about the contact point is conserved while sliding (friction and
        # the normal force pass through it): m v0 r = m v r + (2/5) m r^2 v / r
        v = mass * v0 * radius / (mass * radius + 0.4 * mass * radius)
        return (v0 - v) / (mu * g), v  # linear impulse of mu m g

    t_marble, _v = rolling(r, 0.005)
    t_bowling, _ = rolling(R, 20.48)
    return {"t_star": "2*v0/(7*mu*g)", "v_at_t_star": "5*v0/7",
            "ratio_t_star_bowling_over_marble": t_bowling / t_marble, "t_star_s": t_marble,
            "bowling_ball_slip_at_t_star": 0.0}


def case_bead_on_rotating_hoop():
    m, R, g, th = 0.1, 0.5, 9.81, 60 * DEG
    # Lagrange: T = m (R^2 th'^2 + R^2 sin^2(th) W^2)/2, V = -m g R cos(th)
    #   => th'' = sin(th) (W^2 cos(th) - g/R); at rest at th: W^2 = g/(R cos th)
    W = np.sqrt(g / (R * np.cos(th)))
    # d(th'')/d(th) at th: W^2 cos(2 th) - (g/R) cos(th) = -W^2 sin^2(th)
    wn = W * np.sin(th)
    a = W**2 * R * np.sin(th)  # centripetal, horizontal
    return {"eom_symbolic": "sin(theta)*(Omega**2*cos(theta) - g/R)", "Omega_for_60": W,
            "omega_small_oscillations": wn, "hoop_force": m * np.hypot(a, g)}


def case_cord_over_table_pulley():
    mA, mB, mu, g = 4.0, 2.0, 0.2, 9.81
    # the two blocks and the cord as one system along the cord: m_B g - mu m_A g = (m_A + m_B) a
    a = (mB - mu * mA) * g / (mA + mB)
    T = mB * (g - a)  # block B alone: m_B g - T = m_B a
    return {"accel": a, "tension": T, "friction": [-mu * mA * g, 0.0, 0.0],
            "accel_symbolic": "g*(m_B - mu_k*m_A*sign(xd))/(m_A + m_B)"}


def case_gyroscope_pivot_precession():
    m, r, L, g, spin = 1.5, 0.06, 0.10, 9.81, 250.0
    # the moment of the weight about the pivot turns the spin's angular momentum:
    # m g L = I_s spin Omega, I_s = m r^2 / 2 about the axle
    Omega = m * g * L / (0.5 * m * r**2 * spin)
    # G moves on a horizontal circle of radius L: the pivot holds the weight and gives m L W^2
    return {"precession_rate": Omega, "pivot_force": [-m * L * Omega**2, m * g, 0.0],
            "spin_rate_change": 0.0}


def case_pendulum_in_accelerating_truck():
    m, L, g, a0 = 0.5, 0.8, 9.81, 3.0
    # in the truck's (translating) frame the bob feels g down and -a0 backwards:
    # L th'' = -g sin(th) - a0 cos(th); the cord takes the radial part, th' = 0
    th = 0.0
    alpha = -(g * np.sin(th) + a0 * np.cos(th)) / L
    T = m * (g * np.cos(th) - a0 * np.sin(th))
    return {"alpha": alpha, "tension": T, "acc_in_truck": [L * alpha, 0.0, 0.0],
            "alpha_symbolic": "-(g*sin(theta) + Xdd*cos(theta))/L"}


def _damped_free_response(m, k, c, v0):
    """x(t), x'(t) of an underdamped mass-spring-damper started at x = 0 with x' = v0:
    x = v0/wd exp(-zeta wn t) sin(wd t), from the characteristic roots by hand."""
    wn = np.sqrt(k / m)
    zeta = c / (2 * m * wn)
    wd = wn * np.sqrt(1 - zeta**2)
    s = zeta * wn

    def x(t):
        return v0 / wd * np.exp(-s * t) * np.sin(wd * t)

    def v(t):
        return v0 / wd * np.exp(-s * t) * (wd * np.cos(wd * t) - s * np.sin(wd * t))

    return x, v, wd, s


def _bisect(f, a, b):
    fa = f(a)
    for _ in range(200):
        mid = (a + b) / 2
        if (f(mid) > 0) == (fa > 0):
            a, fa = mid, f(mid)
        else:
            b = mid
    return (a + b) / 2


def case_damped_block_positions():
    m, k, c, v0 = 5.0, 2000.0, 40.0, 1.0
    x, v, wd, s = _damped_free_response(m, k, c, v0)
    back = np.pi / wd  # the next zero of sin(wd t) after the start
    peak = np.arctan(wd / s) / wd  # x' = 0: tan(wd t) = wd / s
    # x rises monotonically to the peak: 20 mm is crossed once before it
    t20 = _bisect(lambda t: x(t) - 0.02, 0.0, peak)
    _, v_half, wd_half, _ = _damped_free_response(m, k, c / 2, v0)
    return {"time_back": back * 1e3, "x_at_30ms": x(0.03) * 1e3,
            "time_to_20mm": t20 * 1e3, "speed_at_20mm": abs(v(t20)),
            "spring_force_at_30ms": k * abs(x(0.03)), "peak_displacement": x(peak) * 1e3,
            "speed_back_half_damping": abs(v_half(np.pi / wd_half))}


def case_ballistic_pendulum_energy_lost():
    m, M, v0 = 0.010, 2.0, 400.0
    # the cord is vertical and the bullet moves along it at right angles: the horizontal
    # momentum of bullet + block is conserved through the impact, and they move together
    v = m * v0 / (m + M)
    before = m * v0**2 / 2
    after = (m + M) * v**2 / 2
    return {"speed_after": v, "bullet_ke_before": before, "ke_lost": before - after,
            "share_lost": (before - after) / before,
            "ke_lost_symbolic": "m*M*v0**2/(2*(m + M))",
            "impulse_on_bullet": [m * (v - v0), 0.0, 0.0]}


def case_ball_thrown_with_drag_apex_and_landing():
    m, c, g, v0, alpha = 0.2, 0.04, 9.81, 20.0, 50 * DEG
    tau = m / c  # m v' = -m g j - c v: each component relaxes with the time constant m/c
    u0, w0 = v0 * np.cos(alpha), v0 * np.sin(alpha)

    def x(t):
        return u0 * tau * (1 - np.exp(-t / tau))

    def y(t):
        return tau * (w0 + g * tau) * (1 - np.exp(-t / tau)) - g * tau * t

    def velocity(t):
        return np.array([u0 * np.exp(-t / tau), (w0 + g * tau) * np.exp(-t / tau) - g * tau])

    apex = tau * np.log(1 + w0 / (g * tau))  # y' = 0
    # y falls from the apex and is negative by 2 * (the time to fall from rest without drag
    # from a height v0^2 / g): the landing is the one root between
    landing = _bisect(y, apex, apex + 2 * np.sqrt(2 * v0**2 / g / g))
    return {"time_of_flight": landing, "range": x(landing),
            "landing_speed": float(np.hypot(*velocity(landing))), "apex_time": apex,
            "apex_height": y(apex), "position_at_1s": [x(1.0), y(1.0), 0.0]}


def case_bowling_ball_skids_then_rolls():
    m, R, g, beta, mu_k, v0, w0 = 7.2, 0.109, 9.81, 10 * DEG, 0.12, 6.0, 20.0
    N = m * g * np.cos(beta)
    # skidding: the contact slips up the slope (v + R w > 0), so kinetic friction mu_k N acts
    # down it; moments about the centre spin the backspin down: (2/5) m R^2 w' = -mu_k N R
    a1 = -g * np.sin(beta) - mu_k * N / m
    alpha1 = -mu_k * N * R / (0.4 * m * R**2)
    t1 = (v0 + R * w0) / -(a1 + R * alpha1)  # the slip speed falls at a constant rate
    v1 = v0 + a1 * t1
    x1 = v0 * t1 + a1 * t1**2 / 2
    # rolling: moments about the contact point (the normal force and friction pass through
    # it), (2/5 m R^2 + m R^2) a / R = -m g R sin(beta); friction from the centre's balance
    a2 = -g * np.sin(beta) / 1.4
    F2 = m * (a2 + g * np.sin(beta))
    t = 2.0 - t1
    t_top = t1 - v1 / a2
    return {"t_rolls": t1, "v_rolls": v1, "x_at_2s": x1 + v1 * t + a2 * t**2 / 2,
            "v_at_2s": v1 + a2 * t, "friction_at_2s": F2, "t_top": t_top,
            "x_top": x1 - v1**2 / (2 * a2)}


def case_three_cart_chain_vibration():
    m1, m2, m3, k1, k2, k3, c, v0 = 3.0, 2.0, 1.0, 400.0, 300.0, 200.0, 12.0, 0.6
    # Lagrange with V = k1 x1^2/2 + k2 (x2-x1)^2/2 + k3 (x3-x2)^2/2 and Rayleigh's D = c x1'^2/2
    # (displacements from equilibrium, so every spring's free length drops out)
    M = np.diag([m1, m2, m3])
    K = np.array([[k1 + k2, -k2, 0.0], [-k2, k2 + k3, -k3], [0.0, -k3, k3]])
    C = np.diag([c, 0.0, 0.0])
    # undamped modes: the symmetric eigenproblem through M^(-1/2) K M^(-1/2)
    root = np.diag(1 / np.sqrt(np.diag(M)))
    w2, u = np.linalg.eigh(root @ K @ root)
    shapes = root @ u
    # damping that is not proportional: the quadratic eigenproblem (l^2 M + l C + K) phi = 0
    # as the symmetric pencil [[C, M], [M, 0]] l z = [[-K, 0], [0, M]] z, z = (phi, l phi)
    Z = np.zeros((3, 3))
    pencil = np.linalg.solve(np.block([[C, M], [M, Z]]), np.block([[-K, Z], [Z, M]]))
    roots = np.linalg.eigvals(pencil)
    upper = sorted((r for r in roots if r.imag > 0), key=abs)
    zetas = [-r.real / abs(r) for r in upper]
    # the free response from rest at equilibrium with x3' = v0: z(t) = V exp(L t) V^-1 z0 for
    # z' = [[0, I], [-M^-1 K, -M^-1 C]] z, in the eigenvectors of that first-order system
    system = np.block([[Z, np.eye(3)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    lam, V = np.linalg.eig(system)
    coefficients = np.linalg.solve(V, np.array([0, 0, 0, 0, 0, v0], dtype=complex))

    def z(t):
        return (V @ (np.exp(lam * t) * coefficients)).real

    # cart 3 first stops: its velocity z[5] changes sign, bracketed on a fine grid
    grid = np.linspace(0.0, 1.0, 2001)
    first = next(i for i in range(1, len(grid)) if z(grid[i])[5] <= 0)
    stop = _bisect(lambda t: z(t)[5], grid[first - 1], grid[first])
    return {"omega_1": np.sqrt(w2[0]), "omega_2": np.sqrt(w2[1]), "omega_3": np.sqrt(w2[2]),
            "zeta_1": zetas[0], "zeta_2": zetas[1], "zeta_3": zetas[2],
            "mode_1_ratio": shapes[2, 0] / shapes[0, 0],
            "x1_at_250ms": z(0.25)[0] * 1e3, "x2_at_250ms": z(0.25)[1] * 1e3,
            "x3_at_250ms": z(0.25)[2] * 1e3, "v1_at_250ms": z(0.25)[3],
            "time_cart3_stops": stop * 1e3, "x3_at_1500ms": z(1.5)[2] * 1e3}


def case_light_pulley_hanger():
    mA, mB, g = 8.0, 20.0, 9.81
    # Lagrange in yA alone (the light pulley carries no energy): yB' = yC' = -yA'/2, so
    # T = (mA + mB/4) yA'^2/2 and V = mA g yA - mB g yA/2
    aA = g * (mB / 2 - mA) / (mA + mB / 4)
    tension = mA * (g + aA)  # block A alone
    pull = mB * (g - aA / 2)  # block B alone
    return {"accel_A": aA, "accel_B": -aA / 2, "tension": tension, "hanger_pull": pull}


def case_block_on_springs_in_series():
    m, k1, k2, L1, L2, v0 = 4.0, 600.0, 300.0, 0.25, 0.2, 0.5
    # the joint condensed out of the stiffness matrix of (x, xj) by hand (static condensation:
    # the joint has no mass, so its row of K q = 0 holds at every instant), then the free
    # response of the one block on what is left, from equilibrium (both springs free) at v0
    K = np.array([[k2, -k2], [-k2, k1 + k2]])
    k = K[0, 0] - K[0, 1] * K[1, 0] / K[1, 1]
    w = np.sqrt(k / m)

    def x(t):  # the block's distance from the wall
        return L1 + L2 + v0 / w * np.sin(w * t)

    def xj(t):  # the joint, from its row of K (u_j = -K_jb u_b / K_jj, u from equilibrium)
        return L1 - K[1, 0] * (x(t) - L1 - L2) / K[1, 1]

    stop = np.pi / (2 * w)
    return {"omega_n": w, "block_at_300ms": x(0.3) * 1e3, "joint_at_300ms": xj(0.3) * 1e3,
            "first_spring_tension_at_300ms": k1 * (xj(0.3) - L1), "farthest": x(stop) * 1e3}


CASES = {name[len("case_"):]: f for name, f in sorted(globals().items())
         if name.startswith("case_")}

if __name__ == "__main__":
    for name, f in CASES.items():
        print(name, f())
