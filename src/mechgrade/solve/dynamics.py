"""Solve a dynamics problem at an instant: the kinematics gives the configuration and the rates,
then the momentum balances and the acceleration-level constraints, linear in the unknown
second rates and reactions (the ``[M C^T; C 0]`` system), are solved together.

Every step is checked: a rank-deficient system (under-constrained or statically indeterminate)
is an error naming the unknowns it leaves open and the bodies they act on; equations the
solution does not satisfy (a missing reaction, a given q'' that contradicts the loads) are an
error naming the balance; a kinetic-friction contact needs slip and a pressing normal force; a
static-friction force must satisfy |F| <= mu N, else the contact slips and the message says how
large mu would have to be.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> solution = solve_dynamics(load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml"))
>>> round(solution.result("alpha").value, 4), solution.result("eom_symbolic").expr
(-7.8822, '-3*g*sin(theta)/(2*L)')
"""

from __future__ import annotations

import warnings
import weakref

from dataclasses import dataclass, replace
from functools import lru_cache, partial
from typing import Callable, Collection, Mapping, Sequence

import numpy as np
import sympy as sp

# scipy is imported by the functions that use it: it takes longer to import than a whole
# `mechgrade check` of most problems, which never needs it.

from ..errors import AuthorWarning, Location, MechgradeError, SolveError
from ..mechanics.dynamics import FrictionBound, Kinetics, Slip, derive_kinetics, read_kinetics
from ..mechanics.loads import PhysicalBound
from ..expressions.syntax import Name, Prime
from ..mechanics.junctions import kinematic_part
from ..mechanics.kinematics import locations
from ..spec.model import ObjectiveKind, Problem
from ..spec.validate import symbol_meanings
from ..spec.dynamics import (Integration, WorkEnergy, dynamics_of, instant_of_objective,
                             unchecked)
from .analysis import analysis_of
from .columns import WithInputs
from .generated import lambdified
from .events import integrated_symbolically
from .motion import accelerations as columns_accelerations
from .motion import (after_event, at_event, balances, cheaper, gathered,
                     reads_parameters_only)
from .work_energy import energy_rate_symbolic, energy_state
from . import rules
from .instant import Reached, drive, read_objectives, symbolic_dependence
from .phases import (Entry, Target, Until, When, asked_when, gripping, reach, reach_columns,
                     stacked)
from .levels import State, place_givens
from .numeric import solve_numeric
from .index import SymbolIndex
from .plan import KinematicsPlan, _OnFirstCall, kinematics_plan, per_problem
from .positions import position_symbolic, positions_where, which_root, without_position
from .result import ObjectiveResult, Solution
from .symbolic import solved_symbolically, symbolic


def kinematic_problem(problem: Problem) -> Problem:
    """The problem's kinematics alone, its massless junctions' balances among its constraints
    (its objectives are read by the dynamics language); the same object for the same problem,
    so that what is kept per problem (:func:`~.plan.per_problem`) is found by every solve."""
    return per_problem(kinematic_part, problem)


@dataclass(frozen=True)
class KineticsPlan:
    """The lambdified kinetics: the system ``A(state) x = rhs(state)`` in the unknown second
    rates and reactions (``residual`` is the equations with every unknown in place), objectives,
    mistakes and friction checks, each a function of ``state values + reactions``."""

    kin: Kinetics
    kp: KinematicsPlan
    symbols: tuple[sp.Symbol, ...]
    columns: tuple[int, ...]  # positions of the unknowns in the extended state
    residual: Callable
    jacobian: Callable
    scale: Callable
    labels: tuple[str, ...]
    wheres: tuple[Location, ...]
    objectives: tuple[tuple[str, Callable], ...]
    mistakes: tuple[tuple[str, tuple[Callable, ...]], ...]
    bounds: tuple[tuple[FrictionBound, Callable, Callable, Callable], ...]
    slips: tuple[tuple[Slip, Callable, Callable], ...]
    requirements: tuple[tuple[str, str, Callable], ...] = ()
    design: Callable | None = None
    physical: tuple[tuple[PhysicalBound, Callable], ...] = ()
    constant_jacobian: bool = False  # it reads parameters only: constant along a motion
    # the residual and the Jacobian as one function, their common subexpressions made once
    # (an integration's right-hand side, where the Jacobian changes along the motion)
    balances: Callable | None = None

    def name(self, column: int) -> str:
        """How an unknown is named in messages."""
        i = self.columns[column]
        n = self.kp.index.size
        if i >= n:
            return self.kin.labels[i - n]
        return self.kp.index.spelling(i)


def _balance_functions(kin: Kinetics, symbols, unknowns, index: SymbolIndex) -> dict:
    """The plan's ``residual``, ``jacobian`` and ``scale`` of ``kin``'s balances and
    constraints, and whether the Jacobian reads parameters only (``index`` lays out
    ``symbols``); an impact's of its rates before too, worked out from the state
    (:class:`~.columns.WithInputs`: a model with other rates before is another ``inputs``)."""
    # the rates before named apart from the state's symbols: a Dummy argument would make
    # lambdify rename every argument in every expression
    taken = {str(s) for s in symbols}
    named = {}
    for i, dummy in enumerate(kin.before.symbols if kin.before is not None else ()):
        name = f"before_{i}"
        while name in taken:
            name = f"_{name}"
        named[dummy] = sp.Symbol(name)
    before = tuple(named.values())
    constraints = [e.expr for e in kin.constraints]
    exprs = sp.Matrix([e.expr for e in kin.written] + constraints).xreplace(named)
    scale = sp.Matrix([sum((sp.Abs(t) for t in sp.Add.make_args(e)), sp.Integer(0))
                       for e in exprs])
    # a kinetic friction's direction u/|u| evaluated as one quotient: as the balances write
    # it (expanded, mu N xd/|xd - Xd| - mu N Xd/|xd - Xd|) it loses the digits of a slip
    # small beside the speeds, where an event's accelerations are read (just before the slip
    # ends)
    slips = [s.speed.args[0] for s in kin.slips if isinstance(s.speed, sp.Abs)]
    whole = partial(_directions_whole, slips)
    exprs = exprs.applyfunc(whole)
    jacobian = exprs.jacobian(unknowns)
    compact = sp.Matrix(list(kin.compact) + constraints).xreplace(named).applyfunc(whole)
    residual = cheaper(compact, exprs)
    out = {name: lambdified(symbols + before, f) for name, f in zip(
        _BALANCE_FUNCTIONS, (residual, jacobian, scale))}
    if kin.before is None:
        constant = reads_parameters_only(jacobian, symbols, index)
        return {**out, "constant_jacobian": constant,
                "balances": None if constant else _OnFirstCall(symbols, [residual, jacobian])}
    rates = lambdified(symbols, kin.before.values)
    return {name: WithInputs(f, rates) for name, f in out.items()}


def _directions_whole(speeds: list, e: sp.Expr) -> sp.Expr:
    """``e`` with its terms over each ``|u|`` of ``speeds`` (kinetic frictions' slips) written
    ``over * u/|u|`` (:func:`~.motion.gathered`)."""
    for u in speeds:
        rest, over = gathered(e, u)
        if over is not None:
            e = rest + over * u / sp.Abs(u)
    return e


_BALANCE_FUNCTIONS = ("residual", "jacobian", "scale")


def kinetics_plan(problem: Problem) -> KineticsPlan:
    """Derive and lambdify ``problem``'s kinetics once."""
    shared = _SHARED.get(id(problem))
    if shared is not None and shared[0]() is problem:
        return shared[1]
    return _kinetics_plan(problem, locations(problem))


# A plan shared with a copy lives as long as the copy: the caches that keep a copy (its
# mistaken models' lru_caches) never find it forgotten, and a copy's death frees its plan.
_SHARED: dict[int, tuple[weakref.ref[Problem], KineticsPlan]] = {}


def share_kinetics(copy: Problem, source: Problem) -> bool:
    """Let ``copy``, ``source`` as a student's mistaken model of it (its loads unchecked, a
    static friction an unknown force: :func:`~mechgrade.spec.dynamics.unchecked`; its
    author's answers and mistakes dropped, nothing else changed), be solved with ``source``'s
    derivation and functions, without its physical bounds, friction bounds and author's
    mistakes (what the unchecked derivation leaves out: the same unknowns and balances);
    whether it is such a copy."""
    if copy.dynamics is None or source.dynamics is None or replace(
            copy, objectives=()) != replace(source, objectives=(),
                                            dynamics=unchecked(source.dynamics)) \
            or copy.objectives != tuple(replace(o, expect=None, mistakes=())
                                        for o in source.objectives):
        return False
    plan = kinetics_plan(source)
    _share(copy, replace(plan, kin=replace(plan.kin, bounds=(), physical=()), bounds=(),
                         physical=(), mistakes=()))
    return True


def read_in(problem: Problem, source: Problem) -> None:
    """Let ``problem``, ``source`` with other objectives (or event, or rates before its
    impact), be solved with ``source``'s balances and functions: only its objectives derived
    and lambdified (:func:`~mechgrade.mechanics.dynamics.read_kinetics`)."""
    plan = kinetics_plan(source)
    kin = read_kinetics(problem, source, plan.kin)
    if kin is None:
        return
    if kin.before is not None and kin.before is not plan.kin.before:
        # other rates before the impact: the same balances, other inputs
        rates = lambdified(plan.symbols, kin.before.values)
        plan = replace(plan, **{name: replace(getattr(plan, name), inputs=rates)
                                for name in _BALANCE_FUNCTIONS})
    _share(problem, replace(plan, kin=kin, **_objective_functions(problem, kin, plan.symbols,
                                                                   plan)))


def _share(problem: Problem, plan: KineticsPlan) -> None:
    key = id(problem)
    _SHARED[key] = (weakref.ref(problem, lambda _: _SHARED.pop(key, None)), plan)


@lru_cache(maxsize=64)
def _kinetics_plan(problem: Problem, _locations: tuple) -> KineticsPlan:
    kin = derive_kinetics(problem)
    kp = kinematics_plan(kinematic_problem(problem))
    symbols = kp.index.symbols + kin.reactions
    level = 1 if kin.impact else 2
    columns = tuple(kp.index.rates(level)) + tuple(range(kp.index.size, len(symbols)))
    equations = kin.written + kin.constraints
    unknowns = [symbols[i] for i in columns]
    return KineticsPlan(
        kin=kin, kp=kp, symbols=symbols, columns=columns,
        **_balance_functions(kin, symbols, unknowns, kp.index),
        labels=tuple(e.label for e in equations), wheres=tuple(e.where for e in equations),
        bounds=tuple((b, lambdified(symbols, b.tangential), lambdified(symbols, b.normal),
                      lambdified(symbols, b.mu)) for b in kin.bounds),
        slips=tuple((s, lambdified(symbols, s.speed), lambdified(symbols, s.normal))
                    for s in kin.slips),
        design=lambdified(symbols, kin.design) if kin.design is not None else None,
        physical=tuple((b, lambdified(symbols, b.expr)) for b in kin.physical),
        **_objective_functions(problem, kin, symbols))


def _objective_functions(problem: Problem, kin: Kinetics, symbols,
                         source: KineticsPlan | None = None) -> dict:
    """The plan's functions of ``problem``'s numeric objectives (their values, author's
    mistakes and requirements) in ``kin``: those of ``source`` (a plan of the same balances)
    where it has one of the same expression."""
    numeric = {o.id for o in problem.objectives if o.kind != ObjectiveKind.SYMBOLIC}
    known: list[tuple[object, Callable]] = []
    if source is not None:
        done = dict(source.objectives)
        known = [(e, done[oid]) for oid, e in source.kin.objectives if oid in done]
        known += [(e, f) for (oid, exprs_), (_, fs) in zip(source.kin.mistakes, source.mistakes)
                  for e, f in zip(exprs_, fs)]
        known += [(e, f) for (_, _, e), (_, _, f) in zip(source.kin.requirements,
                                                          source.requirements)]

    def function(expr) -> Callable:
        return next((f for e, f in known if e is expr or e == expr), None) \
            or lambdified(symbols, expr)

    return dict(
        objectives=tuple((oid, function(e)) for oid, e in kin.objectives if oid in numeric),
        mistakes=tuple((oid, tuple(function(e) for e in exprs_))
                       for oid, exprs_ in kin.mistakes if oid in numeric),
        requirements=tuple((oid, reason, function(expr))
                           for oid, reason, expr in kin.requirements))


def _call(f: Callable, x: np.ndarray) -> np.ndarray:
    with np.errstate(all="ignore"):
        return np.asarray(f(*x), dtype=float).ravel()


def solve_kinetics(problem: Problem, kp: KineticsPlan, state: State) -> np.ndarray:
    """The extended state (state values, then reactions) with the unknown second rates and
    reactions solved from the momentum balances; raises when they are not determined, the
    equations cannot all hold, or a friction contact contradicts its model (the checks of
    :func:`~.motion.balances`, with one column)."""
    solved = balances(problem, kp, state.values[:, None], state.given)
    error = solved.errors[0]
    if error is not None:
        raise error
    return solved.x[:, 0]


def accelerations(kp: KineticsPlan, values: np.ndarray) -> np.ndarray:
    """The extended state with every second rate and reaction solved by least squares, without
    the checks of :func:`solve_kinetics` (:func:`~.motion.accelerations` with one column);
    raises where the equations are undefined."""
    x = np.concatenate([values, np.zeros(len(kp.kin.reactions))])
    x[list(kp.columns)] = 0.0
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        x = columns_accelerations(kp, x[:, None])[:, 0]
    if not np.isfinite(x[list(kp.columns)]).all():
        raise SolveError("the equations of motion became undefined during the integration "
                         "(a division by zero)", where=problem_where(kp))
    return x


def problem_where(kp: KineticsPlan) -> Location:
    return kp.wheres[0] if kp.wheres else Location()


# ---------------------------------------------------------------------------- entry point


def solve_dynamics(problem: Problem, *, givens: Mapping[str, float | None] | None = None,
                   objectives: Collection[str] | None = None) -> Solution:
    """Like :func:`mechgrade.solve.solve`, for a problem with bodies and loads."""
    return drive(problem, kinetic_reach(problem), givens, objectives)


BalancesSolver = Callable[[Problem, KineticsPlan, State], np.ndarray]
"""How the momentum balances are solved at a state: :func:`solve_kinetics`, or with each
given second rate held by a drive (:func:`~.carried.carried_kinetics`)."""


@dataclass(frozen=True)
class Arrived:
    """Where a kind of :class:`KineticInstant` reaches an instant: the state there, the
    extended state the objectives are read from (second rates and reactions solved), the
    kinematics' warnings, and for an integration the extended state just before its event
    (:func:`~.events.at_the_event`), else ``None``; ``phase``, the problem whose model holds
    at the instant when it is not the problem's own (a contact gripping: :mod:`.phases`)."""

    state: State
    x: np.ndarray
    warnings: tuple[AuthorWarning, ...] = ()
    before: np.ndarray | None = None
    phase: Problem | None = None  # the model that holds there, when not the problem's own


@dataclass(frozen=True)
class KineticInstant:
    """A dynamics problem's instants (:class:`~.instant.Reach`) with its rates given: the
    kinematics at the givens, then the momentum balances. The other kinds of reaching an
    instant are its subclasses (:class:`WorkEnergyInstant`, :class:`IntegratedInstant`,
    :class:`DesignedInstant`), :func:`kinetic_reach` picks one; its generated mistakes are
    worked out once for the whole solution (:mod:`.dynamics_mutants`). Each kind solves the
    momentum balances where it reaches a state with ``balances`` (:data:`BalancesSolver`)."""

    source: Problem
    problem: Problem  # its kinematics (kinematic_problem)
    kinetics: KineticsPlan
    balances: BalancesSolver = solve_kinetics

    @property
    def plan(self) -> KinematicsPlan:
        return self.kinetics.kp

    @property
    def warnings(self) -> tuple[AuthorWarning, ...]:
        return tuple(self.plan.k.warnings)

    def arrive(self, given_map: dict, asked_at: str | When | None) -> tuple[dict, Arrived]:
        """The givens the instant is reached with (a design parameter's value put in) and
        where it is reached; ``asked_at``: the key of ``given_map`` that fixes an
        integration's instant before its event (``None``: the event)."""
        return given_map, self.reached(given_map, asked_at)

    def reached(self, given_map: dict, asked_at: str | When | None) -> Arrived:  # noqa: ARG002 - only an integration has instants of its own
        """The instant ``given_map`` describes, as this kind reaches it."""
        instant = solve_numeric(self.problem, self.plan, given_map, set())
        state = self.rates(instant.state, given_map)
        return Arrived(state, self.balances(self.source, self.kinetics, state),
                       tuple(instant.warnings))

    def at_events(self, given_maps: list[dict]) -> list[np.ndarray | MechgradeError | None]:
        """The extended state each of ``given_maps`` reaches (no instant asked), those this
        kind reaches together; ``None`` for each to be reached alone (:meth:`reached`),
        here all of them."""
        return [None] * len(given_maps)

    def rates(self, state: State, given_map: dict) -> State:  # noqa: ARG002 - the givens fix them here
        """The state's rates, where this kind does not take them from the givens."""
        return state

    def instant(self, given_map: dict, numeric: set[str], overrides: dict) -> Reached:
        problem, kp = self.source, self.kinetics
        asked_at: str | When | None = instant_of_objective(problem, overrides)
        if asked_at is None and isinstance(dynamics_of(problem).analysis, Integration):
            asked_at = asked_when(problem, numeric)
        given_map, arrived = self.arrive(given_map, asked_at)
        if arrived.phase is not None:
            problem, kp = arrived.phase, kinetics_plan(arrived.phase)
        x, before = arrived.x, arrived.before
        read = read_objectives(problem, kp, x[:, None], numeric, rules.REQUIRED_KINETIC,
                               None if before is None else before[:, None])
        return Reached(given_map, _with_kinetics(kp, arrived.state, x),
                       {oid: v[:, 0] for oid, v in read.values.items()},
                       {oid: [v[:, 0] for v in vs] for oid, vs in read.mistakes.items()},
                       read.missing[0], arrived.warnings)

    def symbolic(self) -> Callable | None:
        return _symbolic_result

    def generated(self, reached: Reached,  # noqa: ARG002 - the Reach protocol's signature
                  values: Mapping[str, np.ndarray],  # noqa: ARG002
                  numeric: set[str]) -> None:  # noqa: ARG002
        return None  # worked out once for the whole solution (dynamics_mutants)

    @property
    def plausible(self) -> None:
        return None  # put in with the generated mistakes


@dataclass(frozen=True)
class WorkEnergyInstant(KineticInstant):
    """An instant whose rates the energy balance from the start state gives
    (:mod:`.work_energy`)."""

    def rates(self, state: State, given_map: dict) -> State:
        given_rates = [key for key, (node, _, _) in given_map.items()
                       if isinstance(node, Prime) and node.order == 1]
        return energy_state(self.source, self.kinetics, state, given_rates)

    def instant(self, given_map: dict, numeric: set[str], overrides: dict) -> Reached:
        """An objective asked ``when`` is read at the position where its equation first holds
        (:mod:`.positions`); the objectives of a group share it (``_instants``)."""
        (at,) = at_positions(self.source, numeric, [given_map])
        if isinstance(at, SolveError):
            raise at
        return super().instant(at, numeric, overrides)


def at_positions(problem: Problem, numeric: Collection[str], given_maps: Sequence[dict]
                 ) -> list[dict | SolveError]:
    """Each of ``given_maps`` with the coordinate put where the ``when`` of the first of the
    objectives ``numeric`` asked ``when`` holds (every column walked together,
    :func:`~.positions.positions_where`), or the error that says where it was looked for;
    each map as it is where none is asked ``when``, or the motion is integrated (its phases
    find that instant, :mod:`.phases`)."""
    asked = [o.id for o in problem.objectives if o.id in numeric and o.when is not None]
    if not asked or not isinstance(dynamics_of(problem).analysis, WorkEnergy):
        return list(given_maps)
    name = problem.coordinates[0].name
    found = positions_where(problem, asked[0], given_maps,
                            [when_residual(problem, asked[0], m) for m in given_maps])
    return [at if isinstance(at, SolveError) else {**m, name: (Name(name), at, None)}
            for m, at in zip(given_maps, found)]


def asked_entry(problem: Problem, kinetics: KineticsPlan, given_map: dict, asked_at: str
                ) -> Entry:
    """The instant an objective's own time, coordinate or rate ``asked_at`` fixes on
    ``problem``'s integrated motion (``given_map``: the givens, its value among them)."""
    node, si, given = given_map[asked_at]
    kp = kinetics.kp
    where = given.where if given is not None else analysis_of(problem, Integration).where
    return Entry(kp.index.symbols.index(kp.k.quantity(node)), si,
                 f"{asked_at}: {given.text}" if given is not None else asked_at, where)


@dataclass(frozen=True)
class IntegratedInstant(KineticInstant):
    """The motion integrated from its start state to its event, or to the time, coordinate or
    rate an objective is asked at (:mod:`.events`)."""

    def reached(self, given_map: dict, asked_at: str | When | None) -> Arrived:
        kp = self.kinetics
        g = place_givens(self.problem, kp.kp, given_map)
        if asked_at is None and gripping(self.source) is None:
            (together,) = self._together([g.values])
            if isinstance(together, MechgradeError):
                raise together
            if together is not None:  # as the variants of a class are integrated
                x, before = together
                return Arrived(State(x[:kp.kp.index.size].copy(), after_event(kp.kp),
                                     frozenset()), x, before=before)
        # an objective's own instant, a motion in phases, or what the integrator over columns
        # does not vouch for: one column integrated alone, which says why it fails where it does
        return self.phased(g.values, given_map, asked_at)

    def at_events(self, given_maps: list[dict]) -> list[np.ndarray | MechgradeError | None]:
        """The extended states at the event, integrated together as columns (a motion in
        phases: each alone)."""
        if gripping(self.source) is not None:
            return super().at_events(given_maps)
        out: list[np.ndarray | MechgradeError | None] = [None] * len(given_maps)
        placed: dict[int, np.ndarray] = {}
        for i, given_map in enumerate(given_maps):
            try:
                placed[i] = place_givens(self.problem, self.kinetics.kp, given_map).values
            except MechgradeError as error:
                out[i] = error
        if not placed:
            return out
        good = list(placed)
        for i, each in zip(good, self._together([placed[i] for i in good])):
            out[i] = each if not isinstance(each, tuple) else each[0]
        return out

    def _together(self, values: list[np.ndarray]
                  ) -> list[tuple[np.ndarray, np.ndarray] | MechgradeError | None]:
        """Each of ``values`` (one's givens placed in the state) integrated to the event as
        a class's variants are, its columns side by side (:func:`~.phases.reach_columns`):
        the extended state at the event and the one just before it, or the error it gives;
        ``None`` where that integration does not vouch for it (alone, it says why)."""
        count = len(values)
        out, ok, errors = stacked(self.source, reach_columns(
            self.source, np.stack(values, axis=1), [Until()] * count, kinetics_plan),
            kinetics_plan, count)
        half = out.shape[0] // 2  # the states at the event, and those just before it under them
        return [errors.get(c) or ((out[:half, c], out[half:, c]) if ok[c] else None)
                for c in range(count)]

    def phased(self, values: np.ndarray, given_map: dict, asked_at: str | When | None
               ) -> Arrived:
        """The instant of the motion integrated alone (one column, :func:`~.phases.reach`:
        through its phases, to its event, an objective's own instant or ``when``), read with
        the model of the phase it is in."""
        target: Target = Until() if asked_at is None else asked_at \
            if isinstance(asked_at, When) else asked_entry(self.source, self.kinetics,
                                                           given_map, asked_at)
        at = reach(self.source, values, target, kinetics_plan, accelerations)
        kp = kinetics_plan(at.phase)
        size = kp.kp.index.size
        state = State(at.values, after_event(kp.kp), frozenset())
        if at.before is None:
            return Arrived(state, self.balances(at.phase, kp, state), phase=at.phase)
        # the contact checks hold along the way: judge them just before the event
        self.balances(at.phase, kp, State(at.before[:size], state.given))
        return Arrived(state, at_event(at.before, at.values, kp.kp), before=at.before,
                       phase=at.phase)



@dataclass(frozen=True)
class DesignedInstant(KineticInstant):
    """A design parameter solved so that the design equation holds at the instant ``inner``
    reaches (the event, for an integration): Newton's method on the whole instant from the
    guess (:func:`~.batch_motion.design_roots`, the design stage of a class of variants with
    one column), else a bracketing search around it."""

    inner: KineticInstant | None = None

    def arrive(self, given_map: dict, asked_at: str | When | None) -> tuple[dict, Arrived]:
        given_map = self.designed(given_map)
        return given_map, self.reached(given_map, asked_at)

    def reached(self, given_map: dict, asked_at: str | When | None) -> Arrived:
        assert self.inner is not None, "a design reaches its instant as another kind does"
        return self.inner.reached(given_map, asked_at)

    def designed(self, given_map: dict) -> dict:
        """``given_map`` with the design parameter's value that makes the design equation
        hold (an objective's own value of it is the value to use)."""
        from .batch_motion import design_roots

        design = dynamics_of(self.source).design
        equation = self.kinetics.design
        assert design is not None and equation is not None
        if design.find in given_map:
            return given_map
        node = Name(design.find)

        def with_value(value: float) -> dict:
            out = dict(given_map)
            out[design.find] = (node, float(value), None)
            return out

        def state_at(value: float) -> np.ndarray | None:
            try:
                return self.reached(with_value(value), None).x
            except MechgradeError:  # the iteration wandered where the model fails: no root
                return None

        def states_at(values: np.ndarray) -> list[np.ndarray | None]:
            # the values' instants reached together where the inner kind can (the columns
            # of one integration), each other alone
            assert self.inner is not None
            reached = self.inner.at_events([with_value(v) for v in values])
            return [state_at(v) if x is None else None if isinstance(x, MechgradeError) else x
                    for v, x in zip(values, reached)]

        def reach(_cols: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            found = states_at(values)
            size = max((len(x) for x in found if x is not None), default=1)
            return (np.stack([np.full(size, np.nan) if x is None else x for x in found],
                             axis=1), np.array([x is not None for x in found]))

        def residual(value: float) -> float:
            x = state_at(value)
            return np.nan if x is None else float(_call(equation, x)[0])

        def residuals(values: np.ndarray) -> np.ndarray:
            return np.array([np.nan if x is None else float(_call(equation, x)[0])
                             for x in states_at(values)])

        guess = design.guess
        # one instant, a design of one column; where Newton does not converge, a bracket
        roots, converged = design_roots(reach, equation, guess, 1)
        if converged[0]:
            return with_value(roots[0])
        result = _bracketed(residuals, residual, guess)
        left, right = design.so_that
        if result is None or not result[1] or not np.isfinite(result[0]):
            raise SolveError(f"design: no value of {design.find} near {guess:g} (SI) makes "
                             f"{left.text} = {right.text} (Newton's method from it does not "
                             "converge, and no sign change is found within 64 times it)",
                             where=design.where)
        return with_value(result[0])


def kinetic_reach(problem: Problem, balances: BalancesSolver = solve_kinetics
                  ) -> KineticInstant:
    """How ``problem``'s instants are reached: the kind its analysis names (rates given, by
    the energy balance, integrated), inside a design when it has one; the momentum balances
    solved at each state with ``balances``."""
    kproblem, kp = kinematic_problem(problem), kinetics_plan(problem)
    dynamics = dynamics_of(problem)
    kind = _KINDS.get(type(dynamics.analysis), KineticInstant)
    reach = kind(problem, kproblem, kp, balances)
    if dynamics.design is None or kp.design is None:  # both, or neither: see derive_kinetics
        return reach
    return DesignedInstant(problem, kproblem, kp, balances, inner=reach)


_KINDS: dict[type, type[KineticInstant]] = {WorkEnergy: WorkEnergyInstant,
                                            Integration: IntegratedInstant}
"""The kind of reaching an instant each analysis names; any other (none, an impulse) has
its rates given."""


def _with_kinetics(kp: KineticsPlan, state: State, x: np.ndarray) -> State:
    """``state`` with the rates the momentum balances solved (second rates, or the rates just
    after an impact) put in."""
    size = kp.kp.index.size
    solved = {i for i in kp.columns if i < size and np.isfinite(x[i])}
    return State(x[:size].copy(), state.given, frozenset(state.free - solved))


def _bracketed(residuals: Callable[[np.ndarray], np.ndarray],
               residual: Callable[[float], float], guess: float) -> tuple[float, bool] | None:
    """A root of ``residual`` between two neighbours of the guess scaled by powers of 2 (up to
    64 times either way, the guess's sign kept, the nearest first), found once the sign
    changes there (:func:`~.batch_motion.root_between`), and whether it converged; ``None``
    when the sign does not change. For a design Newton's method overshoots from the guess (a
    residual like 1/R²). ``residuals``: ``residual`` at several values at once (the guess
    and its nearest neighbours, then, where they do not bracket a root, all the others).

    >>> root, ok = _bracketed(lambda v: 1 / v ** 2 - 0.25, lambda v: 1 / v ** 2 - 0.25, 0.5)
    >>> round(root, 12), ok
    (2.0, True)
    """
    from .batch_motion import root_between

    if guess == 0:
        return None
    values: dict[int, float] = {}
    for ring in ([0, 1, -1], [k for n in range(2, 7) for k in (n, -n)]):
        values.update(zip(ring, residuals(np.array([guess * 2.0 ** k for k in ring]))))
        for n in range(1, 7):
            for a, b in ((n - 1, n), (-n, 1 - n)):
                fa, fb = values.get(a, np.nan), values.get(b, np.nan)
                if np.isfinite(fa) and np.isfinite(fb) and fa * fb <= 0:
                    # scipy.optimize's brentq finds it as closely, but importing it costs
                    # more (~0.15 s) than most solves that come here
                    return root_between(residual, guess * 2.0 ** a, guess * 2.0 ** b, fa, fb)
    return None


_AT_ROOTS: dict = {}


def _symbolic_result(problem: Problem, objective_id: str, givens: tuple) -> ObjectiveResult:
    """A symbolic objective's answer (:func:`_derived`). One asked ``when`` is derived once
    per closed-form root that is its position (:func:`~.positions.which_root`) and what else
    it depends on (:func:`~.instant.symbolic_dependence` with that root), not again for each
    value that finds the same root."""
    if problem.objective(objective_id).when is None:
        return _derived(problem, objective_id, givens)
    given_map = dict(givens)
    try:
        root = which_root(problem, objective_id, given_map,
                          when_residual(problem, objective_id, given_map))
    except SolveError:  # fails as it always did, the first error first
        return _derived(problem, objective_id, givens)
    key = (problem, objective_id, symbolic_dependence(problem, given_map, objective_id, root))
    answer = _AT_ROOTS.get(key)
    if answer is None:
        if len(_AT_ROOTS) >= 1024:
            _AT_ROOTS.clear()
        answer = _AT_ROOTS[key] = _derived(problem, objective_id, givens)
    return answer


def _forget_symbolic() -> None:
    _derived.cache_clear()
    _AT_ROOTS.clear()


_symbolic_result.cache_clear = _forget_symbolic  # type: ignore[attr-defined]


@lru_cache(maxsize=512)
def _derived(problem: Problem, objective_id: str, givens: tuple) -> ObjectiveResult:
    from .instant import _quantity_unit
    obj = problem.objective(objective_id)
    kin = derive_kinetics(problem)
    expr = solved_symbolically(problem, objective_id, givens)
    analysis = dynamics_of(problem).analysis
    if isinstance(analysis, Integration):
        numbers = {kin.k.quantity(node): si for _, (node, si, _) in givens
                   if isinstance(node, (Name, Prime))}
        expr = integrated_symbolically(kin, expr, numbers, obj.where)
    if isinstance(analysis, WorkEnergy):
        declared = {kin.k.quantity(node) for node in symbol_meanings(problem, obj).values()}
        expr = energy_rate_symbolic(problem, kinetics_plan(problem), expr, declared)
        if obj.when is not None:
            expr = expr.xreplace({kin.k.q[0]: position_symbolic(
                problem, objective_id, givens, when_residual(problem, objective_id, dict(givens)))})
    k = replace(kin.k, objectives=((objective_id, expr),))
    answer, meanings = symbolic(problem, k, obj, dict(givens))
    units = tuple(_quantity_unit(problem, node) for node in meanings.values())
    return ObjectiveResult(
        id=obj.id, kind=obj.kind, unit=obj.unit, expr=sp.sstr(answer), symbols=tuple(meanings),
        symbol_units=units, rel=obj.tolerance.rel, abs=obj.tolerance.abs, prompt=obj.prompt)


def when_residual(problem: Problem, objective_id: str, given_map: dict) -> sp.Expr:
    """``lhs - rhs`` of the objective's ``when`` in the coordinate and the parameters (the
    rates from the energy integral), worked out once for every objective asked at the same
    equation and every variant that leaves the same givens to stand in."""
    whens = derive_kinetics(problem).whens
    equation = dict(whens)[objective_id]
    first = next(oid for oid, e in whens if e == equation)
    return _when_residual(problem, first, without_position(problem, given_map))


@lru_cache(maxsize=128)
def _when_residual(problem: Problem, objective_id: str, givens: tuple) -> sp.Expr:
    kin = derive_kinetics(problem)
    expr = solved_symbolically(problem, objective_id, givens, dict(kin.whens)[objective_id])
    return sp.expand(energy_rate_symbolic(problem, kinetics_plan(problem), expr, set()))
