"""Equations of motion written as equations (``m x'' = m g sin(β) - mu_k N``), read safely and
judged against the model's motion (:func:`mechgrade.solve.derivation.motion_samples`).

An equation is right when it holds for the model's accelerations at every sampled state, for
some value of the unknowns of the student's own (names that are not the problem's symbols,
such as a reaction ``N``), the same values in every equation of the set: so any rearrangement,
scaling or combination of the model's equations is right, and so is any name or sign for a
reaction. The set is complete when it determines every acceleration.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.solve import solve
>>> from mechgrade.solve.derivation import motion_samples
>>> problem = load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml")
>>> samples = motion_samples(problem, solve(problem))
>>> judged = judge_equations("m x'' = m g sin(β) - μ_k N; N = m g cos(β)", samples)
>>> judged.verdict, judged.credit
(<Verdict.CORRECT: 'correct'>, 1.0)
>>> judged = judge_equations("m x'' = m g sin(β) - μ_k N; N = m g sin(β)", samples)
>>> judged.verdict, [row.right for row in judged.rows]
(<Verdict.PARTIAL: 'partial'>, [True, False])
"""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass
from itertools import combinations

import numpy as np

from ..errors import AnswerError, ExpressionError
from ..expressions import syntax
from ..expressions.excerpt import excerpt
from ..expressions.functions import StrEnum
from ..expressions.numeric import evaluate
from ..expressions.syntax import Bin, Node, Unary
from ..solve import rules
from ..solve.derivation import MotionSamples, SampledLoad
from ..spec.dynamics import LoadKind
from ..tolerance import parts
from .answers import rename_to_symbols
from .compare import Assessment, Judged, not_evaluated, unreadable
from .results import Verdict

MAX_EQUATIONS = 12
MAX_UNKNOWNS = 12
REL = 1e-3
"""An equation holds when its two sides differ by at most this share of their size (the
values are the model's own, so only rounding is forgiven: 9.81 for g, 0.866 for cos 30°)."""
FIT = 1e-6
"""How closely an unknown's values over a configuration's states must follow a fixed
combination of the model's reactions or accelerations: both are exact where the equations
hold exactly, and a share of the reactions that is wrong follows none but by a chance far
larger than this."""


class LoadSlip(StrEnum):
    """What a wrong equation does to one of the model's loads."""

    MISSING = "missing"
    DOUBLED = "doubled"
    TURNED_ROUND = "turned round"


_SAID = {LoadSlip.MISSING: "is missing from", LoadSlip.DOUBLED: "is counted twice in",
         LoadSlip.TURNED_ROUND: "is turned round in"}
_COUNTED = {LoadSlip.MISSING: "left out of", LoadSlip.DOUBLED: "counted twice in",
            LoadSlip.TURNED_ROUND: "turned round in"}
"""How a load's mistake in an equation is said on the feedback and counted by the class
report."""


@dataclass(frozen=True)
class StudentEquation:
    """One equation as read: ``residual`` is left side minus right side."""

    text: str
    residual: Node
    unknowns: tuple[str, ...]


@dataclass(frozen=True)
class EquationRow:
    """One equation judged; ``reversed_term`` is the term of a wrong one that is right but
    for its sign (a load drawn the other way), when one is; ``load`` the model's load that a
    wrong one leaves out or turns round (``load_mistake``), when one load fits."""

    equation: str
    right: bool
    feedback: str
    reversed_term: str | None = None
    load: str | None = None  # the model's load it leaves out or turns round, named
    load_mistake: LoadSlip | None = None
    balance: str | None = None  # the wrong body's or the wrong point's balance it is, named


@dataclass(frozen=True)
class EquationsJudgement(Judged):
    """A set of equations judged: a row per equation, whether the set determines every
    acceleration (``complete``), and the verdict and credit (``assessment``)."""

    rows: tuple[EquationRow, ...]
    complete: bool
    assessment: Assessment


def read_equations(text: str, samples: MotionSamples) -> tuple[StudentEquation, ...]:
    """Read ``text`` as equations separated by ``;`` (or line breaks); :class:`AnswerError`
    says why not.

    >>> samples = MotionSamples(("x", "m", "g", "xd"), ("xdd",), (), ((0.0, 2.0, 9.81, 0.0, -9.81),))
    >>> [e.text for e in read_equations("m x'' = -m g; m ẍ + mg = 0", samples)]
    ['m*xdd = -m*g', 'm*xdd+m*g = 0']
    >>> read_equations("m x'' == -m g", samples)
    Traceback (most recent call last):
    ...
    mechgrade.errors.AnswerError: expected an equation with one '=', found 'm x'' == -m g'
    """
    parts = [p.strip() for p in re.split(r"[;\n\r]", text) if p.strip()]
    if not parts:
        raise AnswerError("expected equations such as 'm x'' = -k x', found nothing")
    if len(parts) > MAX_EQUATIONS:
        raise AnswerError(f"expected at most {MAX_EQUATIONS} equations, found {len(parts)}")
    symbols = samples.symbols + samples.accelerations
    out = [_read_equation(part, symbols) for part in parts]
    unknowns = {u for e in out for u in e.unknowns}
    if len(unknowns) > MAX_UNKNOWNS:
        raise AnswerError(f"expected at most {MAX_UNKNOWNS} unknowns of your own, "
                          f"found {len(unknowns)}")
    return tuple(out)


def _read_equation(text: str, symbols: tuple[str, ...]) -> StudentEquation:
    if text.count("=") != 1:
        raise AnswerError(f"expected an equation with one '=', found {excerpt(text)}")
    left, right = text.split("=")
    try:
        sides = Bin("-", syntax.parse(left, attributes=False),
                    syntax.parse(right, attributes=False))
    except ExpressionError as exc:
        raise AnswerError(f"{exc.message} (in {excerpt(text)})") from None
    node, unknowns = rename_to_symbols(sides, symbols)
    assert isinstance(node, Bin)
    for name in unknowns:
        if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", name):
            raise AnswerError(f"expected the problem's symbols or names of your own for "
                              f"unknowns, found {excerpt(name)} (in {excerpt(text)})")
    shown = syntax.to_text(node.left) + " = " + syntax.to_text(node.right)
    return StudentEquation(shown, node, unknowns)


def judge_equations(text: str | None, samples: MotionSamples | None) -> EquationsJudgement:
    """Read and judge ``text`` as equations of motion of the model sampled in ``samples``."""
    if text is None or not text.strip():
        return EquationsJudgement((), False, Assessment(Verdict.MISSING, 0.0, None,
                                                        "No answer was given.", None))
    if samples is None:
        return EquationsJudgement((), False, not_evaluated(
            "the model has no solved state to judge the equations at"))
    try:
        equations = read_equations(text, samples)
        system = _System(equations, samples)
    except AnswerError as exc:
        return EquationsJudgement((), False, unreadable(exc.message))
    right = system.right()
    rows = []
    for i, (e, ok, trivial) in enumerate(zip(equations, right, system.trivial)):
        said = ("right" if ok else "says nothing about the motion" if trivial
                else "does not hold for the motion")
        fine = [r for r, good in enumerate(right) if good]
        found = None if ok or trivial else system.wrong_load(i, fine)
        # a balance of the wrong body or about the wrong point explains the whole misfit:
        # it is said before a load found only by its size (which fits by chance)
        balance = (None if ok or trivial or (found is not None and found[2])
                   else system.wrong_balance(i, fine))
        found = None if balance else found
        term = None if ok or trivial or balance else system.reversed_term(i, fine)
        named, how = (_naming(found[0]), found[1]) if found is not None else (None, None)
        if balance is not None:
            said += f" ({balance})"
        elif term is not None and how is LoadSlip.TURNED_ROUND:
            said += f" (its term {term} has the wrong sign: {named} is turned round in it)"
        elif term is not None:
            said += f" (its term {term} has the wrong sign)"
        elif named is not None and how is not None:
            said += f" ({named} {_SAID[how]} it)"
        rows.append(EquationRow(e.text, ok, f"{e.text}: {said}.", term, named, how, balance))
    complete = system.complete()
    count = sum(right)
    missing = 0 if complete else system.undetermined()
    credit = count / (len(rows) + missing)
    verdict = (Verdict.CORRECT if count == len(rows) and complete else Verdict.PARTIAL if count
               else Verdict.INCORRECT)
    notes = [row.feedback for row in rows if not row.right]
    if not complete:
        notes.append(f"The equations do not determine {system.undetermined_names()} "
                     f"(an equation is missing).")
    feedback = " ".join(notes) or "Every equation is right and they determine the motion."
    read_back = "; ".join(e.text for e in equations)
    # what the class report counts: each load left out or turned round, once
    counted = dict.fromkeys(
        [f"{_COUNTED[row.load_mistake]} an equation: {row.load}" for row in rows
         if row.load and row.load_mistake]
        + [f"an equation for {row.balance}" for row in rows if row.balance])
    return EquationsJudgement(tuple(rows), complete,
                              Assessment(verdict, credit, "; ".join(counted) or None, feedback,
                                         read_back))


class _System:
    """The equations' values at the samples, as ``A u + b`` in the unknowns ``u`` of the
    student's own (refused unless each is linear in them and in the accelerations), and their
    slopes along the accelerations at each state (``slopes``: at the first)."""

    def __init__(self, equations: tuple[StudentEquation, ...], samples: MotionSamples):
        self.equations, self.samples = equations, samples
        self.unknowns = tuple(dict.fromkeys(u for e in equations for u in e.unknowns))
        self.accelerations = samples.accelerations
        self.reactions = np.array([[samples.state(k)[r] for r in samples.reactions]
                                   for k in range(len(samples.states))])
        self.accelerations_sampled = np.array([[samples.state(k)[a] for a in
                                                samples.accelerations]
                                               for k in range(len(samples.states))])
        n_eq, n_u, n_s = len(equations), len(self.unknowns), len(samples.states)
        self.b = np.zeros((n_s, n_eq))
        self.a = np.zeros((n_s, n_eq, n_u))
        self.slopes_at = np.zeros((n_s, n_eq, len(self.accelerations)))
        self.scale = np.zeros((n_s, n_eq))
        for i, e in enumerate(equations):
            self._linear(i, e, samples)
        self.slopes = self.slopes_at[0]
        # an equation free of accelerations whose unknowns appear in no other one only
        # names them: it says nothing about the motion, unless it gives a reaction
        # (N = m g cos β); without unknowns either, it is an identity
        shared = [{u for u in e.unknowns
                   if any(u in other.unknowns for other in equations if other is not e)}
                  for e in equations]
        self.trivial = [not self.slopes_at[:, i].any() and not shared[i]
                        and (not e.unknowns or self._flips([i]) is None)
                        for i, e in enumerate(equations)]

    def _linear(self, i: int, e: StudentEquation, samples: MotionSamples) -> None:
        pairs = list(combinations(self.unknowns, 2))
        moves: list[dict[str, float]] = [{}]
        moves += [{u: 1.0} for u in self.unknowns] + [{u: 1.7} for u in self.unknowns]
        moves += [{u: 1.0, v: 1.0} for u, v in pairs]
        moves += [{a: 1.0} for a in self.accelerations]
        moves += [{a: 1.7} for a in self.accelerations]
        n, m = len(self.unknowns), len(self.accelerations)
        n_s, n_m = len(samples.states), len(moves)
        states = np.array(samples.states)
        # every state with every move, in one evaluation: state k's moves are row k
        env = {name: np.add.outer(states[:, c], [move.get(name, 0.0) for move in moves]).ravel()
               for c, name in enumerate(samples.symbols + samples.accelerations)}
        for u in self.unknowns:
            env[u] = np.tile([move.get(u, 0.0) for move in moves], n_s)
        f = evaluate(e.residual, env).reshape(n_s, n_m)
        if not np.all(np.isfinite(f)):
            raise AnswerError(f"expected equations defined at the problem's states, found "
                              f"{excerpt(e.text)} undefined (a division by zero?)")
        size = np.maximum(np.abs(f).max(axis=1), 1e-300)[:, None]

        def same(x: np.ndarray, y: np.ndarray) -> bool:
            return not parts(x - y, size if x.ndim == 2 else size[:, 0]).any()

        base = f[:, :1]
        self.a[:, i, :] = f[:, 1:1 + n] - base
        ok = same(f[:, 1 + n:1 + 2 * n] - base, 1.7 * self.a[:, i, :])
        for p, (u, v) in enumerate(pairs):
            ok = ok and same(f[:, 1 + 2 * n + p] - base[:, 0],
                             self.a[:, i, self.unknowns.index(u)]
                             + self.a[:, i, self.unknowns.index(v)])
        start = 1 + 2 * n + len(pairs)
        slope = f[:, start:start + m] - base
        ok = ok and same(f[:, start + m:start + 2 * m] - base, 1.7 * slope)
        if not ok:
            raise AnswerError(f"expected an equation linear in the accelerations and in "
                              f"each unknown of your own, found {excerpt(e.text)}")
        self.slopes_at[:, i] = slope
        self.b[:, i] = f[:, 0]
        self.scale[:, i] = _term_sizes(e.residual, env, n_m)

    def _holds(self, rows: list[int]) -> np.ndarray:
        """Whether each of ``rows`` holds at every sample with the unknowns fitted to them."""
        ok = np.ones(len(rows), dtype=bool)
        for k in range(len(self.b)):
            a, b = self.a[k][rows], self.b[k][rows]
            residual, size = b, self.scale[k][rows]
            if a.size:
                u = np.linalg.lstsq(a, -b, rcond=None)[0]
                residual = a @ u + b
                # the terms of the unknowns count at their values (every term of
                # 0 = N_F a - N_R b has one)
                size = np.maximum(size, np.abs(a) @ np.abs(u))
            ok &= np.abs(residual) <= REL * size + 1e-12
        return ok

    def right(self) -> list[bool]:
        """Whether each equation is right: all hold together; else, the one whose leaving out
        lets all the others hold is wrong; else each is judged with the unknowns fitted to it
        and the equations free of unknowns (which say nothing of an unknown alone)."""
        rows = list(range(self.b.shape[1]))
        ok = self._holds(rows)
        if ok.all() and not self._accounted(rows):
            # they hold only with unknowns that are not the model's reactions (nor its
            # accelerations, by a name of the student's): an unknown in one equation alone
            # takes up whatever is wrong in it
            ok[:] = False
        if not ok.all():
            known = [r for r in rows if not self.a[:, r, :].any()]
            ok = np.array([r in known and bool(self._holds([r])[0]) for r in rows])
            # with the others right, the unknowns come out as the model's reactions would
            wrong: list[tuple[int, int]] = []
            for i in rows:
                rest = [r for r in rows if r != i]
                flips = self._flips(rest) if rest and self._holds(rest).all() else None
                if flips is not None:
                    wrong.append((flips, i))
            # a reaction's sign is the student's to choose: the reading that flips the fewest
            # is taken when two are possible (N = m g cos β beside m x'' = ... + μ N)
            fewest = [i for flips, i in wrong if flips == min(f for f, _ in wrong)]
            if len(fewest) == 1:
                ok = np.array([r != fewest[0] for r in rows])
        return [bool(v) and not t for v, t in zip(ok, self.trivial)]

    def _misfits(self, i: int, right: list[int]) -> list[tuple[float, float, dict]] | None:
        """Equation ``i``'s misfit at each state with the unknowns the ``right`` equations
        give, the misfit it may have, and the values it was taken at; ``None`` when the
        unknowns are not all given, or it holds at every state (it may at some: a spring's
        force is nought where the spring has its free length)."""
        e = self.equations[i]
        out = []
        for k in range(len(self.b)):
            u = np.zeros(len(self.unknowns))
            if e.unknowns:  # their values from the right equations, when those fix them
                a = self.a[k][right]
                if not right or rules.matrix_rank(a) < len(self.unknowns):
                    return None
                u = np.linalg.lstsq(a, -self.b[k][right], rcond=None)[0]
            misfit = float(self.a[k][i] @ u + self.b[k][i])
            tol = REL * max(self.scale[k][i], float(np.abs(self.a[k][i]) @ np.abs(u))) + 1e-12
            env = {name: np.array([value]) for name, value in self.samples.state(k).items()}
            env.update({name: np.array([value]) for name, value in zip(self.unknowns, u)})
            out.append((misfit, tol, env))
        return None if all(abs(m) <= tol for m, tol, _ in out) else out

    def reversed_term(self, i: int, right: list[int]) -> str | None:
        """The one term of equation ``i`` that, with its sign changed, makes it hold with
        the unknowns the ``right`` equations give (its value half the equation's misfit at
        every state); ``None`` when there is none, or the unknowns are not all given."""
        misfits = self._misfits(i, right)
        if misfits is None:
            return None
        candidates = _signed_terms(self.equations[i].residual)
        for misfit, tol, env in misfits:
            candidates = [(sign, t) for sign, t in candidates
                          if abs(sign * float(evaluate(t, env)[0]) - misfit / 2) <= tol]
        return syntax.to_text(candidates[0][1]) if len(candidates) == 1 else None

    def wrong_load(self, i: int, right: list[int]) -> tuple[SampledLoad, LoadSlip, bool] | None:
        """The one load of the model that equation ``i``'s misfit is a fixed multiple of (a
        component or a moment of it, at every state, with the unknowns the ``right``
        equations give), whether it is ``missing`` from it, ``doubled`` or ``turned round``
        in it, and whether that is sure: a term of the wrong sign (:meth:`reversed_term`) or
        the multiple read off a balance of the load's body (:meth:`_multiple`) is; else the
        misfit twice the load at the equation's scale (the multiple its other terms are of
        their loads; 1 when none is) is a load turned round, once one left out. Of loads alike
        on several bodies (a rope's tension), the one whose body's balance the equation is,
        else the one on the body most of the equation's other terms are loads of; ``None``
        when no load or several fit."""
        misfits = self._misfits(i, right)
        if misfits is None:
            return None
        values = np.array([m for m, _, _ in misfits])
        fitting = {(load.name, load.body): (load, ratios) for load in self.samples.loads
                   if (ratios := _ratios(values, load))}
        terms = [np.array([float(evaluate(t, env)[0]) for _, _, env in misfits])
                 for _, t in _signed_terms(self.equations[i].residual)]
        if len(fitting) > 1:
            read = {k: v for k, v in fitting.items()
                    if self._multiple(i, v[0], misfits) is not None}
            fitting = read if len(read) == 1 else fitting
        if len(fitting) > 1:
            # a moment about another point can be a multiple too (I_G θ'' = M_G of the pin
            # beside I_O θ'' = M_O of the weight): the load the misfit is once or twice first
            plain = {k: v for k, v in fitting.items() if any(map(_plain, v[1]))}
            fitting = plain or fitting
        if len(fitting) > 1:
            bodies = Counter(load.body for load in self.samples.loads
                             for t in terms if _ratios(t, load))
            most = max(bodies[load.body] for load, _ in fitting.values())
            fitting = {k: v for k, v in fitting.items() if bodies[v[0].body] == most}
        if len(fitting) != 1:
            return None
        ((load, ratios),) = fitting.values()
        if self.reversed_term(i, right) is not None:
            return load, LoadSlip.TURNED_ROUND, True
        multiple = self._multiple(i, load, misfits)
        if multiple is not None:
            return load, {-1: LoadSlip.MISSING, 1: LoadSlip.DOUBLED,
                          -2: LoadSlip.TURNED_ROUND}[multiple], True
        scales = Counter(float(f"{abs(r):.3g}") for t in terms for other in self.samples.loads
                         for r in _ratios(t, other))
        scale = scales.most_common(1)[0][0] if scales else 1.0
        times = [n for r in ratios if (n := _plain(r / scale)) is not None]
        return load, LoadSlip.TURNED_ROUND if times and times[0] == 2 else LoadSlip.MISSING, False

    def _multiple(self, i: int, load: SampledLoad, misfits: list) -> int | None:
        """How many times over equation ``i`` has ``load``: -1 (left out), 1 (twice), -2
        (turned round), read off the balances of the load's body its accelerations are a
        multiple of, at the state ``misfits`` (:meth:`_misfits`) tell most by; ``None`` when
        none or several readings say so."""
        k = max(range(len(misfits)), key=lambda n: abs(misfits[n][0]) / misfits[n][1])
        misfit = misfits[k][0]
        slope = self.slopes_at[k, i]
        if not slope.any():
            return None
        found: set[int] = set()
        for balance in self.samples.balances:
            along = np.array(balance.slope[k])
            if balance.body != load.body or not along.any() or \
                    (balance.axis, balance.about) not in load.along:
                continue
            times = float(slope @ along / (along @ along))
            if np.abs(slope - times * along).max() > FIT * np.abs(slope).max():
                continue
            component = load.components[load.along.index((balance.axis, balance.about))][k]
            if not parts(component, misfit):
                continue
            # the equation is ``times`` (m a - loads): a load's error enters with -times
            found.update(n for n in (-1, 1, -2)
                         if abs(misfit / (-times * component) - n) <= REL * abs(n) * 10)
        return found.pop() if len(found) == 1 else None

    def wrong_balance(self, i: int, right: list[int]) -> str | None:
        """What equation ``i`` is when it is a momentum balance put together wrong, at every
        state and with the unknowns the ``right`` equations give: one body's m a with another
        body's loads along the same axis (either way round), or a body's rate of angular
        momentum about one point with its loads' moment about another; ``None`` when it is
        neither, or it could be several.
        """
        misfits = self._misfits(i, right)
        slope = self.slopes[i]
        if misfits is None or not slope.any():
            return None
        values = np.array([m for m, _, _ in misfits])
        tol = np.array([t for _, t, _ in misfits])
        balances = self.samples.balances
        found: set[str] = set()
        for motion in balances:
            along = np.array(motion.slope[0])
            if not along.any():
                continue
            times = float(slope @ along / (along @ along))
            if np.abs(slope - times * along).max() > FIT * np.abs(slope).max():
                continue  # the equation's accelerations are not this balance's
            for loads in balances:
                if loads.axis != motion.axis or (
                        (loads.about is None) != (motion.about is None)
                        or (loads.body == motion.body) == (loads.about is None)
                        or (loads.about is not None and loads.about == motion.about)):
                    continue
                for sign in (1.0, -1.0):
                    # the motion's side is the model's loads on its own body at every state
                    wrong = times * (np.array(motion.loads) - sign * np.array(loads.loads))
                    if np.all(np.abs(values - wrong) <= tol) and np.any(np.abs(wrong) > tol):
                        found.add(f"the wrong body: the loads on {loads.body} balanced "
                                  f"against the m a of {motion.body}" if loads.about is None
                                  else f"the wrong point: the moments about {loads.about} "
                                  f"balanced against the rate of angular momentum about "
                                  f"{motion.about}")
        return found.pop() if len(found) == 1 else None

    def _fitted(self, rows: list[int]) -> np.ndarray:
        """The unknowns fitted to ``rows`` at each state."""
        return np.array([np.linalg.lstsq(self.a[k][rows], -self.b[k][rows], rcond=None)[0]
                         for k in range(len(self.b))])

    def _accounted(self, rows: list[int]) -> bool:
        """Whether the unknowns fitted to ``rows`` are the model's reactions and accelerations
        by names of the student's (:meth:`_readings`)."""
        return self._readings(rows) is not None

    def _flips(self, rows: list[int]) -> int | None:
        """How many reactions the unknowns fitted to ``rows`` take the other way round, when
        each is one of the model's reactions by another name, sign or axis (in the solved
        configuration); ``None`` when one is not."""
        if not self.unknowns:
            return 0
        readings = self._readings(rows)
        if readings is None or not np.all(np.abs(readings[0]).max(axis=1, initial=0) > 0):
            return None
        return int(np.sum(readings[0] < 0))

    def _readings(self, rows: list[int]) -> np.ndarray | None:
        """What each unknown fitted to ``rows`` is in each configuration of the samples, as
        its coefficients on the model's reactions (one row an unknown); ``None`` when one is
        not what a student's name may stand for. An unknown may be a reaction by another name,
        sign or axis: a fixed combination, over the configuration's states, of one reaction's
        components along unit vectors (coefficients of size 1, or less where a component is
        nought at each state); or an acceleration by a name of the student's (a fixed
        combination of the accelerations; its row is nought). An unknown the equations leave
        free, or nought at each state, has a nought row too: nought at every state only as
        many as the model's reactions are (a pendulum hanging at rest has no sideways
        reaction: an unknown nought besides it took up what is wrong in its own equation).
        A fit that only shares the reactions otherwise among the unknowns (a reaction left out
        of one balance, another's share taking it up) is no fixed combination of one
        reaction's, or not of size 1."""
        fitted = self._fitted(rows)
        free = self._free(rows)
        n_u, n_r = len(self.unknowns), self.reactions.shape[1]
        size = np.abs(fitted).max(initial=0) + max(np.abs(self.reactions).max(initial=0),
                                                   np.abs(self.accelerations_sampled).max(
                                                       initial=0))
        groups: dict[str, list[int]] = {}
        for r in range(n_r):
            groups.setdefault(self.samples.reaction_load(r), []).append(r)
        configurations = [self.samples.configuration(k) for k in range(len(self.b))]
        out = []
        for c in dict.fromkeys(configurations):
            at = [k for k, of in enumerate(configurations) if of == c]
            reactions = self.reactions[at]
            nought = ~parts(np.abs(reactions).max(axis=0, initial=0), size)
            accelerations = self.accelerations_sampled[at]
            moving = accelerations[:, parts(np.abs(accelerations).max(axis=0, initial=0), size)]
            reading = np.zeros((n_u, n_r))
            of: dict[int, str] = {}  # the reaction each unknown is
            noughts = 0
            for j in range(n_u):
                values = fitted[at, j]
                if free[at, j].any():
                    continue
                if not parts(np.abs(values).max(), size):
                    noughts += 1
                    continue
                found = [(row, name) for name, group in groups.items()
                         if (row := _one_reaction(values, reactions, group, nought)) is not None]
                if found:  # reactions alike at every state (R_A, -R_B): the fewest turned round
                    reading[j], of[j] = min(found, key=lambda pair: int(np.sum(pair[0] < 0)))
                elif not (moving.size and _fits(values, moving) is not None):
                    return None
            if noughts > int(np.sum(nought)) or not all(
                    _whole(reading[[j for j in range(n_u) if of.get(j) == name]][:, group],
                           reactions[:, group]) for name, group in groups.items()):
                return None
            out.append(reading)
        return np.array(out)

    def _free(self, rows: list[int]) -> np.ndarray:
        """Which unknowns the equations ``rows`` leave free at each state."""
        out = np.zeros((len(self.b), len(self.unknowns)), dtype=bool)
        for k in range(len(self.b)):
            a = self.a[k][rows]
            if not a.size:
                continue
            out[k] = rules.left_open(rules.null_space(a))
        return out

    def _determined(self) -> int:
        a = self.a[0]
        full = np.hstack([self.slopes, a]) if a.size else self.slopes
        return rules.matrix_rank(full) - rules.matrix_rank(a)

    def complete(self) -> bool:
        return self._determined() >= len(self.accelerations)

    def undetermined(self) -> int:
        return max(len(self.accelerations) - self._determined(), 0)

    def undetermined_names(self) -> str:
        return ", ".join(a[:-2] + "''" for a in self.accelerations)


def _fits(values: np.ndarray, basis: np.ndarray) -> np.ndarray | None:
    """The fixed coefficients ``values`` (one per state) are of the columns of ``basis`` (a row
    per state), to within :data:`FIT`; ``None`` when none are.

    >>> _fits(np.array([2.0, 4.0, 7.0]), np.array([[1.0], [2.0], [3.5]]))
    array([2.])
    >>> _fits(np.array([2.0, 4.0, 7.0]), np.array([[1.0], [2.0], [3.0]])) is None
    True
    """
    coefficients = np.linalg.lstsq(basis, values, rcond=None)[0]
    misfit = np.abs(basis @ coefficients - values).max()
    # a coefficient of rounding's size is none (nor is it a sign)
    coefficients[~parts(coefficients)] = 0.0
    return coefficients if misfit <= FIT * np.abs(values).max() else None


def _whole(rows: np.ndarray, basis: np.ndarray) -> bool:
    """Whether unknowns that are one reaction's components (their coefficients ``rows`` on
    every reaction, read on ``basis``: the reaction's components at each state), as many as
    the components that are not alike at every state (one nought, two in a fixed ratio), are
    its components along unit vectors at right angles, as any axes' are: with more, which
    coefficients each has is not seen (axes turned about a nought component's).

    >>> basis = np.array([[0.0, 3.0], [0.0, 5.0], [0.0, 2.0]])  # the first nought
    >>> _whole(np.array([[0.0, 1.0]]), basis), _whole(np.array([[0.0, 0.6]]), basis)
    (True, False)
    >>> _whole(np.array([[0.0, 0.6], [0.0, 0.8]]), basis)
    True
    """
    rank = rules.matrix_rank(basis)
    if len(rows) != rank or rank == basis.shape[1]:
        return True
    return bool(np.all(np.abs(rows @ rows.T - np.eye(rank)) <= REL))


def _one_reaction(values: np.ndarray, reactions: np.ndarray, group: list[int],
                  nought: np.ndarray) -> np.ndarray | None:
    """The coefficients on every reaction (a row) when ``values`` are one reaction's by
    another name, sign or axis: a fixed combination of its components ``group`` (columns of
    ``reactions``) of size 1, or at most 1 where some are ``nought`` or alike at every state
    (then one of size 1 fits too); else ``None``.

    >>> reactions = np.array([[3.0, 4.0], [1.0, -2.0], [2.0, 5.0]])
    >>> _one_reaction(np.array([-4.0, 2.0, -5.0]), reactions, [0, 1], np.zeros(2, bool))
    array([ 0., -1.])
    >>> _one_reaction(np.array([8.0, -4.0, 10.0]), reactions, [0, 1], np.zeros(2, bool)) is None
    True
    """
    columns = [r for r in group if not nought[r]]
    if not columns:
        return None
    basis = reactions[:, columns]
    coefficients = _fits(values, basis)
    if coefficients is None:
        return None
    # components alike at every state (one nought, two in a fixed ratio) leave some
    # coefficients free: then the least of size 1 or under will do (one of size 1 fits too)
    length = float(np.linalg.norm(coefficients))
    alike = len(columns) < len(group) or rules.matrix_rank(basis) < len(columns)
    if not (length <= 1 + REL if alike else abs(length - 1) <= REL):
        return None
    row = np.zeros(reactions.shape[1])
    row[columns] = coefficients
    return row


def _ratios(values: np.ndarray, load: SampledLoad) -> list[float]:
    """The fixed non-zero multiples ``values`` (one per state) are of a component of ``load``
    at the same states: the parameters change from state to state, so loads of other sizes
    (a friction, a weight) are not multiples of one another's."""
    out = []
    mass = np.array(load.mass) if load.mass else np.ones(len(values))
    for row in load.components:
        component = np.array(row)
        # where it is nought (a spring at its free length), the values must be too
        seen = parts(component)
        if not np.all(np.isfinite(component)) or not seen.any():
            continue
        # the equation as written, or divided by the body's mass (x'' = g sin β - μ g cos β)
        for scaled in (values, values * mass):
            ratio = scaled[seen] / component[seen]
            if np.all(np.isfinite(ratio)) and ratio[0] != 0 and \
                    np.all(np.abs(ratio - ratio[0]) <= REL * abs(ratio[0])) and \
                    np.all(np.abs(scaled[~seen]) <= REL * np.abs(scaled).max()):
                out.append(float(ratio[0]))
                break
    return out


def _plain(ratio: float) -> int | None:
    """1 or 2 when ``ratio`` is once or twice (either sign), else ``None``.

    >>> _plain(-1.0), _plain(2.0004), _plain(0.25)
    (1, 2, None)
    """
    return next((n for n in (1, 2) if abs(abs(ratio) - n) <= REL * n), None)


def _signed_terms(node: Node, sign: int = 1) -> list[tuple[int, Node]]:
    """The terms of a sum, each with the sign it enters it with (``a - (b - c)``: +a, -b,
    +c)."""
    if isinstance(node, Bin) and node.op in "+-":
        return _signed_terms(node.left, sign) + _signed_terms(
            node.right, sign if node.op == "+" else -sign)
    if isinstance(node, Unary) and node.op == "-":
        return _signed_terms(node.operand, -sign)
    return [(sign, node)]


def _naming(load: SampledLoad) -> str:
    """A load as a reader names it.

    >>> _naming(SampledLoad("F_P", LoadKind.KINETIC_FRICTION, "block", ()))
    'the kinetic friction F_P on block'
    >>> _naming(SampledLoad("gravity", LoadKind.WEIGHT, "block1", ()))
    'the weight of block1'
    >>> _naming(SampledLoad("spring", LoadKind.SPRING, "puck", ()))
    'the spring on puck'
    >>> _naming(SampledLoad("friction", LoadKind.KINETIC_FRICTION, "block", ()))
    'the kinetic friction on block'
    """
    if load.kind == LoadKind.WEIGHT:
        return f"the weight of {load.body}"
    # a load named by its kind ("spring", "friction") is named once
    if load.name.replace("_", " ").lower() in (load.kind, load.kind.split()[-1]):
        return f"the {load.kind} on {load.body}"
    return f"the {load.kind} {load.name} on {load.body}"


def _term_sizes(node: Node, env: dict, moves: int) -> np.ndarray:
    """The size of the largest term of either side at each state's first move (nothing
    changed; ``env`` has ``moves`` values a state), so that a right equation whose sides
    cancel is judged against its terms."""
    terms: list[Node] = []

    def split(n: Node) -> None:
        if isinstance(n, Bin) and n.op in "+-":
            split(n.left)
            split(n.right)
        else:
            terms.append(n)

    split(node)
    return np.max([np.abs(evaluate(t, env)[::moves]) for t in terms], axis=0)
