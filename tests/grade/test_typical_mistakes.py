"""Every typical mistake of the library's problems gets its own diagnosis, and no correct
answer gets one.

The mistakes and their values are in tests/data/mistakes/<problem>.yaml, written by an
independent numpy script (typical.py beside them), never by the mistake generator.
"""

from __future__ import annotations

import importlib.util
from functools import lru_cache
from pathlib import Path

import pytest
import yaml

from mechgrade.grade.compare import assess

from mechgrade.grade.policy import GradingPolicy
from mechgrade.solve import solve
from mechgrade.solve.mutants import separating_rel
from library import library_problem

ROOT = Path(__file__).resolve().parents[2]
TABLES = ROOT / "tests" / "data" / "mistakes"
PROBLEMS = sorted((ROOT / "problems").glob("*.yaml"))


def _module(name: str):
    spec = importlib.util.spec_from_file_location(f"mistakes_{name}", TABLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


MEASURE = _module("measure")
ROWS = [(path.stem, i, row) for path in sorted(TABLES.glob("*.yaml"))
        for i, row in enumerate(yaml.safe_load(path.read_text(encoding="utf-8")))]


@lru_cache(maxsize=None)
def _solution(problem: str):
    return solve(library_problem(problem))


def _result(problem: str, objective: str):
    return _solution(problem).result(objective)


def test_every_problem_has_at_least_three_typical_mistakes():
    counts = {p.stem: 0 for p in PROBLEMS}
    for problem, _, _row in ROWS:
        counts[problem] += 1  # named or not yet: how many are named is measure.py's figure
    for path in (ROOT / "tests" / "data" / "heldout").glob("*.yaml"):  # the held-out problems
        counts[path.stem] += len(yaml.safe_load(path.read_text(encoding="utf-8")))
    assert min(counts.values()) >= 3, counts


def test_the_tables_are_what_the_independent_script_computes():
    tables = _module("typical").tables()
    for path in TABLES.glob("*.yaml"):
        assert yaml.safe_load(path.read_text(encoding="utf-8")) == tables[path.stem], path.name


@pytest.mark.parametrize("problem,index,row", ROWS,
                         ids=[f"{p}.{r['objective']}.{i}" for p, i, r in ROWS])
def test_a_typical_mistake_gets_its_own_diagnosis(problem, index, row):
    result = _result(problem, row["objective"])
    policy = GradingPolicy()
    if row.get("inside"):
        # inside the default tolerance it is graded right, as check warns; the separating
        # tolerance (when one exists) names it
        assert assess(row["answer"], result).verdict == "correct"
        if separating_rel(result) is None:
            return
        policy = GradingPolicy(separate_mistakes=True)
    kind, judged = MEASURE.classify(row, result, policy)
    if row.get("known"):
        # a mistake the grader does not name yet: it must at least not name another one
        assert kind == row["known"], judged
        return
    assert kind == "named", judged
    assert not judged.feedback.startswith("Not within")


NUMERIC = [(p.stem, o.id) for p in PROBLEMS for o in library_problem(p.stem).objectives
           if o.kind != "symbolic"]


@pytest.mark.parametrize("problem,objective", NUMERIC, ids=[f"{p}.{o}" for p, o in NUMERIC])
def test_a_correct_answer_in_any_notation_gets_no_diagnosis(problem, objective):
    result = _result(problem, objective)
    for text in MEASURE.notations(result):
        judged = assess(text, result)
        assert (judged.verdict, judged.diagnosis) == ("correct", None), (text, judged)


SYMBOLIC = [(p.stem, o.id) for p in PROBLEMS for o in library_problem(p.stem).objectives
            if o.kind == "symbolic"]


@pytest.mark.parametrize("problem,objective", SYMBOLIC, ids=[f"{p}.{o}" for p, o in SYMBOLIC])
def test_a_correct_expression_gets_no_diagnosis(problem, objective):
    result = _result(problem, objective)
    for text in (result.expr, result.expr.replace("**", "^")):
        judged = assess(text, result)
        assert (judged.verdict, judged.diagnosis) == ("correct", None), (text, judged)
