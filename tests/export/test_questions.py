"""Questions out: the Canvas QTI package and the Moodle XML follow their formats, read back
by re-implementations of each LMS's importer (tests/lms/), and every variant's answer is the
solver's for the numbers the question shows; the tolerance never accepts what mechgrade
refuses."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner
from moodle_questions import answer_for, moodle_accepts, read_quiz
from qti_questions import canvas_accepts, check_qti, read_package

from mechgrade.cli import main
from mechgrade.export.questions import QUESTION_WRITERS, number_text
from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.questions import EssayItem, NumberItem, display_unit, question_bank
from mechgrade.grade.results import VariantGiven
from mechgrade.grade.run import graded_result, plan_assignment
from mechgrade.grade.variants import recorded_variant, solve_variant
from mechgrade.tolerance import within
from mechgrade.units import si_factor

ROOT = Path(__file__).resolve().parents[2]
HW1 = ROOT / "examples" / "hw1" / "assignment.yaml"
HW2 = ROOT / "examples" / "hw2_variants" / "assignment.yaml"
VARIANTS = 4


@pytest.fixture(scope="module")
def hw2():
    plan = plan_assignment(load_assignment(HW2))
    return plan, question_bank(plan, VARIANTS)


@pytest.fixture(scope="module")
def hw1():
    plan = plan_assignment(load_assignment(HW1))
    return plan, question_bank(plan, VARIANTS)


def solved(plan, item: NumberItem, givens: dict[str, float]) -> tuple[float, float]:
    """The solver's answer to ``item`` for the variables' values ``givens`` (by variable
    name), solved again from the numbers shown, and mechgrade's tolerance for it
    (``max(rel * scale, abs)``, the scale a vector's magnitude), in the unit asked for."""
    key, _, label = item.key.partition(" (")
    problem_id, objective_id = key.split(".")
    problem = next(p for p in plan.problems if p.id == problem_id)
    if item.variables:
        drawn = tuple(VariantGiven(problem.id, v.given, givens[v.name],
                                   next(d.unit for d in problem.variants.draws
                                        if d.key == v.given))
                      for v in item.variables)
        solution = solve_variant(problem, recorded_variant(problem, "x", "x", drawn))
    else:
        solution = plan.solutions[plan.problems.index(problem)]
    result = graded_result(solution, objective_id)
    factor = si_factor(result.unit) / si_factor(item.unit)
    if label:
        value = float(result.value["xyz".index(label[0])])
        scale = math.sqrt(sum(float(c) ** 2 for c in result.value))
    else:
        value = float(result.value)
        scale = abs(value)
    return value * factor, max(result.rel * scale, result.abs) * factor


@pytest.fixture(scope="module")
def canvas(hw2, tmp_path_factory):
    _plan, bank = hw2
    out = tmp_path_factory.mktemp("canvas") / "hw2.zip"
    QUESTION_WRITERS["canvas-qti"](bank, out)
    return read_package(out.read_bytes())


@pytest.fixture(scope="module")
def moodle(hw2, tmp_path_factory):
    _plan, bank = hw2
    out = tmp_path_factory.mktemp("moodle") / "hw2.xml"
    QUESTION_WRITERS["moodle-xml"](bank, out)
    return read_quiz(out.read_text(encoding="utf-8"))


def test_the_canvas_package_follows_qti_12_asi(canvas):
    root, questions = canvas
    check_qti(root)
    assert [q.question_type for q in questions] == ["calculated_question"] * 5


def test_every_canvas_variant_answer_is_the_solvers_for_its_numbers(hw2, canvas):
    plan, bank = hw2
    _, questions = canvas
    for item, question in zip(bank.items, questions):
        assert len(question.answers) == (VARIANTS if item.variables else 1)
        assert {v["name"] for v in question.variables} == \
            ({"L", "theta", "theta_d", "theta_dd"} if item.variables else set())
        for answer_set in question.answers:
            answer, _ = solved(plan, item, answer_set["variables"])
            assert math.isclose(answer_set["answer"], answer, rel_tol=1e-9, abs_tol=1e-12)
            for name, value in answer_set["variables"].items():
                assert f"[{name}]" in question.text
                spec = next(v for v in question.variables if v["name"] == name)
                assert spec["min"] <= value <= spec["max"]
                assert round(value, spec["scale"]) == value  # shown with its decimals


def test_canvas_never_accepts_what_mechgrade_refuses(hw2, canvas):
    plan, bank = hw2
    _, questions = canvas
    for item, question in zip(bank.items, questions):
        for answer_set in question.answers:
            a = answer_set["answer"]
            _, limit = solved(plan, item, answer_set["variables"])
            margin = float(str(question.answer_tolerance).rstrip("%")) * (
                abs(a) / 100 if str(question.answer_tolerance).endswith("%") else 1)
            assert margin <= limit * (1 + 1e-9)
            for inside in (a + 0.999 * margin, a - 0.999 * margin):
                assert canvas_accepts(question, answer_set, number_text(inside))
                assert within(inside, a, 0.0, limit)
            outside = a + 1.01 * limit
            assert not canvas_accepts(question, answer_set, number_text(outside))
            assert not within(outside, a, 0.0, limit)


def test_a_tolerance_mechgrade_scales_per_variant_is_tightened_and_said(hw2):
    _, bank = hw2
    by_key = {i.key: i for i in bank.items}
    speed = by_key["pendulum_variants.speed"]
    assert (speed.relative, speed.absolute, speed.notes) == (0.01, None, ())
    component = by_key["pendulum_variants.acc_N (x component in frame N)"]
    assert component.relative is None and component.notes[0].startswith(
        "one tolerance for every variant: the strictest of mechgrade's")
    assert [(o.key, o.reason) for o in bank.left_out] == [
        ("pendulum_variants.acc_N (z component in frame N)", "zero in every variant")]


def test_every_moodle_variant_answer_is_the_solvers_for_its_numbers(hw2, moodle):
    plan, bank = hw2
    numbers = [q for q in moodle if q.qtype == "calculated"]
    assert len(numbers) == 4  # the speed, the magnitude, two components
    calculated = [i for i in bank.items if i.variables]
    for item, question in zip(calculated, numbers):
        assert question.units[0] == (1.0, item.unit)
        for n in range(1, VARIANTS + 1):
            givens = {v.name: question.datasets[v.name][n] for v in item.variables}
            assert all("{" + v.name + "}" in question.text for v in item.variables)
            answer = answer_for(question, n)
            expected, limit = solved(plan, item, givens)
            assert math.isclose(answer, expected, rel_tol=1e-9)
            assert moodle_accepts(question, answer + 0.999 * min(limit, _width(question,
                                                                                answer)), n)
            assert not moodle_accepts(question, answer + 1.01 * limit, n)


def _width(question, answer: float) -> float:
    (entry,) = question.answers
    return abs(answer) * entry["tolerance"] if entry["tolerancetype"] == 1 else entry["tolerance"]


def test_a_problem_without_variants_is_a_numerical_question_and_a_symbolic_one_an_essay(hw1,
                                                                                       tmp_path):
    plan, bank = hw1
    kinds = {i.key: type(i).__name__ for i in bank.items}
    assert kinds["bowling_3_15_4_pendulum.acc_mag_symbolic"] == "EssayItem"
    assert kinds["bowling_3_15_4_pendulum.acc_mag"] == "NumberItem"
    QUESTION_WRITERS["moodle-xml"](bank, tmp_path / "hw1.xml")
    quiz = read_quiz((tmp_path / "hw1.xml").read_text(encoding="utf-8"))
    essay = next(q for q in quiz if q.qtype == "essay")
    assert "(mechgrade key: bowling_3_15_4_pendulum.acc_mag_symbolic)" in essay.text
    numerical = [q for q in quiz if q.qtype == "numerical"]
    items = [i for i in bank.items if isinstance(i, NumberItem)]
    assert len(numerical) == len(items)
    for item, question in zip(items, numerical):
        assert math.isclose(answer_for(question), solved(plan, item, {})[0], rel_tol=1e-9)
    QUESTION_WRITERS["canvas-qti"](bank, tmp_path / "hw1.zip")
    root, questions = read_package((tmp_path / "hw1.zip").read_bytes())
    check_qti(root)
    assert [q.question_type for q in questions].count("essay_question") == \
        sum(isinstance(i, EssayItem) for i in bank.items)


def test_answers_too_small_for_canvas_are_asked_in_a_smaller_unit(tmp_path):
    source = (ROOT / "examples/hw2_variants/pendulum_variants.yaml").read_text(encoding="utf-8")
    (tmp_path / "p.yaml").write_text(source.replace("unit: ft/s\n", "unit: km/s\n"),
                                     encoding="utf-8")
    (tmp_path / "hw.yaml").write_text(textwrap.dedent("""\
        id: hwkm
        title: Small numbers
        problems: [{path: p.yaml, objectives: [speed]}]
        variants: {seed: s, redraw: true}
        """), encoding="utf-8")
    plan = plan_assignment(load_assignment(tmp_path / "hw.yaml"))
    (item,) = question_bank(plan, 3).items
    assert item.unit == "m/s" and "Answer in m/s." in item.prompt
    assert item.notes[0] == ("asked in m/s, not km/s: some answers are too small to show in "
                             "km/s with 4 decimal places")
    for values, answer in zip(item.values, item.answers):
        givens = dict(zip((v.name for v in item.variables), values))
        assert math.isclose(answer, solved(plan, item, givens)[0], rel_tol=1e-9)
        assert answer >= 0.01


@pytest.mark.parametrize("unit, values, expected", [
    ("m/s", [0.004], ("mm/s", 1000.0)),
    ("ft", [0.001], ("in", 12.0)),
    ("N*m", [5e-6], ("uN*m", 1e6)),
    ("deg", [0.001], None),
])
def test_the_unit_asked_in_is_the_first_where_the_answers_show(unit, values, expected):
    found = display_unit(unit, values, [v * 0.01 for v in values])
    if expected is None:
        assert found is None
    else:
        assert found[0] == expected[0] and math.isclose(found[1], expected[1])


def test_export_questions_writes_the_file_and_says_what_it_wrote(tmp_path):
    out = tmp_path / "hw2.zip"
    result = CliRunner().invoke(main, ["export-questions", str(HW2), "--format", "canvas-qti",
                                       "--variants", "2", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert result.stdout == (f"wrote 5 numerical questions (2 variants each where the problem "
                             f"draws its givens) and 0 essay questions (graded by mechgrade "
                             f"from the quiz's responses) to {out}\n")
    assert "note: pendulum_variants.acc_N (z component in frame N): not exported (zero in " \
           "every variant)" in result.stderr
    assert out.read_bytes()[:2] == b"PK"


def test_export_questions_refuses_a_variant_count_out_of_range(tmp_path):
    result = CliRunner().invoke(main, ["export-questions", str(HW2), "--format", "moodle-xml",
                                       "--variants", "0"])
    assert result.exit_code == 2 and "Invalid value for '--variants'" in result.stderr
