"""A problem's catalogue entry: how it is analysed (from its model), its answers, the variants
it draws, and a fault for a file that does not load."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.resources import shipped_dir
from mechgrade.grade.catalog import Approach, analyses, catalog_entries, catalog_entry
from mechgrade.spec import load_problem

DATA = Path(__file__).resolve().parents[1] / "data" / "catalog"


@pytest.mark.parametrize("problem, expected", [
    ("bowling_3_15_4_pendulum", ["KINEMATICS"]),
    ("atwood_machine", ["INSTANT"]),
    ("ruina_9_20_ladder_energy", ["WORK_ENERGY"]),
    ("block_slides_on_cart", ["INTEGRATION"]),
    ("rod_struck_on_ice", ["IMPACT"]),
    ("flywheel_speed_drop", ["INTEGRATION", "DESIGN"]),
    ("two_mass_spring_chain", ["INSTANT", "VIBRATION"]),
])
def test_the_analysis_comes_from_the_model(problem, expected):
    found = analyses(load_problem(shipped_dir("problems") / f"{problem}.yaml"))
    assert [a.name for a in found] == expected


def test_an_entry_has_the_statement_tags_answers_and_the_variants_drawn():
    entry = catalog_entry(DATA / "mixed" / "pendulum_variants.yaml")
    assert (entry.id, entry.tags, entry.analyses) == (
        "pendulum_variants", ("circular-motion", "particle-kinematics"), (Approach.KINEMATICS,))
    assert [(o.id, o.answer) for o in entry.objectives] == [
        ("speed", "8 ft/s"), ("acc_mag", "37.7359 ft/s^2"),
        ("acc_N", "(-37.7128, 1.32051, 0) ft/s^2 in frame N")]
    assert [d.key for d in entry.variants] == ["L", "theta", "theta'", "theta''"]
    # the statement is shown with the problem's own givens, not {L}
    assert entry.statement.startswith("A rigid pendulum of length 2 ft turns about a fixed pin")
    assert entry.requires == ("theta'' > 0.2*theta'^2",)
    assert entry.worked.picture.startswith("<svg") and entry.failures == ()


def test_an_objective_the_givens_leave_free_is_listed_as_not_solved():
    entry = catalog_entry(DATA / "unsolved" / "free_rate.yaml")
    assert [o.id for o in entry.failures] == ["speed"]
    assert "is not determined by the givens: give a value for theta'" in entry.failures[0].answer
    assert entry.objectives[0].answer == "(1.73205, 1, 0) m in frame N"


def test_a_file_that_does_not_load_is_a_fault_and_the_others_are_still_entries():
    entries, faults = catalog_entries(sorted((DATA / "mixed").glob("*.yaml")))
    assert [e.id for e in entries] == ["pendulum_variants"]
    assert [(Path(f.file).name, f.message) for f in faults] == [(
        "broken.yaml", f"{DATA / 'mixed' / 'broken.yaml'}:7:15: frames.A.parent: unknown parent "
                       "frame 'NN'; did you mean 'N'? (expected one of: N, A)")]
