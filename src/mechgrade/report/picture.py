"""An SVG picture of a mechanism at the instant (matplotlib, no sympy): points labelled, each
point joined to the point its position is written from, frames' unit vectors at their
origins, velocity (blue) and acceleration (red) arrows, each kind scaled to the picture.

>>> from mechgrade.solve.picture import Scene, SceneFrame, ScenePoint
>>> s = Scene("p", (ScenePoint("O", (0, 0, 0), (0, 0, 0), (0, 0, 0), None),
...                 ScenePoint("A", (1, 1, 0), (-7, 7, 0), (-50, -40, 0), "O")),
...           (SceneFrame("N", (0, 0, 0), (1, 0, 0), (0, 1, 0)),))
>>> svg = picture_svg(s)
>>> svg.startswith("<?xml") and "<svg" in svg
True
"""

from __future__ import annotations

import io
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..solve.picture import Scene  # noqa: E402

VELOCITY, ACCELERATION, FRAME = "#1565c0", "#c62828", "#7b8794"


def picture_svg(scene: Scene) -> str:
    """The picture as SVG text (deterministic: no dates, fixed ids)."""
    shown = [p for p in scene.points if all(math.isfinite(c) for c in p.position[:2])]
    xs = [p.position[0] for p in shown] or [0.0]
    ys = [p.position[1] for p in shown] or [0.0]
    size = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    matplotlib.rcParams["svg.hashsalt"] = "mechgrade"
    fig, ax = plt.subplots(figsize=(6, 6))
    by_name = {p.name: p for p in shown}
    for p in shown:
        origin = by_name.get(p.described_from) if p.described_from is not None else None
        if origin is not None:
            ax.plot([origin.position[0], p.position[0]], [origin.position[1], p.position[1]],
                    color="#323f4b", linewidth=2.5, solid_capstyle="round")
    for frame in scene.frames:
        if frame.origin is None or frame.x is None or frame.y is None:
            continue
        for axis, vector in (("x", frame.x), ("y", frame.y)):
            _arrow(ax, frame.origin, vector, 0.18 * size, FRAME, 1.0)
            ax.annotate(f"{frame.name}.{axis}", _tip(frame.origin, vector, 0.2 * size),
                        color=FRAME, fontsize=8)
    for kind, colour in (("velocity", VELOCITY), ("acceleration", ACCELERATION)):
        vectors = [(p, getattr(p, kind)) for p in shown if getattr(p, kind) is not None]
        largest = max((math.hypot(v[0], v[1]) for _, v in vectors), default=0.0)
        if largest <= 0:
            continue
        for p, v in vectors:
            if math.hypot(v[0], v[1]) > 1e-12 * largest:
                _arrow(ax, p.position, v, 0.35 * size / largest, colour, 1.6)
        ax.plot([], [], color=colour, label=f"{kind} (longest {largest:.3g} SI)")
    for p in shown:
        ax.plot(p.position[0], p.position[1], "o", color="#1f2933", markersize=4)
        ax.annotate(p.name, (p.position[0], p.position[1]), textcoords="offset points",
                    xytext=(5, 5), fontsize=10, weight="bold")
    ax.set_aspect("equal")
    ax.margins(0.35)
    ax.set_title(scene.problem, fontsize=9)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(loc="lower right", fontsize=7)
    out = io.StringIO()
    fig.savefig(out, format="svg", metadata={"Date": None})
    plt.close(fig)
    return out.getvalue()


def _tip(start, vector, scale):
    return (start[0] + scale * vector[0], start[1] + scale * vector[1])


def _arrow(ax, start, vector, scale, colour, width):
    ax.annotate("", xy=_tip(start, vector, scale), xytext=(start[0], start[1]),
                arrowprops={"arrowstyle": "-|>", "color": colour, "linewidth": width})
