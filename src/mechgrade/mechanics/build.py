"""Build a problem's ``sympy.physics`` model: frames oriented with ``orient_axis`` (a body-fixed
sequence is a chain of simple rotations), and every point's position from the inertial point.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> model = build(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"))
>>> sorted(model.frames), str(model.positions["A"])
(['A', 'N'], 'L*A.x')
"""

from __future__ import annotations

from dataclasses import dataclass

from sympy.physics.vector import ReferenceFrame, Vector

from ..spec.model import Problem
from .interpret import Interpreter
from .symbols import Symbols


@dataclass(frozen=True)
class Model:
    """The ``sympy.physics`` objects of one problem and the interpreter reading its language."""

    problem: Problem
    symbols: Symbols
    frames: dict[str, ReferenceFrame]
    positions: dict[str, Vector]
    language: Interpreter

    @property
    def inertial(self) -> ReferenceFrame:
        return self.frames[self.problem.inertial_frame]

    def plain(self, expr):
        return self.symbols.plain(expr)

    def components(self, value) -> list:
        """Scalar equations of a (scalar or vector) difference, vectors in the inertial frame."""
        if isinstance(value, Vector):
            return list(value.to_matrix(self.inertial))
        return [value]


def build(problem: Problem) -> Model:
    """Frames, then points (their descriptions may use any frame), of ``problem``."""
    symbols = Symbols(problem)
    frames: dict[str, ReferenceFrame] = {}
    positions: dict[str, Vector] = {}
    language = Interpreter(problem, symbols, frames, positions)
    spec_frames = {f.name: f for f in problem.frames}
    spec_points = {p.name: p for p in problem.points}

    def frame(name: str) -> ReferenceFrame:
        if name in frames:
            return frames[name]
        spec = spec_frames[name]
        made = ReferenceFrame(name)
        if spec.parent is not None:
            current = frame(spec.parent)
            # A body-fixed sequence is a chain of simple rotations, each about an axis of the
            # frame the previous one produced.
            for i, rotation in enumerate(spec.rotations):
                last = i == len(spec.rotations) - 1
                target = made if last else ReferenceFrame(f"{name}_{i + 1}")
                target.orient_axis(current, getattr(current, rotation.axis),
                                   language.scalar(rotation.angle))
                current = target
        frames[name] = made
        return made

    def position(name: str) -> Vector:
        if name in positions:
            return positions[name]
        spec = spec_points[name]
        origin, located = spec.origin, spec.position
        # both, or neither: only the inertial point has no location description
        vector = Vector(0) if origin is None or located is None else \
            position(origin) + language.vector(located)
        positions[name] = vector
        return vector

    for f in problem.frames:
        frame(f.name)
    for p in problem.points:
        position(p.name)
    return Model(problem, symbols, frames, positions, language)
