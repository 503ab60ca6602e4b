"""What an LMS import would change, decided against the grades already in the LMS.

An LMS import replaces every cell that differs from the grade it holds (Canvas compares at two
decimals, ``EX`` and blank included: ``app/models/gradebook_importer.rb``,
``no_change_to_value?``; Moodle replaces the grade, and a blank clears it:
``grade/import/csv/classes/load_data.php``, ``update_grade_item``). With the gradebook exported
from the LMS as roster, each student's cell is compared with mechgrade's grade before anything
is written, by one rule (:func:`decide`):

* no grade in the LMS (blank or ``-``): mechgrade's grade is written (``new``);
* the same grade at two decimals: the LMS's text is written back (``unchanged``);
* ``EX`` (excused), ``N/A`` (not assigned to the student) or a grade when mechgrade has none
  (no submission with ``--missing blank``, or not evaluated): the LMS's cell is kept (``kept``);
* another grade, typed by hand or imported before: kept, unless ``--replace-existing`` asks to
  replace it (``changed``).

Every row that is new, changed or kept is listed in ``<name>.changes.csv`` beside the import
file, with the reason; ``--dry-run`` prints the same list and writes nothing.

>>> decide("", 7.0, replace_existing=False).kind, decide("EX", 7.0, False).kind
(<ChangeKind.NEW: 'new'>, <ChangeKind.KEPT: 'kept'>)
>>> decide("6.999", 7.0, False).kind, decide("5", 7.0, False).written
(<ChangeKind.UNCHANGED: 'unchanged'>, '5')
"""

from __future__ import annotations

import enum
import os
from dataclasses import dataclass
from pathlib import Path

from .cells import format_points, write_csv
from .unmatched import remove_stale


class Notice(str):
    """A line for the user that is no warning (the CLI prints it without ``warning:``)."""


class ChangeKind(enum.Enum):
    NEW = "new"
    CHANGED = "changed"
    KEPT = "kept"
    UNCHANGED = "unchanged"


@dataclass(frozen=True)
class Decision:
    """What is written in a student's cell, and how it compares with the LMS's."""

    written: float | str
    kind: ChangeKind
    reason: str = ""


@dataclass(frozen=True)
class Change:
    """One row of ``<name>.changes.csv``."""

    id: str
    name: str
    before: str
    written: str
    kind: ChangeKind
    reason: str


CHANGES_HEADER = ("id", "name", "in_lms", "written", "change", "reason")
NO_GRADE = ("", "-")
EXCUSED = "EX"
NOT_ASSIGNED = "N/A"


def decide(existing: str | None, new: float | str, replace_existing: bool,
           lms: str = "the LMS") -> Decision:
    """The cell to write for a student whose LMS cell is ``existing`` (``None``: no LMS cell
    to compare with) when mechgrade's grade is ``new`` (a number, or ``""`` for none).

    >>> decide("8", "", False)
    Decision(written='8', kind=<ChangeKind.KEPT: 'kept'>, reason='mechgrade has no grade for this student; the LMS keeps 8')
    >>> decide("5", 7.0, True).kind
    <ChangeKind.CHANGED: 'changed'>
    """
    if existing is None:
        return Decision(new, ChangeKind.NEW if new != "" else ChangeKind.UNCHANGED)
    before = existing.strip()
    if before.upper() == EXCUSED:
        return Decision(before, ChangeKind.KEPT if new != "" else ChangeKind.UNCHANGED,
                        f"excused in {lms} (EX); to grade this student, remove the excuse in "
                        f"{lms} and export again")
    if before.upper() == NOT_ASSIGNED:
        return Decision(before, ChangeKind.KEPT if new != "" else ChangeKind.UNCHANGED,
                        f"the assignment is not assigned to this student in {lms} (N/A)")
    if before in NO_GRADE:
        return Decision(new, ChangeKind.NEW if new != "" else ChangeKind.UNCHANGED)
    if new == "":
        return Decision(before, ChangeKind.KEPT,
                        f"mechgrade has no grade for this student; {lms} keeps {before}")
    if _same(before, float(new)):
        return Decision(before, ChangeKind.UNCHANGED)
    if replace_existing:
        return Decision(new, ChangeKind.CHANGED,
                        f"{lms} had {before}; replaced (--replace-existing)")
    return Decision(before, ChangeKind.KEPT,
                    f"already graded in {lms} ({before}, mechgrade {format_points(float(new))}); "
                    "export with --replace-existing to replace it")


def _same(before: str, new: float) -> bool:
    """Whether the LMS's text is ``new`` at two decimals (as Canvas compares)."""
    try:
        return round(float(before.replace(",", ".")), 2) == round(new, 2)
    except ValueError:
        return False


def not_compared_warning(out_path, column: str, lms: str) -> str:
    """The warning for an import column the LMS's gradebook (the roster) does not have: no
    grade already there could be compared with mechgrade's."""
    return (f"{out_path}: the roster (the gradebook exported from {lms}) has no column "
            f"{column!r}, so the grades already in {lms} were not compared: {lms} adds the "
            "column as a new grade item, or replaces the grades of an item of that name")


def changes_path(out_path: str | os.PathLike) -> Path:
    """``<name>.changes.csv`` beside the import file.

    >>> changes_path("out/canvas.csv").as_posix()
    'out/canvas.changes.csv'
    """
    path = Path(out_path)
    return path.with_name(f"{path.stem}.changes.csv")


def report_changes(out_path: str | os.PathLike, changes: list[Change], lms: str,
                   dry_run: bool) -> tuple[str, ...]:
    """Write :func:`changes_path` (every change that is not ``unchanged``; removed when there
    is none) and return the summary line; with ``dry_run`` write nothing and return the
    summary and one line per change instead.

    >>> import tempfile, pathlib
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "canvas.csv"
    >>> rows = [Change("1", "Ada", "", "7", ChangeKind.NEW, ""),
    ...         Change("2", "Bob", "EX", "EX", ChangeKind.KEPT, "excused")]
    >>> print(report_changes(out, rows, "Canvas", dry_run=True)[1])
    1 (Ada): new grade 7
    """
    listed = [c for c in changes if c.kind is not ChangeKind.UNCHANGED]
    counts = {kind: sum(1 for c in changes if c.kind is kind) for kind in ChangeKind}
    summary = (f"{counts[ChangeKind.NEW]} new, {counts[ChangeKind.CHANGED]} changed, "
               f"{counts[ChangeKind.KEPT]} kept as {lms} has them, "
               f"{counts[ChangeKind.UNCHANGED]} unchanged")
    path = changes_path(out_path)
    if dry_run:
        lines = [_line(c) for c in listed]
        return (Notice(f"dry run, nothing written: {out_path} would import {summary}"),
                *map(Notice, lines))
    if listed:
        write_csv(path, [CHANGES_HEADER, *([c.id, c.name, c.before, c.written, c.kind.value,
                                             c.reason] for c in listed)])
        where = f"; each listed in {path}"
    else:
        remove_stale(path, "the changes list")
        where = ""
    return (Notice(f"{out_path}: {summary}{where}"),)


def _line(change: Change) -> str:
    who = f"{change.id} ({change.name})" if change.name else change.id
    if change.kind is ChangeKind.NEW:
        return f"{who}: new grade {change.written}"
    if change.kind is ChangeKind.CHANGED:
        return f"{who}: {change.before} -> {change.written}"
    return f"{who}: kept {change.before}: {change.reason}"
