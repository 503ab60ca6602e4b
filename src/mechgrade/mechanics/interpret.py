"""The expression language read as ``sympy.physics`` objects: positions, velocities and
accelerations of points (named, ``coincident(P, A)``, ``ic(A, F)``), angular velocities, and the
vector functions of the objective language, each an ``_fn_<name>`` method.

An interpreter's :attr:`~Interpreter.functions` maps each function name of the language's table
(:mod:`mechgrade.expressions.functions`) to its implementation; adding a function is one table
entry and one ``_fn_<name>`` method.

Velocities and accelerations come from explicit time derivatives of positions in the frame
asked for (never from ``Point.vel``'s path search).
"""

from __future__ import annotations

from typing import Callable, ClassVar

from sympy.physics.vector import ReferenceFrame, Vector

from ..errors import SpecError
from ..expressions.build import to_sympy
from ..expressions.syntax import Attr, Call, Name, Node, Prime, name_of
from ..spec.model import TIME, Expr, Problem
from .symbols import TIME_SYMBOL, Symbols, as_expr


class Interpreter:
    """The value of spec expressions in a model's frames and point positions.

    ``frames`` and ``positions`` are filled by :func:`mechgrade.mechanics.build.build`, which
    uses this interpreter for the rotation angles and location descriptions themselves.
    ``requirements`` collects ``(reason, expr)``: conditions an expression read since the last
    ``clear`` needs at the instant (an instantaneous centre needs planar motion).
    """

    functions: ClassVar[dict[str, Callable]] = {}
    """Objective function name -> the method computing its value (set per class)."""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        cls.functions = implementations(cls)

    def __init__(self, problem: Problem, symbols: Symbols, frames: dict[str, ReferenceFrame],
                 positions: dict[str, Vector]):
        self.problem = problem
        self.symbols = symbols
        self.dyn = symbols.dyn
        self.params = symbols.params
        self.frames = frames
        self.positions = positions
        self.spec_frames = {f.name: f for f in problem.frames}
        self.requirements: list[tuple[str, object]] = []

    def scalar(self, expr: Expr):
        value = self.value(expr.node)
        if isinstance(value, Vector):
            raise SpecError("expected a scalar, found a vector", where=expr.where)
        return as_expr(value)

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
        assert isinstance(node, Attr), node  # fold resolves names, primes and unit vectors
        return getattr(self.frames[node.base], node.attr)

    def _call(self, func: str, args: tuple):
        return self.functions[func](self, *args)

    def frame(self, node: Node) -> ReferenceFrame:
        return self.frames[name_of(node)]

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
        assert isinstance(node, Call), node  # a point: a name, coincident(P, A) or ic(A, F)
        if node.func == "coincident":
            return self.point_position(node.args[0])
        body, frame = name_of(node.args[0]), name_of(node.args[1])
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
        assert isinstance(node, Call), node  # a point: a name, coincident(P, A) or ic(A, F)
        if node.func == "coincident":
            body = name_of(node.args[1])
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
        assert isinstance(node, Call), node  # a point: a name, coincident(P, A) or ic(A, F)
        if node.func == "coincident":
            body = name_of(node.args[1])
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


def implementations(interpreter: type) -> dict[str, Callable]:
    """The objective functions a class implements, by name: its ``_fn_<name>`` methods.

    >>> sorted(implementations(Interpreter))[:3]
    ['acc', 'acc_n', 'acc_t']
    """
    return {name[len("_fn_"):]: getattr(interpreter, name) for name in dir(interpreter)
            if name.startswith("_fn_")}


Interpreter.functions = implementations(Interpreter)
