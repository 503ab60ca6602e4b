"""The rules the numeric solver judges by, the same for one instant and for many columns."""

from __future__ import annotations

import numpy as np

from mechgrade.solve.rules import (left_open, near_zero, on_branch, real, same_value, satisfied,
                                   unchanged)
from mechgrade.spec.model import Root


def test_an_equation_holds_within_the_consistency_of_its_terms_and_an_undefined_one_does_not():
    residual = np.array([[2e-7, 2e-7], [np.nan, 1e-11]])
    scale = np.array([[100.0, 1.0], [1.0, 0.0]])
    assert satisfied(residual, scale, 1e-8).tolist() == [[True, False], [False, True]]


def test_an_unknown_with_any_part_in_a_free_direction_is_left_open_and_rounding_is_not():
    # 1e-7 of a direction is an unknown it moves (the grader and the messages read 1e-6 as
    # nothing, while the solver marked it free); 1e-12 is the SVD's rounding
    basis = np.array([[1.0, 0.0], [1e-7, 0.0], [1e-12, 0.0], [0.0, 1.0]])
    assert left_open(basis).tolist() == [True, True, False, True]
    assert left_open(basis[:, 0]).tolist() == [True, True, False, False]


def test_a_root_is_on_a_branch_when_it_is_clear_of_zero_for_the_size_of_its_quantity():
    # 1e-6 is zero for a quantity of size 1e4 (a rounding of its solve), not for one of size 1
    values = np.array([1e-6, 1e-6, -3.0])
    scales = np.array([1e4, 1.0, 1.0])
    assert on_branch(values, scales, Root.POSITIVE).tolist() == [False, True, False]
    assert on_branch(values, scales, Root.NEGATIVE).tolist() == [False, False, True]
    assert on_branch(values, scales, None).all()


def test_a_root_within_a_billionth_of_its_typical_size_of_zero_is_zero_in_any_unit():
    # one root in m and in mm: the same verdict (an absolute 1e-12 m judged them apart)
    assert near_zero(np.array([5e-10, 5e-7]), np.array([1.0, 1e3])).tolist() == [True, True]
    assert near_zero(np.array([5e-9, 5e-6]), np.array([1.0, 1e3])).tolist() == [False, False]


def test_a_value_is_unchanged_within_the_probe_tolerance_of_its_size_column_by_column():
    before = np.array([[1e3, 1e3, 0.0, np.nan, 1.0], [0.0, 0.0, 0.0, 1.0, 1.0]])
    after = np.array([[1e3 + 5e-5, 1e3 + 5e-4, 2e-12, np.nan, np.nan], [0.0, 0.0, 0.0, 1.0, 1.0]])
    assert unchanged(before, after).tolist() == [True, False, False, True, False]


def test_two_roots_have_the_same_value_within_a_millionth_of_it_and_of_one():
    assert same_value(1e4, 1e4 + 5e-3) and not same_value(1e4, 1e4 + 2e-2)
    assert same_value(0.0, 9e-7) and not same_value(0.0, 2e-6)


def test_a_closed_form_root_is_real_within_the_square_root_of_rounding_of_its_size():
    # a double root whose discriminant rounded negative (1.8e-8 s at 1.36 s), and one of 1e3
    # carrying 1e-5: real; 1e-6 at 1, a purely imaginary root and an undefined one: not
    roots = np.array([1.3591573224600748 + 1.8114853889568622e-08j, 1e3 + 1e-5j,
                      1.0 + 1e-6j, 3j, complex("nan")])
    assert real(roots).tolist() == [True, True, False, False, False]
    assert real(np.array([2e-7j, 1e-7j])).tolist() == [False, True]
