"""Many variants of one problem solved together: every student's givens at once.

The lambdified functions of a problem's plan take arrays as well as numbers, so the instants
of many variants are solved in one pass, one column each, by the stages a single solve runs
(:func:`~.numeric.solve_numeric_columns`: the levels, the roots, the freedoms probed, the
givens checked to hold, the degenerate configurations), each non-linear level from the
reference's root (the solution with the spec's own givens): the root a variant continues
from the configuration the author checked, and for a level with one root (every linear
level, every level the spec picks a root of) the root :func:`~.entry.solve` finds.
Misread givens are solved as :func:`~.mutants.given_mistakes` solves them, every
misreading of every variant together.

A dynamics instant reached otherwise is reached the same way for every variant at once: the
rates from the energy balance (:func:`~.work_energy.energy_rates`); the motion integrated
to its event (:func:`~.batch_motion.integrate_to_events`: each variant's DOP853 steps, all
variants' right-hand sides in one call); a design parameter by Newton's method around the
whole instant (:func:`~.batch_motion.newton`: every variant's iterate and a point beside it
in one call), from the guess :meth:`~.dynamics.DesignedInstant.designed` starts at. An
objective asked before an integration's event (at a time, coordinate or rate of its own) is
read at each variant's instant as :func:`~.instant.drive` reaches it alone, beside the others
solved together.

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

import warnings
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Callable, Collection, Mapping, Sequence

import numpy as np

from ..errors import MechgradeError
from ..expressions.syntax import Name, Prime, to_text
from ..mechanics.kinematics import locations
from ..spec.dynamics import Integration, WorkEnergy, instant_of_objective
from ..spec.model import Objective, Problem, Root
from .batch_motion import ROOT_RTOL, ROOT_XTOL, newton
from .entry import solve
from .events import event_never_happens
from .instant import (_instants, _key, _size, _symbolic_answer, answer_group,
                      collect_results, in_unit,
                      instant_givens, numeric_result, read_objectives, shown, solution_of,
                      symbolic_dependence, wanted_objectives)
from .columns import FirstErrors, call
from .levels import State, place_givens
from .mutants import (ZERO_NAMES, kept_mistakes, misread, model_mistake_at, model_mistake_table,
                      plausible_slips, slips_of, stacked)
from .numeric import solve_numeric, solve_numeric_columns
from .dynamics_mutants import with_class_mistakes
from .motion import Motion, after_event, balances
from .phases import gripping
from .plan import KinematicsPlan, kinematics_plan
from . import rules
from .result import (GeneratedMistake, Solution)
from .work_energy import energy_rates
from .stored import Outcome, load_variant, store_variant, variant_keys

def solve_variants(problem: Problem, variants: Sequence[Mapping[str, float | None] | None],
                   objectives: Collection[str] | None = None) -> list[Outcome]:
    """``[solve(problem, givens=g, objectives=objectives) for g in variants]``, each a
    :class:`Solution` or the error :func:`~.entry.solve` raises, computed together (see the
    module's docstring).

    With the disk cache on, a dynamics problem's variants (all its objectives) are kept there
    (:mod:`.stored`): those stored are read back, the others solved together and stored, equal
    givens once (a variant's last digits depend on the others solved with it: one entry per
    givens gives them all the same, in this run and the next)."""
    given = [dict(g or {}) for g in variants]
    keys = [key for key in variant_keys(problem, given) if key is not None] \
        if problem.dynamics is not None and objectives is None else []
    if len(keys) < len(given):  # not kept (a kinematics problem, the cache off...)
        return [outcome for outcome, _ in _solved_together(problem, given, objectives)]
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


def answers_together(problem: Problem, variants: Sequence[Mapping[str, float | None]],
                     objectives: Collection[str]) -> list[Outcome]:
    """:func:`solve_variants` of a dynamics problem (a mistaken model, a misread given) for
    the answers alone: no generated mistakes attached and nothing kept in the disk cache, a
    variant not solved together solved by :func:`~.dynamics.solve_dynamics`."""
    return [outcome for outcome, _ in _solved_together(problem, [dict(g) for g in variants],
                                                       objectives, mistakes=False)]


def _solved_together(problem: Problem, given: list[dict],
                     objectives: Collection[str] | None = None,
                     mistakes: bool = True) -> list[tuple[Outcome, bool]]:
    """Each variant's outcome, and whether it was solved with the others (else by
    :func:`~.entry.solve`). A dynamics solution carries its model's generated mistakes, as
    :func:`~.entry.solve` gives them: those solved together are worked out together, for all
    of them at once, when one is first looked at (without ``mistakes``: none, and a variant
    solved alone by :func:`~.dynamics.solve_dynamics`)."""
    found: list[Outcome | None] = [None] * len(given)
    template = _template(problem) if given else None
    if template is not None:
        chosen = [i for i, g in enumerate(given) if template.covers(g)]
        for i, solution in zip(chosen, template.solve([given[i] for i in chosen],
                                                      objectives)):
            found[i] = solution
        if problem.dynamics is not None and mistakes:
            together = [i for i in chosen if isinstance(found[i], Solution)]
            solved = [s for s in found if isinstance(s, Solution)]
            for i, solution in zip(together, with_class_mistakes(
                    problem, solved, [given[i] for i in together], answers_together)):
                found[i] = solution
    alone = solve
    if not mistakes:
        from .dynamics import solve_dynamics as alone
    out: list[tuple[Outcome, bool]] = []
    for givens, solution in zip(given, found):
        if solution is None:
            try:
                out.append((alone(problem, givens=givens, objectives=objectives), False))
            except MechgradeError as err:
                out.append((err, False))
        else:
            out.append((solution, True))
    return out


# ---------------------------------------------------------------------------- the template


@dataclass(frozen=True)
class _Group:
    """One instant of the problem (objectives asked with the same givens) as the reference
    solved it: its givens, its root (or, for an integration, its givens placed), where each
    given sits in the state and the unknowns its givens leave free."""

    overrides: dict
    objectives: tuple[Objective, ...]
    numeric: frozenset[str]
    givens: dict
    state: np.ndarray
    positions: Mapping[str, int]
    free: frozenset[int]
    after: np.ndarray  # what the reached state marks given (the analysis fixes the rates)
    loose: frozenset[int]  # and leaves free
    alone: bool = False  # an instant before an integration's event: each column reached alone


class _Template:
    """What every variant of a problem shares with the reference solve."""

    def __init__(self, problem: Problem, kproblem: Problem, p: KinematicsPlan, kinetics, groups):
        self.problem, self.kproblem, self.p, self.kinetics = problem, kproblem, p, kinetics
        self.groups: tuple[_Group, ...] = groups
        self.keys = frozenset(to_text(g.key.node) for g in problem.givens)
        self.branches = {p.index.position(to_text(b.key.node)): b.root
                         for b in problem.branches}
        self.parameters = {q.name for q in problem.parameters}
        self.plausible = plausible_slips(problem)
        dynamics = problem.dynamics
        self.analysis = dynamics.analysis if dynamics is not None else None
        # the motion over columns (a problem without bodies and loads has none)
        self.motion = Motion(problem, kinetics) if kinetics is not None else None
        self.design = dynamics.design if dynamics is not None else None

    def _motion(self) -> Motion:
        assert self.motion is not None, "a problem with bodies and loads"
        return self.motion

    def covers(self, givens: dict) -> bool:
        """Whether ``givens`` only change values the reference has (no new given, none
        removed)."""
        try:
            return all(value is not None and _key(key)[1] in self.keys
                       for key, value in givens.items())
        except MechgradeError:
            return False

    # -- solving

    def solve(self, variants: list[dict], asked: Collection[str] | None = None
              ) -> list[Solution | MechgradeError | None]:
        """Each variant's solution (or, for a dynamics problem, the error
        :func:`~.dynamics.solve_dynamics` raises when no objective is solved), or ``None``
        where it must be solved one by one; only the objectives ``asked`` (all by default)."""
        n = len(variants)
        if not n:
            return []
        problem = self.problem
        wanted = wanted_objectives(problem, asked)
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
            if group.alone:
                self._alone(group, maps, objectives, ok, results, lost, base)
                continue
            values: dict = {}
            mistakes: dict = {}
            generated: dict = {}
            # the columns whose instant is not reached, for a reason solve() gives too
            unreached: dict[int, MechgradeError] = {}
            missing: list[dict] = [{} for _ in range(n)]  # objectives not existing there
            if group.numeric & wanted:
                X, fine, values, mistakes, unreached, missing = self._instant(group, maps)
                for ms in mistakes.values():
                    for m in ms:  # an undefined declared mistake fails its objective
                        fine &= np.isfinite(m).all(axis=0)
                unreached = {i: err for i, err in unreached.items() if ok[i] and not fine[i]}
                never = np.zeros(n, dtype=bool)
                never[list(unreached)] = True
                ok &= fine | never
                self._keep_state(group, X, ok & ~never, maps, base)
                if self.kinetics is None:
                    generated = self._generated(group, maps, X, ok, values)
            numeric = [o for o in objectives if o.kind != "symbolic"]
            symbols = [o.id for o in objectives if o.kind == "symbolic"]
            answers: dict = {}  # this problem's symbolic answers, by what they depend on
            value_shown = {o.id: shown(values[o.id], o) for o in numeric}
            declared = {o.id: [shown(v, o) for v in mistakes.get(o.id, ())] for o in numeric}
            # a dynamics objective undefined at a variant's instant is that objective's
            # failure (as collect_results words it); any other has made the variant not ok
            defined = {o.id: np.isfinite(values[o.id]).all(axis=0)
                       & np.all([np.isfinite(v).all(axis=0) for v in mistakes.get(o.id, ())]
                                + [np.ones(n, dtype=bool)], axis=0) for o in numeric}
            for i in np.flatnonzero(ok):
                failures: dict = {}
                for o in numeric:
                    if int(i) in unreached:  # as solve_dynamics keeps it
                        failures[o.id] = unreached[int(i)]
                        continue
                    if o.id in missing[i]:
                        failures[o.id] = missing[i][o.id]
                        continue
                    if not defined[o.id][i]:
                        collect_results(problem, [o], maps[i], {o.id: values[o.id][:, i]},
                                        {o.id: [m[:, i] for m in mistakes.get(o.id, ())]},
                                        results[i], failures)
                        continue
                    results[i][o.id] = numeric_result(
                        o, value_shown[o.id][i], [v[i] for v in declared[o.id]],
                        generated[o.id](i) if generated else (),
                        self.plausible if self.kinetics is None else None)
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
        return [self._solution(results[i], base[i], lost[i], wanted) if ok[i] else None
                for i in range(n)]

    def _alone(self, group: _Group, maps: list[dict], objectives: list[Objective],
               ok: np.ndarray, results: list[dict], lost: list[dict], base: list) -> None:
        """The objectives of ``group`` at every column's instant, each column's reached as
        :func:`~.instant.drive` reaches it alone: an instant before an integration's event,
        which the integrator over columns does not stop at (and which, integrated, carries
        no warning of its own)."""
        from .dynamics import kinetic_reach

        reach = kinetic_reach(self.problem)
        for i in np.flatnonzero(ok) if objectives else ():
            reached = answer_group(self.problem, reach, maps[i], objectives, group.overrides,
                                   results[i], lost[i])
            if reached is not None and base[i] is None:
                base[i] = (reached.state, reached.givens)

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
        if self.kinetics is not None:  # the rates the balances solved
            from .dynamics import _with_kinetics
        for i in np.flatnonzero(ok):
            if not group.overrides or base[i] is None:
                state = State(X[:size, i], group.after, group.loose)
                if self.kinetics is not None:
                    state = _with_kinetics(self.kinetics, state, X[:, i])
                base[i] = (state, maps[i])

    def _solution(self, results: dict, base, failures: dict,
                  wanted: set[str]) -> Solution | MechgradeError:
        return solution_of(self.problem, self.kproblem, self.p, results, failures, base,
                           tuple(self.p.k.warnings), wanted)

    def _instant(self, group: _Group, maps: list[dict]):
        """The numeric objectives and declared mistakes of ``group`` at every variant's
        instant, which instants passed every screen, those not reached with the error the
        scalar solver gives them (an integration's event that never happens, a balance that
        fails at an instant otherwise reached), and per column the objectives that
        do not exist there with their errors (in dynamics each objective's failure, as
        :func:`~.dynamics.solve_dynamics` keeps it; a kinematics column with one fails)."""
        p = self.p
        unreached: dict[int, MechgradeError] = {}
        if self.design is not None and self.design.find not in group.overrides:
            X, ok = self._designed(group, maps)
        elif isinstance(self.analysis, Integration):
            X, ok, never, stuck = self._motion().integrated(self._placed(group, maps))
            assert isinstance(self.analysis, Integration)
            unreached = dict.fromkeys(np.flatnonzero(never).tolist(),
                                      event_never_happens(self.analysis))
            unreached.update(stuck)
        else:
            X, ok, warned = self._reached(group, maps, unreached)
            ok &= ~warned
        X, before = self._at_event(X)
        read = read_objectives(self.problem, self.kinetics or p, X, group.numeric,
                               rules.REQUIRED if self.kinetics is None
                               else rules.REQUIRED_KINETIC, before)
        values, declared = read.values, read.mistakes
        if self.kinetics is None:  # a dynamics objective undefined there is its failure
            for v in values.values():
                ok &= np.isfinite(v).all(axis=0)
        missing = read.missing
        if self.kinetics is None:
            ok &= np.array([not m for m in missing], dtype=bool)
        return X, ok, values, declared, unreached, missing

    def _placed(self, group: _Group, maps: list[dict]) -> np.ndarray:
        """The givens of every variant placed in the state layout, one column each (what an
        integration starts from)."""
        X = np.repeat(group.state[:, None], len(maps), axis=1)
        for key, at in group.positions.items():
            X[at] = [m[key][1] for m in maps]
        return X

    def _reached(self, group: _Group, maps: list[dict],
                 raised: dict[int, MechgradeError] | None = None
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The instants the givens ``maps`` describe, one column each (the state extended by
        the reactions for a dynamics problem), which passed the screens, and which the
        scalar solver would warn of (a degenerate configuration). Each column's levels are
        solved as :func:`~.entry.solve` solves them, all at once
        (:func:`~.numeric.solve_numeric_columns`); a column that solve refuses, or that
        leaves an objective undetermined or other unknowns free than the reference, fails
        the screens (solved alone, it gets that solve's own message). Into ``raised``: the
        columns that passed every screen of the configuration but whose energy balance or
        momentum balances fail, with the error :func:`~.dynamics.solve_dynamics` raises for
        them (it would reach the instant the same way and stop there)."""
        if isinstance(self.analysis, Integration):
            X, ok, _, _ = self._motion().integrated(self._placed(group, maps))
            return X, ok, np.zeros(len(maps), dtype=bool)
        n = len(maps)
        # a column not solved keeps the reference's root: every later stage stays defined
        X = np.repeat(group.state[:, None], n, axis=1)
        ok = np.zeros(n, dtype=bool)
        warned = np.zeros(n, dtype=bool)
        only = set(group.numeric) if self.kinetics is None else set()
        for i, instant in enumerate(solve_numeric_columns(self.kproblem, self.p, maps, only,
                                                          near=group.state)):
            if isinstance(instant, MechgradeError) or instant.errors or \
                    instant.state.free != group.free:
                continue
            X[:, i] = instant.state.values
            ok[i] = True
            warned[i] = bool(instant.warnings)
        if self.kinetics is None:
            return X, ok, warned
        first = FirstErrors(n)
        if isinstance(self.analysis, WorkEnergy):
            X, first = energy_rates(self.problem, self.kinetics, X)
        solved = balances(self.problem, self.kinetics, X, group.after)
        fine = first.ok & solved.ok
        if raised is not None:
            for k in np.flatnonzero(ok & ~fine & ~warned).tolist():  # warned: alone
                error = first[k] or solved.errors[k]
                assert error is not None  # a column not fine has its error
                raised[k] = error
        return solved.x, ok & fine, warned

    def _designed(self, group: _Group, maps: list[dict]) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_reached` with the design parameter solved at every column by Newton's
        method from the guess (:func:`~.batch_motion.newton`, as
        :class:`~.dynamics.DesignedInstant` solves one instant); a column it does not
        converge for is solved alone, where the bracketing search may find its root."""
        assert self.design is not None and self.kinetics is not None
        find = self.design.find
        node = Name(find)
        equation = self.kinetics.design
        n = len(maps)
        last: dict[str, np.ndarray] = {}  # each column's instant at its latest iterate

        def valued(cols, values) -> list[dict]:
            return [{**maps[i], find: (node, float(v), None)} for i, v in zip(cols, values)]

        def residual(cols: np.ndarray, values: np.ndarray) -> np.ndarray:
            both = np.concatenate([cols, cols])  # the iterates, then the points beside them
            reached, fine, warned = self._reached(group, valued(both, values.ravel()))
            if not last:
                last.update(X=np.full((reached.shape[0], n), np.nan),
                            ok=np.zeros(n, dtype=bool), warned=np.zeros(n, dtype=bool),
                            at=np.full(n, np.nan))
            k = len(cols)
            last["X"][:, cols], last["ok"][cols], last["warned"][cols], last["at"][cols] = \
                reached[:, :k], fine[:k], warned[:k], values[0]
            r = np.where(fine, call(equation, self._at_event(reached)[0], 1)[0], np.nan)
            return r.reshape(2, k)

        guess = self.design.guess
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            root, converged = newton(residual, np.full(n, guess))
        converged &= np.isfinite(root)
        # Newton stops once its next iterate is within its tolerance of the last one
        # evaluated: that instant is the root's (as closely as the root is known), not
        # reached again
        kept = converged & (np.abs(last["at"] - root) <= ROOT_RTOL * np.abs(root) + ROOT_XTOL)
        out, ok = last["X"].copy(), last["ok"] & kept
        redo = np.flatnonzero(~kept)
        if len(redo):
            out[:, redo], ok[redo], warned = self._reached(group, valued(
                redo, np.where(converged[redo], root[redo], guess)))
            ok[redo] &= ~warned
        if not isinstance(self.analysis, Integration):  # of the configuration only
            ok[kept] &= ~last["warned"][kept]
        return out, ok & converged

    def _at_event(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """``X`` as :meth:`_reached` gave it, parted: the extended states the objectives are
        read from, and for an integration the states just before the event stacked under
        them by :meth:`integrated` (else ``None``)."""
        if not isinstance(self.analysis, Integration):
            return X, None
        half = X.shape[0] // 2
        return X[:half], X[half:]

    # -- generated mistakes

    def _generated(self, group: _Group, maps: list[dict], X: np.ndarray, ok: np.ndarray,
                   values: dict) -> dict:
        """Each numeric objective's generated mistakes at every variant's instant, as a
        function of the variant: the model mutations there, then its givens misread (those
        instants solved together too); kept as :func:`~.mutants.attach` keeps them."""
        problem, p = self.problem, self.p
        n = len(maps)
        table = model_mistake_table(problem, p, X[:p.index.size], group.numeric)
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
            mistaken = shown(found[oid], obj) if changed else []
            defined = (solved & np.isfinite(found[oid]).all(axis=0)) if changed else []
            for k in np.flatnonzero(defined):
                i, code, sentence = owner[k]
                misreadings[oid][i].append(GeneratedMistake(code, sentence, mistaken[k]))
        out = {}
        for oid in group.numeric:
            obj = problem.objective(oid)
            rows_ = [row for row in table if row[0].objective == oid]
            out[oid] = _kept(obj, values[oid], rows_, misreadings[oid])
        return out

    def _misread_values(self, group: _Group, changed: list) -> tuple[np.ndarray, dict]:
        """The numeric objectives at each misread instant (``changed`` holds ``(values,
        givens, changes)``): which solved, and each objective's SI values (size x count),
        all solved together as :func:`~.mutants.given_mistakes` solves one variant's."""
        if not changed:
            return np.zeros(0, dtype=bool), {}
        instants = solve_numeric_columns(self.problem, self.p, [
            misread(givens, changes) for _, givens, changes in changed], set(group.numeric),
            probe=False)
        solved = np.array([not isinstance(i, MechgradeError) for i in instants], dtype=bool)
        values = {oid: np.full((_size(self.problem, oid), len(changed)), np.nan)
                  for oid in group.numeric}
        for k in np.flatnonzero(solved):
            instant = instants[k]
            assert not isinstance(instant, MechgradeError)
            for oid, v in values.items():
                v[:, k] = instant.values[oid]
        return solved, values


def _kept(obj: Objective, si: np.ndarray, rows_: list, misread: list[list]):
    """The generated mistakes :func:`~.mutants.attach` keeps for every variant at once (the
    model mutations in ``rows_``, then each variant's ``misread`` givens): those that differ
    from the answer and from every one kept before them, and are not a vague zero. Returns
    the mistakes of variant ``i`` as a function of ``i``."""
    n, size = si.shape[1], si.shape[0]
    if not rows_ and not any(misread):
        return lambda _i: ()
    V = np.full((n, len(rows_), size), np.nan)
    exists = np.zeros((n, len(rows_)), dtype=bool)
    other = np.zeros((n, len(rows_)), dtype=bool)
    codes = np.full((n, len(rows_)), "", dtype=object)
    for j, row in enumerate(rows_):
        V[:, j], exists[:, j] = row[3], row[2]
        other[:, j], codes[:, j] = row[0].code in ZERO_NAMES, row[0].code
    # the model's mutations, then each variant's misread givens
    V, exists, other, codes = (np.concatenate(parts, axis=1) for parts in
                               zip((V, exists, other, codes), stacked(misread, size)))
    keep = kept_mistakes(in_unit(si, obj).T, V, exists, other, codes=codes)

    def at(i: int) -> tuple[GeneratedMistake, ...]:
        return tuple(model_mistake_at(rows_[j], i) if j < len(rows_)
                     else misread[i][j - len(rows_)] for j in np.flatnonzero(keep[i]))
    return at


def _positions(p: KinematicsPlan, given_map: dict) -> dict[str, int]:
    """Where each given of a coordinate, rate, parameter or ``t`` sits in the state."""
    return {key: p.index.symbols.index(p.k.quantity(node))
            for key, (node, _, _) in given_map.items() if isinstance(node, (Name, Prime))}


def _integration_group(p: KinematicsPlan, overrides: dict, objectives, numeric: frozenset,
                       given_map: dict, g) -> _Group:
    """An instant reached by integrating the motion: only the givens are placed (the start
    state and the motion come from them), and the state at the event has its coordinates,
    rates, parameters and time known (as :func:`~.events.integrate_to_event` marks them)."""
    return _Group(overrides, tuple(objectives), numeric, given_map, g.values.copy(),
                  _positions(p, given_map), frozenset(), after_event(p), frozenset())


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
        from .dynamics import kinematic_problem, kinetics_plan, solve_dynamics
        kinetics = kinetics_plan(problem)
        kproblem = kinematic_problem(problem)
        p = kinetics.kp
    else:
        p = kinematics_plan(problem)
    if any(b.root is Root.FIRST_POSITIVE for b in problem.branches) or \
            any(o.when is not None for o in problem.objectives) or gripping(problem):
        # each variant solved alone (an objective's own position is searched, or the motion
        # goes on in another phase once a slip ends)
        return None
    # An integrated motion's variants are reached from their own givens, each column
    # screened: its reference need not be solved (a mistaken model's event may never happen
    # for the spec's givens, as for every variant). Any other continues from the reference's
    # root, which must be one the scalar solver finds without care.
    integrated = isinstance(analysis, Integration) and problem.dynamics is not None \
        and problem.dynamics.design is None
    if integrated:
        # solved all the same, first: a symbolic answer, kept for the givens it depends on,
        # is the one the spec's givens give, as when the reference must be solved
        try:
            solve_dynamics(problem)
        except MechgradeError:
            pass
    else:
        try:
            # the reference's answers only (a dynamics one's generated mistakes are not asked)
            reference = solve(problem) if kinetics is None else solve_dynamics(problem)
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
                                 {}, frozenset(), empty.astype(bool), frozenset()))
            continue
        try:
            if kinetics is not None:
                from .dynamics import DesignedInstant, kinetic_reach
                reach = kinetic_reach(problem)
                if isinstance(reach, DesignedInstant):
                    given_map = reach.designed(given_map)
            g = place_givens(kproblem, p, given_map)
            if isinstance(analysis, Integration):
                groups.append(replace(
                    _integration_group(p, overrides, objectives, numeric, given_map, g),
                    alone=instant_of_objective(problem, overrides) is not None))
                continue
            instant = solve_numeric(kproblem, p, given_map,
                                    set() if kinetics is not None else set(numeric))
        except MechgradeError:
            return None
        free = instant.state.free
        if instant.errors or instant.warnings:
            return None
        after, loose = g.known.copy(), free
        if isinstance(analysis, WorkEnergy):  # the energy balance fixes the rates
            after[list(p.index.rates(1))] = True
            loose = frozenset()
        groups.append(_Group(overrides, tuple(objectives), numeric, given_map,
                             instant.state.values.copy(), _positions(p, given_map), free,
                             after, loose))
    if not groups:
        return None
    return _Template(problem, kproblem, p, kinetics, tuple(groups))


solve_variants.cache_clear = _template_cached.cache_clear  # type: ignore[attr-defined]
