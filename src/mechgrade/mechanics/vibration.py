"""Natural modes of n coordinates, worked out with numbers: the linearised motion's stiffness
and damping matrices come from the momentum balances at the instant, and their eigenvalues
from numpy, where a symbolic determinant of three or more coordinates would take hours.

The balances ``A x = b`` (x the second rates and the reactions) are handed over as entries,
with their derivatives by every coordinate and every rate at rest: the solved accelerations'
derivatives are ``A^-1 (db/ds - dA/ds x)``, so no symbolic inverse is ever formed. With
``K = -d q''/d q`` and ``C = -d q''/d q'`` (both already divided by the masses), the n-th
natural frequency is the square root of the n-th smallest eigenvalue of K (dampers ignored,
as the textbook's undamped natural frequency is), and the damping ratio of mode n is read from
the state-space matrix ``[[0, I], [-K, -C]]``: its eigenvalues ``-zeta w_n +- i w_n
sqrt(1 - zeta^2)`` give ``zeta = -Re(lambda)/|lambda|`` of the n-th pair by |lambda|. That
holds for damping that is not proportional to mass or stiffness too (the modes are then
complex, and a modal damping ratio of the undamped modes would be an approximation).

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


class Modal(IntEnum):
    """What :func:`modal_value` returns: a mode's value, or a residual that must be zero for
    it to exist (:data:`REASONS`)."""

    FREQUENCY = 0
    DAMPING_RATIO = 1
    SHAPE = 2
    EQUILIBRIUM = 3
    STABLE = 4
    UNDERDAMPED = 5
    COUPLED = 6


REASONS = {
    Modal.EQUILIBRIUM: "the configuration is not an equilibrium (a second rate is not zero at "
                       "rest there): give the equilibrium's coordinates and zero rates among "
                       "the objective's givens",
    Modal.STABLE: "the equilibrium is not stable (a squared natural frequency is negative or "
                  "not real), so it has no natural frequencies: linearise about a stable one "
                  "(its coordinates among the objective's givens)",
    Modal.UNDERDAMPED: "a mode does not oscillate (it is critically damped or overdamped: its "
                       "state-space eigenvalues are real), so its damping ratio is not that of "
                       "a vibration",
    Modal.COUPLED: "the reference coordinate does not move in this mode (the coordinates are "
                   "not coupled in it), so the amplitude ratio has no value",
}
"""Why a mode does not exist, for each residual :func:`modal_value` checks."""


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
    (:class:`Modal`). Undefined values are NaN. A solve alone is a class of one column.

    >>> entries = modal_entries([[1]], [0], [[[0]]], [[-4]], [[[0]]], [[-0.4]])
    >>> [round(float(modal_value(w, 1, 0, 0, 1, 1, *entries)), 6) for w in (0, 1, 3, 4, 5)]
    [2.0, 0.1, 0.0, 0.0, 0.0]
    """
    flat, shape = _one_state(entries)
    if flat is None:  # each entry put in its row (a number in every column)
        shape = np.broadcast_shapes(*(np.shape(e) for e in entries))
        flat = np.empty((len(entries), *shape))
        for row, e in zip(flat, entries):
            row[...] = e
        flat = flat.reshape(len(entries), -1)
    else:  # a solve alone: hundreds of entries not broadcast one by one
        flat = flat[:, None]
    n, m = int(n), int(m)
    modes = _modes(n, m, flat.shape[1], np.ascontiguousarray(flat).tobytes())
    return _value(Modal(int(what)), int(number), int(i), int(j), modes).reshape(shape)


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
    """Every column's modes (N columns, n coordinates), worked out once for the several
    values and residuals asked of the same states (a frequency, its mode shape, the checks
    that it exists), each stage stacked over the columns; NaN where undefined. ``defined``:
    the columns whose balances' ``A`` is regular; ``equilibrium``, ``stable`` and
    ``oscillating`` the residuals of :data:`REASONS`; per mode (the lowest first),
    ``frequencies`` and ``damping`` (N x n) and ``shapes`` (N x n coordinates x n modes)."""

    defined: np.ndarray
    equilibrium: np.ndarray
    stable: np.ndarray
    oscillating: np.ndarray
    frequencies: np.ndarray
    damping: np.ndarray
    shapes: np.ndarray


@lru_cache(maxsize=16)
def _modes(n: int, m: int, columns: int, v: bytes) -> _Modes:
    """:class:`_Modes` of the entries ``v`` (their bytes: entries x ``columns``)."""
    entries = np.frombuffer(v).reshape(-1, columns)
    size = m * m + m
    blocks = [(entries[s:s + m * m].T.reshape(columns, m, m), entries[s + m * m:s + size].T)
              for s in range(0, (2 * n + 1) * size, size)]
    held = entries[(2 * n + 1) * size:].T.reshape(columns, -1, n)
    A, b = blocks[0]
    defined = np.asarray(np.isfinite(entries).all(axis=0))
    defined[defined] = ~_singular(A[defined])  # no linearised motion where A is singular
    equilibrium = np.full(columns, np.nan)
    stable, oscillating = np.zeros(columns, dtype=bool), np.zeros(columns, dtype=bool)
    frequencies, damping = np.full((columns, n), np.nan), np.full((columns, n), np.nan)
    shapes = np.full((columns, n, n), np.nan)
    on = np.flatnonzero(defined)
    if not len(on):
        return _Modes(defined, equilibrium, stable, oscillating, frequencies, damping, shapes)
    A = A[on]
    x = _solved(A, b[on])
    K, C = np.empty((len(on), n, n)), np.empty((len(on), n, n))
    for j, (dA, db) in enumerate(blocks[1:]):
        (K if j < n else C)[:, :, j % n] = -_solved(A, db[on] - _solved_product(dA[on], x))[:, :n]
    equilibrium[on] = np.abs(x[:, :n]).sum(axis=1) / (1 + np.abs(K).sum(axis=(1, 2)))
    # the motions that keep the position constraints: q = T z, T an orthonormal basis of
    # their null space (K and C act within it: a motion across it has no restoring force, a
    # zero frequency that is no mode)
    bases = [_basis(held[c], n) for c in on]
    for k in sorted({T.shape[1] for T in bases}):
        group = [g for g, T in enumerate(bases) if T.shape[1] == k]
        cols = on[group]
        T = np.stack([bases[g] for g in group])
        Kk, Ck = K[group], C[group]
        if held.shape[1]:
            Tt = T.transpose(0, 2, 1)
            Kk, Ck = Tt @ Kk @ T, Tt @ Ck @ T
        squares, vectors = np.linalg.eig(Kk)
        scale = 1e-9 * (np.abs(squares).max(axis=1, keepdims=True) + 1e-300)
        # a zero squared frequency is a mode that moves freely (a rigid-body mode), not
        # unstable
        stable[cols] = ((np.abs(squares.imag) <= scale) & (squares.real >= -scale)).all(axis=1)
        order = np.argsort(squares.real, axis=1, kind="stable")
        frequencies[cols, :k] = np.sqrt(np.maximum(np.take_along_axis(squares.real, order, 1),
                                                   0.0))
        shapes[cols, :, :k] = (T @ np.take_along_axis(vectors, order[:, None, :], 2)).real
        # the state-space matrix [[0, I], [-K, -C]]: one root of each oscillating pair, sorted
        # by size
        M = np.zeros((len(cols), 2 * k, 2 * k))
        M[:, :k, k:] = np.eye(k)
        M[:, k:, :k], M[:, k:, k:] = -Kk, -Ck
        roots = np.linalg.eigvals(M)
        up = roots.imag > 1e-9 * np.abs(roots).max(axis=1, keepdims=True)
        oscillating[cols] = up.sum(axis=1) == k
        pairs = np.take_along_axis(roots, np.argsort(np.where(up, np.abs(roots), np.inf),
                                                     axis=1, kind="stable"), 1)[:, :k]
        with np.errstate(all="ignore"):  # read only where every mode oscillates
            damping[cols, :k] = np.where(oscillating[cols, None],
                                         -pairs.real / np.abs(pairs), np.nan)
    frequencies[~stable] = np.nan
    return _Modes(defined, equilibrium, stable, oscillating, frequencies, damping, shapes)


def _singular(A: np.ndarray) -> np.ndarray:
    """Which of the matrices ``A`` (N x m x m) LAPACK's LU finds singular (an exactly zero
    pivot), where ``np.linalg.solve`` refuses."""
    out = np.zeros(len(A), dtype=bool)
    try:
        np.linalg.solve(A, np.zeros((*A.shape[:2], 1)))
    except np.linalg.LinAlgError:  # which of them: one at a time
        for c, matrix in enumerate(A):
            try:
                np.linalg.solve(matrix, np.zeros(len(matrix)))
            except np.linalg.LinAlgError:
                out[c] = True
    return out


def _solved(A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Each ``A x = b`` (N x m x m, N x m) solved: N x m."""
    return np.linalg.solve(A, b[..., None])[..., 0]


def _solved_product(A: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Each ``A x`` (N x m x m, N x m): N x m."""
    return (A @ x[..., None])[..., 0]


def _basis(held: np.ndarray, n: int) -> np.ndarray:
    """An orthonormal basis (n x kept) of the coordinates' motions that keep the position
    constraints whose Jacobian is ``held`` (p x n): the identity when nothing is held."""
    if not len(held):
        return np.eye(n)
    _, sizes, rows = np.linalg.svd(held)
    rank = int((sizes > 1e-10 * (sizes.max() if sizes.size else 1.0)).sum())
    return rows[rank:].T


def _value(what: Modal, number: int, i: int, j: int, modes: _Modes) -> np.ndarray:
    """:func:`modal_value` of every column of ``modes`` (NaN where undefined)."""
    on = modes.defined
    if what == Modal.EQUILIBRIUM:
        return modes.equilibrium.copy()
    if what == Modal.FREQUENCY:
        return modes.frequencies[:, number - 1].copy()
    if what == Modal.DAMPING_RATIO:
        return modes.damping[:, number - 1].copy()
    if what in (Modal.STABLE, Modal.UNDERDAMPED):
        holds = modes.stable if what == Modal.STABLE else modes.oscillating
        return np.where(on, np.where(holds, 0.0, 1.0), np.nan)
    shape = modes.shapes[:, :, number - 1]
    with np.errstate(all="ignore"):  # read only where the reference coordinate moves
        moves = np.abs(shape[:, j]) > 1e-9 * np.abs(shape).max(axis=1)
        if what == Modal.COUPLED:
            return np.where(on & modes.stable, np.where(moves, 0.0, 1.0), np.nan)
        return np.where(on & modes.stable & moves, shape[:, i] / shape[:, j], np.nan)


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
