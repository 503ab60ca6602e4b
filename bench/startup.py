"""Start-up time of the CLI next to ``python -c "import click"`` (median of several rounds).

Run: ``.venv/bin/python bench/startup.py [runs]`` (default 7 runs of each command).
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PROBLEM = ROOT / "problems" / "bowling_3_15_4_pendulum.yaml"


def seconds(command: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    return time.perf_counter() - start


def main(runs: int) -> None:
    python = sys.executable
    script = Path(python).with_name("mechgrade")  # the installed command, as users run it
    mechgrade = [str(script)] if script.exists() else [python, "-m", "mechgrade"]
    floor = [python, "-c", "import click"]
    commands = {
        "mechgrade --help": mechgrade + ["--help"],
        "mechgrade export --help": mechgrade + ["export", "--help"],
        "mechgrade report --help": mechgrade + ["report", "--help"],
        f"mechgrade check {PROBLEM.name}": mechgrade + ["check", str(PROBLEM)],
    }
    seconds(floor)  # warm the file cache
    # Round robin (floor, each command, floor, ...), so that other load on the machine falls on
    # every command alike; each ratio is the median of the per-round ratios.
    times: dict[str, list[float]] = {"floor": [], **{label: [] for label in commands}}
    for _ in range(runs):
        for label, command in commands.items():
            times["floor"].append(seconds(floor))
            times[label].append(seconds(command))
    floors = times["floor"]
    label = 'python -c "import click"'
    print(f"{label:<52} {statistics.median(floors) * 1000:7.0f} ms")
    for index, label in enumerate(commands):
        mine = times[label]
        ratios = [t / floors[round_ * len(commands) + index] for round_, t in enumerate(mine)]
        print(f"{label:<52} {statistics.median(mine) * 1000:7.0f} ms  "
              f"{statistics.median(ratios):5.1f}x")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
