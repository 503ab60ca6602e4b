"""Mistaken constraints: a problem copy with one of its constraints written the way a student
writes it wrongly, for the solver to solve again (kinematic problems as well as those with
bodies: a cord's strands miscounted changes every objective the cord's length fixes). A
rewrite of the spec only, without sympy: a warm solve reads its mistaken copies' plans from the
disk cache.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("problems") / "truck_hoists_crate_pulley.yaml")
>>> [(m.code, m.problem.constraints[0].lhs.text) for m in constraint_mutations(problem)]
[('strands_miscounted', 'sqrt(x**2+h**2)+(h-y)')]
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Iterator

from ..expressions.notation import textbook
from ..expressions.syntax import (Bin, Call, Name, Node, Num, Prime, additive_terms, name_of, names,
                                  sum_of_terms, to_text)
from .model import ConstraintLevel, Expr, Problem


@dataclass(frozen=True)
class ConstraintMutation:
    """One mistaken constraint: ``problem`` the copy to solve again (its author's answers and
    mistakes dropped), ``sentence`` the diagnosis."""

    code: str
    sentence: str
    problem: Problem


def constraint_mutations(problem: Problem) -> tuple[ConstraintMutation, ...]:
    """Every mistaken-constraint copy of ``problem``, family by family."""
    return (*strands_once(problem), *surface_taken_fixed(problem))


def strands_once(problem: Problem) -> Iterator[ConstraintMutation]:
    """A cord's length written with a strand count of one: in a position constraint that
    fixes a length (one side free of the coordinates), a term counted n times (the strands
    of a movable pulley, 2 y_B) taken once."""
    coordinates = {c.name for c in problem.coordinates}
    for i, c in enumerate(problem.constraints):
        if c.level is not ConstraintLevel.POSITION:
            continue
        sides = [c.lhs.node, c.rhs.node]
        moving = [bool(names(side) & coordinates) for side in sides]
        if sum(moving) != 1:
            continue
        side = sides[moving.index(True)]
        terms = additive_terms(side)
        for j, term in enumerate(terms):
            count = _strands(term[1])
            if count is None or len(terms) < 2 or not names(term[1]) & coordinates:
                continue
            once = sum_of_terms(terms[:j] + [(term[0], count[1])] + terms[j + 1:])
            written = Expr(to_text(once), once)
            new = replace(c, lhs=written) if moving[0] else replace(c, rhs=written)
            constraints = problem.constraints[:i] + (new,) + problem.constraints[i + 1:]
            shown = _spaced(count[1])
            yield ConstraintMutation(
                "strands_miscounted", f"Your value counts {shown} once in the length of "
                f"{c.name} ({textbook(c.lhs.text)} = {textbook(c.rhs.text)}): it is there "
                f"{count[0]} times, once for each strand that holds it.",
                _copy(problem, constraints))


def surface_taken_fixed(problem: Problem) -> Iterator[ConstraintMutation]:
    """A body rolling on a moving surface (a rack, a plank) written as rolling on a fixed one:
    the contact point's velocity ``vel(coincident(P, S), N)`` taken as zero (S's point at P
    taken at rest)."""
    for i, c in enumerate(problem.constraints):
        # a rolling contact as the loader writes it: the body's point = the surface's point
        body, contact = _surface_point(c.lhs.node), _surface_point(c.rhs.node)
        if c.level is not ConstraintLevel.VELOCITY or body is None or contact is None \
                or body[0] != contact[0]:
            continue
        point, surface, frame = contact
        text = f"vel(coincident({point}, {frame}), {frame})"
        rest = Expr(text, Call("vel", (Call("coincident", (Name(point), Name(frame))),
                                       Name(frame))))
        new = replace(c, rhs=rest)
        yield ConstraintMutation(
            "surface_taken_fixed", f"Your value takes {surface} as fixed where {body[1]} "
            f"rolls on it at {point} ({c.name}): {surface} moves, so without slip the point "
            f"{point} of {body[1]} moves with {surface}'s point there, not at zero speed.",
            _copy(problem, problem.constraints[:i] + (new,) + problem.constraints[i + 1:]))


def _surface_point(node: Node) -> tuple[str, str, str] | None:
    """``(P, S, F)`` of ``vel(coincident(P, S), F)`` with S not F: a moving surface's point."""
    if not (isinstance(node, Call) and node.func == "vel" and len(node.args) == 2):
        return None
    inner, frame = node.args
    if not (isinstance(inner, Call) and inner.func == "coincident" and len(inner.args) == 2
            and all(isinstance(a, Name) for a in (*inner.args, frame))):
        return None
    point, surface = (name_of(a) for a in inner.args)
    return None if surface == name_of(frame) else (point, surface, name_of(frame))


def _copy(problem: Problem, constraints: tuple) -> Problem:
    """``problem`` with ``constraints``, its author's answers and mistakes dropped."""
    objectives = tuple(replace(o, expect=None, mistakes=()) for o in problem.objectives)
    return replace(problem, constraints=constraints, objectives=objectives, warnings=())


def _spaced(node: Node) -> str:
    """``node`` as a textbook writes a term, a sum in parentheses with spaced signs."""
    text = textbook(to_text(node, spaced=True))
    return f"({text})" if len(additive_terms(node)) > 1 else text


def _strands(node: Node) -> tuple[int, Node] | None:
    """``(n, X)`` of a term ``n*X`` (or ``X*n``) with a whole number n of 2 or more."""
    if not (isinstance(node, Bin) and node.op == "*"):
        return None
    for count, rest in ((node.left, node.right), (node.right, node.left)):
        if isinstance(count, Num) and count.text.isdigit() and int(count.text) >= 2:
            return int(count.text), rest
    return None


def position_unchosen(problem: Problem) -> Problem | None:
    """``problem`` with the choices of its position-level root (``guesses:`` and ``branch:``
    entries of quantities, not of rates) dropped, for every assembly branch to be found
    again; ``None`` when the spec makes no such choice.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "slotted_arm_crank_coriolis.yaml")
    >>> position_unchosen(problem).guesses
    ()
    """
    guesses = tuple(g for g in problem.guesses if isinstance(g.key.node, Prime))
    branches = tuple(b for b in problem.branches if isinstance(b.key.node, Prime))
    if (guesses, branches) == (problem.guesses, problem.branches):
        return None
    return replace(problem, guesses=guesses, branches=branches)
