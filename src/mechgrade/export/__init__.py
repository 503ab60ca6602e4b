"""Exports of grading results for learning-management systems and spreadsheets.

:data:`EXPORTERS` is the explicit registry: format name -> function
``(report, out_path, *, roster=None, options=ExportOptions()) -> warnings`` (a tuple of
messages for the user: rows held back from an LMS import, unchecked keys...). Every file is written
with the stdlib ``csv``/``json`` writers through a temporary file and ``os.replace``; every CSV
cell is neutralised against formula injection (:func:`mechgrade.export.cells.safe_cell`).

>>> list(EXPORTERS)
['canvas', 'moodle', 'gradescope', 'grades-csv', 'long-csv', 'json']
"""

from __future__ import annotations

import json
import os
from typing import Callable

from ..files import read_text
from ..errors import ExportError, Location
from ..grade.results import STATUSES, VERDICTS, GradeReport
from ..roster import Roster
from .canvas import export_canvas
from .gradescope import export_gradescope
from .jsonfile import export_json
from .matching import RosterMatch, match_roster
from .moodle import export_moodle
from .options import ExportOptions
from .tables import export_grades_csv, export_long_csv

Exporter = Callable[..., tuple[str, ...]]

EXPORTERS: dict[str, Exporter] = {
    "canvas": export_canvas,
    "moodle": export_moodle,
    "gradescope": export_gradescope,
    "grades-csv": export_grades_csv,
    "long-csv": export_long_csv,
    "json": export_json,
}

__all__ = ["EXPORTERS", "ExportOptions", "RosterMatch", "export", "match_roster",
           "read_results"]


def export(report: GradeReport, fmt: str, out_path: str | os.PathLike, *,
           roster: Roster | None = None,
           options: ExportOptions = ExportOptions()) -> tuple[str, ...]:
    """Write ``report`` in format ``fmt`` (a key of :data:`EXPORTERS`); return its warnings."""
    try:
        exporter = EXPORTERS[fmt]
    except KeyError:
        raise ExportError(f"expected a format among {', '.join(EXPORTERS)}, found {fmt!r}",
                          where=Location(field="format")) from None
    return exporter(report, out_path, roster=roster, options=options)


def read_results(path: str | os.PathLike) -> GradeReport:
    """Read a ``results.json`` file, checking its shape with messages that say where.

    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "results.json"
    >>> _ = p.write_text('{"assignment": {"id": "hw1", "title": "HW 1"}, "students": [{}]}')
    >>> read_results(p)
    Traceback (most recent call last):
    ...
    mechgrade.errors.ExportError: ...results.json: students[0]: expected field 'id', found it missing
    """
    name = str(path)
    text = read_text(path, what="a results.json file", error=ExportError,
                     max_bytes=200_000_000)
    try:
        data = json.loads(text)
    except json.JSONDecodeError as err:
        raise ExportError(f"expected JSON (a results.json written by mechgrade), found "
                          f"invalid JSON: {err.msg}", where=Location(name, err.lineno, err.colno)) \
            from None
    _check_results(data, name)
    return GradeReport.from_json(data)


_STR, _NUM, _OPT_STR = "a string", "a number", "a string or null"


def _check_results(data: object, name: str) -> None:
    def fail(field: str, expected: str, found: str) -> ExportError:
        return ExportError(f"expected {expected}, found {found}", where=Location(name, field=field))

    def kind(value: object) -> str:
        if value is None:
            return "null"
        return {bool: "a boolean", int: "a number", float: "a number", str: "a string",
                list: "a list", dict: "an object"}.get(type(value), type(value).__name__)

    def check(obj: object, where: str, fields: dict[str, str], required: set[str]) -> None:
        if not isinstance(obj, dict):
            raise fail(where, "an object", kind(obj))
        for key in fields:
            if key not in obj:
                if key in required:
                    raise fail(where, f"field {key!r}", "it missing")
                continue
            value, want = obj[key], fields[key]
            ok = {_STR: isinstance(value, str),
                  _OPT_STR: value is None or isinstance(value, str),
                  _NUM: isinstance(value, (int, float)) and not isinstance(value, bool),
                  "a list": isinstance(value, list),
                  "an object": isinstance(value, dict),
                  "a list of strings": isinstance(value, list)
                  and all(isinstance(v, str) for v in value)}[want]
            if not ok:
                raise fail(f"{where}.{key}" if where else key, want, kind(value))
        unknown = sorted(set(obj) - set(fields))
        if unknown:
            raise fail(where or "(top level)", f"only the fields {', '.join(fields)}",
                       f"{unknown[0]!r}")

    check(data, "", {"assignment": "an object", "objectives": "a list", "students": "a list",
                     "skipped": "a list", "notes": "a list of strings",
                     "internal_errors": "a list of strings"},
          {"assignment", "students"})
    for i, entry in enumerate(data.get("skipped", [])):
        check(entry, f"skipped[{i}]", {"path": _STR, "reason": _STR}, {"path", "reason"})
    check(data["assignment"], "assignment", {"id": _STR, "title": _STR}, {"id", "title"})
    for i, objective in enumerate(data.get("objectives", [])):
        fields = {"problem": _STR, "objective": _STR, "prompt": _STR, "max_points": _NUM}
        check(objective, f"objectives[{i}]", fields, set(fields))
    for i, student in enumerate(data["students"]):
        where = f"students[{i}]"
        check(student, where, {"id": _STR, "name": _STR, "status": _STR, "score": _NUM,
                               "max_score": _NUM, "answers": "a list",
                               "messages": "a list of strings", "identity": "an object"},
              {"id", "status", "score", "max_score"})
        if student["status"] not in STATUSES:
            raise fail(f"{where}.status", "one of " + ", ".join(STATUSES),
                       repr(student["status"]))
        for j, answer in enumerate(student.get("answers", [])):
            at = f"{where}.answers[{j}]"
            check(answer, at, {"problem": _STR, "objective": _STR, "answer": _OPT_STR,
                               "verdict": _STR, "points": _NUM, "max_points": _NUM,
                               "diagnosis": _OPT_STR, "feedback": _STR, "read_back": _OPT_STR,
                               "expected": _OPT_STR},
                  {"problem", "objective", "answer", "verdict", "points", "max_points"})
            if answer["verdict"] not in VERDICTS:
                raise fail(f"{at}.verdict", "one of " + ", ".join(VERDICTS),
                           repr(answer["verdict"]))
