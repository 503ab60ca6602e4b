"""The kinetics of a problem: Newton–Euler balances of every body, written from its free-body
loads, in plain symbols, with the unknown reactions as symbols of their own.

For each body: the linear momentum balance ``sum F = sum m_i a_Gi`` (three components in the
inertial frame) and, for a rigid body, the angular momentum balance about its reference point
C, ``sum M_C = sum r_Gi/C x m_i a_Gi + sum d/dt (I_Gi . omega)``, which holds for any C and
any composition of parts, so a composite body never needs its mass centre worked out by hand.
Components that vanish identically (a planar problem's out-of-plane balances) are dropped.
Together with the kinematic constraints at the acceleration level these equations are linear in
the unknown second rates and reactions.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> kin = derive_kinetics(load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml"))
>>> [str(s) for s in kin.reactions], len(kin.balances)
(['R_O_1', 'R_O_2'], 3)
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field, replace
from functools import cached_property, lru_cache

import sympy as sp
from sympy.physics.vector import Dyadic, ReferenceFrame, Vector, dynamicsymbols

from ..errors import Location, SolveError
from ..expressions.syntax import Call, Name, Node, constant_value, to_text, walk
from ..spec.dynamics import (GROUND, Analysis, Body, Damper, Dynamics, Impulse,
                             Integration, KineticFriction, LoadKind, Reaction, Restitution,
                             Spring, StaticFriction, WorkEnergy, dynamics_of,
                             junction_coordinates)
from ..spec.model import Expr, ObjectiveKind, Problem
from .derivation import kinematics_derivation
from .bodies import central_inertia, parallel_axis
from .build import Model, build
from .interpret import Interpreter
from .junctions import check_junctions, is_junction_balance, kinematic_part
from .kinematics import Equation, Kinematics, _objective_value, derive, locations
from .loads import AppliedLoad, PhysicalBound, check_loads, diagram, physical_bounds
from .symbols import identically_zero, without_deltas
from .vibration import REASONS, Modal, NaturalMode, modal_entries


@dataclass(frozen=True)
class FrictionBound:
    """A friction bound to check in the solution: ``|tangential| <= mu * normal``."""

    name: str
    body: str
    point: str
    tangential: object  # 3x1 matrix of the friction force, inertial components
    normal: sp.Expr
    mu: sp.Expr
    where: Location = Location()


@dataclass(frozen=True)
class Slip:
    """A kinetic-friction contact: it needs a slip speed and a compressive normal force."""

    name: str
    point: str
    speed: sp.Expr
    normal: sp.Expr
    where: Location = Location()


@dataclass(frozen=True)
class RatesBefore:
    """An impact's rates just before it as inputs of its balances: ``symbols`` stand for the
    ``rates`` that are not zero in the balances as derived (:attr:`Kinetics.written`), worth
    ``values`` (in the parameters and coordinates). A model that differs only in these values
    is the same balances with other inputs (:func:`read_kinetics`), not derived again.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> kin = derive_kinetics(load_problem(shipped_dir("problems") / "ruina_9_25_units_matrix.yaml"))
    >>> kin.before.rates, kin.before.values
    ((std, snd), (-v0*sin(theta), -v0*cos(theta)))
    >>> kin.before.shown(kin.written) == kin.balances
    True
    """

    rates: tuple[sp.Symbol, ...]
    symbols: tuple[sp.Symbol, ...]
    values: tuple[sp.Expr, ...]

    def shown(self, equations) -> tuple[Equation, ...]:
        """``equations`` (in :attr:`symbols`) with the rates' values put in, as written up."""
        if not self.symbols:
            return tuple(equations)
        values = dict(zip(self.symbols, self.values))
        return tuple(replace(e, expr=sp.expand(e.expr.xreplace(values))) for e in equations)


@dataclass(frozen=True)
class Kinetics:
    """A problem's kinetics in plain symbols.

    ``written`` are the momentum balances (``expr = 0``) as derived, an impact's in its rates
    before (``before``), and :attr:`balances` as written up; ``reactions`` the unknown force
    magnitudes, one per direction of each reaction (``labels`` says which); ``objectives`` and
    ``mistakes`` are in these symbols too; the write-up text is :func:`_kinetics_lines`'s
    (written only when asked: a mistaken model is solved, never written up).
    """

    k: Kinematics
    reactions: tuple[sp.Symbol, ...]
    labels: tuple[str, ...]
    written: tuple[Equation, ...]
    compact: tuple[sp.Expr, ...]  # ``written``'s left sides as derived, not expanded
    objectives: tuple[tuple[str, object], ...]
    mistakes: tuple[tuple[str, tuple[object, ...]], ...]
    bounds: tuple[FrictionBound, ...]
    slips: tuple[Slip, ...]
    energy: sp.Expr = sp.Integer(0)
    nonconservative: tuple[str, ...] = ()
    workless: tuple[tuple[str, sp.Expr], ...] = ()
    start: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()
    settled: tuple[sp.Symbol, ...] = ()  # start coordinates and rates a junction's balance fixes
    until: sp.Expr | None = None
    requirements: tuple[tuple[str, str, sp.Expr], ...] = ()
    impact: bool = False
    design: sp.Expr | None = None
    physical: tuple[PhysicalBound, ...] = ()  # what the instant must keep (mechanics.loads)
    whens: tuple[tuple[str, sp.Expr], ...] = ()  # objective id -> lhs - rhs of its 'when'
    before: RatesBefore | None = None  # an impact's balances with its rates before as inputs
    built: tuple = field(default=(), compare=False, repr=False)  # (model, loads, language)

    @cached_property
    def balances(self) -> tuple[Equation, ...]:
        """The momentum balances (and an impact's contact conditions) as written up: an
        impact's rates before put in (worked out when first asked: a mistaken model's only
        for its symbolic answers)."""
        return self.before.shown(self.written) if self.before is not None else self.written

    @property
    def compact_balances(self) -> tuple[sp.Expr, ...]:
        """:attr:`compact` with an impact's rates before put in (as :attr:`balances`), not
        expanded."""
        if self.before is None:
            return self.compact
        values = dict(zip(self.before.symbols, self.before.values))
        return tuple(e.xreplace(values) for e in self.compact)

    @property
    def rates(self) -> tuple[sp.Symbol, ...]:
        """The rates the balances are solved for: second rates, or (an impact) the rates just
        after it."""
        return self.k.qd if self.impact else self.k.qdd

    @property
    def constraints(self):
        """The constraint equations solved with the balances, at the level of ``rates``."""
        return self.k.velocity if self.impact else self.k.acceleration

    def objective(self, objective_id: str):
        return dict(self.objectives)[objective_id]


class _Loads:
    """Every load as applications ``(body, point, force)`` and couples ``(body, moment)``,
    in ``sympy.physics`` vectors, keyed by load name (gravity under ``gravity``)."""

    def __init__(self, problem: Problem, model: Model, reactions: dict):
        self.problem = problem
        self.d = dynamics_of(problem)
        self.model = model
        self.language = model.language
        self.N = problem.inertial_frame
        self.forces: dict[str, list[tuple[str, str, Vector]]] = {}
        self.couples: dict[str, list[tuple[str, Vector]]] = {}
        self.reactions = reactions

    def impulsive(self, name: str) -> bool:
        """Whether load ``name`` acts during an impact (a reaction or a known impulse)."""
        return name in self.reactions or name in {j.name for j in self.d.impulses}

    def velocity(self, body: str, point: str) -> Vector:
        """Velocity in the inertial frame of the material point of ``body`` at ``point``."""
        if body == GROUND:
            return Vector(0)
        b = self.d.body(body)
        v = self.language.point_velocity(Name(b.centre), self.N)
        if b.frame is None:
            return v
        omega = self.model.frames[b.frame].ang_vel_in(self.model.inertial)
        return v + (omega ^ (self.model.positions[point] - self.model.positions[b.centre]))

    def build(self) -> None:
        lang, d = self.language, self.d
        if d.gravity is not None:
            g = lang.vector(d.gravity)
            self.forces["gravity"] = [(b.name, p.at, lang.scalar(p.mass) * g)
                                      for b in d.bodies for p in b.parts]
        for f in d.forces:
            self.forces[f.name] = [(f.on, f.at, lang.vector(f.force))]
        for c in d.couples:
            self.couples[c.name] = [(c.on, lang.vector(c.moment))]
        for j in d.impulses:
            self.forces[j.name] = [(j.on, j.at, lang.vector(j.impulse))]
        ends: tuple[Spring | Damper, ...] = (*d.springs, *d.dampers)
        for s in ends:
            a, b = (self.model.positions[p] for p in s.between)
            r = b - a
            length = r.magnitude()
            if isinstance(s, Spring):
                tension = lang.scalar(s.stiffness) * (length - lang.scalar(s.length))
            else:
                tension = lang.scalar(s.coefficient) * (r & r.dt(self.model.inertial)) / length
            pull = tension * r / length  # on the first end, toward the second
            self.forces[s.name] = [(s.on[0], s.between[0], pull), (s.on[1], s.between[1], -pull)]
        for r in d.reactions:
            vector = self.reaction_vector(r.name, r.directions)
            self.forces[r.name] = [
                (a.on, a.at, a.sign * (vector if a.direction is None else
                                       self.reaction_vector(r.name, (a.direction,))))
                for a in r.acts]
        bodies = {b.name for b in d.bodies}
        for contact in d.friction:
            if isinstance(contact, StaticFriction):
                vector = self.reaction_vector(contact.name, contact.directions)
            else:
                slip = self.slip_velocity(contact)
                vector = -lang.scalar(contact.mu) * self.normal(contact.normal) * slip \
                    / slip.magnitude()
            self.forces[contact.name] = [(contact.on, contact.at, vector)]
            if contact.surface in bodies:  # between two free bodies: equal and opposite
                self.forces[contact.name].append((contact.surface, contact.at, -vector))

    def reaction_vector(self, name: str, directions) -> Vector:
        return sum((s * self.language.vector(e) for s, e in zip(self.reactions[name], directions)),
                   Vector(0))

    def normal(self, name: str) -> sp.Symbol:
        return self.reactions[name][0]

    def slip_velocity(self, f: KineticFriction) -> Vector:
        """The velocity of ``f``'s body at its contact relative to the surface's material
        point there (a body's, or a frame's)."""
        v = self.velocity(f.on, f.at)
        if f.surface in {b.name for b in self.d.bodies}:
            return v - self.velocity(f.surface, f.at)
        if f.surface not in (GROUND, self.N):
            v -= self.language.point_velocity(Call("coincident", (Name(f.at), Name(f.surface))),
                                              self.N)
        return v

    def on(self, body: str):
        """The applications and couples acting on ``body``."""
        forces = [(name, p, F) for name, apps in self.forces.items() for b, p, F in apps
                  if b == body]
        couples = [(name, M) for name, items in self.couples.items() for b, M in items
                   if b == body]
        return forces, couples


class DynamicsInterpreter(Interpreter):
    """The objective language with the dynamics functions: loads, momenta, energies.

    ``kinematics``, ``balances`` and ``reactions`` are set once the balances are written (they
    need the loads this interpreter reads); only the linearised motion reads them.
    """

    kinematics: Kinematics
    balances: tuple[Equation, ...]
    reactions: tuple[sp.Symbol, ...]

    def __init__(self, problem: Problem, model: Model, loads: _Loads, inertias: dict):
        super().__init__(problem, model.symbols, model.frames, model.positions)
        self.loads = loads
        self.inertias = inertias  # body -> [(mass, centre, central inertia or None)]
        self.d = dynamics_of(problem)
        self._linearised: dict[str, tuple] = {}
        self.reactions_by_name = loads.reactions
        self.where = Location()
        self.before: dict = {}  # the rates just before an impact
        self.symbolic = False  # whether the objective read is a symbolic one
        # (find, frame, symbolic) -> its value and the requirements reading it adds
        self.readings: dict[tuple, tuple[object, tuple]] = {}

    def reading(self, model: Model, find: Expr, frame: str | None) -> tuple[object, tuple]:
        """An objective's (or mistake's) ``find`` read in ``model`` (with this language), and
        the requirements it adds at the instant: read once for every copy of the model that
        asks it (a mistaken one, the same objectives)."""
        key = (find.node, frame, self.symbolic)
        found = self.readings.get(key)
        if found is None:
            self.requirements.clear()
            value = _objective_value(model, find, frame)
            found = self.readings[key] = (value, tuple(self.requirements))
        return found

    def _omega(self, body: Body, frame: str) -> Vector:
        if body.frame is None:
            return Vector(0)
        return self.frames[body.frame].ang_vel_in(self.frames[frame])

    def _first_body(self, load: str) -> str | None:
        """The body a load's ``force``/``moment`` refer to: the first it acts on (a spring
        fixed to the ground at one end: the body at the other end)."""
        bodies = [b for b, _, _ in self.loads.forces.get(load, ())] + \
            [b for b, _ in self.loads.couples.get(load, ())]
        return next((b for b in bodies if b != GROUND), None)

    def _fn_force(self, load: Name):
        if isinstance(self.d.analysis, Impulse) and self.loads.impulsive(load.id):
            raise SolveError(f"during an impact {load.id} is an impulse: ask for "
                             f"impulse({load.id})", where=self.where)
        return self._load_force(load)

    def with_rates_before(self, before: dict) -> DynamicsInterpreter:
        """This language with other rates just before the impact (``before(...)`` reads)."""
        other = copy.copy(self)
        other.before, other.requirements = before, []
        other.readings = {key: found for key, found in self.readings.items()
                          if not any(isinstance(n, Call) and n.func == "before"
                                     for n in walk(key[0]))}
        return other

    def _fn_before(self, quantity: Node):
        return self._across_the_impact("before", quantity).subs(self.before)

    def _fn_after(self, quantity: Node):
        return self._across_the_impact("after", quantity)

    def _across_the_impact(self, name: str, quantity: Node):
        """A scalar or vector read just before or after an impact, in the rates after."""
        if not isinstance(self.d.analysis, Impulse):
            raise SolveError(f"{name}(...) needs an impact: 'analysis: impulse'",
                             where=self.where)
        value = self.value(quantity)
        return sp.sympify(value) if not isinstance(value, Vector) else value

    def _load_force(self, load: Name):
        body = self._first_body(load.id)
        return sum((F for b, _, F in self.loads.forces.get(load.id, ()) if b == body), Vector(0))

    def _fn_impulse(self, load: Name):
        if not isinstance(self.d.analysis, Impulse):
            raise SolveError(f"impulse({load.id}) needs an impact: 'analysis: impulse'",
                             where=self.where)
        return self._load_force(load)

    def _fn_moment(self, load: Name, point: Node):
        body = self._first_body(load.id)
        about = self.point_position(point)
        moment = sum((M for b, M in self.loads.couples.get(load.id, ()) if b == body),
                     Vector(0))
        for b, at, F in self.loads.forces.get(load.id, ()):
            if b == body:
                moment += (self.positions[at] - about) ^ F
        return moment

    def _fn_power(self, load: Name, frame: Name):
        total = sp.Integer(0)
        for body, at, F in self.loads.forces.get(load.id, ()):
            total += F & self._material_velocity(body, at, frame.id)
        for body, M in self.loads.couples.get(load.id, ()):
            total += M & self._omega(self.d.body(body), frame.id)
        return total

    def _material_velocity(self, body: str, point: str, frame: str) -> Vector:
        if body == GROUND:
            return self.point_velocity(
                Call("coincident", (Name(point), Name(self.problem.inertial_frame))), frame)
        b = self.d.body(body)
        v = self.point_velocity(Name(b.centre), frame)
        return v + (self._omega(b, frame) ^ (self.positions[point] - self.positions[b.centre]))

    def _fn_momentum(self, body: Name, frame: Name):
        return sum((m * self.point_velocity(Name(at), frame.id)
                    for m, at, _ in self.inertias[body.id]), Vector(0))

    def _fn_angmom(self, body: Name, point: Node, frame: Name):
        b = self.d.body(body.id)
        omega = self._omega(b, frame.id)
        about = self.point_position(point)
        total = Vector(0)
        for m, at, central in self.inertias[body.id]:
            total += (self.positions[at] - about) ^ (m * self.point_velocity(Name(at), frame.id))
            if central is not None:
                total += central & omega
        return total

    def _fn_ke(self, body: Name, frame: Name):
        b = self.d.body(body.id)
        omega = self._omega(b, frame.id)
        total = sp.Integer(0)
        for m, at, central in self.inertias[body.id]:
            v = self.point_velocity(Name(at), frame.id)
            total += m * (v & v) / 2
            if central is not None:
                total += (omega & (central & omega)) / 2
        return total

    def _fn_pe(self, item: Name):
        if item.id in self.inertias:
            if self.d.gravity is None:
                return sp.Integer(0)
            g = self.vector(self.d.gravity)
            return -sum((m * (g & self.positions[at]) for m, at, _ in self.inertias[item.id]),
                        sp.Integer(0))
        spring = self.d.load(item.id)
        r = self.positions[spring.between[1]] - self.positions[spring.between[0]]
        return self.scalar(spring.stiffness) * (r.magnitude() - self.scalar(spring.length)) ** 2 / 2

    def linearised(self, coordinate: Name) -> tuple[sp.Expr, sp.Expr]:
        """``(k, c)`` of q'' = -k (q - q_eq) - c q' + ..., the motion of a single degree of
        freedom linearised about the instant's configuration (rates zero there); an
        equilibrium requirement (q'' = 0 at rest) is recorded."""
        if coordinate.id in self._linearised:
            stiffness, damping, requirement = self._linearised[coordinate.id]
            self.requirements.append(requirement)
            return stiffness, damping
        k = self.kinematics
        if len(k.q) != 1 or k.velocity:
            raise SolveError("omega_n and zeta need a single coordinate without constraints "
                             "(one degree of freedom)", where=self.where)
        unknowns = (*k.qdd, *self.reactions)
        A, b = sp.linear_eq_to_matrix([e.expr for e in self.balances], list(unknowns))
        if A.rows != A.cols:
            raise SolveError("omega_n and zeta need as many momentum balances as unknown "
                             "accelerations and reactions", where=self.where)
        q, qd = k.q[0], k.qd[0]
        rest = {qd: 0}
        # q'' by Cramer's rule with division-free (Berkowitz) determinants: an elimination's
        # pivot that is not zero in symbols may be zero at the instant (a reaction's
        # coefficient m L/2 sin(theta) at theta = 0), and q'' would be 0/0 there; det(A) is
        # zero only where the balances do not fix the motion
        top = A.copy()
        top[:, 0] = b
        numerator, denominator = top.det(method="berkowitz"), A.det(method="berkowitz")

        def rate(s):
            return ((numerator.diff(s) * denominator - numerator * denominator.diff(s))
                    / denominator ** 2).xreplace(rest)

        equilibrium = (numerator / denominator).xreplace(rest)
        stiffness, damping = _linear_term(-rate(q)), _linear_term(-rate(qd))
        requirement = (f"the configuration is not an equilibrium ({coordinate.id}'' is not "
                       "zero at rest there)", equilibrium / (1 + sp.Abs(stiffness)))
        self._linearised[coordinate.id] = (stiffness, damping, requirement)
        self.requirements.append(requirement)
        return stiffness, damping

    def stiffness(self) -> sp.Matrix:
        """K of q'' = -K (q - q_eq) + ... for every coordinate, the motion linearised about the
        instant's configuration (rates zero there), which must be an equilibrium (recorded)."""
        if "*" in self._linearised:
            K, requirement = self._linearised["*"]
            self.requirements.append(requirement)
            return K
        k = self.kinematics
        if k.velocity:
            raise SolveError("natural modes need coordinates without constraints",
                             where=self.where)
        unknowns = (*k.qdd, *self.reactions)
        A, b = sp.linear_eq_to_matrix([e.expr for e in self.balances], list(unknowns))
        if A.rows != A.cols:
            raise SolveError("natural modes need as many momentum balances as unknown "
                             "accelerations and reactions", where=self.where)
        n = len(k.q)
        rest = {qd: 0 for qd in k.qd}
        x = A.LUsolve(b)
        K = sp.zeros(n, n)
        for j, q in enumerate(k.q):
            dx = A.LUsolve(b.diff(q) - A.diff(q) * x)
            for i in range(n):
                K[i, j] = self._within_reach(-dx[i].xreplace(rest))
        off = sum((sp.Abs(x[i].xreplace(rest)) for i in range(n)), sp.Integer(0))
        requirement = (REASONS[Modal.EQUILIBRIUM],
                       off / (1 + sum((sp.Abs(e) for e in K), sp.Integer(0))))
        self._linearised["*"] = (K, requirement)
        self.requirements.append(requirement)
        return K

    def _within_reach(self, entry):
        """A stiffness entry with its signs cancelled (:func:`_without_signs`), refused when it
        is too large for that (and the frequencies built from it) to finish in seconds."""
        size = sp.count_ops(entry)
        if size > SYMBOLIC_MODE_OPS:
            raise SolveError(f"natural modes in symbols are out of reach for this model (an "
                             f"entry of its stiffness matrix has {size} operations, more than "
                             f"{SYMBOLIC_MODE_OPS}): expected 'kind: scalar' (worked out with "
                             "numbers), found 'kind: symbolic'", where=self.where)
        return _without_signs(entry)

    def _mode_number(self, number: Node) -> int:
        k = self.kinematics
        # a massless junction's balance is the one constraint modes are worked out with:
        # the motion is restricted to the configurations that keep it
        held = [e for e in k.position if is_junction_balance(e.label)]
        if len(k.velocity) != len(held):
            raise SolveError("natural modes need coordinates without constraints",
                             where=self.where)
        n = len(k.q) - len(held)
        value = constant_value(number)
        if value is None or value != int(value) or not 1 <= value <= n:
            what = "the coordinates" if not held else \
                "the coordinates less the junctions' balances"
            raise SolveError(f"expected a mode number 1 to {n} ({what}), found "
                             f"'{to_text(number)}'", where=self.where)
        return int(value)

    def _numeric_mode(self, what: Modal, number: int, i: int = 0, j: int = 0):
        """A mode's value worked out with numbers (:mod:`.vibration`), which a symbolic
        determinant of a multibody system may take hours to give. Its existence (an
        equilibrium, stable; for a damping ratio, a mode that does not move freely and whose
        roots are told from the others'; for a shape, a reference coordinate that moves in it)
        is recorded."""
        if self.symbolic:  # only a damping ratio of two or more coordinates comes here
            raise SolveError(f"a mode's damping ratio in symbols is worked out for one "
                             f"coordinate; this problem has {len(self.kinematics.q)}: expected "
                             "'kind: scalar' (worked out with numbers), found 'kind: symbolic'",
                             where=self.where)
        if "modal" not in self._linearised:
            self._linearised["modal"] = self._modal_entries()
        n, m, entries = self._linearised["modal"]
        checks = [Modal.EQUILIBRIUM, Modal.STABLE] + \
            ([Modal.FREE, Modal.PAIRED] if what == Modal.DAMPING_RATIO else []) + \
            ([Modal.COUPLED] if what == Modal.SHAPE else [])
        for check in checks:
            self.requirements.append((REASONS[check].format(number=number),
                                      NaturalMode(check, number, i, j, n, m, *entries)))
        return NaturalMode(what, number, i, j, n, m, *entries)

    def _modal_entries(self):
        k = self.kinematics
        unknowns = (*k.qdd, *self.reactions)
        A, b = sp.linear_eq_to_matrix([e.expr for e in self.balances], list(unknowns))
        if A.rows != A.cols:
            raise SolveError("natural modes need as many momentum balances as unknown "
                             "accelerations and reactions", where=self.where)
        rest = {qd: 0 for qd in k.qd}

        def at_rest(matrix):
            return without_deltas(matrix.xreplace(rest))

        held = [e.expr for e in k.position if is_junction_balance(e.label)]
        entries = modal_entries(at_rest(A), at_rest(b),
                                [at_rest(A.diff(q)) for q in k.q], [at_rest(b.diff(q)) for q in k.q],
                                [at_rest(A.diff(r)) for r in k.qd], [at_rest(b.diff(r)) for r in k.qd],
                                sp.Matrix(held).jacobian(k.q) if held else None)
        return len(k.q), A.rows, entries

    def _mode(self, value: int):
        """The squared natural frequency of mode ``value`` (1 the lowest) and the stiffness
        matrix in symbols, for one or two coordinates."""
        if len(self.kinematics.q) > 2:
            raise SolveError(f"natural modes in symbols are worked out for one or two "
                             f"coordinates; this problem has {len(self.kinematics.q)}: "
                             "expected 'kind: scalar' (worked out with numbers), found "
                             "'kind: symbolic'", where=self.where)
        K = self.stiffness()
        if K.rows == 1:
            return K[0, 0], K
        # the 2x2 determinant written out: Matrix.det() simplifies its pivots, which takes
        # hours on the entries of a linearised multibody system
        trace, det = K[0, 0] + K[1, 1], K[0, 0] * K[1, 1] - K[0, 1] * K[1, 0]
        root = sp.sqrt(trace ** 2 - 4 * det)
        return _tidy((trace - root) / 2 if value == 1 else (trace + root) / 2), K

    def _fn_mode_frequency(self, number: Node):
        value = self._mode_number(number)
        if not self.symbolic:
            return self._numeric_mode(Modal.FREQUENCY, value)
        squared, _ = self._mode(value)
        return sp.sqrt(squared)

    def _fn_mode_damping(self, number: Node):
        value = self._mode_number(number)
        if self.symbolic and len(self.kinematics.q) == 1:
            return self._fn_zeta(Name(self.kinematics.coordinates[0]))
        return self._numeric_mode(Modal.DAMPING_RATIO, value)

    def _fn_mode_shape(self, number: Node, coordinate: Name, reference: Name):
        value = self._mode_number(number)
        names = list(self.kinematics.coordinates)
        i, j = names.index(coordinate.id), names.index(reference.id)
        if i == j:
            return sp.Integer(1)
        if not self.symbolic:
            return self._numeric_mode(Modal.SHAPE, value, i, j)
        squared, K = self._mode(value)
        if not identically_zero(K[0, 1]):
            shape = (K[0, 1], squared - K[0, 0])
        elif not identically_zero(K[1, 0]):
            shape = (squared - K[1, 1], K[1, 0])
        else:
            raise SolveError("the coordinates are not coupled: each mode moves one of them "
                             "only", where=self.where)
        return _tidy(shape[i] / shape[j])

    def _fn_omega_n(self, coordinate: Name):
        stiffness, _ = self.linearised(coordinate)
        return sp.sqrt(stiffness)

    def _fn_zeta(self, coordinate: Name):
        stiffness, damping = self.linearised(coordinate)
        return damping / (2 * sp.sqrt(stiffness))

    def _fn_eom(self, coordinate: Name):
        from .symbols import TIME_SYMBOL
        return self.dyn[coordinate.id].diff(TIME_SYMBOL, 2)


def derive_kinetics(problem: Problem) -> Kinetics:
    """The momentum balances, reactions, friction checks and objectives of ``problem``."""
    read = _READ.get(id(problem))
    if read is not None and read[0] is problem:
        return read[1]
    return _derive_kinetics(problem, locations(problem))


_READ: dict[int, tuple[Problem, Kinetics]] = {}


def read_kinetics(problem: Problem, source: Problem, kin: Kinetics) -> Kinetics | None:
    """The kinetics of ``problem``, ``source`` (whose kinetics is ``kin``) with other
    objectives, another event to integrate to, or other rates just before its impact (the
    same model): the source's balances (their rates before put in: :class:`RatesBefore`),
    only the objectives and the event read in its model (what :func:`derive_kinetics` gives
    ``problem`` from now on); ``None`` when the two differ in more."""
    struck = _struck_otherwise(problem, source)
    # a design's condition is read in the source's rates before
    if not readable_in(problem, source) or (struck and kin.design is not None):
        return None
    model, loads, language = kin.built
    before = kin.before
    if struck and before is not None:
        analysis = dynamics_of(problem).analysis
        assert isinstance(analysis, Impulse)
        values = _values_before(analysis, model, kin.k)
        if any(not v.is_zero for qd, v in values.items() if qd not in before.rates):
            return None  # a rate the source's balances take as zero
        language = language.with_rates_before(dict(zip(language.before, values.values())))
        before = replace(before, values=tuple(values[qd] for qd in before.rates))
    objectives, mistakes, requirements = _objective_values(problem, model, language)
    read = replace(kin, objectives=tuple(objectives), mistakes=tuple(mistakes),
                   requirements=tuple(requirements), whens=_whens(problem, model, language),
                   until=kin.until if problem.dynamics == source.dynamics
                   else _analysis(problem, model, language, kin.k)[1],
                   before=before, built=(model, loads, language))
    if len(_READ) >= 256:
        _READ.clear()
    _READ[id(problem)] = (problem, read)
    return read


def readable_in(problem: Problem, source: Problem) -> bool:
    """Whether ``problem`` is ``source`` with other objectives, another event to integrate
    to, or other rates just before its impact: its kinetics read in the source's balances
    (:func:`read_kinetics`), not derived again.

    >>> from dataclasses import replace
    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("problems") / "ruina_9_25_units_matrix.yaml")
    >>> impact = p.dynamics.analysis
    >>> struck = replace(p, dynamics=replace(p.dynamics, analysis=replace(
    ...     impact, start=impact.start[:1])))
    >>> readable_in(struck, p), readable_in(replace(struck, parameters=()), p)
    (True, False)
    """
    return replace(problem, objectives=()) == replace(_as_read(problem, source), objectives=())


def _as_read(problem: Problem, source: Problem) -> Problem:
    """``source`` integrated to ``problem``'s event where both are integrated, or struck with
    ``problem``'s rates just before where both are impacts (the same model read otherwise)."""
    a, b = (p.dynamics.analysis if p.dynamics else None for p in (problem, source))
    if isinstance(a, Integration) and isinstance(b, Integration) and a.until != b.until:
        changed: Analysis = replace(b, until=a.until)
    elif isinstance(a, Impulse) and isinstance(b, Impulse) and a.start != b.start:
        changed = replace(b, start=a.start)
    else:
        return source
    return replace(source, dynamics=replace(dynamics_of(source), analysis=changed))


def _struck_otherwise(problem: Problem, source: Problem) -> bool:
    """Whether ``problem`` and ``source`` are impacts with other rates just before."""
    a, b = (p.dynamics.analysis if p.dynamics else None for p in (problem, source))
    return isinstance(a, Impulse) and isinstance(b, Impulse) and a.start != b.start


@lru_cache(maxsize=64)
def _derive_kinetics(problem: Problem, _locations: tuple) -> Kinetics:
    d = dynamics_of(problem)
    k = derive(kinematic_part(problem))
    check_junctions(problem, k)
    model = build(problem)
    reactions, labels = _reaction_symbols(d)
    loads = _Loads(problem, model, reactions)
    loads.build()
    inertias = _inertias(d, model)
    language = DynamicsInterpreter(problem, model, loads, inertias)
    analysis = d.analysis
    impact = isinstance(analysis, Impulse)
    values = _values_before(analysis, model, k) if isinstance(analysis, Impulse) else {}
    functions = {qd: model.symbols.dyn[c].diff(dynamicsymbols._t)
                 for c, qd in zip(k.coordinates, k.qd)}
    language.before = {functions[qd]: v for qd, v in values.items()}
    # the rates before that are not zero stand in the balances as inputs (RatesBefore)
    rates = tuple(qd for qd, v in values.items() if not v.is_zero)
    inputs = RatesBefore(rates, tuple(sp.Dummy("before") for _ in rates),
                         tuple(values[qd] for qd in rates))
    stand = {functions[qd]: inputs.symbols[rates.index(qd)] if qd in rates else v
             for qd, v in values.items()}
    written: list[Equation] = []
    compact: list[sp.Expr] = []
    junctions = {b.name for b in d.junctions}
    for b in d.bodies:
        if b.name in junctions:  # its balance is a constraint of the kinematics
            continue
        for label, expr in _body_balances(problem, model, loads, inertias, b, stand, impact):
            if b.name in d.unbalanced and " balance about " in label:
                continue
            compact.append(model.plain(expr))
            written.append(Equation(label, sp.expand(compact[-1]), b.where))
    kept = [(e, shown, c) for e, shown, c in zip(written, inputs.shown(written), compact)
            if not identically_zero(shown.expr)]
    balances = [shown for _, shown, _ in kept]
    check_loads(problem, model, loads, k.qd if impact else k.qdd, balances,
                k.velocity if impact else k.acceleration, impact)
    language.kinematics = k
    language.balances = tuple(balances) + k.acceleration
    language.reactions = tuple(s for v in reactions.values() for s in v)
    written = [e for e, _, _ in kept]
    compact = [c for _, _, c in kept]
    if isinstance(analysis, Impulse):
        contacts = _contact_conditions(analysis, model, loads, stand)
        balances += inputs.shown(contacts)
        written += contacts
        compact += [c.expr for c in contacts]
    objectives, mistakes, requirements = _objective_values(problem, model, language)
    bounds, slips = _friction_checks(d, model, loads, language, reactions)
    start, until, settled = _analysis(problem, model, language, k)
    weights = _weight_potentials(d, model, language, k)
    kin = Kinetics(k=k, reactions=tuple(s for v in reactions.values() for s in v),
                   labels=tuple(labels), written=tuple(written), compact=tuple(compact),
                   objectives=tuple(objectives), mistakes=tuple(mistakes), bounds=tuple(bounds),
                   slips=tuple(slips),
                   energy=model.plain(_energy(problem, language)) + sum(
                       weights.values(), sp.Integer(0)),
                   nonconservative=tuple(x.name for x in (*d.forces, *d.couples, *d.dampers,
                                                          *d.friction)
                                         if not isinstance(x, StaticFriction)
                                         and x.name not in weights),
                   workless=_workless(problem, model, language, reactions, labels),
                   start=start, settled=settled, until=until, requirements=tuple(requirements),
                   impact=impact,
                   design=_difference(d.design.so_that, model, language) if d.design else None,
                   physical=physical_bounds(problem, model, reactions, impact),
                   whens=_whens(problem, model, language),
                   before=inputs if impact else None, built=(model, loads, language))
    if impact:  # the rates before put in already, for the checks above
        kin.__dict__["balances"] = tuple(balances)
    return kin


def _whens(problem: Problem, model: Model, language: DynamicsInterpreter
           ) -> tuple[tuple[str, sp.Expr], ...]:
    return tuple((o.id, _difference(o.when, model, language))
                 for o in problem.objectives if o.when is not None)


def free_body_loads(problem: Problem) -> tuple[AppliedLoad, ...]:
    """Every body's free-body diagram in the model's symbols (:func:`.loads.diagram`), built
    the first time it is asked for (solving does not need it).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
    >>> [(a.name, str(a.kind), a.point, a.unknowns) for a in free_body_loads(p)]
    [('gravity', 'weight', 'G', ()), ('R_O', 'pin', 'O', (R_O_1, R_O_2))]
    """
    return _free_body_loads(problem, locations(problem))


@lru_cache(maxsize=64)
def _free_body_loads(problem: Problem, _locations: tuple) -> tuple[AppliedLoad, ...]:
    model, loads, _ = derive_kinetics(problem).built
    return diagram(problem, model, loads)


def _reaction_symbols(d: Dynamics) -> tuple[dict[str, tuple[sp.Symbol, ...]], list[str]]:
    """One unknown per direction of each reaction and static-friction force, with labels."""
    reactions: dict[str, tuple[sp.Symbol, ...]] = {}
    labels: list[str] = []
    unknown: tuple[Reaction | StaticFriction, ...] = (
        *d.reactions, *(f for f in d.friction if isinstance(f, StaticFriction)))
    for r in unknown:
        names = [r.name] if len(r.directions) == 1 else \
            [f"{r.name}_{i + 1}" for i in range(len(r.directions))]
        reactions[r.name] = tuple(sp.Symbol(n, real=True) for n in names)
        labels += [f"{r.name} (along {e.text})" for e in r.directions]
    return reactions, labels


def _inertias(d: Dynamics, model: Model) -> dict[str, list]:
    """Each body's parts ``(mass, centre, central inertia or None)``."""
    lang = model.language
    inertias: dict[str, list] = {}
    for b in d.bodies:
        parts = []
        frame = model.frames[b.frame] if b.frame else None
        for part in b.parts:
            m = lang.scalar(part.mass)
            central = _central(part.shape, m, frame, lang) if frame is not None else None
            if frame is not None:
                _check_fixed(model, part.at, b, frame, part.where)
            parts.append((m, part.at, central))
        inertias[b.name] = parts
    return inertias


def _kinetics_lines(problem: Problem, kin: Kinetics) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """The write-up of ``kin`` (``problem``'s kinetics): the bodies (the parallel-axis shift
    of every part to the body's reference point), free-body loads, momentum balances and
    unknown reactions."""
    d = dynamics_of(problem)
    model, loads, _ = kin.built
    inertias = _inertias(d, model)
    bodies: list[str] = []
    for b in d.bodies:
        parts = inertias[b.name]
        total = Dyadic(0)
        if b.frame:
            frame = model.frames[b.frame]
            for m, at, central in parts:
                offset = model.positions[at] - model.positions[b.centre]
                total += parallel_axis(central if central is not None else Dyadic(0), m,
                                       offset, frame)
        bodies += _body_lines(b, parts, total, model)
    return (("Bodies", tuple(bodies)),
            ("Free-body loads", tuple(_load_line(b, loads, model) for b in d.bodies)),
            ("Momentum balances", tuple(f"{e.label}: {sp.sstr(e.expr)} = 0"
                                        for e in kin.balances)),
            ("Unknown reactions", tuple(kin.labels) or ("none",)))


def _values_before(analysis: Impulse, model: Model, k: Kinematics) -> dict:
    """The rates just before an impact (those not named in ``before:`` are 0), keyed by the
    rates' symbols in the order of the coordinates."""
    lang = model.language
    values = {k.quantity(s.key.node): (sp.nsimplify(s.si) if s.si == 0 else sp.Float(s.si))
              if s.value is None else model.plain(lang.scalar(s.value))
              for s in analysis.start}
    return {qd: values.get(qd, sp.Integer(0)) for qd in k.qd}


def _load_line(body: Body, loads: _Loads, model: Model) -> str:
    forces, couples = loads.on(body.name)
    return f"{body.name}: " + "; ".join(
        [f"{name} at {p}: {model.plain(F)}" for name, p, F in forces]
        + [f"couple {name}: {model.plain(M)}" for name, M in couples])


def _body_balances(problem: Problem, model: Model, loads: _Loads, inertias: dict, b: Body,
                   before: dict, impact: bool) -> list[tuple[str, object]]:
    """The linear (and, for a rigid body, angular) momentum balance of body ``b`` as
    ``(label, expression = 0)`` in inertial components; during an impact only the impulses act
    and the momenta change by them."""
    N, lang = model.inertial, model.language
    forces, couples = loads.on(b.name)
    if impact:
        forces = [(name, p, F) for name, p, F in forces if loads.impulsive(name)]
        couples = []

    def motion(at: str) -> Vector:
        """The velocity change (impact) or the acceleration of point ``at``."""
        if impact:
            v = lang.point_velocity(Name(at), problem.inertial_frame)
            return v - v.subs(before)
        return lang.point_acceleration(Name(at), problem.inertial_frame)

    axes = [f"{problem.inertial_frame}.{a}" for a in "xyz"]
    total = sum((F for _, _, F in forces), Vector(0))
    ma = sum((m * motion(at) for m, at, _ in inertias[b.name]), Vector(0))
    linear = (total - ma).to_matrix(N)
    kind = "impulse-momentum" if impact else "force"
    equations = [(f"body {b.name}: {axes[i]} {kind} balance", linear[i]) for i in range(3)]
    if b.frame is None:
        return equations
    C = model.positions[b.centre]
    moment = sum((M for _, M in couples), Vector(0))
    for _, p, F in forces:
        moment += (model.positions[p] - C) ^ F
    omega = model.frames[b.frame].ang_vel_in(N)
    rate = Vector(0)
    for m, at, central in inertias[b.name]:
        rate += (model.positions[at] - C) ^ (m * motion(at))
        if central is None:
            continue
        spin = central & omega
        rate += spin - spin.subs(before) if impact else spin.dt(N)
    angular = (moment - rate).to_matrix(N)
    kind = "angular impulse-momentum" if impact else "moment"
    return equations + [(f"body {b.name}: {kind} balance about {b.centre} ({axes[i]} "
                         "component)", angular[i]) for i in range(3)]


def balance_part(label: str) -> tuple[str, bool] | None:
    """The body a momentum balance (by its label, as :func:`_body_balances` writes it) is of,
    and whether it is a moment balance; ``None`` for another equation (a constraint).

    >>> balance_part("body rod: N.x force balance"), balance_part("body rod: moment balance about G (N.z component)")
    (('rod', False), ('rod', True))
    >>> balance_part("rolling at P") is None
    True
    """
    if not label.startswith("body ") or ": " not in label:
        return None
    body, rest = label[len("body "):].split(": ", 1)
    return body, " balance about " in rest


def _contact_conditions(analysis: Impulse, model: Model, loads: _Loads,
                        before: dict) -> tuple[Equation, ...]:
    """The restitution and sticking conditions of an impact's contacts."""
    lang = model.language
    out = []
    for i, c in enumerate(analysis.contacts):
        relative = loads.velocity(c.bodies[0], c.at) - loads.velocity(c.bodies[1], c.at)
        if isinstance(c, Restitution):
            after = relative & lang.vector(c.direction)
            rows = [(f"contact {i + 1} at {c.at}: restitution",
                     after + lang.scalar(c.e) * after.subs(before))]
        else:
            rows = [(f"contact {i + 1} at {c.at}: sticking along {e.text}",
                     relative & lang.vector(e)) for e in c.directions]
        out += [Equation(label, sp.expand(model.plain(expr)), c.where) for label, expr in rows]
    return tuple(out)


def _objective_values(problem: Problem, model: Model, language: DynamicsInterpreter):
    """Each objective's and mistake's value in the model's quantities, and the requirements
    they need at the instant."""
    objectives, mistakes, requirements = [], [], []
    view = replace(model, language=language)
    for obj in problem.objectives:
        language.where = obj.where
        language.symbolic = obj.kind == ObjectiveKind.SYMBOLIC
        read = [language.reading(view, find, obj.frame)
                for find in (obj.find, *(m.find for m in obj.mistakes))]
        objectives.append((obj.id, read[0][0]))
        mistakes.append((obj.id, tuple(value for value, _ in read[1:])))
        requirements += [(obj.id, reason, model.plain(expr))
                         for _, needs in read for reason, expr in needs]
    return objectives, mistakes, requirements


def _friction_checks(d: Dynamics, model: Model, loads: _Loads, language, reactions: dict):
    """The bound of every static-friction contact and the slip of every kinetic one."""
    bounds, slips = [], []
    N = model.inertial
    for f in d.friction:
        normal = reactions[f.normal][0]
        if isinstance(f, StaticFriction):
            force = model.plain(language._load_force(Name(f.name)).to_matrix(N))
            bounds.append(FrictionBound(f.name, f.on, f.at, force, normal,
                                model.plain(model.language.scalar(f.mu)), f.where))
        else:
            speed = model.plain(loads.slip_velocity(f).magnitude())
            slips.append(Slip(f.name, f.at, speed, normal, f.where))
    return bounds, slips


def _energy(problem: Problem, language: DynamicsInterpreter):
    """Kinetic plus potential energy of every body and spring, in the inertial frame."""
    d = dynamics_of(problem)
    N_node = Name(problem.inertial_frame)
    energy = sum((language._fn_ke(Name(b.name), N_node) + language._fn_pe(Name(b.name))
                  for b in d.bodies), sp.Integer(0))
    return energy + sum((language._fn_pe(Name(s.name)) for s in d.springs), sp.Integer(0))


def _weight_potentials(d: Dynamics, model: Model, language, k: Kinematics) -> dict:
    """Each weight written as a force whose vector does not change with the motion -> its
    potential energy -W·r (a constant force is conservative), for a work-energy balance."""
    moving = {*k.q, *k.qd, dynamicsymbols._t}
    out = {}
    for f in d.forces:
        if f.kind != LoadKind.WEIGHT:
            continue
        weight = language.vector(f.force)
        if any(model.plain(c).free_symbols & moving for c in weight.to_matrix(model.inertial)):
            continue
        out[f.name] = model.plain(-(weight & model.positions[f.at]))
    return out


def _workless(problem: Problem, model: Model, language, reactions: dict, labels: list[str]):
    """The power of each reaction component per unit magnitude (zero for a workless one)."""
    out = []
    N_node = Name(problem.inertial_frame)
    for name, symbols in reactions.items():
        power = model.plain(language._fn_power(Name(name), N_node))
        out += [(label, sp.diff(power, s)) for s, label in
                zip(symbols, [lb for lb in labels if lb.startswith(name + " ")])]
    return tuple(out)


def _difference(equation, model: Model, language) -> sp.Expr:
    left, right = (model.plain(language.value(e.node)) for e in equation)
    return left - right


def _analysis(problem: Problem, model: Model, language, k: Kinematics):
    """The start state (plain symbol -> value; rates not named are 0) and the event."""
    d = dynamics_of(problem)
    analysis = d.analysis
    if analysis is None or isinstance(analysis, Impulse):
        return (), None, ()
    if isinstance(analysis, WorkEnergy) and d.junctions:
        raise SolveError(f"work-energy with a massless junction ({d.junctions[0].name}): its "
                         "position at the start and at the instant is fixed by its balance, "
                         "which an energy balance does not solve; expected the motion "
                         "integrated: analysis: {integrate: {from: ..., until: ...}}",
                         where=analysis.where)
    values = {}
    for s in analysis.start:
        symbol = k.quantity(s.key.node)
        values[symbol] = sp.nsimplify(s.si) if s.value is None and s.si == 0 else \
            sp.Float(s.si) if s.value is None else model.plain(language.scalar(s.value))
    # a junction's coordinate and rate not named are settled by its balance at the start
    own = {k.q[k.coordinates.index(c)] for c in junction_coordinates(problem)}
    own |= {k.qd[k.q.index(q)] for q in own}
    start = tuple((q, values[q]) for q in k.q if q in values or q not in own) + \
        tuple((qd, values.get(qd, sp.Integer(0))) for qd in k.qd
              if qd in values or qd not in own)
    settled = tuple(s for s in (*k.q, *k.qd) if s in own and s not in values)
    until = None
    if isinstance(analysis, Integration):
        left, right = (model.plain(language.value(e.node)) for e in analysis.until)
        until = left - right
    return start, until, settled


def _central(shape, m, frame, lang) -> Dyadic | None:
    return None if shape is None else central_inertia(shape, m, frame, lang.scalar)


def _check_fixed(model: Model, point: str, body: Body, frame: ReferenceFrame,
                 where: Location) -> None:
    relative = (model.positions[point] - model.positions[body.centre]).dt(frame)
    if not all(identically_zero(model.plain(c)) for c in relative.to_matrix(frame)):
        raise SolveError(f"the centre '{point}' of a part of body '{body.name}' moves relative "
                         f"to its frame {body.frame}; expected a point fixed in the body",
                         where=where)


def _body_lines(body: Body, parts, total: Dyadic, model: Model) -> list[str]:
    mass = sum((m for m, _, _ in parts), sp.Integer(0))
    if body.frame is None:
        return [f"{body.name}: particle of mass {sp.sstr(mass)} at {body.centre}"]
    frame = model.frames[body.frame]
    lines = [f"{body.name}: rigid body, frame {body.frame}, mass {sp.sstr(mass)}, "
             f"reference point {body.centre}"]
    for m, at, central in parts:
        own = _matrix_text(central.to_matrix(frame)) if central is not None \
            else "0 (point mass)"
        offset = model.plain(model.positions[at] - model.positions[body.centre])
        if offset == Vector(0):
            lines.append(f"  part of mass {sp.sstr(m)} at {at}: I_{at} = {own}")
        else:
            lines.append(f"  part of mass {sp.sstr(m)} at {at}: I_{at} = {own}; shifted to "
                         f"{body.centre} by r = {offset}: I + m (|r|^2 U - r r)")
    matrix = sp.simplify(model.plain(total.to_matrix(frame))) if total != Dyadic(0) else 0
    lines.append(f"  I_{body.centre} (in {body.frame} axes) = {_matrix_text(matrix)}")
    return lines


SYMBOLIC_MODE_OPS = 2000
"""The most operations a stiffness entry may have for natural modes in symbols (the pendulum
hung from a cart on a spring: 323 at most): sympy's cancel, and the frequencies' square roots
of sums of products of such entries, grow past what finishes in seconds beyond it."""


def _without_signs(expr):
    """``expr`` with ``sign(u)`` written ``u/|u|`` and cancelled: a spring's stiffness k, not
    k (1 - L/|u| + L u sign(u)/u^2), which holds wherever its length u is not zero."""
    expr = expr.replace(sp.DiracDelta, lambda *_: sp.Integer(0))
    return sp.cancel(expr.replace(sp.sign, lambda u: u / sp.Abs(u)))


def _linear_term(expr):
    """A coefficient of the linearised motion, tidied; a spring along the coordinate has |q|
    in its length, whose simplified derivative is a Piecewise with zoo at q = 0 (lambdify
    cannot print it): then with the signs cancelled first (:func:`_without_signs`)."""
    tidy = _tidy(expr)
    if tidy.has(sp.zoo, sp.Piecewise):
        return _tidy(_without_signs(expr))
    return tidy


def _tidy(expr):
    """A simpler form when one is cheap to find (the solver lambdifies either)."""
    if sp.count_ops(expr) > 400:
        return expr
    try:
        simple = sp.simplify(expr)
    except TypeError:  # sympy's simplify can trip over its own comparisons (NaN)
        return expr
    return simple if sp.count_ops(simple) <= sp.count_ops(expr) else expr


def _matrix_text(matrix) -> str:
    if not isinstance(matrix, sp.MatrixBase):
        return sp.sstr(matrix)
    return "[" + "; ".join(", ".join(sp.sstr(e) for e in matrix.row(i))
                           for i in range(matrix.rows)) + "]"


def how_the_instant(problem: Problem) -> str:
    """How a dynamics problem reaches its instant, in words (its ``analysis``)."""
    analysis = dynamics_of(problem).analysis
    if isinstance(analysis, Integration):
        grips = [f for f in dynamics_of(problem).friction
                 if isinstance(f, KineticFriction) and f.then is not None]
        phases = "".join(f", {f.name} kinetic until its slip ends, then gripping (static "
                         f"friction, |F| <= {f.then.mu.text} N)" for f in grips if f.then)
        return (f"integrated from t = 0{phases} until {analysis.until[0].text} = "
                f"{analysis.until[1].text}; the objectives are read there")
    if isinstance(analysis, Impulse):
        return "an impact: the rates given are those just after it, the reactions are impulses"
    if analysis is not None:
        return ("the givens fix the configuration; the work-energy balance from the start "
                "state fixes the rates")
    return "the givens state the configuration and the rates at the instant"


def _where_asked(objective, integrated: bool = False) -> str:
    """Where an objective asked ``when`` is read, for the write-up."""
    if objective.when is None:
        return ""
    left, right = objective.when
    if integrated:
        return f", at the first instant of the integrated motion where {left.text} = {right.text}"
    return (f", at the first position from the start where {left.text} = {right.text} "
            "(the rate from the energy balance)")


def kinetics_derivation(problem: Problem, dof: int | None = None):
    """The write-up of a dynamics problem: the kinematics, then bodies (with the parallel-axis
    shifts), free-body loads, momentum balances, the unknowns and how they are solved, and
    each objective in the model's quantities."""
    kin = derive_kinetics(problem)
    kinematics = kinematics_derivation(kinematic_part(problem), dof)
    mark = "'" if kin.impact else "''"
    unknowns = [f"{c}{mark}" for c in kin.k.coordinates] + list(kin.labels)
    level = "velocity" if kin.impact else "acceleration"
    solved = (f"instant: {how_the_instant(problem)}",
              f"unknowns: {', '.join(unknowns)} (those not given)",
              f"{len(kin.balances)} momentum balances and {len(kin.constraints)} "
              f"{level}-level constraints, linear in the unknowns, solved together "
              "(rank and every equation checked)")
    integrated = isinstance(dynamics_of(problem).analysis, Integration)
    objectives = tuple(f"{o.id}: {o.find.text} = {_matrix_text(value)}"
                       f"{_where_asked(o, integrated)}"
                       for o, (_, value) in zip(problem.objectives, kin.objectives))
    return (*kinematics[:-2], *_kinetics_lines(problem, kin), ("Solution", solved),
            ("Objectives in the model's quantities", objectives))


# Functions take attributes at run time; mypy models none (python/mypy#2087).
derive_kinetics.cache_clear = _derive_kinetics.cache_clear  # type: ignore[attr-defined]
