"""The reference solver: every objective of a problem, derived from its model."""

from .entry import solve
from .plan import kinematics_plan
from .result import MistakeValue, ObjectiveFailure, ObjectiveResult, Solution, StateValue

__all__ = ["MistakeValue", "ObjectiveFailure", "ObjectiveResult", "Solution", "StateValue",
           "kinematics_plan", "solve"]
