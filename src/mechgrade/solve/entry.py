"""The solver's one entry point: a problem with bodies and loads goes to the dynamics solver,
any other to the kinematics solver (each a module of its own).

The dynamics solver is imported only for a problem that needs it (it imports sympy), and a
dynamics problem's solution, for any givens and objectives, is kept in the disk cache
(:mod:`.stored`): a kinematics problem whose plan is cached, or a dynamics problem whose
solution is, is solved again without sympy.
"""

from __future__ import annotations

from typing import Collection, Mapping

from ..spec.model import Problem
from .instant import solve_kinematics
from .result import Solution


def solve(problem: Problem, *, givens: Mapping[str, float | None] | None = None,
          objectives: Collection[str] | None = None) -> Solution:
    """Solve every objective of ``problem`` (or only those named in ``objectives``).

    ``givens`` overrides given values for this call only: keys are given names as written in
    the spec (``"theta'"``, ``"dot(vel(B, N), B.x)"``), values are SI numbers, ``None`` removes
    a given. Objectives with givens of their own are solved at their own instant.

    An objective that cannot be solved is a failure beside the others' answers
    (:attr:`Solution.failures`); when none of them can be, the first error is raised.
    """
    if problem.dynamics is None:
        return solve_kinematics(problem, givens=givens, objectives=objectives)
    return _stored_dynamics(problem, givens, objectives)


def _solve_dynamics(problem: Problem, givens, objectives) -> Solution:
    from .dynamics import solve_dynamics
    from .dynamics_mutants import with_generated_mistakes

    return with_generated_mistakes(problem, solve_dynamics(
        problem, givens=givens, objectives=objectives), givens)


def _stored_dynamics(problem: Problem, givens, objectives) -> Solution:
    """A dynamics problem solved: read from the disk cache, or solved and (its generated
    mistakes worked out, or the error it raised) written there."""
    from .stored import kept, solution_key

    return kept(solution_key(problem, givens, objectives),
                lambda: _solve_dynamics(problem, givens, objectives))
