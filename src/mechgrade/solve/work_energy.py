"""The instant of a dynamics problem reached by the work–energy balance from a start state.

The givens fix the configuration; the rates are ``lambda * u`` along the one free direction
``u`` of the velocity constraints, with ``T(lambda u) + V = E(start)``. Every load must be
conservative and every reaction workless at the instant (checked), and the spec says the sign
of a rate (``sense``).
"""

from __future__ import annotations

from functools import partial

import numpy as np
import sympy as sp

from ..errors import SolveError
from ..spec.dynamics import WorkEnergy
from ..spec.model import Problem
from ..tolerance import parts
from . import rules
from .analysis import analysis_of, analysis_plan
from .columns import FirstErrors, call
from .levels import State


def energy_state(problem: Problem, kp, state: State, given_rates: list[str]) -> State:
    """The instant's rates from the energy balance (see the module docstring):
    :func:`energy_rates` with one column."""
    analysis = analysis_of(problem, WorkEnergy)
    if given_rates:
        raise SolveError(f"work_energy fixes the rates; do not also give {given_rates[0]}",
                         where=analysis.where)
    values, errors = energy_rates(problem, kp, state.values[:, None])
    error = errors[0]
    if error is not None:
        raise error
    known = state.given.copy()
    known[list(kp.kp.index.rates(1))] = True
    out = values[:, 0]
    # a given second rate (a student's, error carried forward) keeps its value
    seconds = [i for i in kp.kp.index.rates(2) if state.given[i]]
    out[seconds] = state.values[seconds]
    return State(out, known, frozenset())


def energy_rates(problem: Problem, kp, X: np.ndarray) -> tuple[np.ndarray, FirstErrors]:
    """Every column of ``X`` (state values, the configuration solved) with its rates from the
    energy balance, and each column's error: loads that are not conservative, more than one
    free direction, an instant that needs more energy than the start state has, a speed
    without the sense of its sign (or a sense of a rate that is zero there), a reaction that
    does work."""
    analysis = analysis_of(problem, WorkEnergy)
    index = kp.kp.index
    rates, n, count = list(index.rates(1)), index.n, X.shape[1]
    errors = FirstErrors(count)
    if kp.kin.nonconservative:
        errors.add(np.ones(count, dtype=bool), lambda _: SolveError(
            f"work_energy needs conservative loads: {', '.join(kp.kin.nonconservative)} can "
            "do work that is not a potential energy's change", where=analysis.where))
    ap = analysis_plan(kp)
    X = X.copy()
    X[rates] = 0.0
    X[list(index.rates(2))] = 0.0
    level = kp.kp.levels[1]
    if level.constraint_rows:
        J = call(level.jacobian, X, len(level.labels) * n).reshape(
            len(level.labels), n, count)[:level.constraint_rows]
        finite = np.isfinite(J).all(axis=(0, 1))
        errors.add(~finite, lambda _: SolveError(
            "work_energy needs the velocity constraints at the instant, but they are "
            "undefined there (a division by zero)", where=analysis.where))
        _, s, Vt = np.linalg.svd(np.where(finite, J, 0.0).transpose(2, 0, 1),
                                 full_matrices=True)
        free = n - rules.rank(s)
        u = Vt[:, n - 1, :].T
    else:
        free = np.full(count, n)
        u = np.ones((n, count))
    errors.add(free != 1, lambda i: SolveError(
        f"work_energy finds the speed of a motion with one degree of freedom; this one has "
        f"{free[i]} at the instant", where=analysis.where))
    reactions = np.zeros((len(kp.kin.reactions), count))
    x = np.concatenate([X, reactions])
    start = x.copy()
    for i, fn in ap.start:
        start[i] = call(fn, x, 1)[0]
    e0 = call(ap.energy, start, 1)[0]
    v = call(ap.energy, x, 1)[0]
    moving = X.copy()
    moving[rates] = u
    with np.errstate(all="ignore"):
        t_unit = call(ap.energy, np.concatenate([moving, reactions]), 1)[0] - v
        square = (e0 - v) / t_unit
        errors.add((square < 0) & parts(e0 - v, np.abs(e0) + np.abs(v)),
                   lambda i: SolveError(
                       f"the instant cannot be reached from the start state: it needs "
                       f"{v[i] - e0[i]:.4g} J more energy than the start state has",
                       where=analysis.where))
        speed = np.sqrt(np.maximum(square, 0.0))
        # an undefined square stays undefined (np.maximum keeps NaN): the balances say where
    sign = np.ones(count)
    if analysis.sense:
        key, sense = analysis.sense[0]
        component = u[rates.index(index.position(key.text.replace(" ", "")))]
        # the motion's one direction (orthonormal) leaves that rate at rest, as it leaves
        # any unknown not open
        errors.add((speed > 0) & ~rules.left_open(component), lambda _: SolveError(
            f"the sense of {key.text} cannot fix the sign: it is zero at the instant",
            where=key.where))
        sign = np.where(speed > 0, np.sign(component) * sense.sign, 1.0)
    else:
        errors.add(speed > 0, lambda i: SolveError(
            "work_energy fixes the speed, not its sign: give 'sense', such as "
            f"{{\"{index.spelling(rates[int(np.argmax(abs(u[:, i])))])}\": negative}}",
            where=analysis.where))
    X[rates] = sign * speed * u
    x = np.concatenate([X, reactions])
    size = 1.0 + np.abs(X[rates]).max(axis=0, initial=0.0)
    for label, fn in ap.workless:
        with np.errstate(invalid="ignore"):
            errors.add(np.abs(call(fn, x, 1)[0]) > rules.REQUIRED_KINETIC * size,
                       partial(_does_work, label, analysis))
    return X, errors


def _does_work(label: str, analysis: WorkEnergy, _: int) -> SolveError:
    return SolveError(f"work_energy needs workless reactions: {label} does work at the "
                      "instant (its point moves along it)", where=analysis.where)


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
