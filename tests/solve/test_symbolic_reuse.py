"""A symbolic answer is derived again only when a given it can depend on changes: its value
where the given stands in for a symbol (a pure number or an angle), or whether it is zero."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import mechgrade.solve.instant as instant
from mechgrade.errors import SolveError
from mechgrade.solve import solve
from mechgrade.solve.batch import solve_variants
from mechgrade.spec import load_problem_text

ROOT = Path(__file__).resolve().parents[2]
BASE = (ROOT / "tests" / "data" / "spec" / "base.yaml").read_text()
VX = ("  - {id: vx, prompt: x-velocity of the tip., find: \"dot(vel(P, N), N.x)\", "
      "kind: symbolic, unit: m/s, symbols: [L, thetad]}\n")


def _counted(monkeypatch, module) -> list[str]:
    """The objectives ``module._symbolic_result`` derives with sympy, one entry a call."""
    calls = []
    derive = module._symbolic_result

    def counted(*args):
        calls.append(args[1])
        return derive(*args)
    instant._symbolic_answer.cache_clear()
    derive.cache_clear()
    monkeypatch.setattr(module, "_symbolic_result", counted)
    return calls


@pytest.fixture
def derivations(monkeypatch):
    """How many times the symbolic answer is derived with sympy."""
    return _counted(monkeypatch, instant)


def test_a_given_with_a_unit_changed_reuses_the_answer(derivations):
    problem = load_problem_text(BASE + VX, "p.yaml")
    answers = {solve(problem, givens={"L": L}).result("vx").expr for L in (0.5, 1.0, 3.0)}
    assert answers == {"-L*thetad/2"} and derivations == ["vx"]


def test_an_angle_that_stands_in_for_a_symbol_changed_gives_its_own_answer(derivations):
    problem = load_problem_text(BASE + VX, "p.yaml")
    answers = [s.result("vx").expr for s in
               solve_variants(problem, [{"theta": math.pi / 6}, {"theta": math.pi / 2},
                                        {"theta": math.pi / 6, "L": 3.0}])]
    assert answers == ["-L*thetad/2", "-L*thetad", "-L*thetad/2"]
    assert derivations == ["vx", "vx"]


def test_a_given_made_zero_gives_its_own_answer(derivations):
    # theta' has a unit and is not among the symbols: only a zero may stand in for it
    problem = load_problem_text(BASE + VX.replace("[L, thetad]", "[L, theta]"), "p.yaml")
    assert solve(problem, givens={"theta'": 0.0}).result("vx").expr == "0"
    for rate in (3.0, 5.0):
        with pytest.raises(SolveError, match="depends on thetad"):
            solve(problem, givens={"theta'": rate}).result("vx")


def test_an_angle_that_does_not_reach_an_answer_is_not_simplified_again(monkeypatch):
    # theta0 never reaches the path radius L/2: were it derived again for a new theta0,
    # its expressions would be the same, and simplifying them is not done again
    import sympy as sp

    import mechgrade.solve.symbolic as symbolic
    from mechgrade.resources import shipped_dir
    from mechgrade.spec import load_problem

    problem = load_problem(shipped_dir("problems") / "ruina_9_19_falling_ladder.yaml")
    simplified = []
    simplify = sp.simplify

    def counted(expr, *args, **kwargs):
        simplified.append(expr)
        return simplify(expr, *args, **kwargs)
    monkeypatch.setattr(sp, "simplify", counted)
    first = solve(problem, givens={"theta0": math.radians(70.0)}, objectives=["G_path_radius"])
    before = len(simplified)
    second = solve(problem, givens={"theta0": math.radians(80.0)}, objectives=["G_path_radius"])
    assert first.result("G_path_radius").expr == second.result("G_path_radius").expr == "L/2"
    assert before > 0 and len(simplified) == before
    assert symbolic._simplify.cache_info().hits > 0


LADDER = (ROOT / "problems" / "ruina_9_19_falling_ladder.yaml").read_text()


@pytest.fixture
def kinetic_derivations(monkeypatch):
    """How many times a dynamics problem's symbolic answer is derived with sympy."""
    import mechgrade.solve.dynamics as dynamics

    return _counted(monkeypatch, dynamics)


def test_a_release_angle_the_energy_integral_does_not_bring_in_reuses_the_answer(
        kinetic_derivations):
    # theta0 is the work-energy start; the eom and the path radius never read the rate the
    # energy integral gives, so a new theta0 changes nothing in them
    problem = load_problem_text(LADDER, "ladder.yaml")
    asked = ["eom_thetaddot", "G_path_radius"]
    answers = {tuple(s.result(oid).expr for oid in asked) for s in solve_variants(
        problem, [{"theta0": math.radians(deg)} for deg in (70.0, 75.0, 80.0)])}
    assert answers == {("-3*g*cos(theta)/(2*L)", "L/2")}
    assert [kinetic_derivations.count(oid) for oid in asked] == [1, 1]


def test_a_release_angle_that_reaches_an_answer_through_the_energy_integral_gives_its_own(
        kinetic_derivations):
    # theta0 not among the symbols: the angle stands in for it, through the energy integral
    declared = ("    symbols: [g, L, theta, theta0]\n"
                "    expect: {expr: -sqrt(3)*sqrt(g)*sqrt(sin(theta0) - sin(theta))/sqrt(L)}\n")
    assert declared in LADDER
    problem = load_problem_text(LADDER.replace(declared, "    symbols: [g, L, theta]\n"),
                                "ladder.yaml")
    answers = [s.result("thetadot_of_theta").expr for s in solve_variants(
        problem, [{"theta0": math.radians(deg)} for deg in (70.0, 80.0)])]
    assert len(set(answers)) == 2 and "theta0" not in answers[0]
    assert kinetic_derivations.count("thetadot_of_theta") == 2
