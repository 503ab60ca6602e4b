"""Variants from the command line: handout, check --variants, grade and gradescope on hw2."""

from __future__ import annotations

import csv
import html
import json
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from mechgrade.cli import main

ROOT = Path(__file__).resolve().parents[2]
HW2 = ROOT / "examples" / "hw2_variants"
DATA = ROOT / "tests" / "data" / "variants"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_handout_writes_each_students_sheet_and_the_givens_table(tmp_path):
    result = run("handout", HW2 / "assignment.yaml", "--roster", HW2 / "roster.csv",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    assert result.output == \
        f"Wrote 4 sheets, 4 answer files and givens.csv to {tmp_path}/ (13 files)\n"
    table = list(csv.DictReader((tmp_path / "givens.csv").open(encoding="utf-8")))
    assert [row["id"] for row in table] == ["20001", "20002", "20003", "20004"]
    for row in table:
        sheet = (tmp_path / f"{row['id']}.md").read_text(encoding="utf-8")
        html = (tmp_path / f"{row['id']}.html").read_text(encoding="utf-8")
        length = f"{row['pendulum_variants.L']} {row['pendulum_variants.L unit']}"
        assert f"A rigid pendulum of length {length} turns" in sheet
        assert f"A rigid pendulum of length {length} turns" in html
        assert f"For **{row['name']}** (id {row['id']})" in sheet
        assert "Answer key `pendulum_variants.acc_mag`" in sheet
        assert "\npendulum_variants.acc_mag =\n" in \
            (tmp_path / f"{row['id']}.txt").read_text(encoding="utf-8")
    assert len({row["pendulum_variants.L"] + row["pendulum_variants.theta'"]
                for row in table}) == 4


def test_the_handout_numbers_are_the_ones_graded(tmp_path):
    run("handout", HW2 / "assignment.yaml", "--roster", HW2 / "roster.csv", "--out",
        tmp_path / "sheets")
    run("grade", HW2 / "assignment.yaml", HW2 / "submissions", "--roster",
        HW2 / "roster.csv", "--out", tmp_path / "out", "--jobs", "1")
    table = {row["id"]: row for row in
             csv.DictReader((tmp_path / "sheets" / "givens.csv").open(encoding="utf-8"))}
    results = json.loads((tmp_path / "out" / "results.json").read_text(encoding="utf-8"))
    for student in results["students"]:
        row = table[student["identity"]["id"]]
        assert {g["name"]: g["value"] for g in student["variant"]["givens"]} == {
            name: float(row[f"pendulum_variants.{name}"])
            for name in ("L", "theta", "theta'", "theta''")}


def test_grading_hw2_end_to_end_records_givens_and_flags_the_neighbours_numbers(tmp_path):
    result = run("grade", HW2 / "assignment.yaml", HW2 / "submissions", "--roster",
                 HW2 / "roster.csv", "--out", tmp_path, "--jobs", "1")
    assert result.exit_code == 0, result.output
    grades = {row["id"]: row["total"] for row in
              csv.DictReader((tmp_path / "grades.csv").open(encoding="utf-8"))}
    assert grades == {"20001": "8", "20002": "2", "20003": "4", "20004": "0"}
    rows = list(csv.DictReader((tmp_path / "results.csv").open(encoding="utf-8")))
    assert rows[0]["seed"] == "engr201-fall2026"
    assert rows[0]["givens"] == ("L = 3.9 ft; theta = 40 deg; theta' = 4.4 rad/s; "
                                 "theta'' = 15 rad/s^2")
    blocks = [r for r in rows if r["problem"] == "bowling_3_15_8_connected_blocks"]
    assert {r["givens"] for r in blocks} == {""}
    ben = [r for r in rows if r["student"] == "20002" and r["problem"] == "pendulum_variants"]
    assert {r["diagnosis"] for r in ben} == {"fits another variant's givens"}
    page = html.unescape((tmp_path / "feedback" / "ben_okafor.html").read_text(encoding="utf-8"))
    assert "Your numbers" in page and "L = 3.4 ft" in page
    assert "fits another variant's givens, not yours" in page


@pytest.mark.slow
def test_check_verifies_variants_and_fails_on_a_planted_degenerate_range():
    result = run("check", DATA / "degenerate_range.yaml", "--variants", "30")
    assert result.exit_code == 1
    lines = result.output.splitlines()
    assert lines[0].startswith("FAIL ") and lines[0].endswith("degenerate_range.yaml (0 tests, DOF 1)")
    assert lines[1].startswith("  FAIL variant for student 1 (a = 0.2 m, theta = 90 deg): "
                               "degenerate configuration: points O and A coincide")
    assert lines[-2].endswith("variants refused (set redraw: true in the assignment to draw "
                              "again, or narrow the ranges / add require:)")
    assert run("check", DATA / "degenerate_range.yaml", "--variants", "0").exit_code == 0


def test_check_passes_the_example_with_the_default_200_variants():
    result = run("check", HW2 / "pendulum_variants.yaml")
    assert result.exit_code == 0, result.output


def test_gradescope_grades_the_variant_of_the_student_id_in_the_metadata(tmp_path):
    ana = HW2 / "submissions" / "ana_silva"
    outcomes = {}
    for sid in ("20001", "20002"):
        folder = tmp_path / sid
        shutil.copytree(ana, folder / "sub")
        (folder / "meta.json").write_text(json.dumps({"users": [{"name": "X", "sid": sid}]}))
        result = run("gradescope", HW2 / "assignment.yaml", "--submission", folder / "sub",
                     "--results", folder / "results.json", "--metadata", folder / "meta.json")
        assert result.exit_code == 0, result.output
        outcomes[sid] = json.loads((folder / "results.json").read_text())["score"]
    # Ana's answers are right for Ana's variant (20001) only
    assert outcomes == {"20001": 8.0, "20002": 2.0}


def test_a_handout_for_a_smaller_roster_removes_and_lists_the_sheets_of_the_others(tmp_path):
    out = tmp_path / "sheets"
    assert run("handout", HW2 / "assignment.yaml", "--roster", HW2 / "roster.csv", "--out",
               out).exit_code == 0
    roster = tmp_path / "roster.csv"
    lines = (HW2 / "roster.csv").read_text(encoding="utf-8").splitlines()
    roster.write_text("\n".join(lines[:3]) + "\n", encoding="utf-8")  # 20001 and 20002
    (out / "instructions.txt").write_text("print double-sided\n", encoding="utf-8")
    result = run("handout", HW2 / "assignment.yaml", "--roster", roster, "--out", out)
    assert result.exit_code == 0, result.output
    assert result.output.splitlines() == [
        f"Wrote 2 sheets, 2 answer files and givens.csv to {out}/ (7 files)",
        "Removed from the previous run (not written by this one):",
        "  20003.html", "  20003.md", "  20003.txt", "  20004.html", "  20004.md", "  20004.txt",
        "Kept (not written by mechgrade):", "  instructions.txt"]
    assert sorted(p.name for p in out.iterdir()) == [
        "20001.html", "20001.md", "20001.txt", "20002.html", "20002.md", "20002.txt",
        "givens.csv", "instructions.txt", "manifest.json"]
    manifest = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    assert manifest["command"] == "mechgrade handout"
    roles = [i["role"] for i in manifest["inputs"]]
    assert roles[0] == "assignment" and set(roles[1:-1]) == {"problem"} and roles[-1] == "roster"
