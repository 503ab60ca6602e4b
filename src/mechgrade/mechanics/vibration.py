"""Natural modes of n coordinates, worked out with numbers: the linearised motion's stiffness
and damping matrices come from the momentum balances at the instant, and their eigenvalues
from numpy, where a symbolic determinant of three or more coordinates would take hours.

The balances ``A x = b`` (x the second rates and the reactions) are handed over as entries,
with their derivatives by every coordinate and every rate at rest: the solved accelerations'
derivatives are ``A^-1 (db/ds - dA/ds x)``, so no symbolic inverse is ever formed. With
``K = -d q''/d q`` and ``C = -d q''/d q'`` (both already divided by the masses), the n-th
natural frequency is the square root of the n-th smallest eigenvalue of K (dampers ignored,
as the textbook's undamped natural frequency is), and the damping ratio of mode n is read from
the state-space matrix ``[[0, I], [-K, -C]]``: each mode's two eigenvalues are the roots of
``l^2 + 2 zeta w_n l + w_n^2``, so ``zeta = -(l1 + l2) / (2 sqrt(l1 l2))`` of the n-th mode by
``l1 l2``. For a vibrating mode (a complex pair) that is ``-Re(l)/|l|``; it is 1 where the
pair meets on the real axis (critical damping, whose double root rounding leaves either two
real roots or a pair ~1e-8 off the axis) and more than 1 for an overdamped mode's two real
roots. That holds for damping that is not proportional to mass or stiffness too (the modes
are then complex, and a modal damping ratio of the undamped modes would be an
approximation).

Which roots make a mode: the complex pairs (beyond :func:`~mechgrade.tolerance.real`) are
each a mode; the real roots left are two when at most one mode does not vibrate, and those two
are that mode (exact for one coordinate). Four or more real roots (two modes or more that do
not vibrate) do not say by themselves which two belong together, so no mode's damping ratio is
given there (:attr:`Modal.PAIRED`). A mode that moves freely (a zero natural frequency, as
:attr:`Modal.FREQUENCY` reads it) has no damping ratio (:attr:`Modal.FREE`) and keeps its
place, first, in the numbering, as textbooks number a rigid-body mode ``omega_1 = 0``.

>>> import numpy as np
>>> two = [[2.0, 0.0], [0.0, 1.0]]                 # two blocks, springs 100 and 50 N/m
>>> entries = modal_entries(two, [0, 0], [[[0, 0], [0, 0]]] * 2, [[-150, 50], [50, -50]],
...                         [[[0, 0], [0, 0]]] * 2, [[0, 0], [0, 0]])
>>> round(float(modal_value(Modal.FREQUENCY, 2, 0, 0, 2, 2, *entries)), 6)
10.0
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum
from functools import lru_cache

import numpy as np
import sympy as sp

from .. import tolerance


class Modal(IntEnum):
    """What :func:`modal_value` returns: a mode's value, or a residual that must be zero for
    it to exist (:data:`REASONS`)."""

    FREQUENCY = 0
    DAMPING_RATIO = 1
    SHAPE = 2
    EQUILIBRIUM = 3
    STABLE = 4
    FREE = 5
    COUPLED = 6
    PAIRED = 7


REASONS = {
    Modal.EQUILIBRIUM: "the configuration is not an equilibrium (a second rate is not zero at "
                       "rest there): give the equilibrium's coordinates and zero rates among "
                       "the objective's givens",
    Modal.STABLE: "the equilibrium is not stable (a squared natural frequency is negative or "
                  "not real), so it has no natural frequencies: linearise about a stable one "
                  "(its coordinates among the objective's givens)",
    Modal.FREE: "mode {number} moves freely (its natural frequency is zero: a rigid-body "
                "motion), so it has no damping ratio",
    Modal.PAIRED: "two or more modes do not vibrate (their state-space eigenvalues are real) "
                  "and those eigenvalues alone do not say which two belong to mode {number}, "
                  "so its damping ratio is not worked out",
    Modal.COUPLED: "the reference coordinate does not move in this mode (the coordinates are "
                   "not coupled in it), so the amplitude ratio has no value",
}
"""Why a mode does not exist, for each residual :func:`modal_value` checks (``{number}`` the
mode's)."""


def modal_entries(A, b, dA_dq, db_dq, dA_dqd, db_dqd, held=None) -> list:
    """The flat argument list of :func:`modal_value` (after ``what, number, i, j, n, m``):
    ``A`` (m x m) and ``b`` (m) of the balances ``A x = b`` at rest, then for each coordinate
    ``dA/dq_j`` and ``db/dq_j``, then for each rate ``dA/dq'_j`` and ``db/dq'_j``; then, when
    the motion keeps position constraints (``held``, p x n: their Jacobian in the
    coordinates), its p x n entries.

    >>> len(modal_entries([[1]], [0], [[[0]]], [[-4]], [[[0]]], [[0]]))
    6
    """
    out = [*np.ravel(_rows(A)), *b]
    for dA, db in (*zip(dA_dq, db_dq), *zip(dA_dqd, db_dqd)):
        out += [*np.ravel(_rows(dA)), *db]
    if held is not None:
        out += [*np.ravel(_rows(held))]
    return out


def _rows(matrix):
    return np.array(matrix, dtype=object)


def modal_value(what, number, i, j, n, m, *entries):
    """One value of mode ``number`` (1 the lowest) for every column of ``entries`` (numbers or
    equal-length arrays, as :func:`modal_entries` lays them out): the natural frequency, the
    damping ratio, the amplitude ratio of coordinate ``i`` to ``j`` (0-based), or a residual
    (:class:`Modal`). Undefined values are NaN.

    >>> entries = modal_entries([[1]], [0], [[[0]]], [[-4]], [[[0]]], [[-0.4]])
    >>> [round(float(modal_value(w, 1, 0, 0, 1, 1, *entries)), 6) for w in (0, 1, 3, 4, 5)]
    [2.0, 0.1, 0.0, 0.0, 0.0]
    """
    one, shape = _one_state(entries)
    if one is not None:  # a solve alone: hundreds of entries not broadcast one by one
        flat = one[:, None]
    else:  # each entry written into its row (a number spread along it): one step apiece
        shape = np.broadcast_shapes(*(np.shape(e) for e in entries))
        flat = np.empty((len(entries),) + shape)
        for row, e in zip(flat, entries):
            row[...] = e
        flat = flat.reshape(len(entries), -1)
    # the states' modes worked out once for the several values and residuals asked of them (a
    # frequency, its mode shape, the checks that it exists)
    modes = _modes(int(n), int(m), flat.shape[1], np.ascontiguousarray(flat).tobytes())
    return _value(modes, Modal(int(what)), int(number), int(i), int(j)).reshape(shape)


def _one_state(entries) -> tuple[np.ndarray | None, tuple[int, ...]]:
    """The entries as one vector and the shape they broadcast to, when each is one number
    (``None`` when some entry holds several states)."""
    values = []
    shape: tuple[int, ...] = ()
    for e in entries:
        if type(e) is np.ndarray:
            if e.size != 1:
                return None, ()
            shape = e.shape if e.ndim > len(shape) else shape
            values.append(e.item())
        else:
            values.append(e)
    return np.array(values, dtype=float), shape


@dataclass(frozen=True)
class _Modes:
    """The modes of every state (one per column of the entries) of one kept dimension
    ``kept`` (the coordinates' motions that keep the position constraints): which states
    they are (``columns``), ``T`` (states x coordinates x kept, ``q = T z``), the squared
    frequencies and their eigenvectors (of ``K`` within the kept motions), and each mode's
    two state-space eigenvalues' ``sums`` and ``products`` (states x kept, by product first;
    NaN where the real roots do not say which two make a mode)."""

    columns: np.ndarray
    T: np.ndarray
    squares: np.ndarray
    shapes: np.ndarray
    sums: np.ndarray
    products: np.ndarray


@dataclass(frozen=True)
class _States:
    """``x``, ``K`` and ``C`` of every state whose ``A`` is regular (``regular``; NaN at the
    others), and their :class:`_Modes`, one for each dimension kept."""

    regular: np.ndarray
    x: np.ndarray
    K: np.ndarray
    kept: tuple[_Modes, ...]


def _solved(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``A^-1 b`` of every state (``A``: states x m x m, ``b``: states x m x right-hand
    sides); NaN where ``A`` is singular."""
    try:
        return np.linalg.solve(A, b)
    except np.linalg.LinAlgError:  # some state's A is singular: each one alone
        out = np.full(b.shape, np.nan)
        for c in range(len(A)):
            try:
                out[c] = np.linalg.solve(A[c], b[c])
            except np.linalg.LinAlgError:
                pass
        return out


@lru_cache(maxsize=256)
def _modes(n: int, m: int, count: int, v: bytes) -> _States:
    """:class:`_States` of the entries ``v`` (their bytes: entries x ``count`` states).
    ``K = -d q''/d q`` and ``C = -d q''/d q'`` are ``A^-1 (db/ds - dA/ds x)``; a position
    constraint kept (the entries' tail, its Jacobian in the coordinates) restricts them to
    its null space: a motion across it has no restoring force, a zero frequency that is no
    mode."""
    entries = np.frombuffer(v).reshape(-1, count).T
    size = m * m + m
    blocks = [(entries[:, s:s + m * m].reshape(count, m, m), entries[:, s + m * m:s + size])
              for s in range(0, (2 * n + 1) * size, size)]
    A, b = blocks[0]
    x = _solved(A, b[:, :, None])[:, :, 0]
    # each derivative solved on its own, as one state's always was: a mode that rounding
    # alone sets (a rigid-body mode's frequency) keeps its digits
    derivatives = [-_solved(A, db[:, :, None] - dA @ x[:, :, None])[:, :n, 0]
                   for dA, db in blocks[1:]]
    K = np.stack(derivatives[:n], axis=2)
    C = np.stack(derivatives[n:], axis=2)
    regular = np.isfinite(x).all(axis=1) & np.isfinite(K).all(axis=(1, 2)) & \
        np.isfinite(C).all(axis=(1, 2))
    held = entries[:, (2 * n + 1) * size:].reshape(count, -1, n)
    if held.shape[1]:
        _, sizes, rows = np.linalg.svd(np.where(regular[:, None, None], held, 0.0))
        ranks = tolerance.rank(sizes)
    else:
        rows, ranks = None, np.zeros(count, dtype=int)
    kept = []
    for rank in np.unique(ranks[regular]) if rows is not None else [0] * bool(regular.any()):
        c = np.flatnonzero(regular & (ranks == rank))
        if rows is None:
            T, Kk, Ck = np.broadcast_to(np.eye(n), (len(c), n, n)), K[c], C[c]
        else:
            T = rows[c, rank:].transpose(0, 2, 1)
            Kk, Ck = T.transpose(0, 2, 1) @ K[c] @ T, T.transpose(0, 2, 1) @ C[c] @ T
        squares, shapes = np.linalg.eig(Kk)
        k = n - rank
        space = np.zeros((len(c), 2 * k, 2 * k))
        space[:, :k, k:] = np.eye(k)
        space[:, k:, :k], space[:, k:, k:] = -Kk, -Ck
        sums, products = _paired(np.linalg.eigvals(space))
        kept.append(_Modes(c, T, squares, shapes, sums, products))
    return _States(regular, x, K, tuple(kept))


def _paired(roots: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The sum and the product of each mode's two roots, by product first, of every state's
    state-space eigenvalues ``roots`` (states x 2k): a complex pair is a mode, and so are the
    two real roots left (a pair rounding leaves within :func:`~mechgrade.tolerance.real` of
    the axis is real: a critically damped or free mode); NaN where four or more are left.

    >>> sums, products = _paired(np.array([[-1.0, -4.0, -0.1 + 3j, -0.1 - 3j]]))
    >>> sums.round(12).tolist(), products.round(12).tolist()
    ([[-5.0, -0.2]], [[4.0, 9.01]])
    """
    k = roots.shape[1] // 2
    real = tolerance.real(roots, np.abs(roots).max(axis=1, keepdims=True))
    upper = ~real & (roots.imag > 0)
    # each pair's upper root, then the real roots, then the pairs' lower roots
    order = np.argsort(np.where(upper, 0, np.where(real, 1, 2)), axis=1, kind="stable")
    ranked = np.take_along_axis(roots, order, axis=1)
    pairs = upper.sum(axis=1, keepdims=True)
    mode = np.arange(k)
    first, second = ranked[:, :k], ranked[:, 1:k + 1]
    sums = np.where(mode < pairs, 2 * first.real, (first + second).real)
    products = np.where(mode < pairs, np.abs(first) ** 2, (first * second).real)
    told = (real.sum(axis=1, keepdims=True) <= 2) & (mode <= pairs)
    sums, products = np.where(told, sums, np.nan), np.where(told, products, np.nan)
    # by product (the mode's own squared frequency); a free mode's is rounding of either sign
    by = np.argsort(np.abs(products), axis=1, kind="stable")
    return np.take_along_axis(sums, by, axis=1), np.take_along_axis(products, by, axis=1)


def _value(states: _States, what: Modal, number: int, i: int, j: int) -> np.ndarray:
    """The value ``what`` of mode ``number`` at every state of ``states`` (NaN where ``A`` is
    singular or it is undefined), as :func:`modal_value` says."""
    out = np.full(len(states.regular), np.nan)
    n = states.K.shape[1]
    if what == Modal.EQUILIBRIUM:
        r = states.regular
        out[r] = np.abs(states.x[r, :n]).sum(axis=1) / (1 + np.abs(states.K[r]).sum(axis=(1, 2)))
        return out
    for modes in states.kept:
        c = modes.columns
        squares = modes.squares
        largest = np.abs(squares).max(axis=1, keepdims=True)
        # a square that is round-off beside the largest is a mode that moves freely (a
        # rigid-body mode, not unstable): its frequency is 0 and it has no damping ratio
        moving = tolerance.parts(squares.real, largest)
        stable = (~tolerance.parts(squares.imag, largest)).all(axis=1) & \
            ((squares.real >= 0) | ~moving).all(axis=1)
        free = number <= (~moving).sum(axis=1)
        told = ~np.isnan(modes.products).any(axis=1)
        if what == Modal.STABLE:
            out[c] = np.where(stable, 0.0, 1.0)
        elif what == Modal.FREE:
            out[c] = np.where(free, 1.0, 0.0)
        elif what == Modal.PAIRED:
            out[c] = np.where(told, 0.0, 1.0)
        elif what == Modal.DAMPING_RATIO:
            with np.errstate(all="ignore"):
                zeta = -modes.sums[:, number - 1] / (2 * np.sqrt(modes.products[:, number - 1]))
            out[c] = np.where(free | ~told, np.nan, zeta)
        else:
            order = np.argsort(squares.real, axis=1)[:, number - 1]
            every = np.arange(len(c))
            if what == Modal.FREQUENCY:
                # a free mode's frequency is 0, not the root of its round-off (1e-7 rad/s)
                value = np.sqrt(np.where(moving[every, order],
                                         np.maximum(squares.real[every, order], 0.0), 0.0))
            else:
                shape = (modes.T @ modes.shapes[every, :, order][:, :, None])[:, :, 0].real
                moves = tolerance.parts(shape[:, j], np.abs(shape).max(axis=1))
                with np.errstate(all="ignore"):
                    value = np.where(moves, 0.0, 1.0) if what == Modal.COUPLED else \
                        np.where(moves, shape[:, i] / shape[:, j], np.nan)
            out[c] = np.where(stable, value, np.nan)
    return out


class NaturalMode(sp.Function):
    """:func:`modal_value` as a sympy function of the balances' entries: the numpy printer
    (and so ``lambdify``) calls :func:`modal_value`, numbers evaluate at once.

    >>> print(NaturalMode(Modal.DAMPING_RATIO, 2, 0, 0, 1, 1, sp.Symbol("k"), 0, 0, 0, 0, 0))
    [the damping ratio of mode 2, from the eigenvalues of the linearised motion, with numbers]
    """

    @classmethod
    def eval(cls, *args):
        if all(a.is_Number for a in args):
            return sp.Float(float(modal_value(*(float(a) for a in args))))
        return None

    def _sympystr(self, _printer):
        """Shown in the write-up as what it is, not as its hundreds of entries."""
        what, number, i, j = (int(a) for a in self.args[:4])
        said = {Modal.FREQUENCY: f"the natural frequency of mode {number}",
                Modal.DAMPING_RATIO: f"the damping ratio of mode {number}",
                Modal.SHAPE: f"the ratio of coordinate {i + 1} to coordinate {j + 1} in mode "
                             f"{number}"}.get(Modal(what), f"{Modal(what).name.lower()} of "
                                                          f"mode {number}")
        return f"[{said}, from the eigenvalues of the linearised motion, with numbers]"

    _latex = _sympystr

    def _numpycode(self, printer):
        function = printer._module_format("mechgrade.mechanics.vibration.modal_value")
        return f"{function}({', '.join(printer._print(a) for a in self.args)})"

    _scipycode = _numpycode
