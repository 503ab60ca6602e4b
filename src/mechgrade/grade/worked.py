"""The worked solutions a grading run's feedback pages show, made once per problem, or once
per variant drawn, never once per student.

Whether pages show them at all is the assignment's rule
(:meth:`~mechgrade.grade.assignment.Assignment.shows_worked_solution`). A student's answer
that matched a generated mistake is tied to the step of the worked solution where that mistake
happens through the diagnosis' code (:data:`mechgrade.grade.diagnose.LABELS`).

>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.grade.assignment import load_assignment
>>> from mechgrade.grade.results import GradeReport, AssignmentInfo
>>> hw = load_assignment(shipped_dir("examples") / "hw1" / "assignment.yaml")
>>> worked = feedback_solutions(hw, GradeReport(AssignmentInfo("hw1", "Homework 1"), (), ()))
>>> [w.problem for w in worked.solutions][:1]
['bowling_3_15_4_pendulum']
>>> worked.code("Coriolis term left out")
'drop_coriolis'
"""

from __future__ import annotations

from dataclasses import dataclass
from datetime import datetime, timezone
from functools import cached_property

from ..solve.worked import WorkedSolution
from ..spec.model import Problem
from .assignment import Assignment
from .results import GradeReport, StudentResult, VariantGiven


@dataclass(frozen=True)
class FeedbackSolutions:
    """Worked solutions for feedback pages: ``solutions`` (the problems' own), ``variants``
    (``(problem, drawn givens, solution)`` for each variant a student was given), and
    ``labels`` (diagnosis label, code) to find where a named mistake happens."""

    solutions: tuple[WorkedSolution, ...]
    variants: tuple[tuple[str, tuple[VariantGiven, ...], WorkedSolution], ...] = ()
    labels: tuple[tuple[str, str], ...] = ()

    def for_student(self, student: StudentResult) -> tuple[WorkedSolution, ...]:
        """The worked solutions of every problem, with the student's own numbers."""
        drawn = student.variant.givens if student.variant else ()
        return tuple(self._by_variant.get(
            (w.problem, tuple(g for g in drawn if g.problem == w.problem)), w)
            for w in self.solutions)

    @cached_property
    def _by_variant(self) -> dict:
        return {(problem, givens): w for problem, givens, w in self.variants}

    @cached_property
    def _codes(self) -> dict[str, str]:  # asked for every answer of every page
        return dict(self.labels)

    def code(self, label: str | None) -> str | None:
        """The code of a generated mistake's diagnosis label (``None`` for any other); of a
        label naming two families that fit equally ("X or Y"), the first's (the nearer).

        >>> FeedbackSolutions((), labels=(("weight left out", "weight_omitted"),
        ...     ("a term or another left out", "other"))).code("weight left out or a term or another left out")
        'weight_omitted'
        """
        codes = self._codes
        if label is None or label in codes:
            return None if label is None else codes[label]
        parts = label.split(" or ")
        return next((codes[" or ".join(parts[:i])] for i in range(1, len(parts))
                     if " or ".join(parts[:i]) in codes and " or ".join(parts[i:]) in codes),
                    None)


def feedback_solutions(assignment: Assignment, report: GradeReport, *,
                       problems: tuple[Problem, ...] | None = None) -> FeedbackSolutions:
    """The worked solution of every problem of ``assignment``, and of every variant the
    students of ``report`` were given (each variant solved once, however many share it)."""
    from ..solve import solve
    from ..solve.worked import worked_solution
    from ..spec import load_problem
    from .diagnose import LABELS
    from .variants import recorded_variant, solve_variant

    if problems is None:
        problems = tuple(load_problem(ref.path) for ref in assignment.problems)
    chosen = {p.id: ref.objectives for p, ref in zip(problems, assignment.problems)}
    solutions = tuple(worked_solution(p, solve(p), chosen[p.id]) for p in problems)
    variants: dict[tuple[str, tuple[VariantGiven, ...]], WorkedSolution] = {}
    for student in report.students:
        for problem in problems:
            if student.variant is None or problem.variants is None:
                continue
            drawn = tuple(g for g in student.variant.givens if g.problem == problem.id)
            if drawn and (problem.id, drawn) not in variants:
                variant = recorded_variant(problem, student.variant.seed, student.id, drawn)
                variants[problem.id, drawn] = worked_solution(
                    problem, solve_variant(problem, variant), chosen[problem.id])
    return FeedbackSolutions(solutions, tuple((p, g, w) for (p, g), w in variants.items()),
                             tuple((label, code) for code, label in LABELS.items()))


def shown_solutions(assignment: Assignment, report: GradeReport,
                    now: datetime | None = None) -> FeedbackSolutions | None:
    """:func:`feedback_solutions` when the assignment's rule shows them at ``now`` (default:
    the present moment), else ``None``."""
    moment = now if now is not None else datetime.now(timezone.utc)
    if not assignment.shows_worked_solution(moment):
        return None
    return feedback_solutions(assignment, report)
