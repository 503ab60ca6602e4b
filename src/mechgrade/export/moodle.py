"""Moodle grade import CSV (Grades > Import > CSV file).

Moodle's CSV import reads the layout of its own grades export and lets the teacher map columns
on the preview page: map the user by ``Email address`` -> *Email address* or ``ID number`` ->
*ID number*, the grade column to the grade item and the feedback column to *Feedback for* that
item. Moodle compares emails case-sensitively, so they are written exactly as the roster has
them. Importing feedback without its grade clears the grade, so both are always written.

Columns: the user key chosen by ``options.moodle_key`` first, then the other identity columns,
then ``<title> (Real)`` and ``<title> (Feedback)`` (Moodle's own export names; with a Moodle
roster whose grade column matches the title, that column's name is reused).
"""

from __future__ import annotations

import os
import re

from ..grade.results import GradeReport, StudentResult
from ..roster import Roster, RosterStudent
from .cells import format_points, write_csv
from .common import answers_by_objective, has_submission, objective_label, score_cell
from .matching import identity_value, match_roster
from .options import ExportOptions

_GRADE_COLUMN = re.compile(r"(?:[^:]+:\s*)?(?P<title>.*?)\s*\((?:Real|Points|Percentage|Letter)\)")


def export_moodle(report: GradeReport, out_path: str | os.PathLike, *,
                  roster: Roster | None = None, options: ExportOptions = ExportOptions()) -> None:
    """Write a Moodle grade import CSV (see module doc) for every roster student and result."""
    key = ("Email address", "ID number") if options.moodle_key == "email" \
        else ("ID number", "Email address")
    grade, feedback = moodle_columns(report, roster)
    rows: list[list[object]] = [[*key, "First name", "Last name", grade, feedback]]
    for pair in match_roster(report, roster).pairs:
        email, number, first, last = _identity(pair.roster, pair.result)
        ids = (email, number) if options.moodle_key == "email" else (number, email)
        rows.append([*ids, first, last, score_cell(pair.result, options),
                     feedback_text(report, pair.result)])
    write_csv(out_path, rows, excel_bom=options.excel_bom)


def moodle_columns(report: GradeReport, roster: Roster | None) -> tuple[str, str]:
    """The grade and feedback column names.

    >>> from mechgrade.grade.results import AssignmentInfo
    >>> moodle_columns(GradeReport(AssignmentInfo("hw1", "Homework 1"), ()), None)
    ('Homework 1 (Real)', 'Homework 1 (Feedback)')
    """
    title = report.assignment.title.strip()
    if roster is not None and roster.format == "moodle":
        for column in roster.header:
            found = _GRADE_COLUMN.fullmatch(column.strip())
            if found and found["title"].casefold() == title.casefold():
                stem = column.strip()[:column.strip().rindex("(")].rstrip()
                return column, f"{stem} (Feedback)"
    return f"{title} (Real)", f"{title} (Feedback)"


def feedback_text(report: GradeReport, result: StudentResult | None) -> str:
    """Plain-text feedback: one line per objective with verdict, points and diagnosis."""
    if result is None:
        return "No submission received."
    lines = list(result.messages)
    if not has_submission(result):
        return "\n".join(lines or ["No submission received."])
    for objective, answer in answers_by_objective(report, result):
        line = (f"{objective_label(objective)}: {answer.verdict.replace('_', ' ')} "
                f"{format_points(answer.points)}/{format_points(answer.max_points)}")
        detail = answer.diagnosis or answer.feedback
        lines.append(f"{line} ({detail})" if detail else line)
    return "\n".join(lines)


def _identity(student: RosterStudent | None, result: StudentResult | None
              ) -> tuple[str, str, str, str]:
    if student is not None:
        cols = {k.lower(): v for k, v in student.columns}
        first, last = cols.get("first name"), cols.get("last name")
        if first is None or last is None:
            first, _, last = student.name.partition(" ")
        number = student.sis_user_id or ("" if student.id == student.email else student.id)
        return student.email, number, first, last
    assert result is not None
    first, _, last = result.name.partition(" ")
    email = identity_value(result, "email") or (result.id if "@" in result.id else "")
    return email, identity_value(result, "sis_user_id"), first, last
