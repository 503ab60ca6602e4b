"""Every exporter, parsed back and checked against its format's rules."""

from __future__ import annotations

import csv
import json
from dataclasses import replace
from pathlib import Path

import pytest

from mechgrade.errors import ExportError
from mechgrade.export import EXPORTERS, ExportOptions, export, match_roster
from mechgrade.grade.results import GradeReport

FORMULA_STARTS = ("=", "+", "@", "\t", "\r")


def read_csv(path: Path) -> list[list[str]]:
    with open(path, encoding="utf-8", newline="") as handle:
        return list(csv.reader(handle))


def assert_no_formula(rows: list[list[str]]) -> None:
    for row in rows:
        for cell in row:
            if cell.startswith(FORMULA_STARTS) or cell.startswith("-"):
                assert cell.startswith("'") or float(cell) < 0, cell


# --- Canvas ------------------------------------------------------------------------------------

def test_canvas_without_roster_has_the_canvas_header_and_points_possible(report, tmp_path):
    out = tmp_path / "canvas.csv"
    EXPORTERS["canvas"](report, out)
    rows = read_csv(out)
    assert rows[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section",
                       "Homework 3 (hw3)"]
    assert rows[1] == ["    Points Possible", "", "", "", "", "10"]
    assert len(rows) == 2 + len(report.students)
    assert all(len(row) == 6 for row in rows)
    by_id = {row[1]: row for row in rows[2:]}
    assert by_id["s1002"][0] == "Émilie du Châtelet" and by_id["s1002"][5] == "5.5"
    assert by_id["s1003"][0].startswith("'=HYPERLINK(")
    assert by_id["s1004"][5] == "0"
    assert_no_formula(rows)


def test_canvas_with_canvas_roster_writes_every_roster_student_back(report, canvas_roster,
                                                                     tmp_path):
    out = tmp_path / "canvas.csv"
    EXPORTERS["canvas"](report, out, roster=canvas_roster)
    rows = read_csv(out)
    # The roster's own column for the assignment is reused, so Canvas updates it in place.
    assert rows[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section",
                       "Homework 3 (48213)"]
    body = rows[2:]
    ids = [row[1] for row in body]
    assert ids[:7] == [s.id for s in canvas_roster.students]
    assert [row[:5] for row in body[:7]] == \
        [[("'" + v if v.startswith("=") else v) for _, v in s.columns]
         for s in canvas_roster.students]
    grade = {row[1]: row[5] for row in body}
    assert grade["70001"] == "10" and grade["70006"] == "3"  # Seán matched by name
    assert grade["70007"] == "0"  # in the roster, no submission
    assert body[-1][0] == "Ghost Student" and body[-1][1] == "x-ghost" and body[-1][5] == "7"
    assert "70099" not in ids  # the Canvas test student


def test_canvas_missing_blank_leaves_the_grade_empty(report, canvas_roster, tmp_path):
    out = tmp_path / "canvas.csv"
    EXPORTERS["canvas"](report, out, roster=canvas_roster,
                        options=ExportOptions(missing="blank", points_possible=False))
    rows = read_csv(out)
    grade = {row[1]: row[5] for row in rows[1:]}
    assert grade["70007"] == "" and grade["70004"] == "" and grade["70005"] == "0"
    assert rows[1][0] != "    Points Possible"


def test_roster_matching_reports_who_is_not_in_the_roster(report, canvas_roster):
    matched = match_roster(report, canvas_roster)
    assert [r.id for r in matched.not_in_roster] == ["x-ghost"]
    assert [s.id for s in matched.no_submission] == ["70007"]
    assert {p.matched_by for p in matched.pairs if p.roster and p.result} == \
        {"sis_user_id", "name"}


def test_an_ambiguous_name_matches_nobody(report, canvas_roster):
    twin = replace(report.students[5], id="s9999")
    doubled = replace(report, students=report.students + (twin,))
    matched = match_roster(doubled, canvas_roster)
    assert {r.id for r in matched.not_in_roster} == {"x-ghost", "s1006", "s9999"}


# --- Moodle ------------------------------------------------------------------------------------

def test_moodle_has_key_columns_grade_and_feedback(report, moodle_roster, tmp_path):
    out = tmp_path / "moodle.csv"
    EXPORTERS["moodle"](report, out, roster=moodle_roster)
    rows = read_csv(out)
    assert rows[0] == ["Email address", "ID number", "First name", "Last name",
                       "Assignment: Homework 3 (Real)", "Assignment: Homework 3 (Feedback)"]
    by_email = {row[0]: row for row in rows[1:]}
    assert set(s.email for s in moodle_roster.students) <= set(by_email)
    emilie = by_email["emilie@uni.example"]
    assert emilie[1:5] == ["s1002", "Émilie", "du Châtelet", "5.5"]
    assert "p1/a_B: partial 1/4 (dropped the Coriolis term)" in emilie[5].splitlines()
    assert by_email["only@uni.example"][4] == "0"
    assert by_email["only@uni.example"][5] == "No submission received."
    # Uma has no ID number in Moodle and the results carry no email: both sides are kept.
    assert by_email["uma@uni.example"][4] == "0"
    assert any(row[3] == "Uma" or row[2] == "Unreadable" for row in rows[1:] if row[0] == "")
    assert_no_formula(rows)


def test_moodle_can_be_keyed_by_id_number(report, tmp_path):
    out = tmp_path / "moodle.csv"
    EXPORTERS["moodle"](report, out, options=ExportOptions(moodle_key="idnumber"))
    rows = read_csv(out)
    assert rows[0][:2] == ["ID number", "Email address"]
    assert rows[0][4:] == ["Homework 3 (Real)", "Homework 3 (Feedback)"]
    assert len(rows) == 1 + len(report.students)


# --- Gradescope --------------------------------------------------------------------------------

VISIBILITY = {"hidden", "after_due_date", "after_published", "visible"}


def check_gradescope(doc: dict, n_objectives: int) -> None:
    assert isinstance(doc["score"], float)
    assert isinstance(doc["output"], str) and doc["visibility"] in VISIBILITY
    assert doc["output_format"] == doc["test_output_format"] == doc["test_name_format"] == "text"
    assert len(doc["tests"]) == n_objectives
    for test in doc["tests"]:
        assert set(test) == {"name", "number", "score", "max_score", "status", "output",
                             "visibility"}
        assert isinstance(test["score"], float) and isinstance(test["max_score"], float)
        assert 0 <= test["score"] <= test["max_score"]
        assert test["status"] in {"passed", "failed"}
        assert isinstance(test["name"], str) and isinstance(test["output"], str)
        assert test["visibility"] in VISIBILITY


def test_gradescope_single_student_results_json(report, tmp_path):
    one = replace(report, students=(report.students[1],))
    out = tmp_path / "results.json"
    EXPORTERS["gradescope"](one, out, options=ExportOptions(gradescope_visibility="after_due_date"))
    doc = json.loads(out.read_text(encoding="utf-8"))
    check_gradescope(doc, 3)
    assert doc["score"] == 5.5 and doc["visibility"] == "after_due_date"
    assert sum(t["score"] for t in doc["tests"]) == doc["score"]
    a_b = doc["tests"][1]
    assert a_b["name"] == "p1/a_B: Acceleration of B (rotating frame)"
    assert a_b["status"] == "failed" and a_b["score"] == 1.0 and a_b["max_score"] == 4.0
    assert "dropped the Coriolis term" in a_b["output"]
    assert doc["tests"][0]["status"] == "passed"


def test_gradescope_missing_student_gets_every_objective_failed(report, tmp_path):
    one = replace(report, students=(report.students[3],))
    out = tmp_path / "results.json"
    EXPORTERS["gradescope"](one, out)
    doc = json.loads(out.read_text(encoding="utf-8"))
    check_gradescope(doc, 3)
    assert doc["score"] == 0.0 and "No submission was found." in doc["output"]
    assert {t["status"] for t in doc["tests"]} == {"failed"}


def test_gradescope_many_students_go_to_one_file_each(report, tmp_path):
    out = tmp_path / "gs"
    EXPORTERS["gradescope"](report, out)
    files = sorted(p.name for p in out.iterdir())
    assert files == sorted(f"{s.id}.json" for s in report.students)
    for path in out.iterdir():
        check_gradescope(json.loads(path.read_text(encoding="utf-8")), 3)


def test_gradescope_with_no_student_is_an_export_error(report, tmp_path):
    with pytest.raises(ExportError, match="expected at least one student"):
        EXPORTERS["gradescope"](replace(report, students=()), tmp_path / "r.json")


# --- mechgrade tables and JSON -----------------------------------------------------------------

def test_grades_csv_has_one_row_per_student_with_objective_points(report, tmp_path):
    out = tmp_path / "grades.csv"
    EXPORTERS["grades-csv"](report, out)
    rows = read_csv(out)
    assert rows[0] == ["id", "name", "status", "p1/v_B", "p1/a_B", "p2/alpha", "total", "max"]
    by_id = {row[0]: row for row in rows[1:]}
    assert set(by_id) == {s.id for s in report.students}
    assert by_id["s1002"][2:] == ["graded", "3", "1", "1.5", "5.5", "10"]
    assert by_id["s1004"][2:] == ["missing", "0", "0", "0", "0", "10"]
    assert_no_formula(rows)


def test_grades_csv_with_roster_keeps_roster_students_and_blank_missing(report, canvas_roster,
                                                                         tmp_path):
    out = tmp_path / "grades.csv"
    EXPORTERS["grades-csv"](report, out, roster=canvas_roster,
                            options=ExportOptions(missing="blank"))
    rows = read_csv(out)
    ids = [row[0] for row in rows[1:]]
    assert ids == [s.id for s in canvas_roster.students] + ["x-ghost"]
    assert rows[7][2:] == ["missing", "", "", "", "", "10"]


def test_long_csv_has_one_row_per_student_and_objective(report, tmp_path):
    out = tmp_path / "results.csv"
    EXPORTERS["long-csv"](report, out)
    rows = read_csv(out)
    assert rows[0] == ["student", "name", "problem", "objective", "answer", "verdict", "points",
                       "max_points", "diagnosis"]
    assert len(rows) == 1 + 3 * len(report.students)
    mallory = [row for row in rows if row[0] == "s1003"]
    assert [row[4] for row in mallory] == ["'=1+1", "'-omega**2*r", "'@SUM(A1)"]
    sean = [row for row in rows if row[0] == "s1006"]
    assert [row[5] for row in sean] == ["unreadable", "missing", "correct"]
    assert_no_formula(rows)


def test_json_export_round_trips_and_adds_missing_roster_students(report, canvas_roster,
                                                                  tmp_path):
    out = tmp_path / "r.json"
    EXPORTERS["json"](report, out)
    assert GradeReport.from_json(json.loads(out.read_text(encoding="utf-8"))) == report
    EXPORTERS["json"](report, out, roster=canvas_roster)
    again = GradeReport.from_json(json.loads(out.read_text(encoding="utf-8")))
    assert len(again.students) == len(report.students) + 1
    only = next(s for s in again.students if s.id == "70007")
    assert only.status == "missing" and dict(only.identity)["Student"] == "Roster, Only"


@pytest.mark.parametrize("fmt", ["canvas", "moodle", "grades-csv", "long-csv"])
def test_every_csv_export_round_trips_unicode_and_honours_the_bom_option(report, tmp_path, fmt):
    plain, bom = tmp_path / "plain.csv", tmp_path / "bom.csv"
    export(report, fmt, plain)
    export(report, fmt, bom, options=ExportOptions(excel_bom=True))
    assert not plain.read_bytes().startswith(b"\xef\xbb\xbf")
    assert bom.read_bytes() == b"\xef\xbb\xbf" + plain.read_bytes()
    text = plain.read_text(encoding="utf-8")
    assert "Émilie du Châtelet" in text or "Émilie" in text
    assert_no_formula(read_csv(plain))


def test_unknown_format_is_an_export_error(report, tmp_path):
    with pytest.raises(ExportError, match="format: expected a format among canvas, moodle, "
                                          "gradescope, grades-csv, long-csv, json, found 'xls'"):
        export(report, "xls", tmp_path / "x")


def test_bad_options_are_refused():
    with pytest.raises(ExportError, match="gradescope_visibility: expected one of 'visible', "
                                          "'hidden', 'after_due_date', 'after_published', "
                                          "found 'public'"):
        ExportOptions(gradescope_visibility="public")
