"""Reading student answer text: every accepted syntax, and every refusal with its reason."""

import pytest
from hypothesis import given, strategies as st

from mechgrade.errors import AnswerError
from mechgrade.grade.answers import (ExpressionAnswer, NumberAnswer, VectorAnswer, clean,
                                     number_value, read_answer, read_expression,
                                     significant_figures, symbol_aliases)
from mechgrade.solve.result import ObjectiveResult

ACC = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51)
VEC = ObjectiveResult("a_P", "vector", "ft/s^2", (-66.0, -40.0, 0.0), frame="N")
OMEGA = ObjectiveResult("w", "vector", "rad/s", (0.0, 0.0, -0.5), frame="N")
SYM = ObjectiveResult("a_sym", "symbolic", "m/s^2", expr="L*sqrt(thetad**4 + thetadd**2)",
                      symbols=("L", "thetad", "thetadd"),
                      symbol_units=("m", "rad/s", "rad/s^2"))


@pytest.mark.parametrize("text, value, unit, figures", [
    ("98.5 ft/s^2", 98.5, "ft / s ** 2", (3, 3)),
    ("98.5 ft/s²", 98.5, "ft / s ** 2", (3, 3)),
    ("30 m*s^-2", 30.0, "m * s ** -2", (1, 2)),
    ("30 m·s⁻²", 30.0, "m * s ** -2", (1, 2)),
    ("4.9e1 m/s", 49.0, "m / s", (2, 2)),
    ("4.9 × 10^1 m/s", 49.0, "m / s", (2, 2)),
    ("4.9 x 10⁻³ m", 0.0049, "m", (2, 2)),
    ("2.24 ft", 2.24, "ft", (3, 3)),
    ("30 deg", 30.0, "deg", (1, 2)),
    ("30°", 30.0, "deg", (1, 2)),
    ("0.52 rad", 0.52, "rad", (2, 2)),
    ("12 rpm", 12.0, "rpm", (2, 2)),
    ("−98.5 ft/s^2", -98.5, "ft / s ** 2", (3, 3)),
    ("a = 98.5 ft/s^2", 98.5, "ft / s ** 2", (3, 3)),
    ("98.5 [ft/s^2]", 98.5, "ft / s ** 2", (3, 3)),
    (".5 m", 0.5, "m", (1, 1)),
])
def test_reads_numbers_with_units(text, value, unit, figures):
    answer = read_answer(text, ACC)
    assert isinstance(answer, NumberAnswer)
    assert answer.value == pytest.approx(value)
    assert answer.unit == unit
    assert (answer.sig_figs, answer.sig_figs_max) == figures


def test_bare_number_has_no_unit():
    answer = read_answer("98.5", ACC)
    assert answer.unit is None and answer.read_back() == "98.5"


def test_constant_expressions_are_exact_numbers():
    answer = read_answer("2*pi rad/s", ACC)
    assert answer.value == pytest.approx(6.283185307)
    assert answer.unit == "rad / s" and answer.sig_figs is None
    assert read_answer("sqrt(2)/2", ACC).value == pytest.approx(0.70710678)
    assert read_answer("pi/6", ACC).read_back() == "pi/6"


@pytest.mark.parametrize("text, components, unit, frame", [
    ("-66 i - 40 j ft/s^2", (-66, -40, 0), "ft / s ** 2", None),
    ("-66i-40j ft/s^2", (-66, -40, 0), "ft / s ** 2", None),
    ("-66 î − 40 ĵ ft/s^2", (-66, -40, 0), "ft / s ** 2", None),
    ("(-66 i - 40 j) ft/s^2", (-66, -40, 0), "ft / s ** 2", None),
    ("(-66, -40) ft/s^2", (-66, -40, 0), "ft / s ** 2", None),
    ("<-66, -40, 0> ft/s^2", (-66, -40, 0), "ft / s ** 2", None),
    ("[-66, -40, 0] ft/s^2", (-66, -40, 0), "ft / s ** 2", None),
    ("3 A.x + 2 A.y m/s", (3, 2, 0), "m / s", "A"),
    ("-7.67 Y_A", (0, -7.67, 0), None, "A"),
    ("-0.5 k rad/s", (0, 0, -0.5), "rad / s", None),
    ("i + j - k", (1, 1, -1), None, None),
    ("2*N.z m", (0, 0, 2), "m", "N"),
])
def test_reads_vectors(text, components, unit, frame):
    answer = read_answer(text, VEC)
    assert isinstance(answer, VectorAnswer)
    assert answer.components == pytest.approx(components)
    assert answer.unit == unit and answer.frame == frame


@pytest.mark.parametrize("text, z", [("0.5 rad/s cw", -0.5), ("0.5 rad/s ccw", 0.5),
                                     ("0.5 rad/s CW", -0.5), ("0.5 rad/s (clockwise)", -0.5),
                                     ("0.5 rad/s counterclockwise", 0.5),
                                     ("0.5 rad/s anti-clockwise", 0.5)])
def test_reads_planar_rotation_sense_as_k_component(text, z):
    answer = read_answer(text, OMEGA)
    assert isinstance(answer, VectorAnswer) and answer.components == (0.0, 0.0, z)


def test_rotation_sense_for_a_scalar_objective_is_a_signed_number():
    scalar = ObjectiveResult("w", "scalar", "rad/s", -0.5)
    assert read_answer("0.5 rad/s cw", scalar).value == -0.5


def test_rotation_sense_with_a_sign_is_refused():
    with pytest.raises(AnswerError, match="either a sign or a sense"):
        read_answer("-0.5 rad/s cw", OMEGA)


def test_units_and_words_that_look_like_unit_vectors_stay_scalars():
    assert read_answer("5 kg", ACC).unit == "kg"
    assert read_answer("12 in", ACC).unit == "in"


@pytest.mark.parametrize("text, expected", [
    ("L sqrt(θ̇^4 + θ̈^2)", "L*sqrt(thetad**4 + thetadd**2)"),
    ("L*sqrt(thetad**4 + thetadd**2)", "L*sqrt(thetad**4 + thetadd**2)"),
    ("L (thetadot^4 + thetaddot^2)^(1/2)", "L*(thetad**4 + thetadd**2)**(1/2)"),
    ("L*sqrt(theta'^4 + theta''^2)", "L*sqrt(thetad**4 + thetadd**2)"),
    ("L*sqrt(theta_dot^4 + theta_ddot^2)", "L*sqrt(thetad**4 + thetadd**2)"),
    ("2 L", "2*L"),
    ("L thetad² - 1e-05", "L*thetad**2 - 1e-05"),
])
def test_reads_expressions_in_the_objectives_symbols(text, expected):
    answer = read_answer(text, SYM)
    assert isinstance(answer, ExpressionAnswer)
    assert answer.text == expected


def test_redundant_parentheses_are_harmless():
    assert read_answer("(" * 200 + "L" + ")" * 200, SYM).text == "L"


def test_greek_names_are_read_as_their_ascii_names():
    assert read_expression("ω^2 r", ("omega", "r")).text == "omega**2*r"


def test_aliases_map_derivative_spellings_to_declared_symbols():
    aliases = symbol_aliases(("thetad", "thetadd", "x"))
    assert aliases[("theta", 1)] == "thetad" and aliases[("theta", 2)] == "thetadd"
    assert aliases["thetaddot"] == "thetadd" and aliases["x"] == "x"


@pytest.mark.parametrize("text, reason", [
    ("", "found nothing"),
    ("   ", "found nothing"),
    ("98.5 flurbs/s^2", "'flurbs' is not a unit"),
    ("98.5 m/s**9**9**9", "unit"),
    ("1,000 m", "thousands separators"),
    ("(-66, -40", "closing"),
    ("(1, 2, 3, 4) m", "2 or 3 components"),
    ("(1 m, 2 m)", "plain numbers as components"),
    ("3 A.x + 2 B.y m/s", "one frame"),
    ("1e999 m", "too large"),
    ("hello", "expected a number"),
    ("cw", "a value before the sense of rotation"),
])
def test_unreadable_numbers_and_vectors_say_why(text, reason):
    with pytest.raises(AnswerError, match=reason):
        read_answer(text, VEC if "(" in text else ACC)


@pytest.mark.parametrize("text, reason", [
    ("__import__('os').system('x')", "expected"),
    ("__import__(1)", "names may not start with '_'"),
    ("().__class__.__base__.__subclasses__()", "expected"),
    ("9**9**9**9", "powers of at most"),
    ("(x+1)**3000", "powers of at most"),
    ("factorial(10**9)", "powers of at most|unknown name"),
    ("factorial(5)", "unknown name 'factorial'"),
    ("lambda: 0", "expected"),
    ("L; import os", "expected"),
    ("'abc'", "expected"),
    ("sqrt(" * 60 + "L" + ")" * 60, "nested"),
    ("-" * 300 + "L", "nested"),
    ("(" * 5000 + "L" + ")" * 5000, "at most 2000 characters"),
    ("L" + "+L" * 500, "at most"),
    ("x", "unknown name 'x'"),
    ("sin theta", "argument in parentheses"),
    ("L.x", "expected"),
])
def test_hostile_and_wrong_expressions_are_refused(text, reason):
    with pytest.raises(AnswerError, match=reason):
        read_answer(text, SYM)


@pytest.mark.parametrize("text, reason", [
    ("9" * 3_000_000, "at most 2000 characters"),
    ("98.5\x00 ft", "control character"),
    ("\x89PNG\r\n\x1a\n", "control character"),
    (b"\xff\xfe98".decode("utf-8", "replace"), "not valid UTF-8"),
    (b"98\xed\xa0\x80".decode("utf-8", "surrogateescape"), "not valid UTF-8"),
])
def test_binary_and_huge_text_is_refused(text, reason):
    for objective in (ACC, SYM):
        with pytest.raises(AnswerError, match=reason):
            read_answer(text, objective)


def test_non_text_is_refused():
    with pytest.raises(AnswerError, match="expected text"):
        clean(98.5)


@pytest.mark.parametrize("text, figures", [
    ("100", (1, 3)), ("100.", (3, 3)), ("1.00e2", (3, 3)), ("0.0010", (2, 2)),
    ("10.0", (3, 3)), ("0", (1, 1)), ("0.0", (1, 1)), (".0", (1, 1)), ("0.00", (2, 2)), ("0.01", (1, 1)), ("98.5", (3, 3)),
    ("-4.90 x 10^1", (3, 3)),
])
def test_counts_written_significant_figures_like_stack(text, figures):
    assert significant_figures(text) == figures


@given(st.floats(min_value=-1e12, max_value=1e12, allow_nan=False, allow_infinity=False))
def test_any_written_float_reads_back_to_itself(value):
    answer = read_answer(f"{value!r} m/s^2", ACC)
    assert answer.value == value
    assert number_value(repr(value)) == value


@given(st.lists(st.floats(min_value=-1e6, max_value=1e6, allow_nan=False), min_size=2,
                max_size=3))
def test_any_bracketed_vector_reads_its_components(values):
    text = "(" + ", ".join(repr(v) for v in values) + ") m"
    answer = read_answer(text, VEC)
    assert list(answer.components[: len(values)]) == values


@given(st.text(max_size=60))
def test_arbitrary_text_either_reads_or_says_why(text):
    for objective in (ACC, VEC, SYM):
        try:
            read_answer(text, objective)
        except AnswerError as exc:
            assert exc.message
