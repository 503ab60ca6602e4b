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

from ..errors import (AssignmentError, InconsistentError, MechgradeError, SpecError, SpecErrors,
                      brief_exception)
from ..parallel import Forked, fork_map, outcome, raise_first
from ..expressions.syntax import Name, Prime
from ..roster import MATCH_KINDS, fold, pair_students
from ..spec.model import Objective, ObjectiveKind, Problem
from .assignment import Assignment, GradingPolicy
from .lms_submissions import read_any_submissions
from .results import (ECF_DIAGNOSIS, AnswerResult, AssignmentInfo, FailingExpect, GradeReport,
                      LoadResult, ObjectiveInfo, StudentResult, unit_text)
from .submissions import Submission, SubmissionSet

if TYPE_CHECKING:  # importing the solver package loads sympy and scipy: only when solving
    from ..solve.derivation import DerivationInstant, MotionSamples
    from ..solve.result import ObjectiveResult, Solution
    from .compare import Assessment

POINTS_DIGITS = 4
"""Points are rounded to this many decimals, so that sums are the same on every machine."""

Progress = Callable[[int, int], None]
Resolver = Callable[[Problem, dict], "Solution"]


@dataclass(frozen=True)
class PlannedObjective:
    """One graded objective: its problem, spec objective, reference result and points."""

    problem: Problem
    objective: Objective
    result: ObjectiveResult
    max_points: float
    givens: tuple[tuple[str, float], ...] = ()  # the student's variant: SI overrides

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
    objective_id = "equations"

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
    return any(_objective(problem, upstream) is not None for upstream in objective.depends_on)


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
            if upstream not in needed and _objective(problem, upstream) is not None:
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
            chosen.append((index, problem.objective(objective_id),
                           assignment.points_for(problem.id, objective_id)))
    keys = {f"{problems[index].id}.{objective.id}" for index, objective, _ in chosen}
    keys |= {f"{problems[index].id}.{body}.fbd"
             for index, body, _ in _choose_diagrams(assignment, problems)}
    keys |= {f"{problems[index].id}.{PlannedEquations.objective_id}"
             for index, _ in _choose_equations(assignment, problems)}
    for key, _ in assignment.points:
        if key not in keys:
            raise AssignmentError(f"expected a graded objective 'problem_id.objective_id' "
                                  f"({_listing(sorted(keys))}), found '{key}'",
                                  where=assignment.where_points(key))
    return chosen


def _choose_diagrams(assignment: Assignment, problems: tuple[Problem, ...]
                     ) -> list[tuple[int, str, float]]:
    """(problem index, body, points) of every graded free-body diagram; raises
    :class:`AssignmentError` for a body the problem does not have, or a problem drawing
    variants (a diagram is judged at the problem's own givens)."""
    chosen = []
    for index, (ref, problem) in enumerate(zip(assignment.problems, problems)):
        if not ref.diagrams:
            continue
        bodies = [b.name for b in problem.dynamics.bodies] if problem.dynamics else []
        if problem.variants is not None:
            raise AssignmentError(f"expected diagrams of problems without variants, found "
                                  f"'{problem.id}' drawing variants (its diagrams cannot be "
                                  f"graded yet)", where=ref.where)
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
    :class:`AssignmentError` for a problem without bodies, drawing variants, or with an
    objective of that id."""
    chosen = []
    for index, (ref, problem) in enumerate(zip(assignment.problems, problems)):
        if not ref.equations:
            continue
        key = PlannedEquations.objective_id
        if problem.dynamics is None or problem.variants is not None or \
                any(o.id == key for o in problem.objectives):
            raise AssignmentError(
                f"expected equations of a problem with bodies, no variants and no objective "
                f"'{key}', found '{problem.id}'", where=ref.where)
        chosen.append((index, assignment.points_for(problem.id, key)))
    return chosen


def _plan(assignment: Assignment, problems: tuple[Problem, ...],
          solutions: tuple[Solution, ...], chosen) -> Plan:
    planned = tuple(PlannedObjective(problems[index], objective,
                                     graded_result(solutions[index], objective.id), points)
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
    if result.kind != "symbolic" or not solution.state:
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
                      submissions_format: str | None = None,
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
    judge = _Judge(plan, resolve, jobs)
    students: list[StudentResult] = []
    faults: list[str] = [s.internal_error for s in submissions.students if s.internal_error]
    if any(p.variants for p in plan.problems):  # every student's variant solved together
        from .variants import prepare_variants
        prepare_variants(plan, [person.variant_key or person.id for person, _ in people])
    own = {person.id: _own_plan(plan, person) for person, _ in people}
    neighbours = None
    if any(variants for _, variants in own.values()):
        from .variants import OWN_GIVENS, NeighbourIndex

        # the problem's own givens are a variant too: the one in the book, or last year's
        neighbours = NeighbourIndex({OWN_GIVENS: plan.objectives,
                                     **{pid: p.objectives for pid, (p, _) in own.items()}})
    try:
        judge.prefetch(submissions.students)
        judge.prefetch_carried_forward((own[person.id][0], submission)
                                       for person, submission in people if submission is not None)
        for done, (person, submission) in enumerate(people, start=1):
            # the student's own references, also for ECF's look-ups
            judge.plan, variants = own[person.id]
            student = _grade_student_safely(judge.plan, judge, person, submission, faults)
            students.append(_with_variant(student, judge.plan, variants, neighbours,
                                          person.id))
            if progress:
                progress(done, total)
    finally:
        judge.close()
    assignment = plan.assignment
    objectives = tuple(ObjectiveInfo(o.problem.id, o.objective.id, o.objective.prompt,
                                     o.max_points, o.problem.title) for o in plan.objectives)
    objectives += tuple(ObjectiveInfo(d.problem.id, d.objective_id,
                                      f"The free-body diagram of the {d.body}.", d.max_points,
                                      d.problem.title) for d in plan.diagrams)
    objectives += tuple(ObjectiveInfo(e.problem.id, e.objective_id, "The equations of motion.",
                                      e.max_points, e.problem.title) for e in plan.equations)
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
        PlannedObjective(o.problem, o.objective,
                         graded_result(solutions[index[o.problem.id]], o.objective.id),
                         o.max_points, givens[o.problem.id])
        for o in plan.objectives)
    return Plan(plan.assignment, plan.problems, tuple(solutions), objectives,
                plan.diagrams, plan.equations), variants


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
    candidates = [{kind: {fold(s.student)} for kind in MATCH_KINDS if kind != "name"}
                  for s in submissions.students]
    pairing = pair_students(roster, candidates)
    kinds = Counter(kind for _, kind in pairing.pairs if kind is not None)
    # A student without a submission is named like the submissions that were matched.
    usual = kinds.most_common(1)[0][0] if kinds else "id"
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
            sid = _roster_value(student, usual) or student.id
            out.append((_Person(sid, student.name, identity, True, student.id,
                                conflicted.get(("s", number), "")), None))
    claimed = {index for index, _ in pairing.pairs if index is not None}
    for i, submission in enumerate(submissions.students):
        if i not in claimed:
            out.append((_Person(submission.student, "", (), False,
                                conflict=conflicted.get(("c", i), "")), submission))
    return out, tuple(notes)


def _roster_value(student, kind: str) -> str:
    if kind == "email_user":
        return student.email.split("@", 1)[0] if "@" in student.email else ""
    return getattr(student, kind, "") or ""


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
        answers = tuple(AnswerResult(o.problem.id, o.objective.id, None, "not_evaluated", 0.0,
                                     o.max_points, None, reason) for o in plan.objectives)
        return StudentResult(person.id, person.name, "not_evaluated", 0.0, plan.max_score,
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
    status = {None: "missing", "missing": "missing", "read": "graded",
              "unreadable": "unreadable"}[submission.status if submission else None]
    if submission is None and not person.conflict:
        messages.append("no submission found")
    answers: list[AnswerResult] = []
    verdicts: dict[str, AnswerResult] = {}
    # An objective not answered never shows its expected answer, even when the assignment
    # reveals answers: an empty upload must not harvest them.
    for item in plan.objectives:
        text = submission.answer(item.key) if submission is not None else None
        if status == "unreadable":
            answer = AnswerResult(item.problem.id, item.objective.id, None, "unreadable", 0.0,
                                  item.max_points, None,
                                  "Your answer file could not be read (see the messages).")
        elif submission is None or text is None or not text.strip():
            answer = AnswerResult(item.problem.id, item.objective.id, text, "missing", 0.0,
                                  item.max_points, None, "No answer was given.")
        else:
            answer = _judge_safely(judge, item, text, submission, verdicts, person, faults)
        verdicts[item.key] = answer
        answers.append(answer)
    parts: list[PlannedDiagram | PlannedEquations] = [*plan.diagrams, *plan.equations]
    for part in parts:
        text = submission.answer(part.key) if submission is not None else None
        if status == "unreadable":
            answers.append(AnswerResult(part.problem.id, part.objective_id, None, "unreadable",
                                        0.0, part.max_points, None, "Your answer file could "
                                        "not be read (see the messages)."))
        else:
            answers.append(_judge_derivation_safely(part, text, person, faults))
    score = _round(sum(a.points for a in answers))
    return StudentResult(person.id, person.name, "conflict" if person.conflict else status,
                         score, plan.max_score, tuple(answers), tuple(messages),
                         person.identity)


def _judge_safely(judge: "_Judge", item: PlannedObjective, text: str, submission: Submission,
                  verdicts: dict, person: _Person, faults: list[str]) -> AnswerResult:
    """One answer judged; a fault of mechgrade's makes it ``not_evaluated``, nothing more."""
    try:
        return judge.judge(item, text, submission, verdicts)
    except Exception as exc:  # noqa: BLE001 - one answer must not take its student down
        detail = brief_exception(exc)
        faults.append(f"judging '{person.id}' {item.key}: {detail}")
        return AnswerResult(item.problem.id, item.objective.id, text, "not_evaluated", 0.0,
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
            rows = tuple(LoadResult(row.label, row.load, str(row.kind) if row.kind else None,
                                    row.point, row.answer, tuple(str(m) for m in row.mistakes),
                                    row.feedback) for row in judged.rows)
            assessment = judged.assessment
        else:
            from .equations import judge_equations

            assessment = judge_equations(text, part.samples).assessment
    except Exception as exc:  # noqa: BLE001 - one answer must not take its student down
        detail = brief_exception(exc)
        faults.append(f"judging '{person.id}' {part.key}: {detail}")
        return AnswerResult(part.problem.id, part.objective_id, text, "not_evaluated", 0.0,
                            part.max_points, None,
                            f"internal error: {detail}; please tell your instructor")
    return AnswerResult(part.problem.id, part.objective_id, text, assessment.verdict,
                        _round(assessment.credit * part.max_points), part.max_points, None,
                        assessment.feedback, assessment.read_back, loads=rows)


# ---------------------------------------------------------------------------- judging


class _Judge:
    """Judges answers in sandbox workers (one per job), once per distinct (objective, text)."""

    def __init__(self, plan: Plan, resolve: Resolver | None, jobs: int = 1):
        self.plan = plan
        self.policy = plan.assignment.policy
        self._resolve = resolve
        self._jobs = jobs
        self._cache: dict[tuple[int, str], Assessment] = {}
        self._references: dict[ObjectiveResult, int] = {}  # each distinct one, numbered
        self._numbers: dict[int, tuple[ObjectiveResult, int]] = {}  # by id(): its number
        self._ecf_solutions: dict[tuple, tuple] = {}
        self._policy = compare_policy(self.policy)
        self._pool = None

    def close(self) -> None:
        if self._pool is not None:
            self._pool.close()
            self._pool = None

    def _sandboxes(self):
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
            self._cache[key] = self._sandboxes().assess(text, result, self._policy)
        return self._cache[key]

    def prefetch(self, submissions: Iterable[Submission]) -> None:
        """Judge every distinct answer of ``submissions`` up front, in batches spread over the
        workers; :meth:`judge` then finds them judged. A fault of mechgrade's here leaves the
        answers to be judged one by one, each inside its own boundary (:func:`_judge_safely`)."""
        try:
            todo: dict[tuple[int, str], ObjectiveResult] = {}
            for submission in submissions:
                if submission.status != "read":
                    continue
                for item in self.plan.objectives:
                    text = submission.answer(item.key)
                    if text is not None and text.strip():
                        key = self._key(item.result, text)
                        if key not in self._cache:
                            todo[key] = item.result
            self._judge_all(todo)
        except Exception:  # noqa: BLE001 - see the docstring: the per-answer path reports it
            pass

    def _judge_all(self, todo: dict[tuple[int, str], ObjectiveResult]) -> None:
        """Judge the answers of ``todo`` (cache key -> reference) in one batch over the sandbox
        workers, into the cache."""
        if todo:
            judged = self._sandboxes().assess_many(
                [(text, result, self._policy) for (_, text), result in todo.items()])
            self._cache.update(zip(todo, judged))

    def expected(self, item: PlannedObjective) -> str | None:
        return expected_text(item.result) if self.policy.reveal_answers else None

    def expected_in(self, item: PlannedObjective, unit: str | None) -> str | None:
        """The reference in the unit the student wrote (see :func:`expected_in_unit`)."""
        return (expected_in_unit(item.result, unit)
                if self.policy.reveal_answers and unit else None)

    def judge(self, item: PlannedObjective, text: str, submission: Submission,
              earlier: dict[str, AnswerResult]) -> AnswerResult:
        assessment = self.assess(text, item.result)
        verdict, credit = assessment.verdict, float(assessment.credit)
        feedback = [assessment.feedback] if assessment.feedback else []
        credit = min(max(credit, 0.0), 1.0)
        diagnosis = assessment.diagnosis
        if verdict != "correct" and item.objective.depends_on and self.policy.ecf.enabled:
            judged = credit
            verdict, credit = self._carry_forward(item, text, submission, earlier, verdict,
                                                  credit, feedback)
            if credit > judged:  # the mistake was upstream: this answer is consistent with it
                diagnosis = ECF_DIAGNOSIS
        return AnswerResult(item.problem.id, item.objective.id, text, verdict,
                            _round(credit * item.max_points), item.max_points,
                            diagnosis, " ".join(f for f in feedback if f),
                            assessment.read_back, self.expected(item),
                            self.expected_in(item, assessment.unit))

    def prefetch_carried_forward(self, work: Iterable[tuple[Plan, Submission]]) -> None:
        """Solve, over the jobs, the re-solves error carried forward will ask for (each
        student's ``(plan, submission)`` in ``work``), into :meth:`_solve_with`'s cache: they
        take most of a run's grading time when they are solved one after the other. Then judge
        the answers again against them, in one batch over the sandbox workers (not one round
        trip per answer). One not foreseen here (an upstream answer itself carried forward) is
        solved when asked; a fault of mechgrade's here leaves every one to be solved when
        asked."""
        if self._resolve is not None or not self.policy.ecf.enabled:
            return
        own = self.plan
        try:
            requests: dict[tuple, tuple] = {}
            again: dict[tuple, None] = {}  # (re-solve key, answer, objective) to judge again
            for plan, submission in work:
                self.plan = plan  # the student's references, for the upstream look-ups
                for item in (i for i in plan.objectives if i.objective.depends_on):
                    text = submission.answer(item.key) if submission.status == "read" else None
                    judged = self._cache.get(self._key(item.result, text)) \
                        if text is not None else None
                    if judged is None or judged.verdict == "correct":
                        continue
                    found = self._upstream_givens(item, submission, {})
                    if isinstance(found, dict) and found:
                        givens = {**dict(item.givens), **found}
                        key = _ecf_key(item.problem, givens, item.objective.id)
                        if key not in self._ecf_solutions:
                            requests[key] = (item.problem, givens, item.objective.id)
                        again[key, text, item.objective.id] = None
            _CARRYING[:] = [self]  # inherited by the forked workers
            try:
                solved = fork_map(_solve_carried, list(requests.values()), jobs=self._jobs)
            finally:
                _CARRYING.clear()
            self._ecf_solutions.update(zip(requests, solved))
            todo: dict[tuple[int, str], ObjectiveResult] = {}
            for key, text, objective_id in again:
                solution = self._ecf_solutions[key][0]
                if isinstance(solution, MechgradeError):
                    continue  # not solved: the per-answer path says why
                try:
                    recomputed = solution.result(objective_id)
                except (KeyError, MechgradeError):
                    continue
                if self._key(recomputed, text) not in self._cache:
                    todo[self._key(recomputed, text)] = recomputed
            self._judge_all(todo)
        except Exception:  # noqa: BLE001 - see the docstring: the per-answer path reports it
            pass
        finally:
            self.plan = own

    def _upstream_givens(self, item, submission, earlier) -> dict[str, float] | str:
        """The givens (SI, by given key) the student's wrong upstream answers stand for, or
        the feedback saying why error carried forward cannot use them."""
        problem = item.problem
        overrides: dict[str, float] = {}
        for upstream_id in item.objective.depends_on:
            key = f"{problem.id}.{upstream_id}"
            upstream = earlier.get(key)
            if upstream is None:
                upstream_text = submission.answer(key)
                if upstream_text is None:
                    continue  # not graded in this assignment and not answered
                try:
                    up_result = self._reference(problem, upstream_id)
                except KeyError:
                    continue
                assessment = self.assess(upstream_text, up_result)
                upstream_verdict = assessment.verdict
            else:
                upstream_text, upstream_verdict = upstream.answer, upstream.verdict
            if upstream_verdict == "correct" or upstream_text is None:
                continue
            if upstream_verdict in ("unreadable", "missing", "not_evaluated"):
                continue
            objective = _objective(problem, upstream_id)
            if objective is None:
                continue
            given_key = given_key_of(objective)
            if given_key is None:
                return (f"Error carried forward could not be applied: '{upstream_id}' is not a "
                        f"plain given quantity the solver can take from your answer.")
            value = _si_value(upstream_text, self._reference(problem, upstream_id))
            if value is None:
                return (f"Error carried forward could not be applied: your answer to "
                        f"'{upstream_id}' could not be read as a number.")
            overrides[given_key] = value
        return overrides

    def _carry_forward(self, item, text, submission, earlier, verdict, credit, feedback):
        """Judge ``text`` again against the reference recomputed from the student's own
        (wrong) upstream answers; keep the better credit."""
        problem = item.problem
        overrides = self._upstream_givens(item, submission, earlier)
        if isinstance(overrides, str):
            feedback.append(overrides)
            return verdict, credit
        if not overrides:
            return verdict, credit
        answered = sorted(overrides)
        overrides = {**dict(item.givens), **overrides}  # on the student's own variant
        solution, replaced = self._solve_with(problem, overrides, item.objective.id)
        if isinstance(solution, MechgradeError):
            feedback.append(f"Error carried forward could not be applied: with your "
                            f"{_listing(answered)} the problem cannot be solved "
                            f"({solution.message}).")
            return verdict, credit
        try:
            recomputed = solution.result(item.objective.id)
        except KeyError:
            return verdict, credit
        again = self.assess(text, recomputed)
        ecf_credit = float(again.credit) * self.policy.ecf.credit
        upstream_names = _listing(sorted(objective_id for objective_id in
                                         item.objective.depends_on))
        if again.verdict in ("correct", "partial") and ecf_credit > credit:
            instead = f" (used in place of {_listing(replaced)})" if replaced else ""
            # one sentence: what the answer was told against the reference no longer holds
            feedback[:] = [f"Error carried forward: this answer follows correctly from your "
                           f"answer to {upstream_names}{instead} and earns {ecf_credit:.0%} "
                           f"of the points."]
            return ("correct" if ecf_credit >= 1.0 else "partial"), ecf_credit
        feedback.append(f"Also checked with your own answer to {upstream_names} (error "
                        f"carried forward): it does not follow from it either.")
        return verdict, credit

    def _reference(self, problem: Problem, objective_id: str) -> ObjectiveResult:
        index = self.plan.problems.index(problem)
        return self.plan.solutions[index].result(objective_id)

    def _solve_with(self, problem: Problem, overrides: dict[str, float], objective_id: str):
        """Solve with the student's values; ``(solution or error, givens replaced)``.

        A value the spec derives from other givens over-determines the problem when simply
        added (x' given while y' fixes it). Then each given of the same derivative order is
        dropped in turn, in spec order, and the first consistent solution is used.
        """
        key = _ecf_key(problem, overrides, objective_id)
        if key in self._ecf_solutions:
            return self._ecf_solutions[key]
        problem, instead = _replaced_by_student(problem, overrides)
        outcome = self._attempt(problem, dict(overrides), objective_id), instead
        if isinstance(outcome[0], InconsistentError):
            orders = {_order(k) for k in overrides}
            for given in problem.givens:
                name = given.key.text
                if name in overrides or _order(name) not in orders:
                    continue
                attempt = self._attempt(problem, {**overrides, name: None}, objective_id)
                if not isinstance(attempt, MechgradeError):
                    outcome = attempt, (f"the given {name}",)
                    break
        self._ecf_solutions[key] = outcome
        return outcome

    def _attempt(self, problem: Problem, givens: dict, objective_id: str):
        try:
            if self._resolve is not None:
                return self._resolve(problem, givens)
            from ..solve import solve

            # Only the objective being re-checked: another one may not exist with these values.
            return solve(problem, givens=givens, objectives=(objective_id,))
        except MechgradeError as err:
            return err


def _replaced_by_student(problem: Problem, overrides: dict[str, float]
                        ) -> tuple[Problem, tuple[str, ...]]:
    """The problem to re-solve for ECF, and what the student's values replace in it. A
    work-energy problem's rates come from its energy balance, and a designed parameter from
    its design condition: a student's rate (or parameter) takes that balance's (or
    condition's) place, and the instant is solved from it as from any other given."""
    from ..spec.dynamics import WorkEnergy

    dynamics = problem.dynamics
    if dynamics is None:
        return problem, ()
    replaced: list[str] = []
    analysis, design = dynamics.analysis, dynamics.design
    if isinstance(analysis, WorkEnergy) and any(_order(k) == 1 for k in overrides):
        replaced.append("the energy balance")
        analysis = None
    if design is not None and design.find in overrides:
        replaced.append("the design condition")
        design = None
    if not replaced:
        return problem, ()
    return (replace(problem, dynamics=replace(dynamics, analysis=analysis, design=design)),
            tuple(replaced))


_CARRYING: list = []


def _ecf_key(problem: Problem, givens: dict, objective_id: str) -> tuple:
    return problem.id, objective_id, tuple(sorted(givens.items()))


def _solve_carried(request: tuple) -> tuple:
    """:meth:`_Judge._solve_with` in a forked worker (see :meth:`_Judge.prefetch_carried_forward`)."""
    return _CARRYING[0]._solve_with(*request)


def _order(key: str) -> int:
    """How many time derivatives a given key names (``x''`` -> 2; an expression -> -1)."""
    stripped = key.rstrip("'")
    return len(key) - len(stripped) if stripped.isidentifier() else -1


def given_key_of(objective: Objective) -> str | None:
    """The given key (``"theta'"``) an objective's value can be fed back to the solver as,
    or ``None`` when the objective is not a plain quantity (a coordinate, its rate, a
    parameter).

    >>> from mechgrade.spec.model import Expr
    >>> from mechgrade.expressions.syntax import parse
    >>> ob = lambda find, kind="scalar": Objective("o", "", Expr(find, parse(find, functions=["mag", "vel"])), kind, "m/s")
    >>> given_key_of(ob("x'")), given_key_of(ob("mag(vel(A, N))")), given_key_of(ob("x", "vector"))
    ("x'", None, None)
    """
    if objective.kind != ObjectiveKind.SCALAR:
        return None
    node = objective.find.node
    if isinstance(node, Name):
        return node.id
    if isinstance(node, Prime):
        return node.id + "'" * node.order
    return None


def _objective(problem: Problem, objective_id: str) -> Objective | None:
    try:
        return problem.objective(objective_id)
    except KeyError:
        return None


def _si_value(text: str, result: ObjectiveResult) -> float | None:
    """The student's scalar answer in SI, read as the objective's unit when none is written."""
    from ..units import to_si
    from .answers import NumberAnswer, read_answer

    try:
        answer = read_answer(text, result)
        if not isinstance(answer, NumberAnswer):
            return None
        unit = answer.unit if answer.unit is not None else result.unit
        value = to_si(answer.value, unit)
    except MechgradeError:
        return None
    return value if math.isfinite(value) else None


def compare_policy(policy: GradingPolicy):
    """The assignment's policy as the answer judge's :class:`~mechgrade.grade.compare.Policy`.

    >>> from mechgrade.grade.assignment import MissingUnitRule, SigFigRule
    >>> p = compare_policy(GradingPolicy(sig_figs=SigFigRule(3, 0.8),
    ...                                  missing_unit=MissingUnitRule("penalize", 0.5)))
    >>> p.written_sig_figs, round(p.written_sig_figs_deduction, 2), p.missing_unit, p.missing_unit_deduction
    (3, 0.2, 'assume', 0.5)
    """
    from .compare import Policy

    sig = policy.sig_figs
    missing = policy.missing_unit
    return Policy(
        rel=policy.rel, abs=policy.abs, sig_figs=policy.accuracy_sig_figs,
        separate_mistakes=policy.separate_mistakes,
        written_sig_figs=sig.figures if sig else None,
        written_sig_figs_strict=sig.strict if sig else False,
        written_sig_figs_deduction=1.0 - sig.credit if sig else 0.25,
        missing_unit="reject" if missing.action == "reject" else "assume",
        missing_unit_deduction=1.0 - missing.credit if missing.action == "penalize" else 0.0,
        partial_credit=policy.partial_credit.diagnoses if policy.partial_credit.enabled else ())


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
    if abs(value) < 1e-12:
        return "0"
    text = f"{value:.4g}"
    return text


def _round(value: float) -> float:
    rounded = round(float(value), POINTS_DIGITS)
    return 0.0 if rounded == 0 else rounded


def _listing(items) -> str:
    items = list(items)
    if len(items) > 8:
        return ", ".join(items[:8]) + ", ..."
    return ", ".join(items)
