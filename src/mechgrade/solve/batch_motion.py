"""Numerics of many variants at once, each a column of a stacked array: the motions integrated
to their events, and Newton's method on one scalar per variant.

Every column takes the steps :func:`scipy.integrate.solve_ivp` (DOP853) would take for it
alone — its own step size, error norm, accepted and rejected steps, the same coefficients —
while the right-hand side is evaluated for all the columns still moving in one call. A column
stops at its event (located on its last step's dense output) or at the end of the time
allowed; its derivative is never evaluated again, so it costs the others nothing.

One difference, for a motion that switches (a slip that ends): the right-hand side may depend
on *modes* (the direction of each slip), read at the start of every step and kept through it,
so a step across the switch integrates the motion before it continued, smoothly. A motion
switching at its event (friction reversing as the slip ends) then reaches it in a few steps
where ``solve_ivp`` shrinks its steps many times against the jump, and as accurately; a
column that switches anywhere but at its event is not answered here.
:func:`newton` solves one scalar per column, each iteration one call for all of them.

>>> import numpy as np
>>> rates = np.array([[1.0, 2.0]])
>>> arrival = integrate_to_events(lambda cols, t, y, modes: rates[:, cols] + 0 * y,
...                               lambda cols, t, y, modes: y[0] - 1.0, np.zeros((1, 2)), 5.0,
...                               1e-11, 1e-12, 20_000)
>>> arrival.status.tolist(), np.round(arrival.t, 12).tolist()
([1, 1], [1.0, 0.5])
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Callable

import numpy as np

from . import dop853, rules
from .columns import call

SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0  # as scipy's Runge-Kutta step control
EPS = np.finfo(float).eps

FIRED, NEVER, FAILED, SWITCHED, STALLED = 1, 0, -1, -2, -3
"""How a column's integration ended: at its event, at the end of the time allowed without
it, or without an answer this path vouches for (a step too small, an undefined value), or
after more evaluations of the right-hand side than allowed (counted as ``solve_ivp`` with its
dense output counts them; ``t``: the step it stopped at); or where one of its modes switched
before its event (:attr:`Arrival.switch` says which, ``t`` and ``y`` where its speed crossed
zero)."""

Field = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], np.ndarray]
"""``f(columns, t, y, modes)``: a value per column of ``y`` (``columns``: which variants they
are, ``t``: each one's time, ``modes``: each one's modes, see :func:`integrate_to_events`)."""



LANES = 16
"""The width of a row of stages (states x columns, flattened) is rounded up to a multiple of
this: BLAS's product of the weights with the stages sums a value in one order in its blocks of
4 (or 8, 16) values and in another in the rest, so a column's bits would depend on how many
columns a step carries and where it sits among them. Padded, every value is in a block: a
column alone is, bit for bit, that column among others."""


def _stages(count: int, m: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Room for ``count`` stages of ``m`` states x ``n`` columns: ``K`` (count x m x n) and
    ``flat``, the same memory as count x (m n, padded with zeros to :data:`LANES`), which
    :func:`_combine` reads.

    >>> K, flat = _stages(13, 3, 1)
    >>> K.shape, flat.shape, np.shares_memory(K, flat)
    ((13, 3, 1), (13, 16), True)
    """
    flat = np.zeros((count, -(-m * n // LANES) * LANES))
    return flat[:, :m * n].reshape(count, m, n), flat


def _combine(weights: np.ndarray, flat: np.ndarray, shape: tuple) -> np.ndarray:
    """``sum_k weights[..., k] * K[k]``, ``K`` given ``flat`` (:func:`_stages`: stages x
    everything else, padded, of ``shape`` states x columns), as ``numpy.tensordot(weights,
    K, 1)`` without its overhead."""
    size = shape[0] * shape[1]
    return (weights @ flat[:weights.shape[-1]])[..., :size].reshape(weights.shape[:-1] + shape)


_ROWS = tuple(dop853.A[s, :s] for s in range(dop853.N_STAGES_EXTENDED))
"""Each stage's weights of the stages before it (the rows of ``A``, sliced once)."""


@dataclass(frozen=True)
class Arrival:
    """Where each column's integration ended: ``status`` (:data:`FIRED`, :data:`NEVER`,
    :data:`FAILED` or :data:`STALLED`), the time ``t`` and state ``y`` of the event (or of
    the end of the time allowed), ``which``
    event it is (of several, see :func:`integrate_to_events`), and ``before``: the state a
    moment earlier (``t * (1 - lead)``, not before the start), read on the same dense output.
    Where a mode switched (:data:`SWITCHED`): ``switch``, which mode (else -1), and
    ``modes``, those the step kept (modes x columns)."""

    status: np.ndarray
    t: np.ndarray
    y: np.ndarray
    before: np.ndarray
    switch: np.ndarray | None = None
    modes: np.ndarray | None = None
    which: np.ndarray | None = None


def integrate_to_events(rhs: Field, event: Field | list[Field], y0: np.ndarray, t_bound: float,
                        rtol: float, atol: float, max_calls: int, lead: float = rules.BEFORE_EVENT,
                        mode: Callable | None = None,
                        direction: np.ndarray | None = None, t0: float | np.ndarray = 0.0,
                        keep: int = 12) -> Arrival:
    """Integrate ``y' = rhs`` from ``y0`` (states x columns) at ``t0`` until ``event``
    changes sign (or becomes zero), per column, as ``solve_ivp(method="DOP853",
    events=event)`` with a terminal event does for each column alone; ``mode(columns, t,
    y)`` gives the modes (modes x columns) each step keeps (see the module docstring).
    ``direction``: each column's event's ``direction``, as scipy reads it (1: only a rise
    fires it, -1: only a fall, 0: either); a column whose event is zero at the start moves
    only with one. ``event`` may be a list of several (``direction`` then events x columns):
    a column stops in the step where one fires, at the earliest root of those that fired
    there (the lowest index of equal ones), as ``solve_ivp`` records terminal events; each
    root is found evaluating its own event alone. ``t0``: the start, or each column's.
    ``keep``: the last steps kept per column, where the moment before the event is read (one
    column alone may keep all it can take, as ``solve_ivp``'s dense output does)."""
    c = dop853
    m, count = y0.shape
    status = np.full(count, FAILED)
    cols = np.arange(count)
    t = np.broadcast_to(np.asarray(t0, dtype=float), (count,)).copy()
    y = y0.astype(float).copy()
    modes = mode(cols, t, y) if mode is not None else np.zeros((0, count))
    f = rhs(cols, t, y, modes)
    events = event if isinstance(event, list) else [event]

    def every(cols: np.ndarray, t: np.ndarray, y: np.ndarray, modes: np.ndarray) -> np.ndarray:
        return np.array([e(cols, t, y, modes) for e in events], dtype=float).reshape(
            len(events), len(cols))

    g = every(cols, t, y, modes)
    h_abs = _first_step(rhs, cols, t, y, f, modes, t_bound, rtol, atol)
    calls = np.full(count, 2)
    retry = np.zeros(count, dtype=bool)
    sense = np.zeros(g.shape)
    if direction is not None:
        sense[:] = direction
    moving = np.isfinite(f).all(axis=0) & np.isfinite(g).all(axis=0) & \
        ((g != 0) | (sense != 0)).all(axis=0)
    history = _History(count, m, c.N_STAGES + 1, len(modes), t.copy(), keep)
    ends = np.zeros((2,) + g.shape)  # the events' values at the ends of the step one fired in
    hit = np.zeros(g.shape, dtype=bool)  # which events fired there
    switch = np.full(count, -1)  # the mode that switched before the event
    flips = np.zeros((2, count))  # its signs at the ends of the step it switched in
    exponent = -1.0 / 8.0  # the error estimator's order, 7, plus one
    # the few operations of a step on few columns cost more than its arithmetic: each value
    # is gathered once, and what ends a column is bookkept only in a step where one ends
    while moving.any():
        a = np.flatnonzero(moving)
        ta, ya, fa, ma = t[a], y[:, a], f[:, a], modes[:, a]
        ra, hv = retry[a], h_abs[a]
        min_step = 10 * np.abs(np.nextafter(ta, np.inf) - ta)
        ha = np.where(~ra & (hv < min_step), min_step, hv)
        small = ra & (ha < min_step)
        t_new = np.minimum(ta + ha, t_bound)
        h = t_new - ta
        times = ta + c.C[:c.N_STAGES, None] * h  # each stage's time, as ta + C[s] * h
        K, flat = _stages(c.N_STAGES + 1, m, len(a))
        shape = ya.shape
        K[0] = fa
        for s in range(1, c.N_STAGES):
            K[s] = rhs(a, times[s], ya + _combine(_ROWS[s], flat, shape) * h, ma)
        y_new = ya + h * _combine(c.B, flat, shape)
        K[c.N_STAGES] = rhs(a, t_new, y_new, ma)
        calls[a] += c.N_STAGES
        scale = atol + np.maximum(np.abs(ya), np.abs(y_new)) * rtol
        with np.errstate(all="ignore"):
            e5 = ((_combine(c.E5, flat, shape) / scale) ** 2).sum(axis=0)
            e3 = ((_combine(c.E3, flat, shape) / scale) ** 2).sum(axis=0)
            norm = np.where((e5 == 0) & (e3 == 0), 0.0,
                            np.abs(h) * e5 / np.sqrt((e5 + 0.01 * e3) * m))
            factor = SAFETY * norm ** exponent
            grow = np.where(norm == 0, MAX_FACTOR, np.minimum(MAX_FACTOR, factor))
            # an undefined error (a stage through a singularity) rejects the step, as
            # scipy's max(MIN_FACTOR, nan) does: a shorter one may pass it
            shrink = np.where(np.isnan(norm), MIN_FACTOR, np.maximum(MIN_FACTOR, factor))
        spent = calls[a] > max_calls
        broken = small | (np.isfinite(norm) & ~np.isfinite(y_new).all(axis=0)) | spent
        accepted = (norm < 1) & ~broken
        h_abs[a] = np.abs(h) * np.where(
            accepted, np.where(ra, np.minimum(1.0, grow), grow), shrink)
        retry[a] = ~accepted
        if broken.any():
            moving[a[broken]] = False
            status[a[spent]] = STALLED
            t[a[spent]] = ta[spent]
        if not accepted.any():
            continue
        k = np.flatnonzero(accepted)
        b = a[k]
        tk, yk, mk = t_new[k], y_new[:, k], ma[:, k]
        # as solve_ivp counts them: it builds every accepted step's dense output
        calls[b] += c.N_STAGES_EXTENDED - c.N_STAGES - 1
        history.push(b, ta[k], tk, ya[:, k], yk, K[:, :, k], mk)
        g_new = every(b, tk, yk, mk)
        g_old = g[:, b]
        t[b], y[:, b], f[:, b], g[:, b] = tk, yk, K[c.N_STAGES][:, k], g_new
        sb = sense[:, b]
        each = ((g_old <= 0) & (g_new >= 0) & (sb >= 0)) | \
            ((g_old >= 0) & (g_new <= 0) & (sb <= 0))
        fired = each.any(axis=0)
        undefined = ~np.isfinite(g_new).all(axis=0)
        switched = np.zeros(len(b), dtype=bool)
        if mode is not None:  # a switch anywhere but at the event: not answered here
            modes[:, b] = mode(b, tk, yk)
            now = modes[:, b]
            changed = now != mk
            switched = ~undefined & (changed.sum(axis=0) == 1) & \
                np.isfinite(now).all(axis=0) & (now != 0).all(axis=0)
            undefined |= ~fired & changed.any(axis=0)
            switch[b[switched]] = changed[:, switched].argmax(axis=0)
            flips[:, b[switched]] = ma[switch[b[switched]], k[switched]], \
                modes[switch[b[switched]], b[switched]]
            switched &= ~fired  # a switch in the step of the event: see _arrivals
        # solve_ivp would have stopped on an evaluation past the most allowed
        spent = calls[b] > max_calls
        undefined |= spent
        fired &= ~undefined
        ended = ~fired & ~undefined & (tk >= t_bound)
        stops = fired | undefined | ended  # (a switch is undefined, unless at the event)
        if not stops.any():
            continue
        status[b[spent]] = STALLED
        status[b[ended]] = NEVER
        status[b[fired]] = FIRED  # provisionally: until its event is located
        # one mode switched (and the step is otherwise sound): located like an event
        status[b[switched & ~spent]] = SWITCHED
        ends[:, :, b[fired]] = g_old[:, fired], g_new[:, fired]
        hit[:, b[fired]] = each[:, fired]
        moving[b[stops]] = False
    arrival = _arrivals(rhs, events, mode, history, status, ends, hit, lead, c, switch, flips,
                        modes)
    stopped = (status == STALLED) | ((status == FAILED) & np.isnan(arrival.t))
    arrival.t[stopped] = t[stopped]  # where it stopped
    never = status == NEVER
    arrival.t[never], arrival.y[:, never] = t[never], y[:, never]  # at the time allowed
    return _switches(rhs, mode, history, arrival, switch, flips, c)


def _earliest(times: np.ndarray) -> np.ndarray:
    """The event each column's instant is (``times``: events x columns, NaN where one did not
    fire): the earliest root, the lowest index of equal ones."""
    return np.where(np.isnan(times), np.inf, times).argmin(axis=0)


def _switches(rhs, mode, history: "_History", arrival: Arrival, switch, flips, c) -> Arrival:
    """``arrival`` with each switched column's switch located on the dense output of the
    step it happened in: where its mode's sign changes (bisected); a switch not located is a
    column failed."""
    w = np.flatnonzero(arrival.status == SWITCHED)
    if not len(w):
        return arrival
    last = (history.pushed[w] - 1) % history.size
    dense, t_old, t_new = history.dense(rhs, w, last, c)
    kept = history.modes[w, last].T
    j = switch[w]

    def sign(i, t, y):
        return mode(w[i], t, y)[j[i], np.arange(len(i))]

    root, found = _event_time(sign, dense, t_old, t_new, flips[0, w], flips[1, w])
    status, t, y = arrival.status.copy(), arrival.t.copy(), arrival.y.copy()
    status[w[~found]] = FAILED
    t[w] = root
    y[:, w] = dense(root, np.arange(len(w)))
    modes = np.full((kept.shape[0], len(status)), np.nan)
    modes[:, w] = kept
    return Arrival(status, t, y, arrival.before, switch, modes, arrival.which)


def _arrivals(rhs, events: list, mode, history: "_History", status, ends, hit, lead, c,
              switch, flips, modes) -> Arrival:
    """Each fired column's event located on the dense output of the step it fired in (of
    several events, the earliest of those that fired there: :func:`_earliest`), and its state a
    moment before (on the dense output of the step that holds that moment); one
    whose mode (``switch``) switched in that step before that moment has
    :data:`SWITCHED`, as has one where a single mode had switched by that moment beside
    those that switch at the event (an event that ends a slip ends its mode too): that
    mode's ``switch`` and ``flips`` (its signs at the step's ends) are set here, ``modes``
    those at the step's end."""
    count, _, m = history.y_old.shape
    t_event = np.full(count, np.nan)
    y_event = np.full((m, count), np.nan)
    before = np.full((m, count), np.nan)
    e = np.flatnonzero(status == FIRED)
    if not len(e):
        return Arrival(status, t_event, y_event, before)
    last = (history.pushed[e] - 1) % history.size
    dense, t_old, t_new = history.dense(rhs, e, last, c)
    kept = history.modes[e, last].T
    times = np.full((len(hit), len(e)), np.nan)
    found = np.ones(len(e), dtype=bool)
    for j in range(len(hit)):
        f = np.flatnonzero(hit[j, e])
        if not len(f):
            continue
        root_j, found_j = _event_time(
            lambda i, t, y, j=j, f=f: events[j](e[f[i]], t, y, kept[:, f[i]]),
            lambda t, i, f=f: dense(t, f[i]), t_old[f], t_new[f], ends[0, j, e[f]],
            ends[1, j, e[f]])
        times[j, f] = root_j
        found[f] &= found_j  # an event not located: the instant is not known
    which = _earliest(times)
    everyone = np.arange(len(e))
    root = times[which, everyone]
    t_event[e] = root
    y_event[:, e] = dense(root, everyone)
    earlier = np.maximum(root * (1 - lead), history.start[e])
    before[:, e] = dense(np.clip(earlier, t_old, t_new), everyone)
    slot, held = history.holding(e, earlier)
    back = np.flatnonzero(held & (slot != last))
    if len(back):
        dense_back, _, _ = history.dense(rhs, e[back], slot[back], c)
        before[:, e[back]] = dense_back(earlier[back], np.arange(len(back)))
    kept_moment = held.copy()
    if mode is not None:  # the motion just before the event is the one integrated to it
        differs = mode(e, earlier, before[:, e]) != kept
        held &= ~differs.any(axis=0)
        one = np.flatnonzero((differs.sum(axis=0) == 1) & (switch[e] < 0))
        j = differs[:, one].argmax(axis=0)
        turned = modes[j, e[one]] == -kept[j, one]  # its sign changes across the step
        one, j = one[turned], j[turned]
        switch[e[one]] = j
        flips[:, e[one]] = kept[j, one], modes[j, e[one]]
    status[e[~(found & held)]] = FAILED  # an event not located, or a moment not kept
    status[e[found & kept_moment & ~held & (switch[e] >= 0) & (slot == last)]] = SWITCHED
    chosen = np.full(count, -1)
    chosen[e] = which
    return Arrival(status, t_event, y_event, before, which=chosen)


class _History:
    """The last accepted steps of every column (the step's ends and stages), enough to
    build the dense output of any of them."""

    def __init__(self, count: int, m: int, stages: int, modes: int, start: np.ndarray,
                 size: int):
        # steps kept per column: the moment before the event is in the last few, unless the
        # steps shorten a great deal before it (a singularity passed)
        self.size = L = size
        self.start = start  # each column's
        # a column's steps side by side (column, step, ...): a step pushed or read is one
        # block of memory per column
        self.modes = np.empty((count, L, modes))
        self.t_old = np.full((L, count), np.nan)
        self.t_new = np.full((L, count), np.nan)
        self.y_old = np.empty((count, L, m))  # read only where a step was pushed
        self.y_new = np.empty((count, L, m))
        self.K = np.empty((count, L, stages, m))
        self.pushed = np.zeros(count, dtype=int)

    def push(self, cols, t_old, t_new, y_old, y_new, K, modes) -> None:
        slot = self.pushed[cols] % self.size
        self.modes[cols, slot] = modes.T
        self.t_old[slot, cols] = t_old
        self.t_new[slot, cols] = t_new
        self.y_old[cols, slot] = y_old.T
        self.y_new[cols, slot] = y_new.T
        self.K[cols, slot] = K.transpose(2, 0, 1)
        self.pushed[cols] += 1

    def holding(self, cols, t) -> tuple[np.ndarray, np.ndarray]:
        """The slot of the step of each column that holds its time ``t`` (``t_old < t <=
        t_new``, as ``OdeSolution`` picks the step; the first step holds its start too), and
        whether one is kept."""
        t_old = self.t_old[:, cols]
        inside = ((t_old < t) | (t_old == self.start[cols])) & (t <= self.t_new[:, cols])
        return inside.argmax(axis=0), inside.any(axis=0)

    def dense(self, rhs, cols, slots, c):
        """The dense output of each column's step in ``slots``, and the steps' ends."""
        stages = self.K.shape[2]
        K, flat = _stages(c.N_STAGES_EXTENDED, self.y_old.shape[2], len(cols))
        K[:stages] = self.K[cols, slots].transpose(1, 2, 0)
        t_old, t_new = self.t_old[slots, cols], self.t_new[slots, cols]
        return (_dense(rhs, cols, t_old, t_new - t_old, self.y_old[cols, slots].T,
                       self.y_new[cols, slots].T, K, flat, self.modes[cols, slots].T, c),
                t_old, t_new)


def _first_step(rhs, cols, t, y, f, modes, t_bound, rtol, atol) -> np.ndarray:
    """scipy's ``select_initial_step`` for every column (each at its time ``t``)."""
    m = y.shape[0]
    interval = t_bound - t
    scale = atol + np.abs(y) * rtol
    with np.errstate(all="ignore"):
        d0 = np.sqrt((((y / scale) ** 2).sum(axis=0)) / m)
        d1 = np.sqrt((((f / scale) ** 2).sum(axis=0)) / m)
        h0 = np.where((d0 < 1e-5) | (d1 < 1e-5), 1e-6, 0.01 * d0 / d1)
        h0 = np.minimum(h0, interval)
        f1 = rhs(cols, t + h0, y + h0 * f, modes)
        d2 = np.sqrt(((((f1 - f) / scale) ** 2).sum(axis=0)) / m) / h0
        h1 = np.where((d1 <= 1e-15) & (d2 <= 1e-15), np.maximum(1e-6, h0 * 1e-3),
                      (0.01 / np.maximum(d1, d2)) ** (1 / 8))
    return np.minimum(np.minimum(100 * h0, h1), interval)


def _dense(rhs, cols, t_old, h, y_old, y_new, K, flat, modes, c):
    """The DOP853 dense output of each column's last step (its three extra stages
    evaluated; ``K``, ``flat``: :func:`_stages`): ``at(t, which)`` the states of the columns
    ``which``, each at its time."""
    for s in range(c.N_STAGES + 1, c.N_STAGES_EXTENDED):
        K[s] = rhs(cols, t_old + c.C[s] * h, y_old + _combine(_ROWS[s], flat, y_old.shape) * h,
                   modes)
    delta = y_new - y_old
    F = np.empty((c.INTERPOLATOR_POWER,) + y_old.shape)
    F[0] = delta
    F[1] = h * K[0] - delta
    F[2] = 2 * delta - h * (K[c.N_STAGES] + K[0])
    F[3:] = h * _combine(c.D, flat, y_old.shape)

    def at(t: np.ndarray, which: np.ndarray) -> np.ndarray:
        x = (t - t_old[which]) / h[which]
        factors = (x, 1 - x)
        y = np.zeros((y_old.shape[0], len(which)))
        for i, term in enumerate(F[::-1, :, which]):
            y += term
            y *= factors[i % 2]
        return y + y_old[:, which]
    return at


def _event_time(event, dense, a, b, fa, fb) -> tuple[np.ndarray, np.ndarray]:
    """Each column's root of ``event`` on its dense output between ``a`` and ``b`` (where
    it changes sign), to a few units in the last place as ``brentq`` finds it: regula falsi
    with the Illinois correction, bisecting where that stalls, until the bracket or the
    step is that small. Returns the roots and which converged."""
    a, b, fa, fb = a.copy(), b.copy(), fa.copy(), fb.copy()
    root = np.where(fb == 0, b, a)
    todo = (fa != 0) & (fb != 0)
    converged = ~todo
    last = np.zeros(len(a), dtype=int)  # which end moved last: -1 a, +1 b
    for step in range(200):
        if not todo.any():
            break
        i = np.flatnonzero(todo)
        ai, bi, fai, fbi, li = a[i], b[i], fa[i], fb[i], last[i]  # each gathered once
        with np.errstate(all="ignore"):
            x = (ai * fbi - bi * fai) / (fbi - fai)
        lo, hi = np.minimum(ai, bi), np.maximum(ai, bi)
        # at an end (whose value is rounding beside the other's): the next number inside it
        # brackets a root there at once (as brentq's least step), where bisecting crawls
        x = np.where(x >= hi, np.nextafter(hi, lo), np.where(x <= lo, np.nextafter(lo, hi), x))
        stalled = ~((x > lo) & (x < hi)) | (step % 4 == 3)
        x = np.where(stalled, 0.5 * (ai + bi), x)
        fx = event(i, x, dense(x, i))
        undefined = ~np.isfinite(fx)
        same_a = np.sign(fx) == np.sign(fai)
        # Illinois: the end that stays twice in a row has its value halved
        ai, fai = np.where(same_a, x, ai), np.where(same_a, fx, np.where(li == 1, fai / 2, fai))
        bi, fbi = np.where(same_a, bi, x), np.where(same_a, np.where(li == -1, fbi / 2, fbi), fx)
        a[i], fa[i], b[i], fb[i] = ai, fai, bi, fbi
        last[i] = np.where(same_a, -1, 1)
        # two iterates a few units in the last place apart: the root is that well known
        close = 4 * EPS * np.abs(x)
        settled = (step > 0) & ~stalled & (np.abs(x - root[i]) <= close)
        root[i] = x
        done = ((fx == 0) | settled | (np.abs(bi - ai) <= 4 * EPS + close)) & ~undefined
        converged[i[done]] = True
        todo[i[done | undefined]] = False
    return root, converged


def design_roots(reach: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
                 equation: Callable, guess: float, count: int
                 ) -> tuple[np.ndarray, np.ndarray]:
    """The design stage over columns: per column, the design parameter's value that makes the
    design ``equation`` (lambdified in an instant's extended state) zero, by :func:`newton`
    from ``guess``. ``reach(columns, values)`` gives the instant reached with each value (one
    state per column of its result) and which were reached: the equation is undefined at the
    others. Returns the roots and which converged to a finite one. One instant is a design
    of one column (:meth:`~.dynamics.DesignedInstant.designed`), a class of variants one
    column each (the batch's ``_designed``).

    >>> roots, ok = design_roots(lambda cols, v: (v[None, :], v > 0), lambda x: x * x - 2.0,
    ...                          1.0, 2)
    >>> np.round(roots, 12).tolist(), ok.tolist()
    ([1.414213562373, 1.414213562373], [True, True])
    """
    def residual(cols: np.ndarray, values: np.ndarray) -> np.ndarray:
        # the iterates (row 0), then the points beside them (row 1): one reach for both
        states, fine = reach(np.concatenate([cols, cols]), values.ravel())
        r = np.full(fine.shape, np.nan)
        if fine.any():
            r = np.where(fine, call(equation, states, 1)[0], np.nan)
        return r.reshape(2, len(cols))

    with warnings.catch_warnings():  # an iteration that wanders off is not converged
        warnings.simplefilter("ignore", RuntimeWarning)
        root, converged = newton(residual, np.full(count, float(guess)))
    return root, converged & np.isfinite(root)


def root_between(f: Callable[[float], float], a: float, b: float, fa: float, fb: float
                 ) -> tuple[float, bool]:
    """A root of ``f`` between ``a`` and ``b``, where it changes sign (``fa``, ``fb`` its
    values there), found as an event's time is (:func:`_event_time`); and whether it
    converged.

    >>> root, ok = root_between(lambda x: x * x - 2.0, 1.0, 2.0, -1.0, 2.0)
    >>> round(root, 12), ok
    (1.414213562373, True)
    """
    roots, converged = _event_time(
        lambda _, x, __: np.array([f(float(v)) for v in x]), lambda *_: None,
        np.array([a]), np.array([b]), np.array([fa]), np.array([fb]))
    return float(roots[0]), bool(converged[0])


ROUNDING_FLOOR = 1e-9
"""A Newton step this small relative to the iterate, that no longer shrinks, is rounding
noise of the residual: the iterate is the root as closely as the residual can tell."""


ROOT_XTOL, ROOT_RTOL, ROOT_ITERATIONS = 1e-15, 1e-13, 100
"""How closely a design parameter's root is found (``xtol + rtol * |x|``) and in how many
iterations at most by :func:`newton` (the bracketing search a design falls back on finds it
to a few units in the last place: :func:`root_between`)."""


def newton(residual: Callable[[np.ndarray, np.ndarray], np.ndarray], x0: np.ndarray,
           xtol: float = ROOT_XTOL, rtol: float = ROOT_RTOL, maxiter: int = ROOT_ITERATIONS,
           step: float = 1e-7) -> tuple[np.ndarray, np.ndarray]:
    """Per column, a root of ``residual`` by Newton's method from ``x0``, the slope a forward
    difference (``step`` relative); ``residual(columns, x)`` gets the iterates (row 0) and
    the points a step beside them (row 1) together, one call per iteration, and gives their
    residuals. A column converges, as ``scipy.optimize.root_scalar``'s secant does, once its
    next iterate is within ``xtol + rtol * |x|`` of its last (whose residual was the last row
    0 evaluated for it), or once a step within :data:`ROUNDING_FLOOR` of ``|x|`` is no
    shorter than the one before (the residual is rounding noise there: the steps wander,
    they do not shrink); an undefined residual or a zero slope stops it, unconverged. Its
    root is then that last iterate, whose residual was evaluated (the next is within the
    tolerance of it): a caller keeps the instant it reached there, a class and one solve
    alike, rather than reaching the next iterate again.

    An iteration costs one call whatever the number of columns, so the count of calls is
    what matters: where a call is an integration, Newton's iterations (two points each,
    converging quadratically) are fewer than the secant's (one point each, order 1.6).

    >>> roots, ok = newton(lambda cols, x: x ** 2 - np.array([2.0, 9.0])[cols],
    ...                    np.array([1.0, 1.0]))
    >>> np.round(roots, 12).tolist(), ok.tolist()
    ([1.414213562373, 3.0], [True, True])
    """
    count = len(x0)
    x = x0.astype(float).copy()
    scale = np.where(x != 0, np.abs(x), 1.0)
    root = np.full(count, np.nan)
    converged = np.zeros(count, dtype=bool)
    todo = np.isfinite(x)
    last = np.full(count, np.inf)  # each column's latest step
    for _ in range(maxiter):
        i = np.flatnonzero(todo)
        if not len(i):
            break
        h = step * np.maximum(np.abs(x[i]), scale[i])
        r = residual(i, np.stack([x[i], x[i] + h]))
        with np.errstate(all="ignore"):
            p = x[i] - r[0] * h / (r[1] - r[0])
            moved = np.abs(p - x[i])
            floor = (moved >= last[i]) & (moved <= ROUNDING_FLOOR * np.abs(x[i]))
        stuck = ~np.isfinite(p)  # an undefined residual, or no slope: stops, unconverged
        todo[i[stuck]] = False
        close = ~stuck & (np.isclose(p, x[i], rtol=rtol, atol=xtol) | floor)
        root[i[close]] = x[i[close]]
        converged[i[close]] = True
        todo[i[close]] = False
        go = ~stuck & ~close
        last[i[go]] = moved[go]
        x[i[go]] = p[go]
    return root, converged
