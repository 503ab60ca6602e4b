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

import math
import warnings
from dataclasses import dataclass
from functools import lru_cache
from typing import Collection, Mapping

import numpy as np
import sympy as sp
from scipy import linalg, optimize

from ..errors import InconsistentError, SolveError, UnderdeterminedError
from ..expressions.syntax import Name, Prime, to_text
from ..mechanics import Kinematics, derive
from ..spec.model import Objective, Problem
from ..spec.validate import symbol_meanings
from ..units import from_si, si_unit
from .result import MistakeValue, ObjectiveResult, Solution, StateValue

RANK_TOL = 1e-9
PROBE_TOL = 1e-7


@dataclass(frozen=True)
class _Plan:
    """Lambdified pieces of a problem's kinematics, made once per problem."""

    k: Kinematics
    symbols: tuple[sp.Symbol, ...]  # q, params, t, qd, qdd
    n_config: int  # how many leading symbols are position-level unknowns (q, params, t)
    position: object
    position_jac: object
    position_scale: object
    position_labels: tuple[str, ...]
    velocity_A: object
    velocity_b: object
    velocity_scale: object
    velocity_labels: tuple[str, ...]
    acceleration_A: object
    acceleration_b: object
    acceleration_scale: object
    acceleration_labels: tuple[str, ...]
    condition_keys: tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...]]
    objectives: tuple[tuple[str, object], ...]
    mistakes: tuple[tuple[str, tuple[object, ...]], ...]
    requirements: tuple[tuple[str, str, object], ...]


def _lambdify(symbols, expr):
    return sp.lambdify(symbols, expr, modules="numpy", cse=True)


def _scale(exprs):
    """Sum of the absolute values of each equation's terms: the size a residual is judged by."""
    return sp.Matrix([sum((sp.Abs(term) for term in sp.Add.make_args(e)), sp.Integer(0))
                      for e in exprs])


@lru_cache(maxsize=64)
def plan(problem: Problem) -> _Plan:
    """Derive and lambdify ``problem`` once (the cold, symbolic part of solving)."""
    k = derive(problem)
    params = tuple(s for _, s in k.parameters)
    config = k.q + params + (k.time,)
    symbols = config + k.qd + k.qdd
    levels = {0: [], 1: [], 2: []}
    for c in k.conditions:
        levels[c.level].append(c)
    pos = [e.expr for e in k.position] + [c.expr for c in levels[0]]
    vel = [e.expr for e in k.velocity] + [c.expr for c in levels[1]]
    acc = [e.expr for e in k.acceleration] + [c.expr for c in levels[2]]

    def linear(exprs, rates):
        if not exprs:
            return (sp.zeros(0, len(rates)), sp.zeros(0, 1))
        m = sp.Matrix(exprs)
        A = m.jacobian(list(rates))
        b = m.xreplace({r: 0 for r in rates})
        return A, b

    vA, vb = linear(vel, k.qd)
    aA, ab = linear(acc, k.qdd)
    pos_m = sp.Matrix(pos) if pos else sp.zeros(0, 1)
    return _Plan(
        k=k, symbols=symbols, n_config=len(config),
        position=_lambdify(symbols, pos_m),
        position_jac=_lambdify(symbols, pos_m.jacobian(list(config)) if pos
                               else sp.zeros(0, len(config))),
        position_scale=_lambdify(symbols, _scale(pos) if pos else sp.zeros(0, 1)),
        position_labels=tuple(e.label for e in k.position)
        + tuple(f"given {c.key}" for c in levels[0]),
        velocity_A=_lambdify(symbols, vA), velocity_b=_lambdify(symbols, vb),
        velocity_scale=_lambdify(symbols, _scale(vel) if vel else sp.zeros(0, 1)),
        velocity_labels=tuple(e.label for e in k.velocity)
        + tuple(f"given {c.key}" for c in levels[1]),
        acceleration_A=_lambdify(symbols, aA), acceleration_b=_lambdify(symbols, ab),
        acceleration_scale=_lambdify(symbols, _scale(acc) if acc else sp.zeros(0, 1)),
        acceleration_labels=tuple(e.label for e in k.acceleration)
        + tuple(f"given {c.key}" for c in levels[2]),
        condition_keys=tuple(tuple(c.key for c in levels[i]) for i in range(3)),
        objectives=tuple((oid, _lambdify(symbols, expr)) for oid, expr in k.objectives
                         if _numeric(problem.objective(oid))),
        mistakes=tuple((oid, tuple(_lambdify(symbols, e) for e in exprs))
                       for oid, exprs in k.mistakes if _numeric(problem.objective(oid))),
        requirements=tuple((oid, reason, _lambdify(symbols, expr))
                           for oid, reason, expr in k.requirements),
    )


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


class _Instant:
    """The numeric state at the instant, solved level by level."""

    def __init__(self, problem: Problem, p: _Plan, givens: dict):
        self.problem = problem
        self.p = p
        self.k = p.k
        self.n = len(self.k.q)
        self.values = np.full(len(p.symbols), np.nan)
        self.known = np.zeros(len(p.symbols), dtype=bool)
        self.index = {s: i for i, s in enumerate(p.symbols)}
        self.conditions = ({}, {}, {})
        self.given_text = {}
        for key, (node, si, given) in givens.items():
            text = f"{key} = {given.text}" if given is not None else f"{key} = {si:g} (SI)"
            if isinstance(node, (Name, Prime)):
                try:
                    sym = self.k.quantity(node)
                except (KeyError, ValueError):
                    raise SolveError(f"cannot give '{key}': not a coordinate, rate, parameter "
                                     "or t of this problem") from None
                i = self.index[sym]
                self.values[i] = si
                self.known[i] = True
                self.given_text[i] = text
            else:
                levels = [lvl for lvl in range(3) if key in p.condition_keys[lvl]]
                if not levels:
                    raise SolveError(f"cannot give '{key}': it is not a given of this problem "
                                     "(expression givens must appear in the spec)")
                self.conditions[levels[0]][key] = si
                self.given_text[("condition", key)] = text
        self.free: set[int] = set()
        guesses = {to_text(g.key.node): g.si for g in problem.guesses}
        self.guess = np.array([guesses.get(str(s), 0.3) for s in p.symbols[:p.n_config]])

    # ------------------------------------------------------------- levels

    def _condition_rows(self, level: int, labels) -> tuple[np.ndarray, np.ndarray]:
        """Which equation rows are active (constraints, and conditions given in this solve),
        and the value each condition row must equal (0 for constraints)."""
        keys = self.p.condition_keys[level]
        n_constraints = len(labels) - len(keys)
        values = np.array([self.conditions[level].get(key, np.nan) for key in keys])
        active = np.concatenate([np.ones(n_constraints, dtype=bool), ~np.isnan(values)])
        target = np.concatenate([np.zeros(n_constraints), np.nan_to_num(values)])
        return active, target

    def position(self, free_override: dict[int, float] | None = None) -> list[int]:
        """Solve the configuration; returns indices of configuration unknowns left free."""
        nc = self.p.n_config
        labels = self.p.position_labels
        active, target = self._condition_rows(0, labels)
        unknown = [i for i in range(nc) if not self.known[i]]
        x = self.values.copy()
        x[unknown] = self.guess[unknown]
        solve_for = unknown

        def residual(vals):
            full = x.copy()
            full[solve_for] = vals
            return (np.asarray(self.p.position(*full), dtype=float).ravel() - target)[active]

        def jac(vals):
            full = x.copy()
            full[solve_for] = vals
            J = np.asarray(self.p.position_jac(*full), dtype=float).reshape(len(labels), nc)
            return J[active][:, solve_for]

        free: list[int] = list(unknown)
        if unknown and active.any():
            determined, free = _split_free(jac(x[unknown]), unknown)
            for i in free:
                x[i] = (free_override or {}).get(i, x[i])
            solve_for = determined
            if determined:
                with np.errstate(all="ignore"):
                    fit = optimize.least_squares(residual, x[determined], jac=jac,
                                                 xtol=1e-14, ftol=1e-14, gtol=1e-14,
                                                 max_nfev=500)
                x[determined] = fit.x
        else:
            for i in free:
                x[i] = (free_override or {}).get(i, x[i])
        self.values = x
        if active.any():
            r = (np.asarray(self.p.position(*x), dtype=float).ravel() - target)
            scale = np.abs(np.asarray(self.p.position_scale(*x), dtype=float).ravel())
            self._check_residual(r[active], scale[active], np.array(labels)[active], "position")
        return free

    def rates(self, level: int, null_override: np.ndarray | None = None) -> np.ndarray:
        """Solve the velocity (1) or acceleration (2) level; returns its nullspace basis."""
        n = self.n
        offset = self.p.n_config + (level - 1) * n
        cols = list(range(offset, offset + n))
        A_f = self.p.velocity_A if level == 1 else self.p.acceleration_A
        b_f = self.p.velocity_b if level == 1 else self.p.acceleration_b
        labels = self.p.velocity_labels if level == 1 else self.p.acceleration_labels
        scale_f = self.p.velocity_scale if level == 1 else self.p.acceleration_scale
        active, target = self._condition_rows(level, labels)
        x = self.values.copy()
        x[cols] = np.where(self.known[cols], x[cols], 0.0)
        with np.errstate(all="ignore"):
            A = np.asarray(A_f(*x), dtype=float).reshape(len(labels), n)
            b = np.asarray(b_f(*x), dtype=float).ravel() - target
        if level == 1:
            constraints = len(labels) - len(self.p.condition_keys[1])
            self.constraint_rank = int(np.linalg.matrix_rank(A[:constraints])) if constraints \
                else 0
        A, b = A[active], b[active]
        if not (np.isfinite(A).all() and np.isfinite(b).all()):
            raise SolveError(f"the {_LEVEL[level]} equations are undefined at this instant "
                             "(a division by zero in the model)")
        known = [j for j in range(n) if self.known[cols[j]]]
        unknown = [j for j in range(n) if not self.known[cols[j]]]
        rhs = -(b + A[:, known] @ x[[cols[j] for j in known]])
        null = np.zeros((len(unknown), 0))
        if unknown:
            A_u = A[:, unknown]
            if len(b):
                sol, *_ = linalg.lstsq(A_u, rhs)
                null = _nullspace(A_u)
            else:
                sol = np.zeros(len(unknown))
                null = np.eye(len(unknown))
            if null_override is not None and null.shape[1]:
                sol = sol + null @ null_override
            for j, value in zip(unknown, sol):
                x[cols[j]] = value
            self.free |= {cols[unknown[i]] for i in range(len(unknown))
                          if null.shape[1] and np.abs(null[i]).max() > 1e-9}
        self.values = x
        if len(b):
            r = A @ x[cols] + b
            with np.errstate(all="ignore"):
                scale = np.abs(np.asarray(scale_f(*x), dtype=float).ravel())[active]
            self._check_residual(r, scale, np.array(labels)[active], _LEVEL[level])
        return null

    def _check_residual(self, r, scale, labels, level: str) -> None:
        bad = [i for i in range(len(r))
               if not abs(r[i]) <= self.problem.consistency * scale[i] + 1e-10]
        if not bad:
            return
        i = bad[0]
        givens = list(self.given_text.values())
        raise InconsistentError(
            f"the givens conflict at the {level} level: '{labels[i]}' is not satisfied "
            f"(residual {r[i]:.4g} against terms of size {scale[i]:.4g}); givens involved: "
            f"{'; '.join(givens) or 'none'}")

    def objective_values(self, only: set[str]) -> dict[str, np.ndarray]:
        """SI values of the numeric objectives in ``only`` (and of their mistaken models,
        under ``(id, index)``)."""
        out = {}
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for oid, f in self.p.objectives:
                if oid in only:
                    out[oid] = np.asarray(f(*self.values), dtype=float).ravel()
        return out

    def check_requirements(self, only: set[str]) -> None:
        """Raise if an objective in ``only`` does not exist at this instant."""
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for oid, reason, f in self.p.requirements:
                if oid in only and abs(float(f(*self.values))) > 1e-9:
                    raise SolveError(f"objective '{oid}' does not exist at this instant: "
                                     f"{reason}", where=self.problem.objective(oid).where)

    def mistake_values(self, only: set[str]) -> dict[str, list[np.ndarray]]:
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return {oid: [np.asarray(f(*self.values), dtype=float).ravel() for f in funcs]
                    for oid, funcs in self.p.mistakes if oid in only}


_LEVEL = {1: "velocity", 2: "acceleration"}


def _split_free(J: np.ndarray, unknown: list[int]) -> tuple[list[int], list[int]]:
    """Which unknowns the position equations determine (pivoted QR), and which stay free."""
    if J.size == 0:
        return [], list(unknown)
    with np.errstate(all="ignore"):
        _, R, piv = linalg.qr(J, pivoting=True, mode="economic")
    diag = np.abs(np.diag(R)) if R.size else np.zeros(0)
    rank = int((diag > RANK_TOL * max(diag.max(initial=0.0), 1.0)).sum())
    determined = sorted(unknown[j] for j in piv[:rank])
    free = sorted(unknown[j] for j in piv[rank:])
    return determined, free


def _nullspace(A: np.ndarray) -> np.ndarray:
    if A.shape[0] == 0:
        return np.eye(A.shape[1])
    _, s, vt = linalg.svd(A)
    rank = int((s > RANK_TOL * max(s.max(initial=0.0), 1.0)).sum())
    return vt[rank:].T


def _solve_numeric(problem: Problem, p: _Plan, givens: dict,
                   only: set[str]) -> tuple[_Instant, dict]:
    """Solve the instant and evaluate the numeric objectives in ``only``; raise if any of them
    depends on something the givens leave free."""
    inst = _Instant(problem, p, givens)
    free_pos = inst.position()
    inst.free |= set(free_pos)
    null_v = inst.rates(1)
    null_a = inst.rates(2)
    base = inst.objective_values(only)
    base_values = inst.values.copy()
    # Probe each freedom the givens leave: an objective that changes depends on it.
    depends: dict[str, list[str]] = {}
    probes = [("position", i) for i in free_pos]
    probes += [("velocity", j) for j in range(null_v.shape[1])]
    probes += [("acceleration", j) for j in range(null_a.shape[1])]
    for level, which in probes:
        trial = _Instant(problem, p, givens)
        if level == "position":
            trial.position({which: base_values[which] + 0.37})
            trial.rates(1)
            trial.rates(2)
            missing = str(p.symbols[which])
        elif level == "velocity":
            trial.position({i: base_values[i] for i in free_pos})
            z = np.zeros(null_v.shape[1])
            z[which] = 0.73
            trial.rates(1, z)
            trial.rates(2)
            missing = _rate_names(p, [i for i in range(p.n_config, p.n_config + inst.n)
                                      if not inst.known[i]], null_v[:, which])
        else:
            trial.position({i: base_values[i] for i in free_pos})
            trial.rates(1, np.zeros(null_v.shape[1]))
            z = np.zeros(null_a.shape[1])
            z[which] = 0.73
            trial.rates(2, z)
            missing = _rate_names(p, [i for i in range(p.n_config + inst.n, len(p.symbols))
                                      if not inst.known[i]], null_a[:, which])
        changed = trial.objective_values(only)
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
    return inst, base


def _rate_names(p: _Plan, unknown_idx: list[int], direction: np.ndarray) -> str:
    names = [str(p.symbols[i]) for i, w in zip(unknown_idx, direction) if abs(w) > 1e-6]
    return " or ".join(names) if names else "a rate"


def _close(a: np.ndarray, b: np.ndarray) -> bool:
    if a.shape != b.shape:
        return False
    if not (np.isfinite(a).all() and np.isfinite(b).all()):
        return np.array_equal(np.isfinite(a), np.isfinite(b))
    scale = max(np.abs(a).max(initial=0.0), 1e-12)
    return bool(np.abs(a - b).max(initial=0.0) <= PROBE_TOL * scale + 1e-12)


# ---------------------------------------------------------------------------- symbolic


def _symbolic(problem: Problem, k: Kinematics, objective: Objective, givens: dict):
    meanings = symbol_meanings(problem, objective)
    declared = {name: k.quantity(node) for name, node in meanings.items()}
    given_symbols = {}
    for key, (node, si, given) in givens.items():
        if isinstance(node, (Name, Prime)):
            given_symbols[k.quantity(node)] = (key, si, given)
    known = set(declared.values()) | set(given_symbols)
    # A zero is a zero in every unit: such givens may always stand in.
    zeros = {sym: sp.Integer(0) for sym, (_, si, _) in given_symbols.items()
             if si == 0 and sym not in declared.values()}
    expr = _simplify(k.objective(objective.id).xreplace(zeros))
    for level, rates, equations in ((2, k.qdd, k.acceleration), (1, k.qd, k.velocity),
                                    (0, k.q, k.position)):
        unknown = [s for s in rates if s not in known]
        needed = [str(u) for u in unknown if u in expr.free_symbols]
        if not needed:
            continue
        eqs = [e.expr.xreplace(zeros) for e in equations]
        solution = sp.solve(eqs, unknown, dict=True) if eqs else []
        if len(solution) != 1:
            reason = ("several solutions" if solution else
                      "no constraint fixes it" if not eqs else "no solution")
            raise UnderdeterminedError(
                f"objective '{objective.id}' cannot be solved symbolically for "
                f"{', '.join(needed)} ({reason}); declare it among the symbols or give it",
                where=objective.where)
        expr = _simplify(expr.xreplace(solution[0]))
    # Pure-number givens (angles, tooth counts) may stand in; givens with units may not.
    extra = {}
    for sym in expr.free_symbols - set(declared.values()):
        entry = given_symbols.get(sym)
        if entry is not None and (entry[2] is None or si_unit(entry[2].unit) in ("", "rad")):
            extra[sym] = _exact(entry)
    if extra:
        expr = _simplify(expr.xreplace(extra))
    leftover = expr.free_symbols - set(declared.values())
    if leftover:
        names = ", ".join(sorted(str(s) for s in leftover))
        raise SolveError(f"symbolic objective '{objective.id}' depends on {names}, which is "
                         f"not among its symbols ({', '.join(declared)}); add it to symbols",
                         where=objective.where)
    rename = {sym: sp.Symbol(name, **sym.assumptions0) for name, sym in declared.items()}
    return expr.xreplace(rename), meanings


def _simplify(expr):
    if sp.count_ops(expr) > 300:
        return expr
    simple = sp.simplify(expr)
    return simple if sp.count_ops(simple) <= sp.count_ops(expr) else expr


def _exact(entry) -> sp.Expr:
    key, si, given = entry
    if given is None:
        return sp.Float(si)
    value = sp.Rational(repr(given.value)) if math.isfinite(given.value) else sp.Float(si)
    unit = given.unit
    if unit in ("deg", "degree"):
        return value * sp.pi / 180
    if unit in ("", "rad", "radian"):
        return value
    return sp.Float(si)


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
    base_inst = None
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
        inst, values, mistakes = None, {}, {}
        if numeric:
            inst, values = _solve_numeric(problem, p, given_map, numeric)
            inst.check_requirements(numeric)
            mistakes = inst.mistake_values(numeric)
            if not overrides or base_inst is None:
                base_inst = inst
        for obj in objectives:
            if obj.kind == "symbolic":
                frozen = tuple(sorted(given_map.items(), key=lambda item: item[0]))
                results[obj.id] = _symbolic_result(problem, obj.id, frozen)
            else:
                results[obj.id] = _numeric_result(obj, values[obj.id], mistakes.get(obj.id, ()))
    return Solution(problem=problem.id,
                    results=tuple(results[o.id] for o in problem.objectives if o.id in wanted),
                    state=_state(problem, p, base_inst), dof=degrees_of_freedom(k, base_inst))


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
    expr, meanings = _symbolic(problem, plan(problem).k, obj, dict(givens))
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


def degrees_of_freedom(k: Kinematics, inst: "_Instant | None" = None) -> int:
    """Coordinates minus independent constraint equations (rank of the velocity-level
    constraints in the rates, at the instant when it is solved)."""
    if inst is not None:
        return len(k.coordinates) - inst.constraint_rank
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


def _state(problem: Problem, p: _Plan, inst: _Instant | None) -> tuple[StateValue, ...]:
    if inst is None:
        return ()
    units = {c.name: c.unit for c in problem.coordinates}
    units.update({q.name: q.unit for q in problem.parameters})
    out = []
    n = inst.n
    for i, sym in enumerate(p.symbols):
        value = inst.values[i]
        if not np.isfinite(value) or i in inst.free:
            continue
        name = str(sym)
        if i < p.n_config:
            unit = si_unit(units.get(name, "s"))
        else:
            base = p.k.coordinates[(i - p.n_config) % n]
            order = 1 if i < p.n_config + n else 2
            unit = si_unit(f"({units[base] or '1'}) / s^{order}")
        out.append(StateValue(name, float(value), unit, bool(inst.known[i])))
    return tuple(out)
