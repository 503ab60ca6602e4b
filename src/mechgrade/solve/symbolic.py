"""Symbolic objectives: the objective solved with sympy, level by level, in the symbols the
objective declares (givens that are pure numbers may stand in; givens with units may not)."""

from __future__ import annotations

import math
from functools import lru_cache

import sympy as sp

from ..errors import SolveError, UnderdeterminedError
from ..expressions.syntax import Name, Prime
from ..mechanics import Kinematics
from ..spec.dynamics import WorkEnergy
from ..spec.model import Objective, Problem
from ..spec.validate import symbol_meanings
from ..units import si_unit


def symbolic(problem: Problem, k: Kinematics, objective: Objective, givens: dict, expr=None):
    """The objective (or ``expr``, a mistaken reading of it, in the model's plain symbols)
    solved in the objective's symbols, and the symbols' meanings."""
    meanings = symbol_meanings(problem, objective)
    declared = {name: k.quantity(node) for name, node in meanings.items()}
    given_symbols = {}
    for key, (node, si, given) in givens.items():
        if isinstance(node, (Name, Prime)):
            try:
                given_symbols[k.quantity(node)] = (key, si, given)
            except KeyError:
                raise SolveError(f"cannot give '{key}': not a coordinate, rate, parameter "
                                 "or t of this problem") from None
    known = set(declared.values()) | set(given_symbols)
    # A zero is a zero in every unit: such givens may always stand in.
    zeros = {sym: sp.Integer(0) for sym, (_, si, _) in given_symbols.items()
             if si == 0 and sym not in declared.values()}
    expr = _simplify((k.objective(objective.id) if expr is None else expr).xreplace(zeros))
    for _level, rates, equations in ((2, k.qdd, k.acceleration), (1, k.qd, k.velocity),
                                    (0, k.q, k.position)):
        unknown = [s for s in rates if s not in known]
        needed = [str(u) for u in unknown if u in expr.free_symbols]
        if not needed:
            continue
        eqs = [e.expr.xreplace(zeros) for e in equations]
        solution = sp.solve(eqs, unknown, dict=True) if eqs else []
        if len(solution) != 1:
            reason = ("several solutions" if solution else
                      "no constraint fixes it" if not eqs else "no solution")
            raise UnderdeterminedError(
                f"objective '{objective.id}' cannot be solved symbolically for "
                f"{', '.join(needed)} ({reason}); declare it among the symbols or give it",
                where=objective.where)
        expr = _simplify(expr.xreplace(solution[0]))
    # Pure-number givens (angles, tooth counts) may stand in; givens with units may not.
    extra = {}
    for sym in expr.free_symbols - set(declared.values()):
        entry = given_symbols.get(sym)
        if entry is not None and (entry[2] is None or si_unit(entry[2].unit) in ("", "rad")):
            extra[sym] = _exact(entry)
    if extra:
        expr = _simplify(expr.xreplace(extra))
    leftover = expr.free_symbols - set(declared.values())
    if leftover:
        names = ", ".join(sorted(str(s) for s in leftover))
        raise SolveError(f"symbolic objective '{objective.id}' depends on {names}, which is "
                         f"not among its symbols ({', '.join(declared)}); add it to symbols",
                         where=objective.where)
    rename = {sym: sp.Symbol(name, **sym.assumptions0) for name, sym in declared.items()}
    return expr.xreplace(rename), meanings


def bearing_givens(problem: Problem, objective_id: str) -> frozenset[str] | None:
    """The quantities (as givens name them: ``mu_s``, ``phi'``) a symbolic objective's answer
    can be read from: those in the objective, the constraints it is solved with (and, in
    dynamics, the momentum balances; under work-energy, the energy integral and its start
    where its rate reaches the answer, :func:`~.dynamics.energy_equations`). A given of any
    other quantity cannot change the answer, whatever its value. ``None`` where an
    analysis reaches the instant by other equations of its own (an integration, an impulse,
    a design): every given may bear on it then.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> problem = load_problem(shipped_dir("problems") / "block_on_turntable.yaml")
    >>> sorted(bearing_givens(problem, "mu_needed_symbolic"))
    ['g', 'm', 'phi', "phi'", "phi''", 'r']
    """
    from ..mechanics import derive

    equations: list = []
    if problem.dynamics is not None:
        analysis = problem.dynamics.analysis
        if not isinstance(analysis, WorkEnergy | None) or problem.dynamics.design is not None:
            return None
        from ..mechanics.dynamics import derive_kinetics
        from .dynamics import energy_equations

        kin = derive_kinetics(problem)
        k = kin.k
        equations += [kin.objective(objective_id),
                      *(e.expr for e in (*kin.balances, *kin.constraints))]
        if analysis is not None:
            equations += energy_equations(problem, objective_id)
    else:
        k = derive(problem)
        equations.append(k.objective(objective_id))
    equations += [e.expr for e in (*k.position, *k.velocity, *k.acceleration)]
    free: set = set()
    for expr in equations:
        free |= expr.free_symbols if isinstance(expr, sp.Basic) else set()
    names = {k.time: "t", **{sym: name for name, sym in k.parameters}}
    for name, q, qd, qdd in zip(k.coordinates, k.q, k.qd, k.qdd):
        names.update({q: name, qd: f"{name}'", qdd: f"{name}''"})
    return frozenset(name for sym, name in names.items() if sym in free)


@lru_cache(maxsize=1024)
def _simplify(expr):
    # kept: the variants of a class often meet the same expression again (a given's value
    # that does not reach the answer changes nothing in it), and simplify is the slow step
    if sp.count_ops(expr) > 300:
        return expr
    simple = sp.simplify(expr)
    return simple if sp.count_ops(simple) <= sp.count_ops(expr) else expr


def _exact(entry) -> sp.Expr:
    _key, si, given = entry
    if given is None:
        return sp.Float(si)
    value = sp.Rational(repr(given.value)) if math.isfinite(given.value) else sp.Float(si)
    unit = given.unit
    if unit in ("deg", "degree"):
        return value * sp.pi / 180
    if unit in ("", "rad", "radian"):
        return value
    return sp.Float(si)
