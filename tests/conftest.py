"""Shared test helpers."""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"
DATA = Path(__file__).resolve().parent / "data"


@pytest.fixture
def problems_dir() -> Path:
    return PROBLEMS
