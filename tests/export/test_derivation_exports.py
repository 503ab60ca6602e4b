"""A graded derivation in the exports: results.csv says what the feedback says of a free-body
diagram or equations of motion, Moodle names the first wrong step of a write-up, Canvas keeps
its grades."""

from __future__ import annotations

import csv

from mechgrade.export import EXPORTERS
from mechgrade.expressions.loads import LoadKind
from mechgrade.export.moodle import feedback_text
from mechgrade.grade.results import (AnswerResult, AssignmentInfo, GradeReport, LoadResult,
                                     ObjectiveInfo, Status, StudentResult)

OBJECTIVES = (ObjectiveInfo("incline", "block.fbd", "The free-body diagram of body block.", 2.0),
              ObjectiveInfo("incline", "equations", "The equations of motion.", 2.0),
              ObjectiveInfo("pendulum", "pin_force", "The pin force.", 2.0))
FRICTION = LoadResult("kinetic friction", "F_P", LoadKind.KINETIC_FRICTION, "P", None, ("missing",),
                      "Missing: the kinetic friction F_P at P.")


def _report(*answers: AnswerResult) -> GradeReport:
    student = StudentResult("ana", "Ana", Status.GRADED, sum(a.points for a in answers), 6.0,
                            answers)
    return GradeReport(AssignmentInfo("hw4", "HW 4"), OBJECTIVES, (student,))


ANA = _report(
    AnswerResult("incline", "block.fbd", "weight: -m g j; normal: N A.y", "partial", 1.33, 2.0,
                 feedback="Missing: the kinetic friction F_P at P.", loads=(FRICTION,)),
    AnswerResult("incline", "equations", "m x'' = m g sin(β)", "incorrect", 0.0, 2.0,
                 feedback="m*xdd = m*g*sin(beta): does not hold for the motion (the kinetic "
                          "friction F_P on block is missing from it)."),
    AnswerResult("pendulum", "pin_force", "(-65.21, 82.62, 0) N", "correct", 2.0, 2.0,
                 "error carried forward", "Error carried forward: ... The first wrong step of "
                 "your write-up is step 1, 'omega'.", first_wrong_step="omega"))


def _rows(path) -> list[list[str]]:
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.reader(f))


def test_results_csv_says_which_load_and_which_equation(tmp_path):
    EXPORTERS["long-csv"](ANA, tmp_path / "results.csv")
    header, *rows = _rows(tmp_path / "results.csv")
    assert header[-2:] == ["diagnosis", "feedback"]
    assert [row[-1] for row in rows] == [
        "Missing: the kinetic friction F_P at P.",
        "m*xdd = m*g*sin(beta): does not hold for the motion (the kinetic friction F_P on block "
        "is missing from it).",
        "Error carried forward: ... The first wrong step of your write-up is step 1, 'omega'."]


def test_results_csv_of_an_assignment_without_a_derivation_keeps_its_columns(tmp_path):
    plain = GradeReport(ANA.assignment, OBJECTIVES[2:], (StudentResult(
        "ana", "Ana", Status.GRADED, 2.0, 2.0, ANA.students[0].answers[2:]),))
    EXPORTERS["long-csv"](plain, tmp_path / "results.csv")
    assert _rows(tmp_path / "results.csv")[0][-1] == "diagnosis"


def test_moodle_feedback_names_the_first_wrong_step_beside_the_diagnosis():
    text = feedback_text(ANA, ANA.students[0])
    assert "(error carried forward; the first wrong step: omega)" in text
    assert "(Missing: the kinetic friction F_P at P.)" in text


def test_canvas_takes_the_total_of_a_derivation_and_no_column_more(tmp_path):
    EXPORTERS["canvas"](ANA, tmp_path / "canvas.csv")
    header, *rows = _rows(tmp_path / "canvas.csv")
    assert header == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "HW 4"]
    assert rows[0] == ["    Points Possible", "", "", "", "", "6"]  # the diagram's too
