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
('ana', 'read', '7.0 m/s')
"""

from __future__ import annotations

import json
import os
import stat
import unicodedata
from dataclasses import dataclass
from pathlib import Path

from ..errors import MechgradeError, SubmissionError
from ..yamlio import read_yaml_text

MAX_FILE_BYTES = 256 * 1024
MAX_ANSWERS = 500
MAX_ANSWER_CHARS = 4000
ANSWER_FILES = ("answers.yaml", "answers.yml", "answers.json", "answers.txt")
SUFFIXES = (".yaml", ".yml", ".json", ".txt")
IGNORED_NAMES = {"__MACOSX", "Thumbs.db", "desktop.ini"}


class _Unread(SubmissionError):
    """A file that gave no answers, with the notes gathered while reading it."""

    def __init__(self, message: str, *, where=None, notes: list[str] | tuple = ()) -> None:
        super().__init__(message, where=where)
        self.notes = tuple(notes)


@dataclass(frozen=True)
class Submission:
    """What one student handed in.

    ``status`` is ``read`` (at least one answer file was read), ``missing`` (nothing handed in)
    or ``unreadable`` (files were there but none could be read). ``answers`` are
    ``(key, text)`` pairs sorted by key; ``files`` the files read, relative to the folder.
    """

    student: str
    status: str
    answers: tuple[tuple[str, str], ...] = ()
    messages: tuple[str, ...] = ()
    files: tuple[str, ...] = ()

    def answer(self, key: str) -> str | None:
        for name, text in self.answers:
            if name == key:
                return text
        return None


@dataclass(frozen=True)
class SubmissionSet:
    """Every student found in a submissions folder (sorted by id), and notes about the folder."""

    folder: Path
    students: tuple[Submission, ...]
    messages: tuple[str, ...] = ()


def read_submissions(folder: str | Path, *, keys: frozenset[str] | set[str] | None = None
                     ) -> SubmissionSet:
    """Read every submission in ``folder``.

    When ``keys`` (the assignment's ``problem_id.objective_id`` keys) is given, answers under
    other keys are reported in the student's messages, and a key that matches one of ``keys``
    but for letter case is read as that key (also reported). Raises :class:`SubmissionError`
    only when ``folder`` itself cannot be listed.
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
    notes: list[str] = []
    for entry in entries:
        name = entry.name
        if name.startswith(".") or name in IGNORED_NAMES:
            continue
        path = root / name
        inside = _inside(path, root)
        if path.is_dir():
            student = _student_id(name)
            sources = found.setdefault(student, [])
            if not inside:
                sources.append(_Source(name, None, "is a link to outside the submissions "
                                                   "folder; it was not followed"))
                continue
            sources.extend(_folder_sources(path, root, name))
            if not sources:
                sources.append(_Source(name, None, None, empty=True))
        elif Path(name).suffix.lower() in SUFFIXES:
            student = _student_id(Path(name).stem)
            reason = None if inside else ("is a link to outside the submissions folder; it was "
                                          "not followed")
            found.setdefault(student, []).append(_Source(name, path if inside else None, reason))
        else:
            notes.append(f"ignored '{name}': expected a folder per student or a file "
                         f"<student_id>.yaml, .json or .txt")
    students = tuple(_read_student(student, sources, keys)
                     for student, sources in sorted(found.items()))
    return SubmissionSet(folder, students, tuple(notes))


def read_student_folder(folder: str | Path, student: str, *,
                        keys: frozenset[str] | set[str] | None = None) -> Submission:
    """Read one student's folder (``answers.yaml``, ``.json`` or ``.txt`` inside it), such as a
    Gradescope submission in ``/autograder/submission``. Never raises: a folder that is not
    there is a ``missing`` submission."""
    folder = Path(folder)
    label = folder.name or str(folder)
    try:
        root = folder.resolve(strict=True)
    except OSError:
        return Submission(student, "missing", messages=(f"no submission folder at '{folder}'",))
    sources = _folder_sources(root, root, label) or [_Source(label, None, None, empty=True)]
    return _read_student(student, sources, keys)


@dataclass
class _Source:
    label: str  # path relative to the submissions folder, for messages
    path: Path | None
    problem: str | None  # why the file is not read, if it is not
    empty: bool = False
    ignored: tuple[str, ...] = ()  # other files in a student's folder


def _student_id(name: str) -> str:
    return unicodedata.normalize("NFC", name).strip()


def _inside(path: Path, root: Path) -> bool:
    try:
        path.resolve().relative_to(root)
        return True
    except (OSError, ValueError, RuntimeError):
        return False


def _folder_sources(folder: Path, root: Path, label: str) -> list[_Source]:
    sources: list[_Source] = []
    ignored: list[str] = []
    try:
        entries = sorted(os.scandir(folder), key=lambda e: e.name)
    except OSError as exc:
        return [_Source(label, None, f"cannot be listed ({exc.strerror or exc})")]
    names = {e.name.lower(): e.name for e in entries}
    for wanted in ANSWER_FILES:
        if wanted in names:
            name = names[wanted]
            path = folder / name
            if _inside(path, root):
                sources.append(_Source(f"{label}/{name}", path, None))
            else:
                sources.append(_Source(f"{label}/{name}", None, "is a link to outside the "
                                       "submissions folder; it was not followed"))
    for entry in entries:
        if entry.name.lower() not in ANSWER_FILES and not entry.name.startswith(".") \
                and entry.name not in IGNORED_NAMES:
            ignored.append(entry.name)
    if ignored:
        sources.append(_Source(label, None, None, ignored=tuple(ignored)))
    return sources


def _read_student(student: str, sources: list[_Source], keys) -> Submission:
    messages: list[str] = []
    answers: dict[str, tuple[str, str]] = {}  # key -> (text, file label)
    files: list[str] = []
    readable = 0
    tried = 0
    for source in sources:
        if source.ignored:
            messages.append("ignored " + ", ".join(f"'{source.label}/{n}'" for n in source.ignored)
                            + ": answers go in answers.yaml, answers.json or answers.txt")
            continue
        if source.empty:
            messages.append(f"the folder '{source.label}' is empty: no answers handed in")
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
        messages.extend(notes)
        for key, text in pairs:
            if key in answers and answers[key][0] != text:
                messages.append(f"'{key}' is answered in both '{answers[key][1]}' and "
                                f"'{source.label}'; the answer in '{answers[key][1]}' was graded")
                continue
            answers.setdefault(key, (text, source.label))
    if len(files) > 1:
        messages.append(f"answers were read from {len(files)} files ({', '.join(files)}) "
                        f"and combined")
    if keys is not None:
        answers = _match_keys(answers, keys, messages)
    if readable:
        status = "read"
    elif tried:
        status = "unreadable"
    else:
        status = "missing"
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
    for key in unknown:
        messages.append(f"'{key}' ({answers[key][1]}) is not a question of this assignment; "
                        f"it was not graded")
    return out


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
    if len(pairs) > MAX_ANSWERS:
        notes.append(f"'{label}' holds {len(pairs)} answers; only the first {MAX_ANSWERS} "
                     f"were read")
        pairs = pairs[:MAX_ANSWERS]
    kept: dict[str, str] = {}
    for key, value in pairs:
        if len(value) > MAX_ANSWER_CHARS:
            notes.append(f"'{label}': the answer to '{key}' is {len(value)} characters long; "
                         f"only the first {MAX_ANSWER_CHARS} were read")
            value = value[:MAX_ANSWER_CHARS]
        kept[key] = value
    if not kept:
        raise _Unread(f"'{label}' holds no answers (expected lines such as "
                              f"'problem_id.objective_id = 7.5 m/s')", notes=notes)
    return sorted(kept.items()), notes


def _read_text(path: Path, label: str) -> tuple[str, str | None]:
    try:
        info = os.stat(path)
        if not stat.S_ISREG(info.st_mode):
            raise _Unread(f"'{label}' is not a regular file; it was not read")
        if info.st_size > MAX_FILE_BYTES:
            raise _Unread(f"'{label}' is {info.st_size} bytes; answer files may be at "
                                  f"most {MAX_FILE_BYTES} bytes")
        with open(path, "rb") as handle:
            raw = handle.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise _Unread(f"'{label}' cannot be read ({exc.strerror or exc})") from None
    if len(raw) > MAX_FILE_BYTES:
        raise _Unread(f"'{label}' is larger than {MAX_FILE_BYTES} bytes; answer files "
                              f"may be at most {MAX_FILE_BYTES} bytes")
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return raw.decode("utf-16"), None
        except UnicodeDecodeError:
            raise _Unread(f"'{label}' is not readable text (bad UTF-16)") from None
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
    for number, line in enumerate(text.splitlines(), start=1):
        content = line.split("#", 1)[0].strip()
        if not content:
            continue
        if "=" not in content:
            shown = content if len(content) <= 40 else content[:37] + "..."
            notes.append(f"{label}:{number}: expected 'problem_id.objective_id = answer', "
                         f"found '{_printable(shown)}'; the line was not read")
            continue
        key, value = (part.strip() for part in content.split("=", 1))
        if not key:
            notes.append(f"{label}:{number}: expected a key before '=', found none; "
                         f"the line was not read")
            continue
        key = _printable(unicodedata.normalize("NFC", key))
        if key in pairs:
            notes.append(f"{label}:{number}: '{key}' is answered again (first on line "
                         f"{lines_of[key]}); the later answer was graded")
            del pairs[key]
        pairs[key] = value
        lines_of[key] = number
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
    for key in sorted(set(repeated)):
        notes.append(f"'{label}': '{key}' is given more than once; the last one was graded")
    return _flatten(data, label, notes, lambda value, key: value)


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
    for key, value in data.items():
        key = str(key)
        if isinstance(value, dict):
            for sub, inner in value.items():
                text = _value_text(as_typed(inner, (key, sub)), f"{key}.{sub}", label, notes,
                                   as_typed, (key, sub))
                if text is not None:
                    out.append((_printable(f"{key}.{sub}"), text))
            continue
        text = _value_text(as_typed(value, (key,)), key, label, notes, as_typed, (key,))
        if text is not None:
            out.append((_printable(key), text))
    return out


def _value_text(value, key: str, label: str, notes: list[str], as_typed, path) -> str | None:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (str, int, float)):
        return str(value).strip()
    if isinstance(value, list) and all(not isinstance(v, (list, dict)) for v in value):
        items = [str(as_typed(v, path + (i,))) for i, v in enumerate(value)]
        return "(" + ", ".join(items) + ")"
    notes.append(f"'{label}': the answer to '{key}' is {_kind(value)}, expected text; "
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
    """Control characters out of keys and echoed lines (they end up in messages and files)."""
    return "".join(ch if ch.isprintable() else "\ufffd" for ch in text)
