"""The ``results.json`` contract, written again (with a roster: roster students without a
submission are added with status ``missing``, score 0 and their roster identity)."""

from __future__ import annotations

import os
from dataclasses import replace

from ..grade.results import GradeReport, StudentResult
from ..roster import Roster
from .cells import write_json
from .common import max_score
from .matching import match_roster
from .options import ExportOptions


def export_json(report: GradeReport, out_path: str | os.PathLike, *,
                roster: Roster | None = None, options: ExportOptions = ExportOptions()) -> None:
    """Write the ``results.json`` document (``GradeReport.to_json``)."""
    if roster is not None:
        students = []
        for pair in match_roster(report, roster).pairs:
            if pair.result is not None:
                students.append(pair.result)
            else:
                students.append(StudentResult(
                    pair.roster.id, pair.roster.name, "missing", 0.0, max_score(report),
                    messages=("in the roster, no submission found",),
                    identity=pair.roster.columns))
        report = replace(report, students=tuple(students))
    write_json(out_path, report.to_json())
