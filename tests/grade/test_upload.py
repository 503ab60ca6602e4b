"""Finding the answers in a Gradescope upload: zipped folders, renamed files, hostile zips."""

from __future__ import annotations

import os
import zipfile
from pathlib import Path

import pytest

from mechgrade.grade.upload import MAX_MEMBERS, read_upload
from mechgrade.grade.submissions import MAX_FILE_BYTES

ANSWERS = b"p.v = 3 m/s\np.a = 2 m/s^2\n"


def zip_of(path: Path, members: dict, compression=zipfile.ZIP_DEFLATED) -> Path:
    with zipfile.ZipFile(path, "w", compression) as archive:
        for name, data in members.items():
            archive.writestr(name, data)
    return path


@pytest.fixture
def upload(tmp_path):
    folder = tmp_path / "submission"
    folder.mkdir()
    return folder


def test_answers_at_the_top_are_read_as_before(upload):
    (upload / "answers.txt").write_bytes(ANSWERS)
    found = read_upload(upload, "ana")
    assert found.read_from is None and found.submission.status == "read"
    assert dict(found.submission.answers) == {"p.v": "3 m/s", "p.a": "2 m/s^2"}


def test_the_answers_file_nearest_the_top_of_a_zip_wins(upload):
    zip_of(upload / "hw1.zip", {"hw1/old/answers.yaml": b"p.v: 9 m/s\n",
                                "hw1/answers.txt": ANSWERS, "hw1/notes.txt": b"hello"})
    found = read_upload(upload, "ana")
    assert found.read_from == "hw1.zip/hw1/answers.txt"
    assert found.submission.files == ("hw1.zip/hw1/answers.txt",)
    assert found.submission.messages[0] == "read 'hw1.zip/hw1/answers.txt' as the answers file"


def test_messages_about_the_file_name_the_file_the_student_uploaded(upload):
    (upload / "my_answers.txt").write_bytes(b"p.v = 3 m/s\nthis is not a line\n")
    found = read_upload(upload, "ana", keys={"p.v"})
    assert found.read_from == "my_answers.txt"
    assert found.submission.messages[1].startswith("my_answers.txt:2: expected ")
    assert not any("mechgrade-upload" in m for m in found.submission.messages)


def test_several_possible_files_are_not_guessed_between(upload):
    (upload / "a.txt").write_bytes(ANSWERS)
    (upload / "b.yaml").write_bytes(b"p: {v: 1 m/s}\n")
    found = read_upload(upload, "ana")
    assert found.read_from is None and found.submission.status == "missing"
    assert found.submission.messages[-1] == (
        "found 2 files that could hold the answers ('a.txt', 'b.yaml'); none was graded: name "
        "the one to grade answers.yaml (or .json, .txt)")


def test_zip_members_that_climb_out_or_are_absolute_are_never_read_or_written(upload,
                                                                             tmp_path):
    zip_of(upload / "evil.zip", {"../../outside/answers.txt": ANSWERS,
                                 "/abs/answers.txt": ANSWERS})
    found = read_upload(upload, "ana")
    assert found.submission.status == "missing" and found.read_from is None
    assert not (tmp_path.parent / "outside").exists()
    assert sorted(p.name for p in upload.iterdir()) == ["evil.zip"]


def test_a_zip_bomb_is_refused_by_its_size_without_inflating_it(upload):
    big = MAX_FILE_BYTES * 40
    zip_of(upload / "bomb.zip", {"answers.txt": b"p.v = 1\n" + b" " * big})
    found = read_upload(upload, "ana")
    assert found.submission.status == "missing" and found.submission.answers == ()
    (note,) = [m for m in found.submission.messages if m.startswith("'bomb.zip/answers.txt'")]
    assert note.startswith(f"'bomb.zip/answers.txt' declares {big + 8} bytes from ")
    assert note.endswith(" (a zip bomb); it was not read")


def test_a_zip_whose_header_lies_about_the_size_is_cut_short(upload):
    path = zip_of(upload / "liar.zip", {"answers.txt": b"p.v = 1\n" + b" " * (MAX_FILE_BYTES * 4)})
    data = bytearray(path.read_bytes())
    # Rewrite the uncompressed size in the central directory to 10 bytes.
    central = data.rindex(b"PK\x01\x02")
    data[central + 24:central + 28] = (10).to_bytes(4, "little")
    path.write_bytes(bytes(data))
    found = read_upload(upload, "ana")
    assert found.submission.messages == ("'liar.zip/answers.txt' cannot be read (BadZipFile)",)


def test_a_zip_with_too_many_entries_is_not_searched(upload):
    zip_of(upload / "many.zip", {f"f{i}.txt": b"" for i in range(MAX_MEMBERS + 1)},
           zipfile.ZIP_STORED)
    found = read_upload(upload, "ana")
    assert f"'many.zip' holds {MAX_MEMBERS + 1} entries (at most {MAX_MEMBERS} are looked " \
           "at); it was not searched" in found.submission.messages


def test_an_encrypted_member_is_not_read(upload):
    path = zip_of(upload / "locked.zip", {"answers.txt": ANSWERS})
    data = bytearray(path.read_bytes())
    for header, offset in ((b"PK\x03\x04", 6), (b"PK\x01\x02", 8)):  # the "encrypted" flag
        at = data.index(header) + offset
        data[at] |= 0x1
    path.write_bytes(bytes(data))
    found = read_upload(upload, "ana")
    assert "'locked.zip/answers.txt' is encrypted; it was not read" in found.submission.messages


def test_a_file_that_is_not_a_zip_is_reported(upload):
    (upload / "hw1.zip").write_bytes(b"not a zip at all")
    found = read_upload(upload, "ana")
    assert "'hw1.zip' is not a zip file that can be read (BadZipFile)" in \
        found.submission.messages


def test_links_in_the_upload_are_not_followed(upload, tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_bytes(ANSWERS)
    os.symlink(secret, upload / "mine.txt")
    found = read_upload(upload, "ana")
    assert found.read_from is None and found.submission.answers == ()
