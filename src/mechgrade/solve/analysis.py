"""The lambdified pieces of a dynamics problem's analysis (how its instant is reached when
its rates are not given): the energy, the start state, the event, the powers of the reactions.
Work–energy (:mod:`.work_energy`) and integration to an event (:mod:`.events`) read them.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Callable, TypeVar

import numpy as np
import sympy as sp

from ..spec.dynamics import Integration, WorkEnergy, dynamics_of
from ..spec.model import Problem
from ..errors import MechgradeError
from .columns import call
from .junctions import settle_junctions


@dataclass(frozen=True)
class AnalysisPlan:
    """The lambdified energy, start values, event and reaction powers (functions of the
    extended state: state values, then reactions)."""

    energy: Callable
    start: tuple[tuple[int, Callable], ...]
    until: Callable | None
    workless: tuple[tuple[str, Callable], ...]
    until_kinetic: bool = True  # the event reads second rates or reactions


def analysis_plan(kp) -> AnalysisPlan:
    return _analysis_plan(kp)


@lru_cache(maxsize=64)
def _analysis_plan(kp) -> AnalysisPlan:
    symbols = kp.symbols
    kin = kp.kin
    position = {s: i for i, s in enumerate(symbols)}

    def f(expr):
        return sp.lambdify(symbols, expr, modules="numpy", cse=True)

    return AnalysisPlan(
        energy=f(kin.energy),
        start=tuple((position[s], f(value)) for s, value in kin.start),
        until=f(kin.until) if kin.until is not None else None,
        workless=tuple((label, f(expr)) for label, expr in kin.workless),
        until_kinetic=kin.until is not None and bool(
            kin.until.free_symbols & {*kin.k.qdd, *kin.reactions}))


def value_at(fn: Callable, x: np.ndarray) -> float:
    """A lambdified function's first value at the extended state ``x``."""
    with np.errstate(all="ignore"):
        return float(np.asarray(fn(*x), dtype=float).ravel()[0])


def extended(kp, values: np.ndarray) -> np.ndarray:
    """The state values with every reaction 0 after them."""
    return np.concatenate([values, np.zeros(len(kp.kin.reactions))])


def start_values(problem: Problem, kp, ap: AnalysisPlan, values: np.ndarray) -> np.ndarray:
    """``values`` with the coordinates and rates of the start state put in: one column of
    :func:`start_columns`, raising its error."""
    settled, errors = start_columns(problem, kp, ap, values[:, None])
    if errors:
        raise errors[0]
    return settled[:, 0]


def start_columns(problem: Problem, kp, ap: AnalysisPlan, X: np.ndarray
                  ) -> tuple[np.ndarray, dict[int, MechgradeError]]:
    """``X`` (state values, one column each) with the coordinates and rates of the start
    state put in (a massless junction's settled by its balance:
    :func:`~.junctions.settle_junctions`), and the error of each column whose junction does
    not settle."""
    x = np.concatenate([X, np.zeros((len(kp.kin.reactions), X.shape[1]))])
    out = X.copy()
    for i, fn in ap.start:
        out[i] = call(fn, x, 1)[0]
    return settle_junctions(problem, kp, out)


_Kind = TypeVar("_Kind", WorkEnergy, Integration)


def analysis_of(problem: Problem, kind: type[_Kind]) -> _Kind:
    """The problem's analysis, of the kind the solver chose this function for."""
    analysis = dynamics_of(problem).analysis
    assert isinstance(analysis, kind), analysis
    return analysis
