"""The mechanism at the solved instant as plain numbers, for a picture: every point's position,
velocity and acceleration, each frame's origin and unit vectors (inertial components, SI).

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

from dataclasses import dataclass

import numpy as np
import sympy as sp

from ..expressions.syntax import Name
from ..mechanics.build import build
from ..spec.model import Problem
from .plan import plan
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
    """A frame's origin (``None`` without one) and its x and y unit vectors."""

    name: str
    origin: Triple | None
    x: Triple
    y: Triple


@dataclass(frozen=True)
class Scene:
    problem: str
    points: tuple[ScenePoint, ...]
    frames: tuple[SceneFrame, ...]


def scene(problem: Problem, solution: Solution) -> Scene:
    """``problem``'s points and frames at the instant ``solution`` solved (values the solver
    left free are ``nan``; a point whose motion is not known has ``None``)."""
    p = plan(problem)
    model = build(problem)
    N = model.inertial
    known = {s.name: s.si for s in solution.state}
    values = [known.get(name, np.nan) for name in p.index.names]

    def number(vector) -> Triple | None:
        matrix = model.plain(vector.to_matrix(N) if not isinstance(vector, sp.MatrixBase)
                             else vector)
        f = sp.lambdify(p.index.symbols, matrix, modules="numpy")
        with np.errstate(all="ignore"):
            out = np.asarray(f(*values), dtype=float).ravel()
        return tuple(float(c) for c in out) if np.all(np.isfinite(out)) else None

    specs = {q.name: q for q in problem.points}
    points = []
    for name, position in model.positions.items():
        spec = specs.get(name)
        points.append(ScenePoint(
            name, number(position) or (np.nan,) * 3,
            number(model.language.point_velocity(Name(name), problem.inertial_frame)),
            number(model.language.point_acceleration(Name(name), problem.inertial_frame)),
            spec.origin if spec is not None else None))
    frames = []
    for f in problem.frames:
        origin = f.origin or (problem.inertial_point if f.name == problem.inertial_frame
                              else None)
        frames.append(SceneFrame(
            f.name, number(model.positions[origin]) if origin in model.positions else None,
            number(model.frames[f.name].x), number(model.frames[f.name].y)))
    return Scene(problem.id, tuple(points), tuple(frames))
