"""Each student's variant of a problem: drawn, verified and solved.

A student's numbers depend only on the assignment's seed, the problem id, the student id and
the draw index: every value comes from SHA-256 of those (never Python's ``hash()``, which
changes between processes), so a student's numbers never change between runs. A draw that
breaks a ``require:`` condition is replaced by the next draw index; with ``redraw: true`` in
the assignment, so is one that fails verification (:func:`variant_faults`).

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("examples") / "hw2_variants" / "pendulum_variants.yaml")
>>> a = draw_variant(problem, "fall", "10001")
>>> a == draw_variant(problem, "fall", "10001"), a == draw_variant(problem, "fall", "10002")
(True, False)
>>> variant_faults(problem, a)
()
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, replace
from functools import partial

import numpy as np

from ..errors import MechgradeError, SolveError, SpecError
from ..expressions.syntax import to_text
from ..solve import Solution, solve
from ..solve.mutants import inside_tolerance
from ..solve.plan import kinematics_plan
from ..solve.result import ObjectiveResult
from ..spec.model import ObjectiveKind, Problem
from ..spec.solving import resolve_given_values
from ..spec.variants import PLACEHOLDER, Choices, Draw, Integers, SteppedRange
from ..tolerance import within
from ..units import from_si, judged_in, to_si
from .results import StudentResult, StudentVariant, VariantGiven, Verdict, unit_text
from .sheets import Question, Sheet, SheetProblem

DRAW_LIMIT = 1000
"""Draw indices tried for one student before the ``require:`` conditions are declared
unsatisfiable."""
OTHER_VARIANT = "fits another variant's givens"
OWN_GIVENS = "(the problem's own givens)"
"""Where :class:`NeighbourIndex` keeps the references at the problem's own givens, beside the
students' (a student with this very id would take its place: that student's answers would
then not be compared with the problem's own numbers, and nothing else changes)."""
"""The diagnosis of an answer computed with another student's numbers."""
REDRAW_LIMIT = 50
"""Draw indices tried for one student before no verified variant is declared found."""


@dataclass(frozen=True)
class Variant:
    """One student's givens for one problem (every given, drawn or derived, in SI)."""

    problem: str
    student: str
    seed: str
    index: int
    drawn: tuple[VariantGiven, ...]
    overrides: tuple[tuple[str, float], ...]

    def text(self) -> str:
        """The drawn givens as ``L = 1.2 m, theta' = 3 rad/s``."""
        return ", ".join(f"{g.name} = {g.text}" for g in self.drawn)


def _number(seed: str, problem: str, student: str, index: int, key: str) -> int:
    """A 256-bit number fixed by its arguments, the same in every process and version."""
    text = "\x1f".join((seed, problem, student, str(index), key))
    # a folder name that is not valid UTF-8 reaches here with surrogates; it still has bytes
    data = text.encode("utf-8", "surrogatepass")
    return int.from_bytes(hashlib.sha256(data).digest(), "big")


def _value(draw: Draw, n: int) -> float:
    """The value ``n`` (a 256-bit number) picks from ``draw``, in the given's unit."""
    if isinstance(draw, Choices):
        return draw.values[n % len(draw.values)]
    if isinstance(draw, Integers):
        return float(draw.low + n % (draw.high - draw.low + 1))
    if isinstance(draw, SteppedRange):
        count = math.floor((draw.high - draw.low) / draw.step + 1e-9) + 1
        return round(draw.low + (n % count) * draw.step, 12)
    # a RoundedRange: the top 64 bits as a fraction of the range, then rounded
    u = (n >> 192) / 2.0 ** 64
    value = float(f"{draw.low + u * (draw.high - draw.low):.{draw.sig_figs - 1}e}")
    return min(max(value, draw.low), draw.high)


def draw_variant(problem: Problem, seed: str, student: str, start: int = 0) -> Variant:
    """The first draw from index ``start`` on that meets the problem's ``require:``
    conditions; raises :class:`SolveError` when none of :data:`DRAW_LIMIT` does."""
    variants = problem.variants
    if variants is None:
        return Variant(problem.id, student, seed, 0, (), ())
    for index in range(start, start + DRAW_LIMIT):
        drawn = {d.key: (_value(d, _number(seed, problem.id, student, index, d.key)), d.unit)
                 for d in variants.draws}
        variant = _variant(problem, seed, student, index, drawn)
        if variant is not None:
            return variant
    conditions = "; ".join(r.text for r in variants.requires) or "givens written as expressions"
    raise SolveError(f"no draw of problem '{problem.id}' meets its conditions ({conditions}) "
                     f"in {DRAW_LIMIT} tries; widen the ranges", where=variants.where)


def _variant(problem: Problem, seed: str, student: str, index: int,
             drawn: dict[str, tuple[float, str]]) -> Variant | None:
    """The variant of the ``drawn`` values (key -> value, unit), its derived givens worked
    out; ``None`` when it breaks a ``require:`` condition or a derived given is undefined."""
    variants = problem.variants
    assert variants is not None  # only problems with a variants: section are drawn
    givens = []
    for g in problem.givens:
        key = to_text(g.key.node)
        if key in drawn:
            value, unit = drawn[key]
            givens.append(replace(g, value=value, si=to_si(value, unit), value_expr=None))
        elif g.value_expr is not None:
            givens.append(replace(g, si=math.nan))
        else:
            givens.append(g)
    try:
        resolved = resolve_given_values(tuple(givens), problem.coordinates,
                                        problem.parameters)
    except SpecError:
        return None  # a given written as an expression is undefined here (sqrt of < 0)
    values = {to_text(g.key.node): g.si for g in resolved}
    if not all(r.holds(values) for r in variants.requires):
        return None
    spec = {to_text(g.key.node): g.si for g in problem.givens}
    overrides = tuple((k, v) for k, v in values.items() if v != spec[k])
    return Variant(problem.id, student, seed, index,
                   tuple(VariantGiven(problem.id, d.key, drawn[d.key][0], d.unit, index)
                         for d in variants.draws), overrides)


def recorded_variant(problem: Problem, seed: str, student: str,
                     drawn: tuple[VariantGiven, ...]) -> Variant:
    """The variant whose drawn givens a result recorded (``StudentResult.variant``).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("examples") / "hw2_variants" / "pendulum_variants.yaml")
    >>> a = draw_variant(p, "fall", "10001")
    >>> recorded_variant(p, "fall", "10001", a.drawn) == a
    True
    """
    index = drawn[0].draw if drawn else 0
    variant = _variant(problem, seed, student, index,
                       {g.name: (g.value, g.unit) for g in drawn if g.problem == problem.id})
    if variant is None:
        raise SolveError(f"the recorded givens of problem '{problem.id}' for student "
                         f"'{student}' do not make a variant of it")
    return variant


def solve_variant(problem: Problem, variant: Variant) -> Solution:
    """The problem solved with the variant's givens (a warm re-solve of the cached plan)."""
    return solve(problem, givens=dict(variant.overrides))


def variant_faults(problem: Problem, variant: Variant,
                   solution: Solution | None = None) -> tuple[str, ...]:
    """Why a variant should not be handed out (empty when it is fine): it does not solve,
    lands on a degenerate configuration, leaves a declared bound, or a declared or generated
    mistake (:func:`mechgrade.solve.mutants.inside_tolerance`) gives the right answer within
    the tolerance."""
    if solution is None:
        try:
            solution = solve_variant(problem, variant)
        except MechgradeError as err:
            return (f"does not solve: {err.message}",)
    faults = [f"objective '{f.id}' cannot be solved: {f.error.message}"
              for f in solution.failures]
    structural = _structural_warnings(problem)  # the same for every variant
    faults += [w.message for w in solution.warnings if w not in structural]
    results = {r.id: r for r in solution.results}
    state = {s.name: s for s in solution.state}
    for bound in problem.variants.bounds if problem.variants else ():
        value = _bounded_value(bound.name, bound.unit, results, state)
        if value is not None and not bound.contains(value):
            unit = unit_text(bound.unit)
            ends = [f"at least {bound.low:g} {unit}" if bound.low is not None else "",
                    f"at most {bound.high:g} {unit}" if bound.high is not None else ""]
            faults.append(f"{bound.name} = {value:.4g} {unit} is outside its bounds "
                          f"({', '.join(e for e in ends if e)})")
    for result in solution.results:
        for mistake in result.mistakes:
            if _indistinguishable(mistake.value, result):
                faults.append(f"objective '{result.id}': the mistake '{mistake.message}' gives "
                              f"the right answer within the tolerance")
        for generated in inside_tolerance(result):
            unit = unit_text(result.unit)
            faults.append(f"objective '{result.id}': the generated mistake {generated.code} "
                          f"gives {_shown(generated.value)} {unit}, within the tolerance "
                          f"({result.rel * 100:g} %) of the answer {_shown(result.value)} {unit}")
    return tuple(faults)


def _structural_warnings(problem: Problem) -> tuple:
    """The warnings of the problem's kinematic plan: those of its model, not of an instant
    (a dynamics problem's objectives are read in the dynamics language: its plan is of its
    kinematics alone, as its solver builds it)."""
    if problem.dynamics is not None:
        from ..solve.dynamics import kinematic_problem
        problem = kinematic_problem(problem)
    return tuple(kinematics_plan(problem).k.warnings)


def _shown(value) -> str:
    if isinstance(value, tuple):
        return "(" + ", ".join(f"{v:.4g}" for v in value) + ")"
    return f"{value:.4g}"


def _bounded_value(name: str, unit: str, results: dict, state: dict) -> float | None:
    if name in results:
        result = results[name]
        if result.value is None:
            return None
        value = (float(np.linalg.norm(result.value)) if isinstance(result.value, tuple)
                 else result.value)
        return from_si(to_si(value, result.unit), unit) if unit else value
    if name in state:
        return from_si(state[name].si, unit) if unit else state[name].si
    return None


def _indistinguishable(value, result: ObjectiveResult) -> bool:
    if value is None or result.value is None:
        return False
    scale = (float(np.linalg.norm(result.value)) if isinstance(result.value, tuple) else None)
    return within(value, result.value, result.rel, result.abs, scale)


def student_variant(problem: Problem, seed: str, student: str,
                    redraw: bool) -> tuple[Variant, Solution]:
    """The student's variant and its solution; with ``redraw``, the first draw that passes
    :func:`variant_faults` (after at most :data:`REDRAW_LIMIT` refusals, raises)."""
    key = (problem, seed, student, redraw)
    found = _SOLVED.get(key)
    if found is None:
        found = student_variants(problem, seed, [student], redraw)[student]
    return found


_SOLVED: dict = {}
_SOLVED_LIMIT = 100_000


def student_variants(problem: Problem, seed: str, students, redraw: bool
                     ) -> dict[str, tuple[Variant, Solution]]:
    """:func:`student_variant` for many students at once: their variants are solved together
    (:func:`mechgrade.solve.batch.solve_variants`), and remembered for
    :func:`student_variant` (call this once with the class, then per student as before).

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("examples") / "hw2_variants" / "pendulum_variants.yaml")
    >>> both = student_variants(p, "fall", ["10001", "10002"], redraw=True)
    >>> both["10001"] == student_variant(p, "fall", "10001", redraw=True)
    True
    """
    from ..solve.batch import solve_variants

    out: dict[str, tuple[Variant, Solution]] = {}
    pending = {student: draw_variant(problem, seed, student) for student in students}
    for _ in range(REDRAW_LIMIT if redraw else 1):
        if not pending:
            break
        names = list(pending)
        solutions = solve_variants(problem, [dict(pending[s].overrides) for s in names])
        refused = {}
        for student, solved in zip(names, solutions):
            variant = pending[student]
            if isinstance(solved, MechgradeError) and not redraw:
                raise solved
            # Without redraw a failed solve has raised: the solution is there.
            if isinstance(solved, Solution) and (not redraw
                                                 or not variant_faults(problem, variant, solved)):
                out[student] = (variant, solved)
            else:
                refused[student] = draw_variant(problem, seed, student, variant.index + 1)
        pending = refused
    if pending:
        raise SolveError(f"no verified variant of problem '{problem.id}' for student "
                         f"'{next(iter(pending))}' in {REDRAW_LIMIT} draws; run mechgrade check "
                         f"--variants on the problem")
    _remember(problem, seed, redraw, out)
    return out


def _remember(problem: Problem, seed: str, redraw: bool,
              found: dict[str, tuple[Variant, Solution]]) -> None:
    """Keep the solved variants for :func:`student_variant`."""
    if len(_SOLVED) + len(found) > _SOLVED_LIMIT:
        _SOLVED.clear()
    _SOLVED.update({(problem, seed, student, redraw): pair for student, pair in found.items()})


def prepare_variants(plan, students, jobs: int = 1) -> None:
    """Solve every student's variant of every problem of ``plan`` (the assignment's
    :class:`~mechgrade.grade.run.Plan`) together, so that :func:`student_variant` finds each
    solved; ``students`` are the ids variants are drawn for. A problem whose variants cannot
    all be drawn or solved is left to :func:`student_variant`, which reports it per student.

    With ``jobs`` > 1 the class is parted into ``jobs`` groups solved in forked processes,
    after a first student solved here has made what they share (the derivation, the solver's
    template): a variant is solved column by column, so its solution does not depend on the
    others solved with it, and students drawing equal numbers are in the same group."""
    assignment = plan.assignment
    students = list(dict.fromkeys(students))
    seed, redraw = assignment.variant_seed, assignment.variants.redraw
    for problem in plan.problems:
        if problem.variants is None:
            continue
        if jobs <= 1 or len(students) <= 2:
            _solved_or_left(problem, seed, redraw, students)
            continue
        from ..parallel import fork_map

        first = _solved_or_left(problem, seed, redraw, students[:1])
        if not first:  # the first student's variant fails: so will the whole class's
            _solved_or_left(problem, seed, redraw, students)
            continue
        for found in fork_map(partial(_solved_or_left, problem, seed, redraw),
                              _groups(problem, seed, students[1:], jobs), jobs=jobs):
            _remember(problem, seed, redraw, found)


def _solved_or_left(problem: Problem, seed: str, redraw: bool,
                    students: list[str]) -> dict[str, tuple[Variant, Solution]]:
    """:func:`student_variants`, or nothing when they cannot all be drawn or solved (each
    student is then reported by :func:`student_variant`)."""
    try:
        return student_variants(problem, seed, students, redraw)
    except MechgradeError:
        return {}


def _groups(problem: Problem, seed: str, students: list[str], count: int) -> list[list[str]]:
    """``students`` in ``count`` groups of about equal size, those who draw equal numbers in
    one group (solved once: their solution is one)."""
    drawn: dict[tuple, list[str]] = {}
    for student in students:
        key: tuple
        try:
            key = tuple(sorted(draw_variant(problem, seed, student).overrides))
        except MechgradeError:
            key = ("", student)  # reported by student_variants, as in one group
        drawn.setdefault(key, []).append(student)
    groups: list[list[str]] = [[] for _ in range(count)]
    size = -(-len(students) // count)
    at = 0
    for same in drawn.values():
        while len(groups[at]) >= size and at < count - 1:
            at += 1
        groups[at] += same
    return [g for g in groups if g]


def statement(problem: Problem, variant: Variant | None = None) -> str:
    """The statement with each ``{given}`` replaced by the variant's value and unit.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("examples") / "hw2_variants" / "pendulum_variants.yaml")
    >>> statement(p).split(".")[0]
    'A rigid pendulum of length 2 ft turns about a fixed pin O'
    """
    values = {to_text(g.key.node): VariantGiven(problem.id, to_text(g.key.node), g.value,
                                                g.unit).text for g in problem.givens}
    values.update({g.name: g.text for g in (variant.drawn if variant else ())})

    def fill(match) -> str:
        return values[match.group(1).strip().replace(" ", "")]

    if problem.variants is None:
        return problem.statement
    return PLACEHOLDER.sub(fill, problem.statement)


# ---------------------------------------------------------------------------- check


@dataclass(frozen=True)
class RefusedDraw:
    """A draw that verification refused: who it was drawn for, its givens, and why."""

    student: str
    givens: str
    faults: tuple[str, ...]


def check_variants(problem: Problem, count: int = 200, seed: str = "check"
                   ) -> tuple[RefusedDraw, ...]:
    """Draw ``count`` variants (for students ``"1"``, ``"2"``...) and return those that fail
    :func:`variant_faults`."""
    from ..solve.batch import solve_variants

    variants = []
    for n in range(1, count + 1):
        try:
            variants.append(draw_variant(problem, seed, str(n)))
        except MechgradeError as err:
            return (RefusedDraw(str(n), "", (err.message,)),)
    solutions = solve_variants(problem, [dict(v.overrides) for v in variants])
    refused = []
    for variant, solution in zip(variants, solutions):
        faults = ((f"does not solve: {solution.message}",)
                  if isinstance(solution, MechgradeError)
                  else variant_faults(problem, variant, solution))
        if faults:
            refused.append(RefusedDraw(variant.student, variant.text(), faults))
    return tuple(refused)


def variant_lines(path, count: int, shown: int = 10) -> list[str]:
    """``mechgrade check``'s lines about the variants of the problem in ``path``: one per
    refused draw (at most ``shown``) and a count; none without a ``variants:`` section.

    >>> from mechgrade.resources import shipped_dir
    >>> variant_lines(shipped_dir("examples") / "hw2_variants" / "pendulum_variants.yaml", 20)
    []
    """
    from ..spec import load_problem

    problem = load_problem(path)
    if problem.variants is None or count == 0:
        return []
    refused = check_variants(problem, count)
    lines = [f"FAIL variant for student {r.student} ({r.givens}): {'; '.join(r.faults)}"
             for r in refused[:shown]]
    if refused:
        lines.append(f"{len(refused)} of {count} variants refused (set redraw: true in the "
                     f"assignment to draw again, or narrow the ranges / add require:)")
    return lines


# ---------------------------------------------------------------------------- handouts


def handout_sheets(plan, students) -> tuple[Sheet, ...]:
    """Every student's problem sheet: ``plan`` is the assignment's
    :class:`~mechgrade.grade.run.Plan`, ``students`` ``(id, name)`` pairs (the id decides
    the variant, as in grading)."""
    from ..solve.picture import drawable, geometry, picture_svg, scene

    def drawn(problem, solution) -> str:
        picture = scene(problem, solution)
        return picture_svg(geometry(picture), inline=True) if drawable(picture) else ""

    assignment = plan.assignment
    seed = assignment.variant_seed
    students = list(students)
    prepare_variants(plan, [student_id for student_id, _ in students])
    # a problem without variants looks the same on every sheet: drawn once
    pictures = {p.id: drawn(p, s) for p, s in zip(plan.problems, plan.solutions)
                if p.variants is None}
    sheets = []
    for student_id, name in students:
        problems = []
        for problem in plan.problems:
            variant = None
            picture = pictures.get(problem.id)
            if problem.variants is not None:
                variant, solution = student_variant(problem, seed, student_id,
                                                    assignment.variants.redraw)
                picture = drawn(problem, solution)
            questions = tuple(Question(o.key, o.objective.prompt, unit_text(o.objective.unit),
                                       o.objective.kind)
                              for o in plan.objectives if o.problem.id == problem.id)
            problems.append(SheetProblem(problem.id, problem.title,
                                         statement(problem, variant),
                                         variant.drawn if variant else (), questions,
                                         picture or ""))
        sheets.append(Sheet(assignment.id, assignment.title, student_id, name, seed,
                            tuple(problems)))
    return tuple(sheets)


# ---------------------------------------------------------------------------- grading


def student_record(seed: str, variants: list[Variant]) -> StudentVariant | None:
    """What results.json keeps of a student's variants (``None`` without variants)."""
    givens = tuple(g for v in variants for g in v.drawn)
    return StudentVariant(seed, givens) if variants else None


class NeighbourIndex:
    """Every student's reference values, per objective, in SI: which students' references a
    value fits (within each objective's tolerance), found for the whole class at once."""

    def __init__(self, objectives_by_student: dict):
        """``objectives_by_student``: student id -> that student's planned objectives (each
        with ``key`` and ``result``)."""
        table: dict[str, tuple[list[str], list]] = {}
        for student, objectives in objectives_by_student.items():
            for item in objectives:
                result = item.result
                if result.value is None:
                    continue
                ids, rows = table.setdefault(item.key, ([], []))
                ids.append(student)
                rows.append(np.atleast_1d(np.asarray(
                    [to_si(v, result.unit) for v in np.atleast_1d(result.value)], dtype=float)))
        self._ids = {key: np.asarray(ids) for key, (ids, _) in table.items()}
        self._values = {key: np.vstack(rows) for key, (_, rows) in table.items()}
        self._tolerance: dict[str, tuple[float, float]] = {}
        for objectives in objectives_by_student.values():
            for item in objectives:
                result = item.result
                absolute = (abs(to_si(result.abs, result.unit) - to_si(0.0, result.unit))
                            if result.abs else 0.0)
                self._tolerance.setdefault(item.key, (result.rel, absolute))

    def fitting(self, key: str, value, student: str) -> set[str]:
        """The students other than ``student`` whose reference for objective ``key``
        ``value`` (SI; a float or components) fits."""
        if key not in self._values:
            return set()
        values = self._values[key]
        value = np.atleast_1d(np.asarray(value, dtype=float))
        if value.shape[0] != values.shape[1]:
            return set()
        rel, absolute = self._tolerance[key]
        scale = np.linalg.norm(values, axis=1) if values.shape[1] > 1 else np.abs(values[:, 0])
        # a loose vectorised filter over the class, then the one tolerance rule on the few left
        with np.errstate(all="ignore"):
            near = np.max(np.abs(values - value), axis=1) <= 2 * np.maximum(rel * scale,
                                                                            absolute) + 1e-300
        return {str(self._ids[key][i]) for i in np.flatnonzero(near & (self._ids[key] != student))
                if within(value, values[i], rel, absolute,
                          scale[i] if values.shape[1] > 1 else None)}


def mark_neighbours(result: StudentResult, own: dict[str, ObjectiveResult],
                    neighbours: NeighbourIndex, student: str, variants: list[Variant]
                    ) -> StudentResult:
    """``result`` with the incorrect number and vector answers to a problem diagnosed as
    answered with another variant's givens when they all fit one other student's references
    (one coincidence in a large class is not enough when there are several). ``own`` holds
    this student's references by objective key; ``student`` is their id in ``neighbours``."""
    if not variants:
        return result
    mine = "; ".join(v.text() for v in variants)
    drawn = {v.problem for v in variants}
    shared: dict[str, set[str]] = {}  # problem -> students whose references every answer fits
    flagged: set[int] = set()
    for i, answer in enumerate(result.answers):
        key = f"{answer.problem}.{answer.objective}"
        reference = own.get(key)
        if (answer.verdict != Verdict.INCORRECT or not answer.answer or reference is None
                or answer.problem not in drawn):
            continue
        value = answer_si(answer.answer, reference)
        if value is None:
            continue
        others = neighbours.fitting(key, value, student)
        shared[answer.problem] = (others if answer.problem not in shared
                                  else shared[answer.problem] & others)
        flagged.add(i)
    note = (f"This answer fits another variant's givens, not yours ({mine}): solve with your "
            f"own numbers.")
    answers = tuple(
        replace(a, diagnosis=OTHER_VARIANT, feedback=" ".join(x for x in (a.feedback, note) if x))
        if i in flagged and shared.get(a.problem) else a
        for i, a in enumerate(result.answers))
    return replace(result, answers=answers)


def answer_si(text: str, reference: ObjectiveResult):
    """A number or vector answer in SI (a float or a tuple), read in the reference's unit
    when none is written; ``None`` when it is neither, or a vector in another frame.

    >>> ref = ObjectiveResult("v", "vector", "ft/s", (1.0, 0.0, 0.0), frame="N")
    >>> [round(x, 4) for x in answer_si("(1, 2) ft/s", ref)]
    [0.3048, 0.6096, 0.0]
    """
    from .answers import NumberAnswer, VectorAnswer, read_answer

    try:
        answer = read_answer(text, reference)
        if isinstance(answer, NumberAnswer) and reference.kind == ObjectiveKind.SCALAR:
            return to_si(answer.value, judged_in(answer.unit, reference.unit))
        if isinstance(answer, VectorAnswer) and reference.kind == ObjectiveKind.VECTOR \
                and answer.frame in (None, reference.frame):
            unit = judged_in(answer.unit, reference.unit)
            return tuple(to_si(c, unit) for c in answer.components)
    except MechgradeError:
        return None
    return None
