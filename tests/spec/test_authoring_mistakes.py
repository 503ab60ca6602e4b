"""Every authoring mistake in tests/data/authoring_mistakes/ gives its exact message from
`mechgrade check` (errors fail the run, warnings are printed); none passes silently."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.yamlio import read_yaml

FOLDER = Path(__file__).resolve().parents[1] / "data" / "authoring_mistakes"
EXPECTED = read_yaml(FOLDER / "expected.yaml").data
FILES = sorted(FOLDER.glob("load_*.yaml"))


def test_every_mistake_file_has_its_expected_output():
    assert len(FILES) >= 24
    assert sorted(EXPECTED) == [f.name for f in FILES]


@pytest.mark.parametrize("path", FILES, ids=[f.stem for f in FILES])
def test_check_prints_the_exact_message(path):
    result = CliRunner().invoke(main, ["check", str(path)])
    expected = EXPECTED[path.name]
    assert result.output.splitlines() == [line.replace("{file}", str(path))
                                          for line in expected["output"]]
    assert result.exit_code == expected["exit"]


@pytest.mark.parametrize("path", FILES, ids=[f.stem for f in FILES])
def test_no_mistake_passes_silently(path):
    output = EXPECTED[path.name]["output"]
    failed = EXPECTED[path.name]["exit"] == 1 and output[0].startswith("FAIL")
    warned = any(": warning: " in line for line in output)
    assert failed or warned
