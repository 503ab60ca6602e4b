"""``mechgrade export`` and ``mechgrade report`` through click's CliRunner."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from mechgrade.cli import main

DATA = Path(__file__).parent.parent / "data" / "export"
RESULTS = str(DATA / "results.json")


@pytest.fixture
def run():
    def invoke(*args: str):
        return CliRunner().invoke(main, list(args), catch_exceptions=False)
    return invoke


def test_export_canvas_with_roster_writes_file_and_warns(run, tmp_path):
    out = tmp_path / "canvas.csv"
    result = run("export", RESULTS, "--format", "canvas", "--roster",
                 str(DATA / "canvas_gradebook.csv"), "--out", str(out))
    assert result.exit_code == 0
    assert result.stdout == f"wrote canvas export of 7 results to {out}\n"
    assert result.stderr == (
        f"warning: {DATA / 'canvas_gradebook.csv'}:11: skipped Canvas test student "
        "'Student, Test'\n"
        "warning: x-ghost (Ghost Student) is not in the roster; written after the roster "
        "students\n"
        "warning: 70007 (Only Roster) has no submission; written with 0\n")
    with open(out, encoding="utf-8", newline="") as handle:
        rows = list(csv.reader(handle))
    assert len(rows) == 2 + 7 + 1


def test_export_blank_and_bom_flags_reach_the_file(run, tmp_path):
    out = tmp_path / "grades.csv"
    result = run("export", RESULTS, "--format", "grades-csv", "--missing", "blank",
                 "--excel-bom", "--out", str(out))
    assert result.exit_code == 0
    data = out.read_bytes()
    assert data.startswith(b"\xef\xbb\xbfid,name,status,")
    assert b"s1004,Missing Mo,missing,,,,,10\r\n" in data


def test_format_specific_flags_reach_the_file(run, tmp_path):
    canvas = tmp_path / "canvas.csv"
    assert run("export", RESULTS, "--format", "canvas", "--no-points-possible",
               "--out", str(canvas)).exit_code == 0
    assert "Points Possible" not in canvas.read_text(encoding="utf-8")
    moodle = tmp_path / "moodle.csv"
    assert run("export", RESULTS, "--format", "moodle", "--moodle-key", "idnumber",
               "--out", str(moodle)).exit_code == 0
    assert moodle.read_text(encoding="utf-8").lower().startswith("id number")
    gs = tmp_path / "gs"
    assert run("export", RESULTS, "--format", "gradescope", "--visibility", "hidden",
               "--out", str(gs)).exit_code == 0
    documents = [json.loads(p.read_text()) for p in gs.iterdir()]
    assert {t["visibility"] for d in documents for t in d["tests"]} == {"hidden"}


def test_export_default_output_name(run, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = run("export", RESULTS, "--format", "long-csv")
    assert result.exit_code == 0 and (tmp_path / "results.csv").is_file()


def test_export_gradescope_for_many_students_makes_a_folder(run, tmp_path):
    out = tmp_path / "gs"
    assert run("export", RESULTS, "--format", "gradescope", "--out", str(out)).exit_code == 0
    assert json.loads((out / "s1001.json").read_text(encoding="utf-8"))["score"] == 10.0


def test_export_of_a_missing_file_is_one_message_and_exit_2(run, tmp_path):
    result = run("export", str(tmp_path / "nope.json"), "--format", "canvas")
    assert result.exit_code == 2
    assert result.stdout == ""
    assert result.stderr == f"{tmp_path / 'nope.json'}: expected a results.json file, found no " \
                            "such file\n"


def test_export_of_bad_json_names_line_and_column(run, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"assignment": {"id": "a"\n', encoding="utf-8")
    result = run("export", str(bad), "--format", "json")
    assert result.exit_code == 2
    assert result.stderr == f"{bad}:2:1: expected JSON (a results.json written by mechgrade), " \
                            "found invalid JSON: Expecting ',' delimiter\n"


def test_export_of_json_with_the_wrong_shape_names_the_field(run, tmp_path):
    bad = tmp_path / "bad.json"
    doc = json.loads((DATA / "results.json").read_text(encoding="utf-8"))
    doc["students"][2]["answers"][0]["verdict"] = "great"
    bad.write_text(json.dumps(doc), encoding="utf-8")
    result = run("export", str(bad), "--format", "canvas")
    assert result.exit_code == 2
    assert result.stderr == (f"{bad}: students[2].answers[0].verdict: expected one of correct, "
                             "partial, incorrect, unreadable, missing, not_evaluated, found "
                             "'great'\n")


def test_export_with_unknown_format_is_refused_by_click(run):
    result = run("export", RESULTS, "--format", "xls")
    assert result.exit_code == 2
    assert result.stderr.endswith(
        "Error: Invalid value for '--format': 'xls' is not one of 'canvas', 'moodle', "
        "'gradescope', 'grades-csv', 'long-csv', 'json'.\n")


def test_export_with_a_bad_roster_is_one_message(run, tmp_path):
    roster = tmp_path / "roster.csv"
    roster.write_text("who,what\n1,2\n", encoding="utf-8")
    result = run("export", RESULTS, "--format", "canvas", "--roster", str(roster),
                 "--out", str(tmp_path / "c.csv"))
    assert result.exit_code == 2
    assert result.stderr.startswith(f"{roster}:1: expected a roster header: ")
    assert not (tmp_path / "c.csv").exists()


def test_export_refuses_to_overwrite_its_input(run, tmp_path):
    copy = tmp_path / "results.json"
    copy.write_bytes((DATA / "results.json").read_bytes())
    result = run("export", str(copy), "--format", "json", "--out", str(copy))
    assert result.exit_code == 2
    assert result.stderr == f"{copy}: expected an output path other than the results file " \
                            "itself\n"


def test_report_writes_html(run, tmp_path):
    out = tmp_path / "class.html"
    result = run("report", RESULTS, "--out", str(out))
    assert result.exit_code == 0
    assert result.stdout == f"wrote class report of 7 students to {out}\n"
    assert out.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")


def test_report_of_a_missing_file_is_one_message_and_exit_2(run, tmp_path):
    result = run("report", str(tmp_path / "nope.json"))
    assert result.exit_code == 2
    assert result.stderr == f"{tmp_path / 'nope.json'}: expected a results.json file, found no " \
                            "such file\n"
