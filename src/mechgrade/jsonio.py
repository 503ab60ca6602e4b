"""Reading a JSON document someone else wrote, with every way it can fail as one located message.

Python's ``json`` reads things that are no JSON numbers and fails in ways that are no message:
``NaN``, ``Infinity`` and ``1e400`` become floats that are not finite (written back as ``nan``
into a CSV), an integer of more than 4,300 digits raises ``ValueError``, and a document nested
some thousand levels deep raises ``RecursionError``. :func:`read_json_text` refuses each of them
with its place: the field path of a number that is not finite or too long, the line and
column where the nesting passes :data:`MAX_DEPTH`.

>>> from mechgrade.errors import ExportError
>>> read_json_text('{"students": [{"score": NaN}]}', "results.json", error=ExportError)
Traceback (most recent call last):
...
mechgrade.errors.ExportError: results.json: students[0].score: expected a finite number, found NaN
>>> read_json_text('{"a": [1, 2.5]}', "x.json", error=ExportError)
{'a': [1, 2.5]}
"""

from __future__ import annotations

import json
import math
import os
import re
import sys
from typing import Any

from .errors import Location, MechgradeError
from .files import read_text
from .schema_errors import field_text

MAX_DEPTH = 100
"""Nesting deeper than this is refused: no document mechgrade reads needs a tenth of it."""
MAX_DIGITS = 400
"""An integer with more digits is refused (a float holds about 309)."""


class _Refused:
    """A number the reader will not turn into a value, kept to be reported at its place."""

    def __init__(self, found: str) -> None:
        self.found = found


def _number(text: str, make):
    shown = text if len(text) <= 24 else f"{text[:12]}...{text[-4:]} ({len(text)} characters)"
    if len(text) > MAX_DIGITS:
        return _Refused(f"{shown}, longer than {MAX_DIGITS} characters")
    value = make(text)
    if not math.isfinite(float(value)) if isinstance(value, float) else abs(value) > _LARGEST:
        return _Refused(f"{shown}, beyond the largest floating-point number")
    return value


_LARGEST = int(sys.float_info.max)


def read_json_text(text: str, name: str, *, error: type[MechgradeError],
                   what: str = "JSON") -> Any:
    """The JSON value of ``text`` (from the file ``name``), or ``error`` saying where it is
    not plain finite JSON (see the module doc); ``what`` names the JSON expected in the
    message about a syntax error.

    >>> from mechgrade.errors import ExportError
    >>> read_json_text('[' * 5000 + ']' * 5000, "deep.json", error=ExportError)
    Traceback (most recent call last):
    ...
    mechgrade.errors.ExportError: deep.json:1:101: expected JSON nested at most 100 levels deep, found deeper nesting
    """
    try:
        data = json.loads(text, parse_int=lambda t: _number(t, int),
                          parse_float=lambda t: _number(t, float),
                          parse_constant=lambda t: _Refused(t))
    except json.JSONDecodeError as err:
        raise error(f"expected {what}, found invalid JSON: {err.msg}",
                    where=Location(name, err.lineno, err.colno)) from None
    except RecursionError:
        line, column = _too_deep(text)
        raise error(f"expected JSON nested at most {MAX_DEPTH} levels deep, found deeper "
                    "nesting", where=Location(name, line, column)) from None
    _check(data, text, name, error)
    return data


def read_json(path: str | os.PathLike, *, what: str, error: type[MechgradeError],
              max_bytes: int, content: str = "JSON") -> Any:
    """The JSON value of the regular file ``path`` (:func:`mechgrade.files.read_text`, then
    :func:`read_json_text`); ``what`` names the file expected (``"a results.json file"``),
    ``content`` the JSON expected in it."""
    text = read_text(os.fspath(path), what=what, error=error, max_bytes=max_bytes)
    return read_json_text(text, str(path), error=error, what=content)


def _check(data, text: str, name: str, error: type[MechgradeError]) -> None:
    """Refuse the first :class:`_Refused` number (in document order) and nesting deeper than
    :data:`MAX_DEPTH`; walked without recursion."""
    stack: list[tuple[tuple[str | int, ...], object]] = [((), data)]
    while stack:
        path, value = stack.pop()
        if isinstance(value, _Refused):
            raise error(f"expected a finite number, found {value.found}",
                        where=Location(name, field=field_text(path)))
        if isinstance(value, (dict, list)) and len(path) >= MAX_DEPTH:
            line, column = _too_deep(text)
            raise error(f"expected JSON nested at most {MAX_DEPTH} levels deep, found deeper "
                        "nesting", where=Location(name, line, column))
        children = value.items() if isinstance(value, dict) else \
            enumerate(value) if isinstance(value, list) else ()
        stack.extend(reversed([((*path, key), child) for key, child in children]))


_TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|[\[\]{}]', re.DOTALL)


def _too_deep(text: str) -> tuple[int | None, int | None]:
    """Line and column of the bracket that opens level :data:`MAX_DEPTH` + 1."""
    depth = 0
    for token in _TOKEN.finditer(text):
        mark = token.group()
        if mark in "[{":
            depth += 1
            if depth > MAX_DEPTH:
                start = token.start()
                line = text.count("\n", 0, start) + 1
                return line, start - (text.rfind("\n", 0, start) + 1) + 1
        elif mark in "]}":
            depth -= 1
    return None, None

