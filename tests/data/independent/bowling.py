"""Independent reference values for the Bowling ch. 3 seed cases (numpy only).

Run:  python tests/data/independent/bowling.py

Each ``case_*`` function returns {objective_id: value} for one case of
/work/shared/cases/seed_examples.yaml, in that objective's unit:
scalars as float, vectors as [x, y, z] in the objective's frame, symbolic
objectives as a sympy-syntax string in the case's symbol names.

Every value is derived here by hand-style closed-form planar kinematics
(no sympy.physics, nothing from mechgrade).  ``cross_checks`` re-derives the
numeric answers a second way (central finite differences of position
functions, a Newton solve of the vector loop) so the closed forms are not
checked only against themselves.  Models and the comparison with the book's
printed answers: bowling_models.md next to this file.
"""

import numpy as np

DEG = np.pi / 180.0


def rot(angle):
    """Unit vectors (X_A, Y_A) of a frame rotated by `angle` about Z_N, in N components."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([c, s, 0.0]), np.array([-s, c, 0.0])


def cross_z(w, v):
    """(w Z_N) x v for a planar vector v = [vx, vy, 0]."""
    return np.array([-w * v[1], w * v[0], 0.0])


def vec(v):
    return [float(c) + 0.0 for c in v]  # + 0.0 turns -0.0 into 0.0


# ---------------------------------------------------------------- 3.15.2
def case_bowling_3_15_2_cannonball():
    # P_NA = x X_N + y Y_N, N inertial -> V_A = xd X_N + yd Y_N (direct differentiation)
    return {"speed": "sqrt(xd**2 + yd**2)"}


# ---------------------------------------------------------------- 3.15.3
def case_bowling_3_15_3_mass_spring_damper():
    xd = 7.0  # m/s; w, h are constants and frame A does not rotate (A parallel to N)
    # P_NA = (x + w) X_A + h Y_A, dX_A/dt = dY_A/dt = 0 -> V_A = xd X_A = xd X_N
    V_A = np.array([xd, 0.0, 0.0])
    return {
        "speed": float(np.linalg.norm(V_A)),
        "V_A": vec(V_A),
        "speed_symbolic": "Abs(xd)",  # = sqrt(xd**2)
    }


# ---------------------------------------------------------------- 3.15.4
def case_bowling_3_15_4_pendulum():
    th, L, thd, thdd = 30 * DEG, 2.0, 7.0, 5.0  # rad, ft, rad/s, rad/s^2
    XA, YA = rot(th)
    # transport theorem twice: V = L thd Y_A ; a = L thdd Y_A - L thd^2 X_A
    a_A = np.array([-L * thd**2, L * thdd, 0.0])  # components on (X_A, Y_A)
    a_N = a_A[0] * XA + a_A[1] * YA
    return {
        "acc_mag": float(np.linalg.norm(a_A)),
        "acc_N": vec(a_N),
        "acc_A": vec(a_A),
        "acc_mag_symbolic": "L*sqrt(thetadd**2 + thetad**4)",
    }


# ---------------------------------------------------------------- 3.15.5
def _cylinder_givens():
    return dict(xd=3.0, yd=4.0, xdd=3.0, ydd=4.0, th=60 * DEG, r=0.01, thd=3.0, thdd=5.0)


def case_bowling_3_15_5_cylinder():
    g = _cylinder_givens()
    XA, _YA = rot(g["th"])
    P_AB = g["r"] * XA
    # P_NA = -x X_N - y Y_N  ->  V_A = -xd X_N - yd Y_N, A_A = -xdd X_N - ydd Y_N
    V_A = np.array([-g["xd"], -g["yd"], 0.0])
    A_A = np.array([-g["xdd"], -g["ydd"], 0.0])
    # velocity propagation A -> B:  V_B = V_A + w x P_AB
    V_B = V_A + cross_z(g["thd"], P_AB)
    # acceleration propagation A -> B:  A_B = A_A + alpha x P_AB + w x (w x P_AB)
    A_B = A_A + cross_z(g["thdd"], P_AB) + cross_z(g["thd"], cross_z(g["thd"], P_AB))
    # normal/tangential description at this instant
    sdot = np.linalg.norm(V_B)
    t_hat = V_B / sdot
    sddot = A_B @ t_hat
    a_perp = A_B - sddot * t_hat
    a_n = np.linalg.norm(a_perp)          # = sdot^2 / rho
    n_hat = a_perp / a_n
    rho = sdot**2 / a_n
    return {
        "vB_mag": float(sdot),
        "aB_mag": float(np.linalg.norm(A_B)),
        "vB_N": vec(V_B),
        "aB_N": vec(A_B),
        "sdot": float(sdot),
        "sddot": float(sddot),
        "a_n": float(a_n),
        "rho": float(rho),
        "t_hat_N": vec(t_hat),
        "n_hat_N": vec(n_hat),
        "vB_symbolic_x": "-xd - r*thetad*sin(theta)",
        "vB_symbolic_y": "-yd + r*thetad*cos(theta)",
    }


# ---------------------------------------------------------------- 3.15.6
def case_bowling_3_15_6_gears():
    nA, nB = 36.0, 10.0
    # arc-length (mesh) constraint: nA*theta = -nB*alpha  ->  alpha = -(nA/nB) theta
    # differentiate twice: alphadd = -(nA/nB) thetadd  ->  thetadd = -(nB/nA) alphadd
    alpha_B = -3.0  # rad/s^2 (Z_N component of gear B's angular acceleration)
    omega_B = -3.0  # rad/s   (alternative reading: gear B's angular velocity)
    return {
        "alpha_A_z": float(-(nB / nA) * alpha_B),
        "omega_A_z_if_given_is_velocity": float(-(nB / nA) * omega_B),
    }


# ---------------------------------------------------------------- 3.15.7
def case_bowling_3_15_7_rolling_ball_mound():
    R, r, phi = 1.0, 0.1, 30 * DEG  # phi = alpha + theta = total rotation N -> A
    # no-slip velocity constraint at contact B1: V_B1 = (r thetad - R alphad) X_B = 0
    # integrate with alpha = theta = 0 at the top: r theta = R alpha
    # phi = alpha + theta = alpha (R + r)/r  ->  alpha = phi r/(R + r)
    alpha = phi * r / (R + r)
    _XB, YB = rot(alpha)
    P_NA = (R + r) * YB  # line of centres along Y_B
    return {
        "P_NA_N": vec(P_NA),
        "alpha_deg": float(alpha / DEG),
        "alpha_symbolic": "phi*r/(R + r)",
    }


# ---------------------------------------------------------------- 3.15.8
def _blocks_givens():
    return dict(theta=30 * DEG, phi=50 * DEG, L=0.10, x=0.02, y=0.0914, alpha=19.17 * DEG, yd=4.0)


def _blocks_rates(th, ph, al, L, yd):
    # loop  x Y_A + L X_E - y X_B = 0, differentiated:  xd Y_A + L alphad Y_E - yd X_B = 0
    #   X_N: -xd sin(phi) - L alphad sin(alpha) - yd cos(theta) = 0
    #   Y_N:  xd cos(phi) + L alphad cos(alpha) - yd sin(theta) = 0
    # eliminate alphad:  xd sin(alpha - phi) = yd cos(theta - alpha)
    xd = yd * np.cos(th - al) / np.sin(al - ph)
    alphad = -(xd * np.sin(ph) + yd * np.cos(th)) / (L * np.sin(al))
    return xd, alphad


def case_bowling_3_15_8_connected_blocks():
    g = _blocks_givens()
    # the rates need only the angles (and L); x and y only fix alpha, which is given
    xd, alphad = _blocks_rates(g["theta"], g["phi"], g["alpha"], g["L"], g["yd"])
    V_A_N = xd * rot(g["phi"])[1]  # V_A = xd Y_A
    # instantaneous centre Z: V_A = alphad Z x P_ZA; V_A is along Y_A so P_ZA is along X_A
    P_ZA = np.array([xd / alphad, 0.0, 0.0])  # frame A components
    return {
        "xdot": float(xd),
        "V_A_frameA": [0.0, float(xd), 0.0],
        "V_A_N": vec(V_A_N),
        "rod_omega_z": float(alphad),
        "P_AZ_frameA": vec(-P_ZA),
        "P_ZA_frameA": vec(P_ZA),
        "IC_distance_from_A": float(abs(P_ZA[0])),
        "xdot_symbolic": "yd*cos(theta - alpha)/sin(alpha - phi)",
    }


# ---------------------------------------------------------------- P3.17
def case_bowling_P3_17_rocking_block():
    a, b, w = 6.0, 3.5, -1.4  # in, in, rad/s (clockwise)
    # contact corner C momentarily at rest:  V_G = V_C + w Z x P_CG,  |P_CG| = half-diagonal
    # for any tilt beta, P_CG = (a/2) X_A + (b/2) Y_A has the same length -> tilt drops out
    speeds = []
    for beta in (0.0, 17 * DEG, 38 * DEG, 71 * DEG):
        XA, YA = rot(-beta)
        speeds.append(np.linalg.norm(cross_z(w, a / 2 * XA + b / 2 * YA)))
    assert np.ptp(speeds) < 1e-12
    return {
        "vG_mag": float(speeds[0]),
        "vG_mag_symbolic": "sqrt(a**2 + b**2)*Abs(betad)/2",
    }


# ---------------------------------------------------------------- P3.8
def case_bowling_P3_8_planetary_gears():
    R, r, wp = 4.0, 1.0, 3.3  # cm, cm, rad/s (CCW)
    X = np.array([1.0, 0.0, 0.0])
    # planet centre P at (R + r) X_N; ring contact at (R + 2r) X_N, sun contact at R X_N
    # no slip on the fixed ring: 0 = V_P + wp Z x (r X_N)  ->  V_P = -wp r Y_N
    V_P = -cross_z(wp, r * X)
    # no slip on the sun: wsun Z x (R X_N) = V_P + wp Z x (-r X_N)  ->  wsun = -2 r wp / R
    v_sun_contact = V_P + cross_z(wp, -r * X)
    w_sun = v_sun_contact[1] / R
    # carrier (line O -> P): V_P = wc Z x ((R + r) X_N)
    w_c = V_P[1] / (R + r)
    return {
        "omega_sun_z": float(w_sun),
        "V_planet_centre_N": vec(V_P),
        "omega_carrier_z": float(w_c),
        "omega_sun_symbolic": "-2*r*omega_p/R",
    }


CASES = {
    "bowling_3_15_2_cannonball": case_bowling_3_15_2_cannonball,
    "bowling_3_15_3_mass_spring_damper": case_bowling_3_15_3_mass_spring_damper,
    "bowling_3_15_4_pendulum": case_bowling_3_15_4_pendulum,
    "bowling_3_15_5_cylinder": case_bowling_3_15_5_cylinder,
    "bowling_3_15_6_gears": case_bowling_3_15_6_gears,
    "bowling_3_15_7_rolling_ball_mound": case_bowling_3_15_7_rolling_ball_mound,
    "bowling_3_15_8_connected_blocks": case_bowling_3_15_8_connected_blocks,
    "bowling_P3_17_rocking_block": case_bowling_P3_17_rocking_block,
    "bowling_P3_8_planetary_gears": case_bowling_P3_8_planetary_gears,
}


# ------------------------------------------------------- second derivations
def _fd(f, h=1e-4):
    """central first and second derivatives at t = 0."""
    fp, f0, fm = np.asarray(f(h)), np.asarray(f(0.0)), np.asarray(f(-h))
    return (fp - fm) / (2 * h), (fp - 2 * f0 + fm) / h**2


def cross_checks():
    """Max |closed form - second method| per case (finite differences / Newton solve)."""
    out = {}
    # pendulum: differentiate the tip position L(cos th, sin th) twice
    th = lambda t: 30 * DEG + 7.0 * t + 2.5 * t * t
    _, a = _fd(lambda t: 2.0 * np.array([np.cos(th(t)), np.sin(th(t)), 0.0]))
    out["pendulum acc_N"] = np.abs(a - case_bowling_3_15_4_pendulum()["acc_N"]).max()

    # cylinder: differentiate P_NB = -x X_N - y Y_N + r X_A with quadratic-in-t coordinates
    g = _cylinder_givens()
    def P_B(t):
        x, y = g["xd"] * t + g["xdd"] * t * t / 2, g["yd"] * t + g["ydd"] * t * t / 2
        q = g["th"] + g["thd"] * t + g["thdd"] * t * t / 2
        return np.array([-x, -y, 0.0]) + g["r"] * rot(q)[0]
    v, a = _fd(P_B)
    c = case_bowling_3_15_5_cylinder()
    # curvature of the planar path: |v x a| / |v|^3
    rho_fd = np.linalg.norm(v) ** 3 / abs(v[0] * a[1] - v[1] * a[0])
    out["cylinder vB_N, aB_N, rho(rel)"] = max(np.abs(v - c["vB_N"]).max(),
                                              np.abs(a - c["aB_N"]).max(),
                                              abs(rho_fd / c["rho"] - 1))

    # rolling ball: the ball's material point at the contact must have zero velocity
    R, r, phid = 1.0, 0.1, 1.0  # any rate
    al0 = 30 * DEG * r / (R + r)
    XA0, YA0 = rot(30 * DEG)
    down = -rot(al0)[1]                        # unit vector A -> contact at t = 0
    u = np.array([down @ XA0, down @ YA0])     # that material point, in frame A
    def material_point(t):
        al = al0 + phid * t * r / (R + r)      # constraint: alpha = phi r/(R + r)
        XA, YA = rot(30 * DEG + phid * t)
        return (R + r) * rot(al)[1] + r * (u[0] * XA + u[1] * YA)
    v, _ = _fd(material_point)
    out["ball contact-point velocity"] = np.abs(v).max()
    out["ball centre vs book"] = np.abs(
        np.array(case_bowling_3_15_7_rolling_ball_mound()["P_NA_N"][:2]) - [-0.052, 1.099]).max()

    # blocks: Newton-solve the loop for (x, alpha) at y(t) = y0 + yd t, differentiate in t
    gb = _blocks_givens()
    XB = rot(gb["theta"])[0]
    def loop_solve(y, x0, a0):
        x, a = x0, a0
        for _ in range(50):
            F = x * rot(gb["phi"])[1] + gb["L"] * rot(a)[0] - y * XB
            J = np.column_stack([rot(gb["phi"])[1][:2], gb["L"] * rot(a)[1][:2]])
            dx, da = np.linalg.solve(J, -F[:2])
            x, a = x + dx, a + da
        return np.array([x, a])
    # anchor on the given alpha (x adjusted so the loop closes with y given and L given)
    base = loop_solve(gb["y"], gb["x"], gb["alpha"])
    d, _ = _fd(lambda t: loop_solve(gb["y"] + gb["yd"] * t, base[0], base[1]), h=1e-7)
    xd_c, ad_c = _blocks_rates(gb["theta"], gb["phi"], base[1], gb["L"], gb["yd"])
    out["blocks (xd, alphad) rel, at loop-closing alpha"] = max(abs(d[0] / xd_c - 1),
                                                               abs(d[1] / ad_c - 1))
    cb = case_bowling_3_15_8_connected_blocks()
    # IC check: B's velocity must equal alphad Z x P_ZB
    P_ZB = np.array(cb["P_ZA_frameA"][0]) * rot(gb["phi"])[0] + gb["L"] * rot(gb["alpha"])[0]
    out["blocks IC reproduces V_B"] = np.abs(cross_z(cb["rod_omega_z"], P_ZB) - gb["yd"] * XB).max()

    # planetary: rigid-planet material points at both contacts, carrier angle c(t), spin psi(t)
    Rs, rp, wp = 4.0, 1.0, 3.3
    cp = case_bowling_P3_8_planetary_gears()
    def planet_point(t, u):
        c, psi = cp["omega_carrier_z"] * t, wp * t
        Xp, Yp = rot(psi)
        return (Rs + rp) * rot(c)[0] + rp * (u[0] * Xp + u[1] * Yp)
    v_ring, _ = _fd(lambda t: planet_point(t, (1.0, 0.0)))
    v_sun, _ = _fd(lambda t: planet_point(t, (-1.0, 0.0)))
    out["planet ring-contact velocity"] = np.abs(v_ring).max()
    out["planet/sun contact mismatch"] = abs(v_sun[1] - cp["omega_sun_z"] * Rs)
    return out


if __name__ == "__main__":
    for name, fn in CASES.items():
        print(name)
        for k, v in fn().items():
            if isinstance(v, float):
                v = f"{v:.8g}"
            elif isinstance(v, list):
                v = "[" + ", ".join(f"{c:.8g}" for c in v) + "]"
            print(f"  {k:32s} {v}")
    print("cross-checks (all should be ~0):")
    for k, v in cross_checks().items():
        print(f"  {k:45s} {v:.3g}")
