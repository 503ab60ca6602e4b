"""The grading policy: one type for everything an instructor decides about judging answers,
read from an assignment's ``policy:`` (:func:`mechgrade.grade.assignment.load_assignment`) or
made directly to judge one answer (:func:`mechgrade.grade.compare.assess`).

>>> GradingPolicy(written_sig_figs=3).written_sig_figs_deduction
0.25
>>> GradingPolicy(missing_unit="guess")
Traceback (most recent call last):
...
mechgrade.errors.AssignmentError: policy.missing_unit: expected one of reject, assume, found 'guess'
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import AssignmentError
from ..expressions.functions import StrEnum


class MissingUnit(StrEnum):
    """What a bare number gets where a unit is expected: refused, or the objective's unit."""

    REJECT = "reject"
    ASSUME = "assume"


class ShowWorked(StrEnum):
    """When feedback pages show the worked solution (``policy.worked_solution``)."""

    ALWAYS = "always"
    AFTER_DUE_DATE = "after_due_date"
    NEVER = "never"


@dataclass(frozen=True)
class ErrorCarriedForward:
    """Credit for an answer that is right when computed from the student's own wrong
    upstream answer (``depends_on`` in the problem spec)."""

    enabled: bool = True
    credit: float = 1.0


@dataclass(frozen=True)
class GradingPolicy:
    """How answers are judged (the instructor's choices; defaults are the objective's own).

    * ``rel``/``abs``: override the objective's tolerance (``abs`` in the objective's unit).
    * ``sig_figs``: judge accuracy to ``n`` significant figures instead of ``rel``/``abs``.
    * ``written_sig_figs``: require ``n`` written significant figures (liberal by default, as
      STACK's NumSigFigs; ``written_sig_figs_strict`` reads ``100`` as exactly one figure);
      a correct value written otherwise loses ``written_sig_figs_deduction``.
    * ``missing_unit``: reject a bare number, or assume the objective's unit and deduct
      ``missing_unit_deduction`` (:class:`MissingUnit`).
    * ``partial_credit``: credit for automatic diagnoses, by code (``(("sign", 0.5),)``);
      author-declared mistakes carry their own credit.
    * ``symbolic_rel``/``symbolic_points``/``seed``: expression equivalence by evaluation.
    * ``separate_mistakes``: tighten an objective's relative tolerance to the one that puts
      every generated mistake outside it (:func:`mechgrade.solve.mutants.separating_rel`).
    * ``reveal_answers``: feedback shows the reference answers; ``worked_solution``
      (:class:`ShowWorked`) when it shows each problem's worked solution; ``ecf`` the
      credit of error carried forward (:mod:`mechgrade.grade.ecf`).
    """

    rel: float | None = None
    abs: float | None = None
    sig_figs: int | None = None
    written_sig_figs: int | None = None
    written_sig_figs_strict: bool = False
    written_sig_figs_deduction: float = 0.25
    missing_unit: MissingUnit = MissingUnit.REJECT
    missing_unit_deduction: float = 0.25
    partial_credit: tuple[tuple[str, float], ...] = ()
    symbolic_rel: float = 1e-6
    symbolic_points: int = 10
    seed: int = 0
    separate_mistakes: bool = False
    reveal_answers: bool = False
    worked_solution: ShowWorked = ShowWorked.AFTER_DUE_DATE
    ecf: ErrorCarriedForward = ErrorCarriedForward()

    def __post_init__(self) -> None:
        def fail(name: str, expected: str, found) -> None:
            raise AssignmentError(f"policy.{name}: expected {expected}, found {found!r}")

        for name in ("rel", "abs"):
            value = getattr(self, name)
            if value is not None and not (isinstance(value, (int, float)) and 0 <= value < 1e300):
                fail(name, "a non-negative number", value)
        for name in ("sig_figs", "written_sig_figs"):
            value = getattr(self, name)
            if value is not None and not (isinstance(value, int) and 1 <= value <= 15):
                fail(name, "a whole number from 1 to 15", value)
        for name in ("written_sig_figs_deduction", "missing_unit_deduction"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and 0 <= value <= 1):
                fail(name, "a number from 0 to 1", value)
        for name, kind in (("missing_unit", MissingUnit), ("worked_solution", ShowWorked)):
            if getattr(self, name) not in list(kind):
                fail(name, "one of " + ", ".join(kind), getattr(self, name))
        if self.partial_credit:
            # the codes live with the diagnoses, whose module loads numpy: only when needed
            from .diagnose import CODES

            for pair in self.partial_credit:
                if not (isinstance(pair, tuple) and len(pair) == 2 and pair[0] in CODES
                        and isinstance(pair[1], (int, float)) and 0 <= pair[1] <= 1):
                    fail("partial_credit", "(code, credit) pairs with a known code and credit "
                         "from 0 to 1", pair)
        if not (isinstance(self.symbolic_rel, (int, float)) and 0 < self.symbolic_rel < 1):
            fail("symbolic_rel", "a number between 0 and 1", self.symbolic_rel)
        if not (isinstance(self.symbolic_points, int) and 3 <= self.symbolic_points <= 200):
            fail("symbolic_points", "a whole number from 3 to 200", self.symbolic_points)
        if not (isinstance(self.ecf.credit, (int, float)) and 0 <= self.ecf.credit <= 1):
            fail("ecf.credit", "a number from 0 to 1", self.ecf.credit)

    def credit_for(self, code: str) -> float:
        """Partial credit for an automatic diagnosis (0 unless configured).

        >>> GradingPolicy(partial_credit=(("sign", 0.5),)).credit_for("sign")
        0.5
        """
        return float(dict(self.partial_credit).get(code, 0.0))
