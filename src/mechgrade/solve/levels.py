"""Solving the instant level by level, as pure functions of a
:class:`~.plan.KinematicsPlan`, the givens placed in its state layout (:class:`Givens`) and the
state solved so far (:class:`State`).

A level whose equations are linear in its unknowns (the velocity and acceleration constraints,
givens that are components) is solved by least squares, with its nullspace (the combinations of
rates the givens leave free). Any other level — the position level, a speed or magnitude
given — is solved numerically from a few deterministic starts; every distinct root found is
returned (the caller chooses among them knowingly). Ranks say which unknowns the equations
leave free.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Callable, Mapping, Sequence

import numpy as np

# scipy is imported by the functions that use it: it takes longer to import than a whole
# `mechgrade check` of most problems, which never needs it.

from ..errors import InconsistentError, Location, MechgradeError, SolveError
from ..expressions.syntax import Name, Prime, to_text
from ..spec.model import Problem, Root
from ..units import from_si
from . import rules
from .columns import (FirstErrors, call, determinant, least_squares,
                      least_squares_solution, quiet)
from .plan import Level, KinematicsPlan, per_problem
from .rules import first_off, on_branch, satisfied

DEFAULT_GUESS = 0.3
JOINT_SPREADS = (0.5, 2.0, 8.0)
SAME_ROOT = 1e-4


@dataclass(frozen=True)
class Givens:
    """The givens of one solve in the state layout.

    ``values`` (NaN where not given) and ``known``; ``solvable`` marks what the solver may solve
    for (coordinates, rates, and the parameters or ``t`` listed under ``unknown:``);
    ``conditions[level][key]`` the expression givens (SI); ``texts``/``wheres`` each given as
    written and where, for messages; ``guess`` start values (``guessed`` where the spec gave
    them); ``branches`` the root each position wants; ``scales`` a typical size of each
    position (the givens of its unit: :func:`_scales`), which roots are told apart by.
    """

    values: np.ndarray
    known: np.ndarray
    solvable: np.ndarray
    conditions: tuple[Mapping[str, float], Mapping[str, float], Mapping[str, float]]
    texts: Mapping[str, str]
    wheres: Mapping[str, Location]
    guess: np.ndarray
    guessed: np.ndarray
    branches: Mapping[int, Root]
    scales: np.ndarray
    # each level's rows (:func:`rows`) by its order, worked out when first asked: a solve
    # asks for them at every stage (the starts, the screens, the probes)
    rows: dict[int, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict,
                                                           compare=False, repr=False)


@dataclass(frozen=True)
class State:
    """The quantities at the instant (``values``, in the state layout, SI); ``given`` marks
    the given positions, ``free`` those nothing determined (their values are arbitrary picks)."""

    values: np.ndarray
    given: np.ndarray
    free: frozenset[int] = frozenset()


def place_givens(problem: Problem, p: KinematicsPlan, givens: Mapping) -> Givens:
    """``givens`` (canonical key -> (key node, SI value, Given or None)) in ``p``'s layout."""
    index = p.index
    values = np.full(index.size, np.nan)
    known = np.zeros(index.size, dtype=bool)
    conditions: tuple[dict[str, float], dict[str, float], dict[str, float]] = ({}, {}, {})
    texts, wheres = {}, {}
    for key, (node, si, given) in givens.items():
        texts[key] = f"{key} = {given.text}" if given is not None else f"{key} = {si:g} (SI)"
        wheres[key] = given.where if given is not None else Location()
        if isinstance(node, (Name, Prime)):
            try:
                i = p.position(node)
            except (KeyError, ValueError):
                raise SolveError(f"cannot give '{key}': not a coordinate, rate, parameter "
                                 "or t of this problem") from None
            values[i] = si
            known[i] = True
        else:
            levels = [level.order for level in p.levels if key in level.conditions]
            if not levels:
                raise SolveError(f"cannot give '{key}': it is not a given of this problem "
                                 "(expression givens must appear in the spec)")
            conditions[levels[0]][key] = si
    solvable, guess, guessed, branches = per_problem(_layout, problem, p)
    return Givens(values, known, solvable, conditions, texts, wheres, guess, guessed, branches,
                  _scales(problem, p, values, known))


def _layout(problem: Problem, p: KinematicsPlan) -> tuple:
    """What of :class:`Givens` the spec fixes whatever the givens: which positions may be
    solved for, each one's guess and whether the spec guessed it, the branches asked for."""
    index = p.index
    unknown = {u.text.strip() for u in problem.unknowns}
    solvable = np.array([not (index.is_parameter(i) or i == index.time)
                         or index.names[i] in unknown for i in range(index.size)])
    guesses = {to_text(g.key.node): g.si for g in problem.guesses}
    guessed = np.array([index.names[i] in guesses for i in range(index.size)])
    guess = np.array([guesses.get(index.names[i], DEFAULT_GUESS) for i in range(index.size)])
    branches = {index.position(to_text(b.key.node)): b.root for b in problem.branches}
    for shared in (solvable, guess, guessed):  # every solve of the problem reads these
        shared.setflags(write=False)
    return solvable, guess, guessed, branches


def _scales(problem: Problem, p: KinematicsPlan, values, known) -> np.ndarray:
    """A typical size for each position, from the givens of the same unit (angles: pi).
    ``values`` holds one state (size) or one per column (size x N): the sizes then are too."""
    return typical_sizes(problem, p, np.asarray(values, dtype=float)[:, None],
                         known)[:, 0] if np.ndim(values) == 1 else \
        typical_sizes(problem, p, values, known)


def typical_sizes(problem: Problem, p: KinematicsPlan, values: np.ndarray, known) -> np.ndarray:
    """:func:`_scales` of every column of ``values`` (size x N): the median of the nonzero
    givens of each unit, in each column."""
    groups, angles = per_problem(_unit_groups, problem, p)
    out = np.ones((p.index.size, values.shape[1]))
    for positions in groups:
        given = positions[known[positions]]
        if len(given):
            out[positions] = _median(np.abs(values[given]))
    out[angles] = np.pi
    return out


def _unit_groups(problem: Problem, p: KinematicsPlan) -> tuple[list[np.ndarray], np.ndarray]:
    """The positions of ``p``'s layout grouped by unit (:func:`_units`), angles apart: the
    groups :func:`typical_sizes` takes a median of, and the angles (a typical size of pi)."""
    of = _units(problem, p)
    angles = np.array([unit in ("rad", "deg", "degree", "radian") for unit in of], dtype=bool)
    groups: dict[str, list[int]] = {}
    for i, unit in enumerate(of):
        if not angles[i]:
            groups.setdefault(unit, []).append(i)
    return [np.array(positions) for positions in groups.values()], angles


def _median(values: np.ndarray) -> np.ndarray:
    """The median of each column's nonzero entries (1 where there are none), as
    ``numpy.median`` gives it, without the import of numpy's masked arrays that
    ``numpy.median`` makes (milliseconds of every ``check``)."""
    if values.shape[1] == 1 and np.isfinite(values).all():
        # one instant: the same picks from a list, without numpy's per-call overhead
        nonzero = sorted(v for v in values[:, 0].tolist() if v != 0)
        count = len(nonzero)
        if count == 0:
            return np.ones(1)
        middle = count // 2
        return np.array([nonzero[middle] if count % 2 == 1
                         else (nonzero[middle - 1] + nonzero[middle]) / 2])
    ordered = np.sort(np.where(values != 0, values, np.inf), axis=0)
    count = (values != 0).sum(axis=0)
    middle = count // 2
    columns = np.arange(values.shape[1])
    upper = ordered[np.minimum(middle, len(ordered) - 1), columns]
    lower = ordered[np.maximum(middle - 1, 0), columns]
    return np.where(count == 0, 1.0, np.where(count % 2 == 1, upper, (lower + upper) / 2))


def _units(problem: Problem, p: KinematicsPlan) -> list[str]:
    """The unit of each position of ``p``'s layout (SI text, ``rad/s^2`` for a rate)."""
    units = {c.name: c.unit for c in problem.coordinates}
    units.update({q.name: q.unit for q in problem.parameters})
    return [_unit_of(p.index, units, i) for i in range(p.index.size)]


def _unit_of(index, units, i) -> str:
    if i == index.time:
        return "s"
    name = index.coordinate_of(i) or index.names[i]
    unit = units.get(name, "")
    order = index.level_of(i) if index.coordinate_of(i) else 0
    return unit if order == 0 else f"{unit}/s^{order}"


def rows(level: Level, g: Givens) -> tuple[np.ndarray, np.ndarray]:
    """Which rows are active (constraints, and the conditions given in this solve), and the
    value each row must equal (0 for constraints); read-only, kept with ``g``."""
    kept = g.rows.get(level.order)
    if kept is not None:
        return kept
    n = level.constraint_rows
    if not level.conditions:  # most levels have none: the constraints alone, every solve's
        kept = g.rows[level.order] = _constraints_only(n)
        return kept
    active = np.ones(n + len(level.conditions), dtype=bool)
    target = np.zeros(n + len(level.conditions))
    values = np.array([g.conditions[level.order].get(key, np.nan)
                       for key in level.conditions])
    active[n:] = ~np.isnan(values)
    target[n:] = values if np.isfinite(values).all() else np.nan_to_num(values)
    for shared in (active, target):  # every stage of the solve reads these
        shared.setflags(write=False)
    g.rows[level.order] = (active, target)
    return active, target


@lru_cache(maxsize=None)
def _constraints_only(n: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`rows` of a level of ``n`` constraints and no condition (read-only, shared)."""
    active, target = np.ones(n, dtype=bool), np.zeros(n)
    for shared in (active, target):
        shared.setflags(write=False)
    return active, target


def missing_values(p: KinematicsPlan, g: Givens, only: set[str]) -> list[int]:
    """Parameters and ``t`` that have no value and may not be solved for, yet are needed by an
    equation or by an objective in ``only``."""
    missing = set(np.flatnonzero(~(g.known | g.solvable)).tolist())
    if not missing:
        return []
    needed: set[int] = set()
    for level in p.levels:
        active, _ = rows(level, g)
        for uses, on in zip(level.uses, active):
            if on:
                needed |= uses
    for oid, uses in p.objective_uses:
        if oid in only:
            needed |= uses
    return sorted(missing & needed)


# ---------------------------------------------------------------------------- non-linear


@dataclass(frozen=True)
class Roots:
    """The distinct solutions of a non-linear level (states), the first from the first start;
    ``free`` the unknowns the equations left free; ``picked`` whether the spec chose the root
    (guesses or a branch)."""

    states: tuple[State, ...]
    free: tuple[int, ...]
    picked: bool


def solve_nonlinear(problem: Problem, p: KinematicsPlan, order: int, state: State, g: Givens,
                    free_values: Mapping[int, float] | None = None,
                    start: np.ndarray | None = None) -> Roots:
    """Solve level ``order`` numerically for its unknowns.

    Unknowns the equations determine are solved by least squares from the spec's guesses (only
    those, when the spec guessed any of them), else from a few deterministic starts spread
    around them; the others keep their guess (or ``free_values``) and are free. ``start`` (a
    whole state) replaces the starts: re-solving near a root already chosen.
    """
    (roots,) = solve_nonlinear_columns(problem, p, order, [state], [g], [(free_values, start)])
    if isinstance(roots, MechgradeError):
        raise roots
    return roots


def solve_nonlinear_columns(problem: Problem, p: KinematicsPlan, order: int,
                            states: Sequence[State], givens: Sequence[Givens],
                            near: Sequence[Near] | None = None
                            ) -> list[Roots | MechgradeError]:
    """:func:`solve_nonlinear` of many instants (``states[i]`` with ``givens[i]``, and
    ``near[i]`` its ``(free_values, start)`` when re-solved near a root), each column's roots
    or the error that function raises for it: the same starts, every start of
    every column solved together by Levenberg-Marquardt steps on the stacked Jacobians
    (:func:`levenberg_marquardt`), the roots then chosen by the same rules.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve.plan import kinematics_plan
    >>> from mechgrade.solve.instant import instant_givens
    >>> problem = load_problem(shipped_dir("problems") / "airplane_crosswind_heading.yaml")
    >>> p = kinematics_plan(problem)
    >>> places = [place_givens(problem, p, instant_givens(problem, {"w'": w}, {}))
    ...           for w in (10.0, 100.0)]
    >>> states = [solve_nonlinear(problem, p, 0, State(g.values.copy(), g.known), g).states[0]
    ...           for g in places]
    >>> fine, off = solve_nonlinear_columns(problem, p, 1, states, places)
    >>> round(float(fine.states[0].values[p.index.position("b'")]), 4)  # sqrt(66.67² - 10²)
    65.9124
    >>> type(off).__name__
    'SolveError'
    """
    with quiet():  # once, not at each column's functions (a class's thousands)
        return _nonlinear_columns(problem, p, order, states, givens, near)


def _nonlinear_columns(problem: Problem, p: KinematicsPlan, order: int,
                       states: Sequence[State], givens: Sequence[Givens],
                       near: Sequence[Near] | None) -> list[Roots | MechgradeError]:
    out: list[Roots | MechgradeError | _Setup] = []
    for state, g, (free_values, start) in zip(states, givens,
                                              near or [(None, None)] * len(states)):
        try:
            out.append(_set_up(problem, p, order, state, g, free_values, start))
        except MechgradeError as err:
            out.append(err)
    pending = [i for i, s in enumerate(out) if isinstance(s, _Setup)]
    setups = [s for s in out if isinstance(s, _Setup)]
    level = p.levels[order]
    fits = _fits(problem.consistency, level, setups)
    for i, setup, found in zip(pending, setups, fits):
        try:
            out[i] = _chosen(problem, p, setup, found)
        except MechgradeError as err:
            out[i] = err
    return out  # type: ignore[return-value]


Near = tuple[Mapping[int, float] | None, np.ndarray | None]
"""An instant re-solved near a root already chosen: the values of the unknowns its equations
leave free, and the whole state its starts are replaced by (:func:`solve_nonlinear`)."""


@dataclass(frozen=True)
class _Setup:
    """One instant's non-linear level ready for its starts: the state (``x``, the free
    unknowns placed), the unknowns the equations determine and those they leave ``free``,
    the starts (values of the determined, a row each), whether the spec picked the root,
    the rows that hold and what each must equal."""

    order: int
    g: Givens
    state: State
    x: np.ndarray
    columns: tuple[int, ...]
    determined: list[int]
    free: list[int]
    starts: np.ndarray
    picked: bool
    active: np.ndarray
    target: np.ndarray


def _set_up(problem: Problem, p: KinematicsPlan, order: int, state: State, g: Givens,
            free_values: Mapping[int, float] | None = None,
            start: np.ndarray | None = None) -> _Setup | Roots:
    """The level set up for its starts (:class:`_Setup`), or its roots when there is nothing
    to solve for (no unknown, or no equation)."""
    level = p.levels[order]
    columns = list(p.index.unknowns(order))
    active, target = rows(level, g)
    x = state.values.copy()
    known, solvable = g.known[columns].tolist(), g.solvable[columns].tolist()
    unknown = [i for i, k, s in zip(columns, known, solvable) if not k and s]
    origin = g.guess if start is None else start
    x[unknown] = origin[unknown]
    x[[i for i, k, s in zip(columns, known, solvable) if not k and not s]] = np.nan
    if not unknown or not active.any():
        for i in unknown:
            x[i] = (free_values or {}).get(i, x[i])
        result = State(x, g.known, state.free | frozenset(unknown))
        error = _unsolved(problem, level, g, x, active, target, 0, 1) if active.any() else None
        if error is not None:
            raise error
        return Roots((result,), tuple(unknown), True)
    position = {c: j for j, c in enumerate(columns)}
    # Equal default guesses can make a Jacobian singular (two angles both 0.3): which unknowns
    # the equations determine is read where it is not.
    place = [position[i] for i in unknown]
    determined, free = _split_free(_evaluate(x, level.jacobian, (
        len(level.labels), len(columns)))[active][:, place], unknown)
    if free:  # else none is left free: the nearby read cannot determine more
        nearby = x.copy()
        nearby[unknown] += 0.1 * (1 + np.arange(len(unknown))) * g.scales[unknown]
        there = _split_free(_evaluate(nearby, level.jacobian, (
            len(level.labels), len(columns)))[active][:, place], unknown)
        if len(there[0]) > len(determined):
            determined, free = there
    # equations linear in the unknowns at hand (the rest given) have one root: one start
    linear = not (level.jacobian_uses & set(determined))
    for i in free:
        x[i] = (free_values or {}).get(i, x[i])
    picked_by_guess = start is not None or bool(g.guessed[determined].any())
    picked = picked_by_guess or any(i in g.branches for i in determined)
    starts = x[determined][None, :]
    if not picked_by_guess and not linear:
        starts = np.concatenate([starts, _starts(x[determined], g.scales[determined], order)])
    return _Setup(order, g, state, x, tuple(columns), determined, free, starts, picked,
                  active, target)


def _evaluate(full, f, shape):
    with quiet():
        return np.asarray(f(*full), dtype=float).reshape(shape)


@dataclass(frozen=True)
class _Ends:
    """Where each start of one setup ended (:func:`_fits`): the whole states (a column
    each), half the sum of the squared residuals of each, whether it started where the
    equations are defined, and whether the level holds there (:func:`~.rules.satisfied`)."""

    X: np.ndarray
    cost: list[float]
    started: list[bool]
    held: list[bool]

LM_STEPS = 200
"""Steps a start may take (the residuals evaluated at most this many times)."""

FIT_TOL = 1e-14
"""A start has converged when its step is below this part of its unknowns, or its cost falls
by less than this part of itself."""

DAMPING = 1e-3
"""Levenberg-Marquardt's first damping (a part of each unknown's scale) from a start spread
around a guess: short steps first, which keep to the root the start is in the basin of."""

NEAR_DAMPING = 1e-12
""":data:`DAMPING` from a root already found for nearby values (a class's reference root):
nearly Newton's steps, which reach the root that root continues to in a few."""


def _fits(consistency: float, level: Level, setups: Sequence[_Setup]) -> list[_Ends | None]:
    """Each start of each setup solved (``None``: a setup that determines nothing), every
    start of every one at once (those determining the same unknowns from the same rows
    stacked as columns) by :func:`solve_level_columns`, an unknown near zero judged against
    its typical size."""
    out: list[_Ends | None] = [None] * len(setups)
    groups: dict[tuple, list[tuple[int, int]]] = {}
    for i, s in enumerate(setups):
        if s.determined:
            groups.setdefault((tuple(s.determined), s.active.tobytes()), []).extend(
                (i, k) for k in range(len(s.starts)))
    for pairs in groups.values():
        first = setups[pairs[0][0]]
        # each setup's state, targets and sizes stacked once, then repeated for its starts
        members = {i: j for j, i in enumerate(dict.fromkeys(i for i, _ in pairs))}
        owner = np.array([members[i] for i, _ in pairs])
        X = np.stack([setups[i].x for i in members], axis=1)[:, owner]
        X[first.determined] = np.concatenate([setups[i].starts for i in members]).T
        T = np.stack([setups[i].target for i in members], axis=1)[first.active][:, owner]
        # the first start (the guess) by Gauss-Newton's steps, as a trust region takes them
        # inside it; the others spread around it kept to their basins by short steps first
        first_damping = np.array([NEAR_DAMPING if k == 0 else DAMPING for _, k in pairs])
        sizes = np.stack([setups[i].g.scales for i in members], axis=1)[first.determined][
            :, owner]
        fits = solve_level_columns(consistency, level, X, first.determined,
                                   list(first.columns), first.active, T, first_damping, sizes)
        cost, started, held = (v.tolist() for v in (fits.cost, fits.started, fits.held))
        at = 0  # each setup's starts are side by side, in its order
        for i in members:
            n = len(setups[i].starts)
            out[i] = _Ends(fits.X[:, at:at + n], cost[at:at + n], started[at:at + n],
                           held[at:at + n])
            at += n
    return out


@dataclass(frozen=True)
class LevelColumns:
    """A non-linear level solved at every column (:func:`solve_level_columns`): the states
    ``X``, half the sum of the squared residuals of each, which columns started where the
    equations are defined and which hold the level (:func:`~.rules.satisfied`, and stopped
    before the step cap)."""

    X: np.ndarray
    cost: np.ndarray
    started: np.ndarray
    held: np.ndarray


def solve_level_columns(consistency: float, level: Level, X: np.ndarray,
                        determined: list[int], columns: list[int], active: np.ndarray,
                        T: np.ndarray, first_damping: float | np.ndarray = DAMPING,
                        sizes: np.ndarray | None = None) -> LevelColumns:
    """The non-linear level's ``active`` rows (each must equal its row of ``T``) solved for
    the positions ``determined`` at every column of ``X``, each from its own start (its
    column: a single solve's starts, a class's reference root) by
    :func:`levenberg_marquardt` (by one least-squares step where the equations are linear
    in them: their Jacobian does not depend on them), and judged there: the one non-linear
    solver of an instant and of a class of variants. A column whose steps reach
    :data:`LM_STEPS` without meeting a test to stop does not hold the level, whatever its
    residual: where the cap stopped it is no root. ``first_damping`` (one, or one per
    column): :data:`DAMPING` from starts spread around a guess, :data:`NEAR_DAMPING` from a
    root already found or from the guess itself. ``sizes`` (the typical size of each
    unknown ``determined``, one column each): an unknown a root puts within
    :data:`~.rules.ON_BRANCH` of its size of zero is zero where the level holds no worse
    there (a root at zero is found as zero, not as a rounding of it).

    >>> level = Level(0, "position", lambda x, y: [[x**2 + y**2 - 25], [x - 3]],
    ...               lambda x, y: [[2 * x, 2 * y], [1 + 0 * x, 0 * y]],
    ...               lambda x, y: [[x**2 + y**2 + 25], [x + 3]], ("c", "x"),
    ...               (), (), False, (), frozenset({0, 1}))
    >>> fits = solve_level_columns(1e-9, level, np.array([[1.0, 1.0], [1.0, -1.0]]),
    ...                            [0, 1], [0, 1], np.ones(2, bool), np.zeros((2, 2)))
    >>> fits.X[1].round(12).tolist(), fits.held.tolist()
    ([4.0, -4.0], [True, True])
    >>> level_rank(level, fits.X, [0, 1], [0, 1], np.ones(2, bool)).tolist()
    [2, 2]
    """
    with quiet():  # once, not at each of the steps' function calls
        if level.jacobian_uses & set(determined):
            X, cost, started, stopped = levenberg_marquardt(level, X, determined, columns,
                                                            active, T, first_damping)
        else:  # linear in the unknowns at hand: one least-squares step solves it
            X = X.copy()
            r, _ = residuals(level, X, active, T)
            J = _jacobians(level, X, len(columns), [columns.index(i) for i in determined],
                           active)
            started = np.isfinite(r).all(axis=0)
            good = started & np.isfinite(J).all(axis=(0, 1))
            step, _, _ = least_squares(J, r, good)
            X[determined] += np.where(good, step, 0.0)
            cost = 0.5 * (residuals(level, X, active, T)[0] ** 2).sum(axis=0)
            stopped = np.ones(X.shape[1], dtype=bool)
        if sizes is not None:
            X, cost = _zeros_kept(level, X, cost, determined, active, T, sizes)
        return LevelColumns(X, cost, started,
                            stopped & holds(consistency, level, X, active, T))


def _zeros_kept(level: Level, X: np.ndarray, cost: np.ndarray, determined: list[int],
                active: np.ndarray, T: np.ndarray, sizes: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """``X`` and ``cost`` with each unknown ``determined`` within :data:`~.rules.ON_BRANCH`
    of its typical size (``sizes``) of zero put at zero, in each column whose cost is no
    higher there."""
    near = X[determined]
    near = (near != 0) & rules.near_zero(near, sizes)
    if not near.any():
        return X, cost
    zeroed = X.copy()
    zeroed[determined] = np.where(near, 0.0, X[determined])
    with np.errstate(all="ignore"):
        at_zero = 0.5 * (residuals(level, zeroed, active, T)[0] ** 2).sum(axis=0)
    better = at_zero <= cost
    return np.where(better, zeroed, X), np.where(better, at_zero, cost)


def level_rank(level: Level, X: np.ndarray, determined: list[int], columns: list[int],
               active: np.ndarray) -> np.ndarray:
    """The rank of the Jacobian of ``level``'s ``active`` rows in the positions
    ``determined`` (of its unknowns ``columns``) at every column of ``X`` (0 where it is
    undefined): whether a root found determines them all."""
    J = _jacobians(level, X, len(columns), [columns.index(i) for i in determined], active)
    finite = np.isfinite(J).all(axis=(0, 1))
    s = np.linalg.svd(np.where(finite, J, 0.0).transpose(2, 0, 1), compute_uv=False)
    return np.where(finite, rules.rank(s), 0)


def _jacobians(level: Level, X: np.ndarray, ncols: int, place: list[int],
               active: np.ndarray) -> np.ndarray:
    """The Jacobian of ``level``'s ``active`` rows (in its ``ncols`` unknowns) in those at
    ``place``, at every column of ``X`` (rows x unknowns x N)."""
    nrows = len(level.labels)
    J = call(level.jacobian, X, nrows * ncols).reshape(nrows, ncols, X.shape[1])
    # (a solve's steps call this hundreds of times: no copy where every row is active or
    # every unknown placed in order)
    J = J if active.all() else J[active]
    return J if place == list(range(ncols)) else J[:, place]


def levenberg_marquardt(level: Level, X: np.ndarray, determined: list[int], columns: list[int],
                        active: np.ndarray, T: np.ndarray,
                        first_damping: float | np.ndarray = DAMPING
                        ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Solve ``level``'s ``active`` rows (each must equal its row of ``T``) for the positions
    ``determined`` at every column of ``X`` (the states, each from its own start), by
    Levenberg-Marquardt steps (Marquardt's scaling by the largest of each unknown's column
    norms yet, as MINPACK scales; the damping ``first_damping`` at first, divided by 3 after
    a step that lowers the cost and multiplied by 4 after one that does not). Each column stops on
    its own (its root does not depend on the columns solved with it) once its step is below
    :data:`FIT_TOL` of its unknowns, or its cost falls by less than that part of itself or to
    zero, or its gradient below :data:`FIT_TOL` (a stationary point: a double root is known no
    better), or after :data:`LM_STEPS` steps.
    Returns the states, half the sum of the squared residuals of each, which columns
    started where the equations are defined (the others are left as they came), and which
    stopped before the step cap (a test above met, or never started).

    A circle x² + y² = 25 with x = 3 (the state: x, y), from y = 1 and from y = -1:

    >>> level = Level(0, "position", lambda x, y: [[x**2 + y**2 - 25], [x - 3]],
    ...               lambda x, y: [[2 * x, 2 * y], [1 + 0 * x, 0 * y]], None, ("c", "x"),
    ...               (), (), False, (), frozenset())
    >>> X, cost, started, stopped = levenberg_marquardt(
    ...     level, np.array([[1.0, 1.0], [1.0, -1.0]]), [0, 1], [0, 1], np.ones(2, bool),
    ...     np.zeros((2, 2)))
    >>> X.round(12).tolist(), bool(cost.max() < 1e-20), started.tolist(), stopped.tolist()
    ([[3.0, 3.0], [4.0, -4.0]], True, [True, True], [True, True])
    """
    nrows, ncols = len(level.labels), len(columns)
    place = [columns.index(i) for i in determined]

    every_row = bool(active.all())

    def residual(Xs, Ts):
        values = call(level.residual, Xs, nrows)
        return (values if every_row else values[active]) - Ts

    def jacobian(Xs):
        return _jacobians(level, Xs, ncols, place, active)

    X = X.copy()
    r, J = residual(X, T), jacobian(X)
    with np.errstate(all="ignore"):
        cost = 0.5 * (r ** 2).sum(axis=0)
    started = np.isfinite(r).all(axis=0)
    live = started & np.isfinite(J).all(axis=(0, 1)) & (cost > 0)
    k = len(determined)
    eye = np.eye(k)[:, :, None]
    diagonal = (np.arange(k), np.arange(k))
    # the live columns only, each quantity a column per live column (``at``: where in X),
    # gathered once and narrowed when columns stop, not gathered and scattered at each step
    at = np.flatnonzero(live)
    Xw, Tw, r, J, cost_w = X[:, at], T[:, at], r[:, at], J[:, :, at], cost[at]
    damping = np.broadcast_to(np.asarray(first_damping, dtype=float), X.shape[1:])[at]
    # Marquardt's scaling, each unknown's largest yet (as MINPACK keeps it): an unknown whose
    # column of the Jacobian vanishes near a root (b at b² = 0) keeps a damping of its size
    scales = np.full((k, len(at)), 1e-300)
    with np.errstate(all="ignore"):
        size = _norms(Xw[determined])  # of each column's unknowns, kept with them

    def stop(stopping: np.ndarray) -> None:
        """The columns ``stopping`` (of the live ones) kept in ``X`` and ``cost``, and
        dropped from the live ones."""
        nonlocal at, Xw, Tw, r, J, cost_w, damping, scales, size
        gone = at[stopping]
        X[:, gone], cost[gone], live[gone] = Xw[:, stopping], cost_w[stopping], False
        going = np.flatnonzero(~stopping)  # (taken by index: one search, not nine)
        at, Xw, Tw, r, J, cost_w, damping, scales, size = (
            v.take(going, axis=-1) for v in (at, Xw, Tw, r, J, cost_w, damping, scales, size))

    with np.errstate(all="ignore"):
        for _ in range(LM_STEPS):
            grad, A = _normal_equations(J, r)
            # a stationary point (scipy's gtol): a double root is found no better
            flat_here = np.abs(grad).max(axis=0, initial=0.0) <= FIT_TOL
            if flat_here.any():
                stop(flat_here)
                grad, A = grad[:, ~flat_here], A[..., ~flat_here]
            if not len(at):
                break
            scales = np.maximum(scales, A[diagonal])
            step = least_squares_solution(A + eye * (damping * scales)[:, None, :], -grad)
            step = np.where(np.isfinite(step), step, 0.0)
            moved = Xw.copy()
            moved[determined] += step
            r_new = residual(moved, Tw)
            cost_new = 0.5 * (r_new ** 2).sum(axis=0)
            better = cost_new < cost_w  # NaN is not better
            small = _norms(step) <= FIT_TOL * (size + FIT_TOL)
            flat = better & (cost_w - cost_new <= FIT_TOL * cost_w)
            damping = np.where(better, damping / 3, damping * 4)
            done = small | flat | (damping > 1e30)
            # only a step taken changes a cost (to zero) or a Jacobian (to undefined); the
            # Jacobian worked out at the columns that took one only
            if better.all():
                Xw, r, cost_w = moved, r_new, cost_new
                J = jacobian(moved)
                size = _norms(moved[determined])
                done |= (cost_new == 0) | ~np.isfinite(J).all(axis=(0, 1))
            elif better.any():
                took = np.flatnonzero(better)
                there = moved.take(took, axis=1)
                Xw[:, took] = there
                r[:, took] = r_new.take(took, axis=1)
                cost_w[took] = cost_new[took]
                J[:, :, took] = fresh = jacobian(there)
                size[took] = _norms(there[determined])
                done[took] |= (cost_new[took] == 0) | ~np.isfinite(fresh).all(axis=(0, 1))
            if done.any():
                stop(done)
        X[:, at], cost[at] = Xw, cost_w  # those the step cap stopped
    return X, cost, started, ~live


def _normal_equations(J: np.ndarray, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``J``'s transpose times ``r`` and times ``J`` at every column (``J``: rows x unknowns x
    N, ``r``: rows x N), the same bits whatever layout they come in: those einsum gives
    columns gathered from a wider class (each column's entries side by side). With one
    unknown einsum sums a column's rows in SIMD lanes there (the order of the sums depends
    on the layout), so they are laid out so; with more it sums them row after row in any
    layout, so in C order, where it is ten times faster at hundreds of columns.

    >>> J, r = np.arange(12.0).reshape(2, 2, 3), np.ones((2, 3))
    >>> [v.tolist() for v in _normal_equations(J, r)][0]
    [[6.0, 8.0, 10.0], [12.0, 14.0, 16.0]]
    """
    if J.shape[1] == 1:
        J = np.ascontiguousarray(J[:, 0].T).T[:, None]
        r = np.ascontiguousarray(r.T).T
    else:
        J = np.ascontiguousarray(J)
    return np.einsum("aki,ai->ki", J, r), np.einsum("aki,ali->kli", J, J)


def _norms(V: np.ndarray) -> np.ndarray:
    """The Euclidean norm of each column of ``V`` (as ``numpy.linalg.norm(V, axis=0)``
    works it out, without its checks of the arguments)."""
    return np.sqrt(np.add.reduce(V * V, axis=0))


def _chosen(problem: Problem, p: KinematicsPlan, setup: _Setup, ends: _Ends | None
            ) -> Roots:
    """The roots of ``setup``'s level from where its starts ``ends``: the distinct ones
    that satisfy the level (the first from the first start), on the branch asked for and,
    for ``first positive``, the smallest; the errors :func:`solve_nonlinear` raises when
    none is."""
    level = p.levels[setup.order]
    g, determined = setup.g, setup.determined
    found: list[np.ndarray] = []
    best = None
    if ends is not None:
        sizes = g.scales[determined].tolist()
        values = ends.X[determined].T.tolist()  # each start's, told apart as numbers
        kept: list[list[float]] = []
        for k, (started, cost, held) in enumerate(zip(ends.started, ends.cost, ends.held)):
            if not started:
                continue
            if best is None or cost < best[0]:
                best = (cost, k)
            if held and not any(_same_values(sizes, values[k], other) for other in kept):
                kept.append(values[k])
                found.append(ends.X[:, k].copy())
    if not found:
        full = ends.X[:, best[1]].copy() if ends is not None and best is not None \
            else setup.x
        error = _unsolved(problem, level, g, full, setup.active, setup.target,
                          len(determined), len(setup.starts))
        assert error is not None, "no start solved the level, so a residual is left"
        raise error
    roots = [r for r in found if _on_branch(g, r, determined)]
    if not roots:
        wanted = "; ".join(f"{p.index.spelling(i)}: {g.branches[i].value}"
                           for i in determined if i in g.branches)
        listing = configurations(problem, p, g, found, determined)
        raise SolveError(f"no solution of the {level.name} equations is on the branch asked "
                         f"for ({wanted}); solutions found: {listing}",
                         where=_branch_where(problem))
    roots = _choose_branch(g, roots, determined)
    # (every field of the state is new: made, not replaced, at 2.5x less per root)
    free = setup.state.free | frozenset(setup.free)
    states = tuple(State(r, g.known, free) for r in roots)
    return Roots(states, tuple(setup.free), setup.picked)


def _starts(guess: np.ndarray, scale: np.ndarray, order: int) -> np.ndarray:
    """Deterministic starts around ``guess`` (one per row): each of the first four unknowns
    moved alone by 1 and 3 typical sizes either way (angles: a quarter and three quarters of a
    turn), then all of them moved together at random (a fixed seed) by a few spreads; made
    at once (a class sets up hundreds of instants).

    >>> _starts(np.array([1.0, 0.0]), np.array([2.0, np.pi]), 0)[:8].round(4).tolist()[::4]
    [[3.0, 0.0], [1.0, 1.5708]]
    """
    k = min(len(guess), 4)
    size = np.where(scale[:k] == np.pi, scale[:k] / 2, scale[:k])
    alone = np.repeat(guess[None, :], 4 * k, axis=0)
    alone[np.arange(4 * k), np.repeat(np.arange(k), 4)] += (size[:, None] * _STEPS).ravel()
    together = guess + _SPREADS * scale * _joint_draws(order, len(guess))
    return np.concatenate([alone, together])


_STEPS = np.array([1.0, -1.0, 3.0, -3.0])  # (a start's moves of one unknown, in sizes)
_SPREADS = np.array(JOINT_SPREADS)[:, None]


@lru_cache(maxsize=None)
def _joint_draws(order: int, count: int) -> np.ndarray:
    """The fixed random moves of :func:`_starts` (one row per spread), drawn once: every
    solve of a level of ``count`` unknowns gets the same ones."""
    rng = np.random.default_rng(11 + order)
    draws = np.array([rng.standard_normal(count) for _ in JOINT_SPREADS])
    draws.setflags(write=False)
    return draws


def residuals(level: Level, X: np.ndarray, active, T: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    """The residual of each of ``level``'s ``active`` rows (less what it must equal, its row
    of ``T``) and the size of its terms, at every column of ``X`` (rows x N each)."""
    if X.shape[1] == 1:  # one state: the functions at its numbers (call's arrays cost more)
        with quiet():
            r, scale = (np.asarray(f(*X[:, 0]), dtype=float).reshape(-1, 1)
                        for f in (level.residual, level.scale))
        return r[active] - T, np.abs(scale)[active]
    nrows = len(level.labels)
    return (call(level.residual, X, nrows)[active] - T,
            np.abs(call(level.scale, X, nrows))[active])


def holds(consistency: float, level: Level, X: np.ndarray, active: np.ndarray,
          T: np.ndarray) -> np.ndarray:
    """Whether ``level``'s ``active`` rows hold (each equals its row of ``T``, as
    :func:`~.rules.satisfied` judges it) at each column of ``X``."""
    return np.all(satisfied(*residuals(level, X, active, T), consistency), axis=0)


def same_root(scales: np.ndarray, a: np.ndarray, b: np.ndarray, positions) -> bool:
    """Whether two roots (states) are the same at ``positions`` (angles compared modulo a
    turn), each within :data:`SAME_ROOT` of the larger of its typical size (``scales``,
    :func:`typical_sizes`) and its values: a double root is only found that well.

    >>> scales = np.array([1.0, np.pi])
    >>> same_root(scales, np.array([0.5, 0.0]), np.array([0.50001, 2 * np.pi]), [0, 1])
    True
    >>> same_root(scales, np.array([0.5, 0.0]), np.array([0.501, 0.0]), [0, 1])
    False
    """
    positions = list(positions)
    return _same_values(scales[positions].tolist(), a[positions].tolist(),
                        b[positions].tolist())


def _same_values(sizes: Sequence[float], a: Sequence[float], b: Sequence[float]) -> bool:
    """:func:`same_root`'s test of the values ``a`` and ``b`` of the same positions, of
    typical sizes ``sizes`` (numbers: a setup's starts are told apart by the dozen)."""
    for size, x, y in zip(sizes, a, b):
        d = x - y
        if size == np.pi:
            d = (d + np.pi) % (2 * np.pi) - np.pi
        if abs(d) > SAME_ROOT * max(size, abs(x), abs(y)):
            return False
    return True


def _on_branch(g: Givens, x: np.ndarray, positions) -> bool:
    if not any(i in g.branches for i in positions):  # no branch asked of these: all are
        return True
    return bool(on_branches(g.branches, x[:, None], g.scales[:, None], positions)[0])


def on_branches(branches: Mapping[int, Root], X: np.ndarray, scales: np.ndarray,
                positions) -> np.ndarray:
    """Which columns of ``X`` (states, each with its typical sizes in ``scales``) have the
    root of every position in ``positions`` on the branch ``branches`` asks for it
    (:func:`~.rules.on_branch`): the branch screen of an instant and of a class.

    >>> on_branches({0: Root.POSITIVE}, np.array([[2.0, -2.0], [1.0, 1.0]]), np.ones((2, 2)),
    ...             [0, 1]).tolist()
    [True, False]
    """
    ok = np.ones(X.shape[1], dtype=bool)
    for i in positions:
        if i in branches:
            ok &= on_branch(X[i], scales[i], branches[i])
    return ok


def branches_asked(problem: Problem, p: KinematicsPlan) -> Mapping[int, Root]:
    """The root each position's ``branch:`` asks for, by position in ``p``'s layout."""
    return per_problem(_layout, problem, p)[3]


def _choose_branch(g: Givens, roots: list, positions) -> list:
    """``first positive`` keeps the smallest root of that quantity."""
    for i in positions:
        if g.branches.get(i) is Root.FIRST_POSITIVE:
            smallest = min(r[i] for r in roots)
            roots = [r for r in roots if rules.same_value(smallest, r[i])]
    return roots


def _branch_where(problem: Problem) -> Location:
    return problem.branches[0].where if problem.branches else Location()


def configurations(problem: Problem, p: KinematicsPlan, g: Givens, states, positions) -> str:
    """Roots listed by their solved quantities in the author's units."""
    units = author_units(problem, p)
    out = []
    for x in states:
        parts = []
        for i in positions:
            unit = units[i]
            value = from_si(x[i], unit) if unit else x[i]
            value = 0.0 if rules.near_zero(x[i], g.scales[i]) else value + 0.0
            parts.append(f"{p.index.spelling(i)} = {value:.6g}{' ' + unit if unit else ''}")
        out.append("(" + ", ".join(parts) + ")")
    return "; ".join(out)


def author_units(problem: Problem, p: KinematicsPlan) -> list[str]:
    """The unit each position is reported in: that of its given or guess, else its own
    (worked out once per problem: every refusal that lists roots reads them; read-only)."""
    return per_problem(_author_units, problem, p)


def _author_units(problem: Problem, p: KinematicsPlan) -> list[str]:
    index = p.index
    declared = {c.name: c.unit for c in problem.coordinates}
    declared.update({q.name: q.unit for q in problem.parameters})
    written = {to_text(x.key.node): x.unit for x in problem.guesses}
    written.update({to_text(x.key.node): x.unit for x in problem.givens})
    out = []
    for i in range(index.size):
        name = index.spelling(i)
        if written.get(name):
            out.append(written[name])
        elif i == index.time:
            out.append("s")
        elif (coordinate := index.coordinate_of(i)) and index.level_of(i):
            base = declared[coordinate] or "1"
            out.append(f"{base}/s" if index.level_of(i) == 1 else f"{base}/s^2")
        else:
            out.append(declared.get(name, ""))
    return out


def givens_conflict(level: str, label: str, residual: float, scale: float, g: Givens,
                    where) -> InconsistentError:
    """The refusal of givens that over-determine a level: the equation they leave unsatisfied,
    the givens involved, and the fix.

    >>> from types import SimpleNamespace
    >>> str(givens_conflict("velocity", "loop", 1.0, 6.0, SimpleNamespace(texts={"x": "x = 1 m"}),
    ...                     None))  # doctest: +NORMALIZE_WHITESPACE
    "the givens conflict at the velocity level: 'loop' is not satisfied (residual 1 against
    terms of size 6); givens involved: x = 1 m; leave out the one that follows from the others
    or correct its value"
    """
    return InconsistentError(
        f"the givens conflict at the {level} level: '{label}' is not satisfied (residual "
        f"{residual:.4g} against terms of size {scale:.4g}); givens involved: "
        f"{'; '.join(g.texts.values()) or 'none'}; leave out the one that follows from the "
        f"others or correct its value", where=where)


def _unsolved(problem, level, g, x, active, target, rank, starts) -> SolveError | None:
    """The error of a level not satisfied at ``x`` (``None`` if it is): a conflict when the
    givens over-determine it (more equations than the ``rank`` of their Jacobian), else a
    solve that found no root (no real solution, or starts too far from it)."""
    r, scale = (v[:, 0] for v in residuals(level, x[:, None], slice(None), target[:, None]))
    bad = np.flatnonzero(active & ~satisfied(r, scale, problem.consistency))
    if not len(bad):
        return None
    i = bad[0]
    if int(active.sum()) > rank:
        return givens_conflict(level.name, level.labels[i], r[i], scale[i], g,
                               level.wheres[i])
    guesses = "give guesses: near the configuration meant" if level.order == 0 else \
        "give a branch: for the rate's sign or check the givens"
    return SolveError(
        f"the {level.name} equations were not solved: '{level.labels[i]}' keeps a residual of "
        f"{r[i]:.4g} (terms of size {scale[i]:.4g}) from {starts} start(s): "
        f"either they have no real solution with these values, or the solve did not "
        f"converge; {guesses}", where=level.wheres[i])


# ---------------------------------------------------------------------------- linear


@dataclass(frozen=True)
class LinearColumns:
    """A linear rate level solved at every column (:func:`solve_linear_columns`): the states
    ``X``, the rank of each column's Jacobian in the unknown rates, each one's right singular
    vectors ``Vt`` (N x unknowns x unknowns: the rows after the rank span the nullspace),
    each column's first error, and the positions of the level's ``rates``."""

    X: np.ndarray
    rank: np.ndarray
    Vt: np.ndarray
    errors: FirstErrors
    rates: range

    def null(self, i: int) -> np.ndarray:
        """Column ``i``'s nullspace basis (unknowns x nullity)."""
        return self.Vt[i, int(self.rank[i]):, :].T

    def state(self, i: int, before: State, g: Givens) -> State:
        """Column ``i``'s solved state (``before`` it, the level's givens ``g``): the unknown
        rates with a part in its nullspace are free."""
        null = self.null(i)
        unknown = [j for j in self.rates if not g.known[j]]
        free = set(before.free)
        if null.shape[1]:  # the unknowns with a part in the nullspace
            free.update(j for j, is_open in zip(unknown, rules.left_open(null).tolist())
                        if is_open)
        return State(self.X[:, i].copy(), g.known, frozenset(free))


def solve_linear_columns(problem: Problem, p: KinematicsPlan, order: int, X: np.ndarray,
                         known: np.ndarray, active: np.ndarray, targets: np.ndarray,
                         placed: Callable[[int], Givens],
                         shifts: Sequence[np.ndarray | None] | None = None) -> LinearColumns:
    """The linear rate level ``order`` at every column of ``X`` (the states, the rates
    ``known`` placed, the others solved for): the minimum-norm least-squares solution of
    each column's ``active`` rows (each must equal its row of ``targets``), moved by
    ``null @ shifts[i]`` where one is given (a probe of column ``i``'s freedoms); a column
    whose equations are undefined, or that the givens over-determine (a row not
    :func:`~.rules.satisfied`), gets its error (its givens ``placed(i)``, worded when read).
    The same stacked solve for one instant and for a class of variants.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve import instant, plan
    >>> problem = load_problem(shipped_dir("problems") / "gear_between_two_racks.yaml")
    >>> p = plan.kinematics_plan(problem)
    >>> g = place_givens(problem, p, instant.instant_givens(problem, None, {}))
    >>> X = np.stack([g.values, g.values], axis=1)
    >>> X[[p.index.position("xr'"), p.index.position("xl'")], 1] *= 2  # racks twice as fast
    >>> active, target = rows(p.levels[1], g)
    >>> solved = solve_linear_columns(problem, p, 1, X, g.known, active,
    ...                               np.stack([target, target], axis=1), lambda _i: g)
    >>> x_rate = solved.X[p.index.position("x'")]
    >>> solved.errors.ok.tolist(), round(float(x_rate[1] / x_rate[0]), 12)
    ([True, True], 2.0)
    """
    level = p.levels[order]
    cols = list(p.index.rates(order))
    nrows, n = len(level.labels), X.shape[1]
    on = np.flatnonzero(active)
    unknown = [j for j, i in enumerate(cols) if not known[i]]
    solved = [cols[j] for j in unknown]
    X = X.copy()
    X[solved] = 0.0
    errors = FirstErrors(n)
    with quiet():
        A = call(level.jacobian, X, nrows * len(cols)).reshape(nrows, len(cols), n)[on]
        b = call(level.residual, X, nrows)[on] - targets[on]
        defined = np.isfinite(A).all(axis=1) & np.isfinite(b)  # rows x N
        errors.add(~defined.all(axis=0), lambda i: _undefined(level, on, defined[:, i]))
        good = errors.ok
        k = len(unknown)
        if len(on):
            # the unknown rates are 0 in X, so b is the residual of the known part
            step, rank, Vt = least_squares(A[:, unknown], b, good)
        else:  # nothing fixes them: all free
            step, rank = np.zeros((k, n)), np.zeros(n, dtype=int)
            Vt = np.broadcast_to(np.eye(k), (n, k, k))
        for i, shift in enumerate(shifts or ()):
            if shift is not None and rank[i] < k:
                step[:, i] += Vt[i, int(rank[i]):, :].T @ shift
        X[solved] = step
        if len(on):
            r, scale = residuals(level, X, on, targets[on])
            held = satisfied(r, scale, problem.consistency)
            errors.add(~held.all(axis=0), lambda i: _conflict(
                problem, level, on, r[:, i], scale[:, i], placed(i)))
    return LinearColumns(X, rank, Vt, errors, p.index.rates(order))


def _undefined(level: Level, on: np.ndarray, defined: np.ndarray) -> SolveError:
    """The refusal of a linear level undefined at an instant (``defined``: each active row
    ``on``)."""
    row = on[np.flatnonzero(~defined)[0]]
    return SolveError(f"the {level.name} equations are undefined at this instant (a "
                      f"division by zero in '{level.labels[row]}')", where=level.wheres[row])


def _conflict(problem: Problem, level: Level, on: np.ndarray, r: np.ndarray,
              scale: np.ndarray, g: Givens) -> InconsistentError:
    """:func:`givens_conflict` at the first active row (``on``) not satisfied."""
    j = first_off(r, scale, problem.consistency)
    assert j is not None, "a column not satisfied has a row that is not"
    return givens_conflict(level.name, level.labels[on[j]], r[j], scale[j], g,
                           level.wheres[on[j]])


def constraint_ranks(p: KinematicsPlan, X: np.ndarray) -> np.ndarray:
    """Rank of the velocity-level constraints in the rates at every solved configuration
    (a column of ``X`` each)."""
    level = p.levels[1]
    if not level.constraint_rows:
        return np.zeros(X.shape[1], dtype=int)
    rates = list(p.index.unknowns(1))
    constraints = np.arange(len(level.labels)) < level.constraint_rows
    return level_rank(level, X, rates, rates, constraints)


def _split_free(J: np.ndarray, unknown: list[int]) -> tuple[list[int], list[int]]:
    """Which unknowns the equations determine (pivoted QR), and which stay free."""
    from scipy import linalg

    if J.size == 0:
        return [], list(unknown)
    if not np.isfinite(J).all():
        return list(unknown), []
    if clearly_independent(J):  # the QR's rank would be full: it determines them all
        return sorted(unknown), []
    with np.errstate(all="ignore"):
        _, R, piv = linalg.qr(J, pivoting=True, mode="economic", check_finite=False)
    rank = int(rules.rank(np.diag(R))) if R.size else 0
    determined = sorted(unknown[j] for j in piv[:rank])
    free = sorted(unknown[j] for j in piv[rank:])
    return determined, free


FULL_RANK_MARGIN = (1e3 * rules.RANK_TOL) ** 2
"""The part of its trace (and of 1) the smallest eigenvalue of a Jacobian's Gram matrix
exceeds where :func:`clearly_independent` vouches for it: singular values a thousand times
:data:`~.rules.RANK_TOL` apart at worst, far beyond any rounding of the QR or of the Gram."""


def clearly_independent(J: np.ndarray) -> bool:
    """Whether the columns of ``J`` (rows x at most three) are independent by a wide margin:
    the smallest eigenvalue of its Gram matrix, at least its determinant over its trace to
    the power one less than its size, is above :data:`FULL_RANK_MARGIN` of the trace (and of
    1). Each diagonal entry of a pivoted QR's R is at least the smallest singular value and
    the largest at most the largest one, so the rank that QR gives (:func:`~.rules.rank`)
    is then full: the same answer without LAPACK's cost per call. ``False`` says nothing
    (the QR decides).

    >>> clearly_independent(np.array([[1.0, 0.0], [0.5, 2.0]]))
    True
    >>> clearly_independent(np.array([[1.0, 2.0], [2.0, 4.0 + 1e-9]]))
    False
    """
    rows_, size = J.shape
    if size > 3 or rows_ < size:
        return False
    columns = J.T.tolist()
    gram = [[sum(a * b for a, b in zip(u, v)) for v in columns] for u in columns]
    trace = sum(gram[i][i] for i in range(size))
    return bool(determinant(gram) > FULL_RANK_MARGIN * trace ** (size - 1) * max(trace, 1.0))


def evaluate(functions, state: State, only: set[str]) -> dict:
    """``{id: values}`` of ``(id, function)`` pairs whose id is in ``only``, at ``state``."""
    with quiet():
        return {oid: np.asarray(f(*state.values), dtype=float).ravel()
                for oid, f in functions if oid in only}
