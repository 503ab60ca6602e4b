"""The kinematics of a problem: from its ``sympy.physics.mechanics`` model (:mod:`.build`),
the constraint equations at every level, the givens and the objectives, handed on as plain
sympy expressions.

Coordinates are ``dynamicsymbols``; frames are oriented with ``orient_axis`` /
``orient_body_fixed``; every point's position is written from the inertial point, and
velocities and accelerations come from explicit time derivatives of positions in the frame
asked for (never from ``Point.vel``'s path search). The results are rewritten in plain
symbols — ``theta``, ``thetad``, ``thetadd`` — second derivatives first, so that replacing
``theta(t)`` can never turn ``Derivative(theta(t), t)`` into zero.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> k = derive(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"))
>>> k.coordinates, [str(s) for s in k.qd]
(('theta',), ['thetad'])
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp
from sympy.physics.vector import Vector

from ..errors import AuthorWarning, Location, SolveError
from ..expressions.syntax import Name, Node, Prime, to_text
from ..spec.model import TIME, Constraint, ConstraintLevel, Expr, Given, Objective, Point, Problem
from .build import Model, build
from .material import material_warnings
from .symbols import TIME_SYMBOL, identically_zero, without_deltas


@dataclass(frozen=True)
class Equation:
    """A scalar equation ``expr = 0`` with a label naming where it came from."""

    label: str
    expr: sp.Expr
    where: Location = Location()


@dataclass(frozen=True)
class Condition:
    """A given written as an expression (``key``): ``expr`` equals the given's value at the
    instant only, at ``level`` 0 (position), 1 (velocity) or 2 (acceleration)."""

    key: str
    expr: sp.Expr
    level: int
    where: Location = Location()


@dataclass(frozen=True)
class Kinematics:
    """A problem's model in plain symbols: what the solver needs, nothing else.

    ``position``, ``velocity`` and ``acceleration`` are the constraint equations at each level
    (velocity and acceleration levels include the time derivatives of the levels above);
    ``objectives`` maps an objective id to a scalar expression or a 3x1 matrix of components
    in the objective's frame; ``mistakes`` likewise for author-declared mistaken models.
    ``requirements`` are ``(objective id, reason, expr)``: ``expr`` must vanish at the instant
    for the objective to exist (a point of zero velocity needs planar motion). ``points`` are
    the position of every point from the inertial point (inertial components); ``warnings``
    the material-point warnings of :mod:`.material`.
    """

    problem: str
    coordinates: tuple[str, ...]
    q: tuple[sp.Symbol, ...]
    qd: tuple[sp.Symbol, ...]
    qdd: tuple[sp.Symbol, ...]
    time: sp.Symbol
    parameters: tuple[tuple[str, sp.Symbol], ...]
    position: tuple[Equation, ...]
    velocity: tuple[Equation, ...]
    acceleration: tuple[Equation, ...]
    conditions: tuple[Condition, ...]
    objectives: tuple[tuple[str, object], ...]
    mistakes: tuple[tuple[str, tuple[object, ...]], ...]
    requirements: tuple[tuple[str, str, object], ...]
    constraint_count: int
    points: tuple[tuple[str, object], ...] = ()
    warnings: tuple[AuthorWarning, ...] = ()

    def objective(self, objective_id: str):
        return dict(self.objectives)[objective_id]

    def quantity(self, node: Node) -> sp.Symbol:
        """The plain symbol of a coordinate, rate, parameter or time node."""
        if isinstance(node, Name):
            if node.id == TIME:
                return self.time
            if node.id in self.coordinates:
                return self.q[self.coordinates.index(node.id)]
            return dict(self.parameters)[node.id]
        if isinstance(node, Prime):
            index = self.coordinates.index(node.id)
            return (self.qd if node.order == 1 else self.qdd)[index]
        raise KeyError(node)


_LOCATIONS: dict[int, tuple[Problem, tuple]] = {}


def locations(problem: Problem) -> tuple:
    """Where the problem's parts are written. Problems compare equal whatever their
    locations, so caches that keep locations (in equations and warnings) key on these too.
    Kept for the problem object itself (not an equal one): each solve asks for them."""
    held = _LOCATIONS.get(id(problem))
    if held is not None and held[0] is problem:
        return held[1]
    if len(_LOCATIONS) >= 256:
        del _LOCATIONS[next(iter(_LOCATIONS))]
    found = _LOCATIONS[id(problem)] = (problem, _locations(problem))
    return found[1]


def _locations(problem: Problem) -> tuple:
    parts: tuple[Point | Constraint | Given | Objective | Expr, ...] = (
        *problem.points, *problem.constraints, *problem.givens, *problem.objectives,
        *(g for o in problem.objectives for g in o.givens),
        *(o.find for o in problem.objectives))
    return (problem.path, *(str(x.where) for x in parts))


def derive(problem: Problem) -> Kinematics:
    """Build the kinematics of ``problem``: constraint equations at the position, velocity and
    acceleration levels, given-conditions, and every objective as a plain sympy expression."""
    return _derive(problem, locations(problem))


@lru_cache(maxsize=64)
def _derive(problem: Problem, _locations: tuple) -> Kinematics:
    model = build(problem)
    t = TIME_SYMBOL
    position_dyn: list[tuple[str, sp.Expr, Location]] = []
    velocity_dyn: list[tuple[str, sp.Expr, Location]] = []
    count = 0
    axes = [f"{problem.inertial_frame}.{a}" for a in "xyz"]
    for c in problem.constraints:
        difference = model.language.value(c.lhs.node) - model.language.value(c.rhs.node)
        parts = model.components(difference)
        labels = [f"{c.name} ({axes[i]} component)" for i in range(3)] if len(parts) == 3 \
            else [c.name]
        for label, part in zip(labels, parts):
            if identically_zero(model.plain(part)):
                continue
            count += 1
            (position_dyn if c.level is ConstraintLevel.POSITION else velocity_dyn).append(
                (label, part, c.where))
    velocity_all = [(label, sp.diff(expr, t), where) for label, expr, where in position_dyn] \
        + velocity_dyn
    acceleration_all = [(label, sp.diff(expr, t), where) for label, expr, where in velocity_all]

    def plain_equations(items):
        return tuple(Equation(label, without_deltas(model.plain(expr)), where)
                     for label, expr, where in items)

    conditions = {}
    for given in problem.givens + tuple(g for o in problem.objectives for g in o.givens):
        node = given.key.node
        key = to_text(node)
        if isinstance(node, (Name, Prime)) or key in conditions:
            continue
        expr = model.plain(model.language.value(node))
        conditions[key] = Condition(key, expr, _level(expr, model), given.where)

    objectives = []
    mistakes = []
    requirements = []
    for obj in problem.objectives:
        model.language.requirements.clear()
        objectives.append((obj.id, _objective_value(model, obj.find, obj.frame)))
        requirements += [(obj.id, reason, model.plain(expr))
                         for reason, expr in model.language.requirements]
        mistakes.append((obj.id, tuple(_objective_value(model, m.find, obj.frame)
                                       for m in obj.mistakes)))
    return Kinematics(
        problem=problem.id, coordinates=tuple(c.name for c in problem.coordinates),
        q=model.symbols.q, qd=model.symbols.qd, qdd=model.symbols.qdd, time=t,
        parameters=tuple(model.symbols.params.items()),
        position=plain_equations(position_dyn), velocity=plain_equations(velocity_all),
        acceleration=plain_equations(acceleration_all), conditions=tuple(conditions.values()),
        objectives=tuple(objectives), mistakes=tuple(mistakes),
        requirements=tuple(requirements), constraint_count=count,
        points=tuple((name, model.plain(r.to_matrix(model.inertial)))
                     for name, r in model.positions.items()),
        warnings=material_warnings(problem, model))


def _level(expr: sp.Expr, model: Model) -> int:
    free = expr.free_symbols
    if free & set(model.symbols.qdd):
        return 2
    if free & set(model.symbols.qd):
        return 1
    return 0


def _objective_value(model: Model, expr: Expr, frame: str | None):
    try:
        value = model.language.value(expr.node)
    except (ZeroDivisionError, TypeError, ValueError) as exc:
        raise SolveError(f"cannot build this objective ({exc})", where=expr.where) from None
    if isinstance(value, Vector):
        return model.plain(value.to_matrix(model.frames[frame or model.problem.inertial_frame]))
    return model.plain(value)




# Functions take attributes at run time; mypy models none (python/mypy#2087).
derive.cache_clear = _derive.cache_clear  # type: ignore[attr-defined]
