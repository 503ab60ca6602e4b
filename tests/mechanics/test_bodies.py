"""Every shape's central inertia, found by the shape's type."""

from __future__ import annotations

import pytest
import sympy as sp
from sympy.physics.vector import ReferenceFrame

from mechgrade.mechanics.bodies import SHAPES, central_inertia
from mechgrade.spec.dynamics import (Block, Cylinder, Disk, Explicit, Ring, Rod, Shape, Shell,
                                     Sphere)

m, r, L, a, b = sp.symbols("m r L a b", positive=True)
B = ReferenceFrame("B")


@pytest.mark.parametrize("shape, moments", [
    (Rod(L, "z"), (m * L ** 2 / 12, m * L ** 2 / 12, 0)),
    (Ring(r, "z"), (m * r ** 2 / 2, m * r ** 2 / 2, m * r ** 2)),
    (Disk(r, "z"), (m * r ** 2 / 4, m * r ** 2 / 4, m * r ** 2 / 2)),
    (Cylinder(r, L, "z"), ((3 * m * r ** 2 + m * L ** 2) / 12,) * 2 + (m * r ** 2 / 2,)),
    (Sphere(r), (sp.Rational(2, 5) * m * r ** 2,) * 3),
    (Shell(r), (sp.Rational(2, 3) * m * r ** 2,) * 3),
    (Block((a, b, 0)), (m * b ** 2 / 12, m * a ** 2 / 12, m * (a ** 2 + b ** 2) / 12)),
    (Explicit((("zz", m * r ** 2),)), (0, 0, m * r ** 2)),
])
def test_each_shape_has_the_textbook_central_inertia(shape, moments):
    matrix = central_inertia(shape, m, B, lambda e: e).to_matrix(B)
    assert [sp.simplify(matrix[i, i] - moments[i]) for i in range(3)] == [0, 0, 0]


def test_every_shape_type_has_its_inertia():
    assert set(SHAPES) == set(Shape.__args__)
    assert {kind: SHAPES[kind].axial for kind in (Ring, Disk, Sphere, Shell)} == \
        {Ring: "1", Disk: "1/2", Sphere: "2/5", Shell: "2/3"}
