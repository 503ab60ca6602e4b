"""Equations of motion written as equations (mechgrade.grade.equations)."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechgrade.grade.equations import judge_equations, read_equations
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.solve.derivation import motion_samples
from mechgrade.spec import load_problem


def _samples(name: str):
    problem = load_problem(shipped_dir("problems") / f"{name}.yaml")
    return motion_samples(problem, solve(problem))


@pytest.fixture(scope="module")
def incline():
    return _samples("block_sliding_down_incline")


@pytest.fixture(scope="module")
def pendulum():
    return _samples("pendulum_pin_reaction")


@pytest.fixture(scope="module")
def atwood():
    return _samples("atwood_machine")


# the incline's two balances, along the slope and across it, as terms (text, sign)
ALONG = [("m x''", -1), ("m g sin(β)", 1), ("μ_k N", -1)]
LOADS = [None, "the weight of block", "the kinetic friction F_P on block"]
"""The load each term of ALONG is of (``None``: the inertia term is no load)."""
ACROSS = [("N", 1), ("m g cos(β)", -1)]


def _equation(terms, scale: int) -> str:
    """``sum(sign * term) = 0`` written with the negative terms moved to the right side and
    every term scaled."""
    left = [f"({scale})*({t})" for t, sign in terms if sign > 0] or ["0"]
    right = [f"({scale})*({t})" for t, sign in terms if sign < 0] or ["0"]
    return " + ".join(left) + " = " + " + ".join(right)


@settings(max_examples=15, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(a=st.integers(1, 5), b=st.sampled_from([-3, -1, 2, 7]), combine=st.booleans(),
       dropped=st.integers(0, len(ALONG) - 1))
def test_rearranged_scaled_and_combined_equations_are_right_a_dropped_term_is_named(
        incline, a, b, combine, dropped):
    along = _equation(ALONG, a)
    across = _equation(ACROSS, b)
    if combine:  # the second equation replaced by the sum of both
        across = _equation([(f"{a}*({t})", s) for t, s in ALONG]
                           + [(f"({b})*({t})", s) for t, s in ACROSS], 1)
    assert judge_equations(f"{along}; {across}", incline).verdict == "correct"
    wrong = _equation([term for n, term in enumerate(ALONG) if n != dropped], a)
    judged = judge_equations(f"{wrong}; {_equation(ACROSS, b)}", incline)
    assert [row.right for row in judged.rows] == [False, True], judged.assessment.feedback
    # the load the dropped term was is named, whatever the equation's scale
    assert judged.rows[0].load == LOADS[dropped], judged.assessment.feedback
    assert judged.rows[0].load_mistake == ("missing" if LOADS[dropped] else None)
    turned = _equation([(t, -sign if n == dropped else sign) for n, (t, sign) in enumerate(ALONG)],
                       a)
    (row, _) = judge_equations(f"{turned}; {_equation(ACROSS, b)}", incline).rows
    assert (row.load, row.load_mistake) == ((LOADS[dropped], "turned round") if LOADS[dropped]
                                            else (None, None)), row.feedback


def test_a_pendulums_moment_equation_and_its_sign(pendulum):
    assert judge_equations("m L^2/3 θ'' = -m g L/2 sin(θ)", pendulum).verdict == "correct"
    assert judge_equations("θ'' = -3 g sin(θ)/(2 L)", pendulum).verdict == "correct"
    for wrong in ("m L^2/3 θ'' = m g L/2 sin(θ)", "m L^2/12 θ'' = -m g L/2 sin(θ)",
                  "m L^2/3 θ'' = -m g L/2 cos(θ)"):
        assert judge_equations(wrong, pendulum).verdict == "incorrect", wrong


def test_an_equation_naming_an_unknown_alone_says_nothing(pendulum):
    judged = judge_equations("Ox = 0", pendulum)
    assert judged.verdict == "incorrect"
    assert "says nothing about the motion" in judged.assessment.feedback


def test_without_a_solved_state_equations_are_not_evaluated():
    assert judge_equations("x'' = 0", None).verdict == "not_evaluated"
    assert judge_equations(None, None).verdict == "missing"


def test_too_many_equations_or_unknowns_are_refused(incline):
    with pytest.raises(Exception, match="at most 12 equations"):
        read_equations("; ".join(["x'' = 0"] * 13), incline)
    with pytest.raises(Exception, match="at most 12 unknowns"):
        read_equations(" + ".join(f"U{n}" for n in range(13)) + " = m x''", incline)
    with pytest.raises(Exception, match="names of your own"):
        read_equations("m z'' = 0", incline)


@pytest.mark.parametrize("text, term", [
    ("m x'' = m g sin(β) + μ_k N; N = m g cos(β)", "mu_k*N"),  # friction drawn downhill
    ("m x'' = -m g sin(β) - μ_k N; N = m g cos(β)", "-m*g*sin(beta)"),
    ("m x'' = m g sin(β) + μ_k m g cos(β)", "mu_k*m*g*cos(beta)"),
    ("m x'' = m g sin(β); N = m g cos(β)", None),  # a term dropped: no term to turn
    ("m x'' = m g sin(β) - μ_k N; N = -m g cos(β)", None),  # N or m g cos β: either
])
def test_a_wrong_equations_one_term_of_the_wrong_sign_is_named(incline, text, term):
    judged = judge_equations(text, incline)
    (wrong,) = [row for row in judged.rows if not row.right]
    assert wrong.reversed_term == term
    assert ("has the wrong sign" in wrong.feedback) == (term is not None)


def test_of_two_terms_either_could_have_the_wrong_sign_so_neither_is_named(pendulum):
    (row,) = judge_equations("m L^2/3 θ'' = m g L/2 sin(θ)", pendulum).rows
    assert not row.right and row.reversed_term is None


@pytest.mark.parametrize("text, load, how", [
    ("x'' = g sin(β)", "the kinetic friction F_P on block", "missing"),  # divided by m
    ("m x'' = -μ_k N; N = m g cos(β)", "the weight of block", "missing"),
    ("m x'' = m g sin(β) - μ_k m g", None, None),  # a term of the wrong size names no load
    ("N = m g; m x'' = m g sin(β) - μ_k N", None, None),
    # N along the slope: the normal force's or the weight's component across it, twice
    ("m x'' = m g sin(β) - μ_k N + 2 N; N = m g cos(β)", None, None),
])
def test_a_wrong_equation_names_the_load_it_leaves_out_or_none_when_no_one_load_fits(
        incline, text, load, how):
    (wrong,) = [row for row in judge_equations(text, incline).rows if not row.right]
    assert (wrong.load, wrong.load_mistake) == (load, how), wrong.feedback
    assert ((f"({load} is {how} from it)" if how == "missing" else "") in wrong.feedback)


@pytest.mark.parametrize("text, feedback", [
    ("m1 y'' = T; m2 y'' = m2 g - T",
     "m1*ydd = T: does not hold for the motion (the weight of block1 is missing from it)."),
    # the rope's tension acts on both blocks: the one whose balance has block 2's weight
    ("m1 y'' = T - m1 g; m2 y'' = m2 g + T",
     "m2*ydd = m2*g+T: does not hold for the motion (its term T has the wrong sign: the "
     "tension T on block2 is turned round in it)."),
    ("m1 y'' = T - m1 g; m2 y'' = m2 g",
     "m2*ydd = m2*g: does not hold for the motion (the tension T on block2 is missing from "
     "it)."),
])
def test_of_a_load_on_two_bodies_the_one_the_equation_is_about_is_named(atwood, text, feedback):
    assert judge_equations(text, atwood).assessment.feedback == feedback


@pytest.mark.parametrize("text, said", [
    ("m L^2/3 θ'' = 0", "(the weight of rod is missing from it)"),
    # either side's sign: no term is named, but the weight's moment is twice the misfit
    ("m L^2/3 θ'' = m g L/2 sin(θ)", "(the weight of rod is turned round in it)"),
])
def test_a_moment_equation_names_the_load_whose_moment_it_leaves_out(pendulum, text, said):
    assert judge_equations(text, pendulum).assessment.feedback.endswith(said + ".")


@pytest.mark.parametrize("text, feedback", [
    # block 2's loads (down positive) with block 1's mass
    ("m1 y'' = T - m1 g; m1 y'' = m2 g - T",
     "m1*ydd = m2*g-T: does not hold for the motion (the wrong body: the loads on block2 "
     "balanced against the m a of block1)."),
    ("m1 y'' = T - m1 g; m2 y'' = m1 g - T",
     "m2*ydd = m1*g-T: does not hold for the motion (the wrong body: the loads on block1 "
     "balanced against the m a of block2)."),
])
def test_an_equation_balancing_one_bodys_loads_against_anothers_motion_is_named(
        atwood, text, feedback):
    judged = judge_equations(text, atwood)
    assert judged.assessment.feedback == feedback
    assert judged.assessment.diagnosis == "an equation for " + feedback.split("(", 1)[1][:-2]


def test_a_moment_balance_about_the_pin_with_the_inertia_about_g_is_the_wrong_point(pendulum):
    (row,) = judge_equations("m L^2/12 θ'' = -m g L/2 sin(θ)", pendulum).rows
    assert row.balance == ("the wrong point: the moments about O balanced against the rate of "
                           "angular momentum about G")
    assert (row.load, row.reversed_term) == (None, None)


@pytest.mark.parametrize("text", [
    "m1 y'' = T - m1 g; m2 y'' = m2 g - T",  # right: nothing to name
    "m1 y'' = T; m2 y'' = m2 g - T",  # a load left out is no other body's balance
    "m1 y'' = T - m1 g; m2 y'' = 2 m2 g - T",  # nor is a load doubled
])
def test_an_equation_that_is_no_misplaced_balance_names_none(atwood, text):
    assert all(row.balance is None for row in judge_equations(text, atwood).rows)
