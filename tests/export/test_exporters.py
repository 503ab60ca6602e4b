"""Every exporter, parsed back and checked against its format's rules."""

from __future__ import annotations

import csv
import json
from dataclasses import replace
from pathlib import Path

import pytest
from gradescope_results import check_results

from mechgrade.errors import ExportError
from mechgrade.export import EXPORTERS, ExportOptions, export
from mechgrade.export.matching import match_roster
from mechgrade.export.canvas import canvas_column
from mechgrade.export.moodle import moodle_names
from mechgrade.export.options import MissingGrade, MoodleKey, Visibility
from mechgrade.grade.results import GradeReport
from mechgrade.roster import MatchKind, Roster, RosterFormat, RosterStudent

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

ROOT = Path(__file__).resolve().parents[2]
UNMATCHED_HEADER = ["id", "name", "status", "score", "reason"]
NO_CANVAS_ID = "no Canvas user ID or SIS id to match it by (not from a Canvas gradebook export)"


def canvas_report(report: GradeReport) -> GradeReport:
    """The test results as if graded with a Canvas gradebook export as roster (x-ghost: not)."""
    ids = {"s1001": "70001", "s1002": "70002", "s1003": "70003", "s1004": "70004"}
    students = tuple(
        replace(s, identity=(("Student", s.name), ("ID", ids[s.id]), ("SIS User ID", s.id),
                             ("SIS Login ID", ""), ("Section", "ME 301-01")))
        if s.id in ids else s for s in report.students)
    return replace(report, students=students)


def test_canvas_without_roster_holds_back_rows_without_a_canvas_id(report, tmp_path):
    out = tmp_path / "canvas.csv"
    warnings = EXPORTERS["canvas"](canvas_report(report), out)
    rows = read_csv(out)
    assert rows[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "Homework 3"]
    assert rows[1] == ["    Points Possible", "", "", "", "", "10"]
    assert [row[1] for row in rows[2:]] == ["70001", "70002", "70003", "70004"]
    assert rows[3] == ["Émilie du Châtelet", "70002", "s1002", "", "ME 301-01", "5.5"]
    assert rows[4][0].startswith("'=HYPERLINK(")
    assert all(len(row) == 6 for row in rows)
    assert_no_formula(rows)
    # A folder name in Canvas's numeric ID column could match another user: never written.
    assert read_csv(tmp_path / "canvas.unmatched.csv") == [
        UNMATCHED_HEADER,
        ["s1005", "Unreadable Uma", "unreadable", "0", NO_CANVAS_ID],
        ["s1006", "Seán O'Brien", "graded", "3", NO_CANVAS_ID],
        ["x-ghost", "Ghost Student", "graded", "7", NO_CANVAS_ID]]
    assert warnings == (
        "the Canvas assignment column 'Homework 3' has no Canvas assignment id: Canvas fills "
        "the assignment of exactly that title or creates a new one; name it with "
        "--canvas-assignment (its id, as in 'Title (12345)')",
        f"{out} was not compared with the grades already in Canvas (no gradebook exported from "
        "Canvas as --roster): Canvas replaces every grade that differs, excused (EX) and "
        "hand-entered ones included",
        f"3 rows kept out of {out} because Canvas could not import them: see "
        f"{tmp_path / 'canvas.unmatched.csv'} for who and why; enter those grades in Canvas by hand, "
        "or export again with --roster set to the gradebook exported from Canvas",
        f"{out}: 4 new, 0 changed, 0 kept as Canvas has them, 0 unchanged; each listed in "
        f"{tmp_path / 'canvas.changes.csv'}")


def test_canvas_without_any_canvas_identity_writes_no_student_row(report, tmp_path):
    out = tmp_path / "canvas.csv"
    EXPORTERS["canvas"](report, out, options=ExportOptions(canvas_assignment="48213"))
    rows = read_csv(out)
    assert rows == [["Student", "ID", "SIS User ID", "SIS Login ID", "Section",
                     "Homework 3 (48213)"], ["    Points Possible", "", "", "", "", "10"]]
    assert len(read_csv(tmp_path / "canvas.unmatched.csv")) == 1 + len(report.students)


def test_canvas_with_a_plain_roster_matches_by_sis_id_with_the_id_left_blank(report, tmp_path):
    roster = Roster((RosterStudent("r1", "Ada Lovelace", sis_user_id="s1001"),
                     RosterStudent("r2", "Bob Roe")), RosterFormat.PLAIN,
                    ("id", "name", "sis_user_id"))
    EXPORTERS["canvas"](report, tmp_path / "canvas.csv", roster=roster)
    rows = read_csv(tmp_path / "canvas.csv")
    assert rows[2:] == [["Ada Lovelace", "", "s1001", "", "", "10"]]
    held = read_csv(tmp_path / "canvas.unmatched.csv")
    assert held[1] == ["r2", "Bob Roe", "missing", "0", NO_CANVAS_ID]
    assert [row[4] for row in held[2:]] == ["not in the roster"] * 6


def test_canvas_with_canvas_roster_writes_every_roster_student_back(report, canvas_roster,
                                                                     tmp_path):
    out = tmp_path / "canvas.csv"
    warnings = EXPORTERS["canvas"](report, out, roster=canvas_roster)
    rows = read_csv(out)
    # The roster's own column for the assignment is reused, so Canvas updates it in place.
    assert rows[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section",
                       "Homework 3 (48213)"]
    body = rows[2:]
    ids = [row[1] for row in body]
    assert ids == [s.id for s in canvas_roster.students]
    assert [row[:5] for row in body] == \
        [[("'" + v if v.startswith("=") else v) for _, v in s.columns]
         for s in canvas_roster.students]
    grade = {row[1]: row[5] for row in body}
    assert grade["70001"] == "10" and grade["70006"] == "3"  # Seán matched by name
    assert grade["70007"] == "0"  # in the roster, no submission
    assert "70099" not in ids  # the Canvas test student
    assert read_csv(tmp_path / "canvas.unmatched.csv") == [
        UNMATCHED_HEADER,
        ["x-ghost", "Ghost Student", "graded", "7", "not in the roster"]]
    assert warnings == (
        "70007 (Only Roster) has no submission; written with 0",
        f"1 row kept out of {out} because Canvas could not import it: see "
        f"{tmp_path / 'canvas.unmatched.csv'} for who and why; enter those grades in Canvas by hand, "
        "or export again with --roster set to the gradebook exported from Canvas",
        f"{out}: 7 new, 0 changed, 0 kept as Canvas has them, 0 unchanged; each listed in "
        f"{tmp_path / 'canvas.changes.csv'}")


def test_the_bundled_example_round_trips_into_the_rosters_own_column(tmp_path):
    """mechgrade grade + export of examples/hw1 fill 'Homework 1 (40211)', every student."""
    from mechgrade.grade.assignment import load_assignment
    from mechgrade.grade.run import grade_submissions
    from mechgrade.roster import read_roster

    hw1 = ROOT / "examples" / "hw1"
    roster = read_roster(hw1 / "roster.csv")
    graded = grade_submissions(load_assignment(hw1 / "assignment.yaml"), hw1 / "submissions",
                               roster)
    out = tmp_path / "canvas.csv"
    assert EXPORTERS["canvas"](graded, out, roster=roster) == (
        f"{out}: 10 new, 0 changed, 0 kept as Canvas has them, 0 unchanged; each listed in "
        f"{tmp_path / 'canvas.changes.csv'}",)
    rows = read_csv(out)
    with open(hw1 / "roster.csv", encoding="utf-8-sig", newline="") as handle:
        exported = list(csv.reader(handle))
    assert rows[0] == exported[0]
    assert [row[:5] for row in rows[2:]] == [row[:5] for row in exported[2:-1]]
    assert [row[5] for row in rows[2:]][:2] == ["19", "14"]
    assert not (tmp_path / "canvas.unmatched.csv").exists()


def roster_with(columns: list[str]) -> Roster:
    return Roster((), RosterFormat.CANVAS, ("Student", "ID", "SIS User ID", "SIS Login ID",
                                            "Section", *columns, "Current Score"))


@pytest.mark.parametrize("wanted, column", [
    (None, "Homework 3 (48213)"), ("48100", "Homework 2 (48100)"),
    ("Homework 2 (48100)", "Homework 2 (48100)"), ("homework 2", "Homework 2 (48100)")])
def test_canvas_assignment_is_named_or_picked_from_the_roster(report, wanted, column):
    roster = roster_with(["Homework 2 (48100)", "Homework 3 (48213)"])
    assert canvas_column(report, roster, wanted) == column


def test_canvas_assignment_is_the_only_assignment_column_whatever_its_title(report):
    assert canvas_column(report, roster_with(["HW three (777)"])) == "HW three (777)"


def test_canvas_assignment_without_a_roster_takes_the_given_name_or_id(report):
    assert canvas_column(report, None, "40211") == "Homework 3 (40211)"
    assert canvas_column(report, None, "Homework 3 (40211)") == "Homework 3 (40211)"
    assert canvas_column(report, None) == "Homework 3"


def test_an_ambiguous_canvas_assignment_is_an_error_listing_the_candidates(report):
    roster = roster_with(["Homework 1 (1)", "Homework 2 (2)"])
    with pytest.raises(ExportError) as caught:
        canvas_column(report, roster)
    assert str(caught.value) == (
        "canvas_assignment: expected one Canvas assignment column for 'Homework 3' in the "
        "roster, found 2: 'Homework 1 (1)', 'Homework 2 (2)'; choose one with "
        "--canvas-assignment (its title or id)")


def test_a_canvas_assignment_not_in_the_roster_is_an_error(report):
    roster = roster_with(["Homework 1 (1)", "Homework 2 (2)"])
    with pytest.raises(ExportError) as caught:
        canvas_column(report, roster, "99")
    assert str(caught.value) == (
        "canvas_assignment: expected one of the roster's assignment columns "
        "('Homework 1 (1)', 'Homework 2 (2)') or its Canvas id, found '99'")


def test_canvas_missing_blank_leaves_the_grade_empty(report, canvas_roster, tmp_path):
    out = tmp_path / "canvas.csv"
    EXPORTERS["canvas"](report, out, roster=canvas_roster,
                        options=ExportOptions(missing="blank", points_possible=False))
    rows = read_csv(out)
    grade = {row[1]: row[5] for row in rows[1:]}
    assert grade["70007"] == "" and grade["70004"] == "" and grade["70005"] == "0"
    assert rows[1][0] != "    Points Possible"


def test_each_import_file_keeps_its_own_unmatched_rows(report, canvas_roster, moodle_roster,
                                                       tmp_path):
    EXPORTERS["canvas"](report, tmp_path / "canvas.csv", roster=canvas_roster)
    EXPORTERS["moodle"](report, tmp_path / "moodle.csv", roster=moodle_roster)
    canvas = read_csv(tmp_path / "canvas.unmatched.csv")
    moodle = read_csv(tmp_path / "moodle.unmatched.csv")
    assert canvas[0] == moodle[0] == ["id", "name", "status", "score", "reason"]
    assert len(canvas) > 1 and len(moodle) > 1
    assert not (tmp_path / "unmatched.csv").exists()


def test_an_export_holding_nothing_back_removes_its_old_unmatched_rows(report, canvas_roster,
                                                                       tmp_path):
    out = tmp_path / "canvas.csv"
    EXPORTERS["canvas"](report, out, roster=canvas_roster)
    assert (tmp_path / "canvas.unmatched.csv").exists()
    matched = replace(report, students=tuple(s for s in report.students
                                             if s.id in {r.id for r in canvas_roster.students}))
    assert not [w for w in EXPORTERS["canvas"](matched, out, roster=canvas_roster)
                if "kept out" in w]
    assert not (tmp_path / "canvas.unmatched.csv").exists()


def test_an_unmatched_file_that_cannot_be_removed_is_an_error(report, canvas_roster, tmp_path):
    (tmp_path / "canvas.unmatched.csv").mkdir()
    matched = replace(report, students=())
    with pytest.raises(ExportError, match=r"canvas.unmatched.csv: expected to remove the "
                                          "unmatched rows of an earlier export"):
        EXPORTERS["canvas"](matched, tmp_path / "canvas.csv", roster=canvas_roster)


def test_roster_matching_reports_who_is_not_in_the_roster(report, canvas_roster):
    matched = match_roster(report, canvas_roster)
    assert [r.id for r in matched.not_in_roster] == ["x-ghost"]
    assert [s.id for s in matched.no_submission] == ["70007"]
    assert {p.matched_by for p in matched.pairs if p.roster and p.result} == \
        {MatchKind.SIS_USER_ID, MatchKind.NAME}


def test_an_ambiguous_name_matches_nobody(report, canvas_roster):
    twin = replace(report.students[5], id="s9999")
    doubled = replace(report, students=report.students + (twin,))
    matched = match_roster(doubled, canvas_roster)
    assert {r.id for r in matched.not_in_roster} == {"x-ghost", "s1006", "s9999"}


# --- Moodle ------------------------------------------------------------------------------------

def test_moodle_has_key_columns_grade_and_feedback(report, moodle_roster, tmp_path):
    out = tmp_path / "moodle.csv"
    warnings = EXPORTERS["moodle"](report, out, roster=moodle_roster)
    rows = read_csv(out)
    # Moodle's own "Last downloaded" column is kept: Moodle then refuses grades changed since
    assert rows[0] == ["Email address", "ID number", "First name", "Last name",
                       "Assignment: Homework 3 (Real)", "Assignment: Homework 3 (Feedback)",
                       "Last downloaded from this course"]
    assert {row[6] for row in rows[1:]} == {"1700000000"}
    by_email = {row[0]: row for row in rows[1:]}
    assert set(by_email) == {s.email for s in moodle_roster.students}
    emilie = by_email["emilie@uni.example"]
    assert emilie[1:5] == ["s1002", "Émilie", "du Châtelet", "5.5"]
    assert "p1/a_B: partial 1/4 (dropped the Coriolis term)" in emilie[5].splitlines()
    assert by_email["only@uni.example"][4] == "0"
    assert by_email["only@uni.example"][5] == "No submission received."
    assert by_email["uma@uni.example"][4] == "0"
    assert_no_formula(rows)
    # Rows Moodle cannot match would abort the whole import: they are held back.
    assert read_csv(tmp_path / "moodle.unmatched.csv") == [
        UNMATCHED_HEADER,
        ["s1005", "Unreadable Uma", "unreadable", "0", "not in the roster"],
        ["s1006", "Seán O'Brien", "graded", "3", "not in the roster"],
        ["x-ghost", "Ghost Student", "graded", "7", "not in the roster"]]
    assert warnings == (
        "uma@uni.example (Uma Unreadable) has no submission; written with 0",
        "s1007 (Roster Only) has no submission; written with 0",
        "Moodle cuts a grade above the grade item's maximum grade to that maximum without a "
        "word: check that 'Assignment: Homework 3 (Real)' is out of 10 points in Moodle, or "
        "export with --scale-to <its maximum grade>",
        "the grades export's 'Last downloaded from this course' of s1001 is '1700000000': "
        "Moodle refuses the whole import unless that is a time within the last year; export "
        "the grades from Moodle again and give that file as --roster",
        f"3 rows kept out of {out} because Moodle could not import them: see "
        f"{tmp_path / 'moodle.unmatched.csv'} for who and why; enter those grades in Moodle by hand, "
        "or export again with --roster set to the grades exported from Moodle",
        f"{out}: 6 new, 0 changed, 0 kept as Moodle has them, 0 unchanged; each listed in "
        f"{tmp_path / 'moodle.changes.csv'}")


def test_moodle_never_writes_a_row_with_a_blank_user_key(report, moodle_roster, tmp_path):
    out = tmp_path / "moodle.csv"
    EXPORTERS["moodle"](report, out, roster=moodle_roster,
                        options=ExportOptions(moodle_key="idnumber"))
    assert all(row[0] for row in read_csv(out))
    held = read_csv(tmp_path / "moodle.unmatched.csv")
    assert held[1] == ["uma@uni.example", "Uma Unreadable", "missing", "0",
                       "no ID number to match the Moodle user by (one unknown user aborts the "
                       "whole Moodle import)"]


def test_moodle_without_a_roster_warns_that_the_keys_are_unchecked(report, tmp_path):
    out = tmp_path / "moodle.csv"
    warnings = EXPORTERS["moodle"](report, out, options=ExportOptions(moodle_key="idnumber"))
    rows = read_csv(out)
    assert rows[0][:2] == ["ID number", "Email address"]
    assert rows[0][4:] == ["Homework 3 (Real)", "Homework 3 (Feedback)"]
    assert [row[0] for row in rows[1:]] == []  # the results carry no ID number
    assert len(read_csv(tmp_path / "moodle.unmatched.csv")) == 1 + len(report.students)
    EXPORTERS["moodle"](report, out)
    warnings = EXPORTERS["moodle"](report, out)
    assert warnings[0] == (
        f"{out} was written without the grades exported from Moodle as --roster, so its "
        "Email address values are unchecked: Moodle aborts the whole import if one of them is "
        "not a Moodle user")
    assert [row[0] for row in read_csv(out)[1:]] == [
        "ada@uni.example", "emilie@uni.example", "mallory@uni.example"]


def test_moodle_feedback_is_html_escaped_so_student_text_survives(report, moodle_roster,
                                                                   tmp_path):
    ada = report.students[0]
    hostile = replace(ada, messages=("<script>alert(1)</script> & <b>x</b>",))
    EXPORTERS["moodle"](replace(report, students=(hostile,)), tmp_path / "m.csv",
                        roster=moodle_roster)
    feedback = read_csv(tmp_path / "m.csv")[1][5]
    assert feedback.splitlines()[0] == \
        "&lt;script&gt;alert(1)&lt;/script&gt; &amp; &lt;b&gt;x&lt;/b&gt;"
    assert "<" not in feedback


@pytest.mark.parametrize("status, missing, why", [
    ("not_evaluated", "zero",
     "not evaluated: mechgrade failed on this student (see the internal errors)"),
    ("missing", "blank", "no submission and --missing blank")])
def test_moodle_never_writes_feedback_without_a_grade(report, moodle_roster, tmp_path, status,
                                                      missing, why):
    ada = replace(report.students[0], status=status)
    EXPORTERS["moodle"](replace(report, students=(ada,)), tmp_path / "m.csv",
                        roster=moodle_roster, options=ExportOptions(missing=missing))
    assert "ada@uni.example" not in {row[0] for row in read_csv(tmp_path / "m.csv")}
    assert ["s1001", "Ada Lovelace", status, "", f"no grade ({why}); Moodle clears the grade "
            "of a row imported with feedback only"] in read_csv(tmp_path / "m.unmatched.csv")


def test_moodle_names_from_a_canvas_roster_split_at_the_comma(report, canvas_roster, tmp_path):
    EXPORTERS["moodle"](report, tmp_path / "m.csv", roster=canvas_roster)
    names = {row[1]: row[2:4] for row in read_csv(tmp_path / "m.csv")[1:]}
    assert names["s1002"] == ["Émilie", "du Châtelet"]
    assert names["s1007"] == ["Only", "Roster"]


def test_moodle_does_not_guess_where_a_name_without_a_comma_splits():
    assert moodle_names(RosterStudent("1", "Mary Ann Smith"), None) == ("Mary Ann Smith", "")
    assert moodle_names(RosterStudent("1", "x", columns=(("Student", "Smith (TA), John"),)),
                        None) == ("John", "Smith (TA)")


# --- Gradescope --------------------------------------------------------------------------------

VISIBILITY = {"hidden", "after_due_date", "after_published", "visible"}


def check_gradescope(doc: dict, n_objectives: int) -> None:
    check_results(doc)  # Gradescope's specification (tests/lms/gradescope_results.py)
    assert isinstance(doc["score"], float)
    assert doc["output_format"] == doc["test_output_format"] == doc["test_name_format"] == "text"
    receipt, *tests = doc["tests"]
    assert receipt["name"] == "Submission received" and receipt["visibility"] == "visible"
    assert "score" not in receipt  # a receipt, worth nothing
    assert len(tests) == n_objectives
    for test in tests:
        assert set(test) == {"name", "number", "score", "max_score", "status", "output",
                             "visibility"}
        assert isinstance(test["score"], float) and isinstance(test["max_score"], float)
        assert 0 <= test["score"] <= test["max_score"]


def test_gradescope_single_student_results_json(report, tmp_path):
    one = replace(report, students=(report.students[1],))
    out = tmp_path / "results.json"
    EXPORTERS["gradescope"](one, out, options=ExportOptions(gradescope_visibility="after_due_date"))
    doc = json.loads(out.read_text(encoding="utf-8"))
    check_gradescope(doc, 3)
    assert doc["score"] == 5.5 and doc["visibility"] == "after_due_date"
    assert sum(t.get("score", 0) for t in doc["tests"]) == doc["score"]
    a_b = doc["tests"][2]
    assert a_b["name"] == "p1/a_B: Acceleration of B (rotating frame)"
    assert a_b["status"] == "failed" and a_b["score"] == 1.0 and a_b["max_score"] == 4.0
    assert "dropped the Coriolis term" in a_b["output"]
    assert doc["tests"][1]["status"] == "passed"
    assert {t["visibility"] for t in doc["tests"][1:]} == {"after_due_date"}


def test_gradescope_missing_student_gets_every_objective_failed(report, tmp_path):
    one = replace(report, students=(report.students[3],))
    out = tmp_path / "results.json"
    EXPORTERS["gradescope"](one, out)
    doc = json.loads(out.read_text(encoding="utf-8"))
    check_gradescope(doc, 3)
    assert doc["score"] == 0.0 and "No submission was found." in doc["output"]
    assert {t["status"] for t in doc["tests"]} == {"failed"}
    assert "No submission was found." in doc["tests"][0]["output"]


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
    report = canvas_report(report) if fmt == "canvas" else report
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


def test_options_written_as_text_are_read_into_their_types_once():
    options = ExportOptions(missing="blank", gradescope_visibility="hidden",
                            moodle_key=MoodleKey.IDNUMBER)
    assert (options.missing, options.gradescope_visibility, options.moodle_key) == (
        MissingGrade.BLANK, Visibility.HIDDEN, MoodleKey.IDNUMBER)


@pytest.mark.parametrize("fmt", list(EXPORTERS))
def test_every_format_in_the_registry_writes_its_file(report, tmp_path, fmt):
    out = tmp_path / f"{fmt}.out"
    warnings = export(report, fmt, out)
    assert isinstance(warnings, tuple)
    assert out.exists() or (fmt == "gradescope" and any(tmp_path.iterdir()))


@pytest.mark.parametrize("title", ["Final Score", "HW current points (1)", "Override Grade 2"])
def test_canvas_refuses_a_column_title_canvas_ignores(report, tmp_path, title):
    out = tmp_path / "canvas.csv"
    with pytest.raises(ExportError, match="Canvas ignores a column whose title holds"):
        EXPORTERS["canvas"](report, out, options=ExportOptions(canvas_assignment=title))
    assert not out.exists()


def test_canvas_accepts_a_title_that_only_mentions_a_grade(report, tmp_path):
    out = tmp_path / "canvas.csv"
    EXPORTERS["canvas"](report, out, options=ExportOptions(canvas_assignment="Grade check (7)"))
    assert "Grade check (7)" in out.read_text(encoding="utf-8").splitlines()[0]
