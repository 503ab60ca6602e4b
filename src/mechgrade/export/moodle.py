"""Moodle grade import CSV (Grades > Import > CSV file).

Moodle's CSV import reads the layout of its own grades export and lets the teacher map columns
on the preview page: map the user by ``Email address`` -> *Email address* or ``ID number`` ->
*ID number*, the grade column to the grade item and the feedback column to *Feedback for* that
item. Moodle compares emails case-sensitively, so they are written exactly as the roster has
them.

What the importer does decides what is written:

* one row whose user key is blank or unknown aborts the whole import, so rows without a key,
  and (with a roster) students not in the roster, go to ``<name>.unmatched.csv`` instead
  (:mod:`mechgrade.export.unmatched`);
* feedback without a grade clears the grade, so a row whose grade is blank (a
  ``not_evaluated`` student, or ``--missing blank``) is held back there too;
* feedback is stored as Moodle-formatted HTML and cleaned, so it is HTML-escaped: a student's
  ``<script>`` shows as text.

Columns: the user key chosen by ``options.moodle_key`` first, then the other key, ``First
name``, ``Last name`` (for the preview; Moodle matches by the key only), then ``<title> (Real)``
and ``<title> (Feedback)`` (Moodle's own export names; with a Moodle roster whose grade column
matches the title, that column's name is reused).
"""

from __future__ import annotations

import html
import os
import re

from ..grade.results import GradeReport, StudentResult
from ..roster import Roster, RosterStudent
from .cells import format_points, write_csv
from .common import (answers_by_objective, conflict_reason, has_submission,
                     no_submission_warnings, objective_label, score_cell)
from .matching import Pair, identity_value, match_roster
from .options import ExportOptions
from .unmatched import HeldBack, held_back, write_unmatched

_REMEDY = ("enter those grades in Moodle by hand, or export again with --roster set to the "
           "grades exported from Moodle")
_KEY_NAMES = {"email": "Email address", "idnumber": "ID number"}

_GRADE_COLUMN = re.compile(r"(?:[^:]+:\s*)?(?P<title>.*?)\s*\((?:Real|Points|Percentage|Letter)\)")


def export_moodle(report: GradeReport, out_path: str | os.PathLike, *,
                  roster: Roster | None = None,
                  options: ExportOptions = ExportOptions()) -> tuple[str, ...]:
    """Write a Moodle grade import CSV (see module doc); return the warnings to show."""
    key = ("Email address", "ID number") if options.moodle_key == "email" \
        else ("ID number", "Email address")
    grade, feedback = moodle_columns(report, roster)
    rows: list[list[object]] = [[*key, "First name", "Last name", grade, feedback]]
    held: list[HeldBack] = []
    match = match_roster(report, roster)
    for pair in match.pairs:
        email, number = _keys(pair)
        first, last = moodle_names(pair.roster, pair.result)
        ids = (email, number) if options.moodle_key == "email" else (number, email)
        score = score_cell(pair.result, options)
        reason = _hold_back_reason(pair, roster, ids[0], score, options)
        if reason:
            held.append(held_back(pair, score, reason))
            continue
        rows.append([*ids, first, last, score,
                     html.escape(feedback_text(report, pair.result), quote=False)])
    write_csv(out_path, rows, excel_bom=options.excel_bom)
    # With --missing blank, those students are held back (no grade), not written.
    warnings = list(no_submission_warnings(match, options)) if options.missing == "zero" else []
    if (roster is None or roster.format != "moodle") and len(rows) > 1:
        warnings.append(f"{out_path} was written without the grades exported from Moodle as "
                        f"--roster, so its {_KEY_NAMES[options.moodle_key]} values are "
                        "unchecked: Moodle aborts the whole import if one of them is not a "
                        "Moodle user")
    return (*warnings, *write_unmatched(out_path, held, "Moodle", _REMEDY))


def _hold_back_reason(pair: Pair, roster: Roster | None, key: str, score: float | str,
                      options: ExportOptions) -> str:
    """Why a row must stay out of the Moodle import file, or ``""``."""
    conflict = conflict_reason(pair.result)
    if conflict is not None:
        return conflict
    if roster is not None and pair.roster is None:
        return "not in the roster"
    if not key:
        return (f"no {_KEY_NAMES[options.moodle_key]} to match the Moodle user by "
                "(one unknown user aborts the whole Moodle import)")
    if score == "":
        why = "not evaluated: mechgrade failed on this student (see the internal errors)" \
            if pair.result is not None and pair.result.status == "not_evaluated" \
            else "no submission and --missing blank"
        return f"no grade ({why}); Moodle clears the grade of a row imported with feedback only"
    return ""


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


def _keys(pair: Pair) -> tuple[str, str]:
    """(email, ID number) of a row."""
    student, result = pair.roster, pair.result
    if student is not None:
        number = student.sis_user_id or ("" if student.id == student.email else student.id)
        return student.email, number
    assert result is not None  # a row has a roster student, a result or both
    email = identity_value(result, "email") or (result.id if "@" in result.id else "")
    return email, identity_value(result, "sis_user_id")


def moodle_names(student: RosterStudent | None, result: StudentResult | None
                 ) -> tuple[str, str]:
    """(First name, Last name): a Moodle roster's own columns, or a name written "Last, First"
    split at its comma (Canvas writes names so); any other name is not split (no rule tells
    where "Mary Ann Smith" splits) and goes whole into First name.

    >>> moodle_names(RosterStudent("1", "Smith (TA), John",
    ...                            columns=(("Student", "Smith (TA), John"),)), None)
    ('John', 'Smith (TA)')
    >>> moodle_names(RosterStudent("2", "Mary Ann Smith"), None)
    ('Mary Ann Smith', '')
    """
    if student is not None:
        columns, whole = student.columns, student.name
    else:
        assert result is not None  # a row has a roster student, a result or both
        columns, whole = result.identity, result.name
    cols = {k.strip().lower(): v for k, v in columns}
    if "first name" in cols and "last name" in cols:
        return cols["first name"], cols["last name"]
    name = cols.get("student") or whole
    if name.count(",") == 1:
        last, first = (part.strip() for part in name.split(","))
        if first and last:
            return first, last
    return name.strip(), ""
