"""Typical mistakes a teacher sees on each problem of the library, with the value each gives.

Numpy-only hand derivations (nothing from mechgrade, no sympy): every value below is what a
student who made that mistake computes, written from the problem's physics. ``diagnosis`` lists
the diagnosis codes that name the mistake (two when two readings of it are the same
mistake: the hub's velocity is the wheel point's velocity without ω × r). ``inside`` marks a
mistake whose effect is smaller than the objective's default tolerance.

Run ``python tests/data/mistakes/typical.py`` to rewrite the tables <problem>.yaml beside it;
the test suite checks that the tables are what this script gives.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import yaml

D = math.pi / 180
Z = np.array([0.0, 0.0, 1.0])


def V(x, y, z=0.0):
    return np.array([x, y, z], float)


def cross_z(w, r):
    """(w k) × r."""
    return w * np.cross(Z, r)


def num(value, unit):
    return f"{value:.4g}" if unit == "1" else f"{value:.4g} {unit}"


def vec(v, unit):
    x, y, z = (0.0 if abs(c) < 1e-12 else c for c in v)
    return f"({x:.4g}, {y:.4g}, {z:.4g}) {unit}"


def entry(objective, mistake, answer, *codes, inside=False, known=None, generic=()):
    """One typical mistake; ``known: generic`` marks one the grader does not name yet, and
    ``generic`` the whole-answer diagnoses that are true of it without naming it."""
    out = {"objective": objective, "mistake": mistake, "answer": answer,
           "diagnosis": list(codes)}
    if inside:
        out["inside"] = True
    if known:
        out["known"] = known
    if generic:
        out["generic"] = list(generic)
    return out


def cannonball():
    return [entry("speed", "adds the components instead of sqrt of squares", "xd + yd",
                  "mag_as_sum"),
            entry("speed", "gives the horizontal rate only", "xd", "component_for_speed"),
            entry("speed", "forgets the square root", "xd^2 + yd^2", "dimension")]


def mass_spring_damper():
    v = V(7, 0)  # corner moves with the block: xdot along X_N (beta = 0)
    return [entry("V_A", "velocity to the left", vec(-v, "m/s"), "sign"),
            entry("V_A", "components swapped", vec(V(0, 7), "m/s"), "swapped"),
            entry("speed", "w, h in cm: 100 times too large", num(700, "m/s"), "cm_m")]


def pendulum():
    L, th, w, al = 2.0, 30 * D, 7.0, 5.0
    ex, ey = V(math.cos(th), math.sin(th)), V(-math.sin(th), math.cos(th))
    tangential, centripetal = L * al * ey, -L * w**2 * ex
    out = [entry("acc_mag", "tangential term L α left out", num(np.linalg.norm(centripetal),
                                                                 "ft/s^2"),
                 "drop_tangential", inside=True),
           entry("acc_mag", "centripetal term L ω² left out",
                 num(np.linalg.norm(tangential), "ft/s^2"), "drop_centripetal"),
           entry("acc_mag", "a_t + a_n added instead of √(a_t² + a_n²)",
                 num(L * al + L * w**2, "ft/s^2"), "mag_as_sum"),
           entry("acc_N", "body components (-Lω², Lα) copied as X_N, Y_N",
                 vec(V(-L * w**2, L * al), "ft/s^2"), "other_basis")]
    th_r = 30.0  # 30 used as radians
    ex_r, ey_r = V(math.cos(th_r), math.sin(th_r)), V(-math.sin(th_r), math.cos(th_r))
    out.append(entry("acc_N", "calculator in radian mode: cos 30, sin 30",
                     vec(-L * w**2 * ex_r + L * al * ey_r, "ft/s^2"), "given_deg_as_rad"))
    out.append(entry("acc_A", "α taken clockwise", vec(V(-L * w**2, -L * al), "ft/s^2"),
                     "given_sign"))
    return out


def cylinder():
    r, th, td, tdd = 0.01, 60 * D, 3.0, 5.0
    vA, aA = V(-3, -4), V(-3, -4)  # centre at -x X_N - y Y_N

    def b(r=r, th=th):
        ex, ey = V(math.cos(th), math.sin(th)), V(-math.sin(th), math.cos(th))
        v = vA + td * r * ey
        a = aA + tdd * r * ey - td**2 * r * ex
        return v, a, ex, ey
    v, a, ex, _ey = b()
    v_rad, _, _, _ = b(th=60.0)
    v_m, _, _, _ = b(r=1.0)
    return [entry("vB_mag", "60 used as radians", num(np.linalg.norm(v_rad), "m/s"),
                  "given_deg_as_rad", inside=True),
            entry("vB_mag", "r = 1 cm used as 1 m", num(np.linalg.norm(v_m), "m/s"),
                  "given_length_unit"),
            entry("rho", "ρ = v²/|a| with the whole acceleration",
                  num(v @ v / np.linalg.norm(a), "m"), "rho_formula"),
            entry("a_n", "the whole |a| for the normal part", num(np.linalg.norm(a), "m/s^2"),
                  "acc_for_acc_n"),
            entry("aB_N", "centripetal term r θ'² left out",
                  vec(a + td**2 * r * ex, "m/s^2"), "drop_centripetal")]


def gears():
    nA, nB, aB = 36, 10, -3.0
    return [entry("alpha_A_z", "tooth ratio inverted", num(-nA / nB * aB, "rad/s^2"),
                  "given_swap"),
            entry("alpha_A_z", "external gears taken to turn the same way",
                  num(nB / nA * aB, "rad/s^2"), "sign"),
            entry("omega_A_z_if_given_is_velocity", "tooth ratio inverted",
                  num(-nA / nB * aB, "rad/s"), "given_swap")]


def rolling_ball_mound():
    R, r, phi = 1.0, 0.1, 30 * D
    alpha = r * phi / (R + r)
    centre = (R + r) * V(-math.sin(alpha), math.cos(alpha))
    contact = R * V(-math.sin(alpha), math.cos(alpha))
    return [entry("alpha_deg", "answer left in radians", num(alpha, "deg"), "rad_as_deg"),
            entry("P_NA_N", "components swapped", vec(centre[[1, 0, 2]], "m"), "swapped"),
            entry("P_NA_N", "position of the contact point (R instead of R + r)",
                  vec(contact, "m"), "other_point")]


def connected_blocks():
    th, ph, al, yd = 30 * D, 50 * D, 19.17 * D, 4.0
    xd = yd * math.cos(th - al) / math.sin(al - ph)
    Ax, Ay = V(math.cos(ph), math.sin(ph)), V(-math.sin(ph), math.cos(ph))
    vA = xd * Ay
    return [entry("xdot", "right block taken to move down its incline", num(-xd, "m/s"),
                  "sign"),
            entry("V_A_N", "components along X_A, Y_A given as X_N, Y_N",
                  vec(V(vA @ Ax, vA @ Ay), "m/s"), "other_basis"),
            entry("V_A_frameA", "components swapped", vec(V(xd, 0), "m/s"), "swapped")]


def rocking_block():
    a, b, bd = 6.0, 3.5, -1.4
    return [entry("vG_mag", "half the side a instead of half the diagonal",
                  num(abs(bd) * a / 2, "in/s"), "position_term"),
            # |β'| b/2 is also the A.x component of v_G: both readings name it
            entry("vG_mag", "half the side b instead of half the diagonal",
                  num(abs(bd) * b / 2, "in/s"), "position_term", "component_for_speed"),
            entry("vG_mag", "the whole diagonal instead of half",
                  num(abs(bd) * math.hypot(a, b), "in/s"), "factor_2")]


def planetary_gears():
    R, r, pd = 4.0, 1.0, 3.3  # cm, cm, rad/s; ring contact at rest
    vP = -pd * r  # along Y_N (carrier along X_N)
    v_sun_contact = vP - pd * r
    w_sun = v_sun_contact / R
    return [entry("omega_sun_z", "sun taken to turn counterclockwise", num(-w_sun, "rad/s"),
                  "sign"),
            entry("V_planet_centre_N", "velocity of the sun-mesh point instead of the centre",
                  vec(V(0, v_sun_contact), "cm/s"), "other_point"),
            entry("V_planet_centre_N", "velocity of the ring contact (at rest)",
                  vec(V(0, 0), "cm/s"), "other_point")]


def collar_bent_arm():
    OA, beta, qd, s, sd = 1.0, 60 * D, 5.0, 0.2, 0.5
    rA = OA * V(math.cos(beta), -math.sin(beta))
    rC = rA + s * V(1, 0)
    transport, relative = cross_z(qd, rC), sd * V(1, 0)
    return [entry("v_C_N", "sliding velocity left out", vec(transport, "m/s"),
                  "drop_relative_vel"),
            entry("v_C_N", "ω × r left out", vec(relative, "m/s"), "drop_omega_r"),
            entry("v_C_N", "velocity of the bend A instead of the collar",
                  vec(cross_z(qd, rA), "m/s"), "other_point"),
            entry("speed", "sliding velocity left out", num(np.linalg.norm(transport), "m/s"),
                  "drop_relative_vel")]


def wheel_on_rotating_rod():
    L, r, q1, q1d, q2, q2d, q2dd = 2.0, 0.5, 30 * D, 3.0, -60 * D, -5.0, -1.0
    rA = L * V(math.cos(q1), math.sin(q1))
    rAP = r * V(math.cos(q1 + q2), math.sin(q1 + q2))
    vA, aA = cross_z(q1d, rA), -q1d**2 * rA
    w, al = q1d + q2d, q2dd
    vA + cross_z(w, rAP)
    a = aA + cross_z(al, rAP) - w**2 * rAP
    coriolis = 2 * cross_z(q1d, cross_z(q2d, rAP))  # 2 ω_B × v_rel in B
    return [entry("v_P_N", "wheel's relative rate q2' used as its absolute ω",
                  vec(vA + cross_z(q2d, rAP), "m/s"), "relative_omega"),
            entry("v_P_N", "velocity of the axle A left out", vec(cross_z(w, rAP), "m/s"),
                  "drop_transport_vel"),
            entry("a_P_N", "Coriolis term left out (rotating rod frame)",
                  vec(a - coriolis, "m/s^2"), "drop_coriolis"),
            entry("a_coriolis_N", "Coriolis term without its 2", vec(coriolis / 2, "m/s^2"),
                  "factor_2")]


def cycloid():
    def state(t):
        return V(1 - math.cos(t), math.sin(t)), V(math.sin(t), math.cos(t))
    v, a = state(math.pi / 2)
    v_pi, _ = state(math.pi)
    return [entry("v_pi_2", "velocity of the hub instead of the rim point", vec(V(1, 0), "m/s"),
                  "other_point", "drop_omega_r"),
            entry("rho_pi_2", "ρ = v²/|a|", num(v @ v / np.linalg.norm(a), "m"),
                  "rho_formula"),
            # at t = π the hub's velocity and ω × r are equal: each alone gives 1 m/s
            entry("speed_pi", "speed of the hub", num(1.0, "m/s"), "other_point",
                  "drop_omega_r", "drop_transport_vel"),
            entry("v_pi", "rim point's velocity without the hub's", vec(v_pi - V(1, 0), "m/s"),
                  "drop_transport_vel")]


def limacon():
    b, th, td = 1.0, 90 * D, 3.0
    R, Rd, Rdd = b * (1 + 2 * math.cos(th)), -2 * b * math.sin(th) * td, \
        -2 * b * math.cos(th) * td**2
    a_pol = V(Rdd - R * td**2, 2 * Rd * td)
    eR, eth = V(math.cos(th), math.sin(th)), V(-math.sin(th), math.cos(th))
    v_N = Rd * eR + R * td * eth
    a_N = a_pol[0] * eR + a_pol[1] * eth
    return [entry("a_polar", "Coriolis 2R'θ' left out", vec(V(a_pol[0], 0), "ft/s^2"),
                  "drop_coriolis"),
            entry("a_polar", "centripetal Rθ'² left out", vec(V(Rdd, a_pol[1]), "ft/s^2"),
                  "drop_centripetal"),
            entry("a_N", "e_R, e_θ components copied as i, j", vec(a_pol, "ft/s^2"),
                  "other_basis"),
            entry("a_t", "|a| for the tangential component", num(np.linalg.norm(a_N), "ft/s^2"),
                  "acc_for_acc_t"),
            entry("rho", "ρ = v²/|a|", num(v_N @ v_N / np.linalg.norm(a_N), "ft"),
                  "rho_formula")]


def spiral_bug():
    R0, k, th, Rd = 5.0, 0.182, math.pi, 2.0
    R = R0 * math.exp(k * th)
    td = Rd / (k * R)
    tdd = -Rd * td / R
    a_pol = V(-R * td**2, R * tdd + 2 * Rd * td)
    return [entry("a_N", "e_R, e_θ components copied as i, j", vec(a_pol, "mm/s^2"),
                  "other_basis"),
            entry("a_polar", "Coriolis 2R'θ' left out", vec(V(a_pol[0], R * tdd), "mm/s^2"),
                  "drop_coriolis"),
            entry("a_polar", "Rθ'' left out (steady read as θ'' = 0)",
                  vec(V(a_pol[0], 2 * Rd * td), "mm/s^2"), "drop_tangential")]


def rotating_tube_accel():
    L, qd, qdd, y, yd, ydd = 2.0, 5.0, 3.0, 2.0, -4.0, -2.0
    r, vrel, arel = V(2 * L, y), V(0, yd), V(0, ydd)
    coriolis = 2 * cross_z(qd, vrel)
    a = cross_z(qdd, r) - qd**2 * r + coriolis + arel
    return [entry("a_P_N", "Coriolis term left out", vec(a - coriolis, "ft/s^2"),
                  "drop_coriolis"),
            entry("a_P_N", "Coriolis term without its 2", vec(a - coriolis / 2, "ft/s^2"),
                  "coriolis_half"),
            entry("a_P_N", "centripetal term left out", vec(a + qd**2 * r, "ft/s^2"),
                  "drop_centripetal")]


def rod_collar_disk():
    L, R, th, ph, xAd = 2.0, 0.5, 30 * D, 30 * D, -2.0
    _rod_x, rod_y = V(math.cos(th), math.sin(th)), V(-math.sin(th), math.cos(th))
    disk_x = V(math.cos(ph), math.sin(ph))
    # xAd X + L θ' rod_y + R φ' disk_x = 0 (x and y components)
    m = np.array([[L * rod_y[0], R * disk_x[0]], [L * rod_y[1], R * disk_x[1]]])
    thd, _phd = np.linalg.solve(m, -np.array([xAd, 0.0]))
    vA = V(xAd, 0)
    vB = vA + L * thd * rod_y
    return [entry("omega_AB_z", "rod taken to turn counterclockwise", num(-thd, "rad/s"),
                  "sign"),
            entry("v_G_N", "velocity of the end B instead of the middle G", vec(vB, "m/s"),
                  "other_point"),
            entry("v_G_N", "velocity of the slider A (ω × r left out)", vec(vA, "m/s"),
                  "drop_omega_r", "other_point")]


def rotating_tube_velocity():
    L, qd, y, yd = 2.0, 5.0, 2.0, -4.0
    r = V(2 * L, y)
    transport, relative = cross_z(qd, r), V(0, yd)
    return [entry("v_P_N", "velocity relative to the tube left out", vec(transport, "ft/s"),
                  "drop_relative_vel", "mistake"),
            entry("v_P_N", "ω × r left out", vec(relative, "ft/s"), "drop_omega_r"),
            entry("speed", "velocity relative to the tube left out",
                  num(np.linalg.norm(transport), "ft/s"), "drop_relative_vel")]


def collar_in_disk_track():
    r, L, phd = 0.4, 1.0, 2.0
    s = 0.75 * r
    e = V(math.cos(45 * D), math.sin(45 * D))
    # P = s Disk.x: v = sd X + phd s Y; on the rod: v = thd k × L e
    sd, thd = np.linalg.solve(np.array([[1.0, L * e[1]], [0.0, -L * e[0]]]),
                              -np.array([0.0, phd * s]))
    transport, relative = V(0, phd * s), V(sd, 0)
    return [entry("v_P_N", "sliding velocity in the slot left out", vec(transport, "m/s"),
                  "drop_relative_vel"),
            entry("v_P_N", "disk's ω × r left out", vec(relative, "m/s"), "drop_omega_r",
                  "mistake"),
            entry("omega_AB_z", "rod taken to turn clockwise", num(-thd, "rad/s"), "sign")]


def unit_vector_rates():
    return [entry("eR_dot_y", "d e_R/dt = -θ' e_θ", "-omega", "sign"),
            entry("etheta_dot_x", "d e_θ/dt = +θ' e_R", "omega", "sign"),
            entry("jprime_dot_x", "d j'/dt = +ω i'", "omega", "sign")]


def bug_on_tire():
    return [entry("v_rest_jprime", "ω × r left out", "ld", "drop_omega_r"),
            entry("v_rest_jprime", "the bug's own speed l' left out", "-s*thetad",
                  "drop_relative_vel"),
            entry("a_rest_iprime", "Coriolis term left out", "l*thetadd - s*thetad^2",
                  "drop_coriolis"),
            entry("a_rest_iprime", "Coriolis term without its 2",
                  "l*thetadd - s*thetad^2 + thetad*ld", "coriolis_half")]


# ---------------------------------------------------------------------------- dynamics


def atwood():
    m1, m2, g = 3.0, 5.0, 9.81
    a = g * (m2 - m1) / (m1 + m2)
    return [entry("a1", "tension taken as block 2's weight in block 1's balance",
                  num((m2 * g - m1 * g) / m1, "m/s^2"), "tension_as_weight"),
            entry("tension", "tension taken as the heavier block's weight m2 g",
                  num(m2 * g, "N"), "tension_as_weight", "reaction_as_weight"),
            entry("tension", "tension taken as the lighter block's weight m1 g",
                  num(m1 * g, "N"), "tension_as_weight", "reaction_as_weight"),
            entry("a1", "masses written for the weights (m instead of m g)",
                  num((m2 - m1) / (m1 + m2), "m/s^2"), "mass_for_weight"),
            entry("a1", "block 1 taken to move down", num(-a, "m/s^2"), "sign")]


def cord_over_table_pulley():
    mA, mB, mu, g = 4.0, 2.0, 0.2, 9.81
    a = (mB - mu * mA) * g / (mA + mB)
    return [entry("tension", "tension taken as the hanging block's weight m_B g",
                  num(mB * g, "N"), "tension_as_weight", "reaction_as_weight"),
            entry("accel", "friction drawn toward the pulley",
                  num((mB + mu * mA) * g / (mA + mB), "m/s^2"), "friction_reversed"),
            entry("accel", "masses written for the weights (m instead of m g)",
                  num((mB - mu * mA) / (mA + mB), "m/s^2"), "mass_for_weight"),
            entry("accel", "block A taken to move away from the pulley", num(-a, "m/s^2"),
                  "sign")]


def gyroscope():
    m, r, L, g, spin = 1.5, 0.06, 0.10, 9.81, 250.0
    Is = m * r**2 / 2
    W = m * g * L / (Is * spin)
    return [entry("precession_rate", "weight's moment m L instead of m g L",
                  num(m * L / (Is * spin), "rad/s"), "mass_for_weight"),
            entry("precession_rate", "precession taken the other way round", num(-W, "rad/s"),
                  "sign", "given_sign"),
            entry("pivot_force", "weight left out: only the centripetal part m L Ω²",
                  vec(V(-m * L * W**2, 0), "N"), "weight_omitted"),
            entry("pivot_force", "mass for the weight in the pivot's vertical part",
                  vec(V(-m * L * (m * L / (Is * spin))**2, m), "N"), "mass_for_weight")]


def truck_pendulum():
    m, L, a0 = 0.5, 0.8, 3.0
    return [entry("alpha", "the bob taken to swing forward", num(a0 / L, "rad/s^2"), "sign",
                  "given_sign"),
            entry("tension", "tension written as the mass m", num(m, "N"), "mass_for_weight"),
            entry("acc_in_truck", "the truck's acceleration taken the other way",
                  vec(V(a0, 0), "m/s^2"), "sign", "given_sign")]


def block_on_turntable():
    m, r, w, al = 0.5, 0.3, 4.0, 2.0
    F = m * V(-r * w**2, r * al)  # along B.x (outward), B.y
    return [entry("normal", "normal force written as the mass m", num(m, "N"),
                  "mass_for_weight"),
            entry("mu_needed", "|F| divided by m instead of m g",
                  num(np.linalg.norm(F) / m, "1"), "mass_for_weight"),
            entry("friction_B", "friction drawn outward, against the centripetal direction",
                  vec(-F, "N"), "sign", "friction_reversed"),
            entry("friction_B", "turntable taken to slow down (φ'' negative)",
                  vec(m * V(-r * w**2, -r * al), "N"), "given_sign")]


def block_sliding_down_incline():
    m, g, beta, mu = 4.0, 9.81, 30 * D, 0.25
    return [entry("accel", "friction drawn down the slope",
                  num(g * (math.sin(beta) + mu * math.cos(beta)), "m/s^2"),
                  "friction_reversed"),
            entry("accel", "normal force taken as m g: friction μ m g",
                  num(g * math.sin(beta) - mu * g, "m/s^2"), "normal_from_weight"),
            entry("normal", "normal force taken as the weight m g", num(m * g, "N"),
                  "reaction_as_weight"),
            entry("friction", "friction μ m g with the weight for the normal force",
                  vec(V(-mu * m * g, 0), "N"), "normal_from_weight"),
            entry("accel", "calculator in radian mode: sin 30, cos 30",
                  num(g * (math.sin(30.0) - mu * math.cos(30.0)), "m/s^2"),
                  "given_deg_as_rad")]


def car_braking():
    m, g, h, a, b, mu = 1200.0, 9.81, 0.55, 1.1, 1.5, 0.8
    W = m * g
    return [entry("front_normal", "static share m g b/(a + b): weight transfer ignored",
                  num(W * b / (a + b), "N"), "weight_transfer_ignored"),
            entry("rear_normal", "static share m g a/(a + b): weight transfer ignored",
                  num(W * a / (a + b), "N"), "weight_transfer_ignored"),
            entry("front_normal", "distances a and b exchanged",
                  num(W * (a + mu * h) / (a + b), "N"), "given_swap"),
            entry("decel", "deceleration given as positive", num(mu * g, "m/s^2"), "sign",
                  "friction_reversed")]


def damped_pendulum():
    m, L, g, c = 1.5, 0.8, 9.81, 0.6
    wn_m = math.sqrt(3 / (2 * L))  # g left out of the weight's moment
    zeta_m = c * L**2 / (2 * (m * L**2 / 3) * wn_m)
    return [entry("omega_n", "weight's moment m L/2 θ instead of m g L/2 θ",
                  num(wn_m, "rad/s"), "mass_for_weight"),
            entry("zeta", "weight's moment without g", num(zeta_m, "1"), "mass_for_weight"),
            entry("damped_period", "weight's moment without g",
                  num(2 * math.pi / (wn_m * math.sqrt(1 - zeta_m**2)), "s"), "mass_for_weight"),
            entry("omega_n", "I_G = m L²/12 used about the pin O",
                  num(math.sqrt((m * g * L / 2) / (m * L**2 / 12)), "rad/s"),
                  "central_inertia_at_pivot")]


def ladder_lift_off():
    m, L, g, th0 = 12.0, 4.0, 9.81, 80 * D
    th = math.asin(2 / 3 * math.sin(th0))
    thd = -math.sqrt(3 * g / L * (math.sin(th0) - math.sin(th)))
    energy = m * g * L / 2 * math.sin(th0)
    return [entry("floor_reaction", "floor reaction taken as the weight m g", num(m * g, "N"),
                  "reaction_as_weight"),
            entry("energy_at_lift_off", "rotational energy ½ I_G θ'² left out",
                  num(energy - 0.5 * (m * L**2 / 12) * thd**2, "J"), "rotational_ke_omitted"),
            entry("theta_wall_contact_lost_deg", "angle left in radians", num(th, "deg"),
                  "rad_as_deg"),
            entry("thetad_at_lift_off", "rate given as positive", num(-thd, "rad/s"), "sign")]


def pendulum_pin():
    m, L, g, th, w = 2.0, 1.2, 9.81, 40 * D, 3.0
    rG = L / 2 * V(math.sin(th), -math.cos(th))
    alpha_G = -(m * g * L / 2 * math.sin(th)) / (m * L**2 / 12)  # I_G at the pin
    aG = cross_z(alpha_G, rG) - w**2 * rG
    alpha = -3 * g * math.sin(th) / (2 * L)
    along_rad = m * (w**2 * L / 2 + g * math.cos(40.0))
    return [entry("alpha", "I_G = m L²/12 used about the pin O", num(alpha_G, "rad/s^2"),
                  "central_inertia_at_pivot"),
            entry("alpha", "calculator in radian mode: sin 40",
                  num(-3 * g * math.sin(40.0) / (2 * L), "rad/s^2"), "given_deg_as_rad"),
            entry("pin_force", "I_G used about the pin, then R = m a_G - m g",
                  vec(m * aG + V(0, m * g), "N"), "central_inertia_at_pivot"),
            entry("pin_force", "weight left out of the force balance: R = m a_G",
                  vec(m * (cross_z(alpha, rG) - w**2 * rG), "N"), "weight_omitted"),
            entry("pin_force_along_rod", "calculator in radian mode: cos 40",
                  num(along_rad, "N"), "given_deg_as_rad"),
            entry("alpha", "clockwise taken as positive", num(-alpha, "rad/s^2"), "sign")]


def rod_ledge():
    m, L, v0, e = 3.0, 1.2, 4.0, 0.5

    def after(e):
        P = m * v0 * (1 + e) / 4  # v_A = v_G + 3P/m = e v0 with v_G = -v0 + P/m
        return P, -v0 + P / m, -6 * P / (m * L)
    P1, vG1, _ = after(1.0)
    _, _, w0 = after(0.0)
    _, _, w = after(e)
    return [entry("vG_after", "perfectly elastic impact (e = 1)", num(vG1, "m/s"),
                  "restitution_ignored"),
            entry("omega_after", "perfectly plastic impact (e = 0)", num(w0, "rad/s"),
                  "restitution_ignored"),
            entry("impulse", "perfectly elastic impact (e = 1)", vec(V(0, P1), "N*s"),
                  "restitution_ignored"),
            entry("omega_after", "clockwise taken as positive", num(-w, "rad/s"), "sign")]


def falling_ladder():
    m, L, g, th0, th = 10.0, 4.0, 9.81, 80 * D, 60 * D
    thd = -math.sqrt(3 * g * (math.sin(th0) - math.sin(th)) / L)  # released from rest at θ0
    N1 = m * math.cos(th) * (3 * g * math.sin(th) - 2 * L * thd**2) / 4
    return [entry("thetaddot_now", "calculator in radian mode: cos 60",
                  num(-3 * g * math.cos(60.0) / (2 * L), "rad/s^2"), "given_deg_as_rad"),
            entry("reactions_now", "floor reaction taken as the weight m g",
                  vec(V(N1, m * g), "N"), "reaction_as_weight"),
            entry("thetaddot_now", "weight's moment without g (m instead of m g)",
                  num(-3 * math.cos(th) / (2 * L), "rad/s^2"), "mass_for_weight"),
            entry("thetaddot_now", "sign of θ'' reversed",
                  num(3 * g * math.cos(th) / (2 * L), "rad/s^2"), "sign")]


def ladder_energy():
    th0, th = 80 * D, 45 * D
    drop = math.sin(th0) - math.sin(th)  # g = L = 1
    lost = math.asin(2 / 3 * math.sin(th0))
    lost_drop = math.sin(th0) - math.sin(lost)
    return [entry("vG_over_sqrt_gL", "rotational energy ½ I_G θ'² left out",
                  num(math.sqrt(drop), "1"), "rotational_ke_omitted"),
            entry("vG_over_sqrt_gL", "calculator in radian mode: sin 45",
                  num(0.5 * math.sqrt(3 * (math.sin(th0) - math.sin(45.0))), "1"),
                  "given_deg_as_rad"),
            entry("vG_over_sqrt_gL", "L θ' (the top relative to the foot) for v_G",
                  num(math.sqrt(3 * drop), "1"), "factor_2"),
            # where the wall lets go: N1 = 0 at sin θ = (2/3) sin θ0
            entry("theta_wall_lost_deg", "angle left in radians", num(lost, "deg"),
                  "rad_as_deg"),
            entry("theta_wall_lost_deg", "angle measured from the wall (90 deg - θ)",
                  num(90 - lost / D, "deg"), known="none"),
            entry("vG_wall_lost", "rotational energy ½ I_G θ'² left out (the same angle)",
                  num(math.sqrt(lost_drop), "1"), "rotational_ke_omitted"),
            entry("vG_wall_lost", "L θ' (the top relative to the foot) for v_G",
                  num(math.sqrt(3 * lost_drop), "1"), "factor_2")]


def wheel_incline():
    r = 0.1  # with m = 1, M = 2 kg, theta = 30 deg and a = 0.2 g, each R solves a r² equation
    return [entry("R_min", "moments about the contact C with I_G (m d² left out)",
                  num(math.sqrt(6) * r, "m"), "central_inertia_at_pivot"),
            entry("R_min", "outer disks taken as rings (M R² each)",
                  num(math.sqrt(1.75) * r, "m"), "other_shape_inertia"),
            entry("R_min", "answer in cm with the unit m", num(math.sqrt(3.5) * r * 100, "m"),
                  "cm_m")]


def ball_skid():
    v0, mu, g = 5.0, 0.12, 9.8

    def rolls(k, mu_g=mu * g):  # I = k m r²: v0 - mu g t = mu g t / k
        t = v0 * k / (mu_g * (1 + k))
        return t, v0 - mu_g * t, v0 * t - mu_g * t**2 / 2
    _t, v, _ = rolls(0.4)
    return [entry("v_at_t_star", "ball taken as a thin shell (2/3 m r²)",
                  num(rolls(2 / 3)[1], "m/s"), "other_shape_inertia"),
            entry("t_star", "ball taken as a thin shell (2/3 m r²)",
                  num(rolls(2 / 3)[0], "s"), "other_shape_inertia"),
            entry("t_star", "ball taken as a disk (½ m r²)", num(rolls(0.5)[0], "s"),
                  "other_shape_inertia"),
            entry("t_star", "friction μ m instead of μ m g", num(rolls(0.4, mu)[0], "s"),
                  "mass_for_weight"),
            entry("omega_at_t_star_z", "spin given as counterclockwise", num(v / 0.1, "rad/s"),
                  "sign")]


def billiard():
    r, d, v = 0.03, 0.01, 1.0  # m, m, m/s: I ω = -d m v

    def omega(k):
        return -d * v / (k * r**2)
    return [entry("omega_z", "ball taken as a thin shell (2/3 m r²)", num(omega(2 / 3), "rad/s"),
                  "other_shape_inertia"),
            entry("omega_z", "ball taken as a disk (½ m r²)", num(omega(0.5), "rad/s"),
                  "other_shape_inertia"),
            entry("omega_z", "spin given as counterclockwise", num(-omega(0.4), "rad/s"),
                  "sign")]


def spring_chain():
    m1, m2, k1, k2, L2, c = 2.0, 1.0, 100.0, 50.0, 0.8, 4.0
    x1, x2, v1, v2 = 0.6, 1.5, 0.5, -0.2
    s2, damper = k2 * (x2 - x1 - L2), c * (v2 - v1)  # pulls block 1 forward, block 2 back
    return [entry("a1", "spring 1's force k1 x1 (free length left out)",
                  num((-k1 * x1 + s2 + damper) / m1, "m/s^2"), "spring_free_length_omitted"),
            entry("spring1_energy", "½ k1 x1² (free length left out)", num(k1 * x1**2 / 2, "J"),
                  "spring_free_length_omitted"),
            entry("a2", "spring 2's force k2 (x2 - x1) (free length left out)",
                  num((-k2 * (x2 - x1) - damper) / m2, "m/s^2"), "spring_free_length_omitted"),
            # m1 = 2 m2: the masses exchanged give the same value; the factor 2 is all that is said
            entry("ke2", "m v² without the ½", num(m2 * v2**2, "J"), "factor_2"),
            entry("spring2_on_block1", "spring 2 taken to push block 1 back",
                  vec(V(-s2, 0), "N"), "sign")]


def cart_pendulum():
    M, m, L, k, x0, g = 2.0, 0.5, 0.8, 50.0, 1.0, 9.81
    x, th, w = 1.1, 20 * D, 1.5

    def accelerations(spring, weight):
        # Lagrange: (M+m) x'' + m L cos th th'' = m L sin th th'^2 - spring,
        #           m L cos th x'' + m L^2 th'' = -weight L sin th
        mass = np.array([[M + m, m * L * math.cos(th)], [m * L * math.cos(th), m * L * L]])
        rhs = np.array([m * L * math.sin(th) * w**2 - spring, -weight * L * math.sin(th)])
        return np.linalg.solve(mass, rhs)

    free_length_left_out = accelerations(k * x, m * g)
    mass_for_weight = accelerations(k * (x - x0), m)
    return [entry("cart_acceleration", "spring force k x (free length left out)",
                  num(free_length_left_out[0], "m/s^2"), "spring_free_length_omitted"),
            entry("alpha", "the bob's weight written as its mass m (g left out)",
                  num(mass_for_weight[1], "rad/s^2"), "mass_for_weight"),
            entry("rod_force", "the rod's force taken as the bob's weight m g",
                  num(m * g, "N"), "tension_as_weight", "reaction_as_weight", known="none"),
            entry("cart_acceleration", "the bob ignored: x'' = -k (x - x0)/M",
                  num(-k * (x - x0) / M, "m/s^2"), known="none"),
            # without gravity the bob has no restoring force and the cart swings with its own
            # mass only (det(K - w^2 M) = 0 gives w^2 = k/M exactly): the same mistake
            entry("omega_2", "the cart alone on its spring: sqrt(k/M)",
                  num(math.sqrt(k / M), "rad/s"), "weight_omitted"),
            entry("omega_1", "the pendulum alone on a fixed pin: sqrt(g/L)",
                  num(math.sqrt(g / L), "rad/s"), known="none")]


def springs_in_series():
    m, k1, k2, L1, L2, v0 = 4.0, 600.0, 300.0, 0.25, 0.2, 0.5
    w = math.sqrt(k1 * k2 / (k1 + k2) / m)
    wp = math.sqrt((k1 + k2) / m)  # the springs added as if side by side

    def block(w_, t):  # distance from the wall, struck at rest with both springs free
        return L1 + L2 + v0 / w_ * math.sin(w_ * t)

    def joint(x):  # the joint's balance k1 (xj - L1) = k2 (x - xj - L2)
        return (k1 * L1 + k2 * (x - L2)) / (k1 + k2)

    return [entry("omega_n", "the springs added as in parallel: sqrt((k1 + k2)/m)",
                  num(wp, "rad/s"), "springs_in_series"),
            entry("omega_n", "frequency in Hz (w/2 pi) given in rad/s",
                  num(w / (2 * math.pi), "rad/s"), "rev_rad"),
            entry("block_at_300ms", "the springs added as in parallel",
                  num(block(wp, 0.3) * 1e3, "mm"), "springs_in_series"),
            entry("joint_at_300ms", "the springs added as in parallel",
                  num(joint(block(wp, 0.3)) * 1e3, "mm"), "springs_in_series"),
            entry("first_spring_tension_at_300ms",
                  "the block's whole displacement on the first spring: k1 (x - L1 - L2)",
                  num(k1 * (block(w, 0.3) - L1 - L2), "N"), known="none"),
            entry("farthest", "the amplitude v0/w given for the distance from the wall",
                  num(v0 / w * 1e3, "mm"), known="none")]


def three_cart_chain():
    m = np.array([3.0, 2.0, 1.0])
    k1, k2, k3, c, v0 = 400.0, 300.0, 200.0, 12.0, 0.6
    K = np.array([[k1 + k2, -k2, 0.0], [-k2, k2 + k3, -k3], [0.0, -k3, k3]])
    root = np.diag(1 / np.sqrt(m))
    w2, u = np.linalg.eigh(root @ K @ root)
    w, shapes = np.sqrt(w2), root @ u
    # the damper ignored: modal superposition of the undamped modes from x = 0, x3' = v0
    # (modal masses 1 in the mass-normalised shapes: q_r' (0) = shapes[:, r] . M x'(0))
    rates = shapes.T @ (m * np.array([0.0, 0.0, v0]))

    def undamped(t):
        return shapes @ (rates / w * np.sin(w * t)), shapes @ (rates * np.cos(w * t))

    # the damper read as proportional: zeta_r = phi_r^T C phi_r / (2 w_r) for mass-normalised
    # shapes (only cart 1's damper: c phi_1r^2)
    modal_zeta = c * shapes[0] ** 2 / (2 * w)
    return [entry("omega_1", "frequency in Hz (w/2 pi) given in rad/s",
                  num(w[0] / (2 * math.pi), "rad/s"), "rev_rad"),
            entry("omega_1", "cart 1 alone on spring 1: sqrt(k1/m1)",
                  num(math.sqrt(k1 / m[0]), "rad/s"), known="none"),
            entry("omega_3", "the masses and stiffnesses summed: sqrt((k1+k2+k3)/(m1+m2+m3))",
                  num(math.sqrt((k1 + k2 + k3) / m.sum()), "rad/s"), known="none"),
            entry("zeta_1", "cart 1 alone with the damper: c/(2 sqrt(k1 m1))",
                  num(c / (2 * math.sqrt(k1 * m[0])), "1"), known="none"),
            entry("zeta_2", "the damping taken as proportional: phi^T C phi/(2 w) of the "
                  "undamped mode", num(modal_zeta[1], "1"), known="none"),
            entry("mode_1_ratio", "the ratio turned over: cart 1's amplitude over cart 3's",
                  num(shapes[0, 0] / shapes[2, 0], "1"), known="none"),
            # cart 3 is two springs from the damper: 0.5 % off at 0.25 s
            entry("x3_at_250ms", "damping ignored: undamped modal superposition",
                  num(undamped(0.25)[0][2] * 1e3, "mm"), "damping_omitted", inside=True),
            entry("x1_at_250ms", "damping ignored: undamped modal superposition",
                  num(undamped(0.25)[0][0] * 1e3, "mm"), "damping_omitted"),
            entry("v1_at_250ms", "damping ignored: undamped modal superposition",
                  num(undamped(0.25)[1][0], "m/s"), "damping_omitted"),
            entry("time_cart3_stops", "cart 3 alone on spring 3: a quarter of 2 pi sqrt(m3/k3)",
                  num(math.pi / 2 * math.sqrt(m[2] / k3) * 1e3, "ms"), known="none")]


def light_pulley_hanger():
    mA, mB, g = 8.0, 20.0, 9.81
    aA = g * (mB / 2 - mA) / (mA + mB / 4)
    # the cord's two strands at the pulley counted once: yB' = -yA', T - mA g = mA aA,
    # T - mB g = -mB aA
    once = g * (mB - mA) / (mA + mB)
    # the strands' family reads a cord's several ends on one body; here they end on the
    # massless pulley, whose balance is a constraint: not named yet
    return [entry("accel_A", "one strand at the movable pulley: (mB - mA) g/(mA + mB)",
                  num(once, "m/s^2"), "strands_miscounted", known="none"),
            entry("tension", "tension taken as block A's weight mA g", num(mA * g, "N"),
                  "tension_as_weight", "reaction_as_weight"),
            entry("tension", "the tension taken as its share of B's weight at rest: mB g/2",
                  num(mB * g / 2, "N"), "tension_as_weight", "reaction_as_weight", known="none"),
            entry("hanger_pull", "the short cord's pull taken as block B's weight mB g",
                  num(mB * g, "N"), "tension_as_weight", "reaction_as_weight"),
            entry("accel_B", "block B's acceleration taken equal to block A's (sign kept)",
                  num(aA, "m/s^2"), known="none"),
            # S = 2 T exactly: only the factor is said
            entry("hanger_pull", "the long cord's tension for the short cord's pull",
                  num(mA * (g + aA), "N"), known="generic", generic=("factor_2",))]


def damped_block_positions():
    m, k, v0 = 5.0, 2000.0, 1.0  # c = 40 N s/m is what these mistakes leave out
    wn = math.sqrt(k / m)  # the block started from equilibrium: x = v0/wn sin(wn t) undamped
    return [entry("time_back", "damping ignored: half the undamped period pi/wn",
                  num(math.pi / wn * 1000, "ms"), "damping_omitted"),
            entry("peak_displacement", "damping ignored: the undamped amplitude v0/wn",
                  num(v0 / wn * 1000, "mm"), "damping_omitted"),
            entry("x_at_30ms", "damping ignored: v0/wn sin(wn t)",
                  num(v0 / wn * math.sin(wn * 0.03) * 1000, "mm"), "damping_omitted"),
            entry("speed_back_half_damping", "speed taken as conserved: the blow's 1 m/s",
                  num(v0, "m/s"), "damping_omitted", "value_at_start")]


def ballistic_pendulum():
    m, M, v0 = 0.010, 2.0, 400.0
    after = m * v0 / (m + M)
    kept = 10.0 * v0 / (10.0 + M)  # the bullet's 10 g read as 10 kg
    return [entry("bullet_ke_before", "the bullet's 10 g read as 10 kg",
                  num(0.5 * 10.0 * v0**2, "J"), "given_unit"),
            entry("ke_lost", "the bullet's 10 g read as 10 kg",
                  num(0.5 * 10.0 * v0**2 - 0.5 * (10.0 + M) * kept**2, "J"), "given_unit"),
            entry("share_lost", "the bullet's 10 g read as 10 kg: M/(m + M)",
                  num(M / (10.0 + M), "1"), "given_unit"),
            entry("speed_after", "the two masses exchanged",
                  num(M * v0 / (m + M), "m/s"), "given_swap", known="none"),
            entry("impulse_on_bullet", "the impulse on the block given for the bullet's",
                  vec(V(-m * (after - v0), 0), "N*s"), "sign")]


def ball_with_drag():
    v0, alpha, g = 20.0, 50 * D, 9.81
    # without the drag the landing speed is the throw's (energy conserved): one mistake
    return [entry("landing_speed", "speed taken as conserved: the throw's 20 m/s",
                  num(v0, "m/s"), "value_at_start", "force_omitted"),
            entry("time_of_flight", "drag ignored: 2 v0 sin(alpha)/g",
                  num(2 * v0 * math.sin(alpha) / g, "s"), "force_omitted"),
            entry("apex_height", "drag ignored: (v0 sin(alpha))^2/(2 g)",
                  num((v0 * math.sin(alpha)) ** 2 / (2 * g), "m"), "force_omitted"),
            entry("range", "drag ignored: v0^2 sin(2 alpha)/g",
                  num(v0**2 * math.sin(2 * alpha) / g, "m"), "force_omitted"),
            entry("position_at_1s", "drag ignored: (v0 cos(alpha) t, v0 sin(alpha) t - g t^2/2)",
                  vec(V(v0 * math.cos(alpha), v0 * math.sin(alpha) - g / 2), "m"), "force_omitted")]


def yo_yo():
    m, k, r, g = 0.2, 0.03, 0.01, 9.81
    a_G = -g * r**2 / k**2  # moments about S with I_G = m k²
    w = 0.5 / r
    return [entry("accel", "moments about the string point S with I_G (m r² left out)",
                  num(a_G, "m/s^2"), "central_inertia_at_pivot"),
            entry("tension", "tension taken as the weight m g", num(m * g, "N"),
                  "reaction_as_weight"),
            entry("tension", "T = m g + m a with a from I_G about S",
                  num(m * g + m * a_G, "N"), "central_inertia_at_pivot"),
            entry("spin_momentum", "I = m k²/2, k read as a disk's radius",
                  vec(V(0, 0, -m * k**2 / 2 * w), "kg*m^2/s"), "factor_2")]


def bead_on_hoop():
    m, R, g, th = 0.1, 0.5, 9.81, 60 * D
    W = math.sqrt(g / (R * math.cos(th)))  # θ'' = sin θ (Ω² cos θ - g/R) = 0
    rho = R * math.sin(th)  # the bead's distance from the spin axis
    return [entry("Omega_for_60", "g left out of the tangential balance (m for m g)",
                  num(math.sqrt(1 / (R * math.cos(th))), "rad/s"), "mass_for_weight"),
            entry("hoop_force", "weight left out: the hoop's force only turns the bead, m Ω² ρ",
                  num(m * W**2 * rho, "N"), "weight_omitted"),
            entry("omega_small_oscillations",
                  "g left out (m for m g): ω_n = Ω sin θ with Ω² = 1/(R cos θ)",
                  num(math.sqrt(1 / (R * math.cos(th))) * math.sin(th), "rad/s"),
                  "mass_for_weight"),
            # the spin axis's distance taken as R, not R sin θ: not generated (a geometric slip
            # of the position, in a dynamics model); nothing is said of it
            entry("Omega_for_60", "centripetal term m Ω² R instead of m Ω² R sin θ: tan θ = "
                  "Ω² R/g", num(math.sqrt(g * math.tan(th) / R), "rad/s"), "position_term",
                  known="none"),
            entry("omega_small_oscillations", "the linearisation's sin² θ left out: ω_n = Ω",
                  num(W, "rad/s"), "position_term", known="none"),
            # at 60° the weight is exactly half the answer (cos 60° = ½), but the bead held
            # by its weight alone names the weight
            entry("hoop_force", "hoop's force taken as the weight m g", num(m * g, "N"),
                  "reaction_as_weight")]


def block_on_cart():
    m, M, mu, g, v0 = 2.0, 8.0, 0.3, 9.81, 5.0
    v = m * v0 / (m + M)  # momentum
    a_block = -mu * g
    t = (v - v0) / a_block
    return [entry("t_slide", "friction μ m instead of μ m g",
                  num(v0 / (mu * (1 + m / M)), "s"), "mass_for_weight"),
            entry("common_speed", "masses exchanged in the momentum balance: M v0/(m + M)",
                  num(M * v0 / (m + M), "m/s"), "given_swap"),
            entry("cart_acceleration", "masses exchanged: μ M g/m", num(mu * M * g / m, "m/s^2"),
                  "given_swap"),
            entry("t_slide", "cart taken as fixed: the block stops at v0/(μ g)",
                  num(v0 / (mu * g), "s"), "surface_taken_fixed"),
            entry("slide_distance", "cart taken as fixed: v0²/(2 μ g)",
                  num(v0**2 / (2 * mu * g), "m"), "surface_taken_fixed"),
            entry("energy_lost", "cart taken as fixed: all of ½ m v0² lost",
                  num(m * v0**2 / 2, "J"), "surface_taken_fixed"),
            # momentum conserved, but only the block's kinetic energy counted (the cart's
            # ½ M v² gained left out)
            entry("energy_lost", "the cart's kinetic energy left out: ½ m (v0² - v²)",
                  num(m * (v0**2 - v**2) / 2, "J"), "body_ke_omitted"),
            entry("slide_distance", "the block's travel over the floor for its slide on the cart",
                  num(v0 * t + a_block * t**2 / 2, "m"), "other_point", known="none")]


def flywheel():
    m, M, T, w0 = 500.0, 1500.0, 0.2, 300 * 2 * math.pi / 60
    I = M * T / (0.1 * w0)  # I Δω = M T
    w1 = 0.9 * w0
    turned = (w0 + w1) / 2 * T  # rad
    return [entry("R_needed", "flywheel taken as a ring (I = m R²)", num(math.sqrt(I / m), "m"),
                  "other_shape_inertia"),
            entry("speed_after", "answer left in rad/s", num(w1, "rpm"), "rpm_rad"),
            entry("turns_during_stroke", "answer left in radians", num(turned, "deg"),
                  "rad_as_deg"),
            entry("R_needed", "300 rpm used as rad/s",
                  num(math.sqrt(2 * M * T / (0.1 * 300) / m), "m"), "given_rate_unit"),
            entry("energy_taken", "a 10 % speed drop taken as a 10 % energy drop",
                  num(0.1 * I * w0**2 / 2, "J"), "energy_formula", known="none"),
            entry("turns_during_stroke", "the deceleration left out: ω0 T",
                  num(w0 * T / D, "deg"), "drop_tangential", known="none")]


def rod_on_ice():
    m, L, J = 1.5, 1.2, 3.0
    vG, w = J / m, J * (L / 2) / (m * L**2 / 12)
    return [entry("omega_after", "spin taken as clockwise", num(-w, "rad/s"), "sign"),
            entry("omega_after", "moment arm L instead of L/2: J L = I_G ω",
                  num(J * L / (m * L**2 / 12), "rad/s"), "factor_2"),
            entry("point_at_rest", "the point at rest placed on the struck side of G",
                  vec(V(vG / w, 0), "m"), "sign"),
            entry("vB_after", "the impulse's moment forgotten (no spin): v_B = v_G",
                  vec(V(0, vG), "m/s"), "impulse_moment_omitted"),
            entry("vB_after", "ω × r added the wrong way: the struck end A's velocity",
                  vec(V(0, vG + w * L / 2), "m/s"), "other_point"),
            entry("omega_after", "I about the end (m L²/3) instead of about G",
                  num(J * (L / 2) / (m * L**2 / 3), "rad/s"), "central_inertia_at_pivot",
                  known="none")]


def marble():
    v0, mu, g = 3.0, 0.1, 9.81
    return [entry("t_star_s", "friction μ m instead of μ m g", num(2 * v0 / (7 * mu), "s"),
                  "mass_for_weight"),
            entry("t_star_s", "slip rate μ g: the friction's moment (the spin-up) left out",
                  num(v0 / (mu * g), "s"), "spin_omitted", known="none"),
            # with the marble's inertia mistaken it rolls after the bowling ball, and the
            # solver cannot integrate past the bowling ball's end of slip: not generated
            entry("t_star_s", "marble taken as a thin shell (2/3 m r²)",
                  num(2 * v0 / (5 * mu * g), "s"), "other_shape_inertia", known="none")]


def ball_skids_then_rolls():
    m, R, g, beta, mu_k, v0, w0 = 7.2, 0.109, 9.81, 10 * D, 0.12, 6.0, 20.0
    s, c = math.sin(beta), math.cos(beta)
    u0 = v0 + R * w0  # the slip speed at the throw

    def rolls_at(normal):  # skidding with friction mu_k normal: (time, speed) when it rolls
        a, alpha = -g * s - mu_k * normal / m, -mu_k * normal * R / (0.4 * m * R**2)
        t = u0 / -(a + R * alpha)
        return t, v0 + a * t

    return [entry("v_rolls", "friction μ m g: the normal force taken as the weight",
                  num(rolls_at(m * g)[1], "m/s"), "normal_from_weight"),
            entry("t_rolls", "slip rate from the centre alone: the friction's spin-down left out",
                  num(u0 / (g * (s + mu_k * c)), "s"), "spin_omitted", known="none"),
            # R read as 10.9 m (or a mass of m g) keeps the ball skidding past 2 s and to the
            # top: those mistakes give exactly these values, and the grader says so
            entry("friction_at_2s", "kinetic friction μ_k N kept once the ball rolls",
                  num(-mu_k * m * g * c, "N"), "friction_kept_kinetic", known="generic",
                  generic=("weight_for_mass", "given_length_unit")),
            entry("friction_at_2s", "rolling friction drawn down the slope",
                  num(-2 / 7 * m * g * s, "N"), "sign"),
            entry("x_top", "rolling ignored: it skids all the way up",
                  num(v0**2 / (2 * g * (s + mu_k * c)), "m"), "phase_omitted", known="generic",
                  generic=("given_length_unit",))]


def momentum_projection():
    return []


def units_matrix():
    v0, th = 20.0, 60 * D
    v2t, v2n = -v0 * math.sin(th), -v0 * math.cos(th)
    return [entry("v2t", "calculator in radian mode: sin 60", num(-v0 * math.sin(60.0), "ft/s"),
                  "given_deg_as_rad"),
            entry("v2n", "calculator in radian mode: cos 60", num(-v0 * math.cos(60.0), "ft/s"),
                  "given_deg_as_rad"),
            entry("v2n", "e_n taken as sin θ i - cos θ j (its sign flipped)", num(-v2n, "ft/s"),
                  "sign"),
            entry("v2t", "v0 converted to m/s, the answer labelled ft/s",
                  num(v2t * 0.3048, "ft/s"), "ft_m"),
            entry("v2t", "sin and cos exchanged: -v0 cos θ", num(v2n, "ft/s"),
                  "given_complement"),
            entry("v2_N", "e_t, e_n components copied as i, j", vec(V(v2t, v2n), "ft/s"),
                  "other_basis")]


TABLES = {
    "bowling_3_15_2_cannonball": cannonball,
    "bowling_3_15_3_mass_spring_damper": mass_spring_damper,
    "bowling_3_15_4_pendulum": pendulum,
    "bowling_3_15_5_cylinder": cylinder,
    "bowling_3_15_6_gears": gears,
    "bowling_3_15_7_rolling_ball_mound": rolling_ball_mound,
    "bowling_3_15_8_connected_blocks": connected_blocks,
    "bowling_P3_17_rocking_block": rocking_block,
    "bowling_P3_8_planetary_gears": planetary_gears,
    "ruina_10_10_collar_bent_arm": collar_bent_arm,
    "ruina_10_11_wheel_on_rotating_rod": wheel_on_rotating_rod,
    "ruina_10_1_cycloid": cycloid,
    "ruina_10_2_limacon": limacon,
    "ruina_10_3_spiral_bug": spiral_bug,
    "ruina_10_4_10_7_rotating_tube_accel": rotating_tube_accel,
    "ruina_10_5_rod_collar_disk": rod_collar_disk,
    "ruina_10_6_rotating_tube_velocity": rotating_tube_velocity,
    "ruina_10_8_collar_in_disk_track": collar_in_disk_track,
    "ruina_10_9_unit_vector_rates": unit_vector_rates,
    "ruina_sec10_bug_on_tire": bug_on_tire,
    "atwood_machine": atwood,
    "block_on_turntable": block_on_turntable,
    "cord_over_table_pulley": cord_over_table_pulley,
    "gyroscope_pivot_precession": gyroscope,
    "pendulum_in_accelerating_truck": truck_pendulum,
    "block_sliding_down_incline": block_sliding_down_incline,
    "car_braking_weight_transfer": car_braking,
    "damped_pendulum_vibration": damped_pendulum,
    "ladder_wall_lift_off": ladder_lift_off,
    "pendulum_pin_reaction": pendulum_pin,
    "rod_strikes_ledge": rod_ledge,
    "ruina_9_19_falling_ladder": falling_ladder,
    "ruina_9_20_ladder_energy": ladder_energy,
    "ruina_9_21_wheel_incline": wheel_incline,
    "ruina_9_23_ball_impulse_momentum": ball_skid,
    "ruina_9_26_billiard_cue": billiard,
    "two_mass_spring_chain": spring_chain,
    "cart_pendulum_spring_modes": cart_pendulum,
    "damped_block_positions": damped_block_positions,
    "three_cart_chain_vibration": three_cart_chain,
    "block_on_springs_in_series": springs_in_series,
    "light_pulley_hanger": light_pulley_hanger,
    "ballistic_pendulum_energy_lost": ballistic_pendulum,
    "ball_thrown_with_drag_apex_and_landing": ball_with_drag,
    "yo_yo_unwinding": yo_yo,
    "bead_on_rotating_hoop": bead_on_hoop,
    "block_slides_on_cart": block_on_cart,
    "flywheel_speed_drop": flywheel,
    "rod_struck_on_ice": rod_on_ice,
    "ruina_9_22_marble_bowling_ball": marble,
    "bowling_ball_skids_then_rolls": ball_skids_then_rolls,
    "ruina_9_24_momentum_projection": momentum_projection,
    "ruina_9_25_units_matrix": units_matrix,
}


# Symbolic answers as a student would type them, each derived by hand from the mistaken balance.
SYMBOLIC = {
    "atwood_machine": [
        entry("a1_symbolic", "tension taken as m2 g in block 1's balance", "g*(m2 - m1)/m1",
              "tension_as_weight"),
        entry("tension_symbolic", "tension taken as the heavier block's weight", "m2*g",
              "tension_as_weight")],
    "pendulum_pin_reaction": [
        entry("eom_symbolic", "I_G θ'' = -m g (L/2) sin θ about the pin", "-6*g*sin(theta)/L",
              "central_inertia_at_pivot")],
    "block_sliding_down_incline": [
        entry("accel_symbolic", "friction drawn down the slope",
              "g*(sin(beta) + mu_k*cos(beta)*sign(xd))", "friction_reversed"),
        entry("accel_symbolic", "friction μ m g", "g*(sin(beta) - mu_k*sign(xd))",
              "normal_from_weight")],
    "car_braking_weight_transfer": [
        entry("front_share_symbolic", "static share: weight transfer ignored", "m*g*b/(a + b)",
              "weight_transfer_ignored")],
    "rod_strikes_ledge": [
        entry("omega_symbolic", "perfectly elastic impact (e = 1)", "-3*v0/L",
              "restitution_ignored")],
    "ruina_9_20_ladder_energy": [
        entry("vG_symbolic", "rotational energy left out: ½ m v² = m g (L/2)(sin θ0 - sin θ)",
              "sqrt(g*L*(sin(theta0) - sin(theta)))", "rotational_ke_omitted"),
        entry("theta_wall_lost", "sine and cosine swapped: cos θ = (2/3) sin θ0",
              "acos(2*sin(theta0)/3)", known="none"),
        entry("theta_wall_lost", "the factor cos θ set to zero: the ladder upright",
              "pi/2", known="none")],
    "ruina_9_21_wheel_incline": [
        entry("aG_symbolic", "moments about C with I_G = m r²/2 + M R²",
              "2*g*r^2*(m + 2*M)*sin(theta)/(m*r^2 + 2*M*R^2)", "central_inertia_at_pivot")],
    "ruina_9_26_billiard_cue": [
        entry("omega_symbolic", "ball taken as a thin shell (2/3 m r²)", "-3*d*v/(2*r^2)",
              "other_shape_inertia")],
    "yo_yo_unwinding": [
        entry("tension_symbolic", "T = m g - m a with a = g r²/k² (I_G about S)",
              "m*g*(1 - r^2/k^2)", "central_inertia_at_pivot")],
    "bead_on_rotating_hoop": [
        entry("eom_symbolic", "g left out of the weight's tangential part (m for m g)",
              "sin(theta)*(Omega^2*cos(theta) - 1/R)", "mass_for_weight"),
        entry("eom_symbolic", "weight left out: only the spin's centripetal part",
              "Omega^2*sin(theta)*cos(theta)", "weight_omitted"),
        entry("eom_symbolic", "centripetal term with R instead of R sin θ",
              "Omega^2*cos(theta) - g*sin(theta)/R", "position_term", known="none")],
    "block_slides_on_cart": [
        entry("t_slide_symbolic", "friction μ m instead of μ m g", "M*v0/(mu*(m + M))",
              "mass_for_weight"),
        entry("t_slide_symbolic", "cart taken as fixed", "v0/(mu*g)", "surface_taken_fixed")],
    "rod_struck_on_ice": [
        entry("omega_symbolic", "moment arm L instead of L/2", "12*J/(m*L)", "factor_2"),
        entry("omega_symbolic", "spin taken as clockwise", "-6*J/(m*L)", "sign")],
    "ruina_9_22_marble_bowling_ball": [
        entry("t_star", "marble taken as a thin shell (2/3 m r²)", "2*v0/(5*mu*g)",
              "other_shape_inertia"),
        entry("t_star", "marble taken as a disk (½ m r²)", "v0/(3*mu*g)", "other_shape_inertia"),
        entry("t_star", "friction μ m instead of μ m g", "2*v0/(7*mu)", "mass_for_weight"),
        entry("v_at_t_star", "marble taken as a thin shell: v = v0/(1 + 2/3)", "3*v0/5",
              "other_shape_inertia"),
        # friction taken as static: the marble rolls from the start and keeps v0
        entry("v_at_t_star", "friction taken as static: rolling from the start", "v0",
              "static_for_kinetic", known="none")],
    "ruina_9_24_momentum_projection": [
        entry("en_equation_residual", "e_n taken as sin θ i - cos θ j (its sign flipped)",
              "m2*v0*cos(theta) + (-m1*v1p*sin(theta) + m2*v2n)", "sign"),
        entry("et_equation_residual", "e_t taken as -cos θ i - sin θ j (its sign flipped)",
              "m2*v0*sin(theta) + m1*v1p*cos(theta) + m2*v2t", "sign"),
        entry("en_equation_residual", "masses left out: velocities balanced, not momenta",
              "-v0*cos(theta) - (-v1p*sin(theta) + v2n)", "dimension"),
        entry("en_equation_residual", "sin and cos exchanged in the projections",
              "-m2*v0*sin(theta) - (-m1*v1p*cos(theta) + m2*v2n)", "given_complement",
              known="none"),
        entry("en_equation_residual", "the block's momentum left out (it moves along i only)",
              "-m2*v0*cos(theta) - m2*v2n", "drop_body", known="none"),
        entry("et_equation_residual", "the ball's velocity before taken upward (+v0 j)",
              "m2*v0*sin(theta) - (m1*v1p*cos(theta) + m2*v2t)", "given_sign")],
}


def tables() -> dict[str, list[dict]]:
    return {problem: make() + SYMBOLIC.get(problem, []) for problem, make in TABLES.items()}


if __name__ == "__main__":
    here = Path(__file__).parent
    for problem, rows in tables().items():
        (here / f"{problem}.yaml").write_text(
            f"# Typical mistakes on {problem}: written by typical.py (numpy, by hand).\n"
            + yaml.safe_dump(rows, sort_keys=False, allow_unicode=True), encoding="utf-8")
