"""The rules the numeric solver judges by, the same for one instant and for many columns."""

from __future__ import annotations

import numpy as np

from hypothesis import given
from hypothesis import strategies as st

from mechgrade.solve.rules import (
    matrix_rank, null_space, on_branch, rank, same_value, satisfied, unchanged)
from mechgrade.spec.model import Root


def test_an_equation_holds_within_the_consistency_of_its_terms_and_an_undefined_one_does_not():
    residual = np.array([[2e-7, 2e-7], [np.nan, 1e-11]])
    scale = np.array([[100.0, 1.0], [1.0, 0.0]])
    assert satisfied(residual, scale, 1e-8).tolist() == [[True, False], [False, True]]


def test_the_rank_counts_singular_values_against_the_largest_or_one():
    singular = np.array([[10.0, 1e-7, 1e-9], [1e-10, 1e-10, 0.0], [5.0, 4.0, 3.0]])
    assert rank(singular).tolist() == [2, 0, 3]


@given(scale=st.sampled_from([1e-3, 1.0, 1e4, 1e8]), seed=st.integers(0, 50))
def test_a_matrix_has_the_same_rank_in_any_unit_with_its_rounding(scale, seed):
    # a dependent row, then the rounding of its entries' size: relative, not absolute
    rng = np.random.default_rng(seed)
    rows = rng.uniform(-1.0, 1.0, (2, 3))
    A = np.vstack([rows, rows[0] - 2.0 * rows[1]]) * scale
    noisy = A * (1.0 + 4e-16 * rng.standard_normal(A.shape))
    assert matrix_rank(A) == matrix_rank(noisy) == 2


def test_the_null_space_of_a_matrix_with_a_free_direction_is_that_direction():
    basis = null_space(np.array([[1.0, -1.0, 0.0], [0.0, 0.0, 1.0]]))
    assert basis.shape == (3, 1)
    assert np.allclose(np.abs(basis[:, 0]), [2 ** -0.5, 2 ** -0.5, 0.0])


def test_a_root_is_on_a_branch_when_it_is_clear_of_zero_for_the_size_of_its_quantity():
    # 1e-6 is zero for a quantity of size 1e4 (a rounding of its solve), not for one of size 1
    values = np.array([1e-6, 1e-6, -3.0])
    scales = np.array([1e4, 1.0, 1.0])
    assert on_branch(values, scales, Root.POSITIVE).tolist() == [False, True, False]
    assert on_branch(values, scales, Root.NEGATIVE).tolist() == [False, False, True]
    assert on_branch(values, scales, None).all()


def test_a_value_is_unchanged_within_the_probe_tolerance_of_its_size_column_by_column():
    before = np.array([[1e3, 1e3, 0.0, np.nan, 1.0], [0.0, 0.0, 0.0, 1.0, 1.0]])
    after = np.array([[1e3 + 5e-5, 1e3 + 5e-4, 2e-12, np.nan, np.nan], [0.0, 0.0, 0.0, 1.0, 1.0]])
    assert unchanged(before, after).tolist() == [True, False, False, True, False]


def test_two_roots_have_the_same_value_within_a_millionth_of_it_and_of_one():
    assert same_value(1e4, 1e4 + 5e-3) and not same_value(1e4, 1e4 + 2e-2)
    assert same_value(0.0, 9e-7) and not same_value(0.0, 2e-6)
