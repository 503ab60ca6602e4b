"""The states a derivation samples: a moment along the motion, back on the constraints."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from mechgrade.solve import rules
from mechgrade.solve.derivation import _on_constraints


def circle():
    """A point on the unit circle, x^2 + y^2 = 1 (a position constraint, no velocity one):
    the state is x, y, their rates, their accelerations and t."""
    index = SimpleNamespace(n=2, size=7, time=6, rates=lambda level: [2 * level, 2 * level + 1])
    position = SimpleNamespace(
        constraint_rows=1, labels=("circle",),
        residual=lambda x, y, *rest: np.array([x * x + y * y - 1.0]),
        scale=lambda x, y, *rest: np.array([x * x + y * y + 1.0]),
        jacobian=lambda x, y, *rest: np.array([2 * x, 2 * y]))
    velocity = SimpleNamespace(constraint_rows=0)
    return SimpleNamespace(kp=SimpleNamespace(index=index, levels=(position, velocity)))


def test_a_state_a_moment_along_the_motion_is_put_back_on_its_position_constraints():
    """Uniform motion round the circle, 0.1 s on: stepped along its rate and acceleration the
    point is 2.5e-5 off the circle (far more than rules.PROJECTED), and put back within it."""
    kp = circle()
    x = np.array([1.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0])
    for dt in (0.1, -0.1):
        stepped = x[:2] + dt * x[2:4] + dt * dt / 2 * x[4:6]
        assert not rules.projected(kp.kp.levels[0].residual(*stepped), 2.0)
        moved = _on_constraints(kp, x, dt)
        assert rules.projected(kp.kp.levels[0].residual(*moved), 2.0)
        assert moved[6] == dt
