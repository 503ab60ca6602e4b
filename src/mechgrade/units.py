"""Units: one cached pint registry, safe unit-text reading, SI conversion and dimensions.

Unit text is tokenised and checked against an allow-list before pint sees it (pint itself has
no ``eval`` but hangs on ``m/s**9**9**9``), then normalised to pint's syntax. Every conversion
factor is cached per unit string. Inside mechgrade all numbers are SI (radians for angles).

>>> to_si(30, "deg")
0.5235987755982988
>>> round(from_si(9.80665, "ft/s^2"), 6)
32.174049
>>> normalize_unit("ft/s2")
'ft / s ** 2'
>>> parse_quantity("98.5 ft/s²")
Quantity(value=98.5, unit='ft / s ** 2')
"""

from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass
from functools import lru_cache

from .errors import UnitError
from .expressions.excerpt import excerpt

MAX_UNIT_LENGTH = 64
MAX_EXPONENT = 12

_SUPERSCRIPTS = str.maketrans({"⁰": "0", "¹": "1", "²": "2", "³": "3", "⁴": "4", "⁵": "5",
                               "⁶": "6", "⁷": "7", "⁸": "8", "⁹": "9", "⁻": "-"})
_NUMBER = re.compile(r"\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)")
_TOKEN = re.compile(r"\s*(?:(?P<name>g_?0(?![\w])|[A-Za-z_µΩ°]+)(?P<power>-?\d+)?"
                    r"|(?P<num>\d+(?:\.\d+)?)"
                    r"|(?P<op>\*\*|[*/^()·⋅.\-]))")
_DIMENSIONLESS_WORDS = {"", "1", "dimensionless", "-", "none", "unitless"}
# pint names that are constants or misreadings, not units a student means.
_NOT_UNITS = {
    "e": "the elementary charge; for a power of ten write 9.85e1",
    "E": "for a power of ten write 9.85e1",
    "k": "Boltzmann's constant; write kg, km or kN",
    "c": "the speed of light",
    "R": "the gas constant",
    "pi": "a number; write it before the unit, as in 2*pi rad",
    "Nm": "write N*m for newton metres",
}
_DEGREE_SIGNS = (("°C", " degC "), ("°F", " degF "), ("°K", " K "), ("°R", " degR "))


@lru_cache(maxsize=1)
def registry():
    """The process-wide pint ``UnitRegistry`` (created once; pint is slow to load).

    Parsing pint's definition file takes most of the registry's start-up, so pint caches the
    parsed definitions in the user's cache folder (pint's own cache), one folder per pint
    installation: in the folder all installations share (``cache_folder=":auto:"``), an entry
    written by another virtual environment makes every read fail. When the folder cannot be
    created, written or read, the registry is built without the cache.
    """
    import zlib

    import pint
    import platformdirs

    folder = platformdirs.user_cache_path("pint", appauthor=False) / \
        f"mechgrade-{zlib.crc32(pint.__file__.encode()):08x}"
    ureg: pint.UnitRegistry
    try:
        ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True, cache_folder=folder)
    except Exception:  # noqa: BLE001 - no usable cache folder (read-only, broken, racing)
        ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.formatter.default_format = "~"
    for definition in _ENGINEERING_UNITS:
        ureg.define(definition)
    return ureg


_ENGINEERING_UNITS = (
    "dioptre = 1 / meter = dpt = diopter",
    "engineering_gauss = 1e-4 * tesla",
    "engineering_maxwell = 1e-8 * weber",
)
"""Units as engineers mean them where pint reads otherwise: ``dpt`` is the dioptre (pint:
a deci-pint), as in STACK's units; the gauss (``G``) is 1e-4 T and the maxwell (``Mx``)
1e-8 Wb, as in WeBWorK's ``lib/Units.pm``, not pint's CGS-Gaussian units, which no SI unit
converts to. A written ``G`` stays ``G``; pint reads it as :data:`_ENGINEERING_NAMES` says."""

_ENGINEERING_NAMES = {"gauss": "engineering_gauss", "maxwell": "engineering_maxwell"}


def _engineering(canonical: str) -> str:
    """Canonical unit text with each (prefixed) gauss or maxwell as the engineering unit.

    >>> _engineering("kG * m")
    'kiloengineering_gauss * m'
    """
    def name(m: re.Match) -> str:
        word = m.group(0)
        for prefix, base, suffix in registry().parse_unit_name(word):
            if base in _ENGINEERING_NAMES:
                return prefix + _ENGINEERING_NAMES[base] + suffix
        return word
    return _WORD.sub(name, canonical) if _GAUSSIAN.search(canonical) else canonical


_WORD = re.compile(r"[A-Za-z_]\w*")
_GAUSSIAN = re.compile(r"G|gauss|Mx|maxwell")


@dataclass(frozen=True)
class Quantity:
    """A number with the unit it was written in (unit text already normalised)."""

    value: float
    unit: str

    def to_si(self) -> float:
        return to_si(self.value, self.unit)


@lru_cache(maxsize=4096)
def normalize_unit(text: str) -> str:
    """Check unit text against the allow-list and return it in pint's syntax.

    Accepts ``^`` or ``**`` powers, superscripts (``s²``), a power glued to a name (``s2``),
    ``·`` or spaces for products, ``°`` for degrees. Raises :class:`UnitError` otherwise.

    >>> normalize_unit("m*s^-2")
    'm * s ** -2'
    >>> normalize_unit("kg m²/s²")
    'kg * m ** 2 / s ** 2'

    Standard gravity is ``g0`` (``g_0``); names pint reads but a student does not mean are
    refused: constants (``e``, ``k``, ``c``, ``R``, ``pi``), plurals of abbreviations (``fts``),
    offset temperature scales (``degC``, ``°C``), and ambiguous or broken operators.

    >>> normalize_unit("g0")
    'g_0'
    >>> normalize_unit("°C")
    Traceback (most recent call last):
    ...
    mechgrade.errors.UnitError: expected an absolute temperature (K or degR), found 'degC' (an offset scale: convert to K first)
    """
    prepared = _prepared(str(text))
    if prepared is None:
        return ""
    canonical = _UnitReader(prepared, text).read()
    _pint_unit(canonical, text)  # proves pint reads it
    return canonical


def _prepared(text: str) -> str | None:
    """The text with superscripts and degree signs spelled out; None for a pure number's
    words (``1``, ``dimensionless``...). Refuses text longer than ``MAX_UNIT_LENGTH``."""
    text = unicodedata.normalize("NFC", text).strip()
    if len(text) > MAX_UNIT_LENGTH:
        raise UnitError(f"expected a unit of at most {MAX_UNIT_LENGTH} characters, "
                        f"found {len(text)} characters: {excerpt(text)}")
    if text.lower() in _DIMENSIONLESS_WORDS:
        return None
    text = text.translate(_SUPERSCRIPTS)
    for sign, name in _DEGREE_SIGNS:
        text = text.replace(sign, name)
    return text.replace("°", " deg ")


class _UnitReader:
    """Reads unit text token by token (names, numbers, operators) into pint's syntax, keeping
    whether an operand (a name, a number or ``(``) is due next; ``raw`` is the text as written,
    for messages."""

    def __init__(self, text: str, raw: str) -> None:
        self.text, self.raw = text, raw
        self.out: list[str] = []
        self.expect_operand = True

    def read(self) -> str:
        """The whole text in pint's syntax (``m * s ** -2``)."""
        pos = 0
        while self.text[pos:].strip():
            m = _TOKEN.match(self.text, pos)
            if not m:
                start = len(self.text) - len(self.text[pos:].lstrip())
                raise UnitError(f"expected a unit such as 'm/s^2', found "
                                f"{excerpt(self.text, start)} (cannot read it)")
            pos = m.end()
            if m.group("name"):
                self.name(m)
            elif m.group("num"):
                self.number(m)
            elif m.group("op") in ("^", "**"):
                pos = self.power(m)
            else:
                self.operator(m)
        if self.expect_operand or self.out.count("(") != self.out.count(")"):
            raise UnitError(f"expected a complete unit such as 'm/s^2', found "
                            f"{excerpt(self.raw)}")
        return " ".join(self.out).replace("( ", "(").replace(" )", ")")

    def refuse(self, m: re.Match, group: str, why: str) -> UnitError:
        return UnitError(f"expected a unit such as 'm/s^2', found "
                         f"{excerpt(self.text, m.start(group), m.end())} ({why})")

    def name(self, m: re.Match) -> None:
        """A unit name, with a power glued to it (``s2``, ``s-2``)."""
        name = m.group("name").replace("µ", "u").replace("g0", "g_0")
        name = _STUDENT_NAMES.get(name, name)
        if not self.expect_operand:
            self.out.append("*")
        _check_unit_name(name, self.raw)
        self.out.append(name)
        if m.group("power"):
            if m.group("power").startswith("-") and self.out[-2:-1] == ["/"]:
                raise self.refuse(m, "name", "a negative power after '/' is ambiguous: write "
                                             "s^2 or *s^-2")
            self.out += ["**", _exponent(m.group("power"), self.raw)]
        self.expect_operand = False

    def number(self, m: re.Match) -> None:
        """A power after ``**``, or a lone 1 (``1/s``); any other number is refused."""
        if self.out and self.out[-1] == "**":
            self.out.append(_exponent(m.group("num"), self.raw))
        elif m.group("num") == "1" and self.expect_operand:
            self.out.append("1")
        else:
            raise self.refuse(m, "num", "a number inside a unit")
        self.expect_operand = False

    def power(self, m: re.Match) -> int:
        """``^`` or ``**`` and the whole number after it; returns where reading goes on."""
        if self.expect_operand or self.out[-2:-1] == ["**"]:
            raise self.refuse(m, "op", "misplaced power")
        exp = _NUMBER.match(self.text, m.end())
        if not exp:
            raise UnitError(f"expected a whole-number power after '^', found "
                            f"{excerpt(self.text, m.start('op'), m.end())}")
        self.out += ["**", _exponent(exp.group(1), self.raw)]
        return exp.end()

    def operator(self, m: re.Match) -> None:
        """A product (``*``, ``·``, ``.``), ``/``, a bracket or a stray minus sign."""
        op = m.group("op")
        if op in ("*", "·", "⋅", ".", "/") and self.expect_operand and (self.out or op != "/"):
            raise self.refuse(m, "op", "an operator with nothing before it")
        if op in ("*", "·", "⋅", "."):
            self.out.append("*")
            self.expect_operand = True
        elif op == "/":
            if self.expect_operand:
                self.out.append("1")
            self.out.append("/")
            self.expect_operand = True
        elif op == "(":
            if not self.expect_operand:
                self.out.append("*")
            self.out.append("(")
            self.expect_operand = True
        elif op == ")":
            self.out.append(")")
            self.expect_operand = False
        else:  # "-": units are not subtracted
            raise self.refuse(m, "op", "a minus sign between units")


def _exponent(text: str, raw: str) -> str:
    try:
        value = int(text)
    except ValueError:
        raise UnitError(f"expected a whole-number power in {excerpt(raw)}, "
                        f"found {excerpt(text)}") from None
    if abs(value) > MAX_EXPONENT:
        raise UnitError(f"expected a power of at most {MAX_EXPONENT} in {excerpt(raw)}, "
                        f"found {excerpt(text)}")
    return str(value)


_STUDENT_NAMES = {"rev": "revolution", "lbm": "pound"}
"""Unit names students write that pint spells otherwise (``rev/s``, ``rev/min``, ``lbm``)."""


@lru_cache(maxsize=1024)
def _check_unit_name(name: str, raw: str) -> None:
    """Refuse names pint reads but a student does not mean: constants (``e``), plurals of
    abbreviations (``fts``: ft or ft*s?) and offset temperature scales (``degC``)."""
    if name in _NOT_UNITS:
        raise UnitError(f"expected a unit such as 'm/s^2', found {excerpt(name)} in "
                        f"{excerpt(raw)} (not a unit here: {_NOT_UNITS[name]})")
    ureg = registry()
    try:
        unit = ureg.parse_units(name)
        stem = ureg.parse_units(name[:-1]) if name.endswith("s") and len(name) <= 4 else None
    except Exception:
        stem = None
        if not name.endswith("s") or len(name) > 4:
            raise UnitError(f"expected a unit such as 'm/s^2', found {excerpt(raw)} "
                            f"({excerpt(name)} is not a unit)") from None
        unit = None
    if unit is None or (stem is not None and stem == unit):
        raise UnitError(f"expected a unit such as 'm/s^2', found {excerpt(name)} in "
                        f"{excerpt(raw)} (ambiguous: write {name[:-1]} or {name[:-1]}*s)")
    if not ureg.Quantity(1.0, unit)._is_multiplicative:
        raise UnitError(f"expected an absolute temperature (K or degR), found {excerpt(name)} "
                        f"(an offset scale: convert to K first)")


@lru_cache(maxsize=4096)
def _pint_unit(canonical: str, raw: str | None = None):
    ureg = registry()
    if canonical == "":
        return ureg.dimensionless
    try:
        return ureg.parse_units(_engineering(canonical))
    except Exception:
        raise UnitError(f"expected a unit such as 'm/s^2', found "
                        f"{excerpt(raw or canonical)}") from None


@lru_cache(maxsize=4096)
def si_factor(unit: str) -> float:
    """Factor that turns a value in ``unit`` into SI base units (radians for angles).

    >>> round(si_factor("cm/s"), 12)
    0.01
    """
    canonical = normalize_unit(unit)
    ureg = registry()
    return float(ureg.Quantity(1.0, _pint_unit(canonical)).to_base_units().magnitude)


def to_si(value: float, unit: str) -> float:
    """``value`` given in ``unit``, in SI base units."""
    return float(value) * si_factor(unit)


def from_si(value: float, unit: str) -> float:
    """An SI value expressed in ``unit``."""
    return float(value) / si_factor(unit)


@lru_cache(maxsize=4096)
def dimension(unit: str):
    """The dimensionality of ``unit`` as a pint ``UnitsContainer`` (hashable, supports * / **).

    >>> str(dimension("ft/s^2"))
    '[length] / [time] ** 2'
    >>> dimension("deg") == dimension("1")
    True
    """
    return _pint_unit(normalize_unit(unit)).dimensionality


def dimensionless():
    """The dimensionality of a pure number."""
    return dimension("")


def time_dimension():
    return dimension("s")


def describe_dimension(dim) -> str:
    """Words for a dimensionality, for messages ("a velocity [length]/[time]"), its powers
    written as a student reads them (pint's pretty form: ``[time]²``, not ``[time] ** 2``).

    >>> describe_dimension(dimension("m/s"))
    'a velocity ([length]/[time])'
    >>> describe_dimension(dimension("N")), describe_dimension(dimension("W"))
    ('a force ([mass]·[length]/[time]²)', 'a power ([mass]·[length]²/[time]³)')
    """
    text = f"{dim:P}" if str(dim) else "dimensionless"
    if text == "dimensionless":
        return "a pure number (or an angle)"
    name = _dimension_names().get(frozenset(dict(dim).items()))
    return f"{name} ({text})" if name else text


_NAMED_DIMENSIONS = (
    ("m", "a length"), ("s", "a time"), ("kg", "a mass"), ("m/s", "a velocity"),
    ("m/s^2", "an acceleration"), ("1/s", "an angular velocity or rate"),
    ("1/s^2", "an angular acceleration"), ("N", "a force"), ("J", "an energy or moment"),
    ("W", "a power"), ("N*s", "a momentum or impulse"), ("kg*m^2/s", "an angular momentum"),
    ("kg*m^2", "a moment of inertia"), ("N/m", "a stiffness"),
    ("N*s/m", "a damping coefficient"))


@lru_cache(maxsize=1)
def _dimension_names() -> dict:
    """Names by dimensionality, keyed by its (base, power) pairs: pint writes the bases in the
    order it met them ('[mass] * [length]' for N, '[length] * [mass]' for lbf), so the text
    cannot be the key."""
    return {frozenset(dict(dimension(unit)).items()): name for unit, name in _NAMED_DIMENSIONS}


@lru_cache(maxsize=1024)
def si_unit(unit: str) -> str:
    """The SI unit (radians for angles) of values mechgrade keeps for ``unit``.

    >>> si_unit("ft/s^2"), si_unit("deg"), si_unit("rpm")
    ('m / s ** 2', 'rad', 'rad / s')
    """
    ureg = registry()
    units = ureg.Quantity(1.0, _pint_unit(normalize_unit(unit))).to_base_units().units
    text = format(units, "~")
    return normalize_unit(text) if text else ""


@lru_cache(maxsize=1024)
def judged_in(answer_unit: str | None, objective_unit: str) -> str:
    """``answer_unit`` as it is read for an objective in ``objective_unit`` (no unit written:
    the objective's). pint's hertz is
    1/s, so 2 Hz would read as 2 rad/s; beside an angular rate (rad/s, deg/s, rpm) a hertz
    is read as a cycle per second, as an rpm is a revolution per minute, and an angular
    rate written for a frequency in hertz is read in cycles likewise. Any other unit, and a
    hertz beside a unit that names no angle (1/s), reads as pint reads it.

    >>> round(to_si(2, judged_in("Hz", "rad/s")), 4)  # 2 cycles per second
    12.5664
    >>> round(from_si(to_si(12.566, judged_in("rad/s", "Hz")), "Hz"), 3)
    2.0
    >>> judged_in("Hz", "1/s"), judged_in("rad/s", "rpm"), judged_in("Hz", "kHz")
    ('Hz', 'rad/s', 'Hz')
    """
    if answer_unit is None:
        return objective_unit
    answer, objective = _angle_or_hertz(answer_unit), _angle_or_hertz(objective_unit)
    if answer == "hertz" and objective == "angle":
        return f"({answer_unit}) * rev"
    if answer == "angle" and objective == "hertz":
        return f"({answer_unit}) / rev"
    return answer_unit


def _angle_or_hertz(unit: str) -> str | None:
    """``"angle"`` for a unit that names an angle (rad/s, rpm), ``"hertz"`` for one in hertz
    that names none, else ``None``."""
    ureg = registry()
    parsed = _pint_unit(normalize_unit(unit))
    if "radian" in ureg.Quantity(1.0, parsed).to_root_units().units._units:
        return "angle"
    return "hertz" if any(name.endswith("hertz") for name in parsed._units) else None


def same_dimension(unit_a: str, unit_b: str) -> bool:
    return dimension(unit_a) == dimension(unit_b)


def parse_quantity(text: str) -> Quantity:
    """Read ``"<number> <unit>"`` (unit optional) into a :class:`Quantity`.

    >>> parse_quantity("-1.4 rad/s")
    Quantity(value=-1.4, unit='rad / s')
    >>> parse_quantity("7")
    Quantity(value=7.0, unit='')
    """
    text = unicodedata.normalize("NFC", str(text)).strip()
    m = _NUMBER.match(text)
    if not m:
        raise UnitError(f"expected a number followed by a unit such as '9.81 m/s^2', "
                        f"found {excerpt(text)}")
    value = float(m.group(1))
    if value != value or value in (float("inf"), float("-inf")):
        raise UnitError(f"expected a finite number, found {excerpt(text)}")
    return Quantity(value, normalize_unit(text[m.end():]))
