"""Solve a problem at the instant its givens describe, and evaluate every objective.

Numeric objectives: the position constraints are solved numerically for the coordinates the
givens leave open (near the spec's guesses), then the velocity and acceleration levels — linear
in the rates — by least squares, with ranks and residuals checked: a rate nothing determines is
reported by name if an objective depends on it, and givens that contradict the constraints are
reported as a conflict. Symbolic objectives are solved with sympy in the declared symbols.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> solution = solve(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"))
>>> round(solution.result("acc_mag").value, 2), solution.result("acc_mag_symbolic").expr
(98.51, 'L*sqrt(thetad**4 + thetadd**2)')
"""

from __future__ import annotations

from functools import lru_cache
from typing import Collection, Mapping

import numpy as np
import sympy as sp

from ..errors import SolveError, UnderdeterminedError
from ..expressions.syntax import Prime, to_text
from ..spec.model import Objective, Problem
from ..units import from_si, si_unit
from .levels import (Givens, State, constraint_rank, evaluate, place_givens, solve_position,
                     solve_rates)
from .plan import Plan, plan
from .result import MistakeValue, ObjectiveResult, Solution, StateValue
from .symbolic import symbolic

PROBE_TOL = 1e-7


def _numeric(objective: Objective) -> bool:
    return objective.kind != "symbolic"


# ---------------------------------------------------------------------------- givens


def _givens(problem: Problem, overrides: Mapping[str, float | None] | None):
    """Given values keyed by canonical key text -> (key node, SI value, Given or None)."""
    out = {to_text(g.key.node): (g.key.node, g.si, g) for g in problem.givens}
    for key, value in (overrides or {}).items():
        from ..expressions.syntax import parse
        from ..spec.language import FUNCTIONS
        node = parse(key, functions=FUNCTIONS)
        canonical = to_text(node)
        if value is None:
            out.pop(canonical, None)
        else:
            out[canonical] = (node, float(value), out.get(canonical, (None, None, None))[2])
    return out


# ---------------------------------------------------------------------------- numeric solve


def _solve_levels(problem: Problem, p: Plan, g: Givens, *,
                  free_values: Mapping[int, float] | None = None,
                  shifts: tuple[np.ndarray | None, np.ndarray | None] = (None, None)):
    """Position, velocity and acceleration levels in turn; the state and the nullspaces of the
    two rate levels."""
    state = solve_position(problem, p, g, free_values)
    state, null_v = solve_rates(problem, p, 1, state, g, shifts[0])
    state, null_a = solve_rates(problem, p, 2, state, g, shifts[1])
    return state, null_v, null_a


def solve_instant(problem: Problem, p: Plan, givens: Mapping,
                  only: set[str]) -> tuple[State, dict]:
    """Solve the instant and evaluate the numeric objectives in ``only``; raise if any of them
    depends on something the givens leave free."""
    g = place_givens(problem, p, givens)
    state, null_v, null_a = _solve_levels(problem, p, g)
    free_pos = sorted(i for i in state.free if i in p.index.config)
    base = evaluate(p.objectives, state, only)
    # Probe each freedom the givens leave: an objective that changes depends on it.
    depends: dict[str, list[str]] = {}
    keep = {i: state.values[i] for i in free_pos}
    probes = [("position", i) for i in free_pos]
    probes += [("velocity", j) for j in range(null_v.shape[1])]
    probes += [("acceleration", j) for j in range(null_a.shape[1])]
    for level, which in probes:
        if level == "position":
            trial, *_ = _solve_levels(problem, p, g,
                                      free_values={which: state.values[which] + 0.37})
            missing = p.index.spelling(which)
        else:
            order = 1 if level == "velocity" else 2
            null = null_v if order == 1 else null_a
            z = np.zeros(null.shape[1])
            z[which] = 0.73
            shifts = (z, None) if order == 1 else (np.zeros(null_v.shape[1]), z)
            trial, *_ = _solve_levels(problem, p, g, free_values=keep, shifts=shifts)
            unknown = [i for i in p.index.rates(order) if not g.known[i]]
            missing = _rate_names(p, unknown, null[:, which])
        changed = evaluate(p.objectives, trial, only)
        for oid, value in base.items():
            if not _close(value, changed[oid]):
                depends.setdefault(oid, []).append(f"{missing} ({level} level)")
    if depends:
        oid, missing = next(iter(depends.items()))
        others = [o for o in depends if o != oid]
        more = f" (also undetermined: {', '.join(others)})" if others else ""
        raise UnderdeterminedError(
            f"objective '{oid}' is not determined by the givens: give a value for "
            f"{' or '.join(missing)}{more}")
    return state, base


def _check_requirements(problem: Problem, p: Plan, state: State, only: set[str]) -> None:
    """Raise if an objective in ``only`` does not exist at this instant."""
    values = evaluate(((oid, f) for oid, _, f in p.requirements), state, only)
    for oid, reason, _ in p.requirements:
        if oid in only and abs(float(values[oid][0])) > 1e-9:
            raise SolveError(f"objective '{oid}' does not exist at this instant: {reason}",
                             where=problem.objective(oid).where)


def _mistake_values(p: Plan, state: State, only: set[str]) -> dict[str, list[np.ndarray]]:
    return {oid: [evaluate((("m", f),), state, {"m"})["m"] for f in funcs]
            for oid, funcs in p.mistakes if oid in only}


def _rate_names(p: Plan, unknown: list[int], direction: np.ndarray) -> str:
    names = [p.index.symbols[i].name for i, w in zip(unknown, direction) if abs(w) > 1e-6]
    return " or ".join(names) if names else "a rate"


def _close(a: np.ndarray, b: np.ndarray) -> bool:
    if a.shape != b.shape:
        return False
    if not (np.isfinite(a).all() and np.isfinite(b).all()):
        return np.array_equal(np.isfinite(a), np.isfinite(b))
    scale = max(np.abs(a).max(initial=0.0), 1e-12)
    return bool(np.abs(a - b).max(initial=0.0) <= PROBE_TOL * scale + 1e-12)


# ---------------------------------------------------------------------------- entry point


def solve(problem: Problem, *, givens: Mapping[str, float | None] | None = None,
          objectives: Collection[str] | None = None) -> Solution:
    """Solve every objective of ``problem`` (or only those named in ``objectives``).

    ``givens`` overrides given values for this call only: keys are given names as written in
    the spec (``"theta'"``, ``"dot(vel(B, N), B.x)"``), values are SI numbers, ``None`` removes
    a given. Objectives with givens of their own are solved at their own instant.
    """
    p = plan(problem)
    k = p.k
    results: dict[str, ObjectiveResult] = {}
    base_state = None
    wanted = set(objectives) if objectives is not None else {o.id for o in problem.objectives}
    unknown = wanted - {o.id for o in problem.objectives}
    if unknown:
        raise SolveError(f"no objective '{sorted(unknown)[0]}' in problem '{problem.id}'")
    for overrides, group in _instants(problem):
        objectives = [o for o in group if o.id in wanted]
        if not objectives:
            continue
        given_map = _givens(problem, givens)
        given_map.update({key: (g.key.node, g.si, g) for key, g in overrides.items()})
        numeric = {o.id for o in objectives if _numeric(o)}
        values, mistakes = {}, {}
        if numeric:
            state, values = solve_instant(problem, p, given_map, numeric)
            _check_requirements(problem, p, state, numeric)
            mistakes = _mistake_values(p, state, numeric)
            if not overrides or base_state is None:
                base_state = state
        for obj in objectives:
            if obj.kind == "symbolic":
                frozen = tuple(sorted(given_map.items(), key=lambda item: item[0]))
                results[obj.id] = _symbolic_result(problem, obj.id, frozen)
            else:
                results[obj.id] = _numeric_result(obj, values[obj.id], mistakes.get(obj.id, ()))
    return Solution(problem=problem.id,
                    results=tuple(results[o.id] for o in problem.objectives if o.id in wanted),
                    state=_state(problem, p, base_state),
                    dof=degrees_of_freedom(p, base_state))


def _instants(problem: Problem):
    """Objectives grouped by the instant they are asked at: the problem's givens, or those
    plus an objective's own givens."""
    groups: dict[tuple, tuple[dict, list[Objective]]] = {}
    for obj in problem.objectives:
        overrides = {to_text(g.key.node): g for g in obj.givens}
        key = tuple(sorted((name, g.si) for name, g in overrides.items()))
        groups.setdefault(key, (overrides, []))[1].append(obj)
    return sorted(groups.values(), key=lambda group: bool(group[0]))


@lru_cache(maxsize=512)
def _symbolic_result(problem: Problem, objective_id: str, givens: tuple) -> ObjectiveResult:
    """A symbolic objective's answer; cached, since re-solving with other givens (error carried
    forward, variants) rarely changes the pure-number givens it depends on."""
    obj = problem.objective(objective_id)
    expr, meanings = symbolic(problem, plan(problem).k, obj, dict(givens))
    units = tuple(_quantity_unit(problem, node) for node in meanings.values())
    return ObjectiveResult(
        id=obj.id, kind=obj.kind, unit=obj.unit, expr=sp.sstr(expr), symbols=tuple(meanings),
        symbol_units=units, rel=obj.tolerance.rel, abs=obj.tolerance.abs, prompt=obj.prompt)


def _numeric_result(obj: Objective, si_values: np.ndarray, mistakes) -> ObjectiveResult:
    return ObjectiveResult(
        id=obj.id, kind=obj.kind, unit=obj.unit, value=_report(si_values, obj),
        frame=obj.frame,
        mistakes=tuple(MistakeValue(m.message, m.credit, _report(v, obj))
                       for m, v in zip(obj.mistakes, mistakes)),
        rel=obj.tolerance.rel, abs=obj.tolerance.abs, prompt=obj.prompt)


def degrees_of_freedom(p: Plan, state: State | None = None) -> int:
    """Coordinates minus independent constraint equations (rank of the velocity-level
    constraints in the rates, at the instant when it is solved)."""
    k = p.k
    if state is not None:
        return len(k.coordinates) - constraint_rank(p, state)
    if not k.velocity:
        return len(k.coordinates)
    return len(k.coordinates) - sp.Matrix([e.expr for e in k.velocity]).jacobian(k.qd).rank()


def _report(si_values: np.ndarray, obj: Objective):
    if not np.isfinite(si_values).all():
        raise SolveError(f"objective '{obj.id}' is undefined at this instant (for example a "
                         "direction of motion when the speed is zero)", where=obj.where)
    if obj.kind == "vector":
        return tuple(float(from_si(v, obj.unit)) + 0.0 for v in si_values)
    return float(from_si(si_values[0], obj.unit)) + 0.0


def _quantity_unit(problem: Problem, node) -> str:
    """SI unit of a coordinate, rate or parameter node."""
    units = {c.name: c.unit for c in problem.coordinates}
    units.update({q.name: q.unit for q in problem.parameters})
    if isinstance(node, Prime):
        return si_unit(f"({units[node.id] or '1'}) / s^{node.order}")
    return si_unit(units[node.id])


def _state(problem: Problem, p: Plan, state: State | None) -> tuple[StateValue, ...]:
    if state is None:
        return ()
    index = p.index
    units = {c.name: c.unit for c in problem.coordinates}
    units.update({q.name: q.unit for q in problem.parameters})
    out = []
    for i, sym in enumerate(index.symbols):
        value = state.values[i]
        if not np.isfinite(value) or i in state.free:
            continue
        order = index.level_of(i)
        if order == 0:
            unit = si_unit(units.get(sym.name, "s"))
        else:
            unit = si_unit(f"({units[index.coordinate_of(i)] or '1'}) / s^{order}")
        out.append(StateValue(sym.name, float(value), unit, bool(state.given[i])))
    return tuple(out)
