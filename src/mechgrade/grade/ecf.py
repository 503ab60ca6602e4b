"""Error carried forward (ECF): an answer judged again against the reference recomputed from
the student's own wrong upstream answers.

An objective may declare ``depends_on: [upstream]`` in its spec. When a student's upstream
answer is wrong and the downstream one is not right, the downstream answer is judged again
against the reference recomputed from the student's own upstream value
(``solve(problem, givens={key: si_value})``), and keeps the better credit (times
``policy.ecf.credit``). This needs the upstream objective to be a plain given quantity (a
coordinate, its rate or a parameter); otherwise the feedback says ECF could not be applied.
Every method takes the student's own plan (their variant's references): nothing here holds
one student's state between calls but the cache of re-solves, keyed by problem and givens.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING, Callable, Iterable, Protocol

import numpy as np

from ..errors import InconsistentError, MechgradeError
from ..expressions.syntax import Call, Name, Prime
from ..parallel import fork_map
from ..spec.dynamics import Integration
from ..spec.model import Objective, ObjectiveKind, Problem
from .policy import GradingPolicy
from .results import ECF_DIAGNOSIS, AnswerResult, Verdict
from .submissions import Submission, SubmissionStatus

if TYPE_CHECKING:  # importing the solver package loads sympy and scipy: only when solving
    from ..solve.result import ObjectiveResult, Solution
    from .compare import Assessment
    from .run import Plan, PlannedObjective

Resolver = Callable[[Problem, dict], "Solution"]


class Judging(Protocol):
    """What ECF asks of the run's judge: judge one answer, look one up, judge a batch."""

    def assess(self, text: str, result: ObjectiveResult) -> Assessment: ...

    def judged(self, result: ObjectiveResult, text: str) -> Assessment | None: ...

    def judge_all(self, pairs: Iterable[tuple[ObjectiveResult, str]]) -> None: ...


class CarriedForward:
    """ECF for one grading run: ``resolve(problem, givens)`` recomputes a solution (default
    :func:`mechgrade.solve.solve`, or :func:`mechgrade.solve.carried.solve_carried` where a
    student's second rate is given); re-solves are kept, and prefetched over ``jobs``."""

    def __init__(self, policy: GradingPolicy, judging: Judging,
                 resolve: Resolver | None = None, jobs: int = 1) -> None:
        self.policy = policy
        self._judging = judging
        self._resolve = resolve
        self._jobs = jobs
        self._solutions: dict[tuple, tuple] = {}

    @property
    def enabled(self) -> bool:
        return self.policy.ecf.enabled

    def prefetch(self, work: Iterable[tuple[Plan, Submission]]) -> None:
        """Solve, over the jobs, the re-solves :meth:`carry_forward` will ask for (each
        student's ``(plan, submission)`` in ``work``), into :meth:`solve_with`'s cache: they
        take most of a run's grading time when they are solved one after the other. Then judge
        the answers again against them, in one batch (not one round trip per answer). One not
        foreseen here (an upstream answer itself carried forward) is solved when asked; a
        fault of mechgrade's here leaves every one to be solved when asked."""
        if self._resolve is not None or not self.enabled:
            return
        try:
            requests: dict[tuple, tuple] = {}
            again: dict[tuple, None] = {}  # (re-solve key, answer, objective) to judge again
            for plan, submission in work:
                for item in (i for i in plan.objectives if i.objective.depends_on):
                    text = (submission.answer(item.key)
                            if submission.status == SubmissionStatus.READ else None)
                    judged = (self._judging.judged(item.result, text)
                              if text is not None else None)
                    if judged is None or judged.verdict == Verdict.CORRECT:
                        continue
                    found = self.upstream_givens(plan, item, submission, {})
                    if isinstance(found, dict) and found:
                        givens = {**dict(item.givens), **found}
                        key = _key(item.problem, givens, item.objective.id)
                        if key not in self._solutions:
                            requests[key] = (item.problem, givens, item.objective.id)
                        again[key, text, item.objective.id] = None
            _CARRYING[:] = [self]  # inherited by the forked workers
            try:
                solved = fork_map(_solve_carried, list(requests.values()), jobs=self._jobs)
            finally:
                _CARRYING.clear()
            self._solutions.update(zip(requests, solved))
            todo: list[tuple[ObjectiveResult, str]] = []
            for key, text, objective_id in again:
                solution = self._solutions[key][0]
                if isinstance(solution, MechgradeError):
                    continue  # not solved: the per-answer path says why
                try:
                    todo.append((solution.result(objective_id), text))
                except (KeyError, MechgradeError):
                    continue
            self._judging.judge_all(todo)
        except Exception:  # noqa: BLE001 - see the docstring: the per-answer path reports it
            pass

    def upstream_givens(self, plan: Plan, item: PlannedObjective, submission: Submission,
                        earlier: dict[str, AnswerResult]) -> dict[str, float] | str:
        """The givens (SI, by given key) the student's wrong upstream answers stand for, or
        the feedback saying why error carried forward cannot use them."""
        found = self._upstream(plan, item, submission, earlier)
        return found if isinstance(found, str) else found[0]

    def _upstream(self, plan: Plan, item: PlannedObjective, submission: Submission,
                  earlier: dict[str, AnswerResult]) -> tuple[dict[str, float], list[str]] | str:
        """:meth:`upstream_givens`, and the upstream objectives they come from."""
        problem = item.problem
        overrides: dict[str, float] = {}
        used: list[str] = []
        for upstream_id in item.objective.depends_on:
            key = f"{problem.id}.{upstream_id}"
            upstream = earlier.get(key)
            if upstream is None:
                upstream_text = submission.answer(key)
                if upstream_text is None:
                    continue  # not graded in this assignment and not answered
                try:
                    up_result = _reference(plan, problem, upstream_id)
                except KeyError:
                    continue
                upstream_verdict = self._judging.assess(upstream_text, up_result).verdict
            elif upstream.diagnosis == ECF_DIAGNOSIS:
                continue  # it follows from an earlier answer: the error is there, not here
            else:
                upstream_text, upstream_verdict = upstream.answer, upstream.verdict
            if upstream_verdict == Verdict.CORRECT or upstream_text is None:
                continue
            if upstream_verdict in (Verdict.UNREADABLE, Verdict.MISSING, Verdict.NOT_EVALUATED):
                continue
            objective = upstream_objective(problem, upstream_id)
            if objective is None:
                continue
            given_key = given_key_of(objective)
            if given_key is None and objective.kind == ObjectiveKind.VECTOR:
                found = self.vector_givens(plan, item, upstream_id, upstream_text)
                if isinstance(found, str):
                    return found
                overrides.update(found)
                used.append(upstream_id)
                continue
            if given_key is None:
                return (f"Error carried forward could not be applied: '{upstream_id}' is not a "
                        f"plain given quantity the solver can take from your answer.")
            value = _si_value(upstream_text, _reference(plan, problem, upstream_id))
            if value is None:
                return (f"Error carried forward could not be applied: your answer to "
                        f"'{upstream_id}' could not be read as a number.")
            overrides[given_key] = value
            used.append(upstream_id)
        return overrides, used

    def vector_givens(self, plan: Plan, item: PlannedObjective, upstream_id: str,
                      text: str) -> dict[str, float] | str:
        """The given rates (SI, by given key) a student's vector answer to ``upstream_id``
        stands for, or the feedback saying why error carried forward cannot use it.

        A velocity (an acceleration) at the instant is affine in the given rates (second
        rates) of the problem: the vector's change with each is measured by re-solving, and
        the rates that give the student's vector are found by least squares. They are used
        only when they give it exactly (within the objective's tolerance) and are the only
        ones that do; otherwise the vector is not one the model can have with other rates."""
        from ..solve import rules  # the solver's rank rule, loaded only when solving

        problem = item.problem
        reference = _reference(plan, problem, upstream_id)
        student = _si_vector(text, reference)
        refused = f"Error carried forward could not be applied: your answer to '{upstream_id}'"
        if student is None:
            return f"{refused} could not be read as a vector in its own frame's unit vectors."
        base = {**{g.key.text: g.si for g in problem.givens}, **dict(item.givens)}
        at = self._vector(problem, base, upstream_id)
        if at is None:
            return f"{refused} cannot be recomputed at the problem's givens."
        for order in (2, 1):
            keys = [g.key.text for g in problem.givens if _order(g.key.text) == order]
            columns = []
            for key in keys:
                moved = self._vector(problem, {**base, key: base[key] + 1.0}, upstream_id)
                if moved is None:
                    return f"{refused} cannot be recomputed with another {key}."
                columns.append(moved - at)
            # the rates the vector changes with: it says nothing of the others
            keys = [k for k, c in zip(keys, columns) if np.abs(c).max() > 0]
            columns = [c for c in columns if np.abs(c).max() > 0]
            if not columns:
                continue
            J = np.array(columns).T
            delta, *_ = np.linalg.lstsq(J, student - at, rcond=None)
            miss = float(np.linalg.norm(J @ delta - (student - at)))
            size = float(np.linalg.norm(student))
            if rules.matrix_rank(J) < len(keys):
                return (f"{refused} does not fix {listing(keys)}: more than one set of them "
                        f"gives it.")
            if miss > reference.rel * size + _si_abs(reference) + 1e-12:
                return (f"{refused} is not one the model can have with other values of "
                        f"{listing(keys)}: none gives it exactly.")
            return {key: base[key] + float(d) for key, d in zip(keys, delta)}
        return f"{refused} does not change with any given rate of the problem."

    def _vector(self, problem: Problem, givens: dict, objective_id: str):
        solution, _ = self.solve_with(problem, givens, objective_id)
        if isinstance(solution, MechgradeError):
            return None
        try:
            value = solution.result(objective_id).value
        except (KeyError, MechgradeError):
            return None
        return np.array(value, dtype=float) if value is not None else None

    def carry_forward(self, plan: Plan, item: PlannedObjective, text: str,
                      submission: Submission, earlier: dict[str, AnswerResult],
                      verdict: Verdict, credit: float,
                      feedback: list[str]) -> tuple[Verdict, float]:
        """Judge ``text`` again against the reference recomputed from the student's own
        (wrong) upstream answers; keep the better credit (``feedback`` says which)."""
        problem = item.problem
        found = self._upstream(plan, item, submission, earlier)
        if isinstance(found, str):
            feedback.append(found)
            return verdict, credit
        overrides, used = found
        if not overrides:
            return verdict, credit
        answered = sorted(overrides)
        overrides = {**dict(item.givens), **overrides}  # on the student's own variant
        rates = [k for k in answered if _order(k) == 2]
        if rates and isinstance(getattr(problem.dynamics, "analysis", None), Integration):
            feedback.append(f"Error carried forward could not be applied: your "
                            f"{listing(rates)} is an acceleration at one instant of a motion "
                            f"integrated from its start, which it does not change.")
            return verdict, credit
        solution, replaced = self.solve_with(problem, overrides, item.objective.id)
        if isinstance(solution, MechgradeError):
            feedback.append(f"Error carried forward could not be applied: with your "
                            f"{listing(answered)} the problem cannot be solved "
                            f"({solution.message}).")
            return verdict, credit
        try:
            recomputed = solution.result(item.objective.id)
        except KeyError:
            return verdict, credit
        again = self._judging.assess(text, recomputed)
        ecf_credit = float(again.credit) * self.policy.ecf.credit
        upstream_names = listing(sorted(used or item.objective.depends_on))
        if again.verdict in (Verdict.CORRECT, Verdict.PARTIAL) and ecf_credit > credit:
            instead = f" (used in place of {listing(replaced)})" if replaced else ""
            # one sentence: what the answer was told against the reference no longer holds
            feedback[:] = [f"Error carried forward: this answer follows correctly from your "
                           f"answer to {upstream_names}{instead} and earns {ecf_credit:.0%} "
                           f"of the points."]
            return (Verdict.CORRECT if ecf_credit >= 1.0 else Verdict.PARTIAL), ecf_credit
        feedback.append(f"Also checked with your own answer to {upstream_names} (error "
                        f"carried forward): it does not follow from it either.")
        return verdict, credit

    def solve_with(self, problem: Problem, overrides: dict[str, float], objective_id: str):
        """Solve with the student's values; ``(solution or error, givens replaced)``.

        A value the spec derives from other givens over-determines the problem when simply
        added (x' given while y' fixes it). Then each given of the same derivative order is
        dropped in turn, in spec order, and the first consistent solution is used.
        """
        key = _key(problem, overrides, objective_id)
        if key in self._solutions:
            return self._solutions[key]
        problem, instead, held = _replaced_by_student(problem, overrides)
        outcome = self._attempt(problem, dict(overrides), objective_id, held), instead
        if isinstance(outcome[0], InconsistentError):
            orders = {_order(k) for k in overrides}
            for given in problem.givens:
                name = given.key.text
                if name in overrides or _order(name) not in orders:
                    continue
                attempt = self._attempt(problem, {**overrides, name: None}, objective_id, held)
                if not isinstance(attempt, MechgradeError):
                    outcome = attempt, (f"the given {name}",)
                    break
        self._solutions[key] = outcome
        return outcome

    def _attempt(self, problem: Problem, givens: dict, objective_id: str, held: bool):
        """The problem solved with ``givens``, by the run's ``resolve`` when it has one,
        else by :func:`~mechgrade.solve.solve`, or with ``held`` by
        :func:`~mechgrade.solve.carried.solve_carried` (a student's second rate held)."""
        try:
            if self._resolve is not None:
                return self._resolve(problem, givens)
            from ..solve import solve
            from ..solve.carried import solve_carried

            # Only the objective being re-checked: another one may not exist with these values.
            return (solve_carried if held else solve)(problem, givens=givens,
                                                      objectives=(objective_id,))
        except MechgradeError as err:
            return err


def _reference(plan: Plan, problem: Problem, objective_id: str) -> ObjectiveResult:
    return plan.solutions[plan.problems.index(problem)].result(objective_id)


def _replaced_by_student(problem: Problem, overrides: dict[str, float]
                        ) -> tuple[Problem, tuple[str, ...], bool]:
    """The problem to re-solve for ECF, what the student's values replace in it, and whether
    a student's second rate is held. A work-energy problem's rates come from its energy
    balance, and a designed parameter from its design condition: a student's rate (or
    parameter) takes that balance's (or condition's) place, and the instant is solved from it
    as from any other given. A student's second rate takes the place of the momentum balance
    that would determine it (:func:`mechgrade.solve.carried.solve_carried`): the reactions
    follow from the others."""
    from ..spec.dynamics import WorkEnergy

    dynamics = problem.dynamics
    if dynamics is None:
        return problem, (), False
    replaced: list[str] = []
    rates = [k for k in overrides if _order(k) == 2]
    if rates:
        replaced.append(f"the balance that gives {listing(sorted(rates))}")
    analysis, design = dynamics.analysis, dynamics.design
    if isinstance(analysis, WorkEnergy) and any(_order(k) == 1 for k in overrides):
        replaced.append("the energy balance")
        analysis = None
    if design is not None and design.find in overrides:
        replaced.append("the design condition")
        design = None
    if not replaced:
        return problem, (), False
    return (replace(problem, dynamics=replace(dynamics, analysis=analysis, design=design)),
            tuple(replaced), bool(rates))


_CARRYING: list = []


def _key(problem: Problem, givens: dict, objective_id: str) -> tuple:
    return problem.id, objective_id, tuple(sorted(givens.items()))


def _solve_carried(request: tuple) -> tuple:
    """:meth:`CarriedForward.solve_with` in a forked worker (see
    :meth:`CarriedForward.prefetch`)."""
    return _CARRYING[0].solve_with(*request)


def _order(key: str) -> int:
    """How many time derivatives a given key names (``x''`` -> 2; an expression -> -1)."""
    stripped = key.rstrip("'")
    return len(key) - len(stripped) if stripped.isidentifier() else -1


def given_key_of(objective: Objective) -> str | None:
    """The given key (``"theta'"``) an objective's value can be fed back to the solver as,
    or ``None`` when the objective is not a plain quantity (a coordinate, its rates, a
    parameter; a scalar ``eom(q)`` is ``q''``).

    >>> from mechgrade.spec.model import Expr
    >>> from mechgrade.expressions.syntax import parse
    >>> ob = lambda find, kind="scalar": Objective("o", "", Expr(find, parse(find, functions=["mag", "vel", "eom"])), kind, "m/s")
    >>> given_key_of(ob("x'")), given_key_of(ob("mag(vel(A, N))")), given_key_of(ob("x", "vector"))
    ("x'", None, None)
    >>> given_key_of(ob("eom(theta)"))
    "theta''"
    """
    if objective.kind != ObjectiveKind.SCALAR:
        return None
    node = objective.find.node
    if isinstance(node, Name):
        return node.id
    if isinstance(node, Prime):
        return node.id + "'" * node.order
    if isinstance(node, Call) and node.func == "eom" and len(node.args) == 1 and \
            isinstance(node.args[0], Name):  # a scalar eom(q) is q'' at the instant
        return node.args[0].id + "''"
    return None



def upstream_objective(problem: Problem, objective_id: str) -> Objective | None:
    try:
        return problem.objective(objective_id)
    except KeyError:
        return None



def _si_value(text: str, result: ObjectiveResult) -> float | None:
    """The student's scalar answer in SI, read as the objective's unit when none is written."""
    from ..units import judged_in, to_si
    from .answers import NumberAnswer, read_answer

    try:
        answer = read_answer(text, result)
        if not isinstance(answer, NumberAnswer):
            return None
        value = to_si(answer.value, judged_in(answer.unit, result.unit))
    except MechgradeError:
        return None
    return value if math.isfinite(value) else None


def _si_vector(text: str, result: ObjectiveResult):
    """The student's vector answer in SI components along the objective's frame, or
    ``None`` (not a vector, or along another frame's unit vectors)."""
    from ..units import judged_in, to_si
    from .answers import VectorAnswer, read_answer

    try:
        answer = read_answer(text, result)
        if not isinstance(answer, VectorAnswer) or answer.frame not in (None, result.frame):
            return None
        unit = judged_in(answer.unit, result.unit)
        value = np.array([to_si(c, unit) for c in answer.components], dtype=float)
    except MechgradeError:
        return None
    return value if np.isfinite(value).all() else None


def _si_abs(result: ObjectiveResult) -> float:
    from ..units import to_si

    return to_si(result.abs, result.unit) if result.abs else 0.0


def listing(items) -> str:
    """Names one after the other, the first eight of them.

    >>> listing(["x'", "y'"]), listing(str(i) for i in range(10))
    ("x', y'", '0, 1, 2, 3, 4, 5, 6, 7, ...')
    """
    items = list(items)
    if len(items) > 8:
        return ", ".join(items[:8]) + ", ..."
    return ", ".join(items)
