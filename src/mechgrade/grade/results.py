"""The outcome of grading, as frozen dataclasses, and its stable JSON contract (``results.json``).

``results.json`` is a public contract (documented in ``docs/grading.md``)::

    {"assignment": {"id": ..., "title": ...},
     "objectives": [{"problem", "objective", "prompt", "max_points", "problem_title"}],
     "students": [{"id", "name", "status", "score", "max_score", "variant" (if drawn),
                   "answers": [{"problem", "objective", "answer", "verdict", "points",
                                "max_points", "diagnosis", "feedback", "read_back",
                                "expected", "expected_in_answer_unit",
                                "loads" (a free-body diagram's: [{"label", "load", "kind",
                                         "point", "answer", "mistakes", "feedback"}]),
                                "first_wrong_step" (an answer graded after steps of its
                                                    write-up, when one is wrong)}]}],
     "skipped": [{"path", "reason"}], "notes": [...], "internal_errors": [...],
     "failing_expects": [{"problem", "objective", "where", "message"}] (only when graded
                                                                        with them)}

Verdicts are :class:`Verdict`, student statuses :class:`Status`: enums whose members are the
very strings ``results.json`` holds (:data:`VERDICTS`, :data:`STATUSES`). Reports and exports
read these dataclasses (never sympy).

>>> r = GradeReport(AssignmentInfo("hw1", "Homework 1"), (), ())
>>> GradeReport.from_json(r.to_json()) == r
True
"""

from __future__ import annotations


from dataclasses import dataclass, field

from ..codec import MAPPING, OMIT_DEFAULT, absent, decode, encode
from ..expressions.functions import StrEnum
from ..expressions.loads import LoadKind


class Verdict(StrEnum):
    """How one answer was judged (``docs/grading.md`` says what each means). A member is its
    text: written to JSON, CSV and pages as that text, equal to it, and shown by ``str`` and
    f-strings as it.

    >>> f"{Verdict.NOT_EVALUATED}", str(Status.GRADED), Verdict("partial") is Verdict.PARTIAL
    ('not_evaluated', 'graded', True)
    """

    CORRECT = "correct"
    PARTIAL = "partial"
    INCORRECT = "incorrect"
    UNREADABLE = "unreadable"
    MISSING = "missing"
    NOT_EVALUATED = "not_evaluated"


class Status(StrEnum):
    """What became of one student's submission."""

    GRADED = "graded"
    MISSING = "missing"
    UNREADABLE = "unreadable"
    NOT_EVALUATED = "not_evaluated"
    CONFLICT = "conflict"


VERDICTS = tuple(v.value for v in Verdict)
STATUSES = tuple(s.value for s in Status)
"""``not_evaluated``: grading this student failed through a fault of mechgrade's (see
``GradeReport.internal_errors``); no grade is exported for them. ``conflict``: a roster student
and the folders that match it other than one to one (two folders one student, a folder two
students; see ``GradeReport.notes``): graded as no one's, no grade is exported for them."""
EXAMPLE_NUMBER = "12.5"
"""The number of an example answer in a message or on a handout: no problem's answer."""

EQUATIONS_OBJECTIVE = "equations"
"""The objective id a problem's equations of motion are answered and reported under."""
ECF_DIAGNOSIS = "error carried forward"
"""The diagnosis of an answer credited by ECF (whatever the answer alone looked like)."""


def derivation_objective(objective_id: str) -> bool:
    """Whether ``objective_id`` is a part of a derivation: a free-body diagram
    (``body.fbd``) or a problem's equations of motion.

    >>> derivation_objective("block.fbd"), derivation_objective("equations"), derivation_objective("v")
    (True, True, False)
    """
    return objective_id == EQUATIONS_OBJECTIVE or objective_id.endswith(".fbd")


@dataclass(frozen=True)
class AssignmentInfo:
    id: str
    title: str


@dataclass(frozen=True)
class ObjectiveInfo:
    """One gradable objective of the assignment; ``problem_title`` is the problem's title as
    students see it (empty in a results.json written before it was kept)."""

    problem: str
    objective: str
    prompt: str
    max_points: float
    problem_title: str = ""


@dataclass(frozen=True)
class AnswerResult:
    """How one student's answer to one objective was judged.

    ``answer`` is the text as the student typed it (``None`` if missing); ``read_back`` is how
    mechgrade read it; ``expected`` is the reference answer text, present only when the
    assignment reveals answers; ``expected_in_answer_unit`` is the same reference in the unit
    the student wrote a number or vector in, when that is another unit of the objective's
    dimension (``None`` otherwise, and in a results.json written before it was kept).
    """

    problem: str
    objective: str
    answer: str | None
    verdict: Verdict
    points: float
    max_points: float
    diagnosis: str | None = None
    feedback: str = ""
    read_back: str | None = None
    expected: str | None = None
    expected_in_answer_unit: str | None = None
    loads: tuple["LoadResult", ...] = field(default=(), metadata=OMIT_DEFAULT)
    first_wrong_step: str | None = field(default=None, metadata=OMIT_DEFAULT)


@dataclass(frozen=True)
class LoadResult:
    """One row of a judged free-body diagram (:mod:`mechgrade.grade.fbd`): the model's load
    (``load``, ``kind``, ``point``; ``load`` ``None`` for an extra one), the student's load as
    read (``answer``, ``None`` when missing) and what is wrong with it (``mistakes``, empty
    when right)."""

    label: str
    load: str | None
    kind: LoadKind | None
    point: str | None
    answer: str | None
    mistakes: tuple[str, ...]
    feedback: str


def unit_text(unit: str) -> str:
    """A unit as a student writes it.

    >>> unit_text("ft / s ** 2")
    'ft/s^2'
    """
    return unit.replace(" ** ", "^").replace(" * ", "*").replace(" / ", "/")


@dataclass(frozen=True)
class VariantGiven:
    """One given drawn for a student: ``value`` in ``unit``, from draw number ``draw``."""

    problem: str
    name: str
    value: float
    unit: str
    draw: int = 0

    @property
    def text(self) -> str:
        """The value with its unit.

        >>> VariantGiven("p", "a", 1.5, "m / s ** 2").text
        '1.5 m/s^2'
        """
        return f"{self.value:g} {unit_text(self.unit)}".strip()


@dataclass(frozen=True)
class StudentVariant:
    """A student's own numbers: the assignment's ``seed`` and every drawn given."""

    seed: str
    givens: tuple[VariantGiven, ...] = ()


@dataclass(frozen=True)
class StudentResult:
    """One student's grade. ``identity`` keeps roster columns (name, SIS ids, email...)."""

    id: str
    name: str = field(metadata=absent(""))
    status: Status
    score: float
    max_score: float
    answers: tuple[AnswerResult, ...] = ()
    messages: tuple[str, ...] = ()
    identity: tuple[tuple[str, str], ...] = field(default=(), metadata=MAPPING)
    # results without variants read as before
    variant: StudentVariant | None = field(default=None, metadata=OMIT_DEFAULT)


@dataclass(frozen=True)
class SkippedEntry:
    """An entry of the submissions folder (or of a student's folder) that was not read as
    anyone's answers, and why. ``path`` is relative to the submissions folder."""

    path: str
    reason: str


@dataclass(frozen=True)
class FailingExpect:
    """An ``expect:`` test a graded problem fails, graded anyway (``--accept-failing-expect``):
    where it is written (``file:line:col: field``) and what ``mechgrade check`` says of it.

    >>> str(FailingExpect("p", "v", "p.yaml:9:5: objectives[0].expect", "7 != expected 8 m/s"))
    'p.yaml:9:5: objectives[0].expect: v: 7 != expected 8 m/s'
    """

    problem: str
    objective: str
    where: str
    message: str

    def __str__(self) -> str:
        return f"{self.where}: {self.objective}: {self.message}"


@dataclass(frozen=True)
class GradeReport:
    """A whole grading run.

    ``skipped`` lists every entry of the submissions folder not read as answers; ``notes``
    are remarks about the folder as a whole (look-alike names, shared files);
    ``internal_errors`` says, one line each, where mechgrade itself failed (those students
    or answers are ``not_evaluated``); ``failing_expects`` the ``expect:`` tests the problems
    fail, when they were graded anyway (``--accept-failing-expect``), one line each.
    """

    assignment: AssignmentInfo
    objectives: tuple[ObjectiveInfo, ...] = field(metadata=absent(()))
    students: tuple[StudentResult, ...] = field(default=())
    skipped: tuple[SkippedEntry, ...] = ()
    notes: tuple[str, ...] = ()
    internal_errors: tuple[str, ...] = ()
    # results of specs that pass their tests read as before
    failing_expects: tuple[FailingExpect, ...] = field(default=(), metadata=OMIT_DEFAULT)

    def to_json(self) -> dict:
        """The ``results.json`` document (plain dicts and lists, stable key order), written
        by :func:`mechgrade.codec.encode`."""
        return encode(self)

    @classmethod
    def from_json(cls, data: dict) -> "GradeReport":
        """Rebuild a report from a ``results.json`` document (read by
        :func:`mechgrade.codec.decode`: a value of another type is a ``CodecError``).

        >>> GradeReport.from_json({"assignment": {"id": "a", "title": "A"}, "students": [
        ...     {"id": "s", "status": "graded", "score": "7", "max_score": 9}]})
        Traceback (most recent call last):
        ...
        mechgrade.codec.CodecError: GradeReport.students: StudentResult.score: expected a number, found str
        """
        return decode(cls, data)
