"""What several exporters share: a student's score cell and per-objective answers."""

from __future__ import annotations

from typing import TypeGuard

from ..grade.results import (AnswerResult, GradeReport, ObjectiveInfo, Status, StudentResult,
                             Verdict)
from .matching import RosterMatch
from .options import ExportOptions, MissingGrade


def has_submission(result: StudentResult | None) -> TypeGuard[StudentResult]:
    return result is not None and result.status != Status.MISSING


def score_cell(result: StudentResult | None, options: ExportOptions) -> float | str:
    """The total to write: the score, or 0 / blank (``options.missing``) with no submission.

    A student whose grading failed through a fault of mechgrade's (``not_evaluated``) or who
    is in a roster conflict (``conflict``) gets a blank cell, which every LMS reads as "no
    score": a bug or a guess never becomes a grade.
    """
    if not has_submission(result):
        return 0.0 if options.missing is MissingGrade.ZERO else ""
    if result.status in (Status.NOT_EVALUATED, Status.CONFLICT):
        return ""
    return result.score


def lms_points(report: GradeReport, options: ExportOptions) -> float:
    """The assignment's points in the LMS: ``options.scale_to``, else the assignment's own."""
    return options.scale_to if options.scale_to is not None else max_score(report)


def lms_score(result: StudentResult | None, report: GradeReport,
              options: ExportOptions) -> float | str:
    """:func:`score_cell` scaled to :func:`lms_points` (``--scale-to``).

    >>> from mechgrade.grade.results import AssignmentInfo
    >>> report = GradeReport(AssignmentInfo("hw", "HW"), (ObjectiveInfo("p", "v", "", 19.0),))
    >>> s = StudentResult("a", "A", "graded", 9.5, 19.0)
    >>> lms_score(s, report, ExportOptions(scale_to=100))
    50.0
    """
    cell = score_cell(result, options)
    total = max_score(report)
    if options.scale_to is None or cell == "" or not total:
        return cell
    return float(cell) * options.scale_to / total


def conflict_reason(result: StudentResult | None) -> str | None:
    """Why a row is kept out of an import file: its student is in a roster conflict (the
    result's first message says which); ``None`` for any other row."""
    if result is None or result.status != Status.CONFLICT:
        return None
    return result.messages[0] if result.messages else "roster conflict"


def max_score(report: GradeReport) -> float:
    """The points possible: the sum of the objectives, or a student's ``max_score``."""
    total = sum(o.max_points for o in report.objectives)
    if total or not report.students:
        return total
    return max(s.max_score for s in report.students)


def answers_by_objective(report: GradeReport, result: StudentResult | None
                         ) -> list[tuple[ObjectiveInfo, AnswerResult]]:
    """One answer per objective of the assignment, in objective order.

    An objective the result has no answer for counts as a missing answer worth 0, so no
    objective disappears from an export; answers to objectives the report does not list
    (should not happen) follow at the end.
    """
    answers = {} if result is None else {(a.problem, a.objective): a for a in result.answers}
    out = []
    for objective in report.objectives:
        key = (objective.problem, objective.objective)
        answer = answers.pop(key, None) or AnswerResult(
            objective.problem, objective.objective, None, Verdict.MISSING, 0.0,
            objective.max_points)
        out.append((objective, answer))
    for answer in answers.values():
        out.append((ObjectiveInfo(answer.problem, answer.objective, "", answer.max_points),
                    answer))
    return out


def objective_label(objective: ObjectiveInfo) -> str:
    """The column name of an objective: ``problem/objective``."""
    return f"{objective.problem}/{objective.objective}"


def not_in_roster_warnings(match: RosterMatch) -> tuple[str, ...]:
    """One warning per result no roster student claimed, written after the roster students."""
    return tuple(f"{r.id} ({r.name}) is not in the roster; written after the roster students"
                 for r in match.not_in_roster if r.status != Status.CONFLICT)


def no_submission_warnings(match: RosterMatch, options: ExportOptions) -> tuple[str, ...]:
    """One warning per roster student without a submission, saying what grade they get."""
    written = "0" if options.missing is MissingGrade.ZERO else "a blank grade"
    return tuple(f"{s.id} ({s.name}) has no submission; written with {written}"
                 for s in match.no_submission)
