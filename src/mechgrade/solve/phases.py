"""A motion integrated in phases: a contact slips (kinetic friction) until its slip ends, then
grips (a ball skids, then rolls), and any instant of it — the event ``until:``, an objective's
own time, coordinate or rate, or the first instant where its ``when:`` equation holds.

The gripping phase is the same problem with that friction static along its ``then:``
direction and the contact's velocity along it held at zero (a velocity constraint): the
momentum balances then give the friction the grip needs, which must stay within mu_s N for the
rest of the motion (a contact that would slip again is refused, where it would). Every phase
is integrated over columns (:mod:`.batch_motion`: DOP853, rtol 1e-11, its roots refined on
the dense output); of events that happen in the same step, the earliest is the instant.

A class of variants is reached together (:func:`reach_columns`): each phase's columns in one
integration over columns, each column switching phase at its own end of the slip and stopping
at its own instant (a class's groups of objectives side by side: one pass of each phase), a
motion without phases too (its one phase). One solve's event is a class of one; one solve's
own instant, ``when:`` or phased motion, and a column a class does not vouch for, is one
column solved alone (:func:`reach`), which raises where it fails.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Callable

import numpy as np
import sympy as sp

from ..errors import Location, MechgradeError, SolveError
from ..expressions.syntax import parse, to_text
from ..spec.dynamics import (GROUND, Cylinder, Disk, Integration, KineticFriction, Ring,
                             Shell, Sphere, StaticFriction, dynamics_of)
from ..spec.language import FUNCTIONS
from ..spec.model import Constraint, ConstraintLevel, Expr, Problem
from . import rules
from .analysis import analysis_of, analysis_plan, start_columns
from .batch_motion import FIRED, NEVER, SWITCHED, Arrival, integrate_to_events
from .columns import loud_call, quiet
from .generated import lambdified
from .events import (ATOL, EVERY_STEP, MAX_CALLS, RTOL, at_start, event_never_happens,
                     event_stays, instant_missed, leaving, not_integrated)
from .motion import Balanced, _switches, after_event, at_event, balances, constant_matrix
from .motion import accelerations as columns_accelerations

def gripping(problem: Problem) -> KineticFriction | None:
    """The kinetic friction that grips once its slip ends (``then:``), if any."""
    d = problem.dynamics
    if d is None:
        return None
    return next((f for f in d.friction if isinstance(f, KineticFriction) and f.then is not None),
                None)


def gripping_word(problem: Problem) -> str:
    """What a textbook calls the phase once the slip ends: a round body (disk, ring, cylinder,
    sphere, shell) at its contact "rolling", anything else (a block on a belt) "sticking".

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> gripping_word(load_problem(shipped_dir("problems") / "bowling_ball_skids_then_rolls.yaml"))
    'rolling'
    """
    f = gripping(problem)
    assert f is not None, "only a contact that grips has a gripping phase"
    d = problem.dynamics
    assert d is not None
    body = next(b for b in d.bodies if b.name == f.on)
    round_ = (Ring, Disk, Cylinder, Sphere, Shell)
    return "rolling" if any(isinstance(part.shape, round_) for part in body.parts) \
        else "sticking"


def grip_constraint(problem: Problem) -> str:
    """The name of the constraint the gripping phase adds: its contact does not slip."""
    f = gripping(problem)
    assert f is not None, "only a contact that grips has a gripping phase"
    return f"{f.name}_grips"


@lru_cache(maxsize=64)
def gripping_phase(problem: Problem) -> Problem:
    """``problem`` once its slip has ended: the friction static along its ``then:`` direction,
    and the velocity of the body's point at the contact along it zero.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = gripping_phase(load_problem(shipped_dir("problems") / "bowling_ball_skids_then_rolls.yaml"))
    >>> p.constraints[-1].lhs.text, type(p.dynamics.friction[0]).__name__
    ('dot(vel(coincident(C, B), N), A.x)', 'StaticFriction')
    """
    f = gripping(problem)
    assert f is not None and f.then is not None, "only a contact that grips has this phase"
    d = dynamics_of(problem)
    body = d.body(f.on)
    point = f.at if body.frame is None else f"coincident({f.at}, {body.frame})"
    text = f"dot(vel({point}, {problem.inertial_frame}), {to_text(f.then.direction.node)})"
    grip = Constraint(grip_constraint(problem), ConstraintLevel.VELOCITY,
                      Expr(text, parse(text, functions=FUNCTIONS), f.then.where),
                      Expr("0", parse("0"), f.then.where), f.then.where)
    static = StaticFriction(f.name, f.on, f.at, f.normal, f.then.mu, (f.then.direction,),
                            f.where, GROUND)
    friction = tuple(static if x is f else x for x in d.friction)
    return replace(problem, constraints=(*problem.constraints, grip),
                   dynamics=replace(d, friction=friction))


# ---------------------------------------------------------------------------- instants


@dataclass(frozen=True)
class Until:
    """The motion's own event (``until:``)."""


@dataclass(frozen=True)
class Entry:
    """Where entry ``at`` of the state (the time, a coordinate or a rate) first takes
    ``value`` (SI); ``given`` says it as written, ``where`` locates it."""

    at: int
    value: float
    given: str
    where: Location


@dataclass(frozen=True)
class When:
    """The first instant where objective ``objective``'s ``when:`` equation holds."""

    objective: str
    text: str
    where: Location


Target = Until | Entry | When


@dataclass(frozen=True)
class PhaseInstant:
    """An instant of a phased motion: the problem whose model holds there (``phase``: the
    source, or its gripping phase), the state values, and the extended state a moment before (the limits an
    event is read with; ``None`` at an objective's own time, coordinate or rate)."""

    phase: Problem
    values: np.ndarray
    before: np.ndarray | None


def asked_when(problem: Problem, numeric) -> When | None:
    """The ``when:`` of the objectives ``numeric`` (asked at one instant), if they have one."""
    obj = next((o for o in problem.objectives if o.id in numeric and o.when is not None), None)
    if obj is None or obj.when is None:
        return None
    left, right = obj.when
    return When(obj.id, f"{left.text} = {right.text}", left.where)


def reach(problem: Problem, base: np.ndarray, target: Target, kinetics_plan: Callable,
          accelerations: Callable) -> PhaseInstant:
    """Integrate ``problem``'s motion from its start (``base``: the parameters placed in the
    state) to ``target``, through the end of the slip into the gripping phase when the
    problem has one (:func:`gripping`): one column of :func:`reach_columns`, solved alone
    (``kinetics_plan(problem)`` and ``accelerations(plan, values)`` are :mod:`.dynamics`'s,
    which imports this module). Raises, located, when the target is not reached before the
    event or the time allowed, or the contact would slip again."""
    found = reach_columns(problem, base[:, None], [target], kinetics_plan,
                          lambda kp: lambda x: accelerations(kp, x[:, 0])[:, None])
    (at,) = found.phases  # alone, every error is raised
    return PhaseInstant(at.phase, at.values[:, 0], None if at.before is None else at.before[:, 0])


def _slips_on(grip: KineticFriction, start: float, held: float) -> SolveError:
    """The error of a grip that needs more than mu_s N where the slip ends (``held``: mu_s
    N - |F| there)."""
    assert grip.then is not None
    return SolveError(f"friction '{grip.name}': the slip ends at t = {start:.6g} s, but the "
                      f"grip then needs more friction than mu_s N ({-held:.6g} N short): the "
                      "contact slips on, which this integration does not follow (a "
                      "larger mu_s, or end the motion where the slip ends: until: its slip "
                      "speed = 0)", where=grip.then.where)


def _slips_again(grip: KineticFriction, start: float, t: float) -> SolveError:
    """The error of a grip that would slip again at ``t``."""
    assert grip.then is not None
    return SolveError(f"friction '{grip.name}' grips once its slip ends at t = {start:.6g} "
                      f"s, and would slip again at t = {t:.6g} s (the friction the grip "
                      "needs reaches mu_s N there): a motion that slips again is not "
                      "supported; end the motion before it (until: t = T, T a parameter given in s)",
                      where=grip.then.where)


def _when(kp, objective: str) -> tuple[Callable, bool]:
    """The ``when:`` equation of ``objective`` as a function of the extended state, and
    whether it reads second rates or reactions (else it is read without the balances)."""
    expr = dict(kp.kin.whens)[objective]
    return _lambdified(kp, expr), bool(expr.free_symbols & {*kp.kin.k.qdd, *kp.kin.reactions})


def _said(target: Entry | When) -> str:
    """An objective's own instant as its messages quote it: its given, or its ``when:``."""
    return target.given if isinstance(target, Entry) else f"when: {target.text}"


def _missed(analysis: Integration, target: Target, until_times) -> SolveError:
    if isinstance(target, Until):
        return event_never_happens(analysis)
    return instant_missed(analysis, _said(target), target.where, until_times)


@lru_cache(maxsize=64)
def _lambdified(kp, expr):
    return lambdified(kp.symbols, expr)


def _slip(problem: Problem, kp, phase):
    """The slip velocity of the gripping contact along its direction (the constraint of the
    gripping phase's kinetics ``phase``), a function of the extended state of ``kp`` (the
    phases share their state's layout)."""
    name = grip_constraint(problem)
    equation = next(e for e in phase.kin.k.velocity if e.label == name)
    return _lambdified(kp, equation.expr)


def _margin(problem: Problem, kp):
    """mu_s N - |F| of the gripping contact, a function of the gripping phase's extended
    state (``kp``)."""
    grip = gripping(problem)
    assert grip is not None
    bound = next(b for b in kp.kin.bounds if b.name == grip.name)
    return _lambdified(kp, bound.mu * bound.normal - sp.sqrt(sum(
        (c ** 2 for c in bound.tangential), sp.Integer(0))))


# ---------------------------------------------------------------------------- over columns


@dataclass(frozen=True)
class PhaseColumns:
    """The columns of a class (``columns``) whose instant lies in ``phase`` (the source, or
    its gripping phase): their state values there (size x k) and extended states a moment
    before (``None`` at an objective's own time, coordinate or rate)."""

    phase: Problem
    columns: np.ndarray
    values: np.ndarray
    before: np.ndarray | None


@dataclass(frozen=True)
class Reaches:
    """Where each column's phased motion reaches its target (:func:`reach_columns`): the
    columns of each phase, and the error of each column whose target is not reached, as
    :func:`reach` raises it. A column in neither is not vouched for here (alone, it says
    why)."""

    phases: tuple[PhaseColumns, ...]
    errors: dict[int, MechgradeError]


@dataclass(frozen=True)
class _Run:
    """Where each column's integration ended (:class:`~.batch_motion.Arrival`'s, ``which``
    -1 where no event fired)."""

    status: np.ndarray
    t: np.ndarray
    y: np.ndarray
    before: np.ndarray
    which: np.ndarray
    switch: np.ndarray | None = None
    modes: np.ndarray | None = None


class _Columns:
    """One phase's motion over columns: ``values`` the start values (size x columns; the
    time and second rates 0), ``at(cols, t, y)`` the state values of columns ``cols``, the
    right-hand side, and event functions of the extended state. ``strict``: one column's
    balances solved as one motion alone solves them (raising where they are undefined),
    else every column's (NaN where undefined).

    A phase whose balances hold a slip's ``|u|`` is integrated with its modes
    (:mod:`.batch_motion`: each step keeps the slip's direction it starts with): the step
    across the end of the slip, the phase's event, continues the motion before it smoothly
    instead of shrinking against the jump in the friction; a slip that ends before the
    event and sticks there is refused (:meth:`stuck`)."""

    def __init__(self, problem: Problem, kp, values: np.ndarray,
                 strict: Callable[[np.ndarray], np.ndarray] | None):
        index = kp.kp.index
        self.problem, self.kp, self.values, self.strict = problem, kp, values, strict
        self.analysis = analysis_of(problem, Integration)
        self.n, self.time = index.n, index.time
        rates, seconds = index.rates(1), index.rates(2)
        self.qd, self.qdd = slice(rates.start, rates.stop), slice(seconds.start, seconds.stop)
        self.reactions = len(kp.kin.reactions)
        self.unknowns = list(kp.columns)
        self.switches = _switches(kp)
        self.careful = strict is not None  # (off while the modes' integration runs)
        values[self.time] = 0.0
        values[self.qdd] = 0.0
        self.y0 = np.concatenate([values[:self.n], values[self.qd]])
        # the right-hand side's extended states (the unknowns 0, then each slip's mode),
        # and its balances' matrix where it reads parameters only (the same all along),
        # worked out once: only the state changes from one call to the next
        modes = np.zeros((self.switches.count if self.switches else 0, values.shape[1]))
        self.full = np.concatenate([self.extended(values), modes])
        self.constant = None if strict is not None else constant_matrix(kp, self.full,
                                                                          self.switches)
        self.last: tuple = (None, self.full, self.constant)

    def among(self, cols: np.ndarray) -> tuple:
        """The right-hand side's extended states of the columns ``cols`` and their
        :attr:`constant`, gathered once for the stages of a step (they share its columns)."""
        if cols is not self.last[0]:  # (cols is sorted: all of them is all in order)
            every = len(cols) == self.full.shape[1]
            self.last = (cols, self.full if every else self.full[:, cols],
                         self.constant if every or self.constant is None
                         else self.constant.of(cols))
        return self.last

    def at(self, cols: np.ndarray, t: np.ndarray, y: np.ndarray) -> np.ndarray:
        x = self.values[:, cols]
        x[:self.n] = y[:self.n]
        x[self.qd] = y[self.n:]
        x[self.time] = t
        return x

    def extended(self, x: np.ndarray) -> np.ndarray:
        return np.concatenate([x, np.zeros((self.reactions, x.shape[1]))])

    def solve(self, x: np.ndarray, modes: np.ndarray | None = None) -> np.ndarray:
        """The extended states with the second rates and reactions solved (with each
        slip's direction ``modes``: :class:`~.motion._Switching`)."""
        if self.strict is not None and self.careful:
            return self.strict(x)
        e = self.extended(x)
        if modes is not None:
            e = np.concatenate([e, modes])
        e[self.unknowns] = 0.0
        return self._solved(e, modes is not None)

    def _solved(self, e: np.ndarray, moded: bool, constant=None) -> np.ndarray:
        """:func:`~.motion.accelerations` of the extended states ``e`` (``moded``: each
        slip's mode under them); ``constant``: their matrix, where it reads parameters only."""
        if moded and self.switches is not None:
            return columns_accelerations(self.kp, e, self.switches, constant)
        return columns_accelerations(self.kp, e, None,
                                     constant if self.switches is None else None)

    def rhs(self, cols, t, y, modes=None) -> np.ndarray:
        moded = modes is not None and len(modes) > 0
        if self.strict is not None and self.careful:
            a = self.strict(self.at(cols, t, y))
        else:
            _, full, constant = self.among(cols)
            x = full.copy()
            x[:self.n] = y[:self.n]
            x[self.qd] = y[self.n:]
            x[self.time] = t
            if moded:
                x[self.values.shape[0] + self.reactions:] = modes
            a = self._solved(x, moded, constant)
        return np.concatenate([y[self.n:], a[self.qdd]])

    def mode(self, cols, t, y) -> np.ndarray:
        """Each slip's direction."""
        assert self.switches is not None
        return np.sign(loud_call(self.switches.speeds, self.extended(self.at(cols, t, y)),
                                 self.switches.count))

    def reading(self, fn: Callable, kinetic: bool) -> Callable:
        """The event ``fn`` (of the extended state; ``kinetic``: read with the balances,
        else without them, which are undefined where a slip speed is exactly zero)."""
        def event(cols, t, y, _modes=None) -> np.ndarray:
            x = self.at(cols, t, y)
            return loud_call(fn, self.solve(x) if kinetic else self.extended(x), 1)[0]
        return event

    def until(self) -> Callable:
        """The motion's own event."""
        ap = analysis_plan(self.kp)
        assert ap.until is not None, "an integration always has its event"
        return self.reading(ap.until, ap.until_kinetic)

    def aims(self, targets: list[Target], asked: np.ndarray
             ) -> list[tuple[Callable, Entry | When]]:
        """The events of the columns' ``targets`` (``asked``: each column's value of an
        :class:`Entry`): one for every column's :class:`Entry` (each its own entry of the
        state and value), one per objective's ``when:`` (the motion's own event,
        :class:`Until`, has none), each with the first target that aims at it: a column
        aiming elsewhere reads 1 there, never zero, so that event does not fire for it (a
        class's groups in one pass)."""
        keys = [Entry if isinstance(t, Entry) else (When, t.objective)
                if isinstance(t, When) else None for t in targets]
        found = []
        for key in dict.fromkeys(k for k in keys if k is not None):
            mine = np.array([k == key for k in keys])
            target = targets[keys.index(key)]
            assert not isinstance(target, Until)
            event = self.entered(targets, asked) if isinstance(target, Entry) else \
                self.reading(*_when(self.kp, target.objective))
            found.append((event if mine.all() else _only(event, mine), target))
        return found

    def entered(self, targets: list[Target], asked: np.ndarray) -> Callable:
        """The event of the columns' :class:`Entry` targets: each column's entry of the
        state less its value ``asked``."""
        at = np.array([t.at if isinstance(t, Entry) else 0 for t in targets])

        def reached(cols, t, y, _modes=None) -> np.ndarray:
            return self.at(cols, t, y)[at[cols], np.arange(len(cols))] - asked[cols]
        return reached

    def crossing(self, event: Callable, where, what: str = "the event"
                 ) -> tuple[np.ndarray, dict[int, MechgradeError]]:
        """Each column's ``direction`` of ``event`` (``what`` names it) from the start (its
        next crossing where it holds there, :func:`~.events.leaving`): one motion alone
        raises its first error, located at ``where``; a class keeps the error of each column
        that stays in it (one whose moment is not reached has none: it does not move)."""
        direction, stays, unfinished = leaving(
            self.rhs, event, None, self.y0, self.analysis.max_time, where, what)
        if self.strict is None:
            return direction, dict(stays)
        errors = [*stays.values(), *unfinished.values()]
        if errors:
            raise errors[0]
        return direction, {}

    def _integrated(self, events: list[Callable], direction: np.ndarray, y0: np.ndarray,
                    t0: np.ndarray, modes: bool) -> Arrival:
        careful = self.careful
        self.careful = careful and not modes
        try:
            return integrate_to_events(self.rhs, events, y0, self.analysis.max_time, RTOL,
                                       ATOL, MAX_CALLS, direction=direction, t0=t0,
                                       mode=self.mode if modes else None,
                                       keep=EVERY_STEP if self.strict is not None else 12)
        finally:
            self.careful = careful

    def run(self, events: list[Callable], senses: list[np.ndarray], y0: np.ndarray,
            t0: np.ndarray) -> _Run:
        """Every column integrated from ``y0`` at ``t0`` to the first of ``events`` (each with
        its ``direction`` per column): an event with no direction that holds at the start
        fires at once, as ``solve_ivp``'s first step finds it. Alone, every step is kept and
        a stall or failure raises."""
        count = y0.shape[1]
        direction = np.array(senses, dtype=float).reshape(len(events), count)
        g = np.array([e(np.arange(count), t0, y0) for e in events]).reshape(len(events), count)
        firing = (direction == 0) & at_start(g)
        now = firing.any(axis=0)
        arrival = self._integrated(events, direction, y0, t0, self.switches is not None)
        if self.strict is not None and self.switches is not None and \
                arrival.status[0] not in (FIRED, NEVER):
            # alone, a motion its modes do not take to an event: without them, step by
            # step, which says why
            arrival = self._integrated(events, direction, y0, t0, False)
        status, t, y = arrival.status.copy(), arrival.t.copy(), arrival.y.copy()
        before = arrival.before.copy()
        which = np.full(count, -1)
        if arrival.which is not None:  # (a column that switched has no event)
            which = np.where(status == FIRED, arrival.which, -1)
        which[now] = firing.argmax(axis=0)[now]
        status[now], t[now], y[:, now], before[:, now] = FIRED, t0[now], y0[:, now], y0[:, now]
        if self.strict is not None and status[0] not in (FIRED, NEVER):
            raise not_integrated(int(status[0]), float(t[0]), self.analysis.where)
        return _Run(status, t, y, before, which, arrival.switch, arrival.modes)

    def stuck(self, run: _Run, among: np.ndarray) -> dict[int, MechgradeError]:
        """The columns ``among`` whose one slip ended before their instant
        (:data:`~.batch_motion.SWITCHED`) and where kinetic friction then holds the contact
        whichever way it is read: slipping on, friction drives the slip speed back across
        zero, turned round it drives it back too. That motion sticks, which an integration
        of these equations cannot follow (one motion alone shrinks its steps against the
        chatter until it gives up). A slip that turns round and goes on is not judged here:
        that column is solved alone."""
        switches = self.switches
        w = np.flatnonzero((run.status == SWITCHED) & among)
        if not len(w) or switches is None or run.switch is None or run.modes is None:
            return {}
        t, y, j = run.t[w], run.y[:, w], run.switch[w]
        kept = run.modes[:, w]
        old = kept[j, np.arange(len(w))]
        h = rules.moment(t)  # a moment on: the slip speed's sign there
        drift = []
        for side in (old, -old):
            modes = kept.copy()
            modes[j, np.arange(len(w))] = side
            with np.errstate(all="ignore"):
                a = self.solve(self.at(w, t, y), modes)[self.qdd]
                undefined = ~np.isfinite(a).all(axis=0)
                if undefined.any():  # 0/0 at the end of the slip: the direction's limit
                    u = np.flatnonzero(undefined)
                    e = np.concatenate([self.extended(self.at(w[u], t[u], y[:, u])),
                                        modes[:, u]])
                    e[self.unknowns] = 0.0
                    a[:, u] = columns_accelerations(self.kp, e,
                                                    _switches(self.kp, at_end=True))[self.qdd]
                moved = y + h * np.concatenate([y[self.n:], a])
                speed = loud_call(switches.speeds, self.extended(self.at(w, t + h, moved)),
                                  switches.count)[j, np.arange(len(w))]
            drift.append(np.sign(speed))
        sticks = (drift[0] == -old) & (drift[1] == old)
        return {int(i): SolveError(
            f"a kinetic-friction slip ends at t = {when:.6g} s, before the event, and friction "
            "then holds the contact whichever way it slips (it sticks): expected a motion that "
            "slips until its event, or the end of the slip as the event",
            where=self.analysis.where)
            for i, when in zip(w[sticks], t[sticks])}


def _only(event: Callable, mine: np.ndarray) -> Callable:
    """``event`` at the columns ``mine``, 1 (never zero) at the others."""
    def only(cols, t, y, _modes=None) -> np.ndarray:
        g = np.ones(len(cols))
        m = mine[cols]
        if m.any():
            g[m] = event(cols[m], np.broadcast_to(t, cols.shape)[m], y[:, m])
        return g
    return only


def reach_columns(problem: Problem, X: np.ndarray, targets: list[Target],
                  kinetics_plan: Callable, alone: Callable | None = None) -> Reaches:
    """Every column of ``X`` (each the parameters placed in the state) integrated from its
    start to its target (``targets``: one per column, of any kind: a class's groups side by
    side), through the end of its slip into the gripping phase when the problem has one
    (:func:`gripping`): each phase integrated once for every column
    (:func:`~.batch_motion.integrate_to_events`), each column switching phase at its own end
    of the slip and stopping at its own target, and each column's instant read with the
    model of its phase (see :class:`Reaches`). ``alone(kp)``: one column solved alone, its
    balances solved by it, every error raised (:func:`reach`); a class leaves a column whose
    integration stalls or fails, or whose target holds at the start, to be solved so."""
    analysis = analysis_of(problem, Integration)
    kp = kinetics_plan(problem)
    asked = np.array([t.value if isinstance(t, Entry) else np.nan for t in targets])
    errors: dict[int, MechgradeError] = {}

    def failed(c: int, error: MechgradeError) -> None:
        if alone is not None:
            raise error
        errors.setdefault(c, error)

    with quiet():
        values, unsettled = start_columns(problem, kp, analysis_plan(kp), X)
        for column, error in unsettled.items():
            failed(column, error)
        todo = np.array([c for c in range(X.shape[1]) if c not in unsettled], dtype=int)
        one = _Columns(problem, kp, values[:, todo], alone(kp) if alone else None)
        count = len(todo)
        until = one.until()
        direction, stays = one.crossing(until, analysis.where)
        for k, error in stays.items():
            failed(int(todo[k]), error)
        fine = np.ones(count, dtype=bool)
        events, senses = [], []
        # the instants first: where one and the event fire together, it is reached
        mine = [targets[c] for c in todo]
        timed = np.array([isinstance(t, Entry) and t.at == kp.kp.index.time for t in mine],
                         dtype=bool)  # t = 0 is the start itself
        for aim, target in one.aims(mine, asked[todo]):
            events.append(aim)
            if alone is not None:
                senses.append(np.zeros(count) if timed[0] else
                              one.crossing(aim, target.where, f"'{_said(target)}'")[0])
                continue
            # a column whose instant holds at the start waits for its next crossing, as
            # alone; one that stays there is refused at its own given, as alone; one whose
            # moment later is not reached is left to be solved alone, which says why
            held = ~timed & at_start(aim(np.arange(count), np.zeros(count), one.y0))
            sense, stays = one.crossing(aim, target.where) if held.any() else \
                (np.zeros(count), {})
            for k in stays:
                if held[k]:
                    failed(int(todo[k]), event_stays(mine[k].where, f"'{_said(mine[k])}'"))
            fine &= ~held | (sense != 0)
            senses.append(np.where(held, sense, 0.0))
        events.append(until)
        senses.append(direction)
        grip = gripping(problem)
        if grip is not None:
            events.append(one.reading(_slip(problem, kp, kinetics_plan(gripping_phase(problem))),
                                      False))
            senses.append(np.zeros(count))
        fine &= ~np.isin(todo, list(errors))
        run = one.run(events, senses, one.y0, np.zeros(count))
        at_until = run.which == events.index(until)
        ended = (run.status == NEVER) | (at_until & _aiming(targets, todo))
        for c in np.flatnonzero(fine & ended):
            failed(int(todo[c]), _missed(analysis, targets[todo[c]],
                                         [run.t[c]] if at_until[c] else []))
        if alone is None:  # a slip that ends before the event and sticks there
            for k, error in one.stuck(run, fine & ~_aiming(targets, todo)).items():
                failed(int(todo[k]), error)
        fired = fine & ~ended & (run.status == FIRED)
        slipped = fired & (run.which == len(events) - 1) & (grip is not None)
        phases = _arrived(problem, one, run, todo, np.flatnonzero(fired & ~slipped), targets,
                          asked)
        s = np.flatnonzero(slipped)
        if len(s):
            phases += _gripped(problem, X[:, todo[s]], todo[s], run, s, direction[s], targets,
                               asked, kinetics_plan, alone, failed)
    return Reaches(tuple(phases), errors)


def checked(at: PhaseColumns, kp) -> tuple[np.ndarray, np.ndarray | None, Balanced]:
    """The extended states of ``at``'s columns the objectives are read from (``kp``: its
    phase's kinetics) and those a moment before (``None`` at an objective's own instant),
    with the momentum balances solved and checked (:func:`~.motion.balances`): at the
    instant, or for an event just before it (the contact checks hold along the way; the
    second rates and reactions at the event are their limits there, :func:`~.motion.at_event`)."""
    known = after_event(kp.kp)
    if at.before is None:
        solved = balances(at.phase, kp, at.values, known)
        return solved.x, None, solved
    solved = balances(at.phase, kp, at.before[:kp.kp.index.size], known)
    return at_event(solved.x, at.values, kp.kp), solved.x, solved


def stacked(problem: Problem, found: Reaches, kinetics_plan: Callable, count: int
            ) -> tuple[np.ndarray, np.ndarray, dict[int, MechgradeError]]:
    """The ``count`` columns of ``found`` on a motion without phases, :func:`checked`: each
    one's extended state at its instant with the one a moment before stacked under it (the
    same twice at an objective's own instant), which are answered, and the error of each
    whose instant is not reached or fails the checks (a column in neither is not vouched
    for: alone, it says why).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve.dynamics import kinematic_problem, kinetics_plan
    >>> from mechgrade.solve.instant import instant_givens
    >>> from mechgrade.solve.numeric import solve_numeric
    >>> problem = load_problem(shipped_dir("problems") / "damped_block_first_peak.yaml")
    >>> kp = kinetics_plan(problem)
    >>> X = solve_numeric(kinematic_problem(problem), kp.kp, instant_givens(problem, None, {}),
    ...                   set()).state.values[:, None]
    >>> out, ok, errors = stacked(problem, reach_columns(problem, X, [Until()], kinetics_plan),
    ...                           kinetics_plan, 1)
    >>> ok.tolist(), errors, out.shape[0] == 2 * (kp.kp.index.size + len(kp.kin.reactions))
    ([True], {}, True)
    """
    kp = kinetics_plan(problem)
    kinetic = kp.kp.index.size + len(kp.kin.reactions)
    out = np.full((2 * kinetic, count), np.nan)
    ok = np.zeros(count, dtype=bool)
    errors = dict(found.errors)
    for at in found.phases:
        assert at.phase is problem, "a motion without phases"
        x, before, solved = checked(at, kp)
        out[:, at.columns] = np.vstack([x, x if before is None else before])
        ok[at.columns] = solved.ok
        errors.update({int(at.columns[j]): error for j in np.flatnonzero(~solved.ok)
                       if (error := solved.errors[int(j)]) is not None})
    return out, ok, errors


def _aiming(targets: list[Target], columns: np.ndarray) -> np.ndarray:
    """Which of ``columns`` aim at an instant before the motion's own event."""
    # (Python's ints index a list several times faster than numpy's)
    return np.array([not isinstance(targets[c], Until) for c in columns.tolist()], dtype=bool)


def _arrived(problem: Problem, motion: _Columns, run: _Run, todo: np.ndarray, k: np.ndarray,
             targets: list[Target], asked: np.ndarray) -> list[PhaseColumns]:
    """The instants of the columns ``k`` of ``run`` (``todo[k]`` in the class) on ``problem``'s
    motion: the state values there (an :class:`Entry`'s given where its root was found),
    else with the extended states a moment before (those are a second part)."""
    values = motion.at(k, run.t[k], run.y[:, k])
    entries = np.array([isinstance(targets[c], Entry) for c in todo[k].tolist()], dtype=bool)
    found = []
    e = np.flatnonzero(entries)
    if len(e):  # where the root was found: the given holds there
        at = [t.at for t in (targets[c] for c in todo[k[e]]) if isinstance(t, Entry)]
        values[at, e] = asked[todo[k[e]]]
        found.append(PhaseColumns(problem, todo[k[e]], values[:, e], None))
    o = k[~entries]
    if len(o):
        found.append(PhaseColumns(problem, todo[o], values[:, ~entries],
                                  motion.solve(motion.at(o, np.maximum(
                                      motion.values[motion.time, o],
                                      run.t[o] * (1 - rules.BEFORE_EVENT)), run.before[:, o]))))
    return found


def _gripped(problem: Problem, X: np.ndarray, columns: np.ndarray, slipped: _Run,
             s: np.ndarray, direction: np.ndarray, targets: list[Target], asked: np.ndarray,
             kinetics_plan: Callable, alone: Callable | None,
             failed: Callable[[int, MechgradeError], None]) -> list[PhaseColumns]:
    """The gripping phase of the columns ``columns`` of the class (``X``: their parameters
    placed), from the end of their slip (``slipped``, at its columns ``s``) to their target;
    ``direction``: that of the motion's event (see :func:`.events.leaving`). A grip
    that needs more than mu_s N where the slip ends, or that would slip again, fails."""
    phase = gripping_phase(problem)
    kp = kinetics_plan(phase)
    grip = gripping(problem)
    assert grip is not None
    values, unsettled = start_columns(phase, kp, analysis_plan(kp), X)
    for k, error in unsettled.items():
        failed(int(columns[k]), error)
    two = _Columns(phase, kp, values, alone(kp) if alone else None)
    everyone = np.arange(len(s))
    start, y0 = slipped.t[s], slipped.y[:, s]
    grips = two.reading(_margin(problem, kp), True)
    held = grips(everyone, start, y0)
    fine = held >= 0
    for c in np.flatnonzero(~fine):
        failed(int(columns[c]), _slips_on(grip, float(start[c]), float(held[c])))
    fine &= ~np.isin(everyone, list(unsettled))
    aims = [aim for aim, _ in two.aims([targets[c] for c in columns], asked[columns])]
    events = [*aims, two.until(), grips]  # the instants first, as in the slipping phase
    senses = [np.zeros(len(s))] * len(aims) + [direction, np.zeros(len(s))]
    run = two.run(events, senses, y0, start)
    again = fine & (run.status == FIRED) & (run.which == len(events) - 1)
    for c in np.flatnonzero(again):
        failed(int(columns[c]), _slips_again(grip, float(start[c]), float(run.t[c])))
    at_until = run.which == len(aims)
    ended = fine & ~again & ((run.status == NEVER) | (at_until & _aiming(targets, columns)))
    for c in np.flatnonzero(ended):
        failed(int(columns[c]), _missed(analysis_of(problem, Integration), targets[columns[c]],
                                        [run.t[c]] if at_until[c] else []))
    two.values[two.time] = start  # each column's start: a moment before is not before it
    return _arrived(phase, two, run, columns,
                    np.flatnonzero(fine & ~again & ~ended & (run.status == FIRED)), targets,
                    asked)
