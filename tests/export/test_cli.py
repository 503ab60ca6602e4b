"""``mechgrade export`` and ``mechgrade report`` through click's CliRunner."""

from __future__ import annotations

import csv
import json
import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from mechgrade.cli import main

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(__file__).parent.parent / "data" / "export"
RESULTS = str(DATA / "results.json")


def read_csv(path: Path, encoding: str = "utf-8") -> list[list[str]]:
    with open(path, encoding=encoding, newline="") as handle:
        return list(csv.reader(handle))


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
    assert result.stdout == (
        f"{out}: 7 new, 0 changed, 0 kept as Canvas has them, 0 unchanged; each listed in "
        f"{tmp_path / 'canvas.changes.csv'}\n"
        f"wrote canvas export of 7 results to {out}\n")
    assert result.stderr == (
        f"warning: {DATA / 'canvas_gradebook.csv'}:11: skipped Canvas test student "
        "'Student, Test'\n"
        "warning: 70007 (Only Roster) has no submission; written with 0\n"
        f"warning: 1 row kept out of {out} because Canvas could not import it: see "
        f"{tmp_path / 'canvas.unmatched.csv'} for who and why; enter those grades in Canvas by hand, "
        "or export again with --roster set to the gradebook exported from Canvas\n")
    assert len(read_csv(out)) == 2 + 7
    assert read_csv(tmp_path / "canvas.unmatched.csv")[1][0] == "x-ghost"


def test_readme_example_round_trips_into_the_rosters_column(run, tmp_path):
    hw1 = ROOT / "examples" / "hw1"
    graded = run("grade", str(hw1 / "assignment.yaml"), str(hw1 / "submissions"),
                 "--roster", str(hw1 / "roster.csv"), "--out", str(tmp_path / "out"), "--jobs", "1")
    assert graded.exit_code == 0
    out = tmp_path / "out" / "canvas.csv"
    result = run("export", str(tmp_path / "out" / "results.json"), "--format", "canvas",
                 "--roster", str(hw1 / "roster.csv"), "--out", str(out))
    assert result.exit_code == 0
    assert result.stderr == (f"warning: {hw1 / 'roster.csv'}:13: skipped Canvas test student "
                             "'Student, Test'\n")
    roster = read_csv(hw1 / "roster.csv", encoding="utf-8-sig")
    rows = read_csv(out)
    assert rows[0] == roster[0] and rows[0][-1] == "Homework 1 (40211)"
    assert [row[1] for row in rows[2:]] == [row[1] for row in roster[2:-1]]


def test_canvas_assignment_option_names_the_column(run, tmp_path):
    out = tmp_path / "canvas.csv"
    result = run("export", RESULTS, "--format", "canvas", "--roster",
                 str(DATA / "canvas_gradebook.csv"), "--canvas-assignment", "48100",
                 "--out", str(out))
    assert result.exit_code == 0
    assert read_csv(out)[0][-1] == "Homework 2 (48100)"


def test_an_unknown_canvas_assignment_is_one_message_and_exit_2(run, tmp_path):
    result = run("export", RESULTS, "--format", "canvas", "--roster",
                 str(DATA / "canvas_gradebook.csv"), "--canvas-assignment", "Homework 9",
                 "--out", str(tmp_path / "c.csv"))
    assert result.exit_code == 2
    assert result.stderr == ("canvas_assignment: expected one of the roster's assignment "
                             "columns ('Homework 2 (48100)', 'Homework 3 (48213)') or its "
                             "Canvas id, found 'Homework 9'\n")
    assert not (tmp_path / "c.csv").exists()


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
    documents = [json.loads(p.read_text()) for p in gs.iterdir() if p.name != "manifest.json"]
    # every test but the receipt saying what was read
    assert {t["visibility"] for d in documents for t in d["tests"][1:]} == {"hidden"}


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


def _results_with(tmp_path, score: str) -> Path:
    """The test results.json with its first student's score written as ``score`` (raw JSON
    text, such as ``NaN``)."""
    doc = json.loads((DATA / "results.json").read_text(encoding="utf-8"))
    text = json.dumps(doc).replace(f'"score": {json.dumps(doc["students"][0]["score"])}',
                                   f'"score": {score}', 1)
    path = tmp_path / "results.json"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("command", ["export", "report"])
@pytest.mark.parametrize("score, found", [
    ("NaN", "NaN"), ("Infinity", "Infinity"), ("-Infinity", "-Infinity"),
    ("1e999", "1e999, beyond the largest floating-point number"),
    ("1" + "0" * 4999, "100000000000...0000 (5000 characters), longer than 400 characters"),
])
def test_a_score_that_is_not_a_finite_number_is_refused_at_its_field(run, tmp_path, command,
                                                                      score, found):
    path = _results_with(tmp_path, score)
    out = tmp_path / "out.csv"
    args = ["--format", "grades-csv", "--out", str(out)] if command == "export" else \
        ["--out", str(out)]
    result = run(command, str(path), *args)
    assert result.exit_code == 2
    assert result.stderr == f"{path}: students[0].score: expected a finite number, found " \
                            f"{found}\n"
    assert not out.exists()


@pytest.mark.parametrize("command", ["export", "report"])
def test_a_results_json_nested_100k_deep_is_one_located_message(run, tmp_path, command):
    path = tmp_path / "results.json"
    path.write_text('{"assignment": {"id": "a", "title": "A"}, "students": [],\n"notes": '
                    + "[" * 100_000 + "]" * 100_000 + "}", encoding="utf-8")
    args = ["--format", "json", "--out", str(tmp_path / "o")] if command == "export" else \
        ["--out", str(tmp_path / "o")]
    result = run(command, str(path), *args)
    assert result.exit_code == 2
    assert result.stderr == f"{path}:2:109: expected JSON nested at most 100 levels deep, " \
                            "found deeper nesting\n"


@pytest.mark.parametrize("field, value, message", [
    (("students", 0, "score"), 1e308, "expected a number of magnitude at most 1e+40, found "
                                      "1e+308"),
    (("students", 0, "score"), 2e9, "expected a number <= 1e+09, found 2000000000.0"),
    (("students", 0, "max_score"), -1.0, "expected a number >= 0, found -1.0"),
    (("objectives", 0, "max_points"), 1e30, "expected a number <= 1000, found 1e+30"),
    (("students", 1, "answers", 0, "points"), 5000, "expected a number <= 1000, found 5000"),
])
def test_points_beyond_what_an_assignment_allows_are_refused_before_any_statistics(
        run, tmp_path, field, value, message):
    doc = json.loads((DATA / "results.json").read_text(encoding="utf-8"))
    target = doc
    for key in field[:-1]:
        target = target[key]
    target[field[-1]] = value
    path = tmp_path / "results.json"
    path.write_text(json.dumps(doc), encoding="utf-8")
    result = run("report", str(path), "--out", str(tmp_path / "r.html"))
    assert result.exit_code == 2
    where = "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in field).lstrip(".")
    assert result.stderr == f"{path}: {where}: {message}\n"


def test_a_results_json_that_is_a_fifo_is_refused_without_waiting(run, tmp_path):
    path = tmp_path / "results.json"
    os.mkfifo(path)
    result = run("export", str(path), "--format", "json", "--out", str(tmp_path / "o.json"))
    assert result.exit_code == 2
    assert result.stderr == f"{path}: expected a results.json file, found a FIFO (named pipe), " \
                            "not a regular file\n"


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


def test_moodle_export_holds_back_rows_and_says_so(run, tmp_path):
    out = tmp_path / "moodle.csv"
    result = run("export", RESULTS, "--format", "moodle", "--roster",
                 str(DATA / "moodle_grades.csv"), "--missing", "blank", "--out", str(out))
    assert result.exit_code == 0
    assert result.stderr == (
        "warning: Moodle cuts a grade above the grade item's maximum grade to that maximum "
        "without a word: check that 'Assignment: Homework 3 (Real)' is out of 10 points in "
        "Moodle, or export with --scale-to <its maximum grade>\n"
        "warning: the grades export's 'Last downloaded from this course' of s1001 is "
        "'1700000000': Moodle refuses the whole import unless that is a time within the last "
        "year; export the grades from Moodle again and give that file as --roster\n"
        f"warning: 6 rows kept out of {out} because Moodle could not import them: see "
        f"{tmp_path / 'moodle.unmatched.csv'} for who and why; enter those grades in Moodle by hand, "
        "or export again with --roster set to the grades exported from Moodle\n")
    held = read_csv(tmp_path / "moodle.unmatched.csv")
    assert held[1] == ["s1004", "Missing Mo", "missing", "",
                       "no grade (no submission and --missing blank); Moodle clears the grade "
                       "of a row imported with feedback only"]
    assert [row[0] for row in read_csv(out)[1:]] == [
        "ada@uni.example", "emilie@uni.example", "mallory@uni.example"]


def test_a_gradescope_folder_for_fewer_students_holds_only_theirs(run, tmp_path):
    out = tmp_path / "gs"
    assert run("export", RESULTS, "--format", "gradescope", "--out", str(out)).exit_code == 0
    data = json.loads(Path(RESULTS).read_text(encoding="utf-8"))
    data["students"] = data["students"][:2]
    fewer = tmp_path / "fewer.json"
    fewer.write_text(json.dumps(data), encoding="utf-8")
    result = run("export", str(fewer), "--format", "gradescope", "--out", str(out))
    assert result.exit_code == 0, result.output
    kept = sorted(p.name for p in out.iterdir())
    assert kept == sorted([f"{s['id']}.json" for s in data["students"]] + ["manifest.json"])
    assert result.stdout.startswith(f"wrote gradescope export of 2 results to {out}\n"
                                    f"Removed from the previous run (not written by this one):")
