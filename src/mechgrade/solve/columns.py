"""Functions of the state evaluated at many states at once, each a column of an array, and the
small linear algebra of every column at once: what every numeric stage of the solver works
with, whether it solves one instant (one column) or a class of variants.

>>> import numpy as np
>>> call(lambda x, y: x + y, np.array([[1.0, 2.0], [3.0, 4.0]]), 1).tolist()
[[4.0, 6.0]]
"""

from __future__ import annotations

import gc
import types
import warnings
from contextlib import contextmanager, nullcontext
from contextvars import ContextVar
from dataclasses import dataclass
from functools import lru_cache, partial
from typing import Callable, Iterator, Sequence

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


@contextmanager
def collector_paused() -> Iterator[None]:
    """Python's cyclic garbage collector paused while a class is solved, and resumed after
    (as it was: a nested pause, or one the caller made, is left alone). A class makes tens of
    thousands of arrays and results that live on, none of them garbage in a cycle: with the
    collector running, its full collections rescan everything the process holds (the imports,
    every derived plan, the results kept so far) several times per class, which measured up
    to half of a class's time (ruina_10_11: 0.77 -> 0.40 ms CPU per student over 6 warm
    classes of 200; a pendulum 0.23 -> 0.13; integrated problems within noise). Whatever
    cyclic garbage a class leaves is collected by the next collection after it.

    >>> import gc
    >>> with collector_paused():
    ...     gc.isenabled()
    False
    >>> gc.isenabled()
    True
    """
    if not gc.isenabled():
        yield
        return
    gc.disable()
    try:
        yield
    finally:
        gc.enable()


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
    return _shaped(_batched(f)(*X), size, n)


def loud_calls(f: Callable, X: np.ndarray, sizes: Sequence[int]) -> list[np.ndarray]:
    """:func:`loud_call` of a function of several matrices (``sizes`` values each).

    >>> [v.tolist() for v in loud_calls(lambda x: (x, [[2 * x]]), np.array([[1.0, 2.0]]), (1, 1))]
    [[[1.0, 2.0]], [[2.0, 4.0]]]
    """
    n = X.shape[1]
    outs = f(*X[:, 0]) if n == 1 else _batched(f)(*X)
    return [_shaped(out, size, n) for out, size in zip(outs, sizes)]


def _shaped(out, size: int, n: int) -> np.ndarray:
    """A lambdified function's value at ``n`` columns as a ``(size, n)`` array (a constant
    one broadcast to every column)."""
    out = np.asarray(out, dtype=float)
    if out.size == size * n:
        return out.reshape(size, n)
    return np.broadcast_to(out.reshape(size, 1), (size, n)).copy()


def least_squares_solution(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The least-squares solution of ``A x = b`` at every column (``A``: rows x unknowns x N,
    ``b``: rows x N), the minimum-norm one where ``A`` is singular, as ``scipy.linalg.lstsq``
    gives it; a square system of up to three unknowns by Cramer's rule (LAPACK's per-matrix
    cost is most of the time of so small a solve; :class:`Cramer` for a matrix that many
    right-hand sides share)."""
    rows_, k, count = A.shape
    if rows_ == k == 1:
        with _silenced():
            solved = b / A[0]
        if np.isfinite(solved.sum()):
            return solved
    elif by_cramer(rows_, k) and count == 1:
        # one column (a single solve's integration): the same products on Python floats,
        # bit for bit, without numpy's cost per operation on one-element arrays
        solved = np.full((k, count), np.nan)
        M, v = A[:, :, 0].tolist(), b[:, 0].tolist()
        det_ = determinant(M)
        if det_ != 0:
            for j in range(k):
                solved[j, 0] = determinant(_replaced(M, j, v)) / det_
    elif by_cramer(rows_, k):
        # the same products on the rows of every column at once (each entry a view of A's)
        M, v = [list(row) for row in A], list(b)
        with _silenced():
            solved = np.array([determinant(_replaced(M, j, v)) for j in range(k)]) \
                / determinant(M)
    else:
        solved = np.full((k, count), np.nan)
    return _where_singular(A, b, solved)


def _silenced():
    """numpy's floating-point warnings silenced, unless a :func:`quiet` stage has already."""
    return nullcontext() if _QUIET.get() else np.errstate(all="ignore")


def _replaced(M: list, j: int, v: list) -> list:
    """The square matrix ``M`` (nested lists) with its column ``j`` replaced by ``v``."""
    return [[v[i] if c == j else x for c, x in enumerate(row)] for i, row in enumerate(M)]


def _where_singular(A: np.ndarray, b: np.ndarray, solved: np.ndarray) -> np.ndarray:
    """``solved`` with each column Cramer's rule left undefined (a singular ``A``) solved by
    LAPACK: its solution, else its minimum-norm least-squares one."""
    if np.isfinite(solved).all():  # (the common case, checked in two operations)
        return solved
    left = ~np.isfinite(solved).all(axis=0)
    if left.any():
        rows_, k = A.shape[:2]
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


class Cramer:
    """:func:`least_squares_solution` of a matrix ``A`` (rows x unknowns x N) that many
    right-hand sides share (a mass matrix along an integration). Where Cramer's rule solves
    it (square, up to three unknowns: :func:`by_cramer`) its products are worked out once:
    those of ``A``'s entries alone are evaluated here, those by an entry 0 at every column
    left out (with ``A`` and ``b`` finite they add a zero, or make one: no digit of the
    solution), and a product two determinants share is made once. A solve then makes the
    products that read ``b``, each as Cramer's rule makes it: the same bits.

    >>> A = np.array([[[2.0, 4.0], [0.0, 0.0]], [[0.0, 0.0], [5.0, 8.0]]])
    >>> b = np.array([[1.0, 2.0], [3.0, 4.0]])
    >>> solver = Cramer(A)
    >>> len(solver.steps), solver.solve(b).tolist() == least_squares_solution(A, b).tolist()
    (2, True)
    """

    def __init__(self, A: np.ndarray, *, _from: tuple | None = None) -> None:
        self.A = A
        self.steps: tuple = ()
        self.numerators: tuple | None = None
        if _from is not None:  # (a subset of another's columns: see of)
            self.det, self.constants, self.steps, self.numerators = _from
            return
        rows_, k = A.shape[:2]
        if not by_cramer(rows_, k):
            return
        graph = _Graph()
        entries = [[graph.constant(A[r, c]) for c in range(k)] for r in range(k)]
        b = [_Term(graph, row=i) for i in range(k)]
        with np.errstate(all="ignore"):
            self.det = determinant(A)
            numerators = [determinant(_replaced(entries, j, b)) for j in range(k)]
        self.constants, self.steps, self.numerators = graph.compiled(numerators, k)

    def of(self, cols: np.ndarray) -> Cramer:
        """The columns ``cols`` only."""
        if self.numerators is None:
            return Cramer(self.A[:, :, cols])
        return Cramer(self.A[:, :, cols], _from=(
            self.det[cols], [c[cols] for c in self.constants], self.steps, self.numerators))

    def solve(self, b: np.ndarray) -> np.ndarray:
        """The solution at every column of ``b`` (rows x N, finite, as ``A``), numpy's
        warnings silenced by the caller (:func:`quiet`)."""
        if self.numerators is None:
            return least_squares_solution(self.A, b)
        values = [*b, *self.constants]
        for f, i, j in self.steps:
            values.append(f(values[i]) if j < 0 else f(values[i], values[j]))
        solved = np.empty(b.shape)
        for row, n in zip(solved, self.numerators):
            np.divide(values[n], self.det, out=row)
        return _where_singular(self.A, b, solved)


def by_cramer(rows_: int, k: int) -> bool:
    """Whether :func:`least_squares_solution` solves a system of ``rows_`` equations in
    ``k`` unknowns by Cramer's rule (square, two or three unknowns)."""
    return rows_ == k and 1 < k <= 3


class _Graph:
    """The products :class:`Cramer` makes, built by :func:`determinant` on :class:`_Term`
    entries; each made once (keyed by its operation and operands)."""

    def __init__(self) -> None:
        # (keyed by the operands' ids: each lives here, or among the entries and rows of
        # the determinants being built, until the graph is compiled; no id is reused)
        self.made: dict[tuple, _Term] = {}

    def constant(self, value: np.ndarray) -> _Term:
        return _Term(self, value=value)

    def made_of(self, f, left: _Term, right: _Term | None = None) -> _Term:
        key = (f, id(left), id(right))
        if key not in self.made:
            if left.value is not None and (right is None or right.value is not None):
                value = f(left.value) if right is None else f(left.value, right.value)
                self.made[key] = _Term(self, value=value)
            else:
                self.made[key] = _Term(self, step=(f, left, right))
        return self.made[key]

    def compiled(self, results: list[_Term], rows: int) -> tuple[list, tuple, tuple]:
        """The constants, steps and result slots a solve evaluates: slot ``i < rows`` is
        ``b``'s row ``i``, then the constants, then each step's value, in order."""
        order: list[_Term] = []
        seen: set[int] = set()

        def visit(term: _Term) -> None:
            if id(term) in seen:
                return
            seen.add(id(term))
            for operand in term.step[1:] if term.step else ():
                if operand is not None:
                    visit(operand)
            order.append(term)

        for term in results:
            visit(term)
        constants = [t for t in order if t.value is not None]
        steps = [(t, t.step) for t in order if t.step is not None]
        slot = {id(t): t.row for t in order if t.row is not None}
        slot.update({id(t): rows + i for i, t in enumerate(constants)})
        slot.update({id(t): rows + len(constants) + i for i, (t, _) in enumerate(steps)})
        return ([t.value for t in constants],
                tuple((f, slot[id(x)], -1 if y is None else slot[id(y)])
                      for _, (f, x, y) in steps),
                tuple(slot[id(t)] for t in results))


class _Term:
    """An entry of a determinant :class:`Cramer` works out: a row of ``b`` (``row``), an
    array of ``A``'s entries alone (``value``; ``zero``: 0 at every column) or a product
    that reads ``b`` (``step``: its operation and operands). Multiplied, added or
    subtracted as :func:`determinant` does it, a term with a zero is left out."""

    def __init__(self, graph: _Graph, *, row: int | None = None,
                 value: np.ndarray | None = None, step: tuple | None = None) -> None:
        self.graph, self.row, self.value, self.step = graph, row, value, step
        self.zero = value is not None and not value.any()

    def __mul__(self, other: _Term) -> _Term:
        if self.zero or other.zero:
            return self if self.zero else other
        return self.graph.made_of(np.multiply, self, other)

    def __add__(self, other: _Term) -> _Term:
        if self.zero or other.zero:
            return other if self.zero else self
        return self.graph.made_of(np.add, self, other)

    def __sub__(self, other: _Term) -> _Term:
        if other.zero:
            return self
        if self.zero:
            return self.graph.made_of(np.negative, other)
        return self.graph.made_of(np.subtract, self, other)


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
