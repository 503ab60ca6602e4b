"""Many variants solved together give what solving each alone gives: answers, generated
mistakes with their messages, solved state, freedoms, warnings and errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechgrade.errors import MechgradeError
from mechgrade.grade.variants import draw_variant
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.solve.batch import _template, solve_variants
from mechgrade.spec import load_problem

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = shipped_dir("problems")


def alone(problem, variants):
    out = []
    for givens in variants:
        try:
            out.append(solve(problem, givens=givens))
        except MechgradeError as err:
            out.append(err)
    return out


def close(a, b) -> bool:
    if a is None or b is None:
        return a is b
    return bool(np.allclose(np.atleast_1d(a), np.atleast_1d(b), rtol=1e-8, atol=1e-10))


def assert_same(together, one):
    if isinstance(one, MechgradeError):
        assert type(together) is type(one) and str(together) == str(one)
        return
    assert [r.id for r in together.results] == [r.id for r in one.results]
    for a, b in zip(together.results, one.results):
        assert (a.expr, a.symbols, a.unit, a.plausible) == (b.expr, b.symbols, b.unit, b.plausible)
        assert close(a.value, b.value), a.id
        assert [(m.message, m.credit) for m in a.mistakes] == \
            [(m.message, m.credit) for m in b.mistakes]
        assert all(close(x.value, y.value) for x, y in zip(a.mistakes, b.mistakes))
        assert [(m.code, m.message, m.expr) for m in a.generated_mistakes] == \
            [(m.code, m.message, m.expr) for m in b.generated_mistakes], a.id
        assert all(close(x.value, y.value) for x, y in
                   zip(a.generated_mistakes, b.generated_mistakes)), a.id
    assert [f.id for f in together.failures] == [f.id for f in one.failures]
    assert [w.message for w in together.warnings] == [w.message for w in one.warnings]
    assert together.dof == one.dof
    assert [(s.name, s.unit, s.given) for s in together.state] == \
        [(s.name, s.unit, s.given) for s in one.state]
    assert close([s.si for s in together.state], [s.si for s in one.state])


def scaled(problem, keys, count=6):
    """Variants that scale the givens ``keys`` by 0.8 to 1.2."""
    si = {k: g.si for g in problem.givens for k in keys if str(g.key.text).strip() == k}
    return [{k: v * (0.8 + 0.4 * ((3 * n + i) % 7) / 6) for i, (k, v) in enumerate(si.items())}
            for n in range(count)]


@pytest.mark.parametrize("name, keys", [
    ("bowling_3_15_4_pendulum", ["L", "theta'"]),        # linear levels
    ("ruina_10_2_limacon", ["b", "theta'"]),                  # a non-linear level from guesses
    ("bowling_3_15_6_gears", ["teeth_A", "dot(angacc(B, N), N.z)"]),  # free unknowns
    ("pendulum_pin_reaction", ["L", "m"]),               # dynamics at an instant
    ("rod_strikes_ledge", ["L", "v0", "e"]),             # an impact
])
def test_variants_solved_together_are_the_variants_solved_alone(name, keys):
    problem = load_problem(PROBLEMS / f"{name}.yaml")
    variants = scaled(problem, keys)
    assert variants and variants[0]
    assert _template(problem) is not None
    for together, one in zip(solve_variants(problem, variants), alone(problem, variants)):
        assert_same(together, one)


def test_a_problem_with_symbolic_objectives_only_is_solved_together():
    problem = load_problem(PROBLEMS / "ruina_sec10_bug_on_tire.yaml")
    assert _template(problem) is not None
    together, = solve_variants(problem, [{}])
    assert_same(together, solve(problem))


def test_drawn_variants_solved_together_are_the_drawn_variants_solved_alone():
    problem = load_problem(shipped_dir("examples") / "hw2_variants" / "pendulum_variants.yaml")
    variants = [dict(draw_variant(problem, "s", str(n)).overrides) for n in range(12)]
    for together, one in zip(solve_variants(problem, variants), alone(problem, variants)):
        assert_same(together, one)


def test_a_degenerate_variant_warns_as_when_solved_alone():
    problem = load_problem(ROOT / "tests" / "data" / "variants" / "degenerate_range.yaml")
    variants = [{"theta": np.pi / 2}, {"theta": np.pi / 6, "a": 0.25}]
    together = solve_variants(problem, variants)
    assert any("degenerate configuration" in w.message for w in together[0].warnings)
    for a, b in zip(together, alone(problem, variants)):
        assert_same(a, b)


def test_a_variant_with_givens_the_reference_lacks_or_removes_is_solved_alone():
    problem = load_problem(PROBLEMS / "bowling_3_15_4_pendulum.yaml")
    variants = [{"theta'": None}, {"L": 0.7, "no_such_given": 1.0}, {"L": 0.7}]
    together = solve_variants(problem, variants)
    for a, b in zip(together, alone(problem, variants)):
        assert_same(a, b)


def test_a_variant_whose_givens_conflict_fails_as_when_solved_alone():
    problem = load_problem(PROBLEMS / "bowling_3_15_8_connected_blocks.yaml")
    variants = [{"L": 0.2}]  # the rod no longer fits the positions given: they conflict
    together, = solve_variants(problem, variants)
    one, = alone(problem, variants)
    assert together.failures and "conflict" in str(together.failures[0].error)
    assert [str(f.error) for f in together.failures] == [str(f.error) for f in one.failures]
    assert_same(together, one)
