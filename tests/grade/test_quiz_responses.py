"""A quiz's responses, as Canvas's Student Analysis and Moodle's Responses report write them,
grade as the folder of the same answers; what cannot be matched is listed, never guessed."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import pytest

from mechgrade.errors import SubmissionError
from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.lms_submissions import read_any_submissions
from mechgrade.grade.quiz_responses import key_marker, read_quiz_responses
from mechgrade.grade.run import grade_plan, plan_assignment
from mechgrade.roster import read_roster

ROOT = Path(__file__).resolve().parents[2]
HW1 = ROOT / "examples" / "hw1"
ANSWERS = {  # Canvas user id -> typed answers (Ada's and Bob's example answers)
    "10001": {"bowling_3_15_4_pendulum.acc_mag": "98.5 ft/s^2",
              "bowling_3_15_4_pendulum.acc_mag_symbolic": "L sqrt(thetad^4 + thetadd^2)",
              "bowling_3_15_8_connected_blocks.xdot": "-7.67 m/s"},
    "10002": {"bowling_3_15_4_pendulum.acc_mag": "98.5 ft/s^2",
              "bowling_3_15_4_pendulum.acc_mag_symbolic": "L*sqrt(thetad**4 + thetadd**2)",
              "bowling_3_15_8_connected_blocks.xdot": "7.67 m/s"},
}
KEYS = list(ANSWERS["10001"])


@pytest.fixture(scope="module")
def plan():
    return plan_assignment(load_assignment(HW1 / "assignment.yaml"))


def csv_text(rows) -> str:
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerows(rows)
    return out.getvalue()


def canvas_student_analysis(tmp_path) -> Path:
    """student_analysis.rb to_csv: identity columns, '<id>: <text>' and points per question,
    then n correct, n incorrect, score; every attempt (an earlier one first)."""
    header = ["name", "id", "sis_id", "section", "section_id", "section_sis_id", "submitted",
              "attempt"]
    for n, key in enumerate(KEYS):
        header += [f"{3100 + n}: Find it. {key_marker(key)}", "2.0"]
    header += ["n correct", "n incorrect", "score"]
    rows = [header]
    for user, answers in ANSWERS.items():
        stale = ["x", user, "", "ENGR", "1", "", "2026-09-18", "1"]
        for _ in KEYS:
            stale += ["0", "0"]
        rows.append(stale + ["0", "3", "0"])
        row = ["x", user, "", "ENGR", "1", "", "2026-09-18", "2"]
        for key in KEYS:
            row += [answers[key], ""]
        rows.append(row + ["", "", ""])
    path = tmp_path / "quiz_student_analysis.csv"
    path.write_text(csv_text(rows), encoding="utf-8")
    return path


def moodle_responses(tmp_path, with_questions: bool = True) -> Path:
    header = ["Last name", "First name", "ID number", "Email address", "State", "Started on",
              "Completed", "Time taken", "Grade/6.00"]
    for n in range(1, len(KEYS) + 1):
        header += ([f"Question {n}"] if with_questions else []) + [f"Response {n}"]
    rows = [header]
    for user, answers in ANSWERS.items():
        row = ["L", "F", user, f"{user}@uni.example", "Finished", "", "", "", "-"]
        for key in KEYS:
            row += ([f"Find it. {key_marker(key)}"] if with_questions else []) + [answers[key]]
        rows.append(row)
    rows.append(["L", "F", "10003", "", "In progress", "", "", "", "-"] +
                ["", ""] * len(KEYS) if with_questions else [""] * len(KEYS))
    path = tmp_path / "responses.csv"
    path.write_text(csv_text(rows), encoding="utf-8")
    return path


def folder(tmp_path) -> Path:
    root = tmp_path / "folder"
    for user, answers in ANSWERS.items():
        (root / user).mkdir(parents=True)
        (root / user / "answers.txt").write_text(
            "".join(f"{k} = {v}\n" for k, v in answers.items()), encoding="utf-8")
    return root


def outcome(report) -> dict:
    return {s.id: (s.status, s.score, tuple((a.objective, a.answer, a.verdict, a.points)
                                            for a in s.answers)) for s in report.students}


@pytest.mark.parametrize("maker", [canvas_student_analysis, moodle_responses])
def test_quiz_responses_grade_as_the_folder_of_the_same_answers(tmp_path, plan, maker):
    roster = read_roster(HW1 / "roster.csv")
    expected = outcome(grade_plan(plan, read_any_submissions(folder(tmp_path), keys=plan.keys),
                                  roster))
    read = read_any_submissions(maker(tmp_path), keys=plan.keys)
    assert outcome(grade_plan(plan, read, roster)) == expected
    assert expected["10001"][2][3][2] == "correct"  # the symbolic answer, graded by mechgrade


def test_the_latest_canvas_attempt_is_read(tmp_path, plan):
    read = read_quiz_responses(canvas_student_analysis(tmp_path), keys=plan.keys)
    assert dict(read.students[0].answers)["bowling_3_15_8_connected_blocks.xdot"] == \
        "-7.67 m/s"


def test_a_moodle_report_without_the_question_text_is_refused(tmp_path, plan):
    with pytest.raises(SubmissionError, match=r"responses.csv:1: expected the questions' text "
                                              r"in the report"):
        read_quiz_responses(moodle_responses(tmp_path, with_questions=False), keys=plan.keys)


def test_an_unfinished_moodle_attempt_is_listed_not_graded(tmp_path, plan):
    read = read_quiz_responses(moodle_responses(tmp_path), keys=plan.keys)
    assert [s.student for s in read.students] == ["10001", "10002"]
    assert [(e.path, e.reason) for e in read.skipped] == [
        ("responses.csv: line 4", "an attempt not finished (In progress)")]


def test_questions_without_a_key_and_drawn_numbers_are_listed_with_their_reason(tmp_path):
    path = tmp_path / "q.csv"
    path.write_text(csv_text([
        ["name", "id", "section", "section_id", "submitted", "1: What is your name?", "1.0",
         f"2: Find v. {key_marker('pend.v')}", "1.0", f"3: Find w. {key_marker('pend.w')}",
         "1.0", "n correct", "n incorrect", "score"],
        ["Ada", "7", "S", "1", "", "Ada", "", "L=>2,3.5", "", "x^2", "", "", "", ""]]))
    read = read_quiz_responses(path, keys={"pend.v", "pend.w"}, drawn_keys={"pend.v"})
    assert [(e.path, e.reason) for e in read.skipped] == [
        ("q.csv: column 6 (1: What is your name?)",
         "no 'mechgrade key: problem.objective' of this assignment in the question's text"),
        ("q.csv: column 8 (2: Find v. (mechgrade key: pend.v))",
         "'pend.v' draws numbers per student: Canvas grades its responses with the numbers it "
         "drew")]
    assert read.students[0].answers == (("pend.w", "x^2"),)


def test_a_row_of_the_wrong_width_is_located(tmp_path):
    path = tmp_path / "q.csv"
    path.write_text("name,id,section,1: x (mechgrade key: p.v),1.0\nAda,7,S,3\n")
    with pytest.raises(SubmissionError, match=r"q.csv:2: expected 5 cells as in the header, "
                                              r"found 4"):
        read_quiz_responses(path, keys={"p.v"})


def test_an_unknown_csv_is_refused_with_what_was_expected(tmp_path):
    path = tmp_path / "q.csv"
    path.write_text("who,what\n1,2\n")
    with pytest.raises(SubmissionError, match="expected a Canvas quiz 'Student Analysis' CSV"):
        read_quiz_responses(path)
