"""Assignment files: the valid form, and a failing input for every validation branch."""

from __future__ import annotations

import textwrap

import pytest

from mechgrade.errors import AssignmentError
from mechgrade.grade.assignment import Assignment, _policy, load_assignment
from mechgrade.grade.policy import ErrorCarriedForward, GradingPolicy, MissingUnit, ShowWorked

MINIMAL = """\
id: hw1
title: Homework 1
problems: [p.yaml]
"""


@pytest.fixture
def folder(tmp_path):
    (tmp_path / "p.yaml").write_text("id: p\n", encoding="utf-8")
    (tmp_path / "q.yaml").write_text("id: q\n", encoding="utf-8")
    return tmp_path


def write(folder, text: str):
    path = folder / "hw.yaml"
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


def error_of(folder, text: str) -> str:
    with pytest.raises(AssignmentError) as info:
        load_assignment(write(folder, text))
    return str(info.value)


def test_minimal_assignment_has_defaults(folder):
    hw = load_assignment(write(folder, MINIMAL))
    assert isinstance(hw, Assignment)
    assert (hw.id, hw.title, hw.default_points, hw.points) == ("hw1", "Homework 1", 1.0, ())
    assert hw.problems[0].path == folder / "p.yaml"
    assert hw.problems[0].objectives is None
    assert hw.policy.reveal_answers is False
    assert hw.policy.rel is None and hw.policy.abs is None
    assert hw.policy.missing_unit == "reject"
    assert hw.policy == GradingPolicy()


def test_full_assignment_reads_every_field(folder):
    hw = load_assignment(write(folder, """\
        id: hw-2.b
        title: Homework 2
        problems:
          - p.yaml
          - {path: q.yaml, objectives: [speed, acc]}
        points: {default: 2, q.speed: 5, p.a: 0.5}
        policy:
          reveal_answers: yes
          tolerance: {rel: 0.02, abs: 0.1, sig_figs: 3}
          sig_figs: {figures: 3, credit: 0.8, strict: true}
          missing_unit: {action: penalize, credit: 0.5}
          partial_credit: {enabled: true, diagnoses: {sign: 0.5, swapped: 0.25}}
          ecf: {enabled: false, credit: 0.5}
        """))
    assert hw.problems[1].objectives == ("speed", "acc")
    assert hw.points == (("p.a", 0.5), ("q.speed", 5.0))
    assert hw.points_for("q", "speed") == 5.0 and hw.points_for("q", "acc") == 2.0
    policy = hw.policy
    assert policy.reveal_answers is True
    assert (policy.rel, policy.abs, policy.sig_figs) == (0.02, 0.1, 3)
    # a written figure or a missing unit keeps its credit: it loses the rest
    assert (policy.written_sig_figs, policy.written_sig_figs_strict) == (3, True)
    assert policy.written_sig_figs_deduction == pytest.approx(0.2)
    assert (policy.missing_unit, policy.missing_unit_deduction) == ("assume", 0.5)
    assert policy.partial_credit == (("sign", 0.5), ("swapped", 0.25))
    assert policy.ecf == ErrorCarriedForward(False, 0.5)
    assert str(hw.where_points("q.speed")).endswith("hw.yaml:6:31: points.q.speed")


@pytest.mark.parametrize("written, taken", [
    ("missing_unit: {action: assume}", ("assume", 0.0)),
    ("missing_unit: {action: reject}", ("reject", GradingPolicy().missing_unit_deduction)),
    ("partial_credit: {enabled: false, diagnoses: {sign: 0.5}}", ()),
])
def test_a_policy_rule_is_read_as_the_one_grading_policy(folder, written, taken):
    hw = load_assignment(write(folder, MINIMAL + f"policy:\n  {written}\n"))
    found = (hw.policy.missing_unit, hw.policy.missing_unit_deduction) \
        if "missing_unit" in written else hw.policy.partial_credit
    assert found == taken


@pytest.mark.parametrize("field, value, message", [
    ("worked_solution", "later", "policy.worked_solution: expected one of always, "
                                 "after_due_date, never, found 'later'"),
    ("ecf", ErrorCarriedForward(True, 1.5), "policy.ecf.credit: expected a number from 0 to 1, "
                                            "found 1.5"),
])
def test_a_grading_policy_made_in_code_is_checked_too(field, value, message):
    with pytest.raises(AssignmentError) as caught:
        GradingPolicy(**{field: value})
    assert str(caught.value) == message


def test_assignment_is_frozen(folder):
    hw = load_assignment(write(folder, MINIMAL))
    with pytest.raises(AttributeError):
        hw.id = "other"  # type: ignore[misc]


@pytest.mark.parametrize("text, expected", [
    ("- a\n- b\n", "hw.yaml:1:1: expected a mapping of fields (id, title, problems...), "
                   "found a list"),
    ("title: T\nproblems: [p.yaml]\n", "hw.yaml:1:1: expected a field 'id', found none"),
    ("id: hw1\nproblems: [p.yaml]\n", "hw.yaml:1:1: expected a field 'title', found none"),
    ("id: hw1\ntitle: T\n", "hw.yaml:1:1: expected a field 'problems', found none"),
    (MINIMAL + "deadline: tomorrow\n",
     "hw.yaml:4:1: deadline: expected only the fields id, title, problems, points, variants, "
     "due, policy, found 'deadline'"),
    (MINIMAL + "due: tomorrow\n",
     "hw.yaml:4:6: due: expected a date (2026-11-20) or a date and time (2026-11-20T23:59, "
     "with an offset such as +01:00 or Z, else UTC), found 'tomorrow'"),
    (MINIMAL + "due: 2026-02-30\n",
     "hw.yaml:4:6: due: expected a date (2026-11-20) or a date and time"),
    (MINIMAL + "due: 2026-11-20T25:00\n",
     "hw.yaml:4:6: due: expected a date (2026-11-20) or a date and time"),
    (MINIMAL + "due: 20261120\n",
     "hw.yaml:4:6: due: expected text, found 20261120"),
    (MINIMAL + "policy: {worked_solution: later}\n",
     "hw.yaml:4:27: policy.worked_solution: expected one of always, after_due_date, never, "
     "found 'later'"),
    (MINIMAL + "policy: {reveal: true}\n",
     "hw.yaml:4:10: policy.reveal: expected only the fields reveal_answers, worked_solution, "
     "tolerance, sig_figs, missing_unit, partial_credit, ecf, found 'reveal'; did you mean "
     "'reveal_answers'?"),
    (MINIMAL + "points: {p: 3}\n",
     "hw.yaml:4:10: points.p: expected only the fields 'default' or "
     "'problem_id.objective_id', found 'p'"),
    ("id: 12\ntitle: T\nproblems: [p.yaml]\n", "hw.yaml:1:5: id: expected an id of letters, digits, '_', '-' and '.' (at most 64), found 12"),
    ("id: hw1\ntitle: T\nproblems: p.yaml\n",
     "hw.yaml:3:11: problems: expected a list, found 'p.yaml'"),
    ("id: hw1\ntitle: T\nproblems: [3]\n",
     "hw.yaml:3:12: problems[0]: expected text or a mapping, found 3"),
    (MINIMAL + "points: {default: -1}\n",
     "hw.yaml:4:19: points.default: expected a number >= 0, found -1"),
    (MINIMAL + "points: {p.a: 5000}\n",
     "hw.yaml:4:15: points.p.a: expected a number <= 1000, found 5000"),
    (MINIMAL + "policy: {tolerance: {rel: 2}}\n",
     "hw.yaml:4:27: policy.tolerance.rel: expected a number <= 1, found 2"),
    (MINIMAL + "policy: {tolerance: {separate_mistakes: yes please}}\n",
     "hw.yaml:4:41: policy.tolerance.separate_mistakes: expected true or false, "
     "found 'yes please'"),
    (MINIMAL + "policy: {reveal_answers: maybe}\n",
     "hw.yaml:4:26: policy.reveal_answers: expected true or false, found 'maybe'"),
    (MINIMAL + "policy: {sig_figs: {figures: 2.5}}\n",
     "hw.yaml:4:30: policy.sig_figs.figures: expected a whole number, found 2.5"),
    ("id: hw1\ntitle: T\nproblems: []\n",
     "hw.yaml:3:11: problems: expected at least 1 item(s), found an empty list"),
    ("id: hw1\ntitle: T\nproblems: [{path: p.yaml, objectives: []}]\n",
     "hw.yaml:3:39: problems[0].objectives: expected at least 1 item(s) (none only beside diagrams: or equations:), found an empty list"),
    (MINIMAL + "policy: {tolerance: {}}\n",
     "hw.yaml:4:21: policy.tolerance: expected at least 1 field(s), found an empty mapping"),
    ("id: hw1\ntitle: ''\nproblems: [p.yaml]\n", "hw.yaml:2:8: title: expected at least 1 character(s), "
                                                     "found empty text"),
    ("id: hw1\ntitle: " + "x" * 201 + "\nproblems: [p.yaml]\n",
     "hw.yaml:2:8: title: expected at most 200 character(s), found 201 characters"),
    ("id: hw 1\ntitle: T\nproblems: [p.yaml]\n",
     "hw.yaml:1:5: id: expected an id of letters, digits, '_', '-' and '.' (at most 64), "
     "found 'hw 1'"),
    ("id: hw1\ntitle: T\nproblems: [{path: p.yaml, objectives: [a-b]}]\n",
     "hw.yaml:3:40: problems[0].objectives[0]: expected an objective id (letters, digits and "
     "'_'), found 'a-b'"),
    (MINIMAL + "policy: {missing_unit: {action: guess}}\n",
     "hw.yaml:4:33: policy.missing_unit.action: expected one of assume, penalize, "
     "reject, found 'guess'"),
    (MINIMAL + "policy: {missing_unit: {credit: 0.5}}\n",
     "hw.yaml:4:24: policy.missing_unit: expected a field 'action', found none"),
    ("id: hw1\ntitle: T\nproblems: [nothere.yaml]\n",
     "hw.yaml:3:12: problems[0]: expected a problem file (relative to the assignment file), "
     "found no file at"),
    ("id: hw1\ntitle: T\nproblems: [p.yaml, ./p.yaml]\n",
     "hw.yaml:3:20: problems[1]: expected each problem once, found './p.yaml' again "
     "(also problems[0])"),
    ("id: hw1\ntitle: T\nproblems: [{path: p.yaml, objectives: [a, b, a]}]\n",
     "hw.yaml:3:39: problems[0].objectives: expected each objective once, found 'a' more than "
     "once"),
    (MINIMAL + "policy: {partial_credit: {diagnoses: {sloppy: 0.5}}}\n",
     "hw.yaml:4:47: policy.partial_credit.diagnoses.sloppy: expected a diagnosis code (mistake, "
     "sign,"),
    ("id: [unclosed\n", "hw.yaml:1:5: unclosed '[': expected ',' or ']' after an item, found the end of the file on line 2"),
    ("id: &a hw1\ntitle: *a\nproblems: [p.yaml]\n",
     "hw.yaml:2:8: expected plain YAML, found an alias"),
    ("id: hw1\nid: hw2\ntitle: T\nproblems: [p.yaml]\n",
     "hw.yaml:2:1: id: expected each key once, found 'id' again"),
])
def test_invalid_assignment_says_where_and_what(folder, text, expected):
    message = error_of(folder, text)
    assert message.startswith(str(folder / "hw.yaml") + expected[len("hw.yaml"):])


def test_every_error_of_a_file_is_one_line_each_in_file_order(folder):
    message = error_of(folder, """\
        id: hw 1
        title: T
        problems: [p.yaml]
        points: {default: -2}
        """)
    lines = message.splitlines()
    assert len(lines) == 2
    assert lines[0].endswith("hw.yaml:1:5: id: expected an id of letters, digits, '_', '-' and "
                             "'.' (at most 64), found 'hw 1'")
    assert lines[1].endswith("hw.yaml:4:19: points.default: expected a number >= 0, found -2")


def test_missing_assignment_file_is_an_assignment_error(tmp_path):
    with pytest.raises(AssignmentError, match="expected an assignment file \\(YAML\\), found no such file"):
        load_assignment(tmp_path / "absent.yaml")


def test_problem_paths_are_relative_to_the_assignment_file(tmp_path):
    (tmp_path / "problems").mkdir()
    (tmp_path / "problems" / "p.yaml").write_text("id: p\n", encoding="utf-8")
    (tmp_path / "hw").mkdir()
    path = tmp_path / "hw" / "a.yaml"
    path.write_text("id: a\ntitle: A\nproblems: [../problems/p.yaml]\n", encoding="utf-8")
    hw = load_assignment(path)
    assert hw.problems[0].path.resolve() == (tmp_path / "problems" / "p.yaml").resolve()


def test_example_assignment_loads():
    from mechgrade.resources import shipped_dir

    hw = load_assignment(shipped_dir("examples") / "hw1" / "assignment.yaml")
    assert hw.id == "hw1"
    assert hw.policy.reveal_answers is True


def test_separate_mistakes_is_read_from_the_tolerance(folder):
    (folder / "hw.yaml").write_text(MINIMAL + "policy: {tolerance: {separate_mistakes: true}}\n",
                                    encoding="utf-8")
    assert load_assignment(folder / "hw.yaml").policy.separate_mistakes is True


@pytest.mark.parametrize("due, rule, shown_on", [
    ("2026-11-20", None, ("2026-11-21T00:00:00+00:00",)),
    ("2026-11-20T18:00-05:00", "after_due_date", ("2026-11-20T23:00:00+00:00",)),
    (None, "always", ("2026-01-01T00:00:00+00:00", "2027-01-01T00:00:00+00:00")),
    ("2026-11-20", "never", ()),
    (None, None, ()),
])
def test_the_worked_solution_is_shown_by_the_due_date_rule(folder, due, rule, shown_on):
    from datetime import datetime

    text = MINIMAL + (f"due: {due}\n" if due else "") + (
        f"policy: {{worked_solution: {rule}}}\n" if rule else "")
    (folder / "hw.yaml").write_text(text, encoding="utf-8")
    hw = load_assignment(folder / "hw.yaml")
    moments = ["2026-01-01T00:00:00+00:00", "2026-11-20T22:00:00+00:00",
               "2026-11-20T23:00:00+00:00", "2026-11-21T00:00:00+00:00",
               "2027-01-01T00:00:00+00:00"]
    shown = [m for m in moments if hw.shows_worked_solution(datetime.fromisoformat(m))]
    assert [m for m in shown if m in shown_on] == list(shown_on)
    assert len(shown) == (0 if rule == "never" or (due is None and rule != "always")
                          else len(moments) - moments.index(shown_on[0]))


@pytest.mark.parametrize("text, expected", [
    (MINIMAL + "points: {default: .nan}\n",
     "hw.yaml:4:19: points.default: expected a finite number, found nan (not a number)"),
    (MINIMAL + "points: {p.a: .inf}\n",
     "hw.yaml:4:15: points.p.a: expected a finite number, found inf (infinite)"),
    (MINIMAL + "policy: {tolerance: {rel: .nan}}\n",
     "hw.yaml:4:27: policy.tolerance.rel: expected a finite number, found nan (not a number)"),
    (MINIMAL + "policy: {tolerance: {abs: .inf}}\n",
     "hw.yaml:4:27: policy.tolerance.abs: expected a finite number, found inf (infinite)"),
    (MINIMAL + "policy: {tolerance: {abs: 1.0e+300}}\n",
     "hw.yaml:4:27: policy.tolerance.abs: expected a number of magnitude at most 1e+40, "
     "found 1e+300"),
    (MINIMAL + "policy: {sig_figs: {figures: 3, credit: .nan}}\n",
     "hw.yaml:4:41: policy.sig_figs.credit: expected a finite number, found nan (not a number)"),
    (MINIMAL + "policy: {missing_unit: {action: penalize, credit: .nan}}\n",
     "hw.yaml:4:51: policy.missing_unit.credit: expected a finite number, found nan"),
    (MINIMAL + "policy: {partial_credit: {diagnoses: {sign: .nan}}}\n",
     "hw.yaml:4:45: policy.partial_credit.diagnoses.sign: expected a finite number, found nan"),
    (MINIMAL + "policy: {ecf: {credit: .nan}}\n",
     "hw.yaml:4:24: policy.ecf.credit: expected a finite number, found nan (not a number)"),
])
def test_nan_infinity_and_absurd_magnitudes_are_refused(folder, text, expected):
    """Each would grade the whole class wrongly (``points.default: .nan`` graded everyone,
    then wrote nothing)."""
    message = error_of(folder, text)
    assert message.startswith(str(folder / "hw.yaml") + expected[len("hw.yaml"):]), message


def test_a_policys_missing_unit_and_worked_solution_are_read_into_their_types():
    policy = _policy({"missing_unit": {"action": "penalize"}, "worked_solution": "never"})
    assert (policy.missing_unit, policy.worked_solution) == (MissingUnit.ASSUME,
                                                             ShowWorked.NEVER)
    assert type(policy.missing_unit) is MissingUnit and type(policy.worked_solution) is ShowWorked
