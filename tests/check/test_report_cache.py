"""A file checked again unchanged has its report read back from the disk cache: the same
report, without loading or solving it; a changed file, or a spoilt entry, is checked again."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mechgrade.check import CheckReport, check_problem
from mechgrade.codec import decode, encode

ROOT = Path(__file__).resolve().parents[2]
PROBLEMS = ROOT / "problems"
FILES = [PROBLEMS / "bowling_3_15_4_pendulum.yaml", PROBLEMS / "ruina_10_3_spiral_bug.yaml",
         PROBLEMS / "ladder_wall_lift_off.yaml", ROOT / "tests" / "data" / "spec" / "bad_unit.yaml",
         ROOT / "tests" / "data" / "variants" / "degenerate_range.yaml"]


@pytest.mark.parametrize("path", FILES, ids=[f.stem for f in FILES])
def test_a_report_read_back_is_the_report_checked(path, disk, monkeypatch, forget):
    monkeypatch.setenv("MECHGRADE_NO_CACHE", "1")
    checked = check_problem(path)
    monkeypatch.delenv("MECHGRADE_NO_CACHE")
    forget()
    assert check_problem(path) == checked  # checked, then written
    forget()
    assert check_problem(path) == checked  # read back
    assert decode(CheckReport, json.loads(json.dumps(encode(checked)))) == checked


def test_a_changed_file_is_checked_again(disk, tmp_path):
    spec = tmp_path / "pendulum.yaml"
    text = (PROBLEMS / "bowling_3_15_4_pendulum.yaml").read_text()
    spec.write_text(text)
    assert check_problem(spec).passed
    assert "98.51" in text
    spec.write_text(text.replace("98.51", "98.61"))
    assert not check_problem(spec).passed


def report_entries(disk):
    for entry in (disk / "entries").glob("*.json"):
        data = json.loads(entry.read_bytes().split(b"\n", 1)[1])
        if isinstance(data, dict) and "outcomes" in data:
            yield entry


def test_a_spoilt_report_entry_is_checked_again(disk, forget, rewrite_entry):
    # signed with the folder's key: read as far as the codec, which refuses it
    path = FILES[0]
    right = check_problem(path)
    for entry in report_entries(disk):
        rewrite_entry(entry, lambda data: {**data, "outcomes": [["x", "yes"]]}, signed=True)
    forget()
    assert check_problem(path) == right


def test_a_report_flipped_to_passed_is_not_trusted(disk, tmp_path, rewrite_entry):
    spec = tmp_path / "pendulum.yaml"
    spec.write_text(FILES[0].read_text().replace("98.51", "98.61"))
    failing = check_problem(spec)
    assert not failing.passed
    flipped = 0
    for entry in report_entries(disk):
        rewrite_entry(entry, lambda data: {**data, "outcomes": [
            {**outcome, "passed": True} for outcome in data["outcomes"]]})
        flipped += 1
    assert flipped == 1
    assert check_problem(spec) == failing


@pytest.mark.slow
def test_a_warm_check_loads_no_units_schema_or_sympy(twice):
    runs = twice("import sys\n"
                 "from mechgrade.check import check_problem\n"
                 f"assert check_problem({str(FILES[0])!r}).passed\n"
                 "print(sorted({m.split('.')[0] for m in sys.modules} & "
                 "{'sympy', 'pint', 'jsonschema', 'scipy'}))\n")
    assert "'pint'" in runs[0] and "'sympy'" in runs[0]  # cold: loaded and derived
    assert runs[1] == "[]"
