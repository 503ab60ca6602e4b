"""The worked solutions of a grading run: one per problem, one per variant, looked up per
student; a recorded variant is rebuilt from its givens."""

import pytest

from mechgrade.errors import SolveError
from mechgrade.grade.results import (AssignmentInfo, GradeReport, StudentResult,
                                     StudentVariant, VariantGiven)
from mechgrade.grade.variants import draw_variant, recorded_variant
from mechgrade.grade.worked import FeedbackSolutions
from mechgrade.resources import shipped_dir
from mechgrade.solve.worked import WorkedSolution
from mechgrade.spec import load_problem

VARIANTS = shipped_dir("examples") / "hw2_variants" / "pendulum_variants.yaml"


def _student(*givens):
    return StudentResult("s", "", "graded", 0.0, 1.0,
                         variant=StudentVariant("seed", givens) if givens else None)


def test_a_student_gets_their_variants_solution_and_the_problems_own_otherwise():
    own = WorkedSolution("p", "P", (), "")
    q = WorkedSolution("q", "Q", (), "")
    drawn = (VariantGiven("p", "L", 2.5, "ft"),)
    theirs = WorkedSolution("p", "P", (), "<svg/>")
    worked = FeedbackSolutions((own, q), (("p", drawn, theirs),))
    assert worked.for_student(_student(*drawn)) == (theirs, q)
    assert worked.for_student(_student()) == (own, q)
    other = (VariantGiven("p", "L", 3.0, "ft"),)
    assert worked.for_student(_student(*other)) == (own, q)


def test_a_diagnosis_label_maps_to_its_code_and_any_other_text_to_none():
    worked = FeedbackSolutions((), (), (("Coriolis term left out", "drop_coriolis"),))
    assert worked.code("Coriolis term left out") == "drop_coriolis"
    assert worked.code("sign error") is None and worked.code(None) is None


def test_a_recorded_variant_is_the_one_drawn():
    problem = load_problem(VARIANTS)
    for student in ("1", "2", "3"):
        variant = draw_variant(problem, "fall", student)
        assert recorded_variant(problem, "fall", student, variant.drawn) == variant


def test_recorded_givens_that_break_a_condition_are_refused():
    problem = load_problem(VARIANTS)
    drawn = draw_variant(problem, "fall", "1").drawn
    # theta'' = 4 rad/s^2 with theta' = 6 rad/s breaks theta'' > 0.2 theta'^2
    broken = tuple(VariantGiven(g.problem, g.name, {"theta'": 6.0, "theta''": 4.0}.get(
        g.name, g.value), g.unit, g.draw) for g in drawn)
    with pytest.raises(SolveError, match="do not make a variant"):
        recorded_variant(problem, "fall", "1", broken)


def test_an_empty_report_still_gets_each_problems_solution():
    from mechgrade.grade.assignment import load_assignment
    from mechgrade.grade.worked import feedback_solutions

    hw = load_assignment(shipped_dir("examples") / "hw2_variants" / "assignment.yaml")
    worked = feedback_solutions(hw, GradeReport(AssignmentInfo("hw2", "Homework 2"), (), ()))
    assert [w.problem for w in worked.solutions] == ["pendulum_variants",
                                                     "bowling_3_15_8_connected_blocks"]
    assert worked.variants == ()
    # only the objectives the assignment grades are worked out
    assert [s.anchor for s in worked.solutions[1].steps if s.anchor.startswith("answer-")] \
        == ["answer-xdot"]
