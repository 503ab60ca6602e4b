"""The start of an integration with massless junctions (:mod:`mechgrade.mechanics.junctions`):
the junctions' coordinates and rates the ``from`` state leaves out are solved from their
balances (:func:`~.levels.solve_level_columns`, every column and start at once), and the ones
it names must keep those balances (:func:`~.levels.holds`, the problem's ``consistency``).
"""

from __future__ import annotations

import numpy as np

from ..errors import MechgradeError, SolveError
from ..expressions.syntax import to_text
from ..mechanics.junctions import is_junction_balance
from ..spec.dynamics import Integration, dynamics_of, junction_coordinates
from .levels import (DEFAULT_GUESS, _starts, holds, residuals, same_root, solve_level_columns,
                     typical_sizes)


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
        active = np.array([is_junction_balance(label) for label in level.labels])
        settled = [names[s] for s in kp.kin.settled if index.level_of(names[s]) == order]
        guessed = order == 0 and all(index.spelling(i) in guesses for i in settled)
        guess = np.array([guesses.get(index.spelling(i), DEFAULT_GUESS) for i in settled])
        todo = [c for c in range(out.shape[1]) if c not in errors]
        if not todo:
            break
        roots = _roots(problem, kp, level, out[:, todo], active, settled,
                       [guess] if guessed or order == 1 or not settled else None, guess)
        for c, found in zip(todo, roots):
            if len(found) == 1:
                out[:, c] = found[0]
            else:
                errors[c] = SolveError(
                    _message(problem, kp, order, settled, found, out[:, c], active),
                    where=where if settled else start)
    return out, errors


def _roots(problem, kp, level, X: np.ndarray, active: np.ndarray, settled: list[int],
           origins: list[np.ndarray] | None, guess: np.ndarray) -> list[list[np.ndarray]]:
    """Each column's distinct states (in the order of the starts that found them) where the
    ``active`` rows of ``level`` hold, ``settled`` solved for from each of ``origins`` (by
    default the guess and the starts spread around it by the column's typical sizes); with
    nothing to solve for, the column itself if they hold there."""
    T = np.zeros((int(active.sum()), X.shape[1]))
    if not settled:
        held = holds(problem.consistency, level, X, active, T)
        return [[X[:, c].copy()] if held[c] else [] for c in range(X.shape[1])]
    starts = [origins if origins is not None else
              [guess, *_starts(guess, _sizes(problem, kp, X[:, c], settled)[settled], 0)]
              for c in range(X.shape[1])]
    pairs = [(c, s) for c, each in enumerate(starts) for s in each]
    Y = X[:, [c for c, _ in pairs]].copy()
    Y[settled] = np.stack([s for _, s in pairs], axis=1)
    fits = solve_level_columns(problem.consistency, level, Y, settled,
                               list(kp.kp.index.unknowns(level.order)), active,
                               np.zeros((T.shape[0], Y.shape[1])))
    out: list[list[np.ndarray]] = [[] for _ in range(X.shape[1])]
    sizes: dict[int, np.ndarray] = {}  # a column's, once it has a root to tell apart
    for j, (c, _) in enumerate(pairs):
        root = fits.X[:, j]
        if not fits.held[j]:
            continue
        if out[c]:
            if c not in sizes:
                sizes[c] = _sizes(problem, kp, X[:, c], settled)
            if any(same_root(sizes[c], root, r, settled) for r in out[c]):
                continue
        out[c].append(root.copy())
    return out


def _sizes(problem, kp, x: np.ndarray, settled: list[int]) -> np.ndarray:
    """The typical size of each quantity of the state ``x`` (:func:`~.levels.typical_sizes`
    of what it knows beside the ``settled`` ones)."""
    known = np.isfinite(x)
    known[settled] = False
    return typical_sizes(problem, kp.kp, np.nan_to_num(x)[:, None], known)[:, 0]


def _message(problem, kp, order: int, settled: list[int], roots: list, x: np.ndarray,
             active: np.ndarray) -> str:
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
    r, _ = residuals(kp.kp.levels[order], x[:, None], active, np.zeros((int(active.sum()), 1)))
    residual = np.abs(r).max()
    mark = "" if order == 0 else "'"
    named = " and ".join(f"{c}{mark}" for c in junction_coordinates(problem))
    return (f"the start state puts the massless junction {junctions} out of its balance: its "
            f"springs' pulls {'' if order == 0 else 'change at a rate that '}add up to "
            f"{residual:.4g} N{'' if order == 0 else '/s'}, expected 0; leave {named} out of "
            "'from' (the junction's balance fixes it), or give the value that keeps it")
