"""The model in the write-up order (``mechgrade solve --steps``): as text, and its equations
and vectors as presentation MathML (sympy's printer; no script, no CDN)."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from enum import Enum
from functools import lru_cache
from html import unescape

import sympy as sp
from sympy.physics.vector import Vector

from ..errors import ExpressionError
from ..expressions.build import to_sympy
from ..expressions.notation import coordinate_names
from ..expressions.syntax import Attr, Name, parse
from ..spec.model import Problem
from .build import build
from .kinematics import derive
from .symbols import identically_zero


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
    points = [f"P_{p.origin}{p.name} = {p.position.text}" for p in problem.points
              if p.origin and p.position is not None]  # both, or neither (the inertial point)
    coordinates = [f"{c.name} [{c.unit or '1'}]" for c in problem.coordinates]
    parameters = [f"{p.name} [{p.unit or '1'}]" for p in problem.parameters]
    constraints = [f"{c.name} ({c.level.value}): {c.lhs.text} = {c.rhs.text}"
                   for c in problem.constraints]
    constraints += [f"  {e.label}: {sp.sstr(e.expr)} = 0" for e in k.position]
    constraints += [f"  {e.label}, rate form: {sp.sstr(e.expr)} = 0" for e in k.velocity]
    independent = len(k.coordinates) - dof if dof is not None else k.constraint_count
    dof_lines = [f"{_count(len(k.coordinates), 'coordinate')} - "
                 f"{_count(independent, 'independent scalar constraint')} = "
                 f"{len(k.coordinates) - independent}"]
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


def _count(n: int, noun: str) -> str:
    """``1 coordinate``, ``2 coordinates``.

    >>> _count(1, "coordinate"), _count(0, "independent scalar constraint")
    ('1 coordinate', '0 independent scalar constraints')
    """
    return f"{n} {noun}" + ("" if n == 1 else "s")


# ---------------------------------------------------------------------------- worked steps


@dataclass(frozen=True)
class Row:
    """One equation of a worked step: ``math`` its presentation MathML (generated from the
    model, never from student text), ``text`` the same in plain text, ``anchor`` its id on a
    page, ``codes`` the generated-mistake families (:data:`~mechgrade.spec.mistake_codes.MODEL_CODES`) that leave
    this very term out, so a feedback page can point at it; ``caption`` what the equation is
    of, in words (``rod: N.x force balance``), shown before it (``text`` is the equation's
    alone)."""

    anchor: str
    math: str
    text: str
    codes: tuple[str, ...] = ()
    caption: str = ""


class Motion(Enum):
    """What a worked step composes for a point: its velocity or its acceleration; the value
    begins the step's anchor (``vel-P``)."""

    VELOCITY = "vel"
    ACCELERATION = "acc"

    @property
    def noun(self) -> str:
        """``velocity`` or ``acceleration``: also the name of a drawn point's value."""
        return self.name.lower()

    @property
    def letter(self) -> str:
        """Its textbook symbol (``v``, ``a``).

        >>> Motion.ACCELERATION.letter, Motion.VELOCITY.anchor("P")
        ('a', 'vel-P')
        """
        return self.noun[0]

    def anchor(self, point: str) -> str:
        """The anchor of the step composing ``point``'s motion."""
        return f"{self.value}-{point}"

    @staticmethod
    def of_anchor(anchor: str) -> tuple[Motion, str] | None:
        """The motion and point a step's anchor composes; ``None`` for another step.

        >>> Motion.of_anchor("acc-P"), Motion.of_anchor("points")
        ((<Motion.ACCELERATION: 'acc'>, 'P'), None)
        """
        prefix, _, point = anchor.partition("-")
        return next(((m, point) for m in Motion if m.value == prefix and point), None)


@dataclass(frozen=True)
class WorkedStep:
    """One step of the worked solution: a title, lines of text and equations."""

    anchor: str
    title: str
    lines: tuple[str, ...] = ()
    rows: tuple[Row, ...] = ()


VELOCITY_TERMS: tuple[tuple[str, str], ...] = (("drop_transport_vel", "origin"), ("drop_omega_r", "omega_r"),
                  ("drop_relative_vel", "relative"))
ACCELERATION_TERMS: tuple[tuple[str, str], ...] = (("drop_transport_acc", "origin"), ("drop_tangential", "alpha_r"),
                      ("drop_centripetal", "omega_omega_r"), ("drop_coriolis", "coriolis"),
                      ("drop_relative_acc", "relative"))
"""The terms of the composition of motion (transport theorem), by the code of the generated
mistake that leaves each out (``coriolis_half`` halves the Coriolis row)."""


@lru_cache(maxsize=64)
def kinematics_steps(problem: Problem, dof: int | None = None,
                     said: tuple[tuple[str, str], ...] = ()) -> tuple[WorkedStep, ...]:
    """The kinematic steps of the worked solution, in the write-up order: frames with their
    angular velocities, where the points are, constraints and degrees of freedom, then the
    velocity and acceleration of every point in the inertial frame, each composed term by
    term (transport theorem) in the moving frame its position is written in. ``said``: a
    constraint (by name) the write-up says in words.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> steps = kinematics_steps(load_problem(shipped_dir("problems")
    ...                                   / "ruina_10_4_10_7_rotating_tube_accel.yaml"))
    >>> [s.anchor for s in steps]
    ['frames', 'points', 'constraints', 'vel-P', 'acc-P']
    >>> [(r.anchor, r.codes) for r in steps[-1].rows][2:4]
    [('acc-P-coriolis', ('drop_coriolis', 'coriolis_half')), ('acc-P-relative', ('drop_relative_acc',))]
    """
    text = dict(kinematics_derivation(problem, dof))
    model = build(problem)
    N = problem.inertial_frame
    show = _Display(model)
    frame_rows = []
    for f in problem.frames:
        if f.parent is None:
            continue
        omega = model.frames[f.name].ang_vel_in(model.frames[N])
        alpha = model.frames[f.name].ang_acc_in(model.frames[N])
        turning = (("ω", omega, "angvel"), ("α", alpha, "angacc"))
        for symbol, value, kind in turning[:1] if _is_zero(omega, model) else turning:
            frame_rows.append(Row(f"{kind}-{f.name}", show.equation(
                _scripted(symbol, N, f.name), model.plain(value)),
                f"{N}_{'omega' if symbol == 'ω' else 'alpha'}_{f.name} = "
                f"{_vector_text(model.plain(value))}",
                ("relative_omega",) if symbol == "ω" else ()))
    k = derive(problem)
    constraint_rows = [Row(f"constraint-{i}", show.math(sp.Eq(e.expr, 0)), f"{sp.sstr(e.expr)} = 0",
                           caption=e.label + (", rate form" if i >= len(k.position) else ""))
                       for i, e in enumerate(k.position + k.velocity)]
    # the author's constraints as written, those ``said`` in words (a junction's balance: its
    # spec form is the solver's), each component typeset in the rows
    constraints = tuple(dict(said).get(c.name) or f"{c.name} ({c.level.value}): {c.lhs.text} = "
                        f"{c.rhs.text}" for c in problem.constraints)
    steps = [WorkedStep("frames", "Frames and their angular velocities", text["Frames"],
                        tuple(frame_rows)),
             WorkedStep("points", "Where the points are", text.get("Definitions", ()),
                        tuple(_position_rows(problem, model, show))),
             WorkedStep("constraints", "Constraints and degrees of freedom",
                        constraints + text["Degrees of freedom"], tuple(constraint_rows))]
    for motion in Motion:
        for p in problem.points:
            if p.origin is not None:
                steps.append(_motion_step(problem, model, show, p.name, motion))
    return tuple(steps)


def _position_rows(problem: Problem, model, show: "_Display"):
    """Each located point's position from its origin, as a textbook writes it (r with the
    subscript P/O, along the frames' unit vectors)."""
    for p in problem.points:
        if p.origin is None or p.position is None:
            continue
        r = model.plain(model.positions[p.name] - model.positions[p.origin])
        label = (f'<msub><mi mathvariant="bold">r</mi><mrow><mi>{p.name}</mi><mo>/</mo>'
                 f"<mi>{p.origin}</mi></mrow></msub>")
        yield Row(f"pos-{p.name}", show.equation(label, r),
                  f"r_{p.name}/{p.origin} = {_vector_text(r)}")


def _motion_step(problem: Problem, model, show: "_Display", point: str,
                 motion: Motion) -> WorkedStep:
    """The velocity or acceleration (``motion``) of ``point`` in the inertial frame: each
    term of its composition in the moving frame it is described in, then the sum."""
    N = problem.inertial_frame
    language = model.language
    velocity = motion is Motion.VELOCITY
    whole = (language.point_velocity if velocity else language.point_acceleration)(
        Name(point), N)
    letter, anchor = motion.letter, motion.anchor(point)
    rows = []
    moving = _moving_frame(problem, model, point)
    if moving is not None:
        B, origin = moving
        F, frame = model.frames[N], model.frames[B]
        r = model.positions[point] - model.positions[origin]
        omega, alpha = frame.ang_vel_in(F), frame.ang_acc_in(F)
        v_rel = r.dt(frame)
        r_math = f"<msub><mi mathvariant=\"bold\">r</mi><mrow><mi>{point}</mi><mo>/</mo>" \
                 f"<mi>{origin}</mi></mrow></msub>"
        w, a = _scripted("ω", N, B), _scripted("α", N, B)
        if velocity:
            terms = {"origin": (language.point_velocity(Name(origin), N),
                                _scripted("v", N, origin), f"{N}_v_{origin}"),
                     "omega_r": (omega ^ r, f"{w}<mo>×</mo>{r_math}", f"omega x r_{point}/{origin}"),
                     "relative": (v_rel, _scripted("v", B, point), f"{B}_v_{point}")}
            codes = VELOCITY_TERMS
        else:
            terms = {"origin": (language.point_acceleration(Name(origin), N),
                                _scripted("a", N, origin), f"{N}_a_{origin}"),
                     "alpha_r": (alpha ^ r, f"{a}<mo>×</mo>{r_math}", f"alpha x r_{point}/{origin}"),
                     "omega_omega_r": (omega ^ (omega ^ r),
                                       f"{w}<mo>×</mo><mo>(</mo>{w}<mo>×</mo>{r_math}<mo>)</mo>",
                                       f"omega x (omega x r_{point}/{origin})"),
                     "coriolis": (2 * (omega ^ v_rel),
                                  f"<mn>2</mn>{w}<mo>×</mo>{_scripted('v', B, point)}",
                                  f"2 omega x {B}_v_{point}"),
                     "relative": (v_rel.dt(frame), _scripted("a", B, point), f"{B}_a_{point}")}
            codes = ACCELERATION_TERMS
        for code, name in codes:
            value, label, label_text = terms[name]
            value = model.plain(value)
            if _is_zero(value, model):
                continue
            rows.append(Row(f"{anchor}-{name}", show.equation(label, value),
                            f"{label_text} = {_vector_text(value)}",
                            (code, "coriolis_half") if name == "coriolis" else (code,)))
    rows.append(Row(f"{anchor}-total", show.equation(_scripted(letter, N, point),
                                                            model.plain(whole)),
                    f"{N}_{letter}_{point} = {_vector_text(model.plain(whole))}"))
    where = f" (composed in frame {moving[0]}, from {moving[1]})" if moving else ""
    return WorkedStep(anchor, f"The {motion.noun} of {point} in {N}{where}", (), tuple(rows))


def _moving_frame(problem: Problem, model, point: str) -> tuple[str, str] | None:
    """The frame (and its origin) ``point`` is described in, when it turns in the inertial
    frame and has an origin: its motion is composed there (transport theorem)."""
    spec = next(p for p in problem.points if p.name == point)
    assert spec.position is not None  # only located points (those with an origin) get here
    used = _frames_used(spec.position.node)
    for f in problem.frames:
        if f.name in used and f.origin is not None and f.origin != point \
                and f.origin == spec.origin and not _is_zero(model.plain(
                    model.frames[f.name].ang_vel_in(model.frames[problem.inertial_frame])),
                    model):
            return f.name, f.origin
    return None


def _frames_used(node) -> set[str]:
    """The frames whose unit vectors a position expression uses (``B.x`` -> ``B``)."""
    found = set()
    stack = [node]
    while stack:
        item = stack.pop()
        if isinstance(item, Attr):
            found.add(item.base)
        for child in ("left", "right", "operand"):
            if getattr(item, child, None) is not None:
                stack.append(getattr(item, child))
        stack.extend(getattr(item, "args", ()) or ())
    return found


def _is_zero(value, model) -> bool:
    if isinstance(value, Vector):
        return all(identically_zero(c) for c in model.plain(value.to_matrix(model.inertial)))
    return identically_zero(value)


def _scripted(letter: str, frame: str, point: str) -> str:
    """``letter`` with ``frame`` as a left superscript and ``point`` as a right one:
    :math:`{}^N\\mathbf{v}^A`, the textbook's velocity of A in N."""
    return (f"<mmultiscripts><mi mathvariant=\"bold\">{letter}</mi><none/><mi>{point}</mi>"
            f"<mprescripts/><none/><mi>{frame}</mi></mmultiscripts>")


def symbolic_math(problem: Problem, text: str, label: str = "") -> str | None:
    """A symbolic answer the solver wrote (sympy syntax, in the problem's names) as MathML:
    rates dotted, ``|x|`` for ``Abs(x)``, ``label =`` before it when given; ``None`` when it
    cannot be read.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml")
    >>> "<mo>|</mo>" in symbolic_math(p, "xd/Abs(xd)")
    True
    """
    model = build(problem)
    known = {str(s): s for s in (*model.symbols.q, *model.symbols.qd, *model.symbols.qdd)}

    def resolve(node):
        if not isinstance(node, Name):
            raise KeyError(node)  # a frame's unit vector or a prime: not in an answer
        return known.get(node.id) or sp.Symbol(node.id, real=True)

    try:
        expr = to_sympy(parse(text), resolve)
    except ExpressionError:
        return None
    show = _Display(model)
    return compact_math(show.math(expr) if not label else
                        f'<math display="block"><mrow>{label}<mo>=</mo>{show._inner(expr)}'
                        '</mrow></math>')


_FLAT = {"math", "mrow"}
"""Elements whose children an ``<mrow>`` without attributes may be spread into: both lay out
their children in a row, as the ``<mrow>`` would."""


def compact_math(text: str) -> str:
    """MathML ``text`` as it renders, in fewer bytes (every feedback page carries each step):
    an ``<mrow>`` of one child is that child, an ``<mrow>`` in a row is spread into it (but
    one that begins or ends with an operator, whose form and stretch its row decides), a
    bold letter is the mathematical bold character (MathML Core renders no ``mathvariant``
    but ``normal``), invisible times is left out. Characters that do not print stay
    character references. Unreadable ``text`` is returned as it is.

    >>> compact_math('<math><mrow><mrow><mi mathvariant="bold">n</mi></mrow><mi>x</mi></mrow>'
    ...              '<mo>&#160;</mo><mrow><mo>&#8722;</mo><mi>y</mi></mrow></math>')
    '<math><mi>𝐧</mi><mi>x</mi><mo>&#160;</mo><mrow><mo>−</mo><mi>y</mi></mrow></math>'
    """
    # invisible times says nothing a reader needs: the row's spoken label reads the product
    text = text.replace("<mo>&InvisibleTimes;</mo>", "").replace("<mo>&#8290;</mo>", "")
    try:
        root = ET.fromstring(re.sub(r"&(#?\w+);", lambda m: _character(m.group(0)), text))
    except ET.ParseError:
        return text
    _compact(root)
    out = ET.tostring(root, encoding="unicode").replace(" />", "/>")
    return "".join(c if c.isprintable() else f"&#{ord(c)};" for c in out)


def _character(reference: str) -> str:
    """A character reference as its character, but for the markup's own (``&lt;`` ...)."""
    shown = unescape(reference)
    return reference if shown in "<>&\"'" else shown


def _compact(element: ET.Element) -> None:
    for child in element:
        _compact(child)
        if child.tag == "mi" and child.get("mathvariant") == "bold" and child.text \
                and len(child.text) == 1 and child.text.isascii() and child.text.isalpha():
            letter = child.text
            child.text = chr(0x1D400 + ord(letter) - 65 if letter.isupper()
                             else 0x1D41A + ord(letter) - 97)
            del child.attrib["mathvariant"]
    i = 0
    while i < len(element):
        child = element[i]
        # an operator's form (prefix, infix, postfix: its spacing) and a fence's stretch
        # depend on its place in its row: a row with an operator at either end is kept
        if child.tag == "mrow" and not child.attrib and not (child.text or "").strip() \
                and len(child) and child[0].tag != "mo" and child[-1].tag != "mo" \
                and (len(child) == 1 or element.tag in _FLAT):
            grandchildren = list(child)
            if (child.tail or "").strip():
                i += 1  # text after it (none in generated MathML): kept as it is
                continue
            element.remove(child)
            for j, g in enumerate(grandchildren):
                element.insert(i + j, g)
            continue  # the spread children are looked at in turn
        i += 1


def _hat(letter: str) -> str:
    """A frame's unit vector's letter, bold with a hat: one letter as the bold character with
    a combining circumflex (its hat sits on it, and in a third of the bytes of an accent)."""
    if len(letter) == 1 and "a" <= letter <= "z":
        return f"<mi>{chr(0x1D41A + ord(letter) - 97)}\u0302</mi>"
    return f'<mover accent="true"><mi mathvariant="bold">{letter}</mi><mo>^</mo></mover>'


_SHORT = re.compile(r"<mi>([acegm-su-z\u03b1\u03b3\u03b5\u03b7\u03b9\u03ba\u03bc\u03bd"
                    r"\u03c0\u03c1\u03c3-\u03c5\u03c7\u03c9])</mi>")


def _dotted(base: str, combining: str) -> str | None:
    """A rate's letter with its dots as combining marks (ẋ: a fifth of the bytes of the dots
    set over it), for a small letter with no ascender in a coordinate ``x`` or ``x_1``: the
    letter in math italic (an ``<mi>`` of two characters is set upright), the dots on it, the
    subscript beside; ``None`` for any other letter (Chromium sets the dots of θ̇ on the θ).

    >>> _dotted("<msub><mi>x</mi><mi>1</mi></msub>", "\u0307") == "<msub><mi>\U0001d465\u0307</mi><mi>1</mi></msub>"
    True
    >>> _dotted("<mi>θ</mi>", "\u0307") is None
    True
    """
    m = re.fullmatch(r"(<msub>)?" + _SHORT.pattern + r"(.*</msub>)?", base)
    if m is None or bool(m.group(1)) != bool(m.group(3)):
        return None
    letter = m.group(2)
    italic = chr(0x1D44E + ord(letter) - 97) if letter.isascii() \
        else chr(0x1D6FC + ord(letter) - 0x3B1)
    return f"{m.group(1) or ''}<mi>{italic}{combining}</mi>{m.group(3) or ''}"


class _Display:
    """MathML of a model's expressions, with rates as dots over their coordinate
    (``thetad`` -> θ̇)."""

    def __init__(self, model):
        symbols = model.symbols
        self.swap = {}
        self.marks = {}
        spelled = dict(coordinate_names([str(q) for q in symbols.q],
                                        [p.name for p in model.problem.points]))
        for i, (q, qd, qdd) in enumerate(zip(symbols.q, symbols.qd, symbols.qdd)):
            base = sp.printing.mathml(sp.Symbol(spelled.get(str(q), str(q))),
                                      printer="presentation")
            if str(q) in spelled:  # x_J, not the spec's xj
                self.swap[q] = sp.Symbol(f"zzcoordinate{i}q", real=True)
                self.marks[f"<mi>zzcoordinate{i}q</mi>"] = base
            # the bullet operator: the dot above (U+02D9) is a pixel at text size in Chromium
            for symbol, mark, name, combining in ((qd, "&#8729;", f"zzrate{i}x", "\u0307"),
                                                  (qdd, "&#8729;&#8729;", f"zzrate{i}xx",
                                                   "\u0308")):
                self.swap[symbol] = sp.Symbol(name, real=True)
                self.marks[f"<mi>{name}</mi>"] = _dotted(base, combining) or \
                    f'<mover accent="true">{base}<mo>{mark}</mo></mover>'

    def _inner(self, expr) -> str:
        text = sp.printing.mathml(sp.sympify(expr).xreplace(self.swap), printer="presentation")
        for placeholder, shown in self.marks.items():
            text = text.replace(placeholder, shown)
        return text

    def math(self, expr) -> str:
        return f'<math display="block">{self._inner(expr)}</math>'

    def equation(self, label: str, value) -> str:
        """``label = value`` (a vector as components along its frames' unit vectors)."""
        body = self._vector(value) if isinstance(value, Vector) else self._inner(value)
        return f'<math display="block"><mrow>{label}<mo>=</mo>{body}</mrow></math>'

    def _vector(self, v: Vector) -> str:
        """A vector as its components times its frames' unit vectors: a sum in parentheses,
        a product or a symbol bare, a negative one after a minus sign."""
        out: list[str] = []
        for matrix, frame in v.args:
            for coefficient, axis in zip(matrix, "xyz"):
                coefficient = min((sp.simplify(coefficient), sp.expand(coefficient)),
                                  key=sp.count_ops)
                if coefficient == 0:
                    continue
                negative = not isinstance(coefficient, sp.Add) \
                    and coefficient.could_extract_minus_sign()
                shown = -coefficient if negative else coefficient
                unit = f"<msub>{_hat(frame.name.lower())}<mi>{axis}</mi></msub>"
                if shown == 1:
                    term = unit
                elif isinstance(shown, sp.Add):
                    term = f"<mo>(</mo>{self._inner(shown)}<mo>)</mo>{unit}"
                else:
                    term = f"{self._inner(shown)}<mo>&#8290;</mo>{unit}"
                out.append(("<mo>&#8722;</mo>" if negative else
                            "<mo>+</mo>" if out else "") + f"<mrow>{term}</mrow>")
        return f"<mrow>{''.join(out) if out else '<mn>0</mn>'}</mrow>"
