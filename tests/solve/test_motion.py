"""The momentum balances over columns: each column solved and checked as the instant alone."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechgrade.errors import SolveError
from mechgrade.solve import solve
from mechgrade.solve.dynamics import kinematic_problem, kinetics_plan
from mechgrade.solve.instant import instant_givens
from mechgrade.solve.motion import balances
from mechgrade.solve.numeric import solve_numeric
from mechgrade.solve.phases import Entry, Until, reach_columns, stacked
from mechgrade.spec import load_problem

TURNTABLE = Path(__file__).resolve().parents[2] / "problems" / "block_on_turntable.yaml"


def test_a_column_that_slips_gets_the_error_the_instant_alone_raises_and_the_others_solve():
    problem = load_problem(TURNTABLE)
    kp = kinetics_plan(problem)
    state = solve_numeric(kinematic_problem(problem), kp.kp,
                          instant_givens(problem, None, {}), set()).state
    X = np.repeat(state.values[:, None], 3, axis=1)
    mu = kp.kp.index.position("mu_s")
    X[mu, 1] = 0.05  # too little friction to hold the block
    X[mu, 2] = -1.0  # not a friction coefficient at all
    solved = balances(problem, kp, X, state.given)
    assert solved.ok.tolist() == [True, False, False]
    np.testing.assert_allclose(solved.x[:, 0],
                               balances(problem, kp, X[:, :1], state.given).x[:, 0], rtol=1e-12)
    for column, mu_s in ((1, 0.05), (2, -1.0)):
        with pytest.raises(SolveError) as alone:
            solution = solve(problem, givens={"mu_s": mu_s})
            for failure in solution.failures:
                raise failure.error
        assert str(solved.errors[column]) == str(alone.value)
    assert "slips at P: sticking needs mu >= " in str(solved.errors[1])


@pytest.mark.slow  # a cold derivation (2 s); test_events' refusal of the same is in the fast core
def test_a_column_at_rest_in_an_event_that_holds_at_the_start_is_refused_by_the_columns():
    """The integrator over columns gives the error one motion alone raises (the event stays),
    without leaving that column to be integrated alone; the other column reaches its event."""
    problem = load_problem(Path(__file__).resolve().parents[2] / "problems"
                           / "damped_block_positions.yaml")
    kp = kinetics_plan(problem)
    state = solve_numeric(kinematic_problem(problem), kp.kp,
                          instant_givens(problem, None, {}), set()).state
    X = np.repeat(state.values[:, None], 2, axis=1)
    X[kp.kp.index.position("v0"), 1] = 0.0
    found = reach_columns(problem, X, [Until(), Until()], kinetics_plan)
    _, ok, errors = stacked(problem, found, kinetics_plan, 2)
    assert ok.tolist() == [True, False]
    assert list(errors) == [1]
    assert "the event holds at the start (t = 0) and stays so: expected a motion that " \
        "leaves it" in str(errors[1])


def test_a_slip_direction_written_as_a_sum_is_defined_where_the_slip_ends():
    """9.22's friction on the bowling ball, N mu (R psi' + xb')/|R psi' + xb'| expanded into
    two terms, read with its mode at the end of its slip: at the very end (R psi' + xb' = 0,
    where the integrator over columns locates a switch) the kept motion has the force of the
    slip before it, not 0/0, so that whether the ball then sticks can be judged there."""
    from mechgrade.solve.columns import call
    from mechgrade.solve.motion import _switches

    problem = load_problem(TURNTABLE.parent / "ruina_9_22_marble_bowling_ball.yaml")
    kp = kinetics_plan(problem)
    switches = _switches(kp, at_end=True)
    assert switches is not None and switches.count == 2
    names = [str(s) for s in kp.symbols]
    x = np.ones((len(names) + 2, 1))
    x[names.index("R")], x[names.index("psid")], x[names.index("xbd")] = 0.5, -4.0, 2.0
    N, mu, M = (x[names.index(n), 0] for n in ("N_D", "mu", "M"))
    assert call(switches.speeds, x[:len(names)], 2)[:, 0].tolist() == [2.0, 0.0]
    residual = call(switches.residual, x, len(kp.labels))[:, 0]
    row = kp.labels.index("body bowling_ball: N.x force balance")
    assert np.isfinite(residual).all()
    assert residual[row] == pytest.approx(-M * x[names.index("xbdd"), 0] - N * mu)


@pytest.mark.slow  # a cold derivation (2 s); the class's parity tests go this way in the fast core
def test_columns_asked_at_their_own_instants_beside_the_event_are_integrated_as_apart():
    """One pass over columns, each to its own instant (a time, a coordinate, a rate) or to
    the event (-1), gives each column what a pass of its own gives: a class integrates its
    motion once however many instants it is asked at."""
    problem = load_problem(Path(__file__).resolve().parents[2] / "problems"
                           / "damped_block_positions.yaml")
    kp = kinetics_plan(problem)
    index = kp.kp.index
    state = solve_numeric(kinematic_problem(problem), kp.kp,
                          instant_givens(problem, None, {}), set()).state
    X = np.repeat(state.values[:, None], 4, axis=1)
    instants = [index.time, index.position("x"), index.rates(1).start]
    values = (0.03, 0.02, 0.0)  # t = 30 ms, x = 20 mm, x' = 0 (the peak)
    X[instants, [1, 2, 3]] = values
    targets = [Until(), *(Entry(at, value, "given", None) for at, value in zip(instants, values))]
    together, ok, errors = stacked(problem, reach_columns(problem, X, targets, kinetics_plan),
                                   kinetics_plan, 4)
    assert ok.all() and not errors
    for c in range(len(targets)):  # the same steps, to the last digits the sums round
        apart, alone_ok, _ = stacked(problem, reach_columns(problem, X[:, [c]], [targets[c]],
                                                            kinetics_plan), kinetics_plan, 1)
        assert alone_ok[0]
        np.testing.assert_allclose(together[:, c], apart[:, 0], rtol=1e-10, atol=1e-13)
    assert together[index.time, 0] == pytest.approx(0.1603187, rel=1e-6)  # back at x = 0
    assert together[index.position("x"), 1] == pytest.approx(0.0251013, rel=1e-5)


def test_a_mass_matrix_of_parameters_only_is_worked_out_once_and_integrates_the_same_bits(
        monkeypatch):
    """Three carts on springs: the balances' matrix reads the masses only, so a class's
    integration evaluates it (and its determinants) once instead of at every right-hand
    side, and every column reaches its instants with the same numbers as evaluating it at
    every step."""
    from mechgrade.solve import phases
    from mechgrade.solve.motion import _switches

    problem = load_problem(TURNTABLE.parent / "three_cart_chain_vibration.yaml")
    kp = kinetics_plan(problem)
    switches = _switches(kp)  # (each spring's length |a + x| read with its sign kept)
    assert kp.constant_jacobian and switches is not None and switches.constant_jacobian
    index = kp.kp.index
    state = solve_numeric(kinematic_problem(problem), kp.kp,
                          instant_givens(problem, None, {}), set()).state
    X = np.repeat(state.values[:, None], 3, axis=1)
    X[index.position("m2"), 1] = 2.5
    X[index.position("k3"), 2] = 150.0
    x3d = index.rates(1).start + 2  # column 1: t = 250 ms; column 2: x3' = 0, cart 3 stops
    targets = [Until(), Entry(index.time, 0.25, "t", None), Entry(x3d, 0.0, "x3'", None)]

    def reached():
        return stacked(problem, reach_columns(problem, X.copy(), targets, kinetics_plan),
                       kinetics_plan, 3)

    once = reached()
    monkeypatch.setattr(phases, "constant_matrix", lambda *args: None)
    every_step = reached()
    assert once[1].all() and not once[2]
    for a, b in zip(once[:2], every_step[:2]):
        assert np.array_equal(a, b, equal_nan=True)
    assert once[0][index.position("x3"), 0] == pytest.approx(-0.0141080, rel=1e-5)
