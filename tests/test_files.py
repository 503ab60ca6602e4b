"""The one output writer and the one sanitiser every output string passes."""

import json
import os
import stat
import threading
from pathlib import Path

import pytest

from mechgrade.errors import ExportError, OutputError
from mechgrade.files import clean_text, read_text, write_json, write_text


def test_atomic_write_leaves_no_temporary_file_and_replaces(tmp_path):
    target = tmp_path / "out.csv"
    target.write_text("old")
    write_text(target, "new")
    assert target.read_text() == "new"
    assert [p.name for p in tmp_path.iterdir()] == ["out.csv"]


def test_writing_into_a_missing_folder_is_an_output_error(tmp_path):
    with pytest.raises(OutputError, match=r"expected an existing folder to write 'x.csv' into, "
                                          "found none"):
        write_text(tmp_path / "nope" / "x.csv", "a")


def test_writing_onto_a_folder_is_an_output_error(tmp_path):
    with pytest.raises(OutputError, match="expected a file path to write, found a folder"):
        write_text(tmp_path, "a")


def test_written_files_get_the_mode_open_would_give_them(tmp_path):
    old = os.umask(0o022)
    try:
        write_text(tmp_path / "a.csv", "x")
        write_json(tmp_path / "r.json", {})
    finally:
        os.umask(old)
    for name in ("a.csv", "r.json"):
        assert stat.S_IMODE((tmp_path / name).stat().st_mode) == 0o644


@pytest.mark.parametrize("text, cleaned", [
    ("bad\udce9name", "bad\\xe9name"),       # a byte that is not UTF-8, from a file name
    ("\ud800", "\\ud800"),                   # a lone surrogate from a JSON "\ud800"
    ("\udfff\ud83d", "\\udfff\\ud83d"),
    ("Zoë 😀 \u2029", "Zoë 😀 \u2029"),      # valid text is left alone
])
def test_lone_surrogates_are_escaped_visibly(text, cleaned):
    assert clean_text(text) == cleaned


def test_json_with_lone_surrogates_is_valid_utf8_json(tmp_path):
    write_json(tmp_path / "r.json", {"bad\udce9": ["\ud800", 1.5]})
    raw = (tmp_path / "r.json").read_bytes()
    assert json.loads(raw.decode("utf-8")) == {"bad\\xe9": ["\\ud800", 1.5]}


def test_json_refuses_nan_with_a_message(tmp_path):
    with pytest.raises(OutputError, match="expected finite numbers"):
        write_json(tmp_path / "r.json", {"x": float("nan")})


def test_a_file_that_already_holds_the_text_is_left_alone(tmp_path):
    path = tmp_path / "page.html"
    write_text(path, "same\n")
    before = path.stat()
    write_text(path, "same\n")
    assert path.stat().st_ino == before.st_ino and path.read_text() == "same\n"
    write_text(path, "other\n")
    assert path.stat().st_ino != before.st_ino and path.read_text() == "other\n"


def test_a_named_pipe_in_the_way_is_replaced_without_waiting(tmp_path):
    path = tmp_path / "page.html"
    os.mkfifo(path)
    write_text(path, "text\n")
    assert stat.S_ISREG(path.stat().st_mode) and path.read_text() == "text\n"


@pytest.mark.parametrize("kind", ["fifo", "device", "folder"])
def test_reading_anything_but_a_regular_file_is_refused_without_waiting(tmp_path, kind):
    path = {"fifo": tmp_path / "results.json", "device": Path("/dev/zero"),
            "folder": tmp_path}[kind]
    if kind == "fifo":
        os.mkfifo(path)
    outcome: list[BaseException] = []

    def read() -> None:
        try:
            read_text(path, what="a results.json file", error=ExportError)
        except ExportError as err:
            outcome.append(err)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    reader.join(60)  # a FIFO without a writer blocked open() for ever
    found = {"fifo": "a FIFO (named pipe), not a regular file",
             "device": "a character device, not a regular file", "folder": "a folder"}[kind]
    assert [str(e) for e in outcome] == [f"{path}: expected a results.json file, found {found}"]


def test_visible_text_escapes_what_would_act_on_a_terminal():
    from mechgrade.files import visible_text

    assert visible_text("Zoë Ω 😀 dan_wu") == "Zoë Ω 😀 dan_wu"
    assert visible_text("\x1b]0;t\x07\x1b[2J\x9b\r\t\n\u2028\u202e") == \
        "\\x1b]0;t\\x07\\x1b[2J\\x9b\\r\\t\\n\\u2028\\u202e"
    assert visible_text("bad\udce9name") == "bad\\xe9name"
