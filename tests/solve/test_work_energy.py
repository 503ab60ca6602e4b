"""The rates of a dynamics instant from the energy balance: one column or many, each column
refused for what it alone would be refused for."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechgrade.errors import SolveError
from mechgrade.solve import solve
from mechgrade.solve.dynamics import kinematic_problem, kinetics_plan
from mechgrade.solve.instant import instant_givens
from mechgrade.solve.numeric import solve_numeric
from mechgrade.solve.work_energy import energy_rates
from mechgrade.spec import load_problem, load_problem_text

ROOT = Path(__file__).resolve().parents[2]
HOOP = ROOT / "problems" / "unbalanced_hoop_rolls.yaml"


def error_of(body: str) -> str:
    with pytest.raises(SolveError) as info:
        solution = solve(load_problem_text(body, "p.yaml"))
        for failure in solution.failures:
            raise failure.error
    return str(info.value)


def test_each_column_gets_its_own_rates_or_its_own_error():
    problem = load_problem(HOOP)
    kp = kinetics_plan(problem)
    state = solve_numeric(kinematic_problem(problem), kp.kp,
                          instant_givens(problem, None, {}), set()).state
    X = np.repeat(state.values[:, None], 2, axis=1)
    X[kp.kp.index.position("R"), 1] = np.nan  # an undefined velocity constraint
    rates, errors = energy_rates(problem, kp, X)
    alone = solve(problem).result("angular_velocity").value  # |phi'|
    phi_rate = kp.kp.index.position("phi'")
    assert errors[0] is None and abs(rates[phi_rate, 0]) == pytest.approx(alone, rel=1e-12)
    assert str(errors[1]).endswith("work_energy needs the velocity constraints at the instant, "
                                   "but they are undefined there (a division by zero)")


def test_work_energy_refuses_more_than_one_free_direction():
    body = HOOP.read_text().replace("constraints:\n  - name: no_slip\n    position: x = -R*phi\n",
                                    "")
    assert error_of(body).endswith("work_energy finds the speed of a motion with one degree of "
                                   "freedom; this one has 2 at the instant")


def _levelled(level: str) -> str:
    """The hoop with a height ``y`` that the constraint ``y = level`` ties to it, its sense
    asked of ``y'``."""
    body = HOOP.read_text().replace("  phi: rad\n", "  phi: rad\n  y: m\n").replace(
        "    position: x = -R*phi\n", "    position: x = -R*phi\n  - name: level\n"
        f"    position: y = {level}\n").replace("sense: {phi': negative}", "sense: {y': negative}")
    return body.replace("from: {x: 0 m, phi: 0 rad}", "from: {x: 0 m, phi: 0 rad, y: 0 m}")


def test_work_energy_refuses_a_sense_of_a_rate_that_is_zero_at_the_instant():
    assert error_of(_levelled("0 m")).endswith("the sense of y' cannot fix the sign: it is "
                                               "zero at the instant")


def test_a_sense_fixes_the_sign_of_a_rate_the_motion_moves_beyond_rounding_only():
    # y' = 1e-10 x' is a component of 4.5e-11 in the motion's one direction (orthonormal):
    # left at rest as the solver leaves any unknown not open (rules.OPEN); 1e-8 x' is not
    assert error_of(_levelled("1e-10*x")).endswith("the sense of y' cannot fix the sign: it "
                                                   "is zero at the instant")
    solution = solve(load_problem_text(_levelled("1e-8*x"), "p.yaml"))
    assert solution.result("angular_velocity").value == pytest.approx(
        solve(load_problem(HOOP)).result("angular_velocity").value, rel=1e-12)


def test_work_energy_refuses_a_given_rate():
    body = HOOP.read_text().replace("  x: pi*R\n", "  x: pi*R\n  phi': -3 rad/s\n")
    assert error_of(body).endswith("work_energy fixes the rates; do not also give phi'")
