"""Solve a problem at the instant its givens describe, and evaluate every objective.

Objectives are grouped by instant (the problem's givens, or those with an objective's own);
numeric ones are solved level by level (:mod:`.numeric`, :mod:`.levels`), symbolic ones with
sympy in the declared symbols (:mod:`.symbolic`). An objective that cannot be answered is a
failure beside the others' answers; the solved state is reported in the author's units.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> solution = solve_kinematics(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"))
>>> round(solution.result("acc_mag").value, 2), solution.result("acc_mag_symbolic").expr
(98.51, 'L*sqrt(thetad**4 + thetadd**2)')
"""

from __future__ import annotations

from functools import lru_cache
from dataclasses import dataclass, replace
from typing import Callable, Collection, Mapping, Protocol, Sequence

import numpy as np

from ..codec import decode, encode
from ..errors import AuthorWarning, MechgradeError, SolveError
from ..expressions.syntax import Prime, parse, to_text
from ..spec.language import FUNCTIONS
from ..spec.model import Given, Objective, ObjectiveKind, Problem
from ..spec.validate import symbol_meanings
from .. import tolerance
from ..units import dimension, si_factor, si_unit
from . import rules
from .columns import call, quiet
from .levels import State, author_units, constraint_ranks, evaluate
from .numeric import solve_numeric
from .plan import KinematicsPlan, generic_dof, kinematics_plan
from .plan import per_problem as _per_problem
from .mutants import (GeneratedColumns, generated_columns, plausible_slips, shown,
                      symbolic_mistakes)
from . import cache
from .result import MistakeValue, ObjectiveFailure, ObjectiveResult, Solution, StateValue

# sympy is imported by the functions that derive a symbolic answer: a warm solve of a problem
# whose plan and symbolic answers are in the disk cache never imports it.

def _numeric(objective: Objective) -> bool:
    return objective.kind != ObjectiveKind.SYMBOLIC


# ---------------------------------------------------------------------------- givens


@lru_cache(maxsize=1024)
def _key(text: str):
    """A given key's tree and canonical text; re-solves (ECF, every student's variant) pass the
    same few keys again and again."""
    node = parse(text, functions=FUNCTIONS)
    return node, to_text(node)


def _spec_givens(problem: Problem) -> dict:
    """The spec's own givens keyed by canonical key text (copied by :func:`_givens`)."""
    return _per_problem(_keyed_givens, problem)


def _keyed_givens(problem: Problem) -> dict:
    return {to_text(g.key.node): (g.key.node, g.si, g) for g in problem.givens}


def _givens(problem: Problem, overrides: Mapping[str, float | None] | None):
    """Given values keyed by canonical key text -> (key node, SI value, Given or None)."""
    return class_givens(problem, [overrides])[0]


def class_givens(problem: Problem, variants: Sequence[Mapping[str, float | None] | None]
                 ) -> list[dict]:
    """Each variant's givens (:func:`_givens`: the spec's, with its overrides): each key a
    class writes is read once (its tree, canonical text and the spec's given), not once per
    variant.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    >>> a, b = class_givens(problem, [{"L": 0.5}, {"L": 1.0}])
    >>> a["L"][1], b["L"][2].text
    (0.5, '3.28084 ft')
    """
    spec = _spec_givens(problem)
    read: dict[str, tuple] = {}  # a key as written -> its tree, canonical text, spec's given
    out = []
    for overrides in variants:
        given_map = dict(spec)
        for key, value in (overrides or {}).items():
            known = read.get(key)
            if known is None:
                node, canonical = _key(key)
                given = spec.get(canonical, (None, None, None))[2]
                known = read[key] = (node, canonical, None if given is None else (
                    si_factor(given.unit), {k: v for k, v in vars(given).items()
                                            if k not in ("value", "si", "text")}))
            node, canonical, replaced = known
            if value is None:
                given_map.pop(canonical, None)
                continue
            si = float(value)
            given = given_map.get(canonical, (None, None, None))[2]
            if given is not None and given.si != si:
                factor, rest = replaced
                # the value replaced, in the spec's unit, so messages show what was solved
                # with (as replace() gives it, at a fraction of the cost)
                number = si / factor + 0.0  # (as from_si gives it)
                given = Given(**rest, value=number, si=si,
                              text=f"{number:.6g} {given.unit}".strip())
            given_map[canonical] = (node, si, given)
        out.append(given_map)
    return out


# ---------------------------------------------------------------------------- numeric solve


def _check_requirements(problem: Problem, p: KinematicsPlan, state: State, only: set[str]) -> dict:
    """Errors for the objectives in ``only`` that do not exist at this instant."""
    return absent(problem, p.requirements, state.values[:, None], only, rules.REQUIRED)[0]


def absent(problem: Problem, requirements, X: np.ndarray, only: Collection[str],
           limit: float) -> list[dict[str, SolveError]]:
    """For every column of ``X`` (a state), the objectives in ``only`` that do not exist
    there (what one requires to be zero is more than ``limit`` away from it), each with its
    error."""
    out: list[dict[str, SolveError]] = [{} for _ in range(X.shape[1])]
    for oid, reason, f in requirements:
        if oid not in only:
            continue
        with np.errstate(invalid="ignore"):
            off = np.abs(call(f, X, 1)[0]) > limit
        for i in np.flatnonzero(off):
            out[i].setdefault(oid, SolveError(
                f"objective '{oid}' does not exist at this instant: {reason}",
                where=problem.objective(oid).where))
    return out


@dataclass(frozen=True)
class Readings:
    """The numeric objectives read at every column of the states: each one's SI values
    (size x N), its declared mistakes' values, and the objectives that do not exist at each
    column (with their errors)."""

    values: dict[str, np.ndarray]
    mistakes: dict[str, list[np.ndarray]]
    missing: list[dict[str, SolveError]]


def read_objectives(problem: Problem, plan, X: np.ndarray, numeric: Collection[str],
                    limit: float, before: np.ndarray | None = None) -> Readings:
    """The objectives ``numeric`` and their declared mistakes read by ``plan`` (a
    kinematics or kinetics plan: its ``objectives``, ``mistakes`` and ``requirements``) at
    every column of ``X``; ``before``: an integration's states just before its event, where
    an objective is read as :func:`~.events.at_the_event` says. ``limit``: how far from zero
    what an objective requires may be (:func:`absent`)."""
    values = {oid: call(f, X, _size(problem, oid)) for oid, f in plan.objectives
              if oid in numeric}
    if before is not None:
        from .events import at_the_event  # sympy: only a dynamics problem integrates

        functions = dict(plan.objectives)
        values = {oid: at_the_event(v, call(functions[oid], before, len(v)),
                                    problem.objective(oid))
                  for oid, v in values.items()}
    mistakes = {oid: [call(f, X, _size(problem, oid)) for f in fs]
                for oid, fs in plan.mistakes if oid in numeric}
    return Readings(values, mistakes, absent(problem, plan.requirements, X, numeric, limit))


def _size(problem: Problem, oid: str) -> int:
    """How many values an objective has: a vector's three components, else one."""
    return 3 if problem.objective(oid).kind == ObjectiveKind.VECTOR else 1


def _mistake_values(p: KinematicsPlan, state: State, only: set[str]) -> dict[str, list[np.ndarray]]:
    return {oid: [evaluate((("m", f),), state, {"m"})["m"] for f in funcs]
            for oid, funcs in p.mistakes if oid in only}


# ---------------------------------------------------------------------------- entry point


@dataclass(frozen=True)
class Reached:
    """One instant reached (:meth:`Reach.instant`) and its numeric objectives evaluated
    there: the givens (a design parameter's value put in), the state the solution reports,
    each objective's SI values and its declared mistakes' values, the objectives that failed
    there and the kinematics' warnings."""

    givens: dict
    state: State
    values: Mapping[str, np.ndarray]
    mistakes: dict
    failures: Mapping[str, MechgradeError]
    warnings: tuple[AuthorWarning, ...]


class Reach(Protocol):
    """How a problem's instants are reached and its objectives read there: the one thing
    :func:`drive` leaves to the kind of problem (kinematics here, kinetics in
    :mod:`.dynamics`)."""

    @property
    def problem(self) -> Problem:
        """The kinematics, whose state the solution reports."""

    @property
    def plan(self) -> KinematicsPlan:
        """Its plan."""

    @property
    def warnings(self) -> tuple[AuthorWarning, ...]:
        """The kinematics' warnings, before any instant's."""

    def instant(self, given_map: dict, numeric: set[str],
                overrides: dict) -> Reached:
        """The instant ``given_map`` describes (``overrides``: the objectives' own givens
        among them) with the objectives ``numeric`` read there; raises what makes every one
        of them fail."""

    def symbolic(self) -> Callable | None:
        """What :func:`group_results` derives a symbolic answer with (``None``: the
        kinematic one)."""

    def generated(self, reached: Reached, values: Mapping[str, np.ndarray],
                  numeric: set[str]) -> GeneratedColumns | None:
        """The generated mistakes of the objectives ``numeric`` at the instant ``reached``
        (``values``: their SI values there, one column), those this kind works out at each
        instant (``None``: none), as :func:`group_results` reads them."""

    @property
    def plausible(self) -> frozenset[str] | None:
        """The model's whole-answer slips put in each result (``None``: none put in)."""


def drive(problem: Problem, reach: Reach, givens: Mapping[str, float | None] | None,
          objectives: Collection[str] | None) -> Solution:
    """One solve: :func:`drive_columns` with one column, each group's instant reached by
    ``reach`` (:func:`reached_alone`); raises the first error when no objective is solved."""
    step = reached_alone(problem, reach)
    (solution,) = drive_columns(problem, reach.problem, reach.plan, reach.warnings,
                                [(overrides, group, step) for overrides, group
                                 in _instants(problem)],
                                [givens], wanted_objectives(problem, objectives))
    if isinstance(solution, MechgradeError):
        raise solution
    return solution


class Columns:
    """What :func:`drive_columns` has found so far for each column (one solve's one, or a
    class's variants): its results and failures, the state and givens its solution reports
    (:func:`reports_state`) and its warnings. Filled group after group by the steps, hence
    mutable."""

    def __init__(self, n: int, warnings: tuple[AuthorWarning, ...]):
        self.results: list[dict[str, ObjectiveResult]] = [{} for _ in range(n)]
        self.failures: list[dict[str, MechgradeError]] = [{} for _ in range(n)]
        self.base: list[tuple[State, dict] | None] = [None] * n
        self.warned: list[list[AuthorWarning]] = [list(warnings) for _ in range(n)]


GroupStep = Callable[[list[dict], list[Objective], dict, Columns], None]
"""How one group of objectives is answered at every column: ``(maps, chosen,
overrides, columns)``, each column's givens at the group's instant, the objectives asked,
their own givens, and what the columns have found (filled in)."""


def drive_columns(problem: Problem, kinematics: Problem, p: KinematicsPlan,
                  warnings: tuple[AuthorWarning, ...],
                  groups: Sequence[tuple[dict, Sequence[Objective], GroupStep]],
                  variants: Sequence[Mapping[str, float | None] | None],
                  wanted: Collection[str], given: Sequence[dict] | None = None
                  ) -> list[Solution | MechgradeError]:
    """The one solver loop, over columns (one per variant of the givens): every group of
    objectives asked at the same givens (``groups``: their own givens, the objectives, the
    :data:`GroupStep` that answers them), then each column's solution (:func:`solutions_of`:
    the objectives ``wanted``, the kinematics ``kinematics`` and its plan ``p``, the
    ``warnings`` before any instant's) or its error. ``given``: each variant's givens
    without a group's own (``instant_givens(problem, variant, {})``), where the caller has
    read them already.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    >>> reach = GivenInstant(problem, kinematics_plan(problem))
    >>> step = reached_alone(problem, reach)
    >>> a, b = drive_columns(problem, problem, reach.plan, (), [
    ...     (overrides, group, step) for overrides, group in _instants(problem)],
    ...     [{"L": 0.5}, {"L": 1.0}], {"acc_mag"})
    >>> round(b.result("acc_mag").value / a.result("acc_mag").value, 6)
    2.0
    """
    columns = Columns(len(variants), warnings)
    if given is None:  # once for all its groups (a class pays them per student)
        given = class_givens(problem, variants)
    for overrides, objectives, step in groups:
        chosen = [o for o in objectives if o.id in wanted]
        if chosen:
            step([with_own(g, overrides) for g in given], chosen, overrides, columns)
    return solutions_of(problem, kinematics, p, columns.results, columns.failures,
                        columns.base, [tuple(w) for w in columns.warned], wanted,
                        range(len(variants)))


def reached_alone(problem: Problem, reach: Reach) -> GroupStep:
    """The :data:`GroupStep` that reaches each column's instant alone (:func:`answer_alone`)."""

    def step(maps: list[dict], chosen: list[Objective], overrides: dict,
             columns: Columns) -> None:
        answer_alone(problem, reach, maps, chosen, overrides, columns, range(len(maps)))
    return step


def answer_alone(problem: Problem, reach: Reach, maps: list[dict], chosen: list[Objective],
                 overrides: dict, columns: Columns, which: Collection[int]) -> None:
    """The :data:`GroupStep`'s work for the columns ``which`` alone: each one's instant reached
    by ``reach`` and its objectives read there (:func:`_answer_group`), into ``columns``; a
    class's step leaves it the columns it does not answer together."""
    for i in which:
        reached = _answer_group(problem, reach, maps[i], chosen, overrides,
                                columns.results[i], columns.failures[i])
        if reached is not None:
            warned = columns.warned[i]
            warned += [w for w in reached.warnings if w not in warned]
            if reports_state(columns.base[i], overrides):
                columns.base[i] = (reached.state, reached.givens)


def reports_state(base: tuple[State, dict] | None, overrides: dict) -> bool:
    """Whether an instant reached for a group of objectives with givens of their own
    ``overrides`` gives the state a solution reports, ``base`` the one so far: the
    problem's own instant (a group without givens of its own) does, else the first reached.

    >>> reports_state(None, {"t": 1.0}), reports_state(("s", {}), {"t": 1.0})
    (True, False)
    """
    return not overrides or base is None


def _answer_group(problem: Problem, reach: Reach, given_map: dict, chosen: list[Objective],
                  overrides: dict, results: dict[str, ObjectiveResult],
                  failures: dict[str, MechgradeError]) -> Reached | None:
    """One group of objectives ``chosen`` asked at the givens ``given_map`` (``overrides``:
    their own among them): the instant reached by ``reach``, each objective read there (a
    symbolic one derived) into ``results``, or its error into ``failures``. Returns the
    instant reached (``None``: no numeric objective asked, or the instant not reached)."""
    numeric = {o.id for o in chosen if _numeric(o)}
    values: Mapping[str, np.ndarray] = {}
    mistakes: Mapping[str, list[np.ndarray]] = {}
    failed: Mapping[str, MechgradeError] = {}
    reached = None
    if numeric:
        try:
            with quiet():  # once for the whole instant, not at each function it calls
                reached = reach.instant(given_map, numeric, overrides)
        except MechgradeError as err:
            failed = dict.fromkeys(numeric, err)
        else:
            given_map, failed = reached.givens, reached.failures
            values = {oid: _column(v) for oid, v in reached.values.items()}
            mistakes = {oid: [_column(v) for v in vs] for oid, vs in reached.mistakes.items()}
    generated = None if reached is None else reach.generated(reached, values, numeric)
    ((solved, lost),) = group_results(problem, chosen, [given_map], values, mistakes, [failed],
                                      [0], reach.symbolic(), generated, reach.plausible)
    failures.update(lost)
    results.update(solved)
    return reached


def _column(si_values) -> np.ndarray:
    """One instant's SI values as the one column of :func:`group_results`."""
    return np.asarray(si_values, dtype=float).reshape(-1, 1)


def group_results(problem: Problem, objectives: Sequence[Objective], maps: Sequence[dict],
                  values: Mapping[str, np.ndarray], mistakes: Mapping[str, list[np.ndarray]],
                  failed: Sequence[Mapping[str, MechgradeError]], columns: Collection[int],
                  symbolic: Callable | None = None,
                  generated: GeneratedColumns | None = None,
                  plausible: frozenset[str] | None = None
                  ) -> list[tuple[dict[str, ObjectiveResult], dict[str, MechgradeError]]]:
    """Each of ``columns``' results and failures of one group of ``objectives`` (one
    instant of one solve, or a class's): a numeric objective's from its SI values at the
    column (``values``: size x N, ``mistakes`` its declared mistakes' values, ``generated``
    its generated mistakes as a function of the column), its error where ``failed`` (per
    column) has one or where it is undefined; a symbolic one's derived by ``symbolic`` (by
    default the kinematic one) at the column's givens ``maps``, once per
    :func:`symbolic_dependence`. ``plausible``: the model's slips put in each result.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    >>> asked = [problem.objective("acc_mag"), problem.objective("acc_mag_symbolic")]
    >>> givens = instant_givens(problem, None, {})
    >>> (right, _), (_, lost) = group_results(problem, asked, [givens] * 2, {
    ...     "acc_mag": np.array([[0.6096, np.nan]])}, {}, [{}, {}], [0, 1])
    >>> round(right["acc_mag"].value, 9), right["acc_mag_symbolic"].expr, list(lost)
    (2.0, 'L*sqrt(thetad**4 + thetadd**2)', ['acc_mag'])
    """
    numeric: list[Objective] = []
    symbols: list[str] = []
    for o in objectives:
        if _numeric(o):
            numeric.append(o)
        else:
            symbols.append(o.id)
    value_shown, declared, defined = {}, {}, {}
    for o in numeric:
        if o.id in values:
            value_shown[o.id] = shown(values[o.id], o)
            declared[o.id] = [shown(v, o) for v in mistakes.get(o.id, ())]
            defined[o.id] = np.isfinite(values[o.id]).all(axis=0)
            for v in mistakes.get(o.id, ()):
                defined[o.id] = defined[o.id] & np.isfinite(v).all(axis=0)
    answers: dict = {}  # the symbolic answers, by what they depend on
    out = []
    for i in columns:
        results: dict[str, ObjectiveResult] = {}
        failures: dict[str, MechgradeError] = {}
        for o in numeric:
            if o.id in failed[i]:
                failures[o.id] = failed[i][o.id]
            elif not defined[o.id][i]:
                failures[o.id] = _undefined(o)
            else:
                results[o.id] = numeric_result(
                    o, value_shown[o.id][i], [v[i] for v in declared[o.id]],
                    generated[o.id](i) if generated else (), plausible)
        for oid in symbols:
            depends = symbolic_dependence(problem, maps[i], oid)
            answer = answers.get((oid, depends))
            if answer is None:
                try:
                    answer = _symbolic_answer(symbolic, problem, oid, maps[i], depends)
                    if plausible is not None:
                        answer = replace(answer, plausible=plausible)
                except MechgradeError as err:
                    answer = err
                answers[oid, depends] = answer
            if isinstance(answer, MechgradeError):
                failures[oid] = answer
            else:
                results[oid] = answer
        out.append((results, failures))
    return out


def solutions_of(problem: Problem, kinematics: Problem, p: KinematicsPlan,
                 results: Sequence[Mapping[str, ObjectiveResult]],
                 failures: Sequence[Mapping[str, MechgradeError]],
                 bases: Sequence[tuple[State, dict] | None],
                 warnings: Sequence[tuple[AuthorWarning, ...]], wanted: Collection[str],
                 columns: Collection[int]) -> list[Solution | MechgradeError]:
    """Each of ``columns``' solution of the objectives ``wanted`` (in the problem's order)
    from its ``results`` and ``failures``, its state ``bases`` (the state and givens of the
    problem's own instant, :func:`reports_state`) reported in the units of ``kinematics``, its
    degrees of freedom (:func:`degrees_of_freedom`, every column's ranked together) and its
    ``warnings``; the first objective's error when none of them is solved."""
    dofs = degrees_of_freedom(p, [b[0] if b else None for b in bases])
    order = [o.id for o in problem.objectives if o.id in wanted]
    states = _states(kinematics, p, bases)
    out: list[Solution | MechgradeError] = []
    for i in columns:
        if not results[i] and order:  # nothing solved of what was asked
            out.append(failures[i][order[0]])
            continue
        out.append(Solution(
            problem=problem.id,
            results=tuple(results[i][oid] for oid in order if oid in results[i]),
            state=states[i], dof=dofs[i],
            failures=tuple(ObjectiveFailure(oid, failures[i][oid]) for oid in order
                           if oid in failures[i]),
            warnings=warnings[i]))
    return out


@dataclass(frozen=True)
class GivenInstant:
    """A kinematics problem's instants: its givens fix them (:func:`~.numeric.solve_numeric`
    solves the rest), its objectives' generated mistakes are worked out at each."""

    problem: Problem
    plan: KinematicsPlan

    @property
    def warnings(self) -> tuple[AuthorWarning, ...]:
        return tuple(self.plan.warnings)

    def instant(self, given_map: dict, numeric: set[str],
                overrides: dict) -> Reached:  # noqa: ARG002 - kinematics has no per-objective instant
        problem, p = self.problem, self.plan
        instant = solve_numeric(problem, p, given_map, numeric)
        return Reached(given_map, instant.state, instant.values,
                       _mistake_values(p, instant.state, numeric),
                       {**instant.errors,
                        **_check_requirements(problem, p, instant.state, numeric)},
                       tuple(instant.warnings))

    def symbolic(self) -> Callable | None:
        return None

    def generated(self, reached: Reached, values: Mapping[str, np.ndarray],
                  numeric: set[str]) -> GeneratedColumns:
        return generated_columns(self.problem, self.plan, [reached.givens],
                                 reached.state.values[:, None], np.ones(1, dtype=bool),
                                 values, numeric)

    @property
    def plausible(self) -> frozenset[str]:
        return plausible_slips(self.problem)


def solve_kinematics(problem: Problem, *, givens: Mapping[str, float | None] | None = None,
                     objectives: Collection[str] | None = None) -> Solution:
    """:func:`mechgrade.solve.solve` for a problem without bodies and loads."""
    return drive(problem, GivenInstant(problem, kinematics_plan(problem)), givens, objectives)


def wanted_objectives(problem: Problem, objectives: Collection[str] | None) -> set[str]:
    """The ids of the objectives asked for (all by default); an unknown id is an error."""
    wanted = set(objectives) if objectives is not None else {o.id for o in problem.objectives}
    unknown = wanted - {o.id for o in problem.objectives}
    if unknown:
        raise SolveError(f"no objective '{sorted(unknown)[0]}' in problem '{problem.id}'")
    return wanted


def instant_givens(problem: Problem, givens, overrides: dict) -> dict:
    """The givens at one instant: the problem's (with the caller's ``givens`` overrides),
    then the objective group's own givens on top."""
    return with_own(_givens(problem, givens), overrides)


def with_own(given_map: dict, overrides: dict) -> dict:
    """``given_map`` (an instant's givens, kept as it is) with an objective group's own
    givens ``overrides`` on top.

    >>> with_own({"a": (None, 1.0, None)}, {})
    {'a': (None, 1.0, None)}
    """
    return {**given_map, **{key: (g.key.node, g.si, g) for key, g in overrides.items()}}


_SYMBOLIC_ANSWERS: dict = {}
_SYMBOLIC_LIMIT = 4096


def _symbolic_answer(symbolic, problem: Problem, objective_id: str, given_map: dict,
                     dependence: tuple):
    """A symbolic objective's answer (by ``symbolic``, by default the kinematic one), solved
    once per problem and ``dependence`` (:func:`symbolic_dependence` of the givens): a
    variant that changes only givens with units (not to or from zero) reuses the answer of
    the first, without sympy. The kinematic answers are kept in the disk cache too
    (:mod:`.cache`), under the problem's plan and that dependence."""
    kinematic = symbolic is None
    symbolic = symbolic or _symbolic_result
    key = (symbolic, problem, objective_id, dependence)
    answer = _SYMBOLIC_ANSWERS.get(key)
    if answer is None:
        stored = _stored_answer_key(problem, objective_id, dependence) if kinematic else None
        answer = _stored_answer(stored) if stored is not None else None
        if answer is None:
            answer = symbolic(problem, objective_id,
                              tuple(sorted(given_map.items(), key=lambda item: item[0])))
            if stored is not None:
                _store_answer(stored, answer)
        if len(_SYMBOLIC_ANSWERS) >= _SYMBOLIC_LIMIT:
            _SYMBOLIC_ANSWERS.clear()
        _SYMBOLIC_ANSWERS[key] = answer
    return answer


def _stored_answer_key(problem: Problem, objective_id: str, dependence: tuple) -> str | None:
    key = kinematics_plan(problem).key
    return None if key is None else cache.digest("symbolic", key, objective_id, dependence)


def _stored_answer(key: str) -> ObjectiveResult | None:
    """The symbolic answer the disk cache holds under ``key`` (``None``: none, or unreadable)."""
    data = cache.load(key)
    try:
        return None if data is None else decode(ObjectiveResult, data)
    except ValueError:
        return None


def _store_answer(key: str, answer: ObjectiveResult) -> None:
    data = encode(answer)
    if decode(ObjectiveResult, data) == answer:  # nothing the stored form leaves out
        cache.store(key, data)


@dataclass(frozen=True)
class BearingGivens:
    """The disk cache's entry of :func:`_bearing_givens`: the givens a symbolic answer bears
    on (``None``: it cannot tell, every given may)."""

    bearing: frozenset[str] | None


def _bearing_givens(problem: Problem, objective_id: str) -> frozenset[str] | None:
    """:func:`.symbolic.bearing_givens`, kept in the disk cache under the problem: reading it
    derives the model with sympy, which a warm solve never imports. An entry that is not a
    :class:`BearingGivens` (spoilt, or of another version) is derived and stored again."""
    problem_key = cache.used_problem_key(problem)
    key = None if problem_key is None else cache.digest("bearing", problem_key, objective_id)
    data = cache.load(key) if key is not None else None
    if data is not None:
        try:
            return decode(BearingGivens, data).bearing
        except ValueError:
            pass
    from .symbolic import bearing_givens

    bearing = bearing_givens(problem, objective_id)
    if key is not None:
        cache.store(key, encode(BearingGivens(bearing)))
    return bearing


def symbolic_dependence(problem: Problem, given_map: dict, objective_id: str,
                        root: int | None = None) -> tuple:
    """What a symbolic objective's answer can depend on in the givens: which are given, which
    are zero (a zero stands in for its symbol in every unit), and the values of those that may
    stand in for their symbols (pure numbers and angles; in dynamics also given rates, which
    enter the momentum balances). A given with a unit is never substituted, nor is one of the
    objective's own symbols, so their values are left out.

    An objective asked ``when`` reads the coordinate only through the closed-form root put in
    for it (whether it is zero aside), and that root is the one found at the values of every
    given its equation reads: those values, unless ``root`` says which root it is
    (:func:`~.positions.which_root`).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    >>> a, b = instant_givens(problem, None, {}), instant_givens(problem, {"L": 0.5}, {})
    >>> key = "acc_mag_symbolic"
    >>> symbolic_dependence(problem, a, key) == symbolic_dependence(problem, b, key)
    True
    """
    dynamics = problem.dynamics is not None
    objective = problem.objective(objective_id)
    declared = _per_problem(_declared, problem, objective)
    bearing = _per_problem(_bearing_givens, problem, objective_id)
    position = problem.coordinates[0].name if objective.when is not None else None
    out: list[tuple[str, object]] = [("root", root)] if position is not None else []
    for key, (node, si, given) in sorted(given_map.items(), key=lambda item: item[0]):
        token: object
        if bearing is not None and key not in bearing:
            token = None
        elif key == position:
            token = si == 0
        elif position is not None and root is None:  # each value may choose another root
            token = (si, None if given is None else (given.value, given.unit))
        elif key in declared:
            token = None
        elif given is None or si_unit(given.unit) in ("", "rad") or \
                (dynamics and isinstance(node, Prime)):
            token = (si, None if given is None else (given.value, given.unit))
        else:
            token = si == 0
        out.append((key, token))
    return tuple(out)


def _declared(problem: Problem, objective: Objective) -> frozenset[str]:
    """The given keys an objective's declared symbols stand for (``theta'`` for ``thetad``)."""
    return frozenset(to_text(node) for node in symbol_meanings(problem, objective).values())


def _instants(problem: Problem):
    """Objectives grouped by the instant they are asked at: the problem's givens, or those
    plus an objective's own givens, or the position its ``when`` fixes (those first: the
    problem's own instant is the last one without givens of its own)."""
    groups: dict[tuple, tuple[dict, list[Objective]]] = {}
    for obj in problem.objectives:
        overrides = {to_text(g.key.node): g for g in obj.givens}
        key = tuple(sorted((name, g.si) for name, g in overrides.items()))
        when = None if obj.when is None else tuple(e.text for e in obj.when)
        groups.setdefault((key, when), (overrides, []))[1].append(obj)
    return sorted(groups.values(),
                  key=lambda group: (bool(group[0]), group[1][0].when is None))


@lru_cache(maxsize=512)
def _symbolic_result(problem: Problem, objective_id: str, givens: tuple) -> ObjectiveResult:
    """A symbolic objective's answer; cached, since re-solving with other givens (error carried
    forward, variants) rarely changes the pure-number givens it depends on."""
    from .symbolic import symbolic

    obj = problem.objective(objective_id)
    expr, meanings = symbolic(problem, kinematics_plan(problem).k, obj, dict(givens))
    units = tuple(_quantity_unit(problem, node) for node in meanings.values())
    signed = tuple(_may_be_negative(problem, node) for node in meanings.values())
    return ObjectiveResult(
        id=obj.id, kind=obj.kind, unit=obj.unit, expr=_shortest(expr), symbols=tuple(meanings),
        symbol_units=units, symbol_signed=signed, rel=obj.tolerance.rel, abs=obj.tolerance.abs,
        prompt=obj.prompt,
        generated_mistakes=symbolic_mistakes(problem, obj, expr, dict(givens)))


def _shortest(expr) -> str:
    """The expression as text in its shortest equivalent form (as simplified, or expanded:
    ``l*thetadd + 2*ld*thetad - s*thetad**2`` rather than ``... + thetad*(ld - s*thetad)``).

    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> _shortest(x*y + y*(x - y))
    '2*x*y - y**2'
    """
    import sympy as sp

    forms = [expr] + ([sp.expand(expr)] if sp.count_ops(expr) <= 300 else [])
    return min((sp.sstr(f) for f in forms), key=lambda text: (len(text), text))


def numeric_result(obj: Objective, value, mistakes: Sequence, generated: Sequence = (),
                   plausible: frozenset[str] | None = None) -> ObjectiveResult:
    """A numeric objective's result from its value and its declared ``mistakes``' values as
    :func:`shown` gives them, with its ``generated`` mistakes and ``plausible`` slips: one
    instant's, or one column's of a class."""
    return ObjectiveResult(
        id=obj.id, kind=obj.kind, unit=obj.unit, value=value, frame=obj.frame,
        mistakes=tuple(MistakeValue(m.message, m.credit, v)
                       for m, v in zip(obj.mistakes, mistakes)),
        rel=obj.tolerance.rel, abs=obj.tolerance.abs, prompt=obj.prompt,
        generated_mistakes=generated, plausible=plausible)


def degrees_of_freedom(p: KinematicsPlan, states: Sequence[State | None]) -> list[int]:
    """Coordinates minus independent constraint equations at each of ``states`` (rank of the
    velocity-level constraints in the rates, at the instant when it is solved; the generic
    count where it is not, ``None``); the states of one length are ranked together.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve.numeric import solve_numeric
    >>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_8_connected_blocks.yaml")
    >>> p = kinematics_plan(problem)
    >>> state = solve_numeric(problem, p, instant_givens(problem, None, {}), set()).state
    >>> p.index.n, degrees_of_freedom(p, [state, None, state])
    (3, [1, 1, 1])
    """
    out = [p.generic_dof if p.generic_dof is not None else generic_dof(p.k)] * len(states)
    by_size: dict[int, list[tuple[int, np.ndarray]]] = {}
    for i, state in enumerate(states):
        if state is not None:
            by_size.setdefault(len(state.values), []).append((i, state.values))
    for solved in by_size.values():
        ranks = constraint_ranks(p, np.stack([values for _, values in solved], axis=1))
        for (i, _), rank in zip(solved, ranks):
            out[i] = p.index.n - int(rank)
    return out


def _undefined(obj: Objective) -> SolveError:
    """The error of a numeric objective whose value (or a declared mistake's) is not finite
    at its instant."""
    return SolveError(f"objective '{obj.id}' is undefined at this instant (for example a "
                      "direction of motion when the speed is zero)", where=obj.where)


def _may_be_negative(problem: Problem, node) -> bool:
    """Whether a symbol's quantity may be negative: a rate, a coordinate, or a parameter
    declared ``positive: false`` (time and positive parameters may not)."""
    if isinstance(node, Prime):
        return True
    if any(c.name == node.id for c in problem.coordinates):
        return True
    return any(q.name == node.id and not q.positive for q in problem.parameters)


def _quantity_unit(problem: Problem, node) -> str:
    """SI unit of a coordinate, rate or parameter node."""
    units = {c.name: c.unit for c in problem.coordinates}
    units.update({q.name: q.unit for q in problem.parameters})
    if isinstance(node, Prime):
        return si_unit(f"({units[node.id] or '1'}) / s^{node.order}")
    return si_unit(units[node.id])


def _without_noise(values: np.ndarray, dimensions: np.ndarray) -> np.ndarray:
    """``values`` (SI, one column per state) with each value that is not a part of the
    largest of its dimension in its column (:func:`~mechgrade.tolerance.parts`) made 0: a
    rate that is zero at the instant in exact arithmetic (a turning point reached by
    integration) carries the solve's error, some 1e-12 of the motion's speeds, and neither
    its digits nor its sign mean anything. ``dimensions``: each row's dimension, numbered
    from 0 in order of first appearance.

    >>> _without_noise(np.array([[8000.0], [2.7e-9], [7.6e-4]]), np.array([0, 0, 1])).ravel()
    array([8.0e+03, 0.0e+00, 7.6e-04])
    """
    sizes = np.where(np.isfinite(values), np.abs(values), 0.0)
    order = np.argsort(dimensions, kind="stable")
    starts = np.flatnonzero(np.diff(dimensions[order], prepend=-1))
    largest = np.maximum.reduceat(sizes[order], starts, axis=0)[dimensions]
    return np.where(tolerance.parts(values, largest), values, 0.0)


def _dimensions(problem: Problem, p: KinematicsPlan) -> np.ndarray:
    """Each reported position's dimension, numbered (:func:`_without_noise`)."""
    return _per_problem(_numbered_dimensions, problem, p)


def _numbered_dimensions(problem: Problem, p: KinematicsPlan) -> np.ndarray:
    kinds: dict = {}
    return np.array([kinds.setdefault(dimension(unit or "1"), len(kinds))
                     for _, _, unit, _ in _reported(problem, p)], dtype=int)


def _reported(problem: Problem, p: KinematicsPlan) -> list[tuple[int, str, str, float]]:
    """Each position's index, spelling, author's unit and that unit's SI factor."""
    return _per_problem(_positions_reported, problem, p)


def _positions_reported(problem: Problem, p: KinematicsPlan) -> list[tuple[int, str, str, float]]:
    units = author_units(problem, p)
    return [(i, p.index.spelling(i), units[i], si_factor(units[i]) if units[i] else 1.0)
            for i in range(p.index.size)]


def _states(problem: Problem, p: KinematicsPlan, bases: Sequence[tuple[State, dict] | None]
            ) -> list[tuple[StateValue, ...]]:
    """Each of ``bases``' solved coordinates, rates, parameters and time (``()`` for none),
    in the author's units: every column's values put in those units at once."""
    out: list[tuple[StateValue, ...]] = [()] * len(bases)
    solved = [(i, base) for i, base in enumerate(bases) if base is not None]
    if not solved:
        return out
    reported = _reported(problem, p)
    raw = np.stack([state.values[:len(reported)] for _, (state, _) in solved], axis=1)
    values = _without_noise(raw, _dimensions(problem, p))
    united = np.array([bool(unit) for _, _, unit, _ in reported])[:, None]
    factors = np.array([factor for *_, factor in reported])[:, None]
    with np.errstate(all="ignore"):  # as from_si reports it
        shown = np.where(united, values / factors + 0.0, values)
    finite = np.isfinite(values)
    for j, (i, (state, givens)) in enumerate(solved):
        value, number, kept = values[:, j].tolist(), shown[:, j].tolist(), finite[:, j].tolist()
        author = raw[:, j].tolist()
        given = state.given.tolist()
        column = []
        for k, name, unit, _ in reported:
            if not kept[k] or k in state.free:
                continue
            entry = givens.get(name) if given[k] else None
            # an author's given as written, however small beside its dimension's others
            if entry is not None and entry[2] is not None and entry[1] == author[k]:
                column.append(StateValue(name, entry[2].value, entry[2].unit, True, author[k]))
            else:
                column.append(StateValue(name, number[k], unit, bool(given[k]), value[k]))
        out[i] = tuple(column)
    return out


_symbolic_answer.cache_clear = _SYMBOLIC_ANSWERS.clear  # type: ignore[attr-defined]
