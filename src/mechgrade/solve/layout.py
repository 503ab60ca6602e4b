"""Where arrows and labels go on a drawing so that none hides another: plain page geometry
(pixels, y down) shared by the mechanism's picture and the free-body diagrams. No sympy.

>>> apart((0.0, 0.0), (50.0, 0.0), [((0.0, 0.0), (40.0, 0.0))])
((0.0, 10.0), (50.0, 10.0))
"""

from __future__ import annotations

import math

from ..spec.dynamics import OutlineKind

Point2 = tuple[float, float]
Box = tuple[float, float, float, float]  # left, top, right, bottom


def apart(tail: Point2, head: Point2, placed: list) -> tuple[Point2, Point2]:
    """The arrow moved across itself until it overlaps no arrow already ``placed`` (pairs of
    tail and head); unmoved when every offset tried overlaps one."""
    for shift in (0.0, 10.0, -10.0, 20.0, -20.0, 30.0):
        dx, dy = head[0] - tail[0], head[1] - tail[1]
        size = math.hypot(dx, dy) or 1.0
        nx, ny = -dy / size * shift, dx / size * shift
        t, h = (tail[0] + nx, tail[1] + ny), (head[0] + nx, head[1] + ny)
        if not any(overlaps(t, h, a, b) for a, b in placed):
            return t, h
    return tail, head


def overlaps(t1: Point2, h1: Point2, t2: Point2, h2: Point2) -> bool:
    """Whether two arrows lie along one line within a few pixels and share some length.

    >>> overlaps((0, 0), (50, 0), (20, 2), (80, 2)), overlaps((0, 0), (50, 0), (0, 0), (0, 50))
    (True, False)
    """
    d1 = (h1[0] - t1[0], h1[1] - t1[1])
    d2 = (h2[0] - t2[0], h2[1] - t2[1])
    n1, n2 = math.hypot(*d1) or 1.0, math.hypot(*d2) or 1.0
    if abs(d1[0] * d2[1] - d1[1] * d2[0]) / (n1 * n2) > 0.15:
        return False
    # the distance of the second arrow's ends from the first one's line
    off = [abs((p[0] - t1[0]) * d1[1] - (p[1] - t1[1]) * d1[0]) / n1 for p in (t2, h2)]
    if min(off) > 6.0:
        return False
    along = sorted(((p[0] - t1[0]) * d1[0] + (p[1] - t1[1]) * d1[1]) / n1 for p in (t2, h2))
    return along[1] > 2.0 and along[0] < n1 - 2.0


def crosses(box: Box, tail: Point2, head: Point2) -> bool:
    """Whether the segment from ``tail`` to ``head`` passes through ``box``.

    >>> crosses((0, 0, 10, 10), (-5, 5), (15, 5)), crosses((0, 0, 10, 10), (-5, 20), (15, 20))
    (True, False)
    """
    for k in range(11):
        x = tail[0] + (head[0] - tail[0]) * k / 10
        y = tail[1] + (head[1] - tail[1]) * k / 10
        if box[0] - 2 < x < box[2] + 2 and box[1] - 2 < y < box[3] + 2:
            return True
    return False


def collides(box: Box, taken: list, avoid: list | tuple = ()) -> bool:
    """Whether ``box`` overlaps a box ``taken`` (with a small gap) or a segment of ``avoid``.

    >>> collides((0, 0, 10, 10), [(12, 0, 20, 10)]), collides((0, 0, 10, 10), [(30, 0, 40, 9)])
    (True, False)
    """
    return any(box[0] < b[2] + 4 and b[0] < box[2] + 4 and box[1] < b[3] + 2
               and b[1] < box[3] + 2 for b in taken) \
        or any(crosses(box, t, h) for t, h in avoid)


ROUND = (OutlineKind.DISK, OutlineKind.RING, OutlineKind.CYLINDER, OutlineKind.SPHERE,
         OutlineKind.SHELL)
"""Shapes drawn as a circle of their radius (their last size)."""


def outline_extent(kind: OutlineKind, at, sizes, axis: str, axes) -> list[Point2]:
    """The points (inertial x and y, m) a body's part of shape ``kind`` centred ``at``
    reaches: a rod's two ends along its ``axis``, a block's four corners (its first two sides
    along the body's x and y ``axes``), a round shape's bounding box, else its centre.
    Unknown sizes count as zero.

    >>> outline_extent(OutlineKind.ROD, (0, 0), (2.0,), "x", ((1, 0, 0), (0, 1, 0), None))
    [(-1.0, 0.0), (1.0, 0.0)]
    """
    size = sizes[0] if sizes and sizes[0] is not None else 0.0
    if kind == OutlineKind.ROD and axes is not None and axis:
        direction = axes["xyz".index(axis)]
        if direction is not None:
            return [(at[0] + s * size / 2 * direction[0], at[1] + s * size / 2 * direction[1])
                    for s in (-1, 1)]
    if kind == OutlineKind.BLOCK and axes is not None:
        ex, ey = axes[0], axes[1]
        if ex is not None and ey is not None:
            a, b = size / 2, (sizes[1] or 0.0) / 2
            return [(at[0] + sa * a * ex[0] + sb * b * ey[0],
                     at[1] + sa * a * ex[1] + sb * b * ey[1])
                    for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    if kind in ROUND and sizes:
        radius = sizes[-1] or 0.0
        return [(at[0] - radius, at[1] - radius), (at[0] + radius, at[1] + radius)]
    return [(at[0], at[1])]
