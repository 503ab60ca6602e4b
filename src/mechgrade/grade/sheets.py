"""Problem sheets handed to students: plain data for the handout templates (no sympy)."""

from __future__ import annotations

from dataclasses import dataclass

from ..spec.model import ObjectiveKind
from .results import VariantGiven


@dataclass(frozen=True)
class Question:
    """One objective as the student sees it: the answer key (``problem.objective``), the
    prompt, the unit to answer in and what the answer is (a number, components or an
    expression)."""

    key: str
    prompt: str
    unit: str
    kind: ObjectiveKind = ObjectiveKind.SCALAR


@dataclass(frozen=True)
class SheetProblem:
    """One problem of a sheet: its statement with the student's numbers, the givens drawn
    for the student (empty when the problem has no variants), its questions and ``picture``,
    the mechanism with the student's numbers as SVG text (without the motion asked for)."""

    id: str
    title: str
    statement: str
    givens: tuple[VariantGiven, ...]
    questions: tuple[Question, ...]
    picture: str = ""


@dataclass(frozen=True)
class Sheet:
    """One student's problem sheet for an assignment."""

    assignment_id: str
    assignment_title: str
    student_id: str
    student_name: str
    seed: str
    problems: tuple[SheetProblem, ...]
