"""The kinetics steps of the worked solution in textbook order and in MathML: the bodies and
their inertia matrices, the free-body loads as vectors, the work-energy balance
T1 + V1 + U12 = T2 + V2 that gives the rates (when the problem reaches its instant that way),
the momentum balances (with the balance along each contact's normal and, for a body on a
fixed pivot, the moment balance about the pivot, free of its reaction), the impact's contact
conditions, and the unknowns solved. Rates are dotted (θ̇, θ̈), a reaction's components
named by their axes (R_O,x), never as code; each row names the generated mistakes that happen
in it, so a feedback page can point a diagnosis at it.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("examples") / "hw3_dynamics" / "pendulum_release.yaml")
>>> [s.anchor for s in kinetics_steps(problem)]  # doctest: +NORMALIZE_WHITESPACE
['kinetics-bodies', 'kinetics-free-body-loads', 'kinetics-work-energy',
 'kinetics-momentum-balances', 'kinetics-solution']
>>> [r.text for r in kinetics_steps(problem)[2].rows][:1]
['T1 + V1 + U12 = T2 + V2']
"""

from __future__ import annotations

import re
from functools import lru_cache
from html import escape

import sympy as sp
from sympy.physics.vector import Dyadic, Vector

from ..spec.dynamics import (Impulse, LoadKind, Reaction, StaticFriction,
                             WorkEnergy, dynamics_of)
from ..expressions.syntax import Name
from ..spec.model import Problem
from .bodies import parallel_axis
from .derivation import Row, WorkedStep, _Display, compact_math
from .dynamics import _inertias, derive_kinetics, free_body_loads, how_the_instant
from .symbols import identically_zero

LOAD_CODES = {LoadKind.WEIGHT: ("weight_omitted", "mass_for_weight", "weight_for_mass",
                               "load_at_other_point"),
              LoadKind.KINETIC_FRICTION: ("friction_reversed", "surface_taken_fixed"),
              LoadKind.STATIC_FRICTION: ("friction_reversed", "contact_taken_smooth"),
              LoadKind.SPRING: ("spring_free_length_omitted", "springs_in_series",
                                "spring_omitted", "load_at_other_point"),
              LoadKind.DAMPER: ("damping_omitted",),
              LoadKind.APPLIED_FORCE: ("force_omitted",)}
"""The mistakes that happen in a load's own row of the free-body loads, by its kind."""
MOMENT_CODES = ("central_inertia_at_pivot", "inertia_omitted", "other_shape_inertia",
                "weight_transfer_ignored", "impulse_moment_omitted")
"""The mistakes that happen in a rigid body's moment balance."""
FORCE_CODES = ("tension_as_weight", "reaction_as_weight", "reaction_as_static")
"""The mistakes that happen in the force balance along a single-direction reaction."""
NORMAL_CODES = ("normal_from_weight",) + FORCE_CODES
"""The mistakes that happen in the balance along a contact's normal."""
ENERGY_CODES = ("rotational_ke_omitted", "body_ke_omitted")
"""The mistakes that happen in the kinetic energy of the work-energy balance."""
CONTACT_CODES = ("restitution_ignored", "restitution_component")
"""The mistakes that happen in an impact's contact condition."""


@lru_cache(maxsize=64)
def kinetics_steps(problem: Problem) -> tuple[WorkedStep, ...]:
    """The kinetics steps of ``problem`` (one with bodies and loads), after its kinematics."""
    kin = derive_kinetics(problem)
    model = kin.built[0]
    d = dynamics_of(problem)
    show = _Display(model)
    N = model.inertial
    shown = _display_names(problem, kin)
    names = {s: sp.Symbol(n, real=True) for s, n in shown.items()}

    def expr_math(expr) -> str:
        return show._inner(sp.sympify(expr).xreplace(names))

    def matrix_math(m: sp.Matrix) -> str:
        return show._vector(Vector([(m.xreplace(names), N)]))

    def text(expr) -> str:
        return _text(sp.sympify(expr).xreplace(names))

    steps = [_bodies(problem, model, expr_math),
             _loads(problem, matrix_math, text)]
    if isinstance(d.analysis, WorkEnergy):
        steps.append(_work_energy(kin, expr_math, text))
    steps.append(_balances(problem, kin, expr_math, text))
    steps.append(_solution(problem, kin, shown, expr_math))
    return tuple(steps)


def _display_names(problem: Problem, kin) -> dict:
    """Each unknown reaction symbol's textbook name: one component per axis ``R_O,x``."""
    d = dynamics_of(problem)
    out = {}
    unknown: tuple[Reaction | StaticFriction, ...] = (
        *d.reactions, *(f for f in d.friction if isinstance(f, StaticFriction)))
    by_name = {s.name: s for s in kin.reactions}
    for r in unknown:
        if len(r.directions) == 1:
            continue
        for i, e in enumerate(r.directions):
            axis = e.text.rpartition(".")[2] if re.fullmatch(r"-?\w+\.[xyz]", e.text) \
                else str(i + 1)
            symbol = by_name.get(f"{r.name}_{i + 1}")
            if symbol is not None:
                out[symbol] = f"{r.name},{axis}"
    return out


def _text(expr) -> str:
    """An expression as the rows' plain text (a row's spoken label, the Markdown page): a
    vector ``(x, y, z)``, a matrix ``[a, b; c, d]``."""
    if isinstance(expr, sp.MatrixBase):
        if 1 in expr.shape:
            return "(" + ", ".join(sp.sstr(e) for e in expr) + ")"
        return "[" + "; ".join(", ".join(sp.sstr(e) for e in expr.row(i))
                               for i in range(expr.rows)) + "]"
    return sp.sstr(expr)


def _block(math: str) -> str:
    """A row's equation as display MathML; its caption (what it is of) is the row's own
    text (:attr:`Row.caption`), set by the page in words before it."""
    return compact_math(f'<math display="block">{math}</math>')


def _bodies(problem: Problem, model, expr_math) -> WorkedStep:
    d = dynamics_of(problem)
    inertias = _inertias(d, model)
    lines, rows = [], []
    for b in d.bodies:
        parts = inertias[b.name]
        mass = sum((m for m, _, _ in parts), sp.Integer(0))
        mass_math = expr_math(model.plain(mass))
        if b.frame is None:
            lines.append(f"{b.name}: a particle at {b.centre}")
            rows.append(Row(f"body-{b.name}", _block(mass_math),
                            f"m = {sp.sstr(model.plain(mass))}", caption=f"{b.name}, mass"))
            continue
        frame = model.frames[b.frame]
        lines.append(f"{b.name}: a rigid body turning with frame {b.frame}, its momentum "
                     f"balances about {b.centre}")
        rows.append(Row(f"body-{b.name}", _block(mass_math),
                        f"m = {sp.sstr(model.plain(mass))}", caption=f"{b.name}, mass"))
        total = Dyadic(0)
        for m, at, central in parts:
            offset = model.positions[at] - model.positions[b.centre]
            total += parallel_axis(central if central is not None else Dyadic(0), m, offset,
                                   frame)
            if len(parts) > 1 or at != b.centre:
                own = central.to_matrix(frame) if central is not None else sp.zeros(3, 3)
                rows.append(Row(f"body-{b.name}-{at}", _block(
                    _inertia(at, expr_math(model.plain(own)))),
                    f"I_{at} = {_text(model.plain(own))}",
                    caption=f"part of mass {sp.sstr(model.plain(m))} at {at}, about {at}"))
        matrix = sp.simplify(model.plain(total.to_matrix(frame))) if total != Dyadic(0) \
            else sp.zeros(3, 3)
        shifted = " (parts shifted by the parallel-axis theorem)" if len(parts) > 1 \
            or any(at != b.centre for _, at, _ in parts) else ""
        rows.append(Row(f"inertia-{b.name}", _block(_inertia(b.centre, expr_math(matrix))),
                        f"I_{b.centre} = {_text(matrix)}",
                        ("other_shape_inertia", "inertia_omitted"),
                        f"{b.name}, inertia about {b.centre} in {b.frame} axes{shifted}"))
    return WorkedStep("kinetics-bodies", "Bodies", tuple(lines), tuple(rows))


def _inertia(at: str, matrix: str) -> str:
    return (f"<mrow><msub><mi mathvariant=\"bold\">I</mi><mi>{at}</mi></msub><mo>=</mo>"
            f"{matrix}</mrow>")


_KIND_WORDS = {LoadKind.WEIGHT: "weight", LoadKind.NORMAL: "normal force",
               LoadKind.STATIC_FRICTION: "static friction",
               LoadKind.KINETIC_FRICTION: "kinetic friction", LoadKind.TENSION: "tension",
               LoadKind.SPRING: "spring force", LoadKind.DAMPER: "damper force",
               LoadKind.PIN: "pin reaction", LoadKind.CONTACT: "contact force",
               LoadKind.APPLIED_FORCE: "force", LoadKind.APPLIED_COUPLE: "couple",
               LoadKind.IMPULSE: "impulse", LoadKind.REACTION: "reaction"}


def _loads(problem: Problem, matrix_math, text) -> WorkedStep:
    rows = []
    for load in free_body_loads(problem):
        couple = load.point is None
        value = load.moment if couple else load.force
        if value is None:
            continue
        where = "" if couple else f" at {load.point}"
        unknown = " (unknown)" if load.unknown else ""
        # a weight is named by its kind alone ("weight at G", not "weight gravity at G")
        name = "" if load.kind == LoadKind.WEIGHT else f" {load.name}"
        words = f"{load.body}, {_KIND_WORDS.get(load.kind, 'load')}{name}{where}{unknown}"
        symbol = "M" if couple else "F"
        letter = _vector_name(symbol, load.name)
        if load.kind == LoadKind.WEIGHT:
            symbol, letter = "W", "<mi mathvariant=\"bold\">W</mi>"
        math = _block(f"<mrow>{letter}<mo>=</mo>{matrix_math(value)}</mrow>")
        codes = LOAD_CODES.get(load.kind, ())
        # the text says what the math shows: the load's own symbol when it is one (N_P)
        said = symbol if symbol == "W" else load.name if _is_symbol(load.name) \
            else f"{symbol}_{load.name}"
        rows.append(Row(f"load-{load.body}-{load.name}", math, f"{said} = {text(value)}",
                        codes, words))
    return WorkedStep("kinetics-free-body-loads", "Free-body loads",
                      ("Each body cut free, with every load on it.",),
                      tuple(rows))


def _is_symbol(name: str) -> bool:
    """Whether a load's name is a symbol (``N_P``, ``T``, ``s1``), not a word (``gravity``)."""
    base, _, sub = name.partition("_")
    return len(base) <= 2 or bool(sub)


def _vector_name(letter: str, name: str) -> str:
    """A load's vector as a textbook names it: its own name in bold when it is a symbol
    (``N_P``: bold N, subscript P; ``T``), else ``letter`` with the name as a subscript."""
    base, _, sub = name.partition("_")
    if not _is_symbol(name):  # a word (gravity, pull): F with it as a subscript
        return f'<msub><mi mathvariant="bold">{letter}</mi><mi>{escape(name)}</mi></msub>'
    letters = base.rstrip("0123456789")
    if letters and letters != base:  # a number is a subscript: s₁ for s1
        base, sub = letters, base[len(letters):] + ("_" + sub if sub else "")
    shown = f'<mi mathvariant="bold">{escape(base)}</mi>'
    return f"<msub>{shown}<mi>{escape(sub.replace('_', ','))}</mi></msub>" if sub else shown


def _work_energy(kin, expr_math, text) -> WorkedStep:
    """T1 + V1 + U12 = T2 + V2: the energy split into its kinetic part (the terms with a
    rate) and its potential part, at the start and at the instant."""
    k = kin.k
    rates = set(k.qd)
    energy = sp.expand(kin.energy)
    T = sp.Add(*[t for t in sp.Add.make_args(energy) if t.free_symbols & rates])
    V = energy - T
    start = dict(kin.start)
    T1, V1 = (sp.simplify(e.xreplace(start)) for e in (T, V))
    T2, V2 = sp.factor_terms(sp.simplify(T)), sp.simplify(V)
    sub = ("<msub><mi>{0}</mi><mn>{1}</mn></msub>")
    U = "<msub><mi>U</mi><mrow><mn>1</mn><mo>&#8594;</mo><mn>2</mn></mrow></msub>"
    balance = (f"<mrow>{sub.format('T', 1)}<mo>+</mo>{sub.format('V', 1)}<mo>+</mo>{U}"
               f"<mo>=</mo>{sub.format('T', 2)}<mo>+</mo>{sub.format('V', 2)}</mrow>")
    rows = [Row("energy-balance", f'<math display="block">{balance}</math>',
                "T1 + V1 + U12 = T2 + V2"),
            Row("energy-start", _block(f"<mrow>{sub.format('T', 1)}<mo>=</mo>"
                                       f"{expr_math(T1)}<mo>,</mo><mspace width=\"1em\"/>"
                                       f"{sub.format('V', 1)}<mo>=</mo>{expr_math(V1)}</mrow>"),
                f"T1 = {text(T1)}, V1 = {text(V1)}", caption="at the start"),
            Row("energy-T2", _block(f"<mrow>{sub.format('T', 2)}<mo>=</mo>{expr_math(T2)}</mrow>"),
                f"T2 = {text(T2)}", ENERGY_CODES, "kinetic energy at the instant"),
            Row("energy-V2", _block(f"<mrow>{sub.format('V', 2)}<mo>=</mo>{expr_math(V2)}</mrow>"),
                f"V2 = {text(V2)}", ("spring_free_length_omitted",),
                "potential energy at the instant")]
    if kin.nonconservative:
        work = f"the work of {', '.join(kin.nonconservative)} from the start to the instant"
    else:
        work = "0: no load that does work is left out of V (the reactions do none)"
    return WorkedStep("kinetics-work-energy", "Work and energy from the start to the instant",
                      (f"U12 is {work}.",
                 "Solved for the rate at the instant, with the sense the problem states."),
                      tuple(rows))


def _balances(problem: Problem, kin, expr_math, text) -> WorkedStep:
    d = dynamics_of(problem)
    N = problem.inertial_frame
    impact = kin.impact
    rows = []
    loads = free_body_loads(problem)
    by_label = {e.label: e.expr for e in kin.balances}
    first_force: set[str] = set()
    for i, e in enumerate(kin.balances):
        label = e.label
        words = label.removeprefix("body ")
        codes: tuple[str, ...] = ()
        if "moment balance" in label or "angular impulse" in label:
            codes = MOMENT_CODES
        elif "restitution" in label or "sticking" in label:
            codes = CONTACT_CODES
        else:
            body = label.removeprefix("body ").partition(":")[0]
            carried = [a for a in loads if a.body == body and len(a.unknowns) == 1
                       and e.expr.has(a.unknowns[0]) and a.name not in first_force]
            if carried:
                first_force.update(a.name for a in carried)
                codes = FORCE_CODES
        rows.append(Row(f"balance-{i}", _block(f"<mrow>{expr_math(e.expr)}<mo>=</mo>"
                                               "<mn>0</mn></mrow>"),
                        f"{text(e.expr)} = 0", codes, words))
    # about a fixed pivot: the moment balance a textbook writes there, free of its reaction
    model = kin.built[0]
    for b in d.bodies:
        moment = by_label.get(f"body {b.name}: moment balance about {b.centre} ({N}.z "
                              "component)")
        if b.frame is None or moment is None or impact:
            continue
        for pivot in dict.fromkeys(a.point for a in loads if a.body == b.name and a.unknown
                                   and a.point is not None and a.point != b.centre):
            if not _fixed(model, pivot, N):
                continue
            r = model.plain((model.positions[b.centre] - model.positions[pivot])
                            .to_matrix(model.inertial))
            fx, fy = (by_label.get(f"body {b.name}: {N}.{a} force balance", sp.Integer(0))
                      for a in "xy")
            about = sp.expand(sp.simplify(moment + r[0] * fy - r[1] * fx))
            words = f"{b.name}: moment balance about the fixed pivot {pivot} ({N}.z component)"
            rows.insert(0, Row(f"balance-pivot-{b.name}-{pivot}", _block(
                f"<mrow>{expr_math(about)}<mo>=</mo><mn>0</mn></mrow>"),
                f"{text(about)} = 0", MOMENT_CODES, words))
            break
    # the balance along each contact's normal: the one that gives a normal force
    kind = "impulse-momentum" if impact else "force"
    for load in loads:
        if load.kind != LoadKind.NORMAL or len(load.directions) != 1:
            continue
        n = load.directions[0]
        parts = [by_label.get(f"body {load.body}: {N}.{a} {kind} balance", sp.Integer(0))
                 for a in "xyz"]
        along = sp.simplify(sum((p * c for p, c in zip(parts, n)), sp.Integer(0)))
        if along == 0:
            continue
        words = f"{load.body}: along the normal of {load.name} ({load.direction_texts[0]})"
        tangent = _tangent(model, load.direction_texts[0], N)
        if tangent is not None:  # an incline's own axes, as a textbook takes them
            name, t = tangent
            along_t = sp.simplify(sum((p * c for p, c in zip(parts, t)), sp.Integer(0)))
            words_t = f"{load.body}: along the surface of {load.name} ({name})"
            rows.insert(0, Row(f"balance-surface-{load.body}-{load.name}", _block(
                f"<mrow>{expr_math(along_t)}<mo>=</mo><mn>0</mn></mrow>"),
                f"{text(along_t)} = 0", caption=words_t))
        rows.insert(0, Row(f"balance-normal-{load.body}-{load.name}", _block(
            f"<mrow>{expr_math(along)}<mo>=</mo><mn>0</mn></mrow>"),
            f"{text(along)} = 0", NORMAL_CODES, words))
    # what this problem's balances are: an impact's or the motion's, moments only for a
    # rigid body
    lines: tuple[str, ...] = ((
        "Impulse and momentum for each body: the impulses equal the change of its momentum"
        if impact else "Newton-Euler for each body: the sum of the loads equals the rate of "
        "change of its momentum") + f", in {N}'s components" + (
        "; the moments about each rigid body's reference point." if any(
            b.frame is not None for b in d.bodies) else "."),)
    if d.analysis is not None and isinstance(d.analysis, Impulse):
        lines += ("Each contact's condition: the restitution (or sticking) condition on the "
                  "velocities just after the impact.",)
    return WorkedStep("kinetics-momentum-balances", "Momentum balances", lines, tuple(rows))


def _tangent(model, normal: str, inertial: str):
    """The surface's own axis across a normal written as a frame's axis (``A.y``: ``A.x``)
    and its inertial components; ``None`` for a normal along the inertial frame's axes
    (its balances are those already written) or written otherwise."""
    frame, _, axis = normal.strip().lstrip("+").partition(".")
    if frame == inertial or frame not in model.frames or axis not in ("x", "y"):
        return None
    other = "y" if axis == "x" else "x"
    vector = getattr(model.frames[frame], other)
    return f"{frame}.{other}", model.plain(vector.to_matrix(model.inertial))


def _fixed(model, point: str, frame: str) -> bool:
    """Whether ``point`` stays fixed in the inertial frame ``frame``."""
    velocity = model.language.point_velocity(Name(point), frame)
    return all(identically_zero(c)
               for c in model.plain(velocity.to_matrix(model.inertial)))


def _solution(problem: Problem, kin, shown: dict, expr_math) -> WorkedStep:
    how = how_the_instant(problem)
    unknowns = list(kin.k.qd if kin.impact else kin.k.qdd) + list(kin.reactions)
    listing = "<mo>,</mo>".join(expr_math(u) for u in unknowns)
    names = [shown.get(u, u.name) for u in unknowns]
    level = "velocity" if kin.impact else "acceleration"
    lines = (f"The instant: {how}.",
             f"{len(kin.balances)} momentum balances and {len(kin.constraints)} {level}-level "
             "constraints, linear in the unknowns, solved together (rank and every equation "
             "checked).")
    row = Row("unknowns", _block(f"<mrow>{listing}</mrow>"),
              ", ".join(str(n) for n in names), caption="unknowns")
    return WorkedStep("kinetics-solution", "Solution", lines, (row,))
