"""Options shared by the exporters, checked once when made.

>>> ExportOptions(missing="blank").missing
<MissingGrade.BLANK: 'blank'>
>>> ExportOptions(missing="skip")
Traceback (most recent call last):
...
mechgrade.errors.ExportError: missing: expected 'zero' or 'blank', found 'skip'
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import Enum

from ..errors import ExportError, Location


class MissingGrade(Enum):
    """What a student without a submission gets: 0, or an empty cell (LMSs leave it
    ungraded)."""

    ZERO = "zero"
    BLANK = "blank"


class Visibility(Enum):
    """When Gradescope shows the tests to the student (Gradescope's own words)."""

    VISIBLE = "visible"
    HIDDEN = "hidden"
    AFTER_DUE_DATE = "after_due_date"
    AFTER_PUBLISHED = "after_published"


class MoodleKey(Enum):
    """The column Moodle maps users by."""

    EMAIL = "email"
    IDNUMBER = "idnumber"


MAX_SCALE = 1_000_000


@dataclass(frozen=True)
class ExportOptions:
    """How to export.

    ``missing``: what a student without a submission gets (:class:`MissingGrade`).
    ``excel_bom``: start CSV files with a UTF-8 byte order mark so Excel reads accents right.
    ``points_possible``: write Canvas's ``Points Possible`` row.
    ``gradescope_visibility``: visibility of the Gradescope tests. ``moodle_key``: the column
    Moodle should map users by, written first. Each of these three may be given as its
    member or its text, read into its type when the options are made.
    ``canvas_assignment``: the Canvas assignment to fill, as its column title
    (``"Homework 1 (40211)"``), its title, or its numeric Canvas id (``"40211"``); ``None``
    picks it from the roster (:func:`mechgrade.export.canvas.canvas_column`).
    ``replace_existing``: replace grades already in the LMS (the roster's cells) that differ
    from mechgrade's; by default they are kept (:mod:`mechgrade.export.changes`).
    ``dry_run``: write nothing, list what the import would change. ``scale_to``: the LMS's
    points for the assignment; Canvas and Moodle grades are scaled from the assignment's points
    to it.

    >>> ExportOptions(scale_to=0)
    Traceback (most recent call last):
    ...
    mechgrade.errors.ExportError: scale_to: expected points above 0 and at most 1000000, found 0
    """

    missing: MissingGrade = MissingGrade.ZERO
    excel_bom: bool = False
    points_possible: bool = True
    gradescope_visibility: Visibility = Visibility.VISIBLE
    moodle_key: MoodleKey = MoodleKey.EMAIL
    canvas_assignment: str | None = None
    replace_existing: bool = False
    dry_run: bool = False
    scale_to: float | None = None

    def __post_init__(self) -> None:
        for field, kind in (("missing", MissingGrade), ("gradescope_visibility", Visibility),
                            ("moodle_key", MoodleKey)):
            value = getattr(self, field)
            allowed = [member.value for member in kind]
            if not isinstance(value, kind) and value not in allowed:
                expected = " or ".join(repr(a) for a in allowed) if len(allowed) == 2 else \
                    "one of " + ", ".join(repr(a) for a in allowed)
                raise ExportError(f"expected {expected}, found {value!r}",
                                  where=Location(field=field))
            object.__setattr__(self, field, kind(value))
        if self.scale_to is not None and not (math.isfinite(self.scale_to)
                                              and 0 < self.scale_to <= MAX_SCALE):
            raise ExportError(f"expected points above 0 and at most {MAX_SCALE}, found "
                              f"{self.scale_to:g}", where=Location(field="scale_to"))
