"""Massless junctions: the balance of a node where springs meet, written as a position
constraint, and the models whose junction balance cannot fix the node (refused with the fix:
each refusal's failing-input fixture is in tests/data/authoring_mistakes/dyn_junction_*.yaml,
run by tests/cli/test_dynamics_slips_cli.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.errors import SolveError
from mechgrade.mechanics.junctions import (is_junction_balance, junction_constraints,
                                           with_junctions)
from mechgrade.resources import shipped_dir
from mechgrade.spec import load_problem, load_problem_text
from mechgrade.spec.model import ConstraintLevel

DATA = Path(__file__).resolve().parents[1] / "data" / "authoring_mistakes"


def text(name: str) -> str:
    return (DATA / f"{name}.yaml").read_text()


def test_a_junctions_balance_sums_the_pulls_of_the_springs_ending_there():
    problem = load_problem(shipped_dir("problems") / "block_on_springs_in_series.yaml")
    (balance,) = junction_constraints(problem)
    assert balance.level is ConstraintLevel.POSITION and balance.rhs.text == "0"
    assert balance.lhs.text == ("k1*(mag(pos(O, J))-L1)*unit(pos(O, J))"
                                "+k2*(mag(pos(P, J))-L2)*unit(pos(P, J))")
    assert is_junction_balance(balance.name)


def test_a_problem_without_junctions_keeps_its_constraints():
    problem = load_problem(shipped_dir("problems") / "light_pulley_hanger.yaml")  # mass 0, cords
    assert junction_constraints(problem) == ()
    assert with_junctions(problem) is problem


def test_a_damper_at_a_junction_is_refused_before_any_derivation():
    problem = load_problem_text(text("dyn_junction_damper"), "p.yaml")
    with pytest.raises(SolveError, match="the damper 'd' ends at J, on 'node', a massless "
                                         "junction"):
        junction_constraints(problem)
