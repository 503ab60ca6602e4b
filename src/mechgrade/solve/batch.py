"""Many variants of one problem solved together: every student's givens at once.

The lambdified functions of a problem's plan take arrays as well as numbers, so the levels of
many instants are solved in one pass: a linear rate level as a single solve solves it
(:func:`~.levels.solve_linear_columns`, every column at once), any other by the single solve's
non-linear solver (:func:`~.levels.solve_level_columns`) started at every column from the
reference's root (the solution with the spec's own givens). That is the root a variant
continues from the configuration the author checked, and for a level with one root (every
linear level, every level the spec picks a root of) it is the root :func:`~.entry.solve` finds.

A dynamics instant reached otherwise is reached the same way for every variant at once: the
rates from the energy balance (:func:`~.work_energy.energy_rates`); the motion integrated
to its event (:func:`~.batch_motion.integrate_to_events`: each variant's DOP853 steps, all
variants' right-hand sides in one call); a design parameter by Newton's method around the
whole instant (:func:`~.batch_motion.newton`: every variant's iterate and a point beside it
in one call), from the guess :meth:`~.dynamics.DesignedInstant.designed` starts at. An
objective asked before an integration's event (at a time, coordinate or rate of its own) is
read where each variant's motion, integrated the same way, first takes that value; a motion
in phases (a slip that ends, then a grip) or an objective asked ``when:`` on an integrated
motion, where :func:`~.phases.reach_columns` reaches it (each variant switching phase at its
own end of the slip; every group's instants in one pass of each phase). The loop over the
groups of objectives is the single solve's (:func:`~.instant.drive_columns`).

Every instant solved this way is screened for what the scalar solver would report: a level
not satisfied or losing rank, a root off its branch, a degenerate configuration, an objective
undefined or not existing there, a contact that slips or lets go, an energy the instant needs
more of than the start has, an event that does not happen, a design that does not converge. A
variant that fails a screen has that instant reached alone, by the single solve's step
(:func:`~.instant.answer_alone`); any problem or variant this path does not cover (givens the
reference does not have) is solved by :func:`~.entry.solve`; so the answers and messages are
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

from dataclasses import dataclass, replace
from functools import lru_cache, partial
from itertools import pairwise
from typing import Callable, Collection, Mapping, Sequence

import numpy as np

from ..errors import MechgradeError
from ..expressions.syntax import Name, Prime, to_text
from ..mechanics.kinematics import locations
from ..spec.dynamics import Integration, WorkEnergy, instant_of_objective
from ..spec.model import Objective, ObjectiveKind, Problem, Root
from .batch_motion import design_roots
from .entry import solve
from .instant import (Columns, GivenInstant, GroupStep, Reach, _instants, _key, _size,
                      answer_alone, class_givens, drive_columns, group_results, instant_givens,
                      read_objectives, reports_state, wanted_objectives, with_own)
from .columns import FirstErrors, call, collector_paused
from .levels import (NEAR_DAMPING, Givens, State, branches_asked, holds, on_branches,
                     level_rank, place_givens, rows, solve_level_columns,
                     solve_linear_columns, solve_nonlinear_columns, typical_sizes)
from .mutants import GeneratedColumns, generated_columns, plausible_slips, values_alone
from .numeric import FREE_PROBE, degenerate, freedoms, solve_numeric
from .dynamics_mutants import ClassMistakes
from .motion import Balanced, after_event, balances
from .phases import (Reaches, Target, Until, asked_when, checked, gripping, reach_columns,
                     stacked)
from .plan import KinematicsPlan, kinematics_plan
from . import rules
from .result import Solution
from .work_energy import energy_rates
from .stored import Outcome, load_variant, store_variant, variant_keys

def solve_variants(problem: Problem, variants: Sequence[Mapping[str, float | None] | None],
                   objectives: Collection[str] | None = None) -> list[Outcome]:
    """``[solve(problem, givens=g, objectives=objectives) for g in variants]``, each a
    :class:`Solution` or the error :func:`~.entry.solve` raises, computed together (see the
    module's docstring).

    With the disk cache on, a dynamics problem's variants (all its objectives) are kept there
    (:mod:`.stored`): those stored are read back, the others solved together and stored, equal
    givens once (a variant's last digits may depend on the others solved with it, where a
    level's Levenberg-Marquardt starts do: one entry per givens gives them all the same, in
    this run and the next)."""
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


@collector_paused()
def _solved_together(problem: Problem, given: list[dict],
                     objectives: Collection[str] | None = None,
                     mistakes: bool = True) -> list[tuple[Outcome, bool]]:
    """Each variant's outcome, and whether it was solved with the others (else by
    :func:`~.entry.solve`: a problem or givens the template does not cover). A dynamics
    solution carries its model's generated mistakes, as :func:`~.entry.solve` gives them:
    those solved together are worked out together, for all of them at once, when one is
    first looked at (without ``mistakes``: none, and a variant solved alone by
    :func:`~.dynamics.solve_dynamics`)."""
    found: list[Outcome | None] = [None] * len(given)
    template = _template(problem) if given else None
    if template is not None:
        chosen = [i for i, g in enumerate(given) if template.covers(g)]
        # a dynamics result made together carries its class's generated mistakes from the
        # start; the others (a column answered alone) have them attached
        attach = ClassMistakes(problem, [given[i] for i in chosen], answers_together) \
            if problem.dynamics is not None and mistakes else None
        solved = template.solve([given[i] for i in chosen], objectives, attach)
        for i, solution in zip(chosen, solved if attach is None else attach.attached(solved)):
            found[i] = solution
    alone = solve
    if not mistakes:
        from .dynamics import solve_dynamics as alone
    out: list[tuple[Outcome, bool]] = []
    for givens, outcome in zip(given, found):
        if outcome is None:
            try:
                out.append((alone(problem, givens=givens, objectives=objectives), False))
            except MechgradeError as err:
                out.append((err, False))
        else:
            out.append((outcome, True))
    return out


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


@dataclass(frozen=True)
class _Read:
    """A class's integrated groups reached side by side (:meth:`_Template._reaches`): where
    (``found``), each of its phases' columns read with their balances solved once for every
    group (``checks``: :func:`~.phases.checked` of each of ``found.phases``), and one group's
    columns among them, ``start`` to ``stop``."""

    found: Reaches
    checks: tuple[tuple[np.ndarray, np.ndarray | None, Balanced], ...]
    start: int
    stop: int


class _Template:
    """What every variant of a problem shares with the reference solve."""

    def __init__(self, problem: Problem, kproblem: Problem, p: KinematicsPlan, kinetics, groups):
        self.problem, self.kproblem, self.p, self.kinetics = problem, kproblem, p, kinetics
        self.groups: tuple[_Group, ...] = groups
        self.keys = frozenset(to_text(g.key.node) for g in problem.givens)
        self.branches = branches_asked(problem, p)
        self.parameters = {q.name for q in problem.parameters}
        self.plausible = plausible_slips(problem)
        dynamics = problem.dynamics
        self.analysis = dynamics.analysis if dynamics is not None else None
        self.design = dynamics.design if dynamics is not None else None
        self.reach: Reach | None = None  # made when a column is first answered alone

    def covers(self, givens: dict) -> bool:
        """Whether ``givens`` only change values the reference has (no new given, none
        removed)."""
        try:
            return all(value is not None and _key(key)[1] in self.keys
                       for key, value in givens.items())
        except MechgradeError:
            return False

    # -- solving

    def solve(self, variants: list[dict], asked: Collection[str] | None = None,
              mistakes: ClassMistakes | None = None) -> list[Solution | MechgradeError]:
        """Each variant's solution, or the error :func:`~.entry.solve` raises for it when
        no objective is solved; only the objectives ``asked`` (all by default). With
        ``mistakes`` (a dynamics class's), each result answered together carries them."""
        if not variants:
            return []
        problem = self.problem
        wanted = wanted_objectives(problem, asked)
        given = class_givens(problem, variants)
        integrated = self._integrated(given, wanted)
        steps: list[tuple[dict, tuple[Objective, ...], GroupStep]] = [
            (group.overrides, group.objectives,
             partial(self._together, group, integrated.get(k), mistakes))
            for k, group in enumerate(self.groups)]
        return drive_columns(problem, self.kproblem, self.p, tuple(self.p.k.warnings), steps,
                             variants, wanted, given)

    def _integrates(self, group: _Group) -> bool:
        """Whether ``group``'s instant is reached by integrating the motion from the givens in
        one pass with the class's other instants (:meth:`_reaches`; not by a design stage
        around it)."""
        return isinstance(self.analysis, Integration) and not self._designs(group)

    def _designs(self, group: _Group) -> bool:
        """Whether ``group``'s instant is reached by solving for the design parameter."""
        return self.design is not None and self.design.find not in group.overrides

    def _integrated(self, given: list[dict], wanted: Collection[str]
                    ) -> dict[int, _Read]:
        """Every integrated group's instant (those with a numeric objective ``wanted``) at
        every variant (``given``: each one's givens), reached in one pass of each phase:
        each group's columns side by side, each column integrated to its group's own instant
        or to the event (:meth:`_reaches`), so a class integrates its motion once however
        many instants it is asked at. By the group's index, its :class:`_Read`, what
        :meth:`_instant` reads."""
        chosen = [k for k, group in enumerate(self.groups) if self._integrates(group)
                  and any(o.id in wanted and o.id in group.numeric for o in group.objectives)]

        def own(k: int) -> list[dict]:  # each variant's givens of group k (read only there)
            overrides = self.groups[k].overrides
            return [with_own(g, overrides) for g in given] if overrides else given

        return dict(zip(chosen, self._reaches([(self.groups[k], own(k)) for k in chosen])))

    def _together(self, group: _Group, integrated: _Read | None,
                  attach: ClassMistakes | None, maps: list[dict],
                  objectives: list[Objective], overrides: dict, columns: Columns) -> None:
        """The :data:`~.instant.GroupStep` of ``group`` reached together: every column at once
        (:meth:`_instant`; an integrated group's instants ``integrated`` with the class's
        others, :meth:`_integrated`); one that fails a screen (or, in kinematics, an objective) is
        answered alone (:func:`~.instant.answer_alone`, the single solve's step). A dynamics
        result made here carries the class's generated mistakes ``attach`` (``None``: none).
        """
        problem, n = self.problem, len(maps)
        ok = np.ones(n, dtype=bool)
        symbolic: Callable | None = None
        if self.kinetics is not None:
            from .dynamics import _symbolic_result
            symbolic = _symbolic_result
        values: dict = {}
        mistakes: dict = {}
        generated: GeneratedColumns = {}
        # the columns whose instant is not reached, for a reason solve() gives too
        unreached: dict[int, MechgradeError] = {}
        missing: list[dict] = [{} for _ in range(n)]  # objectives not existing there
        numeric = frozenset(o.id for o in objectives) & group.numeric
        if numeric:
            placed, lost = self._at_positions(maps, numeric)
            X, fine, values, mistakes, unreached, missing = self._instant(group, placed, True,
                                                                          integrated)
            unreached.update(lost)
            for ms in mistakes.values():
                for m in ms:  # an undefined declared mistake fails its objective
                    fine &= np.isfinite(m).all(axis=0)
            unreached = {i: err for i, err in unreached.items() if not fine[i]}
            # the givens of an instant reached, its position among them (as a single solve's)
            maps = [m if i in unreached else placed[i] for i, m in enumerate(maps)]
            never = np.zeros(n, dtype=bool)
            never[list(unreached)] = True
            # (a kinematics instant not reached is no solution: answered alone, which raises)
            ok = fine | never if self.kinetics is not None else fine
            reached = ok & ~never
            self._designed_given(X, reached, maps)
            if self.kinetics is None:
                generated = generated_columns(problem, self.p, maps, X, ok, values,
                                              group.numeric, partial(self._misread, group),
                                              partial(_mutant_values, group))
            elif attach is not None:
                generated = {oid: partial(attach.of, objective_id=oid) for oid in group.numeric}
        # an objective undefined at a dynamics variant's instant is that objective's
        # failure (a kinematics one has made the variant not ok)
        failed = [dict.fromkeys(numeric, unreached[i]) if i in unreached else missing[i]
                  for i in range(n)]
        answered = np.flatnonzero(ok).tolist()
        for i, (solved, failures) in zip(answered, group_results(
                problem, objectives, maps, values, mistakes, failed, answered, symbolic,
                generated, self.plausible if self.kinetics is None
                else None if attach is None else attach.plausible)):
            if failures and self.kinetics is None:
                ok[i] = False
                continue
            columns.results[i].update(solved)
            columns.failures[i].update(failures)  # as solve_dynamics keeps them
        if numeric:
            self._keep_state(group, X, ok & reached, maps, columns.base)
        answer_alone(problem, self._reach(), maps, objectives, overrides, columns,
                     np.flatnonzero(~ok).tolist())

    def _reach(self) -> Reach:
        """How the single solve reaches an instant of the problem: the one column's step
        (:func:`~.instant.answer_alone`) a column failing together is answered by."""
        if self.reach is None:
            if self.kinetics is None:
                self.reach = GivenInstant(self.problem, self.p)
            else:
                from .dynamics import kinetic_reach
                self.reach = kinetic_reach(self.problem)
        return self.reach

    def _at_positions(self, maps: list[dict], numeric: Collection[str]
                      ) -> tuple[list[dict], dict[int, MechgradeError]]:
        """Each column's givens with the position an objective asked ``when`` fixes
        (:func:`~.dynamics.at_positions`, every column at once), and the columns that have
        none with its error (their position undefined: not reached)."""
        if self.kinetics is None:
            return maps, {}
        from .dynamics import at_positions

        placed: list[dict] = []
        lost: dict[int, MechgradeError] = {}
        name = self.problem.coordinates[0].name
        for i, (m, at) in enumerate(zip(maps, at_positions(self.problem, numeric, maps))):
            if isinstance(at, MechgradeError):
                lost[i] = at
                at = {**m, name: (Name(name), np.nan, None)}
            placed.append(at)
        return placed, lost

    def _designed_given(self, X: np.ndarray, ok: np.ndarray, maps: list[dict]) -> None:
        """The design parameter's value solved at each column ``ok`` put in its givens (it
        is given at the instant)."""
        if self.design is not None:
            at = self.p.index.position(self.design.find)
            for i in np.flatnonzero(ok):
                maps[i][self.design.find] = (Name(self.design.find), float(X[at, i]), None)

    def _keep_state(self, group: _Group, X: np.ndarray, ok: np.ndarray, maps: list[dict],
                    base: list) -> None:
        """Each variant's solved state and givens (a design parameter's value among them,
        :meth:`_designed_given`) as the solution reports them: those of the problem's own
        instant, else the first solved."""
        size = self.p.index.size
        if self.kinetics is not None:  # the rates the balances solved
            from .dynamics import _with_kinetics
        for i in np.flatnonzero(ok):
            if reports_state(base[i], group.overrides):
                state = State(X[:size, i], group.after, group.loose)
                if self.kinetics is not None:
                    state = _with_kinetics(self.kinetics, state, X[:, i])
                base[i] = (state, maps[i])

    def _instant(self, group: _Group, maps: list[dict], degenerate: bool,
                 integrated: _Read | None = None):
        """The numeric objectives and declared mistakes of ``group`` at every variant's
        instant, which instants passed every screen (with ``degenerate``, also the one for a
        degenerate configuration), those not reached with the error the scalar solver
        gives them (an integration's event that never happens, a balance that fails at an
        instant otherwise reached), and per column the objectives that
        do not exist there with their errors (in dynamics each objective's failure, as
        :func:`~.dynamics.solve_dynamics` keeps it; a kinematics column with one fails).
        An integrated group's instants are ``integrated`` already (its :class:`_Read`,
        :meth:`_integrated`)."""
        p = self.p
        unreached: dict[int, MechgradeError] = {}
        if self._designs(group) and self._reached_after_design(group):
            integrated = self._designed_when(group, maps)
        if integrated is not None:
            return self._in_phases(group, integrated)
        X, targets = self._placed(group, maps)

        def placed(i: int) -> Givens:  # column i's givens, for the error a stage words
            return place_givens(self.kproblem, p, maps[i])

        if self._designs(group):
            X, ok = self._designed(group, X, targets, placed, degenerate)
        else:
            X, ok = self._reached(group, X, targets, placed, degenerate, unreached)
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

    def _placed(self, group: _Group, maps: list[dict]) -> tuple[np.ndarray, list[np.ndarray]]:
        """``group``'s reference state and level targets at every column, each variant's
        givens (``maps``) placed in them."""
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
        return X, targets

    def _reaches(self, groups: list[tuple[_Group, list[dict]]]) -> list[_Read]:
        """Where each column of ``groups`` (each an integrated group, with its columns'
        givens) reaches the group's instant (the event, an objective's own time, coordinate
        or rate, or its ``when:``): every group's columns side by side, reached in one pass
        of each phase (:func:`~.phases.reach_columns`, as
        :meth:`~.dynamics.IntegratedInstant.phased` reaches one instant) and read with the
        balances solved once per phase for all of them; each group's part."""
        if not groups:
            return []
        from .dynamics import asked_entry, kinetics_plan

        problem = self.problem
        targets: list[Target] = []
        for group, maps in groups:
            asked = instant_of_objective(problem, group.overrides)
            when = asked_when(problem, group.numeric)
            if asked is not None:  # the group's entry, each column's value of it
                entry = asked_entry(problem, self.kinetics, maps[0], asked)
                targets += [replace(entry, value=m[asked][1]) for m in maps]
            else:
                targets += [when if when is not None else Until()] * len(maps)
        found = reach_columns(problem, np.hstack([self._placed(group, maps)[0]
                                                  for group, maps in groups]),
                              targets, kinetics_plan)
        checks = tuple(checked(at, kinetics_plan(at.phase)) for at in found.phases)
        starts = np.cumsum([0] + [len(maps) for _, maps in groups])
        return [_Read(found, checks, int(a), int(b)) for a, b in pairwise(starts)]

    def _in_phases(self, group: _Group, reached: _Read):
        """:meth:`_instant` of an integrated group at its columns, each reached and read
        (``reached``: :meth:`_reaches`): each column's objectives read with the model of the
        phase its instant is in (:func:`~.phases.checked`). The states returned are the state
        values (the extended states differ between phases)."""
        from .dynamics import kinetics_plan

        problem, size = self.problem, self.p.index.size
        start, stop = reached.start, reached.stop
        n = stop - start
        unreached: dict[int, MechgradeError] = {c - start: error for c, error
                                                in reached.found.errors.items()
                                                if start <= c < stop}
        ok = np.zeros(n, dtype=bool)
        out = np.full((size, n), np.nan)
        values = {oid: np.full((_size(problem, oid), n), np.nan) for oid in group.numeric}
        declared: dict[str, list[np.ndarray]] = {}
        missing: list[dict] = [{} for _ in range(n)]
        for at, (x, before, solved) in zip(reached.found.phases, reached.checks):
            mine = np.flatnonzero((at.columns >= start) & (at.columns < stop))
            if not len(mine):
                continue
            kp = kinetics_plan(at.phase)
            cols = at.columns[mine] - start
            fine = solved.ok[mine]
            for j in mine[~fine]:
                error = solved.errors[int(j)]
                assert error is not None  # a column not solved has its error
                unreached[int(at.columns[j]) - start] = error
            ok[cols] = fine
            out[:, cols] = x[:size, mine]
            read = read_objectives(at.phase, kp, x[:, mine], group.numeric,
                                   rules.REQUIRED_KINETIC,
                                   None if before is None else before[:, mine])
            for oid, v in read.values.items():
                values[oid][:, cols] = v
            for oid, vs in read.mistakes.items():
                into = declared.setdefault(oid, [np.full((len(v), n), np.nan) for v in vs])
                for whole, v in zip(into, vs):
                    whole[:, cols] = v
            for j, lost in zip(cols, read.missing):
                missing[int(j)] = lost
        return out, ok, values, declared, unreached, missing

    def _reached(self, group: _Group, X: np.ndarray, targets: list,
                 placed: Callable[[int], Givens], degenerate: bool,
                 raised: dict[int, MechgradeError] | None = None
                 ) -> tuple[np.ndarray, np.ndarray]:
        """The instants (each column of ``X`` the givens placed, ``placed(i)`` column ``i``'s,
        the state extended by the reactions for a dynamics problem) and which passed the
        screens. Into ``raised``: the
        columns that passed every screen of the configuration but whose energy balance or
        momentum balances fail, with the error :func:`~.dynamics.solve_dynamics` raises for
        them (it would reach the instant the same way and stop there); in kinematics, those
        whose first positive root is not found (:meth:`_first_positive`), with the error
        :func:`~.entry.solve` raises at that level."""
        if isinstance(self.analysis, Integration):
            from .dynamics import kinetics_plan

            X, ok, _ = stacked(self.problem, reach_columns(self.problem, X, [Until()] * X.shape[1],
                                                          kinetics_plan), kinetics_plan, X.shape[1])
            return X, ok
        n = X.shape[1]
        ok = np.all(np.isfinite(X[group.known]), axis=0) if group.known.any() else \
            np.ones(n, dtype=bool)
        searched: dict[int, MechgradeError] = {}
        nulls = self._levels(group, X, targets, placed, 0, ok, searched)
        if self.kinetics is None and (group.free or any(k for k in group.nullity)):
            ok &= self._determined(group, X, targets, placed, nulls, ok)
        ok &= self._on_branch(group, X)
        if degenerate:
            ok &= ~self._degenerate(group, X)
        if self.kinetics is None:
            if raised is not None:
                raised.update(searched)
            return X, ok
        first = FirstErrors(X.shape[1])
        if isinstance(self.analysis, WorkEnergy):
            X, first = energy_rates(self.problem, self.kinetics, X)
        solved = balances(self.problem, self.kinetics, X, group.after)
        fine = first.ok & solved.ok
        if raised is not None:
            for i in np.flatnonzero(ok & ~fine):
                error = first[int(i)] or solved.errors[int(i)]
                assert error is not None  # a column not fine has its error
                raised[int(i)] = error
        return solved.x, ok & fine

    def _designed(self, group: _Group, X: np.ndarray, targets: list,
                  placed: Callable[[int], Givens], degenerate: bool
                  ) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_reached` with the design parameter solved at every column by the design
        stage (:func:`~.batch_motion.design_roots`, as :class:`~.dynamics.DesignedInstant`
        solves one instant); a column it does not converge for is solved alone, where the
        bracketing search may find its root."""
        assert self.design is not None and self.kinetics is not None
        at = self.p.index.position(self.design.find)
        n = X.shape[1]
        last: dict[str, np.ndarray] = {}  # each column's instant at its latest iterate

        def reach(cols: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            moved = X[:, cols]
            moved[at] = values
            reached, fine = self._reached(group, moved, [t[:, cols] for t in targets],
                                          lambda j: placed(int(cols[j])), False)
            if not last:
                last.update(X=np.full((reached.shape[0], n), np.nan),
                            ok=np.zeros(n, dtype=bool), at=np.full(n, np.nan))
            k = len(cols) // 2  # the iterates, then the points beside them
            last["X"][:, cols[:k]], last["ok"][cols[:k]], last["at"][cols[:k]] = \
                reached[:, :k], fine[:k], values[:k]
            return self._at_event(reached)[0], fine

        guess = self.design.guess
        root, converged = design_roots(reach, self.kinetics.design, guess, n)
        # Newton's root is the last iterate it evaluated (its next within its tolerance):
        # that instant is the root's, not reached again
        kept = converged & (last["at"] == root)
        out, ok = last["X"].copy(), last["ok"] & kept
        redo = np.flatnonzero(~kept)
        if len(redo):
            moved = X[:, redo].copy()
            moved[at] = np.where(converged[redo], root[redo], guess)
            out[:, redo], ok[redo] = self._reached(group, moved,
                                                   [t[:, redo] for t in targets],
                                                   lambda j: placed(int(redo[j])), degenerate)
        again = np.flatnonzero(kept)
        if degenerate and len(again) and not isinstance(self.analysis, Integration):
            ok[again] &= ~self._degenerate(group, out[:, again])  # of the configuration only
        return out, ok & converged

    def _reached_after_design(self, group: _Group) -> bool:
        """Whether ``group`` on a designed motion is asked at an instant other than the event
        the design holds at: an objective's own instant, or ``when:``."""
        return instant_of_objective(self.problem, group.overrides) is not None or \
            asked_when(self.problem, group.numeric) is not None

    def _designed_when(self, group: _Group, maps: list[dict]) -> _Read:
        """Where each column of a group asked at its own instant or ``when`` on a designed
        motion (:meth:`_reached_after_design`) reaches it (:meth:`_reaches`), with its design
        value solved at the event first (:meth:`_designed`), as one solve designs the motion,
        then reaches the instant. A
        column whose design does not converge is in neither part of the result: answered
        alone, where the bracketing search may find its root."""
        assert self.design is not None
        find = self.design.find
        X, targets = self._placed(group, maps)
        designed, ok = self._designed(group, X, targets,
                                      lambda i: place_givens(self.kproblem, self.p, maps[i]),
                                      False)
        good = np.flatnonzero(ok)
        if not len(good):
            return _Read(Reaches((), {}), (), 0, len(maps))
        at = self.p.index.position(find)
        (read,) = self._reaches([(group, [{**maps[i], find: (Name(find), float(designed[at, i]),
                                                             None)} for i in good])])
        found = read.found
        return _Read(Reaches(tuple(replace(phase, columns=good[phase.columns])
                                   for phase in found.phases),
                             {int(good[c]): error for c, error in found.errors.items()}),
                     read.checks, 0, len(maps))

    def _at_event(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """``X`` as :meth:`_reached` gave it, parted: the extended states the objectives are
        read from, and for an integration the states just before the event stacked under
        them (:func:`~.phases.stacked`; else ``None``)."""
        if not isinstance(self.analysis, Integration):
            return X, None
        half = X.shape[0] // 2
        return X[:half], X[half:]

    def _levels(self, group: _Group, X: np.ndarray, targets, placed: Callable[[int], Givens],
                first: int, ok: np.ndarray,
                searched: dict[int, MechgradeError] | None = None
                ) -> dict[int, np.ndarray | None]:
        """Solve the levels from ``first`` on at every column of ``X`` (in place), clearing
        ``ok`` where a level is not solved as the reference's was; the nullspace bases of the
        linear rate levels (N x unknowns x nullity). Every level is solved as the single
        solve solves it (:func:`~.levels.solve_linear_columns`,
        :func:`~.levels.solve_level_columns` from the reference's root); with ``searched``
        (the instant itself, not a probe of its freedoms near it), a level whose branch asks
        for the first positive root is searched at every column (:meth:`_first_positive`),
        the position level's error at each column without one put in ``searched``."""
        p = self.p
        nulls: dict[int, np.ndarray | None] = {}
        for level in p.levels[first:]:
            order = level.order
            unknown = list(group.unknown[order])
            active, target = group.active[order], targets[order]
            if level.linear and order > 0:
                solved = solve_linear_columns(self.kproblem, p, order, X, group.known, active,
                                              target, placed)
                X[:] = solved.X
                ok &= solved.errors.ok & (solved.rank == len(unknown) - group.nullity[order])
                nulls[order] = solved.Vt[:, solved.rank.max(initial=0):, :].transpose(
                    0, 2, 1) if group.nullity[order] else None
                continue
            # the unknowns the level determines, each column from the reference's root (its
            # root does not depend on the other variants solved with it), the others kept
            solve_for = [i for i in unknown if i not in group.free]
            if solve_for:
                columns = list(p.index.unknowns(order))
                if searched is not None and any(self.branches.get(i) is Root.FIRST_POSITIVE
                                                for i in solve_for):
                    ok &= self._first_positive(group, order, X, placed, ok,
                                               searched if order == 0 else {})
                else:
                    fits = solve_level_columns(self.problem.consistency, level, X, solve_for,
                                               columns, active, target[active], NEAR_DAMPING)
                    X[:] = fits.X
                    ok &= fits.started & fits.held
                ok &= level_rank(level, X, solve_for, columns, active) == len(solve_for)
            elif active.any():
                ok &= holds(self.problem.consistency, level, X, active, target[active])
        return nulls

    def _first_positive(self, group: _Group, order: int, X: np.ndarray,
                        placed: Callable[[int], Givens], ok: np.ndarray,
                        errors: dict[int, MechgradeError]) -> np.ndarray:
        """Level ``order`` at the columns ``ok`` of ``X`` (in place) as the single solve
        solves it (:func:`~.levels.solve_nonlinear_columns`: the same starts, every column's
        at once, and the first positive root chosen by the same rule), not continued from the
        reference's root: another variant's first positive root may be another root. Which
        columns have one root there, leaving free what the reference's leaves free (another
        is answered alone, where that solve follows each root); into ``errors``, each column
        without a root with the error that solve meets there."""
        columns = list(self.p.index.unknowns(order))
        free = group.free & set(columns)
        found = np.zeros(X.shape[1], dtype=bool)
        chosen = np.flatnonzero(ok).tolist()
        gs = [placed(i) for i in chosen]
        size = self.p.index.size
        for i, roots in zip(chosen, solve_nonlinear_columns(
                self.kproblem, self.p, order, [State(X[:size, i].copy(), g.known) for i, g in zip(chosen, gs)],
                gs)):
            if isinstance(roots, MechgradeError):
                errors[i] = roots
                continue
            if len(roots.states) != 1 or set(roots.free) != free:
                continue
            X[columns, i] = roots.states[0].values[columns]
            found[i] = True
        return found

    def _determined(self, group: _Group, X: np.ndarray, targets,
                    placed: Callable[[int], Givens], nulls, ok: np.ndarray) -> np.ndarray:
        """Whether every numeric objective stays the same when what the givens leave free
        moves (each free unknown, each direction of a nullspace), as the scalar solver
        probes: where one changes, that solver names the objective not determined."""
        p = self.p
        same = ok.copy()
        before = {oid: call(f, X, _size(self.problem, oid)) for oid, f in p.objectives
                  if oid in group.numeric}
        nullity = {order: null.shape[2] for order, null in nulls.items() if null is not None}
        for freedom in freedoms(p, sorted(group.free), nullity):
            moved = X.copy()
            if freedom.position is not None:
                moved[freedom.position] += FREE_PROBE
            else:
                moved[list(group.unknown[freedom.order])] += (
                    nulls[freedom.order] @ freedom.shift(nullity[freedom.order])).T
            self._levels(group, moved, targets, placed, freedom.first, same)
            for oid, value in before.items():
                after = call(dict(p.objectives)[oid], moved, value.shape[0])
                same &= rules.unchanged(value, after)
        return same

    def _on_branch(self, group: _Group, X: np.ndarray) -> np.ndarray:
        """Which columns have every root the spec picks a branch of on it
        (:func:`~.levels.on_branches`, each column's typical sizes from its own givens)."""
        index = self.p.index
        picked = [i for i in self.branches if i in group.unknown[index.level_of(i)]]
        if not picked:
            return np.ones(X.shape[1], dtype=bool)
        return on_branches(self.branches, X, typical_sizes(self.kproblem, self.p,
                                                           X[:index.size], group.known), picked)

    def _degenerate(self, group: _Group, X: np.ndarray) -> np.ndarray:
        """Instants where the scalar solver would warn of a degenerate configuration."""
        pairs, singular = degenerate(self.p, X, list(group.solved))
        for _, _, flagged in pairs:
            singular = singular | flagged
        return singular

    # -- generated mistakes

    def _misread(self, group: _Group, maps: list[dict]) -> tuple[np.ndarray, dict, np.ndarray]:
        """The :data:`~.mutants.Misreadings` of ``group``: the instants of misread givens
        reached together, as the variants' (a degenerate configuration no reason to drop a
        mistake), and those one solve refuses: their position level without the root asked
        for (:meth:`_first_positive`), or their givens breaking the positions
        (:meth:`_conflicting`)."""
        _, ok, values, _, unreached, _ = self._instant(group, maps, False)
        refused = np.zeros(len(maps), dtype=bool)
        refused[list(unreached)] = True  # one solve stops there, with the same error
        failed = np.flatnonzero(~ok & ~refused)
        if len(failed):  # (most classes vouch for every one)
            refused[failed] = self._conflicting(group, [maps[i] for i in failed])
        return ok, values, refused

    def _conflicting(self, group: _Group, maps: list[dict]) -> np.ndarray:
        """Which columns' givens fix every position the position level reads but break it
        (a linkage's angle misread as radians): one solve refuses them by the same residual
        rule before it solves anything (:func:`~.levels.givens_conflict`), so no column's
        refusal depends on a root found or a start taken."""
        active = group.active[0]
        if group.unknown[0] or not active.any() or self._designs(group) \
                or self._integrates(group):
            return np.zeros(len(maps), dtype=bool)
        X, targets = self._placed(group, maps)
        return ~holds(self.problem.consistency, self.p.levels[0], X, active,
                      targets[0][active])


def _mutant_values(group: _Group, mutant: Problem, maps: Sequence[dict], wanted: set[str]
                   ) -> list[Mapping[str, np.ndarray] | None]:
    """:data:`~.mutants.MutantValues` of a class (``maps``: each variant's givens of
    ``group``): the mistaken model's instants solved together by its own template, from its
    own reference's root, as the class's variants are (:meth:`_Template._misread`); alone
    where it has none (:func:`~.mutants.values_alone`)."""
    template = _template(mutant, warned=False)
    # the same instant, each given placed where the class's own places it
    same = [g for g in template.groups if g.overrides == group.overrides
            and g.numeric == group.numeric and g.positions.keys() == group.positions.keys()
            and g.conditions.keys() == group.conditions.keys()] if template is not None else []
    if template is None or not maps or not same or frozenset(wanted) != group.numeric:
        return values_alone(mutant, maps, wanted)
    ok, values, refused = template._misread(same[0], list(maps))
    alone = np.flatnonzero(~ok & ~refused).tolist()
    redone = dict(zip(alone, values_alone(mutant, [maps[k] for k in alone], wanted)
                             if alone else ()))
    return [None if refused[k] else redone[k] if k in redone
            else {oid: v[:, k] for oid, v in values.items()} for k in range(len(maps))]


def _positions(p: KinematicsPlan, given_map: dict) -> dict[str, int]:
    """Where each given of a coordinate, rate, parameter or ``t`` sits in the state."""
    return {key: p.index.symbols.index(p.k.quantity(node))
            for key, (node, _, _) in given_map.items() if isinstance(node, (Name, Prime))}


def _integration_group(p: KinematicsPlan, overrides: dict, objectives, numeric: frozenset,
                       given_map: dict, g) -> _Group:
    """An instant reached by integrating the motion: only the givens are placed (the start
    state and the motion come from them), and the state at the event has its coordinates,
    rates, parameters and time known (:func:`~.motion.after_event`)."""
    return _Group(overrides, tuple(objectives), numeric, given_map, g.values.copy(),
                  g.known.copy(), ((), (), ()), (), (), {}, (), frozenset(),
                  _positions(p, given_map), (0, 0, 0), after_event(p), frozenset())


def _template(problem: Problem, warned: bool = True) -> _Template | None:
    return _template_cached(problem, locations(problem), warned)


@lru_cache(maxsize=64)
def _template_cached(problem: Problem, _locations: tuple, warned: bool) -> _Template | None:
    """The reference solve of ``problem`` kept for its variants; ``None`` when this path does
    not cover the problem, or the reference itself needs the scalar solver's care (a failed
    objective, a freedom, a warning). Without ``warned`` (the template of a mistaken model,
    whose values alone are read), a warning of the reference is no reason."""
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
    # An integrated motion's variants are reached from their own givens, each column
    # screened: its reference need not be solved (a mistaken model's event may never happen
    # for the spec's givens, as for every variant). Any other continues from the reference's
    # root, which must be one the scalar solver finds without care.
    integrated = isinstance(analysis, Integration) and problem.dynamics is not None \
        and problem.dynamics.design is None
    if not integrated and gripping(problem) is not None:
        # each variant solved alone (a motion designed goes on in another phase once a slip
        # ends: the design holds at an event reached through the phases)
        return None
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
        if reference.failures or (warned and tuple(reference.warnings) != tuple(p.k.warnings)):
            return None
    groups = []
    for overrides, objectives in _instants(problem):
        given_map = instant_givens(problem, None, overrides)
        numeric = frozenset(o.id for o in objectives if o.kind != ObjectiveKind.SYMBOLIC)
        if not numeric:  # symbolic objectives only: no instant to solve
            empty = np.zeros(p.index.size)
            groups.append(_Group(overrides, tuple(objectives), numeric, given_map, empty,
                                 empty.astype(bool), ((), (), ()), (), (), {}, (),
                                 frozenset(), {}, (0, 0, 0), empty.astype(bool),
                                 frozenset()))
            continue
        try:
            if kinetics is not None:
                from .dynamics import DesignedInstant, at_positions, kinetic_reach
                (at,) = at_positions(problem, numeric, [given_map])
                if isinstance(at, MechgradeError):
                    return None
                given_map = at
                reach = kinetic_reach(problem)
                if isinstance(reach, DesignedInstant):
                    given_map = reach.designed(given_map)
            g = place_givens(kproblem, p, given_map)
            if isinstance(analysis, Integration):
                groups.append(_integration_group(p, overrides, objectives, numeric, given_map, g))
                continue
            instant = solve_numeric(kproblem, p, given_map,
                                    set() if kinetics is not None else set(numeric))
        except MechgradeError:
            return None
        free = instant.state.free
        if instant.errors or (warned and instant.warnings):
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
            # how many directions of a linear rate level's unknowns its equations leave free
            # at the reference's instant
            nullity.append(len(mine) - int(solve_linear_columns(
                kproblem, p, level.order, instant.state.values[:, None], g.known, on,
                goal[:, None], (g,).__getitem__).rank[0]) if level.linear and level.order > 0
                else 0)
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
