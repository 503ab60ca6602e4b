"""Typical student mistakes on the problem bank's held-out problems, computed by hand.

Numpy only (nothing from mechgrade, no sympy). Each row is what a student who made that
mistake answers, worked from the problem's physics with the mistaken step. The rows were
written before mechgrade's mistake families were looked at, and are frozen: the measurement
(measure.py beside this file) judges mechgrade's diagnosis of each row against the row's
``kind``, a name from this file's own vocabulary (KINDS), not from mechgrade's.

``inside`` marks a mistake whose value is within the default tolerance (1 %) of the correct
answer (the reference values are tests/data/independent/bank.py's).

Run ``python tests/data/heldout/typical.py`` to rewrite the tables <problem>.yaml beside it;
the test suite checks that the tables are what this script gives.
"""
from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import yaml

HERE = Path(__file__).parent
DEG = np.pi / 180.0
G0 = 9.81
RPM = 2 * np.pi / 60
HP = 550.0

KINDS = {
    "constant_acceleration": "a varying acceleration (a(v), a(x), a spring) taken as constant",
    "initial_speed_forgotten": "the initial speed (or spin) left out",
    "sign": "the right size with the wrong sense (or a relative quantity subtracted the wrong way)",
    "sin_cos_swap": "sine and cosine of an angle exchanged",
    "deg_as_rad": "an angle in degrees used as radians (calculator mode)",
    "normal_as_weight": "a normal force taken as the weight m g",
    "friction_as_mu_m_g": "friction computed as mu m g instead of mu N",
    "friction_reversed": "friction drawn in the wrong direction",
    "tension_as_weight": "a cord tension taken as a weight (static value)",
    "reaction_as_static": "a pin or support reaction taken as its static value",
    "weight_for_mass": "the weight used where the mass belongs (or the mass for the weight)",
    "unit_slip": "a unit not converted (km/h, rpm, lb/in, mm, hp, g = 9.81 in ft/s^2)",
    "hz_for_rad_s": "a frequency in hertz given for rad/s or the reverse (a factor 2 pi)",
    "period_for_frequency": "a period and a frequency confused (1/f for f, or 2 pi/omega for omega)",
    "series_parallel": "springs in parallel combined as if in series, or the reverse",
    "inertia_about_wrong_point": "the moment of inertia about the mass centre used about a pin (or the reverse)",
    "inertia_wrong_shape": "the inertia of another shape (a disk's for a hoop, m r^2 for m k^2 ...)",
    "massless_rotor": "the inertia of a drum, pulley or wheel left out",
    "coriolis_dropped": "the Coriolis term 2 r' theta' (2 omega x v_rel) dropped",
    "coriolis_halved": "the Coriolis term written r' theta' (no factor 2)",
    "centripetal_dropped": "the centripetal (normal) part of an acceleration dropped",
    "tangential_dropped": "the tangential part of an acceleration dropped",
    "curvature_without_slope": "radius of curvature taken as 1/y'' without the slope term",
    "velocity_component_wrong": "a velocity component or rate taken as the whole speed (or the wrong projection)",
    "kinematic_factor": "a kinematic relation's factor wrong (pulley strands, rolling, lever ratio)",
    "angular_rate_equal": "a connected body's angular rate taken equal to the driver's",
    "acceleration_zero_constant_speed": "an acceleration set to zero because a speed or rate is constant",
    "spring_energy_total_length": "a spring's energy from its total length instead of its stretch",
    "spring_energy_difference": "a spring's energy from the change of stretch squared, (s2 - s1)^2",
    "spring_term_dropped": "a spring's force or energy left out",
    "gravity_dropped": "gravity (or its component) left out",
    "ke_conserved": "kinetic energy taken as conserved in an impact (energy lost = 0)",
    "head_on": "an oblique impact treated as head-on (whole speeds along the line of impact)",
    "restitution_wrong_component": "the coefficient of restitution applied to the wrong component (or to both)",
    "restitution_ignored": "restitution ignored (perfectly plastic or perfectly elastic assumed)",
    "momentum_with_pin": "linear momentum taken as conserved although a pin gives an impulse",
    "efficiency_inverted": "efficiency multiplied instead of divided (or the reverse)",
    "acceleration_term_dropped": "the m a term dropped from a force (the static value)",
    "speed_conserved": "speed taken as conserved where angular momentum is",
    "half_factor": "a factor 1/2 dropped or added (kinetic energy, mean speed, bearing spacing)",
    "rolling_assumed": "rolling without slip assumed where the body slips",
    "damping_ignored": "damping ignored in the response",
    "translation_ke_dropped": "the translational kinetic energy of a rolling body left out",
    "wrong_root": "the other root of a quadratic or another assembly branch",
    "magnitudes_added": "magnitudes of vectors added instead of components",
}


def _bank():
    path = HERE.parent / "independent" / "bank.py"
    spec = importlib.util.spec_from_file_location("independent_bank", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.CASES


REFERENCE = _bank()


def num(value, unit):
    return f"{value:.4g}" if unit == "1" else f"{value:.4g} {unit}"


def vec(v, unit):
    x, y, z = (0.0 if abs(c) < 1e-12 else float(c) for c in (*v, 0.0, 0.0, 0.0)[:3])
    return f"({x:.4g}, {y:.4g}, {z:.4g}) {unit}"


def row(objective, mistake, kind, answer):
    assert kind in KINDS, kind
    return {"objective": objective, "mistake": mistake, "kind": kind, "answer": answer}


# ------------------------------------------------------------------ rectilinear motion

def boat_coasting_quadratic_drag():
    m, c, v0, v1 = 400.0, 20.0, 12.0, 4.0
    a0 = c * v0**2 / m
    return [row("time", "deceleration taken constant at its initial value c v0^2/m",
                "constant_acceleration", num((v0 - v1) / a0, "s")),
            row("distance", "constant deceleration c v0^2/m in v^2 = v0^2 - 2 a d",
                "constant_acceleration", num((v0**2 - v1**2) / (2 * a0), "m")),
            row("distance", "ln(v1/v0) for ln(v0/v1): a negative distance", "sign",
                num(m / c * np.log(v1 / v0), "m")),
            row("deceleration", "deceleration at the initial speed 12 m/s", "initial_speed_forgotten",
                num(-a0, "m/s^2")),
            row("deceleration", "drag divided by the weight instead of the mass", "weight_for_mass",
                num(-c * v1**2 / (m * G0), "m/s^2"))]


def spring_launcher_a_of_x():
    m, k, d = 0.5, 800.0, 0.1
    wn = np.sqrt(k / m)
    return [row("speed", "spring energy k d^2 without the 1/2 (= m v^2/2)", "half_factor",
                num(np.sqrt(2 * k * d**2 / m), "m/s")),
            row("time", "constant acceleration k d/m over the distance d", "constant_acceleration",
                num(np.sqrt(2 * d / (k * d / m)), "s")),
            row("time", "a whole period 2 pi sqrt(m/k) instead of a quarter", "period_for_frequency",
                num(2 * np.pi / wn, "s")),
            row("time", "time = distance / final speed, as if at constant speed",
                "constant_acceleration", num(d / (d * wn), "s")),
            row("speed", "deflection in cm (10) in the energy with k in N/m", "unit_slip",
                num(10 * wn, "m/s")),
            row("kinetic_energy", "k d^2 without the 1/2", "half_factor", num(k * d**2, "J"))]


def car_constant_power_acceleration():
    m, P, v1, v2 = 1200.0, 60e3, 10.0, 25.0
    F1 = P / v1
    return [row("time", "force taken constant at P/v1", "constant_acceleration",
                num(m * (v2 - v1) / F1, "s")),
            row("time", "power written as force x distance: t from P t = m (v2 - v1)",
                "velocity_component_wrong", num(m * (v2 - v1) / P, "s")),
            row("distance", "constant force P/v1 in v2^2 - v1^2 = 2 a d", "constant_acceleration",
                num(m * (v2**2 - v1**2) / (2 * F1), "m")),
            row("distance", "distance = mean speed x the right time", "constant_acceleration",
                num((v1 + v2) / 2 * m * (v2**2 - v1**2) / (2 * P), "m")),
            row("force_at_25", "force at the initial speed P/v1", "initial_speed_forgotten",
                num(F1, "N")),
            row("force_at_25", "kW not converted: P = 60 W", "unit_slip", num(60 / v2, "N"))]


# ------------------------------------------------------------------ curvilinear motion

def car_on_parabolic_road():
    b, x, v, at = 200.0, 40.0, 15.0, 2.0
    rho0 = b / 2  # 1/y''
    ref = REFERENCE["car_on_parabolic_road"]()
    return [row("radius_of_curvature", "rho = 1/y'' without the slope term", "curvature_without_slope",
                num(rho0, "m")),
            row("radius_of_curvature", "exponent 1/2 for 3/2 in (1 + y'^2)^(3/2)/y''",
                "curvature_without_slope", num(np.sqrt(1 + (2 * x / b) ** 2) / (2 / b), "m")),
            row("normal_acceleration", "v^2/rho with rho = 1/y''", "curvature_without_slope",
                num(v**2 / rho0, "m/s^2")),
            row("normal_acceleration", "v/rho (not squared)", "unit_slip",
                num(v / ref["radius_of_curvature"], "m/s^2")),
            row("acceleration_magnitude", "only the tangential part", "centripetal_dropped",
                num(at, "m/s^2")),
            row("acceleration_magnitude", "a_t + a_n added", "magnitudes_added",
                num(at + ref["normal_acceleration"], "m/s^2"))]


def radar_tracks_airplane_polar():
    h, th, v = 3000.0, 30 * DEG, 200.0
    r = h / np.sin(th)
    return [row("distance", "r = h/cos theta", "sin_cos_swap", num(h / np.cos(th), "m")),
            row("r_dot", "r' = v sin theta", "sin_cos_swap", num(v * np.sin(th), "m/s")),
            row("r_dot", "r' = v (the whole speed)", "velocity_component_wrong", num(v, "m/s")),
            row("theta_dot", "theta' = v/r (the whole speed across the line of sight)",
                "velocity_component_wrong", num(-v / r, "rad/s")),
            row("theta_dot", "positive: the angle taken to grow", "sign",
                num(v * np.sin(th) / r, "rad/s")),
            row("r_ddot", "r'' = 0 because the speed is constant", "acceleration_zero_constant_speed",
                num(0.0, "m/s^2")),
            row("theta_ddot", "theta'' = 0 because the speed is constant",
                "acceleration_zero_constant_speed", num(0.0, "rad/s^2")),
            row("theta_ddot", "Coriolis term without the 2: theta'' = -r' theta'/r",
                "coriolis_halved", num(v * np.cos(th) * v * np.sin(th) / r**2, "rad/s^2"))]


def collar_on_circle_rotating_rod():
    b, th, w = 0.3, 30 * DEG, 3.0
    r = 2 * b * np.cos(th)
    rd, rdd = -2 * b * w * np.sin(th), -2 * b * w**2 * np.cos(th)
    return [row("velocity", "r' = 0 (the rod's speed only: r theta')", "velocity_component_wrong",
                vec([0.0, r * w], "m/s")),
            row("acceleration", "Coriolis term 2 r' theta' dropped", "coriolis_dropped",
                vec([rdd - r * w**2, 0.0], "m/s^2")),
            row("acceleration", "r theta'^2 dropped from the radial part", "centripetal_dropped",
                vec([rdd, 2 * rd * w], "m/s^2")),
            row("acceleration", "Coriolis term r' theta' (no 2)", "coriolis_halved",
                vec([rdd - r * w**2, rd * w], "m/s^2")),
            row("speed", "speed r theta' only", "velocity_component_wrong", num(r * w, "m/s")),
            row("speed", "|r'| + r theta' added", "magnitudes_added", num(abs(rd) + r * w, "m/s"))]


def two_cars_relative_motion():
    ref = REFERENCE["two_cars_relative_motion"]()
    vA, aA, R, vB, atB, phi = 25.0, 1.5, 100.0, 15.0, -2.0, 60 * DEG
    e_r = np.array([np.cos(phi), np.sin(phi)])
    e_t = np.array([-np.sin(phi), np.cos(phi)])
    v_rel = np.array(ref["relative_velocity"][:2])
    a_B_no_n = atB * e_t
    return [row("relative_velocity", "A relative to B (v_A - v_B)", "sign", vec(-v_rel, "m/s")),
            row("relative_velocity", "v_B + v_A added", "sign",
                vec(vB * e_t + np.array([0.0, vA]), "m/s")),
            row("relative_acceleration", "B's normal acceleration v^2/R left out",
                "centripetal_dropped", vec(a_B_no_n - np.array([0.0, aA]), "m/s^2")),
            row("relative_acceleration", "B's tangential deceleration left out", "tangential_dropped",
                vec(-vB**2 / R * e_r - np.array([0.0, aA]), "m/s^2")),
            row("relative_speed", "speeds subtracted: 25 - 15", "magnitudes_added",
                num(vA - vB, "m/s")),
            row("relative_speed", "speeds added: 25 + 15", "magnitudes_added", num(vA + vB, "m/s"))]


def airplane_crosswind_heading():
    va, w = 240.0, 60.0
    return [row("heading", "tan psi = w/va", "sin_cos_swap", num(np.arctan(w / va) / DEG, "deg")),
            row("heading", "cos psi = w/va", "sin_cos_swap", num(np.arccos(w / va) / DEG, "deg")),
            row("heading", "the angle in radians written as degrees", "deg_as_rad",
                num(np.arcsin(w / va), "deg")),
            row("ground_speed", "va + w added", "magnitudes_added", num(va + w, "km/h")),
            row("ground_speed", "sqrt(va^2 + w^2): the wind added at right angles to the heading",
                "magnitudes_added", num(np.hypot(va, w), "km/h")),
            row("ground_speed", "the airspeed itself", "velocity_component_wrong", num(va, "km/h"))]


# ------------------------------------------------------------------ dependent motion

def truck_hoists_crate_pulley():
    h, L, x, xd = 3.0, 8.0, 4.0, 2.0
    s = np.hypot(x, h)
    return [row("height", "rope taken as one strand to the crate: y = h - (L - s)", "kinematic_factor",
                num(h - (L - s), "m")),
            row("velocity", "half the truck's speed (the slant ignored)", "velocity_component_wrong",
                num(xd / 2, "m/s")),
            row("velocity", "the factor 2 of the two strands left out", "kinematic_factor",
                num(x * xd / s, "m/s")),
            row("velocity", "h/s for x/s: the cosine of the other angle", "sin_cos_swap",
                num(h * xd / s / 2, "m/s")),
            row("acceleration", "zero because the truck's speed is constant",
                "acceleration_zero_constant_speed", num(0.0, "m/s^2")),
            row("acceleration", "the factor 2 of the two strands left out", "kinematic_factor",
                num(xd**2 * h**2 / s**3, "m/s^2"))]


def movable_pulley_two_blocks():
    mA, mB, g = 10.0, 30.0, G0
    # a_A = a_B (no pulley factor), T on A, 2T on B
    aB1 = (2 * mA - mB) * g / (mB + 2 * mA)
    # a_A = -2 a_B but a single strand on B's pulley: T - mB g = mB a_B
    aB2 = (mA - mB) * g / (mB + 2 * mA)
    # T = mA g
    aB3 = (2 * mA * g - mB * g) / mB
    return [row("accel_A", "a_A = -a_B (the pulley's factor 2 left out)", "kinematic_factor",
                num(-aB1, "m/s^2")),
            row("accel_B", "a_A = -a_B (the pulley's factor 2 left out)", "kinematic_factor",
                num(aB1, "m/s^2")),
            row("accel_B", "one strand on B's pulley (T instead of 2T)", "kinematic_factor",
                num(aB2, "m/s^2")),
            row("tension", "tension taken as A's weight", "tension_as_weight", num(mA * g, "N")),
            row("tension", "tension taken as half of B's weight", "tension_as_weight",
                num(mB * g / 2, "N")),
            row("accel_B", "tension taken as A's weight in B's balance", "tension_as_weight",
                num(aB3, "m/s^2")),
            row("accel_A", "B taken to go up: the sign of both accelerations", "sign",
                num(-REFERENCE["movable_pulley_two_blocks"]()["accel_A"], "m/s^2"))]


# ------------------------------------------------------------------ work and energy

def collar_spring_vertical_rod():
    m, g, k, L0, d, h = 2.0, G0, 200.0, 0.3, 0.4, 0.3
    s1, s2 = d - L0, np.hypot(d, h) - L0
    l2 = np.hypot(d, h)

    def v(spring_work):
        return num(np.sqrt(2 * (m * g * h - spring_work) / m), "m/s")
    return [row("speed", "the spring's work counted as helping the fall", "sign",
                v(-k * (s2**2 - s1**2) / 2)),
            row("speed", "spring energy (1/2) k (s2 - s1)^2", "spring_energy_difference",
                v(k * (s2 - s1) ** 2 / 2)),
            row("speed", "the spring's energy at the start left out", "spring_energy_difference",
                v(k * s2**2 / 2)),
            row("speed", "spring left out: v = sqrt(2 g h)", "spring_term_dropped",
                num(np.sqrt(2 * g * h), "m/s")),
            row("spring_energy", "(1/2) k l^2 with the total length", "spring_energy_total_length",
                num(k * l2**2 / 2, "J")),
            row("spring_energy", "k s^2 without the 1/2", "half_factor", num(k * s2**2, "J")),
            row("rod_force", "the whole spring force k s (not its horizontal part)",
                "velocity_component_wrong", num(-k * s2, "N")),
            row("rod_force", "vertical component of the spring force", "sin_cos_swap",
                num(-k * s2 * h / l2, "N"))]


def block_incline_spring_compression():
    m, g, k, mu, th, v1 = 5.0, G0, 200.0, 0.4, 40 * DEG, 3.0

    def d_of(F):
        return (F + np.sqrt(F**2 + k * m * v1**2)) / k
    F = m * g * (np.sin(th) - mu * np.cos(th))
    rows = [row("max_compression", "friction mu m g", "friction_as_mu_m_g",
                num(d_of(m * g * (np.sin(th) - mu)) * 1000, "mm")),
            row("max_compression", "sin and cos exchanged", "sin_cos_swap",
                num(d_of(m * g * (np.cos(th) - mu * np.sin(th))) * 1000, "mm")),
            row("max_compression", "gravity and friction left out during the compression",
                "gravity_dropped", num(v1 * np.sqrt(m / k) * 1000, "mm")),
            row("max_compression", "friction drawn down the slope", "friction_reversed",
                num(d_of(m * g * (np.sin(th) + mu * np.cos(th))) * 1000, "mm")),
            row("max_compression", "the other root of the quadratic", "wrong_root",
                num((F - np.sqrt(F**2 + k * m * v1**2)) / k * 1000, "mm")),
            row("spring_force", "friction mu m g", "friction_as_mu_m_g",
                num(k * d_of(m * g * (np.sin(th) - mu)), "N")),
            row("time_to_stop", "a quarter period pi/(2 wn), the constant forces ignored",
                "gravity_dropped", num(np.pi / 2 / np.sqrt(k / m), "s"))]
    return rows


# ------------------------------------------------------------------ power

def elevator_motor_power():
    W, g, eta, v, a = 3000.0, 32.2, 0.75, 12.0, 2.0
    T = W + W / g * a
    return [row("tension", "the cab's weight (acceleration left out)", "acceleration_term_dropped",
                num(W, "lbf")),
            row("tension", "weight used as the mass: W (g + a)", "weight_for_mass",
                num(W * (g + a), "lbf")),
            row("power_to_cab", "tension = weight", "acceleration_term_dropped",
                num(W * v / HP, "hp")),
            row("power_to_cab", "1 hp taken as 746 ft lbf/s", "unit_slip", num(T * v / 746, "hp")),
            row("motor_power", "efficiency multiplied", "efficiency_inverted",
                num(T * v / HP * eta, "hp")),
            row("motor_power", "tension = weight, then divided by the efficiency",
                "acceleration_term_dropped", num(W * v / HP / eta, "hp"))]


def car_climbs_grade_power():
    m, g, th, R, eta, v = 1500.0, G0, 8 * DEG, 500.0, 0.85, 90 / 3.6
    F = m * g * np.sin(th) + R
    return [row("driving_force", "m g cos theta for the weight's component", "sin_cos_swap",
                num(m * g * np.cos(th) + R, "N")),
            row("driving_force", "resistance left out", "gravity_dropped",
                num(m * g * np.sin(th), "N")),
            row("driving_force", "the angle read in radians", "deg_as_rad",
                num(m * g * np.sin(8) + R, "N")),
            row("wheel_power", "speed left in km/h", "unit_slip", num(F * 90 / 1e3, "kW")),
            row("engine_power", "efficiency multiplied", "efficiency_inverted",
                num(F * v / 1e3 * eta, "kW")),
            row("engine_power", "cos for sin in the weight's component", "sin_cos_swap",
                num((m * g * np.cos(th) + R) * v / 1e3 / eta, "kW"))]


# ------------------------------------------------------------------ impulse and momentum

def crate_pushed_impulse_momentum():
    m, g, P, beta, mu, v0, T = 50.0, G0, 300.0, 30 * DEG, 0.3, 2.0, 4.0
    N = m * g + P * np.sin(beta)
    return [row("speed", "friction mu m g (the push's vertical part ignored)", "friction_as_mu_m_g",
                num(v0 + (P * np.cos(beta) - mu * m * g) * T / m, "m/s")),
            row("speed", "the initial speed left out", "initial_speed_forgotten",
                num((P * np.cos(beta) - mu * N) * T / m, "m/s")),
            row("speed", "sin and cos of 30 deg exchanged", "sin_cos_swap",
                num(v0 + (P * np.sin(beta) - mu * (m * g + P * np.cos(beta))) * T / m, "m/s")),
            row("speed", "the push's vertical part taken upward (N = m g - P sin)", "sign",
                num(v0 + (P * np.cos(beta) - mu * (m * g - P * np.sin(beta))) * T / m, "m/s")),
            row("normal", "normal force taken as the weight", "normal_as_weight", num(m * g, "N")),
            row("friction", "friction mu m g", "friction_as_mu_m_g", num(-mu * m * g, "N")),
            row("friction", "friction drawn forward", "friction_reversed", num(mu * N, "N"))]


def freight_cars_couple():
    m1, m2, v0 = 20e3, 30e3, 1.5
    v = m1 * v0 / (m1 + m2)
    return [row("velocity_after", "the moving car's mass divided by the other's only",
                "kinematic_factor", num(m1 * v0 / m2, "m/s")),
            row("velocity_after", "kinetic energy conserved instead of momentum", "ke_conserved",
                num(v0 * np.sqrt(m1 / (m1 + m2)), "m/s")),
            row("impulse_on_second", "the first car's whole momentum", "kinematic_factor",
                vec([m1 * v0 / 1e3, 0.0], "kN*s")),
            row("impulse_on_second", "the impulse on the first car (its sign)", "sign",
                vec([-m2 * v / 1e3, 0.0], "kN*s")),
            row("energy_lost", "no energy lost (KE conserved)", "ke_conserved", num(0.0, "kJ")),
            row("energy_lost", "the kinetic energy after the coupling", "sign",
                num((m1 + m2) * v**2 / 2 / 1e3, "kJ"))]


def baseball_bat_impulse():
    m, v1, v2, beta, tc = 0.145, 40.0, 50.0, 30 * DEG, 1.5e-3
    J = REFERENCE["baseball_bat_impulse"]()["impulse"]
    return [row("impulse", "the incoming velocity's sense ignored: m (v2 - v1) along x",
                "sign", vec([m * (v2 * np.cos(beta) - v1), m * v2 * np.sin(beta)], "N*s")),
            row("impulse", "sin and cos of 30 deg exchanged", "sin_cos_swap",
                vec([m * (v2 * np.sin(beta) + v1), m * v2 * np.cos(beta)], "N*s")),
            row("impulse_magnitude", "speeds subtracted: m (50 - 40)", "magnitudes_added",
                num(m * (v2 - v1), "N*s")),
            row("impulse_magnitude", "speeds added: m (50 + 40)", "magnitudes_added",
                num(m * (v2 + v1), "N*s")),
            row("average_force", "1.5 ms taken as 1.5 s", "unit_slip",
                num(np.hypot(J[0], J[1]) / 1.5, "N")),
            row("average_force", "speeds added: m (50 + 40)/dt", "magnitudes_added",
                num(m * (v2 + v1) / tc, "N"))]


def pucks_oblique_impact():
    mA, mB, vA, vB, e = 0.4, 0.6, 6.0, 4.0, 0.8
    uA = np.array([vA * np.cos(30 * DEG), -vA * np.sin(30 * DEG)])
    uB = np.array([-vB * np.cos(60 * DEG), -vB * np.sin(60 * DEG)])
    ref = REFERENCE["pucks_oblique_impact"]()

    def line(ua, ub, ee):
        M = np.array([[mA, mB], [-1.0, 1.0]])
        return np.linalg.solve(M, [mA * ua + mB * ub, ee * (ua - ub)])
    # head-on: whole speeds along the line, tangential parts lost
    hA, hB = line(vA, -vB, e)
    # restitution on both components: tangential parts also scaled by -e? students scale by e
    # elastic: e = 1
    eA, _eB = line(uA[0], uB[0], 1.0)
    # sin/cos exchanged in the incoming velocities
    sA, _sB = line(vA * np.sin(30 * DEG), -vB * np.sin(60 * DEG), e)
    return [row("velocity_A", "head-on: the whole speeds along the line of centres", "head_on",
                vec([hA, 0.0], "m/s")),
            row("velocity_A", "perfectly elastic (e = 1)", "restitution_ignored",
                vec([eA, uA[1]], "m/s")),
            row("velocity_A", "sin and cos exchanged in the components", "sin_cos_swap",
                vec([sA, -vA * np.cos(30 * DEG)], "m/s")),
            row("velocity_B", "head-on: the whole speeds along the line of centres", "head_on",
                vec([hB, 0.0], "m/s")),
            row("velocity_B", "the tangential component also reversed with e",
                "restitution_wrong_component", vec([ref["velocity_B"][0], -e * uB[1]], "m/s")),
            row("energy_lost", "no energy lost", "ke_conserved", num(0.0, "J"))]


def ball_bounces_oblique_floor():
    v1, beta, e = 20.0, 30 * DEG, 0.7
    vx, vy = v1 * np.cos(beta), v1 * np.sin(beta)
    return [row("velocity_after", "e applied to both components", "restitution_wrong_component",
                vec([e * vx, e * vy], "m/s")),
            row("velocity_after", "e applied to the horizontal component", "restitution_wrong_component",
                vec([e * vx, vy], "m/s")),
            row("velocity_after", "the normal component not reversed", "sign",
                vec([vx, -e * vy], "m/s")),
            row("speed_after", "speed e v1", "restitution_wrong_component", num(e * v1, "m/s")),
            row("speed_after", "sin and cos exchanged", "sin_cos_swap",
                num(np.hypot(vy, e * vx), "m/s")),
            row("rebound_angle", "angle unchanged (30 deg)", "restitution_ignored", num(30.0, "deg")),
            row("rebound_angle", "the angle in radians written as degrees", "deg_as_rad",
                num(np.arctan2(e * vy, vx), "deg"))]


def ball_strikes_hanging_rod():
    M, L, m, d, v0, e = 4.0, 1.2, 0.5, 0.9, 8.0, 0.6

    def solve(I, ee):
        A = np.array([[m * d, I], [-1.0, d]])
        return np.linalg.solve(A, [m * v0 * d, ee * v0])
    v_g, w_g = solve(M * L**2 / 12, e)  # I_G for I_O
    _v_p, w_p = solve(M * L**2 / 3, 0.0)  # plastic
    _v_1, w_1 = solve(M * L**2 / 3, 1.0)  # elastic
    # linear momentum conserved (pin ignored): m v0 = m v + M (L/2) w, with restitution
    A = np.array([[m, M * L / 2], [-1.0, d]])
    _v_l, w_l = np.linalg.solve(A, [m * v0, e * v0])
    ref = REFERENCE["ball_strikes_hanging_rod"]()
    return [row("omega_after", "I_G = M L^2/12 used about the pin", "inertia_about_wrong_point",
                num(w_g, "rad/s")),
            row("omega_after", "plastic impact (e = 0)", "restitution_ignored", num(w_p, "rad/s")),
            row("omega_after", "elastic impact (e = 1)", "restitution_ignored", num(w_1, "rad/s")),
            row("omega_after", "linear momentum conserved (the pin's impulse ignored)",
                "momentum_with_pin", num(w_l, "rad/s")),
            row("ball_velocity_after", "I_G used about the pin", "inertia_about_wrong_point",
                num(v_g, "m/s")),
            row("ball_velocity_after", "rebound taken forward", "sign",
                num(-ref["ball_velocity_after"], "m/s")),
            row("pin_impulse", "no pin impulse (momentum conserved)", "momentum_with_pin",
                vec([0.0, 0.0], "N*s"))]


# ------------------------------------------------------------------ angular momentum

def puck_string_through_hole():
    m, r0, r1, u, w0 = 0.5, 0.8, 0.4, 0.2, 2.0
    w1 = w0 * (r0 / r1) ** 2
    return [row("angular_velocity", "r theta' conserved (the speed) instead of r^2 theta'",
                "speed_conserved", num(w0 * r0 / r1, "rad/s")),
            row("angular_velocity", "theta' unchanged", "speed_conserved", num(w0, "rad/s")),
            row("speed", "the radial speed left out", "velocity_component_wrong",
                num(r1 * w1, "m/s")),
            row("speed", "speed conserved: r0 w0", "speed_conserved", num(r0 * w0, "m/s")),
            row("angular_momentum", "m r theta' without the second r", "kinematic_factor",
                num(m * r1 * w1, "kg*m^2/s")),
            row("tension", "m v^2/r with the whole speed", "velocity_component_wrong",
                num(m * (u**2 + (r1 * w1) ** 2) / r1, "N")),
            row("tension", "the initial tension m r0 w0^2", "initial_speed_forgotten",
                num(m * r0 * w0**2, "N"))]


def satellite_apogee_speed():
    GM, R, h, vp = 398600.0, 6378.0, 500.0, 8.0
    rp = R + h
    ref = REFERENCE["satellite_apogee_speed"]()
    ra = ref["apogee_distance"]
    return [row("apogee_speed", "speed conserved", "speed_conserved", num(vp, "km/s")),
            row("apogee_speed", "the ratio of radii inverted: vp ra/rp", "kinematic_factor",
                num(vp * ra / rp, "km/s")),
            row("apogee_speed", "altitudes for radii: vp h/(ra - R)", "kinematic_factor",
                num(vp * h / (ra - R), "km/s")),
            row("apogee_distance", "the altitude (from the surface) given for the distance",
                "kinematic_factor", num(ra - R, "km")),
            row("apogee_distance", "circular orbit assumed: ra = rp", "wrong_root", num(rp, "km")),
            row("half_period", "the whole period", "half_factor",
                num(2 * ref["half_period"], "min")),
            row("half_period", "circular orbit of radius rp", "wrong_root",
                num(np.pi * np.sqrt(rp**3 / GM) / 60, "min"))]


# ------------------------------------------------------------------ rotation about a fixed axis

def drum_hoist_falling_block():
    M, k, r, m, g = 30.0, 0.2, 0.25, 20.0, G0

    def accel(I):
        return m * g * r**2 / (I + m * r**2)
    return [row("block_acceleration", "drum inertia left out: a = g", "massless_rotor",
                num(-g, "m/s^2")),
            row("block_acceleration", "drum as a uniform disk M r^2/2 (k ignored)", "inertia_wrong_shape",
                num(-accel(M * r**2 / 2), "m/s^2")),
            row("block_acceleration", "tension taken as the block's weight", "tension_as_weight",
                num(-(m * g * r / (M * k**2)) * r, "m/s^2")),
            row("angular_acceleration", "a/r with the drum as a uniform disk", "inertia_wrong_shape",
                num(-accel(M * r**2 / 2) / r, "rad/s^2")),
            row("angular_acceleration", "alpha = a r instead of a/r", "kinematic_factor",
                num(-accel(M * k**2) * r, "rad/s^2")),
            row("tension", "tension taken as the block's weight", "tension_as_weight",
                num(m * g, "N")),
            row("tension", "m (g + a): the block taken to accelerate upward", "sign",
                num(m * (g + accel(M * k**2)), "N"))]


def disk_pinned_at_rim_released():
    m, r, g = 8.0, 0.3, G0
    IG, IO = m * r**2 / 2, 1.5 * m * r**2
    return [row("angular_acceleration", "I_G used about the pin", "inertia_about_wrong_point",
                num(-m * g * r / IG, "rad/s^2")),
            row("angular_acceleration", "a point mass at G: I = m r^2", "inertia_wrong_shape",
                num(-g / r, "rad/s^2")),
            row("angular_acceleration", "counterclockwise (the sign)", "sign",
                num(m * g * r / IO, "rad/s^2")),
            row("pin_force", "the static value m g", "reaction_as_static", vec([0.0, m * g], "N")),
            row("pin_force", "no pin force: the disk falls freely", "reaction_as_static",
                vec([0.0, 0.0], "N")),
            row("pin_force", "I_G about the pin", "inertia_about_wrong_point",
                vec([0.0, m * g - m * (m * g * r / IG) * r], "N")),
            row("centre_acceleration", "free fall: a_G = g", "reaction_as_static",
                vec([0.0, -g], "m/s^2"))]


def flywheel_lever_brake():
    M, R, k, b, c, P, mu, w0 = 60.0, 0.25, 0.18, 0.5, 0.75, 100.0, 0.4, 600 * RPM
    N = P * (b + c) / b
    I = M * k**2

    def t(normal, inertia=I, w=w0):
        return w * inertia / (mu * normal * R)
    return [row("normal_force", "N = P (the lever's advantage ignored)", "kinematic_factor",
                num(P, "N")),
            row("normal_force", "lever arms inverted: N = P b/(b + c)", "kinematic_factor",
                num(P * b / (b + c), "N")),
            row("normal_force", "the arm c taken from A: N = P c/b", "kinematic_factor",
                num(P * c / b, "N")),
            row("stopping_time", "N = P", "kinematic_factor", num(t(P), "s")),
            row("stopping_time", "rpm taken as rad/s", "unit_slip", num(t(N, w=600.0), "s")),
            row("stopping_time", "flywheel as a uniform disk M R^2/2", "inertia_wrong_shape",
                num(t(N, M * R**2 / 2), "s")),
            row("revolutions", "radians reported as revolutions", "unit_slip",
                num(w0 * t(N) / 2, "rev")),
            row("revolutions", "the mean speed's 1/2 left out", "half_factor",
                num(w0 * t(N) / (2 * np.pi), "rev"))]


# ------------------------------------------------------------------ plane motion, IC

def gear_between_two_racks():
    r, vu, vl = 0.15, 2.0, -1.0
    return [row("angular_velocity", "the upper rack only: w = vu/r", "kinematic_factor",
                num(-vu / r, "rad/s")),
            row("angular_velocity", "speeds subtracted: (2 - 1)/(2 r)", "sign",
                num(-(vu + vl) / (2 * r), "rad/s")),
            row("angular_velocity", "counterclockwise (the sign)", "sign",
                num((vu - vl) / (2 * r), "rad/s")),
            row("centre_velocity", "mean of the speeds: (2 + 1)/2", "sign",
                num((vu - vl) / 2, "m/s")),
            row("centre_velocity", "the upper rack's speed", "kinematic_factor", num(vu, "m/s")),
            row("instant_centre", "at the lower mesh point", "kinematic_factor",
                vec([0.0, -r * 1000], "mm")),
            row("instant_centre", "above the centre", "sign",
                vec([0.0, 50.0], "mm"))]


def rod_in_two_slots_ic():
    L, th, vA, be = 1.0, 30 * DEG, 2.0, 45 * DEG
    ref = REFERENCE["rod_in_two_slots_ic"]()
    return [row("angular_velocity", "the ladder formula vA/(L sin theta) (B's slot vertical)",
                "kinematic_factor", num(vA / (L * np.sin(th)), "rad/s")),
            row("angular_velocity", "vA/(L cos theta)", "sin_cos_swap",
                num(vA / (L * np.cos(th)), "rad/s")),
            row("angular_velocity", "clockwise (the sign)", "sign",
                num(-ref["angular_velocity"], "rad/s")),
            row("velocity_B", "vB = vA (a rigid rod moves as a whole)", "kinematic_factor",
                num(vA, "m/s")),
            row("velocity_B", "vB = vA cos 45", "velocity_component_wrong",
                num(vA * np.cos(be), "m/s")),
            row("speed_G", "the mean of the end speeds", "magnitudes_added",
                num((vA + ref["velocity_B"]) / 2, "m/s")),
            row("speed_G", "w L/2 (G's distance to the IC taken as L/2)", "kinematic_factor",
                num(ref["angular_velocity"] * L / 2, "m/s"))]


def rolling_wheel_rim_points():
    r, v, a, gam = 0.4, 3.0, 1.5, 45 * DEG
    ref = REFERENCE["rolling_wheel_rim_points"]()
    w, al = -v / r, -a / r
    rP = r * np.array([np.cos(gam), np.sin(gam)])
    aP = np.array(ref["acceleration_P"][:2])
    return [row("velocity_P", "w x r added with the wrong sense (counterclockwise w)", "sign",
                vec(np.array([v, 0.0]) + _rot(-w, rP), "m/s")),
            row("velocity_P", "the centre's velocity only", "kinematic_factor",
                vec([v, 0.0], "m/s")),
            row("acceleration_P", "the centripetal part w^2 r dropped", "centripetal_dropped",
                vec(aP + w**2 * rP, "m/s^2")),
            row("acceleration_P", "the tangential part alpha x r dropped", "tangential_dropped",
                vec(aP - _rot(al, rP), "m/s^2")),
            row("acceleration_P", "the centre's acceleration left out", "kinematic_factor",
                vec(aP - np.array([a, 0.0]), "m/s^2")),
            row("acceleration_contact", "zero: the contact point is at rest", "centripetal_dropped",
                vec([0.0, 0.0], "m/s^2")),
            row("acceleration_contact", "the centre's acceleration (a, 0)", "kinematic_factor",
                vec([a, 0.0], "m/s^2"))]


def _rot(w, r):
    return w * np.array([-r[1], r[0]])


def slotted_arm_crank_coriolis():
    r, h, w, ph = 0.2, 0.4, 4.0, 30 * DEG
    B = np.array([r * np.cos(ph), h + r * np.sin(ph)])
    s = np.linalg.norm(B)
    e_s, e_t = B / s, np.array([-B[1], B[0]]) / s
    vB = r * w * np.array([-np.sin(ph), np.cos(ph)])
    aB = -r * w**2 * np.array([np.cos(ph), np.sin(ph)])
    sd, td = vB @ e_s, vB @ e_t / s
    return [row("arm_angular_velocity", "the arm's rate taken equal to the crank's", "angular_rate_equal",
                num(w, "rad/s")),
            row("arm_angular_velocity", "|v_B|/s: the whole pin speed across the arm",
                "velocity_component_wrong", num(r * w / s, "rad/s")),
            row("arm_angular_acceleration", "Coriolis term 2 s' theta' dropped", "coriolis_dropped",
                num(aB @ e_t / s, "rad/s^2")),
            row("arm_angular_acceleration", "zero because the crank turns steadily",
                "acceleration_zero_constant_speed", num(0.0, "rad/s^2")),
            row("arm_angular_acceleration", "Coriolis term s' theta' (no 2)", "coriolis_halved",
                num((aB @ e_t - sd * td) / s, "rad/s^2")),
            row("sliding_rate", "the pin's whole speed r w", "velocity_component_wrong",
                num(r * w, "m/s")),
            row("relative_acceleration", "the arm's centripetal term s theta'^2 left out",
                "centripetal_dropped", num(aB @ e_s, "m/s^2"))]


def collar_slides_on_spinning_rod():
    m, r, rd, w, g = 0.5, 0.3, 1.2, 5.0, G0
    return [row("sliding_acceleration", "zero: nothing pushes along the smooth rod",
                "centripetal_dropped", num(0.0, "m/s^2")),
            row("sliding_acceleration", "r w^2 taken inward", "sign", num(-r * w**2, "m/s^2")),
            row("side_force", "Coriolis dropped: no side force at constant w", "coriolis_dropped",
                num(0.0, "N")),
            row("side_force", "m r' w (no factor 2)", "coriolis_halved", num(m * rd * w, "N")),
            row("side_force", "the weight m g (the vertical reaction)", "normal_as_weight",
                num(m * g, "N")),
            row("drive_moment", "Coriolis force without the 2: m r' w r", "coriolis_halved",
                num(m * rd * w * r, "N*m"))]


# ------------------------------------------------------------------ rolling

def cylinder_pulled_rolls():
    m, r, g, P, mu = 20.0, 0.2, G0, 60.0, 0.2
    return [row("acceleration", "friction ignored: a = P/m", "kinematic_factor", num(P / m, "m/s^2")),
            row("acceleration", "friction taken as mu m g (limiting)", "friction_as_mu_m_g",
                num((P - mu * m * g) / m, "m/s^2")),
            row("acceleration", "a hoop's inertia m r^2", "inertia_wrong_shape",
                num(P / (2 * m), "m/s^2")),
            row("acceleration", "moments about the contact with I_G (no parallel axis)",
                "inertia_about_wrong_point",
                num(P * r / (m * r**2 / 2) * r, "m/s^2")),
            row("friction", "friction mu m g backward", "friction_as_mu_m_g", num(-mu * m * g, "N")),
            row("friction", "friction forward", "friction_reversed", num(P / 3, "N")),
            row("mu_needed", "friction/N with friction = P", "kinematic_factor",
                num(P / (m * g), "1")),
            row("angular_acceleration", "counterclockwise (the sign)", "sign",
                num(P / (1.5 * m * r), "rad/s^2"))]


def hoop_slips_down_incline():
    m, r, g, beta, mu = 3.0, 0.5, G0, 40 * DEG, 0.15
    return [row("acceleration", "rolling without slip assumed: g sin/2", "rolling_assumed",
                num(g * np.sin(beta) / 2, "m/s^2")),
            row("acceleration", "friction mu m g", "friction_as_mu_m_g",
                num(g * (np.sin(beta) - mu), "m/s^2")),
            row("acceleration", "sin and cos exchanged", "sin_cos_swap",
                num(g * (np.cos(beta) - mu * np.sin(beta)), "m/s^2")),
            row("acceleration", "calculator in radian mode", "deg_as_rad",
                num(g * (np.sin(40) - mu * np.cos(40)), "m/s^2")),
            row("angular_acceleration", "alpha = a/r (rolling)", "rolling_assumed",
                num(g * (np.sin(beta) - mu * np.cos(beta)) / r, "rad/s^2")),
            row("angular_acceleration", "a disk's inertia m r^2/2", "inertia_wrong_shape",
                num(2 * mu * g * np.cos(beta) / r, "rad/s^2")),
            row("friction", "mu m g", "friction_as_mu_m_g", num(-mu * m * g, "N")),
            row("friction", "friction down the slope", "friction_reversed",
                num(mu * m * g * np.cos(beta), "N"))]


def disk_rolls_on_pulled_plank():
    M, m, P, r = 10.0, 6.0, 60.0, 0.2
    return [row("plank_acceleration", "disk moves with the plank: P/(M + m)", "kinematic_factor",
                num(P / (M + m), "m/s^2")),
            row("plank_acceleration", "friction left out: P/M", "kinematic_factor", num(P / M, "m/s^2")),
            row("disk_acceleration", "the disk moves with the plank: a = A", "kinematic_factor",
                num(P / (M + m / 3), "m/s^2")),
            row("disk_acceleration", "the disk stays in place", "kinematic_factor", num(0.0, "m/s^2")),
            row("disk_acceleration", "backward: the disk rolls back relative to the plank",
                "sign", num(-P / (M + m / 3) / 3, "m/s^2")),
            row("friction", "friction mu m g", "friction_as_mu_m_g", num(0.5 * m * G0, "N")),
            row("angular_acceleration", "alpha = a/r with the disk's own acceleration",
                "kinematic_factor", num(P / (M + m / 3) / 3 / r, "rad/s^2"))]


# ------------------------------------------------------------------ energy of rigid systems

def bar_swings_down_spring_energy():
    m, L, g, k, L0, H = 5.0, 1.2, G0, 20.0, 0.5, 0.9
    s1, s2 = np.hypot(L, H) - L0, H + L - L0
    l1, l2 = np.hypot(L, H), H + L

    def w(I, spring, drop=L / 2):
        return num(np.sqrt(2 * (m * g * drop - spring) / I), "rad/s")
    IO = m * L**2 / 3
    return [row("angular_velocity", "I_G used about the pin", "inertia_about_wrong_point",
                w(m * L**2 / 12, k * (s2**2 - s1**2) / 2)),
            row("angular_velocity", "spring energy from the total lengths", "spring_energy_total_length",
                w(IO, k * (l2**2 - l1**2) / 2)),
            row("angular_velocity", "spring energy (1/2) k (s2 - s1)^2", "spring_energy_difference",
                w(IO, k * (s2 - s1) ** 2 / 2)),
            row("angular_velocity", "spring left out", "spring_term_dropped", w(IO, 0.0)),
            row("angular_velocity", "G drops L instead of L/2", "kinematic_factor",
                w(IO, k * (s2**2 - s1**2) / 2, L)),
            row("spring_energy", "(1/2) k l^2 with the total length", "spring_energy_total_length",
                num(k * l2**2 / 2, "J")),
            row("pin_force", "the static value: m g minus the spring", "reaction_as_static",
                vec([0.0, m * g - k * s2], "N"))]


def unbalanced_hoop_rolls():
    M, m, R, g = 4.0, 1.0, 0.5, G0
    E = m * g * 2 * R
    return [row("angular_velocity", "the hoop's translation left out: KE = M R^2 w^2/2",
                "translation_ke_dropped", num(np.sqrt(2 * E / (M * R**2)), "rad/s")),
            row("angular_velocity", "a disk's inertia M R^2/2 about the centre", "inertia_wrong_shape",
                num(np.sqrt(2 * E / (1.5 * M * R**2)), "rad/s")),
            row("angular_velocity", "the small mass moving at 2 R w (as at the top)", "kinematic_factor",
                num(np.sqrt(2 * E / (2 * M * R**2 + m * 4 * R**2)), "rad/s")),
            row("angular_velocity", "the small mass moving with the centre (R w)", "kinematic_factor",
                num(np.sqrt(2 * E / (2 * M * R**2 + m * R**2)), "rad/s")),
            row("centre_speed", "the small mass's drop R instead of 2 R", "kinematic_factor",
                num(np.sqrt(2 * m * g * R / (2 * M * R**2)) * R, "m/s")),
            row("kinetic_energy", "m g R (drop R)", "kinematic_factor", num(m * g * R, "J"))]


def drum_block_energy_us():
    Wd, Wb, k, r, g, h = 100.0, 40.0, 0.8, 1.0, 32.2, 6.0
    mb, I = Wb / g, Wd / g * k**2
    return [row("block_speed", "drum left out: free fall", "massless_rotor",
                num(np.sqrt(2 * g * h), "ft/s")),
            row("block_speed", "weights used as masses in the kinetic energy", "weight_for_mass",
                num(np.sqrt(2 * Wb * h / (Wb + Wd * k**2 / r**2)), "ft/s")),
            row("block_speed", "drum as a uniform disk (W/g) r^2/2", "inertia_wrong_shape",
                num(np.sqrt(2 * Wb * h / (mb + Wd / g / 2)), "ft/s")),
            row("block_speed", "kinetic energies without the 1/2", "half_factor",
                num(np.sqrt(Wb * h / (mb + I / r**2)), "ft/s")),
            row("drum_angular_velocity", "w = v/k: the radius of gyration for the drum's radius",
                "kinematic_factor", num(REFERENCE["drum_block_energy_us"]()["block_speed"] / k,
                                         "rad/s")),
            row("tension", "tension taken as the block's weight", "tension_as_weight", num(Wb, "lbf")),
            row("tension", "m (g + a): the block taken to accelerate upward", "sign",
                num(mb * (g + Wb / (mb + I / r**2)), "lbf"))]


# ------------------------------------------------------------------ vibration

def block_on_spring_us_units():
    W, k_in, g = 10.0, 20.0, 32.2
    k = k_in * 12
    wn = np.sqrt(k * g / W)
    return [row("omega_n", "weight used as the mass: sqrt(k/W)", "weight_for_mass",
                num(np.sqrt(k / W), "rad/s")),
            row("omega_n", "lb/in not converted to lb/ft", "unit_slip",
                num(np.sqrt(k_in * g / W), "rad/s")),
            row("omega_n", "the frequency in hertz given for rad/s", "hz_for_rad_s",
                num(wn / (2 * np.pi), "rad/s")),
            row("frequency", "omega_n in rad/s given as hertz", "hz_for_rad_s", num(wn, "Hz")),
            row("frequency", "1/period confused: 2 pi/omega_n", "period_for_frequency",
                num(2 * np.pi / wn, "Hz")),
            row("period", "1/omega_n", "hz_for_rad_s", num(1 / wn, "s")),
            row("period", "weight for mass", "weight_for_mass", num(2 * np.pi / np.sqrt(k / W), "s"))]


def block_between_two_springs():
    m, k1, k2, x0, v0 = 12.0, 3e3, 5e3, 0.02, 0.5
    ks = k1 * k2 / (k1 + k2)
    wn = np.sqrt((k1 + k2) / m)
    ws = np.sqrt(ks / m)

    def amp(w):
        return np.hypot(x0, v0 / w)

    def first_stop(w):
        A = amp(w)
        return (np.pi / 2 - np.arcsin(x0 / A)) / w
    return [row("amplitude", "springs in series: k1 k2/(k1 + k2)", "series_parallel",
                num(amp(ws) * 1000, "mm")),
            row("amplitude", "the initial displacement only", "initial_speed_forgotten",
                num(x0 * 1000, "mm")),
            row("amplitude", "x0 + v0/wn added", "magnitudes_added",
                num((x0 + v0 / wn) * 1000, "mm")),
            row("amplitude", "v0/wn only (the displacement left out)", "kinematic_factor",
                num(v0 / wn * 1000, "mm")),
            row("first_stop", "a quarter period", "kinematic_factor", num(np.pi / 2 / wn, "s")),
            row("first_stop", "springs in series", "series_parallel", num(first_stop(ws), "s")),
            row("right_spring_force", "both springs: (k1 + k2) A", "kinematic_factor",
                num(-(k1 + k2) * amp(wn), "N")),
            row("right_spring_force", "pushes right (the sign)", "sign", num(k2 * amp(wn), "N"))]


def damped_block_first_peak():
    m, k, c, v0 = 5.0, 2000.0, 40.0, 1.0
    wn = np.sqrt(k / m)
    z = c / (2 * np.sqrt(k * m))
    wd = wn * np.sqrt(1 - z**2)
    tp = np.arctan2(wd, z * wn) / wd
    xp = v0 / wd * np.exp(-z * wn * tp) * np.sin(wd * tp)
    return [row("time_to_peak", "damping ignored: a quarter period pi/(2 wn)", "damping_ignored",
                num(np.pi / 2 / wn, "s")),
            row("time_to_peak", "a quarter of the damped period pi/(2 wd)", "damping_ignored",
                num(np.pi / 2 / wd, "s")),
            row("peak_displacement", "damping ignored: v0/wn", "damping_ignored",
                num(v0 / wn * 1000, "mm")),
            row("peak_displacement", "v0/wd, the decay left out", "damping_ignored",
                num(v0 / wd * 1000, "mm")),
            row("peak_displacement", "e^(-zeta t) for e^(-zeta wn t)", "kinematic_factor",
                num(v0 / wd * np.exp(-z * tp) * np.sin(wd * tp) * 1000, "mm")),
            row("spring_force", "spring and damper forces added", "magnitudes_added",
                num(k * xp + c * v0, "N")),
            row("spring_force", "damping ignored: k v0/wn", "damping_ignored",
                num(k * v0 / wn, "N"))]


def disk_pendulum_period():
    r, d, g = 0.2, 0.1, G0
    wn = np.sqrt(g * d / (r**2 / 2 + d**2))
    return [row("omega_n", "a simple pendulum of length d", "inertia_wrong_shape",
                num(np.sqrt(g / d), "rad/s")),
            row("omega_n", "I_G used about the pin", "inertia_about_wrong_point",
                num(np.sqrt(g * d / (r**2 / 2)), "rad/s")),
            row("omega_n", "I_O = m r^2/2 + m r^2 (the rim's parallel axis)", "inertia_about_wrong_point",
                num(np.sqrt(g * d / (1.5 * r**2)), "rad/s")),
            row("period", "1/omega_n", "hz_for_rad_s", num(1 / wn, "s")),
            row("period", "simple pendulum of length d", "inertia_wrong_shape",
                num(2 * np.pi * np.sqrt(d / g), "s")),
            row("equivalent_length", "the pin's distance d", "inertia_wrong_shape", num(100.0, "mm")),
            row("equivalent_length", "k_O^2/d with I_G", "inertia_about_wrong_point",
                num(r**2 / 2 / d * 1000, "mm"))]


def motor_on_beam_resonance():
    m, k = 25.0, 400e3
    wn = np.sqrt(k / m)
    return [row("omega_n", "weight used as the mass", "weight_for_mass",
                num(np.sqrt(k / (m * G0)), "rad/s")),
            row("omega_n", "kN/m not converted", "unit_slip", num(np.sqrt(400 / m), "rad/s")),
            row("frequency", "omega_n given as hertz", "hz_for_rad_s", num(wn, "Hz")),
            row("resonant_speed", "rad/s times 60 (2 pi left out)", "hz_for_rad_s",
                num(wn * 60, "rpm")),
            row("resonant_speed", "hertz given as rpm", "unit_slip", num(wn / (2 * np.pi), "rpm")),
            row("resonant_speed", "rad/s reported as rpm", "unit_slip", num(wn, "rpm"))]


def bar_on_spring_vibration():
    m, L, a, k, g = 6.0, 1.5, 1.0, 2000.0, G0
    IO = m * L**2 / 3
    wn = np.sqrt(k * a**2 / IO)
    return [row("omega_n", "I_G used about the pin", "inertia_about_wrong_point",
                num(np.sqrt(k * a**2 / (m * L**2 / 12)), "rad/s")),
            row("omega_n", "sqrt(k/m) as for a block", "inertia_wrong_shape", num(np.sqrt(k / m), "rad/s")),
            row("omega_n", "the spring at the tip: k L^2", "kinematic_factor",
                num(np.sqrt(k * L**2 / IO), "rad/s")),
            row("omega_n", "the spring taken at G (L/2 from O)", "kinematic_factor",
                num(np.sqrt(k * (L / 2) ** 2 / IO), "rad/s")),
            row("period", "1/omega_n", "hz_for_rad_s", num(1 / wn, "s")),
            row("spring_force", "the bar's whole weight", "reaction_as_static", num(m * g, "N")),
            row("spring_force", "moments with the weight at the tip", "kinematic_factor",
                num(m * g * L / a, "N"))]


# ------------------------------------------------------------------ 3-D rigid bodies

def disk_on_bent_shaft():
    m, r, beta, g, w = 4.0, 0.15, 10 * DEG, G0, 60.0
    ref = REFERENCE["disk_on_bent_shaft"]()
    H = np.array(ref["angular_momentum"])
    Ay = ref["bearing_A"][1]
    I_a, I_d = m * r**2 / 2, m * r**2 / 4
    # sin/cos swapped in the components of the shaft's rate in the disk's axes
    wy, wz = w * np.cos(beta), w * np.sin(beta)
    Hy, Hz = I_d * wy, I_a * wz
    Hs = np.array([0.0, Hy * np.cos(beta) - Hz * np.sin(beta), Hy * np.sin(beta) + Hz * np.cos(beta)])
    return [row("angular_momentum", "H = I_axis w along the shaft (the tilt ignored)",
                "kinematic_factor", vec([0.0, 0.0, I_a * w], "kg*m^2/s")),
            row("angular_momentum", "H = I_axis w along the disk's axis", "kinematic_factor",
                vec(I_a * w * np.array([0.0, -np.sin(beta), np.cos(beta)]), "kg*m^2/s")),
            row("angular_momentum", "sin and cos of the tilt exchanged", "sin_cos_swap",
                vec(Hs, "kg*m^2/s")),
            row("tilt_of_angular_momentum", "the disk's tilt itself (10 deg)", "kinematic_factor",
                num(10.0, "deg")),
            row("tilt_of_angular_momentum", "zero: H along the shaft", "kinematic_factor",
                num(0.0, "deg")),
            row("bearing_A", "no dynamic reaction: only the weight", "reaction_as_static",
                vec([0.0, 0.0, m * g], "N")),
            row("bearing_A", "the couple divided by b instead of 2 b", "half_factor",
                vec([0.0, 2 * Ay, m * g], "N")),
            row("bearing_A", "the couple's force taken the other way", "sign",
                vec([0.0, -Ay, m * g], "N")),
            row("angular_momentum", "H in the other sense across the shaft", "sign",
                vec([0.0, -H[1], H[2]], "kg*m^2/s"))]


def gyroscope_steady_precession():
    m, r, l, g, spin = 0.5, 0.05, 0.1, G0, 3000 * RPM
    I = m * r**2 / 2
    Om = m * g * l / (I * spin)
    return [row("precession_rate", "the hoop's inertia m r^2", "inertia_wrong_shape",
                num(m * g * l / (m * r**2 * spin), "rad/s")),
            row("precession_rate", "rpm taken as rad/s", "unit_slip",
                num(m * g * l / (I * 3000), "rad/s")),
            row("precession_rate", "the ratio inverted: I spin/(m g l)", "kinematic_factor",
                num(I * spin / (m * g * l), "rad/s")),
            row("precession_rate", "weight for mass: the mass m in place of m g", "weight_for_mass",
                num(m * l / (I * spin), "rad/s")),
            row("precession_period", "1/Omega", "hz_for_rad_s", num(1 / Om, "s")),
            row("support_horizontal", "zero: the support holds only the weight", "reaction_as_static",
                num(0.0, "N")),
            row("support_horizontal", "pointing outward (away from the axis)", "sign",
                num(m * l * Om**2, "N"))]


PROBLEMS = [boat_coasting_quadratic_drag, spring_launcher_a_of_x, car_constant_power_acceleration,
            car_on_parabolic_road, radar_tracks_airplane_polar, collar_on_circle_rotating_rod,
            two_cars_relative_motion, airplane_crosswind_heading, truck_hoists_crate_pulley,
            movable_pulley_two_blocks, collar_spring_vertical_rod,
            block_incline_spring_compression, elevator_motor_power, car_climbs_grade_power,
            crate_pushed_impulse_momentum, freight_cars_couple, baseball_bat_impulse,
            pucks_oblique_impact, ball_bounces_oblique_floor, ball_strikes_hanging_rod,
            puck_string_through_hole, satellite_apogee_speed, drum_hoist_falling_block,
            disk_pinned_at_rim_released, flywheel_lever_brake, gear_between_two_racks,
            rod_in_two_slots_ic, rolling_wheel_rim_points, slotted_arm_crank_coriolis,
            collar_slides_on_spinning_rod, cylinder_pulled_rolls, hoop_slips_down_incline,
            disk_rolls_on_pulled_plank, bar_swings_down_spring_energy, unbalanced_hoop_rolls,
            drum_block_energy_us, block_on_spring_us_units, block_between_two_springs,
            damped_block_first_peak, disk_pendulum_period, motor_on_beam_resonance,
            bar_on_spring_vibration, disk_on_bent_shaft, gyroscope_steady_precession]


def _value(answer: str) -> np.ndarray:
    """The numbers of a table answer (its unit is the objective's: the tables write it so)."""
    text = answer.strip()
    if text.startswith("("):
        return np.array([float(x) for x in text[1:text.index(")")].split(",")])
    return np.array([float(text.split()[0])])


def _inside(answer: str, reference) -> bool:
    """Within the default tolerance: 1 % of the value (of the vector's size, per component)."""
    want = np.atleast_1d(np.asarray(reference, float))
    got = _value(answer)
    got = np.pad(got, (0, max(0, len(want) - len(got))))
    size = np.linalg.norm(want)
    return bool(np.all(np.abs(got[:len(want)] - want) <= 0.01 * size))


def tables() -> dict[str, list[dict]]:
    """Problem id -> its rows, each marked ``inside`` when the default tolerance accepts it."""
    out = {}
    for f in PROBLEMS:
        reference = REFERENCE[f.__name__]()
        rows = f()
        for r in rows:
            if _inside(r["answer"], reference[r["objective"]]):
                r["inside"] = True
        out[f.__name__] = rows
    return out


if __name__ == "__main__":
    for name, rows in tables().items():
        header = (f"# Typical mistakes on {name}: written by typical.py (numpy, by hand, before "
                  "mechgrade's families were read).\n")
        text = yaml.safe_dump(rows, sort_keys=False, allow_unicode=True, width=100)
        (HERE / f"{name}.yaml").write_text(header + text, encoding="utf-8")
    print(f"{len(PROBLEMS)} tables, {sum(len(r) for r in tables().values())} mistakes")
