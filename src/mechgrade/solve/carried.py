"""The momentum balances solved with a student's own second rate given (error carried
forward): the balance that would determine that acceleration gives way, the rest is a linear
solve of the remaining unknowns. :func:`solve_carried` is the entry point (the grader's
:mod:`mechgrade.grade.ecf` calls it), as :func:`mechgrade.solve.solve` is the problem's own.

The acceleration is held as if by a drive on the coordinate: a couple on the body it turns
(its moment balance gives way), or for a coordinate that turns no body a force along the
motion of the mass centre it moves (the force balance along that motion gives way). The
reactions then follow from the other balances, as a write-up takes a pin force from
``sum F = m a_G`` with its own ``alpha``. Where the acceleration turns (or moves) more than
one body, every choice of the body whose balance gives way is solved: they must agree, or the
remaining balances do not determine the unknowns and the error says so (the tension of an
Atwood machine with a wrong ``a``: block 1's balance and block 2's give two tensions).

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
>>> solution = solve_carried(problem, givens={"theta''": 7.882})  # alpha turned round
>>> [round(c, 2) for c in solution.result("pin_force").value]  # m a_G + m g j, a_G with it
[0.3, 33.97, 0.0]
"""

from __future__ import annotations

from itertools import product
from typing import Collection, Mapping

import numpy as np

from ..errors import UnderdeterminedError
from ..mechanics.dynamics import balance_part
from ..spec.model import Problem
from . import rules
from .columns import call
from .dynamics import kinetic_reach
from .dynamics_mutants import with_generated_mistakes
from .instant import drive
from .levels import State
from .motion import undefined_balances
from .result import Solution
from .stored import carried_key, kept


def solve_carried(problem: Problem, *, givens: Mapping[str, float | None] | None = None,
                  objectives: Collection[str] | None = None) -> Solution:
    """Like :func:`mechgrade.solve.solve`, for a problem with bodies and loads, with each
    given second rate held by a drive and the balance that would determine it set aside (see
    above); kept in the disk cache as a solution is (:func:`~.stored.carried_key`), its
    generated mistakes each mistaken model solved so too.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> incline = load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml")
    >>> round(solve_carried(incline, givens={"x''": 1.0}).result("normal").value, 3)
    33.983
    """
    assert problem.dynamics is not None, "only a problem with bodies has balances"
    return kept(carried_key(problem, givens, objectives), lambda: with_generated_mistakes(
        problem, held_dynamics(problem, givens=givens, objectives=objectives), givens,
        held_dynamics))


def held_dynamics(problem: Problem, *, givens: Mapping[str, float | None] | None = None,
                  objectives: Collection[str] | None = None) -> Solution:
    """:func:`solve_carried` without the disk cache and the generated mistakes (what
    :func:`~.dynamics.solve_dynamics` is to :func:`mechgrade.solve.solve`): each instant
    reached as the problem's analysis reaches it, its balances solved by
    :func:`carried_kinetics`.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> pendulum = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
    >>> force = held_dynamics(pendulum, givens={"theta''": -31.53}, objectives=("pin_force",))
    >>> [round(c, 2) for c in force.result("pin_force").value]
    [-35.93, 3.57, 0.0]
    """
    return drive(problem, kinetic_reach(problem, carried_kinetics), givens, objectives)


def carried_kinetics(problem: Problem, kp, state: State) -> np.ndarray:
    """The extended state (state values, then reactions) with the unknown second rates and
    reactions solved, each given second rate held by a drive (the module's docstring); raises
    when the equations are undefined or the balances left do not determine the unknowns."""
    size = kp.kp.index.size
    rows = len(kp.labels)
    x = np.concatenate([state.values, np.zeros(len(kp.kin.reactions))])
    known = np.concatenate([state.given, np.zeros(len(kp.kin.reactions), bool)])
    free = [j for j, i in enumerate(kp.columns) if not known[i]]
    held = [j for j, i in enumerate(kp.columns) if known[i] and i < size]
    for j in free:
        x[kp.columns[j]] = 0.0
    A = call(kp.jacobian, x[:, None], rows * len(kp.columns)).reshape(rows, len(kp.columns))
    b = call(kp.residual, x[:, None], rows)[:, 0]
    defined = np.isfinite(A).all(axis=1) & np.isfinite(b)
    if not defined.all():
        raise undefined_balances(kp, defined)
    drives = [_drives(kp, A[:, j]) for j in held]
    solved: list[tuple[tuple[str, ...], np.ndarray]] = []
    for choice in product(*drives):
        E = np.array([e for _, e in choice]).reshape(-1, rows).T
        M = np.hstack([A[:, free], E])
        sol, *_ = np.linalg.lstsq(M, -b, rcond=None)
        if rules.matrix_rank(M) < M.shape[1]:
            continue
        out = x.copy()
        out[[kp.columns[j] for j in free]] = sol[:len(free)]
        r = call(kp.residual, out[:, None], rows)[:, 0] + E @ sol[len(free):]
        scale = np.abs(call(kp.scale, out[:, None], rows)[:, 0])
        if rules.satisfied(r, scale, problem.consistency).all():
            solved.append((tuple(name for name, _ in choice), out))
    given = ", ".join(kp.name(j) for j in held)
    unknowns = [kp.columns[j] for j in free]
    if not solved:
        raise UnderdeterminedError(
            f"with the given {given}, the momentum balances left when the one that gives it "
            f"is set aside do not determine {', '.join(kp.name(j) for j in free)}",
            where=kp.wheres[0] if kp.wheres else None)
    first_names, first = solved[0]
    for names, other in solved[1:]:
        differ = [j for j, i in zip(free, unknowns)
                  if not rules.same_value(first[i], other[i])]
        if differ:
            i = kp.columns[differ[0]]
            raise UnderdeterminedError(
                f"with the given {given}, the momentum balances left do not determine "
                f"{', '.join(kp.name(j) for j in differ)}: setting aside "
                f"{' and '.join(first_names)} gives {kp.name(differ[0])} = {first[i]:.4g}, "
                f"setting aside {' and '.join(names)} gives {other[i]:.4g}",
                where=kp.wheres[0] if kp.wheres else None)
    return first


def _drives(kp, column: np.ndarray) -> list[tuple[str, np.ndarray]]:
    """The ways a drive can hold a given second rate whose column in the balances is
    ``column``: a couple on each body it turns (that body's moment balance), else a force on
    each body whose mass centre it moves (along the motion, in that body's force balance);
    ``(what gives way, the drive's column)``. None at all where it enters no balance."""
    parts = [balance_part(label) for label in kp.labels]
    size = np.abs(column).max() if len(column) else 0.0
    if not size > 0:
        return [("nothing", np.zeros(len(column)))]
    for moment, kind in ((True, "moment"), (False, "force")):
        bodies = list(dict.fromkeys(
            p[0] for p, c in zip(parts, column)
            if p is not None and p[1] == moment and abs(c) > rules.RANK_TOL * size))
        if bodies:
            return [(f"the {kind} balance of {body}",
                     np.where([p == (body, moment) for p in parts], column, 0.0))
                    for body in bodies]
    return [("nothing", np.zeros(len(column)))]
