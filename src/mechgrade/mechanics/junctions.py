"""Massless junctions: a point where springs meet with no mass there (a node between springs in
series, :attr:`~mechgrade.spec.dynamics.Dynamics.junctions`).

A junction has no inertia, so its momentum balance says only that the springs' pulls on it add
up to zero. For springs that is an equation in the positions alone: a position-level
constraint, which fixes the junction's own coordinates at every instant (solved with the
problem's other constraints: Newton's method from the last state, one step when it is linear)
and is differentiated for the velocity and acceleration levels like any loop closure. Two
springs k1, k2 in series then act on the block as one of k1 k2/(k1 + k2), with nobody writing
that formula down.

Refused, each with its fix: a damper ending at a junction (its coordinate would obey a first
order equation, c xj' = ..., which is not a constraint), a junction where one spring ends
(a spring with a free end pulls nothing), and junctions whose balances do not fix their own
coordinates (none of their own, junctions joined to nothing but each other, or a balance with
more components than the junction has coordinates).

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("problems") / "block_on_springs_in_series.yaml")
>>> [(c.name, c.lhs.text) for c in junction_constraints(problem)]
[('node (massless): sum of forces', 'k1*(mag(pos(O, J))-L1)*unit(pos(O, J))+k2*(mag(pos(P, J))-L2)*unit(pos(P, J))')]
"""

from __future__ import annotations

import random
from dataclasses import replace
from functools import lru_cache

import numpy as np
import sympy as sp

from ..errors import SolveError
from ..expressions.syntax import Bin, Call, Name, Node, Num, to_text
from ..spec.dynamics import junction_coordinates
from ..spec.model import Constraint, ConstraintLevel, Expr, Problem
from ..tolerance import matrix_rank

BALANCE = "(massless): sum of forces"
"""How a junction's balance is named among the constraints (after the body's name)."""


def junction_constraints(problem: Problem) -> tuple[Constraint, ...]:
    """Each junction's balance, the sum of its springs' pulls = 0, as a position constraint
    written in the spec's language (k (|QJ| - L0) along JQ for a spring from J to Q)."""
    return _junction_constraints(problem)


@lru_cache(maxsize=64)
def _junction_constraints(problem: Problem) -> tuple[Constraint, ...]:
    d = problem.dynamics
    if d is None:
        return ()
    out = []
    for b in d.junctions:
        for damper in d.dampers:
            if b.name in damper.on:
                raise SolveError(
                    f"the damper '{damper.name}' ends at {b.centre}, on '{b.name}', a massless "
                    f"junction: its balance would be a first-order equation in its position "
                    f"(c times a rate = the springs' pulls), which the solver does not "
                    f"integrate; expected only springs at a massless junction: give "
                    f"'{b.name}' a mass (a small one if the book neglects it), or end the "
                    f"damper at a body with mass", where=damper.where)
        pulls: list[Node] = []
        ends = []
        for s in d.springs:
            for i in (0, 1):
                if s.on[i] != b.name or s.on[1 - i] == b.name:
                    continue
                ends.append(s.name)
                toward = Call("pos", (Name(s.between[1 - i]), Name(s.between[i])))
                stretch = Bin("-", Call("mag", (toward,)), s.length.node)
                pulls.append(Bin("*", Bin("*", s.stiffness.node, stretch),
                                 Call("unit", (toward,))))
        if len(ends) < 2:
            raise SolveError(
                f"'{b.name}' is a massless junction at {b.centre} where only the spring "
                f"'{ends[0] if ends else '?'}' ends: a spring with a massless free end pulls "
                f"nothing, so the spring does nothing; expected two springs or more meeting "
                f"at {b.centre} (springs in series): end the next spring there, or give "
                f"'{b.name}' its mass", where=b.where)
        lhs: Node = pulls[0]
        for pull in pulls[1:]:
            lhs = Bin("+", lhs, pull)
        out.append(Constraint(f"{b.name} {BALANCE}", ConstraintLevel.POSITION,
                              Expr(to_text(lhs), lhs, b.where), Expr("0", Num("0"), b.where),
                              b.where))
    return tuple(out)


def junction_balances_said(problem: Problem) -> dict[str, str]:
    """Each junction's balance (by its constraint's name) as a worked solution says it: in
    words and the springs' names, not in the spec's language.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> junction_balances_said(load_problem(shipped_dir("problems") / "block_on_springs_in_series.yaml"))
    {'node (massless): sum of forces': 'The joint J is massless, so the pulls of the springs s1 and s2 on it are in balance: s1 + s2 = 0.'}
    """
    d = problem.dynamics
    if d is None:
        return {}
    out = {}
    for b in d.junctions:
        springs = [s.name for s in d.springs if b.name in s.on]
        out[f"{b.name} {BALANCE}"] = (
            f"The joint {b.centre} is massless, so the pulls of the springs "
            f"{', '.join(springs[:-1])} and {springs[-1]} on it are in balance: "
            f"{' + '.join(springs)} = 0.")
    return out


def with_junctions(problem: Problem) -> Problem:
    """``problem`` with its junctions' balances among its constraints.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("problems") / "block_on_springs_in_series.yaml")
    >>> [c.name for c in with_junctions(p).constraints]
    ['node (massless): sum of forces']
    """
    extra = junction_constraints(problem)
    return replace(problem, constraints=problem.constraints + extra) if extra else problem


def kinematic_part(problem: Problem) -> Problem:
    """The problem's kinematics alone, its junctions' balances among its constraints (its
    objectives are read by the dynamics language)."""
    return replace(with_junctions(problem), objectives=(), dynamics=None)


def is_junction_balance(label: str) -> bool:
    """Whether a constraint row (by its label) is a junction's balance.

    >>> is_junction_balance("node (massless): sum of forces (N.x component)")
    True
    """
    return BALANCE in label


def check_junctions(problem: Problem, k) -> None:
    """The junctions' balances fix their own coordinates: as many independent components as
    the junctions have coordinates of their own (:func:`junction_coordinates`), checked at a
    generic configuration."""
    d = problem.dynamics
    if d is None or not d.junctions or d.mistaken:
        return
    rows = [e for e in k.position if is_junction_balance(e.label)]
    names = junction_coordinates(problem)
    nodes = ", ".join(b.name for b in d.junctions)
    where = d.junctions[0].where
    if not names:
        raise SolveError(
            f"the massless junction {nodes} moves with no coordinate of its own: its balance "
            "(sum of the springs' pulls = 0) would hold the bodies' coordinates instead; "
            "expected the junction located by a coordinate of its own (J: {from: O, position: "
            "xj*N.x}, xj not locating any body with mass)", where=where)
    q = [k.q[k.coordinates.index(c)] for c in names]
    J = sp.Matrix([e.expr for e in rows]).jacobian(q)
    rng = random.Random(7)
    symbols = sorted(J.free_symbols, key=str)
    generic = J.xreplace({s: sp.Float(rng.uniform(0.4, 1.3)) for s in symbols})
    rank = matrix_rank(np.array(generic.tolist(), dtype=complex))
    listed = ", ".join(names)
    if rank < len(q):
        raise SolveError(
            f"the balances of the massless junctions ({nodes}) do not fix {listed}: "
            f"{'their' if len(q) > 1 else 'its'} springs leave {len(q) - rank} of them free "
            "(junctions joined to nothing but each other may sit anywhere); expected each "
            "junction joined through its springs to the ground or to a body with mass: end "
            "one of its springs there", where=where)
    if len(rows) > rank:
        raise SolveError(
            f"the balance of the massless junction {nodes} has {len(rows)} components but "
            f"{listed} only {len(q)} coordinate{'s' if len(q) > 1 else ''}: the springs' pulls "
            "across its path need a guide's reaction, which a junction of springs does not "
            "have; expected the junction free to move in every direction its springs pull "
            "(a coordinate per direction), or give it a mass and the guide's normal force",
            where=where)
