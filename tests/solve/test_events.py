"""An integrated motion read at its event, or at an objective's own time, coordinate or rate
before it; an event that holds at the start waits for its next crossing."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechgrade.errors import SolveError
from mechgrade.solve import solve
from mechgrade.solve.events import leaving
from mechgrade.spec import load_problem, load_problem_text

ROOT = Path(__file__).resolve().parents[2]
SWING = (ROOT / "problems" / "damped_block_positions.yaml").read_text()


def swing(old: str, new: str):
    assert old in SWING
    return load_problem_text(SWING.replace(old, new, 1), "p.yaml")


def failure_of(problem, objective: str) -> str:
    """The error of ``objective`` asked alone (solve raises it: nothing else was asked)."""
    with pytest.raises(SolveError) as info:
        solve(problem, objectives=[objective])
    return str(info.value)


def test_an_objective_at_a_time_reads_the_integrated_motion_there():
    """x(t) = v0/wd exp(-zeta wn t) sin(wd t) at three times of the first swing."""
    wn, zeta = 20.0, 0.2
    wd = wn * np.sqrt(1 - zeta ** 2)
    for ms in (5, 50, 120):
        problem = swing("givens: {t: 30 ms}", f"givens: {{t: {ms} ms}}")
        t = ms / 1000
        expected = 1 / wd * np.exp(-zeta * wn * t) * np.sin(wd * t) * 1000
        assert solve(problem, objectives=["x_at_30ms"]).result("x_at_30ms").value == \
            pytest.approx(expected, rel=1e-9)


def test_an_objective_at_time_zero_reads_the_start_and_one_at_the_start_position_its_return():
    at_start = swing("givens: {t: 30 ms}", "givens: {t: 0 s}")
    assert solve(at_start, objectives=["x_at_30ms"]).result("x_at_30ms").value == 0.0
    back = swing("givens: {x: 20 mm}", "givens: {x: 0 mm}")
    wd = 20.0 * np.sqrt(1 - 0.2 ** 2)
    assert solve(back, objectives=["time_to_20mm"]).result("time_to_20mm").value == \
        pytest.approx(np.pi / wd * 1000, rel=1e-9)


def test_a_position_is_read_where_it_is_first_reached_not_on_the_way_back():
    """20 mm is passed twice in the first swing; the first time is before the peak."""
    solution = solve(load_problem(ROOT / "problems" / "damped_block_positions.yaml"),
                     objectives=["time_to_20mm", "peak_displacement"])
    problem = swing("givens: {t: 30 ms}", "givens: {t: 22.6292 ms}")
    assert solution.result("time_to_20mm").value == pytest.approx(22.6292, rel=1e-5)
    assert solve(problem, objectives=["x_at_30ms"]).result("x_at_30ms").value == \
        pytest.approx(20.0, rel=1e-5)


def test_an_instant_after_the_event_is_refused_at_its_given():
    problem = swing("givens: {t: 30 ms}", "givens: {t: 0.5 s}")
    assert failure_of(problem, "x_at_30ms") == (
        "p.yaml:54:17: objectives[1].givens.t: 't: 0.5 s' does not hold before the event "
        "('x = 0', at t = 0.160319 s), where the integrated motion ends: expected an instant "
        "before it")


def test_a_position_never_reached_before_the_event_is_refused():
    problem = swing("givens: {x: 20 mm}", "givens: {x: 50 mm}")
    assert "'x: 50 mm' does not hold before the event ('x = 0', at t = 0.160319 s)" in \
        failure_of(problem, "time_to_20mm")


def test_an_instant_beyond_the_time_allowed_is_refused():
    problem = load_problem_text(SWING.replace("until: x = 0 ", "until: x = 0\n    max_time: 0.1 s")
                                .replace("givens: {t: 30 ms}", "givens: {t: 120 ms}"), "p.yaml")
    assert "'t: 120 ms' does not hold within 0.1 s of the integrated motion: expected an " \
        "instant it reaches (or a larger max_time)" in failure_of(problem, "x_at_30ms")


def test_an_event_that_holds_at_the_start_is_its_next_crossing():
    """The block starts at equilibrium, x = 0: the event is its return, at pi / wd."""
    wd = 20.0 * np.sqrt(1 - 0.2 ** 2)
    solution = solve(load_problem(ROOT / "problems" / "damped_block_positions.yaml"),
                     objectives=["time_back"])
    assert solution.result("time_back").value == pytest.approx(np.pi / wd * 1000, rel=1e-9)


def test_an_event_that_holds_at_the_start_and_stays_is_refused():
    problem = swing("  v0: 1 m/s\n", "  v0: 0 m/s\n")
    assert "the event holds at the start (t = 0) and stays so: expected a motion that " \
        "leaves it" in failure_of(problem, "time_back")


def test_an_instant_that_holds_at_the_start_and_stays_is_refused_at_its_given():
    """At rest at x = 0, an objective asked at x: 0 mm has no next crossing: its given says
    so (the event, x = a, is not at the start)."""
    problem = load_problem_text(SWING.replace("until: x = 0 ", "until: x = a ")
                                .replace("  v0: 1 m/s\n", "  v0: 0 m/s\n")
                                .replace("givens: {x: 20 mm}", "givens: {x: 0 mm}", 1), "p.yaml")
    assert failure_of(problem, "time_to_20mm") == (
        "p.yaml:61:17: objectives[2].givens.x: 'x: 0 mm' holds at the start (t = 0) and stays "
        "so: expected a motion that leaves it")


def test_an_event_undefined_as_the_motion_leaves_it_is_refused_not_fired_at_once():
    """An event that holds at t = 0 and has no value a moment later has no next crossing."""
    direction, stays, undefined = leaving(
        lambda c, t, y, m: np.stack([y[1], -np.ones(len(c))]),
        lambda c, t, y, m: np.where(t == 0, 0.0, np.nan), None, np.array([[0.0], [2.0]]),
        10.0, None)
    assert direction.tolist() == [0.0] and stays == {}
    assert "the motion is undefined" in str(undefined[0])


def test_one_motion_and_a_column_of_many_leave_an_event_alike():
    """A motion alone is one column of leaving: the same direction, the same refusal."""
    def rhs(c, t, y, m):
        return np.stack([y[1], np.where(y[1] != 0.0, -1.0, 0.0)])

    def event(c, t, y, m):
        return y[0]

    starts = np.array([[0.0, 0.0, 0.0], [2.0, -2.0, 0.0]])  # up, down, at rest (no force: 0)
    columns, stays, _ = leaving(rhs, event, None, starts, 10.0, None)
    assert columns.tolist() == [-1.0, 1.0, 0.0] and list(stays) == [2]
    for i in range(3):
        alone, stays_alone, _ = leaving(rhs, event, None, starts[:, [i]], 10.0, None)
        assert alone.tolist() == [columns[i]]
        assert list(stays_alone) == ([0] if i == 2 else [])


def test_a_design_parameter_an_objective_gives_is_the_value_used():
    """Sample 9.21 sizes R; an objective asked with R: 0.25 m reads the wheel of that R, as
    Sample 9.21's own formula gives; the design is still solved for R_min."""
    text = (ROOT / "problems" / "ruina_9_21_wheel_incline.yaml").read_text()
    asked = text.replace("    expect: {components: [-14.715, 42.4785, 0]}\n",
                         "    expect: {components: [-14.715, 42.4785, 0]}\n"
                         "  - id: a_with_R\n    prompt: a\n    find: dot(acc(G, N), A.x)\n"
                         "    kind: scalar\n    unit: m/s^2\n    givens: {R: 0.25 m}\n")
    value = solve(load_problem_text(asked, "p.yaml"), objectives=["a_with_R", "R_min"])
    m, M, r, R, g, theta = 1.0, 2.0, 0.1, 0.25, 9.81, np.radians(30)
    closed = 2 * g * r**2 * (m + 2 * M) * np.sin(theta) / (3 * m * r**2 + 4 * M * r**2
                                                           + 2 * M * R**2)
    assert value.result("a_with_R").value == pytest.approx(closed, rel=1e-9)
    assert value.result("R_min").value == pytest.approx(0.1870829, rel=1e-6)


def test_a_symbolic_answer_of_a_motion_integrated_to_a_given_time():
    """until: t = T with T a parameter: the closed form at the event is that at t = T (the
    event's root is the symbol T itself); the cart's speed grows at mu m g / M."""
    text = (ROOT / "problems" / "block_slides_on_cart.yaml").read_text()
    text = text.replace("until: x' = X'", "until: t = T").replace(
        "  v0: m/s\n", "  v0: m/s\n  T: s\n").replace("givens:\n", "givens:\n  T: 0.5 s\n", 1)
    text = text.replace("    find: t\n    kind: symbolic\n    unit: s\n    symbols: [v0, mu, g, m, M]",
                        "    find: X'\n    kind: symbolic\n    unit: m/s\n"
                        "    symbols: [v0, mu, g, m, M, T]")
    solution = solve(load_problem_text(text, "p.yaml"),
                     objectives=["t_slide", "t_slide_symbolic", "common_speed"])
    assert solution.result("t_slide").value == pytest.approx(0.5, rel=1e-12)
    assert solution.result("t_slide_symbolic").expr == "T*g*m*mu/M"
    assert solution.result("common_speed").value == pytest.approx(0.3 * 2 * 9.81 * 0.5 / 8,
                                                                 rel=1e-9)


def test_a_symbolic_answer_of_an_integration_with_a_massless_junction_is_refused():
    from types import SimpleNamespace

    import sympy as sp

    from mechgrade.errors import Location
    from mechgrade.solve.events import integrated_symbolically

    kin = SimpleNamespace(k=None, settled=(sp.Symbol("xj"),))  # a junction's start: numbers
    with pytest.raises(SolveError, match="with a massless junction is out of reach"):
        integrated_symbolically(kin, sp.Symbol("t"), {}, Location())


LONGEST = 5.0 ** 2 * 8.0 / (2 * 0.3 * 9.81 * (2.0 + 8.0))  # v0^2 M / (2 mu g (m + M)), m


@pytest.mark.parametrize("distance, reached", [
    (float(np.nextafter(np.nextafter(LONGEST, 4.0), 4.0)), True),  # rounds off the real axis
    (LONGEST * (1 + 1e-14), True),
    (LONGEST * (1 + 1e-13), False)])
def test_an_event_the_motion_just_reaches_has_its_closed_form_time_and_one_beyond_has_none(
        distance, reached):
    """until: x - X = D, the block sliding D along the cart: at the longest slide (the block
    then stops sliding) the event's two times meet, a root that rounding puts an imaginary
    part of 1e-8 of its size on (refused as no time at all before); 1e-13 farther, the block
    never slides so far."""
    text = (ROOT / "problems" / "block_slides_on_cart.yaml").read_text()
    text = text.replace("until: x' = X'", "until: x - X = D").replace(
        "  v0: m/s\n", "  v0: m/s\n  D: m\n").replace(
        "givens:\n", f"givens:\n  D: {distance!r} m\n", 1).replace(
        "symbols: [v0, mu, g, m, M]", "symbols: [v0, mu, g, m, M, D]")
    problem = load_problem_text(text, "p.yaml")
    if not reached:
        assert "has no closed-form time" in failure_of(problem, "t_slide_symbolic")
        return
    expr = solve(problem, objectives=["t_slide_symbolic"]).result("t_slide_symbolic").expr
    assert expr == "(-sqrt(M)*sqrt(-2*D*M*g*mu - 2*D*g*m*mu + M*v0**2) + M*v0)/(g*mu*(M + m))"


def test_an_event_that_holds_at_the_start_is_its_next_crossing_in_closed_form_too():
    """A ball thrown from h until it is at H = h: the event holds at the throw. Its closed-form
    time t = 0 comes out +1.8e-16 s at 36° (the root's rounding), which was taken as the
    event; like the integrator, the closed form waits for the landing, 2 v0 sin(alpha) / g."""
    import sympy as sp

    problem = load_problem(ROOT / "tests" / "data" / "events" / "ball_back_at_its_height.yaml")
    solution = solve(problem)
    flight = 2 * 20.0 * np.sin(np.radians(36.0)) / 9.81
    assert solution.result("t_numeric").value == pytest.approx(flight, rel=1e-9)
    symbolic = sp.sympify(solution.result("t_symbolic").expr)
    givens = {"g": 9.81, "v0": 20.0, "alpha": np.radians(36.0), "h": 1.5, "H": 1.5}
    assert float(symbolic.subs(givens)) == pytest.approx(flight, rel=1e-12)


@pytest.mark.parametrize("h, H", [("35 cm", "0.35 m"), ("0.35 m", "35 cm")])
def test_an_event_that_holds_at_the_start_to_the_units_rounding_is_its_next_crossing(h, H):
    """h = 0.35 m and H = 35 cm are 5.5e-17 m apart once in metres: the integrator took the
    start below H and fired 4.7e-18 s on; it waits for the landing, as the closed form does."""
    text = (ROOT / "tests" / "data" / "events" / "ball_back_at_its_height.yaml").read_text()
    text = text.replace("h: 1.5 m", f"h: {h}").replace("H: 1.5 m", f"H: {H}")
    solution = solve(load_problem_text(text, "p.yaml"), objectives=["t_numeric"])
    flight = 2 * 20.0 * np.sin(np.radians(36.0)) / 9.81
    assert solution.result("t_numeric").value == pytest.approx(flight, rel=1e-9)
