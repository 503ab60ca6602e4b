"""The ``results.json`` contract, written again (with a roster: roster students without a
submission are added with status ``missing``, score 0 and their roster identity)."""

from __future__ import annotations

import os
from dataclasses import replace

from ..grade.results import GradeReport, Status, StudentResult
from ..roster import Roster
from .cells import write_json
from .common import max_score, no_submission_warnings, not_in_roster_warnings
from .matching import match_roster
from .options import ExportOptions


def export_json(report: GradeReport, out_path: str | os.PathLike, *,
                roster: Roster | None = None,
                options: ExportOptions = ExportOptions()) -> tuple[str, ...]:
    """Write the ``results.json`` document (``GradeReport.to_json``)."""
    warnings: tuple[str, ...] = ()
    if roster is not None:
        students = []
        match = match_roster(report, roster)
        warnings = (*not_in_roster_warnings(match), *no_submission_warnings(match, options))
        for pair in match.pairs:
            if pair.result is not None:
                students.append(pair.result)
            elif pair.roster is not None:
                students.append(StudentResult(
                    pair.roster.id, pair.roster.name, Status.MISSING, 0.0, max_score(report),
                    messages=("in the roster, no submission found",),
                    identity=pair.roster.columns))
        report = replace(report, students=tuple(students))
    write_json(out_path, report.to_json())
    return warnings
