"""What the LMS hands the instructor, graded directly: Canvas, Moodle and Gradescope download
zips built from the documented layouts grade as the folder holding the same files, and every
hostile-input rule of the folder reader holds for zip members."""

from __future__ import annotations

import io
import shutil
import stat
import zipfile
from pathlib import Path

import pytest

from mechgrade.errors import SubmissionError
from mechgrade.grade import lms_submissions
from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.lms_submissions import detect_zip_format, read_lms_zip
from mechgrade.grade.submissions import SubmissionFormat
from mechgrade.grade.run import grade_plan, plan_assignment
from mechgrade.grade.lms_submissions import read_any_submissions
from mechgrade.roster import read_roster

ROOT = Path(__file__).resolve().parents[2]
HW1 = ROOT / "examples" / "hw1"


@pytest.fixture(scope="module")
def plan():
    return plan_assignment(load_assignment(HW1 / "assignment.yaml"))


@pytest.fixture(scope="module")
def roster():
    return read_roster(HW1 / "roster.csv")


def uploads(roster) -> dict[str, list[tuple[str, bytes]]]:
    """Every example student's uploaded files, by Canvas user id (the example folder names
    are the roster's SIS login ids); a file handed in alone is uploaded as such."""
    by_login = {s.sis_login_id: s for s in roster.students}
    out: dict[str, list[tuple[str, bytes]]] = {}
    for entry in sorted((HW1 / "submissions").iterdir()):
        login = entry.name if entry.is_dir() else entry.stem
        files = sorted(entry.iterdir()) if entry.is_dir() else [entry]
        out[by_login[login].id] = [
            (f.name if entry.is_dir() else f"answers{f.suffix}", f.read_bytes())
            for f in files]
    return out


def folder_of(tmp_path: Path, files: dict[str, list[tuple[str, bytes]]]) -> Path:
    folder = tmp_path / "folder"
    for student, items in files.items():
        (folder / student).mkdir(parents=True)
        for name, data in items:
            (folder / student / name).write_bytes(data)
    return folder


def zip_with(path: Path, members: dict[str, bytes]) -> Path:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in members.items():
            archive.writestr(name, data)
    return path


def canvas_zip(tmp_path, roster, files) -> Path:
    names = {s.id: s for s in roster.students}
    members = {}
    for n, (student, items) in enumerate(files.items()):
        # content_zipper.rb: sortable name, LATE when late, user id; word characters only,
        # lower case; then the attachment id and the file's own name
        who = "".join(ch for ch in names[student].columns[0][1] if ch.isalnum()).lower()
        late = "_late" if n % 3 == 0 else ""
        for k, (name, data) in enumerate(items):
            members[f"{who}{late}_{student}_{9000 + 10 * n + k}_{name}"] = data
    return zip_with(tmp_path / "canvas submissions.zip", members)


def moodle_zip(tmp_path, roster, files, folders: bool = True) -> Path:
    names = {s.id: s.name for s in roster.students}
    members = {}
    for n, (student, items) in enumerate(files.items()):
        prefix = f"{names[student]}_{500 + n}_assignsubmission_file_"
        for name, data in items:
            members[f"{prefix}/{name}" if folders else f"{prefix}{name}"] = data
        members[f"{names[student]}_{500 + n}_assignsubmission_onlinetext_/onlinetext.html"] = \
            b"<p>typed</p>"
    return zip_with(tmp_path / "moodle.zip", members)


def gradescope_zip(tmp_path, files) -> Path:
    members = {}
    lines = []
    for n, (student, items) in enumerate(files.items()):
        lines.append(f"submission_{700 + n}:\n  :submitters:\n  - :name: Someone\n"
                     f"    :sid: '{student}'\n    :email: s{student}@uni.example\n"
                     f"  :created_at: 2026-09-18 10:00:00.000000000 -05:00\n  :score: 0.0\n")
        for name, data in items:
            members[f"assignment_42_export/submission_{700 + n}/{name}"] = data
    members["assignment_42_export/submission_metadata.yml"] = "".join(lines).encode()
    return zip_with(tmp_path / "gradescope.zip", members)


def outcome(report) -> dict:
    """What a grade is: per student, the status, score and every answer's judgement."""
    return {s.id: (s.status, s.score, tuple((a.problem, a.objective, a.answer, a.verdict,
                                             a.points) for a in s.answers))
            for s in report.students}


@pytest.mark.parametrize("maker", ["canvas", "moodle", "moodle-flat", "gradescope"])
def test_a_download_zip_grades_as_the_folder_of_the_same_files(tmp_path, plan, roster, maker):
    files = uploads(roster)
    folder = read_any_submissions(folder_of(tmp_path, files), keys=plan.keys)
    archive = {"canvas": lambda: canvas_zip(tmp_path, roster, files),
               "moodle": lambda: moodle_zip(tmp_path, roster, files),
               "moodle-flat": lambda: moodle_zip(tmp_path, roster, files, folders=False),
               "gradescope": lambda: gradescope_zip(tmp_path, files)}[maker]()
    from_zip = read_any_submissions(archive, keys=plan.keys, roster=roster)
    expected = outcome(grade_plan(plan, folder, roster))
    assert outcome(grade_plan(plan, from_zip, roster)) == expected
    assert expected["10001"][1] == 19.0 and expected["10002"][1] == 14.0


def test_every_member_of_a_canvas_zip_is_read_or_listed_with_its_reason(tmp_path, plan, roster):
    files = uploads(roster)
    archive = canvas_zip(tmp_path, roster, files)
    with zipfile.ZipFile(archive, "a") as z:
        z.writestr("lovelaceada_10001_text.html", "<p>typed</p>")
        z.writestr("__MACOSX/._x", b"junk")
    read = read_lms_zip(archive, keys=plan.keys)
    listed = {e.path: e.reason for e in read.skipped}
    assert listed["canvas submissions.zip/lovelaceada_10001_text.html"].startswith(
        "a Canvas online text entry (HTML), not an answers file")
    assert "canvas submissions.zip/emptyfrank_10006_9050_.keep" in listed
    assert listed["canvas submissions.zip/__MACOSX/._x"] == \
        "made by the operating system, not a submission"
    # every other member is a student's: read, or named in the student's messages
    said = "\n".join(m for s in read.students for m in (*s.files, *s.messages))
    for name in zipfile.ZipFile(archive).namelist():
        assert f"canvas submissions.zip/{name}" in listed or \
            f"canvas submissions.zip/{name}" in said, name
    (ivy,) = [s for s in read.students if s.student == "10009"]
    assert ivy.status == "unreadable" and ivy.messages[-1].startswith(
        "'canvas submissions.zip/binaryivy_10009_9080_answers.txt' is a binary file")


def test_a_late_canvas_submission_is_read_as_its_student(tmp_path, plan, roster):
    archive = zip_with(tmp_path / "c.zip", {
        "lovelaceada_late_10001_5_answers.yaml":
            (HW1 / "submissions/ada_lovelace/answers.yaml").read_bytes()})
    (ada,) = read_lms_zip(archive, keys=plan.keys).students
    assert ada.student == "10001" and ada.status == "read"
    assert ada.files == ("c.zip/lovelaceada_late_10001_5_answers.yaml",)


def test_a_file_the_lms_renamed_is_still_found(tmp_path, plan):
    archive = zip_with(tmp_path / "c.zip", {
        "roebob_10002_6_answers-1.txt": (HW1 / "submissions/bob_roe/answers.txt").read_bytes(),
        "roebob_10002_7_sketch.pdf": b"%PDF-1.4"})
    read = read_lms_zip(archive, keys=plan.keys)
    (bob,) = read.students
    assert bob.status == "read" and bob.messages[0] == \
        "read 'c.zip/roebob_10002_6_answers-1.txt' as the answers file"
    assert [e.reason for e in read.skipped] == [
        "not an answers file: answers go in answers.yaml, answers.json or answers.txt"]


def test_moodle_names_map_to_the_roster_and_unknown_names_are_kept(tmp_path, plan, roster):
    archive = zip_with(tmp_path / "m.zip", {
        "Ada Lovelace_501_assignsubmission_file_/answers.yaml":
            (HW1 / "submissions/ada_lovelace/answers.yaml").read_bytes(),
        "Zed Nobody_502_assignsubmission_file_/answers.txt": b"x.y = 1\n"})
    read = read_lms_zip(archive, keys=plan.keys, roster=roster)
    assert [s.student for s in read.students] == ["10001", "Zed Nobody_502"]
    assert read.notes == ("1 Moodle submission(s) matched no roster student by full name "
                          "(Zed Nobody_502); graded under the name and participant id Moodle "
                          "gave them",)


def test_a_gradescope_group_submission_is_graded_for_each_submitter(tmp_path, plan):
    meta = (b"submission_1:\n  :submitters:\n  - :sid: '10001'\n  - :sid: '10002'\n")
    archive = zip_with(tmp_path / "g.zip", {
        "submission_metadata.yml": meta,
        "submission_1/answers.yaml": (HW1 / "submissions/ada_lovelace/answers.yaml")
        .read_bytes()})
    read = read_lms_zip(archive, keys=plan.keys)
    assert [(s.student, s.status) for s in read.students] == [("10001", "read"),
                                                              ("10002", "read")]


def test_gradescope_metadata_that_is_malformed_is_one_located_message(tmp_path):
    archive = zip_with(tmp_path / "g.zip", {
        "submission_metadata.yml": b"submission_1:\n  :submitters: nobody\n",
        "submission_1/answers.yaml": b"a.b: 1\n"})
    with pytest.raises(SubmissionError) as caught:
        read_lms_zip(archive)
    assert str(caught.value) == ("g.zip/submission_metadata.yml:2:16: submission_1.:submitters: "
                                 "expected ':submitters:', a list of the students who "
                                 "submitted it")


# ------------------------------------------------------------------------------- hostile


def member(name: str, data: bytes = b"p.v = 1\n", mode: int | None = None) -> zipfile.ZipInfo:
    info = zipfile.ZipInfo(name)
    if mode is not None:
        info.external_attr = mode << 16
    return info


def hostile_zip(tmp_path, entries: list[tuple[zipfile.ZipInfo, bytes]]) -> Path:
    path = tmp_path / "hostile.zip"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for info, data in entries:
            info.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(info, data)
    return path


OK = "lovelaceada_10001_1_answers.txt"


@pytest.mark.parametrize("name, reason", [
    ("lovelaceada_10001_2_../../etc/answers.txt",
     "its name climbs out of the zip (..); it was not read"),
    ("/lovelaceada_10001_3_answers.txt", "its name is an absolute path; it was not read"),
    ("C:/lovelaceada_10001_3_answers.txt", "its name is an absolute path; it was not read"),
    ("roebob_10002_4_..\\..\\answers.txt", "its name climbs out of the zip (..); it was not read"),
])
def test_a_member_whose_name_leaves_the_zip_is_never_read(tmp_path, name, reason):
    archive = hostile_zip(tmp_path, [(member(OK), b"p.v = 1\n"), (member(name), b"p.v = 2\n")])
    read = read_lms_zip(archive, "canvas-zip")
    assert [(e.path.split("/", 1)[1], e.reason) for e in read.skipped] == \
        [(name.replace("\\", "/"), reason)]
    assert [s.student for s in read.students] == ["10001"]
    assert not list(tmp_path.glob("**/etc")) and not Path("/etc/answers.txt").exists()


def test_a_link_in_the_zip_is_never_followed(tmp_path):
    link = member("roebob_10002_4_answers.txt", mode=stat.S_IFLNK | 0o777)
    archive = hostile_zip(tmp_path, [(member(OK), b"p.v = 1\n"), (link, b"/etc/passwd")])
    read = read_lms_zip(archive, "canvas-zip")
    assert [e.reason for e in read.skipped] == ["is a link; links in a zip are never followed"]
    assert [s.student for s in read.students] == ["10001"]


def test_a_zip_bomb_member_is_refused_without_inflating_it(tmp_path):
    archive = hostile_zip(tmp_path, [(member(OK), b"p.v = 1\n"),
                                     (member("roebob_10002_4_answers.txt"), b" " * 50_000_000)])
    read = read_lms_zip(archive, "canvas-zip")
    (skipped,) = read.skipped
    assert skipped.reason.startswith("declares 50000000 bytes from ")
    assert skipped.reason.endswith(" (a zip bomb); it was not read")


def test_what_is_read_from_one_zip_is_bounded(tmp_path, monkeypatch):
    monkeypatch.setattr(lms_submissions, "MAX_TOTAL_BYTES", 20)
    archive = hostile_zip(tmp_path, [(member(OK), b"p.v = 1\n" * 4),
                                     (member("roebob_10002_4_answers.txt"), b"p.v = 2\n")])
    read = read_lms_zip(archive, "canvas-zip")
    assert [(e.path, e.reason) for e in read.skipped] == [
        ("hostile.zip/roebob_10002_4_answers.txt",
         "past the 20 bytes read from one download zip; it was not read")]


def test_a_zip_with_too_many_members_is_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(lms_submissions, "MAX_MEMBERS", 1)
    archive = hostile_zip(tmp_path, [(member(OK), b"1"), (member("x_1_2_y.txt"), b"2")])
    with pytest.raises(SubmissionError, match="expected at most 1 members in a download "
                                              "zip, found 2"):
        read_lms_zip(archive, "canvas-zip")


def test_duplicate_member_names_are_neither_read(tmp_path):
    path = tmp_path / "dup.zip"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr(OK, b"p.v = 1\n")
        with pytest.warns(UserWarning, match="Duplicate name"):
            archive.writestr(OK, b"p.v = 2\n")
        archive.writestr("roebob_10002_4_answers.txt", b"p.v = 3\n")
    read = read_lms_zip(path, "canvas-zip")
    assert [(e.path, e.reason) for e in read.skipped] == [
        (f"dup.zip/{OK}", "the zip holds 2 members of this name: none was read (which one is "
                          "meant cannot be told)")] * 2
    assert [s.student for s in read.students] == ["10002"]


def test_a_name_without_the_utf8_flag_is_read_as_utf8_when_it_is(tmp_path):
    path = tmp_path / "legacy.zip"
    with zipfile.ZipFile(path, "w") as archive:
        info = zipfile.ZipInfo("Zoë Ng_7_assignsubmission_file_/answers.txt")
        archive.writestr(info, b"p.v = 1\n")
    data = bytearray(path.read_bytes())
    for mark in (b"PK\x03\x04", b"PK\x01\x02"):  # clear the UTF-8 flag (bit 11) in both headers
        at = data.find(mark)
        offset = at + (6 if mark == b"PK\x03\x04" else 8)
        flags = int.from_bytes(data[offset:offset + 2], "little") & ~0x800
        data[offset:offset + 2] = flags.to_bytes(2, "little")
    path.write_bytes(bytes(data))
    (student,) = read_lms_zip(path, "moodle-zip").students
    assert student.student == "Zoë Ng_7"


def test_a_name_flagged_utf8_that_is_not_is_one_clear_message(tmp_path):
    path = tmp_path / "broken.zip"
    name = "é_10001_1_answers.txt"
    zip_with(path, {name: b"p.v = 1\n"})
    data = path.read_bytes().replace(name.encode(), b"\xff\xfe" + name.encode()[2:])
    path.write_bytes(data)
    with pytest.raises(SubmissionError) as caught:
        read_lms_zip(path)
    assert str(caught.value) == (f"{path}: expected a zip whose member names are text, found a "
                                 "name flagged UTF-8 that is not UTF-8: the zip is damaged; "
                                 "download it from the LMS again")


def test_a_zip_of_no_known_lms_is_refused_with_the_fix(tmp_path):
    path = zip_with(tmp_path / "x.zip", {"hw/answers.txt": b"p.v = 1"})
    with pytest.raises(SubmissionError, match=r"name the format with --submissions-format$"):
        read_lms_zip(path)


def test_a_file_that_is_not_a_zip_is_refused(tmp_path):
    path = tmp_path / "x.zip"
    path.write_bytes(b"not a zip")
    with pytest.raises(SubmissionError, match="expected a zip file of submissions, found one "
                                              r"that cannot be read \(BadZipFile\)"):
        read_lms_zip(path)


def test_the_formats_are_told_apart_by_their_names():
    assert detect_zip_format(["submission_metadata.yml", "submission_1/a.txt"]) is \
        SubmissionFormat.GRADESCOPE_ZIP
    assert detect_zip_format(["Ada Lovelace_1_assignsubmission_file_a.txt"]) is \
        SubmissionFormat.MOODLE_ZIP
    assert detect_zip_format(["a/b.txt"]) is None


def test_a_student_zip_inside_the_download_is_opened_by_the_upload_rule(tmp_path, plan):
    inner = io.BytesIO()
    with zipfile.ZipFile(inner, "w") as z:
        z.writestr("hw1/answers.yaml", (HW1 / "submissions/ada_lovelace/answers.yaml")
                   .read_bytes())
    archive = zip_with(tmp_path / "c.zip", {"lovelaceada_10001_1_hw1.zip": inner.getvalue()})
    (ada,) = read_lms_zip(archive, keys=plan.keys).students
    assert ada.status == "read"
    assert ada.messages[0] == \
        "read 'c.zip/lovelaceada_10001_1_hw1.zip/hw1/answers.yaml' as the answers file"


def test_the_example_folder_is_unchanged_by_reading_zips(tmp_path, plan, roster):
    before = sorted(p.relative_to(HW1) for p in HW1.rglob("*"))
    read_lms_zip(canvas_zip(tmp_path, roster, uploads(roster)), keys=plan.keys)
    assert sorted(p.relative_to(HW1) for p in HW1.rglob("*")) == before
    shutil.rmtree(tmp_path)
