"""The kinetics of a model: its linearised motion about an instant's configuration."""

from __future__ import annotations

import math

import pytest

from mechgrade.mechanics.dynamics_mutations import dynamics_mutations
from mechgrade.resources import shipped_dir
from mechgrade.solve.dynamics import solve_dynamics
from mechgrade.spec import load_problem


@pytest.mark.slow
def test_omega_n_is_found_where_an_elimination_pivot_is_zero_at_the_instant():
    # the disk pendulum with the inertia about G used at the pin: the balances' first
    # reaction coefficient, m d cos(theta) eliminated, leaves a pivot d sin(theta) that is zero
    # hanging (theta = 0), where an LU solve gave 0/0
    problem = load_problem(shipped_dir("problems") / "disk_pendulum_period.yaml")
    (mistaken,) = [m.problem for m in dynamics_mutations(problem)
                   if m.code == "central_inertia_at_pivot"]
    omega_n = solve_dynamics(mistaken, objectives={"omega_n"}).result("omega_n").value
    m, r, d, g = 3.0, 0.2, 0.1, 9.81
    assert omega_n == pytest.approx(math.sqrt(m * g * d / (m * r ** 2 / 2)), rel=1e-9)
