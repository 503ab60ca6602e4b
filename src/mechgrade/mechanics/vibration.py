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
    (:class:`Modal`). Undefined values are NaN.

    >>> entries = modal_entries([[1]], [0], [[[0]]], [[-4]], [[[0]]], [[-0.4]])
    >>> [round(float(modal_value(w, 1, 0, 0, 1, 1, *entries)), 6) for w in (0, 1, 3, 4, 5)]
    [2.0, 0.1, 0.0, 0.0, 0.0]
    """
    args = (Modal(int(what)), int(number), int(i), int(j), int(n), int(m))
    one, shape = _one_state(entries)
    if one is not None:  # a solve alone: hundreds of entries not broadcast one by one
        return np.array(_one(*args, one)).reshape(shape)
    arrays = np.broadcast_arrays(*(np.asarray(e, dtype=float) for e in entries))
    shape = arrays[0].shape
    flat = np.stack([a.reshape(-1) for a in arrays])
    out = np.array([_one(*args, flat[:, c]) for c in range(flat.shape[1])])
    return out.reshape(shape)


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


@lru_cache(maxsize=256)
def _linearised(n: int, m: int, v: bytes) -> tuple[np.ndarray, ...] | None:
    """``x``, ``K`` and ``C`` of the entries ``v`` (their bytes), ``None`` where ``A`` is
    singular: worked out once for the several values and residuals asked of the same state (a
    frequency, its mode shape, the checks that it exists)."""
    entries = np.frombuffer(v)
    size = m * m + m
    blocks = [(entries[s:s + m * m].reshape(m, m), entries[s + m * m:s + size])
              for s in range(0, (2 * n + 1) * size, size)]
    A, b = blocks[0]
    try:
        x = np.linalg.solve(A, b)
        K = -np.column_stack([np.linalg.solve(A, db - dA @ x)[:n] for dA, db in blocks[1:n + 1]])
        C = -np.column_stack([np.linalg.solve(A, db - dA @ x)[:n] for dA, db in blocks[n + 1:]])
    except np.linalg.LinAlgError:
        return None
    return _shared(x, K, C)


@lru_cache(maxsize=256)
def _kept(n: int, m: int, v: bytes) -> tuple[np.ndarray, ...]:
    """``T``, ``K`` and ``C`` of the motions that keep the position constraints (the entries'
    tail, their Jacobian in the coordinates): ``q = T z``, ``T`` an orthonormal basis of its
    null space; ``T`` is the identity when nothing is held."""
    linearised = _linearised(n, m, v)
    assert linearised is not None  # asked only of a state whose A is regular
    _, K, C = linearised
    held = np.frombuffer(v)[(2 * n + 1) * (m * m + m):].reshape(-1, n)
    if not len(held):
        return _shared(np.eye(n), K, C)
    # K and C act within the null space: a motion across it has no restoring force, a zero
    # frequency that is no mode
    _, sizes, rows = np.linalg.svd(held)
    rank = int((sizes > 1e-10 * (sizes.max() if sizes.size else 1.0)).sum())
    T = rows[rank:].T
    return _shared(T, T.T @ K @ T, T.T @ C @ T)


@lru_cache(maxsize=256)
def _eigen(n: int, m: int, v: bytes) -> tuple[np.ndarray, ...]:
    """The eigenvalues and eigenvectors of :func:`_kept`'s ``K``."""
    return _shared(*np.linalg.eig(_kept(n, m, v)[1]))


@lru_cache(maxsize=256)
def _pairs(n: int, m: int, v: bytes) -> np.ndarray:
    """The eigenvalues of the state-space matrix ``[[0, I], [-K, -C]]`` of :func:`_kept`'s
    ``K`` and ``C`` with a positive imaginary part (one of each oscillating mode's pair):
    every damping ratio and the check that each mode oscillates read them."""
    T, K, C = _kept(n, m, v)
    k = T.shape[1]
    roots = np.linalg.eigvals(np.block([[np.zeros((k, k)), np.eye(k)], [-K, -C]]))
    return _shared(roots[roots.imag > 1e-9 * np.abs(roots).max()])[0]


def _shared(*arrays: np.ndarray) -> tuple[np.ndarray, ...]:
    for array in arrays:
        array.setflags(write=False)  # cached: every caller of the same state reads them
    return arrays


def _one(what: Modal, number: int, i: int, j: int, n: int, m: int, v: np.ndarray) -> float:
    key = np.ascontiguousarray(v, dtype=float).tobytes()
    linearised = _linearised(n, m, key)
    if linearised is None:
        return np.nan
    x, K, _ = linearised
    if what == Modal.EQUILIBRIUM:
        return float(np.abs(x[:n]).sum() / (1 + np.abs(K).sum()))
    squares, shapes = _eigen(n, m, key)
    T = _kept(n, m, key)[0]
    kept = T.shape[1]  # the coordinates' motions that keep the constraints
    scale = 1e-9 * (np.abs(squares).max() + 1e-300)
    # a zero squared frequency is a mode that moves freely (a rigid-body mode), not unstable
    stable = bool((np.abs(squares.imag) <= scale).all() and (squares.real >= -scale).all())
    if what == Modal.STABLE:
        return 0.0 if stable else 1.0
    if what in (Modal.DAMPING_RATIO, Modal.UNDERDAMPED):
        pairs = _pairs(n, m, key)
        if what == Modal.UNDERDAMPED:
            return 0.0 if len(pairs) == kept else 1.0
        if len(pairs) != kept:
            return np.nan
        pair = pairs[np.argsort(np.abs(pairs))][number - 1]
        return float(-pair.real / abs(pair))
    if not stable:
        return np.nan
    order = np.argsort(squares.real)
    if what == Modal.FREQUENCY:
        return float(np.sqrt(max(squares.real[order[number - 1]], 0.0)))
    shape = (T @ shapes[:, order[number - 1]]).real
    moves = abs(shape[j]) > 1e-9 * np.abs(shape).max()
    if what == Modal.COUPLED:
        return 0.0 if moves else 1.0
    return float(shape[i] / shape[j]) if moves else np.nan


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
