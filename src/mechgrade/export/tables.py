"""mechgrade's own tables: ``grades.csv`` (one row per student) and ``results.csv`` (one row per
student and objective).

``grades.csv`` columns: ``id,name,status,<problem/objective>...,total,max``. ``results.csv``
columns: ``student,name,problem,objective,answer,verdict,points,max_points,diagnosis``, then
``seed,givens`` when students have their own variants, then ``feedback`` when the assignment
grades free-body diagrams or equations of motion. Roster
students without a submission get a row (status ``missing``); results not in the roster follow.
"""

from __future__ import annotations

import os

from ..grade.results import GradeReport, Status, StudentResult, derivation_objective
from ..roster import Roster, RosterStudent
from .cells import write_csv
from .common import (answers_by_objective, has_submission, max_score, no_submission_warnings,
                     not_in_roster_warnings, objective_label, score_cell)
from .matching import match_roster
from .options import ExportOptions

GRADES_FIXED = ("id", "name", "status")
LONG_HEADER = ("student", "name", "problem", "objective", "answer", "verdict", "points",
               "max_points", "diagnosis")


def export_grades_csv(report: GradeReport, out_path: str | os.PathLike, *,
                      roster: Roster | None = None,
                      options: ExportOptions = ExportOptions()) -> tuple[str, ...]:
    """Write ``grades.csv``: per-objective points and the total of every student."""
    rows: list[list[object]] = [[*GRADES_FIXED, *(objective_label(o) for o in report.objectives),
                                 "total", "max"]]
    total = max_score(report)
    match = match_roster(report, roster)
    for pair in match.pairs:
        ident, name = _who(pair.roster, pair.result)
        status = pair.result.status if pair.result is not None else Status.MISSING
        points: list[float | str]
        if _points_shown(pair.result):
            points = [a.points for _, a in answers_by_objective(report, pair.result)]
            points = points[:len(report.objectives)]
        else:
            points = [score_cell(pair.result, options)] * len(report.objectives)
        rows.append([ident, name, status, *points, score_cell(pair.result, options), total])
    write_csv(out_path, rows, excel_bom=options.excel_bom)
    return _roster_warnings(match, roster, options)


def export_long_csv(report: GradeReport, out_path: str | os.PathLike, *,
                    roster: Roster | None = None,
                    options: ExportOptions = ExportOptions()) -> tuple[str, ...]:
    """Write ``results.csv``: one row per student and objective, with answer and diagnosis."""
    # Variants add each student's seed and own givens (of the row's problem); a graded
    # derivation, what the feedback says (which loads, which equation and load).
    variants = any(student.variant for student in report.students)
    derivation = any(derivation_objective(o.objective) for o in report.objectives)
    rows: list[list[object]] = [[*LONG_HEADER, *(["seed", "givens"] if variants else []),
                                 *(["feedback"] if derivation else [])]]
    match = match_roster(report, roster)
    for pair in match.pairs:
        ident, name = _who(pair.roster, pair.result)
        variant = pair.result.variant if pair.result is not None else None
        for objective, answer in answers_by_objective(report, pair.result):
            points = answer.points if _points_shown(pair.result) \
                else score_cell(pair.result, options)
            rows.append([ident, name, objective.problem, objective.objective,
                         answer.answer or "", answer.verdict, points, answer.max_points,
                         answer.diagnosis or ""])
            if variants:
                givens = [f"{g.name} = {g.text}" for g in (variant.givens if variant else ())
                          if g.problem == objective.problem]
                rows[-1] += [variant.seed if variant else "", "; ".join(givens)]
            if derivation:
                rows[-1].append(answer.feedback if _points_shown(pair.result) else "")
    write_csv(out_path, rows, excel_bom=options.excel_bom)
    return _roster_warnings(match, roster, options)


def _points_shown(result: StudentResult | None) -> bool:
    """Whether a row shows its points: not without a submission, nor in a roster conflict
    (whose points are no one's: the row's cells are blank)."""
    return has_submission(result) and result.status != Status.CONFLICT


def _who(student: RosterStudent | None, result: StudentResult | None) -> tuple[str, str]:
    if student is not None:
        return student.id, student.name
    assert result is not None
    return result.id, result.name


def _roster_warnings(match, roster: Roster | None, options: ExportOptions) -> tuple[str, ...]:
    if roster is None:
        return ()
    return (*not_in_roster_warnings(match), *no_submission_warnings(match, options))
