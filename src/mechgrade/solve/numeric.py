"""The numeric instant: every level solved, the root chosen knowingly, freedoms probed, and
every given and constraint checked against the solution.

Several roots (assembly branches, a degenerate configuration, the launch and the landing of a
projectile, the two senses of a given speed) are an error when they give different answers and
the spec did not pick one (``guesses:`` or ``branch:``). Degenerate configurations (two points
coinciding, a singular constraint Jacobian) are warnings.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Mapping, Sequence

import numpy as np

from ..errors import AuthorWarning, Location, MechgradeError, SolveError, UnderdeterminedError
from ..spec.model import Problem
from ..units import from_si
from .levels import (SAME_ROOT, Givens, Near, State, configurations, evaluate, missing_values,
                     place_givens, residuals, rows, solve_linear_columns,
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


def solve_numeric(problem: Problem, p: KinematicsPlan, givens: Mapping, only: set[str]) -> Instant:
    """Solve the instant and evaluate the numeric objectives in ``only``.

    Raises when the instant itself cannot be solved; an objective that depends on something
    the givens leave free gets its own error in :attr:`Instant.errors`.
    """
    (instant,) = solve_numeric_columns(problem, p, [givens], only)
    if isinstance(instant, MechgradeError):
        raise instant
    return instant


def solve_numeric_columns(problem: Problem, p: KinematicsPlan, givens: Sequence[Mapping],
                          only: set[str]) -> list[Instant | MechgradeError]:
    """:func:`solve_numeric` of many instants, one per ``givens``: each one's instant or the
    error that function raises for it. The non-linear levels of all of them are solved
    together, every start of every instant at once (:func:`~.levels.solve_nonlinear_columns`);
    which roots are distinct, which one the spec asks for and what the instant then is are
    judged as for one instant.

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
        return _solved_columns(problem, p, givens, only)


def _solved_columns(problem: Problem, p: KinematicsPlan, givens: Sequence[Mapping],
                    only: set[str]) -> list[Instant | MechgradeError]:
    out: list[Instant | MechgradeError | None] = [None] * len(givens)
    placed: dict[int, Givens] = {}
    for i, given in enumerate(givens):
        try:
            placed[i] = _placed(problem, p, given, only)
        except MechgradeError as err:
            out[i] = err
    chosen: dict[int, tuple[Candidate, dict]] = {}
    for i, found in _branches_columns(problem, p, placed).items():
        try:
            if isinstance(found, MechgradeError):
                raise found
            chosen[i] = _chosen(problem, p, placed[i], found, only)
        except MechgradeError as err:
            out[i] = err
    keys = list(chosen)
    for i, error in zip(keys, _givens_not_holding(problem, p, [
            (placed[i], givens[i], chosen[i][0].state) for i in keys])):
        if error is not None:
            out[i] = error
            del chosen[i]
    probed = _undetermined(problem, p, {i: (placed[i], *c) for i, c in chosen.items()}, only)
    solved = {i: tuple(j for j in p.index.config if not placed[i].known[j]
                       and j not in base.free)
              for i, (base, _) in chosen.items() if not isinstance(probed[i], MechgradeError)}
    warned = _degenerate(problem, p, {i: (chosen[i][0].state, solved[i]) for i in solved})
    for i, (base, values) in chosen.items():
        errors = probed[i]
        if isinstance(errors, MechgradeError):  # a probe of its freedoms not solved
            out[i] = errors
            continue
        out[i] = Instant(base.state, values, errors, warned[i])
    return out  # type: ignore[return-value]


def every_branch_columns(problem: Problem, p: KinematicsPlan, givens: Sequence[Mapping],
                         only: set[str]) -> list[list[dict]]:
    """The objectives in ``only`` on every distinct solution of the levels of each instant of
    ``givens`` (its values as :func:`solve_numeric` gives them, one dict each; none where
    the instant is not solved): where the spec's choice of root is dropped
    (:func:`~mechgrade.spec.constraint_mutations.position_unchosen`), each assembly branch,
    the givens checked to hold on it."""
    out: list[list[dict]] = [[] for _ in givens]
    placed: dict[int, Givens] = {}
    with quiet():
        for i, given in enumerate(givens):
            try:
                placed[i] = _placed(problem, p, given, only)
            except MechgradeError:
                continue
        found = [(i, c) for i, roots in _branches_columns(problem, p, placed).items()
                 if not isinstance(roots, MechgradeError) for c in roots]
        # a root the screens refuse is no configuration: every root judged at once
        holding = [(i, c) for (i, c), error in zip(found, _givens_not_holding(
            problem, p, [(placed[i], givens[i], c.state) for i, c in found])) if error is None]
        kept: dict[int, list[Candidate]] = {}
        for i, c in holding:
            mine = kept.setdefault(i, [])
            if not any(_same_answers(p, k, c, only) or _same_configuration(p, k, c)
                       for k in mine):
                mine.append(c)
        for i, mine in kept.items():
            out[i] = [evaluate(p.objectives, c.state, only) for c in mine]
    return out


def _same_configuration(p: KinematicsPlan, a: Candidate, b: Candidate) -> bool:
    """Whether every point is at the same place in both (coordinates read another way, an
    angle half a turn on and a length reversed along it: no other assembly)."""
    count = len(p.points)
    if not count:
        return False
    here, there = (call(p.point_positions, c.state.values[:, None], 3 * count).ravel()
                   for c in (a, b))
    return bool(np.all(_coincide(np.abs(here - there), np.nanmax(np.abs(here), initial=0.0))))


def _coincide(gap, largest) -> np.ndarray:
    """Whether places ``gap`` apart (each coordinate) are one place: within
    :data:`~.levels.SAME_ROOT` of the ``largest`` coordinate there (and of 1e-12 m).

    >>> _coincide(np.array([1e-5, 1e-3]), 1.0).tolist()
    [True, False]
    """
    return gap <= SAME_ROOT * np.maximum(largest, 1e-12)


def _placed(problem: Problem, p: KinematicsPlan, givens: Mapping, only: set[str]) -> Givens:
    """``givens`` placed (:func:`~.levels.place_givens`), refused when a parameter an
    equation or objective needs has no value."""
    g = place_givens(problem, p, givens)
    missing = missing_values(p, g, only)
    if missing:
        raise _missing_error(problem, p, missing[0])
    return g


Probe = tuple[Mapping[int, float] | None, tuple[np.ndarray | None, np.ndarray | None],
              np.ndarray | None]
"""A probe of an instant's freedoms, re-solved near its root: the values of the unknowns the
non-linear levels leave free, the shifts along the rate levels' nullspaces, and the state the
starts are replaced by."""


def _branches_columns(problem: Problem, p: KinematicsPlan, placed: Mapping[int, Givens],
                      probes: Mapping[int, Probe] | None = None
                      ) -> dict[int, list[Candidate] | MechgradeError]:
    """Every complete solution of each instant in ``placed`` (each root of each non-linear
    level followed to the end), or the error met first following the roots in order; each
    level solved for all of them at once. ``probes[i]``: instant ``i`` is a probe of its
    freedoms."""
    errors: dict[int, tuple[tuple[int, ...], MechgradeError]] = {}

    def failed(i: int, at: tuple[int, ...], err: MechgradeError) -> None:
        # the error met first following the roots depth first (one root after another)
        if i not in errors or at < errors[i][0]:
            errors[i] = (at, err)

    keys = list(placed)
    gs = [placed[i] for i in keys]
    # (instant, roots taken, state, nullspaces, unknowns left free, picked by the spec)
    paths: list[tuple[int, tuple[int, ...], State, tuple, tuple[int, ...], bool]] = []

    def near(i: int) -> Near:
        return (probes[i][0], probes[i][2]) if probes else (None, None)

    firsts = solve_nonlinear_columns(problem, p, 0, [State(g.values.copy(), g.known)
                                                     for g in gs], gs,
                                     [near(i) for i in keys])
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
            for k, solved in _linear(problem, p, order, [(path[2], placed[path[0]])
                                                         for path in paths],
                                     [probes[path[0]][1][order - 1] if probes else None
                                      for path in paths]).items():
                i, at, _, nulls, free, picked = paths[k]
                if isinstance(solved, MechgradeError):
                    failed(i, at, solved)
                    continue
                s1, null = solved
                grown.append((i, at + (0,), s1, nulls + (null,), free, picked))
        else:
            roots = solve_nonlinear_columns(problem, p, order, [path[2] for path in paths],
                                            [placed[path[0]] for path in paths],
                                            [near(path[0]) for path in paths])
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


def _linear(problem: Problem, p: KinematicsPlan, order: int, paths: list[tuple[State, Givens]],
            shifts: list[np.ndarray | None]
            ) -> dict[int, tuple[State, np.ndarray] | MechgradeError]:
    """The linear rate level ``order`` at each ``(state, givens)`` of ``paths`` (moved by its
    ``shifts`` along the nullspace, where a probe gives one): the solved state and the
    nullspace basis of its unknown rates, or the error; those with the same givens known and
    rows active solved together (:func:`~.levels.solve_linear_columns`)."""
    placed = [rows(p.levels[order], g) for _, g in paths]  # (active, target) of each
    together: dict[object, list[int]] = {}
    for k, (_, g) in enumerate(paths):
        key = (g.known.tobytes(), placed[k][0].tobytes())
        together.setdefault(key, []).append(k)
    out: dict[int, tuple[State, np.ndarray] | MechgradeError] = {}
    for members in together.values():
        gs = [paths[k][1] for k in members]
        # the states hold their givens (every level writes only its unknowns)
        X, targets = (paths[members[0]][0].values[:, None], placed[members[0]][1][:, None]) \
            if len(members) == 1 else \
            (np.stack([paths[k][0].values for k in members], axis=1),
             np.stack([placed[k][1] for k in members], axis=1))
        active = placed[members[0]][0]
        solved = solve_linear_columns(problem, p, order, X, gs[0].known, active, targets,
                                      gs.__getitem__, [shifts[k] for k in members])
        for j, k in enumerate(members):
            error = solved.errors[j]
            out[k] = error if error is not None else (solved.state(j, paths[k][0], gs[j]),
                                                      solved.null(j))
    return dict(sorted(out.items()))


def _chosen(problem: Problem, p: KinematicsPlan, g: Givens, candidates: list[Candidate],
            only: set[str]) -> tuple[Candidate, dict]:
    """The solution of the instant among every complete solution of its levels
    (:func:`_branches_columns`) and its objectives' values: refused when they give different
    answers, else the first (its givens then checked to hold, :func:`_givens_not_holding`)."""
    base = candidates[0]
    values = evaluate(p.objectives, base.state, only)
    distinct = [base]
    for c in candidates[1:]:
        other = evaluate(p.objectives, c.state, only)
        if _differing(values, other) and \
                not any(_same_answers(p, d, c, only) for d in distinct[1:]):
            distinct.append(c)
    if len(distinct) > 1:
        raise _ambiguous(problem, p, g, distinct)
    return base, values


def _same_answers(p: KinematicsPlan, a: Candidate, b: Candidate, only) -> bool:
    va, vb = evaluate(p.objectives, a.state, only), evaluate(p.objectives, b.state, only)
    return not _differing(va, vb)


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


def _givens_not_holding(problem: Problem, p: KinematicsPlan,
                        instants: Sequence[tuple[Givens, Mapping, State]]
                        ) -> list[SolveError | None]:
    """Whether every constraint and expression given, at every level, holds at each instant
    (placed givens, givens, state): the error naming the first that does not, or ``None``;
    each level's residuals evaluated at every instant at once."""
    out: list[SolveError | None] = [None] * len(instants)
    for level in p.levels:
        placed = [rows(level, g) for g, _, _ in instants]
        todo = [k for k, (active, _) in enumerate(placed) if active.any() and out[k] is None]
        if not todo:
            continue
        values, scales = residuals(level, np.stack([instants[k][2].values for k in todo], axis=1),
                                   slice(None), np.zeros((1, 1)))
        r = values - np.stack([placed[k][1] for k in todo], axis=1)
        wrong = np.stack([placed[k][0] for k in todo], axis=1) & ~(
            np.isfinite(values) & satisfied(r, scales, problem.consistency))
        for column in np.flatnonzero(wrong.any(axis=0)):
            k = todo[column]
            out[k] = _not_holding(level, instants[k][0], instants[k][1],
                                  int(np.flatnonzero(wrong[:, column])[0]), values[:, column],
                                  r[:, column], scales[:, column])
    return out


def _not_holding(level, g: Givens, givens: Mapping, i: int, value, r, scale) -> SolveError:
    j = i - level.constraint_rows
    if j < 0:
        return SolveError(f"the constraint '{level.labels[i]}' does not hold in the "
                          f"solution (residual {r[i]:.4g} against terms of size "
                          f"{scale[i]:.4g})", where=level.wheres[i])
    key = level.conditions[j]
    _, _si, given = givens[key]
    unit = given.unit if given is not None else ""
    found = from_si(value[i], unit) if unit else value[i]
    return SolveError(f"the given '{g.texts[key]}' does not hold in the solution: "
                      f"{key} is {found:.6g}{' ' + unit if unit else ''} there",
                      where=level.wheres[i])


def _undetermined(problem: Problem, p: KinematicsPlan,
                  instants: Mapping[int, tuple[Givens, Candidate, dict]], only: set[str]
                  ) -> dict[int, dict[str, MechgradeError] | MechgradeError]:
    """Probe each freedom the givens leave at each instant (``(givens, solution, objectives'
    values)``): an objective that changes depends on it. Every probe of every instant is
    solved together, each a column (:func:`_branches_columns`); an instant whose probe is not
    solved gets the error of its first such probe."""
    out: dict[int, dict[str, MechgradeError] | MechgradeError] = {}
    probes = {i: _probes(p, g, base) if values else [] for i, (g, base, values) in
              instants.items()}  # no objective asked here (a dynamics instant): none moves
    depends: dict[int, dict[str, list[str]]] = {i: {} for i in instants}
    # (instant, probe) of each column, the k-th probes of all the instants before the k+1-th
    columns = [(i, k) for k in range(max(map(len, probes.values()), default=0))
               for i, probe in probes.items() if k < len(probe)]
    trials = _branches_columns(problem, p, {m: instants[i][0] for m, (i, _) in
                                            enumerate(columns)},
                               {m: probes[i][k][0] for m, (i, k) in enumerate(columns)}
                               ) if columns else {}
    solved: list[tuple[int, np.ndarray]] = []  # (column, its state) of each probe solved
    for m, (i, _) in enumerate(columns):
        found = trials[m]
        if i in out:
            continue
        if isinstance(found, MechgradeError):
            out[i] = found
        else:
            solved.append((m, found[0].state.values))
    if solved:  # every probed instant's objectives at once (compared by rules.unchanged)
        X = np.stack([values for _, values in solved], axis=1)
        for oid, f in p.objectives:
            if oid not in only:
                continue
            before = np.stack([instants[columns[m][0]][2][oid] for m, _ in solved], axis=1)
            for (m, _), same in zip(solved, unchanged(before, call(f, X, len(before)))):
                if not same:
                    i, k = columns[m]
                    depends[i].setdefault(oid, []).append(probes[i][k][1])
    for i in instants:
        out.setdefault(i, {oid: UnderdeterminedError(
            f"objective '{oid}' is not determined by the givens: give a value for "
            f"{' or '.join(missing)}", where=problem.objective(oid).where)
            for oid, missing in depends[i].items()})
    return out


FREE_PROBE = 0.37
"""How far a probe moves an unknown a non-linear level leaves free (SI)."""

NULL_PROBE = 0.73
"""How far a probe moves the unknown rates along a direction of their null space (the basis
is orthonormal)."""


@dataclass(frozen=True)
class Freedom:
    """One freedom the givens leave at an instant, as a probe moves it: an unknown a
    non-linear level leaves free (``position``), or a ``direction`` of the null space of the
    linear rate level ``order``. A probe re-solves the levels from :attr:`first` on."""

    order: int
    position: int | None = None
    direction: int | None = None

    @property
    def first(self) -> int:
        return self.order if self.position is not None else self.order + 1

    def shift(self, nullity: int) -> np.ndarray:
        """The probe's move in the null space's coordinates (``nullity`` directions)."""
        z = np.zeros(nullity)
        z[self.direction] = NULL_PROBE
        return z


def freedoms(p: KinematicsPlan, free, nullity: Mapping[int, int]) -> list[Freedom]:
    """What the probes of an instant move, in order: each unknown in ``free`` a non-linear
    level leaves free, then each direction of the velocity and acceleration levels' null
    spaces (``nullity[order]`` of them): the one probe rule of an instant and of a class.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve.plan import kinematics_plan
    >>> p = kinematics_plan(load_problem(shipped_dir("problems") / "gear_between_two_racks.yaml"))
    >>> freedoms(p, [], {1: 1, 2: 0})
    [Freedom(order=1, position=None, direction=0)]
    """
    out = [Freedom(p.index.level_of(i), position=i) for i in free
           if not (p.levels[p.index.level_of(i)].linear and p.index.level_of(i) > 0)]
    return out + [Freedom(order, direction=j) for order in (1, 2)
                  for j in range(nullity.get(order, 0))]


def _probes(p: KinematicsPlan, g: Givens, base: Candidate) -> list[tuple[Probe, str]]:
    """Each probe of the freedoms of the instant ``base`` (:data:`Probe`, :func:`freedoms`),
    with the freedom it moves as a message names it."""
    state = base.state
    keep = {i: state.values[i] for i in base.free}
    nulls = dict(zip((1, 2), base.nulls))
    nullity = {order: null.shape[1] for order, null in nulls.items() if null is not None}
    out: list[tuple[Probe, str]] = []
    for freedom in freedoms(p, base.free, nullity):
        i, order = freedom.position, freedom.order
        if i is not None:
            level = p.levels[order].name
            out.append((({**keep, i: keep[i] + FREE_PROBE}, (None, None), state.values),
                        f"{p.index.spelling(i)} ({level} level)"))
            continue
        null = nulls[order]
        assert null is not None  # a probe of this level exists only with its null space
        z = freedom.shift(null.shape[1])
        zero_v = np.zeros(nullity[1]) if 1 in nullity else None
        shifts = (z, None) if order == 1 else (zero_v, z)
        unknown = [k for k in p.index.rates(order) if not g.known[k]]
        out.append(((keep, shifts, state.values),
                    f"{_rate_names(p, unknown, null[:, freedom.direction])} "
                    f"({p.levels[order].name} level)"))
    return out


def _degenerate(problem: Problem, p: KinematicsPlan,
                instants: Mapping[int, tuple[State, tuple[int, ...]]]
                ) -> dict[int, tuple[AuthorWarning, ...]]:
    """Warnings for a degenerate configuration the position solve landed on at each instant
    (its state, the positions solved for): :func:`degenerate` over the instants that solved
    for the same positions at once."""
    wheres = {q.name: q.where for q in problem.points}
    groups: dict[tuple[int, ...], list[int]] = {}
    for i, (_, solved) in instants.items():
        groups.setdefault(solved, []).append(i)
    out: dict[int, tuple[AuthorWarning, ...]] = {}
    for solved, keys in groups.items():
        X = np.stack([instants[i][0].values for i in keys], axis=1)
        pairs, singular = degenerate(p, X, list(solved))
        for j, i in enumerate(keys):
            found = [AuthorWarning(f"degenerate configuration: points {p.points[b]} and "
                                   f"{p.points[a]} coincide in the solution",
                                   wheres.get(p.points[a], Location()))
                     for a, b, flagged in pairs if flagged[j]]
            if singular[j]:
                found.append(AuthorWarning(
                    "degenerate configuration: the position constraints are singular in the "
                    "solution (their Jacobian loses rank: a dead point or a folded linkage)",
                    p.levels[0].wheres[0]))
            out[i] = tuple(found)
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
        largest = finite.max(axis=(0, 1))
        # every pair's distances at once (pairs x N): numpy calls per pair of points were
        # most of the time of a small solve
        a, b = _pairs(count)
        close = _coincide(np.abs(here[:, a] - here[:, b]).max(axis=0), largest)
        always = _coincide(np.abs(there[:, a] - there[:, b]).max(axis=0), largest)
        flagged = close & ~always
        pairs = [(int(a[k]), int(b[k]), flagged[k]) for k in range(len(a))]
    singular = np.zeros(n, dtype=bool)
    if p.levels[0].constraint_rows and p.constraint_rank:
        singular = _weakest(p, X[:size]) < SINGULAR * _weakest(p, other)
    return pairs, singular


@lru_cache(maxsize=64)
def _pairs(count: int) -> tuple[np.ndarray, np.ndarray]:
    """Every pair ``(a, b)``, ``a > b``, of ``count`` points (made once per count: a small
    solve's pairs took as long as their distances)."""
    return np.tril_indices(count, -1)


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
    names = [p.index.spelling(i) for i, is_open in zip(unknown, rules.left_open(direction).tolist())
             if is_open]
    return " or ".join(names) if names else "a rate"


def _differing(before: Mapping[str, np.ndarray], after: Mapping[str, np.ndarray]) -> set[str]:
    """The objectives whose value in ``after`` is not the one in ``before``
    (:func:`~.rules.unchanged`), compared at once: each objective's values a column, padded
    with zeros (a single solve compares a few values a few dozen times).

    >>> sorted(_differing({"a": np.array([1.0]), "b": np.array([0.0, 2.0, np.nan])},
    ...                   {"a": np.array([1.1]), "b": np.array([0.0, 2.0, np.nan])}))
    ['a']
    """
    out = {o for o in before if before[o].shape != after[o].shape}
    ids = [o for o in before if o not in out]
    if ids:
        size = max(before[o].size for o in ids)
        a, b = np.zeros((size, len(ids))), np.zeros((size, len(ids)))
        for j, o in enumerate(ids):
            a[:before[o].size, j], b[:after[o].size, j] = before[o], after[o]
        out.update(o for o, same in zip(ids, unchanged(a, b)) if not same)
    return out