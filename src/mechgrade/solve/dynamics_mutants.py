"""The values typical mistakes of kinetics give, for the grader to name them.

Four sources, all applied to the model and never to the answer: the mistaken models of
:mod:`mechgrade.mechanics.dynamics_mutations` (the weight left out, the inertia about the mass
centre used at a pivot, friction turned round...), each solved again like the problem; the
mistaken readings of objectives (a reaction read as a weight), read in the right model;
mistaken givens (an angle in degrees used as radians, a rate's sign flipped, a length in the
wrong unit), for which the problem is solved again with the given changed; and the kinematic
mutations of :mod:`mechgrade.mechanics.mutations` (another point's velocity, ω × r left out,
another frame's unit vectors), read at the solved instant.

A mistaken model that changes only numbers (the mass written for the weight, the weight left
out, e read as 1) is the problem's unchanged copy solved with its parameters' mistaken values
(:mod:`mechgrade.mechanics.revalue`); one that changes only the instant of the motion (a value
read at its start), or the rates just before an impact (a sign flipped, sine and cosine
exchanged: inputs of its balances), is read in the unchanged copy's balances, as the readings
are in the problem's own: none is derived and lambdified again. Mistaken models that differ among
themselves only in numbers (e on either component of an impact, a weight at one point or
another) are derived once, together, each number a parameter of its own.

Solving the mistaken models costs from tens of milliseconds to seconds (an integration to an
event, an inverse design), and most answers are right: a solution's generated mistakes are
worked out, for all its objectives at once, the first time one of them is looked at
(:class:`LazyMistakes`), and kept for the same problem and givens. Each step is written for
a class of variants (each mistaken model solved for all of them at once,
:class:`ClassMistakes`); a single solve is a class of one whose mistaken models its own
solver solves (:func:`with_generated_mistakes`).

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.solve import solve
>>> result = solve(load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
...               ).result("alpha")
>>> [(m.code, round(m.value, 2)) for m in result.generated_mistakes][:3]
[('mass_for_weight', -0.8), ('weight_for_mass', -0.8), ('central_inertia_at_pivot', -31.53)]
"""

from __future__ import annotations

import operator
import warnings
from collections.abc import Sequence
from dataclasses import replace
from functools import lru_cache
from typing import Callable, Mapping

import numpy as np
import sympy as sp

from ..errors import MechgradeError
from ..expressions.syntax import Name
from ..mechanics.dynamics_mutations import (DynamicsMutation, dynamics_mutations,
                                            unchanged_copy)
from ..mechanics.dynamics import readable_in
from ..mechanics.revalue import common_models, revaluation
from ..spec.model import Objective, ObjectiveKind, Problem
from .dynamics import kinetics_plan, read_in, share_kinetics, solve_dynamics
from .instant import _instants, instant_givens
from .mutants import (kept_at, model_mistake_at, model_mistake_table, plausible_slips,
                      slips_of, symbolic_kept)
from .result import GeneratedMistake, ObjectiveResult, Solution, StateValue

# a mistaken model is no mistake where it cannot be solved (no motion, an event that never
# happens, a division by zero): sympy and numpy raise more than MechgradeError there
_UNSOLVABLE = (MechgradeError, ArithmeticError, ValueError, TypeError, KeyError)


Solver = Callable[..., Solution]
"""How a problem is solved: ``solver(problem, givens=..., objectives=...)``
(:func:`~.dynamics.solve_dynamics`, or :func:`~.carried.held_dynamics`)."""

Together = Callable[[Problem, list[dict], set[str]], list]
"""How a problem is solved for many variants at once: ``together(problem, givens,
objectives)``, each variant's solution or error (:func:`~.batch.answers_together`, or a
:data:`Solver` one variant after the other: :func:`_one_by_one`)."""


def with_generated_mistakes(problem: Problem, solution: Solution,
                            givens: Mapping[str, float | None] | None = None,
                            solver: Solver = solve_dynamics) -> Solution:
    """``solution`` (of a problem with bodies and loads, solved by ``solver``) with the
    generated mistakes of its objectives attached (worked out when first looked at: values
    for the numeric ones, expressions for the symbolic ones; each mistaken model solved by
    ``solver`` too), and the whole-answer slips its model makes plausible: a class of one
    (:class:`ClassMistakes`), kept for the same problem and givens."""
    key = tuple(sorted((givens or {}).items()))
    return _attached(solution, plausible_slips(problem), _Pending(lambda: [_generated(
        problem, key, solution.results, solution.state, solver)]), 0)


class ClassMistakes:
    """The generated mistakes of a class of variants solved together (``givens``: each
    column's overrides; ``together`` solves each mistaken model for all of them at once),
    worked out for every column when one is first looked at: a result made for a column
    (:meth:`of`) carries them from the start, :meth:`attached` puts them in the others.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
    >>> mistakes = ClassMistakes(problem, [{}, {}], _one_by_one(solve_dynamics))
    >>> error = MechgradeError("not solved")
    >>> mistakes.attached([error])[0] is error, type(mistakes.of(0, "alpha")).__name__
    (True, 'LazyMistakes')
    """

    def __init__(self, problem: Problem, givens: Sequence[Mapping[str, float | None] | None],
                 together: Together):
        self.problem, self.together = problem, together
        self.givens = [dict(g or {}) for g in givens]
        self.plausible = plausible_slips(problem)
        self.pending = _Pending(self._work)
        self.outcomes: list = []  # each column's solution or error, once solved

    def of(self, column: int, objective_id: str) -> LazyMistakes:
        """The generated mistakes of one objective of one column."""
        return LazyMistakes(self.pending, column, objective_id)

    def attached(self, outcomes: Sequence) -> list:
        """``outcomes`` (each column's solution or error) with every result of a solution
        carrying its generated mistakes and the plausible whole-answer slips (a result made
        with them, :meth:`of`, is kept as it is)."""
        self.outcomes = list(outcomes)
        return [_attached(solution, self.plausible, self.pending, k)
                if isinstance(solution, Solution) else solution
                for k, solution in enumerate(self.outcomes)]

    def _work(self) -> list[dict]:  # (a column without a solution has none)
        solved = [k for k, s in enumerate(self.outcomes) if isinstance(s, Solution)]
        found = _generated_class(self.problem, [self.givens[k] for k in solved],
                                 [self.outcomes[k].results for k in solved],
                                 [self.outcomes[k].state for k in solved], self.together)
        out: list[dict] = [{} for _ in self.outcomes]
        for k, mine in zip(solved, found):
            out[k] = mine
        return out


def _attached(solution: Solution, plausible: frozenset[str], pending: _Pending, k: int
              ) -> Solution:
    """``solution`` (column ``k`` of ``pending``) with its generated mistakes still to work
    out and the plausible whole-answer slips attached to every result that has not got them."""
    # each result and solution as replace() would give it, at a fraction of the cost (a
    # class's results are made by the thousand)
    results = tuple(r if isinstance(r.generated_mistakes, LazyMistakes)
                    and r.generated_mistakes.pending is pending and r.plausible is plausible
                    else ObjectiveResult(**{**vars(r), "plausible": plausible,
                                            "generated_mistakes": LazyMistakes(pending, k, r.id)})
                    for r in solution.results)
    if all(map(operator.is_, results, solution.results)):
        return solution
    return Solution(**{**vars(solution), "results": results})


class _Pending:
    """The generated mistakes of a class of variants (one solve's: a class of one), each
    variant's objective id -> its mistakes, worked out once when first asked for."""

    def __init__(self, work: Callable[[], list[dict]]):
        self.work: Callable[[], list[dict]] | None = work
        self.found: list[dict] | None = None

    def get(self, k: int) -> dict:
        if self.found is None:
            assert self.work is not None
            self.found, self.work = self.work(), None  # what it held is no longer needed
        return self.found[k]


@lru_cache(maxsize=256)
def _generated(problem: Problem, givens: tuple, results: tuple,
               state: tuple[StateValue, ...], solver: Solver) -> dict:
    """:func:`_generated_class` of one solve (``givens`` its overrides as sorted items), each
    mistaken model solved by ``solver`` (a mistaken model that changes only numbers solved as
    the unchanged copy with them only by :func:`~.dynamics.solve_dynamics`)."""
    return _generated_class(problem, [dict(givens)], [results], [state], _one_by_one(solver),
                            revalue=solver is solve_dynamics)[0]


def _one_by_one(solver: Solver) -> Together:
    """``solver`` as a :data:`Together`: each variant solved alone, its error in its place.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> pendulum = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
    >>> [round(s.result("alpha").value, 2) for s in _one_by_one(solve_dynamics)(
    ...     pendulum, [{}, {"theta": 0.0}], {"alpha"})]
    [-7.88, 0.0]
    >>> type(_one_by_one(solve_dynamics)(pendulum, [{}], {"nothing"})[0]).__name__
    'SolveError'
    """
    def together(problem: Problem, givens: list[dict], objectives: set[str]) -> list:
        outcomes: list = []
        for g in givens:
            try:
                outcomes.append(solver(problem, givens=g, objectives=objectives))
            except _UNSOLVABLE as err:
                outcomes.append(err)
        return outcomes
    return together


def _generated_class(problem: Problem, givens: list[dict], results: list[tuple],
                     states: list[tuple[StateValue, ...]], together: Together,
                     revalue: bool = True) -> list[dict]:
    """Each variant's objective id -> its generated mistakes (those equal to the answer, or
    to an earlier one, or a zero, dropped), each source of mistakes solved for all of them at
    once by ``together``; ``states`` are the solved instants the kinematic readings are read
    at; without ``revalue``, a mistaken model that changes only numbers is solved as itself
    (:func:`_revalued`)."""
    numeric = [{r.id: r for r in rs if r.value is not None} for rs in results]
    asked = [set(n) for n in numeric]
    mutations = dynamics_mutations(problem)
    # a mistaken model's numerical troubles (an inverse design that does not converge) are
    # nobody's to fix
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        models = _model_mistakes(together, problem, mutations, givens, asked, revalue)
        slips = _given_mistakes(together, problem, givens, asked)
        readings = _kinematic_mistakes(problem, states, asked)
        symbolic = _symbolic_mistakes(together, mutations, givens, results)
    out = []
    for k, rs in enumerate(results):
        found = [models[k], slips[k], readings[k]] if numeric[k] else []
        mine: dict[str, Sequence[GeneratedMistake]] = {r.id: () for r in rs}
        mine.update({oid: kept_at(r.value, [m for source in found for m in source.get(oid, ())])
                     for oid, r in numeric[k].items()})
        mine.update(symbolic[k])
        out.append(mine)
    return out


def _texts(results) -> tuple[tuple[str, str | None, tuple[str, ...]], ...]:
    return tuple((r.id, r.expr, r.symbols) for r in results)


@lru_cache(maxsize=1024)
def _symbolic_kept(mutations: tuple[DynamicsMutation, ...], results: tuple,
                   answers: tuple) -> dict[str, tuple[GeneratedMistake, ...]]:
    """The symbolic mistakes kept of each mistaken model's ``answers`` (``(mutation index,
    (id, expr, symbols) of each answer)``) of the answers ``results`` (two families of one
    expression both, for the grader to name both): worked out once for all the variants whose
    answers are the same."""
    # (family, expression): the answer's family is None
    kept = {oid: [(None, _expression(expr, symbols))] for oid, expr, symbols in results}
    out: dict[str, list[GeneratedMistake]] = {oid: [] for oid, _, _ in results}
    for i, solved in answers:
        m = mutations[i]
        for oid, text, symbols in solved:
            expr = _expression(text, symbols) if text else None
            # a zero is what many mistakes give (the weight left out of a fall): no name
            if expr is None or not symbolic_kept(kept[oid], m.code, expr):
                continue
            out[oid].append(GeneratedMistake(m.code, m.sentence.replace(" = {term}", ""),
                                             None, text, step=m.step))
    return {oid: tuple(found) for oid, found in out.items()}


def _symbolic_mistakes(together: Together, mutations: tuple[DynamicsMutation, ...],
                       givens: list[dict], results: list[tuple]) -> list[dict]:
    """Each variant's symbolic mistakes: each mistaken model's symbolic answers, in the
    objectives' own symbols, solved for all the variants at once (those equivalent to the
    answer or to an earlier one dropped)."""
    symbolic = [[r for r in rs if r.expr is not None] for rs in results]
    ids = {r.id for rs in symbolic for r in rs}
    answers: list[list] = [[] for _ in givens]
    for i, m in enumerate(mutations):
        mistaken = m.problem
        if mistaken is None or not ids & {o.id for o in mistaken.objectives}:
            continue
        asked = ids & {o.id for o in mistaken.objectives}
        solved = _answers(together, mistaken, givens, asked)
        for k, solution in enumerate(solved):
            mine = {r.id for r in symbolic[k]}
            if solution is not None and mine & {o.id for o in mistaken.objectives}:
                answers[k].append((i, _texts(r for r in solution.results if r.id in mine)))
    return [_symbolic_kept(mutations, _texts(rs), tuple(found)) if rs else {}
            for rs, found in zip(symbolic, answers)]


@lru_cache(maxsize=4096)
def _expression(text: str, symbols: tuple[str, ...]):
    """The solver's own answer text as a sympy expression (never a student's)."""
    return sp.sympify(text, locals={name: sp.Symbol(name) for name in symbols})


class LazyMistakes(Sequence):
    """One objective's generated mistakes (a sequence of
    :class:`~mechgrade.solve.result.GeneratedMistake`), worked out on first use."""

    __slots__ = ("_id", "_k", "pending")

    def __init__(self, pending: _Pending, k: int, objective_id: str):
        self.pending, self._k, self._id = pending, k, objective_id

    def _items(self) -> tuple:
        return self.pending.get(self._k)[self._id]

    def __getitem__(self, index):
        return self._items()[index]

    def __len__(self) -> int:
        return len(self._items())

    def __iter__(self):
        return iter(self._items())

    def __eq__(self, other) -> bool:
        return tuple(self) == tuple(other) if isinstance(other, Sequence) else NotImplemented

    def __hash__(self) -> int:
        return hash(self._items())

    def __repr__(self) -> str:
        return repr(self._items())

    def __reduce__(self):
        # sent to another process (a grading worker) as the mistakes themselves: not the
        # pending work, which for a class holds every variant's
        return tuple, (tuple(self._items()),)


def _revalued(problem: Problem, mistaken: Problem, givens: Sequence[Mapping]
              ) -> tuple[Problem, list[dict]] | None:
    """A mistaken model that changes only numbers (:mod:`~mechgrade.mechanics.revalue`) as
    the unchanged copy of ``problem`` (:func:`_shared_copy`), and each of
    ``givens`` with the parameters' mistaken values; ``None`` for any other model, or where
    a mistaken value is not one its parameter may take (a positive one made negative)."""
    base = _shared_copy(problem)
    changes = revaluation(base, mistaken)
    if changes is None:
        common = _common_model(problem, mistaken)
        if common is None:
            return None
        base, changes = common
    positive = {q.name for q in problem.parameters if q.positive}
    out = []
    for overrides in givens:
        given_map = instant_givens(problem, overrides, {})
        at = {}
        for name, value in changes:
            symbols = {str(x): x for x in value.free_symbols}
            if any(given_map.get(x, (None, None))[1] is None for x in symbols):
                return None
            si = float(value.subs({x: given_map[n][1] for n, x in symbols.items()}))
            # zero: a load left out (the weight) of a positive parameter (g)
            if not np.isfinite(si) or (name in positive and si < 0):
                return None
            at[name] = si
        out.append({**overrides, **at})
    return base, out


def _common_model(problem: Problem, mistaken: Problem
                  ) -> tuple[Problem, tuple[tuple[str, sp.Expr], ...]] | None:
    """The model ``mistaken`` shares with the other mistaken copies of ``problem`` that
    differ from it only in numbers (:func:`~mechgrade.mechanics.revalue.common_models`; those
    that are the unchanged copy with other numbers, or read in its balances, left out), and
    its values there."""
    base = _shared_copy(problem)
    copies = tuple(m.problem for m in dynamics_mutations(problem)
                   if m.problem is not None and revaluation(base, m.problem) is None
                   and not readable_in(m.problem, base))
    if mistaken not in copies:
        return None
    return common_models(problem, copies)[copies.index(mistaken)]


@lru_cache(maxsize=64)
def _shared_copy(problem: Problem) -> Problem:
    """The unchanged mistaken copy of ``problem``: solved with ``problem``'s own derivation
    (:func:`~.dynamics.share_kinetics`), a static friction's bound left out."""
    base = unchanged_copy(problem)
    share_kinetics(base, problem)
    return base


@lru_cache(maxsize=256)
def _read_in_copy(problem: Problem, mistaken: Problem) -> Problem:
    """``mistaken``, solved with the balances of ``problem``'s unchanged copy
    (:func:`_shared_copy`) where it differs from it only in its objectives, its event (a
    value read at another instant of the motion) or its rates before an impact
    (:func:`~.dynamics.read_in`)."""
    try:
        read_in(mistaken, _shared_copy(problem))
    except _UNSOLVABLE:
        pass  # one that cannot be lambdified (a zoo) is derived in full, and fails, when solved
    return mistaken


@lru_cache(maxsize=256)
def _reading(problem: Problem, mutations, numeric: frozenset[str]) -> Problem | None:
    """The right model asked for each mistaken reading of the objectives in ``numeric`` and
    each mutation's named term (``None``: nothing to read); one object for the same
    arguments, solved with the problem's own balances."""
    objectives = [replace(problem.objective(oid), id=f"{oid}~{i}", find=find, expect=None,
                          mistakes=())
                  for i, m in enumerate(mutations) for oid, find in m.readings if oid in numeric]
    objectives += [Objective(f"~{i}", "", m.term, ObjectiveKind.SCALAR, m.term_unit)
                   for i, m in enumerate(mutations) if m.term is not None]
    if not objectives:
        return None
    reading = replace(problem, objectives=tuple(objectives), warnings=())
    try:
        read_in(reading, problem)  # the right model: its balances are the problem's
    except _UNSOLVABLE:
        pass  # one that cannot be lambdified (a zoo) is derived in full, and fails, when solved
    return reading


def _readings(results) -> tuple[dict[int, dict], dict[int, str]]:
    """The readings and terms (see :func:`_read`) in the results of :func:`_reading`'s
    problem. A term is shown to four figures of its value to twelve: the same text for values
    that differ in their last digits (the motion integrated alone or with others); a term
    that is zero there is left out of the sentence (its `` = {term}`` goes).

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> _readings([ObjectiveResult("~0", "scalar", "J", 0.0), ObjectiveResult("~1", "scalar",
    ...                                                                        "J", 2.5)])
    ({}, {1: '2.5 J'})"""
    readings: dict[int, dict] = {}
    terms: dict[int, str] = {}
    for result in results:
        oid, i = result.id.rsplit("~", 1)
        if oid:
            readings.setdefault(int(i), {})[oid] = result.value
            continue
        term = result.value
        assert term is not None and not isinstance(term, tuple)  # a term is a scalar objective
        # a term zero at this instant is not named by its value ("½ I_G ω² = 0 J")
        if np.isfinite(term) and float(f"{term:.12g}") != 0:
            unit = "" if result.unit in ("", "1") else f" {result.unit}"
            terms[int(i)] = f"{float(f'{term:.12g}') + 0.0:.4g}{unit}"
    return readings, terms


def _slips(problem: Problem, givens):
    """``(code, sentence, step, the givens misread)`` for each typical misreading of the
    givens (:func:`~mechgrade.solve.mutants.slips_of`), ``step`` the section of the worked
    solution it is anchored to (its parameters or coordinates)."""
    given_map = instant_givens(problem, givens, {})
    parameters = {q.name for q in problem.parameters}
    for code, changes, sentence in slips_of(given_map, parameters):
        node = given_map[changes[0][0]][0]
        step = "Parameters" if isinstance(node, Name) and node.id in parameters \
            else "Coordinates"
        changed = dict(givens or {})
        changed.update(dict(changes))
        yield code, sentence, step, changed


@lru_cache(maxsize=256)
def _derivable(problem: Problem) -> bool:
    """Whether a (mistaken) model's kinetics can be derived: one that cannot is solved for no
    variant, and is derived only once to find that out."""
    try:
        kinetics_plan(problem)
    except _UNSOLVABLE:
        return False
    return True


def _answers(together: Together, problem: Problem, givens: list[dict],
             objectives: set[str]) -> list:
    """Each variant's solution of ``problem`` (or ``None`` where it has none), solved by
    ``together``, else one by one (:func:`~.dynamics.solve_dynamics`) where that fails."""
    if not _derivable(problem):
        return [None] * len(givens)
    try:
        outcomes = together(problem, givens, objectives)
    except _UNSOLVABLE:
        outcomes = _one_by_one(solve_dynamics)(problem, givens, objectives)
    return [o if isinstance(o, Solution) else None for o in outcomes]


def _model_mistakes(together: Together, problem: Problem,
                    mutations: tuple[DynamicsMutation, ...], givens: list[dict],
                    numeric: list[set[str]], revalue: bool) -> list[dict]:
    """Each variant's mistakes of the mistaken models (each solved again for all the variants
    at once; with ``revalue``, one that changes only numbers as the unchanged copy:
    :func:`_revalued`) and of the mistaken readings (read in the right model for all of them
    at once), of its numeric objectives ``numeric``."""
    union = set().union(*numeric)
    out: list[dict[str, list[GeneratedMistake]]] = [{} for _ in givens]
    if not union:
        return out  # nothing to read: not even the terms named in the sentences
    readings, terms = _read(together, problem, mutations, givens, union)
    for i, m in enumerate(mutations):
        solved = None
        if m.problem is not None:
            revalued = _revalued(problem, m.problem, givens) if revalue else None
            # read in the unchanged copy's balances even when nothing numeric is asked of it:
            # its symbolic answers are then read there too, whichever comes first
            mistaken, asked = revalued or (_read_in_copy(problem, m.problem), givens)
            ids = union & {o.id for o in m.problem.objectives}
            if not ids:
                continue
            solved = _answers(together, mistaken, asked, ids)
        for k in range(len(givens)):
            sentence = m.sentence.replace("{term}", terms[k][i]) if i in terms[k] else \
                m.sentence.replace(" = {term}", "")
            if solved is not None:
                solution = solved[k]
                if solution is None:
                    continue
                values = {r.id: r.value for r in solution.results}
            else:
                values = readings[k].get(i, {})
            for oid, value in values.items():
                if oid in numeric[k] and value is not None and np.all(np.isfinite(value)):
                    out[k].setdefault(oid, []).append(GeneratedMistake(
                        m.code, sentence, value, step=m.step))
    return out


def _read(together: Together, problem: Problem, mutations, givens: list[dict],
          numeric: set[str]) -> tuple[list[dict[int, dict]], list[dict[int, str]]]:
    """Each variant's mistaken readings of the objectives in ``numeric`` (mutation index ->
    objective id -> value) and each mutation's named term as text with its unit (mutation
    index -> text), read together in the right model: one more solve of the problem."""
    reading = _reading(problem, mutations, frozenset(numeric))
    if reading is None:
        return [{} for _ in givens], [{} for _ in givens]
    solved = [_readings(s.results if s is not None else ())
              for s in _answers(together, reading, givens, {o.id for o in reading.objectives})]
    return [r for r, _ in solved], [t for _, t in solved]


def _given_mistakes(together: Together, problem: Problem, givens: list[dict],
                    numeric: list[set[str]]) -> list[dict]:
    """Each variant's numeric objectives ``numeric`` solved again with each given mistaken
    in one way (:func:`_slips`), every variant's misread givens solved together."""
    slips = [(k, *slip) for k, overrides in enumerate(givens) if numeric[k]
             for slip in _slips(problem, overrides)]  # (variant, code, sentence, step, givens)
    out: list[dict[str, list[GeneratedMistake]]] = [{} for _ in givens]
    if not slips:
        return out
    solved = _answers(together, problem, [s[4] for s in slips], set().union(*numeric))
    for (k, code, sentence, step, _), solution in zip(slips, solved):
        for result in solution.results if solution is not None else ():
            if result.id in numeric[k] and result.value is not None \
                    and np.all(np.isfinite(result.value)):
                out[k].setdefault(result.id, []).append(GeneratedMistake(
                    code, sentence, result.value, step=step))
    return out


def _kinematic_mistakes(problem: Problem, states: list[tuple[StateValue, ...]],
                        numeric: list[set[str]]) -> list[dict]:
    """Each variant's kinematic mistakes (:func:`mechgrade.solve.mutants.model_mistake_table`:
    another point's velocity, ω × r left out, another frame's unit vectors...) of its numeric
    objectives asked at the problem's own instant, read at its solved state (the balances
    right, the reading of the motion they give mistaken): all the states at once."""
    out: list[dict[str, list[GeneratedMistake]]] = [{} for _ in states]
    own = {o.id for overrides, group in _instants(problem) if not overrides for o in group}
    wanted = own & set().union(*numeric)
    solved = [k for k, state in enumerate(states) if state and own & numeric[k]]
    if not wanted or not solved:
        return out
    p = kinetics_plan(problem).kp
    X = np.full((p.index.size, len(solved)), np.nan)
    for j, k in enumerate(solved):
        for value in states[k]:
            if value.name in p.index.names:
                X[p.index.position(value.name), j] = value.si
    try:
        table = model_mistake_table(problem, p, X, wanted)
    except _UNSOLVABLE:
        return out
    for j, k in enumerate(solved):
        for row in table:
            if row[2][j] and row[0].objective in numeric[k]:
                out[k].setdefault(row[0].objective, []).append(model_mistake_at(row, j))
    return out
