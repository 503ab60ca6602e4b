"""The problem model as frozen dataclasses, in the textbook's systematic order.

A :class:`Problem` is what :func:`mechgrade.spec.load_problem` returns: inertial frame and point,
body frames, points with location descriptions, generalized coordinates, parameters,
constraints, givens at the instant, objectives with tolerances and author tests. Every
expression keeps its text, its parsed tree and the :class:`~mechgrade.errors.Location` it came
from, so any later error can point back into the file.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from enum import Enum
from typing import TYPE_CHECKING

from ..errors import AuthorWarning, Location
from ..expressions.functions import StrEnum
from ..expressions.syntax import Node
from .variant_model import Variants

if TYPE_CHECKING:
    from .dynamics import Dynamics

TIME = "t"
"""The reserved name of time in every expression."""


@dataclass(frozen=True)
class Expr:
    """An expression as written in the spec: its text, syntax tree and location."""

    text: str
    node: Node
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Rotation:
    """A simple rotation of a frame from its parent: ``angle`` about the parent's ``axis``."""

    axis: str  # "x", "y" or "z"
    angle: Expr


@dataclass(frozen=True)
class Frame:
    """A reference frame. ``rotations`` is one simple rotation or a body-fixed sequence.

    ``origin`` is a point fixed in the frame, needed for velocities relative to the frame,
    coincident points and instantaneous centres.
    """

    name: str
    parent: str | None
    rotations: tuple[Rotation, ...]
    origin: str | None
    where: Location = field(default_factory=Location, compare=False)
    parent_where: Location = field(default_factory=Location, compare=False)
    origin_where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Point:
    """A point located from another point by a vector (its location description)."""

    name: str
    origin: str | None  # None only for the inertial point
    position: Expr | None
    where: Location = field(default_factory=Location, compare=False)
    origin_where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Coordinate:
    """A generalized coordinate (a function of time), with the unit that sets its dimension."""

    name: str
    unit: str
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Parameter:
    """A constant of the problem (length, radius, fixed angle, tooth count)."""

    name: str
    unit: str
    positive: bool = True
    where: Location = field(default_factory=Location, compare=False)


class ConstraintLevel(Enum):
    """The level a constraint holds at: its ``position:`` or ``velocity:`` key (a rolling
    contact holds at the velocity level)."""

    POSITION = "position"
    VELOCITY = "velocity"


@dataclass(frozen=True)
class Constraint:
    """``lhs = rhs`` holding for all time, at the position or the velocity level.

    Position constraints (holonomic: loop closures, paths, gear and arc-length relations) are
    differentiated for the velocity and acceleration levels; velocity constraints (rolling
    without slip, non-holonomic) are differentiated once. Vector equations stand for their
    components in the inertial frame.
    """

    name: str
    level: ConstraintLevel
    lhs: Expr
    rhs: Expr
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Given:
    """A value known at the instant: of a parameter, a coordinate or its rates, or of any
    scalar expression (``dot(vel(B, N), B.x)``). ``value`` is in ``unit``; ``si`` in SI.
    ``value_expr`` is set when the value was written as an expression of other givens
    (``x: L/2``); loading evaluates it."""

    key: Expr
    value: float
    unit: str
    si: float
    text: str
    where: Location = field(default_factory=Location, compare=False)
    value_expr: Expr | None = None


class Root(Enum):
    """Which root of the position (or a non-linear rate) level a ``branch:`` entry asks for."""

    POSITIVE = "positive"
    NEGATIVE = "negative"
    FIRST_POSITIVE = "first positive"


@dataclass(frozen=True)
class Branch:
    """``branch: {t: first positive}``: the root wanted for one solved quantity."""

    key: Expr
    root: Root
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Definition:
    """``define: {r_AB: pos(B, A)}``: a name for an intermediate quantity; expressions that use
    the name are read with the definition in its place."""

    name: str
    expr: Expr
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Tolerance:
    """Accepted difference: ``|a - b| <= max(rel * |b|, abs)``; ``abs`` in the objective's unit.

    For vectors ``|b|`` is the reference vector's magnitude, applied to each component.
    """

    rel: float = 0.01
    abs: float = 0.0
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class SymbolDecl:
    """A name a symbolic answer is written in, and the spec quantity it stands for."""

    name: str
    means: Expr


@dataclass(frozen=True)
class Expect:
    """The author's test of an objective: the value the solver must reproduce.

    Exactly one of ``value`` (scalar), ``components`` (vector, in the objective's frame) and
    ``expr`` (symbolic) is set. ``book`` is the printed answer when it differs, explained in
    ``note``. ``written`` keeps the value (or each component) as the author typed it: its
    digits set how closely the solver must reproduce it.
    """

    value: float | None = None
    components: tuple[float, ...] | None = None
    expr: str | None = None
    unit: str | None = None
    book: str | None = None
    note: str | None = None
    where: Location = field(default_factory=Location, compare=False)
    written: str | tuple[str, ...] | None = None


class ObjectiveKind(StrEnum):
    """What an objective's answer is: a number, components in a frame, or an expression in
    the objective's symbols. Members equal their text (``ObjectiveKind.SCALAR == "scalar"``)
    and serialise as it.

    >>> import json
    >>> ObjectiveKind("vector"), json.dumps(ObjectiveKind.VECTOR), f"{ObjectiveKind.SYMBOLIC}"
    (<ObjectiveKind.VECTOR: 'vector'>, '"vector"', 'symbolic')
    """

    SCALAR = "scalar"
    VECTOR = "vector"
    SYMBOLIC = "symbolic"


@dataclass(frozen=True)
class Mistake:
    """An author-declared typical mistake: the mistaken model's expression, a message for the
    student and the credit (0..1) it earns."""

    find: Expr
    message: str
    credit: float = 0.0
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Objective:
    """What to find: an expression of the objective language, reported in ``unit``.

    ``kind`` is ``scalar``, ``vector`` (components in ``frame``) or ``symbolic`` (an
    expression in ``symbols``). ``givens`` add to or replace the problem's givens for this
    objective only (another instant, "if the rate were ..."). ``when`` (``lhs = rhs``, under
    ``analysis: work_energy``) asks at the first position the motion from the start reaches
    where the equation holds (a contact lost, a speed reached).
    """

    id: str
    prompt: str
    find: Expr
    kind: ObjectiveKind
    unit: str
    frame: str | None = None
    symbols: tuple[SymbolDecl, ...] = ()
    tolerance: Tolerance = Tolerance()
    expect: Expect | None = None
    mistakes: tuple[Mistake, ...] = ()
    depends_on: tuple[str, ...] = ()
    givens: tuple[Given, ...] = ()
    when: tuple[Expr, Expr] | None = None
    where: Location = field(default_factory=Location, compare=False)
    frame_where: Location = field(default_factory=Location, compare=False)
    depends_where: tuple[Location, ...] = field(default=(), compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", ObjectiveKind(self.kind))  # text from a file


CONSISTENCY = 5e-3
"""The part of its terms' size an equation may be off by and still hold, where a spec does
not say (``consistency:``; the schema's default says the same)."""


@dataclass(frozen=True)
class Problem:
    """A whole problem file; ``warnings`` are legal oddities found while loading it."""

    id: str
    title: str
    statement: str
    source: str
    inertial_frame: str
    inertial_point: str
    frames: tuple[Frame, ...]
    points: tuple[Point, ...]
    coordinates: tuple[Coordinate, ...]
    parameters: tuple[Parameter, ...]
    constraints: tuple[Constraint, ...]
    givens: tuple[Given, ...]
    guesses: tuple[Given, ...]
    objectives: tuple[Objective, ...]
    consistency: float = CONSISTENCY
    path: str | None = field(default=None, compare=False)
    unknowns: tuple[Expr, ...] = ()
    branches: tuple[Branch, ...] = ()
    definitions: tuple[Definition, ...] = ()
    warnings: tuple[AuthorWarning, ...] = field(default=(), compare=False)
    variants: Variants | None = None  # spec.variants: how each student's givens are drawn
    dynamics: "Dynamics | None" = None  # bodies and loads (spec/dynamics.py)
    tags: tuple[str, ...] = field(default=(), compare=False)  # a catalogue's topics, not physics

    def __hash__(self) -> int:
        # the solver's caches are keyed by the problem, and hashing one walks all of it
        known = self.__dict__.get("_hash")
        if known is None:
            known = hash(tuple(getattr(self, f.name) for f in fields(self) if f.compare))
            object.__setattr__(self, "_hash", known)
        return known

    def __getstate__(self) -> dict:
        # a string's hash differs from process to process
        return {k: v for k, v in self.__dict__.items() if k != "_hash"}

    def objective(self, objective_id: str) -> Objective:
        for objective in self.objectives:
            if objective.id == objective_id:
                return objective
        raise KeyError(objective_id)
