"""The one table of the expression and objective language: every function is one entry.

A :class:`MathFunction` (``sin``, ``atan2``, ``sqrt``...) holds its arity, the names students
may also write (``ln``, ``arctan``), its dimension rule and its sympy, numpy and constant
(``math``) implementations. An :class:`ObjectiveFunction` (``vel``, ``force``...) holds its
argument kinds, result kind and dimension rule; its implementation needs ``sympy.physics`` and
lives in :mod:`mechgrade.mechanics` under the same name. The reader, the spec checks, sympy
construction, numeric sampling and the docs are all views of :data:`TABLE`.

Implementations are read from their library when first used (``attrgetter`` of the module),
so reading an expression never imports sympy or numpy.

>>> MATH_FUNCTIONS["atan2"].arity, ALIASES["ln"]
(2, 'log')
>>> OBJECTIVE_FUNCTIONS["vel"].args
(<Kind.POINT: 'point'>, <Kind.FRAME: 'frame'>)
>>> sympy_functions()["cot"](0), float(numpy_functions()["cot"](0.5))
(zoo, 1.830487721712452)
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from functools import lru_cache
from operator import attrgetter
from typing import Callable

from ..errors import ExpressionError, Location
from ..units import describe_dimension, dimension, dimensionless

if sys.version_info >= (3, 11):
    from enum import StrEnum
else:  # Python 3.10: the same behaviour, spelled out
    from enum import Enum

    class StrEnum(str, Enum):
        """An enum whose members are their string values (``==``, ``str``, JSON)."""

        __str__ = str.__str__
        __format__ = str.__format__


class Kind(StrEnum):
    """What an expression, or an argument of an objective function, stands for."""

    SCALAR = "scalar"
    VECTOR = "vector"
    POINT = "point"
    FRAME = "frame"
    ZERO = "zero"  # the literal 0: a scalar or a vector, of any dimension
    BODY = "body"
    LOAD = "load"
    BODY_OR_SPRING = "body or spring"
    COORDINATE = "coordinate"
    QUANTITY = "scalar or vector"  # an argument of either kind; as a result: its argument's


class DimensionError(ExpressionError):
    """An expression combines quantities of inconsistent dimensions or kinds.

    ``message`` is worded for the author of a spec (it quotes the expression); ``student``
    completes "Your expression ..." in a student's feedback.
    """

    def __init__(self, message: str, student: str | None = None, **where):
        super().__init__(message, **where)
        self.student = student or message

    def located(self, where: Location) -> "DimensionError":
        err = super().located(where)
        err.student = self.student
        return err


# ---------------------------------------------------------------------------- dimension rules
# A rule takes the function's name and its arguments' dimensions and gives the result's.


def _pure(name: str, dims: tuple):
    """Arguments pure numbers or angles; a pure number out (sin, exp, log...)."""
    for dim in dims:
        if dim != dimensionless():
            raise DimensionError(f"{name}(...) needs a pure number or angle, found "
                                 f"{describe_dimension(dim)}",
                                 f"takes {name} of {describe_dimension(dim)}, which needs a "
                                 "pure number")
    return dimensionless()


def _same(name: str, dims: tuple):
    """The argument's dimension (abs)."""
    return dims[0]


def _root(name: str, dims: tuple):
    """Half the argument's dimension (sqrt)."""
    return dims[0] ** 0.5


def _number_of_any(name: str, dims: tuple):
    """A pure number from any quantity (sign)."""
    return dimensionless()


def _ratio(name: str, dims: tuple):
    """Two arguments of one dimension; a pure number (an angle) out (atan2)."""
    if dims[0] != dims[1]:
        raise DimensionError(f"{name}(y, x) needs y and x in the same dimension",
                             f"compares quantities of different dimensions in {name}")
    return dimensionless()


def _reciprocal(name: str) -> Callable:
    """``1/f`` of numpy's ``f`` (numpy has no cot, sec, csc)."""
    def numpy_function(np):
        inner = getattr(np, name)
        return lambda a: 1 / inner(a)
    return numpy_function


@dataclass(frozen=True)
class MathFunction:
    """A scalar function of scalars: ``sympy``, ``numpy`` and ``math`` pick its implementation
    out of that library (``math`` is ``None`` when constants are not folded through it)."""

    name: str
    arity: int
    dimension: Callable[[str, tuple], object]
    sympy: Callable
    numpy: Callable
    math: Callable | None
    doc: str
    aliases: tuple[str, ...] = ()


_NOT_FOLDED = None


def _math(name: str, doc: str, *, dim=_pure, arity: int = 1, sympy_name: str | None = None,
          numpy=None, constant=attrgetter, aliases: tuple[str, ...] = ()) -> MathFunction:
    return MathFunction(name, arity, dim, attrgetter(sympy_name or name),
                        numpy or attrgetter(name), constant and constant(name), doc, aliases)


_MATH = (
    _math("sin", "sin(x): sine of an angle or pure number"),
    _math("cos", "cos(x): cosine"),
    _math("tan", "tan(x): tangent"),
    _math("cot", "cot(x): cotangent", numpy=_reciprocal("tan"), constant=_NOT_FOLDED),
    _math("sec", "sec(x): secant", numpy=_reciprocal("cos"), constant=_NOT_FOLDED),
    _math("csc", "csc(x): cosecant", numpy=_reciprocal("sin"), constant=_NOT_FOLDED),
    _math("asin", "asin(x): inverse sine, in radians", numpy=attrgetter("arcsin"),
          aliases=("arcsin",)),
    _math("acos", "acos(x): inverse cosine, in radians", numpy=attrgetter("arccos"),
          aliases=("arccos",)),
    _math("atan", "atan(x): inverse tangent, in radians", numpy=attrgetter("arctan"),
          aliases=("arctan",)),
    _math("atan2", "atan2(y, x): the angle of the point (x, y), in radians", dim=_ratio,
          arity=2, numpy=attrgetter("arctan2"), constant=_NOT_FOLDED, aliases=("arctan2",)),
    _math("sinh", "sinh(x): hyperbolic sine"),
    _math("cosh", "cosh(x): hyperbolic cosine"),
    _math("tanh", "tanh(x): hyperbolic tangent"),
    _math("sqrt", "sqrt(x): square root (of any quantity)", dim=_root),
    _math("exp", "exp(x): e to the x"),
    _math("log", "log(x): natural logarithm", aliases=("ln",)),
    _math("abs", "abs(x): absolute value (of any quantity)", dim=_same, sympy_name="Abs",
          constant=lambda name: lambda module: abs, aliases=("Abs",)),
    _math("sign", "sign(x): -1, 0 or 1 by the sign of any quantity", dim=_number_of_any,
          constant=_NOT_FOLDED),
)


# ---------------------------------------------------------------------------- objective functions


def _fixed(unit: str) -> Callable[[tuple], object]:
    return lambda dims: dimension(unit)


def _first(dims: tuple):
    return dims[0]


def _pure_number(dims: tuple):
    return dimensionless()


@dataclass(frozen=True)
class ObjectiveFunction:
    """A function of points, frames, vectors, bodies or loads: argument kinds, result kind,
    the rule giving the result's dimension from the arguments', and a description. Its
    implementation is :mod:`mechgrade.mechanics`'s function of the same name.

    ``origin_of`` is the position of the frame argument whose origin (a point fixed in it) the
    function needs, if any: velocities are taken relative to it.
    """

    name: str
    args: tuple[Kind, ...]
    result: Kind
    dim: Callable[[tuple], object]
    doc: str
    origin_of: int | None = None


_P, _F, _V, _S = Kind.POINT, Kind.FRAME, Kind.VECTOR, Kind.SCALAR
_B, _L, _Q = Kind.BODY, Kind.LOAD, Kind.COORDINATE

_OBJECTIVE = (
    ObjectiveFunction("pos", (_P, _P), _V, _fixed("m"),
                      "pos(P, Q): position of point P relative to point Q"),
    ObjectiveFunction("vel", (_P, _F), _V, _fixed("m/s"),
                      "vel(P, F): velocity of P as seen in frame F", origin_of=1),
    ObjectiveFunction("acc", (_P, _F), _V, _fixed("m/s^2"),
                      "acc(P, F): acceleration of P as seen in frame F", origin_of=1),
    ObjectiveFunction("angvel", (_F, _F), _V, _fixed("1/s"),
                      "angvel(A, F): angular velocity of frame A in frame F"),
    ObjectiveFunction("angacc", (_F, _F), _V, _fixed("1/s^2"),
                      "angacc(A, F): angular acceleration of frame A in frame F"),
    ObjectiveFunction("dt", (_V, _F), _V, lambda dims: dims[0] / dimension("s"),
                      "dt(v, F): time derivative of vector v taken in frame F"),
    ObjectiveFunction("mag", (_V,), _S, _first, "mag(v): magnitude of v"),
    ObjectiveFunction("dot", (_V, _V), _S, lambda dims: dims[0] * dims[1],
                      "dot(u, v): dot product"),
    ObjectiveFunction("cross", (_V, _V), _V, lambda dims: dims[0] * dims[1],
                      "cross(u, v): cross product"),
    ObjectiveFunction("unit", (_V,), _V, _pure_number, "unit(v): unit vector along v"),
    ObjectiveFunction("speed", (_P, _F), _S, _fixed("m/s"),
                      "speed(P, F): speed (s-dot) of P in F", origin_of=1),
    ObjectiveFunction("acc_t", (_P, _F), _S, _fixed("m/s^2"),
                      "acc_t(P, F): tangential acceleration (s-double-dot) of P in F", origin_of=1),
    ObjectiveFunction("acc_n", (_P, _F), _S, _fixed("m/s^2"),
                      "acc_n(P, F): normal acceleration s-dot^2/rho of P in F", origin_of=1),
    ObjectiveFunction("rho", (_P, _F), _S, _fixed("m"),
                      "rho(P, F): radius of curvature of P's path in F", origin_of=1),
    ObjectiveFunction("tangent", (_P, _F), _V, _pure_number,
                      "tangent(P, F): unit tangent of P's path in F", origin_of=1),
    ObjectiveFunction("normal", (_P, _F), _V, _pure_number,
                      "normal(P, F): unit normal of P's path in F, toward the centre of "
                      "curvature", origin_of=1),
    ObjectiveFunction("coincident", (_P, _F), _P, _fixed("m"),
                      "coincident(P, A): the point fixed in frame A that is at P now", origin_of=1),
    ObjectiveFunction("ic", (_F, _F), _P, _fixed("m"),
                      "ic(A, F): instantaneous centre of zero velocity of body A in F "
                      "(usable inside pos)", origin_of=0),
    # dynamics (see spec/dynamics.py): loads, momenta and energies of bodies
    ObjectiveFunction("force", (_L,), _V, _fixed("N"),
                      "force(R): the force of a load (a reaction, friction, spring, applied "
                      "force)"),
    ObjectiveFunction("impulse", (_L,), _V, _fixed("N*s"),
                      "impulse(R): the impulse of a reaction during an impact"),
    ObjectiveFunction("before", (Kind.QUANTITY,), Kind.QUANTITY, lambda dims: dims[0],
                      "before(x): scalar or vector x with the rates just before the impact "
                      "(analysis: impulse), e.g. before(ke(B, N))"),
    ObjectiveFunction("after", (Kind.QUANTITY,), Kind.QUANTITY, lambda dims: dims[0],
                      "after(x): scalar or vector x with the rates just after the impact "
                      "(analysis: impulse; x alone means the same)"),
    ObjectiveFunction("moment", (_L, _P), _V, _fixed("N*m"),
                      "moment(R, P): the moment of a load about point P"),
    ObjectiveFunction("momentum", (_B, _F), _V, _fixed("kg*m/s"),
                      "momentum(B, F): linear momentum of body B in frame F"),
    ObjectiveFunction("angmom", (_B, _P, _F), _V, _fixed("kg*m^2/s"),
                      "angmom(B, P, F): angular momentum of body B about point P in frame F"),
    ObjectiveFunction("ke", (_B, _F), _S, _fixed("J"),
                      "ke(B, F): kinetic energy of body B in frame F"),
    ObjectiveFunction("pe", (Kind.BODY_OR_SPRING,), _S, _fixed("J"),
                      "pe(X): potential energy of body X in gravity (zero at the inertial point) "
                      "or of spring X"),
    ObjectiveFunction("power", (_L, _F), _S, _fixed("W"),
                      "power(R, F): power of a load, with velocities in frame F"),
    ObjectiveFunction("eom", (_Q,), _S, lambda dims: dims[0] / dimension("s") ** 2,
                      "eom(q): q'' from the equations of motion"),
    ObjectiveFunction("omega_n", (_Q,), _S, _fixed("rad/s"),
                      "omega_n(q): natural frequency of the motion linearised about the "
                      "instant's configuration (an equilibrium)"),
    ObjectiveFunction("mode_frequency", (_S,), _S, _fixed("rad/s"),
                      "mode_frequency(n): the n-th natural frequency (1 the lowest) of the "
                      "motion linearised about the equilibrium"),
    ObjectiveFunction("mode_damping", (_S,), _S, _pure_number,
                      "mode_damping(n): the damping ratio of the n-th mode (1 the lowest), "
                      "from the eigenvalues of the linearised motion's state-space matrix"),
    ObjectiveFunction("mode_shape", (_S, _Q, _Q), _S, lambda dims: dims[1] / dims[2],
                      "mode_shape(n, q, r): the amplitude ratio of q to r in mode n"),
    ObjectiveFunction("zeta", (_Q,), _S, _pure_number,
                      "zeta(q): damping ratio of the motion linearised about the equilibrium"),
)

TABLE: tuple[MathFunction | ObjectiveFunction, ...] = _MATH + _OBJECTIVE
"""Every function of the language, in the order the docs list them."""

MATH_FUNCTIONS: dict[str, MathFunction] = {f.name: f for f in _MATH}
OBJECTIVE_FUNCTIONS: dict[str, ObjectiveFunction] = {f.name: f for f in _OBJECTIVE}
ALIASES: dict[str, str] = {alias: f.name for f in _MATH for alias in f.aliases}
"""Other spellings of math functions (``ln``, ``arctan``), read as the canonical name."""

WRITTEN_MATH_NAMES: frozenset[str] = frozenset(MATH_FUNCTIONS) | frozenset(ALIASES)
"""Every math function name the reader accepts (canonical names and aliases)."""

assert not set(MATH_FUNCTIONS) & set(OBJECTIVE_FUNCTIONS)


@lru_cache(maxsize=1)
def sympy_functions() -> dict[str, Callable]:
    """Canonical math name -> its sympy function (imports sympy on first use)."""
    import sympy
    return {f.name: f.sympy(sympy) for f in _MATH}


@lru_cache(maxsize=1)
def numpy_functions() -> dict[str, Callable]:
    """Canonical math name -> its numpy function (imports numpy on first use)."""
    import numpy
    return {f.name: f.numpy(numpy) for f in _MATH}


CONSTANT_FUNCTIONS: dict[str, Callable[[float], float]] = {
    f.name: f.math(math) for f in _MATH if f.math is not None}
"""Canonical name -> the ``math`` function that folds a constant argument (one-argument
functions whose value at a constant is worth computing while reading)."""
