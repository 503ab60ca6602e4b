"""Check problem files: load and validate them, solve them, and run every ``expect:`` test.

An ``expect:`` value is compared to the digits the author wrote (:func:`written_tolerance`),
not to the student tolerance. Declared ``mistakes:`` are compared with the answer: one equal
to it is an error (it can never be told apart), one within the objective's tolerance a
warning (a student making it gets full credit).

>>> from mechgrade.resources import shipped_dir
>>> report = check_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
>>> report.passed, [o.objective for o in report.outcomes][:2]
(True, ['acc_mag', 'acc_N'])
"""

from __future__ import annotations

import hashlib
import os
import stat
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..codec import decode, encode

from ..errors import AuthorWarning, ExpressionError, MechgradeError, SpecError
from ..files import MAX_BYTES
from ..expressions.numeric import evaluate, reference_tree
from ..solve import cache
from ..solve.mutants import inside_tolerance, separating_rel
from ..solve.result import ObjectiveResult, in_frame
from ..spec.model import Expect, Objective, Problem
from ..tolerance import REFERENCE_ACCURACY, agree_at_points, within
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
    """Everything ``check`` found in one file: a blocking error (one line per error), or the
    expect outcomes, errors in declared mistakes, and warnings."""

    path: str
    problem: str | None = None
    error: str | None = None
    outcomes: tuple[ExpectOutcome, ...] = ()
    dof: int | None = None
    untested: tuple[str, ...] = ()
    faults: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    state: tuple[str, ...] = ()  # the solved state, "theta' = 7 rad/s   (solved)"
    results: tuple[ObjectiveResult, ...] = ()  # the solved objectives, in file order
    # generated mistakes a student gets full credit for, and the tolerance that separates them
    separations: tuple[str, ...] = ()
    variants: bool = False  # the problem draws per-student variants (a variants: section)

    @property
    def passed(self) -> bool:
        return self.error is None and not self.faults and all(o.passed for o in self.outcomes)


def problem_files(paths) -> list[Path]:
    """The problem files named by ``paths``: files as given, folders searched for ``*.yaml``."""
    out: list[Path] = []
    for path in map(Path, paths):
        if path.is_dir():
            out += sorted(p for p in path.rglob("*.y*ml") if p.is_file())
        else:
            out.append(path)
    return out


def watch(paths, interval: float = 0.5) -> Iterator[list[Path]]:
    """The problem files under ``paths``: all of them first, then, polling every ``interval``
    seconds, those created or saved since the last look (modification time or size changed).

    Polling needs no dependency and works on every file system; a file caught mid-save (gone
    for a moment while an editor replaces it) is picked up on the next look.

    >>> import tempfile
    >>> folder = Path(tempfile.mkdtemp())
    >>> _ = (folder / "a.yaml").write_text("id: a")
    >>> changes = watch([folder], interval=0.01)
    >>> [p.name for p in next(changes)]
    ['a.yaml']
    >>> _ = (folder / "b.yaml").write_text("id: b")
    >>> [p.name for p in next(changes)]
    ['b.yaml']
    """
    seen = _stamps(paths)
    yield sorted(seen)
    while True:
        time.sleep(interval)
        now = _stamps(paths)
        changed = sorted(p for p, stamp in now.items() if seen.get(p) != stamp)
        seen = now
        if changed:
            yield changed


def _stamps(paths) -> dict[Path, tuple[int, int]]:
    stamps = {}
    for path in problem_files(paths):
        try:
            info = os.stat(path)
        except OSError:
            continue
        stamps[path] = (info.st_mtime_ns, info.st_size)
    return stamps


def check_problem(path) -> CheckReport:
    """Load, validate and solve one file, then compare every objective with its ``expect:``
    and its declared mistakes with its answer.

    The report of a file is kept in the disk cache (:mod:`mechgrade.solve.cache`), keyed by
    its path and bytes and the code that checked it (mechgrade's and its libraries'): a file
    checked again unchanged is neither loaded nor solved, its report is read back."""
    key = _report_key(path)
    if key is not None:
        data = cache.load(key)
        try:
            if data is not None:
                return decode(CheckReport, data)
        except ValueError:
            pass  # not an entry this code wrote
    report = _checked(path)
    if key is not None and _report_key(path) == key and decode(CheckReport, encode(report)) \
            == report:  # the file did not change meanwhile; nothing the stored form leaves out
        cache.store(key, encode(report))
    return report


def _report_key(path) -> str | None:
    """The entry of a file's report: its path and bytes (read only if it is a regular file no
    larger than a problem file may be; a pipe is never waited on) and the code checking it."""
    if not cache.enabled():
        return None
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError:
        return None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_size > MAX_BYTES:
            return None
        with open(fd, "rb", closefd=False) as handle:
            content = hashlib.sha256(handle.read(MAX_BYTES + 1)).hexdigest()
    except OSError:
        return None
    finally:
        os.close(fd)
    return cache.digest("check", str(path), content, *cache.code_key(
        "yaml", "jsonschema", "pint", "numpy", "scipy"))


def _checked(path) -> CheckReport:
    from ..solve import solve
    from ..spec import load_problem

    try:
        problem = load_problem(path)
    except MechgradeError as err:
        return CheckReport(str(path), error=str(err) if err.where.file else f"{path}: {err}")
    try:
        solution = solve(problem)
    except MechgradeError as err:
        return CheckReport(str(path), problem.id,
                           error=str(err) if err.where.file else f"{path}: {err}",
                           warnings=tuple(str(w) for w in problem.warnings))
    outcomes = []
    untested = []
    errors = [str(f.error) if f.error.where.file else f"{path}: {f.error}"
              for f in solution.failures]
    solved = {r.id for r in solution.results}
    for objective in problem.objectives:
        if objective.id not in solved:
            continue  # its failure is listed in errors
        if objective.expect is None:
            untested.append(objective.id)
            continue
        try:
            outcomes.append(expect_outcome(objective, solution.result(objective.id)))
        except MechgradeError as err:
            where = err.where if err.where.file else objective.expect.where
            errors.append(str(err.located(where)))
    faults, warnings = mistake_findings(problem, solution)
    faults += tolerance_faults(problem, solution)
    state = tuple(str(s) for s in solution.state)
    return CheckReport(str(path), problem.id, None, tuple(outcomes), solution.dof,
                       tuple(untested), tuple(errors + faults),
                       tuple(str(w) for w in problem.warnings + solution.warnings
                             + tuple(warnings)), state, solution.results,
                       tuple(str(w) for w in separation_findings(problem, solution)),
                       problem.variants is not None)


def separation_findings(problem: Problem, solution) -> list[AuthorWarning]:
    """One warning per objective whose tolerance a generated mistake falls inside (a student
    making it gets full credit), with the tolerance that separates them.

    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve import solve
    >>> from mechgrade.spec import load_problem
    >>> p = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    >>> print(separation_findings(p, solve(p))[0].message)  # doctest: +ELLIPSIS
    objective 'acc_mag': generated mistakes drop_tangential gives 98 ft/s^2; acc_n_for_acc gives ...
    """
    out = []
    for result in solution.results:
        inside = inside_tolerance(result)
        if not inside:
            continue
        objective = problem.objective(result.id)
        unit = f" {result.unit}" if result.unit not in ("", "1") else ""
        listed = "; ".join(f"{m.code} gives {_show(m.value)}{unit}" for m in inside)
        rel = separating_rel(result)
        advice = (f"tolerance: {{rel: {rel:g}}} separates them (or policy: {{tolerance: "
                  "{separate_mistakes: true}} in the assignment)" if rel is not None else
                  "no tolerance that still accepts four significant figures separates them")
        out.append(AuthorWarning(
            f"objective '{result.id}': generated mistake{'s' if len(inside) > 1 else ''} "
            f"{listed}, within the tolerance ({result.rel * 100:g} %) of the answer "
            f"{_show(result.value)}: a student making {'them' if len(inside) > 1 else 'it'} "
            f"gets full credit; {advice}", objective.where))
    return out


def mistake_findings(problem: Problem, solution) -> tuple[list[str], list[AuthorWarning]]:
    """Declared mistakes equal to the answer (errors) or within its tolerance (warnings)."""
    faults, warnings = [], []
    results = {r.id: r for r in solution.results}
    for objective in problem.objectives:
        result = results.get(objective.id)
        if result is None or result.value is None:
            continue
        for declared, mistake in zip(objective.mistakes, result.mistakes):
            if mistake.value is None:
                continue
            answer = _as_vector(result.value)
            wrong = _as_vector(mistake.value)
            size = sum(a * a for a in answer) ** 0.5
            where = declared.where
            if within(wrong, answer, 0.0, 1e-9 * max(size, 1.0)):
                faults.append(f"{where}: mistake '{declared.find.text}' gives the correct answer "
                              f"({_show(result.value)} {objective.unit}); expected a different "
                              "value, or remove it")
            elif within(wrong, answer, objective.tolerance.rel, objective.tolerance.abs,
                        scale=size):
                warnings.append(AuthorWarning(
                    f"mistake '{declared.find.text}' gives {_show(mistake.value)} "
                    f"{objective.unit}, within the tolerance of the answer "
                    f"{_show(result.value)}: a student making it gets full credit", where))
    return faults, warnings


def tolerance_faults(problem: Problem, solution) -> list[str]:
    """Objectives whose absolute tolerance (without a relative one) is tighter than the
    reference's own accuracy for its answer: no student could match it."""
    out = []
    for result in solution.results:
        objective = problem.objective(result.id)
        tol = objective.tolerance
        if result.value is None or tol.rel >= REFERENCE_ACCURACY or tol.abs <= 0:
            continue
        size = sum(v * v for v in _as_vector(result.value)) ** 0.5
        floor = REFERENCE_ACCURACY * size
        if tol.abs < floor:
            where = tol.where if tol.where.file else objective.where
            out.append(f"{where}: expected a tolerance no tighter than the reference's own "
                       f"accuracy ({floor:.3g} {objective.unit}, {REFERENCE_ACCURACY:g} of the "
                       f"answer {_show(result.value)}), found abs: {tol.abs:g}: no student could "
                       "match it; write rel: 0.01 (1 %, the default) or a larger abs")
    return out


def _as_vector(value) -> tuple[float, ...]:
    return tuple(value) if isinstance(value, (tuple, list)) else (float(value),)


def _show(value) -> str:
    if isinstance(value, (tuple, list)):
        return "(" + ", ".join(f"{v:.6g}" for v in value) + ")"
    return f"{value:.6g}"


def check_paths(paths) -> tuple[CheckReport, ...]:
    """:func:`check_problem` for every problem file under ``paths``."""
    files = problem_files(paths)
    return tuple(check_problem(f) for f in files)


def expect_outcome(objective: Objective, result: ObjectiveResult) -> ExpectOutcome:
    """Compare the solver's ``result`` with the objective's ``expect:``, to the digits written.
    The expect's one value (``expr``, ``value`` or ``components``, as the loader checked
    against the objective's kind) says which comparison."""
    e = objective.expect
    if e is not None and e.expr is not None and result.expr is not None:
        same = equivalent(result.expr, e.expr, result.symbols, result.symbol_signed)
        message = (f"{result.expr} {'==' if same else '!='} expected {e.expr}")
        return ExpectOutcome(objective.id, same, message, e.note, e.book)
    if e is not None and e.value is not None and isinstance(result.value, (int, float)):
        return _scalar_outcome(objective, e, e.value, result.value)
    if e is not None and e.components is not None and isinstance(result.value, tuple):
        return _vector_outcome(objective, e, e.components, result.value)
    raise ValueError(f"objective '{objective.id}': no expect: of its kind to compare with")


def _scalar_outcome(objective: Objective, e: Expect, value: float,
                    solved: float) -> ExpectOutcome:
    unit = objective.unit
    written = e.written if isinstance(e.written, str) else repr(value)
    expected = _convert(value, e.unit, unit)
    limit = (_convert(written_tolerance(written), e.unit, unit) if float(written) != 0
             else 1e-9)
    ok = within(solved, expected, 0.0, limit)
    message = f"{solved:.6g} {'~' if ok else '!='} expected {written} {unit}"
    if not ok:
        message += f" (±{limit:.3g}, from the digits written)"
    return ExpectOutcome(objective.id, ok, message, e.note, e.book)


def _vector_outcome(objective: Objective, e: Expect, components: tuple[float, ...],
                    solved: tuple[float, ...]) -> ExpectOutcome:
    unit = objective.unit
    texts = e.written if isinstance(e.written, tuple) else tuple(map(repr, components))
    expected = [_convert(c, e.unit, unit) for c in components]
    expected += [0.0] * (3 - len(expected))
    size = sum(c * c for c in expected) ** 0.5
    # A written zero stands for an exact zero: zero to 1e-4 of the vector's size (1e-9 when the
    # whole vector is zero), whatever digits it was written with.
    zero = max(1e-4 * size, 1e-9)
    limits = [_convert(written_tolerance(t), e.unit, unit) if float(t) != 0 else zero
              for t in texts]
    limits += [zero] * (3 - len(limits))
    ok = all(within(a, b, 0.0, lim) for a, b, lim in zip(solved, expected, limits))
    shown = ", ".join(f"{v:.6g}" for v in solved)
    want = ", ".join(texts + ("0",) * (3 - len(texts)))
    message = (f"({shown}) {'~' if ok else '!='} expected ({want}) "
               f"{unit}{in_frame(objective.frame)}")
    return ExpectOutcome(objective.id, ok, message, e.note, e.book)


def written_tolerance(text: str) -> float:
    """How far a value may be from the number written as ``text``: half a unit in its last
    digit, and never less than 1e-5 of it (a solver's own precision, as in an integration).
    An author's test is far tighter than a student's: a typo in the fifth digit is caught.

    >>> written_tolerance("98.51"), written_tolerance("6"), written_tolerance("1.5e3")
    (0.005, 0.5, 50.0)
    >>> written_tolerance("-89.87"), round(written_tolerance("41.036426"), 9)
    (0.005, 0.000410364)
    """
    mantissa, _, exponent = text.strip().lstrip("+-").lower().partition("e")
    _whole, _, decimals = mantissa.partition(".")
    return max(0.5 * 10.0 ** (int(exponent or 0) - len(decimals)), 1e-5 * abs(float(text)))


def _convert(value: float, unit: str | None, target: str) -> float:
    if unit is None or unit == target:
        return float(value)
    return from_si(to_si(value, unit), target)


def equivalent(a: str, b: str, symbols, signed=None, *, trials: int = 24,
               seed: int = 20261121) -> bool:
    """Whether expressions ``a`` and ``b`` in ``symbols`` agree at random points (the one
    "equal at random points" test of :func:`mechgrade.tolerance.agree_at_points`). Each
    symbol is drawn with either sign, or positive where ``signed`` (one flag per symbol, as
    :attr:`ObjectiveResult.symbol_signed`) says it cannot be negative.

    >>> equivalent("sqrt(xd**2)", "Abs(xd)", ["xd"])
    True
    >>> equivalent("xd", "Abs(xd)", ["xd"]), equivalent("sqrt(x)", "x**(1/2)", ["x"])
    (False, True)
    >>> equivalent("sqrt(g)*sqrt(L)", "sqrt(g*L)", ["g", "L"], [False, False])
    True
    """
    symbols = tuple(symbols)
    signed = tuple(signed) if signed else (True,) * len(symbols)
    rng = np.random.default_rng(seed)
    env = {name: (rng.choice([-1.0, 1.0], trials) if may else 1.0)
           * rng.uniform(0.3, 1.7, trials) for name, may in zip(symbols, signed)}
    env["E"] = np.full(trials, np.e)
    try:
        va, vb = (evaluate(reference_tree(text, symbols), env) for text in (a, b))
    except ExpressionError as err:
        raise SpecError(f"cannot read expression: {err.message}") from None
    defined = np.isfinite(vb)  # outside the reference's domain (sqrt of a negative) is no test
    if defined.sum() < 3:
        raise SpecError(f"cannot compare {a!r} with {b!r}: undefined at most sample points")
    return agree_at_points(1e-8, vb[defined])(va[defined], vb[defined])