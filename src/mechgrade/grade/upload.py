"""Find a student's answers in a Gradescope upload, whatever shape it came in.

Gradescope puts the uploaded files in ``/autograder/submission/``. Students upload
``answers.yaml`` (or ``.yml``/``.json``/``.txt``) as asked, but also a zipped folder
(``hw1.zip`` holding ``hw1/answers.yaml``) or a renamed file (``my_answers.txt``). The answers
file is chosen by one rule:

1. an ``answers.*`` file at the top of the upload is read as in a submissions folder;
2. otherwise, among the files of the upload and the members of its ``.zip`` files (folders
   searched, hidden entries and ``__MACOSX`` left out), the ``answers.*`` file nearest the top
   (ties in the order ``.yaml``, ``.yml``, ``.json``, ``.txt``);
3. otherwise the one file with an answers suffix, whatever its name; several such files are not
   guessed between: the student is told to name the one to grade ``answers.yaml``.

Zip files are read in memory and never extracted: no member name becomes a path, links are not
followed, members refused by :mod:`mechgrade.grade.archives` (``..``, absolute names, links,
duplicate names, bombs) are noted, and the counts and sizes are bounded (:data:`MAX_MEMBERS`, :data:`MAX_ZIP_BYTES`; a
member is read at most :data:`~mechgrade.grade.submissions.MAX_FILE_BYTES` + 1 bytes, so a zip
bomb is cut short). The chosen file is copied into a temporary folder and read there like any
answers file; the student's feedback says which file was read.
"""

from __future__ import annotations

import os
import stat
import tempfile
import zipfile
import zlib
from dataclasses import dataclass, replace
from pathlib import Path, PurePosixPath

from ..errors import Location, SubmissionError
from ..files import clean_text
from ..jsonio import read_json
from .archives import safe_members
from .submissions import (SubmissionStatus, ANSWER_FILES, MAX_FILE_BYTES, SUFFIXES, SYSTEM_NAMES, Submission,
                          read_student_folder)

MAX_MEMBERS = 1000
"""Entries looked at: files of the upload folder plus members of its zip files."""
MAX_ZIP_BYTES = 50_000_000
MAX_DEPTH = 6
MAX_METADATA_BYTES = 10_000_000


@dataclass(frozen=True)
class AnswerFile:
    """A file that may hold the answers: where it is (as shown to the student) and how to get
    its bytes."""

    label: str
    depth: int
    size: int
    path: Path | None = None  # a file of the upload folder
    zip_path: Path | None = None  # or a member of this zip
    member: str | None = None


@dataclass(frozen=True)
class Upload:
    """What the upload held: the submission read from it, and the file read (``None`` when
    the answers came straight from ``answers.*`` at the top, or nothing was read)."""

    submission: Submission
    read_from: str | None


def read_upload(folder: str | Path, student: str, *, keys=None) -> Upload:
    """Read a Gradescope upload (see module doc). Never raises on what the student uploaded.

    >>> import tempfile, pathlib, zipfile
    >>> up = pathlib.Path(tempfile.mkdtemp())
    >>> with zipfile.ZipFile(up / "hw1.zip", "w") as z:
    ...     z.writestr("hw1/answers.txt", "p.v = 3 m/s\\n")
    >>> found = read_upload(up, "ana")
    >>> found.read_from, found.submission.answers
    ('hw1.zip/hw1/answers.txt', (('p.v', '3 m/s'),))
    """
    folder = Path(folder)
    direct = read_student_folder(folder, student, keys=keys)
    if direct.status != SubmissionStatus.MISSING or not folder.is_dir():
        return Upload(direct, None)
    notes: list[str] = []
    chosen = choose(candidates(folder, notes), notes)
    if chosen is None:
        return Upload(replace(direct, messages=direct.messages + tuple(notes)), None)
    data = _bytes_of(chosen, notes)
    if data is None or chosen.size > MAX_FILE_BYTES:
        if data is not None:
            notes.append(f"'{chosen.label}' is {chosen.size} bytes; answer files may be at most "
                         f"{MAX_FILE_BYTES} bytes")
        return Upload(Submission(student, SubmissionStatus.UNREADABLE, messages=tuple(notes)), chosen.label)
    suffix = PurePosixPath(chosen.label).suffix.lower()
    with tempfile.TemporaryDirectory(prefix="mechgrade-upload-") as tmp:
        (Path(tmp) / f"answers{suffix}").write_bytes(data)
        read = read_student_folder(tmp, student, keys=keys)
    # The reader names the file by its (random, unique) temporary folder: name it as uploaded.
    shown = f"{Path(tmp).name}/answers{suffix}"
    messages = [f"read '{chosen.label}' as the answers file", *notes,
                *(m.replace(shown, chosen.label) for m in read.messages)]
    files = tuple(chosen.label if f == shown else f for f in read.files)
    return Upload(replace(read, messages=tuple(messages), files=files), chosen.label)


def candidates(folder: Path, notes: list[str]) -> list[AnswerFile]:
    """Every file of ``folder`` (and member of its zip files) with an answers suffix."""
    found: list[AnswerFile] = []
    seen = 0
    for current, dirs, files in os.walk(folder, followlinks=False):
        rel = Path(current).relative_to(folder)
        depth = len(rel.parts)
        dirs[:] = sorted(d for d in dirs if _wanted(d) and depth < MAX_DEPTH
                         and not os.path.islink(os.path.join(current, d)))
        for name in sorted(files):
            seen += 1
            if seen > MAX_MEMBERS:
                notes.append(f"the upload holds more than {MAX_MEMBERS} files; the rest were "
                             "not looked at")
                return found
            path = Path(current) / name
            label = clean_text((rel / name).as_posix())
            if not _wanted(name):
                continue
            try:
                info = os.lstat(path)
            except OSError:
                continue
            if not stat.S_ISREG(info.st_mode):
                continue  # links (possibly to outside the upload) and devices are not read
            suffix = Path(name).suffix.lower()
            if suffix == ".zip":
                found.extend(_zip_members(path, label, depth, notes))
            elif suffix in SUFFIXES:
                found.append(AnswerFile(label, depth, info.st_size, path=path))
    return found


def choose(found: list[AnswerFile], notes: list[str]) -> AnswerFile | None:
    """The answers file by the rule of the module doc, or ``None`` (``notes`` says why)."""
    rank = {name: i for i, name in enumerate(ANSWER_FILES)}
    named = [c for c in found if PurePosixPath(c.label).name.lower() in rank]
    if named:
        return min(named, key=lambda c: (c.depth, rank[PurePosixPath(c.label).name.lower()],
                                         c.label))
    if len(found) == 1:
        return found[0]
    if found:
        listing = ", ".join(f"'{c.label}'" for c in found[:10])
        notes.append(f"found {len(found)} files that could hold the answers ({listing}); none "
                     "was graded: name the one to grade answers.yaml (or .json, .txt)")
    return None


def _wanted(name: str) -> bool:
    return not name.startswith(".") and name not in SYSTEM_NAMES


def _zip_members(path: Path, label: str, depth: int, notes: list[str]) -> list[AnswerFile]:
    try:
        if path.stat().st_size > MAX_ZIP_BYTES:
            notes.append(f"'{label}' is larger than {MAX_ZIP_BYTES} bytes; it was not opened")
            return []
        with zipfile.ZipFile(path) as archive:
            count = len(archive.infolist())
            members, refused = safe_members(archive) if count <= MAX_MEMBERS else ([], [])
    except (OSError, zipfile.BadZipFile, ValueError, RuntimeError, NotImplementedError) as exc:
        notes.append(f"'{label}' is not a zip file that can be read ({type(exc).__name__})")
        return []
    if count > MAX_MEMBERS:
        notes.append(f"'{label}' holds {count} entries (at most {MAX_MEMBERS} are "
                     "looked at); it was not searched")
        return []
    notes.extend(f"'{label}/{name}' {reason}" for name, reason in refused)
    out = []
    for member in members:
        parts = PurePosixPath(member.name).parts
        if not parts or not all(_wanted(p) for p in parts) or len(parts) > MAX_DEPTH:
            continue
        if PurePosixPath(member.name).suffix.lower() not in SUFFIXES:
            continue
        out.append(AnswerFile(clean_text(f"{label}/{member.name}"), depth + len(parts),
                             member.info.file_size, zip_path=path,
                             member=member.info.filename))
    return out


def archive_of(path: Path) -> zipfile.ZipFile:
    """The zip at ``path``, its members listed (closed when collected: listing keeps no file
    open past it)."""
    with zipfile.ZipFile(path) as archive:
        return archive


def _bytes_of(chosen: AnswerFile, notes: list[str]) -> bytes | None:
    """The chosen file's bytes, at most ``MAX_FILE_BYTES`` + 1 of them (the answers reader
    refuses longer files with their size); ``None`` with a note if it cannot be read."""
    try:
        if chosen.path is not None:
            with open(chosen.path, "rb") as handle:
                return handle.read(MAX_FILE_BYTES + 1)
        assert chosen.zip_path is not None and chosen.member is not None  # else a file
        with zipfile.ZipFile(chosen.zip_path) as archive:
            if archive.getinfo(chosen.member).flag_bits & 0x1:
                notes.append(f"'{chosen.label}' is encrypted; it was not read")
                return None
            with archive.open(chosen.member) as handle:
                return handle.read(MAX_FILE_BYTES + 1)
    except (OSError, zipfile.BadZipFile, KeyError, RuntimeError, ValueError,
            NotImplementedError, EOFError, zlib.error) as exc:
        notes.append(f"'{chosen.label}' cannot be read ({type(exc).__name__})")
        return None


def submitter(metadata_path: str | Path) -> tuple[str, str]:
    """(id, name) of who submitted, from Gradescope's ``submission_metadata.json``: the first
    user's ``sid`` (the student id the variants and rosters use), else ``email``, else ``id``.

    No file (a run outside Gradescope) is the submitter ``"submission"``; a file that cannot be
    read or is not shaped as Gradescope writes it raises :class:`SubmissionError` at the field,
    since a guessed id would grade the wrong student's variant.

    >>> import tempfile, pathlib, json
    >>> meta = pathlib.Path(tempfile.mkdtemp()) / "submission_metadata.json"
    >>> _ = meta.write_text(json.dumps({"users": [{"name": "Ada", "sid": 10001}]}))
    >>> submitter(meta), submitter(meta.with_name("none.json"))
    (('10001', 'Ada'), ('submission', ''))
    >>> _ = meta.write_text(json.dumps({"users": {"name": "Ada"}}))
    >>> submitter(meta)
    Traceback (most recent call last):
    ...
    mechgrade.errors.SubmissionError: ...submission_metadata.json: users: expected a list of users, found a mapping
    """
    name = str(metadata_path)
    if not os.path.lexists(metadata_path):
        return "submission", ""
    data = read_json(metadata_path, what="Gradescope's submission metadata (JSON)",
                     error=SubmissionError, max_bytes=MAX_METADATA_BYTES)
    if not isinstance(data, dict):
        raise SubmissionError(f"expected a mapping (Gradescope's submission metadata), found "
                              f"{_json_kind(data)}", where=Location(name))
    users = data.get("users", [])
    if not isinstance(users, list):
        raise SubmissionError(f"expected a list of users, found {_json_kind(users)}",
                              where=Location(name, field="users"))
    if not users:
        return "submission", ""
    user = users[0]
    if not isinstance(user, dict):
        raise SubmissionError(f"expected a user (a mapping with sid, email, name), found "
                              f"{_json_kind(user)}", where=Location(name, field="users[0]"))
    for key in ("sid", "email", "id", "name"):
        value = user.get(key)
        if value is not None and (isinstance(value, bool) or
                                  not isinstance(value, (str, int))):
            raise SubmissionError(f"expected text or a whole number, found {_json_kind(value)}",
                                  where=Location(name, field=f"users[0].{key}"))
    ident = next((str(user[k]) for k in ("sid", "email", "id")
                  if user.get(k) is not None and str(user[k]).strip()), "submission")
    return clean_text(ident), clean_text(str(user.get("name") or ""))


def _json_kind(value: object) -> str:
    kinds = ((dict, "a mapping"), (list, "a list"), (str, "text"), (bool, "true or false"),
             (int, "a whole number"), (float, "a decimal number"))
    return next((noun for kind, noun in kinds if isinstance(value, kind)), "null")
