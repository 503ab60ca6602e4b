"""What judging a student's derivation needs of the model at the solved instant, as plain
numbers (no sympy): the value of every symbol a student may write, where every point is and
which way every frame's unit vectors point, with each body's free-body diagram
(:mod:`.fbd`). Rates are named as symbolic answers name them (``thetad`` for ``theta'``,
``thetadd`` for ``theta''``); vectors are in the inertial frame's components, in SI.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.solve import solve
>>> problem = load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml")
>>> instant = derivation_instant(problem, solve(problem))
>>> [(name, round(value, 4)) for name, value in instant.values if name in ("m", "beta", "xd")]
[('m', 4.0), ('beta', 0.5236), ('xd', 2.0)]
>>> [round(c, 4) for c in instant.unit_vector("A", "x")], instant.inertial_frame
([0.866, -0.5, 0.0], 'N')
>>> [d.body for d in instant.diagrams], [round(c, 4) for c in instant.point("P")]
(['block'], [0.866, -0.5, 0.0])
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import MechgradeError
from ..mechanics.kinematics import locations
from ..spec.dynamics import LoadKind, dynamics_of
from ..spec.model import Problem
from ..tolerance import parts
from .dynamics import kinetics_plan, solve_kinetics
from .generated import lambdified
from .levels import State
from .rules import projected
from .fbd import (FreeBodyDiagram, Vec3, _diagram_plan, _extended_state, _scalar, _vector,
                  free_body_diagrams)
from .result import Solution

AXES = ("x", "y", "z")


@dataclass(frozen=True)
class DerivationInstant:
    """The model at the solved instant. ``values``: each symbol a student may write (the
    coordinates, their rates as ``xd``/``xdd``, the parameters) and its SI value; ``points``
    every point's position (m; ``None`` where it cannot be had); ``frames`` each frame's unit
    vectors along x, y, z in inertial components; ``unvalued`` the problem's symbols with no
    value at the instant (never a student's unknown: one would absorb any sign)."""

    problem: str
    inertial_frame: str
    values: tuple[tuple[str, float], ...]
    points: tuple[tuple[str, Vec3 | None], ...]
    frames: tuple[tuple[str, tuple[Vec3, Vec3, Vec3] | None], ...]
    diagrams: tuple[FreeBodyDiagram, ...]
    unvalued: tuple[str, ...] = ()

    def point(self, name: str) -> Vec3 | None:
        """Where ``name`` is (``KeyError`` for a name that is not a point)."""
        return dict(self.points)[name]

    def unit_vector(self, frame: str, axis: str) -> Vec3 | None:
        """The unit vector ``frame.axis`` in inertial components."""
        vectors = dict(self.frames)[frame]
        return None if vectors is None else vectors[AXES.index(axis)]

    def diagram(self, body: str) -> FreeBodyDiagram:
        """The free-body diagram of ``body`` (``KeyError`` for a name that is not a body)."""
        return {d.body: d for d in self.diagrams}[body]


def rate_name(spelling: str) -> str:
    """A state quantity's name as symbolic answers write it.

    >>> rate_name("theta''"), rate_name("x'"), rate_name("m")
    ('thetadd', 'xd', 'm')
    """
    base = spelling.rstrip("'")
    return base + "d" * (len(spelling) - len(base))


def derivation_instant(problem: Problem, solution: Solution) -> DerivationInstant:
    """The model of ``problem`` at the instant ``solution`` solved (a problem without bodies
    has no diagrams)."""
    diagrams = free_body_diagrams(problem, solution)
    if problem.dynamics is None:
        return DerivationInstant(problem.id, problem.inertial_frame,
                                 _given_values(solution), (), (), ())
    x = _extended_state(problem, solution)
    plan = _diagram_plan(problem, locations(problem))
    index = kinetics_plan(problem).kp.index
    values = []
    if x is not None:
        for i, name in enumerate(index.names):
            if i != index.time and x[i] == x[i]:  # NaN: not solved
                values.append((rate_name(name), float(x[i])))
    frames = tuple((name, _unit_vectors(f, x)) for name, f in _frame_plan(problem).items())
    points = tuple((name, _vector(f, x)) for name, f in plan.points.items())
    values = values or list(_given_values(solution))
    valued = {name for name, _ in values}
    unvalued = tuple(rate_name(name) for i, name in enumerate(index.names)
                     if i != index.time and rate_name(name) not in valued)
    return DerivationInstant(problem.id, problem.inertial_frame, tuple(values), points, frames,
                             diagrams, unvalued)


def _given_values(solution: Solution) -> tuple[tuple[str, float], ...]:
    return tuple((rate_name(s.name), s.si) for s in solution.state)


def _unit_vectors(f, x) -> tuple[Vec3, Vec3, Vec3] | None:
    vectors = tuple(_vector(g, x) for g in f)
    return None if any(v is None for v in vectors) else vectors  # type: ignore[return-value]


@lru_cache(maxsize=32)
def _frame_plan(problem: Problem) -> dict:
    from ..mechanics.build import build
    model = build(problem)
    symbols = kinetics_plan(problem).symbols
    out = {}
    for name, frame in model.frames.items():
        out[name] = tuple(
            lambdified(symbols, model.plain(getattr(frame, axis).to_matrix(model.inertial)))
            for axis in AXES)
    return out


SAMPLES = 5
"""How many states equations of motion are judged at in each configuration (more where the
model has more accelerations: a fixed combination of them must be told from a chance fit)."""

MOVE = 0.15
"""How far along the motion the other configurations are: the coordinate that moves most
moves this share of its typical size (angles: of pi), before and after the solved instant."""


@dataclass(frozen=True)
class SampledLoad:
    """One load of the model at each sampled state: its ``name``, ``kind`` and ``body``, and
    ``components``: rows of one value per state, every way it can enter a balance (a force
    along each frame's unit vectors, and its moment about each point along them; a couple's
    moment along them, about each point), ``nan`` where it has no value; ``along`` says
    which for each row (``("A.x", None)``: the force along ``A.x``; ``("A.x", "O")``: the
    moment about ``O``); ``mass`` the body's at each state."""

    name: str
    kind: LoadKind
    body: str
    components: tuple[tuple[float, ...], ...]
    mass: tuple[float, ...] = ()  # its body's mass at each state (an equation divided by it)
    along: tuple[tuple[str, str | None], ...] = ()  # each row's axis and point (None: a force)


@dataclass(frozen=True)
class SampledBalance:
    """One momentum balance of a body along one frame's unit vector ``axis`` (``A.x``): of
    forces (``about`` is ``None``) or of moments about the point ``about``. ``loads`` is the
    loads' side at each sampled state (their resultant, or their moment about ``about``, along
    ``axis``), which the model's motion there matches; ``slope`` how the motion's side (m a,
    or the rate of angular momentum about ``about``, along ``axis``) changes with each
    acceleration, at each state."""

    body: str
    axis: str
    about: str | None
    loads: tuple[float, ...]
    slope: tuple[tuple[float, ...], ...]


@dataclass(frozen=True)
class MotionSamples:
    """The model's motion at a few states: ``symbols`` a student may write (coordinates,
    parameters, rates as ``xd``), ``accelerations`` (``xdd``), ``reactions`` (the model's
    names, ``R_O_1``), and per state the value of each, in that order; ``loads`` each load
    at those states. ``configurations`` says which configuration (where the bodies are) each
    state is in, ``reaction_loads`` which reaction each reaction's name is a component of
    (``R_O`` for ``R_O_1``); empty, one configuration and a reaction of its own each."""

    symbols: tuple[str, ...]
    accelerations: tuple[str, ...]
    reactions: tuple[str, ...]
    states: tuple[tuple[float, ...], ...]
    loads: tuple[SampledLoad, ...] = ()
    balances: tuple[SampledBalance, ...] = ()
    configurations: tuple[int, ...] = ()
    reaction_loads: tuple[str, ...] = ()

    @property
    def names(self) -> tuple[str, ...]:
        return self.symbols + self.accelerations + self.reactions

    def state(self, k: int) -> dict[str, float]:
        """The ``k``-th state by name."""
        return dict(zip(self.names, self.states[k]))

    def configuration(self, k: int) -> int:
        """Which configuration the ``k``-th state is in."""
        return self.configurations[k] if self.configurations else 0

    def reaction_load(self, r: int) -> str:
        """The reaction the ``r``-th reaction's name is a component of."""
        return self.reaction_loads[r] if self.reaction_loads else self.reactions[r]


def motion_samples(problem: Problem, solution: Solution, count: int = SAMPLES,
                   seed: int = 0) -> MotionSamples | None:
    """The model's motion in a few configurations along it — the solved instant's and, where
    the bodies move, a moment before and after it (:data:`MOVE`) — and in each, at ``count``
    states or more: every parameter and rate scaled by a seeded factor in 0.8 to 1.25 (the
    parameters alone where scaling the rates breaks a constraint on them), with the
    accelerations and reactions the model solves there. A state the model cannot solve is
    left out; ``None`` without a solved state.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve import solve
    >>> problem = load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml")
    >>> samples = motion_samples(problem, solve(problem))
    >>> samples.accelerations, samples.reactions, len(samples.states)
    (('xdd',), ('N_P',), 15)
    >>> s = samples.state(0)
    >>> round(s["xdd"], 4), round(s["N_P"], 4)
    (2.7811, 33.9828)
    >>> sorted({round(samples.state(k)["x"], 4) for k in range(15)})
    [0.8642, 1.0, 1.15]
    >>> all(abs(s["xdd"] - s["g"] * (np.sin(s["beta"]) - s["mu_k"] * np.cos(s["beta"])))
    ...     < 1e-9 for s in map(samples.state, range(15)))
    True
    """
    if problem.dynamics is None:
        return None
    x = _extended_state(problem, solution)
    if x is None:
        return None
    kp = kinetics_plan(problem)
    index = kp.kp.index
    parameters = [i for i in range(index.size) if index.is_parameter(i)]
    rates = list(index.rates(1))
    given = np.zeros(index.size, dtype=bool)
    given[list(index.config) + rates] = True
    # the solved state of an integration has the accelerations of the limit just before its
    # event (rules.BEFORE_EVENT) beside the event's coordinates and rates: off by that
    # fraction, which is the whole of them where the loads vanish at the event (a spring at
    # its free length), and a right equation would not hold there. Solved again from its own
    # coordinates and rates, as the states near it are, where the model can (a slip ending at
    # the event has its direction only in the limit before)
    try:
        x = solve_kinetics(problem, kp, State(x[:index.size].copy(), given))
    except MechgradeError:
        pass
    rng = np.random.default_rng(seed)
    per = max(count, len(index.rates(2)) + 3)
    found, configurations = [], []
    for c, base in enumerate([x, *_along_motion(problem, kp, x, given)]):
        found.append(base)
        configurations.append(c)
        for _ in range(per - 1):
            factors = rng.uniform(0.8, 1.25, index.size)
            for scaled in (parameters + rates, parameters):
                values = base[:index.size].copy()
                values[scaled] *= factors[scaled]
                try:
                    found.append(solve_kinetics(problem, kp, State(values, given)))
                    configurations.append(c)
                    break
                except MechgradeError:
                    continue
    symbols = [i for i in list(index.config) + rates if i != index.time]
    accelerations = list(index.rates(2))
    reactions = list(range(index.size, len(kp.symbols)))
    order = symbols + accelerations + reactions
    finite = [k for k, v in enumerate(found) if np.all(np.isfinite(v[order]))]
    kept = [found[k] for k in finite]
    states = tuple(tuple(float(v[i]) for i in order) for v in kept)
    if not states:
        return None
    return MotionSamples(tuple(rate_name(index.names[i]) for i in symbols),
                         tuple(rate_name(index.names[i]) for i in accelerations),
                         tuple(str(kp.symbols[i]) for i in reactions), states,
                         _sampled_loads(problem, kept), _sampled_balances(problem, kept),
                         tuple(configurations[k] for k in finite),
                         tuple(label.split(" (along ")[0] for label in kp.kin.labels))


def _along_motion(problem: Problem, kp, x: np.ndarray, given: np.ndarray) -> list[np.ndarray]:
    """The solved state ``x`` moved a moment back and a moment on along its motion (each
    coordinate by its rate and acceleration, then put back on the constraints), with the
    accelerations and reactions solved there; a move is halved while it turns a rate round
    (a slip would change its direction) or the model cannot solve it, and left out after a
    few; none when nothing moves."""
    from .levels import typical_sizes

    index = kp.kp.index
    n = index.n
    qd, qdd = np.array(index.rates(1)), np.array(index.rates(2))
    v, a = x[qd], x[qdd]
    size = MOVE * typical_sizes(problem, kp.kp, x[:index.size, None], given)[:n, 0]
    # the time in which each coordinate moves its share: |v| t + |a| t^2 / 2 = size
    with np.errstate(all="ignore"):  # the root without cancelling (a ≈ 0 beside v)
        times = 2 * size / (np.abs(v) + np.sqrt(v ** 2 + 2 * np.abs(a) * size))
    times = times[np.isfinite(times) & (times > 0)]
    if not times.size:
        return []
    # a coordinate a thousand times slower than the fastest is still (its rate a rounding)
    times = times[times <= 1e3 * times.min()]
    out = []
    for sign in (-1.0, 1.0):
        # the slowest coordinate moves its share (a fast spin about a symmetry axis would
        # leave the others where they are): its rate is all that sets it
        dt = sign * float(times.max())
        for _ in range(8):
            moved = _on_constraints(kp, x, dt)
            # a rate turned round, or set going against its acceleration (before a start
            # from rest), would turn a slip's friction round
            if moved is not None and not _turned(moved[qd], v, a):
                try:
                    out.append(solve_kinetics(problem, kp, State(moved, given)))
                    break
                except MechgradeError:
                    pass
            dt /= 2
    return out


def _turned(rates: np.ndarray, v: np.ndarray, a: np.ndarray) -> bool:
    """Whether one of ``rates`` goes against ``v`` (where that is still, against ``a``),
    roundings aside.

    >>> _turned(np.array([1.0, -0.5]), np.array([2.0, 0.0]), np.array([0.0, 1.0]))
    True
    >>> _turned(np.array([1.0, -1e-17]), np.array([2.0, 0.0]), np.array([0.0, 1e-17]))
    False
    """
    along = np.where(parts(v), v, a)
    return bool(np.any((rates * along < 0) & parts(rates) & parts(along)))


def _on_constraints(kp, x: np.ndarray, dt: float) -> np.ndarray | None:
    """The state ``x`` a time ``dt`` on (``x + v dt + a dt^2 / 2``), the coordinates put back
    on the position constraints (Gauss-Newton) and the rates on the velocity constraints
    (least squares) until :func:`~.rules.projected`; ``None`` where the coordinates cannot
    be."""
    index = kp.kp.index
    n = index.n
    qd, qdd = list(index.rates(1)), list(index.rates(2))
    values = x[:index.size].copy()
    values[:n] += dt * x[qd] + dt * dt / 2 * x[qdd]
    values[qd] += dt * x[qdd]
    values[index.time] += dt
    values[qdd] = 0.0
    position, velocity = kp.kp.levels[0], kp.kp.levels[1]
    with np.errstate(all="ignore"):
        for _ in range(30):
            m = position.constraint_rows
            r = np.asarray(position.residual(*values), dtype=float).ravel()[:m]
            scale = np.asarray(position.scale(*values), dtype=float).ravel()[:m]
            if not np.all(np.isfinite(r)):
                return None
            if projected(r, scale):
                break
            jacobian = np.asarray(position.jacobian(*values), dtype=float).reshape(
                len(position.labels), -1)[:m, :n]
            values[:n] -= np.linalg.lstsq(jacobian, r, rcond=None)[0]
        else:
            return None
        m = velocity.constraint_rows
        if m:
            jacobian = np.asarray(velocity.jacobian(*values), dtype=float).reshape(
                len(velocity.labels), n)[:m]
            r = np.asarray(velocity.residual(*values), dtype=float).ravel()[:m]
            if not (np.all(np.isfinite(jacobian)) and np.all(np.isfinite(r))):
                return None
            values[qd] -= np.linalg.lstsq(jacobian, r, rcond=None)[0]
    return values


def _sampled_loads(problem: Problem, states: list[np.ndarray]) -> tuple[SampledLoad, ...]:
    """Every load of ``problem`` at each of ``states`` (see :class:`SampledLoad`)."""
    plan = _diagram_plan(problem, locations(problem))
    frames = _frame_plan(problem)
    masses = {body: [_scalar(f, x) for x in states] for body, f in _mass_plan(problem).items()}
    nan3 = (np.nan,) * 3
    axes = [[np.array(v if v is not None else nan3) for f in frames.values()
             for v in (_unit_vectors(f, x) or (nan3,) * 3)] for x in states]
    names = [f"{frame}.{a}" for frame in frames for a in AXES]
    out = []
    for applied, force, moment, *_ in plan.loads:
        couple = applied.point is None
        # a couple's moment is the same about every point
        along: list[tuple[str, str | None]] = [] if couple else [(a, None) for a in names]
        along += [(axis, about) for about in plan.points for axis in names]
        rows: list[list[float]] = []
        for k, x in enumerate(states):
            vector = np.array(_vector(moment if couple else force, x) or nan3)
            values = [] if couple else [float(vector @ e) for e in axes[k]]
            at = None if couple else np.array(_vector(plan.points.get(applied.point), x) or nan3)
            for f in plan.points.values():
                turning = vector if at is None else np.cross(
                    at - np.array(_vector(f, x) or nan3), vector)
                values += [float(turning @ e) for e in axes[k]]
            rows.append(values)
        out.append(SampledLoad(applied.name, applied.kind, applied.body,
                               tuple(zip(*rows)), tuple(np.nan if m is None else m
                                                        for m in masses[applied.body]),
                               tuple(along)))
    return tuple(out)


@lru_cache(maxsize=32)
def _mass_plan(problem: Problem) -> dict:
    """Each body's mass as a function of the kinetics symbols."""
    import sympy as sp

    from ..mechanics.build import build
    model = build(problem)
    symbols = kinetics_plan(problem).symbols
    return {body.name: lambdified(symbols, sp.Matrix([sum(
        (model.plain(model.language.scalar(part.mass)) for part in body.parts), sp.S.Zero)]))
        for body in dynamics_of(problem).bodies}


# the labels mechanics.dynamics gives a body's momentum balances (in the inertial axes)
_FORCE_LABEL = re.compile(r"body (\w+): \w+\.([xyz]) force balance")
_MOMENT_LABEL = re.compile(r"body (\w+): moment balance about \w+ \(\w+\.([xyz]) component\)")


def _sampled_balances(problem: Problem, states: list[np.ndarray]) -> tuple[SampledBalance, ...]:
    """Every body's force balance along each frame's unit vectors, and (a rigid body's) moment
    balance about each point along them, at each of ``states`` (see
    :class:`SampledBalance`); none for an impact (its balances are of impulses)."""
    kp = kinetics_plan(problem)
    if kp.kin.impact or not states:
        return ()
    plan = _diagram_plan(problem, locations(problem))
    frames = _frame_plan(problem)
    n = len(list(kp.kp.index.rates(2)))
    jacobians = np.array([np.asarray(kp.jacobian(*x), dtype=float)[:, :n] for x in states])
    nan3 = np.full(3, np.nan)
    points = {name: [np.array(_vector(f, x) or nan3) for x in states]
              for name, f in plan.points.items()}
    axes = [(f"{frame}.{AXES[a]}", [np.array((_unit_vectors(f, x) or (nan3,) * 3)[a])
                                    for x in states])
            for frame, f in frames.items() for a in range(3)]
    out = []
    for body in dynamics_of(problem).bodies:
        # the motion's side (m a; the rate of angular momentum about the centre) is the
        # balance's part in the accelerations, turned round
        ma, spin = np.zeros((len(states), 3, n)), np.zeros((len(states), 3, n))
        for row, label in enumerate(kp.labels):
            for pattern, slopes in ((_FORCE_LABEL, ma), (_MOMENT_LABEL, spin)):
                found = pattern.fullmatch(label)
                if found and found.group(1) == body.name:
                    slopes[:, AXES.index(found.group(2))] = -jacobians[:, row]
        forces = [(applied, force, couple) for applied, force, couple, *_ in plan.loads
                  if applied.body == body.name]
        resultant = [sum((np.array(_vector(force, x) or nan3) for a, force, _ in forces
                          if a.point is not None), np.zeros(3)) for x in states]
        for axis, e in axes:
            out.append(SampledBalance(body.name, axis, None,
                                      tuple(float(r @ u) for r, u in zip(resultant, e)),
                                      _per_state(e, ma)))
        if body.frame is None:
            continue  # a particle: no moment balance
        for about, where in points.items():
            moment = [sum((np.array(_vector(couple, x) or nan3) if a.point is None else
                           np.cross(points[a.point][k] - where[k],
                                    np.array(_vector(force, x) or nan3))
                           for a, force, couple in forces), np.zeros(3))
                      for k, x in enumerate(states)]
            # about another point, the rate of angular momentum gains the moment of m a
            rate = spin + np.array([np.cross(points[body.centre][k] - where[k], ma[k].T).T
                                    for k in range(len(states))])
            for axis, e in axes:
                out.append(SampledBalance(body.name, axis, about,
                                          tuple(float(m @ u) for m, u in zip(moment, e)),
                                          _per_state(e, rate)))
    return tuple(out)


def _per_state(axis: list[np.ndarray], slopes: np.ndarray) -> tuple[tuple[float, ...], ...]:
    """How a balance's motion side along ``axis`` (its unit vector at each state) changes
    with each acceleration at each state, from ``slopes`` (state, component, acceleration)."""
    return tuple(tuple(float(v) for v in e @ slope) for e, slope in zip(axis, slopes))
