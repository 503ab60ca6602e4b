"""The kind (scalar, vector, ...) and dimension of an expression: one inference for the spec
checks and for students' answers.

The caller says what names stand for (``leaf``) and, for a spec, how to type calls of the
objective language (``call``); arithmetic and math functions follow the rules here and in the
language's table. An inconsistent expression raises :class:`DimensionError`, worded for the
author and, in ``student``, for feedback ("Your expression ...").

>>> from mechgrade.expressions.syntax import parse
>>> from mechgrade.units import dimension
>>> units = {"L": "m", "thetad": "rad/s"}
>>> leaf = lambda n: Type(Kind.SCALAR, dimension(units[n.id]))
>>> str(infer(parse("L*thetad^2"), leaf).dim)
'[length] / [time] ** 2'
>>> infer(parse("L + thetad"), leaf)
Traceback (most recent call last):
...
mechgrade.expressions.functions.DimensionError: cannot add a length ([length]) and an angular velocity or rate (1/[time]) in 'L+thetad'
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from operator import is_
from typing import Any, Callable

from ..units import describe_dimension, dimension, dimensionless
from .functions import MATH_FUNCTIONS, DimensionError, Kind
from .syntax import Bin, Call, Name, Node, Num, Unary, constant_value, to_text

__all__ = ["DimensionError", "Kind", "Type", "described", "infer", "scalar"]


@dataclass(frozen=True)
class Type:
    """Kind (scalar, vector, point, frame or zero) and dimension of an expression."""

    kind: Kind
    dim: Any = None  # a pint dimensionality (UnitsContainer), None for points and frames


@lru_cache(maxsize=256)
def scalar(unit: str) -> Type:
    """A scalar quantity in ``unit`` (``""``: a pure number), kept per unit: typing an
    expression types each of its names and numbers.

    >>> str(scalar("m/s").dim), scalar("m/s") is scalar("m/s")
    ('[length] / [time]', True)
    """
    return Type(Kind.SCALAR, dimension(unit))


@lru_cache(maxsize=1)
def _zero() -> Type:
    return Type(Kind.ZERO, dimensionless())


def infer(node: Node, leaf: Callable[[Node], Type],
          call: Callable[[Call], Type] | None = None) -> Type:
    """The type of ``node``: ``leaf`` types names (other than ``pi``), primes and unit vectors;
    ``call`` types calls of functions outside the math table."""
    def walk(n: Node) -> Type:
        # the commonest kinds first, told by their exact type (a wrong answer is typed)
        if type(n) is Bin:
            return _binary(n, walk(n.left), walk(n.right))
        if type(n) is Name and n.id != "pi":
            return leaf(n)
        if type(n) is Num:
            return _zero() if n.value == 0 else scalar("")
        if type(n) is Name:  # pi
            return scalar("")
        if isinstance(n, Unary):
            t = walk(n.operand)
            if t.kind not in (Kind.SCALAR, Kind.VECTOR, Kind.ZERO):
                raise DimensionError(f"cannot negate a {t.kind}")
            return t
        if isinstance(n, Call):
            if n.func in MATH_FUNCTIONS:
                return _math(n, [walk(a) for a in n.args])
            if call is None:
                raise DimensionError(f"expected a math function, found '{n.func}(...)'")
            return call(n)
        return leaf(n)

    return walk(node)


def _binary(node: Bin, a: Type, b: Type) -> Type:
    for t in (a, b):
        if t.kind in (Kind.POINT, Kind.FRAME):
            raise DimensionError(f"a {t.kind} cannot take part in arithmetic; expected scalars "
                                 "or vectors")
    def text() -> str:  # for messages only: most expressions are consistent
        return to_text(node)

    if node.op in "+-":
        if a.kind == Kind.ZERO:
            return b
        if b.kind == Kind.ZERO:
            return a
        if a.kind != b.kind:
            raise DimensionError(f"cannot add a {a.kind} and a {b.kind} in '{text()}'")
        if a.dim is not b.dim and a.dim != b.dim:  # pint's == is slow; most are one object
            verb, joint = ("adds", "to") if node.op == "+" else ("subtracts", "and")
            raise DimensionError(f"cannot add {described(a.dim)} and "
                                 f"{described(b.dim)} in '{text()}'",
                                 f"{verb} {described(a.dim)} {joint} "
                                 f"{described(b.dim)}")
        return a
    if node.op == "*":
        if a.kind == Kind.VECTOR and b.kind == Kind.VECTOR:
            raise DimensionError(f"cannot multiply two vectors in '{text()}'; expected "
                                 "dot(u, v) or cross(u, v)")
        if Kind.ZERO in (a.kind, b.kind):
            return Type(Kind.ZERO, _arithmetic("*", a.dim, b.dim))
        kind = Kind.VECTOR if Kind.VECTOR in (a.kind, b.kind) else Kind.SCALAR
        return Type(kind, _arithmetic("*", a.dim, b.dim))
    if node.op == "/":
        if b.kind != Kind.SCALAR:
            raise DimensionError(f"expected a nonzero scalar divisor in '{text()}'",
                                 "divides by zero" if b.kind == Kind.ZERO else None)
        return Type(a.kind, _arithmetic("/", a.dim, b.dim))
    # power
    if a.kind == Kind.VECTOR or b.kind == Kind.VECTOR:
        raise DimensionError(f"cannot raise a vector to a power in '{text()}'")
    variable = "raises a quantity with units to a variable power"
    pure = dimensionless()
    if b.dim is not pure and b.dim != pure:
        raise DimensionError(f"expected a pure-number exponent in '{text()}'", variable)
    if a.dim is pure or a.dim == pure:
        return Type(a.kind if a.kind != Kind.ZERO else Kind.SCALAR, a.dim)
    exponent = constant_value(node.right)
    if exponent is None:
        raise DimensionError(f"a quantity with units needs a constant exponent in '{text()}'",
                             variable)
    return Type(Kind.SCALAR, _arithmetic("**", a.dim, exponent))


_KEPT: dict[tuple, tuple] = {}
MAX_KEPT = 4096


def _kept(objects: tuple, extra: tuple, compute: Callable[[], Any]) -> Any:
    """``compute()``, kept by the identity of ``objects`` (dimensionalities) and the value of
    ``extra``. The leaves' dimensionalities are the same objects from one answer to the next
    (:func:`mechgrade.units.dimension` keeps them), so the parts' are too (kept here), and
    pint's arithmetic and text cost more than the rest of typing a wrong answer. ``objects``
    are kept with the result, so an identity is never reused while kept.

    >>> from mechgrade.units import dimension
    >>> length = dimension("m")
    >>> _kept((length,), ("square",), lambda: length ** 2) is _kept((length,), ("square",), None)
    True
    """
    key = (*map(id, objects), *extra)
    kept = _KEPT.get(key)
    if kept is not None and all(map(is_, kept[0], objects)):
        return kept[1]
    out = compute()
    if len(_KEPT) >= MAX_KEPT:
        _KEPT.clear()
    _KEPT[key] = (objects, out)
    return out


def _arithmetic(op: str, a, b):
    """``a op b`` of dimensionalities (``b`` of ``**``: an exponent, kept by its value and
    type: 2 is not 2.0 in messages), as pint works it out (:func:`_kept`).

    >>> from mechgrade.units import dimension
    >>> str(_arithmetic("**", dimension("m"), 2.0)), str(_arithmetic("/", dimension("m"), dimension("m")))
    ('[length] ** 2', 'dimensionless')
    """
    if op == "**":
        return _kept((a,), (op, b, type(b)), lambda: a ** b)
    return _kept((a, b), (op,), lambda: a * b if op == "*" else a / b)


def _math(node: Call, args: list[Type]) -> Type:
    for t in args:
        if t.kind == Kind.VECTOR:
            raise DimensionError(f"{node.func}(...) takes a scalar, found a vector "
                                 "(use mag(v) or dot(u, v))")
    entry = MATH_FUNCTIONS[node.func]
    dims = tuple(t.dim for t in args)
    return Type(Kind.SCALAR, _kept(dims, (node.func,), lambda: entry.dimension(node.func, dims)))


_DESCRIBED: dict[tuple, str] = {}


def described(dim) -> str:
    """:func:`mechgrade.units.describe_dimension`, kept per dimensionality: pint's text of one
    costs more than judging an answer. Kept by its bases in pint's order and their powers as
    written, which the text follows ('[mass]·[length]' for N, '[length]·[mass]' for lbf).

    >>> from mechgrade.units import dimension
    >>> described(dimension("m/s"))
    'a velocity ([length]/[time])'
    """
    return _kept((dim,), ("described",), lambda: _described(dim))


def _described(dim) -> str:
    key = tuple((base, repr(power)) for base, power in dict(dim).items())  # 2 is not 2.0
    if key not in _DESCRIBED:
        if len(_DESCRIBED) > 1024:
            _DESCRIBED.clear()
        _DESCRIBED[key] = describe_dimension(dim)
    return _DESCRIBED[key]
