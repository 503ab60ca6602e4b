"""Read a class roster: a Canvas gradebook export, a Moodle grades export, or a plain CSV.

The format is recognised from the header row:

* **Canvas** gradebook export: ``Student,ID,SIS User ID,SIS Login ID,[...,]Section,<assignments>``
  (or, with separate name columns, ``LastName,FirstName,ID,...``). Its ``Points Possible`` row
  (kept in :attr:`Roster.points_possible`) and other metadata rows (``Muted``, ``Manual
  Posting``: no ``ID``) are not students; the Canvas *Test Student* is skipped and listed in
  :attr:`Roster.skipped`.
* **Moodle** grades export: ``First name,Last name,ID number,Institution,Department,
  Email address,<grade items>`` (comma, semicolon or tab separated).
* **Plain** CSV: ``id,name[,email][,section][,...]``.

Each :class:`RosterStudent` keeps every identity column of its row, in order, in ``columns``
so an export can write the same identity back, and its other cells (the grades already in the
LMS) in ``cells``, so an export never overwrites them unknowingly.

>>> import tempfile, pathlib
>>> p = pathlib.Path(tempfile.mkdtemp()) / "class.csv"
>>> _ = p.write_text("id,name,email\\ns1,Ada Lovelace,ada@uni.edu\\n", encoding="utf-8")
>>> r = read_roster(p)
>>> r.format, r.students[0].id, r.students[0].email
(<RosterFormat.PLAIN: 'plain'>, 's1', 'ada@uni.edu')
"""

from __future__ import annotations

import csv
import io
import os
import re
import unicodedata
from dataclasses import dataclass
from enum import Enum
from pathlib import Path
from typing import Collection, Mapping, Sequence

from .files import read_text
from .errors import AssignmentError, Location


class RosterFormat(Enum):
    """Which export a roster file is (see the module doc), read from its header row."""

    CANVAS = "canvas"
    MOODLE = "moodle"
    PLAIN = "plain"


_CANVAS_META_ROWS = {"points possible", "muted", "manual posting", ""}
_CANVAS_TEST_NAMES = {"student, test", "test student"}
_CANVAS_IDENTITY = {"student", "lastname", "firstname", "id", "sis user id", "sis login id",
                    "integration id", "root account", "section"}
_MOODLE_IDENTITY = {"first name", "last name", "id number", "institution", "department",
                    "email address", "username", "phone", "mobile phone", "address",
                    "city/town", "country"}


@dataclass(frozen=True)
class RosterStudent:
    """One student of the roster; ``columns`` keeps the identity cells as ``(header, value)``,
    ``cells`` the row's other cells (grades already in the LMS) the same way."""

    id: str
    name: str
    email: str = ""
    sis_user_id: str = ""
    sis_login_id: str = ""
    section: str = ""
    columns: tuple[tuple[str, str], ...] = ()
    cells: tuple[tuple[str, str], ...] = ()

    def cell(self, column: str) -> str | None:
        """The student's cell in ``column`` (``None`` when the roster has no such column).

        >>> RosterStudent("1", "Ada", cells=(("Homework 1 (40211)", "EX"),)).cell(
        ...     "Homework 1 (40211)")
        'EX'
        """
        return next((value for name, value in self.cells if name == column), None)


@dataclass(frozen=True)
class Roster:
    """The students of a roster file in file order.

    ``header`` is the file's whole header row (identity and grade columns); ``skipped`` lists
    ``(line, reason)`` for rows that were deliberately not read as students;
    ``points_possible`` holds the cells of a Canvas export's ``Points Possible`` row by column
    (``"19"``, or ``"(read only)"`` for a column Canvas does not import).
    """

    students: tuple[RosterStudent, ...]
    format: RosterFormat
    header: tuple[str, ...]
    skipped: tuple[tuple[int, str], ...] = ()
    points_possible: tuple[tuple[str, str], ...] = ()

    @property
    def identity_header(self) -> tuple[str, ...]:
        """The names of the identity columns, as kept in each student's ``columns``."""
        return _identity_columns(self.format, self.header)


class MatchKind(Enum):
    """An identifier a roster student is matched by; members in the order they are tried."""

    ID = "id"
    SIS_USER_ID = "sis_user_id"
    SIS_LOGIN_ID = "sis_login_id"
    EMAIL = "email"
    EMAIL_USER = "email_user"
    NAME = "name"

    @property
    def words(self) -> str:
        """The identifier as messages name it.

        >>> MatchKind.SIS_USER_ID.words
        'SIS user id'
        """
        return {MatchKind.SIS_USER_ID: "SIS user id", MatchKind.SIS_LOGIN_ID: "SIS login id",
                MatchKind.EMAIL_USER: "email user name"}.get(self, self.value)


MATCH_KINDS = tuple(MatchKind)
"""The identifiers a roster student is matched by, in the order they are tried."""


def normalise_name(name: str) -> str:
    """A name as a comparison key: "Last, First" turned around, case and spacing folded.

    >>> normalise_name("O'Brien,  Seán") == normalise_name("seán o'brien")
    True
    """
    if name.count(",") == 1:
        last, first = name.split(",")
        name = f"{first} {last}"
    name = unicodedata.normalize("NFC", name)
    return re.sub(r"\s+", " ", name).strip().casefold()


def fold(identifier: str) -> str:
    """An identifier as a comparison key (NFC, trimmed, case-folded)."""
    return unicodedata.normalize("NFC", identifier).strip().casefold()


def identifier(student: RosterStudent, kind: MatchKind) -> str:
    """A roster student's identifier of ``kind`` as written (``""`` when it has none); its
    email user name is its email before the ``@``.

    >>> identifier(RosterStudent("1", "Ada", email="Ada@uni.edu"), MatchKind.EMAIL_USER)
    'Ada'
    """
    if kind is MatchKind.EMAIL_USER:
        return student.email.split("@", 1)[0] if "@" in student.email else ""
    return getattr(student, kind.value)


def student_keys(student: RosterStudent) -> dict[MatchKind, str]:
    """A roster student's identifiers by kind, folded (a name as :func:`normalise_name`)."""
    return {kind: normalise_name(student.name) if kind is MatchKind.NAME
            else fold(identifier(student, kind)) for kind in MatchKind}


@dataclass(frozen=True)
class RosterConflict:
    """Roster students and candidates (folders, results) that match each other other than one
    to one: none of them is paired. ``routes`` holds ``(student, candidate, kinds)`` for every
    match: the indices of a roster student and a candidate, and the kinds of identifier by
    which they match."""

    students: tuple[int, ...]
    candidates: tuple[int, ...]
    routes: tuple[tuple[int, int, tuple[MatchKind, ...]], ...]

    def describe(self, roster: Roster, labels: Sequence[str]) -> str:
        """Every match, with the candidates named by ``labels`` (their folder names or ids):
        ``'101' matches Ada Lovelace (101) by id; 'ada' matches ...``."""
        return "; ".join(
            f"'{labels[c]}' matches {roster.students[s].name or roster.students[s].id} "
            f"({roster.students[s].id}) by " + " and ".join(k.words for k in kinds)
            for s, c, kinds in self.routes)


@dataclass(frozen=True)
class Pairing:
    """The outcome of :func:`pair_students`: ``(candidate index or None, kind or None)`` per
    roster student, in roster order, and the conflicts that left students unpaired."""

    pairs: tuple[tuple[int | None, MatchKind | None], ...]
    conflicts: tuple[RosterConflict, ...] = ()


def pair_students(roster: Roster, candidates: Sequence[Mapping[MatchKind, Collection[str]]]
                  ) -> Pairing:
    """Pair roster students with candidates, each with at most one, never by a guess.

    A candidate offers folded identifiers per kind of :data:`MATCH_KINDS`; it matches a roster
    student whose identifier of that kind it offers (an identifier two roster students share
    identifies neither). A roster student and a candidate that match only each other are
    paired, by the first kind in :data:`MATCH_KINDS` order by which they match. Students and
    candidates matching more than that (two folders one student, one folder two students,
    through any kinds) form a :class:`RosterConflict`: none of them is paired, so a folder
    named with one student's id never wins over that student's own folder.

    >>> roster = Roster((RosterStudent("101", "Ada Lovelace", sis_login_id="ada"),
    ...                  RosterStudent("102", "Bob Roe")), RosterFormat.PLAIN, ("id", "name"))
    >>> pair_students(roster, [{MatchKind.SIS_LOGIN_ID: {"ada"}}, {MatchKind.ID: {"999"}}]).pairs
    ((0, <MatchKind.SIS_LOGIN_ID: 'sis_login_id'>), (None, None))
    """
    owners: dict[tuple[MatchKind, str], list[int]] = {}
    for s, student in enumerate(roster.students):
        for kind, key in student_keys(student).items():
            if key:
                owners.setdefault((kind, key), []).append(s)
    routes: dict[tuple[int, int], list[MatchKind]] = {}
    for c, offered in enumerate(candidates):
        for kind in MATCH_KINDS:
            for key in offered.get(kind, ()):
                owner = owners.get((kind, key), [])
                if len(owner) == 1 and kind not in routes.get((owner[0], c), []):
                    routes.setdefault((owner[0], c), []).append(kind)
    # the students and candidates linked by matches, as connected groups (union-find)
    parent: dict[tuple[str, int], tuple[str, int]] = {}

    def root(node: tuple[str, int]) -> tuple[str, int]:
        while parent.setdefault(node, node) != node:
            parent[node] = parent[parent[node]]
            node = parent[node]
        return node

    for s, c in routes:
        parent[root(("s", s))] = root(("c", c))
    groups: dict[tuple[str, int], list[tuple[int, int]]] = {}
    for s, c in sorted(routes):
        groups.setdefault(root(("s", s)), []).append((s, c))
    pairs: list[tuple[int | None, MatchKind | None]] = [(None, None)] * len(roster.students)
    conflicts = []
    for links in groups.values():
        students = tuple(sorted({s for s, _ in links}))
        found = tuple(sorted({c for _, c in links}))
        if len(students) == 1 and len(found) == 1:
            kinds = routes[students[0], found[0]]
            pairs[students[0]] = (found[0], min(kinds, key=MATCH_KINDS.index))
        else:
            conflicts.append(RosterConflict(students, found, tuple(
                (s, c, tuple(sorted(routes[s, c], key=MATCH_KINDS.index))) for s, c in links)))
    return Pairing(tuple(pairs), tuple(sorted(conflicts, key=lambda k: k.students)))


def read_roster(path: str | os.PathLike) -> Roster:
    """Read a roster CSV file; a malformed file raises :class:`AssignmentError` at file:line."""
    name = str(path)
    text = _read_text(Path(path))
    lines = text.splitlines()
    first = next((i for i, line in enumerate(lines) if line.strip()), None)
    if first is None:
        raise AssignmentError("expected a roster header row, found an empty file",
                              where=Location(name, 1))
    delimiter = _delimiter(lines[first])
    rows = _records(text, delimiter, name)
    if not rows:
        raise AssignmentError("expected a roster header row, found an empty file",
                              where=Location(name, 1))
    header_line, cells = rows[0]
    header = tuple(cell.strip() for cell in cells)
    kind = header_format(header)
    if kind is None:
        raise AssignmentError(
            "expected a roster header: a Canvas gradebook export (Student,ID,SIS User ID,"
            "SIS Login ID,Section,...), a Moodle grades export (First name,Last name,ID number,"
            "...,Email address) or a plain CSV (id,name[,email]); found "
            f"{','.join(header)!r}", where=Location(name, header_line))
    _check_duplicate_headers(header, name, header_line)
    reader = {RosterFormat.CANVAS: _canvas_student, RosterFormat.MOODLE: _moodle_student,
              RosterFormat.PLAIN: _plain_student}[kind]
    identity = _identity_columns(kind, header)
    students: list[RosterStudent] = []
    skipped: list[tuple[int, str]] = []
    points_possible: tuple[tuple[str, str], ...] = ()
    seen: dict[str, int] = {}
    for line, cells in rows[1:]:
        if not any(cell.strip() for cell in cells):
            continue
        if len(cells) > len(header):
            raise AssignmentError(
                f"expected at most {len(header)} cells as in the header, found {len(cells)}",
                where=Location(name, line))
        record = {h: (cells[i].strip() if i < len(cells) else "") for i, h in enumerate(header)}
        if kind is RosterFormat.CANVAS and "Points Possible" in cells[0]:
            # Canvas's own test (gradebook_importer.rb, check_for_non_student_row)
            points_possible = tuple((h, v) for h, v in record.items()
                                    if h not in identity and v)
            continue
        student = reader(record, name, line, skipped)
        if student is None:
            continue
        if student.id in seen:
            raise AssignmentError(
                f"expected each student once, found id {student.id!r} again "
                f"(first on line {seen[student.id]})", where=Location(name, line))
        seen[student.id] = line
        columns = tuple((h, record[h]) for h in identity)
        others = tuple((h, v) for h, v in record.items() if h and h not in identity)
        students.append(RosterStudent(student.id, student.name, student.email,
                                      student.sis_user_id, student.sis_login_id,
                                      student.section, columns, others))
    return Roster(tuple(students), kind, header, tuple(skipped), points_possible)


def _read_text(path: Path) -> str:
    return read_text(path, what="a roster CSV file", error=AssignmentError,
                     hint=" (save the roster as 'CSV UTF-8')")


def _delimiter(header_line: str) -> str:
    # Moodle lets the teacher pick the separator; the header tells which one was used.
    counts = {d: len(next(csv.reader([header_line], delimiter=d))) for d in (",", ";", "\t")}
    return max(counts, key=lambda d: (counts[d], d == ","))


def _records(text: str, delimiter: str, name: str) -> list[tuple[int, list[str]]]:
    reader = csv.reader(io.StringIO(text, newline=""), delimiter=delimiter, strict=True)
    rows: list[tuple[int, list[str]]] = []
    start = 1
    try:
        for cells in reader:
            rows.append((start, cells))
            start = reader.line_num + 1
    except csv.Error as err:
        raise AssignmentError(f"expected CSV cells, found bad quoting ({err})",
                              where=Location(name, start)) from None
    return rows


def header_format(header: tuple[str, ...]) -> RosterFormat | None:
    """The roster format a header row belongs to (see module doc), or ``None``.

    >>> header_format(("Student", "ID", "SIS User ID", "Section")), header_format(("x",))
    (<RosterFormat.CANVAS: 'canvas'>, None)
    >>> header_format(("LastName", "FirstName", "ID", "SIS User ID", "Section"))
    <RosterFormat.CANVAS: 'canvas'>
    """
    low = {h.lower() for h in header}
    if ({"student", "id"} <= low or {"lastname", "firstname", "id"} <= low) \
            and low & {"sis user id", "sis login id", "section"}:
        return RosterFormat.CANVAS
    if {"first name", "last name"} <= low or "email address" in low:
        return RosterFormat.MOODLE
    if {"id", "name"} <= low:
        return RosterFormat.PLAIN
    return None


def _check_duplicate_headers(header: tuple[str, ...], name: str, line: int) -> None:
    seen: set[str] = set()
    for i, h in enumerate(header, start=1):
        if h and h.lower() in seen:
            raise AssignmentError(f"expected distinct column names, found {h!r} twice",
                                  where=Location(name, line, i))
        seen.add(h.lower())


def _identity_columns(kind: RosterFormat, header: tuple[str, ...]) -> tuple[str, ...]:
    if kind is RosterFormat.CANVAS:
        return tuple(h for h in header if h.lower() in _CANVAS_IDENTITY)
    if kind is RosterFormat.MOODLE:
        return tuple(h for h in header if h.lower() in _MOODLE_IDENTITY)
    return tuple(h for h in header if h)


def _get(record: dict[str, str], *names: str) -> str:
    for key, value in record.items():
        if key.lower() in names:
            return value
    return ""


def _column(record: dict[str, str], wanted: str) -> str:
    return next(k for k in record if k.lower() == wanted)


def _canvas_student(record, name, line, skipped):
    student = _get(record, "student")
    if not student and _get(record, "lastname", "firstname"):
        # the gradebook layout with separate name columns
        last, first = _get(record, "lastname"), _get(record, "firstname")
        student = f"{last}, {first}" if last and first else last or first
    canvas_id = _get(record, "id")
    if not canvas_id:
        if student.lower() in _CANVAS_META_ROWS:
            return None  # Points Possible / Muted / Manual Posting rows describe assignments
        raise AssignmentError(f"column {_column(record, 'id')!r}: expected a Canvas user ID "
                              f"for {student!r}, found an empty cell",
                              where=Location(name, line))
    if student.lower() in _CANVAS_TEST_NAMES:
        skipped.append((line, f"Canvas test student {student!r}"))
        return None
    return RosterStudent(canvas_id, _display_name(student),
                         sis_user_id=_get(record, "sis user id"),
                         sis_login_id=_get(record, "sis login id"),
                         section=_get(record, "section"),
                         email=_email_like(_get(record, "sis login id")))


def _moodle_student(record, name, line, _skipped):
    first, last = _get(record, "first name"), _get(record, "last name")
    email, number = _get(record, "email address"), _get(record, "id number")
    if not (email or number):
        raise AssignmentError("expected an 'Email address' or 'ID number' to identify the "
                              f"student {f'{first} {last}'.strip()!r}, found both empty",
                              where=Location(name, line))
    return RosterStudent(number or email, f"{first} {last}".strip(), email=email,
                         sis_user_id=number, sis_login_id=_get(record, "username"),
                         section=_get(record, "department"))


def _plain_student(record, name, line, _skipped):
    student_id = _get(record, "id")
    if not student_id:
        raise AssignmentError(f"column {_column(record, 'id')!r}: expected a student id, "
                              "found an empty cell", where=Location(name, line))
    return RosterStudent(student_id, _get(record, "name"), email=_get(record, "email"),
                         sis_user_id=_get(record, "sis_user_id", "sis user id"),
                         sis_login_id=_get(record, "sis_login_id", "sis login id", "login"),
                         section=_get(record, "section"))


def _display_name(canvas_name: str) -> str:
    """Canvas writes "Last, First"; reports read better as "First Last"."""
    if canvas_name.count(",") == 1 and not re.search(r'[()"=@]', canvas_name):
        last, first = (part.strip() for part in canvas_name.split(","))
        if first and last:
            return f"{first} {last}"
    return canvas_name


def _email_like(login: str) -> str:
    return login if re.fullmatch(r"[^@\s]+@[^@\s]+\.[^@\s]+", login) else ""
