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

import importlib
import json
import os
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Callable

from ..errors import ExportError, Location
from ..jsonio import read_json
from .options import ExportOptions

if TYPE_CHECKING:
    from ..grade.results import GradeReport
    from ..roster import Roster

Exporter = Callable[..., tuple[str, ...]]


class _Exporter:
    """The exporter ``function`` of module ``export.<module>``, imported when first called:
    ``mechgrade export --help`` lists every format without importing any exporter."""

    def __init__(self, module: str, function: str):
        self.module, self.function = module, function

    def __call__(self, *args, **kwargs) -> tuple[str, ...]:
        exporter = getattr(importlib.import_module(f"{__package__}.{self.module}"),
                           self.function)
        return exporter(*args, **kwargs)

    def __repr__(self) -> str:
        return f"<exporter {self.module}.{self.function}>"


EXPORTERS: dict[str, Exporter] = {
    "canvas": _Exporter("canvas", "export_canvas"),
    "moodle": _Exporter("moodle", "export_moodle"),
    "gradescope": _Exporter("gradescope", "export_gradescope"),
    "grades-csv": _Exporter("tables", "export_grades_csv"),
    "long-csv": _Exporter("tables", "export_long_csv"),
    "json": _Exporter("jsonfile", "export_json"),
}

__all__ = ["EXPORTERS", "ExportOptions", "export", "read_results", "results_schema"]


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
    """Read a ``results.json`` file, checked against :func:`results_schema` with messages that
    say where.

    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "results.json"
    >>> _ = p.write_text('{"assignment": {"id": "hw1", "title": "HW 1"}, "students": [{}]}')
    >>> read_results(p)
    Traceback (most recent call last):
    ...
    mechgrade.errors.ExportError: ...results.json: students[0]: expected a field 'id', found none
    """
    name = str(path)
    data = read_json(path, what="a results.json file", error=ExportError,
                     max_bytes=200_000_000,
                     content="JSON (a results.json written by mechgrade)")
    from ..grade.results import GradeReport
    from ..schema_errors import schema_problems

    problems = schema_problems(results_schema(), data)
    if problems:
        raise ExportError(problems[0].message, where=Location(name, field=problems[0].field))
    return GradeReport.from_json(data)


RESULTS_SCHEMA_PATH = Path(__file__).with_name("results.schema.json")


@lru_cache(maxsize=1)
def results_schema() -> dict:
    """The JSON Schema of ``results.json`` (shipped as ``export/results.schema.json``)."""
    return json.loads(RESULTS_SCHEMA_PATH.read_text(encoding="utf-8"))
