"""Sides of a comparison timed in rounds, as the benches that compare judge them.

A round times every side once, each on inputs of its own (``draw(count, round)``, called
untimed; a draw gives inputs no earlier call has seen), the order of the sides turning round
by round, so that other load on the machine falls on every side alike. A side's figure
against the first side is the median of the per-round ratios (min and max show the spread a
loaded machine gives). In-process sides also give the ratio of process CPU time, which a
loaded machine disturbs less than the wall clock.
"""

from __future__ import annotations

import statistics
import time
from dataclasses import dataclass
from typing import Any, Callable, Sequence


@dataclass(frozen=True)
class Run:
    """One side's call in one round: its wall and process CPU seconds, inputs and outputs."""

    wall: float
    cpu: float
    batch: Any
    out: Any


def timed(func: Callable, batch) -> Run:
    """``func(batch)`` timed."""
    wall, cpu = time.perf_counter(), time.process_time()
    out = func(batch)
    return Run(time.perf_counter() - wall, time.process_time() - cpu, batch, out)


def in_rounds(sides: Sequence[tuple[str, Callable]], draw: Callable[[int, int], Any],
              count: int, rounds: int) -> dict[str, list[Run]]:
    """Every side's runs, ``rounds`` rounds of ``count`` inputs a side."""
    runs: dict[str, list[Run]] = {label: [] for label, _ in sides}
    for round_ in range(rounds):
        turn = round_ % len(sides)
        for label, side in [*sides[turn:], *sides[:turn]]:
            runs[label].append(timed(side, draw(count, round_)))
    return runs


def against(base: list[Run], runs: list[Run], cpu: bool = False) -> str:
    """The median of the per-round ratios base / this (wall, or process CPU), and their
    range."""
    ratios = sorted((b.cpu / r.cpu) if cpu else (b.wall / r.wall) for b, r in zip(base, runs))
    return f"{statistics.median(ratios):6.1f}x ({ratios[0]:.1f}-{ratios[-1]:.1f})"


def per_item_ms(runs: list[Run], count: int) -> float:
    """The median wall time of one input, in milliseconds."""
    return 1000 * statistics.median(r.wall for r in runs) / count
