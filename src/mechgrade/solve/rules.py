"""The rules the numeric solver judges by, each written once: whether an equation holds, the
rank of a matrix (the grader's too: a student's equations, directions, rates), whether a root
is on the branch the spec asks for, whether a closed-form root is real. Each takes arrays, so
one instant and a class of variants (one column each) are judged alike. The rank rule lives
in :mod:`mechgrade.tolerance` (the mechanics, which cannot import the solver, judge ranks by
it too); it is named here as well.

>>> import numpy as np
>>> satisfied(np.array([1e-12, 1e-3]), np.array([1.0, 1.0]), 1e-6).tolist()
[True, False]
>>> int(rank(np.array([3.0, 1e-12]))), rank(np.array([[2.0, 1.0], [1.0, 0.0]])).tolist()
(1, [2, 1])
"""

from __future__ import annotations

import numpy as np

from ..spec.model import Root
from ..tolerance import RANK_TOL as RANK_TOL
from ..tolerance import REAL as REAL
from ..tolerance import matrix_rank as matrix_rank
from ..tolerance import null_space as null_space
from ..tolerance import rank as rank
from ..tolerance import real as real
from ..tolerance import significant as significant

RESIDUAL_FLOOR = 1e-10
"""What a residual may keep beside the problem's ``consistency`` times its terms' size: an
equation whose terms are all zero holds to rounding, not exactly."""

PROBE_TOL = 1e-7
"""An objective is the same at two states when it differs by at most this part of its size
(and 1e-12): a root found again, an objective that what the givens leave free does not move."""

REQUIRED = 1e-9
"""How far from zero the expression an objective requires to be zero (an equilibrium, a
motion at rest) may be at an instant of the kinematics for the objective to exist there."""

REQUIRED_KINETIC = 1e-8
""":data:`REQUIRED` at an instant of the kinetics, whose second rates and reactions come out
of a linear solve (and an integration) with more rounding than the kinematics' levels; and
the power of a workless constraint there, of the largest rate (and 1)."""

OPEN = 1e-9
"""An unknown is left open by equations whose solutions form a null space when its component
in a direction of that space is more than this (the basis is orthonormal)."""

SAME_VALUE = 1e-6
"""Two roots have the same value of a quantity when they differ by at most this part of it
(and of 1): the smallest of the first positive roots, the unknowns two branches differ in,
the closed-form root that is the position a ``when`` was walked to."""

BEFORE_EVENT = 1e-9
"""The moment just before an event (its time times one minus this) at which the limits of
the second rates and reactions are read; an instant within this part of an event's time is
at the event (a phase read at the end of a slip is read while it slips)."""

MOMENT = 1e-7
"""A moment away from an instant, by this part of its time (or seconds, before t = 1 s), where
a limit is read by stepping along the solved rates: the loads of a free-body diagram before an
event (a kinetic friction whose slip ends there has its direction only in that limit), a slip
speed's sign just after it switched. Far inside any tolerance: the rates moved are off by
about this part."""


def moment(t):
    """The step :data:`MOMENT` away from the time ``t`` (s, one or an array).

    >>> float(moment(0.0)), float(moment(np.array([20.0]))[0])
    (1e-07, 2e-06)
    """
    return MOMENT * np.maximum(np.abs(t), 1.0)


PROJECTED = 1e-12
"""A state moved a moment along its motion (a derivation's sampled loads, see
:func:`~.derivation.motion_samples`) is back on its position constraints when each residual
is at most this part of its terms' size (and of 1): where Gauss-Newton stops. Not
:func:`satisfied`, which judges whether a solved state holds the equations (to the problem's
``consistency``, with :data:`RESIDUAL_FLOOR`): this one ends an iteration that can go on
converging, and the loads sampled there stand in for the motion's own, so it goes on to
rounding, far inside the problem's tolerance."""


def projected(residual, scale) -> bool:
    """Whether every position constraint's ``residual`` (its terms' size ``scale``) is
    within :data:`PROJECTED` of zero.

    >>> projected(np.array([1e-13, -2e-12]), np.array([0.0, 5.0])), projected(np.array([1e-11]), 1.0)
    (True, False)
    """
    return bool(np.all(np.abs(residual) <= PROJECTED * (np.abs(scale) + 1.0)))


ON_BRANCH = 1e-9
"""A root is positive (or negative) when it is more than this part of its quantity's typical
size away from zero: nearer, it is zero to the rounding of the solve."""


CONTACT = 1e-9
"""A contact lets go when its normal force is below minus this (N), and a static friction
slips when its force is more than ``1 +`` this times ``mu N`` (and 1e-12 N): a contact that
just holds is judged by the rounding of the solve, not against it."""


def pushes(normal) -> np.ndarray:
    """Whether each normal force ``normal`` (N) pushes, or is zero to rounding
    (:data:`CONTACT`).

    >>> pushes(np.array([1.0, -1e-12, -1e-3])).tolist()
    [True, True, False]
    """
    with np.errstate(invalid="ignore"):
        return ~(np.asarray(normal) < -CONTACT)


def sticks(friction, normal, mu) -> np.ndarray:
    """Whether each static friction force of size ``friction`` stays within ``mu`` times its
    ``normal`` force (:data:`CONTACT`).

    >>> sticks(np.array([1.0, 1.0 + 1e-12, 1.1]), 2.0, 0.5).tolist()
    [True, True, False]
    """
    with np.errstate(invalid="ignore"):
        return ~(np.asarray(friction) > mu * np.asarray(normal) * (1 + CONTACT) + 1e-12)


def satisfied(residual, scale, consistency: float) -> np.ndarray:
    """Whether each equation holds: ``|residual| <= consistency * |scale| + 1e-10`` (``scale``
    the sum of the sizes of its terms); an undefined residual does not hold."""
    with np.errstate(invalid="ignore"):
        return np.abs(residual) <= consistency * np.abs(scale) + RESIDUAL_FLOOR


def first_off(residual, scale, consistency: float) -> int | None:
    """The first equation that does not hold (:func:`satisfied`), or ``None``."""
    off = np.flatnonzero(~satisfied(residual, scale, consistency))
    return int(off[0]) if len(off) else None


def cutoff(rows: int, columns: int) -> float:
    """The part of the largest singular value below which a least-squares solution of a
    ``rows`` x ``columns`` system treats one as zero (eps times the larger dimension, as
    numpy's ``pinv`` cuts them): one cutoff for every such solution, one instant alone or a
    class of them, whatever its rank (:func:`significant`) says of freedoms.

    >>> cutoff(3, 2) == 3 * float(np.finfo(float).eps)
    True
    """
    return float(np.finfo(float).eps * max(rows, columns, 1))


def inverted(values, rows: int, columns: int) -> np.ndarray:
    """The reciprocals of the singular values ``values`` (along the last axis) of a ``rows`` x
    ``columns`` system that its least-squares solution divides by (:func:`cutoff`), 0 for
    the others: the minimum-norm solution along them.

    >>> inverted(np.array([2.0, 1e-17, 0.0]), 3, 3).tolist()
    [0.5, 0.0, 0.0]
    """
    s = np.asarray(values, dtype=float)
    kept = s > cutoff(rows, columns) * s.max(axis=-1, initial=0.0, keepdims=True)
    return np.divide(1.0, s, out=np.zeros(s.shape), where=kept)


def left_open(basis) -> np.ndarray:
    """Which unknowns (rows) the null space ``basis`` (orthonormal columns, or one direction)
    leaves open: those with a component more than :data:`OPEN` along one of its directions.
    The one rule for the solver's free rates and reactions and a student's free unknowns.

    >>> left_open(np.array([[0.8, 0.0], [1e-12, 0.0], [0.6, 1.0]])).tolist()
    [True, False, True]
    >>> left_open(np.array([0.0, 1.0])).tolist(), left_open(np.zeros((2, 0))).tolist()
    ([False, True], [False, False])
    """
    b = np.abs(np.asarray(basis, dtype=float))
    return b.reshape(len(b), -1).max(axis=1, initial=0.0) > OPEN


def same_value(a, b) -> bool:
    """Whether the values ``a`` and ``b`` of a quantity at two roots are the same
    (:data:`SAME_VALUE`).

    >>> same_value(2.0, 2.0 + 1e-7), same_value(0.0, 1e-5)
    (True, False)
    """
    return bool(abs(a - b) <= SAME_VALUE * (1 + abs(a)))


def near_zero(values, scales) -> np.ndarray:
    """Whether each root ``values`` (of a quantity of typical size ``scales``) is zero to the
    rounding of the solve (:data:`ON_BRANCH`): put at zero, and shown as 0.

    >>> near_zero(np.array([1e-12, 1e-6, -1e-10]), np.array([1.0, 1.0, 0.01])).tolist()
    [True, False, False]
    """
    return np.abs(values) <= ON_BRANCH * np.asarray(scales)


def on_branch(values, scales, root: Root | None) -> np.ndarray:
    """Whether each root ``values`` (of a quantity of typical size ``scales``) is on the
    ``root`` a branch asks for (any root is on no branch).

    >>> on_branch(np.array([1.0, 1e-12, -2.0]), 1.0, Root.POSITIVE).tolist()
    [True, False, False]
    """
    x = np.asarray(values, dtype=float)
    if root in (Root.POSITIVE, Root.FIRST_POSITIVE):
        return x > ON_BRANCH * np.asarray(scales)
    if root is Root.NEGATIVE:
        return x < -ON_BRANCH * np.asarray(scales)
    return np.ones(x.shape, dtype=bool)


def unchanged(before, after) -> np.ndarray:
    """Whether each column (values along the first axis) of ``after`` is ``before``'s, to
    :data:`PROBE_TOL` of ``before``'s largest size: where a value is undefined, whether the
    same values are undefined in both.

    >>> unchanged(np.array([[1.0, 1.0, np.nan]]), np.array([[1.0 + 1e-9, 1.1, np.nan]])).tolist()
    [True, False, True]
    """
    a, b = np.asarray(before, dtype=float), np.asarray(after, dtype=float)
    fa, fb = np.isfinite(a), np.isfinite(b)
    if fa.all() and fb.all():  # every value defined: the same test without the masks (a
        # single solve compares a few values many times, where each numpy call counts)
        scale = np.maximum(np.abs(a).max(axis=0, initial=0.0), 1e-12)
        return np.abs(a - b).max(axis=0, initial=0.0) <= PROBE_TOL * scale + 1e-12
    finite = fa.all(axis=0) & fb.all(axis=0)
    scale = np.maximum(np.abs(np.where(fa, a, 0.0)).max(axis=0, initial=0.0), 1e-12)
    with np.errstate(invalid="ignore"):
        gap = np.abs(np.where(finite, a - b, 0.0)).max(axis=0, initial=0.0)
    return np.where(finite, gap <= PROBE_TOL * scale + 1e-12, (fa == fb).all(axis=0))
