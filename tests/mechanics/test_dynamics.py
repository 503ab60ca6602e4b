"""The kinetics of a model: its linearised motion about an instant's configuration."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from mechgrade.mechanics.dynamics import derive_kinetics, read_kinetics
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


def test_an_impact_copy_whose_zero_rate_before_is_not_zero_is_derived_in_full():
    # 9.25's block is at rest before (x1' = 0): its balances take that rate as zero, so a
    # copy moving it is another model; one with the ball's rates otherwise is read in them
    problem = load_problem(shipped_dir("problems") / "ruina_9_25_units_matrix.yaml")
    kin = derive_kinetics(problem)
    impact = problem.dynamics.analysis

    def struck(i: int, si: float):
        start = tuple(replace(s, value=None, si=si) if j == i else s
                      for j, s in enumerate(impact.start))
        return replace(problem, dynamics=replace(problem.dynamics,
                                                 analysis=replace(impact, start=start)))

    assert read_kinetics(struck(0, 1.0), problem, kin) is None
    read = read_kinetics(struck(1, 1.0), problem, kin)
    assert read is not None and read.written is kin.written
    assert read.before.values[0] == 1.0 and read.before.values[1] == kin.before.values[1]
