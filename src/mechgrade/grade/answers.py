"""Read one student's answer text into a frozen value, or say exactly why it cannot be read.

Three shapes, chosen from the text and the objective's kind:

* :class:`NumberAnswer` -- ``98.5 ft/s^2``, ``4.9e1 m/s``, ``30°``, ``0.5 rad/s cw``;
* :class:`VectorAnswer` -- ``-66 i - 40 j ft/s^2``, ``(-66, -40) ft/s^2``,
  ``<-66, -40, 0> ft/s^2``, ``3 A.x + 2 A.y m/s``, ``-7.67 Y_A``;
* :class:`ExpressionAnswer` -- ``L sqrt(θ̇^4 + θ̈^2)`` in the objective's symbols.

Nothing here calls ``eval``, ``sympify`` or ``parse_expr``: numbers are read with a regular
expression, units through :func:`mechgrade.units.normalize_unit` (an allow-list) and expressions
through :func:`mechgrade.expressions.syntax.parse` (an ``ast`` allow-list with size, depth and
exponent bounds). Every refusal is an :class:`~mechgrade.errors.AnswerError` whose message says
what was expected and what was found.

>>> from mechgrade.solve.result import ObjectiveResult
>>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
>>> read_answer("98.5 ft/s²", acc)
NumberAnswer(value=98.5, unit='ft / s ** 2', sig_figs=3, sig_figs_max=3, text='98.5', degrees=None)
>>> read_answer("(-66, -40) ft/s^2", ObjectiveResult("v", "vector", "ft/s^2", (-66.0, -40.0, 0.0), frame="N")).components
(-66.0, -40.0, 0.0)
"""

from __future__ import annotations

import math
import re
import unicodedata
from dataclasses import dataclass
from functools import lru_cache
from types import MappingProxyType
from typing import Mapping, TypeGuard, Union

from ..errors import AnswerError, ExpressionError, UnitError
from ..expressions import syntax
from ..expressions.syntax import Bin, Call, Name, Node, Num, Prime, Unary
from ..expressions.excerpt import excerpt
from ..solve.result import ObjectiveResult, in_frame
from .results import EXAMPLE_NUMBER
from ..spec.model import ObjectiveKind
from ..spec.validate import is_angle_unit
from ..units import MAX_UNIT_LENGTH, dimension, normalize_unit, to_si

MAX_ANSWER_LENGTH = 2000
"""Longest answer text read at all (the expression reader has the same bound)."""

MAX_COMPONENTS = 3
SHORT = 16
"""Longest part of an answer a reason repeats in full (in its readings); longer parts are
quoted cut, so a reason stays short."""


# ---------------------------------------------------------------------------- values


@dataclass(frozen=True)
class NumberAnswer:
    """A number, the unit it was written in (``None``: no unit written; ``""``: a pure number
    written as such) and its written significant figures.

    ``sig_figs`` .. ``sig_figs_max`` is the range the written form allows: ``100`` has 1 to 3,
    ``1.00e2`` exactly 3 (the STACK convention). ``text`` is the number as written; a constant
    expression such as ``pi/6`` has ``sig_figs=None`` (exact). ``degrees`` is the value of
    a constant such as ``sin(30)`` with its trig arguments read in degrees (a hint for the
    judge; ``None`` without such an argument).
    """

    value: float
    unit: str | None
    sig_figs: int | None
    sig_figs_max: int | None
    text: str
    degrees: float | None = None

    kind = "scalar"

    def read_back(self) -> str:
        return _with_unit(self.text, self.unit)


@dataclass(frozen=True)
class VectorAnswer:
    """Components ``(x, y, z)`` along the unit vectors of ``frame`` (``None``: plain
    ``i, j, k`` or a bracketed tuple, meaning the objective's own frame).

    ``sig_figs`` holds the written range of each component, as for :class:`NumberAnswer`;
    ``texts`` the components as written (``"0"`` for an omitted one); ``degrees`` the
    components with trig arguments read in degrees (as :class:`NumberAnswer`); ``written``
    the answer as read when it was not given by components (``5 m/s at 126.87 deg``).
    """

    components: tuple[float, ...]  # always three
    unit: str | None
    frame: str | None
    sig_figs: tuple[tuple[int | None, int | None], ...]
    texts: tuple[str, ...]  # always three
    degrees: tuple[float, ...] | None = None
    written: str | None = None

    kind = "vector"

    def read_back(self) -> str:
        if self.written:
            return self.written
        return _with_unit(f"({', '.join(self.texts)})", self.unit) + in_frame(self.frame)


@dataclass(frozen=True)
class ExpressionAnswer:
    """An expression tree whose names are exactly the objective's symbols (aliases resolved)."""

    node: Node
    text: str

    kind = "symbolic"

    def read_back(self) -> str:
        return self.text


StudentAnswer = Union[NumberAnswer, VectorAnswer, ExpressionAnswer]


def _with_unit(text: str, unit: str | None) -> str:
    if not unit:
        return text
    return f"{text} {_pretty_unit(unit)}"


def _pretty_unit(unit: str) -> str:
    """Canonical unit text written compactly (``ft / s ** 2`` -> ``ft/s^2``)."""
    return unit.replace(" ** ", "^").replace(" * ", "*").replace(" / ", "/")


# ---------------------------------------------------------------------------- cleaning

_DASHES = str.maketrans({"−": "-", "–": "-", "—": "-", "‐": "-", "﹣": "-", "－": "-",
                         "×": "*", "⋅": "*", "·": "*", "∙": "*", "\u00a0": " ",
                         "î": "i", "ĵ": "j", "⟨": "<", "⟩": ">"})
_SUPERSCRIPT_RUN = re.compile(r"([⁺⁻]?)([⁰¹²³⁴⁵⁶⁷⁸⁹]+)")
_SUPER_DIGITS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹", "0123456789")
_ASSIGNMENT = re.compile(r"^\s*[A-Za-z_\u0370-\u03ff][\w\u0300-\u036f\u0370-\u03ff']*\s*=(?!=)\s*")
_SENSE = re.compile(r"\s*\(?\s*(?P<sense>ccw|cw|counter[- ]?clockwise|anti[- ]?clockwise|clockwise)"
                    r"\s*\)?\s*$", re.IGNORECASE)


def clean(text: str) -> str:
    """Check that ``text`` is one bounded line of readable text; normalise dashes, superscripts
    and spaces (thin and no-break spaces are spaces).

    >>> clean("  −66 î − 40 ĵ ft/s² ")
    '-66 i - 40 j ft/s^2'
    >>> clean("9\\x00")
    Traceback (most recent call last):
    ...
    mechgrade.errors.AnswerError: expected text, found a control character at '9«\\x00»' (binary data?)
    >>> clean("98.5\\r\\n30 m/s^2")
    Traceback (most recent call last):
    ...
    mechgrade.errors.AnswerError: expected one answer on one line, found a line break at '98.5«\\r»\\n30 m/s^2'
    """
    if not isinstance(text, str):
        raise AnswerError(f"expected text, found {type(text).__name__}")
    if len(text) > MAX_ANSWER_LENGTH:
        raise AnswerError(f"expected an answer of at most {MAX_ANSWER_LENGTH} characters, "
                          f"found {len(text)} characters: {excerpt(text)}")
    # printable ASCII (most answers) holds none of the characters looked for below
    plain = text.isascii() and text.isprintable()
    bad = None if plain else next((i for i, c in enumerate(text)
                                   if c == "\ufffd" or 0xD800 <= ord(c) <= 0xDFFF), None)
    if bad is not None:
        raise AnswerError(f"expected readable text, found bytes that are not valid UTF-8 at "
                          f"{excerpt(text, bad)}")
    text = text.strip()
    bad = None if plain else next((i for i, c in enumerate(text) if unicodedata.category(c)
                                   == "Cc" and c not in _LINE_BREAKS and c != "\t"), None)
    if bad is not None:
        raise AnswerError(f"expected text, found a control character at {excerpt(text, bad)} "
                          f"(binary data?)")
    bad = None if plain else next((i for i, c in enumerate(text) if c in _LINE_BREAKS), None)
    if bad is not None:
        raise AnswerError(f"expected one answer on one line, found a line break at "
                          f"{excerpt(text, bad)}")
    if "#" in text:
        raise AnswerError(f"expected an answer without '#' (nothing after it would be read), "
                          f"found {excerpt(text, text.index('#'))}")
    if not plain:  # printable ASCII is its own NFC form, without dashes, hats or superscripts
        text = unicodedata.normalize("NFC", text).translate(_DASHES)
        text = text.replace("k\u0302", "k").replace("i\u0302", "i").replace("j\u0302", "j")
        text = _SUPERSCRIPT_RUN.sub(lambda m: "^" + ("-" if m.group(1) == "⁻" else "")
                                    + m.group(2).translate(_SUPER_DIGITS), text)
    return " ".join(text.split())


_LINE_BREAKS = "\n\r\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029"


# ---------------------------------------------------------------------------- numbers

# An integer part is digits, or SI-style groups of exactly three digits after one to three
# (``12 345``, ``3 002.28``): grouped digits are one number, never a product.
_INTEGER = r"(?:\d{1,3}(?: \d{3})+(?![\d])|\d+)"
_NUMBER_TEXT = (r"[+-]?\s*(?:" + _INTEGER + r"(?:\.\d*)?|\.\d+)"
                r"(?:[eE][+-]?\d+|\s*[x*]\s*10\s*(?:\^|\*\*)\s*\(?\s*[+-]?\d+\s*\)?)?")
_NUMBER = re.compile(r"\s*(" + _NUMBER_TEXT + r")")
_MANTISSA = re.compile(r"[+-]?\s*(?P<m>\d+(?:\.\d*)?|\.\d+)"
                       r"(?:[eE](?P<e1>[+-]?\d+)|\s*[x*]\s*10\s*(?:\^|\*\*)\s*\(?\s*(?P<e2>[+-]?\d+)"
                       r"\s*\)?)?$")
MAX_MAGNITUDE = 1e300


def number_value(text: str) -> float:
    """The value of a number as written (``4.9e1``, ``4.9 x 10^1``, ``-.5``, ``12 345``).

    >>> number_value("4.9 x 10^1"), number_value("-2.5e-3"), number_value("1 000")
    (49.0, -0.0025, 1000.0)
    """
    compact = text.replace(" ", "")
    m = _MANTISSA.match(compact)
    if not m:
        raise AnswerError(f"expected a number such as 98.5 or 4.9e1, found {excerpt(text)}")
    exponent_text = m.group("e1") or m.group("e2") or "0"
    if len(exponent_text.lstrip("+-")) > 4:
        raise AnswerError(f"expected a number of at most {MAX_MAGNITUDE:g}, found "
                          f"{excerpt(text)} (too large)")
    sign = -1.0 if compact.startswith("-") else 1.0
    value = sign * float(f"{m.group('m')}e{int(exponent_text)}")
    if abs(value) > MAX_MAGNITUDE:
        raise AnswerError(f"expected a number of at most {MAX_MAGNITUDE:g}, found "
                          f"{excerpt(text)} (too large)")
    return value


def significant_figures(text: str) -> tuple[int, int]:
    """The range of significant figures a written number has (STACK's liberal reading).

    Leading zeros never count; trailing zeros of a whole number without a decimal point may or
    may not (``100``: 1 to 3); with a decimal point or in scientific notation they count.

    Zero has as many figures as it has decimal places (at least one): ``0`` and ``0.0`` one,
    ``0.00`` two (STACK's StrictSigFigs table; PrairieLearn counts the same way).

    >>> [significant_figures(t) for t in ("100", "1.00e2", "0.0010", "10.0", "0", "0.00", "98.5")]
    [(1, 3), (3, 3), (2, 2), (3, 3), (1, 1), (2, 2), (3, 3)]
    """
    m = _MANTISSA.match(text.replace(" ", ""))
    if not m:
        raise AnswerError(f"expected a number such as 98.5 or 4.9e1, found {excerpt(text)}")
    mantissa = m.group("m")
    digits = mantissa.replace(".", "")
    significant = digits.lstrip("0")
    if not significant:  # the number zero
        places = len(mantissa.partition(".")[2])
        return max(1, places), max(1, places)
    if "." in mantissa:
        return len(significant), len(significant)
    trailing = len(significant) - len(significant.rstrip("0"))
    return len(significant) - trailing, len(significant)


# ---------------------------------------------------------------------------- reading


def read_answer(text: str, result: ObjectiveResult) -> StudentAnswer:
    """:func:`_read_answer`, whose messages give their examples in the objective's own unit
    and kind (an example in ft/s² for an answer asked in m/s misleads, and its number was
    the answer to a problem of the examples).

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> read_answer("fast", ObjectiveResult("v", "scalar", "m / s", 2.0))
    Traceback (most recent call last):
    ...
    mechgrade.errors.AnswerError: expected a number with its unit such as '12.5 m/s', found 'fast'
    """
    try:
        return _read_answer(text, result)
    except AnswerError as exc:
        raise AnswerError(_in_own_unit(exc.message, result)) from None


_SCALAR_EXAMPLE = "a number with a unit such as '98.5 ft/s^2'"
_VECTOR_EXAMPLE = "components such as '(-66, -40) ft/s^2'"
_UNIT_EXAMPLE = "unit such as 'm/s^2'"  # in mechgrade.units' messages about text that is no unit


def _in_own_unit(message: str, result: ObjectiveResult) -> str:
    """``message`` with its generic examples written as an answer to ``result`` is."""
    unit = _pretty_unit(result.unit)
    vector = f"({EXAMPLE_NUMBER}, -3)" + (f" {unit}" if unit else "")
    scalar = (f"a vector such as '{vector}'" if result.kind == ObjectiveKind.VECTOR
              else f"a number with its unit such as '{EXAMPLE_NUMBER} {unit}'" if unit
              else f"a number such as '{EXAMPLE_NUMBER}'")
    message = message.replace(_SCALAR_EXAMPLE, scalar)
    message = message.replace(_VECTOR_EXAMPLE, f"components such as '{vector}'")
    return message.replace(_UNIT_EXAMPLE, f"unit such as '{unit}'") if unit else message


def _read_answer(text: str, result: ObjectiveResult) -> StudentAnswer:
    """Read ``text`` as an answer to ``result``; raise :class:`AnswerError` saying why not.

    The objective's kind decides what is expected: a symbolic objective reads an expression in
    its symbols; scalar and vector objectives read numbers with units, bracketed tuples or sums
    over unit vectors (whichever the text is; a vector for a scalar objective is judged later).

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> sym = ObjectiveResult("a", "symbolic", "m/s^2", expr="L*sqrt(thetad**4 + thetadd**2)",
    ...                       symbols=("L", "thetad", "thetadd"),
    ...                       symbol_units=("m", "rad/s", "rad/s^2"))
    >>> read_answer("L sqrt(θ̇^4 + theta''^2)", sym).text
    'L*sqrt(thetad**4 + thetadd**2)'
    >>> read_answer("2 x", sym)
    Traceback (most recent call last):
    ...
    mechgrade.errors.AnswerError: expected an expression in L, thetad, thetadd, found the unknown name 'x'
    """
    text = clean(text)
    if not text:
        raise AnswerError("expected an answer, found nothing")
    # a leading label is ignored: 'a = 9.8 m/s^2', and an equation of motion written as one,
    # "theta'' = -3 g sin(theta)/(2 L)"
    if "=" in text:
        text = _ASSIGNMENT.sub("", text, count=1)
    if result.kind == ObjectiveKind.SYMBOLIC:
        return read_expression(text, result.symbols)
    signs = _DOUBLE_SIGN.search(text)
    if signs:
        raise AnswerError(f"expected one sign, found two at {excerpt(text, signs.start(), signs.end())}"
                          f" (a leading '- ' from a list?)")
    sense = _SENSE.search(text)
    if sense:
        text = text[:sense.start()].strip()
        if not text:
            raise AnswerError("expected a value before the sense of rotation, found only "
                              f"{excerpt(sense.group('sense'))}")
        return _rotation(text, sense.group("sense").lower(), result)
    polar = _polar_vector(text)
    if polar is not None:
        return polar
    if _looks_bracketed(text):
        return _bracketed_vector(text)
    vector = _unit_vector_sum(text)
    if vector is not None:
        return vector
    comma = _DECIMAL_COMMA.match(text)
    if comma and result.kind == ObjectiveKind.VECTOR:
        whole, fraction = comma.group("whole"), comma.group("fraction")
        if len(comma.group(0)) > SHORT:
            whole, fraction = "12", "5"  # an example: the written number is quoted already
        raise AnswerError(f"expected a vector in brackets or one number, found "
                          f"{excerpt(comma.group(0))}: two components (write ({whole}, "
                          f"{fraction})) or {whole}.{fraction} with a decimal comma?")
    return _scalar(text)


_DOUBLE_SIGN = re.compile(r"[+-]\s*[+-]")


def _rotational(result: ObjectiveResult) -> bool:
    """Whether a sense of rotation can describe the objective: an angle, angular velocity or
    acceleration, an angular momentum, or a moment asked as a vector (a scalar in N*m may be
    an energy)."""
    dim = dimension(result.unit)
    if str(dim) in ("dimensionless", "1 / [time]", "1 / [time] ** 2"):
        return True
    return dim == dimension("kg*m^2/s") or (result.kind == ObjectiveKind.VECTOR and dim == dimension("N*m"))


def _rotation(text: str, sense: str, result: ObjectiveResult) -> StudentAnswer:
    """``0.5 rad/s cw``, ``12 N*m ccw``: counter-clockwise is +k (right-handed, k out of the
    page)."""
    if not _rotational(result):
        raise AnswerError(f"expected a signed value: a sense of rotation ({sense}) only goes "
                          f"with an angle or angular velocity or acceleration, an angular "
                          f"momentum or a moment")
    number = _scalar(text)
    if number.value < 0:
        raise AnswerError(f"expected a positive size with '{sense}', found "
                          f"{excerpt(number.text)} (give either a sign or a sense of rotation)")
    clockwise = sense.startswith("cl") or sense == "cw"
    value = -number.value if clockwise else number.value
    shown = ("-" if clockwise else "") + number.text
    if result.kind == ObjectiveKind.VECTOR:
        return VectorAnswer((0.0, 0.0, value), number.unit, None,
                            ((None, None), (None, None), (number.sig_figs, number.sig_figs_max)),
                            ("0", "0", shown))
    return NumberAnswer(value, number.unit, number.sig_figs, number.sig_figs_max, shown)


def _scalar(text: str) -> NumberAnswer:
    bracketed = _bracketed_number(text)
    if bracketed is not None:
        return bracketed
    comma = _DECIMAL_COMMA.match(text)
    point = _decimal_point(comma) if comma else None
    if comma and point is not None:  # 12,5 m/s^2: read back as 12.5 m/s^2
        return _scalar(point + text[comma.end():])
    m = _NUMBER.match(text)
    if not m:
        constant = _constant_with_unit(text)
        if constant is not None:
            return constant
        raise AnswerError(f"expected {_SCALAR_EXAMPLE}, found {excerpt(text)}")
    number_text = " ".join(m.group(1).split()).replace("- ", "-").replace("+ ", "")
    rest = text[m.end():].strip()
    after = len(text) - len(text[m.end():].lstrip())
    if rest[:1] == ".":
        raise AnswerError(f"expected one number, found a second decimal point at "
                          f"{excerpt(text, after)}")
    if rest[:1].isdigit():
        raise AnswerError(f"expected one number, found more digits at {excerpt(text, after)} "
                          f"(write 1000, or group digits in threes: 1 000)")
    if rest.startswith(","):
        grouped = _THOUSANDS.match(text)
        if grouped and grouped.group("whole").strip("+- ") not in ("0", "") \
                and len(grouped.group(0).strip()) <= SHORT:
            number = grouped.group(0).strip()
            plain, decimal = number.replace(",", ""), number.replace(",", ".")
            raise AnswerError(f"expected one number, found {excerpt(number)}: {plain} with "
                              f"thousands separators or {decimal} with a decimal comma? "
                              f"Write {plain} or {decimal}")
        raise AnswerError(f"expected a number without thousands separators (1000, not 1,000) "
                          f"or a vector in brackets such as '(-66, -40)', found "
                          f"{excerpt(text, after)}")
    lo, hi = significant_figures(number_text)
    if rest.startswith("*") and not rest.startswith("**"):
        try:  # 98.5*ft/s^2: an explicit product with the unit keeps the written figures
            return NumberAnswer(number_value(number_text), _unit(rest[1:]), lo, hi, number_text)
        except AnswerError:
            pass
    if _OPERATOR_OR_CONSTANT.match(rest):
        constant = _constant_with_unit(text)
        if constant is not None:
            return constant
    try:
        unit = _unit(rest)
    except AnswerError as unit_error:
        constant = _constant_with_unit(text)
        if constant is not None:
            return constant
        raise unit_error
    return NumberAnswer(number_value(number_text), unit, lo, hi, number_text)


_OPERATOR_OR_CONSTANT = re.compile(r"[*/^(]|\*\*|pi\b|(?:sqrt|sin|cos|tan|exp|log)\s*\(")
# A decimal comma (12,5 or 1 000,25): unambiguous unless it could group thousands (1,250).
_DECIMAL_COMMA = re.compile(r"(?P<whole>[+-]?\s*" + _INTEGER + r"),(?P<fraction>\d+)"
                            r"(?P<exponent>[eE][+-]?\d+)?(?![\d,.])")
_THOUSANDS = re.compile(r"(?P<whole>[+-]?\s*\d{1,3})(?:,\d{3})+(?:\.\d*)?(?![\d,])")
_BRACKETED = re.compile(r"(?P<sign>[+-]?)\s*(?P<open>\(+)\s*(?P<number>" + _NUMBER_TEXT
                        + r")\s*(?P<close>\)+)")


def _decimal_point(comma: re.Match) -> str | None:
    """The number of a decimal-comma match written with a point, or ``None`` where the comma
    could as well group thousands (three digits after it, something other than 0 before)."""
    whole, fraction = comma.group("whole"), comma.group("fraction")
    if len(fraction) == 3 and whole.strip("+- ") != "0":
        return None
    return f"{whole}.{fraction}{comma.group('exponent') or ''}"


def _bracketed_number(text: str) -> NumberAnswer | None:
    """``(-12.00)``, ``-(0.05) m``, ``(-9.81)m/s^2``: one number in brackets keeps its written
    figures (as STACK's NumSigFigs reads ``-(0.05)``); ``None`` when the text is more than
    that (``(2)^2 m`` is a constant expression)."""
    m = _BRACKETED.match(text)
    if not m or len(m.group("open")) != len(m.group("close")):
        return None
    rest = text[m.end():].strip()
    if rest.startswith("*") and not rest.startswith("**"):
        rest = rest[1:]
    try:
        unit = _unit(rest)
    except AnswerError:
        return None
    inner = " ".join(m.group("number").split()).replace("- ", "-").replace("+ ", "")
    negative = (m.group("sign") == "-") != inner.startswith("-")
    number_text = ("-" if negative else "") + inner.lstrip("+-")
    lo, hi = significant_figures(number_text)
    return NumberAnswer(number_value(number_text), unit, lo, hi, number_text)


def _unit(text: str) -> str | None:
    text = text.strip()
    if not text:
        return None
    if text.startswith("[") and text.endswith("]"):
        text = text[1:-1]
    try:
        return normalize_unit(text)
    except UnitError as exc:
        raise AnswerError(exc.message) from None


def _constant_with_unit(text: str) -> NumberAnswer | None:
    """``2*pi rad/s``, ``sqrt(2)/2``, ``1/3*m/s^2``, ``sqrt(2)*m``: a constant expression, then
    an optional unit after a space, a ``*`` or a closing bracket.

    A constant that overflows or is not a real number is refused, never skipped; so is one
    that could be read two ways (``1/2kg``), when no other cut reads."""
    ambiguous = None
    for cut in _cuts(text):
        expression, rest = text[:cut].rstrip(), text[cut:]
        if expression.endswith("*") and not expression.endswith("**"):
            expression = expression[:-1].rstrip()
        if not expression:
            break
        try:  # the unit first: it is short, and most cuts leave no unit
            unit = _unit(rest)
        except AnswerError:
            continue
        try:
            node = syntax.parse(expression, attributes=False)
            value = syntax.constant_value(node)
        except ExpressionError as exc:
            if exc.message.endswith(syntax.CONSTANT_PROBLEMS):
                raise AnswerError(exc.message) from None
            if exc.message == syntax.TOO_MANY_PARTS:
                break  # a few words less will not make a constant expression of it
            if exc.message.startswith(syntax.AMBIGUOUS) and ambiguous is None:
                ambiguous = exc.message
            continue
        if value is None:
            continue
        degrees = syntax.degree_reading(node)
        return NumberAnswer(float(value), unit, None, None, syntax.to_text(node),
                            None if degrees is None else degrees[0])
    if ambiguous is not None:
        raise AnswerError(ambiguous)
    return None


MAX_CUTS = 12
"""Most places a constant expression and its unit are tried apart at (the unit is short)."""


def _cuts(text: str):
    """Where a unit may start after a constant expression, the whole text first: after a
    space, or a unit's first letter after ``*`` or ``)`` (``sqrt(2)*m``, ``(1+2)N``),
    within a unit's length of the end."""
    yield len(text)
    count = 0
    for cut in range(len(text) - 1, max(0, len(text) - MAX_UNIT_LENGTH - 2), -1):
        before, first = text[cut - 1], text[cut]
        if (before == " " and first != " ") or (_UNIT_START.match(first) and (
                before == ")" or (before == "*" and text[cut - 2:cut] != "**"))):
            yield cut
            count += 1
            if count == MAX_CUTS:
                return


_UNIT_START = re.compile(r"[A-Za-z_\[°µΩ]")


# ---------------------------------------------------------------------------- vectors

_OPEN = {"(": ")", "<": ">", "[": "]"}


def _looks_bracketed(text: str) -> bool:
    return text[:1] in _OPEN and "," in text


def _split_components(text: str) -> tuple[list[str], str]:
    """The comma-separated parts inside the opening bracket (commas inside calls such as
    ``atan2(1, 2)`` belong to the call) and the text after the closing bracket."""
    close, parts, depth, start = _OPEN[text[0]], [], 0, 1
    for pos in range(1, len(text)):
        ch = text[pos]
        if depth == 0 and ch == close:
            parts.append(text[start:pos].strip())
            return parts, text[pos + 1:]
        if ch in "([":
            depth += 1
        elif ch in ")]" and depth:
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(text[start:pos].strip())
            start = pos + 1
    raise AnswerError(f"expected a closing {close!r} after the components, found "
                      f"{excerpt(text)}")


def _bracketed_vector(text: str) -> VectorAnswer:
    parts, rest = _split_components(text)
    if not 2 <= len(parts) <= MAX_COMPONENTS or not all(parts):
        raise AnswerError(f"expected 2 or 3 {_VECTOR_EXAMPLE}, found {len(parts)} in "
                          f"{excerpt(text)}")
    values, texts, figures, degrees = [], [], [], []
    for part in parts:
        number = _component(part)
        values.append(number.value)
        texts.append(number.text)
        figures.append((number.sig_figs, number.sig_figs_max))
        degrees.append(number.value if number.degrees is None else number.degrees)
    while len(values) < 3:
        values.append(0.0)
        texts.append("0")
        figures.append((None, None))
        degrees.append(0.0)
    return VectorAnswer(tuple(values), _unit(rest), None, tuple(figures), tuple(texts),
                        tuple(degrees) if degrees != values else None)


_POLAR = re.compile(r"\s+at\s+|\s*[@∠]\s*")


def _polar_vector(text: str) -> VectorAnswer | None:
    """``5 m/s at 126.87°`` (also ``@``, ``∠``): a planar vector by its magnitude and its
    angle counter-clockwise from the x axis of the objective's frame; the angle's unit is
    required (degrees or radians?). ``None`` when the text has no magnitude before ``at``."""
    at = _POLAR.search(text)
    if at is None:
        return None
    magnitude, angle_text = text[:at.start()].strip(), text[at.end():].strip()
    try:
        size = _scalar(magnitude)
    except AnswerError:
        return None  # not this form: the text is read (and refused) as any other
    try:
        angle = _scalar(angle_text) if angle_text else None
    except AnswerError:
        angle = None
    if angle is None or angle.unit is None or not is_angle_unit(angle.unit):
        raise AnswerError(f"expected an angle with its unit after {at.group(0).strip()!r}, "
                          f"such as '126.87°' or '2.214 rad', found {excerpt(angle_text)} "
                          f"(the magnitude's unit goes before it)")
    theta = to_si(angle.value, angle.unit)
    x, y = size.value * math.cos(theta), size.value * math.sin(theta)
    figures = (size.sig_figs, size.sig_figs_max)
    shown = " at ".join((_with_unit(size.text, size.unit), _with_unit(angle.text, angle.unit)))
    return VectorAnswer((x, y, 0.0), size.unit, None, (figures, figures, (None, None)),
                        (_number_text(x), _number_text(y), "0"), written=shown)


def _number_text(value: float) -> str:
    return f"{value:.6g}"


def _component(text: str) -> NumberAnswer:
    number = _scalar(text)
    if number.unit is not None:
        raise AnswerError(f"expected plain numbers as components with one unit after the "
                          f"brackets, found {excerpt(text)}")
    return number


_BASIS = (r"(?P<basis>[ijk]|(?P<frame>[A-Za-z]\w*)\.(?P<axis>[xyzijk])"
          r"|(?P<axis2>[XYZxyz])_(?P<frame2>[A-Za-z]\w*)|(?P<axis3>[ijk])_(?P<frame3>[A-Za-z]\w*))")
_TERM = re.compile(r"\s*(?P<sign>[+-])?\s*(?P<coef>(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)?"
                   r"\s*\*?\s*" + _BASIS + r"(?![\w.])")
_AXIS = {"x": 0, "y": 1, "z": 2, "i": 0, "j": 1, "k": 2}


def _unit_vector_sum(text: str) -> VectorAnswer | None:
    """``-66 i - 40 j ft/s^2``, ``(3 A.x + 2 A.y) m/s``, ``-7.67 Y_A``; ``None`` if not one."""
    body, rest = text, ""
    if text.startswith("("):
        depth = 0
        for pos, ch in enumerate(text):
            depth += (ch == "(") - (ch == ")")
            if depth == 0:
                body, rest = text[1:pos], text[pos + 1:]
                break
    pos, count = 0, 0
    values = [0.0, 0.0, 0.0]
    texts: list[list[str]] = [[], [], []]
    figures: list[tuple[int | None, int | None]] = [(None, None)] * 3
    frames: set[str | None] = set()
    while True:
        m = _TERM.match(body, pos)
        if not m or (count and not m.group("sign")):
            break
        sign = -1.0 if m.group("sign") == "-" else 1.0
        coef = m.group("coef") or "1"
        axis_name = m.group("axis") or m.group("axis2") or m.group("axis3") or m.group("basis")
        frame = m.group("frame") or m.group("frame2") or m.group("frame3")
        axis = _AXIS[axis_name.lower()]
        frames.add(frame)
        values[axis] += sign * number_value(coef)
        texts[axis].append(("-" if sign < 0 else "") + coef)
        lo, hi = significant_figures(coef) if m.group("coef") else (None, None)
        figures[axis] = (lo, hi)
        count += 1
        pos = m.end()
    if count == 0:
        return None
    tail = body[pos:].strip()
    if rest.strip():
        if tail:
            raise AnswerError(f"expected components such as '-66 i - 40 j' inside the "
                              f"parentheses, found {excerpt(tail)}")
        tail = rest.strip()
    if len(frames) > 1:
        shown = ", ".join(sorted(f or "i/j/k" for f in frames))
        raise AnswerError(f"expected components along one frame's unit vectors, found several "
                          f"({shown})")
    try:
        unit = _unit(tail)
    except AnswerError:
        if count == 1 and not any(c.isdigit() for c in body[:pos]):
            return None  # a lone letter such as "k" followed by something else: not a vector
        raise
    return VectorAnswer(tuple(values), unit, frames.pop(), tuple(figures),
                        tuple(_join(t) for t in texts))


def _join(parts: list[str]) -> str:
    if not parts:
        return "0"
    if len(parts) == 1:
        return parts[0]
    return "+".join(parts).replace("+-", "-")


# ---------------------------------------------------------------------------- expressions

_DERIVATIVE_SUFFIXES = ((2, ("ddot", "_ddot", "dd", "_dd")), (1, ("dot", "_dot", "d", "_d")))


@lru_cache(maxsize=256)
def symbol_aliases(symbols: tuple[str, ...]) -> Mapping[object, str]:
    """Other spellings of the declared symbols, keyed by name or by ``(base, order)``.

    A symbol ``thetad`` is the first derivative of ``theta``: students may write ``θ̇``,
    ``theta'``, ``thetadot`` or ``theta_dot``; ``thetadd`` likewise with two dots or primes.

    >>> sorted(k for k in symbol_aliases(("thetad",)) if isinstance(k, str))
    ['theta_d', 'theta_dot', 'thetad', 'thetadot']
    """
    aliases: dict[object, str] = {}
    for symbol in symbols:
        for order, suffixes in _DERIVATIVE_SUFFIXES:
            suffix = next((s for s in suffixes if symbol.endswith(s) and len(symbol) > len(s)), None)
            if suffix is None:
                continue
            base = symbol[: -len(suffix)]
            aliases.setdefault((base, order), symbol)
            for spelled in suffixes:
                aliases.setdefault(base + spelled, symbol)
            break
    for symbol in symbols:
        aliases[symbol] = symbol
    return MappingProxyType(aliases)  # one per objective, shared: read-only


def read_expression(text: str, symbols: tuple[str, ...]) -> ExpressionAnswer:
    """Read an expression and rename its names to the declared ``symbols``.

    An undeclared ``e`` (or ``E``) is Euler's number, as in PrairieLearn (``e^x`` is read
    back as ``exp(x)``); a name that is not declared but is declared names written together
    is their product (``gh`` for ``g h``, as WeBWorK reads it), refused when it splits more
    than one way.

    >>> read_expression("2L omega^2", ("L", "omega")).text
    '2*L*omega**2'
    >>> read_expression("e^(-t/tau) sqrt(2gh)", ("t", "tau", "g", "h")).text
    'exp(-t/tau)*sqrt(2*g*h)'
    """
    exponent = _E_NOTATION.search(text)
    if exponent and exponent.group("e") in symbols:
        letter = exponent.group("e")
        raise AnswerError(f"expected 2*{letter} or 2*10^3, found "
                          f"{excerpt(text, exponent.start(), exponent.end())} ({letter} is a "
                          f"declared symbol: a power of ten or a product?)")
    try:
        node = syntax.parse(text, attributes=False)
    except ExpressionError as exc:
        raise AnswerError(exc.message) from None
    aliases = symbol_aliases(tuple(symbols))
    unknown: list[str] = []
    mapped = _rename(node, aliases, unknown)
    if unknown:
        raise AnswerError(f"expected an expression in {_names(symbols) or 'numbers only'}, "
                          f"found the unknown name {excerpt(unknown[0])}"
                          f"{_glued_function(unknown[0], aliases)}")
    return ExpressionAnswer(mapped, syntax.to_text(mapped, spaced=True))


def rename_to_symbols(node: Node, symbols: tuple[str, ...]) -> tuple[Node, tuple[str, ...]]:
    """``node`` in the declared ``symbols`` as :func:`read_expression` reads it (aliases,
    names written together, Euler's ``e``) and the names it left undeclared, in order.

    >>> from mechgrade.expressions import syntax
    >>> node, unknown = rename_to_symbols(syntax.parse("mg + Ox"), ("m", "g"))
    >>> syntax.to_text(node), unknown
    ('m*g+Ox', ('Ox',))
    """
    unknown: list[str] = []
    mapped = _rename(node, symbol_aliases(tuple(symbols)), unknown)
    return mapped, tuple(dict.fromkeys(unknown))


def _glued_function(name: str, aliases: Mapping[object, str]) -> str:
    """A hint for a name that is a function's glued to a number or declared names
    (``sqrt2gh``, ``sinx``): its argument goes in brackets."""
    function = max((f for f in syntax.MATH_FUNCTIONS if name.startswith(f) and f != name),
                   key=len, default=None)
    rest = name[len(function):] if function else ""
    if not rest or len(name) > SHORT or not (rest[0].isdigit() or rest in aliases
                                             or _split(rest, aliases)):
        return ""
    return f" (a function's argument goes in brackets: {function}({rest}))"


def _names(symbols: tuple[str, ...], most: int = 60) -> str:
    """The declared symbols for a message, cut after about ``most`` characters."""
    shown = ", ".join(symbols)
    return shown if len(shown) <= most else shown[:most] + "…"


_E_NOTATION = re.compile(r"(?<![\w.])\d+(?:\.\d*)?(?P<e>[eE])[+-]?\d")


MAX_SPLIT = 24
"""Longest undeclared name tried as declared names written together."""


def _split(name: str, aliases: Mapping[object, str]) -> list[Name] | None:
    """``gh`` as ``g``, ``h`` when ``g`` and ``h`` are declared (or ``pi``): the only way to
    write ``name`` with declared names; ``None`` when there is none. Greek letters' names
    are never split (``mu`` is not ``m*u``)."""
    if len(name) > MAX_SPLIT or name in syntax.GREEK.values():
        return None
    pieces = [k for k in aliases if isinstance(k, str)] + ["pi"]
    # ways[i]: up to two ways to write name[i:] with declared names
    ways: list[list[list[str]]] = [[] for _ in name] + [[[]]]
    for i in range(len(name) - 1, -1, -1):
        for piece in pieces:
            if name.startswith(piece, i):
                ways[i] += [[piece] + rest for rest in ways[i + len(piece)]][:2 - len(ways[i])]
    if not ways[0]:
        return None
    if len(ways[0]) > 1:
        readings = [" ".join(way) for way in ways[0]]
        said = (f": {readings[0]} or {readings[1]}?" if len(name) <= SHORT
                else " in more than one way")
        raise AnswerError(f"expected declared names, found {excerpt(name)}{said} (write "
                          f"spaces or * between them)")
    return [Name(aliases.get(piece, piece)) for piece in ways[0][0]]


def _product(factors: list[Node], first: Node | None = None) -> Node:
    """``first * factors[0] * factors[1] ...``, nested to the left as the reader nests it."""
    out = first
    for factor in factors:
        out = factor if out is None else Bin("*", out, factor)
    assert out is not None  # factors is never empty
    return out


def _rename(node: Node, aliases: Mapping[object, str], unknown: list[str]) -> Node:
    """``node`` in the declared names (a part unchanged is kept as it is); an undeclared
    ``e`` is Euler's number (``e^x`` as ``exp(x)``, a lone ``e`` as ``exp(1)``)."""
    # the commonest kinds first, told by their exact type (every answer read is renamed)
    if type(node) is Name:
        if node.id == "pi":
            return node
        target = aliases.get(node.id)
        if target is not None:
            return node if target == node.id else Name(target)
        if node.id in _EULER:
            return _EXP_1
        split = _split(node.id, aliases)
        if split is not None:
            return _product(list(split))
        unknown.append(node.id)
        return node
    if type(node) is Bin:
        if node.op == "**" and _euler(node.left, aliases):
            return Call("exp", (_rename(node.right, aliases, unknown),))
        if node.op == "**" and _splits(node.left, aliases):
            # pir^2 is pi*r^2: the power takes the last name, as written
            split = _split(node.left.id, aliases) or []
            factors: list[Node] = [*split[:-1], Bin("**", split[-1],
                                                    _rename(node.right, aliases, unknown))]
            return _product(factors)
        left = _rename(node.left, aliases, unknown)
        if node.op == "*" and _splits(node.right, aliases):
            split = _split(node.right.id, aliases)  # 2gh: 2*g*h, as if spaced
            if split is not None:
                return _product(list(split), left)
        right = _rename(node.right, aliases, unknown)
        return node if left is node.left and right is node.right else Bin(node.op, left, right)
    if type(node) is Num:
        return node
    if isinstance(node, Prime):
        target = aliases.get((node.id, node.order))
        if target is None:
            unknown.append(node.id + "'" * node.order)
            return node
        return Name(target)
    if isinstance(node, Unary):
        operand = _rename(node.operand, aliases, unknown)
        return node if operand is node.operand else Unary(node.op, operand)
    if isinstance(node, Call):
        args = tuple(_rename(a, aliases, unknown) for a in node.args)
        return node if all(a is b for a, b in zip(args, node.args)) else Call(node.func, args)
    unknown.append(syntax.to_text(node))  # pragma: no cover - attributes are refused above
    return node


_EULER = ("e", "E")
_EXP_1 = Call("exp", (Num("1"),))


def _splits(node: Node, aliases: Mapping[object, str]) -> TypeGuard[Name]:
    """Whether ``node`` is a name that is not declared (nor ``pi``, nor Euler's ``e``) but
    may be declared names written together."""
    return isinstance(node, Name) and node.id not in aliases and node.id != "pi" \
        and not _euler(node, aliases) and _split(node.id, aliases) is not None


def _euler(node: Node, aliases: Mapping[object, str]) -> bool:
    """Whether ``node`` is Euler's number: an ``e`` (or ``E``) not declared."""
    return isinstance(node, Name) and node.id in _EULER and node.id not in aliases
