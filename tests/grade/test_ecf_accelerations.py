"""Error carried forward from a wrong acceleration (a step of a write-up on a problem with
bodies): the balance that would give it is set aside and the reactions follow from the rest;
refused, with the reason in the feedback, where they do not (two blocks) or where the motion
is integrated from its start."""

from __future__ import annotations

import pytest

from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.run import grade_submissions
from mechgrade.resources import shipped_dir

PROBLEMS = shipped_dir("problems")


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ecf_accelerations")
    (folder / "hw.yaml").write_text(
        "id: hw\ntitle: HW\nproblems:\n"
        f"  - path: {PROBLEMS / 'atwood_machine.yaml'}\n"
        "    objectives: [tension]\n    steps: {tension: [a1]}\n"
        f"  - path: {PROBLEMS / 'boat_coasting_quadratic_drag.yaml'}\n"
        "    objectives: [distance]\n    steps: {distance: [deceleration]}\n"
        "policy: {ecf: {credit: 1.0}}\n", encoding="utf-8")
    (folder / "subs").mkdir()
    (folder / "subs" / "ola.txt").write_text(
        "atwood_machine.a1 = 9 m/s^2\natwood_machine.tension = 10 N\n"
        "boat_coasting_quadratic_drag.deceleration = -1 m/s^2\n"
        "boat_coasting_quadratic_drag.distance = 1 m\n", encoding="utf-8")
    return {a.objective: a for a in grade_submissions(load_assignment(folder / "hw.yaml"),
                                                      folder / "subs").students[0].answers}


@pytest.mark.slow  # a grading run with error carried forward's re-solves
@pytest.mark.parametrize("objective, step, said", [
    # two blocks: setting aside either one's balance gives its own tension
    ("tension", "a1", "Error carried forward could not be applied: with your y'' the problem "
                      "cannot be solved (with the given y'', the momentum balances left do not "
                      "determine T (along N.y): setting aside the force balance of block1 gives "
                      "T (along N.y) = "),
    ("distance", "deceleration", "Error carried forward could not be applied: your x'' is an "
                                 "acceleration at one instant of a motion integrated from its "
                                 "start, which it does not change."),
])
def test_a_wrong_acceleration_the_later_answers_do_not_follow_from_is_not_carried_forward(
        graded, objective, step, said):
    answer = graded[objective]
    assert (answer.verdict, answer.diagnosis, answer.first_wrong_step) == (
        "incorrect", None, step)
    assert said in answer.feedback
