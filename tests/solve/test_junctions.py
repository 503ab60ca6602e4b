"""A massless junction's start settled from its balance (mechgrade.solve.junctions): every
column of a class and every start at once on the level solver, each column as it is alone."""

from __future__ import annotations

import numpy as np
import pytest

from mechgrade.resources import shipped_dir
from mechgrade.solve.analysis import analysis_plan
from mechgrade.solve.columns import call
from mechgrade.solve.dynamics import kinematic_problem, kinetics_plan
from mechgrade.solve.instant import instant_givens
from mechgrade.solve.junctions import settle_junctions
from mechgrade.solve.levels import place_givens
from mechgrade.spec import load_problem


@pytest.fixture(scope="module")
def springs():
    problem = load_problem(shipped_dir("problems") / "block_on_springs_in_series.yaml")
    kp = kinetics_plan(problem)
    values = place_givens(kinematic_problem(problem), kp.kp,
                          instant_givens(problem, None, {})).values
    for i, fn in analysis_plan(kp).start:
        values[i] = call(fn, np.concatenate([values, np.zeros(len(kp.kin.reactions))])[:, None],
                         1)[0, 0]
    return problem, kp, values


def starts(kp, values, blocks) -> np.ndarray:
    """The spec's start with the block at each of ``blocks`` (m), one column each."""
    X = np.repeat(values[:, None], len(blocks), axis=1)
    X[kp.kp.index.position("x")] = blocks
    return X


def test_the_joint_starts_where_the_springs_pulls_cancel(springs):
    problem, kp, values = springs
    settled, errors = settle_junctions(problem, kp, starts(kp, values, [0.45, 0.6]))
    index = kp.kp.index
    # k1 (xj - L1) = k2 (x - xj - L2) with k1 = 600, k2 = 300, L1 = 0.25, L2 = 0.2
    assert settled[index.position("xj")].tolist() == pytest.approx([0.25, 0.3], rel=1e-12)
    assert settled[index.position("xj'")].tolist() == pytest.approx([0.5 / 3] * 2, rel=1e-12)
    assert errors == {}


def test_a_class_settles_each_column_as_alone_and_keeps_each_columns_refusal(springs):
    problem, kp, values = springs
    # the block behind the wall: from the spec's guess, no root of the joint's balance
    X = starts(kp, values, [0.45, -0.75, 0.52])
    together, errors = settle_junctions(problem, kp, X)
    assert list(errors) == [1]
    assert "has no solution at the start for xj" in str(errors[1])
    for c in (0, 2):
        alone, none = settle_junctions(problem, kp, X[:, [c]])
        assert none == {} and np.array_equal(alone[:, 0], together[:, c], equal_nan=True)
    (error,) = settle_junctions(problem, kp, X[:, [1]])[1].values()
    assert str(error) == str(errors[1])
