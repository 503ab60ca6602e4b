"""A motion that skids, then rolls (solve/phases.py): the friction of a contact that grips once
its slip ends, refused where it is not supported, and refused where it would slip again."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechgrade.errors import SolveError, SpecError
from mechgrade.solve.dynamics import (accelerations, asked_entry, kinematic_problem,
                                     kinetics_plan, solve_dynamics)
from mechgrade.solve.instant import instant_givens
from mechgrade.solve.levels import place_givens
from mechgrade.solve.phases import (Until, asked_when, gripping, gripping_phase,
                                    gripping_word, reach, reach_columns)
from mechgrade.spec import load_problem, load_problem_text
from mechgrade.spec.dynamics import StaticFriction
from mechgrade.spec.model import ConstraintLevel

ROOT = Path(__file__).resolve().parents[2]
BALL = (ROOT / "problems" / "bowling_ball_skids_then_rolls.yaml").read_text()
INCLINE = (ROOT / "problems" / "block_sliding_down_incline.yaml").read_text()
SLIDES_ON = ROOT / "tests" / "data" / "phases" / "ball_slides_on_past_its_slip.yaml"
GRIPS = "kind: kinetic,\n          then: {kind: static, mu: mu_s, direction: A.x}}"


def error_of(text: str) -> str:
    with pytest.raises(SpecError) as err:
        load_problem_text(text, "p.yaml")
    return str(err.value)


def test_the_gripping_phase_holds_the_contact_still_along_the_slope_with_static_friction():
    problem = load_problem_text(BALL, "p.yaml")
    phase = gripping_phase(problem)
    assert gripping(phase) is None and gripping(problem).name == "F_C"
    (friction,) = phase.dynamics.friction
    assert isinstance(friction, StaticFriction)
    assert (friction.mu.text, [d.text for d in friction.directions]) == ("mu_s", ["A.x"])
    grip = phase.constraints[-1]
    assert (grip.name, grip.level, grip.lhs.text) == \
        ("F_C_grips", ConstraintLevel.VELOCITY, "dot(vel(coincident(C, B), N), A.x)")


def test_a_round_body_that_grips_rolls_and_a_block_sticks():
    assert gripping_word(load_problem_text(BALL, "p.yaml")) == "rolling"
    block = BALL.replace("inertia: {sphere: {radius: R}}", "inertia: {block: {sides: [2*R, 2*R, 2*R]}}")
    assert gripping_word(load_problem_text(block, "p.yaml")) == "sticking"


@pytest.mark.parametrize("case,text,message", [
    ("then on static friction",
     BALL.replace(GRIPS, "kind: static, direction: A.x,\n          then: {kind: static, mu: "
                  "mu_s, direction: A.x}}"),
     "p.yaml:40:17: loads.friction.F_C.then: 'then' says what a kinetic friction becomes once "
     "its slip ends; 'F_C' is static friction already (write kind: kinetic, or leave 'then' "
     "out)"),
    ("a contact gripping a moving frame",
     BALL.replace("kind: kinetic,\n", "kind: kinetic, surface: A,\n"),
     "p.yaml:40:17: loads.friction.F_C.then: friction 'F_C': a contact that grips once its slip "
     "ends is supported on the ground only, found surface: A; integrate until the slip ends "
     "instead (until: its slip speed = 0)"),
    ("a symbolic objective of a motion that grips",
     BALL.replace("find: x\n    kind: scalar", "find: x\n    kind: symbolic"),
     "p.yaml:98:5: objectives[6]: objective 'x_top': a motion that slips, then grips ('F_C' "
     "has 'then') is integrated numerically, so its objectives are numbers: expected kind: "
     "scalar or vector, found kind: symbolic"),
    ("a symbolic objective asked 'when' on an integrated motion",
     BALL.replace("when: x' + R*theta' = 0\n    kind: scalar", "when: x' + R*theta' = 0\n"
                  "    kind: symbolic", 1),
     "p.yaml:58:11: objectives[0].when: objective 't_rolls': 'when: x' + R*theta' = 0' is an "
     "instant of the motion integrated numerically: expected kind: scalar or vector, found "
     "kind: symbolic (or end the motion there with 'until: x' + R*theta' = 0')"),
    ("a contact that grips without an integration",
     INCLINE.replace("kind: kinetic}", "kind: kinetic, then: {kind: static, mu: mu_k, "
                     "direction: A.x}}"),
     "p.yaml:28:75: loads.friction.F_P.then: friction 'F_P': 'then' says how an integrated "
     "motion goes on once the slip ends; expected 'analysis: integrate', found no analysis "
     "(leave 'then' out)"),
])
def test_a_contact_that_grips_where_it_is_not_supported_is_refused(case, text, message):
    # a symbolic objective is also told it needs 'symbols' and 'expect.expr': one line each
    assert message in error_of(text).splitlines(), case


def _failures(text: str) -> dict[str, SolveError]:
    solution = solve_dynamics(load_problem_text(text, "p.yaml"))
    return {f.id: f.error for f in solution.failures}


@pytest.mark.slow
def test_a_grip_that_needs_more_than_mu_s_n_once_the_slip_ends_is_refused_where_it_is_declared():
    failures = _failures(BALL.replace("mu_s: 0.2", "mu_s: 0.04"))
    # asked while it skids, the objectives are read; in the rolling phase, refused
    assert sorted(failures) == ["friction_at_2s", "t_top", "v_at_2s", "x_at_2s", "x_top"]
    error = failures["x_top"]
    assert str(error).startswith(
        "p.yaml:40:17: loads.friction.F_C.then: friction 'F_C': the slip ends at t = 1.41987 s, but the grip then needs more friction "
        "than mu_s N (0.721962 N short): the contact slips on")


@pytest.mark.slow
def test_a_grip_that_would_slip_again_is_refused_with_the_instant():
    pushed = BALL.replace("  gravity: -g*N.y\n", "  gravity: -g*N.y\n  forces:\n    push: "
                          "{body: ball, at: G, force: k*t*A.x}\n") \
        .replace("  w0: rad/s\n", "  w0: rad/s\n  k: N/s\n") \
        .replace("  w0: 20 rad/s\n", "  w0: 20 rad/s\n  k: 10 N/s\n")
    failures = _failures(pushed)
    assert sorted(failures) == ["t_top", "x_top"]  # pushed up the slope, it never stops
    assert str(failures["t_top"]).startswith(
        "p.yaml:43:17: loads.friction.F_C.then: friction 'F_C' grips once its slip ends at t = 1.81848 s, and would slip again at "
        "t = 6.09564 s (the friction the grip needs reaches mu_s N there)")


@pytest.mark.slow
def test_an_instant_after_the_motion_ends_is_refused_in_the_rolling_phase_too():
    failures = _failures(BALL.replace("givens: {t: 2 s}", "givens: {t: 5 s}", 1))
    assert list(failures) == ["x_at_2s"]
    assert str(failures["x_at_2s"]) == (
        "p.yaml:73:17: objectives[2].givens.t: 't: 5 s' does not hold before the event ('x' = 0', at t = 3.01029 s), where the "
        "integrated motion ends: expected an instant before it")


@pytest.mark.slow
def test_an_objective_asked_when_on_a_motion_without_phases_is_read_where_it_first_holds():
    throw = (ROOT / "problems" / "ball_thrown_with_drag_apex_and_landing.yaml").read_text()
    asked = throw.replace("    givens: {y': 0 m/s}\n    expect: {value: 9.940268}",
                          "    when: y' = 0\n    expect: {value: 9.940268}")
    solution = solve_dynamics(load_problem_text(asked, "p.yaml"), objectives=["apex_height"])
    assert solution.result("apex_height").value == pytest.approx(9.940268, rel=1e-6)


@pytest.mark.slow  # derives both phases (over 2 s)
def test_each_column_of_a_class_switches_phase_at_its_own_end_of_the_slip():
    problem = load_problem_text(BALL, "p.yaml")
    kp = kinetics_plan(problem)
    overrides = {"t": problem.objective("x_at_2s").givens[0]}
    # rolls from t = 1.42 s; with less friction it still skids at t = 2 s
    maps = [instant_givens(problem, g, overrides) for g in ({}, {"mu_k": 0.05})]
    X = np.stack([place_givens(kinematic_problem(problem), kp.kp, m).values for m in maps],
                 axis=1)
    targets = [asked_entry(problem, kp, m, "t") for m in maps]
    found = reach_columns(problem, X, targets, kinetics_plan)
    assert not found.errors
    assert [(p.phase is problem, p.columns.tolist()) for p in found.phases] == \
        [(True, [1]), (False, [0])]
    for p in found.phases:
        (c,) = p.columns
        one = reach(problem, X[:, c], targets[c], kinetics_plan, accelerations)
        assert one.phase is p.phase and one.before is None is p.before
        assert np.array_equal(one.values, p.values[:, 0])  # the steps it takes alone



@pytest.mark.slow  # derives both phases (over 2 s)
def test_columns_aiming_at_different_instants_each_reach_their_own_in_one_pass_as_alone():
    problem = load_problem_text(BALL, "p.yaml")
    kp = kinetics_plan(problem)
    overrides = {"t": problem.objective("x_at_2s").givens[0]}
    # a class's three groups side by side: the event, t = 2 s (rolling by then; with less
    # friction still skidding) and the end of the slip, asked when
    maps = [instant_givens(problem, g, overrides) for g in ({}, {}, {"mu_k": 0.05}, {})]
    X = np.stack([place_givens(kinematic_problem(problem), kp.kp, m).values for m in maps],
                 axis=1)
    targets = [Until(), asked_entry(problem, kp, maps[1], "t"),
               asked_entry(problem, kp, maps[2], "t"),
               asked_when(problem, {"t_rolls"})]
    found = reach_columns(problem, X, targets, kinetics_plan)
    assert not found.errors
    assert sorted((p.phase is problem, c) for p in found.phases for c in p.columns) == \
        [(False, 0), (False, 1), (True, 2), (True, 3)]
    for p in found.phases:
        for k, c in enumerate(p.columns):
            one = reach(problem, X[:, c], targets[c], kinetics_plan, accelerations)
            assert one.phase is p.phase and (one.before is None) is (p.before is None)
            assert np.array_equal(one.values, p.values[:, k])


@pytest.mark.slow  # a cold derivation (over 1 s)
def test_a_slip_that_ends_before_the_instant_asked_when_stalls_there_as_step_by_step():
    problem = load_problem(SLIDES_ON)
    with pytest.raises(SolveError, match=r"the integration stalls near t = 1\.41987 s"):
        solve_dynamics(problem, objectives=["v_rolls"])
