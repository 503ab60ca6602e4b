"""Solutions of problems with bodies and loads, kept in the disk cache (:mod:`.cache`).

A problem with bodies and loads is derived with sympy in more places than its plan (its
kinetics, its events, each mistaken model its generated mistakes come from); what it is solved
to is plain data, so that is what is kept for it: one entry per problem, givens overrides and
objectives asked (:func:`solution_key`; :func:`carried_key` for an answer's error carried
forward), holding the solution (its generated mistakes worked out) or the error solving
raised. ``check`` of an unchanged problem, a second grading run (its
objectives, each answer carried forward) and each student's variant
(:func:`mechgrade.solve.batch.solve_variants`, :func:`variant_keys`) read them back without
sympy. An entry is kept only when reading it back gives exactly what was solved.

>>> from mechgrade.errors import Location, SolveError
>>> from mechgrade.solve.result import ObjectiveFailure, ObjectiveResult, Solution
>>> s = Solution("p", (ObjectiveResult("v", "vector", "m/s", (1.0, 2.0, 0.0), "N"),),
...              failures=(ObjectiveFailure("w", SolveError("no", where=Location("p.yaml"))),))
>>> back = outcome_from(outcome_data(s))
>>> back.results == s.results, str(back.failures[0].error)
(True, 'p.yaml: no')
"""

from __future__ import annotations

from typing import Any, Callable, Collection, Mapping, Sequence

from ..codec import decode, encode
from ..errors import MechgradeError
from . import cache
from .result import Solution


Outcome = Solution | MechgradeError
"""What solving gives: a solution, or the error it raised."""


def solution_key(problem, givens: Mapping[str, float | None] | None,
                 objectives: Collection[str] | None) -> str | None:
    """The entry of ``solve(problem, givens=givens, objectives=objectives)``, or ``None`` when
    it is not kept (the cache off, a problem without a canonical text, a given's value that is
    not a number). Overrides are keyed exactly (each value's ``repr``, in name order) and
    objectives as a set; numpy's and scipy's versions are part of it (the roots a numeric
    solve lands on are theirs).

    >>> from unittest import mock
    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("problems") / "atwood_machine.yaml")
    >>> with mock.patch.dict("os.environ", MECHGRADE_NO_CACHE="0"):
    ...     alike = solution_key(p, {"m1": 2, "g": None}, ["tension", "a1"]) == \\
    ...         solution_key(p, {"g": None, "m1": 2.0}, ("a1", "tension"))
    ...     apart = solution_key(p, {"m1": 2.0}, None) == \\
    ...         solution_key(p, {"m1": 2.0000000000000004}, None)
    >>> alike, apart, solution_key(p, None, None)  # the last with the cache off
    (True, False, None)
    """
    return _key("solution", cache.used_problem_key(problem), givens, objectives)


def carried_key(problem, givens: Mapping[str, float | None] | None,
                objectives: Collection[str] | None) -> str | None:
    """The entry of :func:`~mechgrade.solve.carried.solve_carried` (apart from
    :func:`solution_key`'s: the same givens solved otherwise), or ``None`` when it is not kept.

    >>> from unittest import mock
    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("problems") / "atwood_machine.yaml")
    >>> with mock.patch.dict("os.environ", MECHGRADE_NO_CACHE="0"):
    ...     carried_key(p, {"y''": 1.0}, None) == solution_key(p, {"y''": 1.0}, None)
    False
    """
    return _key("carried", cache.used_problem_key(problem), givens, objectives)


def kept(key: str | None, solving: Callable[[], Solution]) -> Solution:
    """What ``solving()`` gives, read from the entry ``key`` (``None``: not kept), else solved
    and kept there: the solution, or the error it raised (raised again when read).

    >>> kept(None, lambda: "solved")
    'solved'
    """
    if key is None:
        return solving()
    found = load_outcome(key)
    if found is None:
        try:
            found = solving()
        except MechgradeError as err:
            store_outcome(key, err)
            raise
        store_outcome(key, found)
    if isinstance(found, MechgradeError):
        raise found
    return found


def variant_keys(problem, variants: Sequence[Mapping[str, float | None]]
                 ) -> list[str | None]:
    """The entries of ``variants`` (givens overrides) of ``problem`` as
    :func:`~mechgrade.solve.batch.solve_variants` solves them together (apart from
    :func:`solution_key`'s: the two may differ in the last digits)."""
    problem_key = cache.used_problem_key(problem)
    return [_key("variant", problem_key, givens, None) for givens in variants]


def _key(what: str, problem_key: str | None, givens, objectives) -> str | None:
    if problem_key is None:
        return None
    try:
        overrides = [[name, None if value is None else repr(float(value))]
                     for name, value in sorted((givens or {}).items())]
    except (TypeError, ValueError):
        return None
    asked = None if objectives is None else sorted(set(objectives))
    return cache.digest(what, problem_key, overrides, asked, *numeric_versions())


def numeric_versions() -> tuple[str, str]:
    """numpy's and scipy's versions."""
    import numpy

    return numpy.__version__, cache.package_version("scipy", "version.py")


def load_outcome(key: str) -> Outcome | None:
    """The outcome stored under ``key``, or ``None`` when there is none this code could have
    written."""
    return _outcome(cache.load(key))


def store_outcome(key: str, outcome: Outcome) -> None:
    """Keep ``outcome`` under ``key`` (a solution's generated mistakes worked out), unless its
    stored form would leave something out."""
    data = outcome_data(outcome)
    back = _outcome(data)
    if back is not None and same_outcome(back, outcome):
        cache.store(key, data)


ALONE = {"alone": True}
"""The entry of a variant solved on its own (by :func:`~mechgrade.solve.entry.solve`, which
keeps it under :func:`solution_key`)."""


def load_variant(problem, givens: Mapping[str, float | None], key: str) -> Outcome | None:
    """The variant ``givens`` of ``problem`` as :func:`store_variant` kept it under ``key``
    (one of :func:`variant_keys`), or ``None``."""
    data = cache.load(key)
    if data == ALONE:
        alone = solution_key(problem, givens, None)
        data = None if alone is None else cache.load(alone)
    return _outcome(data)


def store_variant(key: str, outcome: Outcome, together: bool) -> None:
    """Keep a variant under ``key`` (one of :func:`variant_keys`): its ``outcome`` if it was
    solved together with others, else only that :func:`solution_key` names it (solving it on
    its own kept it there)."""
    if together:
        store_outcome(key, outcome)
    else:
        cache.store(key, ALONE)


def _outcome(data: Any) -> Outcome | None:
    if data is None:
        return None
    try:
        return outcome_from(data)
    except ValueError:
        return None  # not an entry this code wrote: solved and written again


def outcome_data(outcome: Outcome) -> Any:
    """``outcome`` as plain JSON (:func:`mechgrade.codec.encode`)."""
    return encode(outcome)


def outcome_from(data: Any) -> Outcome:
    """The outcome :func:`outcome_data` gave ``data`` for; raises
    :class:`~mechgrade.codec.CodecError` on anything else."""
    return decode(Outcome, data)


def same_outcome(a: Outcome, b: Outcome) -> bool:
    """Whether two outcomes say the same (errors: of one kind, with equal attributes)."""
    if isinstance(a, Solution) and isinstance(b, Solution):
        return same(a, b)
    return type(a) is type(b) and vars(a) == vars(b) and str(a) == str(b)


def same(a: Solution, b: Solution) -> bool:
    """Whether two solutions say the same (errors compared by their kind and message)."""
    def content(s: Solution) -> tuple:
        return (s.problem, s.results, s.state, s.dof, s.warnings,
                tuple((f.id, type(f.error), str(f.error)) for f in s.failures))
    return content(a) == content(b)
