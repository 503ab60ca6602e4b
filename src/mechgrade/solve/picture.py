"""The mechanism at the solved instant as plain numbers, and its picture: every point's
position, velocity and acceleration, each frame's origin and unit vectors (inertial components,
SI), and what a dynamics problem declares about its mechanism: each body's shape, the pins,
the fixed surfaces, the strings, the springs and the dampers; drawn as a small inline SVG
(``mechgrade solve --plot``, feedback pages, handouts) as a textbook draws the mechanism.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.solve import solve
>>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
>>> s = scene(problem, solve(problem))
>>> [(p.name, p.described_from) for p in s.points]
[('O', None), ('A', 'O')]
>>> [round(c, 3) for c in s.points[1].position[:2]]
[0.528, 0.305]
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from decimal import Decimal
from functools import lru_cache
from itertools import pairwise
from html import escape

import numpy as np

from ..expressions.functions import StrEnum
from ..expressions.syntax import Name
from ..mechanics.build import build
from ..spec.dynamics import GROUND, LoadKind, OutlineKind
from ..spec.model import Problem
from ..units import same_dimension, si_factor
from .fbd import drawn_shape
from .generated import lambdified
from .layout import ROUND, apart, collides, outline_extent
from .plan import kinematics_plan
from .result import Solution

Triple = tuple[float, float, float]


@dataclass(frozen=True)
class ScenePoint:
    """A point at the instant; ``described_from`` the point its position is written from."""

    name: str
    position: Triple
    velocity: Triple | None
    acceleration: Triple | None
    described_from: str | None


@dataclass(frozen=True)
class SceneFrame:
    """A frame's origin (``None`` without one) and its x and y unit vectors (``None`` where
    not known at the instant)."""

    name: str
    origin: Triple | None
    x: Triple | None
    y: Triple | None


@dataclass(frozen=True)
class SceneBody:
    """One part of a body as the picture draws it: its shape ``kind``, its ``centre``, its
    ``sizes`` in m (a rod's length, a radius, a block's sides; ``None`` where not known), the
    body ``axis`` (``x``/``y``/``z``) the shape lies along or turns about, and the body's
    ``axes`` (its x, y and z unit vectors; ``None`` for a particle)."""

    body: str
    kind: OutlineKind
    centre: Triple
    sizes: tuple[float | None, ...] = ()
    axis: str = ""
    axes: tuple[Triple | None, Triple | None, Triple | None] | None = None


class SupportKind(StrEnum):
    """What joins the bodies to each other and to the ground, as the picture draws it."""

    PIN = "pin"  # a pin to the ground
    JOINT = "joint"  # a pin between two bodies
    SURFACE = "surface"  # a fixed surface a body touches
    STRING = "string"  # a string's ends, each pulling its body along its direction
    SPRING = "spring"
    DAMPER = "damper"


@dataclass(frozen=True)
class SceneSupport:
    """A support of ``kind`` named ``name``: its points ``at`` (a pin's or a contact's one, a
    spring's or a damper's two ends, a string's ends), ``directions`` (a surface's normal into
    the body; each string end's pull on its body) and the body at each point (``ground`` for
    a fixed end)."""

    kind: SupportKind
    name: str
    at: tuple[Triple, ...]
    directions: tuple[Triple | None, ...] = ()
    bodies: tuple[str, ...] = ()


@dataclass(frozen=True)
class Scene:
    problem: str
    points: tuple[ScenePoint, ...]
    frames: tuple[SceneFrame, ...]
    title: str = ""  # the problem's title, which the picture's text alternative names
    bodies: tuple[SceneBody, ...] = ()
    supports: tuple[SceneSupport, ...] = ()
    down: Triple | None = None  # the problem's down (its gravity's direction), a unit vector
    units: tuple[str, str] = ("m/s", "m/s^2")  # the legend's velocity and acceleration units


def scene(problem: Problem, solution: Solution) -> Scene:
    """``problem``'s points and frames at the instant ``solution`` solved (values the solver
    left free are ``nan``; a point whose motion is not known has ``None``). The model is
    turned into functions once per problem; each solution (a student's variant) only
    evaluates them."""
    names, points, frames, bodies, supports, down = _drawing(problem)
    known = {s.name: s.si for s in solution.state}
    values = [known.get(name, np.nan) for name in names]

    def evaluated(f) -> np.ndarray | None:
        if f is None:
            return None
        with np.errstate(all="ignore"):
            out = np.asarray(f(*values), dtype=float).ravel()
        return out if np.all(np.isfinite(out)) else None

    def number(f) -> Triple | None:
        out = evaluated(f)
        if out is None:
            return None
        x, y, z = (float(c) + 0.0 for c in out)  # a vector's components
        return x, y, z

    def unit(f) -> Triple | None:
        v = number(f)
        size = math.sqrt(sum(c * c for c in v)) if v is not None else 0.0
        return tuple(c / size + 0.0 for c in v) if v is not None and size > 0 else None  # type: ignore[return-value]

    def size(f) -> float | None:
        out = evaluated(f)
        return None if out is None else float(out[0])

    def placed(fs) -> tuple[Triple, ...] | None:
        out = tuple(number(f) for f in fs)
        return None if None in out else out  # type: ignore[return-value]

    drawn_bodies = []
    for body, kind, centre, sizes, axis, axes in bodies:
        at = number(centre)
        if at is not None:
            x, y, z = (unit(f) for f in axes) if axes else (None, None, None)
            drawn_bodies.append(SceneBody(body, kind, at, tuple(size(f) for f in sizes), axis,
                                          (x, y, z) if axes else None))
    drawn_supports = []
    for kind, name, at, directions, on in supports:
        ends = placed(at)
        if ends is not None:
            drawn_supports.append(SceneSupport(kind, name, ends,
                                               tuple(unit(f) for f in directions), on))
    return Scene(problem.id, tuple(
        ScenePoint(name, number(position) or (np.nan,) * 3, number(velocity),
                   number(acceleration), origin)
        for name, position, velocity, acceleration, origin in points), tuple(
        SceneFrame(name, number(origin) if origin is not None else None, number(x), number(y))
        for name, origin, x, y in frames), problem.title, tuple(drawn_bodies),
        tuple(drawn_supports), unit(down), motion_units(problem))


def motion_units(problem: Problem) -> tuple[str, str]:
    """The units ``problem`` writes velocities and accelerations in: an objective's of that
    dimension, else the length unit of its givens per second (squared), else SI.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> motion_units(load_problem(shipped_dir("problems") / "ruina_10_4_10_7_rotating_tube_accel.yaml"))
    ('ft/s', 'ft/s^2')
    """
    length = next((g.unit for g in problem.givens if g.unit and same_dimension(g.unit, "m")),
                  "m")
    asked = [o.unit for o in problem.objectives if o.unit]
    return (next((u for u in asked if same_dimension(u, "m/s")), f"{length}/s"),
            next((u for u in asked if same_dimension(u, "m/s^2")), f"{length}/s^2"))


def drawable(s: Scene) -> bool:
    """Whether the scene has a mechanism to draw: two points with a known position (a
    problem answered only in symbols has no numbers to place its points with).

    >>> drawable(Scene("p", (ScenePoint("O", (0, 0, 0), None, None, None),), ()))
    False
    """
    return sum(all(math.isfinite(c) for c in p.position[:2]) for p in s.points) >= 2


def geometry(s: Scene) -> Scene:
    """The scene without its velocities and accelerations: the mechanism as a problem sheet
    shows it (the motion is what the student works out).

    >>> s = Scene("p", (ScenePoint("A", (1, 0, 0), (0, 2, 0), (-4, 0, 0), None),), ())
    >>> geometry(s).points[0].velocity is None
    True
    """
    return replace(s, points=tuple(replace(p, velocity=None, acceleration=None)
                                   for p in s.points))


_REACTION_SUPPORTS = {LoadKind.NORMAL: SupportKind.SURFACE, LoadKind.CONTACT: SupportKind.SURFACE,
                      LoadKind.PIN: SupportKind.PIN, LoadKind.TENSION: SupportKind.STRING}
"""What an unknown force of each kind is drawn as (a reaction of unstated kind with two or
more directions at one point is a pin)."""


@lru_cache(maxsize=64)
def _drawing(problem: Problem):
    """The state's names, and every point's position, velocity and acceleration and every
    frame's origin and unit vectors as functions of the state (inertial components)."""
    kinematic = replace(problem, objectives=(), dynamics=None)  # loads draw nothing
    p = kinematics_plan(kinematic)
    model = build(kinematic)
    N = model.inertial

    def function(vector):
        matrix = model.plain(vector.to_matrix(N))
        return lambdified(p.index.symbols, matrix)

    specs = {q.name: q for q in problem.points}
    points = []
    for name, position in model.positions.items():
        spec = specs.get(name)
        points.append((name, function(position),
                       function(model.language.point_velocity(Name(name), N.name)),
                       function(model.language.point_acceleration(Name(name), N.name)),
                       spec.origin if spec is not None else None))
    frames = []
    for f in problem.frames:
        origin = f.origin or (problem.inertial_point if f.name == problem.inertial_frame
                              else None)
        frames.append((f.name, function(model.positions[origin])
                       if origin in model.positions else None,
                       function(model.frames[f.name].x), function(model.frames[f.name].y)))
    bodies, supports, down = _mechanism(problem, model, p.index.symbols)
    return tuple(p.index.names), tuple(points), tuple(frames), bodies, supports, down


def _mechanism(problem: Problem, model, symbols):
    """The bodies' parts, the supports and the problem's down of a dynamics problem, as
    functions of the state (none without a ``bodies:`` section)."""
    d = problem.dynamics
    if d is None:
        return (), (), None
    N = model.inertial

    def vector(expr, sign: int = 1):
        return lambdified(symbols, model.plain(
            sign * model.language.vector(expr).to_matrix(N)))

    def scalar(expr):
        return lambdified(symbols, model.plain(model.language.scalar(expr)))

    def point(name):
        return lambdified(symbols, model.plain(model.positions[name].to_matrix(N)))

    bodies = []
    for body in d.bodies:
        frame = model.frames[body.frame] if body.frame is not None else None
        axes = () if frame is None else tuple(
            lambdified(symbols, model.plain(e.to_matrix(N)))
            for e in (frame.x, frame.y, frame.z))
        for part in body.parts:
            kind, sizes, axis = drawn_shape(part.shape if frame is not None else None)
            bodies.append((body.name, kind, point(part.at), tuple(scalar(e) for e in sizes),
                           axis, axes))
    supports: list[tuple] = []
    for spring in d.springs:
        supports.append((SupportKind.SPRING, spring.name, tuple(point(q) for q in spring.between),
                         (), spring.on))
    for damper in d.dampers:
        supports.append((SupportKind.DAMPER, damper.name, tuple(point(q) for q in damper.between),
                         (), damper.on))
    for reaction in d.reactions:
        support = _REACTION_SUPPORTS.get(reaction.kind)
        if support is None and len(reaction.directions) > 1 and len(reaction.acts) == 1:
            support = SupportKind.PIN
        if support is None:
            continue
        if support == SupportKind.PIN and len(reaction.acts) > 1:
            support = SupportKind.JOINT
        if support == SupportKind.SURFACE:
            if reaction.contact_surface != GROUND and reaction.contact_surface in \
                    {b.name for b in d.bodies}:
                continue  # against another body: that body's outline is the surface
            act = reaction.acts[0]
            supports.append((support, reaction.name, (point(act.at),),
                             (vector(reaction.direction_at(act), act.sign),),
                             (act.on,)))
            continue
        if support == SupportKind.STRING:
            supports.append((support, reaction.name, tuple(point(a.at) for a in reaction.acts),
                             tuple(vector(reaction.direction_at(a), a.sign)
                                   for a in reaction.acts),
                             tuple(a.on for a in reaction.acts)))
            continue
        supports.append((support, reaction.name, (point(reaction.acts[0].at),), (),
                         tuple(a.on for a in reaction.acts)))
    down = d.down if d.down is not None else d.gravity
    return tuple(bodies), tuple(supports), vector(down) if down is not None else None


# ---------------------------------------------------------------------------- drawing

VELOCITY, ACCELERATION, FRAME, BODY = "#1565c0", "#c62828", "#616e7c", "#323f4b"  # AA on white
FILL, SUPPORT = "#e4e7eb", "#52606d"
"""A body's fill, and the ground's and the supports' lines."""
WIDTH, HEIGHT, MARGIN = 480.0, 360.0, 40.0
BLOCK = 14.0
"""Half the side of a block drawn for a particle that rests on a surface or hangs (px)."""
HALO = 'paint-order="stroke" stroke="#fff" stroke-width="3" stroke-linejoin="round"'
"""Labels stay readable where they cross a line."""
SUBSCRIPT = 'baseline-shift="sub" font-size="8"'
"""A label's subscript (an axis of a unit vector)."""
_OWN_STYLE = ' xmlns="http://www.w3.org/2000/svg"', ' font-family="system-ui, sans-serif" font-size="13"'
_GROUND = '<rect width="{w:g}" height="{h:g}" fill="#fff"/>'
"""What a picture on its own says and a page's style sheet gives every picture inline."""
_CANDIDATES = ((7, -7, "start"), (7, 18, "start"), (-7, -7, "end"), (-7, 18, "end"),
               (0, -12, "middle"), (0, 24, "middle"), (12, 5, "start"), (-12, 5, "end"),
               # clear of a block drawn on the point (BLOCK px each way, turned any angle)
               (24, 5, "start"), (-24, 5, "end"), (0, -24, "middle"), (0, 36, "middle"))
"""Where a point's label may go, relative to the point (px) and how it is anchored: the first
that overlaps no label and crosses no line drawn is taken."""

Seg = tuple[tuple[float, float], tuple[float, float]]


@dataclass
class _Sheet:
    """The SVG being drawn: its elements, the lines a label must not cross, the boxes
    labels already take and the arrows already placed (page pixels)."""

    out: list
    lines: list
    boxes: list
    arrows: list


def picture_svg(s: Scene, ident: str | None = None, *, inline: bool = False) -> str:
    """The picture as a small, self-contained SVG (text, no script, no external reference;
    the same bytes each time). ``ident`` prefixes its element ids (default: the problem id),
    so several pictures can sit inline in one page. ``inline``: for a page whose style sheet
    gives what every picture would say again (``.mechanism`` in worked.css.j2: its font, its
    white ground, the labels' halo), without them, its namespace or its line breaks.

    >>> s = Scene("p", (ScenePoint("O", (0, 0, 0), (0, 0, 0), (0, 0, 0), None),
    ...                 ScenePoint("A", (1, 1, 0), (-7, 7, 0), (-50, -40, 0), "O")),
    ...           (SceneFrame("N", (0, 0, 0), (1, 0, 0), (0, 1, 0)),))
    >>> svg = picture_svg(s)
    >>> svg.startswith("<svg") and "velocity (longest 9.9 m/s)" in svg and "𝐧̂<tspan" in svg
    True
    """
    ident = _ident(ident or s.problem)
    motion = (", velocities and accelerations"
              if any(p.velocity or p.acceleration for p in s.points) else "")
    shown = [p for p in s.points if all(math.isfinite(c) for c in p.position[:2])]
    world = [p.position[:2] for p in shown] + [e for b in s.bodies for e in _extent(b)]
    world += [a[:2] for support in s.supports for a in support.at]
    xs, ys = [w[0] for w in world] or [0.0], [w[1] for w in world] or [0.0]
    size = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    strings = [_string(support, s.bodies, size) for support in s.supports
               if support.kind == SupportKind.STRING]
    world += [q for string in strings for q in string.reach]
    xs, ys = [w[0] for w in world] or [0.0], [w[1] for w in world] or [0.0]
    legend = _legend(s, shown)
    # motion arrows reach 0.35 size beyond the points, frame labels 0.25: the view covers them
    reach = (0.4 if motion else 0.3) * size
    x0, x1 = min(xs) - reach, max(xs) + reach
    y0, y1 = min(ys) - reach, max(ys) + reach
    bottom = MARGIN + 18 * len(legend)  # the legend has its own band
    scale = min((WIDTH - 2 * MARGIN) / (x1 - x0), (HEIGHT - MARGIN - bottom) / (y1 - y0))
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2

    def at(x: float, y: float) -> tuple[float, float]:  # y up
        return WIDTH / 2 + scale * (x - cx), (HEIGHT - bottom + MARGIN) / 2 - scale * (y - cy)

    sheet = _Sheet([f'<svg{_OWN_STYLE[0]} viewBox="0 0 {WIDTH:g} {HEIGHT:g}" '
                    f'width="{WIDTH:g}" height="{HEIGHT:g}" role="img" '
                    f'class="mechanism"{_OWN_STYLE[1]}>',
                    # an image's first title and desc are its name and description
                    f'<title>{escape(s.title or s.problem)}: the mechanism at '
                    f'the instant</title>',
                    f'<desc>{escape(described(s, legend))}</desc>', "<defs>"],
                   [], [], [])
    for name, colour in (("v", VELOCITY), ("a", ACCELERATION), ("f", FRAME)):
        sheet.out.append(f'<marker id="{ident}-{name}" viewBox="0 0 10 10" refX="9" refY="5" '
                         f'markerWidth="7" markerHeight="7" orient="auto">'
                         f'<path d="M0,0 10,5 0,10z" fill="{colour}"/></marker>')
    sheet.out += ["</defs>", _GROUND.format(w=WIDTH, h=HEIGHT)]
    down = _page(s.down) if s.down is not None else (0.0, 1.0)
    if not s.bodies:  # a kinematics problem: its points joined as they are described
        by_name = {p.name: p for p in shown}
        for p in shown:
            origin = by_name.get(p.described_from) if p.described_from is not None else None
            if origin is not None:
                _segment(sheet, at(*origin.position[:2]), at(*p.position[:2]),
                         f'stroke="{BODY}" stroke-width="4" stroke-linecap="round"')
    resting = {support.bodies[0]: support for support in s.supports
               if support.kind == SupportKind.SURFACE and support.directions[0] is not None}
    # a particle a string wraps round is the pulley drawn on it (a light pulley's axle), one
    # something else holds a block
    wrapped = {b for string in strings for b in string.wrapped}
    held = {b for support in s.supports for b in support.bodies} - wrapped
    for support in s.supports:
        if support.kind == SupportKind.SURFACE and support.directions[0] is not None:
            kinds = {b.kind: b for b in s.bodies if b.body == support.bodies[0]}
            rod = kinds.get(OutlineKind.ROD)
            _surface(sheet, at(*support.at[0][:2]), _page(support.directions[0]),
                     BLOCK if OutlineKind.PARTICLE in kinds else 0.0,
                     at(*rod.centre[:2]) if rod is not None else None)
    for string in strings:
        _draw_string(sheet, string, at, scale)
    _springs(sheet, s.supports, at)
    for body in _unwrapped(s.bodies, wrapped):
        _body(sheet, body, at, scale, resting, held, down)
    for support in s.supports:
        if support.kind == SupportKind.PIN:
            _pin(sheet, at(*support.at[0][:2]), down)
        elif support.kind == SupportKind.JOINT:
            x, y = at(*support.at[0][:2])
            sheet.out.append(f'<circle cx="{x:.0f}" cy="{y:.0f}" r="4.5" fill="#fff" '
                             f'stroke="{BODY}" stroke-width="2"/>')
    boxes = [at(*b.centre[:2]) for b in s.bodies
             if b.kind == OutlineKind.BODY or (b.kind == OutlineKind.PARTICLE and b.body in held)]
    axes = _frames(sheet, s, at, size, ident, boxes)
    for colour, _, mark, kind, largest in legend:
        sheet.out.append(f'<g stroke="{colour}" stroke-width="2.2" '
                         f'marker-end="url(#{ident}-{mark})">')
        for p in shown:
            v = getattr(p, kind)
            if v is None or math.hypot(v[0], v[1]) <= 1e-3 * largest:
                continue
            tail, head = apart(at(*p.position[:2]),
                               at(*_tip(p.position, v, 0.35 * size / largest)), sheet.arrows)
            sheet.arrows.append((tail, head))
            _segment(sheet, tail, head)
        sheet.out.append("</g>")
    _frame_labels(sheet, axes)
    places: dict[tuple[int, int], list[str]] = {}  # coincident points share one label
    for p in shown:
        x, y = at(*p.position[:2])
        places.setdefault((round(x), round(y)), []).append(p.name)
    for x, y in places:
        sheet.out.append(f'<circle cx="{x}" cy="{y}" r="3.5" fill="#1f2933"/>')
    labels = ['<g font-weight="bold" font-size="15" fill="#1f2933" '
              f'{HALO}>']
    for (x, y), names in places.items():
        text = ", ".join(names)
        labels.append(_placed_label(sheet, (x, y), ", ".join(point_svg(n) for n in names),
                                    8.6 * len(text), markup=True))
    sheet.out += labels + ["</g>"]
    for i, (colour, text, *_) in enumerate(legend):
        y = HEIGHT - 14 - 18 * (len(legend) - 1 - i)
        sheet.out.append(f'<path d="M12,{y - 4:g}h24" stroke="{colour}" stroke-width="2.2"/>')
        sheet.out.append(f'<text x="42" y="{y:g}" fill="{colour}" font-size="12">'
                         f'{escape(text)}</text>')
    sheet.out.append("</svg>")
    return _inlined(sheet.out) if inline else "\n".join(sheet.out) + "\n"


def _inlined(out: list[str]) -> str:
    """A picture's elements for a page that styles every picture (``.mechanism``): what it
    would say again left out, no line breaks."""
    return "".join(out).replace(HALO, 'class="halo"').replace(SUBSCRIPT, 'class="sb"').replace(
        _OWN_STYLE[0], "").replace(
        _OWN_STYLE[1], "").replace(_GROUND.format(w=WIDTH, h=HEIGHT), "")


def _legend(s: Scene, shown) -> list[tuple[str, str, str, str, float]]:
    """The kinds of arrow drawn: colour, legend text (the longest in the problem's unit),
    marker, attribute and the longest's length (SI). A kind whose longest arrow is round-off
    (a body at rest) is not drawn."""
    legend = []
    for kind, colour, mark, unit in (("velocity", VELOCITY, "v", s.units[0]),
                                     ("acceleration", ACCELERATION, "a", s.units[1])):
        largest = max((math.hypot(v[0], v[1]) for p in shown
                       if (v := getattr(p, kind)) is not None), default=0.0)
        if largest <= 1e-9:
            continue
        shown_unit = unit.replace("**", "^").replace("^2", "²").replace("^3", "³")
        legend.append((colour, f"{kind} (longest {plain_number(largest / si_factor(unit))} "
                               f"{shown_unit})",
                       mark, kind, largest))
    return legend


def plain_number(x: float, digits: int = 2) -> str:
    """``x`` to ``digits`` significant digits as a student reads a number: no exponent.

    >>> plain_number(499.7), plain_number(0.01234), plain_number(3.21), plain_number(1.2e-7)
    ('500', '0.012', '3.2', '0.00000012')
    """
    return format(Decimal(f"{x:.{digits}g}"), "f")


def _page(v: Triple) -> tuple[float, float]:
    """A direction (inertial x, y) on the page (y down), of unit length."""
    size = math.hypot(v[0], v[1]) or 1.0
    return v[0] / size, -v[1] / size


def _segment(sheet: _Sheet, a, b, style: str = "") -> None:
    """A straight line from ``a`` to ``b`` (page); ``style`` its attributes, none when an
    enclosing group gives them."""
    sheet.lines.append((a, b))
    sheet.out.append(f'<path d="M{a[0]:.0f},{a[1]:.0f}L{b[0]:.0f},{b[1]:.0f}"'
                     + (f" {style}" if style else "") + "/>")


def _hatch(at: tuple[float, float], along: tuple[float, float], away: tuple[float, float],
           half: float) -> str:
    """A ground line through ``at`` along ``along`` (unit, page), ``half`` px each way,
    hatched on the side ``away`` (unit, page)."""
    x, y = at
    path = [f"M{x - half * along[0]:.0f},{y - half * along[1]:.0f}"
            f"L{x + half * along[0]:.0f},{y + half * along[1]:.0f}"]
    count = max(int(half / 7), 2)
    for k in range(-count, count + 1):
        px, py = x + k * half / count * along[0], y + k * half / count * along[1]
        path.append(f"M{px:.0f},{py:.0f}l{7 * away[0] - 5 * along[0]:.0f},"
                    f"{7 * away[1] - 5 * along[1]:.0f}")
    return f'<path class="ground" d="{"".join(path)}" stroke="{SUPPORT}" fill="none"/>'


def _surface(sheet: _Sheet, contact, normal, offset: float, away=None) -> None:
    """A fixed surface at ``contact`` (page), ``normal`` (page) out of it into the body; a
    particle drawn as a block sits ``offset`` px above its point. A rod touching it at
    ``contact`` (its centre ``away`` from there) touches a ledge: drawn on the far side."""
    x, y = contact[0] - offset * normal[0], contact[1] - offset * normal[1]
    along = (-normal[1], normal[0])
    half = 70.0
    if away is not None and math.dist(away, contact) > 1.0:
        if _dot(along, (away[0] - x, away[1] - y)) > 0:
            along = (-along[0], -along[1])
        half = 30.0
        x, y = x + (half - 12) * along[0], y + (half - 12) * along[1]
    sheet.lines.append(((x - half * along[0], y - half * along[1]),
                        (x + half * along[0], y + half * along[1])))
    sheet.out.append(_hatch((x, y), along, (-normal[0], -normal[1]), half))


def _pin(sheet: _Sheet, p, down) -> None:
    """A pin to the ground at ``p``: a triangle on a hatched base below it."""
    across = (-down[1], down[0])
    base = (p[0] + 22 * down[0], p[1] + 22 * down[1])
    corners = [(base[0] + s * 11 * across[0], base[1] + s * 11 * across[1]) for s in (-1, 1)]
    sheet.out.append(f'<path class="pin" d="M{p[0]:.0f},{p[1]:.0f}L{corners[0][0]:.0f},'
                     f'{corners[0][1]:.0f}L{corners[1][0]:.0f},{corners[1][1]:.0f}z" '
                     f'fill="{FILL}" stroke="{SUPPORT}" stroke-width="1.5"/>')
    sheet.out.append(_hatch(base, across, down, 18.0))
    sheet.out.append(f'<circle cx="{p[0]:.0f}" cy="{p[1]:.0f}" r="4.5" fill="#fff" '
                     f'stroke="{BODY}" stroke-width="2"/>')
    sheet.lines.append((p, base))


@dataclass(frozen=True)
class _String:
    """A string as drawn (inertial x, y in m): its straight runs, its pulleys (centre,
    radius in m, or ``None`` for a small one drawn at a corner) and the points where it or a
    pulley hangs from the ceiling (with the direction up, away from the string), and the
    bodies it wraps round (a pulley on each)."""

    runs: tuple[tuple[tuple[float, float], tuple[float, float]], ...]
    pulleys: tuple[tuple[tuple[float, float], float | None], ...]
    anchors: tuple[tuple[tuple[float, float], tuple[float, float]], ...]
    wrapped: tuple[str, ...] = ()

    @property
    def reach(self) -> list[tuple[float, float]]:
        out = [q for run in self.runs for q in run] + [a for a, _ in self.anchors]
        for c, r in self.pulleys:
            out += [(c[0] - (r or 0), c[1] - (r or 0)), (c[0] + (r or 0), c[1] + (r or 0))]
        return out


def _string(support: SceneSupport, bodies, size: float) -> _String:
    """How a string's ends lead over pulleys: ends pulling one way rise to one level, where
    ends on two bodies side by side share a fixed pulley, two ends on one body wrap round a
    pulley on it and an end wrapping with nothing beyond it is tied to the ceiling; two ends
    whose lines meet turn round a pulley at the corner; ends at one point (a cord that leaves
    a drum) hang their particle from it."""
    ends = [(p[:2], d[:2], body) for p, d, body in zip(support.at, support.directions,
                                                        support.bodies) if d is not None]
    centres = {b.body: b.centre[:2] for b in bodies if b.kind == OutlineKind.PARTICLE}
    runs: list = []
    pulleys: list = []
    anchors: list = []
    if len({(round(p[0], 9), round(p[1], 9)) for p, _, _ in ends}) == 1:
        for p, _, body in ends:
            if body in centres and math.dist(centres[body], p) > 1e-9:
                runs.append((centres[body], p))
        return _String(tuple(runs), (), ())
    u0 = _unit2(ends[0][1]) if ends else (0.0, 1.0)
    if len(ends) == 2 and abs(_cross(u0, _unit2(ends[1][1]))) > 1e-6:
        (p, u, _), (q, w, _) = (ends[0][0], _unit2(ends[0][1]), 0), (ends[1][0],
                                                                     _unit2(ends[1][1]), 0)
        det = _cross(u, w)
        t = _cross((q[0] - p[0], q[1] - p[1]), w) / det
        r = _cross((q[0] - p[0], q[1] - p[1]), u) / det
        if t > 0 and r > 0:
            corner = (p[0] + t * u[0], p[1] + t * u[1])
            return _String(((p, corner), (q, corner)), ((corner, None),), ())
    if all(_dot(_unit2(d), u0) > 0.999 for _, d, _ in ends):
        across = (-u0[1], u0[0])
        ends.sort(key=lambda e: _dot(e[0], across))
        widest = max((math.dist(p, q) / 2 for (p, _, a), (q, _, b) in pairwise(ends)
                      if a != b), default=0.0)
        # strands long beside their pulley, as a textbook draws an Atwood machine
        level = max(_dot(p, u0) for p, _, _ in ends) + max(0.45 * size, 3 * widest)
        tops = [(p[0] + (level - _dot(p, u0)) * u0[0], p[1] + (level - _dot(p, u0)) * u0[1])
                for p, _, _ in ends]
        joined = [0] * len(ends)
        wraps = [False] * len(ends)
        fixed = []
        wrapped = []
        for i in range(len(ends) - 1):
            (p, _, a), (q, _, b) = ends[i], ends[i + 1]
            joined[i] += 1
            joined[i + 1] += 1
            if a == b:
                wraps[i] = wraps[i + 1] = True
                wrapped.append(a)
                pulleys.append((((p[0] + q[0]) / 2, (p[1] + q[1]) / 2), math.dist(p, q) / 2))
            else:
                c = ((tops[i][0] + tops[i + 1][0]) / 2, (tops[i][1] + tops[i + 1][1]) / 2)
                fixed.append((c, math.dist(tops[i], tops[i + 1]) / 2))
        ceiling = level + max((r for _, r in fixed), default=0.0) + 0.15 * size
        runs = [(p, top) for (p, _, _), top in zip(ends, tops)]
        for i, top in enumerate(tops):
            if wraps[i] and joined[i] < 2:
                roof = (top[0] + (ceiling - level) * u0[0], top[1] + (ceiling - level) * u0[1])
                runs.append((top, roof))
                anchors.append((roof, u0))
        for c, _ in fixed:
            roof = (c[0] + (ceiling - level) * u0[0], c[1] + (ceiling - level) * u0[1])
            runs.append((c, roof))
            anchors.append((roof, u0))
        return _String(tuple(runs), tuple(pulleys + fixed), tuple(anchors), tuple(wrapped))
    for p, d, _ in ends:  # a cord to a fixed point
        u = _unit2(d)
        end = (p[0] + 0.3 * size * u[0], p[1] + 0.3 * size * u[1])
        runs.append((p, end))
        anchors.append((end, u))
    return _String(tuple(runs), (), tuple(anchors))


def _draw_string(sheet: _Sheet, string: _String, at, scale: float) -> None:
    sheet.out.append(f'<g stroke="{BODY}" stroke-width="1.5">')
    for a, b in string.runs:
        _segment(sheet, at(*a), at(*b))
    sheet.out.append("</g>")
    for c, r in string.pulleys:
        x, y = at(*c)
        radius = 8.0 if r is None else max(r * scale, 4.0)
        sheet.out.append(f'<circle class="pulley" cx="{x:.0f}" cy="{y:.0f}" r="{radius:.0f}" '
                         f'fill="{FILL}" stroke="{BODY}" stroke-width="2"/>'
                         f'<circle cx="{x:.0f}" cy="{y:.0f}" r="2.5" fill="{BODY}"/>')
    for a, up in string.anchors:
        page_up = (up[0], -up[1])
        sheet.out.append(_hatch(at(*a), (-page_up[1], page_up[0]), page_up, 20.0))


def _springs(sheet: _Sheet, supports, at) -> None:
    """Springs as coils and dampers as dashpots; several between one pair of points are
    drawn side by side."""
    pairs: dict[tuple, list] = {}
    for support in supports:
        if support.kind in (SupportKind.SPRING, SupportKind.DAMPER):
            a, b = at(*support.at[0][:2]), at(*support.at[1][:2])
            pairs.setdefault(tuple(sorted((_round(a), _round(b)))), []).append((support, a, b))
    for items in pairs.values():
        for i, (support, a, b) in enumerate(items):
            length = math.dist(a, b)
            if length < 1.0:
                continue
            u = ((b[0] - a[0]) / length, (b[1] - a[1]) / length)
            n = (-u[1], u[0])
            shift = (i - (len(items) - 1) / 2) * 20.0
            a = (a[0] + shift * n[0], a[1] + shift * n[1])
            b = (b[0] + shift * n[0], b[1] + shift * n[1])

            def along(f: float, side: float = 0.0) -> tuple[float, float]:
                # B023 does not apply: called only in this iteration, on its a, u, n, length
                return (a[0] + f * length * u[0] + side * n[0],  # noqa: B023 - said above
                        a[1] + f * length * u[1] + side * n[1])  # noqa: B023

            if support.kind == SupportKind.SPRING:
                zigs = [along(0.2 + 0.6 * k / 12, 6.0 * (-1) ** k if 0 < k < 12 else 0.0)
                        for k in range(13)]
                points = [a, *zigs, b]
                d = "M" + "L".join(f"{x:.0f},{y:.0f}" for x, y in points)
                sheet.out.append(f'<path class="spring" d="{d}" fill="none" stroke="{BODY}" '
                                 f'stroke-width="1.6"/>')
            else:
                rod, wall, end = along(0.5), along(0.62), along(0.38)
                d = (f"M{a[0]:.0f},{a[1]:.0f}L{end[0]:.0f},{end[1]:.0f}"
                     f"M{along(0.38, -8)[0]:.0f},{along(0.38, -8)[1]:.0f}"
                     f"L{along(0.38, 8)[0]:.0f},{along(0.38, 8)[1]:.0f}"
                     f"M{along(0.3, -8)[0]:.0f},{along(0.3, -8)[1]:.0f}"
                     f"L{along(0.62, -8)[0]:.0f},{along(0.62, -8)[1]:.0f}"
                     f"L{along(0.62, 8)[0]:.0f},{along(0.62, 8)[1]:.0f}"
                     f"L{along(0.3, 8)[0]:.0f},{along(0.3, 8)[1]:.0f}"
                     f"M{wall[0]:.0f},{wall[1]:.0f}L{b[0]:.0f},{b[1]:.0f}")
                del rod
                sheet.out.append(f'<path class="damper" d="{d}" fill="none" stroke="{BODY}" '
                                 f'stroke-width="1.6"/>')
            sheet.lines.append((a, b))
            for end_at, on, away in ((a, support.bodies[0], (-u[0], -u[1])),
                                     (b, support.bodies[1], u)):
                if on == GROUND:
                    sheet.out.append(_hatch(end_at, n, away, 14.0))


def _body(sheet: _Sheet, body: SceneBody, at, scale: float, resting, held, down) -> None:
    """A body's part by its shape: a rod its full length, a disk or a ring round its centre,
    a block by its sides, a particle that something supports as a block (square to the
    surface it rests on, else upright), a free one as a dot, a body given by its inertia's
    entries as a rounded box round its centre."""
    x, y = at(*body.centre[:2])
    style = f'fill="{FILL}" stroke="{BODY}" stroke-width="2"'
    cls = f'class="body" data-body="{escape(body.body, quote=True)}"'
    if body.kind == OutlineKind.PARTICLE and body.body in held:
        if body.body in resting:
            n = _page(resting[body.body].directions[0])
        else:
            n = (-down[0], -down[1])
        angle = math.degrees(math.atan2(n[0], -n[1]))
        reach = BLOCK * (abs(n[0]) + abs(n[1]))  # half the turned square's width
        sheet.boxes.append((x - reach, y - reach, x + reach, y + reach))  # no label on it
        sheet.out.append(f'<rect {cls} x="{x - BLOCK:.0f}" y="{y - BLOCK:.0f}" '
                         f'width="{2 * BLOCK:g}" height="{2 * BLOCK:g}" {style} '
                         f'transform="rotate({angle:.0f} {x:.0f} {y:.0f})"/>')
        return
    if body.kind == OutlineKind.ROD:
        ends = _extent(body)
        if len(ends) == 2:
            (ax, ay), (bx, by) = at(*ends[0]), at(*ends[1])
            sheet.lines.append(((ax, ay), (bx, by)))
            sheet.out.append(f'<path {cls} d="M{ax:.0f},{ay:.0f}L{bx:.0f},{by:.0f}" '
                             f'stroke="{BODY}" stroke-width="9" stroke-linecap="round"/>'
                             f'<path d="M{ax:.0f},{ay:.0f}L{bx:.0f},{by:.0f}" stroke="{FILL}" '
                             f'stroke-width="5" stroke-linecap="round"/>')
            return
    if body.kind == OutlineKind.BLOCK and body.axes is not None:
        corners = [at(*c) for c in _extent(body)]
        if len(corners) == 4:
            sheet.out.append(f'<path {cls} d="M' + "L".join(f"{cx:.0f},{cy:.0f}"
                                                          for cx, cy in corners)
                             + f'z" {style}/>')
            return
    if body.kind in ROUND and body.sizes and body.sizes[-1] is not None:
        r = max(body.sizes[-1] * scale, 4.0)
        fill = "none" if body.kind in (OutlineKind.RING, OutlineKind.SHELL) else FILL
        sheet.out.append(f'<circle {cls} cx="{x:.0f}" cy="{y:.0f}" r="{r:.0f}" fill="{fill}" '
                         f'stroke="{BODY}" stroke-width="2"/>')
        axis = body.axes[0] if body.axes is not None else None
        if axis is not None:  # a radius marked on the body shows it turn
            ex, ey = x + r * axis[0], y - r * axis[1]
            sheet.out.append(f'<path d="M{x:.0f},{y:.0f}L{ex:.0f},{ey:.0f}" stroke="{BODY}" '
                             f'stroke-width="1.2" stroke-dasharray="4 3"/>')
        return
    if body.kind == OutlineKind.BODY:  # inertia by its entries: a rigid body of no set shape
        sheet.out.append(f'<rect {cls} x="{x - 2 * BLOCK:.0f}" y="{y - 1.4 * BLOCK:.0f}" '
                         f'width="{4 * BLOCK:g}" height="{2.8 * BLOCK:g}" rx="{BLOCK:g}" '
                         f'{style}/>')
        return
    sheet.out.append(f'<circle {cls} cx="{x:.0f}" cy="{y:.0f}" r="9" {style}/>')


def _extent(body: SceneBody) -> list[tuple[float, float]]:
    """The points (inertial x, y in m) a body's part reaches."""
    return outline_extent(body.kind, body.centre, body.sizes, body.axis, body.axes)


def _frames(sheet: _Sheet, s: Scene, at, size: float, ident: str,
            boxes: list[tuple[float, float]] | None = None) -> list:
    """Each frame's unit vectors at its origin; frames sharing an origin and a direction share
    one arrow and one label ("N.x = B.x"). A frame whose origin is inside a box drawn for a
    body (``boxes``: their centres on the page) has them in the sheet's lower right corner
    instead, where they hide no body."""
    axes: dict[tuple, tuple[tuple[float, float], tuple[float, float], list[str]]] = {}
    sheet.out.append(f'<g stroke="{FRAME}" stroke-width="1.5" marker-end="url(#{ident}-f)">')
    for frame in s.frames:
        if frame.origin is None or frame.x is None or frame.y is None:
            continue
        origin = at(*frame.origin[:2])
        crowded = any(math.dist(origin, b) < 1.5 * BLOCK for b in boxes or ())
        for axis, vector in (("x", frame.x), ("y", frame.y)):
            start = origin
            end = at(*_tip(frame.origin, vector, 0.18 * size))
            if crowded:  # moved whole: the arrows keep their directions and lengths
                corner = (WIDTH - MARGIN - 0.18 * size * _page_scale(at), HEIGHT - 24.0)
                start, end = corner, (corner[0] + end[0] - origin[0],
                                      corner[1] + end[1] - origin[1])
            key = (start, round(end[0]), round(end[1]))
            if key not in axes:
                _segment(sheet, start, end)
                sheet.arrows.append((start, end))
                axes[key] = (start, end, [])
            axes[key][2].append(f"{frame.name}.{axis}")
    sheet.out.append("</g>")
    return list(axes.values())


def _unwrapped(bodies, wrapped: set[str]) -> list:
    """The bodies drawn by their own shape: not a particle a string wraps round (the pulley
    drawn on it is its shape)."""
    return [b for b in bodies if b.kind != OutlineKind.PARTICLE or b.body not in wrapped]


def _page_scale(at) -> float:
    """Page pixels per metre of ``at``."""
    return math.dist(at(0.0, 0.0), at(1.0, 0.0))


def _frame_labels(sheet: _Sheet, axes) -> None:
    """The frames' axis labels, placed once every line is drawn."""
    labels = [f'<g fill="{FRAME}" font-size="11" {HALO}>']
    for start, end, names in axes:
        shown = " = ".join(unit_vector_svg(name) for name in names)
        # a label's width: the letters and signs, a subscript set smaller
        labels.append(_placed_label(sheet, end, shown, 6.2 * (4 * len(names) - 3), start,
                                    markup=True))
    if len(labels) > 1:
        sheet.out += labels + ["</g>"]


def point_svg(name: str) -> str:
    """A point's name as an SVG label writes it, as the page's equations do: trailing digits
    a subscript (P₁).

    >>> point_svg("P1"), point_svg("G")
    ('P<tspan baseline-shift="sub" font-size="8">1</tspan>', 'G')
    """
    stem = name.rstrip("0123456789")
    if not stem or stem == name:
        return escape(name)
    return f'{escape(stem)}<tspan {SUBSCRIPT}>{name[len(stem):]}</tspan>'


def unit_vector_svg(name: str) -> str:
    """A frame's unit vector (``N.x``) as an SVG label writes it, as the page's equations do:
    the frame's letter bold and lower case with a hat, the axis its subscript.

    >>> unit_vector_svg("N.x")
    '𝐧̂<tspan baseline-shift="sub" font-size="8">x</tspan>'
    """
    frame, _, axis = name.partition(".")
    letter = frame.lower()
    hat = f"{chr(0x1D41A + ord(letter) - 97)}\u0302" if len(letter) == 1 and "a" <= letter <= "z" \
        else f"{escape(letter)}\u0302"
    return f'{hat}<tspan {SUBSCRIPT}>{escape(axis)}</tspan>'


def _placed_label(sheet: _Sheet, p, text: str, width: float, from_=None,
                  markup: bool = False) -> str:
    """A label near ``p`` (beyond it, away from ``from_`` when given) where it overlaps no
    label and crosses no line (the first place tried when every one does); ``text`` is
    escaped unless it is ``markup`` already."""
    if from_ is not None:
        d = math.dist(from_, p) or 1.0
        u = ((p[0] - from_[0]) / d, (p[1] - from_[1]) / d)
        tried = [(u[0] * k, u[1] * k + 4, "start" if u[0] > 0.35 else
                  "end" if u[0] < -0.35 else "middle") for k in (10, 18, 28, 40)]
        tried += list(_CANDIDATES)
    else:
        tried = list(_CANDIDATES)
    first = None
    for dx, dy, anchor in tried:
        x, y = p[0] + dx, p[1] + dy
        left = x if anchor == "start" else x - width if anchor == "end" else x - width / 2
        box = (left, y - 12, left + width, y + 3)
        first = first or (x, y, anchor, box)
        if not collides(box, sheet.boxes, sheet.lines):
            break
    else:
        x, y, anchor, box = first  # type: ignore[misc]
    sheet.boxes.append(box)
    middle = {"start": "", "end": ' text-anchor="end"', "middle": ' text-anchor="middle"'}
    return f'<text x="{x:.0f}" y="{y:.0f}"{middle[anchor]}>{text if markup else escape(text)}</text>'


def described(s: Scene, legend=()) -> str:
    """The picture in words, for whoever cannot see it: the bodies, the supports, the points,
    what joins them, the frames' unit vectors and the arrows with their scales (``legend``:
    colour and text first).

    >>> print(described(Scene("p", (ScenePoint("O", (0, 0, 0), None, None, None),
    ...     ScenePoint("A", (1, 1, 0), None, None, "O")), (SceneFrame("N", (0, 0, 0),
    ...     (1, 0, 0), (0, 1, 0)),)), [("#c62828", "acceleration (longest 64 m/s²)")]))
    Points O and A; a line joins A to O. Unit vectors x and y of frame N. Arrows: acceleration (longest 64 m/s²), in red.
    """
    shown = [p.name for p in s.points if all(math.isfinite(c) for c in p.position[:2])]
    parts = []
    if s.bodies:
        parts.append("Bodies: " + "; ".join(f"{b.body}, {_shape_words(b)}" for b in s.bodies))
    supports = [_support_words(support) for support in s.supports]
    if supports:
        parts.append("Supports: " + "; ".join(supports))
    parts.append(f"{'Point' if len(shown) == 1 else 'Points'} {_and(shown)}")
    joined = [f"{p.name} to {p.described_from}" for p in s.points
              if p.described_from in shown and p.name in shown]
    if joined and not s.bodies:
        parts[-1] += f"; a line joins {_and(joined)}"
    frames = [f.name for f in s.frames if None not in (f.origin, f.x, f.y)]
    if frames:
        parts.append(f"Unit vectors x and y of {'frame' if len(frames) == 1 else 'frames'} "
                     f"{_and(frames)}")
    colours = {VELOCITY: "blue", ACCELERATION: "red"}
    if legend:
        parts.append("Arrows: " + "; ".join(f"{text}, in {colours.get(colour, colour)}"
                                            for colour, text, *_ in legend))
    return ". ".join(parts) + "."


def _shape_words(b: SceneBody) -> str:
    size = b.sizes[-1] if b.sizes else None
    if b.kind == OutlineKind.ROD:
        return "a rod" + (f" {b.sizes[0]:.3g} m long" if b.sizes[0] is not None else "")
    if b.kind in (OutlineKind.DISK, OutlineKind.RING, OutlineKind.SPHERE, OutlineKind.SHELL,
                  OutlineKind.CYLINDER):
        return f"a {b.kind}" + (f" of radius {size:.3g} m" if size is not None else "")
    return {OutlineKind.BLOCK: "a block", OutlineKind.BODY: "a rigid body"}.get(b.kind,
                                                                                "a particle")


def _support_words(support: SceneSupport) -> str:
    named = ", ".join(b for b in support.bodies if b != GROUND)
    if support.kind == SupportKind.PIN:
        return f"{named} pinned to the ground"
    if support.kind == SupportKind.JOINT:
        return f"a pin joining {_and(list(support.bodies))}"
    if support.kind == SupportKind.SURFACE:
        return f"{named} on a fixed surface"
    if support.kind == SupportKind.STRING:
        return f"string {support.name} pulling {_and(list(dict.fromkeys(support.bodies)))}"
    ends = _and([b for b in support.bodies])
    return f"{support.kind} {support.name} between {ends}"


def _and(names: list[str]) -> str:
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def _ident(text: str) -> str:
    """An XML id from ``text`` (letters, digits, ``-`` and ``_``; starts with a letter)."""
    cleaned = re.sub(r"[^A-Za-z0-9_-]", "-", text)
    return cleaned if cleaned[:1].isalpha() else "p-" + cleaned


def _tip(start, vector, scale) -> tuple[float, float]:
    return start[0] + scale * vector[0], start[1] + scale * vector[1]


def _unit2(v) -> tuple[float, float]:
    size = math.hypot(v[0], v[1]) or 1.0
    return v[0] / size, v[1] / size


def _dot(a, b) -> float:
    return a[0] * b[0] + a[1] * b[1]


def _cross(a, b) -> float:
    return a[0] * b[1] - a[1] * b[0]


def _round(p) -> tuple[int, int]:
    return round(p[0]), round(p[1])
