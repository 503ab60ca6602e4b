"""The dynamics sections of a problem file: ``bodies:`` and ``loads:``.

Bodies are particles (a mass at a point) or rigid bodies (a body frame, a mass centre, and an
inertia given explicitly about the mass centre or by shape); a composite body lists ``parts``,
each a mass at its own centre with its own shape: the mechanics core shifts every part's
inertia to the body's reference point (parallel axes), never the author. Loads are gravity,
applied forces and couples, linear springs and dampers, unknown reactions (normal forces, pins,
tensions, contact forces) and friction (kinetic, or static with its bound checked). Every load
has a :class:`LoadKind` (weight, normal, friction, tension, spring, ...): stated with ``kind:``
or read from the form of the load where that is unambiguous (:func:`reaction_kind`), so the
free-body diagram of each body knows what its loads are.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> d = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml").dynamics
>>> [b.name for b in d.bodies], [r.name for r in d.reactions]
(['rod'], ['R_O'])
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from enum import Enum
from typing import ClassVar

from ..errors import Location, SpecError, UnitError
from ..expressions.functions import Kind, StrEnum
from ..expressions.loads import LoadKind as LoadKind
from ..expressions.syntax import (MATH_FUNCTIONS, Attr, Bin, Call, Name, Node, Prime, Unary,
                                  constant_value, names, to_text, walk)
from ..units import dimension, dimensionless, parse_quantity, to_si
from .model import Expr, ObjectiveKind, Problem

GROUND = "ground"
"""The name standing for the inertial frame where a load's other end is fixed."""


_REACTION_KINDS = {"normal": LoadKind.NORMAL, "pin": LoadKind.PIN, "tension": LoadKind.TENSION,
                   "contact": LoadKind.CONTACT, "applied": LoadKind.APPLIED_FORCE}
"""``kind:`` of a reaction (an unknown force) as written, and what it means."""
_FORCE_KINDS = {"applied": LoadKind.APPLIED_FORCE, "weight": LoadKind.WEIGHT,
                "tension": LoadKind.TENSION}
"""``kind:`` of a known force as written, and what it means."""


# ---------------------------------------------------------------------------- shapes

Size = Callable[[Expr], "float | None"]
"""A shape's dimension in metres, ``None`` when unknown."""


class _Sized:
    """A shape given by its sizes: lengths (:attr:`UNIT`, :attr:`WHAT`), which
    :meth:`expressions` gives (a spec's check types each)."""

    UNIT: ClassVar[str] = "m"
    WHAT: ClassVar[str] = "a length"


@dataclass(frozen=True)
class Rod(_Sized):
    """A slender rod along body axis ``axis``: m L^2/12 about the perpendicular axes."""

    length: Expr
    axis: str

    def expressions(self) -> tuple[Expr, ...]:
        """Its sizes, as written."""
        return (self.length,)

    def volumes(self, size: Size) -> tuple[float, float] | None:
        """The greatest and least volume (m^3) a rod of this length may have: as thick as it
        is long, down to a thousandth of that; ``None`` when the length is unknown or zero.

        >>> Rod(Expr("L", Name("L")), "x").volumes(lambda e: 2.0)  # doctest: +ELLIPSIS
        (6.28..., 6.28...e-06)
        """
        length = size(self.length)
        if not length:
            return None
        return math.pi / 4 * length ** 3, math.pi / 4 * (length / 1000) ** 2 * length


def _flat(radius: float | None) -> tuple[float, float] | None:
    """A disk's or ring's volumes: at most as thick as it is wide, down to a thousandth of
    its radius."""
    if not radius:
        return None
    return math.pi * radius ** 2 * 2 * radius, math.pi * radius ** 2 * radius / 1000


@dataclass(frozen=True)
class Ring(_Sized):
    """A thin ring of ``radius`` about body axis ``axis``: m R^2 about it, m R^2/2 across."""

    radius: Expr
    axis: str

    def expressions(self) -> tuple[Expr, ...]:
        """Its sizes, as written."""
        return (self.radius,)

    def volumes(self, size: Size) -> tuple[float, float] | None:
        """A ring's volumes are a disk's: see :func:`_flat`."""
        return _flat(size(self.radius))


@dataclass(frozen=True)
class Disk(_Sized):
    """A uniform thin disk of ``radius`` about body axis ``axis``: m R^2/2, m R^2/4 across."""

    radius: Expr
    axis: str

    def expressions(self) -> tuple[Expr, ...]:
        """Its sizes, as written."""
        return (self.radius,)

    def volumes(self, size: Size) -> tuple[float, float] | None:
        """See :func:`_flat`."""
        return _flat(size(self.radius))


@dataclass(frozen=True)
class Cylinder(_Sized):
    """A solid cylinder: m R^2/2 about its axis, m (3R^2 + h^2)/12 across."""

    radius: Expr
    length: Expr
    axis: str

    def expressions(self) -> tuple[Expr, ...]:
        """Its sizes, as written."""
        return (self.radius, self.length)

    def volumes(self, size: Size) -> tuple[float, float] | None:
        """Its one volume, twice; ``None`` when a size is unknown or zero."""
        radius, length = size(self.radius), size(self.length)
        if not radius or not length:
            return None
        value = math.pi * radius ** 2 * length
        return value, value


def _ball(radius: float | None) -> float | None:
    """The volume of a ball of ``radius``; ``None`` when unknown or zero."""
    return 4 / 3 * math.pi * radius ** 3 if radius else None


@dataclass(frozen=True)
class Sphere(_Sized):
    """A uniform solid sphere: 2 m R^2/5 about every axis."""

    radius: Expr

    def expressions(self) -> tuple[Expr, ...]:
        """Its sizes, as written."""
        return (self.radius,)

    def volumes(self, size: Size) -> tuple[float, float] | None:
        """Its ball's volume, twice."""
        full = _ball(size(self.radius))
        return None if full is None else (full, full)


@dataclass(frozen=True)
class Shell(_Sized):
    """A thin spherical shell: 2 m R^2/3 about every axis."""

    radius: Expr

    def expressions(self) -> tuple[Expr, ...]:
        """Its sizes, as written."""
        return (self.radius,)

    def volumes(self, size: Size) -> tuple[float, float] | None:
        """Its ball's volume, down to none (a shell may be as thin as it likes)."""
        full = _ball(size(self.radius))
        return None if full is None else (full, 0.0)


@dataclass(frozen=True)
class Block(_Sized):
    """A rectangular block with sides along the body x, y, z axes (a plate has one side 0)."""

    sides: tuple[Expr, Expr, Expr]

    def expressions(self) -> tuple[Expr, ...]:
        """Its sizes, as written."""
        return self.sides

    def volumes(self, size: Size) -> tuple[float, float] | None:
        """Its one volume, twice; ``None`` when a side is unknown or zero (a plate)."""
        sides = [size(s) for s in self.sides]
        if any(s is None for s in sides) or not all(sides):
            return None
        value = math.prod(sides)  # type: ignore[arg-type]
        return value, value


@dataclass(frozen=True)
class Explicit:
    """Moments and products of inertia about the mass centre in the body axes."""

    entries: tuple[tuple[str, Expr], ...]  # ("xx", expr), ... ; missing entries are zero
    UNIT: ClassVar[str] = "kg*m^2"
    WHAT: ClassVar[str] = "a moment of inertia"

    def expressions(self) -> tuple[Expr, ...]:
        """Its moments and products, as written.

        >>> Explicit((("zz", Expr("J", Name("J"))),)).expressions()[0].text
        'J'
        """
        return tuple(e for _, e in self.entries)

    def volumes(self, _size: Size) -> None:
        """Unknown: an inertia says nothing of the body's size."""
        return None


Shape = Rod | Ring | Disk | Cylinder | Sphere | Shell | Block | Explicit
INERTIA_KEYS = ("xx", "yy", "zz", "xy", "yz", "zx")


# ---------------------------------------------------------------------------- bodies


class OutlineKind(StrEnum):
    """The shape a part of a body is drawn as (a free-body diagram's outline)."""

    PARTICLE = "particle"
    ROD = "rod"
    DISK = "disk"
    RING = "ring"
    CYLINDER = "cylinder"
    SPHERE = "sphere"
    SHELL = "shell"
    BLOCK = "block"
    BODY = "body"  # inertia given by its entries: no shape to draw, a blob at its centre


@dataclass(frozen=True)
class Part:
    """A mass at its own centre ``at``, with the inertia of ``shape`` about ``at`` (None: a
    point mass)."""

    mass: Expr
    at: str
    shape: Shape | None
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Body:
    """A particle (``frame`` None: one part without a shape) or a rigid body turning with
    ``frame``; ``centre`` is the point its momentum balances refer to (the mass centre of a
    one-part body)."""

    name: str
    frame: str | None
    centre: str
    parts: tuple[Part, ...]
    where: Location = field(default_factory=Location, compare=False)


# ---------------------------------------------------------------------------- loads


@dataclass(frozen=True)
class Force:
    """A known force ``force`` on body ``on`` at point ``at``: an applied force, a weight
    written as a force (when no ``gravity:`` acts) or the known pull of a cord."""

    name: str
    on: str
    at: str
    force: Expr
    where: Location = field(default_factory=Location, compare=False)
    kind: LoadKind = LoadKind.APPLIED_FORCE


@dataclass(frozen=True)
class KnownImpulse:
    """A known impulse ``impulse`` (N s) on body ``on`` at point ``at`` during an impact (a
    hammer blow of known strength); it acts in ``analysis: impulse`` only."""

    name: str
    on: str
    at: str
    impulse: Expr
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Couple:
    """A known couple (pure moment) on body ``on``."""

    name: str
    on: str
    moment: Expr
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Spring:
    """A linear spring from point ``between[0]`` on body ``on[0]`` to ``between[1]`` on
    ``on[1]`` (``ground`` for a fixed end): tension k (l - l0) along the line."""

    name: str
    between: tuple[str, str]
    on: tuple[str, str]
    stiffness: Expr
    length: Expr
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Damper:
    """A linear damper between two points: tension c times the rate of its length."""

    name: str
    between: tuple[str, str]
    on: tuple[str, str]
    coefficient: Expr
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Act:
    """Where an unknown force acts: on body ``on`` at point ``at``, with ``sign`` +1 or -1;
    ``direction``, when set, is this end's own (a cord's segment ending here pulls along its
    line, over ideal pulleys with the same tension as the others)."""

    on: str
    at: str
    sign: int = 1
    direction: Expr | None = None


@dataclass(frozen=True)
class Reaction:
    """An unknown force: one unknown magnitude per direction in ``directions``, acting
    wherever ``acts`` says (a joint between two bodies acts on each with opposite signs; a
    string over ideal pulleys pulls every end it ``acts`` on with the same tension).

    ``kind`` says what it is (:func:`reaction_kind`); a normal force or a gripping contact
    is on ``surface``: the ground, a frame whose motion the kinematics prescribes, or the
    other body of a joint (``None``: the second of ``bodies``, else the ground)."""

    name: str
    directions: tuple[Expr, ...]
    acts: tuple[Act, ...]
    where: Location = field(default_factory=Location, compare=False)
    kind: LoadKind = LoadKind.REACTION
    surface: str | None = None

    def direction_at(self, act: Act) -> Expr:
        """The direction of a one-direction reaction at one of its ends."""
        return act.direction if act.direction is not None else self.directions[0]

    @property
    def contact_surface(self) -> str:
        """What the contact is against: ``surface``, else the joint's second body, else the
        ground."""
        if self.surface is not None:
            return self.surface
        return self.acts[1].on if len(self.acts) == 2 and self.acts[1].sign < 0 else GROUND


@dataclass(frozen=True)
class Grip:
    """What a kinetic-friction contact becomes once its slip ends (``then: {kind: static}``):
    it grips the ground (a wheel rolls), its friction an unknown along ``direction`` with
    |F| <= ``mu`` N."""

    mu: Expr
    direction: Expr
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class KineticFriction:
    """mu N opposing the slip velocity of body ``on`` at ``at`` relative to ``surface`` (the
    ground, a frame whose motion is prescribed, or another body, which then feels the opposite
    force); ``normal`` is the reaction (one direction) pressing the surfaces together;
    ``then``, what the contact does once an integrated motion's slip ends (``None``: the
    motion must end first)."""

    name: str
    on: str
    at: str
    normal: str
    mu: Expr
    surface: str
    where: Location = field(default_factory=Location, compare=False)
    then: Grip | None = None


@dataclass(frozen=True)
class StaticFriction:
    """An unknown tangential force (one unknown per direction) at a contact that does not
    slip; the solution must satisfy |F| <= mu N, or the contact slips."""

    name: str
    on: str
    at: str
    normal: str
    mu: Expr
    directions: tuple[Expr, ...]
    where: Location = field(default_factory=Location, compare=False)
    surface: str = GROUND  # the ground, or another body (which feels the opposite force)


Friction = KineticFriction | StaticFriction


@dataclass(frozen=True)
class Start:
    """A coordinate or rate at the start of a motion: a quantity (``si``, in SI units) or an
    expression of parameters (``value``, such as ``theta0``)."""

    key: Expr
    value: Expr | None
    si: float | None
    where: Location = field(default_factory=Location, compare=False)


class Sense(Enum):
    """The sign a rate has at the instant of a work–energy analysis."""

    POSITIVE = "positive"
    NEGATIVE = "negative"

    @property
    def sign(self) -> int:
        """+1 or -1.

        >>> Sense("negative").sign
        -1
        """
        return 1 if self is Sense.POSITIVE else -1


@dataclass(frozen=True)
class WorkEnergy:
    """The instant is reached from the state ``start`` with the mechanical energy conserved:
    the givens fix the configuration, the energy fixes the speed; ``sense`` says which sign
    a rate has (``{"theta'": negative}``)."""

    start: tuple[Start, ...]
    sense: tuple[tuple[Expr, Sense], ...]
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Integration:
    """The motion integrated in time from ``start`` (at t = 0) until ``until`` (``lhs = rhs``)
    first holds, at most ``max_time`` seconds: the instant of the objectives is that event."""

    start: tuple[Start, ...]
    until: tuple[Expr, Expr]
    max_time: float
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Restitution:
    """At the contact point ``at`` of ``bodies`` (the second may be ``ground``): the relative
    velocity along ``direction`` just after is ``-e`` times the one just before."""

    at: str
    bodies: tuple[str, str]
    direction: Expr
    e: Expr
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Sticking:
    """At ``at`` the relative velocity of ``bodies`` along ``directions`` is zero just after
    the impact (the contact grips)."""

    at: str
    bodies: tuple[str, str]
    directions: tuple[Expr, ...]
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Impulse:
    """An impact: the rates just ``before`` it are known (left out: 0), the givens' rates are
    those just after; the reactions are impulses (N s), every other load is finite and does
    not act during the impact. Contacts add their restitution or sticking conditions."""

    start: tuple[Start, ...]
    where: Location = field(default_factory=Location, compare=False)
    contacts: tuple[Restitution | Sticking, ...] = ()


Analysis = WorkEnergy | Integration | Impulse


@dataclass(frozen=True)
class Design:
    """Inverse design: the parameter ``find`` (not given) is solved so that ``so_that``
    (``lhs = rhs``, any objective-language equation) holds, starting from ``guess`` (SI)."""

    find: str
    so_that: tuple[Expr, Expr]
    guess: float
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Dynamics:
    """The bodies and loads of a problem (``Problem.dynamics``)."""

    bodies: tuple[Body, ...]
    gravity: Expr | None = None
    forces: tuple[Force, ...] = ()
    couples: tuple[Couple, ...] = ()
    springs: tuple[Spring, ...] = ()
    dampers: tuple[Damper, ...] = ()
    reactions: tuple[Reaction, ...] = ()
    friction: tuple[Friction, ...] = ()
    analysis: Analysis | None = None
    design: Design | None = None
    impulses: tuple[KnownImpulse, ...] = ()
    down: Expr | None = None  # the problem's "down" (loads.down), a direction
    mistaken: bool = False  # a student's mistaken model: its loads are not checked
    # a student's mistaken model: the bodies whose moment balance the student left out
    unbalanced: tuple[str, ...] = ()

    def body(self, name: str) -> Body:
        return {b.name: b for b in self.bodies}[name]

    @property
    def loads(self) -> tuple:
        """Every named load, in the order of the file's sections."""
        return (*self.forces, *self.couples, *self.springs, *self.dampers, *self.reactions,
                *self.friction, *self.impulses)

    def load(self, name: str):
        return {item.name: item for item in self.loads}[name]

    @property
    def junctions(self) -> tuple[Body, ...]:
        """The massless junctions: particles written with no mass (``mass: 0``) where only
        springs and dampers end (a node between springs in series).

        >>> from mechgrade.spec import load_problem
        >>> from mechgrade.resources import shipped_dir
        >>> p = load_problem(shipped_dir("problems") / "block_on_springs_in_series.yaml")
        >>> [b.name for b in p.dynamics.junctions]
        ['node']
        """
        loaded: tuple[Force | Couple | Friction | KnownImpulse, ...] = (
            *self.forces, *self.couples, *self.friction, *self.impulses)
        held = {f.on for f in loaded} | {a.on for r in self.reactions for a in r.acts} \
            | {f.surface for f in self.friction}
        ends = {body for x in self.springs for body in x.on} | \
            {body for x in self.dampers for body in x.on}
        return tuple(b for b in self.bodies
                     if b.frame is None and b.name in ends and b.name not in held
                     and all(constant_value(p.mass.node) == 0 for p in b.parts))

    def kind(self, name: str) -> LoadKind:
        """The kind of the load named ``name``.

        >>> from mechgrade.spec import load_problem
        >>> from mechgrade.resources import shipped_dir
        >>> d = load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml").dynamics
        >>> d.kind("N_P"), d.kind("F_P")
        (<LoadKind.NORMAL: 'normal'>, <LoadKind.KINETIC_FRICTION: 'kinetic friction'>)
        """
        item = self.load(name)
        if isinstance(item, (Force, Reaction)):
            return item.kind
        return {Couple: LoadKind.APPLIED_COUPLE, Spring: LoadKind.SPRING,
                Damper: LoadKind.DAMPER, KineticFriction: LoadKind.KINETIC_FRICTION,
                StaticFriction: LoadKind.STATIC_FRICTION,
                KnownImpulse: LoadKind.IMPULSE}[type(item)]


def unchecked(dynamics: Dynamics) -> Dynamics:
    """``dynamics`` as a student's mistaken model of it takes them: its loads unchecked
    (``mistaken``), each static friction an unknown force without its bound, equal and
    opposite on its surface where that is a body (third law).

    >>> grip = StaticFriction("F", "block", "P", "N", mu=None, directions=())
    >>> student = unchecked(Dynamics(bodies=(), friction=(grip,)))
    >>> [(r.name, r.acts) for r in student.reactions], student.friction, student.mistaken
    ([('F', (Act(on='block', at='P', sign=1, direction=None),))], (), True)
    """
    bodies = {b.name for b in dynamics.bodies}
    reactions = dynamics.reactions + tuple(
        Reaction(f.name, f.directions, (Act(f.on, f.at),) + (
            (Act(f.surface, f.at, -1),) if f.surface in bodies else ()), f.where,
            surface=f.surface)
        for f in dynamics.friction if isinstance(f, StaticFriction))
    friction = tuple(f for f in dynamics.friction if not isinstance(f, StaticFriction))
    return replace(dynamics, reactions=reactions, friction=friction, mistaken=True)


# ---------------------------------------------------------------------------- reading


_SHAPES = {"rod": (Rod, ("length",)), "ring": (Ring, ("radius",)), "disk": (Disk, ("radius",)),
           "cylinder": (Cylinder, ("radius", "length")), "sphere": (Sphere, ("radius",)),
           "shell": (Shell, ("radius",))}


def dynamics_of(problem: Problem) -> Dynamics:
    """The dynamics section of a problem that has one (the solver and the mistake families
    for bodies and loads are chosen for such problems only).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
    >>> [b.name for b in dynamics_of(problem).bodies]
    ['rod']
    """
    assert problem.dynamics is not None, problem.id
    return problem.dynamics


def read_dynamics(data: dict, expr, where) -> Dynamics | None:
    """The ``bodies:`` and ``loads:`` sections (already schema-checked), or None if absent.

    ``expr(text, *path)`` parses an expression at a field path; ``where(*path)`` locates it.
    """
    if "bodies" not in data:
        for key in ("loads", "analysis"):
            if key in data:
                raise SpecError(f"'{key}' needs bodies: expected a 'bodies' section",
                                where=where(key))
        return None
    bodies = tuple(_body(name, spec, expr, where) for name, spec in data["bodies"].items())
    loads = data.get("loads") or {}

    def section(key):
        return (loads.get(key) or {}).items()

    forces = tuple(Force(n, s["body"], s["at"], expr(s["force"], "loads", "forces", n, "force"),
                         where("loads", "forces", n), _FORCE_KINDS[s.get("kind", "applied")])
                   for n, s in section("forces"))
    couples = tuple(Couple(n, s["body"], expr(s["moment"], "loads", "couples", n, "moment"),
                           where("loads", "couples", n)) for n, s in section("couples"))
    springs = tuple(Spring(n, tuple(s["between"]), tuple(s["bodies"]),
                           expr(s["stiffness"], "loads", "springs", n, "stiffness"),
                           expr(s.get("length", 0), "loads", "springs", n, "length"),
                           where("loads", "springs", n)) for n, s in section("springs"))
    dampers = tuple(Damper(n, tuple(s["between"]), tuple(s["bodies"]),
                           expr(s["coefficient"], "loads", "dampers", n, "coefficient"),
                           where("loads", "dampers", n)) for n, s in section("dampers"))
    impulses = tuple(KnownImpulse(n, s["body"], s["at"],
                                  expr(s["impulse"], "loads", "impulses", n, "impulse"),
                                  where("loads", "impulses", n)) for n, s in section("impulses"))
    reactions = tuple(_reaction(n, s, expr, where) for n, s in section("reactions"))
    friction = tuple(_friction(n, s, expr, where, reactions) for n, s in section("friction"))
    reactions = tuple(replace(r, kind=reaction_kind(r, friction, loads["reactions"][r.name]),
                              surface=r.surface if r.surface is not None else
                              _friction_surface(r, friction)) for r in reactions)
    down = expr(loads["down"], "loads", "down") if "down" in loads else None
    gravity = _gravity(expr(loads["gravity"], "loads", "gravity"), down) \
        if "gravity" in loads else None
    analysis = dict(data.get("analysis") or {})
    design = analysis.pop("design", None)
    return Dynamics(bodies, gravity, forces, couples, springs, dampers, reactions, friction,
                    _analysis(analysis, expr, where), _design(design, expr, where), impulses,
                    down)


def reaction_kind(reaction: Reaction, friction, spec: dict) -> LoadKind:
    """The kind of an unknown force: its ``kind:`` when written, else what its form says: a
    string over pulleys (``acts:``) is a tension, the ``normal:`` of a friction force a normal
    force; any other is a reaction of unstated kind (``kind:`` names it).

    >>> r = Reaction("T", (), (Act("a", "P"), Act("b", "Q")))
    >>> reaction_kind(r, (), {"acts": []}), reaction_kind(r, (), {"kind": "pin"})
    (<LoadKind.TENSION: 'tension'>, <LoadKind.PIN: 'pin'>)
    """
    if "kind" in spec:
        return _REACTION_KINDS[spec["kind"]]
    if "acts" in spec:
        return LoadKind.TENSION
    if any(f.normal == reaction.name for f in friction):
        return LoadKind.NORMAL
    return LoadKind.REACTION


def _friction_surface(reaction: Reaction, friction) -> str | None:
    """The surface of a normal force that a friction force names as its ``normal:``."""
    return next((f.surface for f in friction if f.normal == reaction.name
                 and f.surface != GROUND), None)


def _gravity(gravity: Expr, down: Expr | None) -> Expr:
    """The gravitational acceleration as a vector: as written, or its magnitude written with
    ``down:`` (``gravity: g``) times that direction."""
    if down is None or _vector_like(gravity.node):
        return gravity
    text = f"({gravity.text})*({down.text})"
    return Expr(text, Bin("*", gravity.node, down.node), gravity.where)


def _vector_like(node: Node) -> bool:
    """Whether an expression may be a vector: it names a unit vector or calls a function of
    the objective language (a scalar of parameters does neither)."""
    return any(isinstance(n, Attr) or (isinstance(n, Call) and n.func not in MATH_FUNCTIONS)
               for n in walk(node))


def _equation(text: str, expr, where, *path) -> tuple[Expr, Expr]:
    if text.count("=") != 1:
        raise SpecError(f"expected an equation 'left = right', found {text!r}",
                        where=where(*path))
    left, right = text.split("=")
    return expr(left.strip(), *path), expr(right.strip(), *path)


def _design(spec: dict | None, expr, where) -> Design | None:
    if spec is None:
        return None
    path = ("analysis", "design")
    guess = to_si(*_quantity(spec["guess"], where(*path, "guess")))
    return Design(spec["find"], _equation(spec["so_that"], expr, where, *path, "so_that"), guess,
                  where(*path))


def _analysis(spec: dict | None, expr, where) -> Analysis | None:
    if not spec:
        return None
    if len(spec) > 1:
        raise SpecError(f"expected one of work_energy, integrate, impulse (and design), found "
                        f"{', '.join(spec)}", where=where("analysis"))
    (kind, body), = spec.items()
    path = ("analysis", kind)
    if kind == "impulse":
        contacts: list[Restitution | Sticking] = []
        for i, c in enumerate(body.get("contacts") or []):
            cpath = (*path, "contacts", i)
            if "restitution" in c:
                contacts.append(Restitution(c["at"], tuple(c["bodies"]),
                                            expr(c["direction"], *cpath, "direction"),
                                            expr(c["restitution"], *cpath, "restitution"),
                                            where(*cpath)))
            else:
                contacts.append(Sticking(c["at"], tuple(c["bodies"]),
                                         _directions(c, expr, *cpath), where(*cpath)))
        return Impulse(tuple(_start(key, value, expr, where, *path, "before")
                             for key, value in (body.get("before") or {}).items()),
                       where(*path), tuple(contacts))
    start = tuple(_start(key, value, expr, where, *path, "from")
                  for key, value in (body.get("from") or {}).items())
    if kind == "work_energy":
        sense = tuple((expr(key, *path, "sense", key), Sense(value))
                      for key, value in (body.get("sense") or {}).items())
        return WorkEnergy(start, sense, where(*path))
    until = _equation(body["until"], expr, where, *path, "until")
    max_time = to_si(*_quantity(body.get("max_time", "60 s"), where(*path, "max_time")))
    return Integration(start, until, max_time, where(*path))


def _quantity(value, where) -> tuple[float, str]:
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value), ""
    try:
        q = parse_quantity(str(value))
    except UnitError as err:
        raise SpecError(err.message, where=where) from None
    return q.value, q.unit


def _start(key, value, expr, where, *path) -> Start:
    place = where(*path, key)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return Start(expr(key, *path, key), None, float(value), place)
    try:
        q = parse_quantity(str(value))
    except UnitError:
        return Start(expr(key, *path, key), expr(value, *path, key), None, place)
    return Start(expr(key, *path, key), None, to_si(q.value, q.unit), place)


def _directions(spec: dict, expr, *path) -> tuple[Expr, ...]:
    if "direction" in spec:
        return (expr(spec["direction"], *path, "direction"),)
    return tuple(expr(d, *path, "directions", i) for i, d in enumerate(spec["directions"]))


def _reaction(name: str, spec: dict, expr, where) -> Reaction:
    path = ("loads", "reactions", name)
    if "acts" in spec:
        acts = tuple(Act(a["body"], a["at"], 1, expr(a["direction"], *path, "acts", i, "direction")
                         if "direction" in a else None) for i, a in enumerate(spec["acts"]))
    elif "bodies" in spec:
        # a joint: equal and opposite on the two bodies it connects
        acts = (Act(spec["bodies"][0], spec["at"], 1), Act(spec["bodies"][1], spec["at"], -1))
    else:
        acts = (Act(spec["body"], spec["at"]),)
    return Reaction(name, _directions(spec, expr, *path), acts, where(*path),
                    surface=spec.get("surface"))


def _friction(name: str, spec: dict, expr, where, reactions=()) -> Friction:
    path = ("loads", "friction", name)
    mu = expr(spec["mu"], *path, "mu")
    if spec["kind"] == "kinetic":
        then = spec.get("then")
        grip = None if then is None else Grip(
            expr(then["mu"], *path, "then", "mu"),
            expr(then["direction"], *path, "then", "direction"), where(*path, "then"))
        return KineticFriction(name, spec["body"], spec["at"], spec["normal"], mu,
                               spec.get("surface", GROUND), where(*path), grip)
    if "then" in spec:
        raise SpecError(f"'then' says what a kinetic friction becomes once its slip ends; "
                        f"'{name}' is static friction already (write kind: kinetic, or leave "
                        "'then' out)", where=where(*path, "then"))
    if "direction" not in spec and "directions" not in spec:
        normal = next((r for r in reactions if r.name == spec["normal"]), None)
        raise SpecError(f"static friction '{name}' needs the directions of its unknown "
                        f"components: expected directions: {_tangents(normal)}, the tangents "
                        f"to the surface at {spec['at']}, found none", where=where(*path))
    return StaticFriction(name, spec["body"], spec["at"], spec["normal"], mu,
                          _directions(spec, expr, *path), where(*path),
                          spec.get("surface", GROUND))


def _tangents(normal: Reaction | None) -> str:
    """Directions perpendicular to a normal force along a frame's unit vector (``N.z``:
    ``[N.x, N.y]``, one of which a planar problem needs), or a description of them.

    >>> from mechgrade.expressions.syntax import parse
    >>> _tangents(Reaction("N_P", (Expr("A.y", parse("A.y")),), ()))
    '[A.x, A.z] (in a planar problem the one in the plane of motion)'
    """
    if normal is None or len(normal.directions) != 1:
        return "[...] (perpendicular to the normal force)"
    node = normal.directions[0].node
    node = node.operand if isinstance(node, Unary) else node
    if isinstance(node, Attr) and node.attr in "xyz":
        others = ", ".join(f"{node.base}.{a}" for a in "xyz" if a != node.attr)
        return f"[{others}] (in a planar problem the one in the plane of motion)"
    return f"[...] (perpendicular to {normal.name} along {normal.directions[0].text})"


def _body(name: str, spec: dict, expr, where) -> Body:
    path = ("bodies", name)
    if "parts" in spec:
        parts = tuple(_part(p, expr, where, *path, "parts", i)
                      for i, p in enumerate(spec["parts"]))
        centre = spec.get("centre", parts[0].at)
    else:
        if "centre" not in spec:
            raise SpecError(f"body '{name}' has a mass but no 'centre' (its mass-centre "
                            "point)", where=where(*path))
        centre = spec["centre"]
        parts = (_part({"mass": spec["mass"], "at": centre, "inertia": spec.get("inertia")},
                       expr, where, *path),)
    return Body(name, spec.get("frame"), centre, parts, where(*path))


def _part(spec: dict, expr, where, *path) -> Part:
    shape = None
    inertia = spec.get("inertia")
    if inertia is not None:
        (kind, args), = inertia.items()
        ipath = (*path, "inertia", kind)
        if kind in _SHAPES:
            cls, keys = _SHAPES[kind]
            values = [expr(args[k], *ipath, k) for k in keys]
            shape = cls(*values, args["axis"]) if "axis" in args else cls(*values)
        elif kind == "block":
            shape = Block(tuple(expr(s, *ipath, "sides", i) for i, s in enumerate(args["sides"])))
        else:  # about_centre
            shape = Explicit(tuple((k, expr(args[k], *ipath, k)) for k in INERTIA_KEYS
                                   if k in args))
    return Part(expr(spec["mass"], *path, "mass"), spec["at"], shape, where(*path))


# ---------------------------------------------------------------------------- validation


def check_dynamics(problem, checker) -> None:
    """Names, kinds and dimensions of the dynamics sections (``checker`` types expressions)."""
    d = problem.dynamics
    _objective_positions(problem, checker)
    if d is None:
        return
    c = _Checker(problem, checker)
    c.distinct_names()
    c.bodies()
    c.applied_loads()
    c.reactions_and_friction()
    if d.analysis is not None:
        _check_analysis(problem, checker, d.analysis)
    if isinstance(d.analysis, Integration):
        _objective_instants(problem, d.analysis)
    if d.design is not None:
        c.design()
    for e in (*(x for r in d.reactions for x in r.directions),
              *(x for f in d.friction if isinstance(f, StaticFriction) for x in f.directions)):
        c.typed(e, Kind.VECTOR, "", "a direction (a vector without units, e.g. N.x)")


class _Checker:
    """The checks of :func:`check_dynamics`, one method per section, sharing the problem's
    names."""

    def __init__(self, problem, checker):
        self.problem = problem
        self.checker = checker
        self.d: Dynamics = problem.dynamics
        self.frames = {f.name for f in problem.frames}
        self.points = {p.name for p in problem.points}
        self.scalars = {c.name for c in problem.coordinates} | {p.name for p in problem.parameters}
        self.body_names = {b.name for b in self.d.bodies}

    def point(self, name, where, field_name):
        if name not in self.points:
            raise SpecError(f"unknown point '{name}' in '{field_name}' (points: "
                            f"{', '.join(sorted(self.points))})", where=where)

    def body(self, name, where, ground_ok=False):
        if name not in self.body_names and not (ground_ok and name == GROUND):
            known = sorted(self.body_names | ({GROUND} if ground_ok else set()))
            raise SpecError(f"unknown body '{name}' (bodies: {', '.join(known)})", where=where)

    def typed(self, e: Expr, kind: Kind, unit: str, what: str):
        t = self.checker.type_of(e)
        if t.kind == Kind.ZERO:
            return
        if t.kind != kind:
            raise SpecError(f"expected {what}, found a {t.kind} ('{e.text}')", where=e.where)
        if t.dim != dimension(unit):
            self.checker._dims_match(t.dim, dimension(unit), e.where, f"'{e.text}' ({what})")

    def distinct_names(self):
        seen: dict[str, str] = {}
        others = self.frames | self.points | self.scalars | {GROUND}
        for item, what in [(b, "body") for b in self.d.bodies] + \
                [(x, "load") for x in self.d.loads]:
            if item.name in seen or item.name in others:
                raise SpecError(f"'{item.name}' names a {what} and something else already; "
                                "expected a distinct name", where=item.where)
            seen[item.name] = what

    def bodies(self):
        for b in self.d.bodies:
            self.point(b.centre, b.where, "centre")
            if b.frame is not None and b.frame not in self.frames:
                raise SpecError(f"unknown frame '{b.frame}' (frames: "
                                f"{', '.join(sorted(self.frames))})", where=b.where)
            for part in b.parts:
                self.part(b, part)

    def part(self, b: Body, part: Part):
        self.point(part.at, part.where, "at")
        self.typed(part.mass, Kind.SCALAR, "kg", "a mass")
        if part.shape is not None and b.frame is None:
            raise SpecError(f"body '{b.name}' has an inertia but no 'frame': a rigid body "
                            "needs the frame it turns with (a particle has no inertia)",
                            where=part.where)
        if part.shape is None:
            return
        for e in part.shape.expressions():
            self.typed(e, Kind.SCALAR, part.shape.UNIT, part.shape.WHAT)

    def applied_loads(self):
        d = self.d
        if d.down is not None:
            self.typed(d.down, Kind.VECTOR, "", "the direction of 'down' (a vector without units, "
                       "e.g. -N.y)")
        if d.gravity is not None:
            if d.down is None and self.checker.type_of(d.gravity).kind == Kind.SCALAR:
                raise SpecError(f"expected the gravitational acceleration as a vector (e.g. "
                                f"-g*N.y), found the magnitude '{d.gravity.text}'; give its "
                                "direction as well: down: -N.y (the way down in the figure)",
                                where=d.gravity.where)
            self.typed(d.gravity, Kind.VECTOR, "m/s^2", "the gravitational acceleration as a "
                       "vector (e.g. -g*N.y), or its magnitude with down: (e.g. gravity: g, "
                       "down: -N.y)")
        for f in d.forces:
            self.body(f.on, f.where)
            self.point(f.at, f.where, "at")
            self.typed(f.force, Kind.VECTOR, "N", "a force vector")
            if f.kind == LoadKind.WEIGHT and d.gravity is not None:
                raise SpecError(f"the weight '{f.name}' on {f.on} is given twice: as this "
                                f"force and by 'gravity: {d.gravity.text}', which acts on "
                                "every body; expected it once: delete this force, or delete "
                                "gravity to give every weight as a force", where=f.where)
        for c in d.couples:
            self.body(c.on, c.where)
            self.typed(c.moment, Kind.VECTOR, "N*m", "a moment vector")
        ends: tuple[Spring | Damper, ...] = (*d.springs, *d.dampers)
        for s in ends:
            for p, b in zip(s.between, s.on):
                self.point(p, s.where, "between")
                self.body(b, s.where, ground_ok=True)
        for s in d.springs:
            self.typed(s.stiffness, Kind.SCALAR, "N/m", "a stiffness")
            self.typed(s.length, Kind.SCALAR, "m", "a free length")
        for s in d.dampers:
            self.typed(s.coefficient, Kind.SCALAR, "N*s/m", "a damping coefficient")
        for j in d.impulses:
            self.body(j.on, j.where)
            self.point(j.at, j.where, "at")
            self.typed(j.impulse, Kind.VECTOR, "N*s", "an impulse vector")
            if not isinstance(d.analysis, Impulse):
                raise SpecError(f"the known impulse '{j.name}' acts during an impact only: "
                                "expected 'analysis: impulse'", where=j.where)

    def reactions_and_friction(self):
        d = self.d
        reactions = {r.name: r for r in d.reactions}
        for r in d.reactions:
            for act in r.acts:
                self.body(act.on, r.where, ground_ok=True)
                self.point(act.at, r.where, "at")
                if act.direction is None:
                    continue
                if len(r.directions) != 1:
                    raise SpecError(f"'{r.name}': an end with its own direction belongs to a "
                                    "cord (one unknown tension): expected one 'direction', "
                                    f"found {len(r.directions)}", where=r.where)
                self.typed(act.direction, Kind.VECTOR, "", "a direction (a vector without units, "
                           "e.g. N.x)")
        for f in d.friction:
            self.body(f.on, f.where)
            self.point(f.at, f.where, "at")
            self.typed(f.mu, Kind.SCALAR, "", "a friction coefficient")
            normal = reactions.get(f.normal)
            if normal is None or len(normal.directions) != 1:
                raise SpecError(f"friction '{f.name}': 'normal' must name a reaction with one "
                                f"direction (reactions: {', '.join(sorted(reactions)) or 'none'})",
                                where=f.where)
            if normal.kind != LoadKind.NORMAL:
                raise SpecError(f"friction '{f.name}': its normal '{f.normal}' is a "
                                f"{normal.kind}; expected the normal force pressing the "
                                f"surfaces together at {f.at} (a reaction with kind: normal)",
                                where=f.where)
            self.surface(f, normal)
            if isinstance(f, KineticFriction) and f.then is not None:
                self.grip(f, f.then)
        for r in d.reactions:  # after friction: a normal force's surface may be its friction's
            self.reaction_form(r)

    def reaction_form(self, r: Reaction):
        """A reaction's kind fits its form: a string pulls along its one line; a normal force,
        a pin or a contact acts at one point (on one body, or a joint between two); only a
        normal force or a contact is on a surface."""
        string = len(r.acts) > 1 and all(a.sign > 0 for a in r.acts)
        if r.kind == LoadKind.TENSION and len(r.directions) != 1:
            raise SpecError(f"the tension '{r.name}' pulls along its string: expected one "
                            f"direction, found {len(r.directions)}", where=r.where)
        if string and r.kind in (LoadKind.NORMAL, LoadKind.PIN, LoadKind.CONTACT):
            raise SpecError(f"a {r.kind} force acts at one point: expected 'body' and 'at' "
                            f"(or 'bodies' and 'at' for a joint), found 'acts' in '{r.name}' "
                            "(a string over pulleys is kind: tension)", where=r.where)
        if r.surface is None:
            return
        if r.kind not in (LoadKind.NORMAL, LoadKind.CONTACT):
            raise SpecError(f"'surface' belongs to a normal force or a contact; '{r.name}' is "
                            f"a {r.kind} (write kind: normal, or leave surface out)",
                            where=r.where)
        joint = len(r.acts) == 2 and r.acts[1].sign < 0
        if joint and r.surface != r.acts[1].on:
            raise SpecError(f"the joint '{r.name}' between {r.acts[0].on} and {r.acts[1].on} "
                            f"is on {r.acts[1].on}: expected surface: {r.acts[1].on} or none, "
                            f"found surface: {r.surface}", where=r.where)
        known = self.frames | self.body_names | {GROUND}
        if r.surface not in known:
            raise SpecError(f"unknown surface '{r.surface}' of '{r.name}' (expected ground, a "
                            f"frame or a body: {', '.join(sorted(known))})", where=r.where)

    def grip(self, f: KineticFriction, grip: Grip):
        """A contact that grips once its slip ends: on the ground, along one direction, in an
        integrated motion whose objectives are numbers (the phases have no closed form)."""
        self.typed(grip.mu, Kind.SCALAR, "", "a friction coefficient")
        self.typed(grip.direction, Kind.VECTOR, "",
                   "a direction (a vector without units, e.g. N.x)")
        if f.surface != GROUND:
            raise SpecError(f"friction '{f.name}': a contact that grips once its slip ends "
                            f"is supported on the ground only, found surface: {f.surface}; "
                            "integrate until the slip ends instead (until: its slip speed "
                            "= 0)", where=grip.where)
        analysis = self.d.analysis
        if not isinstance(analysis, Integration):
            found = "no analysis" if analysis is None else \
                f"analysis: {_ANALYSIS_NAMES[type(analysis)]}"
            raise SpecError(f"friction '{f.name}': 'then' says how an integrated motion goes "
                            f"on once the slip ends; expected 'analysis: integrate', found "
                            f"{found} (leave 'then' out)", where=grip.where)
        for obj in self.problem.objectives:
            if obj.kind == ObjectiveKind.SYMBOLIC:
                raise SpecError(f"objective '{obj.id}': a motion that slips, then grips "
                                f"('{f.name}' has 'then') is integrated numerically, so its "
                                f"objectives are numbers: expected kind: scalar or vector, "
                                "found kind: symbolic", where=obj.where)

    def surface(self, f: Friction, normal: Reaction):
        """The ground, a frame (kinetic friction only) or another body pressed by ``normal``."""
        if f.surface in self.body_names:
            pressed = {act.on for act in normal.acts}
            if f.surface == f.on or pressed != {f.on, f.surface}:
                raise SpecError(f"friction '{f.name}' between {f.on} and {f.surface}: its "
                                f"normal '{f.normal}' must act on both bodies (a reaction with "
                                f"bodies: [{f.on}, {f.surface}])", where=f.where)
            return
        known = self.frames | {GROUND} if isinstance(f, KineticFriction) else {GROUND}
        if f.surface not in known:
            what = "frames or bodies" if isinstance(f, KineticFriction) else "bodies"
            raise SpecError(f"unknown surface '{f.surface}' ({what}: "
                            f"{', '.join(sorted((known - {GROUND}) | self.body_names))})",
                            where=f.where)

    def design(self):
        design = self.d.design
        assert design is not None  # called only for a problem with a design
        params = {p.name for p in self.problem.parameters}
        given = {g.key.text.strip() for g in self.problem.givens}
        if design.find not in params or design.find in given:
            raise SpecError(f"design 'find' must name a parameter that is not given, found "
                            f"'{design.find}'", where=design.where)
        left, right = design.so_that
        self.checker._same(self.checker.type_of(left), self.checker.type_of(right), left,
                           "both sides of 'so_that'")


def _objective_instants(problem, analysis: Integration) -> None:
    """Under an integration an objective's own givens are parameters (the values to use) and at
    most one of the time ``t``, a coordinate or a rate: the instant of the integrated motion
    where it first holds (:func:`instant_of_objective`). Anything else would be read at the
    event, silently: refused."""
    params = {p.name for p in problem.parameters}
    coords = {c.name for c in problem.coordinates}
    until = f"{analysis.until[0].text} = {analysis.until[1].text}"
    for obj in problem.objectives:
        instant = None
        for g in obj.givens:
            node = g.key.node
            if isinstance(node, Name) and node.id in params:
                continue
            if not _names_an_instant(node, coords):
                raise SpecError(f"expected parameters and one of the time t, a coordinate or a "
                                f"rate (q, q') among an objective's own givens under 'analysis: "
                                f"integrate', found '{g.key.text}: {g.text}'; the motion is "
                                f"integrated from 'from:' (the instant is where the given first "
                                f"holds, else the event, when {until})", where=g.where)
            if instant is not None:
                raise SpecError(f"expected one given fixing the instant of objective "
                                f"'{obj.id}' on the integrated motion (the time t, a coordinate "
                                f"or a rate), found '{instant.key.text}' and '{g.key.text}'; "
                                "keep one of them", where=g.where)
            if obj.kind == ObjectiveKind.SYMBOLIC:
                raise SpecError(f"a symbolic objective of an integrated motion is answered at "
                                f"the event, when {until} (in closed form), found "
                                f"'{g.key.text}: {g.text}'; ask for a scalar or a vector at "
                                "that instant", where=g.where)
            instant = g


def _objective_positions(problem, checker) -> None:
    """An objective asked ``when: lhs = rhs`` is read at the first position the motion from
    the work–energy start reaches where the equation holds: only under ``analysis:
    work_energy`` of one coordinate without constraints (the rates follow from the position),
    and without a position of its own among its givens."""
    d = problem.dynamics
    analysis = d.analysis if d is not None else None
    coords = [c.name for c in problem.coordinates]
    for obj in problem.objectives:
        if obj.when is None:
            continue
        left, right = obj.when
        text = f"{left.text} = {right.text}"
        if isinstance(analysis, Integration) and obj.kind == ObjectiveKind.SYMBOLIC:
            raise SpecError(f"objective '{obj.id}': 'when: {text}' is an instant of the motion "
                            "integrated numerically: expected kind: scalar or vector, found "
                            f"kind: symbolic (or end the motion there with 'until: {text}')",
                            where=left.where)
        if not isinstance(analysis, (WorkEnergy, Integration)):
            found = "no analysis" if analysis is None else \
                f"analysis: {_ANALYSIS_NAMES[type(analysis)]}"
            raise SpecError(f"objective '{obj.id}': 'when: {text}' is the position the motion "
                            f"from a work_energy start reaches, or the first instant an "
                            f"integrated motion reaches where it holds; expected 'analysis: "
                            f"work_energy' or 'analysis: integrate', found {found}: add one "
                            "with the start state ('from')", where=left.where)
        if isinstance(analysis, WorkEnergy) and (len(coords) != 1 or problem.constraints):
            raise SpecError(f"objective '{obj.id}': 'when: {text}' needs one coordinate "
                            f"without constraints (its rate follows from the energy balance "
                            f"as a function of the position), found {len(coords)} coordinates "
                            f"and {len(problem.constraints)} constraints; ask at a given "
                            f"position instead (givens: {{{coords[0]}: ...}})",
                            where=left.where)
        for g in obj.givens:
            if _names_an_instant(g.key.node, set(coords)):
                raise SpecError(f"objective '{obj.id}': 'when: {text}' fixes the position, "
                                f"found also '{g.key.text}: {g.text}' among its givens; keep "
                                "one of them", where=g.where)
        checker._same(checker.type_of(left), checker.type_of(right), left,
                      "both sides of 'when'")


_ANALYSIS_NAMES = {Integration: "integrate", WorkEnergy: "work_energy", Impulse: "impulse"}


def _names_an_instant(node: Node, coords: set[str]) -> bool:
    """Whether a given's key is the time, a coordinate or a first rate."""
    if isinstance(node, Prime):
        return node.order == 1 and node.id in coords
    return isinstance(node, Name) and (node.id in coords or node.id == "t")


def instant_of_objective(problem, overrides) -> str | None:
    """The key among an objective's own givens (``overrides``: canonical key text -> Given)
    that names the time ``t``, a coordinate or a rate: on an integrated motion it fixes the
    objective's instant (``None``: the event).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "damped_block_positions.yaml")
    >>> [instant_of_objective(problem, {g.key.text: g for g in o.givens})
    ...  for o in problem.objectives][:3]
    [None, 't', 'x']
    """
    coords = {c.name for c in problem.coordinates}
    return next((key for key, g in overrides.items() if _names_an_instant(g.key.node, coords)),
                None)


def junction_coordinates(problem: Problem) -> tuple[str, ...]:
    """The coordinates that locate massless junctions only (:attr:`Dynamics.junctions`):
    every point whose location uses one is a junction, and no frame turns with it. The
    junctions' balances fix them at every instant, so an integration's ``from`` may leave
    them out.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> junction_coordinates(load_problem(shipped_dir("problems") / "block_on_springs_in_series.yaml"))
    ('xj',)
    """
    if problem.dynamics is None:
        return ()
    nodes = {b.centre for b in problem.dynamics.junctions}
    if not nodes:
        return ()
    points = {p.name: p for p in problem.points}
    chains: dict[str, set[str]] = {}

    def chain(name: str) -> set[str]:
        if name not in chains:
            chains[name] = set()  # a cycle is refused elsewhere
            p = points.get(name)
            if p is not None and p.position is not None:
                chains[name] = names(p.position.node) | (chain(p.origin) if p.origin else set())
        return chains[name]

    turning = {n for f in problem.frames for r in f.rotations for n in names(r.angle.node)}
    out = []
    for c in problem.coordinates:
        located = [p for p in points if c.name in chain(p)]
        if located and set(located) <= nodes and c.name not in turning:
            out.append(c.name)
    return tuple(out)


def _check_analysis(problem, checker, analysis: Analysis) -> None:
    coords = {c.name: c for c in problem.coordinates}
    named = set()
    for start in analysis.start:
        node = start.key.node
        if not (isinstance(node, (Name, Prime)) and node.id in coords
                and (isinstance(node, Name) or node.order == 1)):
            raise SpecError(f"expected a coordinate or its rate (q, q') in 'from', found "
                            f"'{start.key.text}'", where=start.where)
        named.add(to_text(node))
        if start.value is not None:
            checker._dims_match(checker.type_of(start.value).dim, checker.type_of(start.key).dim,
                                start.where, f"the start value of '{start.key.text}'")
            params = {p.name for p in problem.parameters}
            for n in walk(start.value.node):
                if isinstance(n, (Name, Prime)) and n.id not in params | {"pi"}:
                    raise SpecError(f"a start value is a quantity or an expression of "
                                    f"parameters; '{to_text(n)}' is not a parameter",
                                    where=start.where)
    if isinstance(analysis, Impulse):
        bodies = {b.name for b in problem.dynamics.bodies} | {GROUND}
        points = {p.name for p in problem.points}
        for c in analysis.contacts:
            if c.at not in points:
                raise SpecError(f"unknown point '{c.at}' in 'at'", where=c.where)
            for b in c.bodies:
                if b not in bodies:
                    raise SpecError(f"unknown body '{b}' (bodies: {', '.join(sorted(bodies))})",
                                    where=c.where)
            directions = (c.direction,) if isinstance(c, Restitution) else c.directions
            for d in directions:
                t = checker.type_of(d)
                if t.kind != Kind.VECTOR or t.dim != dimensionless():
                    raise SpecError(f"expected a direction (a vector without units, e.g. N.y), "
                                    f"found '{d.text}'", where=c.where)
            if isinstance(c, Restitution) and checker.type_of(c.e).dim != dimensionless():
                raise SpecError(f"expected a pure number for the coefficient of restitution, "
                                f"found '{c.e.text}'", where=c.where)
        for start in analysis.start:
            if not isinstance(start.key.node, Prime):
                raise SpecError(f"expected a rate (q') in 'before', found '{start.key.text}' "
                                "(the configuration does not change during an impact)",
                                where=start.where)
        return
    settled = set(junction_coordinates(problem))  # by the junctions' balances
    missing = [c for c in coords if c not in named and c not in settled]
    if missing:
        raise SpecError(f"'from' needs every coordinate (rates default to 0): missing "
                        f"{', '.join(missing)}", where=analysis.where)
    if isinstance(analysis, WorkEnergy):
        for key, _ in analysis.sense:
            node = key.node
            if not (isinstance(node, Prime) and node.order == 1 and node.id in coords):
                raise SpecError(f"expected a rate (q') in 'sense', found '{key.text}'",
                                where=key.where)
    else:
        left, right = analysis.until
        checker._same(checker.type_of(left), checker.type_of(right), left,
                      "both sides of 'until'")


def argument_dimension(problem, func: str, arg: Node, kind: Kind):
    """The dimension of a ``body``, ``load`` or ``coordinate`` argument of an objective
    function (see :mod:`mechgrade.spec.language`), after checking that it names one."""
    d = problem.dynamics
    name = arg.id if isinstance(arg, Name) else to_text(arg)
    if kind == Kind.COORDINATE:
        coords = {c.name: c for c in problem.coordinates}
        if name not in coords:
            raise SpecError(f"expected a coordinate as argument of {func}(...), found "
                            f"'{name}' (coordinates: {', '.join(coords) or 'none'})")
        return dimension(coords[name].unit)
    bodies = [b.name for b in d.bodies] if d else []
    names = {Kind.BODY: bodies, Kind.LOAD: [x.name for x in d.loads] if d else [],
             Kind.BODY_OR_SPRING: bodies + ([s.name for s in d.springs] if d else [])}[kind]
    if name not in names:
        raise SpecError(f"expected a {kind} as argument of {func}(...), found '{name}' "
                        f"(known: {', '.join(names) or 'none: add a bodies/loads section'})")
    return dimensionless()
