"""The steps of a write-up (an assignment's ``steps:``): graded in order before the objective
they lead to, the first wrong one named, its error carried forward."""

from __future__ import annotations

import json
import textwrap

import pytest

from mechgrade.errors import AssignmentError
from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.results import AnswerResult, GradeReport
from mechgrade.grade.run import grade_submissions, plan_assignment
from mechgrade.resources import shipped_dir

BLOCKS = shipped_dir("problems") / "bowling_3_15_8_connected_blocks.yaml"
P = "bowling_3_15_8_connected_blocks"


def _assignment(folder, problem_lines: str, extra: str = ""):
    text = (f"id: hw\ntitle: HW\nproblems:\n  - path: {BLOCKS}\n"
            + textwrap.indent(textwrap.dedent(problem_lines), "    ") + extra)
    (folder / "hw.yaml").write_text(text, encoding="utf-8")
    return folder / "hw.yaml"


@pytest.mark.parametrize("lines, message", [
    ("steps: {rod_omega_z: [xdot, xdot]}\n", "expected each step once, found 'xdot' more than once"),
    ("steps: {rod_omega_z: [xdot, rod_omega_z]}\n",
     "expected the steps before objective 'rod_omega_z', found 'rod_omega_z' itself among them"),
    ("steps: {rod_omega_z: [V_A_N], V_A_N: [xdot]}\n",
     "expected steps without steps of their own, found 'V_A_N' \\(list all of its steps under "
     "'rod_omega_z' instead\\)"),
    ("steps: {rod_omega_z: []}\n", "steps.rod_omega_z"),
    ("steps: {rod_omega_z: xdot}\n", "steps.rod_omega_z"),
    ("steps: {}\n", "steps"),
])
def test_a_chain_of_steps_that_cannot_be_graded_is_refused_where_it_is_written(
        tmp_path, lines, message):
    with pytest.raises(AssignmentError, match=message) as caught:
        load_assignment(_assignment(tmp_path, lines))
    assert caught.value.where.line == 5


@pytest.mark.parametrize("lines, message", [
    ("objectives: [xdot]\nsteps: {rod_omega_z: [xdot]}\n",
     "expected steps of a graded objective of problem 'bowling_3_15_8_connected_blocks' "
     "\\(xdot\\), found 'rod_omega_z'"),
    ("objectives: [rod_omega_z]\nsteps: {rod_omega_z: [omega]}\n",
     "expected steps that are objectives of problem 'bowling_3_15_8_connected_blocks' "
     "\\(xdot, .*\\), found 'omega'"),
])
def test_steps_of_an_objective_not_graded_or_not_objectives_are_refused_before_solving(
        tmp_path, lines, message):
    hw = load_assignment(_assignment(tmp_path, lines))
    with pytest.raises(AssignmentError, match=message) as caught:
        plan_assignment(hw, solutions=())  # refused before anything is solved
    assert caught.value.where.line == 6


ANSWERS = {  # xdot -7.666 m/s, V_A_N (5.872, -4.928, 0) m/s, rod_omega_z 73.34 rad/s
    "all_right": ("-7.666 m/s", "(5.872, -4.928, 0) m/s", "73.34 rad/s"),
    # xdot wrong; V_A_N and rod_omega_z follow from it
    "carried": ("-1 m/s", "(0.766, -0.643, 0) m/s", "9.567 rad/s"),
    # xdot right; V_A_N wrong, and no value of the given rate y' gives it
    "second": ("-7.666 m/s", "(5, -4, 0) m/s", "60 rad/s"),
    # xdot wrong, V_A_N not answered: the missing step is not where the error is
    "skipped": ("-1 m/s", None, "9.567 rad/s"),
    # xdot right; V_A_N half the reference, as y' half the given gives: rod_omega_z follows
    "halved": ("-7.666 m/s", "(2.936, -2.464, 0) m/s", "36.67 rad/s"),
}


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    folder = tmp_path_factory.mktemp("steps")
    hw = _assignment(folder, """\
        objectives: [rod_omega_z]
        steps:
          rod_omega_z: [xdot, V_A_N]   # the spec declares no depends_on for V_A_N
        """, f"points: {{default: 2, {P}.xdot: 1}}\n")
    for sid, (xdot, v, omega) in ANSWERS.items():
        lines = [f"{P}.xdot = {xdot}", f"{P}.rod_omega_z = {omega}"]
        lines += [f"{P}.V_A_N = {v}"] if v else []
        (folder / "subs" / sid).mkdir(parents=True)
        (folder / "subs" / sid / "answers.txt").write_text("\n".join(lines) + "\n")
    return grade_submissions(load_assignment(hw), folder / "subs")


def _answers(report, sid) -> dict[str, AnswerResult]:
    return {a.objective: a for s in report.students if s.id == sid for a in s.answers}


@pytest.mark.slow  # a grading run with error carried forward's re-solves
def test_the_steps_are_graded_in_order_before_the_objective_with_their_own_points(graded):
    assert [(o.objective, o.max_points) for o in graded.objectives] == [
        ("xdot", 1.0), ("V_A_N", 2.0), ("rod_omega_z", 2.0)]
    assert [s.score for s in graded.students] == [5.0, 4.0, 3.0, 1.0, 2.0]


@pytest.mark.slow  # a grading run with error carried forward's re-solves
def test_a_wrong_steps_error_is_carried_forward_to_the_later_steps_and_named(graded):
    carried = _answers(graded, "carried")
    assert [carried[k].verdict for k in ("xdot", "V_A_N", "rod_omega_z")] == [
        "incorrect", "correct", "correct"]
    # V_A_N depends on xdot only through the assignment's steps
    assert carried["V_A_N"].diagnosis == "error carried forward"
    assert [carried[k].first_wrong_step for k in ("xdot", "V_A_N", "rod_omega_z")] == [
        None, "xdot", "xdot"]
    # V_A_N, credited by error carried forward, is not named as a wrong answer used
    assert carried["rod_omega_z"].feedback == (
        "Error carried forward: this answer follows correctly from your answer to xdot (used in "
        "place of the given y') and earns 100% of the points. The first wrong step of your "
        "write-up is step 1, 'xdot'.")
    assert _answers(graded, "skipped")["rod_omega_z"].first_wrong_step == "xdot"


@pytest.mark.slow  # a grading run with error carried forward's re-solves
def test_the_first_wrong_step_is_named_on_the_objective_and_on_later_steps_not_right(graded):
    second = _answers(graded, "second")
    assert second["rod_omega_z"].first_wrong_step == "V_A_N"
    assert second["rod_omega_z"].feedback.endswith(
        "Error carried forward could not be applied: your answer to 'V_A_N' is not one the "
        "model can have with other values of y': none gives it exactly. The first wrong step "
        "of your write-up is step 2, 'V_A_N'.")
    right = _answers(graded, "all_right")
    assert {a.first_wrong_step for a in right.values()} == {None}


@pytest.mark.slow  # a grading run with error carried forward's re-solves
def test_a_wrong_vector_step_gives_the_rates_that_make_it_exactly_to_the_later_steps(graded):
    halved = _answers(graded, "halved")
    assert [halved[k].verdict for k in ("xdot", "V_A_N", "rod_omega_z")] == [
        "correct", "incorrect", "correct"]
    assert halved["rod_omega_z"].diagnosis == "error carried forward"
    assert halved["rod_omega_z"].first_wrong_step == "V_A_N"
    assert halved["rod_omega_z"].feedback == (
        "Error carried forward: this answer follows correctly from your answer to V_A_N and "
        "earns 100% of the points. The first wrong step of your write-up is step 2, 'V_A_N'.")


@pytest.mark.slow  # a grading run with error carried forward's re-solves
def test_the_first_wrong_step_survives_results_json(graded):
    again = GradeReport.from_json(json.loads(json.dumps(graded.to_json())))
    assert again == graded
    rows = json.loads(json.dumps(graded.to_json()))["students"]
    right = next(s for s in rows if s["id"] == "all_right")
    assert all("first_wrong_step" not in a for a in right["answers"])
