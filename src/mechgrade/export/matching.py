"""Pair the students of a roster with the students of a grading report.

A roster student is matched, in this order, by Canvas/roster ID, SIS user ID (or Moodle ID
number), SIS login ID, email, and last by name ("Last, First" and "First Last" are the same
name; a name shared by two students never matches). Each result is used at most once.

>>> from mechgrade.grade.results import AssignmentInfo, GradeReport, StudentResult
>>> from mechgrade.roster import Roster, RosterStudent
>>> report = GradeReport(AssignmentInfo("hw1", "HW 1"), (), (
...     StudentResult("s1", "Ada Lovelace", "graded", 3, 3),
...     StudentResult("zz", "Ghost", "graded", 1, 3)))
>>> roster = Roster((RosterStudent("101", "Ada Lovelace", sis_user_id="s1"),
...                  RosterStudent("102", "Bob Roe")), "plain", ("id", "name"))
>>> m = match_roster(report, roster)
>>> [(p.roster.id if p.roster else None, p.result.id if p.result else None, p.matched_by)
...  for p in m.pairs]
[('101', 's1', 'sis_user_id'), ('102', None, None), (None, 'zz', None)]
>>> [s.id for s in m.not_in_roster], [s.id for s in m.no_submission]
(['zz'], ['102'])
"""

from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass

from ..grade.results import GradeReport, StudentResult
from ..roster import Roster, RosterStudent

# Which identity keys (lower-cased) of a StudentResult carry which kind of identifier.
_IDENTITY_KINDS = {
    "canvas_id": {"id", "canvas id", "canvas_id", "canvas user id"},
    "sis_user_id": {"sis user id", "sis_user_id", "id number", "idnumber", "student id",
                    "student number"},
    "sis_login_id": {"sis login id", "sis_login_id", "login", "username"},
    "email": {"email", "email address", "e-mail"},
}
_ORDER = ("id", "sis_user_id", "sis_login_id", "email", "name")


@dataclass(frozen=True)
class Pair:
    """A roster student and its result; either may be ``None`` (no submission / not in roster)."""

    roster: RosterStudent | None
    result: StudentResult | None
    matched_by: str | None = None


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
    used: set[int] = set()
    keyed = {kind: _index(results, kind) for kind in _ORDER}
    pairs: list[Pair] = []
    for student in roster.students:
        found = None
        for kind in _ORDER:
            value = _roster_key(student, kind)
            candidates = [i for i in keyed[kind].get(value, ()) if i not in used] if value else []
            if kind == "name" and len(keyed[kind].get(value, ())) != 1:
                candidates = []  # an ambiguous name identifies nobody
            if len(candidates) == 1:
                found = (candidates[0], kind)
                break
        if found is None:
            pairs.append(Pair(student, None))
        else:
            used.add(found[0])
            pairs.append(Pair(student, results[found[0]], found[1]))
    pairs.extend(Pair(None, s) for i, s in enumerate(results) if i not in used)
    return RosterMatch(tuple(pairs))


def identity_value(result: StudentResult, kind: str) -> str:
    """The identifier of ``kind`` ("canvas_id", "sis_user_id", "sis_login_id", "email") a
    result carries in its identity columns, or ``""``."""
    names = _IDENTITY_KINDS[kind]
    return next((v for k, v in result.identity if k.strip().lower() in names and v), "")


def normalise_name(name: str) -> str:
    """A name as a comparison key: "Last, First" turned around, case and spacing folded.

    >>> normalise_name("O'Brien,  Seán") == normalise_name("seán o'brien")
    True
    """
    if name.count(",") == 1:
        last, first = name.split(",")
        name = f"{first} {last}"
    name = unicodedata.normalize("NFC", name)
    return re.sub(r"\s+", " ", name).strip().casefold()


def _roster_key(student: RosterStudent, kind: str) -> str:
    if kind == "id":
        return student.id
    if kind == "email":
        return student.email.casefold()
    if kind == "name":
        return normalise_name(student.name)
    return getattr(student, kind)


def _index(results: list[StudentResult], kind: str) -> dict[str, list[int]]:
    index: dict[str, list[int]] = {}
    for i, result in enumerate(results):
        if kind == "name":
            keys = {normalise_name(result.name)} if result.name.strip() else set()
        elif kind == "id":
            keys = {result.id, identity_value(result, "canvas_id")}
        elif kind == "email":
            keys = {result.id.casefold(), identity_value(result, "email").casefold()}
        else:
            keys = {result.id, identity_value(result, kind)}
        for key in keys - {""}:
            index.setdefault(key, []).append(i)
    return index
