"""A motion integrated in phases: a contact slips (kinetic friction) until its slip ends, then
grips (a ball skids, then rolls), and any instant of it — the event ``until:``, an objective's
own time, coordinate or rate, or the first instant where its ``when:`` equation holds.

The gripping phase is the same problem with that friction static along its ``then:``
direction and the contact's velocity along it held at zero (a velocity constraint): the
momentum balances then give the friction the grip needs, which must stay within mu_s N for the
rest of the motion (a contact that would slip again is refused, where it would). Every phase
is integrated as :mod:`.events` integrates one motion (DOP853, rtol 1e-11, its roots refined
on the dense output).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Callable

import numpy as np
import sympy as sp

from ..errors import Location, SolveError
from ..expressions.syntax import parse, to_text
from ..spec.dynamics import (GROUND, Cylinder, Disk, Integration, KineticFriction, Ring,
                             Shell, Sphere, StaticFriction, dynamics_of)
from ..spec.language import FUNCTIONS
from ..spec.model import Constraint, Expr, Problem
from . import rules
from .analysis import analysis_of, extended, value_at
from .events import (ATOL, RTOL, _next_crossing, _ScalarMotion, event_never_happens,
                     instant_missed)

SAME_INSTANT = 1e-9
"""Two events this close (a part of the time, at least 1 s) are one instant: an objective asked
``when`` the slip ends is read at the end of the slipping phase."""


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
    from scipy.integrate import solve_ivp

    analysis = analysis_of(problem, Integration)
    kp = kinetics_plan(problem)

    def solve_in(plan):
        return lambda values: accelerations(plan, values)

    m = _ScalarMotion(problem, kp, base, solve_in(kp))
    aim = _aimed(target, kp, m, solve_in(kp))
    if isinstance(target, When) or (isinstance(target, Entry) and \
            target.at != kp.kp.index.time):  # t = 0 is the start itself
        assert aim is not None
        _next_crossing(aim, m.rhs, m.y0, analysis.max_time, target.where)
    grip = gripping(problem)
    events = [m.until] + ([aim] if aim is not None else [])
    if grip is not None:
        slip = _slip(problem, kp, kinetics_plan(gripping_phase(problem)))

        def slipping(t, y):
            return value_at(slip, extended(kp, m.at(t, y)))

        events.append(slipping)
    for e in events:
        e.terminal = True
    result = solve_ivp(m.rhs, (0.0, analysis.max_time), m.y0, method="DOP853", rtol=RTOL,
                       atol=ATOL, events=events, dense_output=True)
    if result.status < 0:
        raise SolveError(f"the integration failed: {result.message}", where=analysis.where)
    first = _first(result, len(events), aim is not None)
    if first is None or (first == 0 and aim is not None):
        raise _missed(analysis, target, result.t_events[0])
    t, y = float(result.t_events[first][0]), result.y_events[first][0]
    if grip is None or first < len(events) - 1:
        return _instant(problem, m, result.sol, solve_in(kp), t, y, target, 0.0)
    return _rolling(problem, base, target, t, y, m.until, kinetics_plan(gripping_phase(problem)),
                    accelerations)


def _rolling(problem: Problem, base: np.ndarray, target: Target, start: float,
             y0: np.ndarray, until, kp, accelerations: Callable) -> PhaseInstant:
    """The gripping phase (its kinetics ``kp``) from the end of the slip (``start``, state
    ``y0``) to ``target``."""
    from scipy.integrate import solve_ivp

    analysis = analysis_of(problem, Integration)
    phase = gripping_phase(problem)

    def solve(values):
        return accelerations(kp, values)

    m = _ScalarMotion(phase, kp, base, solve, leave=False)
    if hasattr(until, "direction"):  # the event held at t = 0: its next crossing
        m.until.direction = until.direction  # type: ignore[attr-defined]
    aim = _aimed(target, kp, m, solve)
    margin = _margin(problem, kp)

    def grips(t, y):
        return value_at(margin, solve(m.at(t, y)))

    grip = gripping(problem)
    assert grip is not None and grip.then is not None
    held = grips(start, y0)
    if not held >= 0:
        raise SolveError(f"friction '{grip.name}': the slip ends at t = {start:.6g} s, but the "
                         f"grip then needs more friction than mu_s N ({-held:.6g} N short): the "
                         "contact slips on, which this integration does not follow (a "
                         "larger mu_s, or end the motion where the slip ends: until: its slip "
                         "speed = 0)", where=grip.then.where)
    events = [m.until] + ([aim] if aim is not None else []) + [grips]
    for e in events:
        e.terminal = True
    result = solve_ivp(m.rhs, (start, analysis.max_time), y0, method="DOP853", rtol=RTOL,
                       atol=ATOL, events=events, dense_output=True)
    if result.status < 0:
        raise SolveError(f"the integration failed: {result.message}", where=analysis.where)
    first = _first(result, len(events), aim is not None)
    if first == len(events) - 1:
        when = float(result.t_events[first][0])
        raise SolveError(f"friction '{grip.name}' grips once its slip ends at t = {start:.6g} "
                         f"s, and would slip again at t = {when:.6g} s (the friction the grip "
                         "needs reaches mu_s N there): a motion that slips again is not "
                         "supported; end the motion before it (until: t = T, T a parameter given in s)",
                         where=grip.then.where)
    if first is None or (first == 0 and aim is not None):
        raise _missed(analysis, target, result.t_events[0])
    t, y = float(result.t_events[first][0]), result.y_events[first][0]
    return _instant(phase, m, result.sol, solve, t, y, target, start)


def _instant(problem: Problem, m: _ScalarMotion, sol, solve, t: float, y: np.ndarray,
             target: Target, start: float) -> PhaseInstant:
    values = m.at(t, y)
    if isinstance(target, Entry):
        values[target.at] = target.value  # where the root was found: the given holds there
        return PhaseInstant(problem, values, None)
    earlier = max(start, t * (1 - rules.BEFORE_EVENT))
    return PhaseInstant(problem, values, solve(m.at(earlier, sol(earlier))))


def _first(result, count: int, aimed: bool) -> int | None:
    """The event that happened first (``None``: none did); the target before the others at
    the same instant, then the motion's event."""
    times = [(float(ts[0]), i) for i, ts in enumerate(result.t_events) if len(ts)]
    if not times:
        return None
    t0 = min(t for t, _ in times)
    close = [i for t, i in times if t - t0 <= SAME_INSTANT * max(1.0, abs(t0))]
    order = ([1] if aimed else []) + [0] + list(range(2 if aimed else 1, count))
    return next(i for i in order if i in close)


def _aimed(target: Target, kp, m: _ScalarMotion, solve):
    """The event function of ``target`` on the motion ``m`` (``None``: the motion's own)."""
    if isinstance(target, Until):
        return None
    if isinstance(target, Entry):
        def reached(t, y):
            return m.at(t, y)[target.at] - target.value
        return reached
    equation = _lambdified(kp, dict(kp.kin.whens)[target.objective])

    def holds(t, y):
        return value_at(equation, solve(m.at(t, y)))
    return holds


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
