"""An objective asked ``when: lhs = rhs`` under work_energy: the first position the motion from
the start reaches where the equation holds, numeric and in closed form, or a located refusal.
Each problem here is derived afresh (seconds each): the slow checks."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mechgrade.errors import SolveError
from mechgrade.solve import solve
from mechgrade.solve.instant import _instants, instant_givens
from mechgrade.solve.dynamics import when_residual
from mechgrade.solve.positions import position_symbolic, position_where
from mechgrade.spec import load_problem, load_problem_text

ROOT = Path(__file__).resolve().parents[2]
LADDER = ROOT / "problems" / "ruina_9_20_ladder_energy.yaml"
WALL = "when: dot(force(N1), N.x) = 0\n"


@pytest.fixture(scope="module")
def ladder():
    return load_problem(LADDER)


def _asked(text: str, when: str):
    """The 9.20 ladder with its objectives asked at another position."""
    return load_problem_text(text.replace(WALL, f"when: {when}\n"), "p.yaml")


def test_objectives_asked_when_are_grouped_apart_before_the_problems_own_instant(ladder):
    groups = _instants(ladder)
    asked = [[o.id for o in objectives] for _, objectives in groups]
    assert asked == [["theta_wall_lost", "theta_wall_lost_deg", "vG_wall_lost"],
                     ["vG_over_sqrt_gL", "eom_thetaddot", "vG_symbolic", "N1_wall"]]


@pytest.mark.slow
@pytest.mark.parametrize("release_deg", [60.0, 80.0, 89.0])
def test_the_wall_lets_go_where_the_closed_form_says_for_any_release(ladder, release_deg):
    givens = instant_givens(ladder, {"theta0": math.radians(release_deg)}, {})
    residual = when_residual(ladder, "theta_wall_lost", givens)
    found = position_where(ladder, "theta_wall_lost_deg", givens, residual)
    assert found == pytest.approx(math.asin(2 / 3 * math.sin(math.radians(release_deg))),
                                  rel=1e-12)
    assert str(position_symbolic(ladder, "theta_wall_lost", tuple(givens.items()),
                                 residual)) == "asin(2*sin(theta0)/3)"


@pytest.mark.slow
def test_the_solution_keeps_the_problems_own_instant_as_its_state(ladder):
    solution = solve(ladder)
    assert solution.result("theta_wall_lost_deg").value == pytest.approx(41.0364105, rel=1e-8)
    theta = next(v for v in solution.state if v.name == "theta")
    assert (theta.value, theta.unit) == (pytest.approx(45.0), "deg")


@pytest.mark.slow
def test_a_position_the_motion_never_reaches_is_refused_with_the_range_searched():
    problem = _asked(LADDER.read_text(), "dot(force(N1), N.x) = 10*m*g")
    with pytest.raises(SolveError) as info:
        givens = instant_givens(problem, None, {})
        position_where(problem, "theta_wall_lost_deg", givens,
                       when_residual(problem, "theta_wall_lost_deg", givens))
    assert str(info.value) == (
        "p.yaml:81:11: objectives[5].when: objective 'theta_wall_lost_deg': "
        "'dot(force(N1), N.x) = 10*m*g' does not hold anywhere the motion from the start "
        "reaches (searched theta from 1.39626 rad to -4.88692 rad, one turn); check the "
        "equation, 'from' and 'sense'")


@pytest.mark.slow
def test_a_position_without_a_quick_closed_form_is_refused_naming_where_it_is():
    problem = _asked(LADDER.read_text(), "dot(force(N1), N.x) = m*g/10")
    solution = solve(problem, objectives=["theta_wall_lost", "theta_wall_lost_deg"])
    assert solution.result("theta_wall_lost_deg").value == pytest.approx(46.1076447, rel=1e-8)
    (failure,) = solution.failures
    assert str(failure.error) == (
        "p.yaml:73:11: objectives[4].when: objective 'theta_wall_lost': 'dot(force(N1), N.x) "
        "= m*g/10' holds at theta = 0.80473 rad, but sympy finds no closed form for that "
        "position; ask for it as a scalar")


@pytest.mark.slow
def test_a_position_past_a_lost_contact_is_refused_as_the_contact_lost():
    problem = _asked(LADDER.read_text(), "speed(G, N) = sqrt(g*L)/2")
    with pytest.raises(SolveError) as info:
        solve(problem, objectives=["theta_wall_lost_deg"])
    assert "contact lost at A: the normal force 'N1' would be -0.008644 N" in str(info.value)


@pytest.mark.slow
def test_the_write_up_says_where_an_objective_asked_when_is_read(ladder):
    from mechgrade.mechanics.dynamics import kinetics_derivation

    (lines,) = [lines for title, lines in kinetics_derivation(ladder)
                if title == "Objectives in the model's quantities"]
    assert "theta_wall_lost_deg: theta = theta, at the first position from the start where " \
        "dot(force(N1), N.x) = 0 (the rate from the energy balance)" in lines
    assert lines[0] == "vG_over_sqrt_gL: speed(G, N)/sqrt(g*L) = " \
        "sqrt(L**2*thetad**2*sin(theta)**2/4 + L**2*thetad**2*cos(theta)**2/4)/(sqrt(L)*sqrt(g))"


@pytest.mark.slow
def test_a_release_past_the_vertical_leaves_the_wall_at_its_own_root_in_a_class(ladder,
                                                                                forget):
    # from 80 deg the wall lets go at asin(2 sin(theta0)/3); from 95 deg the ladder first
    # passes the vertical, where cos(theta) = 0: a root of its own, mistakes and all
    from mechgrade.solve.batch import solve_variants

    past = {"theta0": math.radians(95.0)}
    forget()  # nothing kept from earlier tests: the class as a fresh process solves it
    together = solve_variants(ladder, [{"theta0": math.radians(80.0)}, past])
    answers = [s.result("theta_wall_lost") for s in together]
    assert [a.expr for a in answers] == ["asin(2*sin(theta0)/3)", "pi/2"]
    assert answers[0].generated_mistakes is not None  # worked out in the class's order
    forget()  # alone, as a fresh process solves it
    alone = solve(ladder, givens=past).result("theta_wall_lost")
    assert answers[1].generated_mistakes == alone.generated_mistakes
