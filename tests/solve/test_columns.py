"""Functions of many states at once: the warnings of a state where a function is undefined
are silenced once for a whole stage (:func:`quiet`), and nowhere outside it."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

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
    """Every column of a class solved at once (with or without its determinants worked out
    beforehand) is the same number for number as that column solved alone on Python floats,
    a singular column included (its minimum-norm solution)."""
    from mechgrade.solve.columns import determinants, least_squares_solution

    rng = np.random.default_rng(7)
    for k in (2, 3):
        A = rng.normal(size=(k, k, 40))
        A[:, :, 5] = 1.0  # singular: every row the same
        b = rng.normal(size=(k, 40))
        together = least_squares_solution(A, b)
        assert np.array_equal(together, least_squares_solution(A, b, determinants(A)))
        for c in range(40):
            alone = least_squares_solution(A[:, :, c:c + 1], b[:, c:c + 1])[:, 0]
            if c == 5:
                np.testing.assert_allclose(together[:, c], alone, rtol=1e-12)
                np.testing.assert_allclose(together[:, c], np.linalg.pinv(A[:, :, c]) @ b[:, c])
            else:
                assert together[:, c].tolist() == alone.tolist()


def test_no_determinants_are_kept_for_a_system_cramer_does_not_solve():
    from mechgrade.solve.columns import determinants

    assert determinants(np.ones((3, 2, 4))) is None  # not square: least squares
    assert determinants(np.ones((4, 4, 4))) is None  # four unknowns: LAPACK
