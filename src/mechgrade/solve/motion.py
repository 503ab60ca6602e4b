"""The motion of a dynamics problem at many states at once, each a column: the second rates and
reactions from the momentum balances, each column checked and given the error it alone would
raise (:func:`balances`, which :func:`~.dynamics.solve_kinetics` calls with one column), and
the motion integrated to its event (:func:`~.batch_motion.integrate_to_events`). A class of
variants (:mod:`.batch`) and an instant solved alone (:mod:`.dynamics`) are solved here alike.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache, partial
from typing import Callable

import numpy as np

from ..errors import (InconsistentError, Location, MechgradeError, SolveError,
                      UnderdeterminedError)
from ..spec.dynamics import Integration, dynamics_of
from ..spec.model import Problem
from . import rules
from .analysis import analysis_plan
from .batch_motion import FIRED, NEVER, SWITCHED, Arrival, integrate_to_events
from .columns import Cramer, FirstErrors, call, least_squares_solution, loud_call, quiet
from .events import ATOL, MAX_CALLS, RTOL, event_never_happens, leaving
from .junctions import settle_junctions
from .plan import KinematicsPlan
from .rules import satisfied


def after_event(p: KinematicsPlan) -> np.ndarray:
    """What the state at an integration's event has known: its coordinates, rates, parameters
    and time."""
    after = np.zeros(p.index.size, dtype=bool)
    after[list(p.index.config)] = True
    after[list(p.index.rates(1))] = True
    return after


def at_event(before: np.ndarray, end: np.ndarray, p: KinematicsPlan) -> np.ndarray:
    """The extended state(s) an event's objectives are read in: everything of ``end`` (the
    state at the event) but its second rates, and those and the reactions of ``before``
    (the balances solved just before it, where the contact checks hold along the way).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve.plan import kinematics_plan
    >>> p = kinematics_plan(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"))
    >>> x = at_event(np.zeros(p.index.size + 1), np.ones(p.index.size), p)
    >>> x[list(p.index.rates(2))].tolist(), float(x[-1])
    ([0.0], 0.0)
    """
    x = before.copy()
    seconds = p.index.rates(2)
    keep = [i for i in range(p.index.size) if i not in seconds]
    x[keep] = end[keep]
    return x


class Motion:
    """The kinetics of ``problem`` (its :class:`~.dynamics.KineticsPlan`) over columns."""

    def __init__(self, problem: Problem, kinetics):
        self.problem, self.kinetics, self.p = problem, kinetics, kinetics.kp
        self.analysis = dynamics_of(problem).analysis

    def integrated(self, X: np.ndarray, instants: np.ndarray | None = None
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict[int, MechgradeError]]:
        """Every column's motion integrated from its start state to its event (together:
        :func:`~.batch_motion.integrate_to_events`, the steps each takes alone): the
        extended state at the event, the accelerations and reactions the limits just before
        it, with the extended states just before the event stacked under them; which
        columns passed the screens, which ended without their event
        (:data:`~.batch_motion.NEVER`), and the error of each that failed the checks of
        :func:`balances` just before its event, or whose slip ended before its event and
        sticks there (:meth:`_stuck`).

        With ``instants`` (per column the position of the time, coordinate or rate an
        objective is asked at, its value in that column of ``X``; -1: the event): those
        columns' states where that value is first taken before the event instead
        (:meth:`_at_instant`), in the same pass as the others (a class's instants of every
        group side by side: one integration)."""
        kp = self.kinetics
        assert kp is not None and isinstance(self.analysis, Integration)
        ap = analysis_plan(kp)
        index = self.p.index
        n, size, count = index.n, index.size, X.shape[1]
        everyone = np.arange(count)
        instant = np.full(count, -1) if instants is None else np.asarray(instants, dtype=int)
        waits = instant >= 0  # the columns asked at an instant of their own
        asked = X[instant, everyone]  # (the event's columns: a value never read)
        rates, seconds = index.rates(1), index.rates(2)
        # slices: the right-hand side is evaluated thousands of times
        qd, qdd = slice(rates.start, rates.stop), slice(seconds.start, seconds.stop)
        kinetic = size + len(kp.kin.reactions)
        extended = np.concatenate([X, np.zeros((kinetic - size, count))])
        values = X.copy()
        for i, fn in ap.start:
            values[i] = call(fn, extended, 1)[0]
        values, unsettled = settle_junctions(self.problem, kp, values)
        for c in unsettled:  # integrated with the others, its error kept
            values[:, c] = np.nan_to_num(values[:, c])
        values[index.time] = 0.0
        values[qdd] = 0.0
        switches = _switches(kp)
        # every column's extended state (second rates and reactions 0, as the unknowns of
        # the balances), then its modes
        full = np.zeros((kinetic + (switches.count if switches else 0), count))
        full[:size] = values
        # a matrix that reads parameters only is the same all along: worked out once
        constant = constant_matrix(kp, full, switches)

        # the stages of a step share its columns: their states and matrix gathered once
        last: list = [None, full, constant]

        def among(cols: np.ndarray) -> list:
            if cols is not last[0]:  # (cols is sorted: all of them is all in order)
                every = len(cols) == count
                last[:] = cols, full if every else full[:, cols], \
                    constant and constant.of(cols)
            return last

        def at(cols: np.ndarray, t: np.ndarray, y: np.ndarray,
               modes: np.ndarray | None = None) -> np.ndarray:
            x = among(cols)[1].copy()
            x[:n] = y[:n]
            x[qd] = y[n:]
            x[index.time] = t
            if modes is not None and switches is not None:
                x[kinetic:] = modes
            return x

        def accelerated(cols: np.ndarray, x: np.ndarray) -> np.ndarray:
            return self.accelerations(x, switches, among(cols)[2])

        def rhs(cols: np.ndarray, t: np.ndarray, y: np.ndarray,
                modes: np.ndarray) -> np.ndarray:
            return np.concatenate([y[n:], accelerated(cols, at(cols, t, y, modes))[qdd]])

        def event(cols: np.ndarray, t: np.ndarray, y: np.ndarray,
                  modes: np.ndarray | None) -> np.ndarray:
            x = at(cols, t, y, modes)
            if ap.until_kinetic:
                x = accelerated(cols, x)
            assert ap.until is not None  # an integration has its event
            return loud_call(ap.until, x[:kinetic], 1)[0]

        def mode(cols: np.ndarray, t: np.ndarray, y: np.ndarray) -> np.ndarray:
            assert switches is not None
            x = at(cols, t, y)[:kinetic]
            return np.sign(loud_call(switches.speeds, x, switches.count))

        def reached(cols: np.ndarray, t: np.ndarray, y: np.ndarray,
                    modes: np.ndarray | None) -> np.ndarray:
            return at(cols, t, y, modes)[instant[cols], np.arange(len(cols))] - asked[cols]

        def either(cols: np.ndarray, t: np.ndarray, y: np.ndarray,
                   modes: np.ndarray) -> np.ndarray:
            # an instant's column stops where its instant's or its event's equation holds
            g = event(cols, t, y, modes)
            return np.where(waits[cols], reached(cols, t, y, modes) * g, g)

        y0 = np.concatenate([values[:n], values[qd]])
        switching = mode if switches else None
        start = np.zeros(count)
        g0 = r0 = start  # the instants' equations at the start
        held: dict[int, SolveError] = {}
        with quiet():
            away_from, stays, _ = leaving(rhs, event, switching, y0, self.analysis.max_time,
                                          self.analysis.where)
            direction = away_from
            if waits.any():
                modes = mode(everyone, start, y0) if switching else None
                g0 = event(everyone, start, y0, modes)
                r0 = reached(everyone, start, y0, modes)
                timed = waits & (instant == index.time)
                # a coordinate or rate taken at the start: its next crossing (t = 0 is the
                # start); a time, or the event, waits for none. One that stays there is not
                # answered: alone, its error is located at the objective's given
                crossing, held, _ = leaving(
                    rhs, lambda c, t, y, m: np.where(waits[c] & ~timed[c],
                                                     reached(c, t, y, m), 1.0),
                    switching, y0, self.analysis.max_time, self.analysis.where)
                direction = np.where(waits, np.where(g0 != 0, np.sign(g0) * crossing,
                                                     np.sign(r0) * away_from), away_from)
            arrival = integrate_to_events(rhs, either if waits.any() else event, y0,
                                          self.analysis.max_time, RTOL, ATOL, MAX_CALLS,
                                          mode=switching, direction=direction)
        out = np.full((2 * kinetic, count), np.nan)
        ok = np.zeros(count, dtype=bool)
        never = np.zeros(count, dtype=bool)
        errors: dict[int, MechgradeError] = {}
        e = np.flatnonzero(~waits)
        if len(e):  # those reaching the event
            ok_e = arrival.status[e] == FIRED
            end = at(e, arrival.t[e], arrival.y[:, e])
            solved = balances(self.problem, self.kinetics,
                              at(e, arrival.t[e] * (1 - rules.BEFORE_EVENT),
                                 arrival.before[:, e])[:size], after_event(self.p))
            before, fine = solved.x, solved.ok
            out[:, e] = np.vstack([at_event(before, end, self.p), before])
            ok[e] = ok_e & fine
            never[e] = arrival.status[e] == NEVER
            # an event reached whose contact checks fail just before it: the error the
            # single solve raises there, without integrating that column again step by step
            errors.update({int(e[i]): error for i in np.flatnonzero(ok_e & ~fine)
                           if (error := solved.errors[int(i)]) is not None})
            if switches is not None:
                errors.update(self._stuck(arrival, at, switches, ~waits))
        a = np.flatnonzero(waits)
        if len(a):
            barred = np.isin(a, list(unsettled) + list(stays) + list(held))
            out[:, a], ok[a], failed = self._at_instant(
                a, instant[a], asked[a], arrival, at, event, reached, switching, y0[:, a],
                (g0[a], r0[a], away_from[a]), barred)
            errors.update(failed)
        ok[list(unsettled)] = ok[list(stays)] = never[list(stays)] = False
        return out, ok, never, {**errors, **stays, **unsettled}

    def _at_instant(self, cols: np.ndarray, instant: np.ndarray, asked: np.ndarray,
                    arrival: Arrival, at: Callable, until: Callable, reached: Callable,
                    mode: Callable | None, y0: np.ndarray,
                    started: tuple[np.ndarray, np.ndarray, np.ndarray], barred: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, dict[int, MechgradeError]]:
        """The columns ``cols`` of :meth:`integrated` asked at an instant of their own: where
        entry ``instant`` of the state first takes each column's ``asked`` value before the
        event (the steps each takes alone, :func:`~.phases.reach`). Their
        motion stopped where the product of the instant's and the event's equations changed
        sign (``arrival``; either one that holds at the start waits for its next crossing,
        :func:`~.events.leaving`; t = 0 is the start); ``started``: the event's and the instant's
        equations at the start and the event's direction. A column is answered where the
        event's equation is then still away from zero on the side it started on
        (:data:`~.rules.EVENT_AWAY`), unless ``barred`` (its error found at the start): the
        state there (stacked twice: it is no event's limit), which columns passed the
        screens, and the error of each that fails :func:`balances` there. A column where both
        hold at the start, that meets its event first, or that never meets either, is not
        answered here: alone, it says why."""
        size = self.p.index.size
        g0, r0, away_from = started
        now = (r0 == 0) & (instant == self.p.index.time)
        t = np.where(now, 0.0, arrival.t[cols])
        y = np.where(now, y0, arrival.y[:, cols])
        with quiet():
            moved = mode(cols, t, y) if mode is not None else None
            r, g = reached(cols, t, y, moved), until(cols, t, y, moved)
        away = np.where(g0 != 0, np.abs(g) > rules.EVENT_AWAY * np.abs(g0),
                        np.abs(r) <= rules.EVENT_AWAY * np.abs(r0))
        side = np.where(g0 != 0, np.sign(g0), -away_from)
        ok = (now | ((arrival.status[cols] == FIRED) & away & (np.sign(g) == side)
                     & (side != 0))) & ~barred
        end = at(cols, t, y)
        everyone = np.arange(len(cols))
        # where the root was found: the given holds there
        end[instant, everyone] = np.where(ok, asked, end[instant, everyone])
        solved = balances(self.problem, self.kinetics, end[:size], after_event(self.p))
        x, fine = solved.x, solved.ok
        failed = {int(cols[i]): error for i in np.flatnonzero(ok & ~fine)
                  if (error := solved.errors[int(i)]) is not None}
        return np.vstack([x, x]), ok & fine, failed

    def _stuck(self, arrival: Arrival, at: Callable, switches: _Switching, among: np.ndarray
               ) -> dict[int, MechgradeError]:
        """The columns whose one slip ended before their event (:data:`~.batch_motion.SWITCHED`)
        and where kinetic friction then holds the contact whichever way it is read: slipping
        on, friction drives the slip speed back across zero, turned round it drives it back
        too. That motion sticks, which an integration of these equations cannot follow (the
        one-by-one integrator shrinks its steps against the chatter until it gives up). A
        slip that turns round and goes on is not judged here: that column is solved alone."""
        w = np.flatnonzero((arrival.status == SWITCHED) & among)
        if not len(w) or arrival.switch is None or arrival.modes is None:
            return {}
        index = self.p.index
        n, kinetic = index.n, self.p.index.size + len(self.kinetics.kin.reactions)
        qdd = slice(index.rates(2).start, index.rates(2).stop)
        t, y, j = arrival.t[w], arrival.y[:, w], arrival.switch[w]
        kept = arrival.modes[:, w]
        old = kept[j, np.arange(len(w))]
        h = 1e-7 * np.maximum(t, 1.0)  # a moment on: the slip speed's sign there
        drift = []
        for side in (old, -old):
            modes = kept.copy()
            modes[j, np.arange(len(w))] = side
            with np.errstate(all="ignore"):
                a = self.accelerations(at(w, t, y, modes), switches)[qdd]
                undefined = ~np.isfinite(a).all(axis=0)
                if undefined.any():  # 0/0 at the end of the slip: the direction's limit
                    a[:, undefined] = self.accelerations(
                        at(w[undefined], t[undefined], y[:, undefined], modes[:, undefined]),
                        _switches(self.kinetics, at_end=True))[qdd]
                moved = y + h * np.concatenate([y[n:], a])
                u = loud_call(switches.speeds, at(w, t + h, moved)[:kinetic],
                              switches.count)[j, np.arange(len(w))]
            drift.append(np.sign(u))
        sticks = (drift[0] == -old) & (drift[1] == old)
        assert isinstance(self.analysis, Integration)
        where = self.analysis.where
        return {int(i): SolveError(
            f"a kinetic-friction slip ends at t = {when:.6g} s, before the event, and friction "
            "then holds the contact whichever way it slips (it sticks): expected a motion that "
            "slips until its event, or the end of the slip as the event", where=where)
            for i, when in zip(w[sticks], t[sticks])}

    def accelerations(self, x: np.ndarray, switches: _Switching | None,
                      constant: ConstantMatrix | None = None) -> np.ndarray:
        """:func:`accelerations` of this motion."""
        return accelerations(self.kinetics, x, switches, constant)


def accelerations(kp, x: np.ndarray, switches: _Switching | None = None,
                  constant: ConstantMatrix | None = None) -> np.ndarray:
    """``x`` (extended states, the unknowns 0, then with ``switches`` each slip's direction)
    with every second rate and reaction solved by least squares, without the checks of
    :func:`balances` (the right-hand side of an integration), in place; NaN where the
    equations are undefined. ``constant``: the balances' matrix of these columns, where it
    reads parameters only (:func:`constant_matrix`). Called with numpy's warnings silenced."""
    count = x.shape[1]
    unknowns, k = kp.columns, len(kp.columns)
    # (a slice where they are side by side, as they are laid out: no index array made)
    cols = slice(unknowns[0], unknowns[0] + k) if k and unknowns[-1] - unknowns[0] == k - 1 \
        else list(unknowns)
    rows_ = len(kp.labels)
    if switches is not None:
        jacobian, residual, args = switches.jacobian, switches.residual, x
    else:
        jacobian, residual = kp.jacobian, kp.residual
        args = x[:len(kp.symbols)]
    if constant is None:
        A = loud_call(jacobian, args, rows_ * k).reshape(rows_, k, count)
    b = loud_call(residual, args, rows_)
    if constant is not None:
        A = constant.A
        if constant.everywhere and np.isfinite(b.sum()):
            x[cols] = constant.solver.solve(-b)
            return x
    elif np.isfinite(A.sum() + b.sum()):  # (an overflow takes the careful way below)
        x[cols] = least_squares_solution(A, -b)
        return x
    good = np.isfinite(A).all(axis=(0, 1)) & np.isfinite(b).all(axis=0)
    x[cols] = least_squares_solution(np.where(good, A, 0.0), np.where(good, -b, 0.0))
    x[:, ~good] = np.nan
    return x


@dataclass(frozen=True)
class ConstantMatrix:
    """The balances' matrix ``A`` (rows x unknowns x columns) of a motion where it reads
    parameters only (a mass matrix: :attr:`~.dynamics.KineticsPlan.constant_jacobian`),
    evaluated once for every right-hand side of its integration, and what solves with it
    (:class:`~.columns.Cramer`, its products of ``A`` alone made once); ``everywhere``: ``A``
    is finite at every column.

    >>> m = ConstantMatrix.of_matrix(np.array([[[2.0, 4.0]]]))
    >>> m.everywhere, m.of(np.array([1])).A.tolist()
    (True, [[[4.0]]])
    """

    A: np.ndarray
    solver: Cramer
    everywhere: bool

    @classmethod
    def of_matrix(cls, A: np.ndarray) -> ConstantMatrix:
        return cls(A, Cramer(A), bool(np.isfinite(A).all()))

    def of(self, cols: np.ndarray) -> ConstantMatrix:
        """The columns ``cols`` (sorted) only."""
        if len(cols) == self.A.shape[2]:
            return self
        A = self.A[:, :, cols]
        return ConstantMatrix(A, self.solver.of(cols),
                              self.everywhere or bool(np.isfinite(A).all()))


def constant_matrix(kp, x: np.ndarray, switches: _Switching | None = None
                    ) -> ConstantMatrix | None:
    """The balances' matrix (with ``switches``, theirs) at every column of ``x`` (extended
    states, as :func:`accelerations` reads them) where it reads parameters only (``None``
    where it does not): the same all along a motion."""
    if not (switches or kp).constant_jacobian:
        return None
    jacobian, args = (switches.jacobian, x) if switches else (kp.jacobian, x[:len(kp.symbols)])
    rows_, k = len(kp.labels), len(kp.columns)
    return ConstantMatrix.of_matrix(
        loud_call(jacobian, args, rows_ * k).reshape(rows_, k, x.shape[1]))


def reads_parameters_only(matrix, symbols: tuple, index) -> bool:
    """Whether ``matrix`` (sympy) reads no entry of the extended state (``symbols``, laid out
    by ``index``) but its parameters: a balances' Jacobian that is the same all along a motion
    (a mass matrix).

    >>> import sympy as sp
    >>> from mechgrade.solve.index import SymbolIndex
    >>> x, m, t, v, a = sp.symbols("x m t v a")
    >>> index = SymbolIndex(("x", "m", "t", "x'", "x''"), ("x",), ("m",), source=None)
    >>> [reads_parameters_only(sp.Matrix([e]), (x, m, t, v, a), index) for e in (-m, -m * x)]
    [True, False]
    """
    parameters = {s for i, s in enumerate(symbols[:index.size]) if index.is_parameter(i)}
    return matrix.free_symbols <= parameters


@dataclass(frozen=True)
class Balanced:
    """The extended states (state values, then reactions; one column each) with the second
    rates (or the rates just after an impact) and the reactions solved, and each column's
    error (``None`` where it has none)."""

    x: np.ndarray
    errors: FirstErrors

    @property
    def ok(self) -> np.ndarray:
        return self.errors.ok


def balances(problem: Problem, kp, X: np.ndarray, known: np.ndarray) -> Balanced:
    """The unknown second rates and reactions of every column of ``X`` (state values, those
    ``known`` given) solved from the momentum balances, each column checked: a kinetic
    friction needs slip, the givens their physical bounds, the equations must be defined,
    determine the unknowns and all hold, the solution its physical bounds, a contact must push
    and a static friction keep ``|F| <= mu N``. A column's error is the first check it fails.
    """
    n = X.shape[1]
    reactions = len(kp.kin.reactions)
    x = np.concatenate([X, np.zeros((reactions, n))])
    known = np.concatenate([known, np.zeros(reactions, bool)])
    cols = [j for j, i in enumerate(kp.columns) if not known[i]]
    for j in cols:
        x[kp.columns[j]] = 0.0
    errors = FirstErrors(n)
    for slip, speed, _ in kp.slips:
        errors.add(~(call(speed, x, 1)[0] > 1e-12), partial(_no_slip, slip))
    _physical(kp, x, errors, given=True)
    rows_ = len(kp.labels)
    A = call(kp.jacobian, x, rows_ * len(kp.columns)).reshape(rows_, len(kp.columns), n)
    A = A[:, cols]
    b = call(kp.residual, x, rows_)
    defined = np.isfinite(A).all(axis=1) & np.isfinite(b)  # rows x columns

    errors.add(~defined.all(axis=0), lambda i: undefined_balances(kp, defined[:, i]))
    ok = errors.ok
    Ab = np.where(ok, A, 0.0).transpose(2, 0, 1)
    U, s, Vt = np.linalg.svd(Ab, full_matrices=False)
    rank = rules.rank(s)

    def underdetermined(i: int) -> MechgradeError:
        a = A[:, :, i]
        null = rules.null_space(a)
        open_ = [cols[j] for j in range(len(cols)) if np.abs(null[j]).max() > rules.OPEN]
        names = [kp.name(j) for j in open_]
        involved = sorted({label.split(":")[0] for r, label in enumerate(kp.labels)
                           if any(abs(a[r, cols.index(j)]) > 1e-12 for j in open_)})
        kind = "statically indeterminate" if any(kp.columns[j] >= kp.kp.index.size
                                                 for j in open_) else "under-constrained"
        return UnderdeterminedError(
            f"the model is {kind}: the momentum balances ({', '.join(involved)}) do not "
            f"determine {', '.join(names)}; remove a redundant reaction or add a constraint",
            where=_body_where(problem, involved))

    errors.add(ok & (rank < len(cols)), underdetermined)
    ok = errors.ok
    with np.errstate(all="ignore"):
        inverse = rules.inverted(s, rows_, len(cols))
        coeff = np.einsum("nmk,mn->nk", U, -np.where(ok, b, 0.0)) * inverse
        sol = np.einsum("nkj,nk->jn", Vt, coeff)
    for j, value in zip(cols, sol):
        x[kp.columns[j]] = value
    r = call(kp.residual, x, rows_)
    scale = np.abs(call(kp.scale, x, rows_))
    holds = satisfied(r, scale, problem.consistency)

    def inconsistent(i: int) -> MechgradeError:
        k = int(np.flatnonzero(~holds[:, i])[0])
        return InconsistentError(
            f"the equations of motion cannot all hold: '{kp.labels[k]}' is off by "
            f"{r[k, i]:.4g} (terms of size {scale[k, i]:.4g}); a reaction may be missing from "
            "the loads, or a given second rate contradicts them", where=kp.wheres[k])

    errors.add(~holds.all(axis=0), inconsistent)
    _physical(kp, x, errors, given=False)
    with np.errstate(invalid="ignore"):
        for slip, _, normal in kp.slips:
            nn = call(normal, x, 1)[0]
            errors.add(~rules.pushes(nn), partial(_lost, slip, nn))
        for bound, tangential, normal, mu in kp.bounds:
            f = np.linalg.norm(call(tangential, x, 3), axis=0)
            nn = call(normal, x, 1)[0]
            m = call(mu, x, 1)[0]
            errors.add(~rules.pushes(nn), partial(_lost, bound, nn))
            errors.add(~rules.sticks(f, nn, m), partial(_slips, bound, f, nn, m))
    return Balanced(x, errors)


def undefined_balances(kp, defined: np.ndarray) -> SolveError:
    """The error of momentum balances undefined at an instant (``defined``: which of the rows
    of ``kp``'s are), naming the first that is not.

    >>> from types import SimpleNamespace
    >>> kp = SimpleNamespace(labels=["body B: x", "body B: y"], wheres=[None, None])
    >>> print(undefined_balances(kp, np.array([True, False])))
    the equations of motion are undefined at this instant (a division by zero in 'body B: y')
    """
    bad = int(np.flatnonzero(~defined)[0])
    return SolveError(f"the equations of motion are undefined at this instant (a division by "
                      f"zero in '{kp.labels[bad]}')", where=kp.wheres[bad])


def _no_slip(slip, _: int) -> SolveError:
    return SolveError(f"kinetic friction '{slip.name}' needs the contact at {slip.point} to "
                      "slip, but its slip velocity is zero at this instant; use 'kind: static'",
                      where=slip.where)


def _lost(contact, normal: np.ndarray, i: int) -> SolveError:
    return SolveError(f"contact lost at {contact.point}: the normal force would be "
                      f"{normal[i]:.4g} N (pulling)", where=contact.where)


def _slips(bound, friction: np.ndarray, normal: np.ndarray, mu: np.ndarray,
           i: int) -> SolveError:
    f, n = friction[i], normal[i]
    needed = f / n if n > 0 else np.inf
    return SolveError(f"the {bound.body} slips at {bound.point}: sticking needs mu >= "
                      f"{needed:.4g} (friction {f:.4g} N against a normal force of {n:.4g} N), "
                      f"but mu = {mu[i]:.4g}", where=bound.where)


def _physical(kp, x: np.ndarray, errors: FirstErrors, *, given: bool) -> None:
    """The physical bounds (:mod:`mechgrade.mechanics.loads`) at every column: those of the
    givens (a mass, mu, e) or those of the solution (a contact pushes, a string pulls)."""
    for bound, f in kp.physical:
        if bound.given == given:
            values = call(f, x, 1)[0]
            errors.add(~np.array([bound.holds(v) for v in values], dtype=bool),
                       partial(_unphysical, bound, values))


def _unphysical(bound, values: np.ndarray, i: int) -> SolveError:
    return SolveError(bound.message(float(values[i])), where=bound.where)


def _body_where(problem: Problem, involved) -> Location:
    for b in dynamics_of(problem).bodies:
        if involved and involved[0] == f"body {b.name}":
            return b.where
    return Location()


@dataclass(frozen=True)
class _Switching:
    """The kinetics with each ``|u|`` and ``sign(u)`` read with a direction given beside the
    state (one per ``u``, the *mode*: ``|u|`` as ``mode * u``): the equations of the motion
    before a slip ends, continued smoothly past it. ``speeds`` gives every ``u``."""

    speeds: Callable
    residual: Callable
    jacobian: Callable
    count: int
    constant_jacobian: bool  # it reads parameters only (no mode): the same all along


def gathered(e, u):
    """``e`` (a sympy expression) as ``rest + over * u/|u|``: its terms over ``|u|`` (a kinetic
    friction's direction ``u/|u|``, which the balances write expanded) summed and divided by
    ``u``; ``over`` is ``None`` where no term is over ``|u|``. Written so, the direction keeps
    its digits where the slip ``u`` is small beside the speeds it is the difference of.

    >>> import sympy as sp
    >>> a, b, N = sp.symbols("a b N")
    >>> gathered(N*a/sp.Abs(a - b) - N*b/sp.Abs(a - b) + 1, a - b)
    (1, N)
    """
    import sympy as sp

    parts = sp.collect(e, 1 / sp.Abs(u), evaluate=False) if e.is_Add else {}
    over = parts.pop(1 / sp.Abs(u), None)
    if over is None:
        return e, None
    return sp.Add(*(k * v for k, v in parts.items())), sp.cancel(over / u)


@lru_cache(maxsize=64)
def _switches(kp, at_end: bool = False) -> _Switching | None:
    """The kinetics of ``kp`` with their switches read as :class:`_Switching` says; ``None``
    when nothing switches. ``at_end``: with the terms over each ``|u|`` gathered and divided
    by ``u`` first, so that a direction ``u/|u|`` written as a sum (``N mu (R psi' +
    xb')/|u|`` expanded) is defined where its slip ends, ``u = 0`` (where a switch is
    located); the integration keeps the terms as the balances write them (its values are
    those of the model's own equations)."""
    import sympy as sp

    exprs = [e.expr for e in (*kp.kin.balances, *kp.kin.constraints)]
    speeds: list = []
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, (sp.Abs, sp.sign)) and node.args[0] not in speeds:
                speeds.append(node.args[0])
    if not speeds:
        return None
    modes = sp.symbols(f"_mode0:{len(speeds)}")
    table = dict(zip(speeds, modes))

    def kept(e):
        for u, mode in table.items() if at_end else ():
            rest, over = gathered(e, u)
            if over is not None:
                e = rest + over / mode
        e = e.replace(lambda a: isinstance(a, sp.Abs) and a.args[0] in table,
                      lambda a: table[a.args[0]] * a.args[0])
        return e.replace(lambda a: isinstance(a, sp.sign) and a.args[0] in table,
                         lambda a: table[a.args[0]])

    matrix = sp.Matrix([kept(e) for e in exprs])
    unknowns = [kp.symbols[i] for i in kp.columns]
    symbols = (*kp.symbols, *modes)
    jacobian = matrix.jacobian(unknowns)
    return _Switching(
        speeds=sp.lambdify(kp.symbols, speeds, modules="numpy", cse=True),
        residual=sp.lambdify(symbols, matrix, modules="numpy", cse=True),
        jacobian=sp.lambdify(symbols, jacobian, modules="numpy", cse=True),
        count=len(speeds),
        constant_jacobian=reads_parameters_only(jacobian, kp.symbols, kp.kp.index))


@lru_cache(maxsize=64)
def _motion(problem: Problem, kinetics) -> Motion:
    return Motion(problem, kinetics)


def integrated_columns(problem: Problem, kinetics, X: np.ndarray
                       ) -> list[tuple[np.ndarray, np.ndarray] | MechgradeError | None] | None:
    """Instants of an integrated motion (each column of ``X``: one's givens placed in the
    state) by the integrator over columns, as a class's variants are integrated: for each,
    the extended state at the event (the accelerations and reactions their limits just
    before it) and just before it; or the error it raises (the event never happens, a slip
    sticks before it); or ``None`` where that integrator does not vouch for it (one column
    integrated alone, :func:`~.phases.reach`, then says why). ``None`` for a motion that is not integrated."""
    motion = _motion(problem, kinetics)
    if not isinstance(motion.analysis, Integration):
        return None
    out, ok, never, stuck = motion.integrated(X.copy())
    half = out.shape[0] // 2  # the states at the event, and those just before it under them
    return [event_never_happens(motion.analysis) if never[c] else stuck[c] if c in stuck
            else (out[:half, c], out[half:, c]) if ok[c] else None
            for c in range(X.shape[1])]
