"""A motion integrated in phases: a contact slips (kinetic friction) until its slip ends, then
grips (a ball skids, then rolls), and any instant of it — the event ``until:``, an objective's
own time, coordinate or rate, or the first instant where its ``when:`` equation holds.

The gripping phase is the same problem with that friction static along its ``then:``
direction and the contact's velocity along it held at zero (a velocity constraint): the
momentum balances then give the friction the grip needs, which must stay within mu_s N for the
rest of the motion (a contact that would slip again is refused, where it would). Every phase
is integrated as :mod:`.events` integrates one motion (DOP853, rtol 1e-11, its roots refined
on the dense output); of events that happen in the same step, the earliest is the instant.
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
from ..spec.model import Constraint, Expr, Problem
from . import rules
from .analysis import analysis_of, analysis_plan, extended, start_columns, value_at
from .batch_motion import FIRED, NEVER, integrate_to_events
from .columns import loud_call, quiet
from .events import (ATOL, MAX_CALLS, RTOL, Run, _ScalarMotion, event_never_happens,
                     instant_missed, next_crossing)
from .motion import _motion
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
    grip = Constraint(grip_constraint(problem), "velocity",
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
    problem has one (:func:`gripping`). ``kinetics_plan(problem)`` and
    ``accelerations(plan, values)`` are :mod:`.dynamics`'s (which imports this module).
    Raises, located, when the target is not reached before the event or the time allowed,
    or the contact would slip again."""
    analysis = analysis_of(problem, Integration)
    kp = kinetics_plan(problem)

    def solve_in(plan):
        return lambda values: accelerations(plan, values)

    m = _ScalarMotion(problem, kp, base, solve_in(kp))
    aim = _aimed(target, kp, m, solve_in(kp))
    events, directions = [m.until], [m.direction]
    if aim is not None:
        assert not isinstance(target, Until), "the motion's own event is aimed at as until"
        events.append(aim)
        directions.append(0.0 if isinstance(target, Entry) and target.at == kp.kp.index.time
                          else next_crossing(aim, m.rhs, m.y0, analysis.max_time,
                                             target.where))  # t = 0 is the start itself
    grip = gripping(problem)
    if grip is not None:
        slip = _slip(problem, kp, kinetics_plan(gripping_phase(problem)))

        def slipping(t, y):
            return value_at(slip, extended(kp, m.at(t, y)))

        events.append(slipping)
        directions.append(0.0)
    run = m.run(events, directions)
    if run.which is None or (run.which == 0 and aim is not None):
        raise _missed(analysis, target, [run.t] if run.which == 0 else [])
    if grip is None or run.which < len(events) - 1:
        return _instant(problem, m, solve_in(kp), run, target)
    return _rolling(problem, base, target, run, m.direction,
                    kinetics_plan(gripping_phase(problem)), accelerations)


def _rolling(problem: Problem, base: np.ndarray, target: Target, slipped: Run,
             direction: float, kp, accelerations: Callable) -> PhaseInstant:
    """The gripping phase (its kinetics ``kp``) from the end of the slip (``slipped``) to
    ``target``; ``direction``: that of the motion's event (see :func:`.events.next_crossing`)."""
    analysis = analysis_of(problem, Integration)
    phase = gripping_phase(problem)
    start = slipped.t

    def solve(values):
        return accelerations(kp, values)

    m = _ScalarMotion(phase, kp, base, solve, leave=False)
    aim = _aimed(target, kp, m, solve)
    margin = _margin(problem, kp)

    def grips(t, y):
        return value_at(margin, solve(m.at(t, y)))

    grip = gripping(problem)
    assert grip is not None and grip.then is not None
    held = grips(start, slipped.y)
    if not held >= 0:
        raise _slips_on(grip, start, held)
    events = [m.until] + ([aim] if aim is not None else []) + [grips]
    run = m.run(events, [direction] + [0.0] * (len(events) - 1), start, slipped.y)
    if run.which == len(events) - 1:
        raise _slips_again(grip, start, run.t)
    if run.which is None or (run.which == 0 and aim is not None):
        raise _missed(analysis, target, [run.t] if run.which == 0 else [])
    return _instant(phase, m, solve, run, target)


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


def _instant(problem: Problem, m: _ScalarMotion, solve, run: Run, target: Target
             ) -> PhaseInstant:
    values = m.at(run.t, run.y)
    if isinstance(target, Entry):
        values[target.at] = target.value  # where the root was found: the given holds there
        return PhaseInstant(problem, values, None)
    return PhaseInstant(problem, values, solve(m.at(run.earlier, run.before)))


def _aimed(target: Target, kp, m: _ScalarMotion, solve):
    """The event function of ``target`` on the motion ``m`` (``None``: the motion's own)."""
    if isinstance(target, Until):
        return None
    if isinstance(target, Entry):
        def reached(t, y):
            return m.at(t, y)[target.at] - target.value
        return reached
    equation, kinetic = _when(kp, target.objective)

    def holds(t, y):
        # an equation of the state alone is read without the balances, as the motion's own
        # event is (they are undefined where a slip speed is exactly zero: at its root)
        return value_at(equation, solve(m.at(t, y)) if kinetic else extended(kp, m.at(t, y)))
    return holds


def _when(kp, objective: str) -> tuple[Callable, bool]:
    """The ``when:`` equation of ``objective`` as a function of the extended state, and
    whether it reads second rates or reactions (else it is read without the balances)."""
    expr = dict(kp.kin.whens)[objective]
    return _lambdified(kp, expr), bool(expr.free_symbols & {*kp.kin.k.qdd, *kp.kin.reactions})


def _missed(analysis: Integration, target: Target, until_times) -> SolveError:
    if isinstance(target, Until):
        return event_never_happens(analysis)
    if isinstance(target, Entry):
        return instant_missed(analysis, target.given, target.where, until_times)
    return instant_missed(analysis, f"when: {target.text}", target.where, until_times)


@lru_cache(maxsize=64)
def _lambdified(kp, expr):
    return sp.lambdify(kp.symbols, expr, modules="numpy", cse=True)


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


class _Columns:
    """One phase's motion over columns (:class:`_ScalarMotion`'s, each column its own):
    ``values`` the start values (size x columns), ``at(cols, t, y)`` the state values of
    columns ``cols``, the right-hand side, and event functions of the extended state."""

    def __init__(self, kp, values: np.ndarray):
        index = kp.kp.index
        self.kp, self.values = kp, values
        self.n, self.time = index.n, index.time
        rates, seconds = index.rates(1), index.rates(2)
        self.qd, self.qdd = slice(rates.start, rates.stop), slice(seconds.start, seconds.stop)
        self.reactions = len(kp.kin.reactions)

    def at(self, cols: np.ndarray, t: np.ndarray, y: np.ndarray) -> np.ndarray:
        x = self.values[:, cols]
        x[:self.n] = y[:self.n]
        x[self.qd] = y[self.n:]
        x[self.time] = t
        return x

    def extended(self, x: np.ndarray) -> np.ndarray:
        return np.concatenate([x, np.zeros((self.reactions, x.shape[1]))])

    def solve(self, x: np.ndarray) -> np.ndarray:
        """The extended states with the second rates and reactions solved (as
        :func:`~.dynamics.accelerations` for each column; NaN where undefined)."""
        e = self.extended(x)
        e[list(self.kp.columns)] = 0.0
        return columns_accelerations(self.kp, e)

    def rhs(self, cols, t, y, _modes=None) -> np.ndarray:
        return np.concatenate([y[self.n:], self.solve(self.at(cols, t, y))[self.qdd]])

    def reading(self, fn: Callable, kinetic: bool) -> Callable:
        """The event ``fn`` (of the extended state; ``kinetic``: read with the balances)."""
        def event(cols, t, y, _modes=None) -> np.ndarray:
            x = self.at(cols, t, y)
            return loud_call(fn, self.solve(x) if kinetic else self.extended(x), 1)[0]
        return event

    def aimed(self, target: Target, asked: np.ndarray) -> Callable | None:
        """The event of ``target`` (:func:`_aimed`; ``asked``: each column's value of an
        :class:`Entry`)."""
        if isinstance(target, Until):
            return None
        if isinstance(target, Entry):
            at = target.at

            def reached(cols, t, y, _modes=None) -> np.ndarray:
                return self.at(cols, t, y)[at] - asked[cols]
            return reached
        return self.reading(*_when(self.kp, target.objective))


def reach_columns(problem: Problem, X: np.ndarray, targets: list[Target],
                  kinetics_plan: Callable) -> Reaches:
    """:func:`reach` for every column of ``X`` (each the parameters placed in the state) to
    its target (``targets``: one per column, all of one kind, an :class:`Entry` at the same
    entry), the phases integrated together (:func:`~.batch_motion.integrate_to_events`),
    each column switching phase at its own end of the slip; each column's instant is that
    :func:`reach` finds for it alone, or its error (see :class:`Reaches`)."""
    analysis = analysis_of(problem, Integration)
    kp = kinetics_plan(problem)
    count = X.shape[1]
    target = targets[0]
    asked = np.array([t.value if isinstance(t, Entry) else np.nan for t in targets])
    errors: dict[int, MechgradeError] = {}
    phases: list[PhaseColumns] = []
    with quiet():
        values, unsettled = start_columns(problem, kp, analysis_plan(kp), X)
        values[kp.kp.index.time] = 0.0
        values[list(kp.kp.index.rates(2))] = 0.0
        errors.update(unsettled)
        todo = np.array([c for c in range(count) if c not in unsettled], dtype=int)
        one = _Columns(kp, values[:, todo])
        y0 = np.concatenate([one.values[:one.n], one.values[one.qd]])
        everyone = np.arange(len(todo))
        ap = analysis_plan(kp)
        assert ap.until is not None, "an integration always has its event"
        until = one.reading(ap.until, ap.until_kinetic)
        direction, stays = _motion(problem, kp)._leaving(one.rhs, until, None, y0)
        errors.update({int(todo[c]): e for c, e in stays.items()})
        aim = one.aimed(target, asked[todo])
        events, senses = [until], [direction]
        if aim is not None:
            # an aim that holds at the start: alone (its next crossing, or its error there)
            fine = aim(everyone, np.zeros(len(todo)), y0) != 0
            events.append(aim)
            senses.append(np.zeros(len(todo)))
        else:
            fine = np.ones(len(todo), dtype=bool)
        grip = gripping(problem)
        if grip is not None:
            phase = gripping_phase(problem)
            kp2 = kinetics_plan(phase)
            events.append(one.reading(_slip(problem, kp, kp2), False))
            senses.append(np.zeros(len(todo)))
        fine &= ~np.isin(todo, list(errors))
        run = integrate_to_events(one.rhs, events, y0, analysis.max_time, RTOL, ATOL,
                                  MAX_CALLS, direction=np.array(senses))
        which = np.where(run.status == FIRED, run.which if run.which is not None else -1, -1)
        ended = (run.status == NEVER) | ((which == 0) & (aim is not None))
        for c in np.flatnonzero(fine & ended):
            errors[int(todo[c])] = _missed(analysis, targets[todo[c]],
                                           [run.t[c]] if which[c] == 0 else [])
        slipped = fine & ~ended & (which == len(events) - 1) & (grip is not None)
        here = fine & ~ended & (run.status == FIRED) & ~slipped
        phases.append(_arrived(problem, one, run, todo, np.flatnonzero(here), target,
                               asked))
        s = np.flatnonzero(slipped)
        if len(s):
            assert grip is not None
            phases.append(_gripped(problem, X[:, todo[s]], todo[s], run, s, direction[s],
                                   targets, asked, kinetics_plan, errors))
    return Reaches(tuple(p for p in phases if len(p.columns)), errors)


def _arrived(problem: Problem, motion: _Columns, run, todo: np.ndarray, k: np.ndarray,
             target: Target, asked: np.ndarray) -> PhaseColumns:
    """The instants of the columns ``k`` of ``run`` (``todo[k]`` in the class) on ``problem``'s
    motion (:func:`_instant` for each)."""
    values = motion.at(k, run.t[k], run.y[:, k])
    if isinstance(target, Entry):
        values[target.at] = asked[todo[k]]  # where the root was found: the given holds there
        return PhaseColumns(problem, todo[k], values, None)
    earlier = np.maximum(motion.values[motion.time, k], run.t[k] * (1 - rules.BEFORE_EVENT))
    return PhaseColumns(problem, todo[k], values,
                        motion.solve(motion.at(k, earlier, run.before[:, k])))


def _gripped(problem: Problem, X: np.ndarray, columns: np.ndarray, slipped, s: np.ndarray,
             direction: np.ndarray, targets: list[Target], asked: np.ndarray,
             kinetics_plan: Callable, errors: dict[int, MechgradeError]) -> PhaseColumns:
    """:func:`_rolling` for the columns ``columns`` of the class (``X``: their parameters
    placed), whose slip ended as run ``slipped`` found it (at its columns ``s``): their
    errors into ``errors``, the instants of the others reached."""
    phase = gripping_phase(problem)
    kp = kinetics_plan(phase)
    grip = gripping(problem)
    assert grip is not None
    values, _ = start_columns(phase, kp, analysis_plan(kp), X)
    values[kp.kp.index.time] = 0.0
    values[list(kp.kp.index.rates(2))] = 0.0
    two = _Columns(kp, values)
    everyone = np.arange(len(s))
    start, y0 = slipped.t[s], slipped.y[:, s]
    grips = two.reading(_margin(problem, kp), True)
    held = grips(everyone, start, y0)
    fine = held >= 0
    for c in np.flatnonzero(~fine):
        errors[int(columns[c])] = _slips_on(grip, float(start[c]), float(held[c]))
    ap = analysis_plan(kp)
    assert ap.until is not None
    target = targets[columns[0]]
    aim = two.aimed(target, asked[columns])
    events = [two.reading(ap.until, ap.until_kinetic)] + ([aim] if aim is not None else []) \
        + [grips]
    senses = [direction] + [np.zeros(len(s))] * (len(events) - 1)
    analysis = analysis_of(problem, Integration)
    run = integrate_to_events(two.rhs, events, y0, analysis.max_time, RTOL, ATOL, MAX_CALLS,
                              direction=np.array(senses), t0=start)
    which = np.where(run.status == FIRED, run.which if run.which is not None else -1, -1)
    again = fine & (which == len(events) - 1)
    for c in np.flatnonzero(again):
        errors[int(columns[c])] = _slips_again(grip, float(start[c]), float(run.t[c]))
    ended = fine & ~again & ((run.status == NEVER) | ((which == 0) & (aim is not None)))
    for c in np.flatnonzero(ended):
        errors[int(columns[c])] = _missed(analysis, targets[columns[c]],
                                          [run.t[c]] if which[c] == 0 else [])
    here = fine & ~again & ~ended & (run.status == FIRED)
    two.values[two.time] = start  # each column's own start: a moment before it is not before
    return _arrived(phase, two, run, columns, np.flatnonzero(here), target, asked)
