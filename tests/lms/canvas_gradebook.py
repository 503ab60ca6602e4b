"""Canvas's gradebook CSV import and export, re-implemented for the tests.

Followed, rule by rule, from instructure/canvas-lms (the index's copy of
``app/models/gradebook_importer.rb``, 2024, and ``lib/gradebook_exporter.rb``); each function
names the method it follows. The model of a course (:class:`Course`) holds what the importer
looks up: students, assignments, and the grades already there.

What the import does with a file is :func:`import_gradebook`: the header check
(``header?``, ``row_has_student_headers?``, ``update_column_count``), the rows skipped
(``check_for_non_student_row``), students found (``process_student``), the assignments found
or created (``parse_assignments``, ``Assignment.title_and_id``), the ``Points Possible`` row
applied (``process_pp``), read-only columns dropped (``readonly_assignment?``), and the cells
that differ from Canvas's grades (``no_change_to_value?``) - which are what the import
applies.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from decimal import Decimal, InvalidOperation


class MalformedCSV(Exception):
    """Ruby's ``CSV::MalformedCSVError``: the upload fails ("did not parse cleanly")."""


class InvalidHeaderRow(Exception):
    """``GradebookImporter::InvalidHeaderRow``: the upload fails with "Invalid header row"."""


@dataclass
class CanvasStudent:
    id: int
    name: str  # "Ada Lovelace"
    sortable_name: str  # "Lovelace, Ada"
    sis_user_id: str = ""
    login_id: str = ""


@dataclass
class CanvasAssignment:
    id: int
    title: str
    points_possible: float | None = None


@dataclass
class Course:
    """What Canvas knows: students, assignments and grades (``(student, assignment) ->
    text``: a score such as ``"7"``, ``"EX"``, or absent for none), and which assignments each
    student is assigned (all, unless listed in ``not_assigned``)."""

    students: list[CanvasStudent]
    assignments: list[CanvasAssignment]
    grades: dict[tuple[int, int], str] = field(default_factory=dict)
    not_assigned: set[tuple[int, int]] = field(default_factory=set)
    allow_last_first_names: bool = True


@dataclass
class ImportResult:
    """What Canvas would do with the file: the changes it applies (``(student id, assignment
    id) -> (before, after)``), the new assignments it creates, the assignments whose points
    it changes, the rows it cannot match (the "unknown student" dialog), and the columns it
    drops."""

    changes: dict[tuple[int, int], tuple[str, str]]
    new_assignments: list[str]
    points_changed: dict[int, tuple[float | None, str]]
    unknown_students: list[str]
    dropped_read_only: list[str]
    ignored_columns: list[str]


# ------------------------------------------------------------------------------ Ruby's CSV


def parse_csv(text: str) -> list[list[str | None]]:
    """The rows Ruby's ``CSV.foreach`` yields with the importer's options (``csv_stream``):
    the column separator detected (``semicolon_delimited?``, ``identify_delimiter``), lines of
    only ``;``, ``,`` and spaces skipped (``skip_lines: /^[;, ]+$/``), empty unquoted fields
    as ``nil`` (``None``) and the ``decimal_comma_to_period`` converter applied to the rest.
    A stray quote raises :class:`MalformedCSV` as Ruby's parser does."""
    # Ruby reads the file as UTF-8 without stripping a byte order mark: it stays in the first
    # cell (harmless for 'Student', fatal for the exact 'LastName' test of update_column_count)
    separator = ";" if _semicolon_delimited(text) else ","
    rows = []
    for line, cells in _records(text, separator):
        if re.fullmatch(r"[;, ]+", line):
            continue
        rows.append([None if c is None else _decimal_comma_to_period(c) for c in cells])
    return rows


def _semicolon_delimited(text: str) -> bool:
    """``semicolon_delimited?``/``identify_delimiter``: the first three physical lines parsed
    with each separator; one giving the same field count on each line wins, ``;`` only if it
    gives more fields than ``,``."""
    lines = text.splitlines(keepends=True)[:3]
    if not lines:
        return False
    counts = {}
    for separator in (";", ","):
        counts[separator] = 0
        try:
            sizes = [len(_parse_line(line, separator)) for line in lines]
        except MalformedCSV:
            continue
        if len(set(sizes)) == 1:
            counts[separator] = sizes[0]
    return counts[";"] > counts[","]


def _parse_line(line: str, separator: str) -> list[str | None]:
    records = list(_records(line, separator))
    if len(records) > 1:
        raise MalformedCSV("unclosed quoted field")
    return records[0][1] if records else []


def _records(text: str, separator: str):
    """RFC 4180 records as Ruby's CSV parser reads them (strict quoting), each with the raw
    line it came from (for ``skip_lines``)."""
    i, n = 0, len(text)
    while i < n:
        start = i
        cells: list[str | None] = []
        while True:
            if i < n and text[i] == '"':
                i += 1
                value = []
                while True:
                    if i >= n:
                        raise MalformedCSV("Unclosed quoted field")
                    if text[i] == '"':
                        if i + 1 < n and text[i + 1] == '"':
                            value.append('"')
                            i += 2
                            continue
                        i += 1
                        break
                    value.append(text[i])
                    i += 1
                cells.append("".join(value))
                if i < n and text[i] not in (separator, "\r", "\n"):
                    raise MalformedCSV("Any value after quoted field isn't allowed")
            else:
                j = i
                while j < n and text[j] not in (separator, "\r", "\n"):
                    if text[j] == '"':
                        raise MalformedCSV("Illegal quoting")
                    j += 1
                cells.append(text[i:j] or None)
                i = j
            if i < n and text[i] == separator:
                i += 1
                continue
            break
        raw = text[start:i]
        if text.startswith("\r\n", i):
            i += 2
        elif i < n:
            i += 1
        yield raw, ([] if cells == [None] else cells)


def _decimal_comma_to_period(value: str) -> str:
    """``CSV::Converters[:decimal_comma_to_period]``."""
    if re.fullmatch(r"-?[0-9.,]+%?", value):
        parts = re.split(r"[,.]", value)
        last = parts.pop()
        return last if not parts else "".join(parts) + "." + last
    return value


# ------------------------------------------------------------------------------ the import


NON_ASSIGNMENT = ("Current Score", "Current Points", "Current Grade", "Final Score",
                  "Final Points", "Final Grade", "Override Score", "Override Grade",
                  "Override Status")  # NON_ASSIGNMENT_COLUMN_HEADERS


def title_and_id(header: str) -> tuple[str, str | None]:
    """``Assignment.title_and_id``."""
    found = re.fullmatch(r"(.*)\s\((\d+)\)", header, re.DOTALL)
    return (found[1], found[2]) if found else (header, None)


def ruby_to_i(text: str) -> int:
    """Ruby's ``String#to_i``: the leading integer, 0 when there is none."""
    found = re.match(r"\s*([-+]?\d+)", text.replace("_", ""))
    return int(found[1]) if found else 0


def import_gradebook(text: str, course: Course) -> ImportResult:
    """What ``GradebookImporter#parse!`` makes of ``text`` for ``course``."""
    rows = parse_csv(text)
    if not rows:
        raise InvalidHeaderRow("empty file")
    header = rows[0]
    layout = _header(header, course)
    student_columns = layout["student_columns"]
    # strip_non_assignment_columns: the identity columns, then any title holding a total's name
    pattern = re.compile("|".join(NON_ASSIGNMENT))
    candidates = [(i, h) for i, h in enumerate(header) if i >= student_columns]
    ignored = [h or "" for _, h in candidates if h is not None and pattern.search(h)]
    assignment_columns = [(i, h or "") for i, h in candidates
                          if h is None or not pattern.search(h)]
    by_id = {a.id: a for a in course.assignments}
    found: list[tuple[int, CanvasAssignment | None, str]] = []  # (column, assignment, title)
    for index, name in assignment_columns:
        title, ident = title_and_id(name)
        assignment = by_id.get(int(ident)) if ident else None
        assignment = assignment or next((a for a in course.assignments if a.title == name), None)
        found.append((index, assignment, title))
    points_row: list[str | None] = []
    students: list[tuple[CanvasStudent | None, list[str | None]]] = []
    unknown: list[str] = []
    for row in rows[1:]:
        # check_for_non_student_row
        if row and row[0] is not None and "Points Possible" in row[0]:
            points_row = row
            continue
        if all(re.fullmatch(r"\s*(Muted|Manual Posting.*)?\s*", c, re.IGNORECASE)
               for c in row if c is not None):
            continue
        student = _student(row, layout, course)
        if student is None:
            name = (f"{row[1] or ''} {row[0] or ''}".strip() if layout["last_first"]
                    else row[0] or "")
            unknown.append(name)
        students.append((student, row))
    points_changed: dict[int, tuple[float | None, str]] = {}
    new_assignments = [title for _, a, title in found if a is None]
    dropped = []
    changes: dict[tuple[int, int], tuple[str, str]] = {}
    for index, assignment, _title in found:
        cell = points_row[index] if index < len(points_row) else None
        if cell is not None and re.search(r"read\s+only", cell):  # readonly_assignment?
            dropped.append(header[index] or "")
            continue
        if assignment is None:
            continue
        if cell is not None and not _same_number(cell, assignment.points_possible):
            points_changed[assignment.id] = (assignment.points_possible, cell)  # process_pp
        if unknown:
            continue  # with an unknown student Canvas stops at its dialog (@missing_student)
        for student, row in students:
            assert student is not None
            grade = (row[index] or "").strip() if index < len(row) else ""
            if (student.id, assignment.id) in course.not_assigned:
                grade = ""  # assignment_assigned_to_student
            before = course.grades.get((student.id, assignment.id), "")
            if grade.upper() == "EX":
                grade = "EX"
            if not no_change_to_value(grade, before):
                changes[(student.id, assignment.id)] = (before, grade)
    return ImportResult(changes, new_assignments, points_changed, unknown, dropped, ignored)


def _header(row: list[str | None], course: Course) -> dict:
    """``header?``, ``row_has_student_headers?`` and ``update_column_count``."""
    cells = [c or "" for c in row]
    if not ((len(cells) > 3 and "Student" in cells[0] and "ID" in cells[1])
            or (len(cells) > 4 and "LastName" in cells[0] and "FirstName" in cells[1]
                and "ID" in cells[2])):
        raise InvalidHeaderRow("row_has_student_headers?")
    last_first = cells[0] == "LastName" and cells[1] == "FirstName"
    if last_first and not course.allow_last_first_names:
        raise InvalidHeaderRow("allow_student_last_first_names?")
    count = columns = 4 if last_first else 3
    sis_user = sis_login = None
    if re.search(r"SIS\s+Login\s+ID", _at(cells, count - 1)):
        sis_login = count - 1
        columns += 1
    elif re.search(r"SIS\s+User\s+ID", _at(cells, count - 1)) and \
            re.search(r"SIS\s+Login\s+ID", _at(cells, count)):
        extra = 1 if re.search(r"Integration\s+ID", _at(cells, count + 1)) else 0
        sis_user, sis_login = count - 1, count
        columns += 2 + extra
        if re.search(r"Root\s+Account", _at(cells, count + 1 + extra)):
            columns += 1
    if "Section" not in _at(cells, columns - 1):
        raise InvalidHeaderRow("last_student_info_column")
    return {"last_first": last_first, "student_columns": columns, "sis_user": sis_user,
            "sis_login": sis_login}


def _at(cells: list[str], index: int) -> str:
    return cells[index] if 0 <= index < len(cells) else ""


def _student(row: list[str | None], layout: dict, course: Course) -> CanvasStudent | None:
    """``process_student``: by ``ID`` (``to_i``), then SIS user id, then login id, then exact
    name or sortable name."""
    cells = [c or "" for c in row] + [""] * 8
    by_id = {s.id: s for s in course.students}
    ident = cells[2] if layout["last_first"] else cells[1]
    if ident:
        found = by_id.get(ruby_to_i(ident))
        if found is not None:
            return found
    if layout["sis_user"] is not None and cells[layout["sis_user"]]:
        found = next((s for s in course.students
                      if s.sis_user_id and s.sis_user_id == cells[layout["sis_user"]]), None)
        if found is not None:
            return found
    if layout["sis_login"] is not None and cells[layout["sis_login"]]:
        found = next((s for s in course.students
                      if s.login_id and s.login_id == cells[layout["sis_login"]]), None)
        if found is not None:
            return found
    name = f"{cells[1]} {cells[0]}".strip() if layout["last_first"] else cells[0]
    return next((s for s in course.students if name in (s.name, s.sortable_name)), None)


def no_score(value: str | None) -> bool:
    """``no_score?``."""
    return value is None or value.strip() == "" or value == "-"


def no_change_to_value(new: str, current: str) -> bool:
    """``no_change_to_value?`` with ``consider_excused: true``: equal text, both no score, or
    the same number at two decimals (``I18n.n(value, precision: 2)``)."""
    if new == current:
        return True
    if no_score(current) and no_score(new):
        return True
    if no_score(current) or no_score(new):
        return False
    if new.upper() == "EX" or current.upper() == "EX":
        return False
    try:
        return _two_decimals(new) == _two_decimals(current)
    except InvalidOperation:
        return False


def _two_decimals(text: str) -> Decimal:
    return Decimal(text).quantize(Decimal("0.01"))


def _same_number(cell: str, points: float | None) -> bool:
    if points is None:
        return False
    try:
        return _two_decimals(cell) == _two_decimals(repr(points))
    except InvalidOperation:
        return False


# ------------------------------------------------------------------------------ the export


def export_gradebook(course: Course, *, last_first: bool = False,
                     read_only_points: frozenset[int] = frozenset()) -> str:
    """The gradebook export Canvas writes for ``course`` (``GradebookExporter``): identity
    columns, one column per assignment titled ``title (id)``, the totals, a ``Points
    Possible`` row with ``(read only)`` under the totals (and under ``read_only_points``
    assignments, to model a column Canvas marks so), ``EX`` for excused, ``N/A`` for not
    assigned."""
    import csv
    import io

    out = io.StringIO(newline="")
    writer = csv.writer(out, lineterminator="\n")
    names = ["LastName", "FirstName"] if last_first else ["Student"]
    identity = [*names, "ID", "SIS User ID", "SIS Login ID", "Section"]
    titles = [f"{a.title} ({a.id})" for a in course.assignments]
    totals = ["Current Score", "Unposted Current Score", "Final Score", "Unposted Final Score"]
    writer.writerow([*identity, *titles, *totals])
    points = ["(read only)" if a.id in read_only_points else _number(a.points_possible)
              for a in course.assignments]
    writer.writerow(["    Points Possible", *[""] * (len(identity) - 1), *points,
                     *["(read only)"] * len(totals)])
    for s in course.students:
        last, _, first = s.sortable_name.partition(", ")
        cells = []
        for a in course.assignments:
            if (s.id, a.id) in course.not_assigned:
                cells.append("N/A")
            else:
                cells.append(course.grades.get((s.id, a.id), ""))
        who = [last, first] if last_first else [s.sortable_name]
        writer.writerow([*who, s.id, s.sis_user_id, s.login_id, "ENGR 201", *cells,
                         "", "", "", ""])
    return out.getvalue()


def _number(value: float | None) -> str:
    return "" if value is None else f"{value:.2f}"
