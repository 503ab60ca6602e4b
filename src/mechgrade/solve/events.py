"""The rules of a motion integrated to an event: the tolerances and steps allowed, the direction
its event is waited for in when it holds at the start (:func:`leaving`), the errors an
integration ends with, an objective read at the event (:func:`at_the_event`), and the motion
in closed form where its accelerations stay constant (:func:`integrated_symbolically`).

The coordinates and rates from ``from:`` at t = 0 are integrated over columns
(:mod:`.batch_motion`: DOP853, rtol 1e-11, the steps ``scipy.integrate.solve_ivp`` takes) until
the event equation first holds (root refined on the dense output): a class's variants by
:func:`~.phases.reach_columns`, one motion as a class of one, or where that does not vouch
for it as one column solved alone (:func:`~.phases.reach`). The objectives are read at the event,
with ``t`` its time; the accelerations and reactions there are the limits just before the
event (a kinetic-friction force has no direction once the slip has ended). An objective asked
at its own time, coordinate or rate is read where that first holds, before the event; an
event, or such a given, that holds at t = 0 is its next crossing.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Callable

import numpy as np
import sympy as sp

from ..errors import SolveError
from ..spec.dynamics import Integration
from ..spec.model import Objective, Root
from ..tolerance import within_each
from ..units import si_factor
from .analysis import closed_forms
from . import dop853
from .batch_motion import NEVER, STALLED, Field, integrate_to_events
from .rules import on_branch, real

RTOL, ATOL = 1e-11, 1e-12
MAX_CALLS = 20_000  # right-hand-side evaluations before an integration is judged stalled
EVERY_STEP = MAX_CALLS // dop853.N_STAGES + 1
"""The steps one motion integrated alone keeps (every step it may take), where the moment
before its event is read, as ``solve_ivp``'s dense output keeps them."""


def at_start(g) -> np.ndarray:
    """Whether an event whose value at the start is ``g`` (SI, one per column) holds there:
    within the integrator's absolute tolerance :data:`ATOL` of zero, which no step resolves
    (a start given as 0.35 m and an event at 35 cm are 5.5e-17 m apart after the units are
    converted: not a crossing 4.7e-18 s on).

    >>> at_start(np.array([0.0, -5.5e-17, 2e-12, np.nan])).tolist()
    [True, True, False, False]
    """
    return np.abs(g) <= ATOL


LEAVING = 1e-6
"""The moment after the start, as a part of the time allowed, at which the side an event that
holds at the start is left to is read: far shorter than any motion the time allowed holds."""


def not_integrated(status: int, t: float, where) -> SolveError:
    """The error of an integration that ended at ``t`` without an answer
    (``status``: :data:`~.batch_motion.STALLED`, or failed)."""
    if status == STALLED:
        return SolveError(f"the integration stalls near t = {t:.6g} s before the event (the "
                          "motion may switch there, e.g. friction reversing once the slip "
                          "ends)", where=where)
    return SolveError(f"the integration failed near t = {t:.6g} s: its step fell below the "
                      "spacing of numbers there, or the motion is undefined", where=where)


def leaving(rhs: Field, event: Callable, mode: Callable | None, y0: np.ndarray, t_bound: float,
            where, what: str = "the event"
            ) -> tuple[np.ndarray, dict[int, SolveError], dict[int, SolveError]]:
    """Each column's event's ``direction`` (as scipy reads it, see
    :func:`~.batch_motion.integrate_to_events`; ``y0``: the start states, one per column):
    where the event holds at t = 0 (a projectile launched from the ground, ``until: y = 0``),
    its next crossing, back through zero from the side the motion leaves to a moment later
    (:data:`LEAVING` of the time allowed, ``t_bound``); 0 (either way) elsewhere. With it,
    the error of each column whose motion stays in the event (a state at rest in it:
    :func:`event_stays`, naming it ``what``), and of each whose moment later is not reached
    or where the event
    is undefined (direction 0: a class solves that column alone, which says why). One
    motion alone is one column, which raises its first error (:mod:`.phases`).

    >>> up = lambda c, t, y, m: np.stack([y[1], -np.ones(len(c))])  # thrown up, or at rest
    >>> rest = lambda c, t, y, m: np.stack([y[1], np.zeros(len(c))])
    >>> direction, stays, _ = leaving(up, lambda c, t, y, m: y[0], None,
    ...                               np.array([[0.0, 0.0, 1.0], [2.0, -2.0, 0.0]]), 10.0, None)
    >>> direction.tolist(), stays
    ([-1.0, 1.0, 0.0], {})
    >>> sorted(leaving(rest, lambda c, t, y, m: y[0], None, np.zeros((2, 1)), 10.0, None)[1])
    [0]
    """
    count = y0.shape[1]
    everyone = np.arange(count)
    start = np.zeros(count)
    g = event(everyone, start, y0, mode(everyone, start, y0) if mode else None)
    direction = np.zeros(count)
    held = np.flatnonzero(at_start(g))
    if not len(held):
        return direction, {}, {}
    moment = integrate_to_events(
        lambda c, t, y, m: rhs(held[c], t, y, m), [], y0[:, held], LEAVING * t_bound, RTOL,
        ATOL, MAX_CALLS, mode=(lambda c, t, y: mode(held[c], t, y)) if mode else None)
    y = moment.y
    side = np.sign(event(held, moment.t, y, mode(held, moment.t, y) if mode else None))
    # a state at rest in the event (an equilibrium) moves only by rounding: it stays there
    moved = np.abs(y - y0[:, held]).max(axis=0, initial=0.0) > ATOL
    reached = moment.status == NEVER  # at the moment: the end of the time it was given
    direction[held] = np.where(reached & moved & np.isfinite(side), -side, 0.0)
    stays = {int(i): event_stays(where, what) for i in held[reached & ((side == 0) | ~moved)]}
    left = ~reached | (moved & ~np.isfinite(side))
    return direction, stays, {int(i): not_integrated(int(status), float(t), where)
                              for i, status, t in zip(held[left], moment.status[left],
                                                      moment.t[left])}


def event_stays(where, what: str = "the event") -> SolveError:
    """The error of an event (or an objective's own instant, ``what`` names it) that holds at
    t = 0 and that the motion does not leave (a state at rest in it), found by
    :func:`leaving`.

    >>> str(event_stays(None, "'x: 0 mm'"))
    "'x: 0 mm' holds at the start (t = 0) and stays so: expected a motion that leaves it"
    """
    return SolveError(f"{what} holds at the start (t = 0) and stays so: expected a motion "
                      "that leaves it", where=where)


def instant_missed(analysis: Integration, given: str, where, until_times) -> SolveError:
    """The error of an objective's own instant (``given`` as written, ``where`` it is) that
    the motion does not reach before its event (at ``until_times[0]``, if it happened) or
    within the time allowed."""
    if len(until_times):
        return SolveError(f"'{given}' does not hold before the event ('{analysis.until[0].text} "
                          f"= {analysis.until[1].text}', at t = {until_times[0]:.6g} s), where "
                          "the integrated motion ends: expected an instant before it",
                          where=where)
    return SolveError(f"'{given}' does not hold within {analysis.max_time:g} s of the "
                      "integrated motion: expected an instant it reaches (or a larger "
                      "max_time)", where=where)


def event_never_happens(analysis: Integration) -> SolveError:
    """The error of an integration that reaches the time allowed without its event."""
    return SolveError(f"the event '{analysis.until[0].text} = {analysis.until[1].text}' does "
                      f"not happen within {analysis.max_time:g} s", where=analysis.where)


def at_the_event(event: np.ndarray, before: np.ndarray, objective: Objective) -> np.ndarray:
    """An objective of an integration at its event: ``event`` (its SI values there, one column
    per variant), but where that is undefined or would be graded otherwise (the objective's
    tolerance) than ``before``, its limit just before the event, that limit. A kinetic
    friction force whose slip ends at the event has direction 0/0 there: a sign by rounding.

    >>> from mechgrade.spec.model import Objective, ObjectiveKind
    >>> friction = Objective(id="F", prompt="", find=None, kind=ObjectiveKind.VECTOR, unit="N")
    >>> at_the_event(np.array([[5.886, -5.886], [0.0, 0.0]]),
    ...              np.array([[-5.886, -5.886], [0.0, 0.0]]), friction)[0].tolist()
    [-5.886, -5.886]
    """
    tolerance = objective.tolerance
    abs_ = tolerance.abs * si_factor(objective.unit) if objective.unit else tolerance.abs
    defined = np.isfinite(before).all(axis=0)  # else nothing better to read
    graded_alike = within_each(event, before, tolerance.rel, abs_,
                               np.sqrt((before ** 2).sum(axis=0)))
    out = event.copy()
    out[:, defined & ~graded_alike] = before[:, defined & ~graded_alike]
    return out


# ---------------------------------------------------------------------------- closed form


def integrated_symbolically(kin, expr, numbers: dict, where=None):
    """``expr`` at the event in closed form, for a motion whose accelerations stay constant
    until it: q = q0 + q0' t + a t^2 / 2, with each kinetic-friction slip keeping the direction
    it has at the start (``|u|`` read as ``sign(u0) u``). The event time is the smallest root
    that is positive at the givens (``numbers``: plain symbol -> SI value), beyond rounding
    (:func:`_after`): the numbers only choose the root, so a class of variants derives the
    motion once (:func:`_closed_form`) and each expression once per root (:func:`_at_event`).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.mechanics.dynamics import derive_kinetics
    >>> kin = derive_kinetics(load_problem(shipped_dir("problems")
    ...                                    / "ruina_9_23_ball_impulse_momentum.yaml"))
    >>> integrated_symbolically(kin, kin.k.time, {s: 1.0 for _, s in kin.k.parameters})
    2*v0/(7*g*mu)
    """
    if kin.settled:  # its start is solved with numbers
        raise SolveError("a symbolic answer of an integrated motion with a massless junction "
                         "is out of reach (the junction's start is solved with numbers): "
                         "expected 'kind: scalar'", where=where)
    at_time, times = _closed_form(kin, where)
    values = closed_forms(times).at(numbers)
    roots = [(value.real, root) for root, value, after in zip(times, values, _after(values))
             if after]
    if not roots:
        raise SolveError("the event of the integrated motion has no closed-form time: ask for "
                         "a scalar", where=where)
    t_event = min(roots, key=lambda pair: pair[0])[1]
    if isinstance(expr, sp.MatrixBase):  # kept by value: the immutable one
        return sp.Matrix(_at_event(sp.ImmutableMatrix(expr), at_time, t_event))
    return _at_event(expr, at_time, t_event)


def _after(values) -> np.ndarray:
    """Which of an event's closed-form times ``values`` (complex, at the givens) are real and
    after the start: positive beyond the rounding of the largest of them
    (:func:`~.rules.on_branch`). A time that is zero in exact arithmetic (the event holds at
    the start) is its next crossing, as the integrator's (:func:`leaving`), whichever side of
    zero rounding puts it.

    >>> _after(np.array([1.8e-16, 2.4, -1.0, 3.0 + 1j])).tolist()
    [False, True, False, False]
    """
    values = np.asarray(values, dtype=complex)
    is_real = real(values)
    scale = np.abs(values.real[is_real]).max(initial=0.0)
    return is_real & on_branch(values.real, scale, Root.POSITIVE)


@lru_cache(maxsize=64)
def _closed_form(kin, where) -> tuple[tuple, tuple]:
    """The state at the event time ``t_event`` (symbol -> expression, as pairs) of the
    motion of ``kin`` with constant accelerations and the event's roots in ``t_event``
    (their values: :func:`~.analysis.closed_forms`); raises, located at ``where``, where
    that closed form is out of reach."""
    k = kin.k
    start = {**dict(kin.start), k.time: sp.Integer(0)}
    equations = [_frozen(e.expr, start, where, k.coordinates)
                 for e in (*kin.balances, *kin.constraints)]
    unknowns = [*k.qdd, *kin.reactions]
    A, b = sp.linear_eq_to_matrix(equations, unknowns)
    if A.rank() < len(unknowns):
        raise SolveError("the accelerations of the integrated motion are not determined "
                         "symbolically: ask for a scalar", where=where)
    solved = dict(zip(unknowns, (sp.simplify(v) for v in A.LUsolve(b))))
    state = {*k.q, *k.qd, k.time}
    if any(solved[a].free_symbols & state for a in k.qdd):
        raise SolveError("a symbolic answer of an integrated motion needs accelerations that "
                         "stay constant until the event (they change with the state here): "
                         "ask for a scalar", where=where)
    at_time = {**solved, k.time: _T}
    for q, qd, qdd in zip(k.q, k.qd, k.qdd):
        at_time[q] = start[q] + start[qd] * _T + solved[qdd] * _T ** 2 / 2
        at_time[qd] = start[qd] + solved[qdd] * _T
    event = sp.simplify(kin.until.xreplace(at_time))
    return tuple(at_time.items()), tuple(sp.solve(event, _T))


_T = sp.Symbol("t_event", positive=True)


@lru_cache(maxsize=256)
def _at_event(expr, at_time: tuple, t_event):
    """``expr`` with the state at the event (``at_time``) and the event's time put in."""
    result = expr.xreplace(dict(at_time)).xreplace({_T: t_event})
    return result.applyfunc(sp.simplify) if isinstance(result, sp.MatrixBase) \
        else sp.simplify(result)


def _frozen(expr, start: dict, where, coordinates=()):
    """``expr`` with every ``|u|`` and ``sign(u)`` of a slip read with the sign ``u`` has at
    the start (the slip keeps its direction until the event)."""

    def sign_at_start(u):
        u0 = sp.simplify(u.xreplace(start))
        s = sp.sign(u0)
        if s not in (1, -1):
            raise SolveError(unknown_slip_sign(u, u0, coordinates), where=where)
        return s

    expr = expr.replace(lambda e: isinstance(e, sp.Abs), lambda e: sign_at_start(e.args[0]) * e.args[0])
    return expr.replace(lambda e: isinstance(e, sp.sign), lambda e: sign_at_start(e.args[0]))


def unknown_slip_sign(u, u0, coordinates=("x",)) -> str:
    """Why a slip's direction at the start is not known, and what to add.

    >>> v0 = sp.Symbol("v0", real=True)
    >>> print(unknown_slip_sign(sp.Symbol("xd", real=True), v0))  # doctest: +NORMALIZE_WHITESPACE
    the sign of the slip x' at the start is not known: it is v0 there, and v0 may be negative;
    a symbolic answer of an integrated motion needs every slip's direction fixed: declare v0
    positive (leave out positive: false), or ask for a scalar objective (integrated
    numerically)
    """
    rates = {f"{c}d": f"{c}'" for c in coordinates} | {f"{c}dd": f"{c}''" for c in coordinates}
    spelled = {x: sp.Symbol(rates[str(x)]) for x in (u.free_symbols | u0.free_symbols)
               if str(x) in rates}
    signed = sorted((x for x in u0.free_symbols if not x.is_positive), key=str)
    positive = {x: sp.Dummy(str(x), positive=True) for x in signed}
    fix = "write the start so that the slip's direction is evident (its speed as one " \
        "positive parameter)"
    if signed and sp.sign(sp.simplify(u0.xreplace(positive))) in (1, -1):
        fix = f"declare {', '.join(map(str, signed))} positive (leave out positive: false)"
    may = f", and {', '.join(map(str, signed))} may be negative" if signed else ""
    return (f"the sign of the slip {sp.sstr(u.xreplace(spelled))} at the start is not known: it "
            f"is {sp.sstr(u0.xreplace(spelled))} there{may}; a symbolic answer of an integrated "
            f"motion needs every slip's direction fixed: {fix}, or ask for a scalar objective "
            "(integrated numerically)")
