"""Functions of many states at once: the warnings of a state where a function is undefined
are silenced once for a whole stage (:func:`quiet`), and nowhere outside it."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from mechgrade.solve.columns import call, quiet


def _log(x):
    return np.log(x)


def test_a_call_gives_nan_where_its_function_is_undefined_and_warns_nobody():
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any warning would fail the test
        assert np.isnan(call(_log, np.array([[-1.0, np.e]]), 1)[0, 0])
        assert call(_log, np.array([[-1.0, np.e]]), 1)[0, 1] == 1.0


def test_quiet_silences_a_stage_and_restores_the_warnings_after_it():
    with quiet():
        with quiet():  # nested: still silent after the inner one ends
            pass
        assert np.isnan(_log(np.array([-1.0]))[0])
        assert np.isnan(call(_log, np.array([[-1.0]]), 1)[0, 0])
    with pytest.warns(RuntimeWarning):
        _log(np.array([-1.0]))


def test_cramer_over_columns_gives_each_column_the_bits_of_its_solve_alone():
    """Every column of a class solved at once (or by a matrix's products worked out
    beforehand) is the same number for number as that column solved alone on Python floats,
    a singular column included (its minimum-norm solution)."""
    from mechgrade.solve.columns import Cramer, least_squares_solution

    rng = np.random.default_rng(7)
    for k in (2, 3):
        A = rng.normal(size=(k, k, 40))
        A[:, :, 5] = 1.0  # singular: every row the same
        b = rng.normal(size=(k, 40))
        together = least_squares_solution(A, b)
        with np.errstate(all="ignore"):
            assert np.array_equal(together, Cramer(A).solve(b))
        for c in range(40):
            alone = least_squares_solution(A[:, :, c:c + 1], b[:, c:c + 1])[:, 0]
            if c == 5:
                np.testing.assert_allclose(together[:, c], alone, rtol=1e-12)
                np.testing.assert_allclose(together[:, c], np.linalg.pinv(A[:, :, c]) @ b[:, c])
            else:
                assert together[:, c].tolist() == alone.tolist()


@settings(max_examples=300, deadline=None)
@given(st.integers(2, 3), st.lists(st.booleans(), min_size=9, max_size=9),
       st.integers(0, 2 ** 32 - 1))
def test_a_shared_matrix_with_zero_entries_solves_to_the_bits_of_cramers_rule(k, zero, seed):
    """A mass matrix worked out once, its entries 0 at every column left out of its
    products (a diagonal one, a sparse one, a singular one), solves every right-hand side
    to the bits :func:`least_squares_solution` gives it, and its columns apart as together."""
    from mechgrade.solve.columns import Cramer, least_squares_solution

    rng = np.random.default_rng(seed)
    A = rng.normal(size=(k, k, 6))
    A[np.array(zero[:k * k]).reshape(k, k)] = 0.0
    A[:, :, 2] = np.where(A[:, :, 2] == 0.0, 0.0, 1.0)  # a column singular where rows repeat
    b = rng.normal(size=(k, 6))
    solver = Cramer(A)
    expected = least_squares_solution(A, b)
    with np.errstate(all="ignore"):
        assert np.array_equal(solver.solve(b), expected, equal_nan=True)
        cols = np.array([1, 2, 4])
        assert np.array_equal(solver.of(cols).solve(b[:, cols]), expected[:, cols],
                              equal_nan=True)


def test_a_shared_matrix_cramer_does_not_solve_is_solved_by_least_squares():
    from mechgrade.solve.columns import Cramer, least_squares_solution

    rng = np.random.default_rng(3)
    for shape in ((3, 2, 4), (4, 4, 4)):  # not square; four unknowns (LAPACK)
        A, b = rng.normal(size=shape), rng.normal(size=(shape[0], 4))
        solver = Cramer(A)
        assert solver.numerators is None
        assert np.array_equal(solver.solve(b), least_squares_solution(A, b))


def test_a_pause_of_the_collector_leaves_one_made_by_the_caller_alone():
    import gc

    from mechgrade.solve.columns import collector_paused

    gc.disable()
    try:
        with collector_paused():
            assert not gc.isenabled()
        assert not gc.isenabled()
    finally:
        gc.enable()
    with collector_paused(), collector_paused():
        assert not gc.isenabled()
    assert gc.isenabled()
