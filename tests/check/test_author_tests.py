"""Author tests are tight: expect: is compared to the digits written; declared mistakes are
compared with the answer."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.check import check_problem, expect_outcome, written_tolerance
from mechgrade.solve.result import ObjectiveResult

BASE = (Path(__file__).resolve().parents[1] / "data" / "spec" / "base.yaml").read_text()


@pytest.mark.parametrize("text, tolerance", [
    ("98.51", 0.005), ("7", 0.5), ("-3.0", 0.05), ("0.0025", 0.00005), ("1.5e3", 50.0),
    ("2.0E-3", 0.00005), ("5.00368", 5.00368e-5), ("-89.8705", 89.8705e-5), ("12345", 0.5),
    ("41.036426", 41.036426e-5),
])
def test_written_tolerance_is_half_the_last_digit_and_at_least_1e_5(text, tolerance):
    assert written_tolerance(text) == pytest.approx(tolerance)


def outcome(tmp_path, expect: str, **result):
    path = tmp_path / "base.yaml"
    path.write_text(BASE.replace("expect: {value: 6}", f"expect: {expect}"))
    from mechgrade.spec import load_problem
    objective = load_problem(path).objectives[0]
    return expect_outcome(objective, ObjectiveResult("speed", objective.kind, "m/s", **result))


@pytest.mark.parametrize("expect, value, passed", [
    ("{value: 98.51}", 98.5149, True),
    ("{value: 98.51}", 98.5051, True),
    ("{value: 98.51}", 98.5151, False),
    ("{value: 98.51}", 98.5049, False),
    ("{value: 98.510}", 98.5200, False),
    ("{value: 5.00368}", 5.00372, True),
    ("{value: 5.00368}", 5.0040, False),
    ("{value: 2.78112}", 2.78107, False),  # a typo in the fifth digit is caught
    ("{value: 0}", 1e-12, True),
    ("{value: 0}", 1e-3, False),
    ("{value: 9.85, unit: cm/s}", 0.09854, True),
    ("{value: 9.85, unit: cm/s}", 0.09856, False),
])
def test_scalar_expect_to_the_digits_written(tmp_path, expect, value, passed):
    assert outcome(tmp_path, expect, value=value).passed is passed


def test_failing_expect_says_the_written_value_and_its_tolerance(tmp_path):
    result = outcome(tmp_path, "{value: 6.03}", value=6.0)
    assert result.message == "6 != expected 6.03 m/s (±0.005, from the digits written)"


def test_vector_components_each_by_their_own_digits(tmp_path):
    text = BASE.replace("find: speed(P, N)\n    kind: scalar", "find: vel(P, N)\n    kind: vector\n"
                        "    frame: N")
    path = tmp_path / "base.yaml"
    for components, value, passed in [
        ("[-3, 5.196]", (-3.0, 5.19615, 0.0), True),
        ("[-3.000, 5.196]", (-3.0, 5.19615, 0.0), True),
        ("[-3.001, 5.196]", (-3.0, 5.19615, 0.0), False),
        ("[-3, 5.19]", (-3.0, 5.19615, 0.0), False),
        ("[-3, 5.196, 0]", (-3.0, 5.19615, 1e-3), False),
        ("[0, 0]", (1e-16, -2e-16, 0.0), True),
    ]:
        path.write_text(text.replace("expect: {value: 6}", f"expect: {{components: {components}}}"))
        from mechgrade.spec import load_problem
        objective = load_problem(path).objectives[0]
        result = ObjectiveResult("speed", "vector", "m/s", value=value, frame="N")
        assert expect_outcome(objective, result).passed is passed, components


def with_mistake(tmp_path, find: str):
    path = tmp_path / "base.yaml"
    path.write_text(BASE.replace("    expect:", f"    mistakes: [{{find: \"{find}\", message: m}}]\n"
                                 "    expect:"))
    return check_problem(path)


def test_a_mistake_equal_to_the_answer_fails(tmp_path):
    report = with_mistake(tmp_path, "L*theta'")
    assert not report.passed
    assert report.faults == (f"{tmp_path / 'base.yaml'}:24:16: objectives[0].mistakes[0]: mistake "
                             "'L*theta'' gives the correct answer (6 m/s); expected a different "
                             "value, or remove it",)


def test_a_mistake_within_tolerance_warns(tmp_path):
    report = with_mistake(tmp_path, "1.005*L*theta'")
    assert report.passed and report.faults == ()
    assert report.warnings == (f"{tmp_path / 'base.yaml'}:24:16: objectives[0].mistakes[0]: "
                               "warning: mistake '1.005*L*theta'' gives 6.03 m/s, within the "
                               "tolerance of the answer 6: a student making it gets full credit",)


def test_a_distinct_mistake_is_silent(tmp_path):
    report = with_mistake(tmp_path, "2*L*theta'")
    assert report.passed and report.faults == () and report.warnings == ()


def test_an_absolute_tolerance_below_the_reference_accuracy_is_a_fault():
    from dataclasses import replace

    from mechgrade.check import tolerance_faults
    from mechgrade.resources import shipped_dir
    from mechgrade.solve import solve
    from mechgrade.spec import load_problem
    from mechgrade.spec.model import Tolerance

    problem = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
    tight = replace(problem, objectives=tuple(
        replace(o, tolerance=Tolerance(0.0, 1e-9)) if o.id == "alpha" else o
        for o in problem.objectives))
    (fault,) = tolerance_faults(tight, solve(tight))
    assert "expected a tolerance no tighter than the reference's own accuracy (7.88e-06 " \
           "rad/s^2, 1e-06 of the answer -7.88218), found abs: 1e-09" in fault
    loose = replace(problem, objectives=tuple(
        replace(o, tolerance=Tolerance(0.0, 0.01)) for o in problem.objectives))
    assert tolerance_faults(loose, solve(loose)) == []
