"""Where arrows and labels go on a drawing so that none hides another: plain page geometry
(pixels, y down) shared by the mechanism's picture and the free-body diagrams. No sympy.

>>> apart((0.0, 0.0), (50.0, 0.0), [((0.0, 0.0), (40.0, 0.0))])
((0.0, 10.0), (50.0, 10.0))
"""

from __future__ import annotations

import math

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
