"""Start-up time of the CLI next to ``python -c "import click"`` (median of several rounds).

``check`` is timed three ways: warm (the solver's disk cache filled by an earlier run: no
sympy), cold (an empty cache: derived with sympy, then written) and with the cache off. Every
run uses a cache folder of its own, never the user's. Loading the spec alone (its imports
and the file, no solve) is shown beside them: what a check without a kept report needs at
least (a warm check reads its report back instead).

Run: ``.venv/bin/python bench/startup.py [runs]`` (default 7 runs of each command).
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PROBLEM = ROOT / "problems" / "bowling_3_15_4_pendulum.yaml"


def seconds(command: list[str], env: dict[str, str] | None = None) -> float:
    start = time.perf_counter()
    subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True,
                   env=env)
    return time.perf_counter() - start


def environment(**variables: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()
           if k not in ("MECHGRADE_CACHE_DIR", "MECHGRADE_NO_CACHE")}
    return {**env, **variables}


def main(runs: int) -> None:
    python = sys.executable
    script = Path(python).with_name("mechgrade")  # the installed command, as users run it
    mechgrade = [str(script)] if script.exists() else [python, "-m", "mechgrade"]
    floor = [python, "-c", "import click"]
    check = mechgrade + ["check", str(PROBLEM)]
    root = tempfile.TemporaryDirectory(prefix="mechgrade-bench-")
    warm = os.path.join(root.name, "warm")
    colds = (os.path.join(root.name, f"cold-{n}") for n in range(10**6))
    off = environment(MECHGRADE_NO_CACHE="1")
    commands = {
        "mechgrade --help": (mechgrade + ["--help"], off),
        "mechgrade export --help": (mechgrade + ["export", "--help"], off),
        "mechgrade report --help": (mechgrade + ["report", "--help"], off),
        # the least a check that loads the spec needs: its imports and the loading
        f"load_problem({PROBLEM.name}) alone": (
            [python, "-c", "import click\nfrom mechgrade.spec import load_problem\n"
                           f"load_problem({str(PROBLEM)!r})"], off),
        f"mechgrade check {PROBLEM.name} (warm cache)":
            (check, environment(MECHGRADE_CACHE_DIR=warm)),
        f"mechgrade check {PROBLEM.name} (cold cache)": (check, None),
        f"mechgrade check {PROBLEM.name} (cache off)": (check, off),
    }
    seconds(floor)  # warm the file cache
    seconds(check, environment(MECHGRADE_CACHE_DIR=warm))  # fill the warm cache
    # Round robin (floor and each command in a pair, the pair's order turning round by round),
    # so that other load on the machine falls on every command alike; each ratio is the median
    # of the per-round ratios.
    times: dict[str, list[float]] = {"floor": [], **{label: [] for label in commands}}
    for turn in range(runs):
        for label, (command, env) in commands.items():
            if env is None:  # cold: an empty cache folder every time
                env = environment(MECHGRADE_CACHE_DIR=next(colds))
            if turn % 2:
                times[label].append(seconds(command, env))
                times["floor"].append(seconds(floor))
            else:
                times["floor"].append(seconds(floor))
                times[label].append(seconds(command, env))
    root.cleanup()
    floors = times["floor"]
    label = 'python -c "import click"'
    print(f"{label:<60} {statistics.median(floors) * 1000:7.0f} ms")
    for index, label in enumerate(commands):
        mine = times[label]
        ratios = [t / floors[round_ * len(commands) + index] for round_, t in enumerate(mine)]
        print(f"{label:<60} {statistics.median(mine) * 1000:7.0f} ms  "
              f"{statistics.median(ratios):5.1f}x")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
