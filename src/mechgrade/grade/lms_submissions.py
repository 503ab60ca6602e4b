"""Submissions as the LMS hands them to the instructor: a download zip, or a quiz's responses.

``mechgrade grade`` takes, instead of a folder, what the LMS gives:

* **Canvas "Download Submissions"** zip: one member per uploaded file, named
  ``<sortable name>_[late_]<user id>_<attachment id>_<file name>`` (canvas-lms
  ``app/models/content_zipper.rb``: ``get_filename`` joins the name, ``LATE`` when late and the
  user id, keeps word characters and lower-cases; ``add_upload_submission`` appends the
  attachment id and the file's name). The student is the Canvas user id: a Canvas gradebook
  export as roster matches it by ``ID``. Text entries (``..._text.html``) and links
  (``..._link.html``) are no answers files.
* **Moodle "Download all submissions"** zip: ``<Full Name>_<participant id>_
  assignsubmission_file_/<file>`` (folders, the default since Moodle 3.1) or the same prefix
  flat before the file name (``mod/assign/locallib.php``, ``download_submissions``). The
  participant id is not the user's id and no grades export holds it: with a roster, the full
  name is matched to the roster's (a name two students share matches nobody); without one the
  student is ``<Full Name>_<participant id>``.
* **Gradescope "Export Submissions"** zip: ``submission_metadata.yml`` beside one folder
  ``submission_<id>/`` per submission; the metadata names each submission's submitters
  (``:sid:``, else ``:email:``). A group submission is graded once per submitter.

Each student's files are read by the rule of a Gradescope upload
(:func:`mechgrade.grade.upload.read_upload`: ``answers.*``, else in a zip the student uploaded,
else the one file with an answers suffix, whatever the LMS renamed it to), so a zip grades as
the folder holding the same files. Every member of the zip is accounted for: read, or in the
run's skipped list with the reason; the zip itself is read under
:mod:`mechgrade.grade.archives`' rules and bounded (:data:`MAX_MEMBERS`,
:data:`MAX_TOTAL_BYTES`).

Quiz responses (a CSV) are read by :mod:`mechgrade.grade.quiz_responses`.
"""

from __future__ import annotations

import os
import re
import tempfile
import zipfile
from collections import defaultdict
from dataclasses import dataclass, replace
from pathlib import Path, PurePosixPath

from ..errors import SubmissionError
from ..files import clean_text, safe_file_names
from ..roster import Roster, normalise_name
from ..yamlio import read_yaml_text
from .archives import Member, read_member, safe_members
from .results import SkippedEntry
from .submissions import (MAX_FILE_BYTES, SUFFIXES, SYSTEM_NAMES, Submission,
                          SubmissionFormat, SubmissionSet)
from .upload import read_upload

MAX_MEMBERS = 100_000
"""Members looked at in one download zip (a class of thousands, a few files each)."""
MAX_TOTAL_BYTES = 512_000_000
"""Bytes read from one download zip, all members together; what is past it is skipped."""
MAX_NESTED_ZIP_BYTES = 50_000_000
"""A zip a student uploaded, inside the download, is read up to this size."""

ZIP_FORMATS = (SubmissionFormat.CANVAS_ZIP, SubmissionFormat.MOODLE_ZIP,
               SubmissionFormat.GRADESCOPE_ZIP)
CANVAS_MEMBER = re.compile(r"(?:(?P<name>.*?)_)??(?:(?P<late>late)_)?(?P<user>\d+)_"
                           r"(?P<attachment>\d+)_(?P<file>.+)", re.DOTALL)
CANVAS_ONLINE = re.compile(r"(?:.*?_)??(?:late_)?(?P<user>\d+)_(?P<kind>text|link)\.html")
MOODLE_MEMBER = re.compile(r"(?P<who>.+?)_(?P<participant>\d+)_assignsubmission_"
                           r"(?P<plugin>[a-z]+)_(?:/(?P<path>.+)|(?P<flat>[^/]+))", re.DOTALL)
GRADESCOPE_METADATA = "submission_metadata.yml"


@dataclass
class _Files:
    """One student's members: ``(member, file name as the student gave it)``."""

    files: list[tuple[Member, str]]
    notes: list[str]


def detect_zip_format(names: list[str]) -> SubmissionFormat | None:
    """Which LMS made a download zip, from its member names (``None``: none of them).

    >>> detect_zip_format(["lovelaceada_101_9001_answers.yaml"])
    <SubmissionFormat.CANVAS_ZIP: 'canvas-zip'>
    >>> detect_zip_format(["Ada Lovelace_77_assignsubmission_file_/answers.yaml"])
    <SubmissionFormat.MOODLE_ZIP: 'moodle-zip'>
    """
    files = [n for n in names if not _system(n)]
    if any(PurePosixPath(n).name == GRADESCOPE_METADATA and len(PurePosixPath(n).parts) <= 2
           for n in files):
        return SubmissionFormat.GRADESCOPE_ZIP
    if files and all(MOODLE_MEMBER.fullmatch(n) for n in files):
        return SubmissionFormat.MOODLE_ZIP
    top = [n for n in files if "/" not in n]
    if top and all(CANVAS_MEMBER.fullmatch(n) or CANVAS_ONLINE.fullmatch(n) for n in top):
        return SubmissionFormat.CANVAS_ZIP
    return None


def read_lms_zip(path: str | Path, fmt: SubmissionFormat | None = None, *, keys=None,
                 roster: Roster | None = None) -> SubmissionSet:
    """Read a download zip of ``fmt`` (detected when ``None``): every student's submission,
    every member not read in ``skipped``. A zip that cannot be opened at all raises
    :class:`SubmissionError`."""
    path = Path(path)
    label = clean_text(path.name)
    try:
        archive = zipfile.ZipFile(path)
    except UnicodeDecodeError:
        raise SubmissionError("expected a zip whose member names are text, found a name "
                              "flagged UTF-8 that is not UTF-8: the zip is damaged; download "
                              "it from the LMS again", where=_where(path)) from None
    except (OSError, zipfile.BadZipFile, ValueError, RuntimeError, NotImplementedError) as exc:
        raise SubmissionError(f"expected a zip file of submissions, found one that cannot be "
                              f"read ({type(exc).__name__})", where=_where(path)) from None
    with archive:
        count = len(archive.infolist())
        if count > MAX_MEMBERS:
            raise SubmissionError(f"expected at most {MAX_MEMBERS} members in a download zip, "
                                  f"found {count}", where=_where(path))
        members, refused = safe_members(archive)
        fmt = fmt or detect_zip_format([m.name for m in members])
        if fmt is None:
            raise SubmissionError(
                "expected a download zip of Canvas (lastnamefirstname_<user id>_<id>_<file>), "
                "Moodle (<Full Name>_<id>_assignsubmission_file_) or Gradescope "
                f"({GRADESCOPE_METADATA} and submission_<id>/ folders), found members such as "
                f"{', '.join(repr(m.name) for m in members[:3]) or 'none'}; name the format "
                "with --submissions-format", where=_where(path))
        skipped = [SkippedEntry(f"{label}/{name}", reason) for name, reason in refused]
        students, notes = _group(archive, fmt, members, label, skipped, roster)
        budget = [MAX_TOTAL_BYTES]
        read: list[Submission] = []
        with tempfile.TemporaryDirectory(prefix="mechgrade-lms-") as tmp:
            for n, (student, found) in enumerate(sorted(students.items())):
                folder = Path(tmp) / str(n)
                folder.mkdir()
                shown = _materialise(archive, found, folder, label, skipped, budget)
                upload = read_upload(folder, student, keys=keys)
                read.append(_relabelled(upload.submission, folder.name, shown, found.notes))
    return SubmissionSet(path, tuple(read), tuple(sorted(skipped, key=lambda e: e.path)),
                         tuple(notes))


def _where(path: Path):
    from ..errors import Location
    return Location(clean_text(str(path)))


def _system(name: str) -> bool:
    return any(p.startswith(".") or p in SYSTEM_NAMES for p in PurePosixPath(name).parts)


def _group(archive: zipfile.ZipFile, fmt: SubmissionFormat, members: list[Member], label: str,
           skipped: list[SkippedEntry], roster: Roster | None
           ) -> tuple[dict[str, _Files], list[str]]:
    """Each student's members (by the student's id), by the naming rule of ``fmt``."""
    students: dict[str, _Files] = defaultdict(lambda: _Files([], []))
    notes: list[str] = []
    metadata = _gradescope_metadata(archive, members, label) \
        if fmt == SubmissionFormat.GRADESCOPE_ZIP else {}
    names = _roster_names(roster) if fmt == SubmissionFormat.MOODLE_ZIP else {}
    for member in members:
        shown = f"{label}/{member.name}"
        if _system(member.name):
            skipped.append(SkippedEntry(shown, "made by the operating system, not a "
                                               "submission"))
            continue
        who, file_name, reason = _owner(fmt, member.name, metadata, names)
        if reason:
            skipped.append(SkippedEntry(shown, reason))
            continue
        for student in who:
            students[student].files.append((member, file_name))
    if fmt == SubmissionFormat.MOODLE_ZIP and roster is not None:
        unmatched = sorted({s for s in students if s not in {r.id for r in roster.students}})
        if unmatched:
            notes.append(f"{len(unmatched)} Moodle submission(s) matched no roster student "
                         f"by full name ({', '.join(unmatched[:10])}); graded under the name "
                         "and participant id Moodle gave them")
    return students, notes


def _owner(fmt: SubmissionFormat, name: str, metadata: dict, names: dict[str, str]
           ) -> tuple[list[str], str, str]:
    """(students, the file's own name, why it is not a submission file or ``""``)."""
    if fmt == SubmissionFormat.CANVAS_ZIP:
        if "/" in name:
            return [], "", "not a Canvas submission file (the download holds no folders)"
        online = CANVAS_ONLINE.fullmatch(name)
        if online:
            return [], "", (f"a Canvas online {'text entry' if online['kind'] == 'text' else 'URL'}"
                            " (HTML), not an answers file: ask for answers.yaml as a file")
        found = CANVAS_MEMBER.fullmatch(name)
        if not found:
            return [], "", "not named as Canvas names submission files"
        return [found["user"]], found["file"], ""
    if fmt == SubmissionFormat.MOODLE_ZIP:
        found = MOODLE_MEMBER.fullmatch(name)
        if not found:
            return [], "", "not named as Moodle names submission files"
        if found["plugin"] != "file":
            return [], "", f"a Moodle '{found['plugin']}' submission, not an uploaded file"
        who = f"{found['who']}_{found['participant']}"
        student = names.get(normalise_name(found["who"]), who)
        return [student], found["path"] or found["flat"], ""
    parts = PurePosixPath(name).parts
    if parts[-1] == GRADESCOPE_METADATA:
        return [], "", "Gradescope's submission metadata (read for the submitters)"
    folder = next((i for i, p in enumerate(parts) if p in metadata), None)
    if folder is None:
        return [], "", f"not inside a submission folder that {GRADESCOPE_METADATA} lists"
    return metadata[parts[folder]], "/".join(parts[folder + 1:]), ""


def _roster_names(roster: Roster | None) -> dict[str, str]:
    """Folded full name -> roster id, for names exactly one roster student has."""
    if roster is None:
        return {}
    counts: dict[str, list[str]] = defaultdict(list)
    for student in roster.students:
        counts[normalise_name(student.name)].append(student.id)
    return {name: ids[0] for name, ids in counts.items() if len(ids) == 1 and name}


def _gradescope_metadata(archive: zipfile.ZipFile, members: list[Member], label: str
                         ) -> dict[str, list[str]]:
    """Submission folder -> its submitters' ids, from ``submission_metadata.yml``."""
    found = [m for m in members if PurePosixPath(m.name).name == GRADESCOPE_METADATA]
    if len(found) != 1:
        raise SubmissionError(f"expected one {GRADESCOPE_METADATA} in the Gradescope export, "
                              f"found {len(found)}", where=_where(Path(label)))
    data = read_member(archive, found[0], 20_000_000)
    where = f"{label}/{found[0].name}"
    if isinstance(data, str) or len(data) > 20_000_000:
        raise SubmissionError(f"expected Gradescope's submission metadata, found a file that "
                              f"{data if isinstance(data, str) else 'is too large'}",
                              where=_where(Path(where)))
    try:
        doc = read_yaml_text(data.decode("utf-8"), where, error=SubmissionError)
    except UnicodeDecodeError:
        raise SubmissionError("expected UTF-8 text, found bytes that are not UTF-8",
                              where=_where(Path(where))) from None
    if not isinstance(doc.data, dict):
        raise SubmissionError("expected a mapping of submission folders to their submitters",
                              where=doc.where(()))
    out: dict[str, list[str]] = {}
    for folder, record in doc.data.items():
        submitters = record.get(":submitters") if isinstance(record, dict) else None
        if not isinstance(submitters, list) or not submitters:
            path = (folder, ":submitters") if isinstance(record, dict) else (folder,)
            raise SubmissionError("expected ':submitters:', a list of the students who "
                                  "submitted it", where=doc.where(path))
        ids = []
        for i, submitter in enumerate(submitters):
            ident = next((str(submitter[k]) for k in (":sid", ":email")
                          if isinstance(submitter, dict) and submitter.get(k) not in (None, "")),
                         "")
            if not ident:
                raise SubmissionError("expected a submitter with ':sid:' or ':email:', found "
                                      "neither", where=doc.where((folder, ":submitters", i)))
            ids.append(clean_text(ident))
        out[str(folder)] = ids
    return out


def _materialise(archive: zipfile.ZipFile, found: _Files, folder: Path, label: str,
                 skipped: list[SkippedEntry], budget: list[int]) -> dict[str, str]:
    """Write a student's answer-like files (and zips) into ``folder`` under safe names;
    return safe name -> the member's name as shown. Other files are skipped, listed."""
    shown: dict[str, str] = {}
    names = safe_file_names([PurePosixPath(f).name for _, f in found.files])
    for (member, file_name), safe in zip(found.files, names):
        where = f"{label}/{member.name}"
        suffix = PurePosixPath(file_name).suffix.lower()
        if suffix not in (*SUFFIXES, ".zip"):
            skipped.append(SkippedEntry(where, "not an answers file: answers go in "
                                               "answers.yaml, answers.json or answers.txt"))
            continue
        limit = MAX_NESTED_ZIP_BYTES if suffix == ".zip" else MAX_FILE_BYTES
        if budget[0] <= 0:
            skipped.append(SkippedEntry(where, f"past the {MAX_TOTAL_BYTES} bytes read from one "
                                               "download zip; it was not read"))
            continue
        data = read_member(archive, member, min(limit, budget[0]))
        if isinstance(data, str):
            skipped.append(SkippedEntry(where, data))
            continue
        budget[0] -= len(data)
        (folder / safe).write_bytes(data)
        shown[safe] = where
    return shown


def _relabelled(submission: Submission, folder: str, shown: dict[str, str],
                notes: list[str]) -> Submission:
    """The submission with its temporary file names replaced by the zip's member names."""
    pairs = sorted(((f"{folder}/{safe}", where) for safe, where in shown.items()),
                   key=lambda p: -len(p[0]))
    pairs += sorted(((f"'{safe}", f"'{where}") for safe, where in shown.items()),
                    key=lambda p: -len(p[0]))

    def fix(text: str) -> str:
        for old, new in pairs:
            text = text.replace(old, new)
        return text.replace(f"'{folder}'", "the submission")

    return replace(submission, messages=(*notes, *map(fix, submission.messages)),
                   files=tuple(fix(f) for f in submission.files))


def read_any_submissions(path: str | os.PathLike, *, keys=None, jobs: int = 1,
                         roster: Roster | None = None, fmt: SubmissionFormat | None = None,
                         drawn_keys=frozenset()) -> SubmissionSet:
    """The submissions at ``path``: a folder (:func:`mechgrade.grade.submissions.read_submissions`),
    a download zip (:func:`read_lms_zip`) or a quiz's responses
    (:func:`mechgrade.grade.quiz_responses.read_quiz_responses`; ``drawn_keys`` are the
    objectives whose problems draw numbers per student), by ``fmt`` or as detected."""
    from .submissions import read_submissions

    path = Path(path)
    if fmt in (None, SubmissionFormat.FOLDER) and path.is_dir():
        return read_submissions(path, keys=keys, jobs=jobs)
    if fmt == SubmissionFormat.FOLDER:
        raise SubmissionError("expected a folder of submissions, found a file",
                              where=_where(path))
    if fmt in ZIP_FORMATS or (fmt is None and path.suffix.lower() == ".zip"):
        return read_lms_zip(path, fmt, keys=keys, roster=roster)
    from .quiz_responses import QUIZ_FORMATS, read_quiz_responses

    if fmt in QUIZ_FORMATS or (fmt is None and path.suffix.lower() == ".csv"):
        return read_quiz_responses(path, fmt, keys=keys, drawn_keys=drawn_keys)
    raise SubmissionError("expected a folder of submissions, an LMS download zip or a quiz's "
                          "responses (.csv), found another kind of file", where=_where(path))

