from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.export import read_results
from mechgrade.roster import read_roster

DATA = Path(__file__).parent.parent / "data" / "export"


@pytest.fixture
def report():
    return read_results(DATA / "results.json")


@pytest.fixture
def canvas_roster():
    return read_roster(DATA / "canvas_gradebook.csv")


@pytest.fixture
def moodle_roster():
    return read_roster(DATA / "moodle_grades.csv")
