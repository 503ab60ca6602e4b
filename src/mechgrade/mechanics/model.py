"""The kinematics core: build a problem's frames, points, constraints and objectives with
``sympy.physics.mechanics``, and hand them on as plain sympy expressions.

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

import random
from dataclasses import dataclass
from functools import lru_cache

import sympy as sp
from sympy.physics.vector import ReferenceFrame, Vector, dynamicsymbols

from ..errors import SolveError, SpecError
from ..expressions.build import to_sympy
from ..expressions.syntax import Name, Node, Prime, to_text
from ..spec.model import TIME, Expr, Problem

TIME_SYMBOL = dynamicsymbols._t


@dataclass(frozen=True)
class Equation:
    """A scalar equation ``expr = 0`` with a label naming where it came from."""

    label: str
    expr: sp.Expr


@dataclass(frozen=True)
class Condition:
    """A given written as an expression (``key``): ``expr`` equals the given's value at the
    instant only, at ``level`` 0 (position), 1 (velocity) or 2 (acceleration)."""

    key: str
    expr: sp.Expr
    level: int


@dataclass(frozen=True)
class Kinematics:
    """A problem's model in plain symbols: what the solver needs, nothing else.

    ``position``, ``velocity`` and ``acceleration`` are the constraint equations at each level
    (velocity and acceleration levels include the time derivatives of the levels above);
    ``objectives`` maps an objective id to a scalar expression or a 3x1 matrix of components
    in the objective's frame; ``mistakes`` likewise for author-declared mistaken models.
    ``requirements`` are ``(objective id, reason, expr)``: ``expr`` must vanish at the instant
    for the objective to exist (a point of zero velocity needs planar motion).
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


class _Model:
    """The sympy.physics objects of one problem, and the interpreter of its expressions."""

    def __init__(self, problem: Problem):
        self.problem = problem
        t = TIME_SYMBOL
        self.dyn = {c.name: dynamicsymbols(c.name, real=True) for c in problem.coordinates}
        self.params = {p.name: sp.Symbol(p.name, positive=True) if p.positive
                       else sp.Symbol(p.name, real=True) for p in problem.parameters}
        names = [c.name for c in problem.coordinates]
        self.q = tuple(sp.Symbol(n, real=True) for n in names)
        self.qd = tuple(sp.Symbol(n + "d", real=True) for n in names)
        self.qdd = tuple(sp.Symbol(n + "dd", real=True) for n in names)
        self._plain = {}
        for name, qs, qds, qdds in zip(names, self.q, self.qd, self.qdd):
            f = self.dyn[name]
            self._plain[f.diff(t, 2)] = qdds
            self._plain[f.diff(t)] = qds
            self._plain[f] = qs
        self.frames: dict[str, ReferenceFrame] = {}
        self.spec_frames = {f.name: f for f in problem.frames}
        for frame in problem.frames:
            self._frame(frame.name)
        self.inertial = self.frames[problem.inertial_frame]
        self.spec_points = {p.name: p for p in problem.points}
        self.positions: dict[str, Vector] = {}
        self.requirements: list[tuple[str, object]] = []
        for point in problem.points:
            self.position(point.name)

    # ---------------------------------------------------------------- building

    def _frame(self, name: str) -> ReferenceFrame:
        if name in self.frames:
            return self.frames[name]
        spec = self.spec_frames[name]
        frame = ReferenceFrame(name)
        if spec.parent is not None:
            parent = self._frame(spec.parent)
            # A body-fixed sequence is a chain of simple rotations, each about an axis of the
            # frame the previous one produced.
            current = parent
            for i, rotation in enumerate(spec.rotations):
                last = i == len(spec.rotations) - 1
                target = frame if last else ReferenceFrame(f"{name}_{i + 1}")
                target.orient_axis(current, getattr(current, rotation.axis),
                                   self.scalar(rotation.angle))
                current = target
        self.frames[name] = frame
        return frame

    def position(self, point: str) -> Vector:
        """Position of a named point from the inertial point."""
        if point in self.positions:
            return self.positions[point]
        spec = self.spec_points[point]
        if spec.origin is None:
            vector = Vector(0)
        else:
            vector = self.position(spec.origin) + self.vector(spec.position)
        self.positions[point] = vector
        return vector

    def plain(self, expr):
        """Rewrite dynamicsymbols and their derivatives as plain symbols (derivatives first)."""
        if isinstance(expr, Vector):
            return expr.applyfunc(lambda e: _as_expr(e).xreplace(self._plain))
        return _as_expr(expr).xreplace(self._plain)

    # ---------------------------------------------------------------- interpreter

    def scalar(self, expr: Expr):
        value = self.value(expr.node)
        if isinstance(value, Vector):
            raise SpecError("expected a scalar, found a vector", where=expr.where)
        return _as_expr(value)

    def vector(self, expr: Expr) -> Vector:
        value = self.value(expr.node)
        if not isinstance(value, Vector):
            if value == 0:
                return Vector(0)
            raise SpecError("expected a vector, found a scalar", where=expr.where)
        return value

    def value(self, node: Node):
        """The sympy value (scalar or Vector) of a spec expression."""
        return to_sympy(node, self._resolve, self._call)

    def _resolve(self, node: Node):
        if isinstance(node, Name):
            if node.id == TIME:
                return TIME_SYMBOL
            if node.id in self.dyn:
                return self.dyn[node.id]
            return self.params[node.id]
        if isinstance(node, Prime):
            return self.dyn[node.id].diff(TIME_SYMBOL, node.order)
        return getattr(self.frames[node.base], node.attr)

    def _call(self, func: str, args: tuple):
        return getattr(self, "_fn_" + func)(*args)

    def frame(self, node: Node) -> ReferenceFrame:
        return self.frames[node.id]

    def origin(self, frame: str) -> str:
        """A point fixed in ``frame``: the inertial point for the inertial frame."""
        if frame == self.problem.inertial_frame:
            return self.problem.inertial_point
        origin = self.spec_frames[frame].origin
        if origin is None:
            raise SpecError(f"frame '{frame}' needs an 'origin' (a point fixed in it)",
                            where=self.spec_frames[frame].where)
        return origin

    # points: a named point, coincident(P, A) or ic(A, F)

    def point_position(self, node: Node) -> Vector:
        if isinstance(node, Name):
            return self.positions[node.id]
        if node.func == "coincident":
            return self.point_position(node.args[0])
        body, frame = node.args[0].id, node.args[1].id
        origin = self.origin(body)
        omega = self.frames[body].ang_vel_in(self.frames[frame])
        v = self.point_velocity(Name(origin), frame)
        # Only motion with v perpendicular to omega (planar) has a point of zero velocity;
        # otherwise this is the point of the screw axis nearest the origin, which still moves.
        self.requirements.append((f"body {body} has no point of zero velocity in {frame} at "
                                  "this instant (its velocity has a part along its angular "
                                  "velocity: the motion is not planar)",
                                  (omega & v) / (omega.magnitude() * v.magnitude() + 1)))
        return self.positions[origin] + (omega ^ v) / (omega & omega)

    def point_velocity(self, node: Node, frame: str) -> Vector:
        F = self.frames[frame]
        if isinstance(node, Name):
            relative = self.positions[node.id] - self.positions[self.origin(frame)]
            return relative.dt(F)
        if node.func == "coincident":
            body = node.args[1].id
            origin = self.origin(body)
            r = self.point_position(node.args[0]) - self.positions[origin]
            return self.point_velocity(Name(origin), frame) + \
                (self.frames[body].ang_vel_in(F) ^ r)
        raise SpecError("the instantaneous centre is a location only; use pos(ic(A, F), P)")

    def point_acceleration(self, node: Node, frame: str) -> Vector:
        F = self.frames[frame]
        if isinstance(node, Name):
            relative = self.positions[node.id] - self.positions[self.origin(frame)]
            return relative.dt(F).dt(F)
        if node.func == "coincident":
            body = node.args[1].id
            origin = self.origin(body)
            r = self.point_position(node.args[0]) - self.positions[origin]
            omega = self.frames[body].ang_vel_in(F)
            alpha = self.frames[body].ang_acc_in(F)
            return self.point_acceleration(Name(origin), frame) + (alpha ^ r) + \
                (omega ^ (omega ^ r))
        raise SpecError("the instantaneous centre is a location only; use pos(ic(A, F), P)")

    def _fn_pos(self, p, q):
        return self.point_position(p) - self.point_position(q)

    def _fn_vel(self, p, f):
        return self.point_velocity(p, f.id)

    def _fn_acc(self, p, f):
        return self.point_acceleration(p, f.id)

    def _fn_angvel(self, a, f):
        return self.frame(a).ang_vel_in(self.frame(f))

    def _fn_angacc(self, a, f):
        return self.frame(a).ang_acc_in(self.frame(f))

    def _fn_dt(self, v, f):
        return self._as_vector(self.value(v)).dt(self.frame(f))

    def _fn_mag(self, v):
        return self._as_vector(self.value(v)).magnitude()

    def _fn_dot(self, u, v):
        return self._as_vector(self.value(u)) & self._as_vector(self.value(v))

    def _fn_cross(self, u, v):
        return self._as_vector(self.value(u)) ^ self._as_vector(self.value(v))

    def _fn_unit(self, v):
        vector = self._as_vector(self.value(v))
        return vector / vector.magnitude()

    def _fn_speed(self, p, f):
        return self.point_velocity(p, f.id).magnitude()

    def _fn_tangent(self, p, f):
        v = self.point_velocity(p, f.id)
        return v / v.magnitude()

    def _fn_acc_t(self, p, f):
        v = self.point_velocity(p, f.id)
        return (self.point_acceleration(p, f.id) & v) / v.magnitude()

    def _fn_acc_n(self, p, f):
        # |v x a| / |v| rather than sqrt(|a|^2 - a_t^2): no cancellation when a is nearly tangent
        v = self.point_velocity(p, f.id)
        return (v ^ self.point_acceleration(p, f.id)).magnitude() / v.magnitude()

    def _fn_rho(self, p, f):
        v = self.point_velocity(p, f.id)
        return v.magnitude() ** 3 / (v ^ self.point_acceleration(p, f.id)).magnitude()

    def _fn_normal(self, p, f):
        v = self.point_velocity(p, f.id)
        a = self.point_acceleration(p, f.id)
        tangent = v / v.magnitude()
        a_n = a - (a & tangent) * tangent
        return a_n / a_n.magnitude()

    @staticmethod
    def _as_vector(value) -> Vector:
        if isinstance(value, Vector):
            return value
        if value == 0:
            return Vector(0)
        raise SpecError("expected a vector, found a scalar")  # pragma: no cover

    # ---------------------------------------------------------------- equations

    def components(self, value) -> list[sp.Expr]:
        """Scalar equations of a (scalar or vector) difference, vectors in the inertial frame."""
        if isinstance(value, Vector):
            return list(value.to_matrix(self.inertial))
        return [_as_expr(value)]


def _as_expr(value) -> sp.Expr:
    """A sympy expression for a sympy object or a plain Python number (never text)."""
    if isinstance(value, bool) or isinstance(value, str):
        raise TypeError(f"expected a number or sympy expression, found {value!r}")
    if isinstance(value, int):
        return sp.Integer(value)
    if isinstance(value, float):
        return sp.Float(value)
    return value


def _identically_zero(expr: sp.Expr) -> bool:
    """Whether ``expr`` is zero for all values (checked at random points, then exactly)."""
    expr = _as_expr(expr)
    if expr == 0:
        return True
    symbols = sorted(expr.free_symbols, key=str)
    rng = random.Random(7)
    for _ in range(3):
        point = {s: rng.uniform(0.3, 1.7) for s in symbols}
        value = complex(_as_expr(expr.xreplace(point)).evalf())
        if abs(value) > 1e-9:
            return False
    return True


@lru_cache(maxsize=64)
def derive(problem: Problem) -> Kinematics:
    """Build the kinematics of ``problem``: constraint equations at the position, velocity and
    acceleration levels, given-conditions, and every objective as a plain sympy expression."""
    model = _Model(problem)
    t = TIME_SYMBOL
    position_dyn: list[tuple[str, sp.Expr]] = []
    velocity_dyn: list[tuple[str, sp.Expr]] = []
    count = 0
    axes = [f"{problem.inertial_frame}.{a}" for a in "xyz"]
    for c in problem.constraints:
        difference = model.value(c.lhs.node) - model.value(c.rhs.node)
        parts = model.components(difference)
        labels = [f"{c.name} ({axes[i]} component)" for i in range(3)] if len(parts) == 3 \
            else [c.name]
        for label, part in zip(labels, parts):
            if _identically_zero(model.plain(part)):
                continue
            count += 1
            (position_dyn if c.level == "position" else velocity_dyn).append((label, part))
    velocity_all = [(label, sp.diff(expr, t)) for label, expr in position_dyn] + velocity_dyn
    acceleration_all = [(label, sp.diff(expr, t)) for label, expr in velocity_all]

    def plain_equations(items):
        return tuple(Equation(label, model.plain(expr)) for label, expr in items)

    conditions = {}
    for given in problem.givens + tuple(g for o in problem.objectives for g in o.givens):
        node = given.key.node
        key = to_text(node)
        if isinstance(node, (Name, Prime)) or key in conditions:
            continue
        expr = model.plain(model.value(node))
        conditions[key] = Condition(key, expr, _level(expr, model))

    objectives = []
    mistakes = []
    requirements = []
    for obj in problem.objectives:
        model.requirements.clear()
        objectives.append((obj.id, _objective_value(model, obj.find, obj.frame)))
        requirements += [(obj.id, reason, model.plain(expr))
                         for reason, expr in model.requirements]
        mistakes.append((obj.id, tuple(_objective_value(model, m.find, obj.frame)
                                       for m in obj.mistakes)))
    return Kinematics(
        problem=problem.id, coordinates=tuple(c.name for c in problem.coordinates),
        q=model.q, qd=model.qd, qdd=model.qdd, time=t,
        parameters=tuple(model.params.items()),
        position=plain_equations(position_dyn), velocity=plain_equations(velocity_all),
        acceleration=plain_equations(acceleration_all), conditions=tuple(conditions.values()),
        objectives=tuple(objectives), mistakes=tuple(mistakes),
        requirements=tuple(requirements), constraint_count=count)


def _level(expr: sp.Expr, model: _Model) -> int:
    free = expr.free_symbols
    if free & set(model.qdd):
        return 2
    if free & set(model.qd):
        return 1
    return 0


def _objective_value(model: _Model, expr: Expr, frame: str | None):
    try:
        value = model.value(expr.node)
    except (ZeroDivisionError, TypeError, ValueError) as exc:
        raise SolveError(f"cannot build this objective ({exc})", where=expr.where) from None
    if isinstance(value, Vector):
        return model.plain(value.to_matrix(model.frames[frame or model.problem.inertial_frame]))
    return model.plain(value)


def derivation(problem: Problem, dof: int | None = None) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """The model in the write-up order, as text: frames, points, coordinates, constraints,
    degrees of freedom (``dof``, as the solver found it), velocities and accelerations of every
    point in the inertial frame."""
    model = _Model(problem)
    k = derive(problem)
    N = problem.inertial_frame
    frames = []
    for f in problem.frames:
        if f.parent is None:
            frames.append(f"{f.name}: inertial frame; inertial point {problem.inertial_point}")
            continue
        turns = ", then ".join(f"{r.angle.text} about {('the new ' if i else f.parent + '.')}"
                               f"{r.axis}" for i, r in enumerate(f.rotations))
        origin = f"; origin {f.origin}" if f.origin else ""
        frames.append(f"{f.name}: from {f.parent} by {turns}{origin}")
    points = [f"P_{p.origin}{p.name} = {p.position.text}" for p in problem.points if p.origin]
    coordinates = [f"{c.name} [{c.unit or '1'}]" for c in problem.coordinates]
    parameters = [f"{p.name} [{p.unit or '1'}]" for p in problem.parameters]
    constraints = [f"{c.name} ({c.level}): {c.lhs.text} = {c.rhs.text}"
                   for c in problem.constraints]
    constraints += [f"  {e.label}: {sp.sstr(e.expr)} = 0" for e in k.position]
    constraints += [f"  {e.label}, rate form: {sp.sstr(e.expr)} = 0" for e in k.velocity]
    independent = len(k.coordinates) - dof if dof is not None else k.constraint_count
    dof_lines = [f"{len(k.coordinates)} coordinates - {independent} independent scalar "
                 f"constraints = {len(k.coordinates) - independent}"]
    if independent != k.constraint_count:
        dof_lines.append(f"({k.constraint_count} scalar constraint equations, "
                         f"{k.constraint_count - independent} of them redundant)")
    velocities, accelerations = [], []
    for p in problem.points:
        if p.origin is None:
            continue
        v = model.point_velocity(Name(p.name), N)
        a = model.point_acceleration(Name(p.name), N)
        velocities.append(f"{N}_V_{p.name} = {_vector_text(model.plain(v))}")
        accelerations.append(f"{N}_A_{p.name} = {_vector_text(model.plain(a))}")
    return (("Frames", tuple(frames)), ("Points", tuple(points)),
            ("Coordinates", tuple(coordinates)), ("Parameters", tuple(parameters)),
            ("Constraints", tuple(constraints)), ("Degrees of freedom", tuple(dof_lines)),
            ("Velocities", tuple(velocities)), ("Accelerations", tuple(accelerations)))


def _vector_text(v: Vector) -> str:
    text = str(v)
    return text if text != "0" else "0"
