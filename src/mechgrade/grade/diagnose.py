"""Name the likely mistake behind a wrong answer, from the reference alone or the author's list.

Diagnoses work on plain arrays, so one routine serves numbers (one value), vectors (three
components) and expressions (values at the sample points): the student's values are compared
with transformed reference values using the same closeness test that judged the answer.

Author-declared mistakes (``result.mistakes``) are tried first and carry their own message and
credit; then the mistakes the solver generated from the model (``result.generated_mistakes``:
the nearest one the answer matches, if it is nearer than the reference); then sign, factor and
unit-slip diagnoses, those that need something in the model (a factor of g needs a g) only when
the model makes them plausible; then, for vectors, swapped components and
right-magnitude/wrong-direction.

>>> import numpy as np
>>> close = lambda s, t: bool(np.all(np.abs(s - t) <= 0.01 * np.abs(t)))
>>> diagnose(np.array([-98.5]), np.array([98.51]), close).label
'sign error'
>>> diagnose(np.array([5644.0]), np.array([98.51]), close).label
'degrees used as radians'
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Callable, Iterable, Iterator, Sequence

import numpy as np

from ..spec.mistake_codes import BRANCH_CODES, DYNAMICS_CODES, GIVEN_CODES, MODEL_CODES
from ..spec.model import ObjectiveKind
from ..solve.result import GeneratedMistake, MistakeValue
from ..tolerance import AgreeAtPoints, AgreeingRows

Close = Callable[[np.ndarray, np.ndarray], bool]

G_SI = 9.80665
G_FT = G_SI / 0.3048


@dataclass(frozen=True)
class Diagnosis:
    """A named mistake: ``code`` for partial-credit settings, ``label`` for results, ``message``
    for the student; ``credit`` is set only for author-declared mistakes."""

    code: str
    label: str
    message: str
    credit: float | None = None
    also: str | None = None  # a second family that fits as well (its code)


# (code, label, message, factors): the student's value is factor * reference.
_FACTORS: tuple[tuple[str, str, str, tuple[float, ...]], ...] = (
    ("sign", "sign error", "Your answer has the wrong sign.", (-1.0,)),
    ("factor_2", "factor of 2", "Your answer is off by a factor of 2.", (2.0, 0.5)),
    ("deg_as_rad", "degrees used as radians",
     "Your answer is 180/π times too large: were degrees used where radians were needed?",
     (180 / math.pi,)),
    ("rad_as_deg", "radians used as degrees",
     "Your answer is π/180 times too small: were radians used where degrees were needed?",
     (math.pi / 180,)),
    ("pi", "factor of π", "Your answer is off by a factor of π.", (math.pi, 1 / math.pi)),
    ("rev_rad", "unit slip (revolutions vs radians)",
     "Your answer is off by a factor of 2π: revolutions (or Hz) mixed with radians?",
     (2 * math.pi, 1 / (2 * math.pi))),
    ("rpm_rad", "unit slip (rpm vs rad/s)",
     "Your answer is off by 60/(2π) ≈ 9.55: rpm mixed with rad/s?",
     (60 / (2 * math.pi), 2 * math.pi / 60)),
    ("g", "factor of g",
     "Your answer is g times too large: weight used for mass, or g applied twice?",
     (G_SI, G_FT)),
    # g times too small: m written for the weight m g (a force), or a force divided by the
    # weight m g for the mass (an acceleration)
    ("g", "factor of g", "Your answer is g times too small: mass used for weight (g left out), "
     "or weight used for mass?", (1 / G_SI, 1 / G_FT)),
    ("cm_m", "unit slip (cm vs m)", "Your answer is off by a factor of 100: cm mixed with m?",
     (100.0, 0.01)),
    ("mm_m", "unit slip (mm vs m)", "Your answer is off by a factor of 1000: mm mixed with m?",
     (1000.0, 0.001)),
    ("ft_m", "unit slip (ft vs m)",
     "Your answer is off by a factor of 3.28: feet mixed with metres?", (1 / 0.3048, 0.3048)),
    ("in_ft", "unit slip (in vs ft)",
     "Your answer is off by a factor of 12: inches mixed with feet?", (12.0, 1 / 12)),
    ("min_s", "unit slip (per minute vs per second)",
     "Your answer is off by a factor of 60: rpm (per minute) mixed with Hz or rev/s (per "
     "second)?", (60.0, 1 / 60)),
    # 1 hp is 550 ft·lbf/s; 746 is its value in watts
    ("hp_746", "unit slip (1 hp taken as 746 ft·lbf/s)",
     "Your answer is off by 746/550: 1 hp is 746 W but 550 ft·lbf/s; divide ft·lbf/s by 550.",
     (550 / 746, 746 / 550)),
)

_ALL_FACTORS = np.array([factor for *_, factors in _FACTORS for factor in factors])
FACTOR_CODES = tuple(dict.fromkeys(code for code, *_ in _FACTORS))
VECTOR_CODES = ("swapped", "direction", "magnitude")
GENERATED_CODES = MODEL_CODES + DYNAMICS_CODES + GIVEN_CODES + BRANCH_CODES
CODES = ("mistake",) + FACTOR_CODES + VECTOR_CODES + GENERATED_CODES + (
    "dimension", "g_number", "frame", "missing_unit", "sig_figs", "shape", "trig_radians")
"""Every diagnosis code (keys for :attr:`mechgrade.grade.policy.GradingPolicy.partial_credit`)."""

_AXES = "xyz"


def diagnose(student: np.ndarray, reference: np.ndarray, close: Close, *,
             kind: ObjectiveKind = ObjectiveKind.SCALAR,
             mistakes: Sequence[tuple[MistakeValue, np.ndarray | None]] = (),
             generated: Sequence[tuple[GeneratedMistake, np.ndarray | None]] | Candidates = (),
             plausible: frozenset[str] | None = None,
             exact: Close | None = None) -> Diagnosis | None:
    """The first diagnosis that explains ``student`` (already known not to match ``reference``).

    ``close(s, t)`` is the judging test; ``exact`` the tighter one a numeric coincidence (a
    factor, a unit slip) must meet to be named (``None``: ``close``), since a ratio that is
    only near a factor names a mistake the student did not make; ``mistakes`` pairs each author-declared mistake with its
    values in the same form as ``reference`` (``None`` when it cannot be evaluated), and
    ``generated`` each generated mistake likewise (or their :class:`Candidates` for the
    exact test, kept by a caller that tries many answers against one reference); ``plausible`` names the model-dependent
    slips (:data:`MODEL_SLIPS`) the model makes plausible (``None``: all of them).

    >>> import numpy as np
    >>> close = lambda s, t: bool(np.all(np.abs(s - t) <= 0.01 * np.linalg.norm(t)))
    >>> vector = ObjectiveKind.VECTOR
    >>> diagnose(np.array([-40.0, -66, 0]), np.array([-66.0, -40, 0]), close, kind=vector).label
    'swapped components'
    >>> diagnose(np.array([66.0, -40, 0]), np.array([-66.0, -40, 0]), close, kind=vector).label
    'wrong direction'
    """
    student = np.asarray(student, dtype=float)
    reference = np.asarray(reference, dtype=float)
    if student.shape != reference.shape or not np.isfinite(student).all():
        return None
    for mistake, values in mistakes:
        if values is None:
            continue
        values = np.asarray(values, dtype=float)
        if values.shape == reference.shape and np.isfinite(values).all() \
                and close(student, values):
            return Diagnosis("mistake", mistake.message, mistake.message, mistake.credit)
    # a mistaken value is matched on the reference's scale when it is a zero there (within
    # the exact test)
    zero = close if exact is None else exact
    candidates = generated if isinstance(generated, Candidates) and generated.zero is zero \
        else Candidates(generated, reference, zero)
    found = _generated(student, reference, close, candidates, plausible)
    if found is not None:
        if exact is None:
            return found  # a factor outweighs a generated mistake only under an exact test
        # a family that only comes near the answer explains it worse than a factor the
        # answer has ten times more nearly (2π: revolutions for radians)
        factor = _factor(student, reference, exact, plausible)
        if factor is not None and _generated(
                student, reference, exact, candidates, plausible) is None:
            near = min(_norm(student - np.asarray(v, dtype=float))
                       for _, v in generated if v is not None
                       and np.shape(v) == reference.shape and close(student, np.asarray(v)))
            if factor[1] <= 0.1 * near:
                return factor[0]
        return found
    factor = _factor(student, reference, zero, plausible, candidates)
    if factor is not None:
        return factor[0]
    if kind == ObjectiveKind.VECTOR:
        return _vector(student, reference, close)
    return None


def _factor(student: np.ndarray, reference: np.ndarray, exact: Close,
            plausible: frozenset[str] | None,
            candidates: Candidates | None = None) -> tuple[Diagnosis, float] | None:
    """The first whole-answer factor (a sign, a factor, a unit slip) ``student`` has
    exactly, among those the model makes plausible, and the distance from it (the factors'
    test prepared by ``candidates`` when its test is ``exact``)."""
    if not (reference != 0).any():
        return None
    # every factor times the reference at once (row by row the same products), and tested
    # at once when the test can be (a score of tests one by one cost most of a diagnosis)
    fits: np.ndarray | None
    if candidates is not None and candidates.zero is exact and candidates.factors is not None:
        scaled, fits = candidates.factors.rows, candidates.factors.each(student)
    else:  # a test of numbers or vectors, or one not prepared
        scaled = _scaled(reference)
        fits = exact.each(student, scaled) if isinstance(exact, AgreeAtPoints) else None
    if fits is not None and not fits.any():
        return None
    end = 0
    for code, label, message, factors in _FACTORS:
        start, end = end, end + len(factors)
        if plausible is not None and code in MODEL_SLIPS and code not in plausible:
            continue
        for at in range(start, end):
            if fits[at] if fits is not None else exact(student, scaled[at]):
                return (Diagnosis(code, label, message),
                        _norm(student - scaled[at]))
    return None


def trig_in_radians(call: str, plausible: frozenset[str] | None) -> Diagnosis | None:
    """The hint for an answer such as ``sin(30)`` that is wrong as read (its argument in
    radians, as every calculator language reads it) and right with the argument in degrees:
    given only where the model has angles in degrees (``plausible``, as ``deg_as_rad``).

    >>> trig_in_radians("sin(30)", None).message
    'sin(30) was read with its argument in radians; read in degrees your value would be right: write sin(30°) or sin(30 deg).'
    """
    if plausible is not None and "deg_as_rad" not in plausible:
        return None
    inside = call[call.index("(") + 1:-1]
    return Diagnosis("trig_radians", "trig argument read in radians",
                     f"{call} was read with its argument in radians; read in degrees your "
                     f"value would be right: write {call[:call.index('(')]}({inside}°) or "
                     f"{call[:call.index('(')]}({inside} deg).")


MODEL_SLIPS = ("g", "deg_as_rad", "rad_as_deg", "rpm_rad", "rev_rad", "min_s", "hp_746")
"""Whole-answer slips that are only plausible when the model has what they name."""


class Candidates:
    """The generated mistakes that can be tried against answers to one reference: each with
    its values (finite, of the reference's shape) and whether those values are a zero on the
    reference's scale (within the ``zero`` test), which no answer changes: worked out once by
    a caller that judges many answers to one reference (one by one, these tests cost most of
    naming a wrong expression's mistake). When ``zero`` is an :class:`AgreeAtPoints` test,
    it is also prepared (:meth:`AgreeAtPoints.rows`) against the candidates' values
    (``rows``) and the reference's multiples by every whole-answer factor (``factors``), so
    an answer is tried against each set in one numpy pass.

    >>> m = GeneratedMistake("weight_omitted", "The weight was left out.", "x")
    >>> close = lambda s, t: bool(np.all(np.abs(s - t) <= 0.01 * np.abs(t)))
    >>> found = Candidates([(m, np.array([1e-3])), (m, None), (m, [np.inf]), (m, [2.0])],
    ...                    np.array([1.0]), close)
    >>> [v.tolist() for _, v in found], found.zeros
    ([[0.001], [2.0]], (True, False))
    """

    __slots__ = ("factors", "pairs", "rows", "zero", "zeros")

    def __init__(self, generated: Iterable[tuple[GeneratedMistake, np.ndarray | None]],
                 reference: np.ndarray, zero: Close):
        pairs = []
        for mistake, values in generated:
            if values is None:
                continue
            values = np.asarray(values, dtype=float)
            if values.shape == reference.shape and np.isfinite(values).all():
                pairs.append((mistake, values))
        self.pairs: tuple[tuple[GeneratedMistake, np.ndarray], ...] = tuple(pairs)
        self.zero = zero
        self.zeros = tuple(zero(values + reference, reference) for _, values in pairs)
        self.rows: AgreeingRows | None = None
        self.factors: AgreeingRows | None = None
        if isinstance(zero, AgreeAtPoints):
            self.factors = zero.rows(_scaled(reference))
            if pairs:
                self.rows = zero.rows(np.array([values for _, values in pairs]))

    def __iter__(self) -> Iterator[tuple[GeneratedMistake, np.ndarray]]:
        return iter(self.pairs)

    def fitting(self, student: np.ndarray, reference: np.ndarray,
                close: Close) -> Iterator[tuple[GeneratedMistake, np.ndarray]]:
        """The candidates ``student`` matches: within ``close`` of their values, or, for
        values that are a zero on the reference's scale (a contact point's velocity), of the
        reference shifted by them, as a zero answer would be matched."""
        fits = self.rows.each(student) if close is self.zero and self.rows is not None \
            else None
        for at, ((mistake, values), is_zero) in enumerate(zip(self.pairs, self.zeros)):
            if (fits[at] if fits is not None else close(student, values)) \
                    or (is_zero and close(student - values + reference, reference)):
                yield mistake, values


def _scaled(reference: np.ndarray) -> np.ndarray:
    """Every whole-answer factor times ``reference``, a row each (:data:`_FACTORS`' order)."""
    return np.multiply.outer(_ALL_FACTORS, reference)


def _norm(values: np.ndarray) -> float:
    """``float(np.linalg.norm(values))``, worked out as numpy does (√ of the flattened values'
    dot product with themselves) without its checks: naming a wrong answer's mistake measures
    a few distances, each cheaper than numpy's set-up.

    >>> _norm(np.array([3.0, -4.0])), _norm(np.array([[1.0, 2.0], [2.0, 4.0]]))
    (5.0, 5.0)
    """
    flat = values.ravel()
    return math.sqrt(flat.dot(flat))


def _generated(student: np.ndarray, reference: np.ndarray, close: Close,
               generated: Candidates,
               plausible: frozenset[str] | None = None) -> Diagnosis | None:
    """The generated mistake nearest ``student`` among those it matches
    (:meth:`Candidates.fitting`) and is nearer to than to ``reference``: a value that merely
    lies between two candidates names neither. When a mistake of another family matches too
    and its value is the nearest's within ``close``, the two fit equally and both are named
    (:func:`_both`)."""
    own = _norm(student - reference)
    matched: list[tuple[float, GeneratedMistake, np.ndarray]] = []
    for mistake, values in generated.fitting(student, reference, close):
        distance = _norm(student - values)
        if distance < own:
            matched.append((distance, mistake, values))
    if not matched:
        return None
    # nearest first; among values one but for round-off (:data:`~mechgrade.solve.mutants.SAME`),
    # the families' own order
    scale = max(_norm(reference), 1e-300)
    matched.sort(key=lambda m: round(m[0] / scale, 7))
    _, best, best_values = matched[0]
    first = _named(best, reference, plausible)
    for _, other, values in matched[1:]:
        if other.code == best.code or not (close(values, best_values)
                                           or close(best_values, values)):
            continue
        second = _named(other, reference, plausible)
        # a physical family is the explanation before a numeric coincidence
        if _coincidence(first) and not _coincidence(second):
            return second
        if _coincidence(second):
            return first
        return _both(first, second) or first
    return first


def _coincidence(found: Diagnosis) -> bool:
    """Whether a diagnosis names a whole-answer slip (a sign, a factor, a unit slip), as a
    given misread that is exactly one is named: true of the answer, but no physical family's
    reason (friction turned round also flips the answer)."""
    return found.code in FACTOR_CODES


_SIGN_FLIPS = ("given_sign", "given_angle_sign")
"""Misread givens whose sign is flipped (a rate, an angle): where the answer is linear in one,
the whole answer flips, and the sign error is said with its sentence."""


def _named(mistake: GeneratedMistake, reference: np.ndarray,
           plausible: frozenset[str] | None) -> Diagnosis:
    """One generated mistake's diagnosis."""
    if mistake.code in GIVEN_CODES and mistake.value is not None:
        return _given_as_transform(mistake, reference, plausible) or Diagnosis(
            mistake.code, LABELS.get(mistake.code, mistake.code), mistake.message)
    return Diagnosis(mistake.code, LABELS.get(mistake.code, mistake.code), mistake.message)


_SPECIAL_CASE = {"tension_as_weight": "reaction_as_weight"}
"""A family that is a special case of another (a string's tension is a reaction): when both
fit one value they are one reading, which the special one says alone."""


def _both(first: Diagnosis, second: Diagnosis) -> Diagnosis | None:
    """Two families that fit one value equally, named together, the nearer first (the label
    names both, so the message says it once); ``None`` when they say the same; the special
    one alone when one is a special case of the other (:data:`_SPECIAL_CASE`).

    >>> a = Diagnosis("weight_omitted", "weight left out", "The weight was left out.")
    >>> b = Diagnosis("force_omitted", "an applied force left out", "The push was left out.")
    >>> both = _both(a, b)
    >>> both.label
    'weight left out or an applied force left out'
    >>> both.message
    'The weight was left out. Or: The push was left out.'
    >>> c = Diagnosis("given_sign", "given rate's sign flipped",
    ...               "Your value is what x' with the opposite sign gives: check x'.")
    >>> _both(a, c).message
    "The weight was left out. It is also what x' with the opposite sign gives: check x'."
    >>> _both(a, a) is None
    True
    >>> t = Diagnosis("tension_as_weight", "tension taken equal to a weight", "T = m g.")
    >>> r = Diagnosis("reaction_as_weight", "reaction taken equal to the weight", "R = m g.")
    >>> _both(r, t).label
    'tension taken equal to a weight'
    """
    if first.code == second.code or first.label == second.label:
        return None
    for special, general in ((first, second), (second, first)):
        if _SPECIAL_CASE.get(special.code) == general.code:
            return special
    # one sentence a reading: the second says "also" rather than the first's opening again
    lead = "Your value is what "
    other = _sentence(second.message)
    other = "It is also what " + other[len(lead):] if other.startswith(lead) else "Or: " + other
    return Diagnosis(first.code, f"{first.label} or {second.label}",
                     f"{_sentence(first.message)} {other}", also=second.code)


def _sentence(message: str) -> str:
    return message if message.endswith((".", "?", "!")) else message + "."


def _given_as_transform(mistake: GeneratedMistake, reference: np.ndarray,
                        plausible: frozenset[str] | None) -> Diagnosis | None:
    """A mistaken given whose value is exactly a whole-answer slip of the reference: a flipped
    rate in a quantity linear in it flips the whole answer (a sign error, graded as the
    policy grades one, with the sentence that says which sign); any other given slip that
    coincides with one (two masses exchanged where one is twice the other) is one of two
    readings, and only the whole-answer slip, true of both, is said. A given's unit not
    converted says which unit, which a factor (1000: mm or ms?) cannot."""
    if mistake.code == "given_unit":  # the unit it names is the slip's (ms, not mm)
        return None
    value = np.asarray(mistake.value, dtype=float).reshape(reference.shape)
    for code, label, message, factors in _FACTORS:
        if plausible is not None and code in MODEL_SLIPS and code not in plausible:
            continue
        if any(np.allclose(value, f * reference, rtol=1e-9, atol=0) for f in factors):
            if code == "sign" and mistake.code in _SIGN_FLIPS:
                return Diagnosis("sign", label, mistake.message)
            return Diagnosis(code, label, message)
    return None


LABELS = {
    "drop_transport_acc": "frame origin's acceleration left out",
    "drop_tangential": "tangential term α × r left out",
    "drop_centripetal": "centripetal term ω × (ω × r) left out",
    "drop_coriolis": "Coriolis term left out",
    "coriolis_half": "Coriolis term without its factor 2",
    "drop_relative_acc": "relative acceleration left out",
    "drop_transport_vel": "frame origin's velocity left out",
    "drop_omega_r": "transport term ω × r left out",
    "drop_relative_vel": "relative velocity left out",
    "other_point": "another point's motion",
    "relative_omega": "relative angular velocity for the absolute one",
    "mag_as_sum": "components or magnitudes added for a magnitude",
    "position_term": "a term of the position left out",
    "zero_for_constant_rate": "acceleration taken as zero at a constant rate",
    "driver_rate": "the driver's angular rate for a connected body's",
    "gyration_for_radius": "a radius of gyration read for a radius",
    "driver_speed": "the driver's speed for a connected point's",
    "rate_relation_inverted": "v = r ω used as ω = v r",
    "omega_reversed": "ω × r taken in the opposite sense",
    "angle_complement": "angle measured from the other axis (sin and cos exchanged)",
    "given_swap": "two givens exchanged",
    "other_basis": "components along another frame",
    "acc_t_for_acc": "tangential acceleration for the whole",
    "acc_n_for_acc": "normal acceleration for the whole",
    "acc_for_acc_t": "whole acceleration for its tangential part",
    "acc_for_acc_n": "whole acceleration for its normal part",
    "rho_formula": "radius of curvature from |a|",
    "rho_without_slope": "radius of curvature without the slope term",
    "component_for_speed": "a velocity component for the speed",
    "speed_for_component": "the whole speed for a velocity component",
    "given_deg_as_rad": "given angle's degrees used as radians",
    "given_complement": "given angle read as its complement (sin and cos exchanged)",
    "given_rate_unit": "given rate's unit not converted to rad/s",
    "given_length_unit": "given length's unit not converted",
    "given_unit": "given's unit not converted",
    "given_sign": "given rate's sign flipped",
    "given_angle_sign": "given angle measured to the other side",
    "given_acceleration_zero": "the given acceleration left out (taken as zero)",
    "weight_omitted": "weight left out",
    "mass_for_weight": "mass used for the weight",
    "central_inertia_at_pivot": "inertia about the mass centre used at the pivot",
    "friction_reversed": "friction in the wrong direction",
    "normal_from_weight": "normal force taken as the weight",
    "weight_transfer_ignored": "weight transfer ignored",
    "tension_as_weight": "tension taken equal to a weight",
    "reaction_as_weight": "reaction taken equal to the weight",
    "reaction_as_static": "reaction taken as its static value",
    "acceleration_reversed": "the acceleration taken in the opposite sense in the balance",
    "spring_work_reversed": "a spring's work taken with the wrong sign",
    "force_component_reversed": "a force's component taken the other way",
    "inertia_omitted": "a body's moment of inertia left out",
    "restitution_component": "restitution applied to the wrong component",
    "damping_omitted": "damping left out",
    "force_omitted": "an applied force left out",
    "springs_in_series": "springs combined the wrong way (in series for in parallel, or the "
                         "reverse)",
    "weight_for_mass": "weight used for the mass",
    "strands_miscounted": "a cord's strands miscounted",
    "initial_speed_omitted": "the initial speed left out",
    "value_at_start": "the value at the start of the motion",
    "force_taken_constant": "a varying force taken constant",
    "efficiency_inverted": "efficiency multiplied for divided (or the reverse)",
    "rotational_ke_omitted": "rotational kinetic energy left out",
    "restitution_ignored": "coefficient of restitution ignored",
    "other_shape_inertia": "another shape's moment of inertia",
    "spring_free_length_omitted": "spring's free length left out",
    "surface_taken_fixed": "the body slid on taken as fixed",
    "body_ke_omitted": "a body's kinetic energy left out",
    "impulse_moment_omitted": "the blow's moment left out",
    "moment_arm_omitted": "the momentum m v for its moment r × m v",
    "spring_omitted": "a spring left out",
    "load_at_other_point": "a load taken at another point of its body",
    "contact_taken_smooth": "a rolling contact taken as smooth",
    "period_for_frequency": "period and frequency confused",
    "spring_energy_from_change": "spring energy from the change of stretch",
    "spring_energy_half_omitted": "spring energy without its ½",
    "mean_of_end_rates": "uniform acceleration assumed (the mean of the end speeds)",
    "end_speed_throughout": "the final speed taken as constant throughout",
    "transverse_speed_kept": "the transverse speed r θ̇ kept instead of the angular momentum",
    "energy_kept_in_coupling": "kinetic energy taken as conserved in a coupling",
    "parallel_axis_with_radius": "the parallel-axis term with the radius for the pivot's "
                                 "distance",
    "impact_taken_head_on": "an oblique impact taken as head-on",
    "reaction_omitted": "a support's force left out (free fall)",
    "pin_impulse_omitted": "linear momentum taken as conserved through a pin's impulse",
    "translational_ke_omitted": "translational kinetic energy left out",
    "rolling_assumed": "rolling without slip assumed where the body slips",
    "initial_displacement_omitted": "the initial displacement left out",
    "angmom_along_axis": "angular momentum taken as I ω along one axis",
    "spring_force_as_resultant": "one spring's force taken as all the springs' together",
    "part_moving_with_centre": "a point mass taken to move with its body's centre",
    "striker_stops": "the striking body taken to stop in the impact",
    "weight_along_surface_omitted": "the weight's component along the slope left out",
    "damped_for_natural": "the damped frequency ω_d for the natural frequency ω_n",
    "other_assembly_branch": "the other assembly branch (the mechanism's mirror configuration)",
}
"""Short labels of the generated mistakes, by code (the result files' diagnosis column)."""


def _vector(student: np.ndarray, reference: np.ndarray, close: Close) -> Diagnosis | None:
    for perm in itertools.permutations(range(3)):
        if perm == (0, 1, 2):
            continue
        permuted = reference[list(perm)]
        if not np.array_equal(permuted, reference) and close(student, permuted):
            moved = [_AXES[i] for i in range(3) if perm[i] != i]
            return Diagnosis("swapped", "swapped components",
                             f"Your {' and '.join(moved)} components are swapped.")
    s_mag, t_mag = _norm(student), _norm(reference)
    if close(np.array([s_mag]), np.array([t_mag])):
        return Diagnosis("direction", "wrong direction",
                         "The magnitude is right but the direction is wrong.")
    if s_mag > 0 and t_mag > 0:
        cosine = float(np.dot(student, reference)) / (s_mag * t_mag)
        if cosine > 1 - 1e-4:
            return Diagnosis("magnitude", "wrong magnitude",
                             "The direction is right but the magnitude is wrong.")
    return None
