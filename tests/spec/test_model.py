"""A problem is a value: equal problems hash alike, and its hash (kept once worked out, since
the solver's caches key on it) never travels to another process."""

from __future__ import annotations

import pickle
from dataclasses import replace

from mechgrade.resources import shipped_dir
from mechgrade.spec import load_problem

PENDULUM = shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"


def test_problems_loaded_twice_are_equal_and_hash_alike():
    a, b = load_problem(PENDULUM), load_problem(PENDULUM)
    assert a == b and hash(a) == hash(b) and hash(a) == hash(a)
    changed = replace(a, consistency=a.consistency * 2)
    assert changed != a and hash(changed) != hash(a)


def test_a_pickled_problem_leaves_its_hash_behind():
    problem = load_problem(PENDULUM)
    hash(problem)
    copy = pickle.loads(pickle.dumps(problem))
    assert "_hash" not in vars(copy)  # str hashes differ between processes
    assert copy == problem and hash(copy) == hash(problem)
