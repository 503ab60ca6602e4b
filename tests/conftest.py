"""Shared test helpers."""

from __future__ import annotations

import hmac
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"
DATA = Path(__file__).resolve().parent / "data"
# The LMS importers re-implemented from their source (tests/lms/), imported by module name
sys.path.insert(0, str(Path(__file__).resolve().parent / "lms"))


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


def _forget() -> None:
    """Forget every derivation and plan kept in memory (the solver's and the mechanics')."""
    for name, module in list(sys.modules.items()):
        if name.startswith(("mechgrade.mechanics", "mechgrade.solve")):
            for value in list(vars(module).values()):
                if callable(getattr(value, "cache_clear", None)):
                    value.cache_clear()


@pytest.fixture
def forget():
    """A function that forgets every derivation kept in memory: what a fresh process knows."""
    return _forget


@pytest.fixture
def disk(tmp_path, monkeypatch) -> Path:
    """The disk cache on, in a folder of this test's own (the suite runs with it off)."""
    monkeypatch.delenv("MECHGRADE_NO_CACHE", raising=False)
    monkeypatch.setenv("MECHGRADE_CACHE_DIR", str(tmp_path / "cache"))
    _forget()
    yield tmp_path / "cache"
    _forget()


@pytest.fixture
def twice(tmp_path):
    """Run a Python script in two fresh processes that share a disk cache of their own (what
    the first writes, the second reads); return their outputs."""
    def run(script: str) -> list[str]:
        env = {k: v for k, v in os.environ.items() if k != "MECHGRADE_NO_CACHE"}
        env["MECHGRADE_CACHE_DIR"] = str(tmp_path / "shared-cache")
        return [subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                               env=env, check=True).stdout.strip() for _ in range(2)]
    return run


@pytest.fixture
def entry_file(disk):
    """``entry_file(key)``: where the disk cache of :func:`disk` keeps the entry ``key``."""
    return lambda key: disk / "entries" / f"{key}.json"


def _rewrite_entry(path: Path, edit, *, signed: bool = False) -> None:
    head, body = path.read_bytes().split(b"\n", 1)
    body = json.dumps(edit(json.loads(body)), separators=(",", ":")).encode()
    if signed:
        secret = (path.parent / "key").read_bytes()
        head = hmac.new(secret, path.stem.encode() + b"\n" + body, "sha256").hexdigest().encode()
    path.write_bytes(head + b"\n" + body)


@pytest.fixture
def rewrite_entry():
    """``rewrite_entry(path, edit, signed=False)``: rewrite the data of the disk-cache entry
    at ``path`` with ``edit(data) -> data``, as someone who may write the folder but cannot
    read its key would (the entry's first line, its HMAC, kept as it was), or ``signed``
    again with the folder's key (someone who can)."""
    return _rewrite_entry
