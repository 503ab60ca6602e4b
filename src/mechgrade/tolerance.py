"""The one tolerance rule of mechgrade, used to grade students and to check authors' tests,
and the one rank rule every matrix is judged by (the model's, the solver's, a student's).

A value is right when it is within ``max(rel * scale, abs)`` of the reference, boundary
included; sampled expressions are equal when every sample agrees that way. A singular value
counts for the rank when it is more than :data:`RANK_TOL` of the largest (and of 1); here,
below ``mechanics``, so the mechanics' ranks and :mod:`mechgrade.solve.rules` share it.
"""

from __future__ import annotations

import numpy as np

FLOAT_SLACK = 1e-9
"""Relative slack on every tolerance, so a boundary value (``1.05`` for ``1`` at 5 %) is not
lost to binary rounding."""

REFERENCE_ACCURACY = 1e-6
"""The reference's own numerical accuracy, relative (an integration to an event is trusted to
about this): no tolerance may be tighter (``check`` refuses one; grading never applies one),
so no answer is marked wrong for the last digits of a floating-point reference."""


def within(student, reference, rel: float, abs_: float, scale=None) -> bool:
    """The one tolerance test: ``|s - t| <= max(rel*scale, abs)``, boundary included (with a
    :data:`FLOAT_SLACK` for binary rounding). ``scale`` defaults to ``|t|``; arrays are compared
    elementwise (all must pass) and anything not finite fails.

    >>> within(99.0, 100.0, 0.01, 0.0), within(98.99, 100.0, 0.01, 0.0), within(1.05, 1, 0.05, 0)
    (True, False, True)
    """
    if isinstance(student, _NUMBERS) and isinstance(reference, _NUMBERS):
        # plain floats follow the same IEEE rules as numpy's, without its call overhead
        a, b = float(student), float(reference)
        size = abs(b) if scale is None else abs(float(scale))
        return _fits(abs(a - b), max(rel * size, abs_), size)
    s, t = np.asarray(student, dtype=float), np.asarray(reference, dtype=float)
    if s.shape == t.shape and s.size <= PYTHON_SIZE and abs_ == abs_:
        # The same arithmetic on Python floats: for a number, a vector or the values at a few
        # sample points numpy's set-up costs more than the test, which stops at the first
        # value that fails (judging one answer tries it against every diagnosis).
        fixed = None if scale is None else abs(float(scale))
        for a, b in zip(s.ravel().tolist(), t.ravel().tolist()):
            size = abs(b) if fixed is None else fixed
            if not _fits(abs(a - b), max(rel * size, abs_), size):
                return False
        return True
    return bool(_elementwise(s, t, rel, abs_, None if scale is None else abs(float(scale)))
                .all())


def within_each(student: np.ndarray, reference: np.ndarray, rel: float, abs_: float,
                scale: np.ndarray) -> np.ndarray:
    """:func:`within` for every column of ``student`` and ``reference`` (values x columns),
    each column with its own ``scale``: one boolean per column.

    >>> within_each(np.array([[99.0, 98.99]]), np.array([[100.0, 100.0]]), 0.01, 0.0,
    ...             np.array([100.0, 100.0])).tolist()
    [True, False]
    """
    fits = _elementwise(np.asarray(student, dtype=float), np.asarray(reference, dtype=float),
                        rel, abs_, np.abs(scale))
    return np.all(fits, axis=0, keepdims=False).reshape(-1)


def _elementwise(s: np.ndarray, t: np.ndarray, rel: float, abs_: float, scale) -> np.ndarray:
    with np.errstate(all="ignore"):
        size = np.abs(t) if scale is None else scale
        return _fits(np.abs(s - t), np.maximum(rel * size, abs_), size)


def _fits(difference, limit, size):
    """The rule itself, for floats and arrays alike (a NaN never fits)."""
    return difference <= _allowed(limit, size)


def _allowed(limit, size):
    """The largest difference the rule lets pass: ``limit`` with the :data:`FLOAT_SLACK`."""
    return limit * (1 + FLOAT_SLACK) + 1e-3 * FLOAT_SLACK * size


_NUMBERS = (float, int)
PYTHON_SIZE = 32
"""Arrays up to this size are compared value by value in Python floats (the same IEEE
arithmetic as numpy's, without its set-up)."""


def agree_at_points(rel: float, reference: np.ndarray) -> "AgreeAtPoints":
    """The one "equal at the sample points" test: every value within ``rel`` of the
    reference's (:func:`within`, with a small floor near zero); a value undefined where the
    reference is defined disagrees.

    >>> import numpy as np
    >>> agree_at_points(1e-6, np.array([1.0, 2.0]))(np.array([1.0, 2.0 + 1e-7]), np.array([1.0, 2.0]))
    True
    """
    # the mean size, as np.mean sums it (np.mean itself costs more than judging an answer)
    scale = float(np.add.reduce(np.abs(reference), axis=None, dtype=float)) / reference.size \
        if reference.size else 0.0
    return AgreeAtPoints(rel, max(rel * scale * 1e-3, 1e-12))


class AgreeAtPoints:
    """:func:`agree_at_points`' test: called with two sets of values, or, through
    :meth:`each`, with one set against many candidates in one numpy pass (naming a mistake
    tries an answer against a score of candidates)."""

    __slots__ = ("floor", "rel")

    def __init__(self, rel: float, floor: float):
        self.rel, self.floor = rel, floor

    def __call__(self, s: np.ndarray, t: np.ndarray) -> bool:
        return s.shape == t.shape and within(s, t, self.rel, self.floor)

    def each(self, s: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """Whether ``s`` agrees with each of ``rows`` (candidates stacked along the first
        axis, each of ``s``'s shape): the same answer as calling the test row by row.

        >>> test = AgreeAtPoints(0.01, 1e-12)
        >>> test.each(np.array([2.0, 4.0]), np.array([[2.0, 4.0], [2.0, 4.1], [1.0, 2.0]])).tolist()
        [True, False, False]
        >>> test.each(np.array([2.0, 4.0]), np.ones((3, 3))).tolist()
        [False, False, False]
        """
        return self.rows(rows).each(s)

    def rows(self, rows: np.ndarray) -> "AgreeingRows":
        """The test against fixed ``rows`` (candidates stacked along the first axis), what
        each value allows worked out once: a caller that tries many answers against the same
        candidates (a reference's mistakes) tests each answer in one numpy pass.

        >>> rows = AgreeAtPoints(0.01, 1e-12).rows(np.array([[2.0, 4.0], [2.0, 4.1]]))
        >>> rows.each(np.array([2.0, 4.0])).tolist(), rows.each(np.array([2.0, 4.1])).tolist()
        ([True, False], [False, True])
        """
        rows = np.asarray(rows, dtype=float)
        flat = rows.reshape(len(rows), -1)
        with np.errstate(all="ignore"):
            size = np.abs(flat)
            allowed = _allowed(np.maximum(self.rel * size, self.floor), size)
        return AgreeingRows(rows, flat, allowed)


class AgreeingRows:
    """:meth:`AgreeAtPoints.rows`' prepared test: ``rows`` as given, and each value's
    allowed difference (:func:`_allowed`), row by row the bounds :func:`within` works out."""

    __slots__ = ("allowed", "flat", "rows")

    def __init__(self, rows: np.ndarray, flat: np.ndarray, allowed: np.ndarray):
        self.rows, self.flat, self.allowed = rows, flat, allowed

    def each(self, s: np.ndarray) -> np.ndarray:
        """Whether ``s`` agrees with each row (none when its shape is not a row's)."""
        s = np.asarray(s, dtype=float)
        if self.rows.shape[1:] != s.shape:
            return np.zeros(len(self.rows), dtype=bool)
        with np.errstate(all="ignore"):
            fits = np.abs(s.reshape(1, -1) - self.flat) <= self.allowed
        return np.logical_and.reduce(fits, axis=1)  # np.all, without its Python wrapper


RANK_TOL = 1e-9
"""A singular value (or a pivot) smaller than this part of the largest (at least 1) is zero."""


def significant(magnitudes) -> np.ndarray:
    """Which of the singular values (or pivots) along the last axis count for the rank."""
    m = np.abs(np.asarray(magnitudes, dtype=float))
    largest = m.max(axis=-1, initial=0.0, keepdims=True)
    return m > RANK_TOL * np.maximum(largest, 1.0)


def rank(magnitudes) -> np.ndarray:
    """The rank that singular values (or pivots) along the last axis give."""
    return significant(magnitudes).sum(axis=-1)


def matrix_rank(A) -> int:
    """The rank of the matrix ``A`` by its singular values (:func:`rank`): the solver's
    matrices and a student's equations alike, in whatever unit they are written (rounding
    grows with the entries, so an absolute tolerance counts it as rank in N and not in kN).

    >>> A = np.array([[1e4, 2e4], [3e4, 6e4 + 1e-8]])
    >>> matrix_rank(A), matrix_rank(A / 1e3), matrix_rank(np.zeros((0, 2)))
    (1, 1, 0)
    """
    a = np.asarray(A)
    return int(rank(np.linalg.svd(a, compute_uv=False))) if a.size else 0


def null_space(A: np.ndarray) -> np.ndarray:
    """An orthonormal basis of the null space of ``A`` (columns), by its singular values.

    >>> null_space(np.array([[1.0, 1.0]])).shape
    (2, 1)
    """
    if A.shape[0] == 0:
        return np.eye(A.shape[1])
    # numpy's SVD (LAPACK gesdd, as scipy's): importing scipy.linalg costs more (~0.15 s) than
    # most solves that end in this message
    _, s, vt = np.linalg.svd(A)
    return vt[int(rank(s)):].T


PART = 1e-9
"""A value smaller than this part of the largest of its kind (a vector's component, a fit's
coefficient, a mode's amplitude) is round-off, not a part."""


def parts(values, largest=None, axis: int = -1) -> np.ndarray:
    """Which of ``values`` are parts, not round-off (at most :data:`PART` of ``largest`` in
    size, by default the largest size along ``axis``): an undefined value is no round-off.

    >>> parts(np.array([1.0, -1e-12, np.nan]), 1.0).tolist(), parts(np.zeros(2)).tolist()
    ([True, False, True], [False, False])
    >>> parts(np.array([[3.0, 1e-10], [1e-10, 1e-10]]), axis=1).tolist()
    [[True, False], [True, True]]
    >>> bool(parts(2e-9, 1.0)), bool(parts(2e-9, 10.0))
    (True, False)
    """
    m = np.abs(np.asarray(values))
    if largest is None:
        largest = m.max(axis=axis, initial=0.0, keepdims=True)
    return ~(m <= PART * np.abs(largest))


REAL = 1e-7
"""A root (a closed-form event time or position, SI, evaluated in complex numbers; an
eigenvalue of a motion) is real when its imaginary part is at most this part of its size.
Where two roots meet (a motion that just reaches its event, an inverse sine of 1, a mode
critically damped or free) rounding can make a discriminant negative by a few eps of its
size: the root then carries an imaginary part of about the square root of that (1.5e-8 of its
size; numpy's eigenvalues of a critically damped mode at 3.7 rad/s: 4.1e-8 j), which this
keeps real; a pair of complex roots this near the real axis leaves the equation's least value
within 1e-14 (this squared) of its size of zero, which is rounding too."""


def real(roots, size=None) -> np.ndarray:
    """Whether each root of ``roots`` (complex) is real (:data:`REAL` of ``size``, by default
    its own: its real part's size and 1, in SI); an undefined root is not. The one test of an
    event's times, a ``when``'s positions and a motion's eigenvalues.

    >>> real(np.array([1.0 + 2e-8j, 1e3 + 1e-5j, 1.0 + 1e-6j, 3j, complex("nan")])).tolist()
    [True, True, False, False, False]
    >>> real(np.array([-3.7 + 4.1e-8j, -0.3 + 3.7j]), 3.7).tolist()
    [True, False]
    """
    r = np.asarray(roots, dtype=complex)
    size = 1 + np.abs(r.real) if size is None else np.abs(size)
    return np.abs(r.imag) <= REAL * size
