"""Where a problem's parts are written: kept for the problem object itself, so problems equal
but read from other places keep their own."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from mechgrade.mechanics.kinematics import locations
from mechgrade.spec import load_problem_text

PENDULUM = Path(__file__).resolve().parents[2] / "problems" / "bowling_3_15_4_pendulum.yaml"


def test_equal_problems_read_from_other_places_keep_their_own_locations():
    here = load_problem_text(PENDULUM.read_text(), "p.yaml")
    there = replace(here, path="q.yaml")
    assert here == there
    assert locations(here)[0] == "p.yaml" and locations(there)[0] == "q.yaml"
    assert locations(here) is locations(here)  # kept, not rebuilt
