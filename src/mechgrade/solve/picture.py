"""The mechanism at the solved instant as plain numbers, and its picture: every point's
position, velocity and acceleration, each frame's origin and unit vectors (inertial components,
SI), drawn as a small inline SVG (``mechgrade solve --plot``, feedback pages, handouts).

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
from functools import lru_cache
from html import escape

import numpy as np
import sympy as sp

from ..expressions.syntax import Name
from ..mechanics.build import build
from ..spec.model import Problem
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
class Scene:
    problem: str
    points: tuple[ScenePoint, ...]
    frames: tuple[SceneFrame, ...]
    title: str = ""  # the problem's title, which the picture's text alternative names


def scene(problem: Problem, solution: Solution) -> Scene:
    """``problem``'s points and frames at the instant ``solution`` solved (values the solver
    left free are ``nan``; a point whose motion is not known has ``None``). The model is
    turned into functions once per problem; each solution (a student's variant) only
    evaluates them."""
    names, points, frames = _drawing(problem)
    known = {s.name: s.si for s in solution.state}
    values = [known.get(name, np.nan) for name in names]

    def number(f) -> Triple | None:
        with np.errstate(all="ignore"):
            out = np.asarray(f(*values), dtype=float).ravel()
        if not np.all(np.isfinite(out)):
            return None
        x, y, z = (float(c) for c in out)  # a vector's components
        return x, y, z

    return Scene(problem.id, tuple(
        ScenePoint(name, number(position) or (np.nan,) * 3, number(velocity),
                   number(acceleration), origin)
        for name, position, velocity, acceleration, origin in points), tuple(
        SceneFrame(name, number(origin) if origin is not None else None, number(x), number(y))
        for name, origin, x, y in frames), problem.title)


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
        return sp.lambdify(p.index.symbols, matrix, modules="numpy")

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
    return tuple(p.index.names), tuple(points), tuple(frames)


# ---------------------------------------------------------------------------- drawing

VELOCITY, ACCELERATION, FRAME, BODY = "#1565c0", "#c62828", "#616e7c", "#323f4b"  # AA on white
WIDTH, HEIGHT, MARGIN = 480.0, 360.0, 40.0
HALO = 'paint-order="stroke" stroke="#fff" stroke-width="3"'  # labels stay readable on lines


def picture_svg(s: Scene, ident: str | None = None) -> str:
    """The picture as a small, self-contained SVG (text, no script, no external reference;
    the same bytes each time). ``ident`` prefixes its element ids (default: the problem id),
    so several pictures can sit inline in one page.

    >>> s = Scene("p", (ScenePoint("O", (0, 0, 0), (0, 0, 0), (0, 0, 0), None),
    ...                 ScenePoint("A", (1, 1, 0), (-7, 7, 0), (-50, -40, 0), "O")),
    ...           (SceneFrame("N", (0, 0, 0), (1, 0, 0), (0, 1, 0)),))
    >>> svg = picture_svg(s)
    >>> svg.startswith("<svg") and "velocity (longest 9.9 m/s)" in svg and "N.x" in svg
    True
    """
    ident = _ident(ident or s.problem)
    motion = (", velocities and accelerations"
              if any(p.velocity or p.acceleration for p in s.points) else "")
    shown = [p for p in s.points if all(math.isfinite(c) for c in p.position[:2])]
    xs = [p.position[0] for p in shown] or [0.0]
    ys = [p.position[1] for p in shown] or [0.0]
    size = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    # motion arrows reach 0.35 size beyond the points, frame labels 0.25: the view covers them
    reach = (0.4 if motion else 0.3) * size
    x0, x1 = min(xs) - reach, max(xs) + reach
    y0, y1 = min(ys) - reach, max(ys) + reach
    scale = min((WIDTH - 2 * MARGIN) / (x1 - x0), (HEIGHT - 2 * MARGIN) / (y1 - y0))
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2

    def at(x: float, y: float) -> tuple[float, float]:
        return WIDTH / 2 + scale * (x - cx), HEIGHT / 2 - scale * (y - cy)  # y up

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {WIDTH:g} {HEIGHT:g}" '
           f'width="{WIDTH:g}" height="{HEIGHT:g}" role="img" '
           f'aria-labelledby="{ident}-title" aria-describedby="{ident}-desc" '
           f'class="mechanism" font-family="system-ui, sans-serif" font-size="13">',
           f'<title id="{ident}-title">{escape(s.title or s.problem)}: the mechanism at the '
           f'instant, its points and frames{motion}</title>', "<defs>"]
    for name, colour in (("v", VELOCITY), ("a", ACCELERATION), ("f", FRAME)):
        out.append(f'<marker id="{ident}-{name}" viewBox="0 0 10 10" refX="9" refY="5" '
                   f'markerWidth="7" markerHeight="7" orient="auto-start-reverse">'
                   f'<path d="M0,0 L10,5 L0,10 z" fill="{colour}"/></marker>')
    out += ["</defs>", f'<rect width="{WIDTH:g}" height="{HEIGHT:g}" fill="#fff"/>']
    by_name = {p.name: p for p in shown}
    for p in shown:
        origin = by_name.get(p.described_from) if p.described_from is not None else None
        if origin is not None:
            out.append(_line(at(*origin.position[:2]), at(*p.position[:2]), BODY, 4,
                             'stroke-linecap="round"'))
    # frames sharing an origin and a direction share one arrow and one label ("N.x = B.x")
    axes: dict[tuple, tuple[tuple[float, float], list[str]]] = {}
    for frame in s.frames:
        if frame.origin is None or frame.x is None or frame.y is None:
            continue
        for axis, vector in (("x", frame.x), ("y", frame.y)):
            start = at(*frame.origin[:2])
            end = at(*_tip(frame.origin, vector, 0.18 * size))
            key = (start, round(end[0]), round(end[1]))
            if key not in axes:
                out.append(_line(start, end, FRAME, 1.5, f'marker-end="url(#{ident}-f)"'))
                axes[key] = (at(*_tip(frame.origin, vector, 0.25 * size)), [])
            axes[key][1].append(f"{frame.name}.{axis}")
    for label, names in axes.values():
        out.append(_text(label, " = ".join(names), FRAME, 'font-size="11" '
                         'text-anchor="middle" dominant-baseline="middle" ' + HALO))
    legend = []
    for kind, colour, mark, unit in (("velocity", VELOCITY, "v", "m/s"),
                                     ("acceleration", ACCELERATION, "a", "m/s²")):
        vectors = [(p, getattr(p, kind)) for p in shown if getattr(p, kind) is not None]
        largest = max((math.hypot(v[0], v[1]) for _, v in vectors), default=0.0)
        if largest <= 0:
            continue
        for p, v in vectors:
            if math.hypot(v[0], v[1]) > 1e-3 * largest:
                out.append(_line(at(*p.position[:2]),
                                 at(*_tip(p.position, v, 0.35 * size / largest)), colour, 2.2,
                                 f'marker-end="url(#{ident}-{mark})"'))
        legend.append((colour, f"{kind} (longest {largest:.2g} {unit})"))
    out.insert(2, f'<desc id="{ident}-desc">{escape(described(s, legend))}</desc>')
    places: dict[tuple[int, int], list[str]] = {}  # coincident points share one label
    for p in shown:
        x, y = at(*p.position[:2])
        places.setdefault((round(x), round(y)), []).append(p.name)
    for (x, y), names in places.items():
        out.append(f'<circle cx="{x}" cy="{y}" r="4" fill="#1f2933"/>')
        out.append(_text((x + 7, y - 7), ", ".join(names), "#1f2933",
                         'font-weight="bold" font-size="15" ' + HALO))
    for i, (colour, text) in enumerate(legend):
        y = HEIGHT - 14 - 18 * (len(legend) - 1 - i)
        out.append(_line((12, y - 4), (36, y - 4), colour, 2.2))
        out.append(_text((42, y), text, colour, 'font-size="12"'))
    out.append("</svg>")
    return "\n".join(out) + "\n"


def described(s: Scene, legend=()) -> str:
    """The picture in words, for whoever cannot see it: the points, what joins them, the
    frames' unit vectors and the arrows with their scales (``legend``: colour and text).

    >>> print(described(Scene("p", (ScenePoint("O", (0, 0, 0), None, None, None),
    ...     ScenePoint("A", (1, 1, 0), None, None, "O")), (SceneFrame("N", (0, 0, 0),
    ...     (1, 0, 0), (0, 1, 0)),)), [("#c62828", "acceleration (longest 64 m/s²)")]))
    Points O and A; a line joins A to O. Unit vectors x and y of frame N. Arrows: acceleration (longest 64 m/s²), in red.
    """
    shown = [p.name for p in s.points if all(math.isfinite(c) for c in p.position[:2])]
    parts = [f"{'Point' if len(shown) == 1 else 'Points'} {_and(shown)}"]
    joined = [f"{p.name} to {p.described_from}" for p in s.points
              if p.described_from in shown and p.name in shown]
    if joined:
        parts[0] += f"; a line joins {_and(joined)}"
    frames = [f.name for f in s.frames if None not in (f.origin, f.x, f.y)]
    if frames:
        parts.append(f"Unit vectors x and y of {'frame' if len(frames) == 1 else 'frames'} "
                     f"{_and(frames)}")
    colours = {VELOCITY: "blue", ACCELERATION: "red"}
    if legend:
        parts.append("Arrows: " + "; ".join(f"{text}, in {colours.get(colour, colour)}"
                                            for colour, text in legend))
    return ". ".join(parts) + "."


def _and(names: list[str]) -> str:
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def _ident(text: str) -> str:
    """An XML id from ``text`` (letters, digits, ``-`` and ``_``; starts with a letter)."""
    cleaned = re.sub(r"[^A-Za-z0-9_-]", "-", text)
    return cleaned if cleaned[:1].isalpha() else "p-" + cleaned


def _tip(start, vector, scale) -> tuple[float, float]:
    return start[0] + scale * vector[0], start[1] + scale * vector[1]


def _line(a, b, colour: str, width: float, extra: str = "") -> str:
    return (f'<line x1="{a[0]:.1f}" y1="{a[1]:.1f}" x2="{b[0]:.1f}" y2="{b[1]:.1f}" '
            f'stroke="{colour}" stroke-width="{width:g}" {extra}/>').replace(" />", "/>")


def _text(at_, text: str, colour: str, extra: str = "") -> str:
    return f'<text x="{at_[0]:.1f}" y="{at_[1]:.1f}" fill="{colour}" {extra}>{escape(text)}</text>'
