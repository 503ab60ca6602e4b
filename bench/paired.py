"""Sides of a comparison timed in rounds, as the benches that compare judge them.

A round times every side once, each on inputs of its own (``draw(count, round)``, called
untimed; a draw gives inputs no earlier call has seen), the order of the sides turning round
by round, so that other load on the machine falls on every side alike. A side's figure
against the first side is the median of the per-round ratios (min and max show the spread a
loaded machine gives). Sides also give the ratio of CPU time, which a loaded machine disturbs
less than the wall clock: the process's own, or what a side's ``clock`` counts (a side that
hands its work to other processes counts theirs too).
"""

from __future__ import annotations

import statistics
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence, Union


@dataclass(frozen=True)
class Run:
    """One side's call in one round: its wall and process CPU seconds, inputs and outputs."""

    wall: float
    cpu: float
    batch: Any
    out: Any


Side = Union[tuple[str, Callable], tuple[str, Callable, Callable[[], float]]]
"""A side's label, its function of a batch and, optionally, the clock of the CPU seconds it
uses (default: this process's, ``time.process_time``)."""


def timed(func: Callable, batch, clock: Callable[[], float] = time.process_time) -> Run:
    """``func(batch)`` timed."""
    wall, cpu = time.perf_counter(), clock()
    out = func(batch)
    return Run(time.perf_counter() - wall, clock() - cpu, batch, out)


def in_rounds(sides: Sequence[Side], draw: Callable[[int, int], Any],
              count: int, rounds: int) -> dict[str, list[Run]]:
    """Every side's runs, ``rounds`` rounds of ``count`` inputs a side."""
    runs: dict[str, list[Run]] = {side[0]: [] for side in sides}
    for round_ in range(rounds):
        turn = round_ % len(sides)
        for label, func, *clock in [*sides[turn:], *sides[:turn]]:
            runs[label].append(timed(func, draw(count, round_), *clock))
    return runs


def cpu_of(pids: Iterable[int]) -> float:
    """The CPU seconds processes ``pids`` have used so far (Linux's ``/proc``)."""
    return sum(int(Path(f"/proc/{pid}/schedstat").read_text().split()[0]) for pid in pids) / 1e9


def against(base: list[Run], runs: list[Run], cpu: bool = False) -> str:
    """The median of the per-round ratios base / this (wall, or process CPU), and their
    range."""
    ratios = sorted((b.cpu / r.cpu) if cpu else (b.wall / r.wall) for b, r in zip(base, runs))
    return f"{statistics.median(ratios):6.1f}x ({ratios[0]:.1f}-{ratios[-1]:.1f})"


def per_item_ms(runs: list[Run], count: int) -> float:
    """The median wall time of one input, in milliseconds."""
    return 1000 * statistics.median(r.wall for r in runs) / count
