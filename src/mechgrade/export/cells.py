"""Safe CSV cells and atomic file writing, shared by every exporter.

Spreadsheet formula injection: a cell whose text begins with ``=``, ``+``, ``-``, ``@``, a tab
or a carriage return (or the full-width ``＝ ＋ － ＠``) is run as a formula by Excel, LibreOffice
and Google Sheets. Such text is prefixed with ``'`` so it shows as text. A cell that is exactly a
plain decimal number (``-3``, ``-0.5``, ``1e-3``) is left alone, so negative points stay numeric:
a number cannot call a function or open a link.

>>> safe_cell("=HYPERLINK(\\"http://x\\")")
'\\'=HYPERLINK("http://x")'
>>> safe_cell("-x*omega^2"), safe_cell("-2.5"), safe_cell("Émilie")
("'-x*omega^2", '-2.5', 'Émilie')
>>> format_points(2.0), format_points(1.25), format_points(-0.0), format_points(1/3)
('2', '1.25', '0', '0.3333')
"""

from __future__ import annotations

import csv
import io
import os
import re
from typing import Iterable, Sequence

from .. import files

_FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r", "\uff1d", "\uff0b", "\uff0d", "\uff20")
_PLAIN_NUMBER = re.compile(r"-?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?")


MAX_CELL_CHARS = 32_000
"""Excel holds at most 32,767 characters in a cell (and splits longer ones over rows); Python's
csv reader refuses fields over 131,072. Longer text is cut, saying so."""


def safe_cell(value: object) -> str:
    """The text of one CSV cell, neutralised against formula injection (see module doc), and at
    most :data:`MAX_CELL_CHARS` long.

    >>> cell = safe_cell("1" * 40_000)
    >>> len(cell) <= MAX_CELL_CHARS, cell[-44:]
    (True, '[cut: 40000 characters; all in results.json]')
    """
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return format_points(value)
    text = str(value)
    if len(text) > MAX_CELL_CHARS:
        text = f"{text[:MAX_CELL_CHARS - 60]}... [cut: {len(text)} characters; all in results.json]"
    if text.startswith(_FORMULA_STARTS) and not _PLAIN_NUMBER.fullmatch(text):
        return "'" + text
    return text


def format_points(value: float) -> str:
    """Points as short decimal text: integers without ``.0``, at most 4 decimals, no ``-0``."""
    text = f"{float(value):.4f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def csv_text(rows: Iterable[Sequence[object]]) -> str:
    """Rows as CSV text (RFC 4180 quoting, CRLF line ends), every cell through :func:`safe_cell`."""
    buffer = io.StringIO(newline="")
    writer = csv.writer(buffer, lineterminator="\r\n")
    for row in rows:
        writer.writerow([safe_cell(cell) for cell in row])
    return buffer.getvalue()


def write_csv(path: str | os.PathLike, rows: Iterable[Sequence[object]], *,
              excel_bom: bool = False) -> None:
    """Write rows as a UTF-8 CSV file atomically; ``excel_bom`` prefixes a BOM for Excel."""
    files.write_text(path, csv_text(rows), encoding="utf-8-sig" if excel_bom else "utf-8")


def write_json(path: str | os.PathLike, data: object) -> None:
    """Write a JSON document atomically (see :func:`mechgrade.files.write_json`)."""
    files.write_json(path, data)
