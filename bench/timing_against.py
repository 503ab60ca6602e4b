"""Compare ``bench/solve_timing.py`` of this tree with another checkout's, problem by problem.

Each round runs, for one problem, the other checkout's bench (its own venv and sources) and
this tree's, the other first in one round and this tree first in the next, in fresh processes
that count process CPU time (not wall time: the machine is shared), and takes the ratio
this/other of every column; the table gives the median of the rounds' ratios. Both sides read
the same problem file (the other checkout's by default, so a problem edited since is timed as it
was).

Run: .venv/bin/python bench/timing_against.py /work/wt/perf-base [--rounds 3] [problems ...]
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
COLUMNS = ("cold", "eval", "symbolic", "mistakes")
# solve_timing.py's own clock becomes the process' CPU time
WRAPPER = ("import sys, time, runpy; time.perf_counter = time.process_time; "
           "sys.argv = sys.argv[1:]; runpy.run_path(sys.argv[0], run_name='__main__')")
ROW = re.compile(r"^(\S+)\s+(\d+) ms\s+([\d.na]+) ms\s+(\d+) ms(?:\s+(\d+) ms)?\s*$")


def figures(tree: Path, problem: Path) -> dict[str, float]:
    """One run of ``tree``'s bench on ``problem``: its columns in ms (absent ones left out)."""
    env = dict(os.environ, PYTHONPATH=str(tree / "src"), MECHGRADE_NO_CACHE="1",
               OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    out = subprocess.run([str(tree / ".venv/bin/python"), "-c", WRAPPER,
                          str(tree / "bench/solve_timing.py"), str(problem)],
                         cwd=tree, env=env, capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        match = ROW.match(line)
        if match and match.group(1) != "median":
            values = [match.group(i) for i in range(2, 6)]
            return {c: float(v) for c, v in zip(COLUMNS, values) if v not in (None, "nan")}
    raise RuntimeError(f"{tree}: no figures for {problem}:\n{out}")


def paired(other: Path, problem: Path, turn: int) -> tuple[dict[str, float], dict[str, float]]:
    """One round: ``(other's figures, this tree's)``, the other first in even turns, this tree
    first in odd ones (so that neither side always runs on a machine the first has warmed)."""
    if turn % 2:
        mine = figures(ROOT, problem)
        return figures(other, problem), mine
    return figures(other, problem), figures(ROOT, problem)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("other", type=Path)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("problems", nargs="*", type=Path)
    args = parser.parse_intermixed_args()
    problems = args.problems or sorted((args.other / "problems").glob("*.yaml"))
    print(f"{'problem':34s} " + " ".join(f"{c:>18s}" for c in COLUMNS)
          + "   (other ms -> this ms, ratio: median of rounds)")
    for problem in problems:
        problem = problem.resolve()
        try:
            rounds = [paired(args.other, problem, turn) for turn in range(args.rounds)]
        except subprocess.CalledProcessError as failed:
            # one side's bench cannot time this problem (an older tree's bench, or a problem it
            # cannot solve): say so and time the others
            print(f"{problem.stem:34s} not timed: the bench of {Path(failed.cmd[3]).parents[1]} failed", flush=True)
            continue
        cells = []
        for c in COLUMNS:
            pairs = [(o[c], t[c]) for o, t in rounds if c in o and c in t and o[c] > 0]
            if not pairs:
                cells.append(f"{'':>18s}")
                continue
            ratio = statistics.median(t / o for o, t in pairs)
            cells.append(f"{statistics.median(o for o, _ in pairs):6.0f}"
                         f"{statistics.median(t for _, t in pairs):6.0f} {ratio:5.2f}")
        print(f"{problem.stem:34s} " + " ".join(cells), flush=True)


if __name__ == "__main__":
    sys.exit(main())
