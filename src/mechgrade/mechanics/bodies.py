"""Inertia of bodies: each shape's central inertia in its body axes (one entry of
:data:`SHAPES` per shape type), and the parallel-axis shift of a part's inertia to the body's
reference point (done here, never by the author).

>>> import sympy as sp
>>> from sympy.physics.vector import ReferenceFrame
>>> from mechgrade.spec.dynamics import Rod
>>> B = ReferenceFrame("B")
>>> m, L = sp.symbols("m L", positive=True)
>>> I = central_inertia(Rod(L, "x"), m, B, lambda e: e)
>>> I.to_matrix(B)[1, 1], I.to_matrix(B)[0, 0]
(L**2*m/12, 0)
>>> shifted = parallel_axis(I, m, L / 2 * B.x, B)
>>> shifted.to_matrix(B)[1, 1]
L**2*m/3
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import sympy as sp
from sympy.physics.mechanics import inertia
from sympy.physics.vector import Dyadic, ReferenceFrame, Vector

from ..spec.dynamics import (INERTIA_KEYS, Block, Cylinder, Disk, Explicit, Ring, Rod, Shape,
                             Shell, Sphere)

_AXES = "xyz"


def principal(frame: ReferenceFrame, axis: str, along, across) -> Dyadic:
    """The inertia with moment ``along`` about body axis ``axis`` and ``across`` about the two
    perpendicular body axes."""
    moments = [along if a == axis else across for a in _AXES]
    return inertia(frame, *moments)


@dataclass(frozen=True)
class ShapeInertia:
    """A shape's inertia: ``central(shape, m, frame, scalar)`` its central inertia (``scalar``
    turns the shape's dimensions into sympy); ``name`` how a textbook names it and, for a round
    shape, ``axial`` the coefficient of m r² about its axis (text, as a mistake's message shows
    it)."""

    name: str
    central: Callable[..., Dyadic]
    axial: str | None = None


def _round(axial: str, across: str | None) -> Callable[..., Dyadic]:
    """A ring, disk, sphere or shell of ``radius``: ``axial`` m r² about its axis, ``across``
    m r² about the others (the same, without an axis)."""

    def central(shape, m, frame, scalar) -> Dyadic:
        r2 = scalar(shape.radius) ** 2
        along = sp.Rational(axial) * m * r2
        if across is None:
            return inertia(frame, along, along, along)
        return principal(frame, shape.axis, along, sp.Rational(across) * m * r2)
    return central


def _cylinder(shape: Cylinder, m, frame, scalar) -> Dyadic:
    r2, h2 = scalar(shape.radius) ** 2, scalar(shape.length) ** 2
    return principal(frame, shape.axis, m * r2 / 2, m * (3 * r2 + h2) / 12)


def _block(shape: Block, m, frame, scalar) -> Dyadic:
    a, b, c = (scalar(side) ** 2 for side in shape.sides)
    return inertia(frame, m * (b + c) / 12, m * (a + c) / 12, m * (a + b) / 12)


SHAPES: dict[type, ShapeInertia] = {
    Rod: ShapeInertia("a slender rod", lambda shape, m, frame, scalar: principal(
        frame, shape.axis, 0, m * scalar(shape.length) ** 2 / 12)),
    Ring: ShapeInertia("a thin ring", _round("1", "1/2"), "1"),
    Disk: ShapeInertia("a uniform disk", _round("1/2", "1/4"), "1/2"),
    Cylinder: ShapeInertia("a solid cylinder", _cylinder),
    Sphere: ShapeInertia("a solid sphere", _round("2/5", None), "2/5"),
    Shell: ShapeInertia("a thin spherical shell", _round("2/3", None), "2/3"),
    Block: ShapeInertia("a rectangular block", _block),
    Explicit: ShapeInertia("an inertia given", lambda shape, _m, frame, scalar: explicit_inertia(
        {key: scalar(e) for key, e in shape.entries}, frame)),
}
"""Every shape's inertia, by the shape's type."""


def central_inertia(shape: Shape, m, frame: ReferenceFrame,
                    scalar: Callable[[object], sp.Expr]) -> Dyadic:
    """Central inertia of a uniform body of mass ``m`` and ``shape`` (its dimensions made
    sympy by ``scalar``), in the body axes ``frame``."""
    return SHAPES[type(shape)].central(shape, m, frame, scalar)


def explicit_inertia(entries: dict, frame: ReferenceFrame) -> Dyadic:
    """``{"xx": Ixx, ...}`` (missing entries zero) as a dyadic in ``frame``."""
    # INERTIA_KEYS lists them in the order inertia() takes them
    return inertia(frame, *(entries.get(key, sp.Integer(0)) for key in INERTIA_KEYS))


def parallel_axis(central: Dyadic, m, offset: Vector, frame: ReferenceFrame) -> Dyadic:
    """Inertia about a point at ``-offset`` from the mass centre (``offset`` = r_G/P):
    I_P = I_G + m (|r|^2 U - r r)."""
    unit = inertia(frame, 1, 1, 1)
    return central + m * ((offset & offset) * unit - (offset | offset))
