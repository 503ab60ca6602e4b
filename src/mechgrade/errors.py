"""The one error hierarchy of mechgrade.

Every error a user can cause is a :class:`MechgradeError`. Its message says where (file, line,
column, field), what was expected and what was found; the CLI prints ``str(error)`` and exits
with :attr:`MechgradeError.exit_code`. Nothing else in the package prints or exits.

>>> err = SpecError("expected a unit such as 'm/s', found 'furlongs/s'",
...                 where=Location("p.yaml", 12, 5, "givens.v"))
>>> str(err)
"p.yaml:12:5: givens.v: expected a unit such as 'm/s', found 'furlongs/s'"
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TypeVar


@dataclass(frozen=True)
class Location:
    """Where a value came from: file, 1-based line and column, and the field path inside it."""

    file: str | None = None
    line: int | None = None
    column: int | None = None
    field: str | None = None

    def __str__(self) -> str:
        parts = []
        if self.file:
            place = self.file
            if self.line is not None:
                place += f":{self.line}"
                if self.column is not None:
                    place += f":{self.column}"
            parts.append(place)
        if self.field:
            parts.append(self.field)
        return ": ".join(parts)


E = TypeVar("E", bound="MechgradeError")


class MechgradeError(Exception):
    """Base of every error caused by bad input; carries a :class:`Location`."""

    exit_code = 2

    def __init__(self, message: str, *, where: Location | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.where = where or Location()

    def located(self: E, where: Location) -> E:
        """The same error placed at ``where``, keeping any field path it already had below it."""
        field = where.field
        if self.where.field and field:
            field = f"{field}{'' if self.where.field.startswith('[') else '.'}{self.where.field}"
        elif self.where.field:
            field = self.where.field
        merged = replace(where, field=field)
        err = type(self)(self.message, where=merged)
        err.__cause__ = self.__cause__
        return err

    def __str__(self) -> str:
        place = str(self.where)
        return f"{place}: {self.message}" if place else self.message


@dataclass(frozen=True)
class AuthorWarning:
    """Something legal in a problem file that is probably not what the author meant.

    Warnings never stop a run; ``check`` and ``solve`` print them after the answers.

    >>> str(AuthorWarning("T moves with the disk centre", Location("p.yaml", 30, 7, "givens")))
    'p.yaml:30:7: givens: warning: T moves with the disk centre'
    """

    message: str
    where: Location = Location()

    def __str__(self) -> str:
        place = str(self.where)
        return f"{place}: warning: {self.message}" if place else f"warning: {self.message}"


class SpecError(MechgradeError):
    """A problem file is malformed: YAML, schema, names, types or dimensions."""


class SpecErrors(SpecError):
    """Every independent error found in one problem file, in file order; one line each.

    >>> errs = SpecErrors([SpecError("b", where=Location("p.yaml", 9, 1)),
    ...                    SpecError("a", where=Location("p.yaml", 2, 5))])
    >>> print(errs)
    p.yaml:2:5: a
    p.yaml:9:1: b
    >>> len(errs.errors)
    2
    """

    def __init__(self, errors) -> None:
        errors = tuple(sorted(errors, key=lambda e: (e.where.line or 0, e.where.column or 0)))
        if not errors:
            raise ValueError("SpecErrors needs at least one error")
        super().__init__("\n".join(str(e) for e in errors), where=Location(errors[0].where.file))
        self.errors = errors

    def located(self: E, where: Location) -> E:  # noqa: ARG002 - the signature it overrides
        return self

    def __str__(self) -> str:
        return "\n".join(str(e) for e in self.errors)


EE = TypeVar("EE", bound="ExpressionError")


class ExpressionError(MechgradeError):
    """Text could not be read as an expression of the allowed language.

    ``offset`` is the 0-based character position in the text where reading failed, if known.
    """

    def __init__(self, message: str, *, where: Location | None = None, offset: int | None = None):
        super().__init__(message, where=where)
        self.offset = offset

    def located(self: EE, where: Location) -> EE:
        err = super().located(where)
        err.offset = self.offset
        return err


class UnitError(MechgradeError):
    """A unit string is unknown, or a quantity has the wrong dimension."""


class SolveError(MechgradeError):
    """The model cannot produce an objective: givens missing, conflicting, or a singular instant."""


class UnderdeterminedError(SolveError):
    """The givens leave an objective undetermined; the message names what is missing."""


class InconsistentError(SolveError):
    """The givens over-determine the model and disagree; the message names the conflict."""


class AssignmentError(MechgradeError):
    """An assignment file or its roster is malformed."""


class SubmissionError(MechgradeError):
    """A submission file could not be read (it is reported, never fatal to a grading run)."""


class ExportError(MechgradeError):
    """Results could not be exported in the requested format."""


class OutputError(MechgradeError):
    """An output file or folder could not be written."""


class SettingError(MechgradeError):
    """An environment variable mechgrade reads (``MECHGRADE_CACHE_DIR``...) holds a value it
    cannot use; ``where.field`` names the variable."""


class AnswerError(MechgradeError):
    """A student's answer text could not be read; the message says why (verdict "unreadable")."""


def brief_exception(exc: BaseException) -> str:
    """An exception as one short line: its type and the start of its message.

    >>> brief_exception(ZeroDivisionError("x" * 300))[:30], len(brief_exception(KeyError()))
    ('ZeroDivisionError: xxxxxxxxxxx', 8)
    """
    try:
        text = " ".join(str(exc).encode("utf-8", "backslashreplace").decode().split())
    except Exception:  # noqa: BLE001 - an exception whose message itself fails
        text = ""
    text = text if len(text) <= 120 else text[:117] + "..."
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__
