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
    return f"{value:.4g} {unit}"


def vec(v, unit):
    x, y, z = (0.0 if abs(c) < 1e-12 else c for c in v)
    return f"({x:.4g}, {y:.4g}, {z:.4g}) {unit}"


def entry(objective, mistake, answer, *codes, inside=False):
    out = {"objective": objective, "mistake": mistake, "answer": answer,
           "diagnosis": list(codes)}
    if inside:
        out["inside"] = True
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
    v, a, ex, ey = b()
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
    thd, phd = np.linalg.solve(m, -np.array([xAd, 0.0]))
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
}


def tables() -> dict[str, list[dict]]:
    return {problem: make() for problem, make in TABLES.items()}


if __name__ == "__main__":
    here = Path(__file__).parent
    for problem, rows in tables().items():
        (here / f"{problem}.yaml").write_text(
            f"# Typical mistakes on {problem}: written by typical.py (numpy, by hand).\n"
            + yaml.safe_dump(rows, sort_keys=False, allow_unicode=True), encoding="utf-8")
