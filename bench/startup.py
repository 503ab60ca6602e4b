"""Start-up time of the CLI next to ``python -c "import click"`` (median of several runs).

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


def median_seconds(command: list[str], runs: int) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main(runs: int) -> None:
    python = sys.executable
    script = Path(python).with_name("mechgrade")  # the installed command, as users run it
    mechgrade = [str(script)] if script.exists() else [python, "-m", "mechgrade"]
    commands = {
        "mechgrade --help": mechgrade + ["--help"],
        "mechgrade export --help": mechgrade + ["export", "--help"],
        "mechgrade report --help": mechgrade + ["report", "--help"],
        f"mechgrade check {PROBLEM.name}": mechgrade + ["check", str(PROBLEM)],
    }
    median_seconds([python, "-c", "import click"], 2)  # warm the file cache
    floor = median_seconds([python, "-c", "import click"], runs)
    label = 'python -c "import click"'
    print(f"{label:<52} {floor * 1000:7.0f} ms")
    for label, command in commands.items():
        seconds = median_seconds(command, runs)
        print(f"{label:<52} {seconds * 1000:7.0f} ms  {seconds / floor:5.1f}x")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
