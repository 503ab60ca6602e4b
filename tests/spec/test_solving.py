"""The solving sections of a spec: unknown:, branch:, define:, givens as expressions."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.errors import SpecError
from mechgrade.spec import load_problem_text
from mechgrade.spec.model import Root

BASE = (Path(__file__).resolve().parents[1] / "data" / "spec" / "base.yaml").read_text()


def with_rate(value: str, extra: str = "") -> str:
    return BASE.replace("  theta': 3 rad/s\n", f"  theta': {value}\n  v: 8 m/s\n").replace(
        "  L: m\n", "  L: m\n  v: m/s\n") + extra


def test_a_given_may_be_an_expression_of_other_givens():
    problem = load_problem_text(with_rate("v/L"), "p.yaml")
    rate = next(g for g in problem.givens if g.key.text == "theta'")
    assert (rate.si, rate.unit, rate.text) == (4.0, "rad/s", "v/L")


def test_unknown_branch_and_define_are_read():
    text = BASE.replace("objectives:\n", "unknown: [t]\nbranch: {t: first positive}\n"
                        "define: {r: \"pos(P, O)\"}\nobjectives:\n")
    problem = load_problem_text(text, "p.yaml")
    assert [u.text for u in problem.unknowns] == ["t"]
    assert problem.branches[0].root is Root.FIRST_POSITIVE
    assert problem.definitions[0].name == "r"


@pytest.mark.parametrize("text, message", [
    (with_rate("v*L"), "p.yaml:17:11: givens.theta': expected 'v*L' to have the dimension of "
                       "rad/s (the unit of 'theta''), found m ** 2 / s"),
    (with_rate("v/L").replace("v: 8 m/s", "v: L*theta'"),
     "p.yaml:17:11: givens.theta': the givens theta', v are defined in terms of each other; "
     "expected a value for at least one"),
    (with_rate("atan2(v, L)"), "p.yaml:17:11: givens.theta': expected arithmetic of givens and "
                               "abs, acos, asin, atan, cos, cosh, exp, log, sin, sinh, sqrt, tan, "
                               "tanh in a "
                               "given's value, found atan2()"),
    (with_rate("3 rad/s", "") .replace("  v: 8 m/s\n", "  v: 8 m/s\n  dot(vel(P, N), A.y): v\n"),
     "p.yaml:19:24: givens.dot(vel(P, N), A.y): expected a number with a unit for a given "
     "that is an expression; only coordinates, rates, parameters and t may be given as "
     "expressions of other givens"),
    (BASE.replace("objectives:\n", "unknown: [theta]\nobjectives:\n"),
     "p.yaml:18:11: unknown[0]: expected a parameter or t to solve for, found 'theta' "
     "(coordinates that are not given are always solved for)"),
    (BASE.replace("objectives:\n", "unknown: [L]\nobjectives:\n"),
     "p.yaml:18:11: unknown[0]: 'L' is both given and unknown; expected one of them"),
    (BASE.replace("objectives:\n", "branch: {L: positive}\nobjectives:\n"),
     "p.yaml:18:13: branch.L: expected a coordinate, a rate (theta') or a quantity listed "
     "under unknown: as a branch, found 'L'"),
    (BASE.replace("objectives:\n", "branch: {t: sideways}\nobjectives:\n"),
     "p.yaml:18:13: branch.t: expected one of positive, negative, first positive, found "
     "'sideways'"),
    (BASE.replace("objectives:\n", "define: {L: 3}\nobjectives:\n"),
     "p.yaml:18:13: define.L: 'L' is already a name of the problem or of the language; "
     "expected another name for the definition"),
])
def test_bad_solving_sections_give_located_messages(text, message):
    with pytest.raises(SpecError) as info:
        load_problem_text(text, "p.yaml")
    assert str(info.value) == message


def test_a_changed_given_is_carried_into_the_givens_stated_from_it():
    from mechgrade.spec.solving import carried
    problem = load_problem_text(with_rate("v/L"), "p.yaml")
    stated = {g.key.text: g for g in problem.givens}
    # theta' = v/L: with v misread the rate follows; givens stated from nothing changed stay
    assert carried(stated, {"v": 16.0}) == {"theta'": pytest.approx(2 * stated["theta'"].si)}
    assert carried(stated, {"L": stated["L"].si}) == {"theta'": pytest.approx(stated["theta'"].si)}
    assert carried(stated, {"theta": 0.1}) == {}


def test_a_given_left_undefined_by_a_change_is_refused():
    from mechgrade.spec.solving import carried
    problem = load_problem_text(with_rate("sqrt(v*v*L)/(L*sqrt(L))"), "p.yaml")
    stated = {g.key.text: g for g in problem.givens}
    with pytest.raises(SpecError, match=r"cannot evaluate .* with L changed"):
        carried(stated, {"L": -1.0})
