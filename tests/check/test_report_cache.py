"""A file checked again unchanged has its report read back from the disk cache: the same
report, without loading or solving it; a changed file, or a spoilt entry, is checked again."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mechgrade.check import check_problem, report_data, report_from

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
    assert report_from(json.loads(json.dumps(report_data(checked)))) == checked


def test_a_changed_file_is_checked_again(disk, tmp_path):
    spec = tmp_path / "pendulum.yaml"
    text = (PROBLEMS / "bowling_3_15_4_pendulum.yaml").read_text()
    spec.write_text(text)
    assert check_problem(spec).passed
    assert "98.51" in text
    spec.write_text(text.replace("98.51", "98.61"))
    assert not check_problem(spec).passed


def test_a_spoilt_report_entry_is_checked_again(disk, forget):
    path = FILES[0]
    right = check_problem(path)
    for entry in disk.glob("*.json"):
        data = json.loads(entry.read_text())
        if isinstance(data["data"], dict) and "outcomes" in data["data"]:
            data["data"]["outcomes"] = [["x", "yes"]]
            entry.write_text(json.dumps(data))
    forget()
    assert check_problem(path) == right


def test_a_warm_check_loads_no_units_schema_or_sympy(twice):
    runs = twice("import sys\n"
                 "from mechgrade.check import check_problem\n"
                 f"assert check_problem({str(FILES[0])!r}).passed\n"
                 "print(sorted({m.split('.')[0] for m in sys.modules} & "
                 "{'sympy', 'pint', 'jsonschema', 'scipy'}))\n")
    assert "'pint'" in runs[0] and "'sympy'" in runs[0]  # cold: loaded and derived
    assert runs[1] == "[]"
