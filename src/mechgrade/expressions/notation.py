"""A model's names and expressions as a textbook writes them, for anything a student reads:
θ̇ for ``thetad``, μ with the subscript k for ``mu_k``, F with the subscript P for ``F_P``,
``kg·m²`` for ``kg*m^2``, ``|ẋ|`` for ``Abs(xd)``. Plain text (a spoken label, an
``aria-label``) sets a subscript in Unicode's subscript characters where it has them and a
frame's unit vector ``N.y`` in words, "n-hat y"; HTML sets a subscript with ``<sub>`` and
the unit vector as 𝐧̂ with the subscript y. Pure text: no sympy, so every layer may use it."""

from __future__ import annotations

import re
import unicodedata
from functools import lru_cache
from html import escape

GREEK = {name: chr(code) for name, code in (
    ("alpha", 0x3B1), ("beta", 0x3B2), ("gamma", 0x3B3), ("delta", 0x3B4),
    ("epsilon", 0x3B5), ("zeta", 0x3B6), ("eta", 0x3B7), ("theta", 0x3B8), ("iota", 0x3B9),
    ("kappa", 0x3BA), ("lambda", 0x3BB), ("mu", 0x3BC), ("nu", 0x3BD), ("xi", 0x3BE),
    ("rho", 0x3C1), ("sigma", 0x3C3), ("tau", 0x3C4), ("phi", 0x3C6), ("chi", 0x3C7),
    ("psi", 0x3C8), ("omega", 0x3C9), ("pi", 0x3C0), ("Gamma", 0x393), ("Delta", 0x394), ("Theta", 0x398),
    ("Lambda", 0x39B), ("Sigma", 0x3A3), ("Phi", 0x3A6), ("Psi", 0x3A8), ("Omega", 0x3A9))}
"""A Greek letter's name as the answer syntax spells it, and the letter."""

_RATE_MARKS = {"d": "\u0307", "dd": "\u0308"}  # combining dot above, diaeresis
_SUBSCRIPTS = dict(zip("0123456789aehijklmnoprstuvx+-=()",
                       "₀₁₂₃₄₅₆₇₈₉ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ₊₋₌₍₎"))
_SUPERSCRIPTS = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
_POWER = re.compile(r"(?:\*\*|\^)\s*(?:\((-?\d+)\)|(-?\d+))")
# a name (not a frame's unit vector after its dot, not a number's exponent)
_NAME = re.compile(r"(?<![\w.])([A-Za-z][A-Za-z0-9_]*(?:,[xyz]\b)?)")
# a point's velocity or acceleration, a body's angular ones, in a frame: ``N_v_P``
_KINEMATIC = re.compile(r"([A-Z]),(v|a|omega|alpha),([A-Za-z0-9]+)")
_OPERATOR = re.compile(r"[*·/=+^]")
# a number and a space just before a name: the name is its unit
_NUMBER_BEFORE = re.compile(r"(?<![\w^*.])\d+(?:\.\d*)?(?:[eE][-+]?\d+)?\s$")
# one letter or a Greek letter's name, a number, a rate's d or dd: the answer syntax's names
_SYMBOL = re.compile(r"(?P<letter>" + "|".join(sorted(GREEK, key=len, reverse=True))
                     + r"|[A-Za-z])(?P<digits>\d*)(?P<rate>dd?)?")


def _symbol(name: str, rates: bool) -> tuple[str, str] | None:
    """``name`` as its letter (Greek, with its rate's dots) and its subscript, or ``None``
    for a word that is not a symbol's name (``tension``, ``block1``)."""
    head, _, sub = name.partition("_")
    sub = sub.replace("_", ",")
    m = _SYMBOL.fullmatch(head)
    if m is None or (m["rate"] and not rates):
        return None
    letter = GREEK.get(m["letter"], m["letter"]) + _RATE_MARKS.get(m["rate"] or "", "")
    return letter, ",".join(s for s in (m["digits"], sub) if s)


def coordinate_names(coordinates, points=()) -> tuple[tuple[str, str], ...]:
    """How a textbook spells each of a problem's ``coordinates`` that the answer syntax's names
    do not (a letter and a word: ``xj``, ``yA``, ``st``): the letter with the rest as its
    subscript, a point's own name when the rest names one of ``points`` (``xj`` is x_J, the
    joint J's position). Pass the result to :func:`textbook` and :func:`textbook_html`.

    >>> coordinate_names(["x", "theta", "xj", "yA", "st", "x1"], ["O", "J"])
    (('xj', 'x_J'), ('yA', 'y_A'), ('st', 's_t'))
    """
    named = {p.upper(): p for p in points}
    out = []
    for name in coordinates:
        m = _SYMBOL.fullmatch(name)
        if (m is not None and not m["rate"]) or "_" in name:
            continue  # the answer syntax's own spelling says it already
        for letter in sorted(GREEK, key=len, reverse=True) + list(name[:1]):
            rest = name[len(letter):]
            if name.startswith(letter) and rest.isalnum():
                out.append((name, f"{letter}_{named.get(rest.upper(), rest)}"))
                break
    return tuple(out)


def _spelled(name: str, names: tuple[tuple[str, str], ...]) -> str:
    """``name`` (a coordinate or its rate, ``xjd``) in the spelling :func:`coordinate_names`
    gives (``xd_J``), as :func:`_symbol` reads it."""
    for coordinate, spelled in names:
        if name.startswith(coordinate) and name[len(coordinate):] in ("", "d", "dd"):
            letter, _, sub = spelled.partition("_")
            return f"{letter}{name[len(coordinate):]}_{sub}"
    return name


def _plain_sub(letter: str, sub: str) -> str:
    if sub and all(c in _SUBSCRIPTS for c in sub):
        return letter + "".join(_SUBSCRIPTS[c] for c in sub)
    # no subscript character for it (an upper-case letter): a space keeps it a subscript's
    # name, not a product, for a reader
    return f"{letter} {textbook(sub)}" if sub else letter


# a given's rate as the answer syntax writes it (x', theta''): a prime or two after a name,
# not closing a quotation ('x') nor an apostrophe's (block's)
_PRIMES = re.compile(r"'{1,2}(?![\w'])")


def _rewritten(text: str, rates: bool, show, names: tuple[tuple[str, str], ...] = ()) -> str:
    out, last = [], 0
    for m in _NAME.finditer(text):
        if m.start() < last:
            continue  # inside a name's primes already written
        name = _spelled(m.group(1), names)
        primes = _PRIMES.match(text, m.end())
        rate = None if primes is None or text[m.start() - 1:m.start()] == "'" \
            else _symbol(_spelled(m.group(1) + "d" * len(primes.group(0)), names), True)
        if rate is not None and primes is not None:  # x' is ẋ, in prose too
            out += [text[last:m.start()], show(*rate)]
            last = primes.end()
            continue
        after = text[m.end():m.end() + 1]
        # a call's name, or a unit after its number (``0.25 g0``, standard gravity; a Greek
        # letter's name is no unit: ``2 omega x v``)
        unit = _NUMBER_BEFORE.search(text, max(0, m.start() - 40), m.start()) is not None \
            and name.partition("_")[0].rstrip("d0123456789") not in GREEK
        # in prose a rate is one only inside a formula (``m*xdd = ...``, not "add")
        formula = rates or bool(_OPERATOR.search(text[max(0, m.start() - 2):m.start()]
                                                 + text[m.end():m.end() + 2]))
        found = None if after == "(" or unit else _symbol(name, formula)
        out.append(text[last:m.start()])
        out.append(show(*found) if found else show(name, None))
        last = m.end()
    out.append(text[last:])
    return "".join(out)


@lru_cache(maxsize=1 << 14)
def textbook(text: str, rates: bool = True, names: tuple[tuple[str, str], ...] = ()) -> str:
    """``text`` (an expression, a unit, a sentence naming symbols) as a textbook writes it,
    in plain text; ``rates=False`` for prose, where a word ending in d is no rate; ``names``
    the problem's coordinates the answer syntax does not spell (:func:`coordinate_names`).

    >>> textbook("-g*mu_k*xd*cos(beta)/Abs(xd) + g*sin(beta)")
    '-g·μₖ·ẋ·cos(β)/|ẋ| + g·sin(β)'
    >>> textbook("L*sqrt(thetadd**2 + thetad**4) kg*m^2 R_O,x N.y")
    'L·sqrt(θ̈² + θ̇⁴) kg·m² R O,x n-hat y'
    >>> textbook("2.453 m/s^2 (0.2501 g0)")
    '2.453 m/s² (0.2501 g0)'
    >>> textbook("check x' and theta'' (the key 'x', block's)", rates=False)
    "check ẋ and θ̈ (the key 'x', block's)"
    >>> textbook("k1*xjd + xj'' - xj", names=(("xj", "x_J"),))
    'k₁·ẋ J + ẍ J - x J'
    """
    def show(name, sub):
        return name if sub is None else _plain_sub(name, sub)
    # a frame's unit vector in words, as it is read out (a plain text has no hat to set)
    return unicodedata.normalize("NFC", _UNIT_VECTOR.sub(
        lambda m: f"{m[1].lower()}-hat {m[2]}", _operators(_rewritten(text, rates, show, names))))


@lru_cache(maxsize=1 << 14)
def textbook_html(text: str, rates: bool = True, names: tuple[tuple[str, str], ...] = ()) -> str:
    """``text`` as :func:`textbook` writes it, as escaped HTML with subscripts as ``<sub>``.

    >>> textbook_html("the friction F_P (mu N = 8.5 N) <b>", rates=False)
    'the friction F<sub>P</sub> (μ N = 8.5 N) &lt;b&gt;'
    >>> textbook_html("N_v_P1 = yd*N.y")
    '<sup>N</sup>v<sub>P1</sub> = ẏ·𝐧̂<sub>y</sub>'
    >>> textbook_html("xjd", names=(("xj", "x_J"),))
    'ẋ<sub>J</sub>'
    """
    def show(name, sub):
        kinematic = _KINEMATIC.fullmatch(f"{name},{sub}")
        if kinematic:  # a point's velocity in a frame: the frame a left superscript
            frame, quantity, point = kinematic.groups()
            return f"<sup>{frame}</sup>{GREEK.get(quantity, quantity)}<sub>{escape(point)}</sub>"
        return f"{name}<sub>{escape(sub)}</sub>" if sub else name
    marked = _rewritten(_operators(text), rates, lambda n, s: f"\x00{n}\x01{s or ''}\x02"
                        if s is not None else n, names)
    shown = re.sub("\x00(.*?)\x01(.*?)\x02", lambda m: show(m[1], m[2]), escape(marked))
    return unicodedata.normalize("NFC", _UNIT_VECTOR.sub(_unit_vector_html, shown))


# a frame's unit vector (N.y) on a page: as its equations write it (mechanics.derivation's
# hat), the frame's letter bold and lower case with a hat, the axis its subscript
_UNIT_VECTOR = re.compile(r"(?<![\w.])([A-Z])\.([xyz])(?!\w)")


def _unit_vector_html(match: re.Match) -> str:
    return f"{chr(0x1D41A + ord(match[1].lower()) - 97)}\u0302<sub>{match[2]}</sub>"


def _operators(text: str) -> str:
    """Powers raised, products as middle dots, ``Abs(x)`` as ``|x|``."""
    text = _POWER.sub(lambda m: (m.group(1) or m.group(2)).translate(_SUPERSCRIPTS), text)
    return _bars(text).replace("*", "·")


def _bars(text: str) -> str:
    """``Abs(x)`` written ``|x|`` (its parentheses matched; one left open stays as it is)."""
    start = text.find("Abs(")
    while start >= 0:
        depth, end = 0, None
        for i in range(start + 3, len(text)):
            depth += {"(": 1, ")": -1}.get(text[i], 0)
            if depth == 0:
                end = i
                break
        if end is None:
            return text
        text = f"{text[:start]}|{text[start + 4:end]}|{text[end + 1:]}"
        start = text.find("Abs(", start)
    return text
