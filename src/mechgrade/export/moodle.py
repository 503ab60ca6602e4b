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
  ``<script>`` shows as text; quotes and backslashes are written as entities, since Moodle's
  ``fgetcsv`` treats a backslash as an escape character (:func:`moodle_html`);
* with the grades exported from Moodle as roster, each student's grade is decided against
  the roster's (:func:`mechgrade.export.changes.decide`; a grade kept leaves the row out, so
  Moodle keeps grade and feedback), and the roster's ``Last downloaded from this course``
  column is kept, so Moodle refuses grades changed since that export;
* a grade above 100 aborts the import unless the site allows it, and one above the grade
  item's maximum is cut to it without a word: both are warned of (``--scale-to`` scales).

Columns: the user key chosen by ``options.moodle_key`` first, then the other key, ``First
name``, ``Last name`` (for the preview; Moodle matches by the key only), then ``<title> (Real)``
and ``<title> (Feedback)`` (Moodle's own export names; with a Moodle roster whose grade column
matches the title, that column's name is reused).
"""

from __future__ import annotations

import html
import os
import re
import time

from ..grade.results import GradeReport, ObjectiveInfo, Status, StudentResult
from ..roster import Roster, RosterFormat, RosterStudent
from .cells import format_points, safe_cell, write_csv
from .changes import Change, ChangeKind, decide, not_compared_warning, report_changes
from .common import (answers_by_objective, conflict_reason, has_submission, lms_points,
                     lms_score, no_submission_warnings, objective_label)
from .matching import Pair, identity_value, match_roster
from .options import ExportOptions, MissingGrade, MoodleKey
from .unmatched import HeldBack, held_back, write_unmatched

_REMEDY = ("enter those grades in Moodle by hand, or export again with --roster set to the "
           "grades exported from Moodle")
_KEY_NAMES = {MoodleKey.EMAIL: "Email address", MoodleKey.IDNUMBER: "ID number"}

_GRADE_COLUMN = re.compile(r"(?:[^:]+:\s*)?(?P<title>.*?)\s*\((?:Real|Points|Percentage|Letter)\)")


def export_moodle(report: GradeReport, out_path: str | os.PathLike, *,
                  roster: Roster | None = None,
                  options: ExportOptions = ExportOptions()) -> tuple[str, ...]:
    """Write a Moodle grade import CSV (see module doc); return the warnings to show."""
    key = ("Email address", "ID number") if options.moodle_key is MoodleKey.EMAIL \
        else ("ID number", "Email address")
    grade, feedback = moodle_columns(report, roster)
    moodle_roster = roster if roster is not None and roster.format is RosterFormat.MOODLE else None
    downloaded = LAST_DOWNLOADED if moodle_roster is not None and \
        LAST_DOWNLOADED in moodle_roster.header else None
    rows: list[list[object]] = [[*key, "First name", "Last name", grade, feedback,
                                 *([downloaded] if downloaded else [])]]
    held: list[HeldBack] = []
    changes: list[Change] = []
    match = match_roster(report, roster)
    for pair in match.pairs:
        email, number = _keys(pair)
        first, last = moodle_names(pair.roster, pair.result)
        ids = (email, number) if options.moodle_key is MoodleKey.EMAIL else (number, email)
        score = lms_score(pair.result, report, options)
        existing = pair.roster.cell(grade) if moodle_roster is not None and \
            pair.roster is not None else None
        decision = decide(existing, score, options.replace_existing, "Moodle")
        reason = _hold_back_reason(pair, roster, ids[0], score, options)
        who = pair.roster if pair.roster is not None else pair.result
        assert who is not None  # a pair holds a result, a roster student or both
        if reason and (decision.kind is not ChangeKind.KEPT or conflict_reason(pair.result)):
            held.append(held_back(pair, score, reason))
            continue
        changes.append(Change(who.id, who.name, existing or "", safe_cell(decision.written),
                              decision.kind, decision.reason))
        if decision.kind is ChangeKind.KEPT:
            continue  # a row left out leaves Moodle's grade and feedback as they are
        rows.append([*ids, first, last, decision.written,
                     moodle_html(feedback_text(report, pair.result)),
                     *([pair.roster.cell(downloaded) if pair.roster else ""]
                       if downloaded else [])])
    if not options.dry_run:
        write_csv(out_path, rows, excel_bom=options.excel_bom)
    # With --missing blank, those students are held back (no grade), not written.
    warnings = list(no_submission_warnings(match, options)) \
        if options.missing is MissingGrade.ZERO else []
    if moodle_roster is None and len(rows) > 1:
        warnings.append(f"{out_path} was written without the grades exported from Moodle as "
                        f"--roster, so its {_KEY_NAMES[options.moodle_key]} values are "
                        "unchecked: Moodle aborts the whole import if one of them is not a "
                        "Moodle user")
    if moodle_roster is not None and grade not in moodle_roster.header:
        warnings.append(not_compared_warning(out_path, grade, "Moodle"))
    warnings.extend(_points_warnings(report, options, grade))
    if downloaded and moodle_roster is not None:
        warnings.extend(_downloaded_warnings(moodle_roster, downloaded))
    return (*warnings, *write_unmatched(out_path, held, "Moodle", _REMEDY, options.dry_run),
            *report_changes(out_path, changes, "Moodle", options.dry_run))


LAST_DOWNLOADED = "Last downloaded from this course"
"""The column of a Moodle grades export that makes the import refuse grades changed in Moodle
since the export (``load_data.php``: the ``timeexported`` string and ``gradealreadyupdated``);
kept, with the roster's values, in the import file."""
MOODLE_DEFAULT_LIMIT = 100.0
"""Above this, Moodle aborts the whole import unless the site allows unlimited grades
(``load_data.php``, ``insert_grade_record``: ``gradevaluetoobig``)."""


def moodle_html(text: str) -> str:
    """Feedback as the HTML Moodle stores, read back by Moodle's CSV reader exactly as written.

    Moodle reads the file with PHP's ``fgetcsv``, whose escape character is ``\\``: a
    backslash before a quote (``\\"``), or at the end of a quoted field, makes it split the
    row otherwise (a wrong number of columns aborts the whole import). Quotes and backslashes
    are therefore written as the HTML entities ``&quot;`` and ``&#92;``, which Moodle shows as
    the characters; ``<`` ``>`` ``&`` are escaped so a student's ``<script>`` shows as text.

    >>> moodle_html('read "x\\\\" as <b>')
    'read &quot;x&#92;&quot; as &lt;b&gt;'
    """
    return html.escape(text, quote=True).replace("&#x27;", "'").replace("\\", "&#92;")


def _points_warnings(report: GradeReport, options: ExportOptions, grade: str
                     ) -> list[str]:
    points = lms_points(report, options)
    warnings = []
    if points > MOODLE_DEFAULT_LIMIT:
        warnings.append(f"grades are out of {format_points(points)} points: Moodle refuses the "
                        f"whole import on a grade above {MOODLE_DEFAULT_LIMIT:g} unless the site "
                        "allows unlimited grades (Site administration > Grades > General "
                        f"settings); export with --scale-to {MOODLE_DEFAULT_LIMIT:g} to scale them")
    if options.scale_to is None:
        warnings.append(f"Moodle cuts a grade above the grade item's maximum grade to that "
                        f"maximum without a word: check that {grade!r} is out of "
                        f"{format_points(points)} points in Moodle, or export with --scale-to "
                        "<its maximum grade>")
    return warnings


def _downloaded_warnings(roster: Roster, column: str) -> list[str]:
    """Moodle refuses the whole import when a 'Last downloaded' value is not a time, lies in
    the future or is more than a year old (``invalidgradeexporteddate``)."""
    now = time.time()
    for student in roster.students:
        value = student.cell(column) or ""
        if not value.isdigit() or not now - 366 * 86400 <= int(value) <= now:
            return [f"the grades export's {column!r} of {student.id} is {value!r}: Moodle "
                    "refuses the whole import unless that is a time within the last year; "
                    "export the grades from Moodle again and give that file as --roster"]
    return []


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
            if pair.result is not None and pair.result.status == Status.NOT_EVALUATED \
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
    if roster is not None and roster.format is RosterFormat.MOODLE:
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
        line = (f"{objective_title(objective)}: {answer.verdict.replace('_', ' ')} "
                f"{format_points(answer.points)}/{format_points(answer.max_points)}")
        detail = answer.diagnosis or answer.feedback
        if answer.first_wrong_step and answer.diagnosis:  # the feedback says it otherwise
            detail += f"; the first wrong step: {answer.first_wrong_step}"
        lines.append(f"{line} ({detail})" if detail else line)
    return "\n".join(lines)


def objective_title(objective: ObjectiveInfo) -> str:
    """An objective as students know it: its problem's title and its prompt (the ids
    ``problem/objective`` when the results do not keep the title).

    >>> objective_title(ObjectiveInfo("p1", "v", "Speed of the tip.", 2.0, "A pendulum"))
    'A pendulum, Speed of the tip'
    >>> objective_title(ObjectiveInfo("p1", "v", "Speed of the tip.", 2.0))
    'p1/v'
    """
    if not objective.problem_title:
        return objective_label(objective)
    prompt = objective.prompt.strip().rstrip(".")
    return f"{objective.problem_title}, {prompt}" if prompt else objective.problem_title


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
