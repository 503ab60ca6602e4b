"""Inertia of bodies: each shape's central inertia in its body axes, and the parallel-axis
shift of a part's inertia to the body's reference point (done here, never by the author).

>>> import sympy as sp
>>> from sympy.physics.vector import ReferenceFrame
>>> B = ReferenceFrame("B")
>>> m, L = sp.symbols("m L", positive=True)
>>> I = shape_inertia("rod", {"length": L, "axis": "x"}, m, B)
>>> I.to_matrix(B)[1, 1], I.to_matrix(B)[0, 0]
(L**2*m/12, 0)
>>> shifted = parallel_axis(I, m, L / 2 * B.x, B)
>>> shifted.to_matrix(B)[1, 1]
L**2*m/3
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.mechanics import inertia
from sympy.physics.vector import Dyadic, ReferenceFrame, Vector

_AXES = "xyz"


def principal(frame: ReferenceFrame, axis: str, along, across) -> Dyadic:
    """The inertia with moment ``along`` about body axis ``axis`` and ``across`` about the two
    perpendicular body axes."""
    moments = [along if a == axis else across for a in _AXES]
    return inertia(frame, *moments)


def shape_inertia(kind: str, size: dict, m, frame: ReferenceFrame) -> Dyadic:
    """Central inertia of a uniform body of mass ``m`` and shape ``kind`` (``rod``, ``ring``,
    ``disk``, ``cylinder``, ``sphere``, ``shell``, ``block``), dimensions in ``size``."""
    half, quarter, twelfth = sp.Rational(1, 2), sp.Rational(1, 4), sp.Rational(1, 12)
    if kind == "rod":
        return principal(frame, size["axis"], 0, twelfth * m * size["length"] ** 2)
    if kind == "ring":
        r2 = size["radius"] ** 2
        return principal(frame, size["axis"], m * r2, half * m * r2)
    if kind == "disk":
        r2 = size["radius"] ** 2
        return principal(frame, size["axis"], half * m * r2, quarter * m * r2)
    if kind == "cylinder":
        r2, h2 = size["radius"] ** 2, size["length"] ** 2
        return principal(frame, size["axis"], half * m * r2, twelfth * m * (3 * r2 + h2))
    if kind in ("sphere", "shell"):
        factor = sp.Rational(2, 5) if kind == "sphere" else sp.Rational(2, 3)
        moment = factor * m * size["radius"] ** 2
        return inertia(frame, moment, moment, moment)
    a, b, c = (s ** 2 for s in size["sides"])
    return inertia(frame, twelfth * m * (b + c), twelfth * m * (a + c), twelfth * m * (a + b))


def explicit_inertia(entries: dict, frame: ReferenceFrame) -> Dyadic:
    """``{"xx": Ixx, ...}`` (missing entries zero) as a dyadic in ``frame``."""
    get = lambda key: entries.get(key, sp.Integer(0))  # noqa: E731
    return inertia(frame, get("xx"), get("yy"), get("zz"), get("xy"), get("yz"), get("zx"))


def parallel_axis(central: Dyadic, m, offset: Vector, frame: ReferenceFrame) -> Dyadic:
    """Inertia about a point at ``-offset`` from the mass centre (``offset`` = r_G/P):
    I_P = I_G + m (|r|^2 U - r r)."""
    unit = inertia(frame, 1, 1, 1)
    return central + m * ((offset & offset) * unit - (offset | offset))
