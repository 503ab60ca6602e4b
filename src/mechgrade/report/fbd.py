"""A body's free-body diagram as a small inline SVG, drawn from the plain data of
:class:`mechgrade.solve.fbd.FreeBodyDiagram` (no sympy here): the body's outline (a rod its
full length, a disk, a block, a particle), every load a labelled arrow at its point (the
weight at the centre, a normal force pushing on the body across its surface, friction along
it, a tension pulling along its string, an unknown reaction as its components, a couple as an
arc), unknowns dashed and marked "?". Arrows are not to scale: their directions are the
loads' at the instant, their lengths all the same, so none hides another.

>>> from mechgrade.solve.fbd import DiagramLoad, FreeBodyDiagram, Outline
>>> from mechgrade.spec.dynamics import LoadKind, OutlineKind
>>> weight = DiagramLoad("gravity", LoadKind.WEIGHT, "rod", "G", (0.0, -19.6, 0.0), "N",
...                      False, (), ((0.0, -1.0, 0.0),), ("-g*N.y",), "g*m", 19.6, None)
>>> pin = DiagramLoad("R_O", LoadKind.PIN, "rod", "O", (3.0, 30.0, 0.0), "N", True,
...                   ("R_O_1", "R_O_2"), ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
...                   ("N.x", "N.y"), "", None, None)
>>> rod = Outline(OutlineKind.ROD, "G", (1.2,), "y",
...               ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)))
>>> d = FreeBodyDiagram("rod", "B", "G", (("G", (0.0, -0.6, 0.0)), ("O", (0.0, 0.0, 0.0))),
...                     (weight, pin), (0.0, -1.0, 0.0), "N", (rod,))
>>> svg = fbd_svg(d, "p-rod")
>>> svg.count('class="load '), svg.count("<line class=\\"arrow"), svg.count('class="load u"')
(2, 3, 1)
>>> print(fbd_description(d))
Body rod, a rod 1.2 m long, with 2 loads: the weight W = 19.6 N at G, downward; the pin reaction R O at O, unknown (drawn dashed, marked ?), as its components along n-hat x and n-hat y.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from html import escape
from typing import TYPE_CHECKING

from ..solve.layout import Point2, apart, collides, outline_extent
from ..spec.dynamics import LoadKind, OutlineKind

if TYPE_CHECKING:  # the diagrams come ready-made: drawing them needs no solver
    from ..solve.fbd import DiagramLoad, FreeBodyDiagram

BODY_SPAN = 120.0
"""How far the body's outline reaches across the diagram (px)."""
ARROW = 58.0
"""Every force arrow's length (px): a free-body diagram shows directions, not sizes."""
PARTICLE = 13.0
"""A particle's radius (px)."""
BLOCK = 20.0
"""Half the side of a particle resting on a surface, drawn as a block (px)."""
KNOWN, UNKNOWN, OUTLINE = "#a61b1b", "#1849a9", "#3e4c59"
"""Colours (WCAG AA on white) of a known load, an unknown one and the body: the arrowheads'
here, the lines' and labels' in the page's style sheet (``.fbd`` in worked.css.j2)."""
PUSHES = (LoadKind.NORMAL, LoadKind.CONTACT)
"""Loads drawn pushing on the body (the arrow's head at the point, its tail outside)."""
_KIND_WORDS = {LoadKind.WEIGHT: "the weight", LoadKind.NORMAL: "the normal force",
               LoadKind.STATIC_FRICTION: "the static friction force",
               LoadKind.KINETIC_FRICTION: "the kinetic friction force",
               LoadKind.TENSION: "the tension", LoadKind.SPRING: "the spring force",
               LoadKind.DAMPER: "the damper force", LoadKind.PIN: "the pin reaction",
               LoadKind.CONTACT: "the contact force", LoadKind.APPLIED_FORCE: "the force",
               LoadKind.APPLIED_COUPLE: "the couple", LoadKind.IMPULSE: "the impulse",
               LoadKind.REACTION: "the reaction"}
_GREEK = {"alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "theta": "θ", "mu": "μ",
          "tau": "τ", "phi": "φ", "omega": "ω", "lambda": "λ", "sigma": "σ"}


def _n(value: float) -> str:
    """A page coordinate in whole pixels (finer says nothing on a diagram this size), never
    ``-0``.

    >>> _n(-0.2), _n(12.6)
    ('0', '13')
    """
    text = f"{value:.0f}"
    return "0" if text == "-0" else text


def as_shown(diagram: FreeBodyDiagram) -> FreeBodyDiagram:
    """``diagram`` with its loads' values in the units the problem writes (its
    ``shown_units``: lbf on a problem in feet); directions are unchanged. Idempotent."""
    shown = {unit: (to, factor) for unit, to, factor in diagram.shown_units if to != unit}
    if not shown:
        return diagram
    loads = []
    for load in diagram.loads:
        if load.unit not in shown:
            loads.append(load)
            continue
        to, factor = shown[load.unit]
        loads.append(replace(
            load, unit=to,
            vector=None if load.vector is None else (load.vector[0] / factor,
                                                     load.vector[1] / factor,
                                                     load.vector[2] / factor),
            magnitude_value=None if load.magnitude_value is None
            else load.magnitude_value / factor))
    return replace(diagram, loads=tuple(loads), shown_units=())


def fbd_svg(diagram: FreeBodyDiagram, ident: str) -> str:
    """``diagram`` as a self-contained SVG (no script, no external reference), its element ids
    prefixed with ``ident``; its title and description say it in words."""
    diagram = as_shown(diagram)
    ident = "".join(c if c.isalnum() or c in "-_" else "-" for c in ident)
    positions = {name: p for name, p in diagram.points if p is not None}
    to_screen = _projection(diagram, positions)
    centre = positions.get(diagram.centre)
    shapes, radius, surface = _outline(diagram, positions, to_screen)
    extents = [to_screen(e) for o in diagram.outline if o.at in positions
               for e in _extent(o, positions[o.at])]
    # the page styles it (worked.css.j2: the font, the colours of the body, a known and an
    # unknown load): each diagram would say them again; its title and desc are its name and
    # description (role="img")
    out = ['<svg viewBox="{view}" width="{width}" height="{height}" role="img" class="fbd">',
           f'<title>Free-body diagram of {escape(diagram.body)}</title>',
           f'<desc>{escape(fbd_description(diagram))}</desc>', "<defs>"]
    for name, colour in (("k", KNOWN), ("u", UNKNOWN)):
        out.append(f'<marker id="{ident}-{name}" viewBox="0 0 10 10" refX="9" refY="5" '
                   'markerWidth="6" markerHeight="6" orient="auto">'
                   f'<path d="M0,0 10,5 0,10z" fill="{colour}"/></marker>')
    out += ["</defs>", *shapes]
    arrows = []  # (load, tail, head, label text parts, unknown)
    couples = []
    for load in diagram.loads:
        at = positions.get(load.point) if load.point is not None else centre
        if at is None:
            at = centre if centre is not None else (0.0, 0.0, 0.0)
        if load.point is None:
            couples.append((load, to_screen(at)))
            continue
        arrows.append((load, _arrows(load, to_screen(at), radius, surface)))
    placed: list[tuple[Point2, Point2]] = []
    labels: list[tuple[float, float, float, float]] = []
    every = [(t, h) for _, parts in arrows for t, h, _ in parts if t != h]
    for load, parts in arrows:
        colour, marker = (UNKNOWN, "u") if load.unknown else (KNOWN, "k")
        group = [f'<g class="load {marker}">']
        for tail, head, label in parts:
            if tail == head:  # along the page's normal: a dot (out of it) or a cross (into it)
                outward = label[3] > 0
                sign = "out-of-page" if outward else "into-page"
                mark = (f'<circle cx="{tail[0]:.0f}" cy="{tail[1]:.0f}" r="2" fill="{colour}"/>'
                        if outward else
                        f'<path d="M{tail[0] - 5:.0f},{tail[1] - 5:.0f} l10,10 m0,-10 l-10,10" '
                        f'stroke="{colour}" stroke-width="1.6"/>')
                group += [f'<g class="arrow {sign}"><circle cx="{tail[0]:.0f}" '
                          f'cy="{tail[1]:.0f}" r="8" fill="none" stroke="{colour}" '
                          f'stroke-width="1.6"/>{mark}</g>',
                          _label((tail[0] + 12, tail[1] - 12), tail, label[:3], labels,
                                 avoid=every)]
                continue
            tail, head = apart(tail, head, placed)
            placed.append((tail, head))
            group.append(f'<line class="arrow" x1="{_n(tail[0])}" y1="{_n(tail[1])}" '
                         f'x2="{_n(head[0])}" y2="{_n(head[1])}" '
                         f'marker-end="url(#{ident}-{marker})"/>')
            far = head if load.kind not in PUSHES else tail
            near = tail if load.kind not in PUSHES else head
            group.append(_label(far, near, label[:3], labels, avoid=every))
        out += group + ["</g>"]
    for load, at in couples:
        marker = "u" if load.unknown else "k"
        z = load.vector[2] if load.vector is not None else 1.0
        sweep = 0 if z >= 0 else 1  # counter-clockwise on the page (y down) for +z
        r = radius + 20
        start = (at[0] + r, at[1])
        end = (at[0], at[1] - r) if z >= 0 else (at[0], at[1] + r)
        out += [f'<g class="load {marker}">',
                f'<path class="arrow couple" d="M{_n(start[0])},{_n(start[1])} A{r:.0f},'
                f'{r:.0f} 0 1 {sweep} {_n(end[0])},{_n(end[1])}" '
                f'marker-end="url(#{ident}-{marker})"/>',
                _label((at[0] + r * 0.8, at[1] - r * 0.8), at, _text_of(load, 0), labels),
                "</g>"]
    seen = [to_screen(p) for p in positions.values()]
    for x, y in seen:
        out.append(f'<circle class="pt" cx="{_n(x)}" cy="{_n(y)}" r="2.5"/>')
    for name, p in positions.items():
        x, y = to_screen(p)
        out.append(_label((x - 1, y + 1), (x, y), (name, "", ""), labels, 12))
    # the view: everything drawn, with a margin
    xs = [c for t, h in placed for c in (t[0], h[0])] + [b[i] for b in labels for i in (0, 2)]
    ys = [c for t, h in placed for c in (t[1], h[1])] + [b[i] for b in labels for i in (1, 3)]
    for x, y in seen + extents:
        xs += [x - radius - 24, x + radius + 24]
        ys += [y - radius - 24, y + radius + 24]
    for _, at in couples:
        xs += [at[0] - radius - 26, at[0] + radius + 26]
        ys += [at[1] - radius - 26, at[1] + radius + 26]
    x0, y0 = min(xs) - 6, min(ys) - 6
    width, height = max(xs) - x0 + 6, max(ys) - y0 + 6
    box = {"x0": f"{x0:.0f}", "y0": f"{y0:.0f}", "width": f"{width:.0f}",
           "height": f"{height:.0f}"}
    out[0] = out[0].format(view=f"{x0:.0f} {y0:.0f} {width:.0f} {height:.0f}", **box)
    return "".join(out + ["</svg>"])


def fbd_description(diagram: FreeBodyDiagram) -> str:
    """The diagram in words: the body, its shape and every load, where and which way."""
    diagram = as_shown(diagram)
    shape = "; ".join(_shape_words(o) for o in diagram.outline) or "a particle"
    loads = []
    for load in diagram.loads:
        where = f" at {load.point}" if load.point else ""
        words = f"{_KIND_WORDS.get(load.kind, 'the load')} {_plain(load)}{where}"
        if load.unknown:
            words += ", unknown (drawn dashed, marked ?)"
            if len(load.components) > 1:
                words += ", as its components along " + " and ".join(
                    _spoken_direction(t) for t in load.direction_texts)
            elif load.direction_texts:
                words += f", along {_spoken_direction(load.direction_texts[0])}"
        elif load.point is None and load.vector is not None:
            words += ", counter-clockwise" if load.vector[2] >= 0 else ", clockwise"
        elif load.vector is not None:
            words += f", {_heading(load.vector, diagram.down)}"
        loads.append(words)
    count = f"{len(loads)} load" + ("" if len(loads) == 1 else "s")
    return f"Body {diagram.body}, {shape}, with {count}: " + "; ".join(loads) + "."


# ---------------------------------------------------------------------------- geometry


def _projection(diagram: FreeBodyDiagram, positions: dict):
    """Inertial (x, y) in m to the page: the outline and the load points fill
    :data:`BODY_SPAN` at the centre of the diagram, y up."""
    xy = [p[:2] for p in positions.values()]
    for o in diagram.outline:
        at = positions.get(o.at)
        if at is None:
            continue
        for end in _extent(o, at):
            xy.append(end)
    if not xy:
        xy = [(0.0, 0.0)]
    xs, ys = [p[0] for p in xy], [p[1] for p in xy]
    span = max(max(xs) - min(xs), max(ys) - min(ys))
    scale = BODY_SPAN / span if span > 1e-12 else 1.0
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2

    def to_screen(p) -> Point2:
        return scale * (p[0] - cx), -scale * (p[1] - cy)

    return to_screen


def _extent(o, at) -> list[Point2]:
    """The points of the page an outline reaches (m, inertial x and y)."""
    return outline_extent(o.kind, at, o.sizes, o.axis, o.axes)


def _outline(diagram: FreeBodyDiagram, positions: dict, to_screen):
    """The outline's SVG elements, the radius (px) arrows keep clear of at a particle, and the
    unit normal (page) of the surface a particle rests on (``None``: none)."""
    shapes: list[str] = []
    radius = 0.0
    surface = next((load.surface.normal for load in diagram.loads
                    if load.surface is not None and load.surface.normal is not None), None)
    page_normal = None
    if surface is not None:
        size = math.hypot(surface[0], surface[1])
        page_normal = (surface[0] / size, -surface[1] / size) if size > 1e-12 else None
    for o in diagram.outline:
        at = positions.get(o.at)
        if at is None:
            continue
        x, y = to_screen(at)
        if o.kind == OutlineKind.PARTICLE and page_normal is not None:
            radius = BLOCK
            angle = math.degrees(math.atan2(page_normal[0], -page_normal[1]))
            shapes.append(f'<rect class="body" x="{x - BLOCK:.0f}" y="{y - BLOCK:.0f}" '
                          f'width="{2 * BLOCK:g}" height="{2 * BLOCK:g}" '
                          f'transform="rotate({_n(angle)} {x:.0f} {y:.0f})"/>')
            shapes.append(_surface(x, y, page_normal))
        elif o.kind == OutlineKind.BODY:  # inertia by its entries: a body of no set shape
            radius = BLOCK
            shapes.append(f'<rect class="body" x="{x - BLOCK:.0f}" y="{y - 0.7 * BLOCK:.0f}" '
                          f'width="{2 * BLOCK:g}" height="{1.4 * BLOCK:g}" '
                          f'rx="{0.5 * BLOCK:g}"/>')
        elif o.kind == OutlineKind.PARTICLE:
            radius = PARTICLE
            shapes.append(f'<circle class="body" cx="{_n(x)}" cy="{_n(y)}" r="{PARTICLE:g}"/>')
        elif o.kind == OutlineKind.ROD:
            ends = [to_screen(e) for e in _extent(o, at)]
            if len(ends) == 2:
                shapes.append(f'<line class="body rod" x1="{_n(ends[0][0])}" '
                              f'y1="{_n(ends[0][1])}" x2="{_n(ends[1][0])}" '
                              f'y2="{_n(ends[1][1])}"/>')
        elif o.kind == OutlineKind.BLOCK:
            corners = [to_screen(c) for c in _extent(o, at)]
            if len(corners) == 4:
                shapes.append('<polygon class="body" points="'
                              + " ".join(f"{_n(cx)},{_n(cy)}" for cx, cy in corners)
                              + '"/>')
        else:
            lo, hi = (to_screen(e) for e in _extent(o, at))
            r = max(abs(hi[0] - lo[0]) / 2, 4.0)
            hollow = " hollow" if o.kind in (OutlineKind.RING, OutlineKind.SHELL) else ""
            shapes.append(f'<circle class="body{hollow}" cx="{_n(x)}" cy="{_n(y)}" '
                          f'r="{r:.0f}"/>')
    return shapes, radius, page_normal


def _surface(x: float, y: float, normal: Point2) -> str:
    """The surface under a block at ``(x, y)``: a line across ``normal`` hatched on its far
    side (the free-body diagram cuts the body free of it: drawn light)."""
    tx, ty = -normal[1], normal[0]
    bx, by = x - normal[0] * BLOCK, y - normal[1] * BLOCK
    reach = 2.6 * BLOCK
    path = [f"M{bx - reach * tx:.0f},{by - reach * ty:.0f} L{bx + reach * tx:.0f},"
            f"{by + reach * ty:.0f}"]
    for k in range(-5, 6):
        px, py = bx + k * reach / 5.5 * tx, by + k * reach / 5.5 * ty
        path.append(f"M{px:.0f},{py:.0f} l{-7 * normal[0] - 5 * tx:.0f},"
                    f"{-7 * normal[1] - 5 * ty:.0f}")
    return f'<path class="surface" d="{" ".join(path)}"/>'


def _arrows(load: DiagramLoad, at: Point2, radius: float, surface):
    """The arrows of ``load`` at the page point ``at``: ``(tail, head, label)`` each, one per
    component of an unknown load with several directions, else one; one along the page's
    normal has its tail at its head and the sign of its z component as a fourth label part."""
    if load.unknown and len(load.directions) > 1:
        headings = [(d, i) for i, d in enumerate(load.directions) if d is not None]
    else:
        vector = load.vector
        if vector is None or math.hypot(vector[0], vector[1]) < 1e-9 or load.unknown:
            vector = load.directions[0] if load.directions and load.directions[0] else vector
        headings = [(vector, 0)] if vector is not None else [((0.0, -1.0, 0.0), 0)]
    out = []
    for d, i in headings:
        size = math.hypot(d[0], d[1])
        if size < 1e-9 * max(1.0, abs(d[2])):
            out.append((at, at, (*_text_of(load, i), d[2])))
            continue
        u = (d[0] / size, -d[1] / size)
        if load.kind in (LoadKind.KINETIC_FRICTION, LoadKind.STATIC_FRICTION) \
                and surface is not None:
            tail = (at[0] - surface[0] * radius, at[1] - surface[1] * radius)
            head = (tail[0] + ARROW * u[0], tail[1] + ARROW * u[1])
        elif load.kind in PUSHES:
            head = (at[0] - radius * u[0], at[1] - radius * u[1])
            tail = (head[0] - ARROW * u[0], head[1] - ARROW * u[1])
        else:
            clear = radius if load.kind != LoadKind.WEIGHT else 0.0
            tail = (at[0] + clear * u[0], at[1] + clear * u[1])
            head = (tail[0] + ARROW * u[0], tail[1] + ARROW * u[1])
        out.append((tail, head, (*_text_of(load, i), 0.0)))
    return out


def _label(far: Point2, near: Point2, parts: tuple[str, str, str], taken: list,
           size_px: int = 14, avoid: tuple | list = ()) -> str:
    """A label past the ``far`` end of an arrow, moved along it until it overlaps no other."""
    dx, dy = far[0] - near[0], far[1] - near[1]
    size = math.hypot(dx, dy) or 1.0
    ux, uy = dx / size, dy / size
    width = size_px * 0.55 * sum(len(p) for p in parts) + 4
    for step in range(10):
        x, y = far[0] + ux * (10 + 9 * step), far[1] + uy * (10 + 9 * step) + 5
        anchor = "start" if ux > 0.35 else "end" if ux < -0.35 else "middle"
        left = x if anchor == "start" else x - width if anchor == "end" else x - width / 2
        top = y - 13 + (6 if uy > 0.35 else 0)
        box = (left, top, left + width, top + size_px + 3)
        if not collides(box, taken, avoid):
            break
    taken.append(box)
    base, sub, rest = parts
    text = escape(base) + (f'<tspan font-size="11" dy="4">{escape(sub)}</tspan>'
                           f'<tspan dy="-4">{escape(rest)}</tspan>' if sub else escape(rest))
    # a load's label takes its group's colour; a point's is set smaller (class pt)
    point = "" if size_px == 14 else ' class="pt"'
    return f'<text{point} x="{_n(box[0])}" y="{_n(box[1] + size_px - 1)}">{text}</text>'


# ---------------------------------------------------------------------------- words


def _symbol(name: str) -> tuple[str, str]:
    """A load's name as a textbook letter and subscript: ``N_P`` -> (N, P), ``mu_k`` -> (μ, k),
    ``s1`` -> (s, 1).

    >>> _symbol("N_P"), _symbol("mu_k"), _symbol("s1"), _symbol("k12_a"), _symbol("rope")
    (('N', 'P'), ('μ', 'k'), ('s', '1'), ('k', '12,a'), ('rope', ''))
    """
    base, _, sub = name.partition("_")
    letters = base.rstrip("0123456789")
    if letters != base and (len(letters) == 1 or letters in _GREEK):
        sub = base[len(letters):] + ("_" + sub if sub else "")
        base = letters
    return _GREEK.get(base, base), sub.replace("_", ",")


def _text_of(load: DiagramLoad, i: int) -> tuple[str, str, str]:
    """The label of ``load``'s ``i``-th arrow: (letter, subscript, the rest)."""
    if load.kind == LoadKind.WEIGHT:
        base, sub = "W", ""
    else:
        base, sub = _symbol(load.name)
    if load.unknown and len(load.components) > 1:
        axis = load.direction_texts[i].rpartition(".")[2] if i < len(load.direction_texts) \
            else str(i + 1)
        sub = f"{sub},{axis}" if sub else axis
    if load.unknown:
        return base, sub, " ?"
    value = load.magnitude_value
    if value is None and load.vector is not None:
        value = math.sqrt(sum(c * c for c in load.vector))
    return base, sub, f" = {abs(value):.3g} {load.unit.replace('*', ' ')}" if value is not None \
        else ""


def _plain(load: DiagramLoad) -> str:
    """The load's symbol as said: its subscript after a space (``R O``, not the file's
    ``R_O``), with its value when known."""
    base, sub, rest = _text_of(load, 0)
    if load.unknown and len(load.components) > 1:
        base, sub = _symbol(load.name) if load.kind != LoadKind.WEIGHT else ("W", "")
        rest = ""
    name = f"{base} {sub}" if sub else base
    return name + (rest if rest != " ?" else "")


_UNIT_VECTOR = re.compile(r"(-?)([A-Za-z]\w*)\.([xyz])")


def _spoken_direction(text: str) -> str:
    """A direction as the file wrote it, in words: a frame's unit vector as it is read out
    (as :func:`~mechgrade.expressions.notation.textbook` says it).

    >>> _spoken_direction("N.x"), _spoken_direction("-A.y"), _spoken_direction("B.x + B.y")
    ('n-hat x', 'minus a-hat y', 'b-hat x + b-hat y')
    """
    return _UNIT_VECTOR.sub(lambda m: ("minus " if m.group(1) else "")
                            + f"{m.group(2).lower()}-hat {m.group(3)}", text)


def _shape_words(o) -> str:
    size = o.sizes[0] if o.sizes else None
    if o.kind == OutlineKind.ROD:
        return "a rod" + (f" {size:.3g} m long" if size is not None else "")
    if o.kind in (OutlineKind.DISK, OutlineKind.RING, OutlineKind.SPHERE, OutlineKind.SHELL):
        radius = o.sizes[-1] if o.sizes else None
        return f"a {o.kind}" + (f" of radius {radius:.3g} m" if radius is not None else "")
    if o.kind == OutlineKind.CYLINDER:
        return "a cylinder"
    if o.kind == OutlineKind.BLOCK:
        return "a block"
    if o.kind == OutlineKind.BODY:
        return "a rigid body"
    return "a particle"


def _heading(vector, down) -> str:
    """Which way a force points, in words relative to the problem's down."""
    size = math.sqrt(sum(c * c for c in vector))
    if size < 1e-12:
        return "zero at this instant"
    u = [c / size for c in vector]
    if down is not None:
        along = sum(a * b for a, b in zip(u, down))
        if along > 0.999:
            return "downward"
        if along < -0.999:
            return "upward"
    angle = math.degrees(math.atan2(u[1], u[0]))
    return f"at {angle:.0f}° from the x axis"
