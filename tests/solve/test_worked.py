"""The worked solution made by the solver: steps in the write-up order, where each generated
mistake happens, the picture; made once per problem, numbers per solution."""

import pytest

from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.spec.mistake_codes import DYNAMICS_CODES, GIVEN_CODES
from mechgrade.spec.mistake_codes import MODEL_CODES as CODES
from mechgrade.solve.worked import worked_solution
from mechgrade.spec import load_problem

PROBLEMS = shipped_dir("problems")


def _worked(name, **givens):
    problem = load_problem(PROBLEMS / f"{name}.yaml")
    return worked_solution(problem, solve(problem, givens=givens or None))


@pytest.mark.parametrize("name, objective, code, place", [
    ("ruina_10_4_10_7_rotating_tube_accel", "a_P_N", "drop_coriolis", "acc-P-coriolis"),
    ("ruina_10_4_10_7_rotating_tube_accel", "a_P_N", "coriolis_half", "acc-P-coriolis"),
    ("ruina_10_4_10_7_rotating_tube_accel", "a_P_N", "drop_centripetal",
     "acc-P-omega_omega_r"),
    ("ruina_10_4_10_7_rotating_tube_accel", "a_P_N", "drop_relative_acc", "acc-P-relative"),
    ("ruina_10_6_rotating_tube_velocity", "v_P_N", "drop_omega_r", "vel-P-omega_r"),
    ("bowling_3_15_4_pendulum", "acc_mag", "drop_tangential", "acc-A-alpha_r"),
    ("bowling_3_15_4_pendulum", "acc_mag", "acc_t_for_acc", "answer-acc_mag"),
    ("bowling_3_15_4_pendulum", "acc_mag", "given_deg_as_rad", "givens"),
    ("bowling_3_15_4_pendulum", "acc_mag", "position_term", "points"),
])
def test_each_mistake_points_at_the_step_where_it_happens(name, objective, code, place):
    assert _worked(name).place(objective, code) == place


@pytest.mark.parametrize("name", ["ruina_10_4_10_7_rotating_tube_accel",
                                  "ruina_10_6_rotating_tube_velocity",
                                  "bowling_3_15_4_pendulum", "bowling_3_15_5_cylinder",
                                  "pendulum_pin_reaction"])
def test_every_place_is_a_step_or_row_of_the_solution(name):
    worked = _worked(name)
    anchors = {s.anchor for s in worked.steps} | {r.anchor for s in worked.steps
                                                  for r in s.rows}
    assert {place for _, _, place in worked.places} <= anchors
    kinetic = DYNAMICS_CODES if any(a.startswith("kinetics-") for a in anchors) else ()
    assert {code for _, code, _ in worked.places} == set(CODES + GIVEN_CODES + kinetic)


@pytest.mark.parametrize("name, objective, code, place", [
    ("pendulum_pin_reaction", "pin_force", "central_inertia_at_pivot",
     "balance-pivot-rod-O"),
    ("pendulum_pin_reaction", "pin_force", "weight_omitted", "load-rod-gravity"),
    ("block_sliding_down_incline", "normal", "normal_from_weight",
     "balance-normal-block-N_P"),
    ("block_sliding_down_incline", "accel", "friction_reversed", "load-block-F_P"),
    ("atwood_machine", "tension", "tension_as_weight", "balance-0"),
])
def test_each_kinetic_mistake_points_at_the_row_where_it_happens(name, objective, code, place):
    assert _worked(name).place(objective, code) == place


def test_a_rate_from_the_energy_balance_is_a_result_not_a_given():
    problem = load_problem(shipped_dir("examples") / "hw3_dynamics" / "pendulum_release.yaml")
    steps = {s.anchor: s for s in worked_solution(problem, solve(problem)).steps}
    assert not any(line.startswith("theta' =") for line in steps["givens"].lines)
    assert "theta' = -4.33442 rad/s" in steps["state"].lines
    assert "theta = 40 deg" in steps["givens"].lines


def test_a_symbolic_answer_is_typeset_with_the_sense_of_the_slip():
    (step,) = [s for s in _worked("block_sliding_down_incline").steps
               if s.anchor == "answer-accel_symbolic"]
    (row,) = step.rows
    assert "<mo>|</mo>" in row.math and "Abs" not in row.math and "xd" not in row.math
    assert "at this instant x' > 0, so x'/|x'| = 1" in step.lines


def test_the_steps_follow_the_write_up_order():
    steps = [s.anchor for s in _worked("pendulum_pin_reaction").steps]
    assert steps[:4] == ["givens", "frames", "points", "constraints"]
    assert steps.index("vel-G") < steps.index("acc-G") < steps.index("kinetics-solution") \
        < steps.index(next(s for s in steps if s.startswith("answer-")))


def test_other_numbers_change_the_numbers_not_the_symbolic_steps():
    base = _worked("bowling_3_15_4_pendulum")
    other = _worked("bowling_3_15_4_pendulum", **{"theta'": 3.0})
    symbolic = [s.rows for s in base.steps if s.rows]
    assert symbolic == [s.rows for s in other.steps if s.rows]
    assert symbolic[0] is next(s.rows for s in other.steps if s.rows)  # made once per problem
    assert "theta' = 3 rad/s" in other.steps[0].lines and other.picture != base.picture
    # the numbers at the instant, in the unit the objective asks (|v| = L theta' = 6 ft/s)
    velocity = next(s for s in other.steps if s.anchor == "vel-A")
    assert velocity.lines[-1] == "At the instant: N_v_A = (-3, 5.196, 0) ft/s along N"


@pytest.mark.slow
def test_a_junction_is_said_in_words_and_its_coordinate_as_a_textbook_writes_it():
    from mechgrade.report.worked import steps_html

    problem = load_problem(PROBLEMS / "block_on_springs_in_series.yaml")
    worked = worked_solution(problem, solve(problem))
    constraints = next(s for s in worked.steps if s.anchor == "constraints")
    assert constraints.lines[0] == ("The joint J is massless, so the pulls of the springs s1 "
                                    "and s2 on it are in balance: s1 + s2 = 0.")
    page = steps_html(worked)
    for code in ("mag(", "pos(", "unit(", "xjd", "xj'", "e+0", "e-1"):
        assert code not in page
    assert "ẋ<sub>J</sub>" in page and "<msub><mi>𝑥̇</mi><mi>J</mi></msub>" in page


@pytest.mark.slow
def test_a_motion_that_slips_then_rolls_is_written_up_phase_by_phase():
    from mechgrade.solve.worked import slip_end_time

    problem = load_problem(PROBLEMS / "bowling_ball_skids_then_rolls.yaml")
    assert slip_end_time(problem) == pytest.approx(1.419869, rel=1e-6)  # the author's t_rolls
    worked = worked_solution(problem, solve(problem))
    titles = [s.title for s in worked.steps]
    assert "Free-body loads, while F_C slips, until t = 1.42 s" in titles
    rolling = "rolling from t = 1.42 s (F_C grips: static friction)"
    assert f"Momentum balances, {rolling}" in titles
    loads = next(s for s in worked.steps if s.anchor == "rolling-kinetics-free-body-loads")
    assert [r.caption for r in loads.rows][-1] == "ball, static friction F_C at C (unknown)"
    # the diagram is drawn where the instant's phase is written up, with its static friction
    assert worked.diagram_step == "rolling-kinetics-free-body-loads"
    assert "read while rolling (the slip ends at t = 1.42 s)" in next(
        s for s in worked.steps if s.anchor == "answer-friction_at_2s").lines
    assert not any("coincident(" in line for s in worked.steps for line in s.lines)


def test_an_answer_zero_up_to_round_off_is_written_as_zero():
    """9.25: the striking ball stops (v1p is -1.3e-15 ft/s as solved) and the struck ball's
    velocity is along -Y_N (its x component 1.2e-14): a student reads 0, not the round-off."""
    steps = {s.anchor: s for s in _worked("ruina_9_25_units_matrix").steps}
    assert "= 0 ft/s" in steps["answer-v1p"].lines
    assert steps["answer-v2_N"].lines[-1] == "= (0, -20, 0) ft/s in frame N"
    assert "x1' = 0 ft/s" in steps["state"].lines
