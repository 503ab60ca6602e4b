"""Many columns integrated to their events, or iterated to their roots, at once: each as
scipy's solvers take it alone (the events), or to the root scipy's secant finds (the roots)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate, optimize

from mechgrade.solve.batch_motion import (FAILED, FIRED, NEVER, STALLED, SWITCHED,
                                          integrate_to_events, newton, root_between)

OMEGA = np.array([1.0, 2.0, 3.0])


def oscillators(cols, t, y, modes):
    """x'' = -omega^2 x for every column."""
    return np.array([y[1], -OMEGA[cols] ** 2 * y[0]])


def crossing(level):
    return lambda cols, t, y, modes: y[0] - level[cols]


def test_each_column_reaches_its_event_where_solve_ivp_finds_it():
    level = np.array([0.5, -0.25, 0.0])
    y0 = np.array([[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]])
    arrival = integrate_to_events(oscillators, crossing(level), y0, 10.0, 1e-11, 1e-12, 20_000)
    assert arrival.status.tolist() == [FIRED] * 3
    for j in range(3):
        def event(t, y, j=j):
            return y[0] - level[j]
        event.terminal = True
        alone = integrate.solve_ivp(lambda t, y, j=j: oscillators(np.array([j]), t, y[:, None],
                                                             None)[:, 0],
                                    (0.0, 10.0), y0[:, j], method="DOP853", rtol=1e-11,
                                    atol=1e-12, events=event, dense_output=True)
        assert arrival.t[j] == pytest.approx(alone.t_events[0][0], rel=1e-13)
        assert np.allclose(arrival.y[:, j], alone.y_events[0][0], rtol=1e-12, atol=1e-13)
        earlier = alone.sol(alone.t_events[0][0] * (1 - 1e-9))
        assert np.allclose(arrival.before[:, j], earlier, rtol=1e-12, atol=1e-13)
    assert arrival.t == pytest.approx(np.arccos(level) / OMEGA, rel=1e-10)


def test_a_column_whose_event_never_happens_ends_at_the_time_allowed_without_it():
    level = np.array([0.5, 2.0, 0.5])  # the second never reaches 2
    y0 = np.array([[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]])
    arrival = integrate_to_events(oscillators, crossing(level), y0, 3.0, 1e-11, 1e-12, 20_000)
    assert arrival.status.tolist() == [FIRED, NEVER, FIRED]
    assert arrival.t[1] == 3.0 and abs(arrival.y[0, 1] - np.cos(6.0)) < 1e-9  # where it ended


def test_an_event_given_a_direction_fires_only_on_a_crossing_that_way_as_solve_ivp_does():
    # every column starts on its event, x = 0, and waits for it to cross back from the side
    # it leaves to (as events.leaving sets it): moving up, a fall; moving down, a rise
    y0 = np.array([[0.0, 0.0, 0.0], [1.0, -1.0, 1.0]])
    direction = np.array([-1.0, 1.0, -1.0])
    arrival = integrate_to_events(oscillators, crossing(np.zeros(3)), y0, 10.0, 1e-11, 1e-12,
                                  20_000, direction=direction)
    assert arrival.status.tolist() == [FIRED] * 3
    for j in range(3):
        def event(t, y):
            return y[0]
        event.terminal, event.direction = True, direction[j]
        alone = integrate.solve_ivp(lambda t, y, j=j: oscillators(np.array([j]), t, y[:, None],
                                                             None)[:, 0],
                                    (0.0, 10.0), y0[:, j], method="DOP853", rtol=1e-11,
                                    atol=1e-12, events=event)
        assert arrival.t[j] == pytest.approx(alone.t_events[0][0], rel=1e-13)
    assert arrival.t == pytest.approx(np.pi / OMEGA, rel=1e-10)


def test_a_column_that_starts_on_its_event_or_runs_out_of_evaluations_is_left_alone():
    level = np.array([1.0, 0.5, -0.9])
    y0 = np.array([[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]])
    arrival = integrate_to_events(oscillators, crossing(level), y0, 10.0, 1e-11, 1e-12, 100)
    assert arrival.status[0] == FAILED  # on its event at t = 0
    assert arrival.status[2] == STALLED  # too many evaluations before it, stopped at a time
    assert 0 < arrival.t[2] < np.arccos(-0.9)


def test_a_column_that_switches_before_its_event_is_located_at_its_switch():
    """A mode kept through a step: the column whose mode changes away from its event is
    not answered (the step across the switch integrated the motion before it); where its
    mode switched is located, with the modes it had before."""
    def rhs(cols, t, y, modes):
        return np.array([modes[0] * 1.0 + 0 * y[0]])

    def mode(cols, t, y):
        return np.array([np.where(t < switch[cols], 1.0, -1.0)])

    switch = np.array([5.0, 0.5])
    arrival = integrate_to_events(rhs, lambda cols, t, y, modes: y[0] - 1.0,
                                  np.zeros((1, 2)), 10.0, 1e-11, 1e-12, 20_000, mode=mode)
    assert arrival.status.tolist() == [FIRED, SWITCHED]
    assert arrival.t.tolist() == pytest.approx([1.0, 0.5], rel=1e-12)
    assert arrival.switch is not None and arrival.modes is not None
    assert arrival.switch[1] == 0 and arrival.modes[0, 1] == 1.0


def test_a_mode_that_switches_in_the_step_of_an_event_that_ends_another_is_located():
    """Two slips whose speeds fall linearly (steps far longer than the motion's switches):
    the event is slip 1's end, and slip 0 ends before it in the same step; the column is
    located at slip 0's end, not left failed (the step across both kept both modes)."""
    def rhs(cols, t, y, modes):
        return -modes * np.array([[1.0], [0.5]])

    def mode(cols, t, y):
        return np.sign(y)

    y0 = np.array([[0.3], [0.25]])  # slip 0 ends at t = 0.3, slip 1 (the event) at 0.5
    arrival = integrate_to_events(rhs, lambda cols, t, y, modes: y[1], y0, 10.0, 1e-11,
                                  1e-12, 20_000, mode=mode)
    assert arrival.status.tolist() == [SWITCHED]
    assert arrival.t.tolist() == pytest.approx([0.3], rel=1e-12)
    assert arrival.switch is not None and arrival.modes is not None
    assert arrival.switch[0] == 0 and arrival.modes[:, 0].tolist() == [1.0, 1.0]


def test_newton_finds_each_column_root_the_secant_finds_from_the_same_guess():
    targets = np.array([2.0, 9.0, -1.0, 1e-6])
    calls = []

    def residual(cols, x):
        calls.append(x.shape)
        return x ** 3 - targets[cols]
    roots, converged = newton(residual, np.full(4, 0.5), 1e-15, 1e-13, 100)
    for j, target in enumerate(targets):
        alone = optimize.root_scalar(lambda x, target=target: x ** 3 - target, x0=0.5, x1=0.5005,
                                     method="secant", xtol=1e-15, rtol=1e-13, maxiter=100)
        assert converged[j] and alone.converged
        assert roots[j] == pytest.approx(alone.root, rel=1e-13)
    assert all(shape[0] == 2 for shape in calls)  # each call: the iterates, and beside them
    assert calls[0] == (2, 4) and calls[-1][1] < 4  # a converged column is not evaluated again


def test_a_column_whose_residual_is_undefined_or_flat_does_not_converge():
    def residual(cols, x):
        return np.where(cols == 1, np.nan, np.where(cols == 2, 5.0, x - 3.0))
    roots, converged = newton(residual, np.ones(3), 1e-15, 1e-13, 100)
    assert converged.tolist() == [True, False, False]
    assert roots[0] == pytest.approx(3.0)
    assert np.isnan(roots[1:]).all()


def test_a_column_that_never_settles_stops_after_maxiter():
    roots, converged = newton(lambda cols, x: np.cbrt(x), np.array([1.0]), 1e-15, 1e-13, 30)
    assert not converged[0] and np.isnan(roots[0])  # Newton doubles |x| on cbrt each step


def test_of_several_events_the_earliest_fired_is_the_instant_from_the_start_time_given():
    """x = cos(omega (t - 0.5)) from t0 = 0.5: x = 0.9 (the second event) comes before
    x = 0 (the first) on every column."""
    y0 = np.array([[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]])
    arrival = integrate_to_events(oscillators, [crossing(np.zeros(3)), crossing(np.full(3, 0.9))],
                                  y0, 10.0, 1e-11, 1e-12, 20_000, t0=0.5)
    assert arrival.status.tolist() == [FIRED] * 3
    assert arrival.which is not None and arrival.which.tolist() == [1, 1, 1]
    assert arrival.t == pytest.approx(0.5 + np.arccos(0.9) / OMEGA, rel=1e-10)
    assert np.all(arrival.before[0] > 0.9)  # a moment before, on the same motion


def test_a_root_an_ulp_inside_an_end_of_its_bracket_takes_a_few_evaluations_not_a_bisection():
    """flywheel_speed_drop's t = T event: the first iterate lands an ulp past the root, every
    later one on that end again; bisecting down to it took 48 evaluations."""
    root_at = np.nextafter(0.16991083119804903, 0.0)
    evaluations = []

    def event(x):
        evaluations.append(x)
        return x - root_at

    a, b = 0.07244069888227622, 0.29080549678745565
    root, converged = root_between(event, a, b, a - root_at, b - root_at)
    assert converged and abs(root - root_at) <= 4 * np.finfo(float).eps * root_at
    assert len(evaluations) <= 4


def test_an_event_is_located_where_its_function_is_zero_to_the_last_bits_of_its_time():
    """spring_launcher_a_of_x's x = 0: the iterates that landed on an end of the bracket were
    bisected down to it, and settled up to 3.9e-15 m from the zero (x'' read just before it
    2.4e-5 off); the dense output's own zero is a few units in the last place of t away."""
    omega = np.sqrt(np.linspace(1200.0, 2400.0, 24))
    y0 = np.array([-0.1 * np.ones(24), np.zeros(24)])

    def springs(cols, t, y, modes):
        return np.array([y[1], -omega[cols] ** 2 * y[0]])

    arrival = integrate_to_events(springs, crossing(np.zeros(24)), y0, 1.0, 1e-10, 1e-12,
                                  20_000)
    assert arrival.status.tolist() == [FIRED] * 24
    assert np.all(np.abs(arrival.y[0]) <= 4 * np.finfo(float).eps * arrival.t * arrival.y[1])


@pytest.mark.parametrize("states", [1, 2, 3, 5, 6])
def test_a_column_integrated_alone_is_bit_for_bit_that_column_among_others(states):
    """However many states a motion has and however many columns a step carries (BLAS sums a
    value in one order inside its blocks and in another in the rest)."""
    rng = np.random.default_rng(states)
    stiffness = rng.uniform(1.0, 3.0, (states, 7))

    def coupled(cols, t, y, modes):
        velocity = np.roll(y, 1, axis=0)
        return velocity - stiffness[:, cols] * np.sin(y) + 0.1 * t

    def event(cols, t, y, modes):
        return t - 0.9 - 0.1 * cols

    y0 = rng.uniform(-1.0, 1.0, (states, 7))
    together = integrate_to_events(coupled, event, y0, 5.0, 1e-10, 1e-12, 20_000)
    for j in range(7):
        alone = integrate_to_events(lambda cols, t, y, modes, j=j: coupled(cols + j, t, y, modes),
                                    lambda cols, t, y, modes, j=j: event(cols + j, t, y, modes),
                                    y0[:, j:j + 1], 5.0, 1e-10, 1e-12, 20_000)
        assert alone.t[0] == together.t[j]
        assert alone.y[:, 0].tolist() == together.y[:, j].tolist()
        assert alone.before[:, 0].tolist() == together.before[:, j].tolist()
