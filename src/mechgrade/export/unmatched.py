"""Rows an LMS cannot match to one of its users: kept out of the import file, written to
``<name>.unmatched.csv`` next to it (``canvas.unmatched.csv`` for ``canvas.csv``), and
announced by one warning.

An LMS import that meets a row it cannot match does harm: Canvas opens an "unknown student"
dialog (or, reading ``ID`` as an integer, gives the grade to another user), Moodle aborts the
whole import. So such rows never go into the import file. Each import file has its own
unmatched file, so two exports into one folder keep both; an export that holds nothing back
removes the one an earlier export of the same file left.

>>> import tempfile, pathlib
>>> out = pathlib.Path(tempfile.mkdtemp()) / "canvas.csv"
>>> held = [HeldBack("zz", "Ghost", "graded", 7.0, "not in the roster")]
>>> (warning,) = write_unmatched(out, held, "Canvas", "enter it by hand")
>>> print(warning.replace(str(out.parent), "out"))  # doctest: +NORMALIZE_WHITESPACE
1 row kept out of out/canvas.csv because Canvas could not import it: see
out/canvas.unmatched.csv for who and why; enter it by hand
>>> (out.parent / "canvas.unmatched.csv").read_text().splitlines()
['id,name,status,score,reason', 'zz,Ghost,graded,7,not in the roster']
>>> write_unmatched(out, [], "Canvas", "enter it by hand"), unmatched_path(out).exists()
((), False)
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from ..errors import ExportError, Location
from ..grade.results import Status
from .cells import write_csv
from .matching import Pair

UNMATCHED_HEADER = ("id", "name", "status", "score", "reason")


@dataclass(frozen=True)
class HeldBack:
    """One row kept out of an import file: who, their grade cell, and why."""

    id: str
    name: str
    status: Status
    score: float | str
    reason: str


def held_back(pair: Pair, score: float | str, reason: str) -> HeldBack:
    """The row of ``pair`` (its result, else its roster student) held back for ``reason``."""
    if pair.result is not None:
        return HeldBack(pair.result.id, pair.result.name, pair.result.status, score, reason)
    assert pair.roster is not None  # a pair holds a result, a roster student or both
    return HeldBack(pair.roster.id, pair.roster.name, Status.MISSING, score, reason)


def unmatched_path(out_path: str | os.PathLike) -> Path:
    """Where the held-back rows of the import file ``out_path`` go: ``<name>.unmatched.csv``
    beside it.

    >>> unmatched_path("out/canvas.csv").as_posix(), unmatched_path("out/moodle").as_posix()
    ('out/canvas.unmatched.csv', 'out/moodle.unmatched.csv')
    """
    path = Path(out_path)
    return path.with_name(f"{path.stem}.unmatched.csv")


def remove_stale(path: Path, what: str) -> None:
    """Remove ``path``, a file an earlier export wrote beside its import file (``what`` it
    holds), which would now describe another export."""
    try:
        path.unlink(missing_ok=True)
    except OSError as exc:
        raise ExportError(f"expected to remove {what} of an earlier export, found it cannot "
                          f"be removed ({exc.strerror or exc})", where=Location(str(path))) \
            from None


def write_unmatched(out_path: str | os.PathLike, rows: list[HeldBack], lms: str,
                    remedy: str, dry_run: bool = False) -> tuple[str, ...]:
    """Write ``rows`` to :func:`unmatched_path` and return the warning about them; with no
    rows, remove that file if an earlier export left one (it would list rows this export
    imports) and return no warning. With ``dry_run`` nothing is written or removed: one
    warning per row says why it would be kept out."""
    path = unmatched_path(out_path)
    if dry_run:
        return tuple(f"{r.id} ({r.name}) would be kept out of {out_path}: {r.reason}"
                     for r in rows)
    if not rows:
        remove_stale(path, "the unmatched rows")
        return ()
    write_csv(path, [UNMATCHED_HEADER,
                     *([r.id, r.name, r.status, r.score, r.reason] for r in rows)])
    count = "1 row" if len(rows) == 1 else f"{len(rows)} rows"
    them = "it" if len(rows) == 1 else "them"
    return (f"{count} kept out of {out_path} because {lms} could not import {them}: see "
            f"{path} for who and why; {remedy}",)
