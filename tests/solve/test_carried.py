"""A student's second rate given with the balance that would determine it set aside (error
carried forward): the reactions from the other balances, refused where they do not determine
them."""

from __future__ import annotations

import pytest

import mechgrade.solve.carried as carried_module
from mechgrade.errors import MechgradeError, SolveError, UnderdeterminedError
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.solve.carried import solve_carried
from mechgrade.spec import load_problem, load_problem_text

PROBLEMS = shipped_dir("problems")


def test_a_pin_force_follows_from_the_students_angular_acceleration():
    # theta = 40 deg, w = 3 rad/s, r_G = 0.6 (sin 40, -cos 40) = (0.385673, -0.459627) m;
    # with alpha = -31.53 rad/s^2: a_G = alpha k x r_G - w^2 r_G
    # = (-14.4920, -12.1602) + (-3.4711, 4.1366) = (-17.9631, -8.0236);
    # R_O = m a_G + m g j = (-35.926, -16.047 + 19.62) = (-35.926, 3.573) N
    problem = load_problem(PROBLEMS / "pendulum_pin_reaction.yaml")
    force = solve_carried(problem, givens={"theta''": -31.53}, objectives=("pin_force",))
    assert force.result("pin_force").value == pytest.approx((-35.926, 3.573, 0.0), abs=2e-3)


def test_a_wrong_acceleration_down_an_incline_leaves_the_normal_force_as_it_is():
    # the balance along the slope gives way: N = m g cos 30 = 4 (9.81) 0.866025 = 33.983 N
    problem = load_problem(PROBLEMS / "block_sliding_down_incline.yaml")
    solution = solve_carried(problem, givens={"x''": 1.0}, objectives=("normal",))
    assert solution.result("normal").value == pytest.approx(33.983, abs=1e-3)


def test_balances_undefined_at_the_instant_are_refused_alike_with_a_given_second_rate():
    """Gravity written over tan(beta), with beta = 0: the force balance divides by zero; with
    the student's x'' held, the balances left say so as the problem's own solve does."""
    text = (PROBLEMS / "block_sliding_down_incline.yaml").read_text()
    problem = load_problem_text(text.replace("gravity: -g*N.y\n", "gravity: -g/tan(beta)*N.y\n")
                                .replace("beta: 30 deg", "beta: 0 deg"), "p.yaml")
    expected = ("p.yaml:22:10: bodies.block: the equations of motion are undefined at this "
                "instant (a division by zero in 'body block: N.y force balance')")
    with pytest.raises(SolveError) as own:
        solve(problem, objectives=("normal",))
    with pytest.raises(SolveError) as carried:
        solve_carried(problem, givens={"x''": 1.0}, objectives=("normal",))
    assert str(own.value) == str(carried.value) == expected


def test_a_wrong_acceleration_of_two_blocks_does_not_determine_the_rope_tension():
    problem = load_problem(PROBLEMS / "atwood_machine.yaml")
    with pytest.raises(UnderdeterminedError) as caught:
        solve_carried(problem, givens={"y''": 1.0}, objectives=("tension",))
    message = caught.value.message
    assert message.startswith("with the given y'', the momentum balances left do not "
                               "determine T (along N.y): setting aside the force balance of "
                               "block1 gives T (along N.y) = ")
    assert ", setting aside the force balance of block2 gives " in message


def test_a_work_energy_instant_keeps_the_students_angular_acceleration():
    # w^2 = 3 g cos 40/L = 18.7872 from the energy balance; alpha = -31.53 rad/s^2:
    # R_O = m (alpha k x r_G - w^2 r_G) + m g j = (-43.475, 12.570) N
    problem = load_problem(shipped_dir("examples") / "hw3_dynamics" / "pendulum_release.yaml")
    force = solve_carried(problem, givens={"theta''": -31.53}, objectives=("pin_force",))
    assert force.result("pin_force").value == pytest.approx((-43.475, 12.570, 0.0), abs=2e-3)


@pytest.mark.slow  # cold derivations of the problem and of each mistaken model: seconds
def test_a_carried_solve_and_its_mistakes_are_kept_in_the_disk_cache_apart_from_the_problems(
        disk, forget, monkeypatch):
    problem = load_problem(PROBLEMS / "block_sliding_down_incline.yaml")
    carried = solve_carried(problem, givens={"x''": 1.0}, objectives=("normal",))
    with pytest.raises(MechgradeError):  # solved as given, x'' contradicts the balances
        solve(problem, givens={"x''": 1.0}, objectives=("normal",))
    forget()
    monkeypatch.setattr(carried_module, "held_dynamics", _not_solved)
    again = solve_carried(problem, givens={"x''": 1.0}, objectives=("normal",))
    assert again.result("normal").value == carried.result("normal").value == \
        pytest.approx(33.983, abs=1e-3)
    # each mistaken model solved with x'' held too (solved as given, none would hold):
    # N = m cos 30 = 3.464 (g left out), m g = 39.24, m g cos(30 rad) = 6.053, m g cos 60
    mistakes = [(m.code, round(m.value, 3)) for m in again.result("normal").generated_mistakes]
    assert mistakes == [("mass_for_weight", 3.464), ("reaction_as_weight", 39.24),
                        ("given_deg_as_rad", 6.053), ("given_complement", 19.62)]
    assert mistakes == [(m.code, round(m.value, 3))
                        for m in carried.result("normal").generated_mistakes]


def _not_solved(*args, **kwargs):
    raise AssertionError("solved again: expected to be read from the cache")
