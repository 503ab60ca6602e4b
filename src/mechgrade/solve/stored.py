"""A problem's solution at its own givens, kept in the disk cache (:mod:`.cache`).

A problem with bodies and loads is derived with sympy in more places than its plan (its
kinetics, its events, each mistaken model its generated mistakes come from); what it is solved
to at the instant its spec describes is plain data, so that is what is kept for it: ``check``
of an unchanged dynamics problem reads it back without sympy. A solution with other givens (a
variant, an answer carried forward) is always solved.

>>> from mechgrade.errors import Location, SolveError
>>> from mechgrade.solve.result import ObjectiveFailure, ObjectiveResult, Solution
>>> s = Solution("p", (ObjectiveResult("v", "vector", "m/s", (1.0, 2.0, 0.0), "N"),),
...              failures=(ObjectiveFailure("w", SolveError("no", where=Location("p.yaml"))),))
>>> back = solution_from(solution_data(s))
>>> back.results == s.results, str(back.failures[0].error)
(True, 'p.yaml: no')
"""

from __future__ import annotations

import json
from typing import Any

from .. import errors
from ..errors import AuthorWarning, MechgradeError
from .cache import where_data, where_from
from .result import (GeneratedMistake, MistakeValue, ObjectiveFailure, ObjectiveResult,
                     Solution, StateValue)


def solution_data(solution: Solution) -> dict:
    """``solution`` as plain JSON, as read back from a file (lists for tuples; its generated
    mistakes worked out)."""
    return json.loads(json.dumps({
        "problem": solution.problem,
        "results": [result_data(r) for r in solution.results],
        "state": [[s.name, s.value, s.unit, s.given, s.si] for s in solution.state],
        "dof": solution.dof,
        "failures": [[f.id, type(f.error).__name__, f.error.message, where_data(f.error.where)]
                     for f in solution.failures],
        "warnings": [[w.message, where_data(w.where)] for w in solution.warnings]}))


def solution_from(data: Any) -> Solution:
    """The solution :func:`solution_data` gave ``data`` for; raises (``KeyError``,
    ``TypeError``, ``ValueError``) on anything else."""
    return Solution(
        problem=str(data["problem"]),
        results=tuple(result_from(r) for r in data["results"]),
        state=tuple(StateValue(str(name), float(value), str(unit), bool(given), float(si))
                    for name, value, unit, given, si in data["state"]),
        dof=None if data["dof"] is None else int(data["dof"]),
        failures=tuple(ObjectiveFailure(str(oid), _error(name, message, where))
                       for oid, name, message, where in data["failures"]),
        warnings=tuple(AuthorWarning(str(message), where_from(where))
                       for message, where in data["warnings"]))


def result_data(r: ObjectiveResult) -> dict:
    """One objective's result as JSON (its generated mistakes worked out)."""
    return {
        "id": r.id, "kind": r.kind.value, "unit": r.unit,
        "value": list(r.value) if isinstance(r.value, tuple) else r.value,
        "frame": r.frame, "expr": r.expr, "symbols": list(r.symbols),
        "symbol_units": list(r.symbol_units), "symbol_signed": list(r.symbol_signed),
        "mistakes": [[m.message, m.credit, _json_value(m.value), m.expr] for m in r.mistakes],
        "rel": r.rel, "abs": r.abs, "prompt": r.prompt,
        "generated_mistakes": [[m.code, m.message, _json_value(m.value), m.expr, m.step]
                               for m in r.generated_mistakes],
        "plausible": None if r.plausible is None else sorted(r.plausible),
        "symbol_signs": list(r.symbol_signs)}


def result_from(r: Any) -> ObjectiveResult:
    """The result :func:`result_data` gave ``r`` for."""
    return ObjectiveResult(
        id=str(r["id"]), kind=r["kind"], unit=str(r["unit"]), value=_value(r["value"]),
        frame=_text(r["frame"]), expr=_text(r["expr"]), symbols=tuple(map(str, r["symbols"])),
        symbol_units=tuple(map(str, r["symbol_units"])),
        symbol_signed=tuple(map(bool, r["symbol_signed"])),
        mistakes=tuple(MistakeValue(str(message), float(credit), _value(value), _text(expr))
                       for message, credit, value, expr in r["mistakes"]),
        rel=float(r["rel"]), abs=float(r["abs"]), prompt=str(r["prompt"]),
        generated_mistakes=tuple(
            GeneratedMistake(str(code), str(message), _value(value), _text(expr), _text(step))
            for code, message, value, expr, step in r["generated_mistakes"]),
        plausible=None if r["plausible"] is None else frozenset(map(str, r["plausible"])),
        symbol_signs=tuple(map(int, r["symbol_signs"])))


def same(a: Solution, b: Solution) -> bool:
    """Whether two solutions say the same (errors compared by their kind and message)."""
    def content(s: Solution) -> tuple:
        return (s.problem, s.results, s.state, s.dof, s.warnings,
                tuple((f.id, type(f.error), str(f.error)) for f in s.failures))
    return content(a) == content(b)


def _json_value(value):
    return list(value) if isinstance(value, tuple) else value


def _value(value):
    if value is None:
        return None
    if isinstance(value, list):
        return tuple(float(v) for v in value)
    return float(value)


def _text(value) -> str | None:
    return None if value is None else str(value)


def _error(name: str, message: str, where) -> MechgradeError:
    kind = getattr(errors, str(name), None)
    if not (isinstance(kind, type) and issubclass(kind, MechgradeError)):
        raise ValueError(f"not an error of mechgrade: {name!r}")
    return kind(str(message), where=where_from(where))
