"""The tolerance rule gives the same verdict on numbers, vectors and short arrays as on long
arrays; the rank and round-off rules judge relative to the largest value, in any unit."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings, strategies as st

from mechgrade.tolerance import (FLOAT_SLACK, PYTHON_SIZE, AgreeAtPoints, agree_at_points,
                                 matrix_rank, null_space, parts, rank, within, within_each)

floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
finite = st.floats(min_value=-1e6, max_value=1e6)


def numpy_within(student, reference, rel, abs_, scale=None) -> bool:
    """The rule written with numpy alone (the path of long arrays)."""
    s, t = np.asarray(student, dtype=float), np.asarray(reference, dtype=float)
    size = np.abs(t) if scale is None else abs(float(scale))
    with np.errstate(all="ignore"):
        limit = np.maximum(rel * size, abs_)
        return bool(np.all(np.abs(s - t) <= limit * (1 + FLOAT_SLACK)
                           + 1e-3 * FLOAT_SLACK * size))


@given(st.lists(st.tuples(floats, floats), min_size=1, max_size=PYTHON_SIZE + 2),
       st.sampled_from([0.0, 1e-9, 0.01, 0.05]), st.sampled_from([0.0, 1e-9, 0.5]),
       st.one_of(st.none(), floats))
def test_numbers_vectors_and_short_arrays_are_judged_as_long_arrays_are(pairs, rel, abs_, scale):
    student, reference = [p[0] for p in pairs], [p[1] for p in pairs]
    assert within(student, reference, rel, abs_, scale) == \
        numpy_within(student, reference, rel, abs_, scale)
    assert within(student[0], reference[0], rel, abs_, scale) == \
        numpy_within(student[0], reference[0], rel, abs_, scale)


@given(finite, st.sampled_from([0.01, 0.05]))
def test_the_boundary_is_included(reference, rel):
    edge = reference + rel * abs(reference)
    assert within(edge, reference, rel, 0.0) == numpy_within(edge, reference, rel, 0.0)


@given(st.lists(st.tuples(finite, finite), min_size=1, max_size=40),
       st.sampled_from([1e-6, 0.01]))
def test_agreement_at_points_has_a_floor_from_the_mean_size(pairs, rel):
    from mechgrade.tolerance import agree_at_points

    student = np.array([p[0] for p in pairs])
    reference = np.array([p[1] for p in pairs])
    floor = max(rel * float(np.mean(np.abs(reference))) * 1e-3, 1e-12)
    assert agree_at_points(rel, reference)(student, reference) == \
        numpy_within(student, reference, rel, floor)
    assert agree_at_points(rel, reference)(reference, reference)


@given(st.lists(st.tuples(floats, floats, floats), min_size=1, max_size=6),
       st.sampled_from([0.0, 1e-9, 0.01]), st.sampled_from([0.0, 0.5]), finite)
def test_each_column_is_judged_as_within_judges_it_alone(rows, rel, abs_, scale):
    student = np.array([[r[0], r[1]] for r in rows])
    reference = np.array([[r[2], r[2]] for r in rows])
    scales = np.array([scale, -scale])
    verdicts = within_each(student, reference, rel, abs_, scales)
    assert verdicts.tolist() == [within(student[:, j], reference[:, j], rel, abs_, scales[j])
                                 for j in range(2)]


@given(st.lists(finite, min_size=1, max_size=12).flatmap(
    lambda ref: st.tuples(st.just(ref), st.lists(st.lists(floats, min_size=len(ref),
                                                          max_size=len(ref)), min_size=1,
                                                 max_size=6))),
       st.sampled_from([1e-6, 0.01]))
@settings(max_examples=20)
def test_agreement_with_many_candidates_at_once_is_the_test_row_by_row(case, rel):
    reference, candidates = case
    test = agree_at_points(rel, np.array(reference))
    student = np.array(reference) * 1.005
    rows = np.array(candidates)
    assert test.each(student, rows).tolist() == [test(student, row) for row in rows]
    # the boundary itself, a candidate as the answer
    with np.errstate(all="ignore"):
        edge = rows[0] * (1 + rel)
    assert test.each(rows[0], np.array([rows[0], edge])).tolist() == \
        [test(rows[0], rows[0]), test(rows[0], edge)]


@given(st.lists(st.lists(finite, min_size=3, max_size=3), min_size=1, max_size=5),
       st.lists(st.lists(floats, min_size=3, max_size=3), min_size=1, max_size=8),
       st.sampled_from([1e-6, 0.01]))
@settings(max_examples=30)
def test_candidates_prepared_once_judge_every_answer_as_the_test_row_by_row(rows, students,
                                                                            rel):
    test = agree_at_points(rel, np.array(rows[0]))
    prepared = test.rows(np.array(rows))
    for student in [*map(np.array, students), *(np.array(r) * (1 + rel) for r in rows)]:
        assert prepared.each(student).tolist() == [test(student, np.array(r)) for r in rows]


def test_candidates_of_another_shape_never_agree():
    test = AgreeAtPoints(0.01, 1e-12)
    assert test.each(np.array([1.0, 2.0]), np.array([[1.0, 2.0, 3.0]])).tolist() == [False]
    assert not test(np.array([1.0, 2.0]), np.array([1.0, 2.0, 3.0]))
    assert test.rows(np.array([[1.0, 2.0, 3.0]])).each(np.array([1.0, 2.0])).tolist() == [False]


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


@given(scale=st.sampled_from([1e-6, 1.0, 1e6]))
def test_a_component_within_a_billionth_of_the_largest_is_round_off_in_any_unit(scale):
    values = np.array([[2.0, -1e-10, 3e-9], [0.0, 0.0, 0.0]]) * scale
    assert parts(values, axis=1).tolist() == [[True, False, True], [False, False, False]]


def test_an_undefined_value_is_no_round_off():
    assert parts(np.array([np.nan, 1e-12, 1.0]), 1.0).tolist() == [True, False, True]
