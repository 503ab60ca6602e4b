"""Values at sample points are the caller's own array, one value per point."""

from __future__ import annotations

import numpy as np
import pytest

from mechgrade.expressions.numeric import evaluate
from mechgrade.expressions.syntax import parse


@pytest.mark.parametrize("text", ["L", "-L", "2*L", "sqrt(L)", "3", "pi"])
def test_values_are_a_fresh_writable_array_per_point(text):
    env = {"L": np.array([1.0, 4.0])}
    values = evaluate(parse(text), env)
    assert values.shape == (2,) and values.dtype == np.float64 and values.flags.writeable
    values[:] = -7.0
    assert env["L"].tolist() == [1.0, 4.0]
