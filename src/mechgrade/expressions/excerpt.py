"""A short, safe quotation of user text for messages: never the whole text, never raw control
characters, the offending part marked with ``«…»``.

Every reason mechgrade gives about an answer or a unit quotes the input through
:func:`excerpt`, so a reason stays short (about 200 characters at most) however long the input.

>>> excerpt("98.5.0 ft/s^2", 4, 6)
"'98.5«.0» ft/s^2'"
>>> excerpt("9" * 1000)
"'99999999999999999999999999999999…'"
>>> excerpt("x" * 100 + "#" + "y" * 100, 100, 101)
"'…xxxxxxxxxxxxxxxx«#»yyyyyyyyyyyyyyyy…'"
"""

from __future__ import annotations

WIDTH = 16
"""Characters shown on each side of a marked part (twice that for an unmarked quotation)."""


def _visible(text: str) -> str:
    """Control and other invisible characters as escapes (a line break shows as ``\\n``)."""
    return "".join(c if c.isprintable() or c == " " else c.encode("unicode_escape").decode("ascii")
                   for c in text)


def excerpt(text: str, start: int | None = None, end: int | None = None,
            width: int = WIDTH) -> str:
    """``text`` quoted, at most about ``4 * width`` characters, ``text[start:end]`` marked.

    Without ``start`` the beginning of the text is quoted (cut with ``…``); with it, ``width``
    characters either side of the marked part. ``end`` defaults to one character after ``start``.
    """
    text = str(text)
    if start is None:
        shown = _visible(text[: 2 * width])
        cut = len(text) > 2 * width or len(shown) > 2 * width
        return f"'{shown[: 2 * width]}{'…' if cut else ''}'"
    start = max(0, min(start, len(text)))
    end = start + 1 if end is None else max(start, min(end, len(text)))
    left = _visible(text[max(0, start - width):start])
    marked = _visible(text[start:end][: width + 1])
    right = _visible(text[end:end + width + 1])
    return ("'" + ("…" if start > width or len(left) > width else "") + left[-width:]
            + "«" + marked[:width] + ("…" if len(marked) > width else "") + "»"
            + right[:width] + ("…" if len(right) > width else "") + "'")
