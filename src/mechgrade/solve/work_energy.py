"""The instant of a dynamics problem reached by the work–energy balance from a start state.

The givens fix the configuration; the rates are ``lambda * u`` along the one free direction
``u`` of the velocity constraints, with ``T(lambda u) + V = E(start)``. Every load must be
conservative and every reaction workless at the instant (checked), and the spec says the sign
of a rate (``sense``).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..errors import SolveError
from ..spec.dynamics import WorkEnergy
from ..spec.model import Problem
from .analysis import analysis_of, analysis_plan, extended, start_values, value_at
from .levels import State
from .rules import null_space


def energy_state(problem: Problem, kp, state: State, given_rates: list[str]) -> State:
    """The instant's rates from the energy balance (see the module docstring)."""
    analysis = analysis_of(problem, WorkEnergy)
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
    u = null_space(J) if len(J) else np.eye(index.n)
    if u.shape[1] != 1:
        raise SolveError(f"work_energy finds the speed of a motion with one degree of freedom; "
                         f"this one has {u.shape[1]} at the instant", where=analysis.where)
    u = u[:, 0]
    e0 = value_at(ap.energy, extended(kp, start_values(kp, ap, values)))
    v = value_at(ap.energy, extended(kp, values))
    moving = values.copy()
    moving[rates] = u
    t_unit = value_at(ap.energy, extended(kp, moving)) - v
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
        sign = np.sign(component) * sense.sign
    values[rates] = sign * speed * u
    x = extended(kp, values)
    size = 1.0 + float(np.abs(values[rates]).max(initial=0.0))
    for label, fn in ap.workless:
        if abs(value_at(fn, x)) > 1e-8 * size:
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
    analysis = analysis_of(problem, WorkEnergy)
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
    sign = analysis.sense[0][1].sign if analysis.sense else 1
    value = sign * sp.sqrt(sp.simplify(2 * (e0 - v) / mass))
    return expr.xreplace({qd: value})
