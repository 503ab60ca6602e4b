"""The model in the write-up order (``mechgrade solve --steps``): as text, and its equations
and vectors as presentation MathML (sympy's printer; no script, no CDN)."""

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


def derivation_mathml(problem: Problem) -> tuple[tuple[str, tuple[tuple[str, str], ...]], ...]:
    """The equations of the write-up as ``(label, MathML)``: each scalar constraint and its
    rate form, then the velocity and acceleration of every point in the inertial frame.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> math = dict(derivation_mathml(load_problem(shipped_dir("problems")
    ...                                            / "bowling_3_15_4_pendulum.yaml")))
    >>> label, mathml = math["Velocities"][0]
    >>> label, mathml.startswith('<math display="block">')
    ('N_V_A', True)
    """
    model = build(problem)
    k = derive(problem)
    N = problem.inertial_frame
    constraints = [(e.label, _math(sp.Eq(e.expr, 0))) for e in k.position]
    constraints += [(f"{e.label}, rate form", _math(sp.Eq(e.expr, 0))) for e in k.velocity]
    velocities, accelerations = [], []
    for p in problem.points:
        if p.origin is None:
            continue
        v = model.language.point_velocity(Name(p.name), N)
        a = model.language.point_acceleration(Name(p.name), N)
        velocities.append((f"{N}_V_{p.name}", _vector_math(model.plain(v))))
        accelerations.append((f"{N}_A_{p.name}", _vector_math(model.plain(a))))
    return (("Constraints", tuple(constraints)), ("Velocities", tuple(velocities)),
            ("Accelerations", tuple(accelerations)))


def _math(expr) -> str:
    return f'<math display="block">{sp.printing.mathml(expr, printer="presentation")}</math>'


def _vector_math(v: Vector) -> str:
    """A vector as a sum of (simplified coefficient) times unit vector, frame by frame."""
    parts = []
    for matrix, frame in v.args:
        for coefficient, axis in zip(matrix, "xyz"):
            coefficient = min((sp.simplify(coefficient), sp.expand(coefficient)),
                              key=sp.count_ops)
            if coefficient == 0:
                continue
            inner = sp.printing.mathml(coefficient, printer="presentation")
            unit = f"<msub><mover><mi>{frame.name.lower()}</mi><mo>^</mo></mover>" \
                   f"<mi>{axis}</mi></msub>"
            parts.append(f"<mrow><mo>(</mo>{inner}<mo>)</mo>{unit}</mrow>")
    body = "<mo>+</mo>".join(parts) if parts else "<mn>0</mn>"
    return f'<math display="block"><mrow>{body}</mrow></math>'
