"""Per-student variants: drawn the same in every process, spread over the class, verified
before handing out, and graded against each student's own reference."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import jsonschema
import pytest

from mechgrade.errors import SolveError
from mechgrade.expressions.syntax import to_text
from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.results import AssignmentInfo, GradeReport, StudentResult
from mechgrade.grade.run import expected_text, grade_submissions
from mechgrade.grade.variants import (OTHER_VARIANT, check_variants, draw_variant,
                                      solve_variant, statement, student_variant,
                                      variant_faults)
from mechgrade.resources import shipped_dir
from mechgrade.roster import read_roster
from mechgrade.solve import solve
from mechgrade.spec import load_problem, load_problem_text

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "variants"
HW2 = shipped_dir("examples") / "hw2_variants"
PENDULUM = HW2 / "pendulum_variants.yaml"
BASE = (ROOT / "tests" / "data" / "spec" / "base.yaml").read_text()


def base_with(section: str, objective_extra: str = "") -> str:
    text = BASE.replace("objectives:", section.strip("\n") + "\nobjectives:", 1)
    return text + objective_extra


# ---------------------------------------------------------------------------- drawing


def test_the_same_seed_and_student_give_the_same_givens_in_another_process():
    problem = load_problem(PENDULUM)
    here = [draw_variant(problem, "fall", sid).text() for sid in ("a", "b", "20001")]
    code = ("from mechgrade.spec import load_problem\n"
            "from mechgrade.grade.variants import draw_variant\n"
            f"p = load_problem({str(PENDULUM)!r})\n"
            "print('|'.join(draw_variant(p, 'fall', s).text() for s in ('a', 'b', '20001')))\n")
    # another hash seed: Python's hash() must play no part
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, env={"PYTHONHASHSEED": "12345", "PATH": ""})
    assert out.stdout.strip().split("|") == here


def test_another_seed_gives_other_givens():
    problem = load_problem(PENDULUM)
    students = [str(n) for n in range(20)]
    assert ([draw_variant(problem, "fall", s).drawn for s in students]
            != [draw_variant(problem, "spring", s).drawn for s in students])


def test_a_thousand_students_never_share_all_givens_when_the_ranges_allow_it():
    problem = load_problem_text(base_with("""
variants:
  draw:
    L: {from: 1 m, to: 9 m, sig_figs: 4}
    theta': {from: 1 rad/s, to: 9 rad/s, sig_figs: 4}
    theta: {integers: [10, 80]}
"""), "p.yaml")
    draws = [draw_variant(problem, "fall", f"s{n}") for n in range(1000)]
    assert len({tuple(g.value for g in d.drawn) for d in draws}) == 1000
    values = {g.name: [] for g in draws[0].drawn}
    for d in draws:
        for g in d.drawn:
            values[g.name].append(g.value)
    assert min(values["L"]) < 1.5 and max(values["L"]) > 8.5  # spread over the range
    assert set(values["theta"]) == set(map(float, range(10, 81)))


def test_every_draw_lies_in_its_range_on_its_grid():
    problem = load_problem(PENDULUM)
    for n in range(300):
        drawn = {g.name: g.value for g in draw_variant(problem, "x", str(n)).drawn}
        assert 1.5 <= drawn["L"] <= 4.0 and round(drawn["L"] * 10) == pytest.approx(drawn["L"] * 10)
        assert drawn["theta"] in (20, 30, 40, 50, 60)
        rate = drawn["theta'"]
        assert 3 <= rate <= 6 and float(f"{rate:.2g}") == rate
        assert drawn["theta''"] == int(drawn["theta''"]) and 4 <= drawn["theta''"] <= 15
        assert drawn["theta''"] > 0.2 * drawn["theta'"] ** 2  # require: holds


def test_a_draw_that_breaks_a_condition_is_replaced_by_the_next_draw_index():
    problem = load_problem(PENDULUM)
    indices = [draw_variant(problem, "x", str(n)).index for n in range(100)]
    assert max(indices) > 0
    late = next(str(n) for n, i in enumerate(indices) if i > 0)
    first = draw_variant(problem, "x", late, start=0)
    assert draw_variant(problem, "x", late, start=first.index).index == first.index


UNSATISFIABLE = """
variants:
  draw:
    L: {from: 1 m, to: 2 m, step: 0.5 m}
  require: ["L > 5"]
"""


def test_an_unsatisfiable_condition_says_so():
    problem = load_problem_text(base_with(UNSATISFIABLE), "p.yaml")
    with pytest.raises(SolveError, match=r"no draw of problem 'base' meets its conditions "
                                          r"\(L > 5\) in 1000 tries"):
        draw_variant(problem, "s", "a")


def test_givens_written_as_expressions_follow_the_drawn_ones():
    text = base_with("variants:\n  draw:\n    L: {choices: [4 m]}\n").replace(
        "  theta'': 1 rad/s^2", "  theta'': theta'^2")
    problem = load_problem_text(text, "p.yaml")
    variant = draw_variant(problem, "s", "a")
    assert dict(variant.overrides) == {"L": 4.0}
    text = text.replace("choices: [4 m]", "choices: [4 rad/s]").replace("    L: {", "    theta': {")
    variant = draw_variant(load_problem_text(text, "p.yaml"), "s", "a")
    assert dict(variant.overrides) == {"theta'": 4.0, "theta''": 16.0}


def test_the_statement_shows_the_students_numbers():
    problem = load_problem(PENDULUM)
    variant = draw_variant(problem, "fall", "20001")
    text = statement(problem, variant)
    for given in variant.drawn:
        assert given.text in text
    assert "{" not in text


# ---------------------------------------------------------------------------- verification


def test_verification_refuses_a_planted_degenerate_range():
    problem = load_problem(DATA / "degenerate_range.yaml")
    refused = check_variants(problem, 12)  # 4 of these 12 draws are degenerate
    assert refused and all("theta = 90 deg" in r.givens for r in refused)
    assert all(any("degenerate configuration" in f for f in r.faults) for r in refused)
    fine = [n for n in range(1, 13) if str(n) not in {r.student for r in refused}]
    assert fine and all("theta = 30 deg" in draw_variant(problem, "check", str(n)).text()
                        for n in fine)


def test_verification_refuses_a_mistake_indistinguishable_from_the_answer():
    mistake = ("    mistakes:\n      - {find: \"L*theta' + L*theta''^2/theta'^3\", "
               "message: a made-up term}\n")
    problem = load_problem_text(base_with(
        "variants:\n  draw:\n    theta'': {choices: [1 rad/s^2, 0.5 rad/s^2]}\n", mistake),
        "p.yaml")
    refused = check_variants(problem, 30)
    assert refused
    for r in refused:
        assert r.givens == "theta'' = 0.5 rad/s^2"
        assert r.faults == ("objective 'speed': the mistake 'a made-up term' gives "
                            "the right answer within the tolerance",)


def test_verification_refuses_a_generated_mistake_indistinguishable_from_the_answer():
    # with a small theta'', dropping the tangential acceleration changes |a| by < 1 %
    acc = ("  - {id: acc, prompt: Acceleration of the tip., find: \"mag(acc(P, N))\", "
           "kind: scalar, unit: m/s^2}\n")
    problem = load_problem_text(base_with(
        "variants:\n  draw:\n    theta'': {choices: [20 rad/s^2, 0.5 rad/s^2]}\n", acc),
        "p.yaml")
    refused = check_variants(problem, 30)
    assert refused and len(refused) < 30
    for r in refused:
        assert r.givens == "theta'' = 0.5 rad/s^2"
        # the normal acceleration for the whole, and the given theta'' taken as zero, are the
        # same value: every family is said
        assert r.faults == tuple(
            f"objective 'acc': the generated mistake {code} gives 18 m/s^2, within the "
            "tolerance (1 %) of the answer 18.03 m/s^2"
            for code in ("drop_tangential", "acc_n_for_acc", "given_acceleration_zero"))


def test_verification_refuses_an_answer_outside_its_bounds():
    problem = load_problem_text(base_with("""
variants:
  draw:
    L: {choices: [1 m, 5 m]}
  bounds:
    speed: {max: 10 m/s}
"""), "p.yaml")
    refused = check_variants(problem, 20)
    assert refused and {r.givens for r in refused} == {"L = 5 m"}
    assert refused[0].faults == ("speed = 15 m/s is outside its bounds (at most 10 m/s)",)


def test_verification_refuses_a_given_outside_its_bounds():
    problem = load_problem_text(base_with("""
variants:
  draw:
    theta: {choices: [10 deg, 80 deg]}
  bounds:
    theta: {max: 45 deg}
"""), "p.yaml")
    assert {r.givens for r in check_variants(problem, 20)} == {"theta = 80 deg"}


@pytest.mark.slow
def test_redraw_takes_the_next_verified_draw_deterministically():
    problem = load_problem(DATA / "degenerate_range.yaml")
    refused = check_variants(problem, 20)
    student = refused[0].student
    assert variant_faults(problem, draw_variant(problem, "check", student))
    variant, solution = student_variant(problem, "check", student, redraw=True)
    assert variant.index > 0 and not variant_faults(problem, variant, solution)
    assert student_variant(problem, "check", student, redraw=True)[0] == variant
    assert student_variant(problem, "check", student, redraw=False)[0].index == 0


# ---------------------------------------------------------------------------- grading


def graded_hw2():
    assignment = load_assignment(HW2 / "assignment.yaml")
    return grade_submissions(assignment, HW2 / "submissions", read_roster(HW2 / "roster.csv"))


def test_each_student_is_graded_against_the_reference_solved_with_their_own_givens():
    assignment = load_assignment(HW2 / "assignment.yaml")
    problem = load_problem(PENDULUM)
    report = graded_hw2()
    for student in report.students:
        roster_id = dict(student.identity)["id"]
        variant, _ = student_variant(problem, "engr201-fall2026", roster_id, redraw=True)
        own = solve(problem, givens=dict(variant.overrides))
        assert student.variant.seed == "engr201-fall2026"
        assert tuple(g.text for g in student.variant.givens) == tuple(g.text for g in variant.drawn)
        assert own.result("acc_mag").value != solve(problem).result("acc_mag").value
        answered = {a.objective: a.expected for a in student.answers
                    if a.problem == "pendulum_variants" and a.verdict != "missing"}
        assert answered == {r.id: expected_text(r) for r in own.results if r.id in answered}
        # an objective left unanswered never shows its expected answer
        assert all(a.expected is None for a in student.answers if a.verdict == "missing")
    scores = {s.id: s.score for s in report.students}
    assert scores == {"ana_silva": 8.0, "ben_okafor": 2.0, "chen_li": 4.0, "dara_novak": 0.0}
    assert assignment.variants.redraw


def test_an_answer_with_a_neighbours_numbers_is_wrong_and_says_so():
    report = graded_hw2()
    ben = next(s for s in report.students if s.id == "ben_okafor")
    pendulum = [a for a in ben.answers if a.problem == "pendulum_variants"]
    assert {a.verdict for a in pendulum} == {"incorrect"}
    assert {a.diagnosis for a in pendulum} == {OTHER_VARIANT}
    assert all("fits another variant's givens, not yours (L = 3.4 ft" in a.feedback
               for a in pendulum)
    chen = next(s for s in report.students if s.id == "chen_li")
    assert OTHER_VARIANT not in {a.diagnosis for a in chen.answers}


def test_results_json_records_each_students_givens_and_seed_and_reads_back():
    report = graded_hw2()
    data = json.loads(json.dumps(report.to_json()))
    schema = json.loads((ROOT / "src" / "mechgrade" / "export" / "results.schema.json").read_text())
    jsonschema.validate(data, schema)
    ana = data["students"][0]
    assert ana["variant"]["seed"] == "engr201-fall2026"
    assert [g["name"] for g in ana["variant"]["givens"]] == ["L", "theta", "theta'", "theta''"]
    assert GradeReport.from_json(data) == report


def test_results_without_variants_have_no_variant_key():
    student = StudentResult("ana", "Ana", "missing", 0.0, 1.0)
    data = GradeReport(AssignmentInfo("hw", "Hw"), (), (student,)).to_json()
    assert "variant" not in data["students"][0]
    assert GradeReport.from_json(data).students[0].variant is None


def test_error_carried_forward_uses_the_students_own_variant():
    assignment = load_assignment(DATA / "ecf" / "assignment.yaml")
    report = grade_submissions(assignment, DATA / "ecf" / "submissions")
    student = report.students[0]
    assert [g.text for g in student.variant.givens] == ["9 m", "3 rad/s"]
    omega, speed = student.answers
    assert omega.verdict == "incorrect"
    assert speed.verdict == "correct" and "Error carried forward" in speed.feedback


def test_solve_variant_is_the_problem_solved_with_the_variants_givens():
    problem = load_problem(PENDULUM)
    variant = draw_variant(problem, "fall", "20001")
    assert solve_variant(problem, variant) == solve(problem, givens=dict(variant.overrides))


def _index_and_result(answers: dict[str, str]):
    from types import SimpleNamespace

    from mechgrade.grade.results import AnswerResult
    from mechgrade.grade.variants import NeighbourIndex, Variant
    from mechgrade.solve.result import ObjectiveResult

    def refs(speed, acc):
        return [SimpleNamespace(key="p.speed", result=ObjectiveResult("speed", "scalar", "m/s", speed)),
                SimpleNamespace(key="p.acc", result=ObjectiveResult("acc", "vector", "m/s^2", acc,
                                                                    frame="N"))]

    index = NeighbourIndex({"me": refs(10.0, (1.0, 2.0, 0.0)), "ana": refs(20.0, (3.0, 4.0, 0.0)),
                            "ben": refs(30.0, (5.0, 6.0, 0.0))})
    own = {o.key: o.result for o in refs(10.0, (1.0, 2.0, 0.0))}
    result = StudentResult("me", "", "graded", 0.0, 2.0, tuple(
        AnswerResult("p", key, text, "incorrect", 0.0, 1.0) for key, text in answers.items()))
    variant = Variant("p", "me", "s", 0, (), ())
    return index, own, result, variant


def test_answers_that_all_fit_one_neighbour_are_diagnosed():
    from mechgrade.grade.variants import mark_neighbours

    index, own, result, variant = _index_and_result({"speed": "20.1 m/s", "acc": "(3, 4) m/s^2"})
    marked = mark_neighbours(result, own, index, "me", [variant])
    assert [a.diagnosis for a in marked.answers] == [OTHER_VARIANT, OTHER_VARIANT]


def test_answers_fitting_different_neighbours_are_a_coincidence_not_a_diagnosis():
    from mechgrade.grade.variants import mark_neighbours

    index, own, result, variant = _index_and_result({"speed": "20 m/s", "acc": "(5, 6) m/s^2"})
    marked = mark_neighbours(result, own, index, "me", [variant])
    assert [a.diagnosis for a in marked.answers] == [None, None]
    index, own, result, variant = _index_and_result({"speed": "25 m/s"})
    assert mark_neighbours(result, own, index, "me", [variant]).answers[0].diagnosis is None


def test_a_draw_where_a_given_written_as_an_expression_is_undefined_is_drawn_again():
    text = base_with("variants:\n  draw:\n    L: {choices: [0.5 m, 4 m]}\n")
    text = text.replace("  L: m\n", "  L: m\n  a: m\n").replace(
        "  theta: 30 deg\n", "  theta: acos(a/L)\n  a: 1 m\n")
    problem = load_problem_text(text, "p.yaml")
    for n in range(10):
        variant = draw_variant(problem, "s", str(n))
        assert dict(variant.overrides)["L"] == 4.0
        assert dict(variant.overrides)["theta"] == pytest.approx(math.acos(0.25))
    stuck = load_problem_text(text.replace("choices: [0.5 m, 4 m]", "choices: [0.5 m]"),
                              "p.yaml")
    with pytest.raises(SolveError, match=r"meets its conditions \(givens written as "
                                          r"expressions\)"):
        draw_variant(stuck, "s", "a")


@pytest.mark.parametrize("section, message", [
    ("variants: {sed: 3}\n", "hw.yaml:4:12: variants.sed: expected only the fields seed, redraw, found 'sed'; did you mean 'seed'?"),
    ('variants: {seed: ""}\n', "hw.yaml:4:18: variants.seed: expected at least 1 character(s), found empty text"),
    ("variants: {seed: s, redraw: 1}\n", "hw.yaml:4:29: variants.redraw: expected true or false, found 1"),
])
def test_a_bad_variants_section_of_an_assignment_says_where_and_what(tmp_path, section, message):
    from mechgrade.errors import AssignmentError

    (tmp_path / "p.yaml").write_text("id: p\n")
    (tmp_path / "hw.yaml").write_text("id: hw\ntitle: T\nproblems: [p.yaml]\n" + section)
    with pytest.raises(AssignmentError) as info:
        load_assignment(tmp_path / "hw.yaml")
    assert message in str(info.value)


def test_the_seed_is_the_assignments_or_else_its_id(tmp_path):
    (tmp_path / "p.yaml").write_text("id: p\n")
    (tmp_path / "hw.yaml").write_text("id: hw\ntitle: T\nproblems: [p.yaml]\n")
    assert load_assignment(tmp_path / "hw.yaml").variant_seed == "hw"
    (tmp_path / "hw.yaml").write_text("id: hw\ntitle: T\nproblems: [p.yaml]\nvariants: {seed: 7}\n")
    assert load_assignment(tmp_path / "hw.yaml").variant_seed == "7"


def test_any_student_id_draws_a_variant_even_one_that_is_not_valid_utf8():
    problem = load_problem(PENDULUM)
    for sid in ("bad\udce9name", "名前", "", " 20001 ", "a" * 5000):
        assert draw_variant(problem, "fall", sid).drawn
    assert draw_variant(problem, "fall", "é").drawn == draw_variant(problem, "fall", "é").drawn


# ---------------------------------------------------------------------------- dynamics

DYNAMICS = ROOT / "tests" / "data" / "variants" / "dynamics"


def pin_pendulum_by_hand(m: float, L: float, theta: float, omega: float, g: float = 9.81):
    """A uniform rod pinned at its end (theta from the downward vertical), by moments about
    the pin and F = m a_G: its angular acceleration, the pin force (N.x, N.y) and that
    force's component along the rod toward the pin."""
    alpha = -3 * g * math.sin(theta) / (2 * L)
    # G at (L/2 sin, -L/2 cos): a_G = alpha k x r_G - omega^2 r_G
    a_g = (alpha * L / 2 * math.cos(theta) - omega ** 2 * L / 2 * math.sin(theta),
           alpha * L / 2 * math.sin(theta) + omega ** 2 * L / 2 * math.cos(theta))
    force = (m * a_g[0], m * a_g[1] + m * g)
    return alpha, force, -force[0] * math.sin(theta) + force[1] * math.cos(theta)


def answers_file(values) -> str:
    alpha, force, along = values
    return (f"pin_pendulum:\n  alpha: {alpha:.6g} rad/s^2\n"
            f"  pin_force: ({force[0]:.6g}, {force[1]:.6g}) N\n"
            f"  pin_force_along_rod: {along:.6g} N\n")


@pytest.mark.slow  # a slow end-to-end check (over 5 s)
def test_a_dynamics_problem_with_variants_is_checked_and_graded_per_student(tmp_path):
    problem = load_problem(DYNAMICS / "pin_pendulum.yaml")
    assert check_variants(problem, 30) == ()  # its kinetics checked for every draw
    book = {to_text(g.key.node): g.si for g in problem.givens}
    for student in ("101", "102"):
        (tmp_path / student).mkdir()
    ann, _ = student_variant(problem, "dynamics-test", "101", redraw=True)
    mine = {**book, **dict(ann.overrides)}  # (a drawn value equal to the book's is no override)
    (tmp_path / "101" / "answers.yaml").write_text(answers_file(pin_pendulum_by_hand(
        mine["m"], mine["L"], mine["theta"], mine["theta'"])))
    # Bo solves the problem with its own givens (the book's numbers), not his
    (tmp_path / "102" / "answers.yaml").write_text(answers_file(pin_pendulum_by_hand(
        book["m"], book["L"], book["theta"], book["theta'"])))
    report = grade_submissions(load_assignment(DYNAMICS / "assignment.yaml"), tmp_path,
                               read_roster(DYNAMICS / "roster.csv"))
    verdicts = {s.id: {a.objective: (a.verdict, a.diagnosis) for a in s.answers
                       if a.verdict != "missing"} for s in report.students}
    assert verdicts["101"] == {o: ("correct", None) for o in
                               ("alpha", "pin_force", "pin_force_along_rod")}
    assert verdicts["102"] == {o: ("incorrect", OTHER_VARIANT) for o in
                               ("alpha", "pin_force", "pin_force_along_rod")}
    assert mine != book


# ---------------------------------------------------------------------------- over processes


def _solved_class(students, jobs, monkeypatch):
    from types import SimpleNamespace

    from mechgrade.grade import variants

    monkeypatch.setattr(variants, "_SOLVED", {})
    assignment = load_assignment(HW2 / "assignment.yaml")
    variants.prepare_variants(SimpleNamespace(assignment=assignment,
                                              problems=(load_problem(PENDULUM),)),
                              students, jobs)
    return {key[2]: (variant, solution.results)
            for key, (variant, solution) in variants._SOLVED.items()}


@pytest.mark.slow  # two class solves, a process forked
def test_a_class_solved_over_two_processes_is_solved_as_in_one(monkeypatch):
    students = [f"s{n}" for n in range(9)]
    apart = _solved_class(students, 2, monkeypatch)
    assert sorted(apart) == sorted(students)
    assert apart == _solved_class(students, 1, monkeypatch)


def test_students_drawing_equal_numbers_are_solved_in_one_group():
    from mechgrade.grade.variants import _groups

    problem = load_problem(PENDULUM)
    students = [str(n) for n in range(60)]
    groups = _groups(problem, "fall", students, 2)
    assert sorted(s for g in groups for s in g) == sorted(students)  # each once
    drawn = [{draw_variant(problem, "fall", s).overrides for s in g} for g in groups]
    assert len(groups) == 2 and not drawn[0] & drawn[1]
    # the grid repeats numbers among 60 students: some group holds two equal draws
    assert sum(len(g) for g in groups) > sum(len(d) for d in drawn)


def test_students_whose_numbers_cannot_be_drawn_are_each_kept_in_a_group():
    from mechgrade.grade.variants import _groups

    problem = load_problem_text(base_with(UNSATISFIABLE), "p.yaml")
    groups = _groups(problem, "s", ["a", "b", "c"], 2)
    assert groups == [["a", "b"], ["c"]]  # none lost: student_variants reports each
