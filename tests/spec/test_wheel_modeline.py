"""Every shipped spec names the schema on its first line, in the repository and in the wheel
(where hatch_build.py rewrites the line for the wheel's layout: specs in mechgrade/problems and
mechgrade/examples, the schema in mechgrade/spec)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from mechgrade.spec.load import SCHEMA_PATH

ROOT = Path(__file__).resolve().parents[2]
MODELINE = "# yaml-language-server: $schema="
SPECS = sorted(p for folder in ("problems", "examples") for p in (ROOT / folder).rglob("*.yaml")
               if p.read_text(encoding="utf-8").startswith(MODELINE))
PACKAGE = SCHEMA_PATH.parents[1]  # mechgrade/ in the wheel: spec/, problems/, examples/


def hook():
    spec = importlib.util.spec_from_file_location("hatch_build", ROOT / "hatch_build.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def target(text: str, folder: Path) -> Path:
    return (folder / text.splitlines()[0][len(MODELINE):]).resolve()


@pytest.mark.parametrize("path", SPECS, ids=[p.stem for p in SPECS])
def test_a_shipped_spec_names_the_schema_in_the_repository_and_in_the_wheel(path):
    text = path.read_text(encoding="utf-8")
    relative = path.relative_to(ROOT)
    assert target(text, path.parent) == SCHEMA_PATH.resolve()
    in_wheel = hook().wheel_modeline(text, len(relative.parts) - 1)
    assert target(in_wheel, (PACKAGE / relative).parent) == SCHEMA_PATH.resolve()
    assert in_wheel.splitlines()[1:] == text.splitlines()[1:]


def test_a_spec_without_a_modeline_ships_unchanged():
    assert hook().wheel_modeline("id: p\n", 1) == "id: p\n"
