"""Free-body diagrams and equations of motion in a grading run (an assignment's ``diagrams:``
and ``equations:``): results.json rows per load, the feedback pages, and
examples/hw4_derivation judged as by hand."""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import pytest

from mechgrade.errors import AssignmentError
from mechgrade.expressions.loads import LoadKind
from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.results import AnswerResult, GradeReport, LoadResult
from mechgrade.grade.run import grade_submissions, plan_assignment
from mechgrade.report.output import write_outputs
from mechgrade.resources import shipped_dir

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = shipped_dir("examples") / "hw4_derivation"
HAND = json.loads((ROOT / "tests" / "data" / "hw4_derivation_verdicts.json").read_text())
SCHEMA = ROOT / "src" / "mechgrade" / "export" / "results.schema.json"
INCLINE = shipped_dir("problems") / "block_sliding_down_incline.yaml"


def _assignment(folder: Path, problem: str) -> Path:
    (folder / "hw.yaml").write_text(f"id: hw\ntitle: HW\nproblems:\n{problem}",
                                    encoding="utf-8")
    return folder / "hw.yaml"


def test_a_diagram_of_a_body_the_problem_has_not_is_refused_before_solving(tmp_path):
    hw = _assignment(tmp_path, f"  - path: {INCLINE}\n    objectives: []\n"
                               f"    diagrams: [wheel]\n")
    with pytest.raises(AssignmentError, match="expected a body of problem "
                       "'block_sliding_down_incline' \\(block\\), found 'wheel'"):
        plan_assignment(load_assignment(hw))


def test_a_body_listed_twice_is_refused(tmp_path):
    hw = _assignment(tmp_path, f"  - path: {INCLINE}\n    diagrams: [block, block]\n")
    with pytest.raises(AssignmentError, match="found 'block' more than once"):
        load_assignment(hw)


def test_points_for_a_diagram_not_graded_say_so(tmp_path):
    hw = _assignment(tmp_path, f"  - path: {INCLINE}\n    objectives: [accel]\n"
                               f"points: {{block_sliding_down_incline.block.fbd: 3}}\n")
    with pytest.raises(AssignmentError, match=r"found 'block_sliding_down_incline\.block\.fbd'"):
        plan_assignment(load_assignment(hw))


def test_a_diagrams_rows_survive_results_json():
    rows = (LoadResult("weight", "gravity", LoadKind.WEIGHT, "G", "weight: -m*g*N.y", (), "right."),
            LoadResult("centrifugal force", None, None, "G", "centrifugal force: m*N.x",
                       ("extra",), "Extra."))
    student = {"id": "ana", "status": "graded", "score": 1.0, "max_score": 2.0,
               "answers": [AnswerResult("p", "rod.fbd", "...", "partial", 1.0, 2.0,
                                        loads=rows).__dict__]}
    student["answers"][0]["loads"] = [row.__dict__ for row in rows]
    # the document as a JSON file holds it: lists, not tuples
    report = GradeReport.from_json(json.loads(json.dumps(
        {"assignment": {"id": "hw", "title": "HW"}, "students": [student]})))
    assert report.students[0].answers[0].loads == rows
    assert GradeReport.from_json(json.loads(json.dumps(report.to_json()))) == report
    plain = AnswerResult("p", "v", "7 m/s", "correct", 2.0, 2.0)
    assert "loads" not in json.loads(json.dumps(
        GradeReport.from_json(json.loads(json.dumps({"assignment": {"id": "hw", "title": "HW"},
                                                     "students": [{**student, "answers": [
                                                         {**plain.__dict__}]}]})))
        .to_json()))["students"][0]["answers"][0]


@pytest.fixture(scope="module")
def graded():
    return grade_submissions(load_assignment(EXAMPLE / "assignment.yaml"),
                             EXAMPLE / "submissions")


@pytest.mark.slow
def test_every_diagram_and_set_of_equations_of_the_example_is_judged_as_by_hand(graded):
    assert {s.id for s in graded.students} == set(HAND) - {"_comment"}
    for student in graded.students:
        for answer in student.answers:
            key = f"{answer.problem}.{answer.objective}"
            hand = HAND[student.id][key]
            named = {m for row in answer.loads for m in row.mistakes}
            if answer.problem == "pendulum_release":  # the steps of the pin force
                expected = {True: "correct", "ecf": "correct", "missing": "missing"}.get(hand)
                if expected is None:  # not right
                    assert answer.verdict not in ("correct", "missing"), (student.id, key)
                else:
                    assert answer.verdict == expected, (student.id, key, answer.feedback)
                assert (answer.diagnosis == "error carried forward") == (hand == "ecf"), \
                    (student.id, key, answer.feedback)
                if answer.objective == "pin_force":
                    assert answer.first_wrong_step == HAND[student.id]["first_wrong_step"], \
                        (student.id, answer.feedback)
                continue
            load = HAND[student.id]["equation_loads"].get(key)
            balance = HAND[student.id]["equation_balances"].get(key)
            if answer.objective == "equations":
                assert (f"({balance}: " in answer.feedback if balance else
                        "(the wrong " not in answer.feedback), (student.id, key, answer.feedback)
            if answer.objective == "equations" and load is not None:
                kind, body, how = load
                assert kind in answer.feedback and body in answer.feedback \
                    and f"is {how}" in answer.feedback, (student.id, key, answer.feedback)
            elif answer.objective == "equations":  # no load is named where a reader sees none
                assert " is missing from it" not in answer.feedback and \
                    " is turned round in it" not in answer.feedback, (student.id, answer.feedback)
            if hand is True:
                assert answer.verdict == "correct", (student.id, key, answer.feedback)
            elif hand in ("wrong", "incomplete", "missing"):  # equations of motion
                said = {"wrong": "does not hold", "incomplete": "do not determine",
                        "missing": "No answer was given"}[hand]
                assert answer.verdict != "correct" and said in answer.feedback, \
                    (student.id, key, answer.feedback)
            elif hand == ["unreadable"]:
                assert answer.verdict == "unreadable", (student.id, key)
            else:
                assert answer.verdict != "correct", (student.id, key)
                assert sorted(named) == sorted(hand), (student.id, key, named)


@pytest.mark.slow
def test_the_reports_objectives_follow_the_assignments_order_of_problems(graded):
    problems = [o.problem for o in graded.objectives]
    assert list(dict.fromkeys(problems)) == [
        "block_sliding_down_incline", "pendulum_pin_reaction", "atwood_machine",
        "two_mass_spring_chain", "pendulum_release"]
    assert problems == sorted(problems, key=problems.index)  # each problem's together
    assert [o.objective for o in graded.objectives][:2] == ["block.fbd", "equations"]


@pytest.mark.slow
def test_results_json_and_the_feedback_page_show_a_row_per_load(graded, tmp_path):
    write_outputs(graded, tmp_path)
    data = json.loads((tmp_path / "results.json").read_text(encoding="utf-8"))
    jsonschema.validate(data, json.loads(SCHEMA.read_text(encoding="utf-8")))
    dan = next(s for s in data["students"] if s["id"] == "dan")
    rod = next(a for a in dan["answers"] if a["objective"] == "rod.fbd")
    assert [(row["label"], row["mistakes"]) for row in rod["loads"]] == [
        ("weight", []), ("pin", []), ("centrifugal force", ["extra"])]
    page = next(tmp_path.rglob("dan*.html")).read_text(encoding="utf-8")
    assert "Your free-body diagram, load by load" in page
    assert "centrifugal force" in page and "<td>extra</td>" in page


def test_equations_of_a_problem_without_bodies_are_refused(tmp_path):
    kinematic = shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"
    hw = _assignment(tmp_path, f"  - path: {kinematic}\n    objectives: []\n"
                               f"    equations: true\n")
    with pytest.raises(AssignmentError, match="expected equations of a problem with bodies"):
        plan_assignment(load_assignment(hw))


@pytest.mark.slow  # solves two students' variants and their derivations (a few seconds)
def test_a_diagram_and_equations_of_a_problem_drawing_variants_are_judged_at_the_students_numbers(
        tmp_path):
    text = INCLINE.read_text(encoding="utf-8").replace("mass m = 4 kg", "mass m = {m}").replace(
        "\nobjectives:\n", "\nvariants:\n  draw:\n    m: {choices: [3 kg, 5 kg]}\n"
                          "\nobjectives:\n", 1)
    (tmp_path / "block_sliding_down_incline.yaml").write_text(text, encoding="utf-8")
    hw = _assignment(tmp_path, "  - path: block_sliding_down_incline.yaml\n    objectives: []\n"
                               "    diagrams: [block]\n    equations: true\n"
                               "variants: {seed: fall}\n")
    from mechgrade.grade.variants import student_variant
    from mechgrade.spec import load_problem

    problem = load_problem(tmp_path / "block_sliding_down_incline.yaml")
    masses = {sid: dict(student_variant(problem, "fall", sid, False)[0].overrides)["m"]
              for sid in ("s1", "s2", "s3", "s4")}
    assert len(set(masses.values())) == 2  # the class has both masses
    for sid, m in masses.items():
        weight = m * 9.81 if sid in ("s1", "s2") else 4 * 9.81  # s3, s4: the book's 4 kg
        (tmp_path / "subs" / sid).mkdir(parents=True)
        (tmp_path / "subs" / sid / "answers.txt").write_text(
            f"block_sliding_down_incline.block.fbd = weight: -{weight:.4f} j; normal: N A.y; "
            f"friction: -mu_k N A.x\n"
            f"block_sliding_down_incline.equations = m x'' = m g sin(β) - μ_k N; "
            f"N = m g cos(β)\n", encoding="utf-8")
    report = grade_submissions(load_assignment(hw), tmp_path / "subs")
    verdicts = {s.id: [a.verdict for a in s.answers] for s in report.students}
    assert verdicts == {"s1": ["correct", "correct"], "s2": ["correct", "correct"],
                        "s3": ["partial", "correct"], "s4": ["partial", "correct"]}
    assert report.students[2].answers[0].loads[0].mistakes == ("wrong magnitude",)
