"""The numeric instant: every level solved, the root chosen knowingly, freedoms probed, and
every given and constraint checked against the solution.

Several roots (assembly branches, a degenerate configuration, the launch and the landing of a
projectile, the two senses of a given speed) are an error when they give different answers and
the spec did not pick one (``guesses:`` or ``branch:``). Degenerate configurations (two points
coinciding, a singular constraint Jacobian) are warnings.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from ..errors import AuthorWarning, Location, MechgradeError, SolveError, UnderdeterminedError
from ..spec.model import Problem
from ..units import from_si
from .levels import (SAME_ROOT, Givens, State, configurations, evaluate, missing_values,
                     place_givens, rows, solve_linear_columns,
                     solve_nonlinear_columns)
from .columns import call, quiet
from .plan import KinematicsPlan
from . import rules
from .rules import satisfied, unchanged

SINGULAR = 1e-3


@dataclass(frozen=True)
class Candidate:
    """One complete solution of the levels: the state, the nullspaces of the linear rate
    levels, the unknowns the non-linear levels left free, and whether every choice of root on
    the way was the spec's."""

    state: State
    nulls: tuple[np.ndarray | None, np.ndarray | None]
    free: tuple[int, ...]
    picked: bool


@dataclass(frozen=True)
class Instant:
    """The solved instant: the chosen state, each numeric objective's SI values or error, and
    the warnings found on the way."""

    state: State
    values: Mapping[str, np.ndarray]
    errors: Mapping[str, MechgradeError]
    warnings: tuple[AuthorWarning, ...]


@dataclass(frozen=True)
class _Probe:
    """One freedom of a solved instant moved, to be solved again near its root (``start``):
    the values the free unknowns keep (one of them moved), and the shifts along the rate
    levels' null spaces."""

    free_values: Mapping[int, float] | None
    shifts: tuple[np.ndarray | None, np.ndarray | None]
    start: np.ndarray


def solve_numeric(problem: Problem, p: KinematicsPlan, givens: Mapping, only: set[str]) -> Instant:
    """Solve the instant and evaluate the numeric objectives in ``only``.

    Raises when the instant itself cannot be solved; an objective that depends on something
    the givens leave free gets its own error in :attr:`Instant.errors`.
    """
    (instant,) = solve_numeric_columns(problem, p, [givens], only, alone=True)
    if isinstance(instant, MechgradeError):
        raise instant
    return instant


def solve_numeric_columns(problem: Problem, p: KinematicsPlan, givens: Sequence[Mapping],
                          only: set[str], *, alone: bool = False, probe: bool = True,
                          near: np.ndarray | None = None) -> list[Instant | MechgradeError]:
    """:func:`solve_numeric` of many instants, one per ``givens``: each one's instant or the
    error that function raises for it. The non-linear levels of all of them are solved
    together, every start of every instant at once (:func:`~.levels.solve_nonlinear_columns`);
    which roots are distinct, which one the spec asks for and what the instant then is are
    judged as for one instant. ``alone``: each start solved by scipy's least squares (as
    :func:`solve_numeric` solves one instant, :func:`~.levels.solve_nonlinear_columns`).
    Without ``probe``, the objectives the givens leave undetermined are not looked for
    (:attr:`Instant.errors` is empty: values wanted whatever they depend on). ``near``: each
    instant's non-linear levels solved from this state alone (a root a class of variants
    continues from), not from the spread of starts.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve.plan import kinematics_plan
    >>> from mechgrade.solve.instant import instant_givens
    >>> problem = load_problem(shipped_dir("problems") / "airplane_crosswind_heading.yaml")
    >>> p = kinematics_plan(problem)
    >>> fine, off = solve_numeric_columns(
    ...     problem, p, [instant_givens(problem, {"w'": w}, {}) for w in (10.0, 100.0)],
    ...     {"heading"})
    >>> round(float(np.degrees(fine.values["heading"][0])), 4)  # asin(10 / 66.67)
    8.6269
    >>> "the velocity equations were not solved" in str(off)  # 100 m/s > 66.67 m/s
    True
    """
    with quiet():  # once, not at each of its dozens of function calls
        return _solved_columns(problem, p, givens, only, alone, probe, near)


def _solved_columns(problem: Problem, p: KinematicsPlan, givens: Sequence[Mapping],
                    only: set[str], alone: bool, probe: bool, near: np.ndarray | None
                    ) -> list[Instant | MechgradeError]:
    out: list[Instant | MechgradeError | None] = [None] * len(givens)
    placed: dict[int, Givens] = {}
    for i, given in enumerate(givens):
        try:
            placed[i] = _placed(problem, p, given, only)
        except MechgradeError as err:
            out[i] = err
    chosen: dict[int, tuple[Givens, Candidate, dict]] = {}
    starts = None if near is None else dict.fromkeys(placed, _Probe(None, (None, None), near))
    for i, found in _branches_columns(problem, p, placed, probes=starts, alone=alone).items():
        try:
            if isinstance(found, MechgradeError):
                raise found
            chosen[i] = (placed[i], *_chosen(problem, p, placed[i], givens[i], found, only))
        except MechgradeError as err:
            out[i] = err
    # with no objective to read, no freedom can move one
    errors = _undetermined(problem, p, chosen, only, alone) if probe and only else {}
    warned = _degenerate(problem, p, {i: base for i, (_, base, _) in chosen.items()},
                         {i: [k for k in p.index.config if not g.known[k] and k not in base.free]
                          for i, (g, base, _) in chosen.items()})
    for i, (_, base, values) in chosen.items():
        found_errors = errors.get(i, {})
        if isinstance(found_errors, MechgradeError):
            out[i] = found_errors
            continue
        out[i] = Instant(base.state, values, found_errors, warned[i])
    return out  # type: ignore[return-value]


def _placed(problem: Problem, p: KinematicsPlan, givens: Mapping, only: set[str]) -> Givens:
    """``givens`` placed (:func:`~.levels.place_givens`), refused when a parameter an
    equation or objective needs has no value."""
    g = place_givens(problem, p, givens)
    missing = missing_values(p, g, only)
    if missing:
        raise _missing_error(problem, p, missing[0])
    return g


def _branches_columns(problem: Problem, p: KinematicsPlan, placed: Mapping[int, Givens], *,
                      probes: Mapping[int, _Probe] | None = None, alone: bool = False
                      ) -> dict[int, list[Candidate] | MechgradeError]:
    """Every complete solution of each instant in ``placed`` (each root of each non-linear
    level followed to the end), or the error met first following the roots in order; each
    level solved for all of them at once. ``probes``: each instant a probe of the freedoms
    of one solved before (:class:`_Probe`), re-solved near its root."""
    errors: dict[int, tuple[tuple[int, ...], MechgradeError]] = {}

    def failed(i: int, at: tuple[int, ...], err: MechgradeError) -> None:
        # the error met first following the roots depth first, as _branches meets it
        if i not in errors or at < errors[i][0]:
            errors[i] = (at, err)

    keys = list(placed)
    gs = [placed[i] for i in keys]
    # (instant, roots taken, state, nullspaces, unknowns left free, picked by the spec)
    paths: list[tuple[int, tuple[int, ...], State, tuple, tuple[int, ...], bool]] = []
    free_values = {i: probes[i].free_values if probes else None for i in keys}
    start = {i: probes[i].start if probes else None for i in keys}
    firsts = solve_nonlinear_columns(problem, p, 0, [State(g.values.copy(), g.known)
                                                     for g in gs], gs,
                                     [free_values[i] for i in keys], [start[i] for i in keys],
                                     alone=alone)
    for i, first in zip(keys, firsts):
        if isinstance(first, MechgradeError):
            failed(i, (), first)
            continue
        paths += [(i, (k,), s, (), first.free, first.picked)
                  for k, s in enumerate(first.states)]
    for order in (1, 2):
        level = p.levels[order]
        grown = []
        if level.linear:
            solved = solve_linear_columns(
                problem, p, order, [path[2] for path in paths],
                [placed[path[0]] for path in paths],
                [probes[path[0]].shifts[order - 1] if probes else None for path in paths])
            for (i, at, _, nulls, free, picked), linear in zip(paths, solved):
                if isinstance(linear, MechgradeError):
                    failed(i, at, linear)
                    continue
                grown.append((i, at + (0,), linear[0], nulls + (linear[1],), free, picked))
        else:
            roots = solve_nonlinear_columns(problem, p, order, [path[2] for path in paths],
                                            [placed[path[0]] for path in paths],
                                            [free_values[path[0]] for path in paths],
                                            [start[path[0]] for path in paths], alone=alone)
            for (i, at, _, nulls, free, picked), level_roots in zip(paths, roots):
                if isinstance(level_roots, MechgradeError):
                    failed(i, at, level_roots)
                    continue
                grown += [(i, at + (k,), r, nulls + (None,), free + level_roots.free,
                           picked and level_roots.picked)
                          for k, r in enumerate(level_roots.states)]
        paths = grown
    out: dict[int, list[Candidate] | MechgradeError] = {
        i: errors[i][1] if i in errors else [] for i in keys}
    for i, _, s, nulls, free, picked in paths:
        found = out[i]
        if not isinstance(found, MechgradeError):
            found.append(Candidate(s, (nulls[0], nulls[1]), free, picked))
    return out


def _chosen(problem: Problem, p: KinematicsPlan, g: Givens, givens: Mapping,
            candidates: list[Candidate], only: set[str]) -> tuple[Candidate, dict]:
    """The instant from every complete solution of its levels (:func:`_branches_columns`),
    and the objectives ``only`` there: refused when they give different answers, else the
    first, its givens checked to hold."""
    base = candidates[0]
    values = evaluate(p.objectives, base.state, only)
    distinct = [base]
    for c in candidates[1:]:
        other = evaluate(p.objectives, c.state, only)
        if any(not _close(values[o], other[o]) for o in values) and \
                not any(_same_answers(p, d, c, only) for d in distinct[1:]):
            distinct.append(c)
    if len(distinct) > 1:
        raise _ambiguous(problem, p, g, distinct)
    _check_givens_hold(problem, p, g, givens, base.state)
    return base, values


def _same_answers(p: KinematicsPlan, a: Candidate, b: Candidate, only) -> bool:
    va, vb = evaluate(p.objectives, a.state, only), evaluate(p.objectives, b.state, only)
    return all(_close(va[o], vb[o]) for o in va)


def _ambiguous(problem: Problem, p: KinematicsPlan, g: Givens,
               branches: list[Candidate]) -> SolveError:
    states = [b.state.values for b in branches]
    free = set().union(*(b.state.free for b in branches))

    def differs(i):
        first = states[0][i]
        return not g.known[i] and i not in free and any(
            not rules.same_value(first, s[i]) for s in states[1:]
            if np.isfinite(s[i]) and np.isfinite(first))

    differ = [i for i in range(p.index.size) if differs(i)]
    order = min((p.index.level_of(i) for i in differ), default=0)
    differ = [i for i in differ if p.index.level_of(i) == order]
    listing = configurations(problem, p, g, states, differ)
    preferred = [i for i in differ if i == p.index.time or p.index.is_parameter(i)] + differ
    example = f"{p.index.spelling(preferred[0])}: positive" if preferred else "x: positive"
    level = p.levels[order]
    active, _ = rows(level, g)
    # a non-linear given (a speed) is the likelier cause than the constraints
    lines = [i for i in range(level.constraint_rows, len(level.labels)) if active[i]] + \
        list(range(level.constraint_rows))
    where = level.wheres[lines[0]] if lines else Location()
    return SolveError(
        f"the {level.name} equations have {len(branches)} solutions that give different "
        f"answers: {listing}; pick one with guesses: (near the one meant) or a branch: "
        f"(e.g. branch: {{{example}}})", where=where)


def _missing_error(problem: Problem, p: KinematicsPlan, i: int) -> SolveError:
    name = p.index.spelling(i)
    where = next((q.where for q in problem.parameters if q.name == name), None)
    if where is None:  # t: point at the first equation that needs it
        where = next((level.wheres[r] for level in p.levels
                      for r, uses in enumerate(level.uses) if i in uses), Location())
    what = "time t" if i == p.index.time else f"parameter '{name}'"
    return SolveError(f"the {what} has no value: give it under givens:, or list it under "
                      f"unknown: to solve for it (with a branch: for the root wanted)",
                      where=where)


def _check_givens_hold(problem: Problem, p: KinematicsPlan, g: Givens, givens: Mapping,
                       state: State) -> None:
    """Every constraint and expression given, at every level, holds in ``state``."""
    for level in p.levels:
        active, target = rows(level, g)
        if not active.any():
            continue
        with np.errstate(all="ignore"):
            value = np.asarray(level.residual(*state.values), dtype=float).ravel()
            scale = np.abs(np.asarray(level.scale(*state.values), dtype=float).ravel())
        for i in np.flatnonzero(active):
            r = value[i] - target[i]
            if np.isfinite(value[i]) and satisfied(r, scale[i], problem.consistency):
                continue
            j = i - level.constraint_rows
            if j < 0:
                raise SolveError(f"the constraint '{level.labels[i]}' does not hold in the "
                                 f"solution (residual {r:.4g} against terms of size "
                                 f"{scale[i]:.4g})", where=level.wheres[i])
            key = level.conditions[j]
            _, _si, given = givens[key]
            unit = given.unit if given is not None else ""
            found = from_si(value[i], unit) if unit else value[i]
            raise SolveError(f"the given '{g.texts[key]}' does not hold in the solution: "
                             f"{key} is {found:.6g}{' ' + unit if unit else ''} there",
                             where=level.wheres[i])


def _undetermined(problem: Problem, p: KinematicsPlan,
                  chosen: Mapping[int, tuple[Givens, Candidate, dict]], only: set[str],
                  alone: bool) -> dict[int, dict[str, MechgradeError] | MechgradeError]:
    """Probe each freedom the givens leave each instant in ``chosen`` (its givens, solution
    and objectives' values), every probe of every instant solved at once: an objective that
    changes depends on it. An instant whose probe cannot be solved gets that error."""
    owner: list[tuple[int, str]] = []  # each probe's instant and what it moves
    placed: dict[int, Givens] = {}
    moved: dict[int, _Probe] = {}
    for i, (g, base, values) in chosen.items():
        if not values:  # no objective asked for here (an instant of a dynamics solve): none
            continue    # can depend on a freedom
        for missing, probe in _probes(p, g, base):
            placed[len(owner)], moved[len(owner)] = g, probe
            owner.append((i, missing))
    trials = _branches_columns(problem, p, placed, probes=moved, alone=alone) if owner else {}
    found: dict[int, dict[str, list[str]] | MechgradeError] = {i: {} for i in chosen}
    for k, (i, missing) in enumerate(owner):
        depends, trial = found[i], trials[k]
        if isinstance(depends, MechgradeError):
            continue  # the first probe that fails is the instant's error
        if isinstance(trial, MechgradeError):
            found[i] = trial
            continue
        changed = evaluate(p.objectives, trial[0].state, only)
        for oid, value in chosen[i][2].items():
            if not _close(value, changed[oid]):
                depends.setdefault(oid, []).append(missing)
    return {i: depends if isinstance(depends, MechgradeError) else {
        oid: UnderdeterminedError(
            f"objective '{oid}' is not determined by the givens: give a value for "
            f"{' or '.join(missing)}", where=problem.objective(oid).where)
        for oid, missing in depends.items()} for i, depends in found.items()}


def _probes(p: KinematicsPlan, g: Givens, base: Candidate):
    """``(what it moves, probe)`` for each freedom of the solution ``base``: each free
    unknown moved, then each direction of the velocity and acceleration null spaces."""
    state = base.state
    keep = {i: state.values[i] for i in base.free}
    for which in base.free:
        level = p.levels[p.index.level_of(which)].name
        yield (f"{p.index.spelling(which)} ({level} level)",
               _Probe({**keep, which: keep[which] + 0.37}, (None, None), state.values))
    null_v, null_a = base.nulls
    for order, kind, null in ((1, "velocity", null_v), (2, "acceleration", null_a)):
        for which in range(null.shape[1] if null is not None else 0):
            assert null is not None
            z = np.zeros(null.shape[1])
            z[which] = 0.73
            zero_v = np.zeros(null_v.shape[1]) if null_v is not None else None
            shifts = (z, None) if order == 1 else (zero_v, z)
            unknown = [i for i in p.index.rates(order) if not g.known[i]]
            yield (f"{_rate_names(p, unknown, null[:, which])} ({kind} level)",
                   _Probe(keep, shifts, state.values))


def _degenerate(problem: Problem, p: KinematicsPlan, bases: Mapping[int, Candidate],
                solved: Mapping[int, list[int]]) -> dict[int, tuple[AuthorWarning, ...]]:
    """Warnings for a degenerate configuration the position solve landed on, at each
    instant (:func:`degenerate` of those that solved the same positions, together)."""
    together: dict[tuple[int, ...], list[int]] = {}
    for i in bases:
        together.setdefault(tuple(solved[i]), []).append(i)
    wheres = {q.name: q.where for q in problem.points}
    out: dict[int, tuple[AuthorWarning, ...]] = {}
    for positions, keys in together.items():
        X = np.stack([bases[i].state.values for i in keys], axis=1)
        pairs, singular = degenerate(p, X, list(positions))
        for j, i in enumerate(keys):
            warned = [AuthorWarning(f"degenerate configuration: points {p.points[b]} and "
                                    f"{p.points[a]} coincide in the solution",
                                    wheres.get(p.points[a], Location()))
                      for a, b, flagged in pairs if flagged[j]]
            if singular[j]:
                warned.append(AuthorWarning(
                    "degenerate configuration: the position constraints are singular in the "
                    "solution (their Jacobian loses rank: a dead point or a folded linkage)",
                    p.levels[0].wheres[0]))
            out[i] = tuple(warned)
    return out


def degenerate(p: KinematicsPlan, X: np.ndarray, solved: list[int]
               ) -> tuple[list[tuple[int, int, np.ndarray]], np.ndarray]:
    """Where the states ``X`` (one per column) are degenerate configurations, the positions
    ``solved`` having been solved for: for each pair of points ``(a, b, columns)``, the
    columns where they coincide but not in the configurations around (the solved positions
    moved); and the columns where the position constraints' Jacobian is singular, far weaker
    (its rank-th singular value) than around."""
    n = X.shape[1]
    if not solved:
        return [], np.zeros(n, dtype=bool)
    size = p.index.size
    other = X[:size].copy()
    other[solved] = other[solved] * 1.13 + 0.07
    pairs = []
    count = len(p.points)
    if count > 1:
        here = call(p.point_positions, X[:size], 3 * count).reshape(3, count, n)
        there = call(p.point_positions, other, 3 * count).reshape(3, count, n)
        finite = np.where(np.isfinite(here), np.abs(here), 0.0)
        scale = SAME_ROOT * np.maximum(finite.max(axis=(0, 1)), 1e-12)
        # every pair's distances at once (pairs x N): numpy calls per pair of points were
        # most of the time of a small solve
        a, b = np.tril_indices(count, -1)
        close = np.abs(here[:, a] - here[:, b]).max(axis=0) <= scale
        always = np.abs(there[:, a] - there[:, b]).max(axis=0) <= scale
        flagged = close & ~always
        pairs = [(int(a[k]), int(b[k]), flagged[k]) for k in range(len(a))]
    singular = np.zeros(n, dtype=bool)
    if p.levels[0].constraint_rows and p.constraint_rank:
        singular = _weakest(p, X[:size]) < SINGULAR * _weakest(p, other)
    return pairs, singular


def _weakest(p: KinematicsPlan, X: np.ndarray) -> np.ndarray:
    """The rank-th singular value of the position constraints' Jacobian in the coordinates
    (NaN where it is undefined), at every column."""
    level = p.levels[0]
    n = X.shape[1]
    ncols = len(p.index.unknowns(0))
    J = call(level.jacobian, X, len(level.labels) * ncols).reshape(
        len(level.labels), ncols, n)[:level.constraint_rows, :p.index.n]
    finite = np.isfinite(J).all(axis=(0, 1))
    sv = np.linalg.svd(np.where(finite, J, 0.0).transpose(2, 0, 1), compute_uv=False)
    rank = p.constraint_rank
    weakest = sv[:, rank - 1] if sv.shape[1] >= rank else np.zeros(n)
    return np.where(finite, weakest, np.nan)


def _rate_names(p: KinematicsPlan, unknown: list[int], direction: np.ndarray) -> str:
    names = [p.index.spelling(i) for i, w in zip(unknown, direction) if abs(w) > 1e-6]
    return " or ".join(names) if names else "a rate"


def _close(a: np.ndarray, b: np.ndarray) -> bool:
    return a.shape == b.shape and bool(unchanged(a[:, None], b[:, None])[0])