"""Solving the instant level by level, as pure functions of a :class:`~.plan.Plan`, the givens
placed in its state layout (:class:`Givens`) and the state solved so far (:class:`State`).

The position level is solved numerically for the configuration quantities the givens leave
open, near the spec's guesses; the velocity and acceleration levels — linear in their rates —
by least squares. Ranks say which unknowns the equations leave free, and residuals are checked.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Mapping

import numpy as np
from scipy import linalg, optimize

from ..errors import InconsistentError, SolveError
from ..expressions.syntax import Name, Prime, to_text
from ..spec.model import Problem
from .plan import Level, Plan

RANK_TOL = 1e-9
DEFAULT_GUESS = 0.3


@dataclass(frozen=True)
class Givens:
    """The givens of one solve in the state layout: ``values`` (NaN where not given) and
    ``known``; expression givens by level (``conditions[level][key]``, SI); ``texts``, each
    given as the author wrote it, for messages; ``guess``, start values for the configuration."""

    values: np.ndarray
    known: np.ndarray
    conditions: tuple[Mapping[str, float], Mapping[str, float], Mapping[str, float]]
    texts: tuple[str, ...]
    guess: np.ndarray


@dataclass(frozen=True)
class State:
    """The quantities at the instant (``values``, in the state layout, SI); ``free`` are the
    positions nothing determined (their values are arbitrary picks); ``given`` marks the
    positions whose values were given."""

    values: np.ndarray
    given: np.ndarray
    free: frozenset[int] = frozenset()


def place_givens(problem: Problem, p: Plan, givens: Mapping) -> Givens:
    """``givens`` (canonical key -> (key node, SI value, Given or None)) in ``p``'s layout."""
    index = p.index
    values = np.full(index.size, np.nan)
    known = np.zeros(index.size, dtype=bool)
    conditions = ({}, {}, {})
    texts = []
    for key, (node, si, given) in givens.items():
        texts.append(f"{key} = {given.text}" if given is not None else f"{key} = {si:g} (SI)")
        if isinstance(node, (Name, Prime)):
            try:
                i = index.symbols.index(p.k.quantity(node))
            except (KeyError, ValueError):
                raise SolveError(f"cannot give '{key}': not a coordinate, rate, parameter "
                                 "or t of this problem") from None
            values[i] = si
            known[i] = True
        else:
            levels = [level.order for level in p.levels if key in level.conditions]
            if not levels:
                raise SolveError(f"cannot give '{key}': it is not a given of this problem "
                                 "(expression givens must appear in the spec)")
            conditions[levels[0]][key] = si
    guesses = {to_text(g.key.node): g.si for g in problem.guesses}
    guess = np.array([guesses.get(index.names[i], DEFAULT_GUESS) for i in index.config])
    return Givens(values, known, conditions, tuple(texts), guess)


def _rows(level: Level, g: Givens) -> tuple[np.ndarray, np.ndarray]:
    """Which rows are active (constraints, and the conditions given in this solve), and the
    value each row must equal (0 for constraints)."""
    values = np.array([g.conditions[level.order].get(key, np.nan) for key in level.conditions])
    n = level.constraint_rows
    active = np.concatenate([np.ones(n, dtype=bool), ~np.isnan(values)])
    target = np.concatenate([np.zeros(n), np.nan_to_num(values)])
    return active, target


def solve_position(problem: Problem, p: Plan, g: Givens,
                   free_values: Mapping[int, float] | None = None) -> State:
    """The configuration: unknowns the position equations determine are solved near the
    guesses; the others keep their guess (or the value in ``free_values``) and are free."""
    level = p.levels[0]
    config = list(p.index.config)
    active, target = _rows(level, g)
    unknown = [i for i in config if not g.known[i]]
    x = g.values.copy()
    x[unknown] = g.guess[unknown]
    solve_for = unknown

    def residual(vals):
        full = x.copy()
        full[solve_for] = vals
        return (np.asarray(level.residual(*full), dtype=float).ravel() - target)[active]

    def jac(vals):
        full = x.copy()
        full[solve_for] = vals
        J = np.asarray(level.jacobian(*full), dtype=float).reshape(len(level.labels), len(config))
        return J[active][:, solve_for]

    free: list[int] = list(unknown)
    if unknown and active.any():
        determined, free = _split_free(jac(x[unknown]), unknown)
        for i in free:
            x[i] = (free_values or {}).get(i, x[i])
        solve_for = determined
        if determined:
            with np.errstate(all="ignore"):
                fit = optimize.least_squares(residual, x[determined], jac=jac, xtol=1e-14,
                                             ftol=1e-14, gtol=1e-14, max_nfev=500)
            x[determined] = fit.x
    else:
        for i in free:
            x[i] = (free_values or {}).get(i, x[i])
    if active.any():
        r = np.asarray(level.residual(*x), dtype=float).ravel() - target
        scale = np.abs(np.asarray(level.scale(*x), dtype=float).ravel())
        _check_residual(problem, level, g, r[active], scale[active], active)
    return State(x, g.known, frozenset(free))


def solve_rates(problem: Problem, p: Plan, order: int, state: State, g: Givens,
                shift: np.ndarray | None = None) -> tuple[State, np.ndarray]:
    """The velocity (``order`` 1) or acceleration (2) level, linear in its rates: the
    least-squares solution (moved by ``null @ shift`` when given), and the nullspace basis of
    the unknown rates (the directions the givens leave free)."""
    level = p.levels[order]
    cols = list(p.index.rates(order))
    n = len(cols)
    active, target = _rows(level, g)
    x = state.values.copy()
    x[cols] = np.where(g.known[cols], g.values[cols], 0.0)
    with np.errstate(all="ignore"):
        A = np.asarray(level.jacobian(*x), dtype=float).reshape(len(level.labels), n)
        b = np.asarray(level.residual(*x), dtype=float).ravel() - target
    A, b = A[active], b[active]
    if not (np.isfinite(A).all() and np.isfinite(b).all()):
        raise SolveError(f"the {level.name} equations are undefined at this instant "
                         "(a division by zero in the model)")
    unknown = [j for j in range(n) if not g.known[cols[j]]]
    rhs = -b  # the unknown rates are 0 in x, so b is the residual of the known part
    null = np.zeros((len(unknown), 0))
    free = set(state.free)
    if unknown:
        A_u = A[:, unknown]
        if len(b):
            sol, *_ = linalg.lstsq(A_u, rhs)
            null = nullspace(A_u)
        else:
            sol = np.zeros(len(unknown))
            null = np.eye(len(unknown))
        if shift is not None and null.shape[1]:
            sol = sol + null @ shift
        for j, value in zip(unknown, sol):
            x[cols[j]] = value
        free |= {cols[unknown[i]] for i in range(len(unknown))
                 if null.shape[1] and np.abs(null[i]).max() > 1e-9}
    if len(b):
        with np.errstate(all="ignore"):
            r = np.asarray(level.residual(*x), dtype=float).ravel()[active] - target[active]
            scale = np.abs(np.asarray(level.scale(*x), dtype=float).ravel())[active]
        _check_residual(problem, level, g, r, scale, active)
    return State(x, g.known, frozenset(free)), null


def constraint_rank(p: Plan, state: State) -> int:
    """Rank of the velocity-level constraints in the rates at the solved configuration."""
    level = p.levels[1]
    if not level.constraint_rows:
        return 0
    with np.errstate(all="ignore"):
        A = np.asarray(level.jacobian(*state.values), dtype=float).reshape(len(level.labels),
                                                                           p.index.n)
    return int(np.linalg.matrix_rank(A[:level.constraint_rows]))


def _check_residual(problem: Problem, level: Level, g: Givens, r, scale, active) -> None:
    labels = np.array(level.labels)[active]
    bad = [i for i in range(len(r)) if not abs(r[i]) <= problem.consistency * scale[i] + 1e-10]
    if not bad:
        return
    i = bad[0]
    raise InconsistentError(
        f"the givens conflict at the {level.name} level: '{labels[i]}' is not satisfied "
        f"(residual {r[i]:.4g} against terms of size {scale[i]:.4g}); givens involved: "
        f"{'; '.join(g.texts) or 'none'}")


def _split_free(J: np.ndarray, unknown: list[int]) -> tuple[list[int], list[int]]:
    """Which unknowns the position equations determine (pivoted QR), and which stay free."""
    if J.size == 0:
        return [], list(unknown)
    with np.errstate(all="ignore"):
        _, R, piv = linalg.qr(J, pivoting=True, mode="economic")
    diag = np.abs(np.diag(R)) if R.size else np.zeros(0)
    rank = int((diag > RANK_TOL * max(diag.max(initial=0.0), 1.0)).sum())
    determined = sorted(unknown[j] for j in piv[:rank])
    free = sorted(unknown[j] for j in piv[rank:])
    return determined, free


def nullspace(A: np.ndarray) -> np.ndarray:
    if A.shape[0] == 0:
        return np.eye(A.shape[1])
    _, s, vt = linalg.svd(A)
    rank = int((s > RANK_TOL * max(s.max(initial=0.0), 1.0)).sum())
    return vt[rank:].T


def evaluate(functions, state: State, only: set[str]) -> dict:
    """``{id: values}`` of ``(id, function)`` pairs whose id is in ``only``, at ``state``."""
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return {oid: np.asarray(f(*state.values), dtype=float).ravel()
                for oid, f in functions if oid in only}
