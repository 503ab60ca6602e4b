"""The derivation of a problem in the systematic write-up order: the kinetics write-up for a
problem with bodies and loads, the kinematics write-up for any other."""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

from ..spec.model import Problem
from .derivation import WorkedStep, compact_math, kinematics_derivation, kinematics_steps
from .junctions import junction_balances_said, kinematic_part
from .kinetics_steps import kinetics_steps
from .dynamics import kinetics_derivation


def derivation(problem: Problem, dof: int | None = None) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """``(section, lines)`` pairs of the write-up (see :func:`kinematics_derivation` and
    :func:`~mechgrade.mechanics.dynamics.kinetics_derivation`)."""
    if problem.dynamics is not None:
        return kinetics_derivation(problem, dof)
    return kinematics_derivation(problem, dof)


@lru_cache(maxsize=64)  # one problem's steps serve every student's variant of it
def worked_steps(problem: Problem, dof: int | None = None) -> tuple[WorkedStep, ...]:
    """The symbolic steps of the worked solution: the kinematics (:func:`kinematics_steps`),
    then, for a problem with bodies and loads, the kinetics sections of the write-up (bodies,
    free-body loads, the work-energy balance, momentum balances, how the unknowns are solved:
    :func:`~mechgrade.mechanics.kinetics_steps.kinetics_steps`).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> steps = worked_steps(load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml"))
    >>> steps[0].anchor, steps[-1].anchor
    ('frames', 'kinetics-solution')
    """
    kinematic = kinematic_part(problem)
    steps = kinematics_steps(kinematic, dof, tuple(junction_balances_said(problem).items()))
    if problem.dynamics is not None:
        steps += kinetics_steps(problem)
    return tuple(replace(step, rows=tuple(replace(row, math=compact_math(row.math))
                                          for row in step.rows)) for step in steps)
