"""An assignment as quiz questions for an LMS: each objective, with numbers drawn and solved.

:func:`question_bank` turns a planned assignment into plain data the question writers
(:mod:`mechgrade.export.questions`) lay out as Canvas QTI or Moodle XML:

* a **number** objective is a :class:`NumberItem`: the statement with one variable per drawn
  given, and ``count`` variants, each drawn for ids ``question-1``, ``question-2``... from the
  assignment's seed and kept only when verified by the solver as ``mechgrade check
  --variants`` verifies (:func:`mechgrade.grade.variants.variant_faults`; a refused draw is
  replaced by the next one). A problem without variants is one variant.
* a **vector** objective is one :class:`NumberItem` per component that is not zero in every
  variant (the component along each of the frame's unit vectors).
* a **symbolic** objective cannot be graded by a formula or numerical question: it is an
  :class:`EssayItem` (a text answer graded by mechgrade from the quiz's responses,
  :mod:`mechgrade.grade.quiz_responses`, whose ``mechgrade key`` it carries).

**Tolerance.** An LMS question holds one tolerance for every variant, relative or absolute;
mechgrade's is ``max(rel·|reference|, abs)`` per variant (vectors: ``rel`` times the
magnitude). It is written exactly when it is the same relative (or the same absolute)
tolerance for every variant; otherwise the strictest over the variants is written as an
absolute tolerance, so the LMS never accepts an answer mechgrade would refuse, and the item
says how much it was tightened.

**Units.** Canvas stores and shows formula answers with a fixed number of decimal places
(at most :data:`MAX_DECIMALS` here): a value below :data:`SMALLEST` would be shown as 0 or
with too few figures. The objective's unit is kept when every answer and its tolerance fit;
otherwise a smaller unit of the same quantity is chosen (``m`` -> ``mm`` -> ``um``,
``ft`` -> ``in``; :func:`display_unit`), and the question asks for the answer in it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

from ..errors import MechgradeError
from ..spec.model import ObjectiveKind
from ..units import si_factor
from .quiz_responses import key_marker
from .results import unit_text

SMALLEST = 0.01
"""The smallest nonzero answer (in the unit asked for) a question may have."""
MAX_DECIMALS = 4
"""Decimal places of answers and tolerances at most."""
MAX_VARIANTS = 500
_PREFIXABLE = {"m", "N", "J", "W", "Pa", "rad", "g", "s", "Hz"}
_PREFIXES = ("G", "M", "k", "c", "d", "m", "u", "\u00b5", "n")
_SMALLER = {"ft": ("in",), "kg": ("g", "mg")}


@dataclass(frozen=True)
class Variable:
    """A drawn given shown in the statement: a name safe in both LMSs, its unit, and the
    decimals its values need."""

    name: str
    given: str
    unit: str
    decimals: int


@dataclass(frozen=True)
class NumberItem:
    """A numerical question: ``text`` alternates plain text and :class:`Variable` references;
    ``values[i]`` are the variables' values and ``answers[i]`` the answer of variant ``i``
    (in ``unit``); the tolerance is ``relative`` (a ratio) or ``absolute`` (in ``unit``)."""

    key: str
    name: str
    text: tuple[str | Variable, ...]
    prompt: str
    unit: str
    points: float
    variables: tuple[Variable, ...]
    values: tuple[tuple[float, ...], ...]
    answers: tuple[float, ...]
    relative: float | None
    absolute: float | None
    decimals: int
    notes: tuple[str, ...] = ()


@dataclass(frozen=True)
class EssayItem:
    """A text question whose answer mechgrade grades from the quiz's responses."""

    key: str
    name: str
    text: str
    prompt: str
    points: float


@dataclass(frozen=True)
class LeftOut:
    key: str
    reason: str


@dataclass(frozen=True)
class QuestionBank:
    """Every question of an assignment, in objective order, and what could not be one."""

    assignment_id: str
    title: str
    items: tuple[NumberItem | EssayItem, ...]
    left_out: tuple[LeftOut, ...] = field(default=())
    variants: int = 1


def question_bank(plan, count: int) -> QuestionBank:
    """The questions of ``plan`` (an assignment's :class:`~mechgrade.grade.run.Plan`) with
    ``count`` verified variants of each problem that draws its givens (see module doc).
    Raises :class:`MechgradeError` when a problem has no verified variant."""
    from .variants import student_variants

    if not 1 <= count <= MAX_VARIANTS:
        raise MechgradeError(f"expected between 1 and {MAX_VARIANTS} variants, found {count}")
    assignment = plan.assignment
    items: list[NumberItem | EssayItem] = []
    left: list[LeftOut] = []
    for problem, solution in zip(plan.problems, plan.solutions):
        objectives = [o for o in plan.objectives if o.problem.id == problem.id]
        if not objectives:
            continue
        draws: list[tuple[Any, Any]] = [(None, solution)]
        if problem.variants is not None:
            ids = [f"question-{n}" for n in range(1, count + 1)]
            solved = student_variants(problem, assignment.variant_seed, ids, redraw=True)
            draws = [solved[i] for i in ids]
        variables = _variables(problem, [v for v, _ in draws])
        for planned in objectives:
            results = [_result(s, planned.objective.id) for _, s in draws]
            kind = results[0].kind
            if kind == ObjectiveKind.SYMBOLIC:
                items.append(_essay(problem, planned, results[0]))
                continue
            for label, values, scales in _components(results):
                made = _number(problem, planned, results[0], variables,
                               [v for v, _ in draws], label, values, scales)
                if isinstance(made, NumberItem):
                    items.append(made)
                else:
                    left.append(made)
            if kind == ObjectiveKind.VECTOR:
                for axis in _zero_components(results):
                    left.append(LeftOut(f"{planned.key} ({axis})", "zero in every variant"))
    return QuestionBank(assignment.id, assignment.title, tuple(items), tuple(left),
                        count if any(p.variants for p in plan.problems) else 1)


def _result(solution, objective_id: str):
    from .run import graded_result

    return graded_result(solution, objective_id)


def _variables(problem, variants) -> tuple[Variable, ...]:
    if problem.variants is None:
        return ()
    used: set[str] = set()
    out = []
    for draw in problem.variants.draws:
        name = _safe_name(draw.key, used)
        values = [g.value for v in variants for g in v.drawn if g.name == draw.key]
        out.append(Variable(name, draw.key, unit_text(draw.unit),
                            max((_decimals_of(x) for x in values), default=0)))
    return tuple(out)


def _safe_name(given: str, used: set[str]) -> str:
    """A variable name both LMSs take (letters, digits, ``_``; a letter first): ``theta'``
    becomes ``theta_d``, ``theta''`` ``theta_dd``.

    >>> _safe_name("theta''", set()), _safe_name("2x", set())
    ('theta_dd', 'v_2x')
    """
    name = re.sub(r"'+", lambda m: "_" + "d" * len(m[0]), given)
    name = re.sub(r"[^A-Za-z0-9_]", "_", name)
    if not name[:1].isalpha():
        name = f"v_{name}"
    base, n = name, 1
    while name in used:
        n += 1
        name = f"{base}_{n}"
    used.add(name)
    return name


def _decimals_of(value: float) -> int:
    text = f"{value:.10f}".rstrip("0").rstrip(".")
    return len(text.split(".")[1]) if "." in text else 0


def _components(results) -> list[tuple[str | None, list[float], list[float]]]:
    """The numbers a question asks, each with the scale its relative tolerance multiplies in
    every variant: the value (its size), or each component not zero in every variant
    (labelled by its axis; the vector's magnitude)."""
    first = results[0]
    if first.kind != ObjectiveKind.VECTOR:
        values = [float(r.value) for r in results]
        return [(None, values, [abs(v) for v in values])]
    sizes = [math.sqrt(sum(float(c) ** 2 for c in r.value)) for r in results]
    out: list[tuple[str | None, list[float], list[float]]] = []
    for i, axis in enumerate(_axes(first)):
        values = [float(r.value[i]) for r in results]
        if any(values):
            out.append((axis, values, sizes))
    return out


def _axes(result) -> list[str]:
    frame = result.frame or ""
    return [f"{axis} component in frame {frame}".strip() for axis in ("x", "y", "z")
            ][:len(result.value)]


def _zero_components(results) -> list[str]:
    first = results[0]
    return [axis for i, axis in enumerate(_axes(first))
            if not any(float(r.value[i]) for r in results)]


def _essay(problem, planned, result) -> EssayItem:
    from .variants import statement

    symbols = ", ".join(result.symbols)
    prompt = (f"{planned.objective.prompt} Type the expression as in mechgrade's answer "
              f"syntax{f', in the symbols {symbols}' if symbols else ''}. "
              f"{key_marker(planned.key)}")
    return EssayItem(planned.key, f"{problem.title}: {planned.objective.id}",
                     statement(problem), prompt, planned.max_points)


def _number(problem, planned, first, variables, variants, label, values, scale
            ) -> NumberItem | LeftOut:
    key = planned.key if label is None else f"{planned.key} ({label})"
    unit = unit_text(first.unit)
    chosen = display_unit(unit, values, [max(first.rel * s, first.abs) for s in scale])
    if chosen is None:
        return LeftOut(key, f"its answers or tolerance ({unit}) are too small for "
                            f"{MAX_DECIMALS} decimal places in any unit of the same quantity "
                            "mechgrade knows; give the objective a smaller unit")
    shown, factor = chosen
    answers = tuple(v * factor for v in values)
    limits = [max(first.rel * s, first.abs) * factor for s in scale]
    relative, absolute, notes = _tolerance(first.rel, first.abs * factor, answers, limits,
                                           label is not None)
    smallest = min(limits)
    decimals = max(0, min(MAX_DECIMALS, math.ceil(-math.log10(smallest)) + 1)) \
        if smallest > 0 else MAX_DECIMALS
    if shown != unit:
        notes = (f"asked in {shown}, not {unit}: some answers are too small to show in "
                 f"{unit} with {MAX_DECIMALS} decimal places", *notes)
    text = _text(problem, variables)
    ask = planned.objective.prompt if label is None else \
        f"{planned.objective.prompt} Give the {label}."
    return NumberItem(key, f"{problem.title}: {planned.objective.id}"
                      + (f" ({label})" if label else ""), text,
                      f"{ask} Answer in {shown}. {key_marker(planned.key)}", shown,
                      planned.max_points, variables,
                      tuple(tuple(_value(v, var.given) for var in variables) for v in variants)
                      if variables else ((),), answers, relative, absolute, decimals, notes)


def _value(variant, given: str) -> float:
    return next(g.value for g in variant.drawn if g.name == given)


def _tolerance(rel: float, abs_: float, answers, limits, vector: bool
               ) -> tuple[float | None, float | None, tuple[str, ...]]:
    """(relative, absolute, notes): exact when one relative or one absolute tolerance is
    mechgrade's for every variant, else the strictest as an absolute one."""
    if not vector and rel > 0 and all(abs_ <= rel * abs(a) for a in answers):
        return rel, None, ()
    if max(limits) - min(limits) <= 1e-12 * max(max(limits), 1e-300):
        return None, min(limits), ()
    ratio = max(limits) / min(limits) if min(limits) > 0 else math.inf
    note = (f"one tolerance for every variant: the strictest of mechgrade's, "
            f"{min(limits):.3g}, is written (mechgrade accepts up to {ratio:.3g} times more "
            "in some variants)")
    return None, min(limits), (note,)


def display_unit(unit: str, values, limits) -> tuple[str, float] | None:
    """The unit to ask an answer in, and the factor from ``unit`` to it: ``unit`` when every
    nonzero value is at least :data:`SMALLEST` and every tolerance at least
    ``10**-MAX_DECIMALS`` in it, else the first smaller unit where they are; ``None`` when
    none.

    >>> display_unit("m/s", [0.004, 0.006], [4e-5, 6e-5])
    ('mm/s', 1000.0)
    >>> display_unit("ft/s", [8.0], [0.08])
    ('ft/s', 1.0)
    """
    for candidate in [unit, *_smaller_units(unit)]:
        try:
            factor = si_factor(unit) / si_factor(candidate)
        except MechgradeError:
            continue
        if all(abs(v) * factor >= SMALLEST for v in values if v) and \
                all(limit * factor >= 10 ** -MAX_DECIMALS for limit in limits if limit):
            return candidate, factor
    return None


def _smaller_units(unit: str) -> list[str]:
    """Smaller units of the same quantity, largest first: SI prefixes on the first unit
    (``km/s`` -> ``m/s``, ``mm/s``, ``um/s``, ``nm/s``), or the next smaller customary unit
    (``ft`` -> ``in``).

    >>> _smaller_units("km/s"), _smaller_units("ft/s^2")
    (['m/s', 'mm/s', 'um/s', 'nm/s'], ['in/s^2'])
    """
    found = re.match(r"[A-Za-z\u00b5]+", unit)
    if not found:
        return []
    first, rest = found[0], unit[found.end():]
    if first in _SMALLER:
        return [f"{u}{rest}" for u in _SMALLER[first]]
    base = next((first[len(p):] for p in ("", *_PREFIXES) if first.startswith(p)
                 and first[len(p):] in _PREFIXABLE), None)
    if base is None:
        return []
    own = si_factor(first)
    return [f"{p}{base}{rest}" for p in ("", "m", "u", "n") if si_factor(f"{p}{base}") < own]


def _text(problem, variables) -> tuple[str | Variable, ...]:
    """The statement with each drawn given a variable (``{L}`` becomes ``[L] ft``), the
    problem's other givens written out; a drawn given the statement does not name is listed
    after it."""
    from ..spec.variants import PLACEHOLDER
    from .results import VariantGiven
    from ..expressions.syntax import to_text

    if problem.variants is None:
        from .variants import statement

        return (statement(problem),)
    by_given = {v.given: v for v in variables}
    fixed = {to_text(g.key.node): VariantGiven(problem.id, to_text(g.key.node), g.value,
                                               g.unit).text for g in problem.givens}
    parts: list[str | Variable] = []
    seen = set()
    last = 0
    for match in PLACEHOLDER.finditer(problem.statement):
        parts.append(problem.statement[last:match.start()])
        name = match.group(1).strip().replace(" ", "")
        if name in by_given:
            parts += [by_given[name], f" {by_given[name].unit}"]
            seen.add(name)
        else:
            parts.append(fixed[name])
        last = match.end()
    parts.append(problem.statement[last:])
    missing = [v for v in variables if v.given not in seen]
    if missing:
        parts.append("\nGiven:")
        for n, var in enumerate(missing):
            parts += [f"{',' if n else ''} {var.given} = ", var, f" {var.unit}"]
        parts.append(".")
    return tuple(p for p in parts if p != "")
