"""Each body's free-body diagram at the solved instant, as plain data (strings, floats and
tuples: no sympy), for the layers that draw, write up and grade it without importing sympy.

The symbolic diagram is :func:`mechgrade.mechanics.dynamics.free_body_loads`; here it is
evaluated at the instant a :class:`~.result.Solution` solved
(its state; the reactions solved again from the balances there). Vectors are in the inertial
frame's components, in SI (forces in N, couples in N m, impulses in N s); a diagram whose
numbers cannot be had (a failed solve) keeps ``None`` for them, its structure intact.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.solve import solve
>>> problem = load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml")
>>> (block,) = free_body_diagrams(problem, solve(problem))
>>> [(load.name, str(load.kind), load.point, load.unknown) for load in block.loads]
[('gravity', 'weight', 'P', False), ('N_P', 'normal', 'P', True), ('F_P', 'kinetic friction', 'P', False)]
>>> normal = block.loads[1]
>>> normal.magnitude, round(normal.magnitude_value, 4), normal.surface.on
('N_P', 33.9828, 'ground')
>>> [round(c, 4) for c in normal.surface.normal], block.down
([0.5, 0.866, 0.0], (0.0, -1.0, 0.0))
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from typing import Callable

import numpy as np
import sympy as sp

from ..errors import MechgradeError
from ..mechanics.build import build
from ..mechanics.dynamics import derive_kinetics, free_body_loads
from ..mechanics.kinematics import locations
from ..spec.dynamics import (Block, Cylinder, Disk, Explicit, LoadKind, OutlineKind, Ring, Rod,
                             Shell, Sphere, dynamics_of)
from ..spec.model import Problem
from ..units import same_dimension, si_factor
from .generated import lambdified
from .levels import State
from . import rules
from .result import Solution

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class Surface:
    """The surface a contact is on: what it belongs to (``ground``, a frame or a body) and
    its unit normal, out of the surface into the body (inertial components)."""

    on: str
    normal: Vec3 | None


@dataclass(frozen=True)
class DiagramLoad:
    """One load on one body, as its free-body diagram shows it.

    ``point`` is where it acts (``None`` for a couple); ``vector`` the force on the body
    there (or the couple's moment, or an impulse during an impact), in ``unit``, at the
    instant. An ``unknown`` load (a reaction, static friction) has one unknown magnitude per
    direction: ``components`` names them as the balances do (``R_O_1``), ``directions`` and
    ``direction_texts`` give each direction (this body's sign included) as a unit vector and
    as the file wrote it. ``magnitude`` is the size a textbook writes along ``directions[0]``
    for a load with one direction (``m*g``, ``N_P``, ``mu_k*N_P``, a spring's
    ``k*(...)``; sympy syntax, rates as ``thetad``), ``""`` otherwise, and
    ``magnitude_value`` its value. ``surface`` is set for a contact (a normal force, a
    gripping contact, friction). ``sign`` is -1 on the second body of a joint or the surface
    body of friction (the equal and opposite force)."""

    name: str
    kind: LoadKind
    body: str
    point: str | None
    vector: Vec3 | None
    unit: str
    unknown: bool
    components: tuple[str, ...]
    directions: tuple[Vec3 | None, ...]
    direction_texts: tuple[str, ...]
    magnitude: str
    magnitude_value: float | None
    surface: Surface | None
    sign: int = 1


@dataclass(frozen=True)
class Outline:
    """One part of a body as a drawing shows it: its ``kind``, its centre ``at``, its
    ``sizes`` in m (a rod's or cylinder's length, a radius, a block's three sides, in the
    order the problem file gives them; ``None`` where not known at the instant), the body
    ``axis`` the shape is about or along (``x``/``y``/``z``, ``""`` for none) and the body's
    ``axes`` (its x, y, z unit vectors, inertial components; ``None`` for a particle)."""

    kind: OutlineKind
    at: str
    sizes: tuple[float | None, ...]
    axis: str
    axes: tuple[Vec3 | None, Vec3 | None, Vec3 | None] | None


@dataclass(frozen=True)
class FreeBodyDiagram:
    """A body with every load on it. ``points`` are the positions (m, from the inertial point,
    inertial components) of its centre, of every part's centre and of every point a load acts
    at; ``outline`` its parts as drawn; ``down`` is the problem's down (``loads.down``, else
    gravity's direction; ``None`` without either), a unit vector; ``frame`` the frame the body
    turns with (``None``: a particle)."""

    body: str
    frame: str | None
    centre: str
    points: tuple[tuple[str, Vec3 | None], ...]
    loads: tuple[DiagramLoad, ...]
    down: Vec3 | None
    inertial_frame: str
    outline: tuple[Outline, ...] = ()
    shown_units: tuple[tuple[str, str, float], ...] = ()
    """``(unit, shown unit, its SI factor)``: each load unit as the problem writes it (lbf on
    a problem in feet), for the labels; the vectors stay in SI."""


US_UNITS = {"N": "lbf", "N*m": "lbf*ft", "N*s": "lbf*s"}
"""The unit a problem in U.S. customary units writes for each SI load unit."""


def shown_unit(problem: Problem, unit: str) -> str:
    """The unit ``problem`` writes loads of ``unit`` in: an objective's or a given's unit of
    that dimension, else the U.S. customary one when the problem's givens are in feet, pounds
    or slugs, else ``unit``.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> shown_unit(load_problem(shipped_dir("problems") / "block_on_spring_us_units.yaml"), "N")
    'lbf'
    """
    written = [o.unit for o in problem.objectives if o.unit] + \
        [g.unit for g in problem.givens if g.unit]
    for candidate in written:
        if same_dimension(candidate, unit):
            return candidate
    if any(word in _US for u in written for word in re.findall(r"[A-Za-z_]+", u)):
        return US_UNITS.get(unit, unit)
    return unit


_US = {"ft", "foot", "feet", "lb", "lbf", "lbm", "slug", "inch", "in", "mi", "mph", "kip"}


def free_body_diagrams(problem: Problem, solution: Solution) -> tuple[FreeBodyDiagram, ...]:
    """Every body's free-body diagram at the instant ``solution`` solved (none without
    bodies). Raises :class:`~mechgrade.errors.MechgradeError` only where ``solve`` would."""
    if problem.dynamics is None:
        return ()
    plan = _diagram_plan(problem, locations(problem))
    x = _extended_state(problem, solution)
    kin = derive_kinetics(problem)
    unit = "N*s" if kin.impact else "N"
    down = _vector(plan.down, x) if plan.down is not None else None
    if down is not None:
        size = float(np.linalg.norm(down))
        down = tuple(float(c) / size + 0.0 for c in down) if size > 0 else None  # type: ignore[assignment]
    out = []
    for body in dynamics_of(problem).bodies:
        loads = []
        for applied, force, moment, magnitude, directions, normal in plan.loads:
            if applied.body != body.name:
                continue
            couple = applied.point is None
            text = sp.sstr(applied.magnitude) if applied.magnitude is not None else ""
            surface = Surface(applied.surface, _vector(normal, x)) \
                if applied.surface is not None else None
            loads.append(DiagramLoad(
                applied.name, applied.kind, body.name, applied.point,
                _vector(moment if couple else force, x), "N*m" if couple else unit,
                applied.unknown, tuple(str(s) for s in applied.unknowns),
                tuple(_vector(f, x) for f in directions), applied.direction_texts, text,
                _scalar(magnitude, x), surface, applied.sign))
        names = dict.fromkeys([body.centre, *(p.at for p in body.parts),
                               *(a.point for a in loads if a.point)])
        outline = tuple(
            Outline(kind, at, tuple(_scalar(f, x) for f in sizes), axis,
                    (_vector(axes[0], x), _vector(axes[1], x), _vector(axes[2], x))
                    if axes else None)
            for kind, at, sizes, axis, axes in plan.outlines[body.name])
        out.append(FreeBodyDiagram(body.name, body.frame, body.centre,
                                   tuple((p, _vector(plan.points.get(p), x)) for p in names),
                                   tuple(loads), down, problem.inertial_frame, outline,
                                   tuple(_shown(problem, u) for u in
                                         dict.fromkeys(a.unit for a in loads))))
    return tuple(out)


def _shown(problem: Problem, unit: str) -> tuple[str, str, float]:
    shown = shown_unit(problem, unit)
    return unit, shown, si_factor(shown)


@dataclass(frozen=True)
class _DiagramPlan:
    loads: tuple  # (AppliedLoad, force f, moment f, magnitude f, direction fs, normal f)
    points: dict[str, Callable]
    down: Callable | None
    outlines: dict[str, tuple]  # body -> ((kind, at, size fs, axis, axis fs), ...)


@lru_cache(maxsize=32)
def _diagram_plan(problem: Problem, _locations: tuple) -> _DiagramPlan:
    # the dynamics solver is imported when a diagram is drawn, not when the write-up module
    # is: a grading run that reads its solutions from the cache derives nothing
    from .dynamics import kinetics_plan

    kin = derive_kinetics(problem)
    applied = free_body_loads(problem)
    symbols = kinetics_plan(problem).symbols

    def f(expr):
        return None if expr is None else lambdified(symbols, expr)

    loads = tuple((a, f(a.force), f(a.moment), f(a.magnitude), tuple(f(e) for e in a.directions),
                   f(a.surface_normal)) for a in applied)
    points = {name: f(sp.Matrix(r)) for name, r in kin.k.points}
    d = dynamics_of(problem)
    down = None
    weights = [a for a in applied if a.kind == LoadKind.WEIGHT]
    model = build(problem)
    if d.down is not None:
        down = f(model.plain(model.language.vector(d.down).to_matrix(model.inertial)))
    elif weights:
        down = f(weights[0].directions[0])
    outlines = {}
    for body in d.bodies:
        frame = model.frames[body.frame] if body.frame is not None else None
        axes = () if frame is None else tuple(
            f(model.plain(e.to_matrix(model.inertial))) for e in (frame.x, frame.y, frame.z))
        parts = []
        for part in body.parts:
            kind, sizes, axis = drawn_shape(part.shape if frame is not None else None)
            parts.append((kind, part.at, tuple(f(model.plain(model.language.scalar(e)))
                                               for e in sizes), axis, axes))
        outlines[body.name] = tuple(parts)
    return _DiagramPlan(loads, points, down, outlines)


def drawn_shape(shape) -> tuple[OutlineKind, tuple, str]:
    """A part's shape as drawn: its kind, its sizes (spec expressions) and its axis.

    >>> drawn_shape(None)
    (<OutlineKind.PARTICLE: 'particle'>, (), '')
    """
    if shape is None:
        return OutlineKind.PARTICLE, (), ""
    if isinstance(shape, Block):
        return OutlineKind.BLOCK, shape.sides, ""
    if isinstance(shape, Explicit):
        return OutlineKind.BODY, (), ""
    kind = {Rod: OutlineKind.ROD, Disk: OutlineKind.DISK, Ring: OutlineKind.RING,
            Cylinder: OutlineKind.CYLINDER, Sphere: OutlineKind.SPHERE,
            Shell: OutlineKind.SHELL}[type(shape)]
    sizes = tuple(getattr(shape, n) for n in ("length", "radius") if hasattr(shape, n))
    return kind, sizes, getattr(shape, "axis", "")


def _extended_state(problem: Problem, solution: Solution) -> np.ndarray | None:
    """The solved state with the reactions solved again from the balances there (by least
    squares alone where the checks refuse the state: the event of an integration is the limit
    just before it); ``None`` when the solution has no state to read (nothing numeric was
    solved)."""
    from .dynamics import accelerations, kinetics_plan, solve_kinetics  # see _diagram_plan

    kp = kinetics_plan(problem)
    index = kp.kp.index
    values = np.full(index.size, np.nan)
    for s in solution.state:
        if s.name in index.names:
            values[index.position(s.name)] = s.si
    if not solution.state:
        return None
    if not np.isfinite(values[index.time]):
        values[index.time] = 0.0  # time-independent: not reported
    known = np.isfinite(values)
    try:
        return solve_kinetics(problem, kp, State(np.where(known, values, 0.0), known))
    except MechgradeError:  # an integration's event (a slip ending): the limit before it
        before = _just_before(index, values)
        if before is not None:
            try:
                return solve_kinetics(problem, kp, State(np.where(np.isfinite(before),
                                                                  before, 0.0),
                                                         np.isfinite(before)))
            except MechgradeError:
                pass
        try:
            return accelerations(kp, np.where(known, values, 0.0))
        except MechgradeError:
            return None


def _just_before(index, values: np.ndarray) -> np.ndarray | None:
    """``values`` with the rates a moment earlier along the solved accelerations, the
    accelerations left to the balances (the coordinates kept: the points stay where the
    event has them, the rates are off by :data:`.rules.MOMENT`, far inside any tolerance);
    ``None`` without solved accelerations."""
    rates, second = list(index.rates(1)), list(index.rates(2))
    if not np.all(np.isfinite(values[rates + second])):
        return None
    step = float(rules.moment(float(values[index.time])))
    before = values.copy()
    before[rates] -= step * values[second]
    before[index.time] -= step
    before[second] = np.nan
    return before


def _call(f: Callable | None, x: np.ndarray | None):
    if f is None or x is None:
        return None
    with np.errstate(all="ignore"):
        value = np.asarray(f(*x), dtype=float).ravel()
    return value if np.all(np.isfinite(value)) else None


def _vector(f: Callable | None, x: np.ndarray | None) -> Vec3 | None:
    value = _call(f, x)
    return None if value is None else (float(value[0]) + 0.0, float(value[1]) + 0.0,
                                       float(value[2]) + 0.0)


def _scalar(f: Callable | None, x: np.ndarray | None) -> float | None:
    value = _call(f, x)
    return None if value is None else float(value[0]) + 0.0
