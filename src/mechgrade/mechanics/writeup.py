"""The derivation of a problem in the systematic write-up order: the kinetics write-up for a
problem with bodies and loads, the kinematics write-up for any other."""

from __future__ import annotations

from ..spec.model import Problem
from .derivation import kinematics_derivation
from .dynamics import kinetics_derivation


def derivation(problem: Problem, dof: int | None = None) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """``(section, lines)`` pairs of the write-up (see :func:`kinematics_derivation` and
    :func:`~mechgrade.mechanics.dynamics.kinetics_derivation`)."""
    if problem.dynamics is not None:
        return kinetics_derivation(problem, dof)
    return kinematics_derivation(problem, dof)
