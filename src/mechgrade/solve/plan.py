"""The lambdified pieces of a problem's kinematics, made once per problem (the cold, symbolic
part of solving): each level's equations, their Jacobian in the level's unknowns and the size
their residuals are judged by; the objectives, mistaken models and requirements.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> p = plan(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"))
>>> [(level.name, level.linear) for level in p.levels]
[('position', True), ('velocity', True), ('acceleration', True)]
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Callable

import numpy as np
import sympy as sp

from ..errors import Location
from ..mechanics import Kinematics, derive
from ..mechanics.kinematics import locations
from ..spec.model import ObjectiveKind, Problem
from .index import SymbolIndex

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
class Plan:
    """A problem's kinematics, ready for numbers: its state layout, its three levels and the
    objective, mistake and requirement functions (each called with the whole state)."""

    k: Kinematics
    index: SymbolIndex
    levels: tuple[Level, Level, Level]
    objectives: tuple[tuple[str, Callable], ...]
    mistakes: tuple[tuple[str, tuple[Callable, ...]], ...]
    requirements: tuple[tuple[str, str, Callable], ...]
    objective_uses: tuple[tuple[str, frozenset[int]], ...]
    points: tuple[str, ...]
    point_positions: Callable
    constraint_rank: int


def _lambdify(symbols, expr):
    return sp.lambdify(symbols, expr, modules="numpy", cse=True)


class _OnFirstCall:
    """``_lambdify(symbols, expr)``, made when first called: a grader asking for a few
    objectives of a problem never pays for the others'."""

    def __init__(self, symbols, expr):
        self._args = (symbols, expr)
        self._function = None

    @property
    def function(self):
        """The lambdified function itself, made now if it was not yet."""
        if self._function is None:
            self._function = _lambdify(*self._args)
        return self._function

    def __call__(self, *values):
        return self.function(*values)


def _scale(exprs):
    """Sum of the absolute values of each equation's terms: the size a residual is judged by."""
    return sp.Matrix([sum((sp.Abs(term) for term in sp.Add.make_args(e)), sp.Integer(0))
                      for e in exprs])


def _level(index: SymbolIndex, order: int, equations, conditions) -> Level:
    symbols = index.symbols
    unknowns = [symbols[i] for i in index.unknowns(order)]
    exprs = [e.expr for e in equations] + [c.expr for c in conditions]
    m = sp.Matrix(exprs) if exprs else sp.zeros(0, 1)
    jac = m.jacobian(unknowns) if exprs else sp.zeros(0, len(unknowns))
    linear = not (jac.free_symbols & set(unknowns))
    positions = {s: i for i, s in enumerate(symbols)}
    return Level(
        order=order, name=LEVEL_NAMES[order], residual=_lambdify(symbols, m),
        jacobian=_lambdify(symbols, jac),
        scale=_lambdify(symbols, _scale(exprs) if exprs else sp.zeros(0, 1)),
        labels=tuple(e.label for e in equations) + tuple(f"given {c.key}" for c in conditions),
        wheres=tuple(e.where for e in equations) + tuple(c.where for c in conditions),
        conditions=tuple(c.key for c in conditions), linear=linear,
        uses=tuple(frozenset(positions[s] for s in e.free_symbols if s in positions)
                   for e in exprs),
        jacobian_uses=frozenset(positions[s] for s in jac.free_symbols if s in positions))


def plan(problem: Problem) -> Plan:
    """Derive and lambdify ``problem`` once (per place it was written: plans keep locations)."""
    return _plan(problem, locations(problem))


@lru_cache(maxsize=64)
def _plan(problem: Problem, _locations: tuple) -> Plan:
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
    return Plan(
        k=k, index=index, levels=levels,
        objectives=tuple((oid, _OnFirstCall(symbols, expr)) for oid, expr in k.objectives
                         if oid in numeric),
        mistakes=tuple((oid, tuple(_OnFirstCall(symbols, e) for e in exprs))
                       for oid, exprs in k.mistakes if oid in numeric),
        requirements=tuple((oid, reason, _lambdify(symbols, expr))
                           for oid, reason, expr in k.requirements),
        objective_uses=tuple((oid, frozenset(positions[s] for s in sp.sympify(expr).free_symbols
                                             if s in positions))
                             for oid, expr in k.objectives),
        points=tuple(name for name, _ in k.points), point_positions=_lambdify(symbols, points),
        constraint_rank=_generic_rank(index, k))


def _generic_rank(index: SymbolIndex, k: Kinematics) -> int:
    """Rank of the position constraints' Jacobian in the coordinates at a generic
    configuration: a configuration where it is lower is singular."""
    if not k.position:
        return 0
    jac = sp.Matrix([e.expr for e in k.position]).jacobian(list(k.q))
    rng = np.random.default_rng(3)
    point = {s: float(rng.uniform(0.4, 1.6)) for s in index.symbols}
    with np.errstate(all="ignore"):
        value = np.array(jac.xreplace(point).evalf(), dtype=complex)
    return int(np.linalg.matrix_rank(value)) if np.isfinite(value).all() else len(k.q)


plan.cache_clear = _plan.cache_clear  # type: ignore[attr-defined]  # as functools' caches
