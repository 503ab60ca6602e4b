"""What the reference solver hands to the grader and the reports: plain numbers and strings.

Nothing here holds a sympy object, so grading, reports and exports can use a
:class:`Solution` without importing sympy.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence, Union

from ..errors import AuthorWarning, MechgradeError
from ..spec.model import ObjectiveKind
from ..tolerance import parts

Value = Union[float, tuple[float, float, float], None]


ROUND_OFF = 1e-12
"""A value this small is zero but for the solver's round-off: a student is shown 0, not
-1.27e-15 ft/s (a speed that is zero after an impact) or -3.45e-31 m/s², and a kinetic
friction whose slip is this slow does not slip (SI)."""


def without_round_off(value):
    """A value as it is shown: a number below :data:`ROUND_OFF` is 0, and so is a vector's
    component below that or not a part of it (:func:`~mechgrade.tolerance.parts`: a
    direction's leftover ``1e-14``).

    >>> without_round_off(-1.27486e-15), without_round_off((0.5, -6.3e-17, 1e-3))
    (0.0, (0.5, 0.0, 0.001))
    """
    if isinstance(value, tuple):
        return tuple(float(c) if part and not abs(c) < ROUND_OFF else 0.0
                     for c, part in zip(value, parts(value).tolist()))
    return 0.0 if abs(value) < ROUND_OFF else value


def in_frame(frame: str | None) -> str:
    """What follows a vector's components and unit to name the frame they are along ("N in
    N" read a frame's bare name as one more unit).

    >>> in_frame("N"), in_frame(None)
    (' in frame N', '')
    """
    return f" in frame {frame}" if frame else ""


@dataclass(frozen=True)
class MistakeValue:
    """The value an author-declared mistaken model gives, in the objective's unit."""

    message: str
    credit: float
    value: Value
    expr: str | None = None


@dataclass(frozen=True)
class GeneratedMistake:
    """The value a typical conceptual mistake gives (see :mod:`mechgrade.solve.mutants`):
    ``code`` its family (a key of the assignment's ``partial_credit``), ``message`` one
    sentence naming the term and the quantity, ``value`` in the objective's unit (``expr``
    for a symbolic objective, in its symbols); ``step``, where known, the section of the
    worked solution where the mistake happens (for the feedback to highlight)."""

    code: str
    message: str
    value: Value
    expr: str | None = None
    step: str | None = None


@dataclass(frozen=True)
class ObjectiveResult:
    """One objective's reference answer.

    ``value`` is a float (scalar), an ``(x, y, z)`` tuple of components in ``frame``
    (vector), or ``None`` for a symbolic objective, whose answer is ``expr`` (sympy syntax,
    readable by :func:`mechgrade.expressions.syntax.parse`) in the names ``symbols``.
    ``symbol_units`` gives each symbol's SI unit, for dimension checks of student answers;
    ``symbol_signed`` says which symbols may be negative (coordinates, their rates, parameters
    declared ``positive: false``), so an answer is checked over each symbol's whole domain.
    ``symbol_signs`` gives each symbol's sign at the instant the problem describes (+1, -1;
    0 when unknown), so a symbol the reference takes only through its sign (kinetic friction's
    sense of sliding, ``sign(xd)``) is judged for the sense the problem states.
    ``rel`` and ``abs`` are the objective's tolerance (``abs`` in ``unit``).
    ``mistakes`` are the author's; ``generated_mistakes`` those the solver derives from the
    model; ``plausible`` the whole-answer slips the model makes plausible (``"g"`` only with a
    ``g``, ``"deg_as_rad"`` only with an angle in degrees...).
    """

    id: str
    kind: ObjectiveKind
    unit: str
    value: Value = None
    frame: str | None = None
    expr: str | None = None
    symbols: tuple[str, ...] = ()
    symbol_units: tuple[str, ...] = ()
    symbol_signed: tuple[bool, ...] = ()
    mistakes: tuple[MistakeValue, ...] = ()
    rel: float = 0.01
    abs: float = 0.0
    prompt: str = ""
    generated_mistakes: Sequence[GeneratedMistake] = ()  # a tuple, or worked out when read
    plausible: frozenset[str] | None = None
    symbol_signs: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        if type(self.kind) is not ObjectiveKind:  # text from results.json
            object.__setattr__(self, "kind", ObjectiveKind(self.kind))


@dataclass(frozen=True)
class StateValue:
    """A coordinate, rate, parameter or time at the instant, named as a spec spells it
    (``theta'``): ``value`` in ``unit`` (the author's: that of its given or guess, else the
    declared one), ``si`` in SI; ``given`` says it was given rather than solved."""

    name: str
    value: float
    unit: str
    given: bool
    si: float

    def __str__(self) -> str:
        """``theta' = 7 rad/s``, marked ``(solved)`` when the solver found it.

        >>> str(StateValue("R", 0.25, "m", False, 0.25))
        'R = 0.25 m   (solved)'
        """
        unit = f" {self.unit}" if self.unit else ""
        return (f"{self.name} = {without_round_off(self.value):.6g}{unit}"
                f"{'' if self.given else '   (solved)'}")


@dataclass(frozen=True)
class ObjectiveFailure:
    """An objective the solver could not answer, and why."""

    id: str
    error: MechgradeError


@dataclass(frozen=True)
class Solution:
    """All objectives of a problem, solved at the instant its givens describe."""

    problem: str
    results: tuple[ObjectiveResult, ...]
    state: tuple[StateValue, ...] = ()
    dof: int | None = None
    failures: tuple[ObjectiveFailure, ...] = ()
    warnings: tuple[AuthorWarning, ...] = ()

    def result(self, objective_id: str) -> ObjectiveResult:
        """The objective's result; raises its error if it failed."""
        for result in self.results:
            if result.id == objective_id:
                return result
        for failure in self.failures:
            if failure.id == objective_id:
                raise failure.error
        raise KeyError(objective_id)
