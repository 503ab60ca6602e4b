"""Read a folder of student submissions, whatever students put in it.

Layout: one sub-folder per student (the folder name is the student id) holding
``answers.yaml``, ``answers.json`` or ``answers.txt``; or one file per student directly in the
folder (``<student_id>.yaml|.yml|.json|.txt``). Answers are keyed by
``problem_id.objective_id`` (YAML and JSON may also nest ``{problem_id: {objective_id: ...}}``)
and kept as the text the student typed. ``answers.txt`` holds ``key = value`` lines; ``#``
starts a comment.

Nothing a student does stops the reading: binary or oversized files, text that is not UTF-8,
links pointing outside the folder, empty folders, repeated or unknown keys and several files for
one student are all reported in that student's messages.

>>> import tempfile, pathlib
>>> root = pathlib.Path(tempfile.mkdtemp())
>>> _ = (root / "ana.txt").write_text("# hw1\\np.speed = 7.0 m/s\\np.angle = 30 deg\\n")
>>> (ana,) = read_submissions(root).students
>>> ana.student, ana.status, ana.answer("p.speed")
('ana', <SubmissionStatus.READ: 'read'>, '7.0 m/s')
"""

from __future__ import annotations

import json
import os
import stat
import unicodedata
from dataclasses import dataclass
from enum import Enum
from functools import partial
from pathlib import Path

from ..errors import MechgradeError, SubmissionError, brief_exception
from ..expressions.functions import StrEnum
from ..files import clean_text
from ..parallel import fork_map
from ..yamlio import read_yaml_text
from .results import SkippedEntry

MAX_FILE_BYTES = 256 * 1024
MAX_LISTED_KEYS = 10
"""The most messages of one kind (an unknown key, a key answered again, a line not read, a
stray file) listed for one student; the rest are counted in one message, so that what a file
repeats thousands of times is not repeated in every output."""
ANSWER_FILES = ("answers.yaml", "answers.yml", "answers.json", "answers.txt")
SUFFIXES = (".yaml", ".yml", ".json", ".txt")
SYSTEM_NAMES = {"__MACOSX": "made by macOS when zipping", "Thumbs.db": "made by Windows Explorer",
                "desktop.ini": "made by Windows Explorer"}
SHARED_WORK = "it was not read (two students handing in the same work)"
NOT_A_SUBMISSION = ("not a submission: expected a folder per student or a file "
                    "<student_id>.yaml, .yml, .json or .txt")
NOT_AN_ANSWER_FILE = "not an answers file: answers go in answers.yaml, answers.json or answers.txt"


class _Unread(SubmissionError):
    """A file that gave no answers, with the notes gathered while reading it."""

    def __init__(self, message: str, *, where=None, notes: list[str] | tuple = ()) -> None:
        super().__init__(message, where=where)
        self.notes = tuple(notes)


class SubmissionFormat(StrEnum):
    """What a class's hand-ins come as: a folder, an LMS's download zip or a quiz's responses
    CSV (``mechgrade grade --submissions-format``)."""

    FOLDER = "folder"
    CANVAS_ZIP = "canvas-zip"
    MOODLE_ZIP = "moodle-zip"
    GRADESCOPE_ZIP = "gradescope-zip"
    CANVAS_QUIZ_CSV = "canvas-quiz-csv"
    MOODLE_QUIZ_CSV = "moodle-quiz-csv"


class SubmissionStatus(StrEnum):
    """What came of reading one student's hand-in."""

    READ = "read"
    MISSING = "missing"
    UNREADABLE = "unreadable"


@dataclass(frozen=True)
class Submission:
    """What one student handed in.

    ``student`` is the folder or file name exactly as it is (no Unicode normalisation, spaces
    kept; bytes that are not UTF-8 in the escaped form ``\\xNN``). ``status`` is ``read`` (at
    least one answer file was read), ``missing`` (nothing handed in) or ``unreadable`` (files
    were there but none could be read). ``answers`` are ``(key, text)`` pairs sorted by key;
    ``files`` the files read, relative to the folder; ``internal_error`` says what went wrong
    when reading failed through a fault of mechgrade's, not of the student's.
    """

    student: str
    status: SubmissionStatus
    answers: tuple[tuple[str, str], ...] = ()
    messages: tuple[str, ...] = ()
    files: tuple[str, ...] = ()
    internal_error: str | None = None

    def answer(self, key: str) -> str | None:
        for name, text in self.answers:
            if name == key:
                return text
        return None


@dataclass(frozen=True)
class SubmissionSet:
    """Every student found in a submissions folder (sorted by id), every entry of it that was
    not read (with the reason), and notes about the folder as a whole."""

    folder: Path
    students: tuple[Submission, ...]
    skipped: tuple[SkippedEntry, ...] = ()
    notes: tuple[str, ...] = ()


def read_submissions(folder: str | Path, *, keys: frozenset[str] | set[str] | None = None,
                     jobs: int = 1) -> SubmissionSet:
    """Read every submission in ``folder``.

    Every entry of the folder ends up either in a student's submission or in ``skipped`` with
    its reason. Reading one student is one unit of work: whatever goes wrong inside it makes
    that student ``unreadable`` and the reading goes on.

    When ``keys`` (the assignment's ``problem_id.objective_id`` keys) is given, answers under
    other keys are reported in the student's messages, and a key that matches one of ``keys``
    but for letter case is read as that key (also reported). Raises :class:`SubmissionError`
    only when ``folder`` itself cannot be listed. The students are read by ``jobs`` processes.
    """
    folder = Path(folder)
    try:
        root = folder.resolve(strict=True)
        entries = sorted(os.scandir(root), key=lambda e: e.name)
    except OSError as exc:
        raise SubmissionError(f"expected a folder of submissions, found "
                              f"{'nothing' if isinstance(exc, FileNotFoundError) else 'an unreadable path'}"
                              f" at '{folder}'") from None
    found: dict[str, list[_Source]] = {}
    skipped: list[SkippedEntry] = []
    notes: list[str] = []
    for entry in entries:
        try:
            _sort_entry(entry, root, found, skipped, notes)
        except Exception as exc:  # noqa: BLE001 - one odd entry must not stop the run
            skipped.append(SkippedEntry(clean_text(entry.name),
                                        f"internal error while listing it: {brief_exception(exc)}"))
    students = tuple(fork_map(partial(_read_found, keys=keys), sorted(found.items()), jobs=jobs))
    for source in (s for sources in found.values() for s in sources):
        skipped.extend(source.skipped)
        if source.problem and source.problem.endswith(SHARED_WORK):
            notes.append(f"'{source.label}' {source.problem}")
    notes.extend(_look_alike_notes([s.student for s in students]))
    return SubmissionSet(folder, students, tuple(sorted(skipped, key=lambda e: e.path)),
                         tuple(notes))


def read_student_folder(folder: str | Path, student: str, *,
                        keys: frozenset[str] | set[str] | None = None) -> Submission:
    """Read one student's folder (``answers.yaml``, ``.json`` or ``.txt`` inside it), such as a
    Gradescope submission in ``/autograder/submission``. Never raises: a folder that is not
    there is a ``missing`` submission."""
    folder = Path(folder)
    label = clean_text(folder.name or str(folder))
    try:
        root = folder.resolve(strict=True)
    except OSError:
        return Submission(student, SubmissionStatus.MISSING, messages=(f"no submission folder at "
                                                        f"'{clean_text(str(folder))}'",))
    sources = _folder_sources(root, root, label)
    if not any(s.path or s.problem or s.ignored for s in sources):
        sources.append(_Source(label, None, None, empty=True))
    return _read_student_safely(student, sources, keys)


@dataclass
class _Source:
    label: str  # path relative to the submissions folder, for messages (cleaned)
    path: Path | None
    problem: str | None  # why the file is not read, if it is not
    empty: bool = False
    ignored: tuple[str, ...] = ()  # other files in a student's folder
    skipped: tuple[SkippedEntry, ...] = ()  # what is not read, for the run's skipped list
    renamed: bool = False  # an answers file whose name is not written the usual way


def _sort_entry(entry: os.DirEntry, root: Path, found: dict, skipped: list,
                _notes: list) -> None:
    """Put one entry of the submissions folder into a student's sources or the skipped list."""
    name, shown = entry.name, clean_text(entry.name)
    if name.startswith("."):
        skipped.append(SkippedEntry(shown, "hidden (its name starts with '.')"))
        return
    if name in SYSTEM_NAMES:
        skipped.append(SkippedEntry(shown, f"{SYSTEM_NAMES[name]}, not a submission"))
        return
    path = root / name
    kind, what = _kind_of(path)
    if kind is _Entry.DANGLING:
        skipped.append(SkippedEntry(shown, f"a link to nothing ('{_link_target(path)}')"))
        return
    is_answer_file = kind is _Entry.FILE and Path(name).suffix.lower() in SUFFIXES
    if kind is _Entry.OTHER or (kind is _Entry.FILE and not is_answer_file):
        reason = NOT_A_SUBMISSION if kind is _Entry.FILE else f"not a file or folder ({what})"
        skipped.append(SkippedEntry(shown, reason))
        return
    student = clean_text(name if kind is _Entry.FOLDER else Path(name).stem)
    sources = found.setdefault(student, [])
    link = _link_problem(path, root, own=name)
    if link is not None:
        sources.append(_Source(shown, None, link, skipped=(SkippedEntry(shown, link),)))
        return
    if kind is _Entry.FOLDER:
        inner = _folder_sources(path, root, shown, own=name)
        if not any(s.path or s.problem or s.ignored for s in inner):
            inner.append(_Source(shown, None, None, empty=True))
        sources.extend(inner)
    else:
        sources.append(_Source(shown, path, None))


class _Entry(Enum):
    """What a folder's entry is, as a submission reader tells them apart."""

    FOLDER = "folder"
    FILE = "file"
    DANGLING = "a link to nothing"
    OTHER = "something else"


def _kind_of(path: Path) -> tuple[_Entry, str]:
    """What the entry at ``path`` is, and in words (``a FIFO``, ``missing``, ...)."""
    try:
        info = os.stat(path)
    except FileNotFoundError:
        return (_Entry.DANGLING, _Entry.DANGLING.value) if os.path.islink(path) \
            else (_Entry.OTHER, "missing")
    except OSError as exc:
        return _Entry.OTHER, f"unreadable: {exc.strerror or exc}"
    if stat.S_ISDIR(info.st_mode):
        return _Entry.FOLDER, _Entry.FOLDER.value
    if stat.S_ISREG(info.st_mode):
        return _Entry.FILE, _Entry.FILE.value
    for test, noun in ((stat.S_ISFIFO, "a FIFO"), (stat.S_ISSOCK, "a socket"),
                       (stat.S_ISCHR, "a device"), (stat.S_ISBLK, "a device")):
        if test(info.st_mode):
            return _Entry.OTHER, noun
    return _Entry.OTHER, "an unknown kind of entry"


def _link_target(path: Path) -> str:
    try:
        return clean_text(os.readlink(path))
    except OSError:
        return "?"


def _link_problem(path: Path, root: Path, *, own: str) -> str | None:
    """Why a link must not be followed: it leads outside the submissions folder, or into
    another student's entry (two students handing in one file); ``None`` when it is fine."""
    if not os.path.islink(path) and not _has_link_above(path, root):
        return None
    try:
        target = path.resolve(strict=True)
        inside = target.relative_to(root)
    except (OSError, ValueError, RuntimeError):
        return "is a link to outside the submissions folder; it was not followed"
    top = inside.parts[0] if inside.parts else ""
    if top and top != own and _owner(top) != _owner(own):
        return (f"is a link to '{clean_text(inside.as_posix())}', inside another student's "
                f"submission: {SHARED_WORK}")
    return None


def _has_link_above(path: Path, root: Path) -> bool:
    parent = path.parent
    while parent != root and root in parent.parents:
        if os.path.islink(parent):
            return True
        parent = parent.parent
    return False


def _owner(name: str) -> str:
    """The student a top-level entry belongs to (``ana.yaml`` and ``ana/`` are both Ana's)."""
    suffix = Path(name).suffix
    return name[:-len(suffix)] if suffix.lower() in SUFFIXES else name


def _folder_sources(folder: Path, root: Path, label: str, *, own: str | None = None
                    ) -> list[_Source]:
    """The answer files of a student's folder, and what else it holds (reported, not read)."""
    own = own if own is not None else folder.name
    try:
        entries = sorted(os.scandir(folder), key=lambda e: e.name)
    except OSError as exc:
        reason = f"cannot be listed ({exc.strerror or exc})"
        return [_Source(label, None, reason, skipped=(SkippedEntry(label, reason),))]
    sources: list[_Source] = []
    ignored: list[str] = []
    skipped: list[SkippedEntry] = []
    others = 0
    # Answers files first in the documented order; names in another letter case are read too.
    rank = {name: i for i, name in enumerate(ANSWER_FILES)}
    answer_entries = sorted((e for e in entries if e.name.lower() in rank),
                            key=lambda e: (rank[e.name.lower()], e.name))
    for entry in answer_entries:
        shown = f"{label}/{clean_text(entry.name)}"
        path = folder / entry.name
        problem = (f"is a link to nothing ('{_link_target(path)}')"
                   if _kind_of(path)[0] is _Entry.DANGLING
                   else _link_problem(path, root, own=own))
        sources.append(_Source(shown, None if problem else path, problem,
                               renamed=entry.name not in ANSWER_FILES,
                               skipped=(SkippedEntry(shown, problem),) if problem else ()))
    for entry in entries:
        if entry.name.lower() in rank:
            continue
        shown = f"{label}/{clean_text(entry.name)}"
        others += 1
        hidden = entry.name.startswith(".") or entry.name in SYSTEM_NAMES
        if others <= MAX_LISTED_KEYS:
            reason = ("hidden (its name starts with '.')" if entry.name.startswith(".")
                      else f"{SYSTEM_NAMES[entry.name]}, not a submission" if hidden
                      else NOT_AN_ANSWER_FILE)
            skipped.append(SkippedEntry(shown, reason))
        if not hidden:
            ignored.append(clean_text(entry.name))
    if others > MAX_LISTED_KEYS:
        skipped.append(SkippedEntry(f"{label}/", f"{others - MAX_LISTED_KEYS} more entries of "
                                                 f"this folder are not answers files (not "
                                                 f"listed one by one)"))
    if ignored or skipped:
        sources.append(_Source(label, None, None, ignored=tuple(ignored), skipped=tuple(skipped)))
    return sources


def _read_student_safely(student: str, sources: list[_Source], keys) -> Submission:
    """:func:`_read_student` as one unit of work: a fault of mechgrade's while reading makes
    the student unreadable, with the reason, and never escapes."""
    try:
        return _read_student(student, sources, keys)
    except Exception as exc:  # noqa: BLE001 - the per-student boundary
        detail = brief_exception(exc)
        return Submission(student, SubmissionStatus.UNREADABLE,
                          messages=(f"internal error while reading this submission: {detail}; "
                                    f"please tell your instructor",),
                          internal_error=f"reading '{student}': {detail}")


def _read_found(found: tuple[str, list[_Source]], keys) -> Submission:
    return _read_student_safely(*found, keys)


def _look_alike_notes(students: list[str]) -> list[str]:
    """Notes on students whose names differ only in Unicode form, letter case or spaces: they
    stay distinct students, but an instructor should know."""
    groups: dict[str, list[str]] = {}
    for name in students:
        key = " ".join(unicodedata.normalize("NFKC", name).casefold().split())
        groups.setdefault(key, []).append(name)
    notes = []
    for names in (g for g in groups.values() if len(g) > 1):
        if len({unicodedata.normalize("NFC", n) for n in names}) == 1:
            how = "Unicode form"
        elif len({unicodedata.normalize("NFC", n).casefold() for n in names}) == 1:
            how = "letter case"
        else:
            how = "letter case, spaces or Unicode form"
        shown = ", ".join(f"'{n}' ({n.encode('ascii', 'backslashreplace').decode()})"
                          for n in names)
        notes.append(f"{len(names)} folders whose names differ only in {how}: {shown}; "
                     f"graded as {len(names)} different students")
    return notes


def _read_student(student: str, sources: list[_Source], keys) -> Submission:
    messages: list[str] = []
    answers: dict[str, tuple[str, str]] = {}  # key -> (text, file label)
    files: list[str] = []
    readable = 0
    tried = 0
    conflicts: list[str] = []
    for source in sources:
        if source.ignored:
            more = len(source.ignored) - MAX_LISTED_KEYS
            messages.append("ignored " + ", ".join(f"'{source.label}/{n}'"
                                                   for n in source.ignored[:MAX_LISTED_KEYS])
                            + (f" and {more} more files" if more > 0 else "")
                            + ": answers go in answers.yaml, answers.json or answers.txt")
            continue
        if source.empty:
            messages.append(f"the folder '{source.label}' is empty: no answers handed in")
            continue
        if source.path is None and source.problem is None:
            continue
        tried += 1
        if source.path is None:
            messages.append(f"'{source.label}' {source.problem}")
            continue
        try:
            pairs, notes = read_answer_file(source.path, label=source.label)
        except _Unread as err:
            messages.extend(err.notes)
            messages.append(str(err))
            continue
        readable += 1
        files.append(source.label)
        if source.renamed:
            messages.append(f"read '{source.label}' as the answers file")
        messages.extend(notes)
        for key, text in pairs:
            if key in answers and answers[key][0] != text:
                conflicts.append(f"'{key}' is answered in both '{answers[key][1]}' and "
                                 f"'{source.label}'; the answer in '{answers[key][1]}' was "
                                 f"graded")
                continue
            answers.setdefault(key, (text, source.label))
    listed(messages, conflicts, lambda more: f"{more} more keys are answered in two files; "
                                            f"the answer in the first was graded")
    if len(files) > 1:
        messages.append(f"answers were read from {len(files)} files ({', '.join(files)}) "
                        f"and combined")
    if keys is not None:
        answers = _match_keys(answers, keys, messages)
    if readable:
        status = SubmissionStatus.READ
    elif tried:
        status = SubmissionStatus.UNREADABLE
    else:
        status = SubmissionStatus.MISSING
    return Submission(student, status, tuple((k, answers[k][0]) for k in sorted(answers)),
                      tuple(messages), tuple(files))


def _match_keys(answers: dict, keys, messages: list[str]) -> dict:
    by_fold: dict[str, list[str]] = {}
    for key in keys:
        by_fold.setdefault(key.casefold(), []).append(key)
    out: dict = {}
    unknown: list[str] = []
    for key in sorted(answers):
        if key in keys:
            out.setdefault(key, answers[key])
            continue
        match = by_fold.get(key.casefold().replace(" ", ""), [])
        if len(match) == 1 and match[0] not in answers:
            messages.append(f"read the key '{key}' as '{match[0]}'")
            out[match[0]] = answers[key]
        else:
            unknown.append(key)
    listed(messages, [f"'{_short(key)}' ({answers[key][1]}) is not a question of this "
                      f"assignment; it was not graded" for key in unknown],
           lambda more: f"{more} more keys are not questions of this assignment; they were "
                        f"not graded")
    return out


def listed(messages: list[str], items: list[str], more) -> None:
    """``items`` (messages of one kind) added to ``messages``: at most
    :data:`MAX_LISTED_KEYS` of them, then ``more(count)`` saying how many more there are.

    >>> out = []
    >>> listed(out, [f"line {i}" for i in range(12)], lambda n: f"{n} more lines")
    >>> out[-2:], len(out)
    (['line 9', '2 more lines'], 11)
    """
    messages.extend(items[:MAX_LISTED_KEYS])
    if len(items) > MAX_LISTED_KEYS:
        messages.append(more(len(items) - MAX_LISTED_KEYS))


def _short(text: str, limit: int = 60) -> str:
    """A key or line as shown in a message: at most ``limit`` characters."""
    return text if len(text) <= limit else text[:limit - 3] + "..."


def read_answer_file(path: str | Path, *, label: str | None = None
                     ) -> tuple[list[tuple[str, str]], list[str]]:
    """Read one answer file into ``(key, text)`` pairs and notes about it.

    Raises :class:`SubmissionError` when nothing in the file can be read.

    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "answers.json"
    >>> _ = p.write_text('{"p": {"speed": 7.10, "angle": "30 deg"}}')
    >>> read_answer_file(p)
    ([('p.angle', '30 deg'), ('p.speed', '7.10')], [])
    """
    path = Path(path)
    label = label or path.name
    text, note = _read_text(path, label)
    notes: list[str] = [note] if note else []
    suffix = path.suffix.lower()
    if not text.strip():
        raise _Unread(f"'{label}' is empty: no answers handed in")
    if suffix in (".yaml", ".yml"):
        pairs = _from_yaml(text, label, notes)
    elif suffix == ".json":
        pairs = _from_json(text, label, notes)
    else:
        pairs = _from_txt(text, label, notes)
    # Nothing is cut here: the file size bounds the answers, and an answer too long to read is
    # refused by the answer reader with its true length.
    kept: dict[str, str] = {}
    twice: list[str] = []
    for key, value in pairs:
        if key in kept and kept[key] != value:
            twice.append(f"'{label}': '{_short(key)}' is answered twice (flat and nested); "
                         f"the later answer was graded")
        kept[key] = value
    listed(notes, twice, lambda more: f"'{label}': {more} more keys are answered twice (flat "
                                      f"and nested); the later answer was graded")
    if not kept:
        raise _Unread(f"'{label}' holds no answers (expected lines such as "
                              f"'problem_id.objective_id = 7.5 m/s')", notes=notes)
    return sorted(kept.items()), notes


def _read_text(path: Path, label: str) -> tuple[str, str | None]:
    try:
        # Opened without blocking and checked on the open descriptor, so a FIFO or a device
        # put in place of a file after it was listed is never read from.
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
        with os.fdopen(fd, "rb") as handle:
            info = os.fstat(handle.fileno())
            if not stat.S_ISREG(info.st_mode):
                raise _Unread(f"'{label}' is not a regular file; it was not read")
            if info.st_size > MAX_FILE_BYTES:
                raise _Unread(f"'{label}' is {info.st_size} bytes; answer files may be at "
                              f"most {MAX_FILE_BYTES} bytes")
            raw = handle.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise _Unread(f"'{label}' cannot be read ({exc.strerror or exc})") from None
    if len(raw) > MAX_FILE_BYTES:
        raise _Unread(f"'{label}' is larger than {MAX_FILE_BYTES} bytes; answer files "
                              f"may be at most {MAX_FILE_BYTES} bytes")
    for boms, codec in (((b"\xff\xfe\x00\x00", b"\x00\x00\xfe\xff"), "utf-32"),
                        ((b"\xff\xfe", b"\xfe\xff"), "utf-16")):
        if raw.startswith(boms):
            try:
                return raw.decode(codec), None
            except UnicodeDecodeError:
                raise _Unread(f"'{label}' is not readable text (bad {codec.upper()})") from None
    if b"\0" in raw:
        raise _Unread(f"'{label}' is a binary file, not text; expected answers typed "
                              f"as text")
    try:
        return raw.decode("utf-8-sig"), None
    except UnicodeDecodeError as exc:
        line = raw[:exc.start].count(b"\n") + 1
        bad = raw[exc.start]
    # Windows editors still save in cp1252; reading it is better than a zero, but the
    # student is told, since a misread character would change the answer.
    try:
        text = raw.decode("cp1252")
    except UnicodeDecodeError:
        raise _Unread(f"'{label}' is not UTF-8 text (byte 0x{bad:02x} on line {line}); "
                              f"save it as UTF-8") from None
    return text, (f"'{label}' is not UTF-8 (byte 0x{bad:02x} on line {line}); it was read as "
                  f"Windows-1252 text: check the answers as read back")


def _from_txt(text: str, label: str, notes: list[str]) -> list[tuple[str, str]]:
    pairs: dict[str, str] = {}
    lines_of: dict[str, int] = {}
    unread: list[str] = []
    again: list[str] = []
    for number, line in enumerate(text.splitlines(), start=1):
        content = line.split("#", 1)[0].strip()
        if not content:
            continue
        if "=" not in content:
            unread.append(f"{label}:{number}: expected 'problem_id.objective_id = answer', "
                          f"found '{_printable(_short(content, 40))}'; the line was not read")
            continue
        key, value = (part.strip() for part in content.split("=", 1))
        if not key:
            unread.append(f"{label}:{number}: expected a key before '=', found none; "
                          f"the line was not read")
            continue
        key = _printable(unicodedata.normalize("NFC", key))
        if key in pairs:
            again.append(f"{label}:{number}: '{_short(key)}' is answered again (first on line "
                         f"{lines_of[key]}); the later answer was graded")
            del pairs[key]
        pairs[key] = value
        lines_of.setdefault(key, number)
    listed(notes, unread, lambda more: f"{label}: {more} more lines were not read (expected "
                                       f"'problem_id.objective_id = answer')")
    listed(notes, again, lambda more: f"{label}: {more} more lines answer a key again; the "
                                      f"latest answer to each was graded")
    return list(pairs.items())


def _from_json(text: str, label: str, notes: list[str]) -> list[tuple[str, str]]:
    repeated: list[str] = []

    def pairs_hook(items):
        out = {}
        for key, value in items:
            if key in out:
                repeated.append(key)
            out[key] = value
        return out

    try:
        # parse_float/parse_int keep numbers exactly as typed ("7.10" keeps its zero).
        data = json.loads(text, object_pairs_hook=pairs_hook, parse_float=str, parse_int=str,
                          parse_constant=str)
    except (ValueError, RecursionError) as exc:
        where = f":{exc.lineno}:{exc.colno}" if isinstance(exc, json.JSONDecodeError) else ""
        reason = exc.msg if isinstance(exc, json.JSONDecodeError) else "nested too deeply"
        raise _Unread(f"{label}{where}: expected valid JSON, found a syntax error "
                              f"({reason})") from None
    listed(notes, [f"'{label}': '{_short(key)}' is given more than once; the last one was "
                   f"graded" for key in sorted(set(repeated))],
           lambda more: f"'{label}': {more} more keys are given more than once; the last of "
                        f"each was graded")
    return _flatten(data, label, notes, lambda value, _key: value)


def _from_yaml(text: str, label: str, notes: list[str]) -> list[tuple[str, str]]:
    try:
        doc = read_yaml_text(text, label, error=SubmissionError)
    except MechgradeError as err:
        raise _Unread(str(err)) from None
    lines = text.splitlines()

    def as_typed(value, path):
        # YAML turns 7.10 into 7.1; the typed text is recovered from the value's position.
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            where = doc.where(path)
            if where.line and where.line <= len(lines) and where.column:
                raw = lines[where.line - 1][where.column - 1:].split("#", 1)[0].strip()
                raw = raw.rstrip(",]}").strip()
                try:
                    if float(raw.replace("_", "")) == float(value):
                        return raw
                except ValueError:
                    pass
        return value

    return _flatten(doc.data, label, notes, as_typed)


def _flatten(data, label: str, notes: list[str], as_typed) -> list[tuple[str, str]]:
    if not isinstance(data, dict):
        raise _Unread(f"'{label}': expected answers keyed by 'problem_id.objective_id', "
                              f"found {_kind(data)}")
    out: list[tuple[str, str]] = []
    not_text: list[str] = []
    for key, value in data.items():
        key = str(key)
        if isinstance(value, dict):
            for sub, inner in value.items():
                text = _value_text(as_typed(inner, (key, sub)), f"{key}.{sub}", label,
                                   not_text, as_typed, (key, sub))
                if text is not None:
                    out.append((_printable(f"{key}.{sub}"), text))
            continue
        text = _value_text(as_typed(value, (key,)), key, label, not_text, as_typed, (key,))
        if text is not None:
            out.append((_printable(key), text))
    listed(notes, not_text, lambda more: f"'{label}': {more} more answers are not text; they "
                                         f"were not read")
    return out


def _value_text(value, key: str, label: str, notes: list[str], as_typed, path) -> str | None:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (str, int, float)):
        return clean_text(str(value).strip())
    if isinstance(value, list) and all(not isinstance(v, (list, dict)) for v in value):
        items = [str(as_typed(v, path + (i,))) for i, v in enumerate(value)]
        return clean_text("(" + ", ".join(items) + ")")
    notes.append(f"'{label}': the answer to '{_short(key)}' is {_kind(value)}, expected text; "
                 f"it was not read")
    return None


def _kind(value) -> str:
    if value is None:
        return "nothing"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    return f"{type(value).__name__} {str(value)[:20]!r}"


def _printable(text: str) -> str:
    """Control characters out of keys and echoed lines (they end up in messages and files).

    >>> _printable("p.v"), _printable("p\\tv") == "p\\ufffdv"
    ('p.v', True)
    """
    if text.isprintable():
        return text
    return "".join(ch if ch.isprintable() else "\ufffd" for ch in text)
