"""Shared test helpers."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"
DATA = Path(__file__).resolve().parent / "data"


@pytest.fixture
def problems_dir() -> Path:
    return PROBLEMS


@pytest.fixture
def chromium(tmp_path):
    """``chromium(page) -> (dom, log)``: the page's DOM after scripts ran, and the browser log.

    Also leaves a screenshot next to the page (``<page>.png``)."""
    if shutil.which("chromium") is None:
        pytest.skip("chromium is not installed (.ci/run installs it)")
    common = ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
              "--disable-background-networking", "--disable-component-update",
              "--enable-logging=stderr", "--v=0", f"--user-data-dir={tmp_path / 'profile'}"]

    def open_page(page: Path) -> tuple[str, str]:
        dom = subprocess.run([*common, "--dump-dom", page.as_uri()], capture_output=True,
                             text=True, timeout=120)
        assert dom.returncode == 0, dom.stderr
        shot = page.with_suffix(".png")
        subprocess.run([*common, f"--screenshot={shot}", "--window-size=1200,2000",
                        page.as_uri()], capture_output=True, timeout=120, check=True)
        assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        return dom.stdout, dom.stderr

    return open_page
