"""Where an objective asked ``when: lhs = rhs`` is read: the first position the motion from the
work–energy start reaches where the equation holds (a wall's reaction vanishing, a speed
reached), the rates there from the energy balance.

The equation is written in the position alone: the unknown second rates and reactions solved
from the momentum balances, the rate from the energy integral (one coordinate without
constraints, :func:`~.work_energy.energy_rate_symbolic`). The position is found numerically,
walking from the start the way ``sense`` says until the equation changes sign (or the motion
turns back), then refined; a symbolic objective gets the closed-form root that is that
position, when sympy finds one.

The closed forms come from the factors of the equation that are quadratics at most in the
coordinate or one of its sines, cosines or tangents (:func:`closed_form_roots`); the ladder of
``problems/ruina_9_20_ladder_energy.yaml`` leaves the wall at ``asin(2*sin(theta0)/3)``
(tests/solve/test_positions.py).

>>> theta, theta0 = sp.symbols("theta theta0")
>>> closed_form_roots(sp.cos(theta) * (3 * sp.sin(theta) - 2 * sp.sin(theta0)), theta)
(pi/2, -pi/2, asin(2*sin(theta0)/3), pi - asin(2*sin(theta0)/3))
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import sympy as sp

from ..errors import SolveError
from ..expressions.syntax import Name, Prime
from ..mechanics.dynamics import derive_kinetics
from ..spec.dynamics import WorkEnergy
from ..spec.model import Problem
from ..spec.validate import is_angle_unit
from .analysis import analysis_of, closed_forms
from .generated import lambdified
from .rules import real, same_value
from ..units import from_si

_STEPS = 4096  # points of the walk from the start: a root closer to another is not told apart
_XTOL = 1e-14
_FIRST = 256  # points of the walk's first stretch


def position_where(problem: Problem, objective_id: str, given_map: dict,
                   residual: sp.Expr) -> float:
    """The coordinate's value (SI) at the first position the motion from the start reaches
    where the objective's ``when`` holds, at the givens ``given_map`` (canonical key ->
    ``(node, si, Given)``); ``residual`` is its ``lhs - rhs`` in the coordinate and the
    parameters (:func:`~.dynamics.when_residual`): :func:`positions_where` of one column,
    its error raised."""
    (found,) = positions_where(problem, objective_id, [given_map], [residual])
    if isinstance(found, SolveError):
        raise found
    return found


def positions_where(problem: Problem, objective_id: str, given_maps: Sequence[dict],
                    residuals: Sequence[sp.Expr]) -> list[float | SolveError]:
    """:func:`position_where` at every column's givens (``given_maps``, each with its
    ``residuals``), walked together: each column's position, or the error that says where
    its equation was looked for."""
    obj = problem.objective(objective_id)
    assert obj.when is not None, "only an objective asked 'when' has a position of its own"
    q = derive_kinetics(problem).k.q[0]
    start_expr = dict(derive_kinetics(problem).start)[q]
    analysis = analysis_of(problem, WorkEnergy)
    sign = analysis.sense[0][1].sign if analysis.sense else 1
    coordinate = problem.coordinates[0]
    angle = is_angle_unit(coordinate.unit)
    numbers = [_numbers(problem, given_map)[1] for given_map in given_maps]
    out: list[float | SolveError] = [0.0] * len(given_maps)
    by_residual: dict[sp.Expr, list[int]] = {}
    for i, residual in enumerate(residuals):
        by_residual.setdefault(residual, []).append(i)
    for residual, columns in by_residual.items():
        equation, start_at = _functions(residual, start_expr, q)
        starts = np.broadcast_to(np.asarray(start_at.function(*(
            np.array([numbers[i][s] for i in columns]) for s in start_at.parameters)),
            dtype=float), (len(columns),))
        walks = _walked(equation, np.array([[numbers[i][s] for s in equation.parameters]
                                            for i in columns]).reshape(len(columns), -1),
                        starts, sign, angle)
        for i, start, found in zip(columns, starts.tolist(), walks):
            out[i] = found if isinstance(found, float) else \
                _nowhere(problem, objective_id, start, *found)
    return out


def _nowhere(problem: Problem, objective_id: str, start: float, last: float | None,
             turned_back: bool) -> SolveError:
    """The error of a ``when`` that holds nowhere the walk from ``start`` reached (up to
    ``last``; ``None``: only the start), where the motion turned back or not."""
    when = problem.objective(objective_id).when
    assert when is not None, "only an objective asked 'when' has a position of its own"
    left, right = when
    coordinate = problem.coordinates[0]
    searched = f"from {_shown(problem, start)} to {_shown(problem, last)}" \
        if last is not None else f"at {_shown(problem, start)}"
    why = "where the motion turns back" if turned_back else \
        ("one turn" if is_angle_unit(coordinate.unit) else "a thousand times its size")
    return SolveError(
        f"objective '{objective_id}': '{left.text} = {right.text}' does not hold anywhere "
        f"the motion from the start reaches (searched {coordinate.name} {searched}, "
        f"{why}); check the equation, 'from' and 'sense'", where=left.where)


Walk = float | tuple[float | None, bool]
"""Where a walk ends: the root found, or the last position searched (``None``: only the
start) and whether the motion turned back there."""

_WALKS: dict[tuple, Walk] = {}
_WALKS_LIMIT = 4096


def _walked(equation: _Function, parameters: np.ndarray, start: np.ndarray, sign: int,
            angle: bool) -> list[Walk]:
    """Per column (``parameters``: one row each, ``start``), the first root of ``equation``
    walking from its start the way ``sign`` says (one turn of an angle), or where the walk
    gave up: kept per column, whose symbolic answer looks for the same position again
    (:func:`position_symbolic`). The columns walk together, stretch by stretch."""
    keys = [(equation, tuple(row), x, sign, angle)
            for row, x in zip(parameters.tolist(), start.tolist())]
    todo = [k for k, key in enumerate(keys) if key not in _WALKS]
    if todo:
        if len(_WALKS) + len(todo) > _WALKS_LIMIT:
            _WALKS.clear()
        _WALKS.update(zip([keys[k] for k in todo],
                          _walked_together(equation, parameters[todo], start[todo], sign,
                                           angle)))
    return [_WALKS[key] for key in keys]


_walked.cache_clear = _WALKS.clear  # type: ignore[attr-defined]


def _walked_together(equation: _Function, parameters: np.ndarray, start: np.ndarray,
                     sign: int, angle: bool) -> list[Walk]:
    """:func:`_walked` of columns not walked before: the equation evaluated on every
    column's grid at once, in stretches twice as long each time (the first crossing is
    often near) until each column has a sign change, an undefined value (beyond it the
    motion has turned back: no energy left to go on) or its grid's end; each root refined
    between the two points that bracket it by scipy's ``brentq`` (a few evaluations, each
    cheaper on a number than an iteration over arrays of columns is)."""
    n = len(start)
    if angle:
        steps = np.broadcast_to(np.linspace(0.0, 2 * np.pi, _STEPS + 1), (n, _STEPS + 1))
    else:
        steps = np.maximum(np.abs(start), 1.0)[:, None] * np.concatenate(
            [[0.0], np.logspace(-6, 3, _STEPS)])
    grid = start[:, None] + sign * steps
    size = grid.shape[1]
    walked = np.full(grid.shape, np.nan)
    out: list[Walk] = [(None, False)] * n
    bracket: list[tuple[int, int]] = []  # (column, index of the point before its root)
    todo, length = np.arange(n), 0
    while todo.size:
        end = min(size, max(2 * length, _FIRST))
        with np.errstate(all="ignore"):
            # (a number where the equation does not hold the coordinate: broadcast)
            walked[todo, length:end] = equation.function(
                grid[todo, length:end], *(p[:, None] for p in parameters[todo].T))
        length = end
        values = walked[todo, :end]
        finite = np.isfinite(values)
        reached = np.where(finite.all(axis=1), end, np.argmin(finite, axis=1))
        # holding at the start: the next crossing
        skip = ((reached > 0) & (values[:, 0] == 0.0)).astype(int)
        signs = np.sign(values)
        pair = np.arange(end - 1)
        change = (signs[:, :-1] * signs[:, 1:] <= 0) & (pair >= skip[:, None]) \
            & (pair + 1 < reached[:, None])
        found = change.any(axis=1)
        first = np.argmax(change, axis=1)
        stop = found | (reached < end) | (end == size)
        for k in np.flatnonzero(stop).tolist():
            column = int(todo[k])
            if found[k] and values[k, first[k]] == 0.0:
                out[column] = float(grid[column, first[k]])
            elif found[k]:
                bracket.append((column, int(first[k])))
            else:
                last = int(reached[k]) - 1
                out[column] = (float(grid[column, last]) if last >= skip[k] else None,
                               bool(reached[k] < size))
        todo = todo[~stop]
    if bracket:
        from scipy import optimize

        for column, i in bracket:  # each column's root between its two points
            row = parameters[column].tolist()
            out[column] = float(optimize.brentq(
                lambda x, row=row: float(equation.function(x, *row)), grid[column, i],
                grid[column, i + 1], xtol=_XTOL, rtol=4 * np.finfo(float).eps))
    return out


def position_symbolic(problem: Problem, objective_id: str, givens: tuple,
                      residual: sp.Expr) -> sp.Expr:
    """The position of :func:`position_where` in closed form (in the parameters), the root of
    the ``when`` equation ``residual`` that is the numeric one at ``givens`` (items of a given
    map): the one of :func:`closed_form_roots` that :func:`which_root` picks."""
    q = derive_kinetics(problem).k.q[0]
    return closed_form_roots(residual, q)[which_root(problem, objective_id, dict(givens),
                                                     residual)]


def which_root(problem: Problem, objective_id: str, given_map: dict,
               residual: sp.Expr) -> int:
    """Which of :func:`closed_form_roots` of ``residual`` is the position of
    :func:`position_where` at the givens ``given_map`` (the first real one there): with the
    givens its terms solve with, what fixes a symbolic answer asked ``when``. Without sympy:
    the roots are evaluated by one function made once (:func:`~.analysis.closed_forms`)."""
    obj = problem.objective(objective_id)
    assert obj.when is not None, "only an objective asked 'when' has a position of its own"
    q, numbers = _numbers(problem, given_map)
    value = position_where(problem, objective_id, given_map, residual)
    # a root complex or undefined here is not the position
    roots = closed_forms(closed_form_roots(residual, q)).at(numbers)
    for i, (at, is_real) in enumerate(zip(roots, real(roots))):
        if is_real and same_value(value, at.real):
            return i
    left, right = obj.when
    raise SolveError(f"objective '{objective_id}': '{left.text} = {right.text}' holds at "
                     f"{problem.coordinates[0].name} = {_shown(problem, value)}, but sympy finds no "
                     "closed form for that position; ask for it as a scalar",
                     where=left.where)


@lru_cache(maxsize=64)
def closed_form_roots(residual: sp.Expr, q: sp.Symbol) -> tuple:
    """The roots of the factors of ``residual`` that are polynomials of degree two at most in
    one of q, sin q, cos q, tan q (each inverse's branches): what closes quickly. Anything
    else (sin q and cos q together, a square root of q) has none here, since sympy's general
    solvers can take minutes on it."""
    u = sp.Dummy("u")
    inverses = {sp.sin(q): lambda r: (sp.asin(r), sp.pi - sp.asin(r)),
                sp.cos(q): lambda r: (sp.acos(r), -sp.acos(r)),
                sp.tan(q): lambda r: (sp.atan(r), sp.atan(r) + sp.pi), q: lambda r: (r,)}
    numerator = sp.numer(sp.together(sp.simplify(residual)))
    if q not in numerator.free_symbols:
        return ()
    try:
        factors = [f for f, _ in sp.factor_list(numerator)[1]]
    except sp.PolynomialError:  # square roots of the parameters: not a polynomial's factors
        factors = list(sp.Mul.make_args(numerator))
    out = []
    for factor in factors:
        for kernel, inverse in inverses.items():
            plain = factor.xreplace({kernel: u})
            if q not in plain.free_symbols and u in plain.free_symbols \
                    and plain.is_polynomial(u) and sp.degree(plain, u) <= 2:
                out += [root for r in sp.solve(plain, u) for root in inverse(r)]
                break
    return tuple(out)


@dataclass(frozen=True)
class _Function:
    """An expression made a numpy function once, of its parameters (sorted by name) after
    the arguments it was made with."""

    parameters: tuple[sp.Symbol, ...]
    function: Callable


@lru_cache(maxsize=64)
def _functions(residual: sp.Expr, start: sp.Expr, q: sp.Symbol) -> tuple[_Function, _Function]:
    """The ``when`` equation's residual as a function of (q, *its parameters) and the start
    position's as one of its parameters: made once per equation, each variant only puts its
    values in."""
    return _function(residual, (q,)), _function(start, ())


def _function(expr: sp.Expr, first: tuple) -> _Function:
    parameters = tuple(sorted(expr.free_symbols - set(first), key=str))
    return _Function(parameters, lambdified((*first, *parameters), expr))


def _numbers(problem: Problem, given_map: dict) -> tuple[sp.Symbol, dict[sp.Symbol, float]]:
    """The coordinate's symbol, and every other given's symbol -> its SI value."""
    k = derive_kinetics(problem).k
    q = k.q[0]
    numbers = {}
    for node, si, _ in given_map.values():
        if isinstance(node, (Name, Prime)) and si is not None:
            symbol = k.quantity(node)
            if symbol != q:
                numbers[symbol] = float(si)
    return q, numbers


def without_position(problem: Problem, given_map: dict) -> tuple:
    """The givens the equation's symbolic solution depends on (those that stand in for a
    symbol, :func:`~.symbolic.solved_symbolically`: zeros and rates), without the coordinate
    (the problem's own instant is not the one asked): one key for every variant."""
    name = problem.coordinates[0].name
    return tuple(sorted((key, (node, si, None)) for key, (node, si, _) in given_map.items()
                        if key != name and (si == 0 or isinstance(node, Prime))))


def _shown(problem: Problem, value: float) -> str:
    """A value of the coordinate (SI) in its own unit, for a message."""
    unit = problem.coordinates[0].unit
    return f"{from_si(value, unit):.6g} {unit}"
