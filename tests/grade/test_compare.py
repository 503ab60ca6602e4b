"""Judging answers: tolerance boundaries, sig figs, units, vectors and expressions."""

import math

import pytest
from hypothesis import given, settings, strategies as st

from mechgrade.errors import AnswerError, AssignmentError
from mechgrade.grade.answers import read_answer
from mechgrade.grade.compare import (Assessment, assess, expression_dimension, last_place,
                                     sample_points, within, within_sig_figs)
from mechgrade.grade.policy import GradingPolicy
from mechgrade.expressions.syntax import parse
from mechgrade.grade.results import VERDICTS
from mechgrade.solve.result import MistakeValue, ObjectiveResult
from mechgrade.units import from_si, to_si

ACC = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51)
VEC = ObjectiveResult("a_P", "vector", "ft/s^2", (-66.0, -40.0, 0.0), frame="N")
OMEGA = ObjectiveResult("w", "vector", "rad/s", (0.0, 0.0, -0.5), frame="N")
SYM = ObjectiveResult("a_sym", "symbolic", "m/s^2", expr="L*sqrt(thetad**4 + thetadd**2)",
                      symbols=("L", "thetad", "thetadd"),
                      symbol_units=("m", "rad/s", "rad/s^2"))
ANGLE = ObjectiveResult("theta", "scalar", "rad", 0.5236)


def verdict(text, result=ACC, policy=GradingPolicy()):
    return assess(text, result, policy).verdict


# ---------------------------------------------------------------- relative and absolute


def test_relative_tolerance_boundary_is_inclusive():
    result = ObjectiveResult("x", "scalar", "m", 100.0, rel=0.01)
    assert verdict("101 m", result) == "correct"
    assert verdict("99 m", result) == "correct"
    assert verdict("101.01 m", result) == "incorrect"
    assert verdict("98.99 m", result) == "incorrect"


def test_absolute_tolerance_applies_in_the_objectives_unit():
    result = ObjectiveResult("x", "scalar", "m", 0.0, rel=0.01, abs=0.05)
    assert verdict("0.05 m", result) == "correct"
    assert verdict("5 cm", result) == "correct"
    assert verdict("0.0501 m", result) == "incorrect"


def test_no_tolerance_is_tighter_than_the_references_accuracy():
    """A zero tolerance (an assignment's policy; a problem's is refused by check) still
    accepts an answer off only in the reference's last digits."""
    result = ObjectiveResult("x", "scalar", "m", 2.78107123456, rel=0.0)
    assert verdict("2.781071 m", result, GradingPolicy(rel=0.0)) == "correct"
    assert verdict("2.7811 m", result, GradingPolicy(rel=0.0)) == "incorrect"


def test_policy_overrides_the_objectives_tolerance():
    assert verdict("97 ft/s^2", ACC, GradingPolicy(rel=0.02)) == "correct"
    assert verdict("97 ft/s^2", ACC) == "incorrect"
    assert verdict("97 ft/s^2", ACC, GradingPolicy(rel=0.0, abs=2.0)) == "correct"


@given(st.floats(min_value=-1.0, max_value=1.0))
def test_any_value_within_tolerance_is_correct(fraction):
    value = 98.51 * (1 + 0.0099 * fraction)
    assert verdict(f"{value!r} ft/s^2") == "correct"


@given(st.floats(min_value=0.0101, max_value=50.0), st.sampled_from([-1, 1]))
def test_any_value_outside_tolerance_is_not_correct(fraction, sign):
    value = 98.51 * (1 + sign * fraction)
    assert verdict(f"{value!r} ft/s^2") in ("incorrect", "partial")


@given(st.floats(min_value=-0.0099, max_value=0.0099),
       st.sampled_from(["m/s^2", "ft/s^2", "in/s^2", "cm/s^2", "km/h^2", "mm/s^2"]))
def test_unit_conversions_round_trip(fraction, unit):
    value = from_si(to_si(98.51 * (1 + fraction), "ft/s^2"), unit)
    assert verdict(f"{value!r} {unit}") == "correct"


# ---------------------------------------------------------------- sig figs


def test_sig_fig_accuracy_is_half_a_unit_in_the_last_place():
    policy = GradingPolicy(sig_figs=3)
    assert verdict("98.5 ft/s^2", ACC, policy) == "correct"
    assert verdict("98.46 ft/s^2", ACC, policy) == "correct"
    assert verdict("98.56 ft/s^2", ACC, policy) == "correct"
    assert verdict("98.45 ft/s^2", ACC, policy) == "incorrect"
    assert verdict("98.57 ft/s^2", ACC, policy) == "incorrect"
    assert verdict("98.4 ft/s^2", ACC, policy) == "incorrect"


def test_sig_fig_accuracy_is_judged_in_the_students_unit():
    # 98.51 ft/s^2 = 30.026 m/s^2: "30.0 m/s^2" is right to 3 figures, though 30.0 m/s^2 is
    # 98.43 ft/s^2, which is not within 0.05 ft/s^2 of 98.51.
    assert verdict("30.0 m/s^2", ACC, GradingPolicy(sig_figs=3)) == "correct"
    assert verdict("30.1 m/s^2", ACC, GradingPolicy(sig_figs=3)) == "incorrect"


def test_last_place_and_sig_fig_helpers():
    assert last_place(98.51, 3) == 0.1
    assert last_place(0.004567, 2) == 0.0001
    assert last_place(0.0, 3) == 0.01
    assert within_sig_figs(0.0046, 0.004567, 2)
    assert not within_sig_figs(0.0047, 0.004567, 2)


def test_written_sig_figs_liberal_rule_accepts_ambiguous_trailing_zeros():
    hundred = ObjectiveResult("x", "scalar", "m", 100.0)
    policy = GradingPolicy(written_sig_figs=3)
    assert verdict("100 m", hundred, policy) == "correct"
    assert verdict("1.00e2 m", hundred, policy) == "correct"
    partial = assess("1.0e2 m", hundred, policy)
    assert partial.verdict == "partial" and partial.credit == 0.75
    assert partial.diagnosis == "significant figures"
    assert "written to 2 significant figures; 3 were asked" in partial.feedback


def test_written_sig_figs_strict_rule_reads_100_as_one_figure():
    hundred = ObjectiveResult("x", "scalar", "m", 100.0)
    policy = GradingPolicy(written_sig_figs=3, written_sig_figs_strict=True)
    assert verdict("100 m", hundred, policy) == "partial"
    assert verdict("100. m", hundred, policy) == "correct"
    assert verdict("1.00e2 m", hundred, policy) == "correct"


def test_written_sig_figs_deduction_is_configurable():
    policy = GradingPolicy(written_sig_figs=2, written_sig_figs_deduction=1.0)
    judged = assess("98.51 ft/s^2", ACC, policy)
    assert (judged.verdict, judged.credit) == ("incorrect", 0.0)


def test_exact_constants_do_not_escape_a_written_sig_figs_rule():
    judged = assess("pi/6 rad", ANGLE, GradingPolicy(written_sig_figs=3))
    assert (judged.verdict, judged.credit) == ("partial", 0.75)
    assert judged.feedback == ("The value is right, but written as an exact expression; "
                               "3 were asked.")
    assert verdict("pi/6 rad", ANGLE) == "correct"


# ---------------------------------------------------------------- units


def test_wrong_dimension_is_named():
    judged = assess("30 m/s", ACC)
    assert judged.verdict == "incorrect" and judged.diagnosis == "wrong dimension"
    assert judged.feedback == ("You gave a velocity ([length]/[time]); an acceleration "
                               "([length]/[time]²) was asked.")


def test_missing_unit_rejected_by_default():
    judged = assess("98.5", ACC)
    assert (judged.verdict, judged.credit, judged.diagnosis) == ("incorrect", 0.0,
                                                                  "missing unit")
    assert "ft/s^2" in judged.feedback


def test_missing_unit_assumed_with_deduction():
    judged = assess("98.5", ACC, GradingPolicy(missing_unit="assume", missing_unit_deduction=0.1))
    assert (judged.verdict, judged.credit) == ("partial", 0.9)
    assert "ft/s^2 was assumed" in judged.feedback


def test_the_unit_a_number_or_vector_was_written_in_is_kept_when_of_the_objectives_dimension():
    speed = ObjectiveResult("w", "vector", "rad/s", (0.0, 0.0, -4.334), frame="B")
    assert assess("(0, 0, -41.4) rpm", speed).unit == "rpm"
    assert assess("-41.4 rpm", speed).unit == "rpm"  # a scalar for a vector: judged, unit kept
    assert assess("98.5 m/s^2", ACC).unit == "m / s ** 2"  # wrong, and still in that unit
    assert assess("98.5 ft", ACC).unit is None  # another dimension
    assert assess("98.5", ACC, GradingPolicy(missing_unit="assume")).unit is None  # none written
    assert assess("98.5 parsecs_per_fortnight", ACC).unit is None  # not read
    symbolic = ObjectiveResult("x", "symbolic", "m", expr="L*theta", symbols=("L", "theta"),
                               symbol_units=("m", ""))
    assert assess("L*theta", symbolic).unit is None


def test_pure_number_objective_needs_no_unit():
    ratio = ObjectiveResult("mu", "scalar", "", 0.25)
    assert verdict("0.25", ratio) == "correct"


def test_angles_convert_between_degrees_and_radians():
    assert verdict("30 deg", ANGLE) == "correct"
    assert verdict("30°", ANGLE) == "correct"
    assert verdict("0.5236 rad", ANGLE) == "correct"
    assert verdict("pi/6 rad", ANGLE) == "correct"


def test_rpm_converts_to_rad_per_second():
    spin = ObjectiveResult("w", "scalar", "rad/s", 12 * 2 * math.pi / 60)
    assert verdict("12 rpm", spin) == "correct"
    assert verdict("1.257 rad/s", spin) == "correct"


def test_hertz_beside_an_angular_rate_are_cycles_per_second_as_rpm_are_revolutions():
    spin = ObjectiveResult("w", "scalar", "rad/s", 2 * 2 * math.pi)  # 2 cycles per second
    assert verdict("2 Hz", spin) == "correct"
    assert verdict("120 rpm", spin) == "correct"
    # the rate in rad/s written with Hz: 2π times too large, named as the 2π slip
    judged = assess("12.57 Hz", spin)
    assert (judged.verdict, judged.diagnosis) == ("incorrect",
                                                  "unit slip (revolutions vs radians)")
    frequency = ObjectiveResult("f", "scalar", "Hz", 2.0)
    assert verdict("12.57 rad/s", frequency) == "correct"
    assert verdict("120 rpm", frequency) == "correct"
    # beside a unit that names no angle a hertz stays pint's 1/s
    assert verdict("2 s^-1", frequency) == "correct"
    assert verdict("12.57 rad/s", ObjectiveResult("n", "scalar", "1/s", 2.0)) == "incorrect"


def test_feedback_never_reveals_the_reference_value():
    for text in ("50 ft/s^2", "-98.5 ft/s^2", "30 m/s", "98.5"):
        assert "98.51" not in assess(text, ACC).feedback


# ---------------------------------------------------------------- vectors


@pytest.mark.parametrize("text", ["-66 i - 40 j ft/s^2", "(-66, -40) ft/s^2",
                                  "<-66, -40, 0> ft/s^2", "-66 N.x - 40 N.y ft/s^2",
                                  "-66 X_N - 40 Y_N ft/s^2", "(-20.12, -12.19) m/s^2",
                                  "(-66.5, -39.5) ft/s^2"])
def test_vector_forms_are_correct(text):
    assert verdict(text, VEC) == "correct"


def test_vector_tolerance_is_relative_to_the_magnitude():
    # |a| = 77.17 ft/s^2, so each component may be off by 0.77 ft/s^2 at 1%.
    assert verdict("(-66, -40.7) ft/s^2", VEC) == "correct"
    assert verdict("(-66, -41) ft/s^2", VEC) == "incorrect"


def test_vector_feedback_names_the_wrong_component():
    judged = assess("(-66, -45) ft/s^2", VEC)
    assert judged.verdict == "incorrect"
    # a planar answer's zero z is not mentioned
    assert judged.feedback.startswith("The y component is not within 1% of the expected value"
                                      " (x is right).")


def test_vector_in_another_frame_is_not_compared():
    judged = assess("-66 A.x - 40 A.y ft/s^2", VEC)
    assert judged.diagnosis == "wrong frame" and "magnitude is right" in judged.feedback


def test_scalar_for_a_vector_objective_says_a_vector_was_asked():
    judged = assess("77.17 ft/s^2", VEC)
    assert judged.diagnosis == "scalar for a vector"
    assert judged.feedback == ("A vector was asked: give its components along frame N's unit "
                               "vectors, such as '(x, y, z) ft/s^2' (your value is the right "
                               "magnitude).")


def test_vector_for_a_scalar_objective_says_a_scalar_was_asked():
    judged = assess("(-66, -40) ft/s^2", ObjectiveResult("m", "scalar", "ft/s^2", 77.17))
    assert judged.diagnosis == "vector for a scalar" and "magnitude is right" in judged.feedback


@pytest.mark.parametrize("text", ["0.5 rad/s cw", "-0.5 k rad/s", "-0.5 rad/s",
                                  "4.775 rpm cw", "(0, 0, -0.5) rad/s"])
def test_planar_angular_velocity_forms(text):
    assert verdict(text, OMEGA) == "correct"


def test_planar_angular_velocity_wrong_sense_is_a_sign_error():
    assert assess("0.5 rad/s ccw", OMEGA).diagnosis == "sign error"


def test_signed_scalar_objective_accepts_a_k_vector():
    assert verdict("-0.5 k rad/s", ObjectiveResult("wz", "scalar", "rad/s", -0.5)) == "correct"


def test_vector_sig_figs_judge_each_component():
    policy = GradingPolicy(sig_figs=2)
    assert verdict("(-66, -40) ft/s^2", VEC, policy) == "correct"
    assert verdict("(-66, -41) ft/s^2", VEC, policy) == "incorrect"


# ---------------------------------------------------------------- expressions


@pytest.mark.parametrize("text", [
    "L sqrt(θ̇^4 + θ̈^2)", "L*sqrt(thetad**4 + thetadd**2)", "sqrt(L^2 thetad^4 + L^2 thetadd^2)",
    "L*(thetadot^4+thetaddot^2)^(1/2)", "L*sqrt(theta'^4 + theta''^2)",
    "L*sqrt((thetad^2)^2 + thetadd^2)", "L*sqrt(thetad^4 + thetadd^2)*(sin(thetad)^2+cos(thetad)^2)",
])
def test_equivalent_expressions_are_correct(text):
    assert verdict(text, SYM) == "correct"


@pytest.mark.parametrize("text", ["L*thetad^2", "L*(thetad^2 + thetadd)", "L*thetadd",
                                  "L*sqrt(thetad^4 + thetadd^2) + 1e-3*L"])
def test_inequivalent_expressions_are_incorrect(text):
    assert verdict(text, SYM) == "incorrect"


def test_expression_with_wrong_dimension_is_diagnosed():
    judged = assess("thetad*sqrt(thetad^4+thetadd^2)", SYM)
    assert judged.diagnosis == "wrong dimension"
    assert "an acceleration ([length]/[time]²) was asked" in judged.feedback


def test_expression_with_inconsistent_dimensions_is_diagnosed():
    judged = assess("L + thetad", SYM)
    assert judged.diagnosis == "inconsistent dimensions"
    assert "adds a length ([length]) to an angular velocity" in judged.feedback


def test_expression_dimension_rules():
    units = {"L": "m", "thetad": "rad/s", "theta": "rad"}
    assert str(expression_dimension(parse("sqrt(L^2*thetad^4)"), units)) == \
        "[length] / [time] ** 2"
    assert str(expression_dimension(parse("L*sin(theta)"), units)) == "[length]"
    with pytest.raises(Exception, match="takes sin of a length"):
        expression_dimension(parse("sin(L)"), units)


def test_expression_unknown_names_are_unreadable_with_the_symbols_listed():
    judged = assess("x + L", SYM)
    assert judged.verdict == "unreadable"
    assert "expected an expression in L, thetad, thetadd" in judged.feedback


def test_angle_symbols_are_sampled_in_range_and_lengths_positive():
    pend = ObjectiveResult("x", "symbolic", "m", expr="L*sin(theta)", symbols=("L", "theta"),
                           symbol_units=("m", "rad"))
    points = sample_points(pend, 50)
    assert (points["L"] > 0).all()
    assert ((points["theta"] > 0) & (points["theta"] < math.pi / 2)).all()
    assert verdict("L sin(θ)", pend) == "correct"
    assert verdict("L cos(θ)", pend) == "incorrect"


def test_expression_equivalence_is_reproducible():
    assert sample_points(SYM, 5)["L"].tolist() == sample_points(SYM, 5)["L"].tolist()


def test_an_answer_kept_judged_is_judged_again_under_another_policy():
    # "1.000001 L" is right within 1e-5 and wrong within 1e-8, whichever policy comes first
    loose, tight = GradingPolicy(symbolic_rel=1e-5), GradingPolicy(symbolic_rel=1e-8)
    text = "1.000001*L*sqrt(thetad**4 + thetadd**2)"
    assert [verdict(text, SYM, p) for p in (loose, tight, loose, tight)] == [
        "correct", "incorrect", "correct", "incorrect"]


def test_equal_objectives_of_other_references_are_not_confused():
    # two results alike but for their reference: each answer judged against its own
    double = ObjectiveResult(SYM.id, "symbolic", SYM.unit, expr=f"2*{SYM.expr}",
                             symbols=SYM.symbols, symbol_units=SYM.symbol_units)
    text = "L sqrt(thetad^4 + thetadd^2)"
    assert [verdict(text, r) for r in (SYM, double, SYM, double)] == [
        "correct", "incorrect", "correct", "incorrect"]
    assert assess(text, double).diagnosis == "factor of 2"


def test_answers_judged_past_the_kept_number_are_judged_anew(monkeypatch):
    from mechgrade.grade import compare
    monkeypatch.setattr(compare, "MAX_JUDGED", 2)
    monkeypatch.setattr(compare, "MAX_OBJECTIVES", 1)
    texts = ["L*sqrt(thetad**4 + thetadd**2)", "L*thetad**2", "-L*sqrt(thetad^4+thetadd^2)"]
    first = [assess(t, SYM) for t in texts]
    other = ObjectiveResult("v", "symbolic", "m/s", expr="L*thetad", symbols=("L", "thetad"),
                            symbol_units=("m", "rad/s"))
    assert verdict("L thetad", other) == "correct"
    assert [assess(t, SYM) for t in texts * 2] == first * 2
    assert [(a.verdict, a.diagnosis) for a in first] == [
        ("correct", None), ("incorrect", None),
        ("incorrect", "sign error")]


def test_reference_undefined_everywhere_is_not_evaluated():
    odd = ObjectiveResult("x", "symbolic", "m", expr="sqrt(-L)", symbols=("L",),
                          symbol_units=("m",))
    assert verdict("L", odd) == "not_evaluated"


def test_a_reference_in_names_it_does_not_declare_is_not_evaluated():
    stray = ObjectiveResult("x", "symbolic", "m", expr="L*k", symbols=("L",),
                            symbol_units=("m",))
    assert verdict("L", stray) == "not_evaluated"


def test_a_symbolic_answer_written_again_is_judged_once_by_its_text(monkeypatch):
    import mechgrade.grade.compare as compare

    result = ObjectiveResult("a", "symbolic", "m/s^2", expr=SYM.expr, symbols=SYM.symbols,
                             symbol_units=SYM.symbol_units)
    policy = GradingPolicy()
    first = assess("L*thetad^2", result, policy)
    assert assess("L*thetad^2", result, policy) is first
    # the same reading written otherwise is judged alike
    assert assess(" L thetad^2", result, policy) == first
    monkeypatch.setattr(compare, "MAX_JUDGED", 2)
    for text in ("L", "2 L", "3 L"):
        assess(text, result, policy)
    assert len(compare._objective(result, policy).judged) <= 2


@pytest.mark.parametrize("answer", [5, ["L"], b"L"])
def test_a_symbolic_answer_that_is_not_text_is_unreadable(answer):
    assert verdict(answer, SYM) == "unreadable"


def test_declared_symbolic_mistake_gives_its_message_and_credit():
    result = ObjectiveResult(
        "a", "symbolic", "m/s^2", expr=SYM.expr, symbols=SYM.symbols,
        symbol_units=SYM.symbol_units,
        mistakes=(MistakeValue("Only the normal component.", 0.3, None, "L*thetad**2"),))
    judged = assess("L θ̇²", result)
    assert (judged.verdict, judged.credit, judged.diagnosis) == (
        "partial", 0.3, "Only the normal component.")


# ---------------------------------------------------------------- verdicts and policy


def test_missing_and_blank_answers():
    assert assess(None, ACC) == Assessment("missing", 0.0, None, "No answer was given.", None)
    assert verdict("   ", ACC) == "missing"


def test_reference_without_value_is_not_evaluated():
    assert verdict("1 m", ObjectiveResult("x", "scalar", "m", None)) == "not_evaluated"


@pytest.mark.parametrize("text", [
    "__import__('os').system('x')", "().__class__.__base__.__subclasses__()", "9**9**9**9",
    "sqrt(" * 60 + "L" + ")" * 60, "9" * 1_000_000, "98\x00", "\udcff\udcfe",
    "exp(exp(exp(exp(L))))", "L**L**L**L", "1/(L-L)"])
def test_hostile_answers_never_raise(text):
    for result in (ACC, VEC, SYM):
        judged = assess(text, result)
        assert judged.verdict in VERDICTS
        assert 0.0 <= judged.credit <= 1.0


@pytest.mark.parametrize("kwargs, field", [
    ({"rel": -1}, "rel"), ({"abs": "x"}, "abs"), ({"sig_figs": 0}, "sig_figs"),
    ({"written_sig_figs": 2.5}, "written_sig_figs"), ({"missing_unit": "guess"}, "missing_unit"),
    ({"missing_unit_deduction": 2}, "missing_unit_deduction"),
    ({"written_sig_figs_deduction": -0.1}, "written_sig_figs_deduction"),
    ({"partial_credit": (("nonsense", 0.5),)}, "partial_credit"),
    ({"partial_credit": (("sign", 1.5),)}, "partial_credit"),
    ({"symbolic_rel": 0}, "symbolic_rel"), ({"symbolic_points": 1}, "symbolic_points"),
])
def test_policy_refuses_bad_settings(kwargs, field):
    with pytest.raises(AssignmentError, match=f"policy.{field}: expected"):
        GradingPolicy(**kwargs)


def test_partial_credit_for_an_automatic_diagnosis():
    judged = assess("-98.5 ft/s^2", ACC, GradingPolicy(partial_credit=(("sign", 0.5),)))
    assert (judged.verdict, judged.credit, judged.diagnosis) == ("partial", 0.5, "sign error")


def test_within_helper():
    assert within(101, 100, 0.01, 0) and not within(101.5, 100, 0.01, 0)
    assert within(0.001, 0, 0.01, 0.001)


# ---------------------------------------------------------------- issue 7: answer-test tables


def test_a_constant_reference_is_compared_not_called_undefined():
    constant = ObjectiveResult("c", "symbolic", "1", expr="1", symbols=("R", "r"),
                               symbol_units=("m", "m"))
    assert verdict("1/(R-r)", constant) == "incorrect"
    assert verdict("R/R", constant) == "correct"


@pytest.mark.parametrize("text, rel, expected", [
    ("1.05 m", 0.05, "correct"), ("0.95 m", 0.05, "correct"), ("1.0500001 m", 0.05, "incorrect"),
    ("1.1 m", 0.1, "correct"), ("0.9 m", 0.1, "correct"), ("1.3 m", 0.3, "correct"),
    ("105 cm", 0.05, "correct"),
])
def test_tolerance_boundaries_survive_binary_rounding(text, rel, expected):
    assert verdict(text, ObjectiveResult("x", "scalar", "m", 1.0, rel=rel)) == expected


def test_within_slack_is_tiny():
    assert within(1.05, 1.0, 0.05, 0.0) and not within(1.05 + 1e-8, 1.0, 0.05, 0.0)
    assert within(0.1 + 0.2, 0.3, 0.0, 0.0)


@pytest.mark.parametrize("text, figures, expected", [
    ("0", 1, "correct"), ("0.0", 1, "correct"), ("0.00", 2, "correct"), ("0.00", 1, "partial"),
    ("0.0", 2, "partial"), ("0.000", 3, "correct"),
])
def test_written_figures_of_zero_follow_stack_and_prairielearn(text, figures, expected):
    zero = ObjectiveResult("z", "scalar", "", 0.0, abs=0.01)
    assert verdict(text, zero, GradingPolicy(written_sig_figs=figures,
                                      written_sig_figs_strict=True)) == expected


def test_tuples_of_constant_expressions_are_graded():
    unit = ObjectiveResult("u", "vector", "", (0.70710678, 0.70710678, 0.0), frame="N")
    assert verdict("(sqrt(2)/2, sqrt(2)/2)", unit) == "correct"
    assert verdict("<sqrt(2)/2, sqrt(2)/2>", unit) == "correct"


def test_a_declared_j_makes_3j_a_product():
    j = ObjectiveResult("j", "symbolic", "m", expr="3*j", symbols=("j",), symbol_units=("m",))
    assert verdict("3j", j) == "correct"


def test_e_notation_with_a_declared_e_is_unreadable_not_a_number():
    e = ObjectiveResult("e", "symbolic", "m", expr="2*E + 3", symbols=("E",),
                        symbol_units=("m",))
    assert verdict("2E+3", e) == "unreadable"
    assert verdict("2 E + 3", e) == "correct"


def test_non_real_and_overflowing_constants_are_unreadable():
    length = ObjectiveResult("s", "symbolic", "m", expr="L", symbols=("L",), symbol_units=("m",))
    assert assess("sqrt(-2) L", length).feedback == ("Could not read the answer: expected a real "
                                                     "constant, found 'sqrt(-2)' (not a real "
                                                     "number).")
    judged = assess("exp(exp(exp(100)))", ACC)
    assert judged.verdict == "unreadable" and "(too large)" in judged.feedback


@pytest.mark.parametrize("reference", ["sqrt(x**2)", "Abs(x)", "x**2/Abs(x)", "(x**2)**(1/2)"])
def test_a_symbol_the_reference_treats_as_signed_is_sampled_negative_too(reference):
    signed = ObjectiveResult("d", "symbolic", "m", expr=reference, symbols=("x",),
                             symbol_units=("m",))
    assert verdict("x", signed) == "incorrect"
    assert verdict("abs(x)", signed) == "correct"
    assert sample_points(signed, 40)["x"].min() < 0


def test_positive_lengths_stay_positive():
    length = ObjectiveResult("d", "symbolic", "m", expr="L", symbols=("L",), symbol_units=("m",))
    assert verdict("sqrt(L^2)", length) == "correct"
    assert sample_points(length, 40)["L"].min() > 0


# ---------------------------------------------------------------- arbitrary text


_FUZZ_OBJECTIVES = (ACC, VEC, OMEGA, SYM, ANGLE,
                    ObjectiveResult("x", "symbolic", "m", expr="Abs(x) + E",
                                    symbols=("x", "E", "j"), symbol_units=("m", "m", "m")))
_FUZZ_PIECES = st.sampled_from(["98.5", "1 000", ".", "e", "E", "e1", "j", "-", "- -", "+", "*",
                                "/", "//", "^", "**", "(", ")", ",", "<", ">", "#", " ", "\n",
                                "\u2029", "\x00", "ft/s^2", "m", "s-2", "g0", "°C", "cw", "pi",
                                "sqrt(", "exp(", "i", "k", "N.x", "L", "thetad", "x", "θ̇", "'",
                                "9" * 40, "1e999", "2E+3", "3j", "abs(", "½", "\ufffd"])


@settings(max_examples=300)
@given(st.one_of(st.text(max_size=80), st.lists(_FUZZ_PIECES, max_size=12).map("".join)),
       st.sampled_from(_FUZZ_OBJECTIVES))
def test_arbitrary_text_gets_a_verdict_or_a_short_reason(text, objective):
    try:
        read_answer(text, objective)
    except AnswerError as exc:
        assert 0 < len(exc.message) <= 200, exc.message
    judged = assess(text, objective)
    assert judged.verdict in VERDICTS
    assert len(judged.feedback) <= 200, judged.feedback
    assert judged.diagnosis is None or len(judged.diagnosis) <= 200


@pytest.mark.parametrize("signed, verdict", [(True, "incorrect"), (False, "correct")])
def test_symbols_are_sampled_over_the_domain_the_solver_declares(signed, verdict):
    # xA is a parameter declared positive: false (signed) or a positive length.
    result = ObjectiveResult("d", "symbolic", "m", expr="2*xA", symbols=("xA",),
                             symbol_units=("m",), symbol_signed=(signed,))
    assert assess("2*sqrt(xA^2)", result).verdict == verdict


# ------------------------------------------- issue 18: answers judged as students meant them

TESLA = ObjectiveResult("B", "scalar", "T", 1.0)
POWER = ObjectiveResult("P", "scalar", "1/m", 0.2)
DEGREES = frozenset({"deg_as_rad", "rad_as_deg"})


@pytest.mark.parametrize("text", ["1e4 G", "1e4 gauss", "10 kG", "1000 mT"])
def test_gauss_is_the_engineering_unit_of_1e_minus_4_tesla(text):
    # WeBWorK lib/Units.pm: G = 1e-4 kg/(A s^2); t/units/electromagnetic.t: 1 mT is 10 G
    assert verdict(text, TESLA) == "correct"


def test_dpt_is_the_dioptre():
    # STACK answertestfixtures: Units 0.200*dpt against 0.200/m is right
    assert verdict("0.200 dpt", POWER) == "correct"
    assert verdict("0.200 dioptre", POWER) == "correct"


def test_a_trig_argument_read_in_radians_gets_a_hint_when_degrees_were_meant():
    half = ObjectiveResult("s", "scalar", "", 0.5, plausible=DEGREES)
    judged = assess("sin(30)", half)
    assert (judged.verdict, judged.credit, judged.diagnosis) == \
        ("incorrect", 0.0, "trig argument read in radians")
    assert judged.feedback == ("sin(30) was read with its argument in radians; read in "
                               "degrees your value would be right: write sin(30°) or "
                               "sin(30 deg).")
    assert verdict("sin(30°)", half) == "correct"
    assert verdict("sin(pi/6)", half) == "correct"
    graded = assess("sin(30)", half, GradingPolicy(partial_credit=(("trig_radians", 0.5),)))
    assert (graded.verdict, graded.credit) == ("partial", 0.5)


def test_no_degrees_hint_where_the_problem_has_no_degrees_or_no_trig():
    assert assess("sin(30)", ObjectiveResult("s", "scalar", "", 0.5,
                                             plausible=frozenset())).diagnosis is None
    assert assess("0.4", ObjectiveResult("s", "scalar", "", 0.5,
                                         plausible=DEGREES)).diagnosis is None


def test_vector_components_with_trig_in_radians_get_the_hint():
    force = ObjectiveResult("F", "vector", "N", (4.330127, 2.5, 0.0), frame="N",
                            plausible=DEGREES)
    judged = assess("(5 cos(30), 5 sin(30)) N", force)
    assert judged.diagnosis == "trig argument read in radians"
    assert verdict("(5 cos(30°), 5 sin(30°)) N", force) == "correct"


def test_a_planar_vector_in_magnitude_and_angle_form_is_judged_by_components():
    velocity = ObjectiveResult("v", "vector", "m/s", (-3.0, 4.0, 0.0), frame="N")
    judged = assess("5 m/s at 126.87°", velocity)
    assert (judged.verdict, judged.read_back) == ("correct", "5 m/s at 126.87 deg")
    assert verdict("5 m/s at 53.13°", velocity) == "incorrect"


def test_brackets_keep_the_written_figures_of_a_number():
    # STACK answertestfixtures: NumSigFigs 1, -(0.05) against -0.0499 is right
    small = ObjectiveResult("x", "scalar", "", -0.0499)
    assert verdict("-(0.05)", small, GradingPolicy(sig_figs=1, written_sig_figs=1)) == "correct"
    acc = ObjectiveResult("a", "scalar", "m/s^2", -12.0)
    assert verdict("(-12.00) m/s^2", acc, GradingPolicy(written_sig_figs=4)) == "correct"


def test_an_exact_constant_times_a_unit_is_judged():
    acc = ObjectiveResult("a", "scalar", "m/s^2", 1 / 3)
    assert verdict("1/3*m/s^2", acc) == "correct"
    assert verdict("(-9.81)m/s^2", ObjectiveResult("g", "scalar", "m/s^2", -9.81)) == "correct"


def test_euler_number_in_an_expression_is_judged():
    decay = ObjectiveResult("r", "symbolic", "1", expr="exp(-zeta*omega*t)",
                            symbols=("zeta", "omega", "t"), symbol_units=("1", "rad/s", "s"))
    assert verdict("e^(-ζωt)", decay) == "correct"
    assert verdict("e^(-ζω)", decay) == "incorrect"
