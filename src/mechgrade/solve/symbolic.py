"""Symbolic objectives: the objective solved with sympy, level by level, in the symbols the
objective declares (givens that are pure numbers may stand in; givens with units may not)."""

from __future__ import annotations

import math
from functools import lru_cache

import sympy as sp

from ..errors import SolveError, UnderdeterminedError
from ..expressions.syntax import Name, Prime
from ..mechanics import Kinematics
from ..mechanics.dynamics import derive_kinetics
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
    where its rate reaches the answer, :func:`energy_equations`). A given of any
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


def solved_symbolically(problem: Problem, objective_id: str, givens: tuple, expr=None):
    """The objective (or ``expr`` of it, such as its ``when``, with no symbol declared) with
    the unknown second rates and reactions replaced by their symbolic solution of the
    momentum balances (zero givens and given second rates stand in)."""
    kin = derive_kinetics(problem)
    k = kin.k
    declared = set() if expr is not None else \
        {k.quantity(node) for node in
         symbol_meanings(problem, problem.objective(objective_id)).values()}
    expr = kin.objective(objective_id) if expr is None else expr
    stand_in = {}
    for _, (node, si, _) in givens:
        if isinstance(node, (Name, Prime)):
            symbol = k.quantity(node)
            if symbol in declared:
                continue
            if si == 0 or symbol in kin.rates:
                stand_in[symbol] = sp.nsimplify(si) if si == 0 else sp.Float(si)
    unknowns = [s for s in (*kin.rates, *kin.reactions) if s not in stand_in]
    # declared rates stay symbols (the velocities after an impact in a projected balance)
    if not (expr.free_symbols if not isinstance(expr, sp.MatrixBase)
            else set().union(*(e.free_symbols for e in expr))) & (set(unknowns) - declared):
        return expr
    equations = tuple(e.expr.xreplace(stand_in) for e in (*kin.balances, *kin.constraints))
    # a declared second rate (phidd of a driven turntable) is known, unless the balances
    # determine it
    solution = _linear_solve(equations, tuple(u for u in unknowns if u not in declared)) or \
        _linear_solve(equations, tuple(unknowns))
    if solution is None:
        names = {s: label for s, label in zip(kin.reactions, kin.labels)}
        listing = ", ".join(names.get(u, str(u)) for u in unknowns)
        raise UnderdeterminedError(
            f"objective '{objective_id}' cannot be solved symbolically: the momentum balances "
            f"do not determine the unknowns {listing} uniquely (or contradict each other)",
            where=problem.objective(objective_id).where)
    return expr.xreplace(stand_in).xreplace(solution)


def energy_equations(problem: Problem, objective_id: str) -> tuple:
    """What of a work–energy analysis a symbolic objective's answer can be read from: the
    energy integral and its start (and the objective's ``when`` equation), where the rate the
    integral gives reaches the answer: the objective is asked ``when``, or an undeclared rate
    is left in it once solved from the momentum balances with nothing standing in (a zero
    given only removes terms from that solution, or leaves it to all the unknowns: both are
    looked at). Empty where it does not reach it: the eom, a reaction in the declared rate.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> ladder = load_problem(shipped_dir("problems") / "ruina_9_19_falling_ladder.yaml")
    >>> energy_equations(ladder, "eom_thetaddot")
    ()
    >>> sorted({str(s) for e in energy_equations(ladder, "N1_wall_of_theta")
    ...         for s in e.free_symbols})
    ['L', 'g', 'm', 'theta', 'theta0', 'thetad']
    """
    kin = derive_kinetics(problem)
    whens = dict(kin.whens)
    energy = (kin.energy, *(value for _, value in kin.start))
    if objective_id in whens:
        return (*energy, whens[objective_id])
    declared = {kin.k.quantity(node) for node in
                symbol_meanings(problem, problem.objective(objective_id)).values()}
    try:
        solved = [solved_symbolically(problem, objective_id, ())]
    except UnderdeterminedError:
        return energy
    objective = kin.objective(objective_id)
    equations = tuple(e.expr for e in (*kin.balances, *kin.constraints))
    everything = _linear_solve(equations, tuple((*kin.rates, *kin.reactions))) \
        if equations else None
    if everything is not None:
        solved.append(objective.xreplace(everything))
    free: set = set()
    for expr in solved:
        free |= set().union(*(e.free_symbols for e in expr)) \
            if isinstance(expr, sp.MatrixBase) else expr.free_symbols
    return energy if free & (set(kin.k.qd) - declared) else ()


@lru_cache(maxsize=128)
def _linear_solve(equations: tuple, unknowns: tuple):
    A, b = sp.linear_eq_to_matrix(list(equations), list(unknowns))
    solutions = sp.linsolve((A, b), list(unknowns))
    if not solutions:
        return None
    (values,) = solutions
    if any(v.free_symbols & set(unknowns) for v in values):
        return None
    return dict(zip(unknowns, values))


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
