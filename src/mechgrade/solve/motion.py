"""The motion of a dynamics problem at many states at once, each a column: the second rates and
reactions from the momentum balances, each column checked and given the error it alone would
raise (:func:`balances`, which :func:`~.dynamics.solve_kinetics` calls with one column), and
solved without the checks for an integration's right-hand side (:func:`accelerations`, which
:mod:`.phases` integrates to every instant). A class of variants (:mod:`.batch`) and an instant
solved alone (:mod:`.dynamics`) are solved here alike.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache, partial
from typing import Callable

import numpy as np

from ..errors import (InconsistentError, Location, MechgradeError, SolveError,
                      UnderdeterminedError)
from ..spec.dynamics import dynamics_of
from ..spec.model import Problem
from ..tolerance import parts
from . import rules
from .columns import (Cramer, FirstErrors, call, least_squares_solution, loud_call,
                      loud_calls)
from .generated import lambdified
from .plan import KinematicsPlan
from .result import ROUND_OFF
from .rules import satisfied


def after_event(p: KinematicsPlan) -> np.ndarray:
    """What the state at an integration's event has known: its coordinates, rates, parameters
    and time."""
    after = np.zeros(p.index.size, dtype=bool)
    after[list(p.index.config)] = True
    after[list(p.index.rates(1))] = True
    return after


def at_event(before: np.ndarray, end: np.ndarray, p: KinematicsPlan) -> np.ndarray:
    """The extended state(s) an event's objectives are read in: everything of ``end`` (the
    state at the event) but its second rates, and those and the reactions of ``before``
    (the balances solved just before it, where the contact checks hold along the way).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve.plan import kinematics_plan
    >>> p = kinematics_plan(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"))
    >>> x = at_event(np.zeros(p.index.size + 1), np.ones(p.index.size), p)
    >>> x[list(p.index.rates(2))].tolist(), float(x[-1])
    ([0.0], 0.0)
    """
    x = before.copy()
    seconds = p.index.rates(2)
    keep = [i for i in range(p.index.size) if i not in seconds]
    x[keep] = end[keep]
    return x


def accelerations(kp, x: np.ndarray, switches: _Switching | None = None,
                  constant: ConstantMatrix | None = None) -> np.ndarray:
    """``x`` (extended states, the unknowns 0, then with ``switches`` each slip's direction)
    with every second rate and reaction solved by least squares, without the checks of
    :func:`balances` (the right-hand side of an integration), in place; NaN where the
    equations are undefined. ``constant``: the balances' matrix of these columns, where it
    reads parameters only (:func:`constant_matrix`). Called with numpy's warnings silenced."""
    count = x.shape[1]
    unknowns, k = kp.columns, len(kp.columns)
    # (a slice where they are side by side, as they are laid out: no index array made)
    cols = slice(unknowns[0], unknowns[0] + k) if k and unknowns[-1] - unknowns[0] == k - 1 \
        else list(unknowns)
    rows_ = len(kp.labels)
    if switches is not None:
        jacobian, residual, args = switches.jacobian, switches.residual, x
    else:
        jacobian, residual = kp.jacobian, kp.residual
        args = x[:len(kp.symbols)]
    if constant is None and switches is None and kp.balances is not None:
        b, A = loud_calls(kp.balances, args, (rows_, rows_ * k))
        A = A.reshape(rows_, k, count)
    else:
        if constant is None:
            A = loud_call(jacobian, args, rows_ * k).reshape(rows_, k, count)
        b = loud_call(residual, args, rows_)
    if constant is not None:
        A = constant.A
        if constant.everywhere and np.isfinite(b.sum()):
            x[cols] = constant.solver.solve(-b)
            return x
    elif np.isfinite(A.sum() + b.sum()):  # (an overflow takes the careful way below)
        x[cols] = least_squares_solution(A, -b)
        return x
    good = np.isfinite(A).all(axis=(0, 1)) & np.isfinite(b).all(axis=0)
    x[cols] = least_squares_solution(np.where(good, A, 0.0), np.where(good, -b, 0.0))
    x[:, ~good] = np.nan
    return x


@dataclass(frozen=True)
class ConstantMatrix:
    """The balances' matrix ``A`` (rows x unknowns x columns) of a motion where it reads
    parameters only (a mass matrix: :attr:`~.dynamics.KineticsPlan.constant_jacobian`),
    evaluated once for every right-hand side of its integration, and what solves with it
    (:class:`~.columns.Cramer`, its products of ``A`` alone made once); ``everywhere``: ``A``
    is finite at every column.

    >>> m = ConstantMatrix.of_matrix(np.array([[[2.0, 4.0]]]))
    >>> m.everywhere, m.of(np.array([1])).A.tolist()
    (True, [[[4.0]]])
    """

    A: np.ndarray
    solver: Cramer
    everywhere: bool

    @classmethod
    def of_matrix(cls, A: np.ndarray) -> ConstantMatrix:
        return cls(A, Cramer(A), bool(np.isfinite(A).all()))

    def of(self, cols: np.ndarray) -> ConstantMatrix:
        """The columns ``cols`` (sorted) only."""
        if len(cols) == self.A.shape[2]:
            return self
        A = self.A[:, :, cols]
        return ConstantMatrix(A, self.solver.of(cols),
                              self.everywhere or bool(np.isfinite(A).all()))


def constant_matrix(kp, x: np.ndarray, switches: _Switching | None = None
                    ) -> ConstantMatrix | None:
    """The balances' matrix (with ``switches``, theirs) at every column of ``x`` (extended
    states, as :func:`accelerations` reads them) where it reads parameters only (``None``
    where it does not): the same all along a motion."""
    if not (switches or kp).constant_jacobian:
        return None
    jacobian, args = (switches.jacobian, x) if switches else (kp.jacobian, x[:len(kp.symbols)])
    rows_, k = len(kp.labels), len(kp.columns)
    return ConstantMatrix.of_matrix(
        loud_call(jacobian, args, rows_ * k).reshape(rows_, k, x.shape[1]))


def reads_parameters_only(matrix, symbols: tuple, index) -> bool:
    """Whether ``matrix`` (sympy) reads no entry of the extended state (``symbols``, laid out
    by ``index``) but its parameters: a balances' Jacobian that is the same all along a motion
    (a mass matrix).

    >>> import sympy as sp
    >>> from mechgrade.solve.index import SymbolIndex
    >>> x, m, t, v, a = sp.symbols("x m t v a")
    >>> index = SymbolIndex(("x", "m", "t", "x'", "x''"), ("x",), ("m",), source=None)
    >>> [reads_parameters_only(sp.Matrix([e]), (x, m, t, v, a), index) for e in (-m, -m * x)]
    [True, False]
    """
    parameters = {s for i, s in enumerate(symbols[:index.size]) if index.is_parameter(i)}
    return matrix.free_symbols <= parameters


@dataclass(frozen=True)
class Balanced:
    """The extended states (state values, then reactions; one column each) with the second
    rates (or the rates just after an impact) and the reactions solved, and each column's
    error (``None`` where it has none)."""

    x: np.ndarray
    errors: FirstErrors

    @property
    def ok(self) -> np.ndarray:
        return self.errors.ok


def balances(problem: Problem, kp, X: np.ndarray, known: np.ndarray) -> Balanced:
    """The unknown second rates and reactions of every column of ``X`` (state values, those
    ``known`` given) solved from the momentum balances, each column checked: a kinetic
    friction needs slip, the givens their physical bounds, the equations must be defined,
    determine the unknowns and all hold, the solution its physical bounds, a contact must push
    and a static friction keep ``|F| <= mu N``. A column's error is the first check it fails.
    """
    n = X.shape[1]
    reactions = len(kp.kin.reactions)
    x = np.concatenate([X, np.zeros((reactions, n))])
    known = np.concatenate([known, np.zeros(reactions, bool)])
    cols = [j for j, i in enumerate(kp.columns) if not known[i]]
    for j in cols:
        x[kp.columns[j]] = 0.0
    errors = FirstErrors(n)
    for slip, speed, _ in kp.slips:
        errors.add(~(call(speed, x, 1)[0] > ROUND_OFF), partial(_no_slip, slip))
    _physical(kp, x, errors, given=True)
    rows_ = len(kp.labels)
    A = call(kp.jacobian, x, rows_ * len(kp.columns)).reshape(rows_, len(kp.columns), n)
    A = A[:, cols]
    b = call(kp.residual, x, rows_)
    defined = np.isfinite(A).all(axis=1) & np.isfinite(b)  # rows x columns

    errors.add(~defined.all(axis=0), lambda i: undefined_balances(kp, defined[:, i]))
    ok = errors.ok
    Ab = np.where(ok, A, 0.0).transpose(2, 0, 1)
    U, s, Vt = np.linalg.svd(Ab, full_matrices=False)
    rank = rules.rank(s)

    def underdetermined(i: int) -> MechgradeError:
        a = A[:, :, i]
        null = rules.null_space(a)
        open_ = [cols[j] for j, is_open in enumerate(rules.left_open(null).tolist()) if is_open]
        names = [kp.name(j) for j in open_]
        held = set(np.flatnonzero(parts(a[:, [cols.index(j) for j in open_]],
                                        np.abs(a).max(initial=0.0)).any(axis=1)).tolist())
        involved = sorted({label.split(":")[0] for r, label in enumerate(kp.labels) if r in held})
        kind = "statically indeterminate" if any(kp.columns[j] >= kp.kp.index.size
                                                 for j in open_) else "under-constrained"
        return UnderdeterminedError(
            f"the model is {kind}: the momentum balances ({', '.join(involved)}) do not "
            f"determine {', '.join(names)}; remove a redundant reaction or add a constraint",
            where=_body_where(problem, involved))

    errors.add(ok & (rank < len(cols)), underdetermined)
    ok = errors.ok
    with np.errstate(all="ignore"):
        inverse = rules.inverted(s, rows_, len(cols))
        coeff = np.einsum("nmk,mn->nk", U, -np.where(ok, b, 0.0)) * inverse
        sol = np.einsum("nkj,nk->jn", Vt, coeff)
    for j, value in zip(cols, sol):
        x[kp.columns[j]] = value
    r = call(kp.residual, x, rows_)
    scale = np.abs(call(kp.scale, x, rows_))
    holds = satisfied(r, scale, problem.consistency)

    def inconsistent(i: int) -> MechgradeError:
        k = int(np.flatnonzero(~holds[:, i])[0])
        return InconsistentError(
            f"the equations of motion cannot all hold: '{kp.labels[k]}' is off by "
            f"{r[k, i]:.4g} (terms of size {scale[k, i]:.4g}); a reaction may be missing from "
            "the loads, or a given second rate contradicts them", where=kp.wheres[k])

    errors.add(~holds.all(axis=0), inconsistent)
    _physical(kp, x, errors, given=False)
    with np.errstate(invalid="ignore"):
        for slip, _, normal in kp.slips:
            nn = call(normal, x, 1)[0]
            errors.add(~rules.pushes(nn), partial(_lost, slip, nn))
        for bound, tangential, normal, mu in kp.bounds:
            f = np.linalg.norm(call(tangential, x, 3), axis=0)
            nn = call(normal, x, 1)[0]
            m = call(mu, x, 1)[0]
            errors.add(~rules.pushes(nn), partial(_lost, bound, nn))
            errors.add(~rules.sticks(f, nn, m), partial(_slips, bound, f, nn, m))
    return Balanced(x, errors)


def undefined_balances(kp, defined: np.ndarray) -> SolveError:
    """The error of momentum balances undefined at an instant (``defined``: which of the rows
    of ``kp``'s are), naming the first that is not.

    >>> from types import SimpleNamespace
    >>> kp = SimpleNamespace(labels=["body B: x", "body B: y"], wheres=[None, None])
    >>> print(undefined_balances(kp, np.array([True, False])))
    the equations of motion are undefined at this instant (a division by zero in 'body B: y')
    """
    bad = int(np.flatnonzero(~defined)[0])
    return SolveError(f"the equations of motion are undefined at this instant (a division by "
                      f"zero in '{kp.labels[bad]}')", where=kp.wheres[bad])


def _no_slip(slip, _: int) -> SolveError:
    return SolveError(f"kinetic friction '{slip.name}' needs the contact at {slip.point} to "
                      "slip, but its slip velocity is zero at this instant; use 'kind: static'",
                      where=slip.where)


def _lost(contact, normal: np.ndarray, i: int) -> SolveError:
    return SolveError(f"contact lost at {contact.point}: the normal force would be "
                      f"{normal[i]:.4g} N (pulling)", where=contact.where)


def _slips(bound, friction: np.ndarray, normal: np.ndarray, mu: np.ndarray,
           i: int) -> SolveError:
    f, n = friction[i], normal[i]
    needed = f / n if n > 0 else np.inf
    return SolveError(f"the {bound.body} slips at {bound.point}: sticking needs mu >= "
                      f"{needed:.4g} (friction {f:.4g} N against a normal force of {n:.4g} N), "
                      f"but mu = {mu[i]:.4g}", where=bound.where)


def _physical(kp, x: np.ndarray, errors: FirstErrors, *, given: bool) -> None:
    """The physical bounds (:mod:`mechgrade.mechanics.loads`) at every column: those of the
    givens (a mass, mu, e) or those of the solution (a contact pushes, a string pulls)."""
    for bound, f in kp.physical:
        if bound.given == given:
            values = call(f, x, 1)[0]
            errors.add(~np.array([bound.holds(v) for v in values], dtype=bool),
                       partial(_unphysical, bound, values))


def _unphysical(bound, values: np.ndarray, i: int) -> SolveError:
    return SolveError(bound.message(float(values[i])), where=bound.where)


def _body_where(problem: Problem, involved) -> Location:
    for b in dynamics_of(problem).bodies:
        if involved and involved[0] == f"body {b.name}":
            return b.where
    return Location()


@dataclass(frozen=True)
class _Switching:
    """The kinetics with each ``|u|`` and ``sign(u)`` read with a direction given beside the
    state (one per ``u``, the *mode*: ``|u|`` as ``mode * u``): the equations of the motion
    before a slip ends, continued smoothly past it. ``speeds`` gives every ``u``."""

    speeds: Callable
    residual: Callable
    jacobian: Callable
    count: int
    constant_jacobian: bool  # it reads parameters only (no mode): the same all along


def gathered(e, u):
    """``e`` (a sympy expression) as ``rest + over * u/|u|``: its terms over ``|u|`` (a kinetic
    friction's direction ``u/|u|``, which the balances write expanded) summed and divided by
    ``u``; ``over`` is ``None`` where no term is over ``|u|``. Written so, the direction keeps
    its digits where the slip ``u`` is small beside the speeds it is the difference of.

    >>> import sympy as sp
    >>> a, b, N = sp.symbols("a b N")
    >>> gathered(N*a/sp.Abs(a - b) - N*b/sp.Abs(a - b) + 1, a - b)
    (1, N)
    """
    import sympy as sp

    parts = sp.collect(e, 1 / sp.Abs(u), evaluate=False) if e.is_Add else {}
    over = parts.pop(1 / sp.Abs(u), None)
    if over is None:
        return e, None
    return sp.Add(*(k * v for k, v in parts.items())), sp.cancel(over / u)


def cheaper(compact, expanded):
    """Whichever of two forms of the balances (sympy matrices: ``compact`` as derived, each
    load's force one product, a spring's ``k l (1 - a/|l|)``; ``expanded``) has fewer
    operations once its common subexpressions are taken out, as :func:`.generated.lambdified`
    compiles it; ``expanded`` on a tie.

    >>> import sympy as sp
    >>> k, l, a = sp.symbols("k l a")
    >>> force = sp.Matrix([k*l*(1 - a/sp.Abs(l))])
    >>> cheaper(force, force.applyfunc(sp.expand)) == force
    True
    """
    return compact if _operations(compact) < _operations(expanded) else expanded


def _operations(exprs) -> int:
    import sympy as sp

    replacements, reduced = sp.cse(exprs)
    return sp.count_ops([v for _, v in replacements] + reduced)


@lru_cache(maxsize=64)
def _switches(kp, at_end: bool = False) -> _Switching | None:
    """The kinetics of ``kp`` with their switches read as :class:`_Switching` says; ``None``
    when nothing switches. ``at_end``: with the terms over each ``|u|`` gathered and divided
    by ``u`` first, so that a direction ``u/|u|`` written as a sum (``N mu (R psi' +
    xb')/|u|`` expanded) is defined where its slip ends, ``u = 0`` (where a switch is
    located); the integration keeps the terms as the balances write them (its values are
    those of the model's own equations)."""
    import sympy as sp

    constraints = [e.expr for e in kp.kin.constraints]
    exprs = [e.expr for e in kp.kin.balances] + constraints
    speeds: list = []
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, (sp.Abs, sp.sign)) and node.args[0] not in speeds:
                speeds.append(node.args[0])
    if not speeds:
        return None
    modes = sp.symbols(f"_mode0:{len(speeds)}")
    table = dict(zip(speeds, modes))

    def switching(a) -> bool:
        return isinstance(a, (sp.Abs, sp.sign)) and sp.expand(a.args[0]) in table

    def kept(e):
        for u, mode in table.items() if at_end else ():
            rest, over = gathered(e, u)
            if over is not None:
                e = rest + over / mode
        # (a speed as the expanded balances write it: the compact form's expands to it)
        return e.replace(switching, lambda a: table[sp.expand(a.args[0])] * (
            a.args[0] if isinstance(a, sp.Abs) else 1))

    matrix = sp.Matrix([kept(e) for e in exprs])
    unknowns = [kp.symbols[i] for i in kp.columns]
    symbols = (*kp.symbols, *modes)
    jacobian = matrix.jacobian(unknowns)
    # the integration's right-hand side as the balances were derived where that is cheaper;
    # the end of a slip keeps its directions gathered (defined where u = 0)
    residual = matrix if at_end else cheaper(
        sp.Matrix([kept(e) for e in (*kp.kin.compact_balances, *constraints)]), matrix)
    return _Switching(
        speeds=lambdified(kp.symbols, speeds),
        residual=lambdified(symbols, residual),
        jacobian=lambdified(symbols, jacobian),
        count=len(speeds),
        constant_jacobian=reads_parameters_only(jacobian, kp.symbols, kp.kp.index))
