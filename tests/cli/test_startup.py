"""Start-up: commands import only what they use; the unit registry works without a cache."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import click
import pytest

from mechgrade.cli import main
from mechgrade.cli.common import COMMANDS

HEAVY = ("sympy", "scipy", "numpy", "matplotlib", "jinja2", "pint")

PROBE = """\
import json, sys
from mechgrade.cli import main
try:
    main(sys.argv[1:], prog_name="mechgrade")
except SystemExit:
    pass
print(json.dumps(sorted(m for m in {heavy!r} if m in sys.modules)), file=sys.stderr)
"""


def heavy_modules_after(*args: str, heavy: tuple[str, ...] = HEAVY) -> list[str]:
    """The ``heavy`` libraries imported by running ``mechgrade *args`` in a fresh interpreter."""
    done = subprocess.run([sys.executable, "-c", PROBE.format(heavy=heavy), *args],
                          capture_output=True, text=True, timeout=120)
    return json.loads(done.stderr.strip().splitlines()[-1])


@pytest.mark.parametrize("args", [["--help"], ["export", "--help"], ["report", "--help"],
                                  ["grade", "--help"], ["--version"]])
def test_help_imports_no_heavy_library(args):
    assert heavy_modules_after(*args) == []


def test_export_help_imports_no_exporter_and_no_roster_reader():
    exporters = ("mechgrade.export.canvas", "mechgrade.export.moodle", "mechgrade.export.gradescope",
                 "mechgrade.export.tables", "mechgrade.export.jsonfile", "mechgrade.roster")
    assert heavy_modules_after("export", "--help", heavy=exporters) == []


@pytest.mark.slow
def test_export_and_report_never_import_sympy(tmp_path):
    results = tmp_path / "results.json"
    results.write_text(json.dumps({
        "assignment": {"id": "hw", "title": "HW"}, "objectives": [], "students": [],
        "skipped": [], "notes": [], "internal_errors": []}), encoding="utf-8")
    for args in (["export", str(results), "--format", "grades-csv", "--out",
                  str(tmp_path / "g.csv")],
                 ["report", str(results), "--out", str(tmp_path / "r.html")]):
        assert "sympy" not in heavy_modules_after(*args)
        assert "scipy" not in heavy_modules_after(*args)


@pytest.mark.slow
def test_check_of_a_kinematics_problem_loads_no_solver_of_scipy_and_no_plotting():
    problem = Path(__file__).resolve().parents[2] / "problems" / "bowling_3_15_4_pendulum.yaml"
    # pint imports the top-level scipy package when it is installed; its solvers are the cost
    assert heavy_modules_after("check", str(problem), heavy=(
        "scipy.linalg", "scipy.optimize", "scipy.integrate", "matplotlib", "jinja2")) == []


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_the_group_help_line_is_the_commands_own(name):
    command = main.get_command(click.Context(main), name)
    assert command is not None and command.name == name
    assert COMMANDS[name][1] == command.get_short_help_str(limit=1000)


def test_group_help_lists_every_command_as_click_would():
    lazy = main.get_help(click.Context(main, info_name="mechgrade"))
    for name in COMMANDS:
        main.get_command(click.Context(main), name)  # now every command is loaded
    loaded = main.get_help(click.Context(main, info_name="mechgrade"))
    assert lazy == loaded
    assert all(name in lazy for name in COMMANDS)


def test_an_unknown_command_is_refused():
    result = subprocess.run([sys.executable, "-m", "mechgrade", "nosuch"], capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 2 and "No such command 'nosuch'" in result.stderr


def test_units_work_when_no_cache_folder_can_be_made(tmp_path):
    blocker = tmp_path / "not_a_folder"
    blocker.write_text("x", encoding="utf-8")
    code = "from mechgrade.units import to_si; print(to_si(1, 'ft'))"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60, env={"XDG_CACHE_HOME": str(blocker / "cache"),
                                           "HOME": str(blocker), "PATH": "/usr/bin:/bin"})
    assert done.returncode == 0, done.stderr
    assert float(done.stdout) == pytest.approx(0.3048)
