"""Mistaken constraints: a cord's strands counted once."""

from dataclasses import replace

import pytest

from mechgrade.expressions.syntax import parse
from mechgrade.resources import shipped_dir
from mechgrade.spec import load_problem
from mechgrade.spec.constraint_mutations import constraint_mutations
from mechgrade.spec.model import Expr



@pytest.fixture(scope="module")
def problem():
    return load_problem(shipped_dir("problems") / "truck_hoists_crate_pulley.yaml")


def _with_length(problem, text):
    (c,) = problem.constraints
    return replace(problem, constraints=(replace(c, lhs=Expr(text, parse(text))),))


def test_a_length_term_counted_twice_is_taken_once_and_the_copy_keeps_no_author_answers(problem):
    (once,) = constraint_mutations(problem)
    assert once.code == "strands_miscounted"
    assert once.problem.constraints[0].lhs.text == "sqrt(x**2+h**2)+(h-y)"
    assert once.problem.constraints[0].rhs == problem.constraints[0].rhs
    assert once.sentence.startswith("Your value counts (h - y) once in the length of rope_length "
                                     "(sqrt(x² + h²) + 2·(h - y) = L): it is there 2 times")
    assert all(o.expect is None and not o.mistakes for o in once.problem.objectives)


def test_a_cord_with_one_strand_each_or_a_factor_without_a_coordinate_has_nothing_to_miscount(
        problem):
    assert constraint_mutations(_with_length(problem, "sqrt(x^2 + h^2) + (h - y)")) == ()
    # 2 h is a fixed length, not a strand of the moving crate's pulley
    assert constraint_mutations(_with_length(problem, "sqrt(x^2 + h^2) + 2*h - y")) == ()
    # 1.5 (h - y) is no whole count of strands
    assert constraint_mutations(_with_length(problem, "sqrt(x^2 + h^2) + 1.5*(h - y)")) == ()
