"""Dynamics objectives are graded as kinematic ones: forces, energies and powers with their
units named, equations of motion written as equations, mass-for-weight slips, and ECF from a
rate that a work-energy balance fixes."""

from __future__ import annotations

import pytest

from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.compare import assess
from mechgrade.grade.policy import GradingPolicy
from mechgrade.grade.run import grade_submissions
from mechgrade.resources import shipped_dir
from mechgrade.solve.result import ObjectiveResult

TENSION = ObjectiveResult("T", "scalar", "N", 36.7875, plausible=frozenset({"g"}))
ENERGY = ObjectiveResult("ke", "scalar", "J", 0.02)
TENSION_SYMBOLIC = ObjectiveResult("T", "symbolic", "N", expr="2*g*m1*m2/(m1 + m2)",
                                   symbols=("m1", "m2", "g"),
                                   symbol_units=("kg", "kg", "m/s^2"))
EOM = ObjectiveResult("eom", "symbolic", "rad/s^2", expr="-3*g*sin(theta)/(2*L)",
                      symbols=("g", "L", "theta"), symbol_units=("m/s^2", "m", "rad"))
PENDULUM = shipped_dir("examples") / "hw3_dynamics" / "pendulum_release.yaml"


@pytest.mark.parametrize("text, result, feedback", [
    ("0.02 W", ENERGY, "You gave a power ([mass]·[length]²/[time]³); an energy or "
                       "moment ([mass]·[length]²/[time]²) was asked."),
    ("36.8 J", TENSION, "You gave an energy or moment ([mass]·[length]²/[time]²); "
                        "a force ([mass]·[length]/[time]²) was asked."),
    ("(m2 - m1)*g/(m1 + m2)", TENSION_SYMBOLIC,
     "Your expression is an acceleration ([length]/[time]²); a force ([mass]·[length]"
     "/[time]²) was asked."),
])
def test_a_wrong_dimension_names_forces_energies_and_powers(text, result, feedback):
    judged = assess(text, result)
    assert (judged.verdict, judged.feedback) == ("incorrect", feedback)


def test_a_force_g_times_too_small_is_read_as_mass_used_for_weight():
    small, large = assess("3.751 N", TENSION), assess("360.8 N", TENSION)
    assert small.diagnosis == large.diagnosis == "factor of g"
    assert small.feedback == "Your answer is g times too small: mass used for weight (g left " \
                             "out), or weight used for mass?"
    assert large.feedback == "Your answer is g times too large: weight used for mass, or g " \
                             "applied twice?"
    assert assess("3.751 N", TENSION, GradingPolicy(partial_credit=(("g", 0.25),))).credit == 0.25


@pytest.mark.parametrize("text, read_back", [
    ("θ̈ = -3 g sin(θ)/(2 L)", "-3*g*sin(theta)/(2*L)"),
    ("theta'' = -3*g*sin(theta)/(2*L)", "-3*g*sin(theta)/(2*L)"),
    ("alpha = -1.5 g/L sin(theta)", "-1.5*g/L*sin(theta)"),
])
def test_an_equation_of_motion_written_as_an_equation_is_read_as_its_right_side(text,
                                                                                read_back):
    judged = assess(text, EOM)
    assert (judged.verdict, judged.read_back) == ("correct", read_back)


def test_a_labelled_wrong_equation_is_still_judged_wrong():
    assert assess("θ̈ = -3 g cos(θ)/(2 L)", EOM).verdict == "incorrect"
    assert assess("θ̈ == -3 g sin(θ)/(2 L)", EOM).verdict == "unreadable"


@pytest.fixture(scope="module")
def released_pendulum_class(tmp_path_factory):
    """The hw3 pendulum released from rest: a wrong rate in (a), forces and energy from it."""
    folder = tmp_path_factory.mktemp("ecf")
    (folder / "pendulum_release.yaml").write_text(PENDULUM.read_text(encoding="utf-8"),
                                                   encoding="utf-8")
    (folder / "hw.yaml").write_text(
        "id: ecf\ntitle: ECF\nproblems: [pendulum_release.yaml]\npolicy: {ecf: {credit: 1.0}}\n",
        encoding="utf-8")
    subs = folder / "subs"
    subs.mkdir()
    # (1/2)(m L^2/3) w^2 = m g L cos 40 (G's drop taken as L cos 40): w^2 = 6 g cos 40/L,
    # w = -6.130 rad/s; R_O = m (alpha k x r_G - w^2 r_G) + m g j = (-36.23, 48.08) N;
    # T = (1/2)(m L^2/3) w^2 = 18.04 J
    (subs / "erin.txt").write_text(
        "pendulum_release.omega = -6.13 rad/s\n"
        "pendulum_release.pin_force = (-36.23, 48.08) N\n"
        "pendulum_release.kinetic_energy = 18.0 J\n", encoding="utf-8")
    # the same wrong rate, and a pin force that follows from neither rate (weight left out)
    (subs / "finn.txt").write_text(
        "pendulum_release.omega = -6.13 rad/s\n"
        "pendulum_release.pin_force = (-36.23, 28.46) N\n", encoding="utf-8")
    return grade_submissions(load_assignment(folder / "hw.yaml"), subs)


def test_ecf_takes_a_students_rate_in_place_of_the_energy_balance(released_pendulum_class):
    erin = {a.objective: a for a in released_pendulum_class.students[0].answers}
    assert (erin["omega"].verdict, erin["omega"].points) == ("incorrect", 0.0)
    for objective in ("pin_force", "kinetic_energy"):
        assert (erin[objective].verdict, erin[objective].points,
                erin[objective].diagnosis) == ("correct", 1.0, "error carried forward")
        assert erin[objective].feedback == (
            "Error carried forward: this answer follows correctly from your answer to omega "
            "(used in place of the energy balance) and earns 100% of the points.")


def test_ecf_through_the_energy_balance_still_finds_an_answer_that_follows_from_nothing(
        released_pendulum_class):
    finn = {a.objective: a for a in released_pendulum_class.students[1].answers}
    assert (finn["pin_force"].verdict, finn["pin_force"].diagnosis) == ("incorrect", None)
    assert finn["pin_force"].feedback.endswith(
        "Also checked with your own answer to omega (error carried forward): it does not "
        "follow from it either.")


@pytest.mark.parametrize("text", ["-3*9.81*sin(theta)/(2*L)", "-1.5*32.2 sin(theta)/L"])
def test_a_number_typed_for_g_is_named(text):
    judged = assess(text, EOM, GradingPolicy(partial_credit=(("g_number", 0.5),)))
    assert (judged.verdict, judged.credit, judged.diagnosis, judged.feedback) == (
        "partial", 0.5, "number typed for g",
        "Your expression has a number where the symbol g was asked: write g.")


def test_a_wrong_expression_with_a_number_for_g_is_not_called_a_number_for_g():
    assert assess("-3*9.81*cos(theta)/(2*L)", EOM).diagnosis == "wrong dimension"


SPIN = ObjectiveResult("H_G", "vector", "kg*m^2/s", (0.0, 0.0, -0.009), frame="N")
MOMENT = ObjectiveResult("M_O", "vector", "N*m", (0.0, 0.0, 12.0), frame="N")


@pytest.mark.parametrize("text, result", [("0.009 kg*m^2/s cw", SPIN), ("0.009 J*s cw", SPIN),
                                          ("12 N*m ccw", MOMENT), ("12 N·m counterclockwise",
                                                                   MOMENT)])
def test_angular_momenta_and_moments_may_be_written_with_a_sense_of_rotation(text, result):
    assert assess(text, result).verdict == "correct"


def test_a_sense_of_rotation_is_refused_for_an_energy():
    judged = assess("9.02 J cw", ObjectiveResult("T", "scalar", "J", 9.02))
    assert (judged.verdict, judged.feedback) == (
        "unreadable", "Could not read the answer: expected a signed value: a sense of rotation "
                      "(cw) only goes with an angle or angular velocity or acceleration, an "
                      "angular momentum or a moment.")


@pytest.mark.slow  # a slow end-to-end check (over 5 s)
def test_ecf_takes_a_students_designed_parameter_in_place_of_the_design_condition(tmp_path):
    """Sample 9.21: the outer radius R is designed so that a_G = 0.2 g; the contact force is
    asked 'with that R'. A student's wrong R, and the force that follows from it, by hand:
    R = 0.25 m: I_G = m r^2/2 + M R^2 = 0.005 + 0.125 = 0.13 kg m^2, total mass 5 kg,
    a_G = 5 g sin 30/(5 + I_G/r^2) = 24.525/18 = 1.3625 m/s^2,
    F_x = 5 a_G - 5 g sin 30 = -17.71 N, F_y = 5 g cos 30 = 42.48 N."""
    spec = (shipped_dir("problems") / "ruina_9_21_wheel_incline.yaml").read_text(
        encoding="utf-8")
    assert "  - id: contact_force\n" in spec
    (tmp_path / "wheel.yaml").write_text(spec.replace(
        "  - id: contact_force\n", "  - id: contact_force\n    depends_on: [R_min]\n"),
        encoding="utf-8")
    (tmp_path / "hw.yaml").write_text(
        "id: ecf\ntitle: ECF\nproblems: [{path: wheel.yaml, objectives: [R_min, contact_force]}]"
        "\npolicy: {ecf: {credit: 1.0}}\n", encoding="utf-8")
    (tmp_path / "subs").mkdir()
    (tmp_path / "subs" / "wes.txt").write_text(
        "ruina_9_21_wheel_incline.R_min = 0.25 m\n"
        "ruina_9_21_wheel_incline.contact_force = (-17.71, 42.48) N\n", encoding="utf-8")
    report = grade_submissions(load_assignment(tmp_path / "hw.yaml"), tmp_path / "subs")
    force = report.students[0].answers[1]
    assert (force.verdict, force.points, force.diagnosis) == ("correct", 1.0,
                                                              "error carried forward")
    assert force.feedback == (
        "Error carried forward: this answer follows correctly from your answer to R_min (used "
        "in place of the design condition) and earns 100% of the points.")


SLIDING = ObjectiveResult("a", "symbolic", "m/s^2",
                          expr="-g*mu_k*xd*cos(beta)/Abs(xd) + g*sin(beta)",
                          symbols=("g", "beta", "mu_k", "xd"),
                          symbol_units=("m/s^2", "rad", "", "m/s"))


@pytest.mark.parametrize("sign, text, verdict", [
    (1, "g*(sin(beta) - mu_k*cos(beta))", "correct"),         # sliding down, as stated
    (1, "g*(sin(beta) - mu_k*cos(beta)*sign(xd))", "correct"),
    (1, "g*(sin(beta) + mu_k*cos(beta))", "incorrect"),       # friction reversed
    (1, "g*sin(beta)", "incorrect"),                           # friction left out
    (-1, "g*(sin(beta) + mu_k*cos(beta))", "correct"),        # sliding up
    (-1, "g*(sin(beta) - mu_k*cos(beta))", "incorrect"),
    (0, "g*(sin(beta) - mu_k*cos(beta))", "incorrect"),       # sense unknown: both judged
    (0, "g*(sin(beta) - mu_k*cos(beta)*sign(xd))", "correct"),
])
def test_kinetic_friction_in_symbols_is_judged_for_the_stated_sense_of_sliding(sign, text,
                                                                                verdict):
    from dataclasses import replace

    result = replace(SLIDING, symbol_signs=(1, 1, 1, sign))
    assert assess(text, result).verdict == verdict


def test_a_rate_the_reference_uses_beyond_its_sign_keeps_both_signs():
    from dataclasses import replace

    speed = ObjectiveResult("v", "symbolic", "m/s", expr="L*thetad",
                            symbols=("L", "thetad"), symbol_units=("m", "rad/s"),
                            symbol_signs=(1, 1))
    assert assess("L*Abs(thetad)", speed).verdict == "incorrect"
    constant = ObjectiveResult("k", "symbolic", "1", expr="1", symbols=("thetad",),
                               symbol_units=("rad/s",))
    assert assess("Abs(thetad)/thetad", replace(constant, symbol_signs=(1,))).verdict \
        == "incorrect"


def test_graded_references_record_the_instant_sign_of_a_sliding_rate():
    from mechgrade.grade.run import graded_result
    from mechgrade.solve import solve
    from mechgrade.spec import load_problem

    block = solve(load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml"))
    result = graded_result(block, "accel_symbolic")
    assert dict(zip(result.symbols, result.symbol_signs))["xd"] == 1   # x' = 2 m/s
    assert assess("g (sin(β) - mu_k cos(β))", result).verdict == "correct"
