"""Functions of the state evaluated at many states at once, each a column of an array, and the
small linear algebra of every column at once: what every numeric stage of the solver works
with, whether it solves one instant (one column) or a class of variants.

>>> import numpy as np
>>> call(lambda x, y: x + y, np.array([[1.0, 2.0], [3.0, 4.0]]), 1).tolist()
[[4.0, 6.0]]
"""

from __future__ import annotations

import types
import warnings
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from functools import lru_cache, partial
from typing import Callable, Iterator

import numpy as np

from ..errors import MechgradeError
from .plan import _OnFirstCall
from .rules import cutoff, inverted, significant


@dataclass(frozen=True)
class WithInputs:
    """A function ``f`` of the state and of inputs worked out from it (``inputs``, of the
    state), called with the state: an impact's balances, of its rates just before it.

    >>> WithInputs(lambda x, y, before: x + y - before, lambda x, y: (2 * x,))(1.0, 5.0)
    4.0
    """

    f: Callable
    inputs: Callable

    def __call__(self, *x):
        return self.f(*x, *self.inputs(*x))


@lru_cache(maxsize=4096)
def _batched(f: Callable) -> Callable:
    """``f`` (made by ``sympy.lambdify``) with its matrices built from entries that may be
    arrays of different shapes (a constant beside a column of values)."""
    if isinstance(f, WithInputs):
        return WithInputs(_batched(f.f), _batched(f.inputs))
    if isinstance(f, _OnFirstCall):
        f = f.function
    namespace = dict(f.__globals__)
    namespace["array"] = _array
    return types.FunctionType(f.__code__, namespace, f.__name__, f.__defaults__, f.__closure__)


def _array(rows):
    """``numpy.array`` for the matrices lambdified functions build, with entries of
    different shapes broadcast together."""
    arrays = [e.shape for row in rows for e in row if type(e) is np.ndarray]
    shapes = set(arrays)
    if not arrays or (len(shapes) == 1 and len(arrays) == len(rows) * len(rows[0])):
        return np.array(rows, dtype=float)
    # a constant entry beside arrays: every entry broadcast to the arrays' shape
    out = np.empty((len(rows), len(rows[0])) + np.broadcast_shapes(*shapes))
    for r, row in enumerate(rows):
        for c, entry in enumerate(row):
            out[r, c] = entry
    return out


class FirstErrors:
    """Each column's first error, as the solver of that column alone would raise it: a stage
    judges all columns at once, and a column's message is worded only when it is read (a
    class whose columns fail by the thousand, as a mistaken model's may, words none).

    >>> from mechgrade.errors import SolveError
    >>> errors = FirstErrors(3)
    >>> errors.add(np.array([False, True, True]), lambda i: SolveError(f"first {i}"))
    >>> errors.add(np.array([True, True, False]), lambda i: SolveError(f"second {i}"))
    >>> [str(errors[i]) for i in range(3)], errors.ok.tolist()
    (['second 0', 'first 1', 'first 2'], [False, False, False])
    """

    def __init__(self, count: int) -> None:
        self._pending: list[Callable[[], MechgradeError] | None] = [None] * count

    def add(self, failing, error: Callable[[int], MechgradeError]) -> None:
        """``error(i)`` for every column ``i`` ``failing`` (booleans) that has no error yet."""
        for i in np.flatnonzero(failing):
            if self._pending[i] is None:
                self._pending[i] = partial(error, int(i))

    @property
    def ok(self) -> np.ndarray:
        """Which columns have no error."""
        return np.array([e is None for e in self._pending], dtype=bool)

    def __len__(self) -> int:
        return len(self._pending)

    def __getitem__(self, i: int) -> MechgradeError | None:
        """Column ``i``'s error (``None`` where it has none)."""
        pending = self._pending[i]
        return None if pending is None else pending()


_QUIET: ContextVar[bool] = ContextVar("mechgrade_quiet", default=False)


@contextmanager
def quiet() -> Iterator[None]:
    """numpy's floating-point warnings and Python's warnings silenced for a whole stage (a
    state where a function is undefined is judged by its NaN, not by a warning): a
    :func:`call` inside, or a nested ``quiet()``, then costs nothing more (a single solve
    makes dozens, an integration thousands).

    >>> import numpy as np
    >>> with quiet():
    ...     np.log(np.array([-1.0])).tolist()
    [nan]
    """
    if _QUIET.get():
        yield
        return
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        token = _QUIET.set(True)
        try:
            yield
        finally:
            _QUIET.reset(token)


def call(f: Callable, X: np.ndarray, size: int) -> np.ndarray:
    """``f`` at every column of ``X`` (the states, one per column): ``size`` values each, as
    a ``(size, N)`` array, :func:`quiet`."""
    if _QUIET.get():
        return loud_call(f, X, size)
    with quiet():
        return loud_call(f, X, size)


def loud_call(f: Callable, X: np.ndarray, size: int) -> np.ndarray:
    """:func:`call` for a caller that has silenced numpy's warnings already."""
    n = X.shape[1]
    if n == 1:
        # one column (a single solve's integration): its entries as numbers, without numpy's
        # cost per operation on one-element arrays and _array's broadcasting (4x faster)
        return np.asarray(f(*X[:, 0]), dtype=float).reshape(size, 1)
    out = np.asarray(_batched(f)(*X), dtype=float)
    if out.size == size * n:
        return out.reshape(size, n)
    return np.broadcast_to(out.reshape(size, 1), (size, n)).copy()


def least_squares_solution(A: np.ndarray, b: np.ndarray, det: np.ndarray | None = None
                           ) -> np.ndarray:
    """The least-squares solution of ``A x = b`` at every column (``A``: rows x unknowns x N,
    ``b``: rows x N), the minimum-norm one where ``A`` is singular, as ``scipy.linalg.lstsq``
    gives it; a square system of up to three unknowns by Cramer's rule (LAPACK's per-matrix
    cost is most of the time of so small a solve), ``det``: its determinants where known
    (:func:`determinants`)."""
    rows_, k, count = A.shape
    if rows_ == k == 1:
        with np.errstate(all="ignore"):
            solved = b / A[0]
        if np.isfinite(solved.sum()):
            return solved
    else:
        solved = np.full((k, count), np.nan)
    if rows_ == k and 1 < k <= 3 and count == 1:
        # one column (a single solve's integration): the same products on Python floats,
        # bit for bit, without numpy's cost per operation on one-element arrays
        M, v = A[:, :, 0].tolist(), b[:, 0].tolist()
        det_ = determinant(M)
        if det_ != 0:
            for j in range(k):
                solved[j, 0] = determinant([[v[i] if c == j else x for c, x in enumerate(row)]
                                             for i, row in enumerate(M)]) / det_
    elif rows_ == k and 1 < k <= 3:
        with np.errstate(all="ignore"):
            det = determinant(A) if det is None else det
            # A with its column j replaced by b, for every j at once (rows x unknowns x j x
            # N): one determinant of arrays k times as long, each entry the same products
            replaced = np.repeat(A[:, :, None], k, axis=2)
            every = np.arange(k)
            replaced[:, every, every] = b[:, None]
            solved = determinant(replaced) / det
    left = ~np.isfinite(solved).all(axis=0)
    if left.any():
        Ab = A[:, :, left].transpose(2, 0, 1)
        bb = b[:, left].T[:, :, None]
        try:
            part = np.linalg.solve(Ab, bb) if rows_ == k else None
        except np.linalg.LinAlgError:  # a singular column: the least-squares solution
            part = None
        if part is None:
            part = np.linalg.pinv(Ab, rtol=cutoff(rows_, k)) @ bb
        solved[:, left] = part[:, :, 0].T
    return solved


def determinants(A: np.ndarray) -> np.ndarray | None:
    """The determinants :func:`least_squares_solution` solves ``A`` with (``None`` where it
    solves without), for a matrix that several right-hand sides share.

    >>> determinants(np.array([[[2.0], [1.0]], [[1.0], [3.0]]])).tolist()
    [5.0]
    """
    rows_, k = A.shape[:2]
    if not (rows_ == k and 1 < k <= 3):
        return None
    with np.errstate(all="ignore"):
        return determinant(A)


def determinant(A):
    """The determinant of a square matrix of up to three rows: of every column's (``A``: rows
    x rows x N), or of one given as nested lists of floats.

    >>> determinant([[2.0, 1.0], [1.0, 3.0]]), float(determinant(np.eye(3)[:, :, None])[0])
    (5.0, 1.0)
    """
    k = len(A)
    if k == 1:
        return A[0][0]
    if k == 2:
        (a, b), (c, d) = A  # (each entry read once: a view of an array's is made once)
        return a * d - b * c
    (a, b, c), (d, e, f), (g, h, i) = A
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)


def least_squares(J: np.ndarray, r: np.ndarray, good: np.ndarray):
    """The minimum-norm least-squares step ``-pinv(J) r`` of every column (``J``: rows x
    unknowns x N, ``r``: rows x N; columns not ``good`` are left at zero), the rank of each
    ``J`` (as :func:`~.levels.nullspace` counts it) and each one's right singular vectors
    (N x unknowns x unknowns: the rows after the rank span its nullspace)."""
    Jb = np.where(good, J, 0.0).transpose(2, 0, 1)
    U, s, Vt = np.linalg.svd(Jb, full_matrices=True)
    k = s.shape[1]
    big = significant(s)
    rank = big.sum(axis=1)
    with np.errstate(all="ignore"):
        inverse = inverted(s, J.shape[0], J.shape[1])
        coeff = np.einsum("nmk,mn->nk", U[:, :, :k], np.where(good, r, 0.0)) * inverse
        step = -np.einsum("nkj,nk->jn", Vt[:, :k, :], coeff)
    return step, rank, Vt
