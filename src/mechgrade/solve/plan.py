"""The lambdified pieces of a problem's kinematics, made once per problem (the cold, symbolic
part of solving): each level's equations, their Jacobian in the level's unknowns and the size
their residuals are judged by; the objectives, mistaken models and requirements.

A plan is kept in memory and, compiled (the functions as the source sympy printed for them),
on disk (:mod:`.cache`): a plan read back from disk is used without importing sympy; its
kinematics (:attr:`KinematicsPlan.k`) are derived again only if something asks for them.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> p = kinematics_plan(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"))
>>> [(level.name, level.linear) for level in p.levels]
[('position', True), ('velocity', True), ('acceleration', True)]
"""

from __future__ import annotations

import dataclasses
import operator
import typing
from dataclasses import dataclass, field
from functools import cached_property, lru_cache
from typing import TYPE_CHECKING, Any, Callable, Mapping

import numpy as np

from ..codec import MAPPING, decode, encode
from ..errors import AuthorWarning, Location
from ..expressions.syntax import Name, Prime
from ..spec.model import ObjectiveKind, Problem
from . import cache
from .generated import UnsafeSource, lambdified, numpy_function, same_namespace
from .index import SymbolIndex
from .rules import matrix_rank

if TYPE_CHECKING:
    from ..mechanics import Kinematics

LEVEL_NAMES = ("position", "velocity", "acceleration")


@dataclass(frozen=True)
class Level:
    """The equations of one level, ``residual(state) = 0``: constraint rows first, then one row
    per expression given of this level (``conditions``, in order).

    ``jacobian`` is in the level's unknowns (``SymbolIndex.unknowns(order)``); ``linear`` says
    the equations are linear in them (velocity and acceleration constraints always are);
    ``jacobian_uses`` are the state positions the Jacobian depends on. ``uses`` are the
    positions each row depends on.
    """

    order: int
    name: str
    residual: Callable
    jacobian: Callable
    scale: Callable
    labels: tuple[str, ...]
    wheres: tuple[Location, ...]
    conditions: tuple[str, ...]
    linear: bool
    uses: tuple[frozenset[int], ...]
    jacobian_uses: frozenset[int]

    @property
    def constraint_rows(self) -> int:
        return len(self.labels) - len(self.conditions)


@dataclass(frozen=True)
class Mutant:
    """A model mutation of a numeric objective (:mod:`mechgrade.mechanics.mutations`), ready
    for numbers: ``value`` its mistaken value (``size`` entries) and ``term`` the dropped
    term's three components (or ``None``), each called with the whole state; ``velocity``
    says the term is a velocity (else an acceleration)."""

    objective: str
    code: str
    sentence: str
    size: int
    velocity: bool
    value: Callable
    term: Callable | None


@dataclass(frozen=True, eq=False)
class KinematicsPlan:
    """A problem's kinematics, ready for numbers: its state layout, its three levels and the
    objective, mistake and requirement functions (each called with the whole state).

    ``warnings`` are the model's; ``key`` names the plan's entries in the disk cache (``None``
    when it is off); ``mutants`` are the numeric objectives' model mutations when compiled
    with the plan (``None``: made when first asked for); ``generic_dof`` the degrees of
    freedom away from any instant, when known. ``k`` (the sympy kinematics) is derived when
    first read."""

    index: SymbolIndex
    levels: tuple[Level, Level, Level]
    objectives: tuple[tuple[str, Callable], ...]
    mistakes: tuple[tuple[str, tuple[Callable, ...]], ...]
    requirements: tuple[tuple[str, str, Callable], ...]
    objective_uses: tuple[tuple[str, frozenset[int]], ...]
    points: tuple[str, ...]
    point_positions: Callable
    constraint_rank: int
    warnings: tuple[AuthorWarning, ...]
    problem: Problem
    key: str | None = None
    mutants: Mapping[str, tuple[Mutant, ...]] | None = None
    generic_dof: int | None = None

    @cached_property
    def k(self) -> Kinematics:
        """The problem's kinematics (sympy), derived now if this plan was read from disk."""
        from ..mechanics import derive

        return derive(self.problem)

    def position(self, node) -> int:
        """The state position of a coordinate, rate, parameter or time node (``theta``,
        ``theta'``, ``t``); :class:`KeyError` for any other, as ``Kinematics.quantity``."""
        index = self.index
        if isinstance(node, Name) and node.id in index.names[:len(index.config)]:
            return index.names.index(node.id)
        if isinstance(node, Prime) and node.id in index.coordinates:
            return index.position(node.id + ("'" if node.order == 1 else "''"))
        raise KeyError(node)


_BY_PROBLEM: dict = {}


def per_problem(make, *args):
    """``make(*args)``, kept per identity of ``args`` (a problem and its plan): hashing a
    problem walks all of it, and re-solves ask for the same few again and again. The entry
    holds ``args``, so an identity is not reused while it is kept."""
    key = (make, *map(id, args))
    entry = _BY_PROBLEM.get(key)
    if entry is None or not all(map(operator.is_, entry[0], args)):
        if len(_BY_PROBLEM) >= 1024:
            _BY_PROBLEM.clear()
        entry = _BY_PROBLEM[key] = (args, make(*args))
    return entry[1]


class _OnFirstCall:
    """``lambdified(symbols, expr)``, made when first called: a grader asking for a few
    objectives of a problem never pays for the others'."""

    def __init__(self, symbols, expr):
        self._args = (symbols, expr)
        self._function: Callable | None = None

    @property
    def function(self) -> Callable:
        """The lambdified function itself, made now if it was not yet."""
        if self._function is None:
            self._function = lambdified(*self._args)
        return self._function

    def __call__(self, *values):
        return self.function(*values)


def _scale(exprs):
    """Sum of the absolute values of each equation's terms: the size a residual is judged by."""
    import sympy as sp

    return sp.Matrix([sum((sp.Abs(term) for term in sp.Add.make_args(e)), sp.Integer(0))
                      for e in exprs])


def _level(index: SymbolIndex, order: int, equations, conditions) -> Level:
    import sympy as sp

    symbols = index.symbols
    unknowns = [symbols[i] for i in index.unknowns(order)]
    exprs = [e.expr for e in equations] + [c.expr for c in conditions]
    m = sp.Matrix(exprs) if exprs else sp.zeros(0, 1)
    jac = m.jacobian(unknowns) if exprs else sp.zeros(0, len(unknowns))
    linear = not (jac.free_symbols & set(unknowns))
    positions = {s: i for i, s in enumerate(symbols)}
    return Level(
        order=order, name=LEVEL_NAMES[order], residual=lambdified(symbols, m),
        jacobian=lambdified(symbols, jac),
        scale=lambdified(symbols, _scale(exprs) if exprs else sp.zeros(0, 1)),
        labels=tuple(e.label for e in equations) + tuple(f"given {c.key}" for c in conditions),
        wheres=tuple(e.where for e in equations) + tuple(c.where for c in conditions),
        conditions=tuple(c.key for c in conditions), linear=linear,
        uses=tuple(frozenset(positions[s] for s in e.free_symbols if s in positions)
                   for e in exprs),
        jacobian_uses=frozenset(positions[s] for s in jac.free_symbols if s in positions))


_BY_IDENTITY: dict[int, tuple[Problem, KinematicsPlan]] = {}
_BY_TEXT: dict[Any, KinematicsPlan] = {}
_LIMIT = 64


def kinematics_plan(problem: Problem) -> KinematicsPlan:
    """Derive and lambdify ``problem`` once (per place it was written: plans keep locations),
    or read it from the disk cache."""
    known = _BY_IDENTITY.get(id(problem))
    if known is not None and known[0] is problem:
        return known[1]
    key = cache.used_problem_key(problem)
    memory = key if key is not None else repr(problem)
    p = _BY_TEXT.get(memory)
    if p is None:
        p = _planned(problem, key)
        if len(_BY_TEXT) >= _LIMIT:
            _BY_TEXT.clear()
        _BY_TEXT[memory] = p
    if len(_BY_IDENTITY) >= 4 * _LIMIT:
        _BY_IDENTITY.clear()
    _BY_IDENTITY[id(problem)] = (problem, p)
    return p


def _cache_clear() -> None:
    _BY_IDENTITY.clear()
    _BY_TEXT.clear()


kinematics_plan.cache_clear = _cache_clear  # type: ignore[attr-defined]  # as functools' caches


def _planned(problem: Problem, key: str | None) -> KinematicsPlan:
    """The plan read from the disk cache under ``key``, else derived (and, with a ``key``,
    compiled and stored)."""
    if key is None:
        return _derived(problem)
    entry = cache.load(key)
    if entry is not None:
        try:
            return _from_entry(problem, key, entry)
        except (KeyError, TypeError, ValueError, SyntaxError, IndexError, AttributeError):
            pass  # not an entry this code wrote: derive and write it again
    p = _derived(problem)
    try:
        entry = _entry(problem, p)
        compiled = _from_entry(problem, key, entry)  # as a later run will read it back
    except UnsafeSource:
        return p  # something the printer wrote that the reader would refuse: not cached
    cache.store(key, entry)
    compiled.__dict__["k"] = p.k  # derived already
    return compiled


def _derived(problem: Problem) -> KinematicsPlan:
    import sympy as sp

    from ..mechanics import derive

    k = derive(problem)
    index = SymbolIndex.of(k)
    symbols = index.symbols
    by_level: dict[int, list] = {0: [], 1: [], 2: []}
    for c in k.conditions:
        by_level[c.level].append(c)
    position, velocity, acceleration = (
        _level(index, order, equations, by_level[order])
        for order, equations in enumerate((k.position, k.velocity, k.acceleration)))
    levels = (position, velocity, acceleration)
    numeric = {o.id for o in problem.objectives if o.kind != ObjectiveKind.SYMBOLIC}
    positions = {s: i for i, s in enumerate(symbols)}
    points = sp.Matrix.hstack(*(r for _, r in k.points)) if k.points else sp.zeros(3, 0)
    p = KinematicsPlan(
        index=index, levels=levels,
        objectives=tuple((oid, _OnFirstCall(symbols, expr)) for oid, expr in k.objectives
                         if oid in numeric),
        mistakes=tuple((oid, tuple(_OnFirstCall(symbols, e) for e in exprs))
                       for oid, exprs in k.mistakes if oid in numeric),
        requirements=tuple((oid, reason, lambdified(symbols, expr))
                           for oid, reason, expr in k.requirements),
        objective_uses=tuple((oid, frozenset(positions[s] for s in sp.sympify(expr).free_symbols
                                             if s in positions))
                             for oid, expr in k.objectives),
        points=tuple(name for name, _ in k.points), point_positions=lambdified(symbols, points),
        constraint_rank=_generic_rank(index, k), warnings=tuple(k.warnings), problem=problem)
    p.__dict__["k"] = k
    return p


@lru_cache(maxsize=512)
def lambdified_mutants(problem: Problem, p: KinematicsPlan, objective: str) -> tuple[Mutant, ...]:
    """The model mutations of a numeric objective (:mod:`mechgrade.mechanics.mutations`),
    lambdified in ``p``'s state layout (kept per plan, as a plan is per problem and place)."""
    import sympy as sp

    from ..mechanics.mutations import mutations
    from ..spec.mistake_codes import VELOCITY_CODES

    symbols = p.index.symbols
    return tuple(Mutant(
        m.objective, m.code, m.sentence,
        len(m.value) if isinstance(m.value, sp.MatrixBase) else 1, m.code in VELOCITY_CODES,
        lambdified(symbols, m.value),
        None if m.term is None else lambdified(symbols, m.term))
        for m in mutations(problem, objective))


def _generic_rank(index: SymbolIndex, k: Kinematics) -> int:
    """Rank of the position constraints' Jacobian in the coordinates at a generic
    configuration: a configuration where it is lower is singular."""
    import sympy as sp

    if not k.position:
        return 0
    jac = sp.Matrix([e.expr for e in k.position]).jacobian(list(k.q))
    rng = np.random.default_rng(3)
    point = {s: float(rng.uniform(0.4, 1.6)) for s in index.symbols}
    with np.errstate(all="ignore"):
        value = np.array(jac.xreplace(point).evalf(), dtype=complex)
    if not np.isfinite(value).all():
        return len(k.q)
    return matrix_rank(value)


@lru_cache(maxsize=64)
def generic_dof(k: Kinematics) -> int:
    """Coordinates minus the rank of the velocity constraints in the rates, away from any
    instant. Kept per model: sympy's rank simplifies its pivots (a second or more for a
    closed loop), and every variant of a problem whose instant is not solved asks again."""
    import sympy as sp

    if not k.velocity:
        return len(k.coordinates)
    return len(k.coordinates) - sp.Matrix([e.expr for e in k.velocity]).jacobian(k.qd).rank()


# ---------------------------------------------------------------------------- compiled form


def source(function: Callable) -> str:
    """The source sympy printed for a lambdified ``function`` (or :class:`_OnFirstCall`),
    when the numpy names it uses are those :func:`.generated.numpy_function` gives."""
    import inspect

    if isinstance(function, _OnFirstCall):
        function = function.function
    if not same_namespace(function):
        raise UnsafeSource("a lambdified function uses names numpy does not give")
    return inspect.getsource(function)


_AS_SOURCE = {Callable: str, Callable | None: str | None}
"""A function field's type as the disk cache keeps it: its source (or ``None``)."""


def _kept(cls: type, left_out: str) -> Any:
    """``cls`` as the disk cache keeps it: a frozen dataclass of its fields in its order but
    ``left_out`` (known from elsewhere), each function as its source (:func:`source`; named in
    the class's ``functions``), so that the entry is the class's own fields.

    >>> [f.name for f in dataclasses.fields(_MutantEntry)], sorted(_MutantEntry.functions)
    (['code', 'sentence', 'size', 'velocity', 'value', 'term'], ['term', 'value'])
    """
    hints = typing.get_type_hints(cls)
    names = [f.name for f in dataclasses.fields(cls) if f.name != left_out]
    functions = frozenset(n for n in names if hints[n] in _AS_SOURCE)
    kept = dataclasses.make_dataclass(
        f"_{cls.__name__}Entry", [(n, _AS_SOURCE.get(hints[n], hints[n])) for n in names],
        frozen=True, namespace={"functions": functions})
    kept.__module__ = __name__
    kept.__doc__ = f"A :class:`{cls.__name__}` as the disk cache keeps it (see :func:`_kept`)."
    return kept


_LevelEntry = _kept(Level, "name")  # the name is its order's
_MutantEntry = _kept(Mutant, "objective")  # the objective is the key it is kept under


def _to_kept(kept: Any, value: Any) -> Any:
    """``value`` (a :class:`Level` or :class:`Mutant`) as its ``kept`` class."""
    return kept(**{f.name: _source_or_none(getattr(value, f.name)) if f.name in kept.functions
                   else getattr(value, f.name) for f in dataclasses.fields(kept)})


def _source_or_none(function: Callable | None) -> str | None:
    return None if function is None else source(function)


def _from_kept(entry: Any, **known: Any) -> dict[str, Any]:
    """The fields of a kept ``entry``, each function compiled (:func:`_compiled`), and
    ``known``'s."""
    return {**{f.name: _compiled_or_none(getattr(entry, f.name)) if f.name in entry.functions
               else getattr(entry, f.name) for f in dataclasses.fields(entry)}, **known}


def _compiled_or_none(text: str | None) -> Callable | None:
    return None if text is None else _compiled(text)


@dataclass(frozen=True)
class _Entry:
    """A :class:`KinematicsPlan` (and its model mutations) as the disk cache keeps it, read
    and written by :mod:`mechgrade.codec`: a field of another type refuses the whole entry."""

    index: tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...]]
    levels: tuple[_LevelEntry, ...]  # type: ignore[valid-type]  # a class made from Level
    objectives: tuple[tuple[str, str], ...]
    mistakes: tuple[tuple[str, tuple[str, ...]], ...]
    requirements: tuple[tuple[str, str, str], ...]
    objective_uses: tuple[tuple[str, frozenset[int]], ...]
    points: tuple[str, ...]
    point_positions: str
    constraint_rank: int
    warnings: tuple[AuthorWarning, ...]
    mutants: tuple[tuple[str, tuple[_MutantEntry, ...]], ...] = field(  # type: ignore[valid-type]
        metadata=MAPPING)  # a class made from Mutant
    generic_dof: int


def _entry(problem: Problem, p: KinematicsPlan) -> Any:
    """The plan (and its model mutations) as plain JSON with the functions' source."""
    index = p.index
    return encode(_Entry(
        index=(index.names, index.coordinates, index.parameters),
        levels=tuple(_to_kept(_LevelEntry, level) for level in p.levels),
        objectives=tuple((oid, source(f)) for oid, f in p.objectives),
        mistakes=tuple((oid, tuple(source(f) for f in fs)) for oid, fs in p.mistakes),
        requirements=tuple((oid, reason, source(f)) for oid, reason, f in p.requirements),
        objective_uses=p.objective_uses, points=p.points,
        point_positions=source(p.point_positions), constraint_rank=p.constraint_rank,
        warnings=p.warnings,
        mutants=tuple((o.id, tuple(_to_kept(_MutantEntry, m)
                                   for m in lambdified_mutants(problem, p, o.id)))
            for o in problem.objectives if o.kind != ObjectiveKind.SYMBOLIC),
        generic_dof=generic_dof(p.k)))


def _from_entry(problem: Problem, key: str, data: Any) -> KinematicsPlan:
    """The plan an :func:`_entry` describes; raises (``ValueError``, ``SyntaxError``...) on
    anything else."""
    entry = decode(_Entry, data)
    names, coordinates, parameters = entry.index
    holder: list[KinematicsPlan] = []
    index = SymbolIndex(names, coordinates, parameters, source=lambda: holder[0].k)
    if index.size != len(coordinates) * 3 + len(parameters) + 1:
        raise ValueError("a state layout of another size")
    levels = tuple(Level(**_from_kept(level, name=LEVEL_NAMES[level.order]))
                   for level in entry.levels)
    if [level.order for level in levels] != [0, 1, 2]:
        raise ValueError("expected the three levels")
    p = KinematicsPlan(
        index=index, levels=levels,  # type: ignore[arg-type]  # three, checked above
        objectives=tuple((oid, _compiled(text)) for oid, text in entry.objectives),
        mistakes=tuple((oid, tuple(_compiled(t) for t in texts))
                       for oid, texts in entry.mistakes),
        requirements=tuple((oid, reason, _compiled(text))
                           for oid, reason, text in entry.requirements),
        objective_uses=entry.objective_uses, points=entry.points,
        point_positions=_compiled(entry.point_positions),
        constraint_rank=entry.constraint_rank, warnings=entry.warnings,
        problem=problem, key=key,
        mutants={oid: tuple(Mutant(**_from_kept(m, objective=oid, size=_size(m.size)))
                            for m in rows) for oid, rows in entry.mutants},
        generic_dof=entry.generic_dof)
    holder.append(p)
    return p


def _size(value) -> int:
    """A mutation's number of values: a scalar's or a vector's."""
    if value not in (1, 3):
        raise ValueError(f"expected 1 or 3 values, found {value!r:.20}")
    return int(value)


def _compiled(text: str) -> Callable:
    """A function of the entry, checked and compiled now: an entry that is not what this code
    wrote is refused whole, never found out in the middle of a solve."""
    return numpy_function(text)
