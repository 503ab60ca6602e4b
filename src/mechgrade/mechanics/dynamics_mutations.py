"""Conceptual mistakes of kinetics applied to a problem's bodies and loads.

Each family looks at the model for its ingredient (a gravity load, a body turning about a point
that does not move, a kinetic-friction contact, a coefficient of restitution, a string...) and,
only where it finds it, makes a mistaken copy of the frozen :class:`~mechgrade.spec.model.Problem`
(``dataclasses.replace``: the gravity load dropped, the inertia about the mass centre used at the
pivot, the friction turned round, ``e`` replaced) for the solver to solve again, or a mistaken
reading of an objective (a reaction read as a weight, a kinetic energy without its rotational
part) for the solver to read in the right model. A :class:`DynamicsMutation` carries its family
``code`` (for partial-credit settings), a sentence in which ``{term}`` stands for the value of
the term it names (``term``, read in the right model, in ``term_unit``), and ``step``, the
section of the worked solution (:func:`mechgrade.mechanics.dynamics.kinetics_derivation`) where
the mistake happens.

The families are registered in :data:`FAMILIES`, one function each.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
>>> [(m.code, m.step) for m in dynamics_mutations(problem)][4:7]
[('mass_for_weight', 'Free-body loads'), ('weight_for_mass', 'Bodies'), ('central_inertia_at_pivot', 'Bodies')]
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Callable, Iterator

from sympy.physics.vector import Vector

from ..expressions.notation import textbook
from ..expressions.syntax import (Attr, Bin, Call, Name, Node, Num, Prime, Unary, name_of,
                                  parse, to_text, walk)
from ..spec.dynamics import (GROUND, Act, Body, Disk, Dynamics, Explicit, Force, Friction,
                             LoadKind,
                             Impulse, Integration, KineticFriction, Part, Reaction, Restitution,
                             Ring, Shape, Shell, Sphere, Start, StaticFriction, WorkEnergy,
                             dynamics_of, instant_of_objective, unchecked)
from ..spec.language import FUNCTIONS
from ..spec.constraint_mutations import strands_once
from ..spec.model import Constraint, ConstraintLevel, Expr, ObjectiveKind, Problem
from ..spec.solving import given_unit
from .bodies import SHAPES
from .build import Model, build
from .mutations import moving_frames
from .symbols import identically_zero

LOADS, BODIES, BALANCES, OBJECTIVES = ("Free-body loads", "Bodies", "Momentum balances",
                                       "Objectives in the model's quantities")


@dataclass(frozen=True)
class DynamicsMutation:
    """One mistaken model (``problem``, solved again: every objective is mistaken) or mistaken
    reading (``readings``: objective id and the expression read instead, in the right model).

    ``sentence`` names the mistake, with ``{term}`` where the value of ``term`` (an expression
    of the right model, in ``term_unit``) goes; ``step`` is the write-up section where the
    mistake happens."""

    code: str
    sentence: str
    step: str
    problem: Problem | None = None
    readings: tuple[tuple[str, Expr], ...] = ()
    term: Expr | None = None
    term_unit: str = "1"


def dynamics_mutations(problem: Problem) -> tuple[DynamicsMutation, ...]:
    """Every family's mutations of ``problem`` (none without bodies and loads)."""
    if problem.dynamics is None:
        return ()
    return _mutations(problem)


@lru_cache(maxsize=64)
def _mutations(problem: Problem) -> tuple[DynamicsMutation, ...]:
    model = build(problem)
    return tuple(m for family in FAMILIES for m in family(problem, model))


# ---------------------------------------------------------------------------- helpers


def _expr(text: str) -> Expr:
    return Expr(text, parse(text, functions=FUNCTIONS))


def _mistaken(problem: Problem, dynamics: Dynamics, without: tuple[str, ...] = ()) -> Problem:
    """A mistaken copy: the author's tests and mistakes dropped, static friction an unknown
    force without its bound and the loads unchecked (a student with a mistaken model checks
    neither: mechanics.loads), and the
    objectives that call a function in ``without`` left out (the mistake is not theirs)."""
    objectives = tuple(replace(o, expect=None, mistakes=()) for o in problem.objectives
                       if not any(next(_calls(o.find.node, f), None) for f in without))
    return replace(problem, objectives=objectives, warnings=(), dynamics=unchecked(dynamics))


def unchanged_copy(problem: Problem) -> Problem:
    """The mistaken copy of ``problem`` with nothing mistaken (what every family changes one
    thing of): the model a mistake that changes only numbers is solved in
    (:mod:`.revalue`)."""
    return _unchanged(problem)


@lru_cache(maxsize=64)
def _unchanged(problem: Problem) -> Problem:
    # one object per problem: the solver's caches find its plan by identity
    return _mistaken(problem, dynamics_of(problem))


def _mass(body: Body) -> str:
    return " + ".join(f"({p.mass.text})" for p in body.parts)


def _weight(body: Body, gravity: Expr) -> Expr:
    return _expr(f"({_mass(body)})*mag({gravity.text})")


def _zero(model: Model, vector: Vector) -> bool:
    return all(identically_zero(model.plain(c)) for c in vector.to_matrix(model.inertial))


def _rewrite(node: Node, change: Callable[[Node], Node | None]) -> Node:
    """``node`` with every sub-tree ``change`` gives a replacement for replaced."""
    new = change(node)
    if new is not None:
        return new
    if isinstance(node, Bin):
        return Bin(node.op, _rewrite(node.left, change), _rewrite(node.right, change))
    if isinstance(node, Unary):
        return Unary(node.op, _rewrite(node.operand, change))
    if isinstance(node, Call):
        return Call(node.func, tuple(_rewrite(a, change) for a in node.args))
    return node


def _replacing(old: Node, new: Node) -> Callable[[Node], Node | None]:
    """The change for :func:`_rewrite` that puts ``new`` for each ``old``."""
    return lambda n: new if n == old else None


def _calls(node: Node, func: str) -> Iterator[Call]:
    if isinstance(node, Call):
        if node.func == func:
            yield node
        for arg in node.args:
            yield from _calls(arg, func)
    for child in (getattr(node, "left", None), getattr(node, "right", None),
                  getattr(node, "operand", None)):
        if child is not None:
            yield from _calls(child, func)


def _readings(problem: Problem, func: str, name: str, replacement: Node, at: str | None = None
              ) -> tuple[tuple[str, Expr], ...]:
    """Each numeric objective that calls ``func(name, ...)``, read with ``replacement`` there;
    with ``at`` (where the force ``name`` acts), its power ``power(name, F)`` too, read as
    the mistaken force's power ``dot(replacement, vel(at, F))``."""
    funcs = (func, "power") if at is not None and func == "force" else (func,)

    def change(n: Node) -> Node | None:
        if not (isinstance(n, Call) and n.func in funcs and n.args[0] == Name(name)):
            return None
        if n.func == func or at is None:
            return replacement
        return Call("dot", (replacement, Call("vel", (Name(at), n.args[1]))))

    out = []
    for obj in problem.objectives:
        node = obj.find.node
        if obj.kind == ObjectiveKind.SYMBOLIC or not any(c.args[0] == Name(name) for f in funcs
                                             for c in _calls(node, f)):
            continue
        new = _rewrite(node, change)
        out.append((obj.id, Expr(to_text(new), new)))
    return tuple(out)


def _rotating(model: Model, body: Body) -> bool:
    """A rigid body turning about its frame's z axis only (planar rotation)."""
    if body.frame is None:
        return False
    omega = model.frames[body.frame].ang_vel_in(model.inertial)
    x, y, z = (model.plain(c) for c in omega.to_matrix(model.frames[body.frame]))
    return identically_zero(x) and identically_zero(y) and not identically_zero(z)


# ---------------------------------------------------------------------------- families


def weight_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The gravity load left out of every free-body diagram."""
    d = dynamics_of(problem)
    if d.gravity is None:
        return
    names = ", ".join(b.name for b in d.bodies)
    total = _expr(" + ".join(f"({_weight(b, d.gravity).text})" for b in d.bodies))
    yield DynamicsMutation(
        "weight_omitted", f"Your value is what the balances give without the weight of {names} "
        "(m g = {term}): include the gravity load in the free-body diagram.", LOADS,
        problem=_mistaken(problem, replace(d, gravity=None)), term=total, term_unit="N")


def weight_omitted_from_reaction(problem: Problem, model: Model
                                 ) -> Iterator[DynamicsMutation]:
    """The weight left out of the force balance that gives the only reaction on a body (a
    pin's force read as m a_G): the reaction read with the weight added back."""
    d = dynamics_of(problem)
    if d.gravity is None or isinstance(d.analysis, Impulse):
        return
    for r, body in _only_reactions(d):
        weight = _weight(body, d.gravity)
        replacement = parse(f"force({r.name}) + ({_mass(body)})*({d.gravity.text})",
                            functions=FUNCTIONS)
        readings = _readings(problem, "force", r.name, replacement)
        if readings:
            yield DynamicsMutation(
                "weight_omitted", f"Your value leaves the weight of {body.name} (m g = "
                f"{{term}}) out of the force balance that gives {r.name}: {r.name} + m g = "
                "m a_G.", BALANCES, readings=readings, term=weight, term_unit="N")


def reaction_as_static(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The only reaction on a body read as its static value: the force balance that gives it
    written with m a_G = 0 (a pin's force as the weight it holds at rest, a support's as if
    the body did not precess), read in the right model as force minus m a_G."""
    d = dynamics_of(problem)
    if isinstance(d.analysis, Impulse):
        return
    N = problem.inertial_frame
    for r, body in _only_reactions(d):
        replacement = parse(f"force({r.name}) - ({_mass(body)})*acc({body.centre}, {N})",
                            functions=FUNCTIONS)
        readings = _readings(problem, "force", r.name, replacement, r.acts[0].at)
        if not readings:
            continue
        term = _expr(f"({_mass(body)})*mag(acc({body.centre}, {N}))")
        # held by its weight alone, the static value is the weight: that family's mistake
        if d.gravity is not None and not any(body.name in _bodies_of(x) for x in (
                *d.forces, *d.couples, *d.springs, *d.dampers)):
            yield DynamicsMutation(
                "reaction_as_weight", f"Your value takes {r.name} equal to the weight of "
                f"{body.name}, as if it did not accelerate: m a_G = {{term}} belongs in the "
                f"force balance that gives {r.name}.", BALANCES, readings=readings,
                term=term, term_unit="N")
            continue
        yield DynamicsMutation(
            "reaction_as_static", f"Your value is {r.name} as if {body.name} did not "
            f"accelerate (its static value): m a_G = {{term}} belongs in the force "
            f"balance that gives {r.name}.", BALANCES, readings=readings,
            term=term, term_unit="N")


def reaction_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The only support of a body that its weight alone loads (a pin that holds a released
    disk) left out: the body taken to fall freely, read in the right model as the support's
    force zero and the mass centre's acceleration g. Not for a body whose mass centre the
    support holds still (a drum on its axle cannot fall)."""
    d = dynamics_of(problem)
    if d.gravity is None or isinstance(d.analysis, Impulse):
        return
    N = problem.inertial_frame
    for r, body in _only_reactions(d):
        if any(body.name in _bodies_of(x) for x in (*d.forces, *d.couples, *d.springs,
                                                     *d.dampers)) \
                or _zero(model, model.language.point_velocity(Name(body.centre), N)):
            continue
        falls = {"force": (r.name, parse(f"0*({d.gravity.text})", functions=FUNCTIONS)),
                 "acc": (body.centre, d.gravity.node)}
        readings = tuple(
            reading for func, (name, replacement) in falls.items()
            for reading in _readings(problem, func, name, replacement, r.acts[0].at
                                     if func == "force" else None)
            if func == "force" or all(c.args[1] == Name(N) for c in _calls(
                next(o.find.node for o in problem.objectives if o.id == reading[0]), "acc")
                if c.args[0] == Name(body.centre)))
        if readings:
            yield DynamicsMutation(
                "reaction_omitted", f"Your value leaves {r.name} out, as if {body.name} fell "
                f"freely (a_G = g, {r.name} = 0): {r.name} holds {body.name} at "
                f"{r.acts[0].at} and belongs in its free-body diagram, with the momentum "
                f"balances giving it and the angular acceleration together.", LOADS,
                readings=readings, term=_weight(body, d.gravity), term_unit="N")


def _bodies_of(load) -> tuple[str, ...]:
    """The bodies a force, couple, spring or damper acts on."""
    return tuple(load.on) if isinstance(load.on, tuple) else (load.on,)


def reactions_as_static(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The reactions on a body held by several supports (a shaft in two bearings) taken as
    their static values: the balances written without m a_G and the rate of the angular
    momentum, the weights kept (solvable where the motion is prescribed: at an instant whose
    rates and a second rate are given; an impact, an integrated motion or an energy balance
    finds the motion from the masses this model takes as zero, and has none)."""
    d = dynamics_of(problem)
    if d.gravity is None or d.analysis is not None or not any(
            isinstance(g.key.node, Prime) and g.key.node.order == 2
            for g in (*problem.givens, *(g for o in problem.objectives for g in o.givens))):
        return  # no second rate given: the motion is not prescribed
    single = {r.name for r, _ in _only_reactions(d)}
    shared = [r.name for r in d.reactions if r.name not in single]
    asked = [o for o in problem.objectives if o.kind != ObjectiveKind.SYMBOLIC
             and any(next((c for c in _calls(o.find.node, "force") if c.args[0] == Name(r)),
                          None) for r in shared)]
    if not asked:
        return
    weights = tuple(Force(f"weight~{b.name}", b.name, b.centre,
                          _expr(f"({_mass(b)})*({d.gravity.text})"), b.where) for b in d.bodies)
    bodies = tuple(replace(b, parts=tuple(replace(p, mass=_expr("0"), shape=None)
                                          for p in b.parts)) for b in d.bodies)
    mistaken = _mistaken(problem, replace(d, bodies=bodies, gravity=None,
                                          forces=d.forces + weights))
    ids = {o.id for o in asked}
    yield DynamicsMutation(
        "reaction_as_static", f"Your value is {', '.join(shared)} as if nothing accelerated "
        "(the static values, the weight alone): the dynamic part, from m a_G and the rate of "
        "change of the angular momentum, belongs in the balances.", BALANCES,
        problem=replace(mistaken, objectives=tuple(o for o in mistaken.objectives
                                                   if o.id in ids)))


def _only_reactions(d: Dynamics) -> Iterator[tuple[Reaction, Body]]:
    """Each reaction that is the only reaction (or friction) on the one body it acts on."""
    on: dict[str, list[Reaction | Friction]] = {}
    for load in (*d.reactions, *d.friction):
        bodies = [a.on for a in load.acts] if isinstance(load, Reaction) else [load.on]
        for owner in bodies:
            on.setdefault(owner, []).append(load)
    for r in d.reactions:
        if len(r.acts) == 1 and r.acts[0].on != GROUND and len(on[r.acts[0].on]) == 1:
            yield r, d.body(r.acts[0].on)


def mass_for_weight(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The mass written where the weight m g belongs (the gravity load without its g)."""
    d = dynamics_of(problem)
    if d.gravity is None:
        return
    unit = _expr(f"({d.gravity.text})/mag({d.gravity.text})")
    names = ", ".join(b.name for b in d.bodies)
    its = "its" if len(d.bodies) == 1 else "their"
    total = _expr(" + ".join(f"({_weight(b, d.gravity).text})" for b in d.bodies))
    yield DynamicsMutation(
        "mass_for_weight", f"Your value is what the balances give with the mass of {names} "
        f"written for {its} weight; the weight is m g = {{term}}: multiply the mass by g.", LOADS,
        problem=_mistaken(problem, replace(d, gravity=unit)), term=total, term_unit="N")


def weight_for_mass(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The weight m g written where the mass belongs (in m a, in ω_n = √(k/m)), the weight
    itself kept."""
    d = dynamics_of(problem)
    if d.gravity is None:
        return
    size = f"mag({d.gravity.text})"
    # the weight's number in the problem's units: in pounds where it is given in them
    # (W = 10 lb used as 10 slug), in newtons otherwise
    number = f"{size}/{0.3048!r}" if _customary(problem) else size

    def heavier(part: Part) -> Part:
        shape = part.shape  # a given inertia (m k²) is a mass times a length squared too
        if isinstance(shape, Explicit):
            shape = Explicit(tuple((key, _expr(f"({e.text})*{number}"))
                                   for key, e in shape.entries))
        return replace(part, mass=_expr(f"({part.mass.text})*{number}"), shape=shape)

    bodies = tuple(replace(b, parts=tuple(heavier(p) for p in b.parts)) for b in d.bodies)
    names = ", ".join(b.name for b in d.bodies)
    total = _expr(" + ".join(f"({_mass(b)})" for b in d.bodies))
    yield DynamicsMutation(
        "weight_for_mass", f"Your value is what the balances give with the weight of {names} "
        "written for the mass: the mass is m = W/g = {term}.", BODIES,
        problem=_mistaken(problem, replace(d, bodies=bodies,
                                           gravity=_expr(f"({d.gravity.text})/({number})"))),
        term=total, term_unit="kg")


def _customary(problem: Problem) -> bool:
    """Whether the problem's givens are in US customary units (feet, pounds)."""
    return any(w in ("ft", "lb", "lbf", "slug", "in") for g in problem.givens
               for w in re.findall(r"[A-Za-z]+", g.unit))


def _pivots(problem: Problem, model: Model, body: Body) -> Iterator[str]:
    """Points of ``body`` (other than its reference point) whose material point does not move:
    a pin fixed in the ground, or a contact rolling (or unwinding) on the ground."""
    N = problem.inertial_frame
    assert body.frame is not None  # a rotating body (the only kind asked about) has a frame
    frame = model.frames[body.frame]
    omega = frame.ang_vel_in(model.inertial)
    centre = model.language.point_velocity(Name(body.centre), N)
    rolling = {q for c in problem.constraints if c.level is ConstraintLevel.VELOCITY
               and (q := _rolling_on_ground(c, body.frame, N)) is not None}
    for point, position in model.positions.items():
        offset = position - model.positions[body.centre]
        if point == body.centre or _zero(model, offset):
            continue
        if point in rolling or _zero(model, centre + (omega ^ offset)):
            yield point


def _rolling_on_ground(constraint: Constraint, frame: str, inertial: str) -> str | None:
    """Q of ``vel(coincident(Q, frame), N) = vel(coincident(Q, N), N)``: the body's point Q
    does not slip on the ground (``None`` for any other constraint)."""
    lhs, rhs = constraint.lhs.node, constraint.rhs.node
    if not (isinstance(lhs, Call) and lhs.func == "vel" and isinstance(lhs.args[0], Call)
            and lhs.args[0].func == "coincident" and lhs.args[0].args[1] == Name(frame)
            and isinstance(rhs, Call) and rhs.func == "vel" and isinstance(rhs.args[0], Call)
            and rhs.args[0].args[1] == Name(inertial)):
        return None
    return name_of(lhs.args[0].args[0])


def central_inertia_at_pivot(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The moment balance about a point that does not move (a pin, a rolling contact) written
    with the inertia about the mass centre, also in an impact's angular impulse-momentum
    balance about the pin: the parallel-axis term m d^2 missing. Modelled by a
    massless part carrying -m d^2 about the body's z axis, so I about the pivot is I_G."""
    d = dynamics_of(problem)
    for body in d.bodies:
        if not _rotating(model, body):
            continue
        for pivot in _pivots(problem, model, body):
            offset = f"pos({pivot}, {body.centre})"
            term = _expr(f"({_mass(body)})*dot({offset}, {offset})")
            yield DynamicsMutation(
                "central_inertia_at_pivot", f"Your value uses the moment of inertia of "
                f"{body.name} about its mass centre {body.centre} for the rotation about "
                f"{pivot}; about {pivot} it needs the parallel-axis term m d² = {{term}}.",
                BODIES, problem=_inertia_added(problem, d, body, f"-({term.text})"),
                term=term, term_unit="kg*m^2")


def _inertia_added(problem: Problem, d: Dynamics, body: Body, zz: str) -> Problem:
    """The mistaken model with a massless part of ``body`` carrying ``zz`` about its z axis
    (its moment of inertia about a pivot mistaken by that much)."""
    part = Part(_expr("0"), body.centre, Explicit((("zz", _expr(zz)),)), body.where)
    bodies = tuple(replace(b, parts=b.parts + (part,)) if b.name == body.name else b
                   for b in d.bodies)
    return _mistaken(problem, replace(d, bodies=bodies), without=("ke", "angmom"))


def parallel_axis_with_radius(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The moment of inertia about a pivot away from the mass centre (a disk hung from a hole)
    with the parallel-axis term written with the body's radius r for the pivot's distance d:
    I_G + m r² for I_G + m d². Modelled, as :func:`central_inertia_at_pivot`, by a massless
    part carrying m (r² - d²) about the body's z axis."""
    d = dynamics_of(problem)
    for body in d.bodies:
        if not _rotating(model, body) or len(body.parts) != 1 \
                or type(body.parts[0].shape) not in _SHAPES:
            continue
        radius = _radius(body.parts[0].shape)
        for pivot in _pivots(problem, model, body):
            offset = f"pos({pivot}, {body.centre})"
            if identically_zero(model.plain(model.language.scalar(
                    _expr(f"dot({offset}, {offset}) - ({radius})^2")))):
                continue  # the pivot on the rim: r is its distance
            extra = f"({_mass(body)})*(({radius})^2 - dot({offset}, {offset}))"
            yield DynamicsMutation(
                "parallel_axis_with_radius", f"Your value takes the parallel-axis term about "
                f"{pivot} as m {radius}² = {{term}}, with the radius {radius} of {body.name}: "
                f"the term is m d², d the distance from {body.centre} to {pivot}.", BODIES,
                problem=_inertia_added(problem, d, body, extra),
                term=_expr(f"({_mass(body)})*({radius})^2"), term_unit="kg*m^2")


def friction_reversed(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """Every kinetic-friction force turned round (along the slip instead of against it); a
    static friction read in the other sense."""
    d = dynamics_of(problem)
    kinetic = [f for f in d.friction if isinstance(f, KineticFriction)]
    yield from _static_friction_reversed(problem, d)
    if not kinetic:
        return
    friction = tuple(replace(f, mu=_expr(f"-({f.mu.text})"))
                     if isinstance(f, KineticFriction) else f for f in d.friction)
    names = ", ".join(f.name for f in kinetic)
    term = _expr(" + ".join(f"mag(force({f.name}))" for f in kinetic))
    yield DynamicsMutation(
        "friction_reversed", f"Your value is what the friction {names} (μ N = {{term}}) "
        "pointing the wrong way gives: kinetic friction opposes the slip velocity.", LOADS,
        problem=_mistaken(problem, replace(d, friction=friction)), term=term, term_unit="N")


def _static_friction_reversed(problem: Problem, d: Dynamics) -> Iterator[DynamicsMutation]:
    """The friction at a contact that does not slip read in the other sense (drawn against
    the motion, or with it, by habit, where the balances need the other)."""
    for f in d.friction:
        if not isinstance(f, StaticFriction):
            continue
        readings = _readings(problem, "force", f.name,
                             parse(f"-force({f.name})", functions=FUNCTIONS))
        if readings:
            yield DynamicsMutation(
                "friction_reversed", f"Your value has the friction {f.name} (= {{term}}) "
                "pointing the wrong way: at a contact that does not slip, the friction acts "
                "in the sense the balances need, which the free-body diagram's solution "
                "gives.", LOADS, readings=readings, term=_expr(f"mag(force({f.name}))"),
                term_unit="N")


def normal_from_weight(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The kinetic friction on a body sliding on the ground on one contact taken as μ m g: μ
    times the weight instead of μ N (an incline, a push with a part along the normal; where N is the weight
    the mistake gives the answer and is dropped)."""
    d = dynamics_of(problem)
    if d.gravity is None:
        return
    for f in d.friction:
        if not isinstance(f, KineticFriction) or f.surface not in (GROUND, problem.inertial_frame):
            continue
        body = d.body(f.on)
        if sum(x.on == f.on for x in d.friction) > 1:  # μ times the weight is their sum's
            continue
        N = problem.inertial_frame
        # the slip velocity: of the particle, or of the body's material point at the contact
        at = f.at if body.frame is None else f"coincident({f.at}, {body.frame})"
        force = Force(f.name, f.on, f.at, _expr(
            f"-({f.mu.text})*({_weight(body, d.gravity).text})*vel({at}, {N})"
            f"/speed({at}, {N})"), f.where)
        friction = tuple(x for x in d.friction if x is not f)
        yield DynamicsMutation(
            "normal_from_weight", f"Your value takes the friction {f.name} as μ m g, with the "
            f"weight in place of the normal force {f.normal} = {{term}}: use μ N.",
            LOADS, problem=_mistaken(problem, replace(d, friction=friction,
                                                      forces=d.forces + (force,))),
            term=_expr(f"mag(force({f.normal}))"), term_unit="N")


def weight_transfer_ignored(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The friction forces of a body that does not turn, on two or more contacts, taken to act
    at its mass centre: their moment, which shifts load between the contacts, left out."""
    d = dynamics_of(problem)
    for body in d.bodies:
        if body.frame is None or not _zero(model, model.frames[body.frame].ang_vel_in(
                model.inertial)):
            continue
        kinetic = [f for f in d.friction if isinstance(f, KineticFriction) and f.on == body.name
                   and f.at != body.centre]
        if len(kinetic) < 2:
            continue
        friction = tuple(replace(f, at=body.centre) if f in kinetic else f for f in d.friction)
        names = ", ".join(f.normal for f in kinetic)
        term = _expr("mag(" + " + ".join(f"moment({f.name}, {body.centre})" for f in kinetic)
                     + ")")
        yield DynamicsMutation(
            "weight_transfer_ignored", f"Your value ignores the weight transfer: the friction "
            f"forces act below the mass centre {body.centre}, and their moment about it = "
            f"{{term}} shifts load between {names}.", BALANCES,
            problem=_mistaken(problem, replace(d, friction=friction)), term=term,
            term_unit="N*m")


def tension_as_weight(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A string pulling two bodies (an Atwood machine) taken to pull with the weight of one of
    them, shared among the strands that hold it (half the weight of a block on a movable
    pulley: the tension at rest), and the other body's balance written with it alone, on
    each of its strands."""
    d = dynamics_of(problem)
    if d.gravity is None:
        return
    for r in d.reactions:
        bodies = [a.on for a in r.acts if a.on != GROUND]
        if len(r.directions) != 1 or len(set(bodies)) < 2:
            continue
        for on in dict.fromkeys(bodies):
            for other in dict.fromkeys(bodies):
                if other == on:
                    continue
                strands = bodies.count(other)
                weight = _weight(d.body(other), d.gravity)
                share = weight if strands == 1 else _expr(f"({weight.text})/{strands}")
                forces = tuple(Force(r.name if i == 0 else f"{r.name}~{i}", on, act.at, _expr(
                    f"{act.sign}*({share.text})*({r.direction_at(act).text})"), r.where)
                    for i, act in enumerate(a for a in r.acts if a.on == on))
                changed = replace(d, bodies=(d.body(on),), forces=d.forces + forces,
                                  reactions=tuple(x for x in d.reactions if x is not r))
                held = "" if strands == 1 else f", shared by the {strands} strands that hold it"
                yield DynamicsMutation(
                    "tension_as_weight", f"Your value takes the tension {r.name} equal to the "
                    f"weight of {other} (m g = {{term}}){held}, in the balance of {on}: the "
                    "bodies accelerate, so the tension is not a weight; solve for it.", LOADS,
                    problem=_mistaken(problem, changed), term=weight, term_unit="N")


def reaction_as_weight(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A reaction along the vertical (a string, a floor) or pressing a friction contact read as
    the weight m g of a body it acts on, as if the body did not accelerate; and a reaction
    across the vertical read as the weight that another reaction of its body carries (a
    collar's side force for the rod's vertical one)."""
    d = dynamics_of(problem)
    if d.gravity is None or isinstance(d.analysis, Impulse):
        return
    g = model.language.vector(d.gravity)
    normals = {f.normal for f in d.friction}
    vertical = {r.name: _zero(model, g ^ model.language.vector(r.directions[0]))
                for r in d.reactions if len(r.directions) == 1}
    for r in d.reactions:
        if len(r.directions) != 1:
            continue
        direction = r.directions[0]
        across = r.name not in normals and not vertical[r.name]
        for name in dict.fromkeys(a.on for a in r.acts if a.on != GROUND):
            carrier = next((o.name for o in d.reactions if vertical.get(o.name)
                            and any(a.on == name for a in o.acts)), None)
            if across and carrier is None:
                continue
            # a body held in place (a drum on its axle) has no weight the reaction could
            # be taken for: its weight goes to its bearing
            if _zero(model, model.language.point_velocity(Name(d.body(name).centre),
                                                           problem.inertial_frame)):
                continue
            weight = _weight(d.body(name), d.gravity)
            replacement = parse(f"({weight.text})*({direction.text})", functions=FUNCTIONS)
            at = next(a.at for a in r.acts if a.on == name)
            readings = _readings(problem, "force", r.name, replacement, at)
            if readings:
                why = (f"the weight goes to {carrier}, along the vertical, and {r.name} comes "
                       "from the momentum balance across it") if across else (
                       f"{r.name} comes from the momentum balance along its direction, where the "
                       "other forces and the acceleration count too")
                yield DynamicsMutation(
                    "reaction_as_weight", f"Your value takes {r.name} equal to the weight of "
                    f"{name}, m g = {{term}}; {why}.", BALANCES, readings=readings,
                    term=weight, term_unit="N")
    yield from _spring_as_weight(problem, d)


def acceleration_reversed(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A one-direction reaction on a moving body (a cord holding a falling block) read from
    the body's momentum balance along it with m a_G in the opposite sense (T = m (g + a) for a
    block that falls): the reaction less twice m a_G's component along it, read in the right
    model. Where a_G has no component along the reaction the value is the answer (dropped)."""
    d = dynamics_of(problem)
    if isinstance(d.analysis, Impulse):
        return
    N = problem.inertial_frame
    for r in d.reactions:
        act = r.acts[0]
        if len(r.directions) != 1 or act.on == GROUND:
            continue
        body = d.body(act.on)
        if _zero(model, model.language.point_velocity(Name(body.centre), N)):
            continue  # held in place (a drum on its axle): no m a_G to reverse
        unit = f"unit({r.directions[0].text})"
        part = f"({_mass(body)})*dot(acc({body.centre}, {N}), {unit})"
        replacement = parse(f"force({r.name}) - 2*{part}*{unit}", functions=FUNCTIONS)
        readings = _readings(problem, "force", r.name, replacement, act.at)
        if readings:
            yield DynamicsMutation(
                "acceleration_reversed", f"Your value is {r.name} from the balance of "
                f"{body.name} along it with m a_G = {{term}} taken in the opposite sense (as "
                f"if {body.name} accelerated the other way): keep the sign the motion gives "
                "the acceleration.", BALANCES, readings=readings, term=_expr(part),
                term_unit="N")


def _spring_as_weight(problem: Problem, d: Dynamics) -> Iterator[DynamicsMutation]:
    """A spring's force on a body read as that body's whole weight m g (along the spring's
    force), as if the spring alone carried it (a pin or another support shares it)."""
    assert d.gravity is not None
    for spring in d.springs:
        for name, point in zip(spring.on, spring.between):
            if name == GROUND:
                continue
            weight = _weight(d.body(name), d.gravity)
            # m g along the spring's own force (a spring pushes or pulls along its line)
            replacement = parse(f"({weight.text})*force({spring.name})"
                                f"/mag(force({spring.name}))", functions=FUNCTIONS)
            readings = _readings(problem, "force", spring.name, replacement, point)
            if readings:
                yield DynamicsMutation(
                    "reaction_as_weight", f"Your value takes the force of spring {spring.name} "
                    f"equal to the weight of {name}, m g = {{term}}: the spring shares the "
                    "load with the other supports; its force comes from the balances (the "
                    "moments about a pin, the momentum balance along it).", BALANCES,
                    readings=readings, term=weight, term_unit="N")


def reaction_without_coriolis(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A one-direction reaction on a particle moving in a turning frame (a collar on a spinning
    rod) read from the balance along its direction with the Coriolis term 2 ω × v_rel of the
    particle's acceleration left out, or with ω × v_rel (the 2 forgotten): the reaction less
    m times that term's component along it. Only where no other unknown of the particle acts
    along the reaction and no coordinate moves it that way (the balance along it fixes it
    alone)."""
    d = dynamics_of(problem)
    if isinstance(d.analysis, Impulse):
        return
    lang, N = model.language, problem.inertial_frame
    for r in d.reactions:
        if len(r.directions) != 1:
            continue
        direction = r.directions[0]
        along = lang.vector(direction)
        for act in r.acts:
            if act.on == GROUND:
                continue
            body = d.body(act.on)
            if body.frame is not None or _pushed_otherwise(model, d, r, body, along):
                continue
            for B, origin in moving_frames(model, body.centre, N):
                rel = f"pos({body.centre}, {origin})"
                term = parse(f"2*cross(angvel({B}, {N}), dt({rel}, {B}))", functions=FUNCTIONS)
                if identically_zero(model.plain(lang.value(term) & along)):
                    continue
                for code, share, name in (
                        ("drop_coriolis", "", "with the Coriolis term 2 ω × v_rel left out of "
                         "its acceleration"),
                        ("coriolis_half", "/2", "with the Coriolis term taken as ω × v_rel, "
                         "without its 2")):
                    unit = f"unit({direction.text})"
                    replacement = parse(
                        f"force({r.name}) - ({_mass(body)})*dot({to_text(term)}{share}, {unit})"
                        f"*{unit}", functions=FUNCTIONS)
                    readings = _force_readings(problem, r.name, act.at, replacement)
                    if readings:
                        yield DynamicsMutation(
                            code, f"Your value takes {r.name} from the balance of {body.name} "
                            f"along {r.name}'s direction {name}: sliding along frame {B} "
                            f"while {B} turns, {body.name} needs a force m × 2 ω × v_rel = "
                            "{term} along it.", BALANCES, readings=readings,
                            term=_expr(f"({_mass(body)})*dot({to_text(term)}, {unit})"),
                            term_unit="N")


def _pushed_otherwise(model: Model, d: Dynamics, reaction: Reaction, body: Body,
                      along: Vector) -> bool:
    """Whether another unknown of ``body`` (another reaction's direction, a coordinate that
    is not driven moving its centre) acts or moves along ``along``."""
    lang = model.language
    for other in d.reactions:
        if other.name == reaction.name or not any(a.on == body.name for a in other.acts):
            continue
        if any(not identically_zero(model.plain(lang.vector(e) & along))
               for e in other.directions):
            return True
    # a driven coordinate (its second derivative given) is no unknown of the balance
    given = {to_text(g.key.node) for g in model.problem.givens}
    position = model.positions[body.centre]
    return any(not identically_zero(model.plain(
        position.diff(lang.value(Name(c.name)), model.inertial) & along))
        for c in model.problem.coordinates if f"{c.name}''" not in given)


def _force_readings(problem: Problem, name: str, at: str, replacement: Node
                    ) -> tuple[tuple[str, Expr], ...]:
    """Each numeric objective that asks for the force ``name`` or its moment, read with
    ``replacement`` for the force (acting at ``at``)."""
    def change(n: Node) -> Node | None:
        if not (isinstance(n, Call) and n.args and n.args[0] == Name(name)):
            return None
        if n.func == "force":
            return replacement
        if n.func == "moment":
            return Call("cross", (Call("pos", (Name(at), n.args[1])), replacement))
        return None

    out = []
    for obj in problem.objectives:
        node = obj.find.node
        if obj.kind == ObjectiveKind.SYMBOLIC or not any(c.args[0] == Name(name) for f in ("force", "moment")
                                             for c in _calls(node, f)):
            continue
        new = _rewrite(node, change)
        out.append((obj.id, Expr(to_text(new), new)))
    return tuple(out)


def rotational_ke_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The rotational kinetic energy ½ ω·I_G·ω of a rigid body left out: in an energy
    objective, and in the work-energy balance that fixes the rates."""
    d = dynamics_of(problem)
    N = problem.inertial_frame
    for body in d.bodies:
        if not _rotating(model, body) or any(p.at != body.centre for p in body.parts):
            continue
        translational = f"dot(momentum({body.name}, {N}), vel({body.centre}, {N}))/2"
        term = _expr(f"ke({body.name}, {N}) - {translational}")
        sentence = (f"Your value leaves out the rotational kinetic energy ½ I_G ω² = {{term}} "
                    f"of {body.name}: a rigid body's kinetic energy is ½ m v_G² + ½ I_G ω².")
        readings = _readings(problem, "ke", body.name,
                             parse(translational, functions=FUNCTIONS))
        if readings:
            yield DynamicsMutation("rotational_ke_omitted", sentence, OBJECTIVES,
                                   readings=readings, term=term, term_unit="J")
        if isinstance(d.analysis, WorkEnergy):
            bodies = tuple(replace(b, parts=tuple(replace(p, shape=None) for p in b.parts))
                           if b.name == body.name else b for b in d.bodies)
            yield DynamicsMutation("rotational_ke_omitted", sentence, BODIES,
                                   problem=_mistaken(problem, replace(d, bodies=bodies)),
                                   term=term, term_unit="J")


def translational_ke_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """In a work-energy balance, a body that turns while its mass centre moves and that no
    fixed pin holds (a wheel that rolls) given the kinetic energy of its parts' spins alone,
    ½ I ω² each: every ½ m v² left out (a point mass's whole energy). Modelled by massless
    parts that keep their spins' inertia, the weights kept as forces at the parts."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, WorkEnergy) or d.gravity is None:
        return
    N = problem.inertial_frame
    pinned = {a.on for r in d.reactions if len(r.directions) > 1 for a in r.acts
              if _zero(model, model.language.point_velocity(Name(a.at), N))}
    for body in d.bodies:
        if not _rotating(model, body) or body.name in pinned or _zero(
                model, model.language.point_velocity(Name(body.centre), N)):
            continue
        parts = tuple(spin for p in body.parts if (spin := _spin_only(p)) is not None)
        if len(parts) != len(body.parts):
            continue
        weights = tuple(Force(f"weight~{b.name}~{i}", b.name, p.at,
                              _expr(f"({p.mass.text})*({d.gravity.text})"), b.where,
                              kind=LoadKind.WEIGHT)
                        for b in d.bodies for i, p in enumerate(b.parts))
        bodies = tuple(replace(b, parts=parts) if b.name == body.name else b
                       for b in d.bodies)
        translational = f"dot(momentum({body.name}, {N}), vel({body.centre}, {N}))/2"
        yield DynamicsMutation(
            "translational_ke_omitted", f"Your value gives {body.name} the kinetic energy of "
            f"its spin alone, ½ I ω²: it also moves along with its mass centre "
            f"{body.centre}, and ½ m v² of each of its parts (½ m v_G² = {{term}} of the "
            f"whole) belongs in its kinetic energy.", BODIES,
            problem=_mistaken(problem, replace(d, bodies=bodies, gravity=None,
                                               forces=d.forces + weights),
                              without=("ke", "momentum", "angmom")),
            term=_expr(translational), term_unit="J")


def weight_along_surface_omitted(problem: Problem, model: Model
                                 ) -> Iterator[DynamicsMutation]:
    """On a slope, the weight's component along the surface a body rubs on left out while its
    part pressing on the surface (and so the friction) is kept: the weight of the body with
    friction replaced by its part along the normal reaction's one direction, every other
    body's weight as it is. At an instant only: along an integrated motion the mistaken
    model's slip lasts otherwise (a ball that would have rolled still skids), and its value
    is another mistake's (kinetic friction kept once the ball rolls)."""
    d = dynamics_of(problem)
    if d.gravity is None or isinstance(d.analysis, Integration):
        return
    gravity = model.language.vector(d.gravity)
    for f in d.friction:
        r = next((r for r in d.reactions if r.name == f.normal), None)
        if r is None or len(r.directions) != 1:
            continue
        along = model.language.vector(r.directions[0])
        if _zero(model, (gravity & along) * along) or _zero(model, gravity ^ along):
            continue  # the weight all along the surface, or all across it: no slope
        unit = f"unit({r.directions[0].text})"
        pressing = f"dot({d.gravity.text}, {unit})*{unit}"
        weights = tuple(
            Force(f"weight~{b.name}~{i}", b.name, part.at, _expr(
                f"({part.mass.text})*({pressing if b.name == f.on else d.gravity.text})"),
                b.where, kind=LoadKind.WEIGHT)
            for b in d.bodies for i, part in enumerate(b.parts))
        yield DynamicsMutation(
            "weight_along_surface_omitted", f"Your value is what the balances give with the "
            f"weight of {f.on} kept only across the surface it rubs on (pressing on it, so "
            f"{f.name} is right) and its component along the surface left out: the weight "
            "acts along the slope too.", LOADS,
            problem=_mistaken(problem, replace(d, gravity=None, forces=d.forces + weights)))


def part_moving_with_centre(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A point mass fixed to a turning body away from its centre (a small mass on a hoop's
    rim) taken to move with the body's centre, which moves: its m v² and its moment of
    inertia m d² those of a mass at the centre, its weight kept at its own point (the
    heights it falls through are right)."""
    d = dynamics_of(problem)
    N = problem.inertial_frame
    for body in d.bodies:
        if not _rotating(model, body) or len(body.parts) < 2 or _zero(
                model, model.language.point_velocity(Name(body.centre), N)):
            continue
        for part in body.parts:
            if part.shape is not None or _zero(
                    model, model.positions[part.at] - model.positions[body.centre]):
                continue
            moved = replace(body, parts=tuple(replace(p, at=body.centre) if p is part else p
                                              for p in body.parts))
            bodies = tuple(moved if b is body else b for b in d.bodies)
            changed = replace(d, bodies=bodies)
            if d.gravity is not None:  # every part's weight at its own point, as forces
                changed = replace(changed, gravity=None, forces=d.forces + tuple(
                    Force(f"weight~{b.name}~{i}", b.name, p.at,
                          _expr(f"({p.mass.text})*({d.gravity.text})"), b.where,
                          kind=LoadKind.WEIGHT)
                    for b in d.bodies for i, p in enumerate(b.parts)))
            yield DynamicsMutation(
                "part_moving_with_centre", f"Your value takes the mass at {part.at} as moving "
                f"with the centre {body.centre} of {body.name}: it turns with {body.name} "
                f"{{term}} from {body.centre}, so its speed is that of the point {part.at}, "
                f"not of {body.centre}.", BODIES, problem=_mistaken(problem, changed),
                term=_expr(f"mag(pos({part.at}, {body.centre}))"), term_unit="m")


def _spin_only(part: Part) -> Part | None:
    """A massless copy of ``part`` with the inertia of its spin about the body's z axis (a
    point mass: none); ``None`` for a shape whose spin this cannot write."""
    shape = part.shape
    if shape is None:
        return replace(part, mass=_expr("0"))
    if isinstance(shape, (Disk, Ring)) and shape.axis != "z":
        return None
    if type(shape) in _SHAPES:
        coefficient = _SHAPES[type(shape)][1]
        zz = _expr(f"({coefficient})*({part.mass.text})*({_radius(shape)})^2")
    elif isinstance(shape, Explicit) and "zz" in dict(shape.entries):
        zz = dict(shape.entries)["zz"]
    else:
        return None
    return replace(part, mass=_expr("0"), shape=Explicit((("zz", zz),)))


def restitution_ignored(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """An impact with the coefficient of restitution replaced by 1 (perfectly elastic) or 0
    (the bodies stay together)."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse):
        return
    for i, c in enumerate(d.analysis.contacts):
        if not isinstance(c, Restitution):
            continue
        for e, kind in (("1", "a perfectly elastic impact (e = 1)"),
                        ("0", "a perfectly plastic impact (e = 0)")):
            contacts = tuple(replace(c, e=_expr(e)) if j == i else x
                             for j, x in enumerate(d.analysis.contacts))
            changed = replace(d, analysis=replace(d.analysis, contacts=contacts))
            yield DynamicsMutation(
                "restitution_ignored", f"Your value is what {kind} at {c.at} gives; the "
                f"coefficient of restitution is e = {{term}}: use it in the contact condition.",
                BALANCES, problem=_mistaken(problem, changed), term=c.e)


def energy_kept_in_coupling(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A coupling (every contact of an impact with e = 0, particles moving along one line)
    read with the kinetic energy kept instead of the momentum: the common velocity after
    sqrt(Σ m v₀² / Σ m), in the sense of the right one."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse) or not d.analysis.contacts or any(
            not isinstance(c, Restitution) or not identically_zero(
                model.plain(model.language.scalar(c.e))) for c in d.analysis.contacts):
        return
    before = {to_text(s.key.node): s.value.text if s.value is not None else repr(s.si)
              for s in d.analysis.start}
    positions = {p.name: p.position.node for p in problem.points if p.position is not None}
    first = d.analysis.contacts[0]
    assert isinstance(first, Restitution)
    rates: list[str] = []
    terms: list[tuple[str, str]] = []
    for body in d.bodies:
        node, line = positions.get(body.centre), first.direction.node
        if body.frame is not None or not (isinstance(node, Bin) and node.op == "*"
                                          and isinstance(node.left, Name)
                                          and node.right == line):
            return
        rate = f"{node.left.id}'"
        rates.append(rate)
        terms.append((_mass(body), before.get(rate, "0")))
    if len(terms) < 2:
        return
    energy = " + ".join(f"({m})*({v})^2" for m, v in terms)
    mass = " + ".join(f"({m})" for m, _ in terms)
    readings = tuple((o.id, _expr(f"sign({rate})*sqrt(({energy})/({mass}))"))
                     for o in problem.objectives for rate in rates
                     if to_text(o.find.node) == rate)
    if readings:
        yield DynamicsMutation(
            "energy_kept_in_coupling", "Your value keeps the kinetic energy through the "
            "coupling: the bodies that move on together lose energy in it; the momentum is "
            "what the impact conserves.", BALANCES, readings=readings)


def impact_taken_head_on(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """An oblique impact of particles treated as head-on: each particle's whole speed just
    before taken along the line of impact (in the sense of its component there), its
    component across the line left out. Only particles whose coordinates move them along
    fixed perpendicular axes, one of them the line of impact."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse):
        return
    before = {to_text(s.key.node): s for s in d.analysis.start}
    for c in d.analysis.contacts:
        if not isinstance(c, Restitution):
            continue
        line = model.language.vector(c.direction)
        rates: dict[str, str] = {}
        for name in c.bodies:
            body = next((b for b in d.bodies if b.name == name), None)
            if body is None or body.frame is not None:
                break
            along = _axes(problem, model, body.centre, line)
            if along is None:
                break
            # each coordinate's rate just before, as written (0 where left out)
            text = {q: _start_text(before.get(f"{q}'")) for q in along[1] + (along[0],)}
            speed = "sqrt(" + " + ".join(f"({t})^2" for t in text.values()) + ")"
            first = text[along[0]]
            if identically_zero(model.plain(model.language.value(parse(
                    f"({speed})^2 - ({first})^2", functions=FUNCTIONS)))):
                break  # already along the line: head-on is right for this body
            rates[f"{along[0]}'"] = f"({first})/abs({first})*{speed}"
            rates.update({f"{q}'": "0" for q in along[1]})
        else:
            if not rates:
                continue
            starts = tuple(replace(s, value=_expr(rates[to_text(s.key.node)]), si=None)
                           if to_text(s.key.node) in rates else s for s in d.analysis.start)
            yield DynamicsMutation(
                "impact_taken_head_on", f"Your value treats the impact at {c.at} as head-on, "
                f"with the whole speeds along the line of impact {c.direction.text}: only the "
                "velocity components along that line change in the impact (restitution and "
                "momentum along it); the components across it are kept.", BALANCES,
                problem=_mistaken(problem, replace(d, analysis=replace(d.analysis,
                                                                       start=starts))))


def striker_stops(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """An impact of a moving particle on one at rest along the line of impact with the
    striker taken to stop there, its whole momentum along the line passed on (as when equal
    masses meet elastically): m1 v0 = m2 v2. Along the line, momentum and a restitution
    e = m1/m2 give exactly that, so the contact's e is replaced by it."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse):
        return
    before = {to_text(s.key.node): s for s in d.analysis.start}
    bodies = {b.name: b for b in d.bodies if b.frame is None}
    for i, c in enumerate(d.analysis.contacts):
        if not isinstance(c, Restitution) or not all(b in bodies for b in c.bodies):
            continue
        line = model.language.vector(c.direction)
        rates = []  # each body's rate along the line just before, as written
        for name in c.bodies:
            along = _axes(problem, model, bodies[name].centre, line)
            rates.append(None if along is None else _start_text(before.get(f"{along[0]}'")))
        if None in rates:
            continue
        still = [identically_zero(model.plain(model.language.value(parse(
            str(rate), functions=FUNCTIONS)))) for rate in rates]
        for striker, struck in ((0, 1), (1, 0)):
            if still[striker] or not still[struck]:
                continue
            first, second = (bodies[c.bodies[j]] for j in (striker, struck))
            e = _expr(f"({_mass(first)})/({_mass(second)})")
            contacts = tuple(replace(c, e=e) if j == i else x
                             for j, x in enumerate(d.analysis.contacts))
            yield DynamicsMutation(
                "striker_stops", f"Your value takes {first.name} to stop in the impact at "
                f"{c.at}, its whole momentum passed on to {second.name} (as when equal masses "
                f"meet elastically): with e = {{term}}, {first.name} keeps moving after the "
                "impact; momentum and restitution together give both velocities after.",
                BALANCES, problem=_mistaken(problem, replace(
                    d, analysis=replace(d.analysis, contacts=contacts))), term=c.e)


def pin_impulse_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """An impact on a body turning about a fixed pin solved with the linear momentum of the
    bodies conserved, as if the pin gave no impulse, where the angular momentum about the pin
    is: the pin's impulse left out and the body's angular impulse-momentum balance with it
    (its impulse read as zero)."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse):
        return
    struck = {b for c in d.analysis.contacts for b in c.bodies}
    N = problem.inertial_frame
    for r in d.reactions:
        if len(r.directions) < 2 or len(r.acts) != 1:
            continue
        body = d.body(r.acts[0].on) if r.acts[0].on != GROUND else None
        if body is None or body.name not in struck or not _rotating(model, body) \
                or not _zero(model, model.language.point_velocity(Name(r.acts[0].at), N)):
            continue
        changed = replace(d, reactions=tuple(x for x in d.reactions if x is not r),
                          unbalanced=d.unbalanced + (body.name,))
        sentence = (f"Your value takes the linear momentum as conserved through the impact, as "
                    f"if the pin {r.acts[0].at} gave no impulse: {r.name} acts on {body.name} "
                    f"during the impact (its impulse is {{term}}); the angular momentum about "
                    f"{r.acts[0].at} is what is conserved.")
        term = _expr(f"mag(impulse({r.name}))")
        mistaken = _without_load(problem, changed, r.name)
        if mistaken is not None:
            yield DynamicsMutation("pin_impulse_omitted", sentence, BALANCES, problem=mistaken,
                                   term=term, term_unit="N*s")
        readings = _readings(problem, "impulse", r.name,
                             parse(f"0*{N}.x", functions=FUNCTIONS))
        if readings:
            yield DynamicsMutation("pin_impulse_omitted", sentence, BALANCES, readings=readings,
                                   term=term, term_unit="N*s")


def start_sense_reversed(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """An impact solved with one rate just before it taken in the opposite sense (a ball
    coming in at -v1 taken at +v1: its sense against the axis ignored): a stated rate's sign
    flipped, as a given's (``given_sign``)."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse):
        return
    for i, s in enumerate(d.analysis.start):
        text = _start_text(s)
        if not s.si if s.value is None else identically_zero(
                model.plain(model.language.value(s.value.node))):
            continue
        starts = tuple(replace(x, value=_expr(f"-({text})"), si=None) if j == i else x
                       for j, x in enumerate(d.analysis.start))
        yield DynamicsMutation(
            "given_sign", f"Your value is what {to_text(s.key.node)} just before "
            f"the impact gives with the opposite sign (it is {text}): a velocity against an "
            "axis has a negative component along it.", BALANCES,
            problem=_mistaken(problem, replace(d, analysis=replace(d.analysis, start=starts))))


def start_trig_exchanged(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """An impact solved with the sine and cosine of one angle exchanged in the rates just
    before it (a velocity's components written from the other axis), in every rate the angle
    enters at once."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse):
        return
    trig = [c for s in d.analysis.start if s.value is not None
            for f in ("sin", "cos") for c in _calls(s.value.node, f)]
    angles = list(dict.fromkeys(c.args[0] for c in trig if len(c.args) == 1))
    # one angle's, or every angle's at once (each velocity written from the other axis)
    for chosen in [(a,) for a in angles] + ([tuple(angles)] if len(angles) > 1 else []):
        starts = tuple(s if s.value is None else replace(s, value=Expr(
            to_text(new := _rewrite(s.value.node, _trig_exchanged(chosen))), new), si=None)
            for s in d.analysis.start)
        which = " and ".join(to_text(a) for a in chosen)
        yield DynamicsMutation(
            "angle_complement", f"Your value is what the velocities just before the impact "
            f"give with the sine and cosine of {which} exchanged: check which axis each angle "
            "is measured from, and which component each function gives.", BALANCES,
            problem=_mistaken(problem, replace(d, analysis=replace(d.analysis, start=starts))))


def _trig_exchanged(angles: tuple[Node, ...]) -> Callable[[Node], Node | None]:
    """The change for :func:`_rewrite` that puts cos for sin, and sin for cos, of ``angles``."""
    other = {"sin": "cos", "cos": "sin"}
    return lambda n: Call(other[n.func], n.args) if isinstance(n, Call) \
        and n.func in other and len(n.args) == 1 and n.args[0] in angles else None


def impulse_from_speeds(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The magnitude of the only impulse on a particle taken as the sum, or the difference,
    of its momenta's magnitudes m |v| after and before (speeds added or subtracted as numbers,
    the velocities' directions ignored): read in the right model. Only particles that move
    along fixed perpendicular axes (their speed before from the rates written)."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse):
        return
    struck = {b for c in d.analysis.contacts for b in c.bodies}
    before = {to_text(s.key.node): s for s in d.analysis.start}
    N = problem.inertial_frame
    for r, body in _only_reactions(d):
        if body.frame is not None or body.name in struck:
            continue
        moving = [e for c in problem.coordinates if not _zero(model, e := model.positions[
            body.centre].diff(model.language.value(Name(c.name)), model.inertial))]
        axes = _axes(problem, model, body.centre, moving[0]) if moving else None
        if axes is None:
            continue
        rates = (before.get(f"{q}'") for q in (axes[0],) + axes[1])
        speed = "sqrt(" + " + ".join(f"({_start_text(s)})^2" for s in rates) + ")"
        target = Call("mag", (Call("impulse", (Name(r.name),)),))
        for verb, combined in (("adds", f"speed({body.centre}, {N}) + {speed}"),
                               ("subtracts", f"abs(speed({body.centre}, {N}) - {speed})")):
            replacement = parse(f"({_mass(body)})*({combined})", functions=FUNCTIONS)
            readings = tuple((o.id, Expr(to_text(new), new)) for o in problem.objectives
                             if o.kind != ObjectiveKind.SYMBOLIC and any(n == target
                                                             for n in walk(o.find.node))
                             for new in (_rewrite(o.find.node, _replacing(target,
                                                                          replacement)),))
            if readings:
                yield DynamicsMutation(
                    "mag_as_sum", f"Your value {verb} the magnitudes of {body.name}'s momenta "
                    f"m v after and before the impact: the impulse of {r.name} is the change "
                    "of the momentum as a vector, m v₂ - m v₁, then its magnitude.", BALANCES,
                    readings=readings)


def _start_text(start: Start | None) -> str:
    """A rate at the start as written (its SI value where given as a quantity; 0 left out)."""
    if start is None:
        return "0"
    return start.value.text if start.value is not None else repr(start.si)


def _axes(problem: Problem, model: Model, point: str, line: Vector
          ) -> tuple[str, tuple[str, ...]] | None:
    """The coordinate that moves ``point`` along ``line`` and those that move it across, when
    each coordinate moves it along a fixed unit vector (its rectangular coordinates)."""
    N = model.inertial
    along, across = None, []
    coordinates = [model.language.value(Name(c.name)) for c in problem.coordinates]
    for coordinate in problem.coordinates:
        q = model.language.value(Name(coordinate.name))
        e = model.positions[point].diff(q, N)
        if _zero(model, e):
            continue
        if not identically_zero(model.plain((e & e) - 1)) or any(
                not identically_zero(model.plain(part.diff(x)))
                for part in e.to_matrix(N) for x in coordinates):
            return None
        if _zero(model, e ^ line) and identically_zero(model.plain((e & line) - 1)):
            along = coordinate.name
        elif identically_zero(model.plain(e & line)):
            across.append(coordinate.name)
        else:
            return None
    return (along, tuple(across)) if along is not None else None


def restitution_component(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A smooth impact (its impulse along the line of impact only) with the coefficient of
    restitution applied to the tangential component too: scaling it, or reversing it."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse):
        return
    axis = f"{problem.inertial_frame}.z"
    for i, c in enumerate(d.analysis.contacts):
        if not isinstance(c, Restitution):
            continue
        smooth = [r for r in d.reactions if {a.at for a in r.acts} == {c.at}
                  and [x.text for x in r.directions] == [c.direction.text]]
        # in the plane: the tangent is the normal turned about the inertial z
        across = model.language.vector(c.direction) & model.language.vector(_expr(axis))
        if len(smooth) != 1 or not identically_zero(model.plain(across)):
            continue
        tangent = _expr(f"cross({axis}, {c.direction.text})")
        reactions = tuple(replace(r, directions=r.directions + (tangent,)) if r is smooth[0]
                          else r for r in d.reactions)
        # the tangential velocity scaled by e (kept in sense), or reversed with it as the
        # normal one is; or e on the tangential component instead, the normal one reversed
        # unscaled (as if e = 1 along the line of impact)
        unchanged = ("e relates the velocities along the line of impact only; the smooth "
                     "contact leaves the tangential velocity unchanged.")
        for e_normal, e_tangent, how in (
                (c.e, _expr(f"-({c.e.text})"), f"scales the tangential velocity at {c.at} "
                 f"with the coefficient of restitution e = {{term}} too: {unchanged}"),
                (c.e, c.e, f"reverses and scales the tangential velocity at {c.at} with the "
                 f"coefficient of restitution e = {{term}} too: {unchanged}"),
                (_expr("1"), _expr(f"-({c.e.text})"), f"scales the tangential velocity at "
                 f"{c.at} by the coefficient of restitution e = {{term}} and reverses the "
                 "normal one unscaled: e belongs to the normal component (along the line of "
                 "impact); the smooth contact leaves the tangential velocity unchanged.")):
            contacts = d.analysis.contacts[:i] + (
                replace(c, e=e_normal), replace(c, direction=tangent, e=e_tangent)
            ) + d.analysis.contacts[i + 1:]
            changed = replace(d, reactions=reactions,
                              analysis=replace(d.analysis, contacts=contacts))
            yield DynamicsMutation(
                "restitution_component", f"Your value {how}", BALANCES,
                problem=_mistaken(problem, changed), term=c.e)
        yield from _restitution_on_each_tangent(problem, d, c, tangent)


def _restitution_on_each_tangent(problem: Problem, d: Dynamics, c: Restitution,
                                 tangent: Expr) -> Iterator[DynamicsMutation]:
    """Two particles colliding, each one's own tangential velocity reversed and scaled by e
    (as a ball's off a wall), where the smooth contact leaves both unchanged."""
    assert isinstance(d.analysis, Impulse)
    bodies = [d.body(name) for name in c.bodies if name != GROUND]
    if len(bodies) != 2 or any(b.frame is not None for b in bodies):
        return
    reactions = d.reactions + tuple(
        Reaction(f"{b.name}_tangential", (tangent,), (Act(b.name, b.centre),)) for b in bodies)
    contacts = d.analysis.contacts + tuple(
        Restitution(b.centre, (b.name, GROUND), tangent, c.e) for b in bodies)
    changed = replace(d, reactions=reactions, analysis=replace(d.analysis, contacts=contacts))
    yield DynamicsMutation(
        "restitution_component", f"Your value reverses each body's tangential velocity at "
        f"{c.at} with the coefficient of restitution e = {{term}} too: e relates the "
        "velocities along the line of impact only; the smooth contact leaves each body's "
        "tangential velocity unchanged.",
        BALANCES, problem=_mistaken(problem, changed), term=c.e)


def strands_miscounted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A cord's length written with a strand count of one
    (:func:`~.constraint_mutations.strands_once`), the bodies' motion solved again."""
    for m in strands_once(problem):
        yield DynamicsMutation(m.code, m.sentence, BALANCES,
                               problem=_mistaken(m.problem, dynamics_of(m.problem)))


def strands_pulling_miscounted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A cord that pulls one body through n strands (a block on a movable pulley: 2 T) and
    another body too, counted once in that body's balance (T for 2 T)."""
    d = dynamics_of(problem)
    for r in d.reactions:
        bodies = [a.on for a in r.acts if a.on != GROUND]
        if len(r.directions) != 1 or len(set(bodies)) < 2:
            continue
        for body in dict.fromkeys(bodies):
            count = bodies.count(body)
            if count < 2:
                continue
            first = next(a for a in r.acts if a.on == body)
            acts = tuple(a for a in r.acts if a.on != body or a is first)
            reactions = tuple(replace(x, acts=acts) if x is r else x for x in d.reactions)
            yield DynamicsMutation(
                "strands_miscounted", f"Your value counts the pull of {r.name} on {body} "
                f"once: {count} strands hold {body}, so the cord pulls it with {count} "
                f"{r.name}.", LOADS, problem=_mistaken(problem, replace(d, reactions=reactions)))


def force_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """Each applied force (a drag, a push, a drive) left out of its body's free-body diagram,
    one at a time: the motion as if only the weight and the supports acted."""
    d = dynamics_of(problem)
    for force in d.forces:
        if force.kind != LoadKind.APPLIED_FORCE:
            continue
        yield DynamicsMutation(
            "force_omitted", f"Your value is what the balances give without the force "
            f"{force.name} on {force.on} ({force.force.text}): include every force that acts "
            "on the body in its free-body diagram.", LOADS,
            problem=_mistaken(problem, replace(d, forces=tuple(
                f for f in d.forces if f is not force))))


def damping_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """Every damper left out: the undamped response (ω_n for ω_d, no decay)."""
    d = dynamics_of(problem)
    if not d.dampers:
        return
    names = ", ".join(x.name for x in d.dampers)
    yield DynamicsMutation(
        "damping_omitted", f"Your value is the undamped response: {names} "
        "(c = {term}) slows the motion and makes it decay; keep its force c x' in the "
        "equation of motion.", LOADS,
        problem=_mistaken(problem, replace(d, dampers=())), term=d.dampers[0].coefficient,
        term_unit="N*s/m")
    yield from _decay_omitted(problem, d)


def damped_for_natural(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """With a damper, the natural frequency ω_n asked read as the damped one,
    ω_d = ω_n √(1 − ζ²), the frequency the motion is seen to oscillate at."""
    if not dynamics_of(problem).dampers:
        return
    for q in problem.coordinates:
        yield from _read_as(
            problem, "omega_n", q.name, f"omega_n({q.name})*sqrt(1 - zeta({q.name})^2)",
            DynamicsMutation(
                "damped_for_natural", "Your value is the damped frequency ω_d = ω_n √(1 − ζ²), "
                "the one the damped motion oscillates at: the natural frequency ω_n is that of "
                "the motion without its damping.", OBJECTIVES))


def _decay_omitted(problem: Problem, d: Dynamics) -> Iterator[DynamicsMutation]:
    """A particle on one spring and one damper side by side, its response written at the
    damped frequency ω_d without the decay e^(−ζ ω_n t): the undamped motion of a spring
    k − c²/(4 m), whose ω_n is the damped ω_d. The spring's own force is left out (the
    mistaken spring's is no answer)."""
    if len(d.dampers) != 1 or len(d.springs) != 1:
        return
    damper, spring = d.dampers[0], d.springs[0]
    moving = [b for b in set(spring.on) if b != GROUND]
    if set(damper.between) != set(spring.between) or set(damper.on) != set(spring.on) \
            or len(moving) != 1 or d.body(moving[0]).frame is not None:
        return
    m, k, c = _mass(d.body(moving[0])), spring.stiffness.text, damper.coefficient.text
    softer = replace(spring, stiffness=_expr(f"({k}) - ({c})^2/(4*({m}))"))
    changed = replace(d, dampers=(), springs=(softer,))
    yield from _load_left_out(
        problem, changed, spring.name, "damping_omitted",
        f"Your value is the response at the damped frequency ω_d = {{term}} without its "
        f"decay: the motion is x = (v₀/ω_d) e^(−ζ ω_n t) sin(ω_d t), and {damper.name} "
        "makes it decay; keep the factor e^(−ζ ω_n t).",
        _expr(f"sqrt(({k})/({m}) - (({c})/(2*({m})))^2)"), "rad/s")


def springs_in_series(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """Springs combined the wrong way: those that hold one body from the ground along one line
    (in parallel: their stiffnesses add) combined as if in series, 1/k = 1/k1 + 1/k2, and the
    two that meet at a massless junction (in series) as if in parallel, k = k1 + k2."""
    d = dynamics_of(problem)
    yield from _series_as_parallel(problem, d)
    for body in d.bodies:
        held = [x for x in d.springs if set(x.on) == {body.name, GROUND}]
        if len(held) < 2:
            continue
        ends = [x.between[x.on.index(body.name)] for x in held]
        anchors = [x.between[x.on.index(GROUND)] for x in held]
        lines = [model.positions[a] - model.positions[e] for a, e in zip(anchors, ends)]
        if len(set(ends)) != 1 or any(not _zero(model, lines[0] ^ line) for line in lines[1:]):
            continue
        total = " + ".join(f"({x.stiffness.text})" for x in held)
        series = "1/(" + " + ".join(f"1/({x.stiffness.text})" for x in held) + ")"
        springs = tuple(replace(x, stiffness=_expr(f"({x.stiffness.text})*({series})/({total})"))
                        if x in held else x for x in d.springs)
        names = " and ".join(x.name for x in held)
        yield DynamicsMutation(
            "springs_in_series", f"Your value combines the springs {names} as if in series "
            f"(1/k = 1/k1 + 1/k2); both hold {body.name} from the ground, so they act in "
            "parallel and their stiffnesses add: k = {term}.", LOADS,
            problem=_mistaken(problem, replace(d, springs=springs)), term=_expr(total),
            term_unit="N/m")


def _series_as_parallel(problem: Problem, d: Dynamics) -> Iterator[DynamicsMutation]:
    """Both springs of a two-spring junction stiffened by (k1 + k2)^2/(k1 k2): in series
    they then act as k1 + k2, and the junction stays where it was."""
    for node in d.junctions:
        pair = [x for x in d.springs if node.name in x.on]
        if len(pair) != 2:
            continue
        total = " + ".join(f"({x.stiffness.text})" for x in pair)
        product = " * ".join(f"({x.stiffness.text})" for x in pair)
        springs = tuple(replace(x, stiffness=_expr(f"({x.stiffness.text})*({total})**2/"
                                                   f"({product})")) if x in pair else x
                        for x in d.springs)
        names = " and ".join(x.name for x in pair)
        yield DynamicsMutation(
            "springs_in_series", f"Your value combines the springs {names} as if in parallel "
            f"(k = k1 + k2); they meet at the massless {node.name} at {node.centre}, one after "
            "the other, so they act in series, 1/k = 1/k1 + 1/k2: k = {term}.", LOADS,
            problem=_mistaken(problem, replace(d, springs=springs)),
            term=_expr(f"{product}/({total})"), term_unit="N/m")


# each shape: its moment of inertia about its axis (coefficient of m r², as written), and the
# shapes its inertia is typically taken from instead
_CONFUSED_SHAPES = {Sphere: (Shell, Disk), Shell: (Sphere,), Disk: (Ring,), Ring: (Disk,)}
_SHAPES = {kind: (SHAPES[kind].name, SHAPES[kind].axial or "") for kind in _CONFUSED_SHAPES}


def other_shape_inertia(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A rigid body's moment of inertia taken from another shape's formula: a solid sphere's
    from a shell's or a disk's, a disk's from a ring's (every part of that shape and size),
    for a body turning in a plane, or spinning in a turning mount (a gyroscope's rotor)."""
    d = dynamics_of(problem)
    parents = {f.name: f.parent for f in problem.frames}
    for body in d.bodies:
        mount = parents.get(body.frame or "")
        if not _rotating(model, body) and (body.frame is None or mount is None or _zero(
                model, model.frames[body.frame].ang_vel_in(model.frames[mount]))):
            continue
        kinds = dict.fromkeys((type(p.shape), _radius(p.shape)) for p in body.parts
                              if type(p.shape) in _SHAPES)
        for kind, radius in kinds:
            for shape in _CONFUSED_SHAPES[kind]:
                mine = [type(p.shape) is kind and _radius(p.shape) == radius
                        for p in body.parts]
                parts = tuple(replace(p, shape=_reshaped(p.shape, shape)) if same else p
                              for p, same in zip(body.parts, mine))
                bodies = tuple(replace(b, parts=parts) if b.name == body.name else b
                               for b in d.bodies)
                own, coefficient = _SHAPES[kind]
                other, mistaken = _SHAPES[shape]
                mass = " + ".join(f"({p.mass.text})" for p, same in zip(body.parts, mine)
                                  if same)
                yield DynamicsMutation(
                    "other_shape_inertia", f"Your value uses the moment of inertia of {other} "
                    f"({_times(mistaken)}m r²) for {own} of radius {radius}: its moment of "
                    f"inertia is {_times(coefficient)}m r² = {{term}}.", BODIES,
                    problem=_mistaken(problem, replace(d, bodies=bodies),
                                      without=("ke", "angmom")),
                    term=_expr(f"({coefficient})*({mass})*({radius})^2"), term_unit="kg*m^2")


def particle_inertia(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A body turning on a pin with its own moment of inertia about its mass centre left out:
    taken as a particle at its mass centre (a simple pendulum of the pin's distance, m d²
    alone; a drum on its axle without inertia)."""
    d = dynamics_of(problem)
    if isinstance(d.analysis, WorkEnergy):  # there rotational_ke_omitted is the same model
        return
    for body in d.bodies:
        if not _rotating(model, body) or all(p.shape is None for p in body.parts):
            continue
        # on a pin (a pendulum, a drum): a rolling body as a particle is a body without
        # friction, a mistake of its own
        frame = body.frame
        assert frame is not None  # a turning body has its frame
        rolling = {q for c in problem.constraints if c.level is ConstraintLevel.VELOCITY
                   and (q := _rolling_on_ground(c, frame, problem.inertial_frame))}
        # a body turning about its fixed mass centre (a drum) as a particle has no inertia
        held = _zero(model, model.language.point_velocity(Name(body.centre),
                                                          problem.inertial_frame))
        if not held and not set(_pivots(problem, model, body)) - rolling:
            continue
        parts = tuple(replace(p, shape=None) for p in body.parts)
        bodies = tuple(replace(b, parts=parts) if b.name == body.name else b for b in d.bodies)
        code, sentence = ("inertia_omitted", f"Your value leaves out the moment of inertia "
                          f"of {body.name} about {body.centre}: it resists the angular "
                          "acceleration and belongs in its moment balance.") if held else (
            "other_shape_inertia", f"Your value takes {body.name} as a particle at its mass "
            f"centre {body.centre}: its own moment of inertia about {body.centre}, I_G, "
            "belongs in the moment balance too.")
        yield DynamicsMutation(
            code, sentence, BODIES,
            problem=_mistaken(problem, replace(d, bodies=bodies), without=("ke", "angmom")))


def disk_for_gyration(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A turning body whose inertia is given (m k², a radius of gyration) taken as a uniform
    disk of the radius at which a load acts on it (a drum's cord, a brake pad): m d²/2."""
    d = dynamics_of(problem)
    acting: dict[str, list[str]] = {}
    for load in (*d.reactions, *d.friction, *d.forces):
        acts = load.acts if isinstance(load, Reaction) else (Act(load.on, load.at),)
        for act in acts:
            acting.setdefault(act.on, []).append(act.at)
    for body in d.bodies:
        if not _rotating(model, body) or len(body.parts) != 1 \
                or not isinstance(body.parts[0].shape, Explicit):
            continue
        part = body.parts[0]
        assert isinstance(part.shape, Explicit)
        given = dict(part.shape.entries).get("zz")
        if given is None:
            continue
        for point in dict.fromkeys(acting.get(body.name, ())):
            offset = model.positions[point] - model.positions[body.centre]
            if point == body.centre or _zero(model, offset):
                continue
            radius = f"pos({point}, {body.centre})"
            zz = _expr(f"({part.mass.text})*dot({radius}, {radius})/2")
            bodies = tuple(replace(b, parts=(replace(part, shape=Explicit((("zz", zz),))),))
                           if b.name == body.name else b for b in d.bodies)
            yield DynamicsMutation(
                "other_shape_inertia", f"Your value takes {body.name} as a uniform disk of "
                f"radius {body.centre}{point} (m r²/2) where its moment of inertia is given: "
                "I = {term}.", BODIES,
                problem=_mistaken(problem, replace(d, bodies=bodies), without=("ke", "angmom")),
                term=given, term_unit="kg*m^2")


def _radius(shape: Shape | None) -> str:
    """The radius, as written, of a shape of ``_SHAPES``."""
    assert isinstance(shape, (Sphere, Shell, Disk, Ring)), shape
    return shape.radius.text


def _reshaped(shape, kind):
    if kind in (Disk, Ring):
        return kind(shape.radius, getattr(shape, "axis", "z"))
    return kind(shape.radius)


def _times(coefficient: str) -> str:
    return "" if coefficient == "1" else f"{coefficient} "


def spring_free_length_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A spring's force (and energy) taken from its whole length, k l, instead of its
    stretch k (l - l0): the free length left out."""
    d = dynamics_of(problem)
    for spring in d.springs:
        if identically_zero(model.plain(model.language.scalar(spring.length))):
            continue
        springs = tuple(replace(s, length=_expr("0")) if s is spring else s for s in d.springs)
        sentence = (f"Your value takes the force of spring {spring.name} from its whole length "
                    f"instead of its stretch: subtract the free length {spring.length.text} "
                    "= {term}.")
        yield DynamicsMutation(
            "spring_free_length_omitted", sentence, LOADS,
            problem=_mistaken(problem, replace(d, springs=springs)),
            term=spring.length, term_unit="m")
        # its energy ½ k l², read in the right model: the mistaken model may have no motion
        # at all (the whole-length energy more than the work done)
        whole = parse(f"({spring.stiffness.text})*mag(pos({spring.between[0]}, "
                      f"{spring.between[1]}))^2/2", functions=FUNCTIONS)
        readings = _readings(problem, "pe", spring.name, whole)
        if readings:
            yield DynamicsMutation("spring_free_length_omitted", sentence.replace(
                "force", "energy"), LOADS, readings=readings, term=spring.length,
                term_unit="m")


def spring_energy_from_change(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """In a work-energy balance, a spring's energy change taken as ½ k (s2 - s1)², the square
    of the change of its stretch, instead of ½ k s2² - ½ k s1²: the spring's energy counted
    from its length at the start (its free length replaced by that length)."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, WorkEnergy):
        return
    at_start = {}
    for start in d.analysis.start:
        if isinstance(start.key.node, Name):
            at_start[model.language.value(start.key.node)] = (
                model.language.value(start.value.node) if start.value is not None
                else start.si)
    for spring in d.springs:
        length = (model.positions[spring.between[0]]
                  - model.positions[spring.between[1]]).magnitude().subs(at_start)
        stretch = model.plain(length - model.language.scalar(spring.length))
        if any(length.has(model.language.value(Name(c.name))) for c in problem.coordinates) \
                or identically_zero(stretch):
            continue  # the start does not fix the length, or the spring is not stretched
        start_length = _expr(str(model.plain(length)))
        springs = tuple(replace(x, length=start_length) if x is spring else x
                        for x in d.springs)
        yield DynamicsMutation(
            "spring_energy_from_change", f"Your value takes the energy of spring "
            f"{spring.name} as ½ k (s2 - s1)², from the change of its stretch: its energy is "
            f"½ k s² at each end of the motion, and the change is ½ k s2² - ½ k s1², with the "
            "stretch s1 = {term} at the start.", LOADS,
            # the forces keep the stretch from the free length (an energy mistake)
            problem=_mistaken(problem, replace(d, springs=springs), without=("force",)),
            term=Expr(str(stretch), parse(str(stretch), functions=FUNCTIONS)), term_unit="m")


def spring_energy_half_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A spring's energy written k s² without its ½: in an energy balance, the same as a spring
    twice as stiff. Read for the energies and the speeds an energy balance gives (not the
    forces, which keep k s, nor the times)."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, (WorkEnergy, Integration)):
        return
    for spring in d.springs:
        springs = tuple(replace(x, stiffness=_expr(f"2*({x.stiffness.text})"))
                        if x is spring else x for x in d.springs)
        mistaken = _mistaken(problem, replace(d, springs=springs), without=("force",))
        energetic = ("ke", "pe", "speed")
        objectives = tuple(o for o in mistaken.objectives if (
            isinstance(o.find.node, Prime) and o.find.node.order == 1) or any(
                next(_calls(o.find.node, f), None) for f in energetic))
        if objectives:
            yield DynamicsMutation(
                "spring_energy_half_omitted", f"Your value takes the energy of spring "
                f"{spring.name} as k s², without its ½: a spring's energy is ½ k s² "
                "(k = {term}).", LOADS, problem=replace(mistaken, objectives=objectives),
                term=spring.stiffness, term_unit="N/m")


def spring_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """Each spring left out of the free-body diagrams (and of the energy), one at a time."""
    d = dynamics_of(problem)
    for spring in d.springs:
        yield from _load_left_out(
            problem, replace(d, springs=tuple(s for s in d.springs if s is not spring)),
            spring.name, "spring_omitted", f"Your value is what the balances give without the "
            f"spring {spring.name} (k = {{term}}): its force, and its energy in a work-energy "
            "balance, belong in the equations.", spring.stiffness, "N/m")


def spring_force_as_resultant(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """One spring's force on a body that two or more springs hold from fixed points read as
    all their forces together, (k1 + k2) x for k2 x: the equivalent spring's force (the
    springs in parallel, as ω_n combines them) for the one asked. A spring between two
    moving bodies is no part of such a pair."""
    springs = [s for s in dynamics_of(problem).springs if GROUND in s.on]
    on = {s.name: next((b for b in s.on if b != GROUND), None) for s in springs}
    for spring in springs:
        together = [s.name for s in springs if on[s.name] == on[spring.name]]
        if on[spring.name] is None or len(together) < 2:
            continue
        resultant = " + ".join(f"force({name})" for name in together)
        listed = f"{', '.join(together[:-1])} and {together[-1]}"
        yield from _read_as(
            problem, "force", spring.name, f"({resultant})", DynamicsMutation(
                "spring_force_as_resultant", f"Your value is the force of the springs "
                f"{listed} together on {on[spring.name]} ({{term}}): the force "
                f"of {spring.name} alone is its own stiffness times its own stretch.",
                OBJECTIVES, term=_expr(f"mag({resultant})"), term_unit="N"))


def _read_as(problem: Problem, func: str, name: str, replacement: str,
             mistake: DynamicsMutation) -> Iterator[DynamicsMutation]:
    """``mistake`` with its readings, ``func(name, ...)`` read as ``replacement`` in each
    objective that calls it (:func:`_readings`); nothing when none does."""
    readings = _readings(problem, func, name, parse(replacement, functions=FUNCTIONS))
    if readings:
        yield replace(mistake, readings=readings)


def force_component_reversed(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """An applied force slanted to a one-direction reaction on its body (a push slanted down
    onto a floor) taken with its part along the reaction the other way (the downward part
    taken upward: the body pressed less), its part across kept."""
    d = dynamics_of(problem)
    for force in d.forces:
        if force.kind != LoadKind.APPLIED_FORCE:
            continue
        vector = model.language.vector(force.force)
        for r in d.reactions:
            if len(r.directions) != 1 or not any(a.on == force.on for a in r.acts):
                continue
            direction = r.directions[0]
            along = model.language.vector(direction)
            if _zero(model, (vector & along) * along) or _zero(model, vector ^ along):
                continue  # no part along the reaction, or none across: not slanted to it
            unit = f"unit({direction.text})"
            text = f"({force.force.text}) - 2*dot({force.force.text}, {unit})*{unit}"
            forces = tuple(replace(f, force=_expr(text)) if f is force else f
                           for f in d.forces)
            yield DynamicsMutation(
                "force_component_reversed", f"Your value is what the balances give with the "
                f"part of {force.name} along {r.name} taken the other way: check which way "
                f"each component of {force.name} points.", LOADS,
                problem=_mistaken(problem, replace(d, forces=forces)))


def spring_work_reversed(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """In a work-energy balance, each spring's work taken with the wrong sign (its energy
    change counted as helping the motion where it resists it, or the reverse): the spring's
    stiffness negated, one spring at a time. Only the objectives of the motion: the spring's
    own energy and the forces (which the negated spring would push the other way) left out."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, WorkEnergy):
        return
    for spring in d.springs:
        springs = tuple(replace(s, stiffness=_expr(f"-({s.stiffness.text})"))
                        if s is spring else s for s in d.springs)
        mistaken = _without_load(problem, replace(d, springs=springs), spring.name)
        if mistaken is None:
            continue
        objectives = tuple(o for o in mistaken.objectives if not any(
            next(_calls(o.find.node, f), None) for f in ("force", "moment", "power")))
        if objectives:
            yield DynamicsMutation(
                "spring_work_reversed", f"Your value counts the work of the spring "
                f"{spring.name} (k = {{term}}) with the wrong sign: a spring that stretches "
                "further takes energy from the motion, one that relaxes gives it back; its "
                "work is minus the change of ½ k s².", LOADS,
                problem=replace(mistaken, objectives=objectives), term=spring.stiffness,
                term_unit="N/m")


def _load_left_out(problem: Problem, dynamics: Dynamics, load: str, code: str, text: str,
                   term, term_unit: str) -> Iterator[DynamicsMutation]:
    """The mistake ``code`` of the model with ``dynamics`` (``load`` left out), when that model
    still stands (:func:`_without_load`)."""
    mistaken = _without_load(problem, dynamics, load)
    if mistaken is not None:
        yield DynamicsMutation(code, text, LOADS, problem=mistaken, term=term,
                               term_unit=term_unit)


def _without_load(problem: Problem, dynamics: Dynamics, load: str) -> Problem | None:
    """The mistaken copy of a model with ``load`` left out, without the objectives about the
    load itself (its force, its energy have no value there); ``None`` when none is left."""
    mistaken = _mistaken(problem, dynamics)
    objectives = tuple(o for o in mistaken.objectives
                       if not any(n == Name(load) for n in walk(o.find.node)))
    return replace(mistaken, objectives=objectives) if objectives else None


def load_at_other_point(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A spring or the weight taken to act at another point of a turning body (a spring taken
    at the mass centre, the weight at the end where the spring holds it): the point another
    load acts at, or the mass centre, never a point that does not move (there the load would
    have no moment). One spring, or one body's weight, at a time."""
    d = dynamics_of(problem)
    N = problem.inertial_frame
    for body in d.bodies:
        if not _rotating(model, body):
            continue
        frame = body.frame
        assert frame is not None  # a turning body has its frame
        at = [a.at for r in d.reactions for a in r.acts if a.on == body.name]
        at += [f.at for f in (*d.forces, *d.friction) if f.on == body.name]
        at += [s.between[i] for s in d.springs for i in (0, 1) if s.on[i] == body.name]
        points = [p for p in dict.fromkeys([body.centre, *at])
                  if not _zero(model, model.language.point_velocity(Name(p), N))
                  and _zero(model, model.language.point_velocity(Name(p), frame))]
        for spring in d.springs:
            for i in (0, 1):
                if spring.on[i] != body.name:
                    continue
                for point in points:
                    if _zero(model, model.positions[point]
                             - model.positions[spring.between[i]]):
                        continue
                    between = (point, spring.between[1]) if i == 0 else \
                        (spring.between[0], point)
                    springs = tuple(replace(s, between=between) if s is spring else s
                                    for s in d.springs)
                    yield DynamicsMutation(
                        "load_at_other_point", f"Your value takes the spring {spring.name} "
                        f"at {point} of {body.name}: it acts at {spring.between[i]}, "
                        f"{{term}} from {point}, and its moment depends on where.", LOADS,
                        problem=_mistaken(problem, replace(d, springs=springs)),
                        term=_expr(f"mag(pos({spring.between[i]}, {point}))"), term_unit="m")
        if d.gravity is None:
            continue
        for point in points:
            if point == body.centre or _zero(model, model.positions[point]
                                             - model.positions[body.centre]):
                continue
            # the weights as forces, this body's at the other point
            weights = tuple(Force(f"weight~{b.name}", b.name,
                                  point if b.name == body.name else b.centre,
                                  _expr(f"({_mass(b)})*({d.gravity.text})"), b.where,
                                  kind=LoadKind.WEIGHT) for b in d.bodies)
            yield DynamicsMutation(
                "load_at_other_point", f"Your value takes the weight of {body.name} at "
                f"{point}: it acts at the mass centre {body.centre}, {{term}} from {point}.",
                LOADS, problem=_mistaken(problem, replace(d, gravity=None,
                                                          forces=d.forces + weights)),
                term=_expr(f"mag(pos({body.centre}, {point}))"), term_unit="m")


def force_at_other_point(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """An applied force on a body that another single-direction reaction also acts on (a
    lever's push and its pad) taken at that reaction's point, the lever's advantage ignored;
    or the two exchanged, each at the other's point (the lever arms inverted). A pin's point
    (a reaction along two directions) is not taken: there the force would have no moment."""
    d = dynamics_of(problem)
    for force in d.forces:
        if force.kind != LoadKind.APPLIED_FORCE:
            continue
        for r in d.reactions:
            acts = [a for a in r.acts if a.on == force.on]
            if len(r.directions) != 1 or len(acts) != 1 or _zero(
                    model, model.positions[acts[0].at] - model.positions[force.at]):
                continue
            at = acts[0].at
            moved = replace(d, forces=tuple(replace(f, at=at) if f is force else f
                                            for f in d.forces))
            term = _expr(f"mag(pos({force.at}, {at}))")
            yield DynamicsMutation(
                "load_at_other_point", f"Your value takes the force {force.name} on "
                f"{force.on} at {at}, where {r.name} acts: it acts at {force.at}, {{term}} "
                f"from {at}, and its moment depends on where.", LOADS,
                problem=_mistaken(problem, moved), term=term, term_unit="m")
            acts_moved = tuple(replace(a, at=force.at) if a is acts[0] else a for a in r.acts)
            exchanged = replace(moved, reactions=tuple(replace(x, acts=acts_moved) if x is r
                                                       else x for x in d.reactions))
            yield DynamicsMutation(
                "load_at_other_point", f"Your value exchanges the points of {force.name} and "
                f"{r.name} on {force.on}: {force.name} acts at {force.at} and {r.name} at {at}, "
                "{term} apart, and their moments depend on where.", LOADS,
                problem=_mistaken(problem, exchanged), term=term, term_unit="m")
            yield from _arm_from_pin(problem, model, d, force, at)


def _arm_from_pin(problem: Problem, model: Model, d: Dynamics, force: Force, pad: str
                  ) -> Iterator[DynamicsMutation]:
    """A force whose point is given from a reaction's point (a lever's push c beyond the pad)
    taken that far from the body's pin instead: its arm about the pin measured from the pad
    (N b = P c for N b = P (b + c))."""
    point = next(x for x in problem.points if x.name == force.at)
    if point.origin != pad or point.position is None:
        return
    pins = [a.at for r in d.reactions if len(r.directions) > 1 for a in r.acts
            if a.on == force.on and _zero(model, model.language.point_velocity(
                Name(a.at), problem.inertial_frame))]
    names = {x.name for x in problem.points}
    for pin in dict.fromkeys(pins):
        moved = f"{force.at}_from_{pin}"
        if moved in names:
            continue
        mistaken = replace(problem, points=problem.points + (replace(point, name=moved,
                                                                     origin=pin),))
        changed = replace(d, forces=tuple(replace(f, at=moved) if f is force else f
                                          for f in d.forces))
        yield DynamicsMutation(
            "load_at_other_point", f"Your value measures the arm of {force.name} about the "
            f"pin {pin} from {pad}, the point {force.at} is given from: about {pin} the arm is "
            f"measured from {pin}, {{term}}.", BALANCES,
            problem=_mistaken(mistaken, changed),
            term=_expr(f"mag(pos({force.at}, {pin}))"), term_unit="m")


def static_friction_as_mu_m_g(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The friction at a contact that does not slip read as μ m g (the limiting value, with
    the weight for the normal force) in the sense it acts: static friction is what the
    balances need, up to μ N."""
    d = dynamics_of(problem)
    if d.gravity is None or isinstance(d.analysis, Impulse):
        return
    for f in d.friction:
        if not isinstance(f, StaticFriction):
            continue
        weight = _weight(d.body(f.on), d.gravity)
        replacement = parse(f"({f.mu.text})*({weight.text})*force({f.name})"
                            f"/mag(force({f.name}))", functions=FUNCTIONS)
        readings = _readings(problem, "force", f.name, replacement)
        if readings:
            yield DynamicsMutation(
                "normal_from_weight", f"Your value takes the friction {f.name} as μ m g = "
                f"{{term}}: the contact does not slip, so the friction is what the balances "
                f"need (at most μ N, with N = {f.normal} from its own balance).", BALANCES,
                readings=readings, term=_expr(f"({f.mu.text})*({weight.text})"),
                term_unit="N")


def contact_taken_smooth(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A contact that rolls without slip taken as smooth: its static friction left out, and
    with it the rolling (the body slides, a = P/m for a pulled wheel); the objectives about
    the friction itself left out (it has none)."""
    d = dynamics_of(problem)
    for f in d.friction:
        if not isinstance(f, StaticFriction):
            continue
        # the rolling constraints at the contact: vel(coincident(C, B), N) = ...
        rolling = [c for c in problem.constraints if c.level is ConstraintLevel.VELOCITY
                   and isinstance(c.lhs.node, Call) and c.lhs.node.func == "vel"
                   and isinstance(c.lhs.node.args[0], Call)
                   and c.lhs.node.args[0].func == "coincident"
                   and c.lhs.node.args[0].args[0] == Name(f.at)]
        if not rolling:
            continue
        smooth = replace(problem, constraints=tuple(c for c in problem.constraints
                                                    if c not in rolling))
        yield from _load_left_out(
            smooth, replace(d, friction=tuple(x for x in d.friction if x is not f)), f.name,
            "contact_taken_smooth", f"Your value takes the contact at {f.at} as smooth: the "
            f"friction {f.name} (= {{term}}) keeps {f.on} from slipping there, and belongs in "
            "its balances with the rolling condition.", _expr(f"mag(force({f.name}))"), "N")


def rolling_assumed(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A body turning about z that slips on the ground (a kinetic-friction contact) taken to
    roll without slip: the model with the rolling condition at the contact and the friction an
    unknown along the ground, its spin's given rate left to the rolling condition; and the
    angular acceleration read from the mass centre's by the rolling relation
    (α = -a_G·(k × r_CG)/|r_CG|², a/r), the slipping acceleration kept."""
    d = dynamics_of(problem)
    N = problem.inertial_frame
    for f in d.friction:
        if not isinstance(f, KineticFriction) or f.surface not in (GROUND, N):
            continue
        body = d.body(f.on)
        if not _rotating(model, body) or f.at == body.centre:
            continue
        assert body.frame is not None  # a turning body has its frame
        frame = next(x for x in problem.frames if x.name == body.frame)
        angle = frame.rotations[0].angle.node if len(frame.rotations) == 1 else None
        if not isinstance(angle, Name):
            continue
        radius = f"pos({f.at}, {body.centre})"
        slip_alpha = parse(f"-dot(acc({body.centre}, {N}), cross({N}.z, {radius}))"
                           f"/dot({radius}, {radius})", functions=FUNCTIONS)
        second = Prime(angle.id, 2)
        readings = []
        for obj in problem.objectives:
            if obj.kind != ObjectiveKind.SYMBOLIC and second in walk(obj.find.node):
                new = _rewrite(obj.find.node, _replacing(second, slip_alpha))
                readings.append((obj.id, Expr(to_text(new), new)))
        sentence = (f"Your value takes {body.name} to roll without slipping at {f.at}: it "
                    f"slips there (the friction {f.name} is μ N = {{term}}), so a_G and α are "
                    "not tied by a = α r; each comes from its own momentum balance.")
        term = _expr(f"mag(force({f.name}))")
        if readings:
            yield DynamicsMutation("rolling_assumed", sentence, OBJECTIVES,
                                   readings=tuple(readings), term=term, term_unit="N")
        normal = next(r for r in d.reactions if r.name == f.normal)
        grip = Reaction(f.name, (_expr(f"cross({normal.directions[0].text}, {N}.z)"),),
                        (Act(f.on, f.at),), f.where, surface=GROUND)
        rolls = Constraint(f"rolling~{f.at}", ConstraintLevel.VELOCITY,
                           _expr(f"vel(coincident({f.at}, {body.frame}), {N})"),
                           _expr(f"vel(coincident({f.at}, {N}), {N})"), f.where)
        spin = f"{angle.id}'"
        rolling = replace(problem, constraints=problem.constraints + (rolls,),
                          givens=tuple(g for g in problem.givens if g.key.text != spin))
        changed = replace(d, friction=tuple(x for x in d.friction if x is not f),
                          reactions=d.reactions + (grip,))
        yield DynamicsMutation("rolling_assumed", sentence, BALANCES,
                               problem=_mistaken(rolling, changed), term=term, term_unit="N")


def surface_taken_fixed(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A kinetic-friction contact between two bodies (a block sliding on a cart) with the
    body it slides on taken as fixed: the friction acts on the slider only, its reaction on
    the other body left out."""
    d = dynamics_of(problem)
    bodies = {b.name for b in d.bodies}
    for f in d.friction:
        if not isinstance(f, KineticFriction) or f.surface not in bodies:
            continue
        friction = tuple(replace(x, surface=GROUND) if x is f else x for x in d.friction)
        # the slider's friction is μ N in both models, and where its slip on the ground ends
        # it has no direction: no force is read from the mistaken model
        yield DynamicsMutation(
            "surface_taken_fixed", f"Your value is what the balances give with {f.surface} "
            f"taken as fixed: the friction {f.name} (μ N = {{term}}) acts on {f.surface} too, "
            f"the opposite way, and sets it moving.", LOADS,
            problem=_mistaken(problem, replace(d, friction=friction), without=("force",)),
            term=_expr(f"mag(force({f.name}))"), term_unit="N")


def body_ke_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """In an objective that adds the kinetic energies of two or more bodies (the energy a
    block sliding on a cart loses), one body's kinetic energy left out."""
    d = dynamics_of(problem)
    N = problem.inertial_frame
    several = {o.id for o in problem.objectives
               if len({c.args[0] for c in _calls(o.find.node, "ke")}) > 1}
    for body in d.bodies:
        readings = tuple((oid, find) for oid, find in _readings(
            problem, "ke", body.name, parse("0", functions=FUNCTIONS)) if oid in several)
        if readings:
            yield DynamicsMutation(
                "body_ke_omitted", f"Your value leaves out the kinetic energy of {body.name} "
                "(= {term}): the system's kinetic energy adds those of all its bodies.",
                OBJECTIVES, readings=readings, term=_expr(f"ke({body.name}, {N})"),
                term_unit="J")


def moment_arm_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A particle's angular momentum r × m v about a point read without the length of r:
    m v across the line to the point (m r θ' for m r² θ'), the moment arm dropped."""
    for body in dynamics_of(problem).bodies:
        if any(p.shape is not None or p.at != body.centre for p in body.parts):
            continue  # a rigid body's own spin I ω has no single arm to drop
        for call in {c for o in problem.objectives for c in _calls(o.find.node, "angmom")
                     if c.args[0] == Name(body.name)}:
            about, frame = (name_of(a) for a in call.args[1:])
            arm = f"pos({body.centre}, {about})"
            if identically_zero(model.plain(model.language.value(parse(
                    f"mag({arm})", functions=FUNCTIONS)))):
                continue
            replacement = parse(f"cross(unit({arm}), momentum({body.name}, {frame}))",
                                functions=FUNCTIONS)
            readings = tuple(r for r in _readings(problem, "angmom", body.name, replacement)
                             if r[1].node != problem.objective(r[0]).find.node)
            if readings:
                yield DynamicsMutation(
                    "moment_arm_omitted", f"Your value is the momentum m v of {body.name} "
                    f"across the line from {about}, without its arm r = {{term}}: the angular "
                    f"momentum about {about} is r × m v (m r² θ' in polar coordinates).",
                    OBJECTIVES, readings=readings, term=_expr(f"mag({arm})"), term_unit="m")


def angmom_along_axis(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """The angular momentum about its mass centre of a disk or ring whose angular velocity
    is tilted from its axis read as I_axis ω, the axial moment of inertia times the
    angular velocity: along ω (the tilt ignored) or along the body's axis (H taken parallel
    to the axis of symmetry). A planar body, ω along or across its axis, has none."""
    for body in dynamics_of(problem).bodies:
        shapes = [p.shape for p in body.parts]
        if body.frame is None or len(body.parts) != 1 or body.parts[0].at != body.centre \
                or not isinstance(shapes[0], (Disk, Ring)):
            continue
        shape, mass = shapes[0], body.parts[0].mass.text
        frame = model.frames[body.frame]
        omega, axis = frame.ang_vel_in(model.inertial), getattr(frame, shape.axis)
        if _zero(model, omega.cross(axis)) or identically_zero(model.plain(omega & axis)):
            continue
        inertia = _expr(f"({SHAPES[type(shape)].axial})*({mass})*({shape.radius.text})^2")
        for call in {c for o in problem.objectives for c in _calls(o.find.node, "angmom")
                     if c.args[0] == Name(body.name)}:
            about, within = (name_of(a) for a in call.args[1:])
            if not _zero(model, model.positions[about] - model.positions[body.centre]):
                continue  # about another point r × m v_G belongs too: another mistake
            spin = f"angvel({body.frame}, {within})"
            for replacement, where in (
                    (f"({inertia.text})*{spin}", "along the angular velocity ω"),
                    (f"({inertia.text})*mag({spin})*{body.frame}.{shape.axis}",
                     f"along the axis {body.frame}.{shape.axis} of {body.name}")):
                yield from _read_as(problem, "angmom", body.name, replacement, DynamicsMutation(
                    "angmom_along_axis", f"Your value takes the angular momentum of "
                    f"{body.name} as I ω {where}, with I = {{term}} about its axis: ω "
                    f"is tilted from that axis, and H = I_G·ω adds the parts of ω along "
                    f"and across the axis, each times its own moment of inertia.",
                    OBJECTIVES, term=inertia, term_unit="kg*m^2"))


def impulse_moment_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A known blow on a turning body away from its mass centre taken to act at the centre:
    its moment, which sets the body spinning, left out of the angular momentum balance."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Impulse):
        return
    for blow in d.impulses:
        body = d.body(blow.on)
        if not _rotating(model, body) or _zero(model, model.positions[blow.at]
                                               - model.positions[body.centre]):
            continue
        impulses = tuple(replace(x, at=body.centre) if x is blow else x for x in d.impulses)
        # a body that does not spin has no instantaneous centre
        yield DynamicsMutation(
            "impulse_moment_omitted", f"Your value takes the blow {blow.name} at the mass "
            f"centre {body.centre}: it acts at {blow.at}, {{term}} from {body.centre}, and its "
            f"moment about {body.centre} sets {body.name} spinning.", BALANCES,
            problem=_mistaken(problem, replace(d, impulses=impulses), without=("ic",)),
            term=_expr(f"mag(pos({blow.at}, {body.centre}))"), term_unit="m")


_NEAR_REST = 1e-6
"""A rate's share of its initial value a motion "started from rest" keeps (its sense)."""


def initial_speed_omitted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A motion integrated, or reached by work and energy, from a state with a rate that is
    not zero, worked out from rest instead: the initial speed (or spin) left out."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, (Integration, WorkEnergy)):
        return
    for i, start in enumerate(d.analysis.start):
        key = start.key.node
        if not isinstance(key, Prime) or key.order != 1:
            continue
        # at rest but about to move the same way: the direction of kinetic friction, or an
        # event on the rate, stays defined at the start
        if start.value is not None and not identically_zero(model.plain(
                model.language.value(start.value.node))):
            rest = replace(start, value=_expr(f"{_NEAR_REST}*({start.value.text})"))
            term, shown = start.value, f" ({start.value.text})"
        elif start.value is None and start.si:
            rest = replace(start, si=_NEAR_REST * start.si)
            term, shown = _expr(f"{start.si!r}"), ""
        else:
            continue
        starts = d.analysis.start[:i] + (rest,) + d.analysis.start[i + 1:]
        yield DynamicsMutation(
            "initial_speed_omitted", f"Your value is what the motion started with "
            f"{start.key.text} = 0 gives: at the start {start.key.text} = {{term}}{shown}; "
            "keep the initial speed.", BALANCES,
            problem=_mistaken(problem, replace(d, analysis=replace(d.analysis, start=starts))),
            term=term, term_unit=given_unit(key, problem.coordinates, problem.parameters) or "1")


def initial_displacement_omitted(problem: Problem, model: Model
                                 ) -> Iterator[DynamicsMutation]:
    """A vibration (a motion integrated from a start, held by springs) started from a
    coordinate's value that is not zero, worked out from zero instead: the initial
    displacement left out (an amplitude v0/ω_n, a first stop a quarter period on)."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Integration) or not d.springs:
        return
    for i, start in enumerate(d.analysis.start):
        if not isinstance(start.key.node, Name):
            continue
        if start.value is not None:
            if identically_zero(model.plain(model.language.value(start.value.node))):
                continue
            term = start.value
        elif start.si:
            term = _expr(f"{start.si!r}")
        else:
            continue
        at_zero = replace(start, value=_expr("0"), si=0.0)
        starts = d.analysis.start[:i] + (at_zero,) + d.analysis.start[i + 1:]
        unit = given_unit(start.key.node, problem.coordinates, problem.parameters) or "1"
        yield DynamicsMutation(
            "initial_displacement_omitted", f"Your value is what the motion started from "
            f"{start.key.text} = 0 gives: at the start {start.key.text} = {{term}}; the "
            "initial displacement changes the amplitude and when the motion turns back.",
            BALANCES,
            problem=_mistaken(problem, replace(d, analysis=replace(d.analysis, start=starts))),
            term=term, term_unit=unit)


def value_at_start(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A motion integrated to an event with the objectives read at its start instead: a force,
    rate or acceleration that varies along the motion (a drag at the initial speed, a drive
    force P/v at the initial speed) taken at its initial value. The coordinates and the time
    themselves, which start from the spec's own values, are left out."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Integration):
        return
    # an event at the start is refused (its instant is t = 0): a moment after it
    early = replace(d.analysis, until=(_expr("t"), _expr(f"{_NEAR_REST}")))
    mistaken = _mistaken(problem, replace(d, analysis=early))
    objectives = tuple(o for o in mistaken.objectives if not isinstance(o.find.node, Name))
    if not objectives:
        return
    event = f"{d.analysis.until[0].text} = {d.analysis.until[1].text}"
    yield DynamicsMutation(
        "value_at_start", f"Your value is the one at the start of the motion (t = 0); it "
        f"changes along the motion: read it at the instant asked for ({event}).", BALANCES,
        problem=replace(mistaken, objectives=objectives))


def transverse_speed_kept(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A motion integrated from a start along polar coordinates (a point at r E.x, frame E
    turning by θ) with the transverse speed r θ̇ taken as conserved instead of r² θ̇ (the
    angular momentum): θ̇ read as r₀ θ̇₀ / r, with the start's values."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Integration):
        return
    at_start = {to_text(s.key.node): s.value.text if s.value is not None else repr(s.si)
                for s in d.analysis.start}
    coordinates = {c.name for c in problem.coordinates}
    for frame in problem.frames:
        angle = frame.rotations[0].angle.node if len(frame.rotations) == 1 else None
        if not (isinstance(angle, Name) and angle.id in coordinates and frame.origin):
            continue
        for point in problem.points:
            node = point.position.node if point.position is not None else None
            if point.origin != frame.origin or not (
                    isinstance(node, Bin) and node.op == "*" and isinstance(node.left, Name)
                    and node.left.id in coordinates and node.right == Attr(frame.name, "x")):
                continue
            r, rate = node.left.id, f"{angle.id}'"
            if r not in at_start or rate not in at_start:
                continue
            kept = _expr(f"({at_start[r]})*({at_start[rate]})/{r}")
            readings = tuple((o.id, kept) for o in problem.objectives
                             if to_text(o.find.node) == rate)
            if readings:
                yield DynamicsMutation(
                    "transverse_speed_kept", f"Your value keeps the transverse speed "
                    f"{textbook(r)} {textbook(rate)} of {point.name} from the start: the speed "
                    "is not what the motion conserves; with no moment about "
                    f"{frame.origin}, the angular momentum m {textbook(r)}² {textbook(rate)} "
                    "is.", OBJECTIVES, readings=readings)


def force_taken_constant(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A motion integrated from a start, with each applied force that depends on the state (a
    drag c v², a drive P/v) taken constant at its value at the start: the acceleration taken
    constant, as in v² = v0² + 2 a s. Read for where the motion gets to (the coordinates,
    their rates, the time)."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Integration):
        return
    at_start = {to_text(s.key.node): s.value.node if s.value is not None else Num(repr(s.si))
                for s in d.analysis.start}
    state = {c.name for c in problem.coordinates}

    def start_value(node: Node) -> Node | None:
        if isinstance(node, (Name, Prime)) and (
                node.id in state if isinstance(node, Name) else True):
            return at_start.get(to_text(node), node)
        return None

    varying = [f for f in d.forces if any(
        (isinstance(n, Name) and n.id in state) or isinstance(n, Prime)
        for n in walk(f.force.node))]
    if not varying or any(to_text(n) not in at_start for f in varying
                          for n in walk(f.force.node) if (isinstance(n, Name) and n.id in state)
                          or isinstance(n, Prime)):
        return
    forces = tuple(replace(f, force=Expr(f.force.text, _rewrite(f.force.node, start_value)))
                   if f in varying else f for f in d.forces)
    names = ", ".join(f.name for f in varying)
    # where the motion gets to (a time, a distance, a speed): the forces themselves and the
    # acceleration keep their starting values, which value_at_start names
    mistaken = _mistaken(problem, replace(d, forces=forces))
    reached = tuple(o for o in mistaken.objectives if isinstance(o.find.node, Name)
                    or (isinstance(o.find.node, Prime) and o.find.node.order == 1))
    if not reached:
        return
    yield DynamicsMutation(
        "force_taken_constant", f"Your value takes {names} constant at its value at the start "
        f"of the motion ({', '.join(f.force.text for f in varying)} with the starting state): "
        "it changes as the body moves, so the acceleration is not constant; integrate "
        "a = F/m along the motion (v dv = a dx, dv/dt = a).", BALANCES,
        problem=replace(mistaken, objectives=reached))


def mean_of_end_rates(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A motion along one coordinate integrated from a stated start, read as uniformly
    accelerated between its ends: the distance as the mean of the start and end rates times
    the time, the time as the distance over that mean (a car at constant power, a boat slowed
    by drag); where the start's rate is stated. And read at its final speed throughout: the
    time as the distance over the final speed (a puck leaving a spring), the distance as that
    speed times the time. The right end rate and time, the mistake in between."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Integration) or len(problem.coordinates) != 1:
        return
    q = problem.coordinates[0].name
    at_start = {to_text(s.key.node): s.value.text if s.value is not None else repr(s.si)
                for s in d.analysis.start}
    if q not in at_start:
        return
    x0 = at_start[q]
    # the event may fix the final speed at 0 (a stop) or the coordinate at its start (a
    # return): a reading there over that zero has no value, only the rounding of its state
    stops, returns = (_event_at(problem, model, node, value) for node, value in (
        (Prime(q, 1), Num("0")), (Name(q), _start_value(d.analysis, q))))
    speeds = [("end_speed_throughout", f"{q}'", "at its final speed throughout: the speed "
               "changes along the motion")]
    v0 = at_start.get(f"{q}'")
    if v0 is not None:
        speeds.insert(0, ("mean_of_end_rates", f"(({v0}) + {q}')/2",
                          "as uniformly accelerated, with the mean of the starting and final "
                          "speeds: the acceleration changes along the motion"))
    for code, speed, how in speeds:
        instead = {q: f"({x0}) + ({speed})*t", "t": f"({q} - ({x0}))/({speed})"}
        undefined = {q, "t"} if stops and code == "end_speed_throughout" else \
            {"t"} if returns else set()
        readings = tuple((o.id, _expr(instead[o.find.node.id])) for o in problem.objectives
                         if isinstance(o.find.node, Name) and o.find.node.id in instead
                         and not (o.find.node.id in undefined and _at_the_event(problem, o)))
        if readings:
            yield DynamicsMutation(
                code, f"Your value takes the motion {how}, so the distance is the integral "
                "of the speed over the time, not one speed times the time.", OBJECTIVES,
                readings=readings)


def _start_value(analysis: Integration, q: str) -> Node:
    """The value ``q`` starts at (``analysis`` states it)."""
    (start,) = (s for s in analysis.start if to_text(s.key.node) == q)
    return start.value.node if start.value is not None else Num(repr(start.si))


def _at_the_event(problem: Problem, objective) -> bool:
    """Whether ``objective`` is read at the integration's event (not at an instant or a
    ``when`` of its own)."""
    return objective.when is None and instant_of_objective(
        problem, {g.key.text: g for g in objective.givens}) is None


def _event_at(problem: Problem, model: Model, node: Node, value: Node) -> bool:
    """Whether ``problem``'s integration event holds where ``node`` (a coordinate or its rate)
    takes ``value``: its two sides equal there, whatever else."""
    d = dynamics_of(problem)
    assert isinstance(d.analysis, Integration)
    if any(isinstance(n, Call) and n.func not in model.language.functions
           for e in d.analysis.until for n in walk(e.node)):
        return False  # an event on a force or an energy: not a coordinate's or rate's value
    lhs, rhs = (model.plain(model.language.value(e.node)) for e in d.analysis.until)
    at = model.plain(model.language.value(node))
    return (lhs - rhs).has(at) and identically_zero(
        (lhs - rhs).subs(at, model.plain(model.language.value(value))))


def spring_taken_constant(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A motion integrated from a start, with each spring's force taken constant at its value
    at the start (k δ over the whole stroke: the acceleration taken constant). Read for where
    the motion gets to (the coordinates, their rates, the time), as
    :func:`force_taken_constant`; only where the start fixes each spring's length."""
    d = dynamics_of(problem)
    if not isinstance(d.analysis, Integration) or not d.springs:
        return
    at_start = {model.language.value(s.key.node): (
        model.language.value(s.value.node) if s.value is not None else s.si)
        for s in d.analysis.start if isinstance(s.key.node, Name)}
    coordinates = [model.language.value(Name(c.name)) for c in problem.coordinates]
    N = model.inertial
    forces = []
    for spring in d.springs:
        a, b = spring.between
        line = model.positions[b] - model.positions[a]  # from a to b
        length = line.magnitude()
        tension = model.language.scalar(spring.stiffness) * (
            length - model.language.scalar(spring.length))
        pull = (tension / length * line).to_matrix(N).subs(at_start)  # on a, toward b
        if any(c.has(q) for c in pull for q in coordinates):
            return  # the start does not fix the spring's length
        for body, point, sign in ((spring.on[0], a, 1), (spring.on[1], b, -1)):
            if body == GROUND:
                continue
            text = " + ".join(f"({model.plain(sign * c)})*{N}.{axis}"
                              for c, axis in zip(pull, "xyz") if not identically_zero(c))
            forces.append(Force(f"{spring.name}_at_start_{body}", body, point,
                                _expr(text or f"0*{N}.x")))
    mistaken = _mistaken(problem, replace(d, springs=(), forces=d.forces + tuple(forces)))
    reached = tuple(o for o in mistaken.objectives if isinstance(o.find.node, Name)
                    or (isinstance(o.find.node, Prime) and o.find.node.order == 1))
    if not reached or any(not _calls_free(o, d.springs) for o in reached):
        return
    names = ", ".join(x.name for x in d.springs)
    yield DynamicsMutation(
        "force_taken_constant", f"Your value takes the force of {names} constant at its value "
        "at the start of the motion (k δ): it changes as the spring extends, so the "
        "acceleration is not constant; integrate a = F/m along the motion (v dv = a dx), or "
        "use the spring's energy ½ k δ².", BALANCES, problem=replace(mistaken, objectives=reached))


def _calls_free(objective, loads) -> bool:
    """Whether ``objective`` names none of ``loads``."""
    return not any(n == Name(x.name) for x in loads for n in walk(objective.find.node))


def efficiency_inverted(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A power divided by an efficiency (a pure-number parameter: the input a machine needs)
    multiplied by it instead, or multiplied (the output it delivers) divided instead."""
    pure = {q.name for q in problem.parameters if q.unit in ("", "1")}
    for obj in problem.objectives:
        node = obj.find.node
        if obj.kind == ObjectiveKind.SYMBOLIC or not isinstance(node, Bin) or node.op not in "*/":
            continue
        for power, eta in ((node.left, node.right), (node.right, node.left)):
            if not (isinstance(eta, Name) and eta.id in pure
                    and next(_calls(power, "power"), None) is not None) \
                    or (node.op == "/" and eta is node.left):
                continue
            other = "*" if node.op == "/" else "/"
            new = Bin(other, power, eta)
            done, wanted = ("multiplies", "divide") if other == "*" else ("divides", "multiply")
            yield DynamicsMutation(
                "efficiency_inverted", f"Your value {done} the power by the efficiency {eta.id} "
                f"= {{term}}: {wanted} by it (the power put in is more than the power "
                "delivered).", OBJECTIVES, readings=((obj.id, Expr(to_text(new), new)),),
                term=Expr(eta.id, eta))


def _two_pi(node: Node) -> bool:
    return isinstance(node, Bin) and node.op == "*" and {to_text(node.left),
                                                         to_text(node.right)} == {"2", "pi"}


def period_for_frequency(problem: Problem, model: Model) -> Iterator[DynamicsMutation]:
    """A frequency in hertz, f = ω/(2π), answered with the period 2π/ω, or the period
    answered with the frequency: the objective read with 2π and the circular frequency the
    other way up."""
    for obj in problem.objectives:
        node = obj.find.node
        if obj.kind == ObjectiveKind.SYMBOLIC or not (isinstance(node, Bin) and node.op == "/"):
            continue
        if _two_pi(node.right):
            new, said = Bin("/", node.right, node.left), ("the period", "frequency f")
        elif _two_pi(node.left):
            new, said = Bin("/", node.right, node.left), ("the frequency", "period τ")
        else:
            continue
        omega = node.left if _two_pi(node.right) else node.right
        yield DynamicsMutation(
            "period_for_frequency", f"Your value is {said[0]} where the {said[1]} was asked: "
            "with ω = {term}, f = ω/(2π) in hertz and τ = 2π/ω = 1/f.",
            OBJECTIVES, readings=((obj.id, Expr(to_text(new), new)),),
            term=Expr(to_text(omega), omega), term_unit="rad/s")


FAMILIES: tuple[Callable[[Problem, Model], Iterator[DynamicsMutation]], ...] = (
    weight_omitted, weight_omitted_from_reaction, reaction_as_static, reactions_as_static,
    reaction_omitted,
    reaction_without_coriolis,
    mass_for_weight, weight_for_mass, central_inertia_at_pivot,
    friction_reversed, normal_from_weight, weight_transfer_ignored, tension_as_weight,
    reaction_as_weight, acceleration_reversed, rotational_ke_omitted, restitution_ignored,
    other_shape_inertia,
    particle_inertia, disk_for_gyration, restitution_component, damping_omitted, force_omitted,
    springs_in_series, strands_miscounted, strands_pulling_miscounted,
    spring_free_length_omitted, surface_taken_fixed, body_ke_omitted, impulse_moment_omitted,
    moment_arm_omitted,
    initial_speed_omitted, value_at_start, force_taken_constant, efficiency_inverted,
    static_friction_as_mu_m_g, spring_omitted, load_at_other_point, contact_taken_smooth,
    period_for_frequency, spring_energy_from_change, force_at_other_point,
    impact_taken_head_on, pin_impulse_omitted, translational_ke_omitted, rolling_assumed,
    initial_displacement_omitted, spring_energy_half_omitted, spring_taken_constant,
    start_sense_reversed, start_trig_exchanged, impulse_from_speeds, spring_work_reversed,
    force_component_reversed,
    angmom_along_axis, spring_force_as_resultant, part_moving_with_centre, striker_stops,
    weight_along_surface_omitted, damped_for_natural,
    mean_of_end_rates, transverse_speed_kept, energy_kept_in_coupling,
    parallel_axis_with_radius)
"""The dynamics mistake families, in the order their mutants are tried (the first of two
equal values names it)."""

