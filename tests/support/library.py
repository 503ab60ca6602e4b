"""The shipped problem library as the tests read it: each problem loaded once per process.

Several test modules parametrize over every problem of the library, which they learn by loading
it while pytest collects them (on every xdist worker): loaded here once, they share the work.
Problems are frozen dataclasses, so a test cannot change what another one reads.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from mechgrade.resources import shipped_dir
from mechgrade.spec import load_problem
from mechgrade.spec.model import Problem


def problem_paths() -> list[Path]:
    """The library's problem files, sorted by name."""
    return sorted(shipped_dir("problems").glob("*.yaml"))


@lru_cache(maxsize=None)
def library_problem(name: str) -> Problem:
    """The library's problem ``name`` (its file's stem), loaded on first use."""
    return load_problem(shipped_dir("problems") / f"{name}.yaml")
