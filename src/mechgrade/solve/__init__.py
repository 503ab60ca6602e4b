"""The reference solver: every objective of a problem, derived from its model."""

from .instant import plan, solve
from .result import MistakeValue, ObjectiveResult, Solution, StateValue

__all__ = ["solve", "plan", "Solution", "ObjectiveResult", "MistakeValue", "StateValue"]
