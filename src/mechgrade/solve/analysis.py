"""The lambdified pieces of a dynamics problem's analysis (how its instant is reached when
its rates are not given): the energy, the start state, the event, the powers of the reactions.
Work–energy (:mod:`.work_energy`) and integration to an event (:mod:`.motion`, :mod:`.phases`)
read them.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Callable, Mapping, TypeVar

import numpy as np
import sympy as sp

from ..spec.dynamics import Integration, WorkEnergy, dynamics_of
from ..spec.model import Problem
from ..errors import MechgradeError
from .columns import call
from .generated import lambdified
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
        return lambdified(symbols, expr)

    return AnalysisPlan(
        energy=f(kin.energy),
        start=tuple((position[s], f(value)) for s, value in kin.start),
        until=f(kin.until) if kin.until is not None else None,
        workless=tuple((label, f(expr)) for label, expr in kin.workless),
        until_kinetic=kin.until is not None and bool(
            kin.until.free_symbols & {*kin.k.qdd, *kin.reactions}))


@dataclass(frozen=True)
class ClosedForms:
    """Closed-form roots (an event's times, a ``when``'s positions) as one numpy function of
    the symbols they hold (sorted by name), evaluated in complex numbers: a root may be
    complex, or undefined, at some values, and the values only choose among the roots."""

    symbols: tuple[sp.Symbol, ...]
    function: Callable

    def at(self, numbers: Mapping[sp.Symbol, float]) -> list[complex]:
        """Each root's value where the symbols have ``numbers``.

        >>> a, b = sp.symbols("a b")
        >>> closed_forms((sp.sqrt(a), -b / a, sp.pi)).at({a: -4.0, b: 2.0})
        [2j, (0.5+0j), (3.141592653589793+0j)]
        """
        with np.errstate(all="ignore"):
            return [complex(v) for v in self.function(*(complex(numbers[s])
                                                        for s in self.symbols))]


@lru_cache(maxsize=128)
def closed_forms(roots: tuple) -> ClosedForms:
    """:class:`ClosedForms` of ``roots`` (sympy expressions), made once per tuple of roots."""
    symbols = tuple(sorted(set().union(*(sp.sympify(r).free_symbols for r in roots)), key=str))
    return ClosedForms(symbols, lambdified(symbols, list(roots)))


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
