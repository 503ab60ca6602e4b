"""The grading run: every student's answers against the reference solutions, into a report.

Each problem of the assignment is loaded and solved once, for the objectives graded and those
they depend on; every answer is judged in the bounded sandbox (a worker per job, reused for the
whole run, answers sent in batches), identical answers only once. With several jobs the
submissions are read, and the problems solved, in forked processes (but for a problem that error
carried forward re-solves: it is solved here, where its re-solves find its derivation made); the
report never depends on the number of jobs. Points are the judged credit times the objective's
points. Every roster student and every submission appears in the report with a status, in a
fixed order (roster order, then students not on the roster by id), so a re-run gives
byte-identical outputs.

Error carried forward (ECF): an objective may declare ``depends_on: [upstream]`` in its spec.
When a student's upstream answer is wrong and the downstream one is not right, the downstream
answer is judged again against the reference recomputed from the student's own upstream value
(``solve(problem, givens={key: si_value})``). This needs the upstream objective to be a plain
given quantity (a coordinate, its rate or a parameter); otherwise the feedback says ECF could
not be applied.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Iterable

from ..errors import (AssignmentError, MechgradeError, SpecError, SpecErrors,
                      brief_exception)
from ..parallel import Forked, fork_map, outcome, raise_first
from ..roster import MatchKind, fold, identifier, pair_students
from ..spec.model import Objective, ObjectiveKind, Problem
from .assignment import Assignment
from .ecf import CarriedForward, Resolver, listing, upstream_objective
from .lms_submissions import read_any_submissions
from .results import (ECF_DIAGNOSIS, EQUATIONS_OBJECTIVE, AnswerResult, AssignmentInfo, FailingExpect, GradeReport,
                      LoadResult, ObjectiveInfo, Status, StudentResult, Verdict, unit_text)
from .policy import GradingPolicy
from .submissions import Submission, SubmissionFormat, SubmissionSet, SubmissionStatus

if TYPE_CHECKING:  # importing the solver package loads sympy and scipy: only when solving
    from ..solve.derivation import DerivationInstant, MotionSamples
    from ..solve.result import ObjectiveResult, Solution
    from .compare import Assessment
    from .sandbox import SandboxPool

POINTS_DIGITS = 4
"""Points are rounded to this many decimals, so that sums are the same on every machine."""

Progress = Callable[[int, int], None]


@dataclass(frozen=True)
class PlannedObjective:
    """One graded objective: its problem, spec objective, reference result and points."""

    problem: Problem
    objective: Objective
    result: ObjectiveResult
    max_points: float
    givens: tuple[tuple[str, float], ...] = ()  # the student's variant: SI overrides
    steps: tuple[str, ...] = ()  # the steps of its write-up graded before it, in order
    step_of: str = ""  # for a step, the objective its write-up leads to

    @property
    def key(self) -> str:
        return f"{self.problem.id}.{self.objective.id}"


@dataclass(frozen=True)
class PlannedDiagram:
    """One graded free-body diagram: its problem, body, the model at the solved instant and
    points. Answered under ``problem_id.body.fbd``."""

    problem: Problem
    body: str
    instant: "DerivationInstant"
    max_points: float

    @property
    def objective_id(self) -> str:
        return f"{self.body}.fbd"

    @property
    def key(self) -> str:
        return f"{self.problem.id}.{self.objective_id}"


@dataclass(frozen=True)
class PlannedEquations:
    """One problem's graded equations of motion, with the model's motion sampled, and
    points. Answered under ``problem_id.equations``."""

    problem: Problem
    samples: "MotionSamples | None"
    max_points: float
    objective_id = EQUATIONS_OBJECTIVE

    @property
    def key(self) -> str:
        return f"{self.problem.id}.{self.objective_id}"


@dataclass(frozen=True)
class Plan:
    """An assignment with its problems loaded and solved once, ready to grade any student."""

    assignment: Assignment
    problems: tuple[Problem, ...]
    solutions: tuple[Solution, ...]
    objectives: tuple[PlannedObjective, ...]
    diagrams: tuple[PlannedDiagram, ...] = ()
    equations: tuple[PlannedEquations, ...] = ()

    @property
    def keys(self) -> frozenset[str]:
        return frozenset([*(o.key for o in self.objectives), *(d.key for d in self.diagrams),
                          *(e.key for e in self.equations)])

    @property
    def max_score(self) -> float:
        return _round(sum(o.max_points for o in self.objectives)
                      + sum(d.max_points for d in self.diagrams)
                      + sum(e.max_points for e in self.equations))


def plan_assignment(assignment: Assignment, *, problems: Iterable[Problem] | None = None,
                    solutions: Iterable[Solution] | None = None, jobs: int = 1) -> Plan:
    """Load (unless given) and solve (unless given; over ``jobs`` processes) every problem; check
    the assignment's objective lists and point keys against the problems. Raises
    :class:`MechgradeError`."""
    problems = tuple(problems) if problems is not None else _load_problems(assignment)
    chosen = _choose_objectives(assignment, problems)  # before solving: its errors are cheap
    if solutions is None:
        solutions = _solve_all(assignment, problems, chosen, jobs)
    return _plan(assignment, problems, tuple(solutions), chosen)


def _solve_all(assignment: Assignment, problems: tuple[Problem, ...], chosen,
               jobs: int) -> list[Solution]:
    """Every problem solved for what grading needs. With several jobs, a problem error carried
    forward may re-solve is solved in this process (the re-solves, here or in processes forked
    from here, find its derivation made) while the others are solved in forked processes."""
    from ..solve import solve

    graded = [[o for i, o, _ in chosen if i == index] for index in range(len(problems))]
    drawn = {index for index, _, _ in _choose_diagrams(assignment, problems)}
    drawn |= {index for index, _ in _choose_equations(assignment, problems)}
    # a diagram needs the instant's state, which only solving an objective gives
    work = [partial(solve, p, objectives=_needed(p, graded[index])
                    if graded[index] or index not in drawn else None)
            for index, p in enumerate(problems)]
    ecf = assignment.policy.ecf.enabled
    here = [index for index, p in enumerate(problems)
            if jobs <= 1 or (ecf and any(_re_solved(p, o) for o in graded[index]))]
    away = [index for index in range(len(problems)) if index not in here]
    if not here:
        return raise_first(fork_map(outcome, work, jobs=jobs))
    forked = Forked(partial(fork_map, outcome, [work[i] for i in away], jobs=jobs)) \
        if away else None
    try:
        outcomes = dict(zip(here, (outcome(work[i]) for i in here)))
        if forked is not None:
            outcomes.update(zip(away, forked.result()))
    finally:
        if forked is not None:
            forked.cancel()
    return raise_first([outcomes[index] for index in range(len(problems))])


def _re_solved(problem: Problem, objective: Objective) -> bool:
    """Whether error carried forward may re-solve ``problem`` for ``objective``: it depends on
    an objective of the problem."""
    return any(upstream_objective(problem, upstream) is not None for upstream in objective.depends_on)


def _needed(problem: Problem, graded: list[Objective]) -> tuple[str, ...]:
    """The objectives of ``problem`` grading needs solved: the graded ones and, for error
    carried forward, those they depend on (deriving the others' mistakes is most of a solve).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("problems") / "bowling_3_15_8_connected_blocks.yaml")
    >>> _needed(p, [p.objective("rod_omega_z"), p.objective("V_A_N")])
    ('xdot', 'V_A_N', 'rod_omega_z')
    """
    needed = {o.id for o in graded}
    todo = [o.id for o in graded]
    while todo:
        for upstream in problem.objective(todo.pop()).depends_on:
            if upstream not in needed and upstream_objective(problem, upstream) is not None:
                needed.add(upstream)
                todo.append(upstream)
    return tuple(o.id for o in problem.objectives if o.id in needed)


def _load_problems(assignment: Assignment) -> tuple[Problem, ...]:
    from ..spec import load_problem

    return tuple(load_problem(ref.path) for ref in assignment.problems)


def _choose_objectives(assignment: Assignment, problems: tuple[Problem, ...]
                       ) -> list[tuple[int, Objective, float]]:
    """(problem index, objective, points) of every graded objective, in assignment order;
    raises :class:`AssignmentError` for a repeated problem, an unknown objective or point key."""
    seen: dict[str, Problem] = {}
    chosen: list[tuple[int, Objective, float]] = []
    for index, (ref, problem) in enumerate(zip(assignment.problems, problems)):
        if problem.id in seen:
            raise AssignmentError(f"expected problems with different ids, found '{problem.id}' "
                                  f"twice", where=ref.where)
        seen[problem.id] = problem
        known = [o.id for o in problem.objectives]
        wanted = ref.objectives if ref.objectives is not None else tuple(known)
        for objective_id in wanted:
            if objective_id not in known:
                raise AssignmentError(
                    f"expected an objective of problem '{problem.id}' ({', '.join(known)}), "
                    f"found '{objective_id}'", where=ref.where)
        _check_steps(ref, problem, wanted)
        placed: set[str] = set()
        for objective_id in wanted:
            # a step is graded before the objective it leads to, its error carried forward
            for step in (*ref.steps_of(objective_id), objective_id):
                if step in placed:
                    continue
                placed.add(step)
                objective = problem.objective(step)
                earlier = _steps_before(ref, step)
                if earlier:
                    objective = replace(objective, depends_on=tuple(
                        dict.fromkeys((*objective.depends_on, *earlier))))
                chosen.append((index, objective, assignment.points_for(problem.id, step)))
    keys = {f"{problems[index].id}.{objective.id}" for index, objective, _ in chosen}
    keys |= {f"{problems[index].id}.{body}.fbd"
             for index, body, _ in _choose_diagrams(assignment, problems)}
    keys |= {f"{problems[index].id}.{PlannedEquations.objective_id}"
             for index, _ in _choose_equations(assignment, problems)}
    for key, _ in assignment.points:
        if key not in keys:
            raise AssignmentError(f"expected a graded objective 'problem_id.objective_id' "
                                  f"({listing(sorted(keys))}), found '{key}'",
                                  where=assignment.where_points(key))
    return chosen


def _check_steps(ref, problem: Problem, wanted: tuple[str, ...]) -> None:
    """Raise :class:`AssignmentError` for ``steps:`` of an objective not graded or naming
    what is not an objective of ``problem``."""
    known = [o.id for o in problem.objectives]
    for objective_id, chain in ref.steps:
        if objective_id not in wanted:
            raise AssignmentError(
                f"expected steps of a graded objective of problem '{problem.id}' "
                f"({', '.join(wanted) or 'none is graded'}), found '{objective_id}'",
                where=ref.where_steps(objective_id))
        for step in chain:
            if step not in known:
                raise AssignmentError(
                    f"expected steps that are objectives of problem '{problem.id}' "
                    f"({', '.join(known)}), found '{step}'",
                    where=ref.where_steps(objective_id))


def _steps_before(ref, objective_id: str) -> tuple[str, ...]:
    """The steps of the write-up graded before ``objective_id``: all of its own steps, or,
    for a step, the steps before it in the first chain that lists it.

    >>> from mechgrade.grade.assignment import ProblemRef
    >>> ref = ProblemRef(Path("p.yaml"), steps=(("omega", ("xdot", "v_A")),))
    >>> _steps_before(ref, "omega"), _steps_before(ref, "v_A"), _steps_before(ref, "xdot")
    (('xdot', 'v_A'), ('xdot',), ())
    """
    own = ref.steps_of(objective_id)
    if own:
        return own
    for _, chain in ref.steps:
        if objective_id in chain:
            return chain[:chain.index(objective_id)]
    return ()


def _step_of(ref, objective_id: str) -> str:
    """The objective whose write-up lists ``objective_id`` as a step first (``""``: none)."""
    return next((o for o, chain in ref.steps if objective_id in chain), "")


def _choose_diagrams(assignment: Assignment, problems: tuple[Problem, ...]
                     ) -> list[tuple[int, str, float]]:
    """(problem index, body, points) of every graded free-body diagram; raises
    :class:`AssignmentError` for a body the problem does not have."""
    chosen = []
    for index, (ref, problem) in enumerate(zip(assignment.problems, problems)):
        if not ref.diagrams:
            continue
        bodies = [b.name for b in problem.dynamics.bodies] if problem.dynamics else []
        for body in ref.diagrams:
            if body not in bodies:
                raise AssignmentError(f"expected a body of problem '{problem.id}' "
                                      f"({', '.join(bodies) or 'it has none'}), found '{body}'",
                                      where=ref.where)
            chosen.append((index, body, assignment.points_for(problem.id, f"{body}.fbd")))
    return chosen


def _choose_equations(assignment: Assignment, problems: tuple[Problem, ...]
                      ) -> list[tuple[int, float]]:
    """(problem index, points) of every problem whose equations of motion are graded; raises
    :class:`AssignmentError` for a problem without bodies or with an objective of that id."""
    chosen = []
    for index, (ref, problem) in enumerate(zip(assignment.problems, problems)):
        if not ref.equations:
            continue
        key = PlannedEquations.objective_id
        if problem.dynamics is None or any(o.id == key for o in problem.objectives):
            raise AssignmentError(
                f"expected equations of a problem with bodies and no objective '{key}', "
                f"found '{problem.id}'", where=ref.where)
        chosen.append((index, assignment.points_for(problem.id, key)))
    return chosen


def _plan(assignment: Assignment, problems: tuple[Problem, ...],
          solutions: tuple[Solution, ...], chosen) -> Plan:
    planned = tuple(PlannedObjective(problems[index], objective,
                                     graded_result(solutions[index], objective.id), points,
                                     steps=_steps_before(assignment.problems[index],
                                                         objective.id),
                                     step_of=_step_of(assignment.problems[index], objective.id))
                    for index, objective, points in chosen)
    diagrams = []
    instants: dict[int, DerivationInstant] = {}
    for index, body, points in _choose_diagrams(assignment, problems):
        if index not in instants:
            from ..solve.derivation import derivation_instant
            instants[index] = derivation_instant(problems[index], solutions[index])
        diagrams.append(PlannedDiagram(problems[index], body, instants[index], points))
    equations = []
    for index, points in _choose_equations(assignment, problems):
        from ..solve.derivation import motion_samples
        equations.append(PlannedEquations(problems[index],
                                          motion_samples(problems[index], solutions[index]),
                                          points))
    return Plan(assignment, problems, solutions, planned, tuple(diagrams), tuple(equations))


def graded_result(solution: Solution, objective_id: str) -> ObjectiveResult:
    """The objective's reference as graded: a symbolic one records each symbol's sign at the
    solved instant (``symbol_signs``), so that kinetic friction's ``sign(xd)`` is judged for
    the sense of sliding the problem states (see :func:`mechgrade.grade.compare.sample_points`).

    >>> from mechgrade.solve.result import ObjectiveResult, Solution, StateValue
    >>> a = ObjectiveResult("a", "symbolic", "m/s^2", expr="g*sign(xd)", symbols=("g", "xd"))
    >>> graded_result(Solution("p", (a,), (StateValue("g", 9.81, "m/s^2", True, 9.81),
    ...               StateValue("x'", -2.0, "m/s", True, -2.0))), "a").symbol_signs
    (1, -1)
    """
    result = solution.result(objective_id)
    if result.kind != ObjectiveKind.SYMBOLIC or not solution.state:
        return result
    from .answers import symbol_aliases

    state = {s.name: s.si for s in solution.state}
    for (base, order), symbol in ((k, v) for k, v in symbol_aliases(result.symbols).items()
                                  if isinstance(k, tuple)):
        state.setdefault(symbol, state.get(base + "'" * order, 0.0))
    signs = tuple(int(math.copysign(1, state[s])) if state.get(s) else 0
                  for s in result.symbols)
    return replace(result, symbol_signs=signs) if any(signs) else result


def failing_expects(plan: Plan) -> tuple[FailingExpect, ...]:
    """The ``expect:`` tests of the plan's problems its solutions fail, each with where it is
    written and what ``mechgrade check`` says; only the objectives solved for grading are
    tested (their solutions are at hand, so this costs a comparison per test).

    >>> from mechgrade.grade.assignment import Assignment
    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.solve import solve
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    >>> plan = Plan(Assignment("hw", "HW", p.path, ()), (p,), (solve(p, objectives=("acc_mag",)),), ())
    >>> failing_expects(plan)
    ()
    """
    from ..check import expect_outcome

    failing = []
    for problem, solution in zip(plan.problems, plan.solutions):
        solved = {r.id: r for r in solution.results}
        for objective in problem.objectives:
            if objective.expect is None or objective.id not in solved:
                continue
            try:
                outcome = expect_outcome(objective, solved[objective.id])
                passed, said = outcome.passed, outcome.message
            except MechgradeError as err:
                passed, said = False, err.message
            if not passed:
                failing.append(FailingExpect(problem.id, objective.id,
                                             str(objective.expect.where), said))
    return tuple(failing)


def failing_expects_error(failing: tuple[FailingExpect, ...]) -> SpecError:
    """The error that stops a grading run whose problems fail their own tests (every student
    would be graded against a reference its author says is wrong): one line per test."""
    errors = [SpecError(f"{f.where}: expected the solver to pass this expect: test before "
                        f"grading, found {f.objective}: {f.message}; fix the problem file "
                        f"(mechgrade check shows it) or grade anyway with "
                        f"--accept-failing-expect") for f in failing]
    return errors[0] if len(errors) == 1 else SpecErrors(errors)


def grade_submissions(assignment: Assignment, submissions_dir: str | Path, roster=None, *,
                      progress: Progress | None = None, jobs: int = 1,
                      submissions_format: SubmissionFormat | None = None,
                      accept_failing_expect: bool = False) -> GradeReport:
    """Grade every submission in ``submissions_dir`` (and list every ``roster`` student).

    ``submissions_dir`` may also be an LMS's download zip or quiz responses CSV
    (:func:`mechgrade.grade.lms_submissions.read_any_submissions`; ``submissions_format``
    names its kind, detected when ``None``). ``progress(done, total)`` is called as students
    are finished. With ``jobs`` > 1 the submissions are read (by ``jobs`` processes) while the
    problems are solved (by ``jobs`` processes), and the answers are judged by ``jobs``
    workers; the report is the same for any ``jobs``. A problem failing its own ``expect:``
    tests stops the run (see :func:`grade_plan`).
    """
    problems = _load_problems(assignment)
    chosen = _choose_objectives(assignment, problems)
    keys = frozenset(f"{problems[index].id}.{objective.id}" for index, objective, _ in chosen)
    keys |= {f"{problems[index].id}.{body}.fbd"
             for index, body, _ in _choose_diagrams(assignment, problems)}
    keys |= {f"{problems[index].id}.{PlannedEquations.objective_id}"
             for index, _ in _choose_equations(assignment, problems)}
    drawn = frozenset(f"{problems[index].id}.{objective.id}" for index, objective, _ in chosen
                      if problems[index].variants is not None)
    read = partial(read_any_submissions, submissions_dir, keys=keys, roster=roster,
                   fmt=submissions_format, drawn_keys=drawn)
    if jobs <= 1:
        plan = plan_assignment(assignment, problems=problems)
        return grade_plan(plan, read(), roster, progress=progress,
                          accept_failing_expect=accept_failing_expect)
    # Reading needs only the keys: it runs in a process forked now, before this one imports
    # sympy and the solver and solves, so the two overlap.
    reading = Forked(partial(outcome, partial(read, jobs=jobs)))
    try:
        plan = plan_assignment(assignment, problems=problems, jobs=jobs)
        submissions = raise_first([reading.result()])[0]
    finally:
        reading.cancel()
    return grade_plan(plan, submissions, roster, progress=progress, jobs=jobs,
                      accept_failing_expect=accept_failing_expect)


def grade_plan(plan: Plan, submissions: SubmissionSet, roster=None, *,
               progress: Progress | None = None, resolve: Resolver | None = None,
               jobs: int = 1, accept_failing_expect: bool = False) -> GradeReport:
    """Grade read submissions against a :class:`Plan` (see :func:`grade_submissions`).

    ``resolve(problem, givens)`` recomputes a solution with overridden givens (for ECF); the
    default is :func:`mechgrade.solve.solve`. Answers are judged by ``jobs`` sandbox workers.

    A problem whose solution fails its own ``expect:`` tests (:func:`failing_expects`) is
    refused with a :class:`SpecError` naming each, before anything is judged; with
    ``accept_failing_expect`` it is graded, and the report records the tests it fails.
    """
    failing = failing_expects(plan)
    if failing and not accept_failing_expect:
        raise failing_expects_error(failing)
    people, conflicts = _people(submissions, roster)
    total = len(people)
    if progress:
        progress(0, total)
    judge = _Judge(plan.assignment.policy, resolve, jobs)
    students: list[StudentResult] = []
    faults: list[str] = [s.internal_error for s in submissions.students if s.internal_error]
    if any(p.variants for p in plan.problems):  # every student's variant solved together
        from .variants import prepare_variants
        prepare_variants(plan, [person.variant_key or person.id for person, _ in people],
                         jobs)
    own = {person.id: _own_plan(plan, person) for person, _ in people}
    neighbours = None
    if any(variants for _, variants in own.values()):
        from .variants import OWN_GIVENS, NeighbourIndex

        # the problem's own givens are a variant too: the one in the book, or last year's
        neighbours = NeighbourIndex({OWN_GIVENS: plan.objectives,
                                     **{pid: p.objectives for pid, (p, _) in own.items()}})
    try:
        judge.prefetch(plan, submissions.students)
        judge.ecf.prefetch((own[person.id][0], submission)
                                       for person, submission in people if submission is not None)
        for done, (person, submission) in enumerate(people, start=1):
            # the student's own references, also for ECF's look-ups
            mine, variants = own[person.id]
            student = _grade_student_safely(mine, judge, person, submission, faults)
            students.append(_with_variant(student, mine, variants, neighbours,
                                          person.id))
            if progress:
                progress(done, total)
    finally:
        judge.close()
    assignment = plan.assignment
    objectives = tuple(ObjectiveInfo(o.problem.id, o.objective.id, o.objective.prompt,
                                     o.max_points, o.problem.title) for o in plan.objectives)
    objectives += tuple(ObjectiveInfo(d.problem.id, d.objective_id,
                                      f"The free-body diagram of body {d.body} ({d.problem.title}).",
                                      d.max_points,
                                      d.problem.title) for d in plan.diagrams)
    objectives += tuple(ObjectiveInfo(e.problem.id, e.objective_id,
                                      f"The equations of motion ({e.problem.title}).",
                                      e.max_points, e.problem.title) for e in plan.equations)
    # in the assignment's order of problems (a problem's objectives, then its diagrams and
    # equations), as the exports list them
    place = {p.id: n for n, p in reversed(list(enumerate(plan.problems)))}
    objectives = tuple(sorted(objectives, key=lambda o: place[o.problem]))
    return GradeReport(AssignmentInfo(assignment.id, assignment.title), objectives,
                       tuple(students), submissions.skipped,
                       (*submissions.notes, *conflicts, *author_warnings(plan)), tuple(faults),
                       failing)


def author_warnings(plan: Plan) -> tuple[str, ...]:
    """The warnings of the assignment's problems and of solving them (a magnitude implausible
    for its unit system, a material point meant): printed by ``grade`` as by ``check``."""
    from ..check import tolerance_faults  # grading never applies them: it says so

    found = [str(w) for p, s in zip(plan.problems, plan.solutions)
             for w in (*p.warnings, *s.warnings, *tolerance_faults(p, s))]
    return tuple(dict.fromkeys(found))


# ---------------------------------------------------------------------------- variants


def _own_plan(plan: Plan, person: "_Person") -> tuple[Plan, list]:
    """The plan with the student's own variant of every problem that draws one (solved warm);
    the plan itself when none does. See :mod:`.variants`."""
    if not any(p.variants for p in plan.problems):
        return plan, []
    from .variants import student_variant

    assignment = plan.assignment
    solutions, variants, givens = list(plan.solutions), [], {}
    for i, problem in enumerate(plan.problems):
        if problem.variants is not None:
            variant, solutions[i] = student_variant(
                problem, assignment.variant_seed, person.variant_key or person.id,
                assignment.variants.redraw)
            variants.append(variant)
            givens[problem.id] = variant.overrides
    index = {p.id: i for i, p in enumerate(plan.problems)}
    objectives = tuple(
        o if o.problem.id not in givens else
        replace(o, result=graded_result(solutions[index[o.problem.id]], o.objective.id),
                givens=givens[o.problem.id])
        for o in plan.objectives)
    # a diagram and the equations are judged at the student's own numbers too
    instants: dict[str, DerivationInstant] = {}
    diagrams = list(plan.diagrams)
    for n, d in enumerate(diagrams):
        if d.problem.id in givens:
            if d.problem.id not in instants:
                from ..solve.derivation import derivation_instant
                instants[d.problem.id] = derivation_instant(
                    d.problem, solutions[index[d.problem.id]])
            diagrams[n] = replace(d, instant=instants[d.problem.id])
    equations = list(plan.equations)
    for n, e in enumerate(equations):
        if e.problem.id in givens:
            from ..solve.derivation import motion_samples
            equations[n] = replace(e, samples=motion_samples(
                e.problem, solutions[index[e.problem.id]]))
    return Plan(plan.assignment, plan.problems, tuple(solutions), objectives,
                tuple(diagrams), tuple(equations)), variants


def _with_variant(student: StudentResult, own: Plan, variants: list, neighbours,
                  person_id: str) -> StudentResult:
    """The student's numbers recorded, and answers that fit a neighbour's numbers noted
    (``own``: the student's plan; ``neighbours``: the class's references by student)."""
    if not variants:
        return student
    from dataclasses import replace

    from .variants import mark_neighbours, student_record

    references = {o.key: o.result for o in own.objectives}
    student = mark_neighbours(student, references, neighbours, person_id, variants)
    return replace(student, variant=student_record(own.assignment.variant_seed, variants))


# ---------------------------------------------------------------------------- students


@dataclass(frozen=True)
class _Person:
    id: str
    name: str
    identity: tuple[tuple[str, str], ...] = ()
    on_roster: bool = True
    variant_key: str = ""  # the roster id: what a student's variant is drawn for
    conflict: str = ""  # the roster conflict this student or folder is in (see _people)


def _people(submissions: SubmissionSet, roster) -> tuple[list[tuple[_Person, Submission | None]],
                                                        tuple[str, ...]]:
    """Roster students in roster order (with their submission, if any), then the submissions
    no roster student claimed, by id; and a note per roster conflict. The students and folders
    of a conflict (:func:`mechgrade.roster.pair_students`) are not paired: each is listed with
    the conflict, and graded as no one's."""
    if roster is None:
        return [(_Person(s.student, ""), s) for s in submissions.students], ()
    # A submission folder may be named by any of a student's identifiers.
    candidates: list[dict[MatchKind, set[str]]] = [
        {kind: {fold(s.student)} for kind in MatchKind if kind is not MatchKind.NAME}
        for s in submissions.students]
    pairing = pair_students(roster, candidates)
    kinds = Counter(kind for _, kind in pairing.pairs if kind is not None)
    # A student without a submission is named like the submissions that were matched.
    usual = kinds.most_common(1)[0][0] if kinds else MatchKind.ID
    labels = [s.student for s in submissions.students]
    conflicted: dict[tuple[str, int], str] = {}
    notes = []
    for conflict in pairing.conflicts:
        said = conflict.describe(roster, labels)
        notes.append(f"roster conflict: {said}; none of these folders was graded as anyone's "
                     f"(status 'conflict', kept out of exports): rename the folders so that "
                     f"each matches one student")
        conflicted.update({("s", s): said for s in conflict.students})
        conflicted.update({("c", c): said for c in conflict.candidates})
    out: list[tuple[_Person, Submission | None]] = []
    for number, (student, (index, _)) in enumerate(zip(roster.students, pairing.pairs)):
        identity = tuple(student.columns)
        if index is not None:
            found = submissions.students[index]
            out.append((_Person(found.student, student.name, identity, True, student.id),
                        found))
        else:
            sid = identifier(student, usual) or student.id
            out.append((_Person(sid, student.name, identity, True, student.id,
                                conflicted.get(("s", number), "")), None))
    claimed = {index for index, _ in pairing.pairs if index is not None}
    for i, submission in enumerate(submissions.students):
        if i not in claimed:
            out.append((_Person(submission.student, "", (), False,
                                conflict=conflicted.get(("c", i), "")), submission))
    return out, tuple(notes)


def _grade_student_safely(plan: Plan, judge: "_Judge", person: _Person,
                          submission: Submission | None, faults: list[str]) -> StudentResult:
    """Grading one student as one unit of work: a fault of mechgrade's inside it makes that
    student ``not_evaluated`` (recorded in ``faults``) and the run goes on."""
    try:
        return _grade_student(plan, judge, person, submission, faults)
    except Exception as exc:  # noqa: BLE001 - the per-student boundary
        detail = brief_exception(exc)
        faults.append(f"grading '{person.id}': {detail}")
        reason = f"internal error: {detail}; please tell your instructor"
        answers = tuple(AnswerResult(o.problem.id, o.objective.id, None, Verdict.NOT_EVALUATED, 0.0,
                                     o.max_points, None, reason) for o in plan.objectives)
        return StudentResult(person.id, person.name, Status.NOT_EVALUATED, 0.0, plan.max_score,
                             answers, (reason,), person.identity)


def _grade_student(plan: Plan, judge: "_Judge", person: _Person,
                   submission: Submission | None, faults: list[str]) -> StudentResult:
    messages: list[str] = []
    if person.conflict:
        messages.append(f"roster conflict: {person.conflict}; graded as no one's until your "
                        f"instructor sorts it out")
    elif not person.on_roster:
        messages.append("not on the roster")
    if submission is not None:
        messages.extend(submission.messages)
    status = _STATUS[submission.status if submission else None]
    if submission is None and not person.conflict:
        messages.append("no submission found")
    answers: list[AnswerResult] = []
    verdicts: dict[str, AnswerResult] = {}
    # An objective not answered never shows its expected answer, even when the assignment
    # reveals answers: an empty upload must not harvest them.
    for item in plan.objectives:
        text = submission.answer(item.key) if submission is not None else None
        if status == Status.UNREADABLE:
            answer = AnswerResult(item.problem.id, item.objective.id, None, Verdict.UNREADABLE, 0.0,
                                  item.max_points, None,
                                  "Your answer file could not be read (see the messages).")
        elif submission is None or text is None or not text.strip():
            answer = AnswerResult(item.problem.id, item.objective.id, text, Verdict.MISSING, 0.0,
                                  item.max_points, None, "No answer was given.")
        else:
            answer = _judge_safely(plan, judge, item, text, submission, verdicts, person,
                                   faults)
            answer = _first_wrong_step(item, answer, verdicts)
        verdicts[item.key] = answer
        answers.append(answer)
    parts: list[PlannedDiagram | PlannedEquations] = [*plan.diagrams, *plan.equations]
    for part in parts:
        text = submission.answer(part.key) if submission is not None else None
        if status == Status.UNREADABLE:
            answers.append(AnswerResult(part.problem.id, part.objective_id, None,
                                        Verdict.UNREADABLE,
                                        0.0, part.max_points, None, "Your answer file could "
                                        "not be read (see the messages)."))
        else:
            answers.append(_judge_derivation_safely(part, text, person, faults))
    score = _round(sum(a.points for a in answers))
    return StudentResult(person.id, person.name, Status.CONFLICT if person.conflict else status,
                         score, plan.max_score, tuple(answers), tuple(messages),
                         person.identity)


def _first_wrong_step(item: PlannedObjective, answer: AnswerResult,
                      verdicts: dict[str, AnswerResult]) -> AnswerResult:
    """``answer`` naming the first of ``item``'s steps answered wrong (a step missing is only
    missing; one credited by error carried forward is not where the error is): on the
    objective the steps lead to, and on a later step not right by itself.

    >>> from mechgrade.grade.results import AnswerResult, Verdict
    >>> step = AnswerResult("p", "xdot", "2", Verdict.INCORRECT, 0.0, 1.0)
    >>> item = PlannedObjective(None, None, None, 1.0, steps=("xdot",))
    >>> answer = AnswerResult("p", "omega", "3", Verdict.CORRECT, 1.0, 1.0)
    >>> named = _first_wrong_step(item, answer, {"p.xdot": step})
    >>> named.first_wrong_step, named.feedback
    ('xdot', "The first wrong step of your write-up is step 1, 'xdot'.")
    >>> _first_wrong_step(replace(item, step_of="v"), answer, {"p.xdot": step}) == answer
    True
    """
    if item.step_of and answer.verdict == Verdict.CORRECT and answer.diagnosis != ECF_DIAGNOSIS:
        return answer
    for number, step in enumerate(item.steps, start=1):
        judged = verdicts.get(f"{answer.problem}.{step}")
        if judged is None or judged.verdict in (Verdict.CORRECT, Verdict.MISSING) or \
                judged.diagnosis == ECF_DIAGNOSIS:
            continue
        said = f"The first wrong step of your write-up is step {number}, '{step}'."
        return replace(answer, first_wrong_step=step,
                       feedback=" ".join(f for f in (answer.feedback, said) if f))
    return answer


_STATUS = {None: Status.MISSING, SubmissionStatus.MISSING: Status.MISSING,
           SubmissionStatus.READ: Status.GRADED, SubmissionStatus.UNREADABLE: Status.UNREADABLE}
"""A student's status from their submission's (``None``: no submission)."""


def _judge_safely(plan: Plan, judge: "_Judge", item: PlannedObjective, text: str, submission: Submission,
                  verdicts: dict, person: _Person, faults: list[str]) -> AnswerResult:
    """One answer judged; a fault of mechgrade's makes it ``not_evaluated``, nothing more."""
    try:
        return judge.judge(plan, item, text, submission, verdicts)
    except Exception as exc:  # noqa: BLE001 - one answer must not take its student down
        detail = brief_exception(exc)
        faults.append(f"judging '{person.id}' {item.key}: {detail}")
        return AnswerResult(item.problem.id, item.objective.id, text, Verdict.NOT_EVALUATED, 0.0,
                            item.max_points, None,
                            f"internal error: {detail}; please tell your instructor", None,
                            judge.expected(item))


def _judge_derivation_safely(part: PlannedDiagram | PlannedEquations, text: str | None,
                             person: _Person, faults: list[str]) -> AnswerResult:
    """One free-body diagram (a row per load, :mod:`.fbd`) or set of equations of motion
    (:mod:`.equations`) judged; a fault of mechgrade's makes it ``not_evaluated``, nothing
    more."""
    rows: tuple[LoadResult, ...] = ()
    try:
        if isinstance(part, PlannedDiagram):
            from .fbd import judge_diagram

            judged = judge_diagram(text, part.instant, part.body)
            rows = tuple(LoadResult(row.label, row.load, row.kind, row.point,
                                    row.answer, tuple(str(m) for m in row.mistakes),
                                    row.feedback) for row in judged.rows)
            assessment = judged.assessment
        else:
            from .equations import judge_equations

            assessment = judge_equations(text, part.samples).assessment
    except Exception as exc:  # noqa: BLE001 - one answer must not take its student down
        detail = brief_exception(exc)
        faults.append(f"judging '{person.id}' {part.key}: {detail}")
        return AnswerResult(part.problem.id, part.objective_id, text, Verdict.NOT_EVALUATED, 0.0,
                            part.max_points, None,
                            f"internal error: {detail}; please tell your instructor")
    return AnswerResult(part.problem.id, part.objective_id, text, assessment.verdict,
                        _round(assessment.credit * part.max_points), part.max_points,
                        assessment.diagnosis, assessment.feedback, assessment.read_back,
                        loads=rows)


# ---------------------------------------------------------------------------- judging


class _Judge:
    """Judges answers in sandbox workers (one per job), once per distinct (objective, text)."""

    def __init__(self, policy: GradingPolicy, resolve: Resolver | None, jobs: int = 1):
        self.policy = policy
        self._jobs = jobs
        self._cache: dict[tuple[int, str], Assessment] = {}
        self._references: dict[ObjectiveResult, int] = {}  # each distinct one, numbered
        self._numbers: dict[int, tuple[ObjectiveResult, int]] = {}  # by id(): its number
        self.ecf = CarriedForward(policy, self, resolve, jobs)
        self._pool: SandboxPool | None = None

    def close(self) -> None:
        if self._pool is not None:
            self._pool.close()
            self._pool = None

    def _sandboxes(self) -> SandboxPool:
        if self._pool is None:
            from .sandbox import SandboxPool

            self._pool = SandboxPool(self._jobs)
        return self._pool

    def _key(self, result: ObjectiveResult, text: str) -> tuple[int, str]:
        """The cache key of judging ``text`` against ``result``: equal references share their
        judgements, and a reference (hashed over all its fields) is hashed once per object,
        not once per answer."""
        known = self._numbers.get(id(result))
        if known is None:  # kept with its number, so that its id() stays its own
            number = self._references.setdefault(result, len(self._references))
            known = self._numbers[id(result)] = (result, number)
        return known[1], text

    def assess(self, text: str, result: ObjectiveResult):
        """Judge one answer in the run's sandbox workers (started once, reused for all)."""
        key = self._key(result, text)
        if key not in self._cache:
            self._cache[key] = self._sandboxes().assess(text, result, self.policy)
        return self._cache[key]

    def judged(self, result: ObjectiveResult, text: str) -> Assessment | None:
        """``text`` as judged against ``result`` already (``None``: not judged yet)."""
        return self._cache.get(self._key(result, text))

    def prefetch(self, plan: Plan, submissions: Iterable[Submission]) -> None:
        """Judge every distinct answer of ``submissions`` to ``plan``'s objectives up front,
        in batches spread over the workers; :meth:`judge` then finds them judged. A fault of
        mechgrade's here leaves the answers to be judged one by one, each inside its own
        boundary (:func:`_judge_safely`)."""
        try:
            self.judge_all((item.result, text)
                           for submission in submissions
                           if submission.status == SubmissionStatus.READ
                           for item in plan.objectives
                           if (text := submission.answer(item.key)) is not None and text.strip())
        except Exception:  # noqa: BLE001 - see the docstring: the per-answer path reports it
            pass

    def judge_all(self, pairs: Iterable[tuple[ObjectiveResult, str]]) -> None:
        """Judge each ``(reference, answer)`` of ``pairs`` not judged yet, in one batch over
        the sandbox workers, into the cache."""
        todo: dict[tuple[int, str], ObjectiveResult] = {}
        for result, text in pairs:
            key = self._key(result, text)
            if key not in self._cache:
                todo[key] = result
        if todo:
            judged = self._sandboxes().assess_many(
                [(text, result, self.policy) for (_, text), result in todo.items()])
            self._cache.update(zip(todo, judged))

    def expected(self, item: PlannedObjective) -> str | None:
        return expected_text(item.result) if self.policy.reveal_answers else None

    def expected_in(self, item: PlannedObjective, unit: str | None) -> str | None:
        """The reference in the unit the student wrote (see :func:`expected_in_unit`)."""
        return (expected_in_unit(item.result, unit)
                if self.policy.reveal_answers and unit else None)

    def judge(self, plan: Plan, item: PlannedObjective, text: str, submission: Submission,
              earlier: dict[str, AnswerResult]) -> AnswerResult:
        """One answer of the student whose references ``plan`` holds (their variant's),
        ``earlier`` their answers judged so far (for error carried forward)."""
        assessment = self.assess(text, item.result)
        verdict, credit = assessment.verdict, float(assessment.credit)
        feedback = [assessment.feedback] if assessment.feedback else []
        credit = min(max(credit, 0.0), 1.0)
        diagnosis = assessment.diagnosis
        if verdict != Verdict.CORRECT and item.objective.depends_on and self.ecf.enabled:
            judged = credit
            verdict, credit = self.ecf.carry_forward(plan, item, text, submission, earlier,
                                                     verdict, credit, feedback)
            if credit > judged:  # the mistake was upstream: this answer is consistent with it
                diagnosis = ECF_DIAGNOSIS
        return AnswerResult(item.problem.id, item.objective.id, text, verdict,
                            _round(credit * item.max_points), item.max_points,
                            diagnosis, " ".join(f for f in feedback if f),
                            assessment.read_back, self.expected(item),
                            self.expected_in(item, assessment.unit))

def expected_text(result: ObjectiveResult) -> str:
    """The reference answer as text, in the objective's unit.

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> expected_text(ObjectiveResult("a", "scalar", "ft / s ** 2", 98.5096))
    '98.51 ft/s^2'
    >>> expected_text(ObjectiveResult("a", "vector", "m/s", (0.0, -7.6712, 0.0), frame="A"))
    '(0, -7.671, 0) m/s in frame A'
    """
    from ..solve.result import in_frame

    unit = result.unit.replace(" ** ", "^").replace(" * ", "*").replace(" / ", "/")
    suffix = f" {unit}" if unit else ""
    if result.kind == ObjectiveKind.SYMBOLIC or result.value is None:
        return f"{result.expr}{suffix}" if result.expr else "(no reference)"
    if isinstance(result.value, tuple):
        parts = ", ".join(_number(v) for v in result.value)
        return f"({parts}){suffix}{in_frame(result.frame)}"
    return f"{_number(result.value)}{suffix}"


def expected_in_unit(result: ObjectiveResult, unit: str) -> str | None:
    """The numeric reference answer in ``unit``, another unit of the objective's dimension, with
    the figures of :func:`expected_text`; ``None`` for a symbolic objective, a unit of another
    dimension, or one whose numbers would read as those in the objective's unit.

    >>> from mechgrade.solve.result import ObjectiveResult
    >>> expected_in_unit(ObjectiveResult("F", "scalar", "N", 36.787), "lbf")
    '8.27 lbf'
    >>> expected_in_unit(ObjectiveResult("v", "vector", "m/s", (0.0, -7.6712, 0.0), frame="A"),
    ...                  "ft / s")
    '(0, -25.17, 0) ft/s'
    >>> expected_in_unit(ObjectiveResult("F", "scalar", "N", 36.787), "kg * m / s ** 2") is None
    True
    """
    from ..units import from_si, same_dimension, to_si

    if result.kind == ObjectiveKind.SYMBOLIC or result.value is None:
        return None
    references = result.value if isinstance(result.value, tuple) else (result.value,)
    try:
        if not same_dimension(unit, result.unit):
            return None
        texts = [_number(from_si(to_si(v, result.unit), unit)) for v in references]
    except MechgradeError:  # a unit mechgrade cannot read shows nothing more
        return None
    if texts == [_number(v) for v in references]:  # N and kg*m/s^2: the same numbers again
        return None
    numbers = f"({', '.join(texts)})" if isinstance(result.value, tuple) else texts[0]
    return f"{numbers} {unit_text(unit)}"


def _number(value: float) -> str:
    from ..solve.result import without_round_off

    return f"{without_round_off(value):.4g}"


def _round(value: float) -> float:
    rounded = round(float(value), POINTS_DIGITS)
    return 0.0 if rounded == 0 else rounded
