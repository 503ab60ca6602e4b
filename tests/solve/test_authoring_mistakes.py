"""Authoring mistakes a solver must not answer silently: each file in
tests/data/authoring_mistakes/solve_*.yaml records, in its header, the exit code of
``mechgrade solve`` (``# exit:``) and every line the output must contain (``# expect:``;
``{file}`` stands for the file's path)."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from mechgrade.cli import main

DATA = Path(__file__).resolve().parents[1] / "data" / "authoring_mistakes"
FILES = sorted(DATA.glob("solve_*.yaml"))


def header(path: Path) -> tuple[int, list[str]]:
    code, expected = None, []
    for line in path.read_text().splitlines():
        if line.startswith("# exit: "):
            code = int(line[len("# exit: "):])
        elif line.startswith("# expect: "):
            expected.append(line[len("# expect: "):].replace("{file}", str(path)))
    return code, expected


def test_every_mistake_file_records_its_outcome():
    assert len(FILES) >= 18
    for path in FILES:
        code, expected = header(path)
        assert code is not None and expected, path.name


@pytest.mark.parametrize("path", FILES, ids=[p.stem for p in FILES])
def test_solve_reports_the_recorded_outcome(path):
    code, expected = header(path)
    result = CliRunner().invoke(main, ["solve", str(path)])
    assert "Traceback" not in result.output
    lines = result.output.splitlines()
    for line in expected:
        assert line in lines, f"{line!r} not in output:\n{result.output}"
    assert result.exit_code == code
