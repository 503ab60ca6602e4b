"""``mechgrade grade`` on examples/hw4_derivation, as an instructor runs it: free-body diagrams,
equations of motion and the steps of a write-up (tests/data/hw4_derivation_verdicts.json holds
each answer judged by hand; tests/grade/test_run_diagrams.py checks the grader agrees)."""

from __future__ import annotations

import csv
import html
import json

import pytest
from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.resources import shipped_dir

HW4 = shipped_dir("examples") / "hw4_derivation"


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    out = tmp_path_factory.mktemp("hw4") / "out"
    result = CliRunner().invoke(main, ["grade", str(HW4 / "assignment.yaml"),
                                       str(HW4 / "submissions"), "--out", str(out), "--jobs", "1"])
    return result, out


@pytest.mark.slow  # grades fourteen students' derivations, with error carried forward
def test_grading_hw4_writes_the_steps_the_loads_and_the_equations(graded):
    result, out = graded
    assert result.exit_code == 0, result.output
    assert result.stdout == (f"Graded 14 students (1 unreadable answer, 0 missing "
                             f"submissions); wrote {out.as_posix()}/\n")
    data = json.loads((out / "results.json").read_text(encoding="utf-8"))
    carla = next(s for s in data["students"] if s["id"] == "carla")
    pin = next(a for a in carla["answers"] if a["objective"] == "pin_force")
    assert (pin["verdict"], pin["diagnosis"], pin["first_wrong_step"]) == (
        "correct", "error carried forward", "omega")
    noor = next(s for s in data["students"] if s["id"] == "noor")
    pin = next(a for a in noor["answers"] if a["objective"] == "pin_force")
    assert (pin["verdict"], pin["diagnosis"], pin["feedback"]) == (
        "correct", "error carried forward",
        "Error carried forward: this answer follows correctly from your answer to alpha (used "
        "in place of the balance that gives theta'') and earns 100% of the points. The first "
        "wrong step of your write-up is step 2, 'alpha'.")
    with open(out / "results.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    mia = {(r["problem"], r["objective"]): r for r in rows if r["student"] == "mia"}
    assert mia["atwood_machine", "equations"]["feedback"] == (
        "m1*ydd = T: does not hold for the motion (the weight of block1 is missing from it).")
    page = html.unescape((out / "feedback" / "carla.html").read_text(encoding="utf-8"))
    # the page writes the step's symbol as a textbook does (results.csv keeps its key, omega)
    assert "The first wrong step of your write-up is step 1, 'ω'." in page
