"""The start of an integration with massless junctions (:mod:`mechgrade.mechanics.junctions`):
the junctions' coordinates and rates the ``from`` state leaves out are solved from their
balances (position level by Newton's method, velocity level in one linear step), and the ones it
names must keep those balances.
"""

from __future__ import annotations

import warnings

import numpy as np

from ..errors import MechgradeError, SolveError
from ..expressions.syntax import to_text
from ..mechanics.junctions import is_junction_balance
from ..spec.dynamics import Integration, dynamics_of, junction_coordinates
from .levels import DEFAULT_GUESS, _starts, typical_sizes

NEWTON_STEPS = 50
TOLERANCE = 1e-10  # of a balance's row, relative to the size of its terms


def settle_junctions(problem, kp, values: np.ndarray
                     ) -> tuple[np.ndarray, dict[int, MechgradeError]]:
    """``values`` (state x columns) with each column's junction coordinates and rates that
    the start leaves out (``Kinetics.settled``) solved from the junctions' balances, and the
    error of each column whose balances cannot hold at the start, or have several roots
    and no ``guesses:`` picks one."""
    junctions = dynamics_of(problem).junctions if problem.dynamics is not None else ()
    if not junctions:
        return values, {}
    index = kp.kp.index
    names = {s: i for i, s in enumerate(kp.symbols)}
    guesses = {to_text(g.key.node): g.si for g in problem.guesses}
    out = values.copy()
    errors: dict[int, MechgradeError] = {}
    where = junctions[0].where
    analysis = dynamics_of(problem).analysis
    start = analysis.where if isinstance(analysis, Integration) else where
    for order in (0, 1):
        level = kp.kp.levels[order]
        rows = [i for i, label in enumerate(level.labels) if is_junction_balance(label)]
        columns = list(index.unknowns(order))
        settled = [names[s] for s in kp.kin.settled if index.level_of(names[s]) == order]
        solve_for = [columns.index(i) for i in settled]
        guessed = order == 0 and all(index.spelling(i) in guesses for i in settled)
        guess = np.array([guesses.get(index.spelling(i), DEFAULT_GUESS) for i in settled])
        for c in range(out.shape[1]):
            if c in errors:
                continue
            x = out[:, c]
            if not settled:
                roots = [x.copy()] if _holds(level, x, rows) else []
            else:
                origins = [guess] if guessed or order == 1 else \
                    [guess, *_starts(guess, _scale(problem, kp, x, settled), 0)]
                roots = []
                for origin in origins:
                    root = _newton(level, x, rows, settled, solve_for, len(columns), origin)
                    if root is not None and not any(_same(root[settled], r[settled])
                                                    for r in roots):
                        roots.append(root)
            if len(roots) == 1:
                out[:, c] = roots[0]
            else:
                errors[c] = SolveError(_message(problem, kp, order, settled, roots, x, rows),
                                       where=where if settled else start)
    return out, errors


def _newton(level, x: np.ndarray, rows: list[int], settled: list[int], solve_for: list[int],
            width: int, origin: np.ndarray) -> np.ndarray | None:
    """The state with ``settled`` solved from ``rows`` of ``level`` by Newton's method from
    ``origin``, or ``None`` where it does not converge."""
    x = x.copy()
    x[settled] = origin
    for _ in range(NEWTON_STEPS):
        r = _rows(level.residual, x, rows)
        J = _rows(level.jacobian, x, rows, width)[:, solve_for]
        if not (np.isfinite(J).all() and np.isfinite(r).all()):
            return None
        step = np.linalg.lstsq(J, -r, rcond=None)[0]
        x[settled] += step
        if np.abs(step).max() <= 1e-13 * (1 + np.abs(x[settled]).max()):
            break
    return x if _holds(level, x, rows) else None


def _holds(level, x: np.ndarray, rows: list[int]) -> bool:
    residual = _rows(level.residual, x, rows)
    scale = 1 + _rows(level.scale, x, rows)
    return bool(np.isfinite(residual).all() and (np.abs(residual) <= TOLERANCE * scale).all())


def _scale(problem, kp, x: np.ndarray, settled: list[int]) -> np.ndarray:
    known = np.isfinite(x)
    known[settled] = False
    return typical_sizes(problem, kp.kp, np.nan_to_num(x)[:, None], known)[settled, 0]


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    return bool(np.allclose(a, b, rtol=1e-6, atol=1e-9))


def _rows(f, x: np.ndarray, rows: list[int], width: int | None = None) -> np.ndarray:
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        value = np.asarray(f(*x), dtype=float)
    value = value.reshape(-1, width) if width is not None else value.ravel()
    return value[rows]


def _message(problem, kp, order: int, settled: list[int], roots: list, x: np.ndarray,
             rows: list[int]) -> str:
    index = kp.kp.index
    junctions = ", ".join(b.name for b in dynamics_of(problem).junctions)
    found = ", ".join(index.spelling(i) for i in settled)
    if len(roots) > 1:
        units = {c.name: c.unit for c in problem.coordinates}
        listed = "; ".join(", ".join(f"{index.spelling(i)} = {r[i]:.4g} "
                                     f"{units.get(index.spelling(i), '')}".rstrip()
                                     for i in settled) for r in roots)
        pick = ", ".join(f"{index.spelling(i)}: {roots[0][i]:.3g} "
                         f"{units.get(index.spelling(i), '')}".rstrip() for i in settled)
        return (f"the balance of the massless junction {junctions} has several solutions at "
                f"the start ({listed}; a spring turned through its end in some of them): pick "
                f"the one meant with guesses: {{{pick}}}")
    if settled:
        return (f"the balance of the massless junction {junctions} has no solution at the "
                f"start for {found} (the springs' pulls on it never add up to 0); check the "
                "springs' free lengths and where they end, or give guesses: near the solution")
    residual = np.abs(_rows(kp.kp.levels[order].residual, x, rows)).max()
    mark = "" if order == 0 else "'"
    named = " and ".join(f"{c}{mark}" for c in junction_coordinates(problem))
    return (f"the start state puts the massless junction {junctions} out of its balance: its "
            f"springs' pulls {'' if order == 0 else 'change at a rate that '}add up to "
            f"{residual:.4g} N{'' if order == 0 else '/s'}, expected 0; leave {named} out of "
            "'from' (the junction's balance fixes it), or give the value that keeps it")
