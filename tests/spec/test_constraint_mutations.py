"""Mistaken constraints: a cord's strands counted once."""

from dataclasses import replace

import pytest

from mechgrade.expressions.syntax import parse
from mechgrade.resources import shipped_dir
from mechgrade.spec import load_problem
from mechgrade.spec.language import FUNCTIONS
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


def test_a_strand_term_with_a_number_in_exponent_form_is_named_whole(problem):
    (once,) = constraint_mutations(_with_length(problem, "sqrt(x^2 + h^2) + 2*(h - 1e-5*y)"))
    assert once.sentence.startswith("Your value counts (h - 1e-05·y) once")


def test_a_cord_with_one_strand_each_or_a_factor_without_a_coordinate_has_nothing_to_miscount(
        problem):
    assert constraint_mutations(_with_length(problem, "sqrt(x^2 + h^2) + (h - y)")) == ()
    # 2 h is a fixed length, not a strand of the moving crate's pulley
    assert constraint_mutations(_with_length(problem, "sqrt(x^2 + h^2) + 2*h - y")) == ()
    # 1.5 (h - y) is no whole count of strands
    assert constraint_mutations(_with_length(problem, "sqrt(x^2 + h^2) + 1.5*(h - y)")) == ()


@pytest.fixture(scope="module")
def gear():
    return load_problem(shipped_dir("problems") / "gear_between_two_racks.yaml")


def test_a_rolling_contact_on_a_moving_surface_is_taken_at_rest_one_contact_at_a_time(gear):
    fixed = [m for m in constraint_mutations(gear) if m.code == "surface_taken_fixed"]
    assert [[c.rhs.text for c in m.problem.constraints] for m in fixed] == [
        ["vel(coincident(T, N), N)", "vel(coincident(B, D), N)"],
        ["vel(coincident(T, U), N)", "vel(coincident(B, N), N)"]]
    assert [c.lhs for c in fixed[1].problem.constraints] == [c.lhs for c in gear.constraints]
    assert fixed[1].sentence.startswith("Your value takes D as fixed where W rolls on it at B "
                                        "(lower_mesh)")


def test_a_contact_on_the_fixed_frame_or_a_velocity_constraint_of_another_form_is_not_taken(gear):
    upper, lower = gear.constraints

    def velocity(text):
        return Expr(text, parse(text, functions=FUNCTIONS))
    on_ground = replace(lower, rhs=velocity("vel(coincident(B, N), N)"))
    # a velocity constraint between two different points is no rolling contact
    other = replace(upper, rhs=velocity("vel(coincident(B, U), N)"))
    for constraints in ((on_ground,), (other,)):
        assert not [m for m in constraint_mutations(replace(gear, constraints=constraints))
                    if m.code == "surface_taken_fixed"]
