"""What the loads of a kinetics problem are: each body's free-body diagram, the geometric
checks a load's kind makes possible, and the physical bounds the solution must keep.

A free-body diagram is one :class:`AppliedLoad` per load acting on a body (a joint or a string
acts on several: one entry each, with its sign there), in plain symbols and inertial
components: its kind, point, force (or couple), unknown magnitudes and their directions, the
magnitude a textbook writes (``m*g``, ``mu_k*N_P``, ``k*(l - L0)``) and, for a contact, the
surface it is on and that surface's normal. :mod:`mechgrade.solve.fbd` evaluates it at the
instant into plain data for pictures, write-ups and grading.

The checks refuse a model whose loads contradict what they are, each with the fix:
gravity against the stated ``down`` or a weight given twice, a point a pin or a spring holds
that is not a point of its body (a body frame that does not turn with the body, a centre not
fixed in it), a rod whose axis is not the line through its ends, a normal force not
perpendicular to its surface, a static friction force not tangent to it, a coordinate that
moves no mass. The :class:`PhysicalBound` list says what must hold at the instant: a positive
mass, mu >= 0, 0 <= e <= 1, a one-sided contact that pushes, a string that pulls.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.mechanics.dynamics import free_body_loads
>>> problem = load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml")
>>> [(a.name, str(a.kind), str(a.magnitude)) for a in free_body_loads(problem)]
[('gravity', 'weight', 'g*m'), ('N_P', 'normal', 'N_P'), ('F_P', 'kinetic friction', 'N_P*mu_k')]
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import TYPE_CHECKING

import sympy as sp
from sympy.physics.vector import ReferenceFrame, Vector, dynamicsymbols

from ..errors import Location, SolveError, UnderdeterminedError
from ..expressions.syntax import Call, Name, Prime, to_text
from ..spec.dynamics import (GROUND, Body, Damper, Dynamics, Force, Impulse, KineticFriction,
                             LoadKind, Reaction, Restitution, Rod, Spring, StaticFriction)
from ..spec.model import Problem
from .build import Model
from .symbols import identically_zero

if TYPE_CHECKING:
    from .dynamics import _Loads


# ---------------------------------------------------------------------------- the diagram


@dataclass(frozen=True)
class AppliedLoad:
    """One load on one body, as its free-body diagram shows it (plain symbols, inertial
    components as 3x1 matrices).

    ``force`` is the force on ``body`` at ``point`` (``None`` for a couple, whose ``moment``
    is set); ``unknowns`` are the magnitudes solved with the balances, one per direction in
    ``directions`` (this body's sign included), named in the file by ``direction_texts``;
    ``magnitude`` is the textbook's size of the load along ``directions[0]`` for a load with
    one direction (a weight ``m*g``, a normal force ``N_P``, kinetic friction ``mu_k*N_P``, a
    spring's tension ``k*(l - L0)``), else ``None``; ``surface`` and ``surface_normal`` (unit,
    pointing out of the surface into the body) are set for a contact: a normal force, a
    gripping contact, friction."""

    name: str
    kind: LoadKind
    body: str
    point: str | None
    force: sp.Matrix | None
    moment: sp.Matrix | None
    unknowns: tuple[sp.Symbol, ...]
    directions: tuple[sp.Matrix, ...]
    direction_texts: tuple[str, ...]
    magnitude: sp.Expr | None
    sign: int = 1
    surface: str | None = None
    surface_normal: sp.Matrix | None = None
    where: Location = Location()

    @property
    def unknown(self) -> bool:
        return bool(self.unknowns)


def diagram(problem: Problem, model: Model, loads: "_Loads") -> tuple[AppliedLoad, ...]:
    """Every load on every body (the ground left out), in the order of the file's sections;
    gravity is one weight per point a body's parts are centred at (a wheel's disks on one axle
    weigh as one, as a textbook draws it), of those parts' mass."""
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    N, lang = model.inertial, model.language
    plain = model.plain

    def matrix(v: Vector) -> sp.Matrix:
        return plain(v.to_matrix(N))

    out: list[AppliedLoad] = []
    if d.gravity is not None:
        g = lang.vector(d.gravity)
        size = sp.sqrt(plain(g & g))
        for b in d.bodies:
            masses: dict[str, sp.Expr] = {}
            for part in b.parts:
                masses[part.at] = masses.get(part.at, sp.S.Zero) + plain(lang.scalar(part.mass))
            for at, m in masses.items():
                out.append(AppliedLoad("gravity", LoadKind.WEIGHT, b.name, at,
                                       matrix(m * g), None, (), (matrix(g) / size,),
                                       (d.gravity.text,), m * size, where=d.gravity.where))
    normals = {r.name: r for r in d.reactions}
    for item in d.loads:
        kind = d.kind(item.name)
        if kind == LoadKind.APPLIED_COUPLE:
            for body, M in loads.couples[item.name]:
                out.append(AppliedLoad(item.name, kind, body, None, None, matrix(M), (), (),
                                       (), None, where=item.where))
            continue
        for i, (body, point, F) in enumerate(loads.forces[item.name]):
            if body == GROUND:
                continue
            out.append(_applied(item, kind, i, body, point, F, loads, model, normals))
    return tuple(out)


def _applied(item, kind: LoadKind, i: int, body: str, point: str, F: Vector, loads: "_Loads",
             model: Model, normals: dict) -> AppliedLoad:
    """The diagram's entry of application ``i`` of load ``item`` (on ``body`` at ``point``)."""
    N, lang, plain = model.inertial, model.language, model.plain
    force = plain(F.to_matrix(N))
    where = item.where
    if isinstance(item, (Reaction, StaticFriction)):
        sign = item.acts[i].sign if isinstance(item, Reaction) else (1 if i == 0 else -1)
        symbols = loads.reactions[item.name]
        written = (item.direction_at(item.acts[i]),) if isinstance(item, Reaction) and \
            item.acts[i].direction is not None else item.directions
        directions = tuple(sign * plain(lang.vector(e).normalize().to_matrix(N))
                           for e in written)
        texts = tuple(e.text for e in written)
        magnitude = symbols[0] if len(symbols) == 1 else None
        surface, normal = None, None
        if kind in (LoadKind.NORMAL, LoadKind.CONTACT) and isinstance(item, Reaction):
            surface = item.contact_surface if sign > 0 else item.acts[0].on
            normal = directions[0] if kind == LoadKind.NORMAL and len(directions) == 1 \
                else None
        elif isinstance(item, StaticFriction):
            surface = item.surface if i == 0 else item.on
            normal = _normal_of(item, normals, model, sign)
        return AppliedLoad(item.name, kind, body, point, force, None, symbols, directions, texts,
                           magnitude, sign, surface, normal, where)
    if isinstance(item, KineticFriction):
        sign = 1 if i == 0 else -1
        size = plain(lang.scalar(item.mu)) * loads.normal(item.normal)
        slip = loads.slip_velocity(item)
        direction = sign * plain((-slip / slip.magnitude()).to_matrix(N))
        return AppliedLoad(item.name, kind, body, point, force, None, (), (direction,), (),
                           size, sign, item.surface if i == 0 else item.on,
                           _normal_of(item, normals, model, sign), where)
    if isinstance(item, (Spring, Damper)):
        a, b = (model.positions[p] for p in item.between)
        toward = (b - a) if i == 0 else (a - b)
        length = toward.magnitude()
        if isinstance(item, Spring):
            tension = lang.scalar(item.stiffness) * (length - lang.scalar(item.length))
        else:
            tension = lang.scalar(item.coefficient) * (toward & toward.dt(N)) / length
        return AppliedLoad(item.name, kind, body, point, force, None, (),
                           (plain((toward / length).to_matrix(N)),), (), plain(tension),
                           where=where)
    # a known force or impulse: its size along its own direction
    size = sp.sqrt(sum((c ** 2 for c in force), sp.Integer(0)))
    direction = force / size if size != 0 else force
    texts = (item.force.text,) if isinstance(item, Force) else (item.impulse.text,)
    return AppliedLoad(item.name, kind, body, point, force, None, (), (direction,), texts, size,
                       where=where)


def _normal_of(friction, normals: dict, model: Model, sign: int) -> sp.Matrix | None:
    """The unit normal of the surface a friction force is on: its normal force's direction
    (on the friction's body; reversed on the surface body)."""
    normal = normals.get(friction.normal)
    if normal is None or len(normal.directions) != 1:
        return None
    return sign * model.plain(model.language.vector(normal.directions[0]).normalize()
                              .to_matrix(model.inertial))


# ---------------------------------------------------------------------------- physical bounds


class Bounded(Enum):
    """What a :class:`PhysicalBound` is about (it words the message)."""

    MASS = "mass"
    FRICTION_COEFFICIENT = "friction coefficient"
    RESTITUTION = "restitution"
    PUSHING = "pushing"
    PULLING = "pulling"


@dataclass(frozen=True)
class PhysicalBound:
    """``low <= expr <= high`` must hold at the instant (``strict``: ``low < expr``).

    ``given`` bounds depend on the givens only and are judged before the balances are
    solved; the others (a normal force, a tension) on their solution."""

    what: Bounded
    name: str
    expr: sp.Expr
    low: float | None
    high: float | None
    strict: bool = False
    given: bool = True
    point: str = ""
    unit: str = ""
    where: Location = Location()
    direction: str = ""  # a reaction's direction as written
    joins: str = ""  # the springs and dampers a body joins (a mass bound's junction)

    def holds(self, value: float) -> bool:
        """Whether ``value`` keeps the bound (with room for rounding).

        >>> PhysicalBound(Bounded.PUSHING, "N", sp.Integer(0), 0.0, None).holds(-1e-12)
        True
        """
        slack = 1e-9
        if self.low is not None and (value <= self.low if self.strict
                                     else value < self.low - slack):
            return False
        return self.high is None or value <= self.high + slack

    def message(self, value: float) -> str:
        """What is wrong with ``value`` and how to fix it.

        >>> b = PhysicalBound(Bounded.RESTITUTION, "e", sp.Integer(0), 0.0, 1.0, point="A")
        >>> b.message(50.0)
        'the coefficient of restitution at A is 50; expected a value from 0 (plastic) to 1 (elastic); a percentage? write 0.5'
        """
        shown = f"{value:.4g}"
        if self.what == Bounded.MASS:
            text = (f"body '{self.name}' has a mass of {shown} {self.unit} at this instant; "
                    "expected a positive mass")
            if self.joins:
                return (f"{text}: {self.name} joins {self.joins}, a junction of no mass, "
                        "which is written so: mass: 0 (its balance, sum of forces = 0, then "
                        "fixes its position at every instant: springs in series)")
            return (f"{text} (a massless link is no body: its pull is a reaction, a string's "
                    "tension or a pin's force)")
        if self.what == Bounded.FRICTION_COEFFICIENT:
            return (f"friction '{self.name}': mu = {shown}; expected a coefficient of friction "
                    ">= 0 (the force opposes the slip by its direction, never by the sign of "
                    "mu)")
        if self.what == Bounded.RESTITUTION:
            text = (f"the coefficient of restitution at {self.point} is {shown}; expected a "
                    "value from 0 (plastic) to 1 (elastic)")
            if 2 <= value <= 100:
                text += f"; a percentage? write {value / 100:g}"
            return text
        if self.what == Bounded.PUSHING:
            return (f"contact lost at {self.point}: the normal force '{self.name}' would be "
                    f"{shown} {self.unit} (pulling); a surface only pushes, so the body has "
                    "left it before this instant: ask for an instant before it lifts off (an "
                    f"integration can stop there: until: dot(force({self.name}), "
                    f"{self.direction}) = 0), or, if "
                    f"'{self.name}' pushes the other way, give its direction reversed "
                    "(a normal force's direction is the way the surface pushes the body)")
        return (f"the string '{self.name}' would push: its tension is {shown} {self.unit} at "
                "this instant; a string only pulls, so it is slack (model the motion without "
                f"it), or its direction is reversed (a tension's direction is the way the "
                "string pulls the body)")


def _held_still(model: Model, body: Body) -> bool:
    """Whether ``body`` neither turns nor moves in the inertial frame (its frame's angular
    velocity and every part's position constant whatever the coordinates do)."""
    N = model.inertial
    if body.frame is not None and model.frames[body.frame].ang_vel_in(N) != Vector(0):
        return False
    t = dynamicsymbols._t
    return not any(t in c.free_symbols for p in body.parts
                   for c in model.positions[p.at].to_matrix(N))


def physical_bounds(problem: Problem, model: Model, reactions: dict, impact: bool
                    ) -> tuple[PhysicalBound, ...]:
    """What the givens and the solution must keep: each body's mass positive, each friction
    coefficient >= 0, each restitution in [0, 1], each one-sided normal force pushing and
    each string pulling."""
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    if d.mistaken:
        return ()
    lang, plain = model.language, model.plain
    out = []
    for b in d.bodies:
        mass = sum((plain(lang.scalar(p.mass)) for p in b.parts), sp.Integer(0))
        # a body held still (a brake lever) may be massless: its balances are a statics
        # member's; a moving one needs a mass its motion is solved from
        # a body where springs or dampers meet and nothing else acts: a junction
        points = {p.at for p in b.parts}
        ends = sorted(x.name for x in _ends(d) if points & set(x.between))
        # a body written massless (mass: 0) is one by declaration: its balances are
        # constraints (sum of forces = 0), which the solver solves with the others when they
        # determine the motion (a light pulley between cords), else names what they leave open
        out.append(PhysicalBound(Bounded.MASS, b.name, mass, 0.0, None,
                                 strict=not (_held_still(model, b) or identically_zero(mass)),
                                 unit="kg",
                                 where=_value_where(problem, b.parts[0].mass, b.where),
                                 joins=", ".join(ends) if len(ends) > 1 else ""))
    for f in d.friction:
        out.append(PhysicalBound(Bounded.FRICTION_COEFFICIENT, f.name, plain(lang.scalar(f.mu)),
                                 0.0, None, point=f.at, where=_value_where(problem, f.mu, f.where)))
    if isinstance(d.analysis, Impulse):
        for c in d.analysis.contacts:
            if isinstance(c, Restitution):
                out.append(PhysicalBound(Bounded.RESTITUTION, "e", plain(lang.scalar(c.e)), 0.0,
                                         1.0, point=c.at, where=_value_where(problem, c.e,
                                                                             c.where)))
    unit = "N*s" if impact else "N"
    for r in d.reactions:
        if len(r.directions) != 1 or r.kind not in (LoadKind.NORMAL, LoadKind.TENSION):
            continue
        what = Bounded.PUSHING if r.kind == LoadKind.NORMAL else Bounded.PULLING
        out.append(PhysicalBound(what, r.name, reactions[r.name][0], 0.0, None, given=False,
                                 point=r.acts[0].at, unit=unit, where=r.where,
                                 direction=r.directions[0].text))
    return tuple(out)


def _value_where(problem: Problem, expr, fallback: Location) -> Location:
    """Where a value comes from: the given of the parameter ``expr`` names, else ``fallback``."""
    if isinstance(expr.node, Name):
        for g in problem.givens:
            if isinstance(g.key.node, Name) and g.key.node.id == expr.node.id:
                return g.where
    return fallback


# ---------------------------------------------------------------------------- checks


def check_loads(problem: Problem, model: Model, loads: "_Loads", rates, balances,
                constraints, impact: bool) -> None:
    """Refuse a model whose loads contradict what they are (see the module's doc); a
    student's mistaken model (``Dynamics.mistaken``) is taken as it is."""
    if problem.dynamics.mistaken:  # type: ignore[union-attr]
        return
    _check_massless(problem, model, rates, balances, constraints, impact)
    _check_down(problem, model)
    _check_weight_forces(problem, model)
    _check_attachments(problem, model)
    _check_rod_axes(problem, model, loads)
    if not isinstance(problem.dynamics.analysis, Impulse):  # type: ignore[union-attr]
        _check_contacts(problem, model, loads)


def _givens(problem: Problem, model: Model) -> dict:
    """The given values (SI) by plain symbol: parameters, coordinates and their rates."""
    s = model.symbols
    names = {name: symbol for name, symbol in s.params.items()}
    coordinates = [c.name for c in problem.coordinates]
    out = {}
    for g in problem.givens:
        node = g.key.node
        if isinstance(node, Name) and node.id in names:
            out[names[node.id]] = g.si
        elif isinstance(node, Name) and node.id in coordinates:
            out[s.q[coordinates.index(node.id)]] = g.si
        elif isinstance(node, Prime) and node.order == 1 and node.id in coordinates:
            out[s.qd[coordinates.index(node.id)]] = g.si
    return out


def _number(expr, values: dict) -> float | None:
    value = sp.sympify(sp.sympify(expr).xreplace(values))
    if value.free_symbols:
        return None
    try:
        return float(value)
    except TypeError:  # complex
        return None


def _text(value, model: Model) -> str:
    """A plain expression or vector as a spec writes it (``theta'`` for ``thetad``)."""
    s = model.symbols
    spelled = {}
    for q, qd, qdd in zip(s.q, s.qd, s.qdd):
        spelled[qd] = sp.Symbol(f"{q}'")
        spelled[qdd] = sp.Symbol(f"{q}''")
    value = model.plain(value)
    if isinstance(value, Vector):
        text = str(value.applyfunc(lambda e: sp.sympify(e).xreplace(spelled)))
    else:
        text = sp.sstr(sp.sympify(value).xreplace(spelled))
    return "-" + text[2:] if text.startswith("- ") else text


def _fixed_in(relative: Vector, frame: ReferenceFrame, model: Model) -> bool:
    """Whether a position difference is constant in ``frame``."""
    rate = model.plain(relative.dt(frame).to_matrix(frame))
    return all(identically_zero(c) for c in rate)


def _check_massless(problem: Problem, model: Model, rates, balances, constraints,
                    impact: bool) -> None:
    """Every coordinate's rate to solve for (second rate, or the rate just after an impact)
    appears in some balance or constraint, unless it is given."""
    present = set().union(*(e.expr.free_symbols for e in (*balances, *constraints))) \
        if balances or constraints else set()
    given = {to_text(g.key.node) for g in problem.givens} | \
        {to_text(g.key.node) for o in problem.objectives for g in o.givens}
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    mark = "'" if impact else "''"
    for coordinate, rate in zip(problem.coordinates, rates):
        if rate in present or f"{coordinate.name}{mark}" in given:
            continue
        q = model.symbols.dyn[coordinate.name]
        N = model.inertial
        moved = [p.name for p in problem.points
                 if any(c.has(q) for c in model.positions[p.name].to_matrix(N))]
        lang = model.language
        # a part of no mass (mass: 0) moves no mass: its point is a junction as much as a
        # point no body is centred at
        centres = {part.at for b in d.bodies for part in b.parts
                   if not identically_zero(model.plain(lang.scalar(part.mass)))}
        ends = sorted({x.name for x in _ends(d) for p in x.between if p in moved})
        turned = [f.name for f in problem.frames if f.name in model.frames and any(
            c.has(q) for c in model.frames[f.name].ang_vel_in(N).to_matrix(N))]
        frames = {b.frame for b in d.bodies}
        cause = []
        junctions = [p for p in moved if p not in centres]
        if junctions and ends:
            first = junctions[0]
            cause.append(f"{', '.join(junctions)} (where {', '.join(ends)} end) moves with "
                         f"{coordinate.name} but no body is centred there: a massless "
                         "junction is a body of no mass, node: {mass: 0, centre: "
                         f"{first}}}, named at the ends at {first} (bodies: [ground, node]); "
                         f"its balance (sum of forces = 0) then fixes {first}")
        for frame in turned:
            if frame not in frames:
                cause.append(f"{coordinate.name} turns frame {frame}, which is no body's frame: "
                             f"if a body turns with it, write frame: {frame} for that body")
        if not cause:
            cause.append(f"give a body moved by {coordinate.name} its mass and inertia, or "
                         f"give {coordinate.name}{mark} (a prescribed motion)")
        raise UnderdeterminedError(
            f"the model is under-constrained: coordinate '{coordinate.name}' moves no mass: "
            f"{coordinate.name}{mark} appears in no body's momentum balance, so the balances do "
            f"not determine {coordinate.name}{mark}; {'; '.join(cause)}", where=coordinate.where)


def _ends(d: Dynamics) -> tuple[Spring | Damper, ...]:
    """The loads with two ends: springs and dampers."""
    return (*d.springs, *d.dampers)


def _check_down(problem: Problem, model: Model) -> None:
    """Gravity points the way the problem says is down."""
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    if d.down is None or d.gravity is None:
        return
    lang, N = model.language, model.inertial
    g, down = lang.vector(d.gravity), lang.vector(d.down)
    across = model.plain((g ^ down).to_matrix(N))
    along = model.plain(g & down)
    sense = _number(along, _givens(problem, model))
    if sense is None:
        sense = 1.0 if along.is_positive else -1.0 if along.is_negative else 0.0
    if all(identically_zero(c) for c in across) and sense > 0:
        return
    which = "up, against" if all(identically_zero(c) for c in across) else "across"
    raise SolveError(f"gravity '{d.gravity.text}' points {which} the problem's down "
                     f"(down: {d.down.text}); expected gravity along down: write its magnitude, "
                     f"gravity: g, with down: {d.down.text} (or fix down)", where=d.gravity.where)


def _check_weight_forces(problem: Problem, model: Model) -> None:
    """No known force is a body's weight while gravity also acts on it."""
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    if d.gravity is None:
        return
    lang, N = model.language, model.inertial
    g = lang.vector(d.gravity)
    values = _givens(problem, model)
    for f in d.forces:
        body = d.body(f.on)
        mass = sum((lang.scalar(p.mass) for p in body.parts), sp.Integer(0))
        difference = model.plain((lang.vector(f.force) - mass * g).to_matrix(N))
        numbers = [_number(c, values) for c in difference]
        size = _number(model.plain((mass * g).magnitude()), values)
        same = all(identically_zero(c) for c in difference) or (
            size is not None and all(n is not None for n in numbers)
            and max(abs(n) for n in numbers) <= 1e-6 * size)  # type: ignore[arg-type]
        if same:
            raise SolveError(f"the force '{f.name}' ({f.force.text}) is the weight of {f.on}, "
                             f"which 'gravity: {d.gravity.text}' already applies to every "
                             "body: the weight is given twice; expected it once: delete "
                             f"'{f.name}' (or delete gravity and write '{f.name}' with kind: "
                             "weight)", where=f.where)


def _attachments(d: Dynamics) -> list[tuple[str, str, str, Location]]:
    """``(body, point, what, where)`` of each point a load holds fixed in a body: a pin's
    point and the ends of springs and dampers (``ground`` for a fixed end)."""
    out = []
    for r in d.reactions:
        if r.kind == LoadKind.PIN:
            out += [(a.on, a.at, f"the pin '{r.name}'", r.where) for a in r.acts]
    for s in _ends(d):
        what = f"{'spring' if isinstance(s, Spring) else 'damper'} '{s.name}'"
        out += [(body, point, f"an end of {what}", s.where)
                for point, body in zip(s.between, s.on)]
    return out


def _check_attachments(problem: Problem, model: Model) -> None:
    """Each pin's point and each end of a spring or damper is a point of the body named:
    fixed relative to its centre in its frame (a particle's: in the inertial frame; the
    ground's: fixed in it)."""
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    N = model.inertial
    for body_name, point, what, where in _attachments(d):
        if body_name == GROUND:
            relative = model.positions[point] - model.positions[problem.inertial_point]
            if not _fixed_in(relative, N, model):
                raise SolveError(f"{what} is on the ground at {point}, but {point} moves "
                                 f"({point} - {problem.inertial_point} = "
                                 f"{_text(relative, model)}); expected a fixed point there, "
                                 "or the body the end moves with", where=where)
            continue
        body = d.body(body_name)
        frame_name = body.frame or problem.inertial_frame
        relative = model.positions[point] - model.positions[body.centre]
        if _fixed_in(relative, model.frames[frame_name], model):
            continue
        raise SolveError(_not_a_point(problem, model, body, point, what, relative), where=where)


def _not_a_point(problem: Problem, model: Model, body: Body, point: str, what: str,
                 relative: Vector) -> str:
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    frame = body.frame or problem.inertial_frame
    where = f" in {body.name}'s frame {frame}" if body.frame else ""
    text = (f"{what} acts on {body.name} at {point}, which is not a point of {body.name}: "
            f"{point} moves relative to {body.name}'s centre {body.centre}{where} ({point} - "
            f"{body.centre} = {_text(relative, model)}); expected a point fixed in "
            f"{body.name}")
    owners = [b.name for b in d.bodies if b.name != body.name and _fixed_in(
        model.positions[point] - model.positions[b.centre],
        model.frames[b.frame or problem.inertial_frame], model)]
    if owners:
        return text + f": {point} is a point of {' and '.join(owners)} (name the bodies in " \
                      "the order of the points)"
    if body.frame is None:
        return text
    return text + _turning_hint(problem, model, body, point, relative)


def _turning_hint(problem: Problem, model: Model, body: Body, point: str,
                  relative: Vector) -> str:
    """Where a point that does not turn with a body's frame does turn: the frame the body
    may turn with, or the vectors its centre and the point should be located with."""
    frame = body.frame or problem.inertial_frame
    turning = [f.name for f in problem.frames if f.name != frame
               and _fixed_in(relative, model.frames[f.name], model)]
    if not turning:
        return ""
    other = turning[0]
    return (f"; {point} - {body.centre} is fixed in {other}, not in {frame}: if {body.name} "
            f"turns with {other}, write frame: {other}; if not, locate {body.centre} and "
            f"{point} with {frame}'s unit vectors")


def _check_rod_axes(problem: Problem, model: Model, loads: "_Loads") -> None:
    """A rod's axis is the line through its ends, and a slender rod is loaded at its points:
    every point where a load acts on a one-rod body lies on that line, turning with the
    rod's frame, within half its length of the centre."""
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    values = _givens(problem, model)
    for b in d.bodies:
        if b.frame is None or len(b.parts) != 1 or not isinstance(b.parts[0].shape, Rod):
            continue
        part, rod = b.parts[0], b.parts[0].shape
        F = model.frames[b.frame]
        axis = getattr(F, rod.axis)
        held = sorted({(p, name) for name, apps in loads.forces.items()
                       for on, p, _ in apps if on == b.name and p != part.at})
        for point, name in held:
            relative = model.positions[point] - model.positions[part.at]
            across = model.plain((relative ^ axis).to_matrix(F))
            if not all(identically_zero(c) for c in across):
                off = (f"the rod '{b.name}' lies along {b.frame}.{rod.axis} (axis: {rod.axis}), "
                       f"but {point}, where '{name}' acts on it, is off that line ({point} - "
                       f"{part.at} = {_text(relative, model)})")
                if not _fixed_in(relative, F, model):
                    raise SolveError(off + _turning_hint(problem, model, b, point, relative),
                                     where=part.where)
                along = [a for a in "xyz" if all(identically_zero(c) for c in model.plain(
                    (relative ^ getattr(F, a)).to_matrix(F)))]
                fix = f"expected axis: {along[0]}" if along else \
                    f"expected {point} on the rod's line"
                raise SolveError(f"{off}: a rod's axis is the line through its ends; {fix}",
                                 where=part.where)
            distance = _number(model.plain(relative.magnitude()), values)
            half = _number(model.plain(model.language.scalar(rod.length)) / 2, values)
            if distance is not None and half is not None and distance > half * (1 + 1e-9):
                raise SolveError(f"{point}, where '{name}' acts on the rod '{b.name}', is "
                                 f"{distance:.4g} m from its centre {part.at}, beyond its ends "
                                 f"({half:.4g} m, half its length {rod.length.text}); expected "
                                 f"{part.at} at the rod's middle and its length the distance "
                                 "between its ends", where=part.where)


def _check_contacts(problem: Problem, model: Model, loads: "_Loads") -> None:
    """A normal force is perpendicular to the surface (the contact's relative motion has no
    component along it); a static friction force is tangent to it."""
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    lang = model.language
    reactions = {r.name: r for r in d.reactions}
    for r in d.reactions:
        if r.kind != LoadKind.NORMAL:
            continue
        act = r.acts[0]
        if act.on == GROUND:
            continue
        relative = _relative_velocity(problem, model, loads, act.on, act.at, r.contact_surface)
        for e in r.directions:
            n = lang.vector(e)
            if identically_zero(model.plain(relative & n)):
                continue
            raise SolveError(_not_normal(model, r, e.text, n, relative, act.on,
                                         act.at), where=r.where)
    for f in d.friction:
        if not isinstance(f, StaticFriction):
            continue
        normal = reactions[f.normal]
        n = lang.vector(normal.directions[0])
        for e in f.directions:
            if identically_zero(model.plain(lang.vector(e) & n)):
                continue
            fix = _perpendicular(model, [n], lang.vector(e))
            raise SolveError(f"static friction '{f.name}' along {e.text} is not tangent to the "
                             f"surface at {f.at}: it has a component along the normal force "
                             f"'{f.normal}' ({normal.directions[0].text}); expected directions "
                             f"perpendicular to {normal.directions[0].text}"
                             + (f", e.g. {fix}" if fix else ""), where=f.where)


def _relative_velocity(problem: Problem, model: Model, loads: "_Loads", body: str, point: str,
                       surface: str) -> Vector:
    """The velocity of ``body``'s material point at ``point`` relative to the surface's
    (the ground, a body's material point, or a frame's point coincident with it)."""
    v = loads.velocity(body, point)
    d: Dynamics = problem.dynamics  # type: ignore[assignment]
    if surface in {b.name for b in d.bodies}:
        return v - loads.velocity(surface, point)
    if surface not in (GROUND, problem.inertial_frame):
        v -= model.language.point_velocity(Call("coincident", (Name(point), Name(surface))),
                                           problem.inertial_frame)
    return v


def _not_normal(model: Model, r: Reaction, text: str, n: Vector,
                relative: Vector, body: str, point: str) -> str:
    s = model.symbols
    slides = []
    plain = model.plain(relative)
    for q, qd in zip(s.q, s.qd):
        partial = plain.diff(qd, model.inertial)
        if partial != Vector(0) and not identically_zero(partial & model.plain(n)):
            slides.append((f"{q}'", partial))
    motion = " and ".join(f"along {_text(p, model)} (with {rate})" for rate, p in slides) \
        or f"with {_text(relative, model)}"
    fix = _perpendicular(model, [p for _, p in slides] or [plain], n)
    return (f"the normal force '{r.name}' along {text} is not perpendicular to the surface at "
            f"{point}: {body}'s point {point} slides {motion} relative to "
            f"{'the ground' if r.contact_surface == GROUND else r.contact_surface}, and {text} "
            "has a component along that; expected the surface's normal, perpendicular to the "
            "sliding" + (f" ({fix})" if fix else "")
            + "; if the surface itself moves, name it: surface: <frame or body>")


def _perpendicular(model: Model, vectors, near: Vector) -> str:
    """A frame's unit vector (signed) perpendicular to every one of ``vectors`` and closest
    to ``near``, as a spec writes it, or ``""``."""
    import random

    near = model.plain(near)
    best, score = "", 0.0
    rng = random.Random(3)
    for name, frame in model.frames.items():
        for axis in "xyz":
            e = getattr(frame, axis)
            if not all(identically_zero(model.plain(v & e)) for v in vectors):
                continue
            dot = sp.sympify(model.plain(near & e))
            value = float(dot.xreplace({x: rng.uniform(0.3, 1.2) for x in dot.free_symbols}))
            if abs(value) > score + 1e-9:
                best, score = f"{'-' if value < 0 else ''}{name}.{axis}", abs(value)
    return best
