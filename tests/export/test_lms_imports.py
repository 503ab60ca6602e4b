"""Every LMS export read back by a re-implementation of that LMS's importer (tests/lms/):
what the import would change, abort or show is what mechgrade meant, and nothing already in
the LMS is lost without the user asking."""

from __future__ import annotations

import html
import json

import pytest
from canvas_gradebook import (CanvasAssignment, CanvasStudent, Course, InvalidHeaderRow,
                              export_gradebook, import_gradebook)
from gradescope_results import check_results, student_view
from moodle_grades import (TIMEEXPORTED, GradeItem, ImportAborted, MoodleUser, Site, fputcsv,
                           import_grades, load_csv_content)

from mechgrade.errors import ExportError
from mechgrade.export import EXPORTERS, ExportOptions
from mechgrade.export.changes import changes_path
from mechgrade.export.gradescope import gradescope_results
from mechgrade.export.moodle import feedback_text
from mechgrade.grade.results import (AnswerResult, AssignmentInfo, GradeReport, ObjectiveInfo,
                                     StudentResult)
from mechgrade.roster import read_roster

HW = ObjectiveInfo("pend", "speed", "Speed of the tip.", 10.0, "A pendulum")
ACC = ObjectiveInfo("pend", "acc", "Acceleration of the tip.", 9.0, "A pendulum")


def result(sid: str, score: float | None, feedback: str = "", answers=None) -> StudentResult:
    if score is None:
        return StudentResult(sid, "", "missing", 0.0, 19.0)
    answers = answers or (
        AnswerResult("pend", "speed", "8 ft/s", "correct" if score >= 10 else "incorrect",
                     min(score, 10.0), 10.0, feedback=feedback),
        AnswerResult("pend", "acc", "3", "correct" if score > 10 else "incorrect",
                     max(score - 10, 0.0), 9.0))
    return StudentResult(sid, "", "graded", score, 19.0, answers)


def report_of(*students: StudentResult, title: str = "Homework 1") -> GradeReport:
    return GradeReport(AssignmentInfo("hw1", title), (HW, ACC), students)


# ---------------------------------------------------------------------------------- Canvas


def course(**grades) -> Course:
    students = [CanvasStudent(101, "Ada Lovelace", "Lovelace, Ada", "s1", "ada"),
                CanvasStudent(102, "Bob Roe", "Roe, Bob", "s2", "bob"),
                CanvasStudent(103, "Carla Diaz", "Diaz, Carla", "s3", "carla"),
                CanvasStudent(104, "Dan Wu", "Wu, Dan", "s4", "dan")]
    assignments = [CanvasAssignment(555, "Homework 1", 19.0),
                   CanvasAssignment(556, "Homework 2", 10.0)]
    by_sis = {s.sis_user_id: s.id for s in students}
    return Course(students, assignments,
                  {(by_sis[k], 555): v for k, v in grades.items()})


def canvas_round_trip(tmp_path, canvas: Course, report: GradeReport,
                      options: ExportOptions = ExportOptions(), **export_options):
    roster_file = tmp_path / "gradebook.csv"
    roster_file.write_text(export_gradebook(canvas, **export_options), encoding="utf-8")
    out = tmp_path / "canvas.csv"
    messages = EXPORTERS["canvas"](report, out, roster=read_roster(roster_file),
                                   options=options)
    written = out.read_text(encoding="utf-8-sig") if out.exists() else ""
    return messages, written


def test_a_canvas_round_trip_imports_exactly_mechgrades_new_grades(tmp_path):
    canvas = course()
    report = report_of(result("s1", 19), result("s2", 7.5), result("s3", None))
    _, written = canvas_round_trip(tmp_path, canvas, report)
    outcome = import_gradebook(written, canvas)
    assert outcome.unknown_students == [] and outcome.new_assignments == []
    assert outcome.points_changed == {} and outcome.dropped_read_only == []
    # Carla handed in nothing, Dan is not in the results: both 0 (--missing zero)
    assert outcome.changes == {(101, 555): ("", "19"), (102, 555): ("", "7.5"),
                               (103, 555): ("", "0"), (104, 555): ("", "0")}


def test_canvas_keeps_an_excused_student_excused_whatever_missing_says(tmp_path):
    canvas = course(s1="EX", s3="EX")
    report = report_of(result("s1", 12), result("s3", None))
    messages, written = canvas_round_trip(tmp_path, canvas, report)
    outcome = import_gradebook(written, canvas)
    # --missing zero wrote 0 over EX before: Canvas would have replaced the excuse
    assert (101, 555) not in outcome.changes and (103, 555) not in outcome.changes
    assert outcome.changes == {(102, 555): ("", "0"), (104, 555): ("", "0")}
    listed = changes_path(tmp_path / "canvas.csv").read_text(encoding="utf-8").splitlines()
    assert listed[1].startswith('101,Ada Lovelace,EX,EX,kept,"excused in Canvas (EX)')
    assert any(m.endswith("2 new, 0 changed, 2 kept as Canvas has them, 0 unchanged; each "
                          f"listed in {changes_path(tmp_path / 'canvas.csv')}")
               for m in messages)


def test_canvas_keeps_a_hand_entered_grade_unless_asked_to_replace_it(tmp_path):
    canvas = course(s2="6.5")
    report = report_of(result("s2", 7.5))
    _, written = canvas_round_trip(tmp_path, canvas, report)
    assert (102, 555) not in import_gradebook(written, canvas).changes
    _, replaced = canvas_round_trip(tmp_path, canvas, report,
                                    ExportOptions(replace_existing=True))
    assert import_gradebook(replaced, canvas).changes[(102, 555)] == ("6.5", "7.5")


def test_canvas_blank_for_no_submission_never_clears_a_grade(tmp_path):
    canvas = course(s3="8")
    report = report_of(result("s3", None))
    _, written = canvas_round_trip(tmp_path, canvas, report, ExportOptions(missing="blank"))
    assert (103, 555) not in import_gradebook(written, canvas).changes
    # what a blank cell would have done (the importer's rule, no_change_to_value?)
    blanked = written.replace("Diaz, Carla\",103,s3,carla,ENGR 201,8",
                              "Diaz, Carla\",103,s3,carla,ENGR 201,")
    assert import_gradebook(blanked, canvas).changes[(103, 555)] == ("8", "")


def test_canvas_same_grade_at_two_decimals_is_no_change(tmp_path):
    canvas = course(s1="9.33")
    report = report_of(result("s1", 9.3333))
    _, written = canvas_round_trip(tmp_path, canvas, report)
    assert (101, 555) not in import_gradebook(written, canvas).changes


def test_canvas_points_possible_is_never_replaced_silently(tmp_path):
    canvas = course()
    canvas.assignments[0].points_possible = 100.0
    report = report_of(result("s1", 19))
    messages, written = canvas_round_trip(tmp_path, canvas, report)
    assert import_gradebook(written, canvas).points_changed == {}
    assert ("Canvas's 'Homework 1 (555)' is worth 100.00 points and mechgrade's grades are "
            "out of 19: they are written as they are and Canvas's points are kept; export "
            "with --scale-to 100.00 to scale them, or change the assignment's points in "
            "Canvas") in messages
    _, scaled = canvas_round_trip(tmp_path, canvas, report, ExportOptions(scale_to=100))
    outcome = import_gradebook(scaled, canvas)
    assert outcome.points_changed == {} and outcome.changes[(101, 555)] == ("", "100")


def test_canvas_what_mechgrade_would_write_without_the_roster_changes_points(tmp_path):
    canvas = course()
    canvas.assignments[0].points_possible = 100.0
    out = tmp_path / "canvas.csv"
    messages = EXPORTERS["canvas"](report_of(result("s1", 19)), out,
                                   options=ExportOptions(canvas_assignment="555"))
    # without the gradebook, the row is held back (no Canvas id) and the warning says so
    assert any("could not import" in m for m in messages)


def test_canvas_refuses_a_column_marked_read_only(tmp_path):
    canvas = course()
    with pytest.raises(ExportError, match=r"marked '\(read only\)' in the roster's Points "
                                          r"Possible row: Canvas drops that column"):
        canvas_round_trip(tmp_path, canvas, report_of(result("s1", 19)),
                          read_only_points=frozenset({555}))
    # the importer's rule the refusal follows
    text = export_gradebook(canvas, read_only_points=frozenset({555}))
    assert import_gradebook(text, canvas).dropped_read_only == ["Homework 1 (555)"]


def test_canvas_keeps_not_assigned_cells(tmp_path):
    canvas = course()
    canvas.not_assigned.add((104, 555))
    _, written = canvas_round_trip(tmp_path, canvas, report_of(result("s4", 15)))
    assert ",N/A" in written and import_gradebook(written, canvas).changes.get((104, 555)) is None
    assert "the assignment is not assigned to this student in Canvas (N/A)" in \
        changes_path(tmp_path / "canvas.csv").read_text(encoding="utf-8")


def test_canvas_last_name_first_name_layout_is_written_back_and_imports(tmp_path):
    canvas = course()
    report = report_of(result("s1", 19), result("s2", 4))
    _, written = canvas_round_trip(tmp_path, canvas, report, last_first=True)
    assert written.startswith("LastName,FirstName,ID,SIS User ID,SIS Login ID,Section,")
    outcome = import_gradebook(written, canvas)
    assert outcome.unknown_students == []
    assert outcome.changes[(101, 555)] == ("", "19") and outcome.changes[(102, 555)] == ("", "4")


def test_canvas_refuses_a_byte_order_mark_with_the_last_name_layout(tmp_path):
    canvas = course()
    with pytest.raises(ExportError, match="expected no byte order mark with the "
                                          "'LastName,FirstName' layout"):
        canvas_round_trip(tmp_path, canvas, report_of(result("s1", 19)),
                          ExportOptions(excel_bom=True), last_first=True)
    # why: Canvas compares the first cell with 'LastName' exactly
    with pytest.raises(InvalidHeaderRow):
        import_gradebook("\ufeff" + export_gradebook(canvas, last_first=True), canvas)


def test_canvas_dry_run_writes_nothing_and_lists_every_change(tmp_path):
    canvas = course(s1="EX", s2="6")
    messages, written = canvas_round_trip(
        tmp_path, canvas, report_of(result("s1", 19), result("s2", 7), result("s3", 5)),
        ExportOptions(dry_run=True, replace_existing=True))
    assert written == "" and not changes_path(tmp_path / "canvas.csv").exists()
    assert [str(m) for m in messages[-5:]] == [
        f"dry run, nothing written: {tmp_path / 'canvas.csv'} would import 2 new, 1 changed, "
        "1 kept as Canvas has them, 0 unchanged",
        "101 (Ada Lovelace): kept EX: excused in Canvas (EX); to grade this student, remove "
        "the excuse in Canvas and export again",
        "102 (Bob Roe): 6 -> 7",
        "103 (Carla Diaz): new grade 5",
        "104 (Dan Wu): new grade 0"]
    assert "104 (Dan Wu) has no submission; written with 0" in messages


# ---------------------------------------------------------------------------------- Moodle


MOODLE_HEADER = ("First name,Last name,ID number,Institution,Department,Email address,"
                 "Assignment: Homework 1 (Real),Course total (Real),")


def moodle_site(**kwargs) -> Site:
    users = [MoodleUser(7, "ada@uni.example", "s1"), MoodleUser(8, "bob@uni.example", "s2")]
    return Site(users, GradeItem(55, "Homework 1", **kwargs))


def moodle_roster(tmp_path, grades=("-", "-"), downloaded: int | None = None):
    extra = f",{TIMEEXPORTED}" if downloaded is not None else ""
    stamp = f",{downloaded}" if downloaded is not None else ""
    path = tmp_path / "moodle_grades.csv"
    path.write_text(
        MOODLE_HEADER.rstrip(",") + extra + "\n"
        f"Ada,Lovelace,s1,Uni,ME,ada@uni.example,{grades[0]},0.00{stamp}\n"
        f"Bob,Roe,s2,Uni,ME,bob@uni.example,{grades[1]},0.00{stamp}\n", encoding="utf-8")
    return read_roster(path)


def moodle_export(tmp_path, report, roster=None, options=ExportOptions()):
    out = tmp_path / "moodle.csv"
    messages = EXPORTERS["moodle"](report, out, roster=roster, options=options)
    return messages, (out.read_text(encoding="utf-8") if out.exists() else "")


def moodle_import(text: str, site: Site, **kwargs):
    return import_grades(text, site, user_column="Email address", user_field="useremail",
                         grade_column="Assignment: Homework 1 (Real)",
                         feedback_column="Assignment: Homework 1 (Feedback)", **kwargs)


HOSTILE_FEEDBACK = 'Read "3 \\" as typed, then C:\\temp\\, ends in \\'


def test_moodle_reads_feedback_with_backslashes_and_quotes_back_identically(tmp_path):
    report = report_of(result("s1", 12, feedback=HOSTILE_FEEDBACK),
                       result("s2", 4, feedback="x\\"))
    _, written = moodle_export(tmp_path, report, moodle_roster(tmp_path))
    committed = moodle_import(written, moodle_site(grademax=19))
    assert committed.grades == {7: 12.0, 8: 4.0}
    # Moodle stores the HTML; shown, it is mechgrade's feedback, character for character
    for userid, student in ((7, report.students[0]), (8, report.students[1])):
        assert html.unescape(committed.feedback[userid]) == feedback_text(report, student)


def test_moodle_would_abort_on_the_same_feedback_written_as_plain_csv(tmp_path):
    # Python's csv module (as before) writes \" inside a quoted field, which PHP's fgetcsv
    # reads as an escaped quote: the row splits into another number of fields
    import csv
    import io

    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["Email address", "Assignment: Homework 1 (Real)",
                     "Assignment: Homework 1 (Feedback)"])
    writer.writerow(["ada@uni.example", "12", 'says "x\\", then, more'])
    with pytest.raises(ImportAborted, match="csvweirdcolumns"):
        load_csv_content(buffer.getvalue())


def test_moodle_feedback_names_problems_by_title(tmp_path):
    report = report_of(result("s1", 12))
    _, written = moodle_export(tmp_path, report, moodle_roster(tmp_path))
    feedback = moodle_import(written, moodle_site(grademax=19)).feedback[7]
    assert "A pendulum, Speed of the tip: correct 10/10" in html.unescape(feedback)
    assert "pend/speed" not in feedback


def test_moodle_grades_above_100_are_warned_of_and_scaled_on_request(tmp_path):
    big = GradeReport(AssignmentInfo("hw1", "Homework 1"),
                      (ObjectiveInfo("p", "a", "", 150.0, "P"),),
                      (StudentResult("s1", "", "graded", 120.0, 150.0),))
    messages, written = moodle_export(tmp_path, big, moodle_roster(tmp_path))
    assert any(m.startswith("grades are out of 150 points: Moodle refuses the whole import on "
                            "a grade above 100") for m in messages)
    with pytest.raises(ImportAborted, match="gradevaluetoobig"):
        moodle_import(written, moodle_site(grademax=150))
    _, scaled = moodle_export(tmp_path, big, moodle_roster(tmp_path),
                              ExportOptions(scale_to=100))
    assert moodle_import(scaled, moodle_site(grademax=100)).grades[7] == 80.0


def test_moodle_clamps_above_the_items_maximum_so_the_export_warns(tmp_path):
    report = report_of(result("s1", 19))
    messages, written = moodle_export(tmp_path, report, moodle_roster(tmp_path))
    committed = moodle_import(written, moodle_site(grademax=10))
    assert committed.clamped == {7: (19.0, 10.0)}  # what Moodle does without a word
    assert ("Moodle cuts a grade above the grade item's maximum grade to that maximum without "
            "a word: check that 'Assignment: Homework 1 (Real)' is out of 19 points in Moodle, "
            "or export with --scale-to <its maximum grade>") in messages
    _, scaled = moodle_export(tmp_path, report, moodle_roster(tmp_path),
                              ExportOptions(scale_to=10))
    committed = moodle_import(scaled, moodle_site(grademax=10))
    assert committed.clamped == {} and committed.grades[7] == 10.0


def test_moodle_keeps_the_last_downloaded_column_so_newer_grades_are_protected(tmp_path):
    site = moodle_site(grademax=19)
    exported = site.now - 3600
    report = report_of(result("s1", 12), result("s2", 7))
    _, written = moodle_export(tmp_path, report, moodle_roster(tmp_path, downloaded=exported))
    assert written.splitlines()[0].endswith(f",{TIMEEXPORTED}")
    assert moodle_import(written, site).grades == {7: 12.0, 8: 7.0}
    site.item.dategraded[8] = site.now - 60  # Bob regraded by hand after the export
    with pytest.raises(ImportAborted, match="gradealreadyupdated"):
        moodle_import(written, site)


def test_moodle_keeps_grades_already_there_unless_asked(tmp_path):
    site = moodle_site(grademax=19)
    site.item.grades[8] = 9.0
    report = report_of(result("s1", 12), result("s2", 7))
    roster = moodle_roster(tmp_path, grades=("-", "9.00"))
    _, written = moodle_export(tmp_path, report, roster)
    assert moodle_import(written, site).grades == {7: 12.0, 8: 9.0}
    _, replaced = moodle_export(tmp_path, report, roster, ExportOptions(replace_existing=True))
    assert moodle_import(replaced, site).grades == {7: 12.0, 8: 7.0}


def test_moodle_aborts_on_an_unknown_user_so_none_is_written(tmp_path):
    report = report_of(result("s1", 12), result("zz", 3))
    _, written = moodle_export(tmp_path, report, moodle_roster(tmp_path))
    assert moodle_import(written, moodle_site(grademax=19)).grades[7] == 12.0
    stray = written + fputcsv(["ghost@uni.example", "", "G", "", "3", "x"]).replace("\n", "\r\n")
    with pytest.raises(ImportAborted, match="usermappingerror"):
        moodle_import(stray, moodle_site(grademax=19))


# ------------------------------------------------------------------------------ Gradescope


def gradescope_doc(student: StudentResult, visibility: str = "visible") -> dict:
    expected = ("8 ft/s", "37.7 ft/s^2")
    answers = tuple(AnswerResult(o.problem, o.objective, a.answer, a.verdict, a.points,
                                 a.max_points, expected=e)
                    for o, a, e in zip((HW, ACC), student.answers, expected))
    report = GradeReport(AssignmentInfo("hw1", "Homework 1"), (HW, ACC),
                         (StudentResult(student.id, "", student.status, student.score, 19.0,
                                        answers),))
    doc = gradescope_results(report, report.students[0],
                             ExportOptions(gradescope_visibility=visibility))
    return json.loads(json.dumps(doc))


def zeros() -> StudentResult:
    return result("s1", 0.0, answers=(
        AnswerResult("pend", "speed", "0", "incorrect", 0.0, 10.0),
        AnswerResult("pend", "acc", "0", "incorrect", 0.0, 9.0)))


def test_gradescope_an_upload_of_zeros_sees_no_expected_answer_before_the_due_date():
    view = student_view(gradescope_doc(zeros()))
    assert "Expected" not in view.text() and "37.7" not in view.text()
    assert "Answers read (2 of 2):\n  pend/speed = 0\n  pend/acc = 0\nScore: 0 / 19 points" \
        in view.text()
    after = student_view(gradescope_doc(zeros()), due_passed=True)
    assert "Expected: 37.7 ft/s^2" in after.text() and after.total_shown


def test_gradescope_after_due_date_still_shows_what_was_read_but_not_the_score():
    doc = gradescope_doc(result("s1", 12), "after_due_date")
    view = student_view(doc)
    assert [t["name"] for t in view.tests] == ["Submission received"]
    assert view.tests[0]["output"] == ("Answers read (2 of 2):\n  pend/speed = 8 ft/s\n"
                                       "  pend/acc = 3\nThe score and the verdicts are shown "
                                       "after the due date.")
    assert not view.total_shown and view.score is None
    assert student_view(doc, due_passed=True).score == 12.0


@pytest.mark.parametrize("visibility", ["visible", "hidden", "after_due_date",
                                        "after_published"])
def test_gradescope_results_follow_the_specification(visibility):
    check_results(gradescope_doc(result("s1", 12), visibility))
    check_results(gradescope_doc(result("s1", None), visibility))


def test_a_roster_without_the_assignments_column_is_said_to_be_uncompared(tmp_path):
    report = report_of(result("s1", 12), title="Homework 9")
    messages, _ = moodle_export(tmp_path, report, moodle_roster(tmp_path))
    out = tmp_path / "moodle.csv"
    assert (f"{out}: the roster (the gradebook exported from Moodle) has no column "
            "'Homework 9 (Real)', so the grades already in Moodle were not compared: Moodle "
            "adds the column as a new grade item, or replaces the grades of an item of that "
            "name") in messages
