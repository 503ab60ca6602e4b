"""The kinds of load a free-body diagram draws: what a spec's load is physically, and what
a judged diagram's row (:class:`~mechgrade.grade.results.LoadResult`) names. Apart from the
spec, so that a results file is read (by reports and exports) without importing it."""

from __future__ import annotations

from .functions import StrEnum


class LoadKind(StrEnum):
    """What a load is physically: the name a free-body diagram gives its arrow. Members equal
    their text and serialise as it.

    >>> LoadKind("normal"), f"{LoadKind.KINETIC_FRICTION}"
    (<LoadKind.NORMAL: 'normal'>, 'kinetic friction')
    """

    WEIGHT = "weight"
    NORMAL = "normal"
    STATIC_FRICTION = "static friction"
    KINETIC_FRICTION = "kinetic friction"
    TENSION = "tension"
    SPRING = "spring"
    DAMPER = "damper"
    PIN = "pin"
    CONTACT = "contact"
    APPLIED_FORCE = "applied force"
    APPLIED_COUPLE = "applied couple"
    IMPULSE = "impulse"
    REACTION = "reaction"  # an unknown force whose kind the file does not state
