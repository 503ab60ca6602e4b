"""Canvas gradebook import CSV.

Canvas imports a CSV shaped like its own gradebook export: the identity columns
``Student,ID,SIS User ID,SIS Login ID,Section`` then one column per assignment, titled
``Assignment Title (canvas assignment id)``, and an optional second row ``Points Possible``.
Canvas finds the assignment by the id in brackets (without one, by exact title; a title it does
not know creates a new assignment), and the student by ``ID`` read as an integer, then the SIS
ids, then the name.

So the file holds only rows Canvas can match: a row's ``ID`` must come from Canvas (a Canvas
gradebook export given as roster, now or when grading); without one, a row with a SIS id is
written with ``ID`` blank; every other row (a student not in the roster, a folder name where
Canvas expects its user id: ``"000421"`` is read as user 421) goes to
``<name>.unmatched.csv`` beside it (:mod:`mechgrade.export.unmatched`).

Canvas replaces every cell that differs from its grade, and applies the ``Points Possible``
row to existing assignments: with a Canvas gradebook export as roster, each cell is decided
against the student's cell in the roster (:func:`mechgrade.export.changes.decide`: ``EX``,
``N/A`` and grades already there are kept unless ``--replace-existing``), the roster's
``Points Possible`` is written back unchanged, and the changes are listed in
``<name>.changes.csv``. The layout ``LastName,FirstName,ID,...`` of a roster is written back
as it is.
"""

from __future__ import annotations

import os
import re

from ..errors import ExportError, Location
from ..grade.results import GradeReport, StudentResult
from ..roster import Roster, RosterFormat, header_format
from .cells import format_points, safe_cell, write_csv
from .changes import Change, decide, not_compared_warning, report_changes
from .common import conflict_reason, lms_points, lms_score, no_submission_warnings
from .matching import Pair, identity_value, match_roster
from .options import ExportOptions
from .unmatched import HeldBack, held_back, write_unmatched

CANVAS_IDENTITY = ("Student", "ID", "SIS User ID", "SIS Login ID", "Section")
_COLUMN = re.compile(r"(?P<title>.*\S)\s*\((?P<id>\d+)\)")
# Canvas's importer skips a column whose title holds one of its totals' names
_IGNORED = re.compile(r"\b(current|final|override|unposted)\s+(score|points|grade|status)\b",
                      re.IGNORECASE)
_REMEDY = ("enter those grades in Canvas by hand, or export again with --roster set to the "
           "gradebook exported from Canvas")


def export_canvas(report: GradeReport, out_path: str | os.PathLike, *,
                  roster: Roster | None = None,
                  options: ExportOptions = ExportOptions()) -> tuple[str, ...]:
    """Write a Canvas gradebook import CSV (see module doc); return the warnings to show."""
    canvas_roster = roster if roster is not None and roster.format is RosterFormat.CANVAS else None
    identity = canvas_roster.identity_header if canvas_roster is not None else CANVAS_IDENTITY
    column = canvas_column(report, roster, options.canvas_assignment)
    ignored = _IGNORED.search(column)
    if ignored:
        raise ExportError(f"expected an assignment column Canvas imports, found {column!r}: "
                          f"Canvas ignores a column whose title holds {ignored[0]!r}; rename the "
                          "assignment in Canvas or name another with --canvas-assignment",
                          where=Location(field="canvas_assignment"))
    if options.excel_bom and identity[0] == "LastName":
        raise ExportError("expected no byte order mark with the 'LastName,FirstName' layout: "
                          "Canvas recognises that header only when its first cell is exactly "
                          "'LastName', and a byte order mark is part of that cell; export "
                          "without --excel-bom", where=Location(field="excel_bom"))
    warnings: list[str] = []
    rows: list[list[object]] = [[*identity, column]]
    if options.points_possible:
        possible = _points_possible(report, canvas_roster, column, options, warnings)
        rows.append(["    Points Possible", *([""] * (len(identity) - 1)), possible])
    held: list[HeldBack] = []
    changes: list[Change] = []
    match = match_roster(report, roster)
    for pair in match.pairs:
        cells = conflict_reason(pair.result) or _identity_cells(identity, pair, roster)
        score = lms_score(pair.result, report, options)
        if isinstance(cells, str):
            held.append(held_back(pair, score, cells))
            continue
        existing = pair.roster.cell(column) if canvas_roster is not None and \
            pair.roster is not None else None
        decision = decide(existing, score, options.replace_existing, "Canvas")
        rows.append([*cells, decision.written])
        who = pair.roster if pair.roster is not None else pair.result
        assert who is not None  # a pair holds a result, a roster student or both
        changes.append(Change(who.id, who.name, existing or "", safe_cell(decision.written),
                              decision.kind, decision.reason))
    if not options.dry_run:
        write_csv(out_path, rows, excel_bom=options.excel_bom)
    warnings.extend(no_submission_warnings(match, options))
    if not _COLUMN.fullmatch(column):
        warnings.append(f"the Canvas assignment column {column!r} has no Canvas assignment id: "
                        "Canvas fills the assignment of exactly that title or creates a new "
                        "one; name it with --canvas-assignment (its id, as in 'Title (12345)')")
    if canvas_roster is not None and column not in canvas_roster.header:
        warnings.append(not_compared_warning(out_path, column, "Canvas"))
    if canvas_roster is None and len(rows) > 1 + options.points_possible:
        warnings.append(f"{out_path} was not compared with the grades already in Canvas (no "
                        "gradebook exported from Canvas as --roster): Canvas replaces every "
                        "grade that differs, excused (EX) and hand-entered ones included")
    return (*warnings, *write_unmatched(out_path, held, "Canvas", _REMEDY, options.dry_run),
            *report_changes(out_path, changes, "Canvas", options.dry_run))


def _points_possible(report: GradeReport, canvas_roster: Roster | None, column: str,
                     options: ExportOptions, warnings: list[str]) -> float | str:
    """The ``Points Possible`` cell: the roster's own (Canvas applies this row to existing
    assignments too, so a different number would change the assignment's points), else the
    assignment's points (:func:`lms_points`). A column the roster marks read only is refused:
    Canvas drops it from the import (``readonly_assignment?``)."""
    points = lms_points(report, options)
    if canvas_roster is None:
        return points
    possible = dict(canvas_roster.points_possible).get(column, "")
    if re.search(r"read\s+only", possible):
        raise ExportError(f"expected an assignment column Canvas imports, found {column!r} "
                          f"marked {possible!r} in the roster's Points Possible row: Canvas drops "
                          "that column from the import; choose another with --canvas-assignment",
                          where=Location(field="canvas_assignment"))
    try:
        canvas_points = float(possible.replace(",", "."))
    except ValueError:
        return points
    if round(canvas_points, 2) != round(points, 2):
        warnings.append(f"Canvas's {column!r} is worth {possible} points and mechgrade's grades "
                        f"are out of {format_points(points)}: they are written as they are and "
                        f"Canvas's points are kept; export with --scale-to {possible} to scale "
                        "them, or change the assignment's points in Canvas")
    return possible


def assignment_columns(roster: Roster) -> tuple[str, ...]:
    """The assignment columns of a Canvas gradebook export: those titled ``Title (id)``.

    Totals (``Current Score``...) carry no id and are no assignments.
    """
    identity = set(roster.identity_header)
    return tuple(c for c in roster.header if c not in identity and _COLUMN.fullmatch(c.strip()))


def canvas_column(report: GradeReport, roster: Roster | None, wanted: str | None = None) -> str:
    """The title of the assignment column to fill.

    ``wanted`` (``--canvas-assignment``) names it by column title, title or numeric Canvas id;
    with a Canvas gradebook export as roster it must be one of the export's assignment columns
    (:func:`assignment_columns`). Without ``wanted``, the roster's column is the one whose title
    (case aside) or id equals the assignment's, else the only assignment column of the roster;
    anything else is ambiguous and an error listing the candidates. Without a Canvas roster the
    column is ``wanted`` (an id gets the assignment title in front) or the assignment title.

    >>> from mechgrade.grade.results import AssignmentInfo
    >>> report = GradeReport(AssignmentInfo("hw1", "Homework 1"), ())
    >>> canvas_column(report, None), canvas_column(report, None, "40211")
    ('Homework 1', 'Homework 1 (40211)')
    """
    title, ident = report.assignment.title.strip(), report.assignment.id.strip()
    candidates = assignment_columns(roster) if roster is not None and \
        roster.format is RosterFormat.CANVAS else ()
    if wanted is not None and wanted.strip():
        wanted = wanted.strip()
        if not candidates:
            return f"{title} ({wanted})" if wanted.isdigit() else wanted
        hits = [c for c in candidates if _names(c, wanted)]
        if len(hits) == 1:
            return hits[0]
        raise ExportError(f"expected one of the roster's assignment columns "
                          f"({_listing(candidates)}) or its Canvas id, found {wanted!r}"
                          + (f", which names {len(hits)} of them" if hits else ""),
                          where=Location(field="canvas_assignment"))
    if not candidates:
        return title
    hits = [c for c in candidates if _names(c, title) or _names(c, ident)]
    if len(hits) == 1:
        return hits[0]
    if not hits and len(candidates) == 1:
        return candidates[0]
    found = hits or candidates
    raise ExportError(f"expected one Canvas assignment column for {title!r} in the roster, "
                      f"found {len(found)}: {_listing(found)}; choose one with "
                      "--canvas-assignment (its title or id)",
                      where=Location(field="canvas_assignment"))


def _names(column: str, wanted: str) -> bool:
    found = _COLUMN.fullmatch(column.strip())
    return column.strip() == wanted or (found is not None and (
        found["id"] == wanted or found["title"].casefold() == wanted.casefold()))


def _listing(columns) -> str:
    return ", ".join(repr(c) for c in columns)


def _identity_cells(identity: tuple[str, ...], pair: Pair, roster: Roster | None
                    ) -> list[str] | str:
    """The identity cells of a row, or why Canvas could not match it."""
    student, result = pair.roster, pair.result
    if student is None and roster is not None:
        return "not in the roster"
    if student is not None and roster is not None and roster.format is RosterFormat.CANVAS:
        if tuple(name for name, _ in student.columns) == identity:
            return [value for _, value in student.columns]
        known = {"student": student.name, "id": student.id, "sis user id": student.sis_user_id,
                 "sis login id": student.sis_login_id, "section": student.section}
        return [known.get(name.lower(), "") for name in identity]
    canvas = _canvas_identity(result)
    sis_user = canvas.get("sis user id") or (student.sis_user_id if student else "") \
        or (identity_value(result, "sis_user_id") if result else "")
    sis_login = canvas.get("sis login id") or (student.sis_login_id if student else "") \
        or (identity_value(result, "sis_login_id") if result else "")
    if not (canvas.get("id") or sis_user or sis_login):
        return "no Canvas user ID or SIS id to match it by (not from a Canvas gradebook export)"
    who = student if student is not None else result
    assert who is not None  # a row has a roster student, a result or both
    known = {"student": canvas.get("student") or who.name,
             "id": canvas.get("id", ""), "sis user id": sis_user, "sis login id": sis_login,
             "section": canvas.get("section") or (student.section if student else "")}
    return [known.get(name.lower(), "") for name in identity]


def _canvas_identity(result: StudentResult | None) -> dict[str, str]:
    """A result's identity columns (lower-cased names) if they came from a Canvas gradebook
    export when grading; its ``ID`` is then a Canvas user id."""
    if result is None or \
            header_format(tuple(k for k, _ in result.identity)) is not RosterFormat.CANVAS:
        return {}
    return {k.strip().lower(): v for k, v in result.identity}

