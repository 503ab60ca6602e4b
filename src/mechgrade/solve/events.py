"""How the instant of a dynamics problem is reached when its rates are not given: by the
work–energy balance from a start state, or by integrating the motion to an event.

Work–energy: the givens fix the configuration; the rates are ``lambda * u`` along the one free
direction ``u`` of the velocity constraints, with ``T(lambda u) + V = E(start)``. Every load
must be conservative and every reaction workless at the instant (checked), and the spec says
the sign of a rate (``sense``).

Integration: the coordinates and rates from ``from:`` at t = 0, integrated with
``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-11) until the event equation first holds (root
refined on the dense output); the objectives are read at the event, with ``t`` its time. The
accelerations and reactions there are the limits just before the event (a kinetic-friction
force has no direction once the slip has ended).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Callable, TypeVar

import numpy as np
import sympy as sp

# scipy is imported by the functions that use it: it takes longer to import than a whole
# `mechgrade check` of most problems, which never needs it.

from ..errors import SolveError
from ..spec.dynamics import Integration, WorkEnergy, dynamics_of
from ..spec.model import Objective, Problem
from ..tolerance import within_each
from ..units import si_factor
from .levels import State, nullspace

RTOL, ATOL = 1e-11, 1e-12
MAX_CALLS = 20_000  # right-hand-side evaluations before an integration is judged stalled


@dataclass(frozen=True)
class AnalysisPlan:
    """The lambdified energy, start values, event and reaction powers (functions of the
    extended state: state values, then reactions)."""

    energy: Callable
    start: tuple[tuple[int, Callable], ...]
    until: Callable | None
    workless: tuple[tuple[str, Callable], ...]
    until_kinetic: bool = True  # the event reads second rates or reactions


def analysis_plan(kp) -> AnalysisPlan:
    return _analysis_plan(kp)


@lru_cache(maxsize=64)
def _analysis_plan(kp) -> AnalysisPlan:
    symbols = kp.symbols
    kin = kp.kin
    position = {s: i for i, s in enumerate(symbols)}

    def f(expr):
        return sp.lambdify(symbols, expr, modules="numpy", cse=True)

    return AnalysisPlan(
        energy=f(kin.energy),
        start=tuple((position[s], f(value)) for s, value in kin.start),
        until=f(kin.until) if kin.until is not None else None,
        workless=tuple((label, f(expr)) for label, expr in kin.workless),
        until_kinetic=kin.until is not None and bool(
            kin.until.free_symbols & {*kin.k.qdd, *kin.reactions}))


def _value(fn: Callable, x: np.ndarray) -> float:
    with np.errstate(all="ignore"):
        return float(np.asarray(fn(*x), dtype=float).ravel()[0])


def _extended(kp, values: np.ndarray) -> np.ndarray:
    return np.concatenate([values, np.zeros(len(kp.kin.reactions))])


def start_values(kp, ap: AnalysisPlan, values: np.ndarray) -> np.ndarray:
    """``values`` with the coordinates and rates of the start state put in."""
    x = _extended(kp, values)
    out = values.copy()
    for i, fn in ap.start:
        out[i] = _value(fn, x)
    return out


_Analysis = TypeVar("_Analysis", WorkEnergy, Integration)


def _analysis(problem: Problem, kind: type[_Analysis]) -> _Analysis:
    """The problem's analysis, of the kind the solver chose this function for."""
    analysis = dynamics_of(problem).analysis
    assert isinstance(analysis, kind), analysis
    return analysis


# ---------------------------------------------------------------------------- work-energy


def energy_state(problem: Problem, kp, state: State, given_rates: list[str]) -> State:
    """The instant's rates from the energy balance (see the module docstring)."""
    analysis = _analysis(problem, WorkEnergy)
    index = kp.kp.index
    rates = list(index.rates(1))
    if given_rates:
        raise SolveError(f"work_energy fixes the rates; do not also give {given_rates[0]}",
                         where=analysis.where)
    if kp.kin.nonconservative:
        raise SolveError(f"work_energy needs conservative loads: "
                         f"{', '.join(kp.kin.nonconservative)} can do work that is not a "
                         "potential energy's change", where=analysis.where)
    ap = analysis_plan(kp)
    values = state.values.copy()
    level = kp.kp.levels[1]
    values[rates] = 0.0
    values[list(index.rates(2))] = 0.0
    with np.errstate(all="ignore"):
        J = np.asarray(level.jacobian(*values), dtype=float).reshape(len(level.labels), index.n)
    J = J[:level.constraint_rows]
    u = nullspace(J) if len(J) else np.eye(index.n)
    if u.shape[1] != 1:
        raise SolveError(f"work_energy finds the speed of a motion with one degree of freedom; "
                         f"this one has {u.shape[1]} at the instant", where=analysis.where)
    u = u[:, 0]
    e0 = _value(ap.energy, _extended(kp, start_values(kp, ap, values)))
    v = _value(ap.energy, _extended(kp, values))
    moving = values.copy()
    moving[rates] = u
    t_unit = _value(ap.energy, _extended(kp, moving)) - v
    square = (e0 - v) / t_unit
    if square < -1e-9 * (abs(e0) + abs(v) + 1e-300) / t_unit:
        raise SolveError(f"the instant cannot be reached from the start state: it needs "
                         f"{v - e0:.4g} J more energy than the start state has",
                         where=analysis.where)
    speed = np.sqrt(max(square, 0.0))
    sign = 1.0
    if speed > 0:
        if not analysis.sense:
            raise SolveError("work_energy fixes the speed, not its sign: give 'sense', such as "
                             f"{{\"{index.spelling(rates[int(np.argmax(abs(u)))])}\": "
                             "negative}", where=analysis.where)
        key, sense = analysis.sense[0]
        j = index.position(key.text.replace(" ", ""))
        component = u[rates.index(j)]
        if abs(component) < 1e-12:
            raise SolveError(f"the sense of {key.text} cannot fix the sign: it is zero at the "
                             "instant", where=key.where)
        sign = np.sign(component) * (1 if sense == "positive" else -1)
    values[rates] = sign * speed * u
    x = _extended(kp, values)
    size = 1.0 + float(np.abs(values[rates]).max(initial=0.0))
    for label, fn in ap.workless:
        if abs(_value(fn, x)) > 1e-8 * size:
            raise SolveError(f"work_energy needs workless reactions: {label} does work at the "
                             "instant (its point moves along it)", where=analysis.where)
    known = state.given.copy()
    known[rates] = True
    return State(values, known, frozenset())


def energy_rate_symbolic(problem: Problem, kp, expr, declared: set):
    """``expr`` with an undeclared rate replaced by its value from the energy balance, for a
    single coordinate without constraints: q' = s sqrt(2 (E0 - V(q)) / M(q))."""
    kin = kp.kin
    k = kin.k
    analysis = _analysis(problem, WorkEnergy)
    free = expr.free_symbols if not isinstance(expr, sp.MatrixBase) \
        else set().union(*(e.free_symbols for e in expr))
    wanted = [qd for qd in k.qd if qd in free and qd not in declared]
    if not wanted:
        return expr
    if len(k.q) != 1 or k.velocity:
        raise SolveError("a symbolic answer through work_energy needs a single coordinate "
                         "without constraints; declare the rate among the symbols",
                         where=analysis.where)
    qd = k.qd[0]
    energy = kin.energy
    e0 = energy.xreplace(dict(kin.start))
    v = energy.xreplace({qd: 0})
    mass = sp.simplify(2 * (energy.xreplace({qd: 1}) - v))
    sign = -1 if analysis.sense and analysis.sense[0][1] == "negative" else 1
    value = sign * sp.sqrt(sp.simplify(2 * (e0 - v) / mass))
    return expr.xreplace({qd: value})


# ---------------------------------------------------------------------------- integration


def integrate_to_event(problem: Problem, kp, base: np.ndarray, solve) -> tuple[State, np.ndarray]:
    """The state at the event and the extended state just before it (accelerations and
    reactions as limits). ``base`` holds the parameters; ``solve(values)`` returns the
    extended state with the second rates and reactions solved."""
    from scipy.integrate import solve_ivp

    analysis = _analysis(problem, Integration)
    ap = analysis_plan(kp)
    index = kp.kp.index
    q, qd, qdd = list(range(index.n)), list(index.rates(1)), list(index.rates(2))
    values = start_values(kp, ap, base)
    values[index.time] = 0.0
    values[qdd] = 0.0

    def at(t, y):
        v = values.copy()
        v[q] = y[:index.n]
        v[qd] = y[index.n:]
        v[index.time] = t
        return v

    calls = [0]

    def rhs(t, y):
        calls[0] += 1
        if calls[0] > MAX_CALLS:
            raise SolveError(f"the integration stalls near t = {t:.6g} s before the event (the "
                             "motion may switch there, e.g. friction reversing once the slip "
                             "ends)", where=analysis.where)
        x = solve(at(t, y))
        return np.concatenate([y[index.n:], x[qdd]])

    def event(t, y):
        # an event of the state alone is read without the balances (which are undefined
        # where a slip speed is exactly zero)
        x = solve(at(t, y)) if ap.until_kinetic else _extended(kp, at(t, y))
        return _value(ap.until, x)

    # scipy reads the event's function attribute; mypy models none (python/mypy#2087)
    event.terminal = True  # type: ignore[attr-defined]
    y0 = np.concatenate([values[q], values[qd]])
    if abs(event(0.0, y0)) == 0.0:
        raise SolveError("the event already holds at the start (t = 0)", where=analysis.where)
    result = solve_ivp(rhs, (0.0, analysis.max_time), y0, method="DOP853", rtol=RTOL,
                       atol=ATOL, events=event, dense_output=True)
    if result.status < 0:
        raise SolveError(f"the integration failed: {result.message}", where=analysis.where)
    if not len(result.t_events[0]):
        raise SolveError(f"the event '{analysis.until[0].text} = {analysis.until[1].text}' does "
                         f"not happen within {analysis.max_time:g} s", where=analysis.where)
    t_event = float(result.t_events[0][0])
    y_event = result.y_events[0][0]
    end = at(t_event, y_event)
    before = solve(at(t_event * (1 - 1e-9), result.sol(t_event * (1 - 1e-9))))
    known = np.zeros(len(end), dtype=bool)
    known[index.config] = True
    known[qd] = True
    return State(end, known, frozenset()), before


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
    that is positive at the givens (``numbers``: plain symbol -> SI value).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.mechanics.dynamics import derive_kinetics
    >>> kin = derive_kinetics(load_problem(shipped_dir("problems")
    ...                                    / "ruina_9_23_ball_impulse_momentum.yaml"))
    >>> integrated_symbolically(kin, kin.k.time, {s: 1.0 for _, s in kin.k.parameters})
    2*v0/(7*g*mu)
    """
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
    T = sp.Symbol("t_event", positive=True)
    at_time = {**solved, k.time: T}
    for q, qd, qdd in zip(k.q, k.qd, k.qdd):
        at_time[q] = start[q] + start[qd] * T + solved[qdd] * T ** 2 / 2
        at_time[qd] = start[qd] + solved[qdd] * T
    event = sp.simplify(kin.until.xreplace(at_time))
    roots = []
    for root in sp.solve(event, T):
        value = complex(root.xreplace(numbers).evalf())
        if abs(value.imag) <= 1e-12 * (1 + abs(value.real)) and value.real > 0:
            roots.append((value.real, root))
    if not roots:
        raise SolveError("the event of the integrated motion has no closed-form time: ask for "
                         "a scalar", where=where)
    t_event = min(roots, key=lambda pair: pair[0])[1]
    result = expr.xreplace(at_time).xreplace({T: t_event})
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
