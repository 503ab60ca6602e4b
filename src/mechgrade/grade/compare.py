"""Judge one student answer against the reference: verdict, credit, diagnosis and feedback.

The rules follow the answer tests of mature systems (see ``docs/answers.md`` for the exact
statement and sources): STACK's NumRelative/NumAbsolute (``|s - t| <= rtol*|t|``), PrairieLearn's
``relabs`` and ``sigfig`` comparisons, STACK's NumSigFigs for written significant figures, and
WeBWorK's formula comparison at random test points (with STACK's ATAlgEquiv, sympy, only as a
bounded fallback).

>>> from mechgrade.solve.result import ObjectiveResult
>>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
>>> assess("98.5 ft/s^2", acc, GradingPolicy()).verdict
<Verdict.CORRECT: 'correct'>
>>> assess("30 m/s", acc, GradingPolicy()).feedback
'You gave a velocity ([length]/[time]); an acceleration ([length]/[time]²) was asked.'
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass, replace
from enum import Enum
from functools import cached_property, lru_cache
from typing import Sequence, TypeVar

import numpy as np

from ..errors import AnswerError, ExpressionError, MechgradeError
from ..expressions import syntax
from ..expressions.dimensions import DimensionError, Type, described, infer, scalar
from ..expressions.numeric import evaluate, reference_tree as _reference_tree
from ..expressions.syntax import Bin, Call, Name, Node
from ..solve.mutants import separating_rel
from ..solve.result import GeneratedMistake, MistakeValue, ObjectiveResult
from ..spec.model import ObjectiveKind
from ..tolerance import REFERENCE_ACCURACY, agree_at_points, within
from ..units import describe_dimension, dimension, from_si, judged_in, to_si
from .answers import (ExpressionAnswer, NumberAnswer, StudentAnswer, VectorAnswer, read_answer,
                      symbol_aliases)
from .diagnose import G_FT, G_SI, Candidates, Diagnosis, diagnose, trig_in_radians
from .policy import GradingPolicy, MissingUnit
from .results import Verdict

@dataclass(frozen=True)
class Assessment:
    """How one answer was judged. ``read_back`` is how mechgrade read the text (``None`` when
    it could not); ``feedback`` never reveals the reference value; ``unit`` is the unit a
    number or vector was written in when it is one of the objective's dimension (``None``
    otherwise), to show the reference in it."""

    verdict: Verdict
    credit: float
    diagnosis: str | None
    feedback: str
    read_back: str | None = None
    unit: str | None = None


class Judged:
    """What a judgement of several parts (a diagram's loads, a set of equations) says as a
    whole: its ``assessment``'s verdict and credit."""

    assessment: Assessment

    @property
    def verdict(self) -> Verdict:
        return self.assessment.verdict

    @property
    def credit(self) -> float:
        return self.assessment.credit


def missing() -> Assessment:
    return Assessment(Verdict.MISSING, 0.0, None, "No answer was given.", None)


def unreadable(reason: str) -> Assessment:
    end = "" if reason.endswith("?") else "."  # a reason may end by asking which reading
    return Assessment(Verdict.UNREADABLE, 0.0, None, f"Could not read the answer: {reason}{end}",
                      None)


def not_evaluated(reason: str, read_back: str | None = None) -> Assessment:
    return Assessment(Verdict.NOT_EVALUATED, 0.0, None,
                      f"This answer could not be evaluated ({reason}); it is not marked wrong.",
                      read_back)


# ---------------------------------------------------------------------------- entry point


def assess(text: str | None, result: ObjectiveResult,
           policy: GradingPolicy = GradingPolicy()) -> Assessment:
    """Read and judge ``text`` as an answer to ``result`` under ``policy``.

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> acc = ObjectiveResult("a", "scalar", "ft/s^2", 98.51)
    >>> assess("-98.5 ft/s^2", acc).diagnosis
    'sign error'
    >>> assess(None, acc).verdict, assess("__import__('os')", acc).verdict
    (<Verdict.MISSING: 'missing'>, <Verdict.UNREADABLE: 'unreadable'>)
    """
    if text is None or (isinstance(text, str) and not text.strip()):
        return missing()
    judged = _judged(text, result, policy)
    if judged is not None:
        kept = judged.get(text)
        if kept is not None:  # the same text again
            return kept
    assessment = _assess(text, result, policy)
    if judged is not None:
        if len(judged) >= MAX_JUDGED:
            judged.clear()
        judged[text] = assessment
    return assessment


def _judged(text: object, result: ObjectiveResult,
            policy: GradingPolicy) -> dict[str, Assessment] | None:
    """The judgements kept for answers to ``result`` under ``policy`` by their text: a
    symbolic objective's, with sample points (:class:`_Sampled`); ``None`` for any other."""
    if type(text) is not str or result.kind != ObjectiveKind.SYMBOLIC or not result.expr:
        return None
    try:
        sampled = _objective(result, policy)
    except MechgradeError:  # judging says why (:func:`_assess`)
        return None
    return None if sampled is None else sampled.judged


def _assess(text: str, result: ObjectiveResult, policy: GradingPolicy) -> Assessment:
    try:
        answer = read_answer(text, result)
    except AnswerError as exc:
        return unreadable(exc.message)
    try:
        # huge but readable values overflow to inf, which no tolerance accepts: no warnings
        with np.errstate(all="ignore"):
            assessment = _judge(answer, result, policy)
    except MechgradeError as exc:
        return not_evaluated(exc.message, answer.read_back())
    unit = _written_unit(answer, result)
    return replace(assessment, unit=unit) if unit else assessment


def _written_unit(answer: StudentAnswer, result: ObjectiveResult) -> str | None:
    """The unit a number or vector answer was written in, when it is one of the objective's
    dimension; ``None`` for an expression, an answer without a unit or of another dimension.

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> force = ObjectiveResult("F", "scalar", "N", 36.79)
    >>> [_written_unit(read_answer(t, force), force) for t in ("8.27 lbf", "36.8", "3 m")]
    ['lbf', None, None]
    """
    if result.kind == ObjectiveKind.SYMBOLIC or not isinstance(answer, (NumberAnswer,
                                                                        VectorAnswer)):
        return None
    if not answer.unit:
        return None
    try:
        return answer.unit if dimension(answer.unit) == dimension(result.unit) else None
    except MechgradeError:  # a unit pint cannot read shows nothing more
        return None


def _judge(answer: StudentAnswer, result: ObjectiveResult, policy: GradingPolicy) -> Assessment:
    if result.kind == ObjectiveKind.SYMBOLIC:
        return _judge_expression(answer, result, policy)
    # read_answer reads an expression for a symbolic objective only
    assert not isinstance(answer, ExpressionAnswer)
    if result.value is None:
        return not_evaluated("the reference answer is not available", answer.read_back())
    if result.kind == ObjectiveKind.VECTOR:
        return _judge_vector(answer, result, policy)
    return _judge_number(answer, result, policy)


# ---------------------------------------------------------------------------- numbers


def last_place(reference: float, figures: int) -> float:
    """The value of the ``figures``-th significant place of ``reference``.

    >>> last_place(98.51, 3), last_place(0.0, 2)
    (0.1, 0.1)
    """
    if reference == 0 or not math.isfinite(reference):
        return 10.0 ** (1 - figures)
    exponent = math.floor(math.log10(abs(reference))) - figures + 1
    return float(f"1e{exponent}")


def within_sig_figs(student: float, reference: float, figures: int, basis=None) -> bool:
    """Accurate to ``figures`` significant figures of ``basis`` (default: the reference): within
    half a unit of that last place (the :func:`within` test with that absolute tolerance).

    >>> within_sig_figs(98.5, 98.51, 3), within_sig_figs(98.4, 98.51, 3), within_sig_figs(98.55, 98.5, 3)
    (True, False, True)
    """
    basis = reference if basis is None else basis
    return within(student, reference, 0.0, 0.5 * last_place(basis, figures), scale=basis)


def _tolerance(result: ObjectiveResult, policy: GradingPolicy) -> tuple[float, float]:
    """The tolerance an answer is judged with, never tighter than the reference's own
    accuracy: no answer is wrong by the reference's last digits."""
    rel, abs_ = _stated_tolerance(result, policy)
    return max(rel, REFERENCE_ACCURACY), abs_


def _stated_tolerance(result: ObjectiveResult, policy: GradingPolicy) -> tuple[float, float]:
    rel = result.rel if policy.rel is None else policy.rel
    abs_ = result.abs if policy.abs is None else policy.abs
    if policy.separate_mistakes and result.generated_mistakes:
        separating = separating_rel(result)
        if separating is not None:
            rel = min(rel, separating)
    return float(rel), float(abs_)


def _describe_tolerance(result: ObjectiveResult, policy: GradingPolicy) -> str:
    if policy.sig_figs:
        return f"accurate to {policy.sig_figs} significant figures"
    rel, abs_ = _stated_tolerance(result, policy)
    parts = []
    if rel:
        parts.append(f"{rel * 100:g}%")
    if abs_:
        parts.append(f"{abs_:g} {result.unit}".strip())
    return "within " + (" or ".join(parts) if parts else "rounding error") + " of the expected value"


def _needs_unit(unit: str) -> bool:
    return str(dimension(unit)) != "dimensionless" or unit.strip() not in ("", "1")


@dataclass
class _Units:
    """The unit an answer is judged in and what the missing-unit rule costs."""

    unit: str
    factor: float = 1.0
    note: str = ""
    label: str | None = None


def _resolve_unit(answer_unit: str | None, result: ObjectiveResult, policy: GradingPolicy,
                  read_back: str) -> _Units | Assessment:
    if answer_unit is None:
        if not _needs_unit(result.unit):
            return _Units(result.unit)
        if policy.missing_unit == MissingUnit.REJECT:
            return Assessment(Verdict.INCORRECT, 0.0, "missing unit",
                              f"A unit is required (for example {_example_unit(result.unit)}).",
                              read_back)
        return _Units(result.unit, 1.0 - policy.missing_unit_deduction,
                      f" No unit was given; {_example_unit(result.unit)} was assumed.",
                      "missing unit")
    given, wanted = dimension(answer_unit), dimension(result.unit)
    if given != wanted:
        return Assessment(Verdict.INCORRECT, policy.credit_for("dimension"), "wrong dimension",
                          f"You gave {describe_dimension(given)}; "
                          f"{describe_dimension(wanted)} was asked.", read_back)
    return _Units(judged_in(answer_unit, result.unit))


def _example_unit(unit: str) -> str:
    from .answers import _pretty_unit
    return _pretty_unit(unit) or "a unit"


def _example_vector(unit: str) -> str:
    from .answers import _pretty_unit
    return f"(x, y, z) {_pretty_unit(unit)}".rstrip()


def _finish_correct(units: _Units, figures: list[tuple[int | None, int | None]],
                    policy: GradingPolicy, read_back: str, what: str) -> Assessment:
    credit, labels, notes = units.factor, [], units.note
    if units.label:
        labels.append(units.label)
    if policy.written_sig_figs:
        bad = [f for f in figures
               if not _figures_ok(f, policy.written_sig_figs, policy.written_sig_figs_strict)]
        if bad:
            credit *= 1.0 - policy.written_sig_figs_deduction
            labels.append("significant figures")
            written = bad[0][0] if policy.written_sig_figs_strict or bad[0][0] == bad[0][1] \
                else f"{bad[0][0]} to {bad[0][1]}"
            plural = "" if written == 1 else "s"
            shown = ("as an exact expression" if written is None
                     else f"to {written} significant figure{plural}")
            notes += (f" The value is right but written {shown}; "
                      f"{policy.written_sig_figs} were asked.")
    credit = max(0.0, min(1.0, credit))
    if credit >= 1.0:
        return Assessment(Verdict.CORRECT, 1.0, None, f"Correct{what}.{notes}", read_back)
    verdict = Verdict.PARTIAL if credit > 0 else Verdict.INCORRECT
    return Assessment(verdict, credit, "; ".join(labels),
                      f"The value is right{what}.{notes}".replace(". The value is right but",
                                                                  ", but"), read_back)


def _figures_ok(figures: tuple[int | None, int | None], n: int, strict: bool) -> bool:
    """Whether written figures meet the rule (``n`` figures, exactly if ``strict``); an exact
    expression (``pi/6``) has none."""
    lo, hi = figures
    if lo is None or hi is None:  # both or neither: a written number has a range
        return False
    if strict:
        return lo == n
    return lo <= n <= hi


def _judge_number(answer: NumberAnswer | VectorAnswer, result: ObjectiveResult,
                  policy: GradingPolicy) -> Assessment:
    value = result.value
    assert value is not None and not isinstance(value, tuple)  # _judge: a scalar's value
    reference = float(value)
    read_back = answer.read_back()
    if isinstance(answer, VectorAnswer):
        return _vector_for_scalar(answer, result, policy, read_back)
    units = _resolve_unit(answer.unit, result, policy, read_back)
    if isinstance(units, Assessment):
        return units
    student = from_si(to_si(answer.value, units.unit), result.unit)
    rel, abs_ = _tolerance(result, policy)
    if policy.sig_figs:
        reference_there = from_si(to_si(reference, result.unit), units.unit)
        ok = within_sig_figs(answer.value, reference_there, policy.sig_figs)
    else:
        ok = within(student, reference, rel, abs_)
    if ok:
        return _finish_correct(units, [(answer.sig_figs, answer.sig_figs_max)], policy,
                               read_back, "")
    if answer.degrees is not None:
        in_degrees = from_si(to_si(answer.degrees, units.unit), result.unit)
        found = _trig_in_radians(answer.text, result) if within(
            in_degrees, reference, rel, abs_) else None
        if found is not None:
            return _wrong(found, policy, units, "", read_back)
    close = _close(max(rel, 1e-3), abs_)
    found = diagnose(np.array([student]), np.array([reference]), close,
                     mistakes=_numeric_mistakes(result.mistakes, scalar=True),
                     generated=_numeric_mistakes(result.generated_mistakes, scalar=True),
                     plausible=result.plausible, exact=_exact(rel, abs_))
    return _wrong(found, policy, units,
                  f"Not {_describe_tolerance(result, policy)}.", read_back)


def _trig_in_radians(text: str, result: ObjectiveResult) -> Diagnosis | None:
    """The degrees hint (:func:`~mechgrade.grade.diagnose.trig_in_radians`) for a constant
    written ``text`` (``5*sin(30)``), naming its first trig call of a plain number."""
    reading = syntax.degree_reading(syntax.parse(text, attributes=False))
    return None if reading is None else trig_in_radians(syntax.to_text(reading[1]),
                                                        result.plausible)


def _close(rel: float, abs_: float):
    """:func:`within` as a closeness test for diagnoses: a number or vector (up to three
    components, scaled by its magnitude) or values at sample points (each by its own size)."""
    def close(s: np.ndarray, t: np.ndarray) -> bool:
        if s.shape != t.shape:
            return False
        with np.errstate(all="ignore"):
            scale = float(np.linalg.norm(t)) if t.size <= 3 else None
        return within(s, t, rel, abs_, scale=scale)
    return close


COINCIDENCE_SHARE = 0.25
"""The share of the tolerance within which a numeric coincidence (a factor of 2 or π, a unit
slip) is named: a ratio 2.016 is inside a 1 % tolerance of 2 but is not a factor of 2."""


def _exact(rel: float, abs_: float):
    """The closeness a numeric coincidence must meet (:data:`COINCIDENCE_SHARE` of the
    judging tolerance)."""
    return _close(COINCIDENCE_SHARE * max(rel, 1e-3), COINCIDENCE_SHARE * abs_)


def _wrong(found: Diagnosis | None, policy: GradingPolicy, units: _Units, summary: str,
           read_back: str) -> Assessment:
    if found is None:
        return Assessment(Verdict.INCORRECT, 0.0, None, summary + units.note, read_back)
    # two families that fit equally: the student has the benefit of the better credit
    credit = found.credit if found.credit is not None else max(
        policy.credit_for(code) for code in (found.code, found.also) if code is not None)
    credit = max(0.0, min(1.0, credit * units.factor))
    verdict = Verdict.PARTIAL if credit > 0 else Verdict.INCORRECT
    message = found.message if found.message.endswith((".", "?", "!")) else found.message + "."
    # the diagnosis says more than the summary: it alone is the feedback
    return Assessment(verdict, credit, found.label, f"{message}{units.note}", read_back)


_Mistake = TypeVar("_Mistake", MistakeValue, GeneratedMistake)


def _numeric_mistakes(mistakes: Sequence[_Mistake],
                      scalar: bool) -> list[tuple[_Mistake, np.ndarray | None]]:
    """Each mistake with its value as an array, or ``None`` where it has no value of the
    objective's shape."""
    out: list[tuple[_Mistake, np.ndarray | None]] = []
    for mistake in mistakes:
        value = mistake.value
        if value is None:
            out.append((mistake, None))
        elif scalar and isinstance(value, (int, float)):
            out.append((mistake, np.array([float(value)])))
        elif not scalar and isinstance(value, (tuple, list)) and len(value) == 3:
            out.append((mistake, np.array([float(v) for v in value])))
        else:
            out.append((mistake, None))
    return out


def _vector_for_scalar(answer: VectorAnswer, result: ObjectiveResult, policy: GradingPolicy,
                       read_back: str) -> Assessment:
    """A vector for a scalar objective: a lone k component is the planar signed scalar."""
    x, y, z = answer.components
    if x == 0 and y == 0 and answer.frame is None:
        planar = NumberAnswer(z, answer.unit, *answer.sig_figs[2], answer.texts[2])
        judged = _judge_number(planar, result, policy)
        return Assessment(judged.verdict, judged.credit, judged.diagnosis, judged.feedback,
                          read_back)
    units = _resolve_unit(answer.unit, result, policy, read_back)
    magnitude = math.sqrt(x * x + y * y + z * z)
    if not isinstance(units, Assessment):
        rel, abs_ = _tolerance(result, policy)
        size = from_si(to_si(magnitude, units.unit), result.unit)
        value = result.value
        assert value is not None and not isinstance(value, tuple)  # _judge: a scalar's value
        if within(size, abs(float(value)), rel, abs_):
            return Assessment(Verdict.INCORRECT, policy.credit_for("shape"), "vector for a scalar",
                              "A single value was asked, not a vector (its magnitude is "
                              "right).", read_back)
    return Assessment(Verdict.INCORRECT, policy.credit_for("shape"), "vector for a scalar",
                      "A single value was asked, not a vector.", read_back)


# ---------------------------------------------------------------------------- vectors


def _judge_vector(answer: NumberAnswer | VectorAnswer, result: ObjectiveResult,
                  policy: GradingPolicy) -> Assessment:
    value = result.value
    assert value is not None and not isinstance(value, (int, float))  # _judge: components
    reference = np.array([float(v) for v in value])
    read_back = answer.read_back()
    if isinstance(answer, NumberAnswer):
        if reference[0] == 0 and reference[1] == 0:  # planar: a signed scalar is its k part
            answer = VectorAnswer((0.0, 0.0, answer.value), answer.unit, None,
                                  ((None, None), (None, None),
                                   (answer.sig_figs, answer.sig_figs_max)),
                                  ("0", "0", answer.text))
        else:
            return _scalar_for_vector(answer, reference, result, policy, read_back)
    units = _resolve_unit(answer.unit, result, policy, read_back)
    if isinstance(units, Assessment):
        return units
    factor = to_si(1.0, units.unit) / to_si(1.0, result.unit)
    student = np.array(answer.components) * factor
    rel, abs_ = _tolerance(result, policy)
    if answer.frame is not None and result.frame is not None and answer.frame != result.frame:
        same_size = within(float(np.linalg.norm(student)), float(np.linalg.norm(reference)),
                           rel, abs_)
        return Assessment(Verdict.INCORRECT, policy.credit_for("frame"), "wrong frame",
                          f"Your components are along {answer.frame}'s unit vectors; give them "
                          f"along {result.frame}'s" + (" (the magnitude is right)." if same_size
                                                       else "."), read_back)
    sig_figs = policy.sig_figs
    components = answer.components
    if sig_figs:
        magnitude_there = float(np.linalg.norm(reference)) / factor
        tiny = last_place(magnitude_there, sig_figs)

        def ok(i: int) -> bool:
            there = reference[i] / factor
            basis = there if abs(there) >= tiny else magnitude_there
            return within_sig_figs(components[i], there, sig_figs, basis)
    else:
        magnitude = float(np.linalg.norm(reference))

        def ok(i: int) -> bool:
            return within(student[i], reference[i], rel, abs_, scale=magnitude)
    wrong = [axis for i, axis in enumerate("xyz") if not ok(i)]
    if not wrong:
        figures = [f for f, v in zip(answer.sig_figs, answer.components) if v != 0]
        return _finish_correct(units, figures, policy, read_back, "")
    if answer.degrees is not None:
        in_degrees = np.array(answer.degrees) * factor
        if all(within(in_degrees[i], reference[i], rel, abs_, scale=float(np.linalg.norm(
                reference))) for i in range(3)):
            trig = next(t for t, v, d in zip(answer.texts, answer.components, answer.degrees)
                        if v != d)
            found = _trig_in_radians(trig, result)
            if found is not None:
                return _wrong(found, policy, units, "", read_back)
    close = _close(max(rel, 1e-3), abs_)
    found = diagnose(student, reference, close, kind=ObjectiveKind.VECTOR,
                     mistakes=_numeric_mistakes(result.mistakes, scalar=False),
                     generated=_numeric_mistakes(result.generated_mistakes, scalar=False),
                     plausible=result.plausible, exact=_exact(rel, abs_))
    # a planar answer's zero z is no news
    right = [axis for i, axis in enumerate("xyz") if axis not in wrong
             and not (i == 2 and reference[2] == 0 and student[2] == 0)]
    summary = (f"The {_listing(wrong)} component{'s are' if len(wrong) > 1 else ' is'} not "
               f"{_describe_tolerance(result, policy)}"
               + (f" ({_listing(right)} {'are' if len(right) > 1 else 'is'} right)."
                  if right else "."))
    return _wrong(found, policy, units, summary, read_back)


def _listing(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def _scalar_for_vector(answer: NumberAnswer, reference: np.ndarray, result: ObjectiveResult,
                       policy: GradingPolicy, read_back: str) -> Assessment:
    units = _resolve_unit(answer.unit, result, policy, read_back)
    hint = ""
    if not isinstance(units, Assessment):
        rel, abs_ = _tolerance(result, policy)
        size = from_si(to_si(answer.value, units.unit), result.unit)
        if within(abs(size), float(np.linalg.norm(reference)), rel, abs_):
            hint = " (your value is the right magnitude)"
    frame = f"frame {result.frame}" if result.frame else "the frame"
    return Assessment(Verdict.INCORRECT, policy.credit_for("shape"), "scalar for a vector",
                      f"A vector was asked: give its components along {frame}'s unit vectors, "
                      f"such as '{_example_vector(result.unit)}'{hint}.", read_back)


# ---------------------------------------------------------------------------- expressions


def _signed_by_reference(node: Node) -> set[str]:
    """Symbols the reference treats as possibly negative: inside ``abs``/``sign``, or raised
    to an even power under a root (``sqrt(x**2)``). The solver's sympy drops such forms for
    symbols declared positive, so they mark a signed symbol (a coordinate such as ``x``)."""
    signed: set[str] = set()
    for part in syntax.walk(node):
        if isinstance(part, Call) and part.func in ("abs", "sign"):
            signed |= syntax.names(part)
        root = None
        if isinstance(part, Call) and part.func == "sqrt":
            root = part.args[0]
        elif isinstance(part, Bin) and part.op == "**":
            exponent = syntax.constant_value(part.right)
            if exponent is not None and exponent != int(exponent):
                root = part.left
        if root is None:
            continue
        for inner in syntax.walk(root):
            if isinstance(inner, Bin) and inner.op == "**" and isinstance(inner.left, Name):
                exponent = syntax.constant_value(inner.right)
                if exponent is not None and exponent % 2 == 0:
                    signed.add(inner.left.id)
    return signed


class Domain(Enum):
    """Where a symbol of a symbolic answer is sampled (see :func:`sample_points`)."""

    ANGLE = "angle"
    SIGNED = "signed"  # what the solver says may be negative, rates, signed in the reference
    POSITIVE = "positive"


def _symbol_domains(result: ObjectiveResult) -> dict[str, Domain]:
    """Each symbol's :class:`Domain`."""
    aliases = symbol_aliases(tuple(result.symbols))
    derivatives = {target for key, target in aliases.items() if isinstance(key, tuple)}
    signed = _signed_by_reference(_reference_tree(result.expr, tuple(result.symbols))) \
        if result.expr else set()
    signed |= {s for s, may in zip(result.symbols, result.symbol_signed) if may}
    kinds = {}
    units = dict(zip(result.symbols, result.symbol_units))
    for symbol in result.symbols:
        unit = units.get(symbol, "")
        dim = str(dimension(unit)) if unit else "dimensionless"
        if dim == "dimensionless" and any(w in unit for w in ("rad", "deg")):
            kinds[symbol] = Domain.ANGLE
        elif symbol in derivatives or symbol in signed or dim in ("1 / [time]",
                                                                 "1 / [time] ** 2"):
            kinds[symbol] = Domain.SIGNED
        else:
            kinds[symbol] = Domain.POSITIVE
    return kinds


def sample_points(result: ObjectiveResult, count: int, seed: int = 0) -> dict[str, np.ndarray]:
    """Seeded random values for each symbol over its domain.

    Angles (symbols in rad or deg) lie in 0.1 to 1.45 rad. Rates (symbols in 1/s or 1/s², or
    derivatives such as ``thetad``) and symbols the reference treats as signed (inside ``abs``
    or ``sign``, or squared under a root: ``sqrt(x**2)``) are signed, 0.5 to 2.5 in size;
    other quantities (lengths, masses, times) are positive, 0.5 to 2.5. The seed depends on the
    objective, so runs are reproducible.

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> r = ObjectiveResult("w", "symbolic", "rad/s", expr="thetad", symbols=("L", "thetad"),
    ...                     symbol_units=("m", "rad/s"))
    >>> points = sample_points(r, 5)
    >>> bool((points["L"] > 0).all()), sorted(points)
    (True, ['E', 'L', 'thetad'])
    """
    digest = zlib.crc32(f"{result.id}|{result.expr}|{seed}".encode("utf-8", "replace"))
    rng = np.random.default_rng(digest)
    env = {"E": np.full(count, math.e)}
    for symbol, kind in _symbol_domains(result).items():
        if kind is Domain.ANGLE:
            env[symbol] = rng.uniform(0.1, 1.45, count)
        elif kind is Domain.SIGNED:
            env[symbol] = rng.uniform(0.5, 2.5, count) * rng.choice([-1.0, 1.0], count)
        else:
            env[symbol] = rng.uniform(0.5, 2.5, count)
    return _with_instant_signs(result, env)


def _with_instant_signs(result: ObjectiveResult, env: dict[str, np.ndarray]
                        ) -> dict[str, np.ndarray]:
    """``env`` with each symbol the reference takes only through its sign (unchanged when
    the symbol is scaled: ``g*(sin(beta) - mu_k*xd*cos(beta)/Abs(xd))``) given the sign it
    has at the instant (``result.symbol_signs``): the problem states which way the block
    slides, and an answer written for that sense is right. Friction pointing the other way
    stays wrong."""
    signs = dict(zip(result.symbols, result.symbol_signs))
    if not result.expr or not any(signs.values()):
        return env
    try:
        node = _reference_tree(result.expr, tuple(result.symbols))
        base = evaluate(node, env)
    except (ExpressionError, KeyError):
        return env
    out = dict(env)
    for symbol, sign in signs.items():
        if not sign or symbol not in env:
            continue
        scaled = evaluate(node, {**env, symbol: env[symbol] * 1.7})
        flipped = evaluate(node, {**env, symbol: -env[symbol]})
        both = np.isfinite(base) & np.isfinite(scaled) & np.isfinite(flipped)
        if both.sum() >= MIN_VALID_POINTS and np.allclose(scaled[both], base[both],
                                                         rtol=1e-9, atol=1e-12) \
                and not np.allclose(flipped[both], base[both], rtol=1e-9, atol=1e-12):
            out[symbol] = sign * np.abs(env[symbol])
    return out


MIN_VALID_POINTS = 3


def _judge_expression(answer: StudentAnswer, result: ObjectiveResult,
                      policy: GradingPolicy) -> Assessment:
    assert isinstance(answer, ExpressionAnswer)
    read_back = answer.read_back()
    if not result.expr:
        return not_evaluated("the reference expression is not available", read_back)
    sampled = _objective(result, policy)
    if sampled is None:
        reference_node = _reference_tree(result.expr, tuple(result.symbols))
        confirmed = _sympy_equivalent(answer.node, reference_node, result)
        if confirmed is True:
            return Assessment(Verdict.CORRECT, 1.0, None, "Correct.", read_back)
        return not_evaluated("the reference is undefined at the sample points", read_back)
    return _judge_sampled(answer, result, policy, sampled)


MAX_JUDGED = 1024
"""Most answers kept judged per objective, by their text (:func:`assess`): a class writes
the same answer many times. Only the text and its assessment are kept, not the answer's tree:
kept trees live long enough for the collector's full passes to walk them again and again
(every answer written differently, in-process: ~80 µs an answer with trees kept, ~68 without)."""


def _judge_sampled(answer: ExpressionAnswer, result: ObjectiveResult, policy: GradingPolicy,
                   sampled: _Sampled) -> Assessment:
    read_back = answer.read_back()
    env, reference = sampled.env, sampled.reference
    student = evaluate(answer.node, env)
    if sampled.close(student, reference):
        return Assessment(Verdict.CORRECT, 1.0, None, "Correct.", read_back)
    found = diagnose(student, reference, sampled.loose, kind=ObjectiveKind.SYMBOLIC,
                     mistakes=sampled.mistakes, generated=sampled.generated,
                     plausible=result.plausible)
    if found is None:
        reference_node = _reference_tree(result.expr, tuple(result.symbols))
        found = _number_for_g(answer.node, reference_node, result, env, student, sampled.loose)
    if found is None:
        found = _dimension_diagnosis(answer.node, result)
    return _wrong(found, policy, _Units(result.unit),
                  "Not equivalent to the expected expression.", read_back)


class _Sampled:
    """What judging any answer to one symbolic objective under one policy needs: the sample
    points, the reference's values there, the equivalence test (``close``), the looser test
    of diagnoses (``loose``: they allow typed constants such as 9.81 for g, 1 %, unlike the
    equivalence test itself) and, once an answer is wrong, each mistake's values there. Worked
    out once per objective (:func:`_objective`): a class's answers go to few objectives.
    ``judged`` keeps each answer's judgement by its text (:func:`assess`)."""

    def __init__(self, result: ObjectiveResult, policy: GradingPolicy,
                 env: dict[str, np.ndarray], reference: np.ndarray):
        self._result, self._policy = result, policy
        self.env, self.reference = env, reference
        self.close = agree_at_points(policy.symbolic_rel, reference)
        self.loose = agree_at_points(max(policy.symbolic_rel, 0.01), reference)
        self.judged: dict[str, Assessment] = {}

    @cached_property
    def mistakes(self) -> list[tuple[MistakeValue, np.ndarray | None]]:
        return self._usable(self._result.mistakes)

    @cached_property
    def generated(self) -> Candidates:
        # diagnose's exact test is its close one, self.loose
        return Candidates(self._usable(self._result.generated_mistakes), self.reference,
                          self.loose)

    def _usable(self, mistakes):
        """Each mistake with its values, only those defined and finite at every sample point:
        :func:`~.diagnose.diagnose` passes over any other, so they are left out once here
        rather than looked at for every wrong answer."""
        out = []
        for mistake in mistakes:
            values = _sampled_mistake(mistake.expr, self._result, self._policy)
            if values is not None and values.shape == self.reference.shape \
                    and np.isfinite(values).all():
                out.append((mistake, values))
        return out


_OBJECTIVES: dict[tuple[int, int], tuple[ObjectiveResult, GradingPolicy, _Sampled | None]] = {}
MAX_OBJECTIVES = 256


def _objective(result: ObjectiveResult, policy: GradingPolicy) -> _Sampled | None:
    """The :class:`_Sampled` of ``result`` under ``policy`` (``None`` when fewer than
    :data:`MIN_VALID_POINTS` sample points are defined). Found by the objects' identity (the
    same objects judge every answer of a class; hashing a result costs more than judging a
    right answer), the objects kept with it so an identity is never reused while kept."""
    key = (id(result), id(policy))
    kept = _OBJECTIVES.get(key)
    if kept is not None and kept[0] is result and kept[1] is policy:
        return kept[2]
    sampled = _sampled(result, policy.symbolic_points, policy.seed)
    out = None if sampled is None else _Sampled(result, policy, *sampled)
    if len(_OBJECTIVES) >= MAX_OBJECTIVES:
        _OBJECTIVES.clear()
    _OBJECTIVES[key] = (result, policy, out)
    return out


def _number_for_g(node: Node, reference_node: Node, result: ObjectiveResult, env,
                  student: np.ndarray, close) -> Diagnosis | None:
    """An expression with 9.81 (or 32.2) typed where the symbol g was asked: it matches the
    reference evaluated with g at standard gravity, in m/s² or ft/s².

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> eom = ObjectiveResult("eom", "symbolic", "rad/s^2", expr="-3*g*sin(theta)/(2*L)",
    ...                       symbols=("g", "L", "theta"), symbol_units=("m/s^2", "m", "rad"))
    >>> assess("-3*9.81*sin(theta)/(2*L)", eom).diagnosis
    'number typed for g'
    """
    if "g" not in result.symbols or "g" in syntax.names(node):
        return None
    for gravity in (G_SI, G_FT):
        there = evaluate(reference_node, {**env, "g": np.full_like(env["g"], gravity)})
        if close(student, there):
            return Diagnosis("g_number", "number typed for g",
                             "Your expression has a number where the symbol g was asked: "
                             "write g.")
    return None


def _sampled(result: ObjectiveResult, wanted: int, seed: int):
    """The sample points of ``result`` and the reference's values there: ``wanted`` points
    where the reference is defined (of ``4 * wanted`` drawn), or ``None`` when fewer than
    :data:`MIN_VALID_POINTS` are. The same for every answer to the objective, so kept per
    objective (a worker judges many answers to few objectives)."""
    return _sampled_cached(result.id, result.expr, tuple(result.symbols),
                           tuple(result.symbol_units), tuple(result.symbol_signed),
                           tuple(result.symbol_signs), wanted, seed)


@lru_cache(maxsize=256)
def _sampled_cached(oid, expr, symbols, units, signed, signs, wanted, seed):
    result = ObjectiveResult(oid, ObjectiveKind.SYMBOLIC, "", expr=expr, symbols=symbols, symbol_units=units,
                             symbol_signed=signed, symbol_signs=signs)
    env = sample_points(result, 4 * wanted, seed)
    reference = evaluate(_reference_tree(expr, symbols), env)
    valid = np.isfinite(reference)
    if int(valid.sum()) < MIN_VALID_POINTS:
        return None
    keep = np.flatnonzero(valid)[:wanted]
    env = {name: values[keep] for name, values in env.items()}
    for values in env.values():
        values.flags.writeable = False
    reference = np.array(reference[keep])
    reference.flags.writeable = False
    return env, reference


def _sampled_mistake(expr: str | None, result: ObjectiveResult, policy: GradingPolicy):
    """A mistaken expression's values at the sample points of ``result`` (``None`` when it
    has none or cannot be evaluated there)."""
    if not expr:
        return None
    return _sampled_mistake_cached(expr, result.id, result.expr, tuple(result.symbols),
                                   tuple(result.symbol_units), tuple(result.symbol_signed),
                                   tuple(result.symbol_signs), policy.symbolic_points,
                                   policy.seed)


@lru_cache(maxsize=1024)
def _sampled_mistake_cached(expr, oid, reference, symbols, units, signed, signs, wanted, seed):
    sampled = _sampled_cached(oid, reference, symbols, units, signed, signs, wanted, seed)
    try:
        values = evaluate(_reference_tree(expr, symbols), sampled[0])
    except (ExpressionError, KeyError):
        return None
    if isinstance(values, np.ndarray):
        values.flags.writeable = False
    return values


SYMPY_MAX_NODES = 60


def _sympy_equivalent(student: Node, reference: Node, result: ObjectiveResult) -> bool | None:
    """ATAlgEquiv-style confirmation, only for small trees (``None``: not attempted/unknown)."""
    if sum(1 for _ in syntax.walk(student)) > SYMPY_MAX_NODES or \
            sum(1 for _ in syntax.walk(reference)) > SYMPY_MAX_NODES:
        return None
    import sympy

    from ..expressions.build import to_sympy
    kinds = _symbol_domains(result)
    table = {s: sympy.Symbol(s, positive=kinds[s] is not Domain.SIGNED, real=True)
             for s in result.symbols}
    table["E"] = sympy.E

    def resolve(node):
        return table[node.id]
    try:
        difference = to_sympy(student, resolve) - to_sympy(reference, resolve)
        return bool(sympy.simplify(difference) == 0) or None
    except (ExpressionError, KeyError, TypeError, ValueError, ZeroDivisionError):
        return None


# ---------------------------------------------------------------------------- dimensions


class DimensionMismatch(Exception):
    """An expression combines quantities of different dimensions (the message says where)."""


def expression_dimension(node: Node, units: dict[str, str]):
    """The dimension of an expression whose names have the given units (the rules of
    :func:`mechgrade.expressions.dimensions.infer`, worded for the student).

    >>> str(expression_dimension(syntax.parse("L*thetad^2"), {"L": "m", "thetad": "rad/s"}))
    '[length] / [time] ** 2'
    >>> expression_dimension(syntax.parse("L + thetad"), {"L": "m", "thetad": "rad/s"})
    Traceback (most recent call last):
    ...
    mechgrade.grade.compare.DimensionMismatch: adds a length ([length]) to an angular velocity or rate (1/[time])
    """
    def leaf(leaf: Node) -> Type:  # Euler's E, and anything not a symbol: a pure number
        return scalar(units.get(leaf.id, "") if isinstance(leaf, Name) and leaf.id != "E" else "")

    try:
        return infer(node, leaf).dim
    except DimensionError as exc:
        raise DimensionMismatch(exc.student) from None


def _dimension_diagnosis(node: Node, result: ObjectiveResult) -> Diagnosis | None:
    units = dict(zip(result.symbols, result.symbol_units))
    try:
        given = expression_dimension(node, units)
    except DimensionMismatch as exc:
        return Diagnosis("dimension", "inconsistent dimensions", f"Your expression {exc}.")
    wanted = dimension(result.unit)
    if given != wanted:
        return Diagnosis("dimension", "wrong dimension",
                         f"Your expression is {described(given)}; "
                         f"{described(wanted)} was asked.")
    return None

