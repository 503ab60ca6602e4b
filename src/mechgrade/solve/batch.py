"""Many variants of one problem solved together: every student's givens at once.

The lambdified functions of a problem's plan take arrays as well as numbers, so the levels of
many instants are solved in one pass: each level by Newton steps from the reference's root (the
solution with the spec's own givens), every step a stacked least-squares solve. That is the root
a variant continues from the configuration the author checked, and for a level with one root
(every linear level, every level the spec picks a root of) it is the root :func:`~.entry.solve`
finds.

A dynamics instant reached otherwise is reached the same way for every variant at once: the
rates from the energy balance (:func:`~.events.energy_state` on arrays); the motion integrated
to its event (:func:`~.batch_motion.integrate_to_events`: each variant's DOP853 steps, all
variants' right-hand sides in one call); a design parameter by Newton's method around the
whole instant (:func:`~.batch_motion.newton`: every variant's iterate and a point beside it
in one call), from the guess :func:`~.dynamics._designed` starts its secant at.

Every instant solved this way is screened for what the scalar solver would report: a level
not satisfied or losing rank, a root off its branch, a degenerate configuration, an objective
undefined or not existing there, a contact that slips or lets go, an energy the instant needs
more of than the start has, an event that does not happen, a design that does not converge. A
variant that fails a screen, and any problem or variant this path does not cover (givens the
reference does not have), is solved by :func:`~.entry.solve`, so the answers and messages are
the same either way. (An objective of a dynamics problem undefined at its instant is that
variant's failure, as :func:`~.dynamics.solve_dynamics` reports it.)

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
>>> a, b = solve_variants(problem, [{"L": 0.5}, {"L": 1.0}])
>>> round(b.result("acc_mag").value / a.result("acc_mag").value, 6)
2.0
"""

from __future__ import annotations

import types
import warnings
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Callable, Mapping, Sequence

import numpy as np

from ..errors import MechgradeError
from ..expressions.syntax import Name, Prime, to_text
from ..mechanics.kinematics import locations
from ..spec.dynamics import Integration, WorkEnergy
from ..spec.model import Objective, Problem, Root
from ..units import si_factor
from .batch_motion import FIRED, integrate_to_events, newton
from .entry import solve
from .events import ATOL, MAX_CALLS, RTOL, analysis_plan, at_the_event
from .instant import (_instants, _key, _state, _symbolic_answer,
                      collect_results, degrees_of_freedom, instant_givens, symbolic_dependence,
                      wanted_objectives)
from .levels import RANK_TOL, SAME_ROOT, State, place_givens, rows
from .mutants import (SAME, misread, model_mistake_at, model_mistake_table, plausible_slips,
                      slips_of)
from .numeric import PROBE_TOL, SINGULAR, solve_numeric
from .dynamics_mutants import with_generated_mistakes
from .plan import Plan, _OnFirstCall, plan
from .result import (GeneratedMistake, MistakeValue, ObjectiveFailure, ObjectiveResult,
                     Solution)
from .stored import load_variant, store_variant, variant_keys

NEWTON_STEPS = 30
"""Newton steps a non-linear level may take from the reference's root."""

Outcome = Solution | MechgradeError


def solve_variants(problem: Problem,
                   variants: Sequence[Mapping[str, float | None] | None]) -> list[Outcome]:
    """``[solve(problem, givens=g) for g in variants]``, each a :class:`Solution` or the
    error :func:`~.entry.solve` raises, computed together (see the module's docstring).

    With the disk cache on, a dynamics problem's variants are kept there (:mod:`.stored`):
    those stored are read back, the others solved together and stored, equal givens once (a
    variant's last digits depend on the others solved with it: one entry per givens gives
    them all the same, in this run and the next)."""
    given = [dict(g or {}) for g in variants]
    keys = [key for key in variant_keys(problem, given) if key is not None] \
        if problem.dynamics is not None else []
    if len(keys) < len(given):  # not kept (a kinematics problem, the cache off...)
        return [outcome for outcome, _ in _solved_together(problem, given)]
    distinct = dict(zip(keys, given))
    out: dict[str, Outcome] = {}
    for key, givens in distinct.items():
        stored = load_variant(problem, givens, key)
        if stored is not None:
            out[key] = stored
    todo = [key for key in distinct if key not in out]
    for key, (outcome, together) in zip(todo, _solved_together(
            problem, [distinct[key] for key in todo])):
        store_variant(key, outcome, together)
        out[key] = outcome
    return [out[key] for key in keys]


def _solved_together(problem: Problem, given: list[dict]) -> list[tuple[Outcome, bool]]:
    """Each variant's outcome, and whether it was solved with the others (else by
    :func:`~.entry.solve`)."""
    found: list[Outcome | None] = [None] * len(given)
    template = _template(problem) if given else None
    if template is not None:
        chosen = [i for i, g in enumerate(given) if template.covers(g)]
        for i, solution in zip(chosen, template.solve([given[i] for i in chosen])):
            # as solve() does: a dynamics solution carries its model's generated mistakes
            found[i] = (with_generated_mistakes(problem, solution, given[i])
                        if problem.dynamics is not None and isinstance(solution, Solution)
                        else solution)
    out: list[tuple[Outcome, bool]] = []
    for givens, solution in zip(given, found):
        if solution is None:
            try:
                out.append((solve(problem, givens=givens), False))
            except MechgradeError as err:
                out.append((err, False))
        else:
            out.append((solution, True))
    return out


# ---------------------------------------------------------------------------- arrays


@lru_cache(maxsize=4096)
def _batched(f: Callable) -> Callable:
    """``f`` (made by ``sympy.lambdify``) with its matrices built from entries that may be
    arrays of different shapes (a constant beside a column of values)."""
    if isinstance(f, _OnFirstCall):
        f = f.function
    namespace = dict(f.__globals__)
    namespace["array"] = _array
    return types.FunctionType(f.__code__, namespace, f.__name__, f.__defaults__, f.__closure__)


def _array(rows):
    """``numpy.array`` for the matrices lambdified functions build, with entries of
    different shapes broadcast together."""
    arrays = [e.shape for row in rows for e in row if type(e) is np.ndarray]
    shapes = set(arrays)
    if not arrays or (len(shapes) == 1 and len(arrays) == len(rows) * len(rows[0])):
        return np.array(rows, dtype=float)
    # a constant entry beside arrays: every entry broadcast to the arrays' shape
    out = np.empty((len(rows), len(rows[0])) + np.broadcast_shapes(*shapes))
    for r, row in enumerate(rows):
        for c, entry in enumerate(row):
            out[r, c] = entry
    return out


def _call(f: Callable, X: np.ndarray, size: int) -> np.ndarray:
    """``f`` at every column of ``X`` (the states, one per column): ``size`` values each, as
    a ``(size, N)`` array."""
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return _loud_call(f, X, size)


def _loud_call(f: Callable, X: np.ndarray, size: int) -> np.ndarray:
    """:func:`_call` for a caller that has silenced numpy's warnings already (an
    integration evaluates its right-hand side thousands of times)."""
    n = X.shape[1]
    out = np.asarray(_batched(f)(*X), dtype=float)
    if out.size == size * n:
        return out.reshape(size, n)
    return np.broadcast_to(out.reshape(size, 1), (size, n)).copy()


def _least_squares_solution(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The least-squares solution of ``A x = b`` at every column (``A``: rows x unknowns x N,
    ``b``: rows x N), the minimum-norm one where ``A`` is singular, as ``scipy.linalg.lstsq``
    gives it; a square system of up to three unknowns by Cramer's rule (LAPACK's per-matrix
    cost is most of the time of so small a solve)."""
    rows_, k, count = A.shape
    if rows_ == k == 1:
        with np.errstate(all="ignore"):
            solved = b / A[0]
        if np.isfinite(solved.sum()):
            return solved
    else:
        solved = np.full((k, count), np.nan)
    if rows_ == k and 1 < k <= 3:
        det = _determinant(A)
        with np.errstate(all="ignore"):
            for j in range(k):
                replaced = A.copy()
                replaced[:, j] = b
                solved[j] = _determinant(replaced) / det
    left = ~np.isfinite(solved).all(axis=0)
    if left.any():
        Ab = A[:, :, left].transpose(2, 0, 1)
        bb = b[:, left].T[:, :, None]
        try:
            part = np.linalg.solve(Ab, bb) if rows_ == k else None
        except np.linalg.LinAlgError:  # a singular column: the least-squares solution
            part = None
        if part is None:
            part = np.linalg.pinv(Ab) @ bb
        solved[:, left] = part[:, :, 0].T
    return solved


def _determinant(A: np.ndarray) -> np.ndarray:
    """The determinant of every column's square matrix of up to three rows."""
    k = A.shape[0]
    if k == 1:
        return A[0, 0]
    if k == 2:
        return A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]
    return (A[0, 0] * (A[1, 1] * A[2, 2] - A[1, 2] * A[2, 1])
            - A[0, 1] * (A[1, 0] * A[2, 2] - A[1, 2] * A[2, 0])
            + A[0, 2] * (A[1, 0] * A[2, 1] - A[1, 1] * A[2, 0]))


def _least_squares(J: np.ndarray, r: np.ndarray, good: np.ndarray):
    """The minimum-norm least-squares step ``-pinv(J) r`` of every column (``J``: rows x
    unknowns x N, ``r``: rows x N; columns not ``good`` are left at zero), the rank of each
    ``J`` (as :func:`~.levels.nullspace` counts it) and each one's right singular vectors
    (N x unknowns x unknowns: the rows after the rank span its nullspace)."""
    Jb = np.where(good, J, 0.0).transpose(2, 0, 1)
    U, s, Vt = np.linalg.svd(Jb, full_matrices=True)
    k = s.shape[1]
    big = s > RANK_TOL * np.maximum(s.max(axis=1, initial=0.0), 1.0)[:, None]
    rank = big.sum(axis=1)
    with np.errstate(all="ignore"):
        inverse = np.where(big, 1.0 / np.where(big, s, 1.0), 0.0)
        coeff = np.einsum("nmk,mn->nk", U[:, :, :k], np.where(good, r, 0.0)) * inverse
        step = -np.einsum("nkj,nk->jn", Vt[:, :k, :], coeff)
    return step, rank, Vt


# ---------------------------------------------------------------------------- the template


@dataclass(frozen=True)
class _Group:
    """One instant of the problem (objectives asked with the same givens) as the reference
    solved it: its givens, root and the unknowns of each level."""

    overrides: dict
    objectives: tuple[Objective, ...]
    numeric: frozenset[str]
    givens: dict
    state: np.ndarray
    known: np.ndarray
    unknown: tuple[tuple[int, ...], ...]
    active: tuple[np.ndarray, ...]
    target: tuple[np.ndarray, ...]
    conditions: Mapping[str, tuple[int, int]]
    solved: tuple[int, ...]
    free: frozenset[int]
    positions: Mapping[str, int]
    nullity: tuple[int, ...]  # per level
    after: np.ndarray  # what the reached state marks given (the analysis fixes the rates)
    loose: frozenset[int]  # and leaves free


class _Template:
    """What every variant of a problem shares with the reference solve."""

    def __init__(self, problem: Problem, kproblem: Problem, p: Plan, kinetics, groups):
        self.problem, self.kproblem, self.p, self.kinetics = problem, kproblem, p, kinetics
        self.groups: tuple[_Group, ...] = groups
        self.keys = frozenset(to_text(g.key.node) for g in problem.givens)
        self.branches = {p.index.position(to_text(b.key.node)): b.root
                         for b in problem.branches}
        self.parameters = {q.name for q in problem.parameters}
        self.plausible = plausible_slips(problem)
        dynamics = problem.dynamics
        self.analysis = dynamics.analysis if dynamics is not None else None
        self.design = dynamics.design if dynamics is not None else None

    def covers(self, givens: dict) -> bool:
        """Whether ``givens`` only change values the reference has (no new given, none
        removed)."""
        try:
            return all(value is not None and _key(key)[1] in self.keys
                       for key, value in givens.items())
        except MechgradeError:
            return False

    # -- solving

    def solve(self, variants: list[dict]) -> list[Solution | MechgradeError | None]:
        """Each variant's solution (or, for a dynamics problem, the error
        :func:`~.dynamics.solve_dynamics` raises when no objective is solved), or ``None``
        where it must be solved one by one."""
        n = len(variants)
        if not n:
            return []
        problem = self.problem
        wanted = wanted_objectives(problem, None)
        symbolic: Callable | None = None
        if self.kinetics is not None:
            from .dynamics import _symbolic_result
            symbolic = _symbolic_result
        results: list[dict] = [{} for _ in range(n)]
        lost: list[dict] = [{} for _ in range(n)]
        ok = np.ones(n, dtype=bool)
        base: list = [None] * n
        for group in self.groups:
            maps = [instant_givens(problem, g, group.overrides) for g in variants]
            objectives = [o for o in group.objectives if o.id in wanted]
            values: dict = {}
            mistakes: dict = {}
            generated: dict = {}
            if group.numeric:
                X, fine, values, mistakes = self._instant(group, maps, True)
                ok &= fine
                for ms in mistakes.values():
                    for m in ms:  # an undefined declared mistake fails its objective
                        ok &= np.isfinite(m).all(axis=0)
                self._keep_state(group, X, ok, maps, base)
                if self.kinetics is None:
                    generated = self._generated(group, maps, X, ok, values)
            numeric = [o for o in objectives if o.kind != "symbolic"]
            symbols = [o.id for o in objectives if o.kind == "symbolic"]
            answers: dict = {}  # this problem's symbolic answers, by what they depend on
            shown = {o.id: _shown(values[o.id], o) for o in numeric}
            declared = {o.id: [_shown(v, o) for v in mistakes.get(o.id, ())] for o in numeric}
            # a dynamics objective undefined at a variant's instant is that objective's
            # failure (as collect_results words it); any other has made the variant not ok
            defined = {o.id: np.isfinite(values[o.id]).all(axis=0)
                       & np.all([np.isfinite(v).all(axis=0) for v in mistakes.get(o.id, ())]
                                + [np.ones(n, dtype=bool)], axis=0) for o in numeric}
            for i in np.flatnonzero(ok):
                failures: dict = {}
                for o in numeric:
                    if not defined[o.id][i]:
                        collect_results(problem, [o], maps[i], {o.id: values[o.id][:, i]},
                                        {o.id: [m[:, i] for m in mistakes.get(o.id, ())]},
                                        results[i], failures)
                        continue
                    results[i][o.id] = ObjectiveResult(
                        id=o.id, kind=o.kind, unit=o.unit, value=shown[o.id][i],
                        frame=o.frame, mistakes=tuple(
                            MistakeValue(m.message, m.credit, v[i])
                            for m, v in zip(o.mistakes, declared[o.id])),
                        rel=o.tolerance.rel, abs=o.tolerance.abs, prompt=o.prompt,
                        generated_mistakes=generated[o.id](i) if generated else (),
                        plausible=self.plausible if self.kinetics is None else None)
                for oid in symbols:
                    depends = symbolic_dependence(problem, maps[i], oid)
                    answer = answers.get((oid, depends))
                    if answer is None:
                        try:
                            answer = _symbolic_answer(symbolic, problem, oid, maps[i])
                            if self.kinetics is None:  # as attach() leaves it
                                answer = replace(answer, plausible=self.plausible)
                        except MechgradeError as err:
                            answer = err
                        answers[oid, depends] = answer
                    if isinstance(answer, MechgradeError):
                        failures[oid] = answer
                    else:
                        results[i][oid] = answer
                if failures and self.kinetics is None:
                    ok[i] = False
                lost[i].update(failures)  # as solve_dynamics keeps them
        return [self._solution(results[i], base[i], lost[i]) if ok[i] else None
                for i in range(n)]

    def _keep_state(self, group: _Group, X: np.ndarray, ok: np.ndarray, maps: list[dict],
                    base: list) -> None:
        """Each variant's solved state and givens (a design parameter's value among them) as
        the solution reports them: those of the problem's own instant, else the first
        solved."""
        if self.design is not None:  # the value solved for is given at the instant
            at = self.p.index.position(self.design.find)
            for i in np.flatnonzero(ok):
                maps[i][self.design.find] = (Name(self.design.find), float(X[at, i]), None)
        size = self.p.index.size
        for i in np.flatnonzero(ok):
            if not group.overrides or base[i] is None:
                free = group.loose
                if self.kinetics is not None:  # the rates the balances solved
                    free = frozenset(free - {c for c in self.kinetics.columns
                                             if c < size and np.isfinite(X[c, i])})
                base[i] = (State(X[:size, i], group.after, free), maps[i])

    def _solution(self, results: dict, base, failures: dict) -> Solution | MechgradeError:
        problem, p = self.problem, self.p
        order = [o.id for o in problem.objectives]
        if not results and order:  # nothing solved: solve_dynamics raises the first error
            return failures[order[0]]
        return Solution(problem=problem.id,
                        results=tuple(results[oid] for oid in order if oid in results),
                        state=_state(self.kproblem, p, base),
                        dof=degrees_of_freedom(p, base[0] if base else None),
                        failures=tuple(ObjectiveFailure(oid, failures[oid]) for oid in order
                                       if oid in failures),
                        warnings=tuple(p.k.warnings))

    def _instant(self, group: _Group, maps: list[dict], degenerate: bool):
        """The numeric objectives and declared mistakes of ``group`` at every variant's
        instant, and which instants passed every screen (with ``degenerate``, also the one
        for a degenerate configuration)."""
        p = self.p
        n = len(maps)
        X = np.repeat(group.state[:, None], n, axis=1)
        targets = [np.repeat(t[:, None], n, axis=1) for t in group.target]
        for key in maps[0]:
            column = np.array([m[key][1] for m in maps], dtype=float)
            if key in group.positions:
                X[group.positions[key]] = column
            elif key in group.conditions:
                level, row = group.conditions[key]
                targets[level][row] = column
        if self.design is not None:
            X, ok = self._designed(group, X, targets, degenerate)
        else:
            X, ok = self._reached(group, X, targets, degenerate)
        X, before = self._at_event(X)
        if self.kinetics is not None:
            objectives, mistakes, requirements = (self.kinetics.objectives,
                                                  self.kinetics.mistakes,
                                                  self.kinetics.requirements)
            limit = 1e-8
        else:
            objectives, mistakes, requirements = p.objectives, p.mistakes, p.requirements
            limit = 1e-9
        values = {oid: _call(f, X, _size(self.problem, oid)) for oid, f in objectives
                  if oid in group.numeric}
        if before is not None:
            functions = dict(objectives)
            values = {oid: at_the_event(v, _call(functions[oid], before, len(v)),
                                        self.problem.objective(oid))
                      for oid, v in values.items()}
        if self.kinetics is None:  # a dynamics objective undefined there is its failure
            for v in values.values():
                ok &= np.isfinite(v).all(axis=0)
        for oid, _, f in requirements:
            if oid in group.numeric:
                with np.errstate(invalid="ignore"):
                    ok &= ~(np.abs(_call(f, X, 1)[0]) > limit)
        declared = {oid: [_call(f, X, _size(self.problem, oid)) for f in fs]
                    for oid, fs in mistakes if oid in group.numeric}
        return X, ok, values, declared

    def _reached(self, group: _Group, X: np.ndarray, targets: list,
                 degenerate: bool) -> tuple[np.ndarray, np.ndarray]:
        """The instants (each column of ``X`` the givens placed, the state extended by the
        reactions for a dynamics problem) and which passed the screens."""
        if isinstance(self.analysis, Integration):
            return self._integrated(group, X)
        n = X.shape[1]
        ok = np.all(np.isfinite(X[group.known]), axis=0) if group.known.any() else \
            np.ones(n, dtype=bool)
        nulls = self._levels(group, X, targets, 0, ok)
        if self.kinetics is None and (group.free or any(k for k in group.nullity)):
            ok &= self._determined(group, X, targets, nulls, ok)
        ok &= self._on_branch(group, X)
        if degenerate:
            ok &= ~self._degenerate(group, X)
        if self.kinetics is None:
            return X, ok
        if isinstance(self.analysis, WorkEnergy):
            ok &= self._energy(X, ok)
        X, fine = self._kinetics(X, group.after)
        return X, ok & fine

    def _designed(self, group: _Group, X: np.ndarray, targets: list,
                  degenerate: bool) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_reached` with the design parameter solved at every column by Newton's
        method from the guess (:func:`~.batch_motion.newton`; the one-by-one solver's secant
        takes 10 calls for the flywheel where it takes 7); a column it does not converge for
        is solved alone, where the bracketing search may find its root."""
        assert self.design is not None and self.kinetics is not None
        at = self.p.index.position(self.design.find)
        equation = self.kinetics.design
        n = X.shape[1]
        last: dict[str, np.ndarray] = {}  # each column's instant at its latest iterate

        def residual(cols: np.ndarray, values: np.ndarray) -> np.ndarray:
            both = np.concatenate([cols, cols])  # the iterates, then the points beside them
            moved = X[:, both]
            moved[at] = values.ravel()
            reached, fine = self._reached(group, moved, [t[:, both] for t in targets], False)
            if not last:
                last.update(X=np.full((reached.shape[0], n), np.nan),
                            ok=np.zeros(n, dtype=bool), at=np.full(n, np.nan))
            k = len(cols)
            last["X"][:, cols], last["ok"][cols], last["at"][cols] = \
                reached[:, :k], fine[:k], values[0]
            r = np.where(fine, _call(equation, self._at_event(reached)[0], 1)[0], np.nan)
            return r.reshape(2, k)

        guess = self.design.guess
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            root, converged = newton(residual, np.full(n, guess), 1e-15, 1e-13, 100)
        converged &= np.isfinite(root)
        # Newton stops once its next iterate is within 1e-13 of the last one evaluated:
        # that instant is the root's (as closely as the root is known), not reached again
        kept = converged & (np.abs(last["at"] - root) <= 1e-13 * np.abs(root) + 1e-15)
        out, ok = last["X"].copy(), last["ok"] & kept
        redo = np.flatnonzero(~kept)
        if len(redo):
            moved = X[:, redo].copy()
            moved[at] = np.where(converged[redo], root[redo], guess)
            out[:, redo], ok[redo] = self._reached(group, moved,
                                                   [t[:, redo] for t in targets], degenerate)
        again = np.flatnonzero(kept)
        if degenerate and len(again) and not isinstance(self.analysis, Integration):
            ok[again] &= ~self._degenerate(group, out[:, again])  # of the configuration only
        return out, ok & converged

    def _energy(self, X: np.ndarray, ok: np.ndarray) -> np.ndarray:
        """Put in every column the rates the energy balance gives (as
        :func:`~.events.energy_state` does), and say which columns it would not refuse."""
        assert self.kinetics is not None and isinstance(self.analysis, WorkEnergy)
        kp, index = self.kinetics, self.p.index
        analysis = self.analysis
        ap = analysis_plan(kp)
        rates, n = list(index.rates(1)), index.n
        count = X.shape[1]
        reactions = np.zeros((len(kp.kin.reactions), count))
        fine = ok.copy()
        X[rates] = 0.0
        X[list(index.rates(2))] = 0.0
        level = self.p.levels[1]
        if level.constraint_rows:
            J = _call(level.jacobian, X, len(level.labels) * n).reshape(
                len(level.labels), n, count)[:level.constraint_rows]
            finite = np.isfinite(J).all(axis=(0, 1))
            fine &= finite
            _, s, Vt = np.linalg.svd(np.where(finite, J, 0.0).transpose(2, 0, 1),
                                     full_matrices=True)
            big = s > RANK_TOL * np.maximum(s.max(axis=1, initial=0.0), 1.0)[:, None]
            fine &= big.sum(axis=1) == n - 1  # one free direction
            u = Vt[:, n - 1, :].T
        else:
            fine &= n == 1
            u = np.ones((n, count))
        start = np.concatenate([X, reactions])
        for i, fn in ap.start:
            start[i] = _call(fn, np.concatenate([X, reactions]), 1)[0]
        e0 = _call(ap.energy, start, 1)[0]
        v = _call(ap.energy, np.concatenate([X, reactions]), 1)[0]
        moving = X.copy()
        moving[rates] = u
        with np.errstate(all="ignore"):
            t_unit = _call(ap.energy, np.concatenate([moving, reactions]), 1)[0] - v
            square = (e0 - v) / t_unit
            fine &= ~(square < -1e-9 * (np.abs(e0) + np.abs(v) + 1e-300) / t_unit)
            fine &= np.isfinite(square)
            speed = np.sqrt(np.maximum(square, 0.0))
        sign = np.ones(count)
        if analysis.sense:
            key, sense = analysis.sense[0]
            component = u[rates.index(index.position(key.text.replace(" ", "")))]
            fine &= ~((speed > 0) & (np.abs(component) < 1e-12))
            sign = np.where(speed > 0, np.sign(component) * (1 if sense == "positive" else -1),
                            1.0)
        else:
            fine &= ~(speed > 0)
        X[rates] = sign * speed * u
        x = np.concatenate([X, reactions])
        size = 1.0 + np.abs(X[rates]).max(axis=0, initial=0.0)
        for _, fn in ap.workless:
            with np.errstate(invalid="ignore"):
                fine &= ~(np.abs(_call(fn, x, 1)[0]) > 1e-8 * size)
        return fine

    def _integrated(self, group: _Group, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Every column's motion integrated from its start state to its event (together:
        :func:`~.batch_motion.integrate_to_events`, the steps
        :func:`~.events.integrate_to_event` takes for each alone): the extended state at
        the event, the accelerations and reactions the limits just before it, with the
        extended states just before the event stacked under them (:meth:`_at_event`)."""
        kp = self.kinetics
        assert kp is not None and isinstance(self.analysis, Integration)
        ap = analysis_plan(kp)
        index = self.p.index
        n, size, count = index.n, index.size, X.shape[1]
        rates, seconds = index.rates(1), index.rates(2)
        # slices: the right-hand side is evaluated thousands of times
        qd, qdd = slice(rates.start, rates.stop), slice(seconds.start, seconds.stop)
        kinetic = size + len(kp.kin.reactions)
        extended = np.concatenate([X, np.zeros((kinetic - size, count))])
        values = X.copy()
        for i, fn in ap.start:
            values[i] = _call(fn, extended, 1)[0]
        values[index.time] = 0.0
        values[qdd] = 0.0
        switches = _switches(kp)
        # every column's extended state (second rates and reactions 0, as the unknowns of
        # the balances), then its modes
        full = np.zeros((kinetic + (switches.count if switches else 0), count))
        full[:size] = values

        def at(cols: np.ndarray, t: np.ndarray, y: np.ndarray,
               modes: np.ndarray | None = None) -> np.ndarray:
            # a copy (every column: cols is sorted, so all of them is all in order)
            x = full.copy() if len(cols) == count else full[:, cols]
            x[:n] = y[:n]
            x[qd] = y[n:]
            x[index.time] = t
            if modes is not None and switches is not None:
                x[kinetic:] = modes
            return x

        def rhs(cols: np.ndarray, t: np.ndarray, y: np.ndarray,
                modes: np.ndarray) -> np.ndarray:
            return np.concatenate([y[n:], self._accelerations(at(cols, t, y, modes),
                                                              switches)[qdd]])

        def event(cols: np.ndarray, t: np.ndarray, y: np.ndarray,
                  modes: np.ndarray) -> np.ndarray:
            x = at(cols, t, y, modes)
            if ap.until_kinetic:
                x = self._accelerations(x, switches)
            assert ap.until is not None  # an integration has its event
            return _loud_call(ap.until, x[:kinetic], 1)[0]

        def mode(cols: np.ndarray, t: np.ndarray, y: np.ndarray) -> np.ndarray:
            assert switches is not None
            x = at(cols, t, y)[:kinetic]
            return np.sign(_loud_call(switches.speeds, x, switches.count))

        y0 = np.concatenate([values[:n], values[qd]])
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            arrival = integrate_to_events(rhs, event, y0, self.analysis.max_time, RTOL, ATOL,
                                          MAX_CALLS, mode=mode if switches else None)
        ok = arrival.status == FIRED
        everyone = np.arange(count)
        end = at(everyone, arrival.t, arrival.y)
        x, fine = self._kinetics(at(everyone, arrival.t * (1 - 1e-9), arrival.before)[:size],
                                 group.after)
        before = x.copy()
        keep = [i for i in range(size) if i not in seconds]
        x[keep] = end[keep]
        return np.vstack([x, before]), ok & fine

    def _at_event(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """``X`` as :meth:`_reached` gave it, parted: the extended states the objectives are
        read from, and for an integration the states just before the event stacked under
        them by :meth:`_integrated` (else ``None``)."""
        if not isinstance(self.analysis, Integration):
            return X, None
        half = X.shape[0] // 2
        return X[:half], X[half:]

    def _accelerations(self, x: np.ndarray, switches: _Switching | None) -> np.ndarray:
        """``x`` (extended states, the unknowns 0, then with ``switches`` each slip's
        direction) with every second rate and reaction solved by least squares (as
        :func:`~.dynamics.accelerations`), in place; NaN where the equations are undefined.
        Called with numpy's warnings silenced."""
        kp = self.kinetics
        assert kp is not None
        count = x.shape[1]
        cols = list(kp.columns)
        rows_ = len(kp.labels)
        if switches is not None:
            jacobian, residual, args = switches.jacobian, switches.residual, x
        else:
            jacobian, residual = kp.jacobian, kp.residual
            args = x[:len(kp.symbols)]
        A = _loud_call(jacobian, args, rows_ * len(cols)).reshape(rows_, len(cols), count)
        b = _loud_call(residual, args, rows_)
        if np.isfinite(A.sum() + b.sum()):  # (an overflow takes the careful way below)
            x[cols] = _least_squares_solution(A, -b)
            return x
        good = np.isfinite(A).all(axis=(0, 1)) & np.isfinite(b).all(axis=0)
        x[cols] = _least_squares_solution(np.where(good, A, 0.0), np.where(good, -b, 0.0))
        x[:, ~good] = np.nan
        return x

    def _levels(self, group: _Group, X: np.ndarray, targets, first: int,
                ok: np.ndarray) -> dict[int, np.ndarray | None]:
        """Solve the levels from ``first`` on at every column of ``X`` (in place), clearing
        ``ok`` where a level is not solved as the reference's was; the nullspace bases of the
        linear rate levels (N x unknowns x nullity)."""
        p = self.p
        nulls: dict[int, np.ndarray | None] = {}
        for level in p.levels[first:]:
            order = level.order
            unknown = list(group.unknown[order])
            active, target = group.active[order], targets[order]
            nrows = len(level.labels)
            columns = list(p.index.unknowns(order))
            linear = level.linear and order > 0
            # a linear rate level: the minimum-norm solution, as least squares gives it;
            # any other: Newton steps for the unknowns it determines, the others kept
            solve_for = unknown if linear else [i for i in unknown if i not in group.free]
            if linear:
                X[unknown] = 0.0
            if linear and solve_for and not active.any():  # nothing fixes them: all free
                nulls[order] = np.broadcast_to(np.eye(len(solve_for)),
                                               (X.shape[1], len(solve_for), len(solve_for)))
                continue
            # a column stops once its own step is that small: its root does not depend on
            # the other variants solved with it
            moving = np.ones(X.shape[1], dtype=bool)
            for _ in range(1 if linear else NEWTON_STEPS if solve_for else 0):
                place = [columns.index(i) for i in solve_for]
                r = _call(level.residual, X, nrows)[active] - target[active]
                J = _call(level.jacobian, X, nrows * len(columns)).reshape(
                    nrows, len(columns), X.shape[1])[active][:, place]
                good = np.isfinite(r).all(axis=0) & np.isfinite(J).all(axis=(0, 1))
                ok &= good
                step, rank, Vt = _least_squares(J, r, good)
                ok &= rank == len(solve_for) - group.nullity[order]
                step[:, ~ok | ~moving] = 0.0
                X[solve_for] += step
                if linear:
                    nulls[order] = Vt[:, rank.max(initial=0):, :].transpose(0, 2, 1) \
                        if group.nullity[order] else None
                    break
                moving &= ~np.all(np.abs(step) <= 1e-12 * np.maximum(np.abs(X[solve_for]), 1.0),
                                  axis=0)
                if not moving.any():
                    break
            if active.any():
                r = _call(level.residual, X, nrows)[active] - target[active]
                scale = np.abs(_call(level.scale, X, nrows))[active]
                with np.errstate(invalid="ignore"):
                    ok &= np.all(np.abs(r) <= self.problem.consistency * scale + 1e-10, axis=0)
        return nulls

    def _determined(self, group: _Group, X: np.ndarray, targets, nulls,
                    ok: np.ndarray) -> np.ndarray:
        """Whether every numeric objective stays the same when what the givens leave free
        moves (each free unknown, each direction of a nullspace), as the scalar solver
        probes: where one changes, that solver names the objective not determined."""
        p = self.p
        same = ok.copy()
        before = {oid: _call(f, X, _size(self.problem, oid)) for oid, f in p.objectives
                  if oid in group.numeric}
        probes: list[tuple[int, int | None, int | None]] = [
            (p.index.level_of(i), i, None) for i in sorted(group.free)
            if not (p.levels[p.index.level_of(i)].linear and p.index.level_of(i) > 0)]
        probes += [(order, None, j) for order, null in nulls.items() if null is not None
                   for j in range(null.shape[2])]
        for order, i, j in probes:
            moved = X.copy()
            if i is not None:
                moved[i] += 0.37
                first = order
            else:
                moved[list(group.unknown[order])] += 0.73 * nulls[order][:, :, j].T
                first = order + 1
            self._levels(group, moved, targets, first, same)
            for oid, value in before.items():
                after = _call(dict(p.objectives)[oid], moved, value.shape[0])
                size = np.maximum(np.abs(value).max(axis=0), 1e-12)
                with np.errstate(invalid="ignore"):
                    same &= np.abs(after - value).max(axis=0) <= PROBE_TOL * size + 1e-12
        return same

    def _on_branch(self, group: _Group, X: np.ndarray) -> np.ndarray:
        ok = np.ones(X.shape[1], dtype=bool)
        scale = 1e-6 * np.maximum(np.abs(group.state), 1.0)
        for i, root in self.branches.items():
            if i not in group.unknown[self.p.index.level_of(i)]:
                continue
            if root is Root.POSITIVE:
                ok &= X[i] > scale[i]
            elif root is Root.NEGATIVE:
                ok &= X[i] < -scale[i]
        return ok

    def _degenerate(self, group: _Group, X: np.ndarray) -> np.ndarray:
        """Instants where the scalar solver would warn of a degenerate configuration."""
        p = self.p
        n = X.shape[1]
        flagged = np.zeros(n, dtype=bool)
        solved = list(group.solved)
        if not solved:
            return flagged
        size = p.index.size
        other = X.copy()
        other[solved] = other[solved] * 1.13 + 0.07
        count = len(p.points)
        if count > 1:
            here = _call(p.point_positions, X[:size], 3 * count).reshape(3, count, n)
            there = _call(p.point_positions, other[:size], 3 * count).reshape(3, count, n)
            finite = np.where(np.isfinite(here), np.abs(here), 0.0)
            scale = SAME_ROOT * np.maximum(finite.max(axis=(0, 1)), 1e-12)
            for a in range(count):
                for b in range(a):
                    close = np.abs(here[:, a] - here[:, b]).max(axis=0) <= scale
                    always = np.abs(there[:, a] - there[:, b]).max(axis=0) <= scale
                    flagged |= close & ~always
        level = p.levels[0]
        rank = p.constraint_rank
        if level.constraint_rows and rank:
            flagged |= self._weakest(X) < SINGULAR * self._weakest(other)
        return flagged

    def _weakest(self, X: np.ndarray) -> np.ndarray:
        p = self.p
        level = p.levels[0]
        n = X.shape[1]
        ncols = len(p.index.unknowns(0))
        J = _call(level.jacobian, X[:p.index.size], len(level.labels) * ncols).reshape(
            len(level.labels), ncols, n)[:level.constraint_rows, :p.index.n]
        finite = np.isfinite(J).all(axis=(0, 1))
        sv = np.linalg.svd(np.where(finite, J, 0.0).transpose(2, 0, 1), compute_uv=False)
        rank = p.constraint_rank
        weakest = sv[:, rank - 1] if sv.shape[1] >= rank else np.zeros(n)
        return np.where(finite, weakest, np.nan)

    def _kinetics(self, X: np.ndarray, known: np.ndarray):
        """The extended states (second rates and reactions solved from the momentum
        balances), and which passed the checks of :func:`~.dynamics.solve_kinetics`."""
        kp = self.kinetics
        n = X.shape[1]
        x = np.concatenate([X, np.zeros((len(kp.kin.reactions), n))])
        known = np.concatenate([known, np.zeros(len(kp.kin.reactions), bool)])
        cols = [j for j, i in enumerate(kp.columns) if not known[i]]
        for j in cols:
            x[kp.columns[j]] = 0.0
        ok = np.ones(n, dtype=bool)
        for _, speed, _ in kp.slips:
            ok &= _call(speed, x, 1)[0] > 1e-12
        rows_ = len(kp.labels)
        A = _call(kp.jacobian, x, rows_ * len(kp.columns)).reshape(rows_, len(kp.columns), n)
        A = A[:, cols]
        b = _call(kp.residual, x, rows_)
        ok &= np.isfinite(A).all(axis=(0, 1)) & np.isfinite(b).all(axis=0)
        Ab = np.where(ok, A, 0.0).transpose(2, 0, 1)
        U, s, Vt = np.linalg.svd(Ab, full_matrices=False)
        ok &= s[:, -1] > RANK_TOL * np.maximum(s[:, 0], 1.0) if len(cols) else ok
        with np.errstate(all="ignore"):
            inverse = np.where(s > 0, 1.0 / np.where(s > 0, s, 1.0), 0.0)
            coeff = np.einsum("nmk,mn->nk", U, -np.where(ok, b, 0.0)) * inverse
            sol = np.einsum("nkj,nk->jn", Vt, coeff)
        for j, value in zip(cols, sol):
            x[kp.columns[j]] = value
        r = _call(kp.residual, x, rows_)
        scale = np.abs(_call(kp.scale, x, rows_))
        with np.errstate(invalid="ignore"):
            ok &= np.all(np.abs(r) <= self.problem.consistency * scale + 1e-10, axis=0)
            for _, _, normal in kp.slips:
                ok &= ~(_call(normal, x, 1)[0] < -1e-9)
            for _, tangential, normal, mu in kp.bounds:
                f = np.linalg.norm(_call(tangential, x, 3), axis=0)
                nn = _call(normal, x, 1)[0]
                m = _call(mu, x, 1)[0]
                ok &= ~(nn < -1e-9) & ~(f > m * nn * (1 + 1e-9) + 1e-12)
            for bound, f in kp.physical:  # as solve_kinetics's check_physical
                ok &= np.array([bound.holds(v) for v in _call(f, x, 1)[0]], dtype=bool)
        return x, ok

    # -- generated mistakes

    def _generated(self, group: _Group, maps: list[dict], X: np.ndarray, ok: np.ndarray,
                   values: dict) -> dict:
        """Each numeric objective's generated mistakes at every variant's instant, as a
        function of the variant: the model mutations there, then its givens misread (those
        instants solved together too); kept as :func:`~.mutants.attach` keeps them."""
        problem, p = self.problem, self.p
        n = len(maps)
        table = model_mistake_table(problem, p, X[:p.index.size], group.numeric, _call)
        changed, owner = [], []
        for i in np.flatnonzero(ok):
            for code, changes, sentence in slips_of(maps[i], self.parameters):
                moved = dict(maps[i])  # only the values are read by the stacked solve
                for key, mistaken_si in changes:
                    moved[key] = (None, mistaken_si, None)
                changed.append((moved, maps[i], changes))
                owner.append((i, code, sentence))
        misreadings: dict[str, list[list]] = {oid: [[] for _ in range(n)]
                                              for oid in group.numeric}
        solved, found = self._misread_values(group, changed)
        for oid in group.numeric:
            obj = problem.objective(oid)
            shown = _shown(found[oid], obj) if changed else []
            defined = (solved & np.isfinite(found[oid]).all(axis=0)) if changed else []
            for k in np.flatnonzero(defined):
                i, code, sentence = owner[k]
                misreadings[oid][i].append(GeneratedMistake(code, sentence, shown[k]))
        out = {}
        for oid in group.numeric:
            obj = problem.objective(oid)
            rows_ = [row for row in table if row[0].objective == oid]
            out[oid] = _kept(obj, values[oid], rows_, misreadings[oid])
        return out

    def _misread_values(self, group: _Group, changed: list) -> tuple[np.ndarray, dict]:
        """The numeric objectives at each misread instant (``changed`` holds ``(values,
        givens, changes)``): which solved, and each objective's SI values (size x count). A
        degenerate configuration is no reason to drop a mistake
        (:func:`~.mutants.given_mistakes`)."""
        if not changed:
            return np.zeros(0, dtype=bool), {}
        _, ok, values, _ = self._instant(group, [c[0] for c in changed], False)
        solved = ok.copy()
        for i in np.flatnonzero(~ok):  # what the stacked path does not vouch for: alone
            _, givens, changes = changed[i]
            try:
                alone = solve_numeric(self.problem, self.p, misread(givens, changes),
                                      set(group.numeric)).values
            except MechgradeError:
                continue
            solved[i] = True
            for oid, v in values.items():
                v[:, i] = alone[oid]
        return solved, values


def _shown(si: np.ndarray, obj: Objective) -> list:
    """SI values (size x N) in the objective's unit, as :func:`~.instant._report` gives
    each (a float, or a tuple of components)."""
    values = (si / si_factor(obj.unit) + 0.0).T.tolist()
    return [tuple(v) for v in values] if obj.kind == "vector" else [v[0] for v in values]


def _kept(obj: Objective, si: np.ndarray, rows_: list, misread: list[list]):
    """The generated mistakes :func:`~.mutants.attach` keeps for every variant at once (the
    model mutations in ``rows_``, then each variant's ``misread`` givens): those that differ
    from the answer and from every one kept before them, and are not a vague zero. Returns
    the mistakes of variant ``i`` as a function of ``i``."""
    n = si.shape[1]
    size = si.shape[0]
    slots = max((len(m) for m in misread), default=0)
    count = len(rows_) + slots
    if not count:
        return lambda i: ()
    V = np.full((n, count, size), np.nan)
    exists = np.zeros((n, count), dtype=bool)
    other = np.zeros((n, count), dtype=bool)
    for j, row in enumerate(rows_):
        V[:, j] = row[3]
        exists[:, j] = row[2]
        other[:, j] = row[0].code == "other_point"
    first = len(rows_)
    for i, mistakes in enumerate(misread):
        if mistakes:
            last = first + len(mistakes)
            V[i, first:last] = np.array([m.value for m in mistakes], float).reshape(-1, size)
            exists[i, first:last] = True
            other[i, first:last] = [m.code == "other_point" for m in mistakes]
    right = (si / si_factor(obj.unit) + 0.0).T
    with np.errstate(invalid="ignore"):
        norms = np.linalg.norm(V, axis=2)
        scale = np.maximum(np.linalg.norm(right, axis=1), 1e-12)
        answer = np.linalg.norm(V - right[:, None, :], axis=2) <= \
            SAME * np.maximum(norms, scale[:, None]) + 1e-12
        vague = ~other & ~(np.abs(V) > 1e-12).any(axis=2)
        keep = np.zeros((n, count), dtype=bool)
        for j in range(count):
            apart = np.linalg.norm(V[:, :j] - V[:, j:j + 1], axis=2)
            same = apart <= SAME * np.maximum(np.maximum(norms[:, :j], norms[:, j:j + 1]),
                                              1e-12) + 1e-12
            keep[:, j] = exists[:, j] & ~(same & keep[:, :j]).any(axis=1) & ~answer[:, j] \
                & ~vague[:, j]

    def at(i: int) -> tuple[GeneratedMistake, ...]:
        return tuple(model_mistake_at(rows_[j], i) if j < len(rows_)
                     else misread[i][j - len(rows_)] for j in np.flatnonzero(keep[i]))
    return at


def _size(problem: Problem, oid: str) -> int:
    return 3 if problem.objective(oid).kind == "vector" else 1


def _nullity(p: Plan, level, values: np.ndarray, active: np.ndarray, unknown: list) -> int:
    """How many directions of the linear ``level``'s unknowns its equations leave free at the
    reference's instant."""
    if not unknown:
        return 0
    if not active.any():
        return len(unknown)
    columns = list(p.index.unknowns(level.order))
    J = _call(level.jacobian, values[:, None], len(level.labels) * len(columns)).reshape(
        len(level.labels), len(columns), 1)[active][:, [columns.index(i) for i in unknown]]
    _, rank, _ = _least_squares(J, np.zeros((int(active.sum()), 1)),
                                np.isfinite(J).all(axis=(0, 1)))
    return len(unknown) - int(rank[0])


@dataclass(frozen=True)
class _Switching:
    """The kinetics with each ``|u|`` and ``sign(u)`` read with a direction given beside the
    state (one per ``u``, the *mode*: ``|u|`` as ``mode * u``): the equations of the motion
    before a slip ends, continued smoothly past it. ``speeds`` gives every ``u``."""

    speeds: Callable
    residual: Callable
    jacobian: Callable
    count: int


@lru_cache(maxsize=64)
def _switches(kp) -> _Switching | None:
    """The kinetics of ``kp`` with their switches read as :class:`_Switching` says; ``None``
    when nothing switches."""
    import sympy as sp

    exprs = [e.expr for e in (*kp.kin.balances, *kp.kin.constraints)]
    speeds: list = []
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, (sp.Abs, sp.sign)) and node.args[0] not in speeds:
                speeds.append(node.args[0])
    if not speeds:
        return None
    modes = sp.symbols(f"_mode0:{len(speeds)}")
    table = dict(zip(speeds, modes))

    def kept(e):
        e = e.replace(lambda a: isinstance(a, sp.Abs) and a.args[0] in table,
                      lambda a: table[a.args[0]] * a.args[0])
        return e.replace(lambda a: isinstance(a, sp.sign) and a.args[0] in table,
                         lambda a: table[a.args[0]])

    matrix = sp.Matrix([kept(e) for e in exprs])
    unknowns = [kp.symbols[i] for i in kp.columns]
    symbols = (*kp.symbols, *modes)
    return _Switching(
        speeds=sp.lambdify(kp.symbols, speeds, modules="numpy", cse=True),
        residual=sp.lambdify(symbols, matrix, modules="numpy", cse=True),
        jacobian=sp.lambdify(symbols, matrix.jacobian(unknowns), modules="numpy", cse=True),
        count=len(speeds))


def _positions(p: Plan, given_map: dict) -> dict[str, int]:
    """Where each given of a coordinate, rate, parameter or ``t`` sits in the state."""
    return {key: p.index.symbols.index(p.k.quantity(node))
            for key, (node, _, _) in given_map.items() if isinstance(node, (Name, Prime))}


def _integration_group(p: Plan, overrides: dict, objectives, numeric: frozenset,
                       given_map: dict, g) -> _Group:
    """An instant reached by integrating the motion: only the givens are placed (the start
    state and the motion come from them), and the state at the event has its coordinates,
    rates, parameters and time known (as :func:`~.events.integrate_to_event` marks them)."""
    index = p.index
    after = np.zeros(index.size, dtype=bool)
    after[list(index.config)] = True
    after[list(index.rates(1))] = True
    return _Group(overrides, tuple(objectives), numeric, given_map, g.values.copy(),
                  g.known.copy(), ((), (), ()), (), (), {}, (), frozenset(),
                  _positions(p, given_map), (0, 0, 0), after, frozenset())


def _template(problem: Problem) -> _Template | None:
    return _template_cached(problem, locations(problem))


@lru_cache(maxsize=64)
def _template_cached(problem: Problem, _locations: tuple) -> _Template | None:
    """The reference solve of ``problem`` kept for its variants; ``None`` when this path does
    not cover the problem, or the reference itself needs the scalar solver's care (a failed
    objective, a freedom, a warning)."""
    kinetics = None
    kproblem = problem
    analysis = problem.dynamics.analysis if problem.dynamics is not None else None
    if problem.dynamics is not None:
        from .dynamics import kinematic_problem, kinetics_plan
        kinetics = kinetics_plan(problem)
        kproblem = kinematic_problem(problem)
        p = kinetics.kp
    else:
        p = plan(problem)
    if any(b.root is Root.FIRST_POSITIVE for b in problem.branches):
        return None
    try:
        reference = solve(problem)
    except MechgradeError:
        return None
    if reference.failures or tuple(reference.warnings) != tuple(p.k.warnings):
        return None
    groups = []
    for overrides, objectives in _instants(problem):
        given_map = instant_givens(problem, None, overrides)
        numeric = frozenset(o.id for o in objectives if o.kind != "symbolic")
        if not numeric:  # symbolic objectives only: no instant to solve
            empty = np.zeros(p.index.size)
            groups.append(_Group(overrides, tuple(objectives), numeric, given_map, empty,
                                 empty.astype(bool), ((), (), ()), (), (), {}, (),
                                 frozenset(), {}, (0, 0, 0), empty.astype(bool),
                                 frozenset()))
            continue
        try:
            if kinetics is not None and problem.dynamics is not None \
                    and problem.dynamics.design is not None:
                from .dynamics import _designed
                given_map = _designed(problem, kproblem, kinetics, given_map)
            g = place_givens(kproblem, p, given_map)
            if isinstance(analysis, Integration):
                groups.append(_integration_group(p, overrides, objectives, numeric,
                                                 given_map, g))
                continue
            instant = solve_numeric(kproblem, p, given_map,
                                    set() if kinetics is not None else set(numeric))
        except MechgradeError:
            return None
        free = instant.state.free
        if instant.errors or instant.warnings:
            return None
        unknown, active, target, conditions = [], [], [], {}
        nullity: list[int] = []
        for level in p.levels:
            on, goal = rows(level, g)
            mine = [i for i in p.index.unknowns(level.order)
                    if not g.known[i] and g.solvable[i]]
            unknown.append(tuple(mine))
            active.append(on)
            target.append(goal)
            nullity.append(_nullity(p, level, instant.state.values, on, mine)
                           if level.linear and level.order > 0 else 0)
            for j, key in enumerate(level.conditions):
                conditions[key] = (level.order, level.constraint_rows + j)
        solved = tuple(i for i in p.index.config if not g.known[i] and i not in free)
        after, loose = g.known.copy(), free
        if isinstance(analysis, WorkEnergy):  # the energy balance fixes the rates
            after[list(p.index.rates(1))] = True
            loose = frozenset()
        groups.append(_Group(overrides, tuple(objectives), numeric, given_map,
                             instant.state.values.copy(), g.known.copy(), tuple(unknown),
                             tuple(active), tuple(target), conditions, solved, free,
                             _positions(p, given_map), tuple(nullity), after, loose))
    if not groups:
        return None
    return _Template(problem, kproblem, p, kinetics, tuple(groups))


solve_variants.cache_clear = _template_cached.cache_clear  # type: ignore[attr-defined]
