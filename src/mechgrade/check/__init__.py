"""Check problem files: load and validate them, solve them, and run every ``expect:`` test.

>>> from mechgrade.resources import shipped_dir
>>> report = check_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
>>> report.passed, [o.objective for o in report.outcomes][:2]
(True, ['acc_mag', 'acc_N'])
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from pathlib import Path

import sympy as sp

from ..errors import ExpressionError, MechgradeError, SpecError
from ..expressions.build import to_sympy
from ..expressions.syntax import parse
from ..solve import solve
from ..solve.result import ObjectiveResult
from ..spec import load_problem
from ..spec.model import Expect, Objective
from ..units import from_si, to_si


@dataclass(frozen=True)
class ExpectOutcome:
    """One ``expect:`` test: did the solver reproduce the author's answer?"""

    objective: str
    passed: bool
    message: str
    note: str | None = None
    book: str | None = None


@dataclass(frozen=True)
class CheckReport:
    """Everything ``check`` found in one file: a blocking error, or the expect outcomes."""

    path: str
    problem: str | None = None
    error: str | None = None
    outcomes: tuple[ExpectOutcome, ...] = ()
    dof: int | None = None
    untested: tuple[str, ...] = ()

    @property
    def passed(self) -> bool:
        return self.error is None and all(o.passed for o in self.outcomes)


def problem_files(paths) -> list[Path]:
    """The problem files named by ``paths``: files as given, folders searched for ``*.yaml``."""
    out: list[Path] = []
    for path in map(Path, paths):
        if path.is_dir():
            out += sorted(p for p in path.rglob("*.y*ml") if p.is_file())
        else:
            out.append(path)
    return out


def check_problem(path) -> CheckReport:
    """Load, validate and solve one file, then compare every objective with its ``expect:``."""
    try:
        problem = load_problem(path)
        solution = solve(problem)
    except MechgradeError as err:
        return CheckReport(str(path), error=str(err) if err.where.file else f"{path}: {err}")
    outcomes = []
    untested = []
    for objective in problem.objectives:
        if objective.expect is None:
            untested.append(objective.id)
            continue
        try:
            outcomes.append(expect_outcome(objective, solution.result(objective.id)))
        except MechgradeError as err:
            where = err.where if err.where.file else objective.expect.where
            return CheckReport(str(path), problem.id, error=str(err.located(where)))
    return CheckReport(str(path), problem.id, None, tuple(outcomes), solution.dof,
                       tuple(untested))


def check_paths(paths) -> tuple[CheckReport, ...]:
    """:func:`check_problem` for every problem file under ``paths``."""
    files = problem_files(paths)
    return tuple(check_problem(f) for f in files)


def expect_outcome(objective: Objective, result: ObjectiveResult) -> ExpectOutcome:
    """Compare the solver's ``result`` with the objective's ``expect:`` (its tolerance)."""
    e: Expect = objective.expect
    tol = objective.tolerance
    if objective.kind == "symbolic":
        same = equivalent(result.expr, e.expr, result.symbols)
        message = (f"{result.expr} {'==' if same else '!='} expected {e.expr}")
        return ExpectOutcome(objective.id, same, message, e.note, e.book)
    unit = objective.unit
    if objective.kind == "scalar":
        expected = _convert(e.value, e.unit, unit)
        ok = abs(result.value - expected) <= max(tol.rel * abs(expected), tol.abs)
        message = f"{result.value:.6g} {'~' if ok else '!='} expected {expected:.6g} {unit}"
        return ExpectOutcome(objective.id, ok, message, e.note, e.book)
    expected = [_convert(c, e.unit, unit) for c in e.components]
    expected += [0.0] * (3 - len(expected))
    size = sum(c * c for c in expected) ** 0.5
    limit = max(tol.rel * size, tol.abs)
    ok = all(abs(a - b) <= limit for a, b in zip(result.value, expected))
    shown = ", ".join(f"{v:.6g}" for v in result.value)
    want = ", ".join(f"{v:.6g}" for v in expected)
    message = f"({shown}) {'~' if ok else '!='} expected ({want}) {unit} in {objective.frame}"
    return ExpectOutcome(objective.id, ok, message, e.note, e.book)


def _convert(value: float, unit: str | None, target: str) -> float:
    if unit is None or unit == target:
        return float(value)
    return from_si(to_si(value, unit), target)


def equivalent(a: str, b: str, symbols, *, trials: int = 12, seed: int = 20261121) -> bool:
    """Whether expressions ``a`` and ``b`` in ``symbols`` agree at random points.

    >>> equivalent("sqrt(xd**2)", "Abs(xd)", ["xd"])
    True
    >>> equivalent("xd", "Abs(xd)", ["xd"])
    False
    """
    table = {name: sp.Symbol(name, real=True) for name in symbols}

    def build(text):
        try:
            return to_sympy(parse(text), lambda n: table[n.id])
        except ExpressionError as err:
            raise SpecError(f"cannot read expression {text!r}: {err.message}") from None

    fa, fb = build(a), build(b)
    rng = random.Random(seed)
    for _ in range(trials):
        point = {s: rng.choice((-1, 1)) * rng.uniform(0.3, 1.7) for s in table.values()}
        va = complex(sp.N(fa.xreplace(point)))
        vb = complex(sp.N(fb.xreplace(point)))
        if abs(va - vb) > 1e-8 * max(abs(va), abs(vb), 1.0):
            return False
    return True
