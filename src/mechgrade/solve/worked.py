"""The worked solution of a problem as ready-made text for pages: its steps in the write-up
order (MathML generated from the model), the answers in the asked units, the picture as inline
SVG, and where each generated mistake happens in it.

Everything symbolic (the steps, the picture's functions) is made once per problem; a solution
(a student's variant) only adds its numbers. Nothing here holds a sympy object, so reports can
show a :class:`WorkedSolution` without importing sympy.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.solve import solve
>>> problem = load_problem(shipped_dir("problems") / "ruina_10_4_10_7_rotating_tube_accel.yaml")
>>> worked = worked_solution(problem, solve(problem))
>>> worked.place("a_P_N", "drop_coriolis"), worked.place("a_P_N", "given_sign")
('acc-P-coriolis', 'givens')
>>> worked.declared_place("a_P_N", "The Coriolis term 2 omega x v_rel is missing.")
'acc-P-coriolis'
>>> worked.picture.startswith("<svg")
True
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from ..expressions.notation import coordinate_names
from ..expressions.syntax import Attr, Bin, Call, Name, Node, Prime, Unary, parse, to_text
from ..mechanics.derivation import Motion, Row, WorkedStep, symbolic_math
from ..mechanics.writeup import worked_steps
from ..spec.model import Expr, Objective, ObjectiveKind, Problem
from ..tolerance import within
from ..units import from_si, same_dimension
from ..spec.mistake_codes import DYNAMICS_CODES, GIVEN_CODES, MODEL_CODES
from .entry import solve
from .fbd import FreeBodyDiagram, free_body_diagrams
from .phases import grip_constraint, gripping, gripping_phase, gripping_word
from .rules import BEFORE_EVENT
from .picture import drawable, picture_svg, scene
from .mutants import SAME
from .result import (ROUND_OFF, GeneratedMistake, MistakeValue, ObjectiveResult, Solution,
                     StateValue, in_frame, without_round_off)

__all__ = ["Row", "WorkedSolution", "WorkedStep", "answer_text", "worked_solution"]

DIAGRAM_STEP = "kinetics-free-body-loads"
"""The step that shows the free-body diagrams."""
EQUATIONS_STEP = "kinetics-momentum-balances"
"""The step that writes the equations of motion (the momentum balances)."""
_DYNAMICS_STEPS = {"strands_miscounted": "constraints", "body_ke_omitted": "kinetics-bodies",
                   "rotational_ke_omitted": "kinetics-bodies",
                   "spring_free_length_omitted": "kinetics-free-body-loads",
                   "springs_in_series": "kinetics-free-body-loads",
                   "damping_omitted": "kinetics-free-body-loads",
                   "force_omitted": "kinetics-free-body-loads",
                   "spring_omitted": "kinetics-free-body-loads",
                   "load_at_other_point": "kinetics-free-body-loads",
                   "contact_taken_smooth": "kinetics-free-body-loads"}
"""Where a dynamics mistake happens when no row of the steps names it: its step."""
_ACCELERATION_CALLS = ("acc", "acc_t", "acc_n", "rho", "normal")
_MOTION_CALLS = _ACCELERATION_CALLS + ("vel", "speed", "tangent")


@dataclass(frozen=True)
class WorkedSolution:
    """One problem's worked solution (for one set of givens): ``steps`` in the write-up order,
    ``picture`` an SVG document (empty when there is nothing to draw), ``places``
    ``(objective, code, anchor)``: the step or row (by anchor) where the generated mistake
    ``code`` of an objective happens; ``diagrams`` each body's free-body diagram (plain
    data), shown in the step anchored ``diagram_step``; ``equations_step`` the step that
    writes its equations of motion (``""``: none); ``names`` how a textbook spells the
    coordinates the answer syntax does not (:func:`~mechgrade.expressions.notation.coordinate_names`)."""

    problem: str
    title: str
    steps: tuple[WorkedStep, ...]
    picture: str
    places: tuple[tuple[str, str, str], ...] = ()
    declared: tuple[tuple[str, str, str], ...] = ()
    diagrams: tuple[FreeBodyDiagram, ...] = ()
    diagram_step: str = ""
    equations_step: str = ""
    names: tuple[tuple[str, str], ...] = ()

    def place(self, objective: str, code: str) -> str | None:
        """The anchor of the step or row where ``code``'s mistake happens for ``objective``."""
        for o, c, anchor in self.places:
            if (o, c) == (objective, code):
                return anchor
        return None

    def declared_place(self, objective: str, message: str) -> str | None:
        """The anchor where the author's mistake with ``message`` happens, when known."""
        for o, m, anchor in self.declared:
            if (o, m) == (objective, message):
                return anchor
        return None


def answer_text(result: ObjectiveResult) -> str:
    """One objective's answer as the write-up (and ``mechgrade solve``) prints it, round-off
    shown as 0.

    >>> answer_text(ObjectiveResult("v", "vector", "m/s", (1.0, 2.5, 1e-14), "N"))
    '(1, 2.5, 0) m/s in frame N'
    """
    if result.kind == ObjectiveKind.SYMBOLIC:
        return f"{result.expr}   [{result.unit or '1'}; in {', '.join(result.symbols)}]"
    shown = without_round_off(result.value)
    if isinstance(shown, tuple):
        inner = ", ".join(f"{v:.6g}" for v in shown)
        return f"({inner}) {result.unit}{in_frame(result.frame)}"
    return f"{shown:.6g} {result.unit}".rstrip()


def worked_solution(problem: Problem, solution: Solution,
                    objectives: tuple[str, ...] | None = None) -> WorkedSolution:
    """The worked solution of ``problem`` with ``solution``'s numbers (its givens, its
    answers, its picture), for the ``objectives`` named (default: every one)."""
    chosen = tuple(o for o in problem.objectives if objectives is None or o.id in objectives)
    # a rate an energy balance or an integration gave is a result, not a given
    stated = {g.key.text for g in problem.givens}
    givens = tuple(_state_text(s) for s in solution.state if s.given and s.name in stated)
    solved = tuple(_state_text(s) for s in solution.state
                   if not (s.given and s.name in stated))
    # what each objective asks, in words and as a textbook writes it (not its answer key)
    asked = tuple(_asked_line(o, problem.inertial_frame) for o in chosen)
    results = {r.id: r for r in solution.results}
    signs = {v.name: int(np.sign(v.si)) for v in solution.state}
    answers = tuple(_answer_step(problem, o, results[o.id], signs) for o in chosen
                    if o.id in results)
    drawing = scene(problem, solution)
    slip_ends = slip_end_time(problem)
    instant = next((v.si for v in solution.state if v.name == "t"), None)
    rolling = slip_ends is not None and instant is not None and instant > slip_ends
    if slip_ends is not None:  # each answer says the phase it is read in
        answers = tuple(_read_in(problem, step, o, slip_ends, instant)
                        for step, o in zip(answers, (o for o in chosen if o.id in results)))
    steps = (WorkedStep("givens", "Givens and what is asked", givens + ("",) + asked),
             *_phased(problem, slip_ends,
                      _at_the_instant(problem, worked_steps(problem, solution.dof), drawing)),
             *((WorkedStep("state", "The instant, solved", solved),) if solved else ()),
             *answers)
    codes = MODEL_CODES + GIVEN_CODES + (DYNAMICS_CODES if problem.dynamics else ())
    places = tuple((o.id, code, _place(steps, o.id, o.find.node, code))
                   for o in chosen if o.id in results for code in codes)
    declared = tuple((o.id, m.message, _place(steps, o.id, o.find.node, g.code))
                     for o in chosen if o.id in results
                     for m in results[o.id].mistakes
                     for g in _same_value(m, results[o.id].generated_mistakes))
    # the diagrams at the instant, with the loads of the phase it is in
    diagrams = free_body_diagrams(gripping_phase(problem) if rolling else problem, solution)
    return WorkedSolution(problem.id, problem.title, steps,
                          picture_svg(drawing, inline=True) if drawable(drawing) else "", places, declared,
                          diagrams, (f"rolling-{DIAGRAM_STEP}" if rolling else DIAGRAM_STEP)
                          if diagrams else "",
                          EQUATIONS_STEP if any(s.anchor == EQUATIONS_STEP for s in steps)
                          else "", problem_names(problem))


def problem_names(problem: Problem) -> tuple[tuple[str, str], ...]:
    """How a textbook spells ``problem``'s coordinates (``xj`` is x_J): for every text of it a
    student reads."""
    return coordinate_names([c.name for c in problem.coordinates], [p.name for p in problem.points])


@lru_cache(maxsize=64)
def slip_end_time(problem: Problem) -> float | None:
    """When the slip of a contact that grips once its slip ends (a ball skids, then rolls)
    ends, in s; ``None`` for a motion in one phase. Kept per problem: a class's pages ask
    again for each student.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> slip_end_time(load_problem(shipped_dir("problems") / "atwood_machine.yaml")) is None
    True
    """
    if gripping(problem) is None:
        return None
    grip = gripping_phase(problem).constraints[-1]  # its contact's slip speed = 0
    asked = Objective("slip_ends", "", Expr("t", parse("t"), grip.where), ObjectiveKind.SCALAR,
                      "s", when=(grip.lhs, grip.rhs))
    found = solve(replace(problem, objectives=(asked,), givens=tuple(
        g for g in problem.givens if g.key.text != "t")))
    return float(found.results[0].value) if found.results else None  # type: ignore[arg-type]


def _phased(problem: Problem, slip_ends: float | None,
            steps: tuple[WorkedStep, ...]) -> tuple[WorkedStep, ...]:
    """``steps`` with, for a motion that slips then grips, the kinetics of each phase: those of
    the slip until ``slip_ends``, then the gripping phase's (its no-slip constraint, loads
    and balances) from then on."""
    if slip_ends is None:
        return steps
    grip = gripping(problem)
    assert grip is not None
    until, since = f"while {grip.name} slips, until t = {slip_ends:.3g} s", \
        f"{gripping_word(problem)} from t = {slip_ends:.3g} s ({grip.name} grips: static friction)"
    kinetics = [i for i, s in enumerate(steps) if s.anchor.startswith("kinetics-")]
    if not kinetics:
        return steps
    # the grip's constraint in words, not in the spec's language the solver wrote it in
    name = grip_constraint(problem)
    said = f"{grip.at} does not slip: its velocity along the surface is zero"
    later = tuple(replace(s, anchor=f"rolling-{s.anchor}", title=f"{s.title}, {since}",
                          lines=tuple(said if line.startswith(f"{name} (") else line
                                      for line in s.lines),
                          rows=tuple(replace(r, anchor=f"rolling-{r.anchor}",
                                             caption=r.caption.replace(name, said))
                                     for r in s.rows))
                  for s in worked_steps(gripping_phase(problem))  # its own degrees of freedom
                  # the bodies are those of the slip
                  if (s.anchor.startswith("kinetics-") and s.anchor != "kinetics-bodies")
                  or s.anchor == "constraints")
    earlier = tuple(replace(s, title=f"{s.title}, {until}") if i in kinetics else s
                    for i, s in enumerate(steps))
    return earlier[:kinetics[-1] + 1] + later + earlier[kinetics[-1] + 1:]


def _read_in(problem: Problem, step: WorkedStep, objective, slip_ends: float,
             instant: float | None) -> WorkedStep:
    """An answer's step saying the phase its value is read in (by the time it is read at:
    its own ``t`` given, else the instant's)."""
    own = next((g.si for g in objective.givens if g.key.text == "t"), None)
    at = own if own is not None else instant if objective.when is None else None
    if at is None:
        return step
    phase = f"read while {gripping_word(problem)}" if at > slip_ends * (1 + BEFORE_EVENT) \
        else "read while slipping"
    return replace(step, lines=(*step.lines, f"{phase} (the slip ends at t = {slip_ends:.3g} s)"))


_KINEMATIC = {"vel": "v", "acc": "a", "omega": "omega", "alpha": "alpha"}
_OF_BODY = {"ke": "E_K", "momentum": "L", "angmom": "H"}
"""A body's energy and momenta as Ruina and Pratap write them (E_K, L, H), of the body named."""

_OF_ONE = {"pe": "E_P", "power": "P"}
"""A body's or spring's potential energy and a load's power, of the one named."""

_OF_MODE = {"mode_frequency": "omega", "mode_damping": "zeta"}
"""Mode n's natural frequency and damping ratio, as ω and ζ with the mode's number."""

_OF_MOTION = {"omega_n": "omega_n", "zeta": "zeta"}
"""The natural frequency and damping ratio of a one-coordinate vibration."""

_ACROSS = {"before": "⁻", "after": "⁺"}
"""An impact's just before and just after, as a textbook marks them (v⁻, v⁺)."""


def asked_text(node: Node, inertial: str = "N") -> str:
    """What an objective's ``find`` asks, as a textbook writes it (in the answer syntax's
    names, which the pages typeset): ``eom(y)`` is ``ydd``, ``vel(P, N)`` is ``v_P``,
    ``dot(force(T), N.y)`` is ``T · N.y``; a quantity with no textbook symbol keeps its call.

    >>> from mechgrade.expressions.syntax import parse
    >>> def asked(text):
    ...     return asked_text(parse(text, functions={"dot", "vel", "mag", "force", "eom", "speed",
    ...                                              "before", "after", "ke", "pe",
    ...                                              "power", "angmom", "mode_frequency",
    ...                                              "mode_damping", "omega_n"}))
    >>> asked("dot(vel(P, B), N.x)"), asked("mag(force(F_P))")
    ('v_P in B · N.x', '|F_P|')
    >>> asked("eom(theta)"), asked("speed(G, N)")
    ('thetadd', '|v_G|')
    >>> asked("after(speed(G, N))"), asked("before(dot(vel(G, N), N.x))")
    ('|v_G|⁺', '(v_G · N.x)⁻')
    >>> asked("before(ke(rod, N))"), asked("pe(s1)"), asked("power(d, B)")
    ('(E_K of rod)⁻', 'E_P of s1', 'P of d')
    >>> asked("dot(angmom(disk, G, B), B.z)")
    'H of disk about G in B · B.z'
    >>> asked("mode_frequency(1)"), asked("mode_damping(2)"), asked("omega_n(x)")
    ('omega_1', 'zeta_2', 'omega_n')
    """
    def text(n: Node) -> str:
        if isinstance(n, Call):
            args = n.args
            if n.func == "eom" and len(args) == 1 and isinstance(args[0], Name):
                return f"{args[0].id}dd"
            if n.func in _KINEMATIC and len(args) == 2 and all(isinstance(a, Name) for a in args):
                frame = "" if args[1].id == inertial else f" in {args[1].id}"  # type: ignore[union-attr]
                return f"{_KINEMATIC[n.func]}_{args[0].id}{frame}"  # type: ignore[union-attr]
            if n.func == "speed" and len(args) == 2:
                return f"|{text(Call('vel', args))}|"
            if n.func == "force" and len(args) == 1:
                return text(args[0])
            if n.func in _OF_BODY and all(isinstance(a, Name) for a in args):
                *about, frame = (a.id for a in args)  # type: ignore[union-attr]
                said = f"{_OF_BODY[n.func]} of {about[0]}"
                said += "".join(f" about {p}" for p in about[1:])
                return said + ("" if frame == inertial else f" in {frame}")
            if n.func in _OF_ONE and args and isinstance(args[0], Name):
                return f"{_OF_ONE[n.func]} of {args[0].id}"
            if n.func in _OF_MODE and len(args) == 1:
                return f"{_OF_MODE[n.func]}_{to_text(args[0])}"
            if n.func in _OF_MOTION and len(args) == 1:
                return _OF_MOTION[n.func]
            if n.func in ("mag", "abs") and len(args) == 1:
                return f"|{text(args[0])}|"
            if n.func in _ACROSS and len(args) == 1:  # an impact's v⁻ and v⁺
                inner = text(args[0])
                inner = inner if inner.startswith("(") or " " not in inner else f"({inner})"
                return f"{inner}{_ACROSS[n.func]}"
            if n.func in ("dot", "cross") and len(args) == 2:
                sign = " · " if n.func == "dot" else " × "
                return f"({text(args[0])}{sign}{text(args[1])})"
            return f"{n.func}({', '.join(text(a) for a in args)})"
        if isinstance(n, (Name, Attr, Prime)):
            return to_text(n)
        if isinstance(n, Unary):
            return n.op + text(n.operand)
        if isinstance(n, Bin):
            return f"({text(n.left)} {n.op} {text(n.right)})"
        return to_text(n)

    out = text(node)
    return out[1:-1] if out.startswith("(") and out.endswith(")") and out.count("(") == 1 \
        else out


def _asked_line(objective, inertial: str) -> str:
    """An objective in the list of what is asked: its prompt, what it finds as a textbook
    writes it, its unit (``The string tension: |T| [N]``); its answer key is the page's
    business, not the worked solution's."""
    said = asked_text(objective.find.node, inertial)
    unit = f" [{objective.unit}]" if objective.unit else ""
    prompt = (objective.prompt or "").strip().rstrip(".")
    return f"{prompt}: {said}{unit}" if prompt else f"{said}{unit}"


def _answer_step(problem: Problem, objective, result: ObjectiveResult,
                 signs: dict[str, int]) -> WorkedStep:
    """An objective's answer: what it asks in the model's terms, then its value (a symbolic
    one typeset, in its unit and the names it is in; the sense of a rate it takes through its
    sign alone from ``signs``, the instant's sign of each value by name)."""
    asked = asked_text(objective.find.node, problem.inertial_frame) + (
        f", components along {objective.frame}" if objective.frame else "")
    title = objective.prompt or objective.id
    math = symbolic_math(problem, result.expr) \
        if result.kind == ObjectiveKind.SYMBOLIC and result.expr else None
    if math is None:
        return WorkedStep(f"answer-{objective.id}", title, (asked, f"= {answer_text(result)}"))
    rates = {f"{c.name}d": f"{c.name}'" for c in problem.coordinates}
    names = ", ".join(rates.get(n, n) for n in result.symbols)
    # a rate the answer takes only through its sign (kinetic friction's sense of sliding)
    senses = tuple(f"at this instant {rates[n]} {'>' if sign > 0 else '<'} 0, so "
                   f"{rates[n]}/|{rates[n]}| = {sign}"
                   for n in result.symbols if n in rates and f"Abs({n})" in (result.expr or "")
                   for sign in (signs.get(rates[n], 0),) if sign)
    return WorkedStep(f"answer-{objective.id}", title,
                      (asked, f"in {result.unit or '1'}, in terms of {names}", *senses),
                      (Row(f"answer-{objective.id}-value", math, answer_text(result)),))


def _at_the_instant(problem: Problem, steps: tuple[WorkedStep, ...],
                    drawing) -> tuple[WorkedStep, ...]:
    """``steps`` with each point's velocity and acceleration in numbers at the instant, along
    the inertial frame, in the unit an objective asks it in, else in the length unit of the
    givens per second (squared)."""
    points = {p.name: p for p in drawing.points}
    length = next((g.unit for g in problem.givens if g.unit and same_dimension(g.unit, "m")),
                  "m")
    units = {Motion.VELOCITY: f"{length}/s", Motion.ACCELERATION: f"{length}/s^2"}
    asked: dict[tuple[Motion, str], str] = {}
    for o in problem.objectives:
        for call in _calls(o.find.node):
            wanted = _motion_of(call)
            if isinstance(call.args[0], Name) and o.unit \
                    and same_dimension(o.unit, units[wanted]):
                asked.setdefault((wanted, call.args[0].id), o.unit)
    out = []
    for step in steps:
        motion, name = Motion.of_anchor(step.anchor) or (None, "")
        value = getattr(points[name], motion.noun, None) \
            if motion is not None and name in points else None
        if motion is not None and value is not None:
            unit = asked.get((motion, name), units[motion])
            shown = ", ".join(f"{from_si(c, unit) + 0.0:.4g}" for c in without_round_off(tuple(value)))
            step = replace(step, lines=step.lines + (
                f"At the instant: {problem.inertial_frame}_{motion.letter}_{name} = ({shown}) "
                f"{unit} along {problem.inertial_frame}",))
        out.append(step)
    return tuple(out)


def _same_value(mistake: MistakeValue, generated) -> tuple[GeneratedMistake, ...]:
    """The first generated mistake with the value of an author's ``mistake`` (or none): within
    :data:`.mutants.SAME`, as a mistake is the answer or another mistake, and shown zeros
    alike (:data:`.result.ROUND_OFF`)."""
    if mistake.value is None:
        return ()
    author = np.atleast_1d(np.asarray(mistake.value, float))
    for g in generated:
        if g.value is not None and within(np.atleast_1d(np.asarray(g.value, float)), author,
                                          SAME, ROUND_OFF):
            return (g,)
    return ()


def _state_text(value: StateValue) -> str:
    """``q'' = 3 rad/s^2``: a value of the instant, its unit as a student writes it (0 for
    round-off).

    >>> _state_text(StateValue("x''", -3.45e-31, "m / s ** 2", False, -3.45e-31))
    "x'' = 0 m/s^2"
    """
    unit = value.unit.replace(" ** ", "^").replace(" * ", "*").replace(" / ", "/")
    return f"{value.name} = {without_round_off(value.value):.6g} {unit}".rstrip()


def _place(steps: tuple[WorkedStep, ...], objective: str, node: Node, code: str) -> str:
    """Where the mistake ``code`` happens in the steps, for the objective ``node`` asks."""
    if code in GIVEN_CODES:
        return "givens"
    if code == "position_term":
        return "points"
    by_anchor = {s.anchor: s for s in steps}
    rows = [row for step in steps for row in step.rows]
    if code == "relative_omega":
        return next((r.anchor for r in rows if code in r.codes), "frames")
    if code in DYNAMICS_CODES:
        return next((r.anchor for r in rows if code in r.codes),
                    _DYNAMICS_STEPS.get(code, "kinetics-momentum-balances"))
    for call in _calls(node):
        if not isinstance(call.args[0], Name):
            continue
        step = by_anchor.get(_motion_of(call).anchor(call.args[0].id))
        if step is None:
            continue
        for row in step.rows:
            if code in row.codes:
                return row.anchor
    return f"answer-{objective}"


def _motion_of(call: Call) -> Motion:
    """The motion a motion call asks of its point (``rho`` and ``normal`` need its
    acceleration)."""
    return Motion.ACCELERATION if call.func in _ACCELERATION_CALLS else Motion.VELOCITY


def _calls(node: Node):
    """The motion calls (``vel(P, N)``, ``acc(P, N)``...) in ``node``, outermost first."""
    if isinstance(node, Call):
        if node.func in _MOTION_CALLS and len(node.args) == 2:
            yield node
        for arg in node.args:
            yield from _calls(arg)
    for child in ("left", "right", "operand"):
        if getattr(node, child, None) is not None:
            yield from _calls(getattr(node, child))
