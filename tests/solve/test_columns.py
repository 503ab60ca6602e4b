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
