"""Moodle's grade import (Grades > Import > CSV file), re-implemented for the tests.

Followed from moodle/moodle as stored in the index:

* ``lib/csvlib.class.php`` (``csv_import_reader::load_csv_content``): the text converted, its
  byte order mark removed, ``\\r\\n?`` made ``\\n``, the whole text trimmed, then read with PHP's
  ``fgetcsv($fp, 0, $delimiter, '"')`` (escape character ``\\``); a blank line is skipped; every
  row must have as many fields as the header (``csvweirdcolumns`` otherwise); the rows are
  stored with ``csv_export_writer::print_array`` (``fputcsv``) and read back with ``fgetcsv``.
* PHP's ``php_fgetcsv`` and ``php_fputcsv`` (php/php-src ``ext/standard/file.c``), ported
  character by character below (:func:`fgetcsv`, :func:`fputcsv`).
* ``grade/import/csv/classes/load_data.php`` (``prepare_import_grade_data``,
  ``map_user_data_with_value``, ``check_user_exists``, ``update_grade_item``,
  ``insert_grade_record``): per line, fields ``trim``-med; the user looked up by the mapped
  column (a blank key skips the lookup and keeps the previous row's user: the first row with
  one aborts, ``usermappingerrorusernotfound``); an unknown user aborts the whole import;
  ``''`` or ``-`` is "no grade"; a grade that is not a number aborts (``badgrade``); a grade
  above 100 (or the site's ``gradepointmax`` with unlimited grades) aborts
  (``gradevaluetoobig``); the ``Last downloaded from this course`` column (not first) makes a
  grade changed since that time abort (``gradealreadyupdated``), and a time that is not an
  integer, in the future or older than a year abort (``invalidgradeexporteddate``).
* ``grade/import/lib.php`` (``grade_import_commit``) and ``grade_item::update_final_grade``
  (``bounded_grade``): each grade is cut to the item's [grademin, grademax]; a null grade
  clears it; feedback is stored when given.

``unformat_float`` (``lib/moodlelib.php``) is not in the index; it is modelled on its known
behaviour: spaces removed, the locale's decimal separator made ``.``, then ``is_numeric``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

TIMEEXPORTED = "Last downloaded from this course"  # get_string('timeexported', 'gradeexport_txt')
YEAR = 365 * 86400


class ImportAborted(Exception):
    """The import stopped and nothing was imported; ``args[0]`` is Moodle's string id."""


@dataclass
class MoodleUser:
    id: int
    email: str
    idnumber: str = ""
    username: str = ""


@dataclass
class GradeItem:
    id: int
    name: str
    grademax: float = 100.0
    grademin: float = 0.0
    grades: dict[int, float | None] = field(default_factory=dict)
    feedback: dict[int, str] = field(default_factory=dict)
    dategraded: dict[int, int] = field(default_factory=dict)


@dataclass
class Site:
    users: list[MoodleUser]
    item: GradeItem
    unlimitedgrades: bool = False
    gradepointmax: float = 100.0
    now: int = 1_800_000_000
    decsep: str = "."


@dataclass
class Committed:
    """What the import did to the item: the grades and feedback after it, and the grades
    Moodle cut to the item's range."""

    grades: dict[int, float | None]
    feedback: dict[int, str]
    clamped: dict[int, tuple[float, float]]


# ------------------------------------------------------------------------------ PHP


def php_trim(text: str, chars: str = " \t\n\r\0\x0b") -> str:
    return text.strip(chars)


def _lines(text: str):
    """``php_stream_get_line``: lines with their ``\\n``."""
    return iter(text.splitlines(keepends=True))


def _trailing(buf: str) -> int:
    """``php_fgetcsv_lookup_trailing_spaces``: where the line's ``\\r\\n``/``\\n``/``\\r``
    begins."""
    if buf.endswith("\r\n"):
        return len(buf) - 2
    if buf.endswith(("\n", "\r")):
        return len(buf) - 1
    return len(buf)


def fgetcsv(lines, delimiter: str = ",", enclosure: str = '"', escape: str = "\\"
            ) -> list[str | None] | None:
    """PHP's ``fgetcsv``: the next record from ``lines`` (an iterator of lines), ``[None]``
    for a blank line, ``None`` at the end. Each character stands for PHP's multibyte unit
    (``php_mblen``): a character that is not ASCII is never a delimiter, quote or escape."""
    buf = next(lines, None)
    if buf is None:
        return None
    values: list[str | None] = []
    limit = line_end = _trailing(buf)
    pos = 0
    first = True
    while True:
        field_chars: list[str] = []
        if pos < limit:
            tmp = pos
            while tmp < len(buf) and buf[tmp] != delimiter and buf[tmp].isspace() \
                    and buf[tmp].isascii():
                tmp += 1
            if tmp < limit and buf[tmp] == enclosure:
                pos = tmp
        if first and pos == line_end:
            return [None]
        first = False
        if pos < limit and buf[pos] == enclosure:
            state = 0
            pos += 1
            hunk = pos
            while True:
                if pos >= limit:  # inc_len == 0: the line is over inside the enclosure
                    if state == 2:
                        field_chars.append(buf[hunk:pos - 1])
                        hunk = pos
                        break
                    field_chars.append(buf[hunk:pos])
                    field_chars.append(buf[line_end:])  # the embedded line end
                    nxt = next(lines, None)
                    if nxt is None:
                        hunk = pos = len(buf)
                        break
                    buf, pos, hunk = nxt, 0, 0
                    limit = line_end = _trailing(buf)
                    state = 0
                    continue
                ch = buf[pos]
                if state == 1:
                    pos += 1
                    state = 0
                elif state == 2:
                    if ch != enclosure:
                        field_chars.append(buf[hunk:pos - 1])
                        hunk = pos
                        break
                    field_chars.append(buf[hunk:pos])
                    pos += 1
                    hunk = pos
                    state = 0
                else:
                    if ch == enclosure:
                        state = 2
                    elif escape and ch == escape:
                        state = 1
                    pos += 1
            # quit_loop_2: look up for a delimiter
            while pos < limit and buf[pos] != delimiter:
                pos += 1
            field_chars.append(buf[hunk:pos])
            more = pos < limit
            pos += 1
            values.append("".join(field_chars))
        else:
            hunk = pos
            while pos < limit and buf[pos] != delimiter:
                pos += 1
            text = buf[hunk:pos]
            values.append(text[:_trailing(text)])
            more = pos < limit
            pos += 1
        if not more:
            return values


def fputcsv(fields: list[str], delimiter: str = ",", enclosure: str = '"',
            escape: str = "\\") -> str:
    """PHP's ``fputcsv`` (``php_fputcsv``): a field holding a delimiter, quote, escape
    character, line break, tab or space is enclosed, its quotes doubled unless they follow
    the escape character."""
    out = []
    for value in fields:
        value = value or ""
        if any(c in value for c in (delimiter, enclosure, escape, "\n", "\r", "\t", " ")):
            chars, escaped = [enclosure], False
            for ch in value:
                if escape and ch == escape:
                    escaped = True
                elif not escaped and ch == enclosure:
                    chars.append(enclosure)
                else:
                    escaped = False
                chars.append(ch)
            chars.append(enclosure)
            out.append("".join(chars))
        else:
            out.append(value)
    return delimiter.join(out) + "\n"


def is_numeric(text: str) -> bool:
    """PHP 8's ``is_numeric`` for a string."""
    return re.fullmatch(r"[ \t\n\r\v\f]*[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?[ \t\n\r\v\f]*",
                        text) is not None


# ------------------------------------------------------------------------------ the import


def load_csv_content(text: str, delimiter: str = ",") -> list[list[str]]:
    """``csv_import_reader::load_csv_content`` then the stored rows read back
    (``init``/``next``): the rows Moodle works on, header first."""
    text = text[1:] if text.startswith("\ufeff") else text
    text = php_trim(re.sub(r"\r\n?", "\n", text))
    lines = _lines(text)
    rows = []
    while True:
        row = fgetcsv(lines, delimiter)
        if row is None:
            break
        if len(row) == 1 and row[0] is None:
            continue  # an empty line
        rows.append(row)
    if not rows:
        raise ImportAborted("csvemptyfile")
    if any(len(r) != len(rows[0]) for r in rows):
        raise ImportAborted("csvweirdcolumns")
    stored = "".join(fputcsv([c or "" for c in r]) for r in rows)
    lines = _lines(stored)
    back = []
    while True:
        row = fgetcsv(lines)
        if row is None:
            break
        back.append([c or "" for c in row])
    return back


def import_grades(text: str, site: Site, *, user_column: str, user_field: str,
                  grade_column: str, feedback_column: str | None = None,
                  forceimport: bool = False, delimiter: str = ",") -> Committed:
    """The import of ``text`` into ``site.item`` with the preview page mapped so: the user by
    ``user_column`` as ``user_field`` (``useremail``, ``useridnumber``, ``username``,
    ``userid``), ``grade_column`` to the item, ``feedback_column`` to its feedback. Raises
    :class:`ImportAborted` where Moodle aborts (nothing is imported then)."""
    rows = load_csv_content(text, delimiter)
    header = [php_trim(h) for h in rows[0]]
    index = {name: i for i, name in enumerate(header)}
    timeexportkey = index.get(TIMEEXPORTED)
    fields = {"useremail": "email", "useridnumber": "idnumber", "username": "username",
              "userid": "id"}
    buffer: dict[int, dict] = {}
    studentid = None  # prepare_import_grade_data sets it once, not per line
    for line in rows[1:]:
        if len(line) <= 1:
            continue
        values = [php_trim(v) for v in line]
        key = values[index[user_column]]
        if key not in ("", "0"):  # PHP's !empty()
            users = [u for u in site.users
                     if str(getattr(u, fields[user_field])) == key]
            if not users:
                raise ImportAborted("usermappingerror")
            studentid = users[0].id
        grade_text = values[index[grade_column]]
        if grade_text in ("", "-"):
            grade = None
        else:
            number = grade_text.replace(" ", "").replace(site.decsep, ".")
            if not is_numeric(number):
                raise ImportAborted("badgrade")
            grade = float(number)
        feedback = values[index[feedback_column]] if feedback_column else None
        if studentid is None:
            raise ImportAborted("usermappingerrorusernotfound")
        if not forceimport and timeexportkey:  # !empty(): a first column is never read
            exported = values[timeexportkey]
            if not re.fullmatch(r"-?\d+", exported) or int(exported) > site.now or \
                    int(exported) < site.now - YEAR:
                raise ImportAborted("invalidgradeexporteddate")
            graded = site.item.dategraded.get(studentid)
            if graded and int(exported) < graded:
                raise ImportAborted("gradealreadyupdated")
        limit = site.gradepointmax if site.unlimitedgrades else 100.0
        if grade is not None and grade > limit:
            raise ImportAborted("gradevaluetoobig")
        buffer[studentid] = {"grade": grade, "feedback": feedback}
    grades = dict(site.item.grades)
    feedbacks = dict(site.item.feedback)
    clamped = {}
    for userid, record in buffer.items():
        grade = record["grade"]
        if grade is not None:
            bounded = min(max(grade, site.item.grademin), site.item.grademax)
            if bounded != grade:
                clamped[userid] = (grade, bounded)
            grade = bounded
        grades[userid] = grade
        if record["feedback"] is not None:
            feedbacks[userid] = record["feedback"]
    return Committed(grades, feedbacks, clamped)
