"""Conceptual mistakes applied to a problem's model: each objective re-read with one term of
the composition of motion dropped, another point, another frame's unit vectors, or a path
quantity confused with its neighbour.

A mutation works on the model, not on the number: the objective's own expression is read again
by an interpreter whose velocity or acceleration of one point in one frame is the mistaken one,
so a magnitude, a component or a tangential part of a mistaken acceleration is mistaken the way
a student's would be. Each :class:`Mutation` carries its family ``code`` (for partial-credit
settings), the mistaken value in plain symbols, the term that was dropped (components along the
objective's frame, or the inertial frame) and a sentence in which ``{term}`` stands for that
term's value.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
>>> sorted({m.code for m in mutations(problem) if m.objective == "acc_mag"})[:3]
['acc_n_for_acc', 'acc_t_for_acc', 'drop_centripetal']
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Any, Iterator

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..expressions.notation import textbook
from ..expressions.syntax import (Attr, Bin, Call, Name, Node, Num, Prime, Unary,
                                  additive_terms, name_of, names, sum_of_terms, to_text, walk)
from ..spec.dynamics import Explicit, dynamics_of
from ..spec.model import ConstraintLevel, Expr, Objective, Problem
from ..units import same_dimension
from .build import Model, build
from .interpret import Interpreter
from .kinematics import locations
from .symbols import identically_zero



@dataclass(frozen=True)
class Mutation:
    """One mistaken reading of one objective: ``value`` a scalar or a 3x1 matrix along the
    objective's frame, ``term`` the dropped term as a 3x1 matrix (or ``None``), ``sentence``
    the diagnosis, with ``{term}`` where the term's value goes."""

    objective: str
    code: str
    value: object
    sentence: str
    term: object = None


class _Mistaken(Interpreter):
    """An interpreter whose velocity or acceleration of ``point`` in ``frame`` (or its
    position) is replaced."""

    def __init__(self, base: Interpreter, point: str | Node, frame: str, velocity=None,
                 acceleration=None, position=None):
        super().__init__(base.problem, base.symbols, base.frames, base.positions)
        # a point's name, or a node such as coincident(C, W) (a body's material point)
        self.target = (Name(point) if isinstance(point, str) else point, frame)
        self.velocity = velocity
        self.acceleration = acceleration
        self.position = position

    def point_position(self, node: Node) -> Vector:
        if self.position is not None and node == self.target[0]:
            return self.position
        return super().point_position(node)

    def point_velocity(self, node: Node, frame: str) -> Vector:
        if self.velocity is not None and node == self.target[0] \
                and frame == self.target[1]:
            return self.velocity
        return super().point_velocity(node, frame)

    def point_acceleration(self, node: Node, frame: str) -> Vector:
        if self.acceleration is not None and node == self.target[0] \
                and frame == self.target[1]:
            return self.acceleration
        return super().point_acceleration(node, frame)


def mutations(problem: Problem, objective: str | None = None) -> tuple[Mutation, ...]:
    """Every model mutation of every numeric objective of ``problem`` (of ``objective`` only,
    when named: a grader asking for a few objectives derives only theirs)."""
    where = locations(problem)
    ids = [o.id for o in problem.objectives] if objective is None else [objective]
    return tuple(m for oid in ids for m in _mutations(problem, where, oid))


@lru_cache(maxsize=64)
def _model(problem: Problem, _locations: tuple) -> Model:
    return build(problem)


@lru_cache(maxsize=512)
def _mutations(problem: Problem, _locations: tuple, objective: str) -> tuple[Mutation, ...]:
    model = _model(problem, _locations)
    obj = problem.objective(objective)
    out = _objective_mutations(model, obj) + _position_mutations(problem, model, obj)
    # a reading undefined for every state (a speed divided by where it is zero) is no mistake
    return tuple(m for m in out if not sp.sympify(m.value).has(sp.zoo, sp.nan, sp.oo))


class _Reading:
    """One objective being read with mistakes: the right value, and the mutations found so
    far (``out``, in the order they are tried)."""

    def __init__(self, model: Model, obj: Objective, right):
        self.model = model
        self.obj = obj
        self.node = obj.find.node
        self.basis = obj.frame or model.problem.inertial_frame
        self.frame = model.frames[self.basis]
        self.base = model.language
        self.right = right
        self.out: list[Mutation] = []

    def add(self, code: str, interpreter: Interpreter | None, sentence: str, term=None,
            value_node: Node | None = None) -> None:
        """The objective (or ``value_node``) read by ``interpreter``, if it can be read."""
        try:
            value = (interpreter or self.base).value(value_node or self.node)
        except Exception:  # the mistaken reading is undefined (a zero magnitude divided by)
            return
        # a reading equal to the answer is dropped where the values are known (solve)
        if isinstance(value, Vector) != isinstance(self.right, Vector):
            return
        self.out.append(Mutation(self.obj.id, code, _matrix(self.model, value, self.frame),
                                 sentence, None if term is None else self.model.plain(
                                     term.to_matrix(self.frame))))

    def append(self, code: str, value, sentence: str) -> None:
        """A mistaken value worked out directly (not by reading the objective again)."""
        self.out.append(Mutation(self.obj.id, code, self.model.plain(value), sentence))


def _objective_mutations(model: Model, obj: Objective) -> list[Mutation]:
    """Every mistaken reading of one objective, step by step: the composition of motion of
    each point it asks about, another point, another point's position, a path quantity for its
    neighbour, a speed from the components, another frame's unit vectors."""
    try:
        right = model.language.value(obj.find.node)
    except Exception:  # an objective the solver reports as a failure has no mutants
        return []
    r = _Reading(model, obj, right)
    for call in _calls(r.node, ("vel", "acc", "speed", "acc_t", "acc_n", "rho", "tangent",
                                "normal")):
        point = call.args[0]
        if isinstance(point, Call) and point.func == "coincident":
            _material_point(r, call, point, name_of(call.args[1]))
            continue
        if not isinstance(point, Name):
            continue
        in_frame = name_of(call.args[1])
        _relative_motion(r, call, point, in_frame)
        for B, origin in [*moving_frames(model, point.id, in_frame),
                          *described_from(model, point.id, in_frame)]:
            _composition(r, call, point, in_frame, B, origin)
        _other_points(r, call, point, in_frame)
    _other_positions(r)
    _path_quantities(r)
    _speed_readings(r)
    _magnitudes_combined(r)
    _angle_from_other_axis(r)
    _other_bases(r)
    _zero_for_constant_rate(r)
    _balance_without_term(r)
    _constraint_without_term(r)
    _driver_rate(r)
    _gyration_for_radius(r)
    _driver_speed(r)
    _whole_speed_for_rate(r)
    _distance_rate_as_speed(r)
    _rate_relation_inverted(r)
    _start_term_left_out(r)
    return r.out


def _uses_acceleration(call: Call) -> bool:
    return call.func in ("acc", "acc_t", "acc_n", "rho", "normal")


def _composition(r: _Reading, call: Call, point: Name, in_frame: str, B: str,
                 origin: str) -> None:
    """Each term of the composition of motion of the point of ``call`` (``point`` in
    ``in_frame``) described in the moving frame ``B`` (origin ``origin``) dropped, and ω and α
    taken relative to B's parent."""
    model = r.model
    uses_acc = _uses_acceleration(call)
    F = model.frames[in_frame]
    rel = model.positions[point.id] - model.positions[origin]
    omega = model.frames[B].ang_vel_in(F)
    v_rel = rel.dt(model.frames[B])
    if not uses_acc:
        _velocity_terms(r, point, in_frame, B, origin, omega, rel, v_rel)
    parent = model.problem.frames[[f.name for f in model.problem.frames].index(B)].parent
    if parent not in (None, in_frame) and not _zero(model, model.frames[parent].ang_vel_in(F)):
        _relative_omega(r, point, in_frame, B, parent, rel, uses_acc)
    if uses_acc:
        _acceleration_terms(r, point, in_frame, B, origin, omega, rel, v_rel)


def _velocity_terms(r: _Reading, point: Name, in_frame: str, B: str, origin: str, omega,
                    rel, v_rel) -> None:
    """The velocity of the point without the frame origin's velocity, ω × r, or v_rel."""
    P, base = point.id, r.base
    v_true = base.point_velocity(point, in_frame)
    where = f"(ω of frame {B} in {in_frame}, r from {origin} to {P})"
    terms = (("drop_transport_vel", base.point_velocity(Name(origin), in_frame),
              f"the velocity of {origin}, the origin of frame {B}"),
             ("drop_omega_r", omega ^ rel, f"the transport term ω × r {where}"),
             ("drop_relative_vel", v_rel, f"the velocity of {P} relative to frame {B}"))
    for code, term, name in terms:
        if _zero(r.model, term):
            continue
        r.add(code, _Mistaken(base, P, in_frame, velocity=v_true - term),
              f"Your value matches the velocity of {P} computed without {name} = "
              "{term} along " + r.basis + ": include it.", term)
    _omega_r_reversed(r, point, in_frame, omega ^ rel, where)


def _omega_r_reversed(r: _Reading, point: Name, in_frame: str, term, where: str) -> None:
    """The velocity of the point with the transport term ω × r taken in the opposite sense
    (the body's rotation read the other way round)."""
    if _zero(r.model, term):
        return
    v_true = r.base.point_velocity(point, in_frame)
    r.add("omega_reversed", _Mistaken(r.base, point.id, in_frame, velocity=v_true - 2 * term),
          f"Your value matches the velocity of {point.id} with the transport term ω × r "
          f"{where} = {{term}} along {r.basis} taken in the opposite sense: check which way "
          "the body turns.", term)


def _relative_omega(r: _Reading, point: Name, in_frame: str, B: str, parent: str, rel,
                    uses_acc: bool) -> None:
    """The velocity or acceleration of the point with B's angular velocity (and acceleration)
    relative to its parent instead of the absolute ones."""
    model, base, P = r.model, r.base, point.id
    F = model.frames[in_frame]
    omega = model.frames[B].ang_vel_in(F)
    omega_p = model.frames[B].ang_vel_in(model.frames[parent])
    sentence = (f"Your value matches the {{kind}} of {P} computed with the angular "
                f"velocity of frame {B} relative to frame {parent} instead of its "
                f"absolute one in {in_frame}: add the angular velocity of {parent}.")
    if not uses_acc:
        v_true = base.point_velocity(point, in_frame)
        r.add("relative_omega", _Mistaken(base, P, in_frame,
                                          velocity=v_true - (omega ^ rel) + (omega_p ^ rel)),
              sentence.format(kind="velocity"))
        return
    alpha = model.frames[B].ang_acc_in(F)
    alpha_p = model.frames[B].ang_acc_in(model.frames[parent])
    a_true = base.point_acceleration(point, in_frame)
    mistaken = a_true - (alpha ^ rel) - (omega ^ (omega ^ rel)) + (alpha_p ^ rel) \
        + (omega_p ^ (omega_p ^ rel))
    r.add("relative_omega", _Mistaken(base, P, in_frame, acceleration=mistaken),
          sentence.format(kind="acceleration"))


def _acceleration_terms(r: _Reading, point: Name, in_frame: str, B: str, origin: str, omega,
                        rel, v_rel) -> None:
    """The acceleration of the point with each term of the composition dropped (or the
    Coriolis term halved)."""
    model, base, P = r.model, r.base, point.id
    alpha = model.frames[B].ang_acc_in(model.frames[in_frame])
    a_true = base.point_acceleration(point, in_frame)
    a_rel = v_rel.dt(model.frames[B])
    where = f"(ω of frame {B} in {in_frame}, r from {origin} to {P})"
    where_acc = f"(ω and α of frame {B} in {in_frame}, r from {origin} to {P})"
    terms = _acceleration_composition(
        base.point_acceleration(Name(origin), in_frame), alpha, omega, rel, v_rel,
        f"the acceleration of {origin}, the origin of frame {B}", where_acc, where,
        f"(ω of frame {B}, v_rel of {P} in {B})") + [
        ("drop_relative_acc", a_rel, 1, f"the acceleration of {P} relative to frame {B}")]
    for code, term, share, name in terms:
        if _zero(model, term):
            continue
        r.add(code, _Mistaken(base, P, in_frame, acceleration=a_true - term * share),
              f"Your value matches the acceleration of {P} computed without {name} = "
              "{term} along " + r.basis + ": include it.", term)


def _material_point(r: _Reading, call: Call, point: Call, in_frame: str) -> None:
    """The motion of a body's material point (``coincident(C, W)``: the rim point at the
    contact) with a term of its rigid-body formula left out (v = v_G + ω × r, a = a_G + α × r
    + ω × (ω × r), G the origin of the body's frame), or as G's own motion."""
    model, base = r.model, r.base
    if not all(isinstance(a, Name) for a in point.args):
        return
    Q, B = name_of(point.args[0]), name_of(point.args[1])
    spec = next((f for f in model.problem.frames if f.name == B), None)
    if spec is None or spec.origin is None or spec.origin == Q or B == in_frame:
        return
    F, origin = model.frames[in_frame], spec.origin
    omega, alpha = model.frames[B].ang_vel_in(F), model.frames[B].ang_acc_in(F)
    rel = model.positions[Q] - model.positions[origin]
    where = f"(ω of frame {B} in {in_frame}, r from {origin} to {Q})"
    if not _uses_acceleration(call):
        kind, right = "velocity", base.point_velocity(point, in_frame)
        ends = base.point_velocity(Name(origin), in_frame)
        terms = [("drop_transport_vel", ends, f"the velocity of {origin}"),
                 ("drop_omega_r", omega ^ rel, f"the transport term ω × r {where}")]
    else:
        kind, right = "acceleration", base.point_acceleration(point, in_frame)
        ends = base.point_acceleration(Name(origin), in_frame)
        terms = [("drop_transport_acc", ends, f"the acceleration of {origin}"),
                 ("drop_tangential", alpha ^ rel, f"the tangential term α × r {where}"),
                 ("drop_centripetal", omega ^ (omega ^ rel),
                  f"the centripetal term ω × (ω × r) {where}")]
    for code, term, name in terms:
        if _zero(model, term):
            continue
        r.add(code, _Mistaken(base, point, in_frame, **{kind: right - term}),
              f"Your value matches the {kind} of the material point of {B} at {Q} computed "
              f"without {name} = " + "{term} along " + r.basis + ": include it.", term)
    r.add("other_point", _Mistaken(base, point, in_frame, **{kind: ends}),
          f"Your value is the {kind} of {origin}, not of the material point of {B} at {Q}: "
          f"add the terms of the rotation of {B} about {origin}.")


def _relative_motion(r: _Reading, call: Call, point: Name, frame: str) -> None:
    """The motion of the point relative to a moving ``frame`` (a slotted arm) solved from its
    composition in the inertial frame, a term of it left out: v_rel = v - v_O - ω × r and
    a_rel = a - a_O - α × r - ω × (ω × r) - 2 ω × v_rel, each dropped term (or half the
    Coriolis term) added back to the right relative motion."""
    model, base, P = r.model, r.base, point.id
    N = model.problem.inertial_frame
    spec = next((f for f in model.problem.frames if f.name == frame), None)
    if frame == N or spec is None or spec.origin is None or spec.origin == P:
        return
    F, origin = model.frames[frame], spec.origin
    omega, alpha = F.ang_vel_in(model.inertial), F.ang_acc_in(model.inertial)
    rel = model.positions[P] - model.positions[origin]
    v_rel = base.point_velocity(point, frame)
    where = f"(ω of frame {frame} in {N}, r from {origin} to {P})"
    if not _uses_acceleration(call):
        terms = [("drop_transport_vel", base.point_velocity(Name(origin), N), 1,
                  f"the velocity of {origin}, the origin of frame {frame}"),
                 ("drop_omega_r", omega ^ rel, 1, f"the transport term ω × r {where}")]
        kind, right = "velocity", v_rel
    else:
        terms = _acceleration_composition(
            base.point_acceleration(Name(origin), N), alpha, omega, rel, v_rel,
            f"the acceleration of {origin}, the origin of frame {frame}", where, where,
            f"(ω of frame {frame}, v_rel of {P} in it)")
        kind, right = "acceleration", base.point_acceleration(point, frame)
    for code, term, share, name in terms:
        if _zero(model, term):
            continue
        mistaken = right + term * share
        r.add(code, _Mistaken(base, P, frame, **{kind: mistaken}),
              f"Your value matches the {kind} of {P} relative to frame {frame} solved from "
              f"its composition in {N} without {name} = " + "{term} along " + r.basis
              + ": include it.", term)


def _acceleration_composition(a_origin, alpha, omega, rel, v_rel, origin: str, where_acc: str,
                              where: str, coriolis: str) -> list[tuple]:
    """``(code, term, share, name)`` of each term of a = a_O + α × r + ω × (ω × r) +
    2 ω × v_rel (+ a_rel) that a mistake leaves out (``share`` of it: half the Coriolis term)."""
    return [("drop_transport_acc", a_origin, 1, origin),
            ("drop_tangential", alpha ^ rel, 1, f"the tangential term α × r {where_acc}"),
            ("drop_centripetal", omega ^ (omega ^ rel), 1,
             f"the centripetal term ω × (ω × r) {where}"),
            ("drop_coriolis", 2 * (omega ^ v_rel), 1, f"the Coriolis term 2 ω × v_rel {coriolis}"),
            ("coriolis_half", 2 * (omega ^ v_rel), sp.Rational(1, 2),
             "the factor 2 of the Coriolis term 2 ω × v_rel")]


def _other_points(r: _Reading, call: Call, point: Name, in_frame: str) -> None:
    """The velocity or acceleration of another point of the model (or of the point of a
    turning body there) for the point of ``call`` (``point`` in ``in_frame``)."""
    model, base = r.model, r.base
    P = point.id
    kind = "acceleration" if _uses_acceleration(call) else "velocity"
    for Q in model.positions:
        if Q in (P, model.problem.inertial_point):
            continue
        other = _Mistaken(base, P, in_frame,
                          velocity=base.point_velocity(Name(Q), in_frame),
                          acceleration=base.point_acceleration(Name(Q), in_frame))
        r.add("other_point", other, f"Your value matches the {kind} of {Q}, not of {P}: "
              f"use the point the question asks about.")
        for body in model.problem.frames:
            if body.origin is None or body.origin == Q or body.name == in_frame \
                    or _zero(model, model.frames[body.name].ang_vel_in(
                        model.frames[in_frame])):
                continue
            material = Call("coincident", (Name(Q), Name(body.name)))
            other = _Mistaken(base, P, in_frame,
                              velocity=base.point_velocity(material, in_frame),
                              acceleration=base.point_acceleration(material, in_frame))
            r.add("other_point", other, f"Your value matches the {kind} of the point of "
                  f"body {body.name} at {Q}, not of {P}: use the point the question asks "
                  "about.")


def _other_positions(r: _Reading) -> None:
    """The position of another point for the point a ``pos`` asks about."""
    for call in _calls(r.node, ("pos",)):
        point, origin = call.args
        if not isinstance(point, Name):
            continue
        for Q in r.model.positions:
            if Q in (point.id, r.model.problem.inertial_point) or Name(Q) == origin:
                continue
            r.add("other_point", _Mistaken(r.base, point.id, "",
                                           position=r.model.positions[Q]),
                  f"Your value matches the position of {Q}, not of {point.id}: use the point "
                  "the question asks about.")


def _call_of(node: Node, func: str) -> Call | None:
    """``node`` if it is a call of ``func``."""
    return node if isinstance(node, Call) and node.func == func else None


def _path_quantities(r: _Reading) -> None:
    """A path quantity for its neighbour: a_t or a_n for |a|, their sum for |a|, |a| for a
    component, ρ from |a|."""
    node = r.node
    if not isinstance(node, Call):
        return
    top = node.func
    inner = _call_of(node.args[0], "acc") if top == "mag" else None
    if inner is not None:
        args = inner.args
        r.add("acc_t_for_acc", None, "Your value is the tangential acceleration a_t = dv/dt "
              "alone; the magnitude of the acceleration is √(a_t² + a_n²).",
              value_node=Call("acc_t", args))
        r.add("acc_n_for_acc", None, "Your value is the normal acceleration v²/ρ alone; the "
              "magnitude of the acceleration is √(a_t² + a_n²).",
              value_node=Call("acc_n", args))
        r.add("mag_as_sum", None, "Your value adds the tangential and normal accelerations; "
              "the magnitude of the acceleration is √(a_t² + a_n²).",
              value_node=Bin("+", Call("acc_t", args), Call("acc_n", args)))
    if top in ("acc_t", "acc_n"):
        r.add(f"acc_for_{top}", None, f"Your value is the magnitude of the whole "
              f"acceleration; the {'tangential' if top == 'acc_t' else 'normal'} component "
              "was asked.", value_node=Call("mag", (Call("acc", node.args),)))
    if top == "rho":
        in_frame = name_of(node.args[1])
        v = r.base.point_velocity(node.args[0], in_frame)
        a = r.base.point_acceleration(node.args[0], in_frame)
        if not _zero(r.model, v ^ a):
            r.append("rho_formula", (v & v) / a.magnitude(), "Your value is v²/|a|; the "
                     "radius of curvature is v²/a_n, with the normal part a_n of the "
                     "acceleration only.")
    if top in ("rho", "acc_n"):
        _curvature_without_slope(r, node)


def _curvature_without_slope(r: _Reading, node: Call) -> None:
    """On a path given as ``y = f(x)`` (a position constraint: one coordinate equal to an
    expression of one other), the radius of curvature ρ = (1 + y′²)^(3/2)/|y″| taken as
    1/|y″| (the slope term left out) or with the exponent 1/2: in ρ itself, and in the
    normal acceleration v²/ρ."""
    coordinates = {c.name for c in r.model.problem.coordinates}
    for c in r.model.problem.constraints:
        if c.level is not ConstraintLevel.POSITION or not isinstance(c.lhs.node, Name) \
                or c.lhs.node.id not in coordinates:
            continue
        along = {n.id for n in walk(c.rhs.node) if isinstance(n, Name)} & coordinates
        if len(along) != 1 or c.lhs.node.id in along:
            continue
        (x,) = along
        y, x_of_t = c.lhs.node.id, r.base.value(Name(x))
        if not _cartesian(r, node.args[0], x_of_t, r.base.value(c.lhs.node)):
            continue  # a polar path r = f(θ) has another formula
        f = r.base.value(c.rhs.node)
        slope, bend = sp.diff(f, x_of_t), sp.diff(f, x_of_t, 2)
        if identically_zero(r.model.plain(slope)) or identically_zero(r.model.plain(bend)):
            continue  # a straight path, or one whose slope is zero here: no slope term
        v = r.base.point_velocity(node.args[0], name_of(node.args[1]))
        for rho, how in ((1 / sp.Abs(bend), f"1/|{y}''|, without the slope term"),
                         (sp.sqrt(1 + slope ** 2) / sp.Abs(bend),
                          f"(1 + {y}'²)^(1/2)/|{y}''|, with the exponent 1/2")):
            value = rho if node.func == "rho" else (v & v) / rho
            r.append("rho_without_slope", value, f"Your value takes the radius of curvature "
                     f"of the path {c.lhs.text} = {c.rhs.text} as {how}: ρ = (1 + "
                     f"{y}'²)^(3/2)/|{y}''|, where {y}' = d{y}/d{x}.")


def _cartesian(r: _Reading, point: Node, x, y) -> bool:
    """Whether ``point``'s position moves along two fixed perpendicular unit vectors as the
    coordinates ``x`` and ``y`` change (its rectangular coordinates)."""
    if not isinstance(point, Name) or point.id not in r.model.positions:
        return False
    position, N = r.model.positions[point.id], r.model.inertial
    ex, ey = (position.diff(q, N) for q in (x, y))
    return all(identically_zero(r.model.plain(value)) for value in (
        (ex & ex) - 1, (ey & ey) - 1, ex & ey)) and all(
        identically_zero(r.model.plain(sp.diff(part, q)))
        for e in (ex, ey) for part in e.to_matrix(N) for q in (x, y))


def _speed_readings(r: _Reading) -> None:
    """A speed from the sum of the velocity's components, or one component alone."""
    node = r.node
    if not isinstance(node, Call):
        return
    inner = _call_of(node.args[0], "vel") if node.func == "mag" else None
    if node.func == "speed":
        args = node.args
    elif inner is not None:
        args = inner.args
    else:
        return
    v = r.base.point_velocity(args[0], name_of(args[1]))
    x, y, z = v.to_matrix(r.frame)
    r.append("mag_as_sum", x + y + z, "Your value adds the components of the velocity; the "
             "speed is the square root of the sum of their squares.")
    for G, frame in r.model.frames.items():
        parts = [v & unit for unit in (frame.x, frame.y, frame.z)]
        for axis, part in zip("xyz", parts):
            if not _zero(r.model, part):
                r.append("component_for_speed", part, f"Your value is only the {G}.{axis} "
                         "component of the velocity; the speed is the magnitude of the whole "
                         "velocity.")
        if sum(not _zero(r.model, part) for part in parts) > 1:
            r.append("mag_as_sum", sum(sp.Abs(part) for part in parts),
                     f"Your value adds the sizes of the velocity's components along {G} (as "
                     "|r'| + |r θ'|); the speed is the square root of the sum of their squares.")
    _terms_added(r, args[0], name_of(args[1]))
    _midpoint_speeds(r, args[0], name_of(args[1]))


def _midpoint_speeds(r: _Reading, point: Node, in_frame: str) -> None:
    """The speed of the midpoint of two points (a rod's centre) taken as the mean of their
    speeds: their velocities' mean, as vectors, is its velocity."""
    model, P = r.model, name_of(point)
    others = [Q for Q in model.positions if Q not in (P, model.problem.inertial_point)]
    for i, A in enumerate(others):
        for B in others[i + 1:]:
            if not _zero(model, 2 * model.positions[P] - model.positions[A]
                         - model.positions[B]):
                continue
            speeds = [r.base.point_velocity(Name(Q), in_frame).magnitude() for Q in (A, B)]
            r.append("mag_as_sum", (speeds[0] + speeds[1]) / 2,
                     f"Your value is the mean of the speeds of {A} and {B}; the velocity of "
                     f"their midpoint {P} is the mean of their velocities as vectors, then "
                     "its magnitude.")


def _terms_added(r: _Reading, point: Node, in_frame: str) -> None:
    """A speed taken as the sum of the sizes of the terms of its composition of motion in a
    moving frame (the wind's speed added to the airspeed, v_O + |ω × r| + |v_rel|), as if they
    were along one line."""
    model, P = r.model, name_of(point)
    F = model.frames[in_frame]
    for spec in model.problem.frames:
        if spec.name == in_frame or spec.origin is None or spec.origin == P:
            continue
        B = model.frames[spec.name]
        rel = model.positions[P] - model.positions[spec.origin]
        terms = [t for t in (r.base.point_velocity(Name(spec.origin), in_frame),
                             B.ang_vel_in(F) ^ rel, rel.dt(B)) if not _zero(model, t)]
        if len(terms) > 1:
            r.append("mag_as_sum", sum(t.magnitude() for t in terms),
                     f"Your value adds the speeds of the terms of the velocity of {P} seen "
                     f"from frame {spec.name} (the velocity of its origin {spec.origin}, ω × r, "
                     "the relative velocity) as numbers; they are vectors along different "
                     "lines: add them as vectors.")
            # two terms at right angles add by Pythagoras; at any other angle they do not
            r.append("mag_as_sum", sp.sqrt(sum(t & t for t in terms)),
                     f"Your value adds the speeds of the terms of the velocity of {P} seen "
                     f"from frame {spec.name} as if they were at right angles (√(a² + b²)); "
                     "they are not here: add them as vectors.")


def _magnitudes_combined(r: _Reading) -> None:
    """The magnitude of a sum or difference of two vectors taken as the sum, or the
    difference, of their magnitudes (speeds added or subtracted as numbers)."""
    node = r.node
    if not (isinstance(node, Call) and node.func == "mag" and isinstance(node.args[0], Bin)
            and node.args[0].op in "+-"):
        return
    left, right = node.args[0].left, node.args[0].right
    try:
        a, b = (r.base.value(Call("mag", (side,))) for side in (left, right))
    except Exception:  # a side that is not a vector
        return
    names = f"{to_text(left)} and {to_text(right)}"
    sentence = (f"Your value {{verb}} the magnitudes of {names}; the magnitude of their "
                f"{'sum' if node.args[0].op == '+' else 'difference'} comes from the components "
                "(the vectors are not along one line).")
    r.append("mag_as_sum", a + b, sentence.format(verb="adds"))
    r.append("mag_as_sum", sp.Abs(a - b), sentence.format(verb="subtracts"))


def _angle_from_other_axis(r: _Reading) -> None:
    """An angle asked as ``atan2(a, b)`` read from the other leg, ``atan2(b, a)``: sin and cos
    exchanged (the complement of the angle in its quadrant)."""
    node = r.node
    if isinstance(node, Call) and node.func == "atan2" and len(node.args) == 2:
        r.add("angle_complement", None, "Your value measures the angle from the other axis "
              "(sin and cos exchanged, its complement): check which leg of the triangle lies "
              "along the side the angle is measured from.",
              value_node=Call("atan2", (node.args[1], node.args[0])))


def _other_bases(r: _Reading) -> None:
    """The right vector's components along another frame's unit vectors."""
    if not isinstance(r.right, Vector) or not r.obj.frame:
        return
    for G, other in r.model.frames.items():
        if G == r.obj.frame or _zero(r.model, r.right - _relabel(r.right, other, r.frame)):
            continue
        r.append("other_basis", r.right.to_matrix(other),
                 f"Your components are those of the right vector along frame {G}'s unit "
                 f"vectors; give them along frame {r.obj.frame}'s.")


_ACCELERATIONS = ("acc", "acc_t", "angacc")


def _zero_for_constant_rate(r: _Reading) -> None:
    """An acceleration (a second derivative, ``acc``, ``angacc``) answered zero because a
    given rate is constant (``q'' = 0`` given with ``q'`` not zero): the driver's steady rate
    taken for no acceleration anywhere."""
    givens = {to_text(g.key.node): g for g in r.model.problem.givens}
    steady = [key for key, g in givens.items() if key.endswith("''") and g.si == 0
              and key[:-1] in givens and givens[key[:-1]].si != 0]
    asks = any(isinstance(n, Prime) and n.order >= 2 for n in walk(r.node)) \
        or next(_calls(r.node, _ACCELERATIONS), None) is not None
    if not steady or not asks:
        return
    zero = sp.zeros(3, 1) if isinstance(r.right, Vector) else sp.S.Zero
    rates = ", ".join(f"{k[:-1]} = {givens[k[:-1]].text}" for k in steady)
    r.append("zero_for_constant_rate", zero, f"Your value is zero, as if the constant rate "
             f"({rates}) meant no acceleration: a steady rate makes its own second derivative "
             "zero, not the other accelerations (their centripetal and coupled terms).")


def _balance_without_term(r: _Reading) -> None:
    """A coordinate's second derivative ``q''`` that a body's force balance gives, read
    from that balance with a term of the body's acceleration relative to a turning frame left
    out (the centripetal ω × (ω × r), the Coriolis 2 ω × v_rel or half of it): along the
    direction in which ``q`` moves the body, ``q''`` is then off by that term's share."""
    node, model = r.node, r.model
    problem = model.problem
    if problem.dynamics is None or not (isinstance(node, Prime) and node.order == 2) \
            or node.id not in {c.name for c in problem.coordinates}:
        return
    q = model.language.value(Name(node.id))
    N = model.inertial
    for body in dynamics_of(problem).bodies:
        for B, origin in moving_frames(model, body.centre, problem.inertial_frame):
            frame = model.frames[B]
            rel = model.positions[body.centre] - model.positions[origin]
            along = rel.diff(q, frame)  # the direction q moves the centre in B
            size = along & along
            if identically_zero(model.plain(size)):
                continue
            omega = frame.ang_vel_in(N)
            v_rel = rel.dt(frame)
            where = f"(ω of frame {B}, r from {origin} to {body.centre})"
            for code, term, name in _turning_terms(omega, rel, v_rel, where):
                share = (term & along) / size
                if identically_zero(model.plain(share)):
                    continue
                # the balance fixes the acceleration along the motion: q'' (its relative
                # part) takes up the term left out
                r.append(code, r.right + share,
                         f"Your value is {textbook(to_text(node))} from the force balance "
                         f"of {body.name} with {name} left out of its acceleration: along the "
                         f"direction in which {textbook(node.id)} moves it in frame {B}, the "
                         "balance fixes the whole acceleration, that term included.")


def _turning_terms(omega, rel, v_rel, where: str) -> tuple[tuple[str, Any, str], ...]:
    """``(code, term, name)`` of the terms of a point's acceleration in a turning frame that
    a mistake leaves out of it: ω × (ω × r), 2 ω × v_rel, and ω × v_rel (the 2 forgotten)."""
    return (("drop_centripetal", omega ^ (omega ^ rel),
             f"the centripetal term ω × (ω × r) {where}"),
            ("drop_coriolis", 2 * (omega ^ v_rel), f"the Coriolis term 2 ω × v_rel {where}"),
            ("coriolis_half", omega ^ v_rel, "the factor 2 of the Coriolis term 2 ω × v_rel"))


def _constraint_without_term(r: _Reading) -> None:
    """A coordinate's second derivative solved from the position constraints differentiated
    twice (a slotted arm's θ'', a tracked airplane's θ'') with the centripetal or Coriolis
    term left out of the acceleration of a side described in a turning frame (``s S.x``):
    ``J Δ = T`` gives each unknown second derivative's change ``Δ``, ``J`` the constraints'
    partial derivatives in the unknown coordinates."""
    node, model = r.node, r.model
    problem = model.problem
    if problem.dynamics is not None or not (isinstance(node, Prime) and node.order == 2):
        return
    given = {to_text(g.key.node) for g in problem.givens}
    unknown = [c.name for c in problem.coordinates if f"{c.name}''" not in given]
    if node.id not in unknown:
        return
    lang, N = model.language, model.inertial
    qs = [lang.value(Name(c)) for c in unknown]
    rows: list[list] = []
    sides: list[tuple[str, int, Vector, list[int]]] = []
    for c in problem.constraints:
        if c.level is not ConstraintLevel.POSITION:
            continue
        try:
            left, right = lang.value(c.lhs.node), lang.value(c.rhs.node)
        except Exception:  # a side the kinematic language cannot read alone
            return
        vector = isinstance(left, Vector) or isinstance(right, Vector)
        difference = (left - right).to_matrix(N) if vector else [left - right]
        at = []
        for component in difference:
            row = [model.plain(sp.diff(component, q)) for q in qs]
            if any(not identically_zero(x) for x in row):
                at.append(len(rows))
                rows.append(row)
            else:
                at.append(-1)
        if vector:
            sides += [(c.name, sign, side, at) for sign, side in ((1, left), (-1, right))
                      if isinstance(side, Vector)]
    if len(rows) != len(qs):
        return
    J = sp.Matrix(rows)
    for name, sign, side, at in sides:
        for B, origin in moving_frames(model, "", problem.inertial_frame):
            if all(frame != model.frames[B] for _, frame in side.args):
                continue
            frame = model.frames[B]
            rel = side - model.positions[origin]
            for code, term, words in _turning_terms(
                    frame.ang_vel_in(N), rel, rel.dt(frame),
                    f"(ω of frame {B}, r from {origin})"):
                b = sp.zeros(len(rows), 1)
                for i, component in zip(at, term.to_matrix(N)):
                    if i >= 0:
                        b[i] = sign * model.plain(component)
                if all(identically_zero(x) for x in b):
                    continue
                try:
                    change = J.LUsolve(b)[unknown.index(node.id)]
                except (ValueError, ZeroDivisionError):  # a singular J: no unique reading
                    return
                if identically_zero(sp.simplify(change)):
                    continue
                r.append(code, r.right + change,
                         f"Your value is {textbook(to_text(node))} solved from the constraint "
                         f"{name} with {words} left out of the acceleration of its side "
                         f"described in frame {B}: include it.")


def _other_given_rates(r: _Reading, coordinates: set[str]) -> Iterator[tuple[Prime, Prime, Any]]:
    """``(asked, key, given)`` for each nonzero given rate ``key`` of another of
    ``coordinates``, of the order of the rate ``asked`` of one of them that the objective is."""
    node = r.node
    if not (isinstance(node, Prime) and node.id in coordinates):
        return
    for g in r.model.problem.givens:
        key = g.key.node
        if isinstance(key, Prime) and key.order == node.order and key.id in coordinates \
                and key.id != node.id and g.si != 0:
            yield node, key, g


def _driver_rate(r: _Reading) -> None:
    """An angle's rate that the constraints fix (a slotted arm's θ', a coupler's) answered
    with the given rate of another angle (the crank's φ'): the connected body taken to turn
    with the driver."""
    angles = {c.name for c in r.model.problem.coordinates if c.unit in ("rad", "deg")}
    for node, key, g in _other_given_rates(r, angles):
        r.append("driver_rate", sp.Float(g.si), f"Your value is {to_text(key)} = "
                 f"{g.text}, the given rate of {key.id}, as if {node.id} turned "
                 f"with it: {to_text(node)} follows from the constraints that connect them.")


def _driver_speed(r: _Reading) -> None:
    """A length's rate that the constraints fix (a slider's s' at the far end of a rod, a
    crate's y' on a rope) answered with the given speed of another length (the driver's a'),
    in the objective's sense: the mechanism taken to move as a whole with its driver."""
    problem = r.model.problem
    lengths = {c.name for c in problem.coordinates if same_dimension(c.unit, "m")}
    for node, key, g in _other_given_rates(r, lengths):
        if _same_point(problem, node.id, key.id):
            continue  # the whole speed for a component: another family's reading
        r.append("driver_speed", sp.Float(abs(g.si)) * sp.sign(r.right),
                 f"Your value is {to_text(node)} = {g.text.lstrip('-')} in size, the given "
                 f"rate of {key.id}, as if the mechanism moved as a whole: {to_text(node)} "
                 "follows from the constraints that connect them.")


def _whole_speed_for_rate(r: _Reading) -> None:
    """A coordinate's rate that a position constraint fixes where one side locates a point
    by coordinates of given rates (its velocity known) and the other by this coordinate among
    others (x N.x + h N.y = r E.x, a pin in a turning slot): the point's whole speed taken
    along the direction this coordinate moves it (ṙ = v, θ̇ = v/r) where only the velocity's
    component along it counts. In the answer's sense; only where the other coordinates move
    the point at right angles to it, as polar ones do."""
    node, model = r.node, r.model
    problem = model.problem
    coordinates = {c.name for c in problem.coordinates}
    if not (isinstance(node, Prime) and node.order == 1 and node.id in coordinates):
        return
    rated = {g.key.node.id for g in problem.givens
             if isinstance(g.key.node, Prime) and g.key.node.order == 1}
    lang, N = model.language, model.inertial
    symbols = {c: lang.value(Name(c)) for c in coordinates}
    rate, name = textbook(to_text(node)), textbook(node.id)
    for c in problem.constraints:
        if c.level is not ConstraintLevel.POSITION:
            continue
        try:
            sides = [lang.value(c.lhs.node), lang.value(c.rhs.node)]
        except Exception:  # a side the kinematic language cannot read alone
            continue
        if not all(isinstance(side, Vector) for side in sides):
            continue
        moved = [{q for q, s in symbols.items() if not _zero(model, side.diff(s, N))}
                 for side in sides]
        for i in (0, 1):
            side, own, known, by = sides[i], moved[i], sides[1 - i], moved[1 - i]
            if node.id not in own or not by or not by <= rated - own:
                continue
            along = side.diff(symbols[node.id], N)
            if any(not _zero(model, along & side.diff(symbols[q], N)) for q in own - {node.id}):
                continue
            r.append("speed_for_component", known.dt(N).magnitude() / along.magnitude()
                     * sp.sign(model.plain(r.right)),
                     f"Your value is {rate} with the whole speed of the point that "
                     f"{c.name} places taken along the direction in which {name} moves it; "
                     f"only the part of its velocity along that direction gives {rate}, the "
                     "rest is across it.")


def _distance_rate_as_speed(r: _Reading) -> None:
    """A rate that scalar position constraints fix where one writes a distance as
    sqrt(u² + v² ...) of coordinates of given rates (a rope's slant sqrt(x² + h²) from a pulley
    to a truck's hitch): the distance's rate taken as the whole speed of its moving end,
    sqrt(u̇² + v̇² ...), in its own sense, as if the end moved along the distance (the slant
    ignored). ``J Δ = b`` gives each unknown rate's change, ``J`` the constraints' partial
    derivatives in the unknown coordinates."""
    node, model = r.node, r.model
    problem = model.problem
    given = {to_text(g.key.node) for g in problem.givens}
    unknown = [c.name for c in problem.coordinates if f"{c.name}'" not in given]
    if not (isinstance(node, Prime) and node.order == 1 and node.id in unknown):
        return
    lang = model.language
    symbols = {c.name: lang.value(Name(c.name)) for c in problem.coordinates}
    t = dynamicsymbols._t
    rows, changes = [], []
    for c in (c for c in problem.constraints if c.level is ConstraintLevel.POSITION):
        try:
            f = lang.value(c.lhs.node) - lang.value(c.rhs.node)
        except Exception:  # a vector constraint, or a side the language cannot read alone
            return
        if isinstance(f, Vector):
            return
        rows.append([model.plain(sp.diff(f, symbols[q])) for q in unknown])
        for call in (n for side in (c.lhs, c.rhs) for n in _calls(side.node, ("sqrt",))):
            legs = [lang.value(leg.left) for _, leg in additive_terms(call.args[0])
                    if isinstance(leg, Bin) and leg.op in ("**", "^") and leg.right == Num("2")]
            moved = names(call) & set(symbols)
            if len(legs) != len(additive_terms(call.args[0])) or not moved \
                    or any(f"{q}'" not in given for q in moved):
                continue
            distance, held = lang.value(call), sp.Dummy()
            rate = sp.diff(distance, t)
            speed = sp.sqrt(sum(sp.diff(leg, t) ** 2 for leg in legs))
            weight = sp.diff(f.subs(distance, held), held)
            changes.append((len(rows) - 1, model.plain(weight * (sp.sign(rate) * speed - rate)),
                            to_text(call)))
    if len(rows) != len(unknown):
        return
    J, rate = sp.Matrix(rows), textbook(to_text(node))
    for at, change, text in changes:
        b = sp.zeros(len(rows), 1)
        b[at] = -change
        try:
            delta = J.LUsolve(b)[unknown.index(node.id)]
        except (ValueError, ZeroDivisionError):  # a singular J: no unique reading
            return
        r.append("speed_for_component", r.right + delta,
                 f"Your value is {rate} with the rate of the distance {textbook(text)} taken "
                 "as the whole speed of its moving end, as if the end moved along that line; "
                 "only the part of the end's velocity along the line changes the distance.")


def _same_point(problem: Problem, asked: str, driver: str) -> bool:
    """Whether a constraint locates one point two ways, one side by ``driver`` alone among
    the coordinates, the other with ``asked`` (x N.x + h N.y = r E.x: r' is a component of the
    driver's own velocity there, not the rate of another part of a mechanism)."""
    coordinates = {c.name for c in problem.coordinates}
    frames = {f.name: f for f in problem.frames}

    def turning(frame: str | None) -> set[str]:  # the angles a frame turns by, from N
        spec = frames.get(frame or "")
        return set() if spec is None else turning(spec.parent).union(
            *(names(rot.angle.node) for rot in spec.rotations))

    def located_by(node: Node) -> set[str]:
        axes = {n.base for n in walk(node) if isinstance(n, Attr)}
        return (names(node) | set().union(*map(turning, axes))) & coordinates

    for c in problem.constraints:
        sides = (located_by(c.lhs.node), located_by(c.rhs.node))
        if any(one == {driver} and asked in other for one, other in (sides, sides[::-1])):
            return True
    return False


def _angle_rate(r: _Reading) -> Prime | None:
    """The rate of an angle the objective asks for (θ', |θ'|, -θ''), if that is all it asks."""
    node = r.node
    inner = node.args[0] if isinstance(node, Call) and node.func == "abs" else node
    inner = inner.operand if isinstance(inner, Unary) else inner
    angles = {c.name for c in r.model.problem.coordinates if c.unit in ("rad", "deg")}
    return inner if isinstance(inner, Prime) and inner.id in angles else None


def _linking_lengths(problem: Problem, angle: str) -> set[str]:
    """The length parameters written with ``angle`` in a constraint (r in y = r φ)."""
    lengths = {q.name for q in problem.parameters if same_dimension(q.unit, "m")}
    return {n for c in problem.constraints
            for n in (names(c.lhs.node) | names(c.rhs.node)) if angle in names(c.lhs.node)
            | names(c.rhs.node)} & lengths


def _gyration_for_radius(r: _Reading) -> None:
    """A body's angular rate ω = v/r answered as v/k: the radius of gyration k (a length of the
    body's inertia only) read for the length r that links its angle to a point's motion in a
    constraint (a drum's radius under its cord, a wheel's rolling radius)."""
    problem, inner = r.model.problem, _angle_rate(r)
    if problem.dynamics is None or inner is None:
        return
    lengths = {q.name for q in problem.parameters if same_dimension(q.unit, "m")}
    linked = _linking_lengths(problem, inner.id)
    frames = {f.name: f for f in problem.frames}
    for body in dynamics_of(problem).bodies:
        spec = frames.get(body.frame or "")
        if spec is None or not any(names(rot.angle.node) == {inner.id}
                                   for rot in spec.rotations):
            continue
        for part in body.parts:
            if not isinstance(part.shape, Explicit):
                continue
            inertia = {n for _, e in part.shape.entries for n in names(e.node)} & lengths
            for k in sorted(inertia - linked):
                for length in sorted(linked - inertia):
                    ratio = r.model.symbols.params[length] / r.model.symbols.params[k]
                    r.append("gyration_for_radius", r.right * ratio, f"Your value takes "
                             f"{to_text(inner)} with the radius of gyration {k} of {body.name} "
                             f"for the length {length} that links it to the motion: {k} only "
                             f"gives the moment of inertia I = m {k}^2.")


def _rate_relation_inverted(r: _Reading) -> None:
    """An angle's rate from a point's, ω = v/r, answered as v r (α = a r): the length that
    links them in a constraint multiplies where it divides. The student multiplies the numbers
    as given, so r is taken in its given unit."""
    inner = _angle_rate(r)
    if inner is None:
        return
    givens = {g.key.node.id: g for g in r.model.problem.givens
              if isinstance(g.key.node, Name) and g.value != 0}
    for length in sorted(_linking_lengths(r.model.problem, inner.id) & set(givens)):
        g = givens[length]
        symbol = r.model.symbols.params[length]
        r.append("rate_relation_inverted", r.right * symbol**2 * sp.Float(g.value / g.si)**2,
                 f"Your value multiplies by {length} = {g.text} where the relation divides: "
                 f"{to_text(inner)} is the point's rate divided by {length}, not times it.")


def _start_term_left_out(r: _Reading) -> None:
    """A length coordinate the motion reaches, answered without a term of its value at the
    start (r = R + h: the height h above the surface for the distance r from the centre)."""
    problem, node = r.model.problem, r.node
    if problem.dynamics is None or not isinstance(node, Name):
        return
    lengths = {c.name for c in problem.coordinates if same_dimension(c.unit, "m")}
    starts = getattr(dynamics_of(problem).analysis, "start", ())
    for start in starts:
        if node.id not in lengths or start.value is None or start.key.node != node:
            continue
        terms = additive_terms(start.value.node)
        for sign, term in terms if len(terms) > 1 else ():
            if isinstance(term, Name) and term.id in r.model.symbols.params:
                r.append("position_term", r.right - sign * r.model.symbols.params[term.id],
                         f"Your value is {node.id} without {term.id}, a term of its start "
                         f"{node.id} = {start.value.text}: {node.id} is measured from the "
                         f"origin, so {term.id} stays in it.")


def _position_mutations(problem: Problem, model: Model, obj: Objective) -> list[Mutation]:
    """The objective with one term of a point's position left out (half a side for half a
    diagonal, the offset of a pin forgotten)."""
    out = []
    for spec in problem.points:
        terms = additive_terms(spec.position.node) if spec.position is not None else []
        if len(terms) < 2:
            continue
        for i, (_, dropped) in enumerate(terms):
            rest = sum_of_terms(terms[:i] + terms[i + 1:])
            text = to_text(rest)
            points = tuple(replace(p, position=Expr(text, rest)) if p.name == spec.name else p
                           for p in problem.points)
            try:
                mutated = build(replace(problem, points=points))
                value = _matrix(mutated, mutated.language.value(obj.find.node),
                                mutated.frames[obj.frame or problem.inertial_frame])
            except Exception:  # the shortened description is not a position
                continue
            out.append(Mutation(obj.id, "position_term", value,
                                f"Your value matches what {spec.name} placed at {text} from "
                                f"{spec.origin} gives, without the term {to_text(dropped)} of "
                                f"its position: check the distance from {spec.origin} to "
                                f"{spec.name}."))
    return out


def _relabel(vector: Vector, source, target) -> Vector:
    """``vector``'s components along ``source`` read as components along ``target``."""
    x, y, z = vector.to_matrix(source)
    return x * target.x + y * target.y + z * target.z


def moving_frames(model: Model, point: str, frame: str):
    """Frames (other than ``frame``) with an origin and an angular velocity in ``frame``, or
    an origin moving in it (the air carried by the wind), in which ``point`` is described: a
    composition of motion applies."""
    for spec in model.problem.frames:
        if spec.name == frame or spec.origin is None or spec.origin == point:
            continue
        if _zero(model, model.frames[spec.name].ang_vel_in(model.frames[frame])) and _zero(
                model, model.language.point_velocity(Name(spec.origin), frame)):
            continue
        yield spec.name, spec.origin


def described_from(model: Model, point: str, frame: str) -> list[tuple[str, str]]:
    """``(G, Q)`` where ``point`` is located from the point ``Q`` along the unit vectors of
    one frame ``G`` that has no origin of its own and turns in ``frame`` (a car on a ramp,
    R F.x from the ramp's centre): its motion is composed in ``G`` about ``Q`` as in a
    frame with that origin (:func:`moving_frames`)."""
    spec = next((p for p in model.problem.points if p.name == point), None)
    if spec is None or spec.origin is None or spec.position is None:
        return []
    axes = {n.base for n in walk(spec.position.node) if isinstance(n, Attr)}
    frames = {f.name: f for f in model.problem.frames}
    if len(axes) != 1 or next(iter(axes)) not in frames:
        return []
    G = next(iter(axes))
    if G == frame or frames[G].origin is not None \
            or _zero(model, model.frames[G].ang_vel_in(model.frames[frame])):
        return []
    return [(G, spec.origin)]


def _calls(node: Node, names: tuple[str, ...]) -> Iterator[Call]:
    if isinstance(node, Call):
        if node.func in names:
            yield node
        for arg in node.args:
            yield from _calls(arg, names)
    for child in (getattr(node, "left", None), getattr(node, "right", None),
                  getattr(node, "operand", None)):
        if child is not None:
            yield from _calls(child, names)


def _zero(model: Model, vector) -> bool:
    if isinstance(vector, sp.MatrixBase):
        return all(identically_zero(c) for c in vector)
    if isinstance(vector, Vector):
        return all(identically_zero(model.plain(c)) for c in vector.to_matrix(model.inertial))
    return identically_zero(model.plain(vector))


def _matrix(model: Model, value, frame):
    if isinstance(value, Vector):
        return model.plain(value.to_matrix(frame))
    return model.plain(value)
