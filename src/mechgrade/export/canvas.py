"""Canvas gradebook import CSV.

Canvas imports a CSV shaped like its own gradebook export: the identity columns
``Student,ID,SIS User ID,SIS Login ID,Section`` then one column per assignment, titled
``Assignment Title (canvas assignment id)``, and an optional second row ``Points Possible``.
Canvas finds the student by ``ID`` (then SIS ids) and the assignment by the id in brackets; a
column without a known id creates a new assignment.

When the roster is a Canvas gradebook export, the file is written back with that export's own
identity columns, one row per roster student, and reuses the roster's column for this
assignment when its title matches (so Canvas updates it instead of creating a new one).
"""

from __future__ import annotations

import os
import re

from ..grade.results import GradeReport, StudentResult
from ..roster import Roster, RosterStudent
from .cells import write_csv
from .common import max_score, score_cell
from .matching import identity_value, match_roster
from .options import ExportOptions

CANVAS_IDENTITY = ("Student", "ID", "SIS User ID", "SIS Login ID", "Section")
_COLUMN = re.compile(r"(?P<title>.*\S)\s*\((?P<id>\d+)\)")


def export_canvas(report: GradeReport, out_path: str | os.PathLike, *,
                  roster: Roster | None = None, options: ExportOptions = ExportOptions()) -> None:
    """Write a Canvas gradebook import CSV (see module doc) for every roster student and result."""
    identity = roster.identity_header if roster is not None and roster.format == "canvas" \
        else CANVAS_IDENTITY
    rows: list[list[object]] = [[*identity, canvas_column(report, roster)]]
    if options.points_possible:
        rows.append(["    Points Possible", *([""] * (len(identity) - 1)), max_score(report)])
    for pair in match_roster(report, roster).pairs:
        cells = _identity_cells(identity, pair.roster, pair.result)
        rows.append([*cells, score_cell(pair.result, options)])
    write_csv(out_path, rows, excel_bom=options.excel_bom)


def canvas_column(report: GradeReport, roster: Roster | None) -> str:
    """The assignment column: the roster's own column for it if any, else ``Title (id)``.

    >>> from mechgrade.grade.results import AssignmentInfo
    >>> canvas_column(GradeReport(AssignmentInfo("hw1", "Homework 1"), ()), None)
    'Homework 1 (hw1)'
    """
    title, ident = report.assignment.title.strip(), report.assignment.id.strip()
    if roster is not None and roster.format == "canvas":
        for column in roster.header:
            found = _COLUMN.fullmatch(column.strip())
            if found and (found["title"].casefold() == title.casefold() or found["id"] == ident):
                return column
    return f"{title} ({ident})"


def _identity_cells(identity: tuple[str, ...], student: RosterStudent | None,
                    result: StudentResult | None) -> list[str]:
    if student is not None and student.columns and \
            tuple(name for name, _ in student.columns) == identity:
        return [value for _, value in student.columns]
    if student is not None:
        known = {"student": student.name, "id": student.id, "sis user id": student.sis_user_id,
                 "sis login id": student.sis_login_id, "section": student.section}
        return [known.get(name.lower(), "") for name in identity]
    assert result is not None
    own = {k.strip().lower(): v for k, v in result.identity}
    known = {"student": result.name,
             "id": identity_value(result, "canvas_id") or result.id,
             "sis user id": identity_value(result, "sis_user_id"),
             "sis login id": identity_value(result, "sis_login_id"),
             "section": own.get("section", "")}
    return [known.get(name.lower(), own.get(name.lower(), "")) for name in identity]
