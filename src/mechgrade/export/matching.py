"""Pair the students of a roster with the students of a grading report.

A roster student is matched, in this order, by Canvas/roster ID, SIS user ID (or Moodle ID
number), SIS login ID, email, and last by name ("Last, First" and "First Last" are the same
name; a name shared by two students never matches). Each result is used at most once, and
results and roster students that match other than one to one are a roster conflict (see
:func:`mechgrade.roster.pair_students`): each is paired with (or is) a result of status
``conflict``, which no exporter writes as a grade.

>>> from mechgrade.grade.results import AssignmentInfo, GradeReport, StudentResult
>>> from mechgrade.roster import Roster, RosterFormat, RosterStudent
>>> report = GradeReport(AssignmentInfo("hw1", "HW 1"), (), (
...     StudentResult("s1", "Ada Lovelace", "graded", 3, 3),
...     StudentResult("zz", "Ghost", "graded", 1, 3)))
>>> roster = Roster((RosterStudent("101", "Ada Lovelace", sis_user_id="s1"),
...                  RosterStudent("102", "Bob Roe")), RosterFormat.PLAIN, ("id", "name"))
>>> m = match_roster(report, roster)
>>> [(p.roster.id if p.roster else None, p.result.id if p.result else None, p.matched_by)
...  for p in m.pairs]
[('101', 's1', <MatchKind.SIS_USER_ID: 'sis_user_id'>), ('102', None, None), (None, 'zz', None)]
>>> [s.id for s in m.not_in_roster], [s.id for s in m.no_submission]
(['zz'], ['102'])
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Literal

from ..grade.results import GradeReport, Status, StudentResult
from ..roster import MatchKind, Roster, RosterStudent, fold, normalise_name, pair_students

IdentityKind = Literal["canvas_id", "sis_user_id", "sis_login_id", "email"]
"""An identifier a result's identity columns may carry (named as :data:`_IDENTITY_KINDS` says)."""

# Which identity keys (lower-cased) of a StudentResult carry which kind of identifier.
_IDENTITY_KINDS: dict[IdentityKind, set[str]] = {
    "canvas_id": {"id", "canvas id", "canvas_id", "canvas user id"},
    "sis_user_id": {"sis user id", "sis_user_id", "id number", "idnumber", "student id",
                    "student number"},
    "sis_login_id": {"sis login id", "sis_login_id", "login", "username"},
    "email": {"email", "email address", "e-mail"},
}


@dataclass(frozen=True)
class Pair:
    """A roster student and its result; either may be ``None`` (no submission / not in roster)."""

    roster: RosterStudent | None
    result: StudentResult | None
    matched_by: MatchKind | None = None


@dataclass(frozen=True)
class RosterMatch:
    """Roster students in roster order, then the results no roster student claimed."""

    pairs: tuple[Pair, ...]

    @property
    def not_in_roster(self) -> tuple[StudentResult, ...]:
        return tuple(p.result for p in self.pairs if p.roster is None and p.result is not None)

    @property
    def no_submission(self) -> tuple[RosterStudent, ...]:
        return tuple(p.roster for p in self.pairs if p.roster is not None and p.result is None)


def match_roster(report: GradeReport, roster: Roster | None) -> RosterMatch:
    """Pair roster students with results (see module doc); without a roster, every result."""
    if roster is None:
        return RosterMatch(tuple(Pair(None, s) for s in report.students))
    results = list(report.students)
    pairing = pair_students(roster, [_keys(result) for result in results])
    pairs = [Pair(student, results[i] if i is not None else None, kind)
             for student, (i, kind) in zip(roster.students, pairing.pairs)]
    for conflict in pairing.conflicts:
        said = "roster conflict: " + conflict.describe(roster, [r.id for r in results])
        for c in conflict.candidates:
            results[c] = replace(results[c], status=Status.CONFLICT,
                                 messages=(said, *results[c].messages))
        for s in conflict.students:
            student = roster.students[s]
            pairs[s] = Pair(student, StudentResult(
                student.id, student.name, Status.CONFLICT, 0.0, results[conflict.candidates[0]]
                .max_score, messages=(said,), identity=student.columns))
    used = {i for i, _ in pairing.pairs if i is not None}
    pairs.extend(Pair(None, s) for i, s in enumerate(results) if i not in used)
    return RosterMatch(tuple(pairs))


def identity_value(result: StudentResult, kind: IdentityKind) -> str:
    """The identifier of ``kind`` ("canvas_id", "sis_user_id", "sis_login_id", "email") a
    result carries in its identity columns, or ``""``."""
    names = _IDENTITY_KINDS[kind]
    return next((v for k, v in result.identity if k.strip().lower() in names and v), "")


def _keys(result: StudentResult) -> dict[MatchKind, set[str]]:
    """The identifiers a result offers: its id (a submission folder may be named by any of
    them) and the roster columns it carries, folded."""
    # a result in a roster conflict is no one's by its id: only its roster columns name it
    own = fold(result.id) if result.status != Status.CONFLICT else ""
    sources: tuple[tuple[MatchKind, IdentityKind], ...] = (
        (MatchKind.ID, "canvas_id"), (MatchKind.SIS_USER_ID, "sis_user_id"),
        (MatchKind.SIS_LOGIN_ID, "sis_login_id"), (MatchKind.EMAIL, "email"))
    keys = {kind: {own, fold(identity_value(result, source))} - {""} for kind, source in sources}
    keys[MatchKind.NAME] = {normalise_name(result.name)} - {""}
    return keys
