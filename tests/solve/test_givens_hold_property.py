"""Property: for problems of the library with their givens moved within ±20 %, every
constraint and every given holds in the solved state — or solving says why it cannot."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechgrade.errors import MechgradeError
from mechgrade.expressions.syntax import to_text
from mechgrade.solve import kinematics_plan, solve
from mechgrade.spec import load_problem

FILES = sorted((Path(__file__).resolve().parents[2] / "problems").glob("*.yaml"))


@lru_cache(maxsize=None)
def problem(path: Path):
    return load_problem(path)


def residuals_hold(prob, solution, overrides) -> None:
    """Every active equation of every level, evaluated at the solution's state."""
    p = kinematics_plan(prob)
    x = np.full(p.index.size, np.nan)
    for value in solution.state:
        x[p.index.position(value.name)] = value.si
    for key, si in overrides.items():
        if key in p.index.names:
            assert x[p.index.position(key)] == si, key
    conditions = {key: si for key, si in overrides.items() if key not in p.index.names}
    for level in p.levels:
        with np.errstate(all="ignore"):
            r = np.asarray(level.residual(*x), dtype=float).ravel()
            scale = np.abs(np.asarray(level.scale(*x), dtype=float).ravel())
        for i, label in enumerate(level.labels):
            key = level.conditions[i - level.constraint_rows] if i >= level.constraint_rows \
                else None
            if key is not None and key not in conditions:
                continue
            target = conditions[key] if key is not None else 0.0
            if np.isnan(r[i]):  # uses a quantity left free (no objective needs it)
                continue
            assert abs(r[i] - target) <= prob.consistency * scale[i] + 1e-9, label


@pytest.mark.slow
@settings(max_examples=30)
@given(data=st.data())
def test_perturbed_givens_hold_in_the_solution_or_solving_says_why(data):
    path = data.draw(st.sampled_from(FILES), label="problem")
    prob = problem(path)
    overrides = {to_text(g.key.node): g.si * data.draw(st.floats(0.8, 1.2), label=g.key.text)
                 for g in prob.givens}
    try:
        solution = solve(prob, givens=overrides)
    except MechgradeError as err:
        assert err.message
        return
    for failure in solution.failures:
        assert failure.error.message
    # The kinematic levels' residuals; a dynamics problem checks its balances in its solver.
    if solution.state and prob.dynamics is None:  # empty state: only symbolic objectives
        residuals_hold(prob, solution, overrides)
