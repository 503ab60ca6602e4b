"""Options shared by the exporters, checked once when made.

>>> ExportOptions(missing="blank").missing
'blank'
>>> ExportOptions(missing="skip")
Traceback (most recent call last):
...
mechgrade.errors.ExportError: missing: expected 'zero' or 'blank', found 'skip'
"""

from __future__ import annotations

from dataclasses import dataclass

from ..errors import ExportError, Location

MISSING_POLICIES = ("zero", "blank")
GRADESCOPE_VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")
MOODLE_KEYS = ("email", "idnumber")


@dataclass(frozen=True)
class ExportOptions:
    """How to export.

    ``missing``: what a student without a submission gets, ``"zero"`` or ``"blank"`` (an empty
    cell, which LMSs leave ungraded). ``excel_bom``: start CSV files with a UTF-8 byte order mark
    so Excel reads accents right. ``points_possible``: write Canvas's ``Points Possible`` row.
    ``gradescope_visibility``: visibility of the Gradescope tests. ``moodle_key``: the column
    Moodle should map users by, written first (``"email"`` or ``"idnumber"``).
    ``canvas_assignment``: the Canvas assignment to fill, as its column title
    (``"Homework 1 (40211)"``), its title, or its numeric Canvas id (``"40211"``); ``None``
    picks it from the roster (:func:`mechgrade.export.canvas.canvas_column`).
    """

    missing: str = "zero"
    excel_bom: bool = False
    points_possible: bool = True
    gradescope_visibility: str = "visible"
    moodle_key: str = "email"
    canvas_assignment: str | None = None

    def __post_init__(self) -> None:
        for field, allowed in (("missing", MISSING_POLICIES),
                               ("gradescope_visibility", GRADESCOPE_VISIBILITIES),
                               ("moodle_key", MOODLE_KEYS)):
            value = getattr(self, field)
            if value not in allowed:
                expected = " or ".join(repr(a) for a in allowed) if len(allowed) == 2 else \
                    "one of " + ", ".join(repr(a) for a in allowed)
                raise ExportError(f"expected {expected}, found {value!r}",
                                  where=Location(field=field))
