"""A quiz's responses exported by the LMS, read as submissions.

* **Canvas "Student Analysis"** CSV (canvas-lms ``app/models/quizzes/quiz_statistics/
  student_analysis.rb``, ``to_csv``): ``name,id[,sis_id][,root_account],section,section_id
  [,section_sis_id],submitted[,attempt]``, then per question a column
  ``<question id>: <question text>`` (tags stripped) and one of its points, then ``n correct,
  n incorrect,score``. The student is the Canvas user ``id``; with every attempt included, the
  highest ``attempt`` of a student is read.
* **Moodle quiz "Responses"** report: ``Last name`` (or ``Surname``), ``First name``, the site's
  identity columns (``ID number``, ``Email address``), ``State``, ..., and per question slot
  ``Response N``, with ``Question N`` (the question's text) when the report is set to include
  it. The student is the ``ID number``, else the ``Email address``; the last finished attempt of
  a student is read.

A response is an answer to the objective whose key appears in its question's text as
``mechgrade key: problem_id.objective_id`` (``mechgrade export-questions`` writes it in every
item it exports); a question without one is listed as not read. Numbers a quiz drew per
attempt are not a student's mechgrade variant: the responses to objectives of problems with
variants (``drawn_keys``) are graded by the LMS itself, and left out with that reason.
"""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path

from ..errors import Location, SubmissionError
from ..files import clean_text, read_text
from .results import SkippedEntry
from .submissions import Submission, SubmissionFormat, SubmissionSet, SubmissionStatus

QUIZ_FORMATS = (SubmissionFormat.CANVAS_QUIZ_CSV, SubmissionFormat.MOODLE_QUIZ_CSV)
KEY = re.compile(r"mechgrade key:\s*(?P<key>[A-Za-z0-9_][A-Za-z0-9_.-]*\.[A-Za-z_][A-Za-z0-9_]*)")
MAX_BYTES = 100_000_000
_CANVAS_QUESTION = re.compile(r"(?P<id>\d+): (?P<text>.*)", re.DOTALL)


def key_marker(key: str) -> str:
    """The text an exported question carries so its responses find their objective.

    >>> KEY.search("Find v. " + key_marker("pend.v"))["key"]
    'pend.v'
    """
    return f"(mechgrade key: {key})"


def read_quiz_responses(path: str | Path, fmt: SubmissionFormat | None = None, *, keys=None,
                        drawn_keys=frozenset()) -> SubmissionSet:
    """Read a quiz's responses CSV (``fmt`` one of :data:`QUIZ_FORMATS`, detected when
    ``None``); raises :class:`SubmissionError` at the line of anything malformed."""
    path = Path(path)
    name = clean_text(str(path))
    text = read_text(path, what="a quiz responses CSV file", error=SubmissionError,
                     max_bytes=MAX_BYTES, hint=" (save it as 'CSV UTF-8')")
    try:
        rows = list(csv.reader(io.StringIO(text, newline=""), strict=True))
    except csv.Error as err:
        raise SubmissionError(f"expected CSV, found bad quoting ({err})",
                              where=Location(name)) from None
    if not rows:
        raise SubmissionError("expected a header row, found an empty file", where=Location(name))
    header = [h.strip() for h in rows[0]]
    fmt = fmt or _detect(header)
    if fmt == SubmissionFormat.CANVAS_QUIZ_CSV:
        return _canvas(path, header, rows[1:], keys, drawn_keys)
    if fmt == SubmissionFormat.MOODLE_QUIZ_CSV:
        return _moodle(path, header, rows[1:], keys, drawn_keys)
    raise SubmissionError("expected a Canvas quiz 'Student Analysis' CSV (name,id,...,section,"
                          "...) or a Moodle quiz 'Responses' CSV (...,Response 1,...), found "
                          f"the header {','.join(header[:6])!r}...", where=Location(name, 1))


def _detect(header: list[str]) -> SubmissionFormat | None:
    low = [h.lower() for h in header]
    if low[:2] == ["name", "id"] and "section" in low:
        return SubmissionFormat.CANVAS_QUIZ_CSV
    if any(re.fullmatch(r"response \d+", h) for h in low):
        return SubmissionFormat.MOODLE_QUIZ_CSV
    return None


def _key_of(text: str, keys) -> str | None:
    found = KEY.search(text)
    if not found:
        return None
    key = found["key"]
    return key if keys is None or key in keys else None


def _canvas(path: Path, header: list[str], rows: list[list[str]], keys, drawn_keys
            ) -> SubmissionSet:
    name = clean_text(str(path))
    low = [h.lower() for h in header]
    ident, attempt = low.index("id"), (low.index("attempt") if "attempt" in low else None)
    columns: dict[int, str] = {}
    skipped: list[SkippedEntry] = []
    for i, column in enumerate(header):
        found = _CANVAS_QUESTION.fullmatch(column)
        if not found:
            continue
        key = _key_of(found["text"], keys)
        where = f"{path.name}: column {i + 1} ({_short(column)})"
        if key is None:
            skipped.append(SkippedEntry(where, "no 'mechgrade key: problem.objective' of this "
                                               "assignment in the question's text"))
        elif key in drawn_keys:
            skipped.append(SkippedEntry(where, f"'{key}' draws numbers per student: Canvas "
                                               "grades its responses with the numbers it drew"))
        else:
            columns[i] = key
    latest: dict[str, tuple[int, list[str], int]] = {}
    for line, row in _records(rows, len(header), name):
        student = row[ident].strip()
        if not student:
            skipped.append(SkippedEntry(f"{path.name}: line {line}", "no Canvas user id (a "
                                        "logged-out or anonymous attempt)"))
            continue
        number = int(row[attempt]) if attempt is not None and row[attempt].isdigit() else 0
        if student not in latest or number > latest[student][0]:
            latest[student] = (number, row, line)
    students = tuple(_submission(student, row, columns, f"{path.name}:{line}")
                     for student, (_, row, line) in sorted(latest.items()))
    return SubmissionSet(path, students, tuple(skipped), ())


def _moodle(path: Path, header: list[str], rows: list[list[str]], keys, drawn_keys
            ) -> SubmissionSet:
    name = clean_text(str(path))
    low = [h.lower() for h in header]
    who = next((low.index(c) for c in ("id number", "email address") if c in low), None)
    if who is None:
        raise SubmissionError("expected an 'ID number' or 'Email address' column to name the "
                              "students (Moodle's identity fields), found neither",
                              where=Location(name, 1))
    state = low.index("state") if "state" in low else None
    slots = {int(m[1]): i for i, h in enumerate(low) if (m := re.fullmatch(r"response (\d+)", h))}
    texts = {int(m[1]): i for i, h in enumerate(low) if (m := re.fullmatch(r"question (\d+)", h))}
    if slots and not texts:
        raise SubmissionError("expected the questions' text in the report (a 'Question N' "
                              "column beside each 'Response N': in Moodle's Responses report "
                              "show the question text), found responses only: which objective "
                              "each answers cannot be told", where=Location(name, 1))
    skipped: list[SkippedEntry] = []
    latest: dict[str, tuple[list[str], int]] = {}
    for line, row in _records(rows, len(header), name):
        if state is not None and row[state].strip().lower() not in ("finished", ""):
            skipped.append(SkippedEntry(f"{path.name}: line {line}",
                                        f"an attempt not finished ({row[state].strip()})"))
            continue
        student = row[who].strip()
        if student:
            latest[student] = (row, line)  # the report lists attempts in order
    students = []
    for student, (row, line) in sorted(latest.items()):
        columns: dict[int, str] = {}
        for slot, response in slots.items():
            key = _key_of(row[texts[slot]], keys) if slot in texts else None
            if key is not None and key not in drawn_keys:
                columns[response] = key
        students.append(_submission(student, row, columns, f"{path.name}:{line}"))
    unread = sorted(slot for slot in slots if slot in texts and all(
        _key_of(r[texts[slot]], keys) is None for r, _ in latest.values()))
    for slot in unread:
        skipped.append(SkippedEntry(f"{path.name}: Response {slot}", "no 'mechgrade key: "
                                    "problem.objective' of this assignment in the question"))
    for slot in sorted(slots):
        keys_here = {k for r, _ in latest.values()
                     if (k := _key_of(r[texts[slot]], keys)) is not None}
        for key in sorted(keys_here & set(drawn_keys)):
            skipped.append(SkippedEntry(f"{path.name}: Response {slot}",
                                        f"'{key}' draws numbers per student: Moodle grades "
                                        "its responses with the numbers it drew"))
    return SubmissionSet(path, tuple(students), tuple(skipped), ())


def _records(rows: list[list[str]], width: int, name: str):
    """``(line, row)`` of each row that is not blank; a row of another width is refused."""
    for line, row in enumerate(rows, start=2):
        if not any(c.strip() for c in row):
            continue
        if len(row) != width:
            raise SubmissionError(f"expected {width} cells as in the header, found "
                                  f"{len(row)}", where=Location(name, line))
        yield line, row


def _submission(student: str, row: list[str], columns: dict[int, str], where: str
                ) -> Submission:
    answers: dict[str, str] = {}
    messages = []
    for index, key in columns.items():
        text = row[index].strip()
        if not text:
            continue
        if key in answers:
            messages.append(f"{where}: '{key}' is answered in two questions; the later one "
                            "was graded")
        answers[key] = text
    status = SubmissionStatus.READ if answers else SubmissionStatus.MISSING
    if not answers:
        messages.append(f"{where}: no response to a question of this assignment")
    return Submission(clean_text(student), status, tuple(sorted(answers.items())),
                      tuple(messages), (where,) if answers else ())


def _short(text: str, limit: int = 50) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit - 3] + "..."
