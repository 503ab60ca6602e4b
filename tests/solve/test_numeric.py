"""The numeric instant's safety net: a solution where a given does not hold is an error."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import given as examples, settings
from hypothesis import strategies as st

from mechgrade.errors import InconsistentError, SolveError
from mechgrade.solve import kinematics_plan
from mechgrade.solve.instant import _givens, instant_givens
from mechgrade.solve.levels import State, place_givens
from mechgrade.solve.numeric import (Instant, _givens_not_holding, solve_numeric,
                                     solve_numeric_columns)
from mechgrade.spec import load_problem_text

BASE = (Path(__file__).resolve().parents[1] / "data" / "spec" / "base.yaml").read_text()


def test_a_given_that_does_not_hold_in_the_solution_is_named_with_its_place():
    problem = load_problem_text(BASE.replace("  theta': 3 rad/s\n",
                                             "  \"dot(vel(P, N), A.y)\": 8 m/s\n"), "p.yaml")
    p = kinematics_plan(problem)
    givens = _givens(problem, None)
    g = place_givens(problem, p, givens)
    good = g.values.copy()
    good[list(p.index.rates(1))] = 4.0  # L theta' = 8 m/s
    wrong = good.copy()
    wrong[list(p.index.rates(1))] = 3.0  # 6 m/s, not the 8 m/s given
    held, error = _givens_not_holding(problem, p, [(g, givens, State(x, g.known))
                                                   for x in (good, wrong)])
    assert held is None and isinstance(error, SolveError)
    assert str(error) == ("p.yaml:16:26: givens.dot(vel(P, N), A.y): the given "
                               "'dot(vel(P, N), A.y) = 8 m/s' does not hold in the solution: "
                               "dot(vel(P, N), A.y) is 6 m / s there")


# ---------------------------------------------------------------- many instants at once


def _circle_level():
    """x² + y² = r² (the state: x, y, r), solved for x and y: a level with a root each side."""
    from mechgrade.errors import Location
    from mechgrade.solve.plan import Level

    def residual(x, y, r):
        return [[x ** 2 + y ** 2 - r ** 2], [x - 0.6 * r]]

    def jacobian(x, y, r):
        return [[2 * x, 2 * y], [1.0 + 0 * x, 0 * y]]

    def scale(x, y, r):
        return [[x ** 2 + y ** 2 + r ** 2], [abs(x) + 0.6 * abs(r)]]

    return Level(0, "position", residual, jacobian, scale, ("circle", "x given"),
                 (Location(), Location()), (), False, (frozenset(), frozenset()),
                 frozenset({0, 1}))


def test_every_start_of_every_instant_is_solved_to_its_own_root():
    import numpy as np

    from mechgrade.solve.levels import levenberg_marquardt

    level = _circle_level()
    # columns: y started above, below, on a circle too small for x (no root), x undefined
    X = np.array([[0.1, 0.1, 0.1, np.nan], [2.0, -2.0, 1.0, 1.0], [5.0, 5.0, 5.0, 5.0]])
    T = np.zeros((2, 4))
    T[1, 2] = 10.0  # the third column asks x - 0.6 r = 10: x = 13 > r
    active = np.ones(2, dtype=bool)
    out, cost, started, _ = levenberg_marquardt(level, X, [0, 1], [0, 1], active, T)
    assert started.tolist() == [True, True, True, False]
    assert out[:2, 0] == pytest.approx([3.0, 4.0], rel=1e-14)
    assert out[:2, 1] == pytest.approx([3.0, -4.0], rel=1e-14)
    assert cost[:2] == pytest.approx([0.0, 0.0], abs=1e-20) and cost[2] > 1.0
    assert np.isnan(out[0, 3])  # left as it came


def test_an_instant_solved_with_others_gets_the_root_it_gets_alone():
    import numpy as np

    from mechgrade.solve.levels import levenberg_marquardt

    level = _circle_level()
    X = np.array([[0.1, 0.2, 0.3], [2.0, -2.0, 0.5], [5.0, 7.0, 1.0]])
    active = np.ones(2, dtype=bool)
    together, _, _, _ = levenberg_marquardt(level, X, [0, 1], [0, 1], active, np.zeros((2, 3)))
    for j in range(3):
        alone, _, _, _ = levenberg_marquardt(level, X[:, [j]], [0, 1], [0, 1], active,
                                          np.zeros((2, 1)))
        assert alone[:, 0].tolist() == together[:, j].tolist()


def test_a_double_root_is_left_where_the_gradient_vanishes():
    """x² = 0 from x = 0.3 by Gauss-Newton's halvings: the root is only known to where the
    gradient 2x³ falls below the tolerance (a trust region stops there too), not to 1e-100."""
    import numpy as np

    from mechgrade.solve.levels import FIT_TOL, NEAR_DAMPING, Level, levenberg_marquardt

    level = Level(0, "position", lambda x: [[x ** 2]], lambda x: [[2 * x]], None, ("c",),
                  (), (), False, (), frozenset({0}))
    X, _, _, _ = levenberg_marquardt(level, np.array([[0.3]]), [0], [0], np.ones(1, bool),
                                  np.zeros((1, 1)), NEAR_DAMPING)
    x = float(X[0, 0])
    assert 2 * x ** 3 <= FIT_TOL < 2 * (2 * x) ** 3
    assert x > 1e-6


def _line_level():
    """x + 2 y = r, x - y = 0 (the state: x, y, r), solved for x and y: linear in them."""
    from mechgrade.errors import Location
    from mechgrade.solve.plan import Level

    return Level(0, "position", lambda x, y, r: [[x + 2 * y - r], [x - y]],
                 lambda x, y, r: [[1.0 + 0 * x, 2.0 + 0 * x], [1.0 + 0 * x, -1.0 + 0 * x]],
                 lambda x, y, r: [[abs(x) + 2 * abs(y) + abs(r)], [abs(x) + abs(y)]],
                 ("sum", "equal"), (Location(), Location()), (), False,
                 (frozenset({0, 1, 2}), frozenset({0, 1})), frozenset())


def test_a_level_linear_in_its_unknowns_reaches_the_root_levenberg_marquardt_reaches():
    import numpy as np

    from mechgrade.solve.levels import levenberg_marquardt, solve_level_columns

    level = _line_level()
    X = np.array([[0.1, 5.0], [0.2, -5.0], [3.0, 6.0]])
    active = np.ones(2, dtype=bool)
    fits = solve_level_columns(1e-9, level, X, [0, 1], [0, 1], active, np.zeros((2, 2)))
    stepped, _, _, _ = levenberg_marquardt(level, X, [0, 1], [0, 1], active, np.zeros((2, 2)))
    assert fits.X[:2] == pytest.approx(np.array([[1.0, 2.0], [1.0, 2.0]]), rel=1e-14)
    assert fits.X[:2] == pytest.approx(stepped[:2], rel=1e-12)
    assert fits.held.tolist() == [True, True] and fits.started.tolist() == [True, True]


def _crosswind_level():
    """a² + b² = v², a + w = 0 (the state: a, b, w, v), solved for a and b: with the wind w
    above the airspeed v there is no root, and b zigzags about 0 where the cost is least."""
    from mechgrade.errors import Location
    from mechgrade.solve.plan import Level

    return Level(1, "velocity", lambda a, b, w, v: [[a ** 2 + b ** 2 - v ** 2], [a + w]],
                 lambda a, b, w, v: [[2 * a, 2 * b], [1.0 + 0 * a, 0 * a]],
                 lambda a, b, w, v: [[a ** 2 + b ** 2 + v ** 2], [abs(a) + abs(w)]],
                 ("speed", "north"), (Location(), Location()), (), False,
                 (frozenset({0, 1, 3}), frozenset({0, 2})), frozenset({0, 1}))


def test_a_start_stopped_by_the_step_cap_is_no_root_though_its_residual_is_small():
    import numpy as np

    from mechgrade.solve.levels import holds, levenberg_marquardt, solve_level_columns

    level = _crosswind_level()
    X = np.array([[-60.0], [1.0], [66.7], [66.6667]])  # the wind 0.05 % above the airspeed
    active, T = np.ones(2, dtype=bool), np.zeros((2, 1))
    stepped, _, _, stopped = levenberg_marquardt(level, X, [0, 1], [0, 1], active, T)
    assert stopped.tolist() == [False]  # still zigzagging at the cap
    assert holds(5e-3, level, stepped, active, T).tolist() == [True]
    fits = solve_level_columns(5e-3, level, X, [0, 1], [0, 1], active, T)
    assert fits.started.tolist() == [True] and fits.held.tolist() == [False]


def test_one_solve_takes_no_start_the_step_cap_stopped_as_a_second_solution():
    """The wind misread 0.75 % above the airspeed: no root; the starts that settle end where
    the residual is least (b' = 0, within the default consistency), and one start still
    zigzagging at the cap is no second solution (main: 'the velocity equations have 2
    solutions that give different answers')."""
    import numpy as np

    from mechgrade.resources import shipped_dir
    from mechgrade.spec import load_problem

    problem = load_problem(shipped_dir("problems") / "airplane_crosswind_heading.yaml")
    p = kinematics_plan(problem)
    instant = solve_numeric(problem, p, instant_givens(problem, {"w'": 67.16769383594512}, {}),
                            {"heading"})
    assert float(np.degrees(instant.values["heading"][0])) == pytest.approx(90.0, abs=1e-5)


def test_a_root_whose_jacobian_loses_rank_has_the_rank_it_keeps():
    import numpy as np

    from mechgrade.solve.levels import level_rank

    level = _circle_level()
    # x = 0, y = 0: the circle's row vanishes; x undefined: no rank at all
    X = np.array([[3.0, 0.0, np.nan], [4.0, 0.0, 1.0], [5.0, 5.0, 5.0]])
    assert level_rank(level, X, [0, 1], [0, 1], np.ones(2, dtype=bool)).tolist() == [2, 1, 0]


@settings(max_examples=300, deadline=None)
@examples(st.integers(1, 3).flatmap(lambda size: st.lists(
    st.lists(st.floats(-1e3, 1e3), min_size=size, max_size=size), min_size=1, max_size=4)),
    st.sampled_from([1.0, 1e-4, 1e-8, 1e-11]))
def test_a_jacobian_vouched_independent_is_the_one_the_pivoted_qr_gives_full_rank(rows, lean):
    import numpy as np
    from scipy import linalg

    from mechgrade.solve import rules
    from mechgrade.solve.levels import _split_free, clearly_independent

    J = np.array(rows)
    J[:, -1] = lean * J[:, -1] + J[:, 0]  # nearly dependent columns as well as independent
    if not clearly_independent(J):
        return
    _, R, _ = linalg.qr(J, pivoting=True, mode="economic")
    assert int(rules.rank(np.diag(R))) == J.shape[1]
    unknown = [7, 3, 5][:J.shape[1]]
    assert _split_free(J, unknown) == (sorted(unknown), [])


def test_a_jacobian_with_dependent_columns_is_left_to_the_pivoted_qr():
    import numpy as np

    from mechgrade.solve.levels import _split_free, clearly_independent

    J = np.array([[1.0, 2.0], [2.0, 4.0 + 1e-12]])
    assert not clearly_independent(J)
    assert not clearly_independent(np.array([[1.0, 2.0]]))  # fewer rows than unknowns
    assert _split_free(J, [4, 9]) == ([9], [4])  # the QR's rank 1, its pivot the longer column


AIRPLANE = Path(__file__).resolve().parents[2] / "problems" / "airplane_crosswind_heading.yaml"


@pytest.mark.slow
def test_instants_solved_together_are_each_what_solve_numeric_gives_alone():
    import numpy as np

    from mechgrade.errors import MechgradeError
    from mechgrade.solve.instant import instant_givens
    from mechgrade.solve.numeric import solve_numeric, solve_numeric_columns
    from mechgrade.spec import load_problem

    problem = load_problem(AIRPLANE)
    p = kinematics_plan(problem)
    only = {"heading", "ground_speed"}
    # crosswinds the airplane can head into, and one faster than the airplane (no real
    # solution: the message names the residual left where the starts got nearest)
    overrides = [{"w'": 10.0}, {"w'": 100.0}, {"w'": 30.0}]
    givens = [instant_givens(problem, o, {}) for o in overrides]
    together = solve_numeric_columns(problem, p, givens, only)
    for given, instant in zip(givens, together):
        try:
            alone = solve_numeric(problem, p, given, only)
        except MechgradeError as err:
            assert isinstance(instant, type(err))
            assert re.sub(r"-?[\d.]+", "#", str(instant)) == re.sub(r"-?[\d.]+", "#", str(err))
            continue
        assert not isinstance(instant, MechgradeError)
        for oid in only:
            assert np.allclose(instant.values[oid], alone.values[oid], rtol=1e-12, atol=0)
    assert [type(i).__name__ for i in together] == ["Instant", "SolveError", "Instant"]
    assert "the velocity equations were not solved: 'due_north'" in str(together[1])


def test_instants_solved_together_are_refused_each_as_alone():
    # the tip's speed along A.y given beside theta': the velocity level over-determined,
    # held for theta' = 3 rad/s only
    problem = load_problem_text(BASE.replace(
        "  L: 2 m\n", "  L: 2 m\n  \"dot(vel(P, N), A.y)\": 6 m/s\n"), "p.yaml")
    p = kinematics_plan(problem)
    instants = [instant_givens(problem, {"theta'": w}, {}) for w in (3.0, 5.0)]
    fine, off = solve_numeric_columns(problem, p, instants, {"speed"})
    assert fine.values["speed"][0] == pytest.approx(6.0)
    with pytest.raises(InconsistentError) as alone:
        solve_numeric(problem, p, instants[1], {"speed"})
    assert isinstance(off, InconsistentError) and str(off) == str(alone.value)
    assert "the givens conflict at the velocity level" in str(off)


def test_the_freedoms_of_instants_solved_together_are_probed_each_as_alone():
    problem = load_problem_text(BASE.replace("  theta': 3 rad/s\n", ""), "p.yaml")
    p = kinematics_plan(problem)
    instants = [instant_givens(problem, {"theta": t}, {}) for t in (0.3, 0.6)]
    together = solve_numeric_columns(problem, p, instants, {"speed"})
    alone = [solve_numeric(problem, p, g, {"speed"}) for g in instants]
    assert [str(i.errors["speed"]) for i in together if isinstance(i, Instant)] == \
        [str(i.errors["speed"]) for i in alone]
    assert "give a value for theta' (velocity level)" in str(alone[1].errors["speed"])


@pytest.mark.parametrize("unknowns", [1, 2, 3])
@pytest.mark.parametrize("rows", [1, 2, 3, 4, 6])
def test_the_normal_equations_of_a_step_are_summed_as_for_columns_gathered_from_a_class(
        unknowns, rows):
    """A step's J'r and J'J have each column's bits whatever layout its Jacobian is kept in,
    those einsum gives columns gathered from a wider class (with one unknown it sums a
    column's rows in SIMD lanes there: in another layout the last bits differ)."""
    import numpy as np

    from mechgrade.solve.levels import _normal_equations

    rng = np.random.default_rng(rows * 10 + unknowns)
    wide, r_wide = (rng.standard_normal(shape) * 10.0 ** rng.integers(-8, 8, shape)
                    for shape in ((rows, unknowns, 400), (rows, 400)))
    at = np.arange(0, 400, 2)
    J, r = wide[:, :, at], r_wide[:, at]  # a step's live columns, as a class gathers them
    expected = (np.einsum("aki,ai->ki", J, r), np.einsum("aki,ali->kli", J, J))
    for layout in (J, np.ascontiguousarray(J), np.asfortranarray(J),
                   np.ascontiguousarray(J.transpose(1, 0, 2)).transpose(1, 0, 2)):
        for got, want in zip(_normal_equations(layout, np.ascontiguousarray(r)), expected):
            assert np.array_equal(got, want)
