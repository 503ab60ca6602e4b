"""Problem specs: load and validate YAML problem files into frozen dataclasses."""

from .load import load_problem, load_problem_text, problem_schema
from .model import Problem

__all__ = ["Problem", "load_problem", "load_problem_text", "problem_schema"]
