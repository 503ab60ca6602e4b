"""Every problem in problems/ loads, solves and passes its expect: tests, and the solver agrees
with independent closed-form derivations of the same cases (tests/data/independent/)."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import pytest

from mechgrade.check import check_problem, equivalent
from mechgrade.solve import solve
from mechgrade.spec import load_problem

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = sorted((ROOT / "problems").glob("*.yaml"))


def _independent():
    """Case id -> function returning {objective id: value} from the independent derivations."""
    out = {}
    for name in ("bowling", "ruina", "dynamics", "bank"):
        path = ROOT / "tests" / "data" / "independent" / f"{name}.py"
        spec = importlib.util.spec_from_file_location(f"independent_{name}", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        cases = module.CASES
        if isinstance(cases, dict):
            out.update(cases)
        else:
            out.update({f.__name__: f for f in cases})
    return out


INDEPENDENT = _independent()


def test_the_library_covers_every_independently_derived_case():
    assert sorted(p.stem for p in PROBLEMS) == sorted(INDEPENDENT)


def test_every_heavy_problem_is_in_the_library_and_the_fast_core_keeps_some(
        heavy_problem_names):
    assert heavy_problem_names <= {p.stem for p in PROBLEMS}
    assert len(heavy_problem_names) < len(PROBLEMS) / 2


@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_problem_passes_its_expect_tests_with_no_author_warnings(path):
    report = check_problem(path)
    assert report.error is None, report.error
    failing = [o.message for o in report.outcomes if not o.passed]
    assert not failing
    assert report.passed and report.warnings == ()
    assert not report.untested, f"objectives without expect: {report.untested}"


@pytest.mark.parametrize("path", PROBLEMS, ids=[p.stem for p in PROBLEMS])
def test_solver_agrees_with_the_independent_derivation(path):
    problem = load_problem(path)
    solution = solve(problem)
    reference = INDEPENDENT[problem.id]()
    assert sorted(reference) == sorted(o.id for o in problem.objectives)
    for result in solution.results:
        expected = reference[result.id]
        if result.kind == "symbolic":
            assert equivalent(result.expr, str(expected), result.symbols), result.id
        elif result.kind == "vector":
            padded = list(expected) + [0.0] * (3 - len(expected))
            size = math.hypot(*padded)
            for got, want in zip(result.value, padded):
                assert got == pytest.approx(want, rel=1e-6, abs=1e-9 + 1e-7 * size), result.id
        else:
            assert result.value == pytest.approx(expected, rel=1e-6, abs=1e-9), result.id
