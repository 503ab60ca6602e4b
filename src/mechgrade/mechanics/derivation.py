"""The model as text in the write-up order (``mechgrade solve --steps``)."""

from __future__ import annotations

import sympy as sp
from sympy.physics.vector import Vector

from ..expressions.syntax import Name
from ..spec.model import Problem
from .build import build
from .kinematics import derive


def kinematics_derivation(problem: Problem, dof: int | None = None
                          ) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """The model in the write-up order, as text: frames, points, coordinates, constraints,
    degrees of freedom (``dof``, as the solver found it), velocities and accelerations of every
    point in the inertial frame."""
    model = build(problem)
    k = derive(problem)
    N = problem.inertial_frame
    frames = []
    for f in problem.frames:
        if f.parent is None:
            frames.append(f"{f.name}: inertial frame; inertial point {problem.inertial_point}")
            continue
        turns = ", then ".join(f"{r.angle.text} about {('the new ' if i else f.parent + '.')}"
                               f"{r.axis}" for i, r in enumerate(f.rotations))
        origin = f"; origin {f.origin}" if f.origin else ""
        frames.append(f"{f.name}: from {f.parent} by {turns}{origin}")
    points = [f"P_{p.origin}{p.name} = {p.position.text}" for p in problem.points if p.origin]
    coordinates = [f"{c.name} [{c.unit or '1'}]" for c in problem.coordinates]
    parameters = [f"{p.name} [{p.unit or '1'}]" for p in problem.parameters]
    constraints = [f"{c.name} ({c.level}): {c.lhs.text} = {c.rhs.text}"
                   for c in problem.constraints]
    constraints += [f"  {e.label}: {sp.sstr(e.expr)} = 0" for e in k.position]
    constraints += [f"  {e.label}, rate form: {sp.sstr(e.expr)} = 0" for e in k.velocity]
    independent = len(k.coordinates) - dof if dof is not None else k.constraint_count
    dof_lines = [f"{len(k.coordinates)} coordinates - {independent} independent scalar "
                 f"constraints = {len(k.coordinates) - independent}"]
    if independent != k.constraint_count:
        dof_lines.append(f"({k.constraint_count} scalar constraint equations, "
                         f"{k.constraint_count - independent} of them redundant)")
    velocities, accelerations = [], []
    for p in problem.points:
        if p.origin is None:
            continue
        v = model.language.point_velocity(Name(p.name), N)
        a = model.language.point_acceleration(Name(p.name), N)
        velocities.append(f"{N}_V_{p.name} = {_vector_text(model.plain(v))}")
        accelerations.append(f"{N}_A_{p.name} = {_vector_text(model.plain(a))}")
    defined = tuple(f"{d.name} = {d.expr.text} = "
                    f"{_vector_text(model.plain(model.language.value(d.expr.node)))}"
                    for d in problem.definitions)
    definitions = (("Definitions", defined),) if defined else ()
    return (("Frames", tuple(frames)), ("Points", tuple(points)), *definitions,
            ("Coordinates", tuple(coordinates)), ("Parameters", tuple(parameters)),
            ("Constraints", tuple(constraints)), ("Degrees of freedom", tuple(dof_lines)),
            ("Velocities", tuple(velocities)), ("Accelerations", tuple(accelerations)))


def _vector_text(v: Vector) -> str:
    text = str(v)
    return text if text != "0" else "0"
