"""Roster conflicts in exports: a student matched by two results (or a result matching two
students) is held back, never written with a guessed grade or a zero."""

from __future__ import annotations

import csv

from mechgrade.export import EXPORTERS
from mechgrade.export.matching import match_roster
from mechgrade.grade.results import AssignmentInfo, GradeReport, ObjectiveInfo, StudentResult
from mechgrade.roster import Roster, RosterFormat, RosterStudent

HEADER = ("Student", "ID", "SIS User ID", "SIS Login ID", "Section")
ANN = RosterStudent("101", "Ann Ash", "ann@uni.edu", "s1", "ann@uni.edu", "A",
                    tuple(zip(HEADER, ("Ash, Ann", "101", "s1", "ann@uni.edu", "A"))))
BEN = RosterStudent("102", "Ben Bo", "ben@uni.edu", "s2", "ben@uni.edu", "A",
                    tuple(zip(HEADER, ("Bo, Ben", "102", "s2", "ben@uni.edu", "A"))))
ROSTER = Roster((ANN, BEN), RosterFormat.CANVAS, (*HEADER, "HW (5)"))
OBJECTIVES = (ObjectiveInfo("p", "v", "Speed", 2.0),)


def report(*students: StudentResult) -> GradeReport:
    return GradeReport(AssignmentInfo("hw", "HW"), OBJECTIVES, students)


def graded(ident: str, score: float) -> StudentResult:
    return StudentResult(ident, "", "graded", score, 2.0)


def rows(path) -> list[list[str]]:
    return list(csv.reader(path.read_text(encoding="utf-8-sig").splitlines()))


def test_two_results_naming_one_student_are_a_conflict_held_back_not_a_zero(tmp_path):
    """Graded without a roster: '101' (Ann's Canvas id) and 's1' (her SIS id) both name Ann."""
    found = report(graded("101", 2.0), graded("s1", 1.0), graded("102", 1.5))
    match = match_roster(found, ROSTER)
    assert [(p.roster.id if p.roster else None, p.result.id if p.result else None,
             p.result.status if p.result else None) for p in match.pairs] == [
        ("101", "101", "conflict"), ("102", "102", "graded"), (None, "101", "conflict"),
        (None, "s1", "conflict")]
    said = ("roster conflict: '101' matches Ann Ash (101) by id; 's1' matches Ann Ash (101) "
            "by SIS user id")
    assert match.pairs[0].result.messages == (said,)
    warnings = EXPORTERS["canvas"](found, tmp_path / "canvas.csv", roster=ROSTER)
    assert [r[1] for r in rows(tmp_path / "canvas.csv")[2:]] == ["102"]
    held = rows(tmp_path / "canvas.unmatched.csv")
    assert held == [["id", "name", "status", "score", "reason"],
                    ["101", "Ann Ash", "conflict", "", said], ["101", "", "conflict", "", said],
                    ["s1", "", "conflict", "", said]]
    assert any("3 rows kept out" in w for w in warnings)
    EXPORTERS["moodle"](found, tmp_path / "moodle.csv", roster=ROSTER)
    assert [r[0] for r in rows(tmp_path / "moodle.csv")[1:]] == ["ben@uni.edu"]
    assert len(rows(tmp_path / "moodle.unmatched.csv")) == 4


def test_a_conflict_from_grading_is_held_back_in_every_import(tmp_path):
    """Graded with the roster: Ann's own record and the folders are all of status conflict."""
    said = "roster conflict: '101' matches Ann Ash (101) by id"
    found = report(
        StudentResult("101", "Ann Ash", "conflict", 0.0, 2.0, messages=(said,),
                      identity=ANN.columns),
        StudentResult("102", "Ben Bo", "graded", 2.0, 2.0, identity=BEN.columns),
        StudentResult("101", "", "conflict", 2.0, 2.0, messages=(said,)),
        StudentResult("ann", "", "conflict", 1.0, 2.0, messages=(said,)))
    match = match_roster(found, ROSTER)
    assert [(p.roster.id if p.roster else None, p.result.id if p.result else None)
            for p in match.pairs] == [("101", "101"), ("102", "102"), (None, "101"),
                                      (None, "ann")]
    assert match.no_submission == ()
    EXPORTERS["grades-csv"](found, tmp_path / "grades.csv", roster=ROSTER)
    assert rows(tmp_path / "grades.csv")[1:] == [
        ["101", "Ann Ash", "conflict", "", "", "2"], ["102", "Ben Bo", "graded", "0", "2", "2"],
        ["101", "", "conflict", "", "", "2"], ["ann", "", "conflict", "", "", "2"]]
    EXPORTERS["long-csv"](found, tmp_path / "results.csv", roster=ROSTER)
    assert [(r[0], r[5], r[6]) for r in rows(tmp_path / "results.csv")[1:]] == [
        ("101", "missing", ""), ("102", "missing", "0"), ("101", "missing", ""),
        ("ann", "missing", "")]
    EXPORTERS["canvas"](found, tmp_path / "canvas.csv", roster=ROSTER)
    assert [r[1] for r in rows(tmp_path / "canvas.csv")[2:]] == ["102"]
    assert [r[2:] for r in rows(tmp_path / "canvas.unmatched.csv")[1:]] == [
        ["conflict", "", said]] * 3
