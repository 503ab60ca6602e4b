"""Reading student answer text: every accepted syntax, and every refusal with its reason."""

import pytest
from hypothesis import given, strategies as st

from mechgrade.errors import AnswerError
from mechgrade.grade.answers import (ExpressionAnswer, NumberAnswer, VectorAnswer, clean,
                                     number_value, read_answer, read_expression,
                                     significant_figures, symbol_aliases)
from mechgrade.grade.compare import assess
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
    ("98.5 m/s**9**9**9", "powers of at most 64"),
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


# ---------------------------------------------------------------- issue 7: no misreadings

DIST = ObjectiveResult("d", "scalar", "m", 1000.0)


@pytest.mark.parametrize("text, reason", [
    # number fragments are never multiplied together
    ("98.5.0", "expected one number, found a second decimal point at '98.5«.»0'"),
    ("98..5", "expected one number, found a second decimal point at '98.«.»5'"),
    ("1.2.3", "expected one number, found a second decimal point at '1.2«.»3'"),
    ("9.85e1.5", "expected one number, found a second decimal point at '9.85e1«.»5'"),
    # digit groups other than SI-style threes
    ("1 00 m", "expected one number, found more digits at '1 «0»0 m' (write 1000, or group "
               "digits in threes: 1 000)"),
    ("12 34", "expected one number, found more digits"),
    # e is not a unit (the elementary charge)
    ("9.85 e1", "found 'e' in 'e1' (not a unit here: the elementary charge; for a power of "
                "ten write 9.85e1)"),
    ("1e", "found 'e' in 'e' (not a unit here: the elementary charge"),
    ("98.5 e", "not a unit here: the elementary charge"),
    # malformed or ambiguous units
    ("98.5 ft//s^2", "expected a unit such as 'ft/s^2', found 'ft/«/»s^2' (an operator with "
                     "nothing before it)"),
    ("98.5 fts^-2", "found 'fts' in 'fts^-2' (ambiguous: write ft or ft*s)"),
    ("98.5 ft/s-2", "found 'ft/«s-2»' (a negative power after '/' is ambiguous: write s^2 or "
                    "*s^-2)"),
    ("98.5 ft*/s^2", "(an operator with nothing before it)"),
    ("98.5 c", "not a unit here: the speed of light"),
    ("98.5 ft pi", "not a unit here: a number; write it before the unit, as in 2*pi rad"),
    # a sense of rotation for a quantity that is not angular
    ("98.5 ft/s^2 cw", "expected a signed value: a sense of rotation (cw) only goes with an "
                       "angle or angular velocity or acceleration"),
    # '#' anywhere
    ("98.5 ft/s^2 # approx", "expected an answer without '#' (nothing after it would be "
                             "read), found '98.5 ft/s^2 «#» approx'"),
    ("#98.5 ft/s^2", "without '#'"),
    # two answers in one value
    ("98.5\r\n30 m/s^2", "expected one answer on one line, found a line break at "
                         "'98.5«\\r»\\n30 m/s^2'"),
    ("98.5\u2029 30 m/s^2", "found a line break at '98.5«\\u2029» 30 m/s^2'"),
    ("98.5\u2028 30 m/s^2", "found a line break"),
    ("98.5\n30 m/s^2", "found a line break"),
    ("98.5\x0b30 m/s^2", "found a line break"),
    ("98.5\x8530 m/s^2", "found a line break"),
    # a list item's "- " before a signed number
    ("- -98.5 ft/s^2", "expected one sign, found two at '«- -»98.5 ft/s^2' (a leading '- ' "
                       "from a list?)"),
    ("+-98.5 ft/s^2", "expected one sign, found two"),
    # constants that overflow are too large, never a verdict
    ("exp(exp(exp(100)))", "expected numbers of at most 1e+150, found 'exp(exp(100))' "
                           "(too large)"),
    ("exp(1000) ft/s^2", "(too large)"),
    ("2^2^7 ft", "expected powers of at most 64, found '2**7'"),
    ("sqrt(-2) ft/s^2", "expected a real constant, found 'sqrt(-2)' (not a real number)"),
    ("1/0 ft/s^2", "(divides by zero)"),
    # offset temperature scales
    ("20 degC", "expected an absolute temperature (K or degR), found 'degC' (an offset "
                "scale: convert to K first)"),
    ("20 °C", "found 'degC' (an offset scale"),
    ("68 °F", "found 'degF' (an offset scale"),
])
def test_misreadings_are_refused_with_a_reason_that_shows_the_fix(text, reason):
    with pytest.raises(AnswerError) as info:
        read_answer(text, ACC)
    assert reason in info.value.message
    assert len(info.value.message) <= 200


@pytest.mark.parametrize("text, objective", [
    ("- -66 i - 40 j ft/s^2", VEC),
    ("- -66 i - 40 j", VEC),
    ("(-66, -40#) ft/s^2", VEC),
    ("(-66, -40)\n(1, 2) ft/s^2", VEC),
    ("L#", SYM),
    ("2 3 L", SYM),
    ("98.5.0 L", SYM),
])
def test_vectors_and_expressions_refuse_the_same_misreadings(text, objective):
    with pytest.raises(AnswerError):
        read_answer(text, objective)


@pytest.mark.parametrize("text, value, unit, figures", [
    ("3 002.28 cm/s^2", 3002.28, "cm / s ** 2", (6, 6)),
    ("12 345", 12345.0, None, (5, 5)),
    ("1 000 m", 1000.0, "m", (1, 4)),
    ("1\u2009000 m", 1000.0, "m", (1, 4)),
    ("1\u202f000.5 m", 1000.5, "m", (5, 5)),
    ("-12 345 678 m", -12345678.0, "m", (8, 8)),
])
def test_si_digit_groups_of_three_are_one_number(text, value, unit, figures):
    answer = read_answer(text, DIST)
    assert (answer.value, answer.unit, (answer.sig_figs, answer.sig_figs_max)) == \
        (value, unit, figures)


@pytest.mark.parametrize("text, unit", [
    ("98.5 *ft/s^2", "ft / s ** 2"),
    ("98.5*ft/s^2", "ft / s ** 2"),
    ("3.05 g0", "g_0"),
    ("3.05 g_0", "g_0"),
    ("3.05 g_n", "g_n"),
    ("300 K", "K"),
    ("540 degR", "degR"),
    ("98.5 ft/s^2 ", "ft / s ** 2"),
    ("98.5 ft/s^2\r\n", "ft / s ** 2"),
])
def test_unambiguous_forms_are_read(text, unit):
    answer = read_answer(text, ACC)
    assert answer.unit == unit and answer.sig_figs is not None


def test_standard_gravity_converts_as_a_unit():
    judged = read_answer("3.0617 g0", ACC)
    assert judged.unit == "g_0"


def test_bracketed_components_may_be_constant_expressions():
    answer = read_answer("(sqrt(2)/2, sqrt(2)/2) ft/s^2", VEC)
    assert answer.components == pytest.approx((0.70710678, 0.70710678, 0.0))
    assert read_answer("(pi/4, 2) rad/s", VEC).components[0] == pytest.approx(0.7853981)


def test_a_sense_of_rotation_still_reads_for_angular_objectives():
    scalar = ObjectiveResult("w", "scalar", "rad/s", -0.5)
    assert read_answer("0.5 rad/s cw", scalar).value == -0.5
    angle = ObjectiveResult("q", "scalar", "deg", -30.0)
    assert read_answer("30 deg cw", angle).value == -30.0


def test_imaginary_literal_is_a_product_with_a_declared_j():
    assert read_expression("3j + 2J", ("j", "J")).text == "3*j + 2*J"


def test_e_notation_is_refused_when_e_is_a_declared_symbol():
    with pytest.raises(AnswerError) as info:
        read_expression("2E+3", ("E",))
    assert info.value.message == ("expected 2*E or 2*10^3, found '«2E+3»' (E is a declared "
                                  "symbol: a power of ten or a product?)")
    assert read_expression("2E+3", ("L",)).text == "2000.0"


def test_a_non_real_constant_is_refused_in_an_expression():
    with pytest.raises(AnswerError, match=r"found 'sqrt\(-2\)' \(not a real number\)"):
        read_expression("sqrt(-2) L", ("L",))


def test_a_huge_answer_gets_a_short_reason():
    for text in ("9" * 1_000_000, "98.5 " + "x" * 1990, "(" + "1, " * 600 + "2) m",
                 "98.5 ft/" + "s" * 1900):
        with pytest.raises(AnswerError) as info:
            read_answer(text, VEC)
        assert len(info.value.message) <= 200, info.value.message


def test_many_long_symbol_names_still_give_a_short_reason():
    symbols = tuple(f"symbol_with_a_long_name_{i}" for i in range(30))
    for text in ("unknown_name", "2e+3 unknown"):
        with pytest.raises(AnswerError) as info:
            read_expression(text, symbols + ("e",))
        assert len(info.value.message) <= 200


SPEED = ObjectiveResult("v", "scalar", "m / s", 7.0)
RATIO = ObjectiveResult("r", "scalar", "", 0.5)


@pytest.mark.parametrize("text, objective, reason", [
    ("fast", SPEED, "expected a number with its unit such as '12.5 m/s', found 'fast'"),
    ("fast", ACC, "expected a number with its unit such as '12.5 ft/s^2', found 'fast'"),
    ("fast", VEC, "expected a vector such as '(12.5, -3) ft/s^2', found 'fast'"),
    ("fast", RATIO, "expected a number such as '12.5', found 'fast'"),
    ("(1, 2, 3, 4) m/s", SPEED, "expected 2 or 3 components such as '(12.5, -3) m/s', found 4"),
    ("7 m//s", SPEED, "expected a unit such as 'm/s', found"),
    ("9.02 Nm", ObjectiveResult("T", "scalar", "J", 9.0),
     "expected a unit such as 'J', found 'Nm' in 'Nm' (not a unit here: write N*m for "
     "newton metres)"),
])
def test_an_example_in_a_reason_is_written_in_the_objectives_own_unit(text, objective,
                                                                       reason):
    with pytest.raises(AnswerError) as info:
        read_answer(text, objective)
    assert info.value.message.startswith(reason), info.value.message


# ------------------------------------------- issue 18: answers read as students type them
# Each row is a student's spelling and how it must be read: (value, unit, written figures) or
# a refusal whose reason names the readings. Checked against the peers' own test tables:
# * STACK, tests/fixtures/answertestfixtures.class.php: NumSigFigs ``-(0.05)`` is right to 1
#   figure (brackets keep the written figures); Units ``(-9.81)*m/s^2`` matches
#   ``-9.81*m/s^2``, ``sqrt(2)*m`` is read (an exact value: "WrongDigits"), ``0.200*dpt`` is
#   ``0.200/m`` (dpt the dioptre); inputfixtures.class.php: ``1,23`` is a decimal comma only
#   where the question says so, otherwise "unencapsulated_comma".
# * WeBWorK, lib/Units.pm and t/units/electromagnetic.t: ``G`` is the gauss of engineering,
#   1e-4 T ("1 milliTesla is 10 Gauss"); lib/Parser/Context/Default.pm gives juxtaposition
#   (precedence 3.1) a tighter binding than ``/`` (3), so ``3g/2L`` is 3g/(2L) there while
#   STACK and sympy read (3g/2)L: peers disagree, so mechgrade asks.
# * PrairieLearn, python/test/sympy_utils_test.py: ``e^(pi * i)`` is -1 (an undeclared ``e``
#   is Euler's number).

SI_ACC = ObjectiveResult("a", "scalar", "m/s^2", -12.0)
SI_VEC = ObjectiveResult("v", "vector", "m/s", (-3.0, 4.0, 0.0), frame="N")
FREE_FALL = ObjectiveResult("h", "symbolic", "m", expr="v**2/(2*g)", symbols=("v", "g"),
                            symbol_units=("m/s", "m/s^2"))
PERIOD = ObjectiveResult("T", "symbolic", "s", expr="2*pi*sqrt(L/g)", symbols=("L", "g"),
                         symbol_units=("m", "m/s^2"))
DROP_SPEED = ObjectiveResult("v", "symbolic", "m/s", expr="sqrt(2*g*h)", symbols=("g", "h"),
                        symbol_units=("m/s^2", "m"))
DECAY = ObjectiveResult("r", "symbolic", "1", expr="exp(-zeta*omega*t)",
                        symbols=("zeta", "omega", "t"), symbol_units=("1", "rad/s", "s"))
EOM = ObjectiveResult("q", "symbolic", "rad/s^2", expr="3*g/(2*L)", symbols=("g", "L"),
                      symbol_units=("m/s^2", "m"))
WITH_X = ObjectiveResult("d", "symbolic", "m", expr="2*L", symbols=("x", "L"),
                         symbol_units=("m", "m"))
SPRING = ObjectiveResult("F", "symbolic", "N", expr="m*omega**2*r",
                         symbols=("m", "omega", "r", "thetad"),
                         symbol_units=("kg", "rad/s", "m", "rad/s"))

AS_TYPED = [
    # (text, objective, (value, unit, (figures lo, hi))) for numbers
    ("(-12.00)", SI_ACC, (-12.0, None, (4, 4))),
    ("-(12.000)", SI_ACC, (-12.0, None, (5, 5))),
    ("-(0.05)", SI_ACC, (-0.05, None, (1, 1))),
    ("((-12.00)) m/s^2", SI_ACC, (-12.0, "m / s ** 2", (4, 4))),
    ("-(12.000) m/s^2", SI_ACC, (-12.0, "m / s ** 2", (5, 5))),
    ("(-9.81)m/s^2", SI_ACC, (-9.81, "m / s ** 2", (3, 3))),
    ("(-9.81)*m/s^2", SI_ACC, (-9.81, "m / s ** 2", (3, 3))),
    ("1/3*m/s^2", SI_ACC, (1 / 3, "m / s ** 2", (None, None))),
    ("sqrt(2)*m", SI_ACC, (2 ** 0.5, "m", (None, None))),
    ("(1+1/sqrt(2)+3)*N", SI_ACC, (4 + 2 ** -0.5, "N", (None, None))),
    ("2*pi*rad/s", SI_ACC, (2 * 3.141592653589793, "rad / s", (None, None))),
    ("0.200 dpt", SI_ACC, (0.2, "dpt", (3, 3))),
    ("1e4 G", SI_ACC, (1e4, "G", (1, 1))),
    ("12,5 m/s^2", SI_ACC, (12.5, "m / s ** 2", (3, 3))),
    ("-9,81 m/s^2", SI_ACC, (-9.81, "m / s ** 2", (3, 3))),
    ("sin(30°)", SI_ACC, (0.5, None, (None, None))),
    ("sin(30 deg)", SI_ACC, (0.5, None, (None, None))),
    ("5*sin(30°) m", SI_ACC, (2.5, "m", (None, None))),
    ("2*30 deg", SI_ACC, (60.0, "deg", (None, None))),
    ("√2/2", SI_ACC, (2 ** -0.5, None, (None, None))),
    # (text, objective, (components, unit)) for vectors
    ("5 m/s at 126.87°", SI_VEC, ((-3.0, 4.0, 0.0), "m / s")),
    ("5 m/s at 126.87 deg", SI_VEC, ((-3.0, 4.0, 0.0), "m / s")),
    ("5.00 m/s @ 2.2143 rad", SI_VEC, ((-3.0, 4.0, 0.0), "m / s")),
    ("5 m/s ∠ -53.13°", SI_VEC, ((3.0, -4.0, 0.0), "m / s")),
    # (text, objective, read back) for expressions
    ("2 × L", WITH_X, "2*L"),
    ("2π√(L/g)", PERIOD, "2*pi*sqrt(L/g)"),
    ("2 pi sqrt(L/g)", PERIOD, "2*pi*sqrt(L/g)"),
    ("√(2gh)", DROP_SPEED, "sqrt(2*g*h)"),
    ("√(2 g h)", DROP_SPEED, "sqrt(2*g*h)"),
    ("e^(-ζωt)", DECAY, "exp(-zeta*omega*t)"),
    ("e^(-zeta omega t)", DECAY, "exp(-zeta*omega*t)"),
    ("mω²r", SPRING, "m*omega**2*r"),
    ("m θd^2 r", SPRING, "m*thetad**2*r"),
    ("v^2/(2g)", FREE_FALL, "v**2/(2*g)"),
    ("3g/(2L)", EOM, "3*g/(2*L)"),
    ("(3g/2)/L", EOM, "3*g/2/L"),
    ("2pisqrt(L/g)", PERIOD, "2*pi*sqrt(L/g)"),
    ("pir^2", ObjectiveResult("A", "symbolic", "m^2", expr="pi*r**2", symbols=("r",),
                              symbol_units=("m",)), "pi*r**2"),
    ("gh^2/L", ObjectiveResult("x", "symbolic", "m^2", expr="g*h**2/L",
                               symbols=("g", "h", "L"), symbol_units=("m/s^2", "m", "m")),
     "g*h**2/L"),
    ("sqrt(2gh)", DROP_SPEED, "sqrt(2*g*h)"),
    ("(2gh)^(1/2)", DROP_SPEED, "(2*g*h)**(1/2)"),
]


@pytest.mark.parametrize("text, objective, expected", AS_TYPED)
def test_answers_are_read_as_students_type_them(text, objective, expected):
    answer = read_answer(text, objective)
    if isinstance(answer, ExpressionAnswer):
        assert answer.text == expected
    elif isinstance(answer, VectorAnswer):
        components, unit = expected
        assert answer.components == pytest.approx(components, abs=1e-3)
        assert answer.unit == unit
    else:
        value, unit, figures = expected
        assert answer.value == pytest.approx(value, rel=1e-12)
        assert answer.unit == unit
        assert (answer.sig_figs, answer.sig_figs_max) == figures


REFUSED_AS_TYPED = [
    # two readings, both shown
    ("3g/2L", EOM, "expected brackets to show what is divided, found '3g/2L': "
                   "3g/(2L) or (3g/2)L?"),
    ("v^2/2g", FREE_FALL, "expected brackets to show what is divided, found 'v^2/2g': "
                          "v^2/(2g) or (v^2/2)g?"),
    ("√2gh", DROP_SPEED, "expected brackets after √, found '√2gh': √(2gh) or √(2)gh?"),
    ("1,250 m/s^2", SI_ACC, "expected one number, found '1,250': 1250 with thousands "
                            "separators or 1.250 with a decimal comma? Write 1250 or 1.250"),
    ("12,5 m/s", SI_VEC, "expected a vector in brackets or one number, found '12,5': two "
                         "components (write (12, 5)) or 12.5 with a decimal comma?"),
    ("1/2kg", SI_ACC, "expected brackets to show what is divided, found '1/2kg': 1/(2kg) "
                      "or (1/2)kg?"),
    ("aba", ObjectiveResult("x", "symbolic", "1", expr="a", symbols=("a", "b", "ba")),
     "expected declared names, found 'aba': a b a or a ba? (write spaces or * between them)"),
    # the part that cannot be read, named
    ("sqrt2gh", DROP_SPEED, "found the unknown name 'sqrt2gh' (a function's argument goes in "
                       "brackets: sqrt(2gh))"),
    ("mu g", ObjectiveResult("f", "symbolic", "m/s^2", expr="m*u*g", symbols=("m", "u", "g"),
                             symbol_units=("1", "1", "m/s^2")),
     "found the unknown name 'mu'"),
    ("5 m/s at 126.87", SI_VEC, "expected an angle with its unit after 'at', such as "
                                "'126.87°' or '2.214 rad', found '126.87'"),
    ("5 at 126.87° m/s", SI_VEC, "expected an angle with its unit after 'at'"),
]


@pytest.mark.parametrize("text, objective, reason", REFUSED_AS_TYPED)
def test_ambiguous_spellings_are_refused_with_both_readings(text, objective, reason):
    with pytest.raises(AnswerError) as info:
        read_answer(text, objective)
    assert reason in info.value.message
    assert len(info.value.message) <= 200


@pytest.mark.parametrize("text, objective", [
    ("0" * 21 + ",0", SI_VEC),
    ("1" + ",000" * 10 + " m/s^2", SI_ACC),
    ("√2" + "gh" * 40, DROP_SPEED),
    ("sqrt" + "2" * 30 + "gh", DROP_SPEED),
    ("v^2/" + "2" * 40 + "g", FREE_FALL),
    ("ab" * 12, ObjectiveResult("x", "symbolic", "1", expr="a", symbols=("a", "b", "ab"))),
    ("5 m/s at " + "1" * 60, SI_VEC),
])
def test_long_spellings_get_short_reasons(text, objective):
    judged = assess(text, objective)
    assert judged.verdict == "unreadable" and len(judged.feedback) <= 200, judged.feedback
