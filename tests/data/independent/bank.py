"""Independent reference values for the problem bank (the held-out problems, numpy only).

Run:  python tests/data/independent/bank.py

Each ``case_*`` function returns {objective_id: value} for one problem of problems/, in that
objective's unit (vectors as [x, y, z] in the objective's frame). The solver differentiates the
model's positions, writes Newton-Euler balances with the reactions as unknowns and integrates
motions numerically; every value here comes by the route a textbook takes instead: closed-form
integrals of a(v) and a(x), n-t and polar formulas, vector loops solved by hand, energy and
momentum balances, Euler's equations written in the body's axes. Nothing here imports mechgrade
or sympy. bank_models.md beside this file says the route of each case.
"""

import numpy as np

DEG = np.pi / 180.0
G0 = 9.81
RPM = 2 * np.pi / 60
HP = 550.0  # ft lbf/s


def _rot(w, r):
    """(w k) x r in the plane."""
    return w * np.array([-r[1], r[0]])


# ------------------------------------------------------------------ rectilinear motion

def case_boat_coasting_quadratic_drag():
    m, c, v0, v1 = 400.0, 20.0, 12.0, 4.0
    # m dv/dt = -c v^2  =>  t = (m/c)(1/v1 - 1/v0);  m v dv/dx = -c v^2  =>  x = (m/c) ln(v0/v1)
    return {"time": m / c * (1 / v1 - 1 / v0), "distance": m / c * np.log(v0 / v1),
            "deceleration": -c * v1**2 / m}


def case_spring_launcher_a_of_x():
    m, k, delta = 0.5, 800.0, 0.1
    # a = -(k/m) x: v dv = a dx from x = -delta to 0 gives v = delta sqrt(k/m); x(t) is a
    # cosine of period 2 pi sqrt(m/k), which reaches 0 after a quarter period
    wn = np.sqrt(k / m)
    v = delta * wn
    return {"speed": v, "time": np.pi / 2 / wn, "kinetic_energy": m * v**2 / 2}


def case_car_constant_power_acceleration():
    m, P, v1, v2 = 1200.0, 60e3, 10.0, 25.0
    # m v dv/dt = P  =>  t = m (v2^2 - v1^2) / (2P);  m v^2 dv/dx = P  =>  x = m (v2^3 - v1^3)/(3P)
    return {"time": m * (v2**2 - v1**2) / (2 * P), "distance": m * (v2**3 - v1**3) / (3 * P),
            "force_at_25": P / v2}


# ------------------------------------------------------------------ curvilinear motion

def case_car_on_parabolic_road():
    b, x, v, at = 200.0, 40.0, 15.0, 2.0
    yp, ypp = 2 * x / b, 2 / b
    rho = (1 + yp**2) ** 1.5 / abs(ypp)  # the calculus formula for a curve y(x)
    an = v**2 / rho
    return {"radius_of_curvature": rho, "normal_acceleration": an,
            "acceleration_magnitude": np.hypot(at, an)}


def case_radar_tracks_airplane_polar():
    h, th, v = 3000.0, 30 * DEG, 200.0
    r = h / np.sin(th)
    # velocity (v, 0) in polar components: v_r = v cos th, v_th = -v sin th
    rd, thd = v * np.cos(th), -v * np.sin(th) / r
    # zero acceleration: a_r = r'' - r th'^2 = 0, a_th = r th'' + 2 r' th' = 0
    return {"distance": r, "r_dot": rd, "theta_dot": thd, "r_ddot": r * thd**2,
            "theta_ddot": -2 * rd * thd / r}


def case_collar_on_circle_rotating_rod():
    b, th, w = 0.3, 30 * DEG, 3.0
    r = 2 * b * np.cos(th)
    rd, rdd = -2 * b * w * np.sin(th), -2 * b * w**2 * np.cos(th)
    v = [rd, r * w, 0.0]
    a = [rdd - r * w**2, 2 * rd * w, 0.0]  # theta'' = 0
    return {"velocity": v, "acceleration": a, "speed": float(np.hypot(v[0], v[1]))}


def case_two_cars_relative_motion():
    vA, aA, R, vB, atB, phi = 25.0, 1.5, 100.0, 15.0, -2.0, 60 * DEG
    e_r = np.array([np.cos(phi), np.sin(phi)])
    e_t = np.array([-np.sin(phi), np.cos(phi)])  # counterclockwise
    v_B = vB * e_t
    a_B = atB * e_t - vB**2 / R * e_r  # n-t components of B on its circle
    v_rel = v_B - np.array([0.0, vA])
    a_rel = a_B - np.array([0.0, aA])
    return {"relative_velocity": [*v_rel, 0.0], "relative_acceleration": [*a_rel, 0.0],
            "relative_speed": float(np.linalg.norm(v_rel))}


def case_airplane_crosswind_heading():
    va, w = 240.0, 60.0  # km/h
    # the air-relative velocity's east component cancels the wind: va sin(psi) = w
    psi = np.arcsin(w / va)
    return {"heading": psi / DEG, "ground_speed": va * np.cos(psi)}


# ------------------------------------------------------------------ dependent motion

def case_truck_hoists_crate_pulley():
    h, L, x, xd = 3.0, 8.0, 4.0, 2.0
    s = np.hypot(x, h)  # the slanted strand
    y = h - (L - s) / 2
    # 2 y' = s' = x x'/s;  s'' = x'^2 h^2 / s^3 (x'' = 0)
    return {"height": y, "velocity": x * xd / s / 2, "acceleration": xd**2 * h**2 / s**3 / 2}


def case_movable_pulley_two_blocks():
    mA, mB, g = 10.0, 30.0, G0
    # a_A = -2 a_B; A: T - mA g = mA a_A; B: 2T - mB g = mB a_B
    A = np.array([[1.0, 2.0, 0.0], [mA, 0.0, -1.0], [0.0, mB, -2.0]])
    b = np.array([0.0, -mA * g, -mB * g])
    aA, aB, T = np.linalg.solve(A, b)
    return {"accel_A": aA, "accel_B": aB, "tension": T}


# ------------------------------------------------------------------ work and energy

def case_collar_spring_vertical_rod():
    m, g, k, L0, d, h = 2.0, G0, 200.0, 0.3, 0.4, 0.3
    s1, s2 = d - L0, np.hypot(d, h) - L0  # stretches before and after
    v = np.sqrt(2 * (m * g * h - k * (s2**2 - s1**2) / 2) / m)
    ell = np.hypot(d, h)
    tension = k * s2
    return {"speed": v, "spring_energy": k * s2**2 / 2,
            # the rod balances the spring's horizontal pull toward D
            "rod_force": -tension * d / ell}


def case_block_incline_spring_compression():
    m, g, k, mu, th, v1 = 5.0, G0, 200.0, 0.4, 40 * DEG, 3.0
    F = m * g * (np.sin(th) - mu * np.cos(th))  # net constant force down the slope
    # work-energy: m v1^2/2 + F d = k d^2/2
    d = (F + np.sqrt(F**2 + k * m * v1**2)) / k
    # x'' = (F - k x)/m: simple harmonic about F/k, from x = 0 moving at v1
    wn = np.sqrt(k / m)
    t = np.arctan2(v1 / wn, -F / k) / wn
    return {"max_compression": d * 1000, "time_to_stop": t, "spring_force": k * d}


# ------------------------------------------------------------------ power

def case_elevator_motor_power():
    W, g, eta, v, a = 3000.0, 32.2, 0.75, 12.0, 2.0
    T = W + W / g * a
    return {"tension": T, "power_to_cab": T * v / HP, "motor_power": T * v / HP / eta}


def case_car_climbs_grade_power():
    m, g, th, R, eta, v = 1500.0, G0, 8 * DEG, 500.0, 0.85, 90 / 3.6
    F = m * g * np.sin(th) + R
    return {"driving_force": F, "wheel_power": F * v / 1e3, "engine_power": F * v / 1e3 / eta}


# ------------------------------------------------------------------ impulse and momentum

def case_crate_pushed_impulse_momentum():
    m, g, P, beta, mu, v0, T = 50.0, G0, 300.0, 30 * DEG, 0.3, 2.0, 4.0
    N = m * g + P * np.sin(beta)
    F = mu * N
    # impulse-momentum along the floor: m v0 + (P cos beta - F) T = m v
    return {"speed": v0 + (P * np.cos(beta) - F) * T / m, "normal": N, "friction": -F}


def case_freight_cars_couple():
    m1, m2, v0 = 20e3, 30e3, 1.5
    v = m1 * v0 / (m1 + m2)
    return {"velocity_after": v, "impulse_on_second": [m2 * v / 1e3, 0.0, 0.0],
            "energy_lost": (m1 * v0**2 / 2 - (m1 + m2) * v**2 / 2) / 1e3}


def case_baseball_bat_impulse():
    m, v1, v2, beta, tc = 0.145, 40.0, 50.0, 30 * DEG, 1.5e-3
    J = m * (np.array([v2 * np.cos(beta), v2 * np.sin(beta)]) - np.array([-v1, 0.0]))
    mag = float(np.linalg.norm(J))
    return {"impulse": [*J, 0.0], "impulse_magnitude": mag, "average_force": mag / tc}


def case_pucks_oblique_impact():
    mA, mB, vA, vB, e = 0.4, 0.6, 6.0, 4.0, 0.8
    uA = np.array([vA * np.cos(30 * DEG), -vA * np.sin(30 * DEG)])
    uB = np.array([-vB * np.cos(60 * DEG), -vB * np.sin(60 * DEG)])
    # along the line of centres: momentum and restitution; across it: unchanged
    M = np.array([[mA, mB], [-1.0, 1.0]])
    xA, xB = np.linalg.solve(M, [mA * uA[0] + mB * uB[0], e * (uA[0] - uB[0])])
    wA, wB = np.array([xA, uA[1]]), np.array([xB, uB[1]])
    lost = (mA * (uA @ uA - wA @ wA) + mB * (uB @ uB - wB @ wB)) / 2
    return {"velocity_A": [*wA, 0.0], "velocity_B": [*wB, 0.0], "energy_lost": lost}


def case_ball_bounces_oblique_floor():
    v1, beta, e = 20.0, 30 * DEG, 0.7
    vx, vy = v1 * np.cos(beta), e * v1 * np.sin(beta)
    return {"velocity_after": [vx, vy, 0.0], "speed_after": np.hypot(vx, vy),
            "rebound_angle": np.arctan2(vy, vx) / DEG}


def case_ball_strikes_hanging_rod():
    M, L, m, d, v0, e = 4.0, 1.2, 0.5, 0.9, 8.0, 0.6
    IO = M * L**2 / 3
    # angular momentum of ball + rod about the pin; restitution at the struck point
    A = np.array([[m * d, IO], [-1.0, d]])
    v, w = np.linalg.solve(A, [m * v0 * d, e * v0])
    # linear impulse on the rod alone: pin + ball's impulse = M (L/2) w
    pin = M * L / 2 * w - m * (v0 - v)
    return {"omega_after": w, "ball_velocity_after": v, "pin_impulse": [pin, 0.0, 0.0]}


# ------------------------------------------------------------------ angular momentum

def case_puck_string_through_hole():
    m, r0, r1, u, w0 = 0.5, 0.8, 0.4, 0.2, 2.0
    w1 = w0 * (r0 / r1) ** 2  # r^2 theta' is conserved (the cord's pull is central)
    return {"angular_velocity": w1, "speed": np.hypot(u, r1 * w1),
            "angular_momentum": m * r1**2 * w1,
            "tension": m * r1 * w1**2}  # radial: -T = m (r'' - r theta'^2), r'' = 0


def case_satellite_apogee_speed():
    GM, rp, vp = 398600.0, 6378.0 + 500.0, 8.0
    h = rp * vp
    E = vp**2 / 2 - GM / rp
    # energy with v = h/r at the apsides: E r^2 + GM r - h^2/2 = 0, the other root
    ra = max(np.roots([E, GM, -h**2 / 2]))
    a = (rp + ra) / 2
    return {"apogee_distance": ra, "apogee_speed": h / ra,
            "half_period": np.pi * np.sqrt(a**3 / GM) / 60}  # Kepler's third law


# ------------------------------------------------------------------ rotation about a fixed axis

def case_drum_hoist_falling_block():
    M, k, r, m, g = 30.0, 0.2, 0.25, 20.0, G0
    I = M * k**2
    # whole system about the axle: m g r = (I + m r^2) alpha (clockwise)
    alpha = m * g * r / (I + m * r**2)
    a = alpha * r
    return {"block_acceleration": -a, "angular_acceleration": -alpha, "tension": m * (g - a)}


def case_disk_pinned_at_rim_released():
    m, r, g = 8.0, 0.3, G0
    IO = m * r**2 / 2 + m * r**2
    alpha = -m * g * r / IO
    aG = alpha * r  # tangential, vertical at release (no speed yet)
    return {"angular_acceleration": alpha, "pin_force": [0.0, m * g + m * aG, 0.0],
            "centre_acceleration": [0.0, aG, 0.0]}


def case_flywheel_lever_brake():
    M, R, k, b, c, P, mu, w0 = 60.0, 0.25, 0.18, 0.5, 0.75, 100.0, 0.4, 600 * RPM
    # lever about its pin A: N b = P (b + c) (friction's line passes through A)
    N = P * (b + c) / b
    alpha = mu * N * R / (M * k**2)
    t = w0 / alpha
    return {"normal_force": N, "stopping_time": t, "revolutions": w0 * t / 2 / (2 * np.pi)}


# ------------------------------------------------------------------ plane motion, IC

def case_gear_between_two_racks():
    r, vu, vl = 0.15, 2.0, -1.0
    # the mesh points move with the racks: vG + w r = vu (top), vG - w r = vl (bottom),
    # with w the clockwise rate
    w_cw = (vu - vl) / (2 * r)
    vG = (vu + vl) / 2
    return {"angular_velocity": -w_cw, "centre_velocity": vG,
            "instant_centre": [0.0, -vG / w_cw * 1000, 0.0]}


def case_rod_in_two_slots_ic():
    L, th, vA, be = 1.0, 30 * DEG, 2.0, 45 * DEG
    A = np.array([0.0, 0.0])
    B = A + L * np.array([np.cos(th), np.sin(th)])
    # the instantaneous centre: on the normal to A's path (vertical through A) and to B's
    # path (the line through B perpendicular to the slot)
    n_B = np.array([-np.sin(be), np.cos(be)])
    # I = A + s (0, 1) = B + u n_B
    s, _u = np.linalg.solve(np.column_stack([[0.0, 1.0], -n_B]), B - A)
    I = A + s * np.array([0.0, 1.0])
    w = vA / s  # v_A = w k x (A - I) = w k x (-s j) = w s i
    vB = _rot(w, B - I) @ np.array([np.cos(be), np.sin(be)])
    G = (A + B) / 2
    return {"angular_velocity": w, "velocity_B": vB, "speed_G": abs(w) * np.linalg.norm(G - I)}


def case_rolling_wheel_rim_points():
    r, v, a, gam = 0.4, 3.0, 1.5, 45 * DEG
    w, al = -v / r, -a / r
    rP = r * np.array([np.cos(gam), np.sin(gam)])
    vP = np.array([v, 0.0]) + _rot(w, rP)
    aP = np.array([a, 0.0]) + _rot(al, rP) - w**2 * rP
    rC = np.array([0.0, -r])
    aC = np.array([a, 0.0]) + _rot(al, rC) - w**2 * rC
    return {"velocity_P": [*vP, 0.0], "acceleration_P": [*aP, 0.0],
            "acceleration_contact": [*aC, 0.0]}


def case_slotted_arm_crank_coriolis():
    r, h, w, ph = 0.2, 0.4, 4.0, 30 * DEG
    B = np.array([r * np.cos(ph), h + r * np.sin(ph)])
    s = np.linalg.norm(B)
    e_s = B / s
    e_t = np.array([-e_s[1], e_s[0]])
    vB = r * w * np.array([-np.sin(ph), np.cos(ph)])
    aB = -r * w**2 * np.array([np.cos(ph), np.sin(ph)])
    # v_B = s' e_s + s theta' e_t; a_B = (s'' - s theta'^2) e_s + (s theta'' + 2 s' theta') e_t
    sd, td = vB @ e_s, vB @ e_t / s
    tdd = (aB @ e_t - 2 * sd * td) / s
    return {"arm_angular_velocity": td, "arm_angular_acceleration": tdd, "sliding_rate": sd,
            "relative_acceleration": aB @ e_s + s * td**2}


def case_collar_slides_on_spinning_rod():
    m, r, rd, w = 0.5, 0.3, 1.2, 5.0
    # smooth rod: no radial force, so r'' = r w^2; transverse: N = m (2 r' w) (w constant)
    N = m * 2 * rd * w
    return {"sliding_acceleration": r * w**2, "side_force": N, "drive_moment": N * r}


# ------------------------------------------------------------------ rolling

def case_cylinder_pulled_rolls():
    m, r, g, P = 20.0, 0.2, G0, 60.0
    # moments about the contact point: P r = (m r^2/2 + m r^2) alpha
    a = P * r**2 / (1.5 * m * r**2)
    F = m * a - P
    return {"acceleration": a, "angular_acceleration": -a / r, "friction": F,
            "mu_needed": abs(F) / (m * g)}


def case_hoop_slips_down_incline():
    m, r, g, beta, mu = 3.0, 0.5, G0, 40 * DEG, 0.15
    N = m * g * np.cos(beta)
    F = mu * N  # the contact slips down the slope (x' + r w = 1 - 0.5 > 0): friction up
    return {"acceleration": g * np.sin(beta) - F / m, "angular_acceleration": F * r / (m * r**2),
            "friction": -F}


def case_disk_rolls_on_pulled_plank():
    M, m, P = 10.0, 6.0, 60.0
    # disk: F = m a, F r = (m r^2/2) alpha_cw, and rolling on the plank: a + r alpha_cw = A
    # => a = A/3; plank: P - F = M A
    A = P / (M + m / 3)
    a = A / 3
    return {"plank_acceleration": A, "disk_acceleration": a,
            "angular_acceleration": (A - a) / 0.2, "friction": m * a}


# ------------------------------------------------------------------ energy of rigid systems

def case_bar_swings_down_spring_energy():
    m, L, g, k, L0, H = 5.0, 1.2, G0, 20.0, 0.5, 0.9
    s1, s2 = np.hypot(L, H) - L0, H + L - L0
    E = m * g * L / 2 - k * (s2**2 - s1**2) / 2
    w = np.sqrt(2 * E / (m * L**2 / 3))
    # vertical bar: no moment about O, so alpha = 0; G moves on a circle: a_G = w^2 L/2 up
    T = k * s2  # the spring pulls A up toward D
    return {"angular_velocity": w, "spring_energy": k * s2**2 / 2,
            "pin_force": [0.0, m * w**2 * L / 2 + m * g - T, 0.0]}


def case_unbalanced_hoop_rolls():
    M, m, R, g = 4.0, 1.0, 0.5, G0
    # the small mass ends at the contact point (at rest): KE = (I_C of the hoop) w^2/2
    w = np.sqrt(m * g * 2 * R / (M * R**2))
    return {"angular_velocity": w, "centre_speed": w * R, "kinetic_energy": m * g * 2 * R}


def case_drum_block_energy_us():
    Wd, Wb, k, r, g, h = 100.0, 40.0, 0.8, 1.0, 32.2, 6.0
    mb, I = Wb / g, Wd / g * k**2
    v = np.sqrt(2 * Wb * h / (mb + I / r**2))
    a = Wb / (mb + I / r**2)
    return {"block_speed": v, "drum_angular_velocity": v / r, "tension": mb * (g - a)}


# ------------------------------------------------------------------ vibration

def case_block_on_spring_us_units():
    W, k, g = 10.0, 20.0 * 12, 32.2  # lbf, lbf/ft, ft/s^2
    wn = np.sqrt(k * g / W)
    return {"omega_n": wn, "frequency": wn / (2 * np.pi), "period": 2 * np.pi / wn}


def case_block_between_two_springs():
    m, k1, k2, x0, v0 = 12.0, 3e3, 5e3, 0.02, 0.5
    wn = np.sqrt((k1 + k2) / m)  # both springs act on the block directly: in parallel
    A = np.hypot(x0, v0 / wn)
    # x = A sin(wn t + p) with sin p = x0/A, moving outward: it stops at wn t + p = pi/2
    t = (np.pi / 2 - np.arcsin(x0 / A)) / wn
    return {"amplitude": A * 1000, "first_stop": t, "right_spring_force": -k2 * A}


def case_damped_block_first_peak():
    m, k, c, v0 = 5.0, 2000.0, 40.0, 1.0
    wn = np.sqrt(k / m)
    z = c / (2 * np.sqrt(k * m))
    wd = wn * np.sqrt(1 - z**2)
    # x = (v0/wd) e^(-z wn t) sin(wd t); x' = 0 where tan(wd t) = wd/(z wn)
    tp = np.arctan2(wd, z * wn) / wd
    xp = v0 / wd * np.exp(-z * wn * tp) * np.sin(wd * tp)
    return {"time_to_peak": tp, "peak_displacement": xp * 1000, "spring_force": k * xp}


def case_disk_pendulum_period():
    r, d, g = 0.2, 0.1, G0
    IO_over_m = r**2 / 2 + d**2
    wn = np.sqrt(g * d / IO_over_m)
    return {"omega_n": wn, "period": 2 * np.pi / wn, "equivalent_length": IO_over_m / d * 1000}


def case_motor_on_beam_resonance():
    m, k = 25.0, 400e3
    wn = np.sqrt(k / m)
    return {"omega_n": wn, "frequency": wn / (2 * np.pi), "resonant_speed": wn / RPM}


def case_bar_on_spring_vibration():
    m, L, a, k, g = 6.0, 1.5, 1.0, 2000.0, G0
    # about the pin: (m L^2/3) theta'' = -k a^2 theta (gravity balanced by the preload)
    wn = np.sqrt(k * a**2 / (m * L**2 / 3))
    return {"omega_n": wn, "period": 2 * np.pi / wn, "spring_force": m * g * L / 2 / a}


# ------------------------------------------------------------------ 3-D rigid bodies

def case_disk_on_bent_shaft():
    m, r, b, beta, g, w = 4.0, 0.15, 0.2, 10 * DEG, G0, 60.0
    # principal moments about the disk's diameter and axis; the shaft's rate in disk axes
    I_d, I_a = m * r**2 / 4, m * r**2 / 2
    wy, wz = w * np.sin(beta), w * np.cos(beta)  # disk axes: y' in the tilted plane, z' normal
    Hy, Hz = I_d * wy, I_a * wz
    # back to shaft axes: y' = cos b y + sin b z, z' = -sin b y + cos b z
    H = np.array([0.0, Hy * np.cos(beta) - Hz * np.sin(beta), Hy * np.sin(beta) + Hz * np.cos(beta)])
    # H is fixed in the shaft's axes: dH/dt = w k x H, supplied by the bearings' couple
    M = np.cross([0.0, 0.0, w], H)
    Ay = M[0] / (2 * b)  # A at -b k: (-b k) x (Ay j) = b Ay i; B carries -Ay
    return {"angular_momentum": list(H),
            "tilt_of_angular_momentum": np.arccos(H[2] / np.linalg.norm(H)) / DEG,
            "bearing_A": [0.0, Ay, m * g]}


def case_gyroscope_steady_precession():
    m, r, l, g, spin = 0.5, 0.05, 0.1, G0, 3000 * RPM
    # steady precession with a horizontal axle: m g l = Omega I_axial spin
    Omega = m * g * l / (m * r**2 / 2 * spin)
    return {"precession_rate": Omega, "precession_period": 2 * np.pi / Omega,
            "support_horizontal": -m * l * Omega**2}  # G on a circle of radius l about O


CASES = {name[len("case_"):]: f for name, f in sorted(globals().items())
         if name.startswith("case_")}

if __name__ == "__main__":
    for name, f in CASES.items():
        print(name, f())
