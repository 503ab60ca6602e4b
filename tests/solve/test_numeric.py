"""The numeric instant's safety net: a solution where a given does not hold is an error."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.errors import SolveError
from mechgrade.solve import kinematics_plan
from mechgrade.solve.instant import _givens
from mechgrade.solve.levels import State, place_givens
from mechgrade.solve.numeric import _check_givens_hold
from mechgrade.spec import load_problem_text

BASE = (Path(__file__).resolve().parents[1] / "data" / "spec" / "base.yaml").read_text()


def test_a_given_that_does_not_hold_in_the_solution_is_named_with_its_place():
    problem = load_problem_text(BASE.replace("  theta': 3 rad/s\n",
                                             "  \"dot(vel(P, N), A.y)\": 8 m/s\n"), "p.yaml")
    p = kinematics_plan(problem)
    givens = _givens(problem, None)
    g = place_givens(problem, p, givens)
    good = g.values.copy()
    good[list(p.index.rates(1))] = 4.0  # L theta' = 8 m/s
    _check_givens_hold(problem, p, g, givens, State(good, g.known))
    wrong = good.copy()
    wrong[list(p.index.rates(1))] = 3.0  # 6 m/s, not the 8 m/s given
    with pytest.raises(SolveError) as info:
        _check_givens_hold(problem, p, g, givens, State(wrong, g.known))
    assert str(info.value) == ("p.yaml:16:26: givens.dot(vel(P, N), A.y): the given "
                               "'dot(vel(P, N), A.y) = 8 m/s' does not hold in the solution: "
                               "dot(vel(P, N), A.y) is 6 m / s there")
