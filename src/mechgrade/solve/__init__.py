"""The reference solver: every objective of a problem, derived from its model."""

from .entry import solve
from .plan import kinematics_plan
from .result import MistakeValue, ObjectiveFailure, ObjectiveResult, Solution, StateValue

__all__ = ["solve", "kinematics_plan", "Solution", "ObjectiveResult", "MistakeValue", "StateValue",
           "ObjectiveFailure"]
