"""Every dynamics authoring slip in tests/data/authoring_mistakes/dyn_*.yaml ends in a refusal
or a warning, located and with the fix, printed alike by ``check``, ``solve`` and ``grade``
(never a plain wrong key). Each file's header says ``# refused``, ``# warned`` or ``# refused
by check`` (a tolerance only the solved answer shows too tight: ``solve`` and ``grade`` print
it, and grading never applies it) and the line ``check`` prints (``# expect:``; ``{file}``
stands for the file's path)."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from mechgrade.cli import main

DATA = Path(__file__).resolve().parents[1] / "data" / "authoring_mistakes"
FILES = sorted(DATA.glob("dyn_*.yaml"))
SLOW = ("dyn_junction_several_roots", "dyn_junction_start_off_balance")
"""Slips found at an integration's start, after its derivation (about 2 s each): ``pytest -m
slow`` runs them."""
PARAMS = [pytest.param(p, id=p.stem, marks=[pytest.mark.slow] if p.stem in SLOW else [])
          for p in FILES]


def header(path: Path) -> tuple[str, str]:
    lines = path.read_text().splitlines()
    assert lines[1] in ("# refused", "# warned", "# refused by check"), path.name
    assert lines[2].startswith("# expect: "), path.name
    return lines[1][2:], lines[2][len("# expect: "):].replace("{file}", str(path))


def run(*args) -> tuple[int, str]:
    result = CliRunner().invoke(main, [*map(str, args)])
    assert "Traceback" not in result.output
    return result.exit_code, result.output


def test_every_slip_class_has_a_fixture():
    assert len(FILES) >= 25
    assert sum(header(p)[0] == "warned" for p in FILES) == 3  # the implausible magnitudes


@pytest.mark.parametrize("path", PARAMS)
def test_check_prints_the_located_message_with_its_fix(path):
    outcome, message = header(path)
    code, output = run("check", path)
    assert f"  {message}" in output.splitlines(), output
    assert code == (0 if outcome == "warned" else 1)


@pytest.mark.parametrize("path", PARAMS)
def test_solve_prints_it_too(path):
    outcome, message = header(path)
    code, output = run("solve", path)
    assert any(line.endswith(message) for line in output.splitlines()), output
    assert (code != 0) == (outcome == "refused")


@pytest.mark.parametrize("path", [p for p in FILES if p.stem in (
    "dyn_contact_lost", "dyn_weight_twice", "dyn_tolerance_rel_zero", "dyn_g_in_feet",
    "dyn_mass_in_grams", "dyn_tolerance_below_accuracy")], ids=lambda p: p.stem)
def test_grade_prints_it_too(path, tmp_path):
    outcome, message = header(path)
    (tmp_path / "hw.yaml").write_text(f"id: hw\ntitle: HW\nproblems: ['{path}']\n")
    (tmp_path / "subs").mkdir()
    (tmp_path / "subs" / "ann.txt").write_text(f"{path.stem}.none = 1\n")
    code, output = run("grade", tmp_path / "hw.yaml", tmp_path / "subs", "--out",
                       tmp_path / "out", "--jobs", "1")
    assert any(line.strip().endswith(message) for line in output.splitlines()), output
    assert code == (2 if outcome == "refused" else 0)
