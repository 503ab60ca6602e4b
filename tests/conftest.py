"""Shared test helpers."""

from __future__ import annotations

import hmac
import html
import json
import os
import re
import select
import shutil
import signal
import subprocess
import sys
import time
import uuid
from functools import lru_cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"
DATA = Path(__file__).resolve().parent / "data"
# The LMS importers re-implemented from their source (tests/lms/), imported by module name
sys.path.insert(0, str(Path(__file__).resolve().parent / "lms"))
# Helpers shared by test modules at collection (tests/support/), imported by module name
sys.path.insert(0, str(Path(__file__).resolve().parent / "support"))


@pytest.fixture
def problems_dir() -> Path:
    return PROBLEMS


HEAVY_PROBLEMS = DATA / "heavy_problems.txt"
"""Problems whose library-wide tests are slow end-to-end checks (one name a line, ``#``
comments): the default command leaves them to ``pytest -m slow``, which CI runs too."""


def heavy_problems() -> frozenset[str]:
    lines = (line.split("#", 1)[0].strip()
             for line in HEAVY_PROBLEMS.read_text(encoding="utf-8").splitlines())
    return frozenset(line for line in lines if line)


@pytest.fixture
def heavy_problem_names() -> frozenset[str]:
    return heavy_problems()


FORGETTING = frozenset({"forget", "disk"})
"""Fixtures that forget every derivation the process kept (:func:`_forget`)."""


@lru_cache(maxsize=1)
def _shipped_names() -> frozenset[str]:
    """The shipped problems' names (a parameter may be any string: a file name test's is
    longer than a path may be)."""
    return frozenset(path.stem for path in PROBLEMS.glob("*.yaml"))


def _library_problem(item) -> str | None:
    """The shipped problem a test is parametrized by (its path, or its name), if any."""
    callspec = getattr(item, "callspec", None)
    for value in callspec.params.values() if callspec is not None else ():
        if isinstance(value, Path) and value.parent == PROBLEMS:
            return value.stem
        if isinstance(value, str) and value in _shipped_names():
            return value
    return None


def pytest_collection_modifyitems(items):
    """A test parametrized by a heavy problem (its path, or its name as the tables give it)
    is marked ``slow``: one list decides it for every library-wide test.

    The order is chosen so that a problem is derived in as few xdist workers as may be (each
    worker derives what its own tests need; pytest-xdist's ``worksteal`` hands each worker a
    half of the list, then moves tests from the end of one to the other): the tests of every
    other shipped problem come first, those of the rest just before the end, and the tests
    that forget every derivation kept in memory last (among the others, each would make the
    tests after it in its worker derive their problems again, cold)."""
    heavy = heavy_problems()
    for item in items:
        callspec = getattr(item, "callspec", None)
        if callspec is not None and any(
                (value.stem if isinstance(value, Path) else value) in heavy
                for value in callspec.params.values() if isinstance(value, (Path, str))):
            item.add_marker(pytest.mark.slow)
    halves = {path.stem: index % 2 for index, path in enumerate(sorted(PROBLEMS.glob("*.yaml")))}

    def place(item) -> int:
        if not FORGETTING.isdisjoint(getattr(item, "fixturenames", ())):
            return 3
        problem = _library_problem(item)
        return 1 if problem is None else 2 * halves[problem]
    items.sort(key=place)


@pytest.fixture
def chromium(tmp_path):
    """``chromium(page) -> (dom, log)``: the page's DOM after scripts ran, and the browser log.

    Also leaves a screenshot next to the page (``<page>.png``)."""
    common = [*_browser(tmp_path), "--enable-logging=stderr", "--v=0"]

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


AXE = DATA / "axe" / "axe.min.js"  # axe-core 4.14.1, see tests/data/axe/README.md
WCAG_AA = ("wcag2a", "wcag2aa", "wcag21a", "wcag21aa")
"""axe-core's tags of the WCAG 2.0 and 2.1 success criteria of levels A and AA."""

_AXE_RUN = """<script src="%s"></script>
<script>
axe.run(document, {runOnly: {type: "tag", values: %s}, resultTypes: ["violations"]})
  .then(r => r.violations.map(v => ({id: v.id, help: v.help,
                                     nodes: v.nodes.slice(0, 5).map(n => n.target.join(" "))})),
        e => [{id: "axe-error", help: String(e), nodes: []}])
  .then(found => { const out = document.createElement("pre"); out.id = "axe-violations";
                   out.textContent = JSON.stringify(found); document.body.append(out); });
</script>
"""

_PHONE_PROBE = """<script>
addEventListener("load", () => parent.postMessage(JSON.stringify({
  width: innerWidth, page: document.documentElement.scrollWidth,
  // what reaches past the screen's edge outside any box that scrolls it sideways
  past: [...document.querySelectorAll("body *")].filter(e => {
    const overflow = getComputedStyle(e).overflowX;
    if (e.getBoundingClientRect().right <= innerWidth + 1
        && (overflow !== "visible" || e.scrollWidth <= innerWidth)) return false;
    for (let a = e.parentElement; a; a = a.parentElement)
      if (["auto", "scroll", "hidden"].includes(getComputedStyle(a).overflowX)) return false;
    return true; }).slice(0, 5).map(e => e.tagName.toLowerCase() + (e.id ? "#" + e.id : ""))
}), "*"));
</script>
"""

_PHONE_FRAME = """<!DOCTYPE html><body><iframe src="%s" width="%d" height="800"></iframe>
<script>addEventListener("message", m => { const out = document.createElement("pre");
  out.id = "probe"; out.textContent = m.data; document.body.append(out); });</script></body>
"""


def _with_script(page: Path, script: str, copy: Path) -> Path:
    """A copy of ``page`` with ``script`` run at the end of its body (the page is left as
    it is)."""
    text = page.read_text(encoding="utf-8")
    copy.write_text(text.replace("</body>", script + "</body>") if "</body>" in text
                    else text + script, encoding="utf-8")
    return copy


def _dumped(common: list[str], page: Path, element: str) -> str:
    """The text of the element ``id=element`` that a script of ``page`` appended to it,
    once the page's scripts have run (Chromium's virtual time runs them without waiting)."""
    dom = subprocess.run([*common, "--virtual-time-budget=60000", "--dump-dom", page.as_uri()],
                         capture_output=True, text=True, timeout=180)
    assert dom.returncode == 0, dom.stderr
    found = re.search(rf'<pre id="{element}">(.*?)</pre>', dom.stdout, re.S)
    assert found, f"the page's script left no result: {dom.stderr[-2000:]}"
    return html.unescape(found.group(1))


def _browser(tmp_path: Path) -> list[str]:
    if shutil.which("chromium") is None:
        pytest.skip("chromium is not installed (.ci/run installs it)")
    return ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
            "--disable-background-networking", "--disable-component-update",
            f"--user-data-dir={tmp_path / 'profile'}"]


@pytest.fixture
def in_browser(tmp_path):
    """``in_browser(page, script, element) -> text``: the text a ``<script>`` added to a copy
    of ``page`` puts in the element ``<pre id=element>`` it appends, in headless Chromium."""
    common = _browser(tmp_path)

    def run(page: Path, script: str, element: str) -> str:
        copy = _with_script(page, script, page.with_name(f"probe-{page.name}"))
        try:
            return _dumped(common, copy, element)
        finally:
            copy.unlink()

    return run


@pytest.fixture
def axe(tmp_path):
    """``axe(page) -> violations``: axe-core's WCAG 2.0/2.1 A and AA rules (:data:`WCAG_AA`)
    run on the page in headless Chromium; each violation a dict of its rule ``id``, ``help``
    and the first elements breaking it (``nodes``). Empty for a page that passes."""
    common = _browser(tmp_path)

    def check(page: Path) -> list[dict]:
        script = _AXE_RUN % (AXE.as_uri(), json.dumps(list(WCAG_AA)))
        copy = _with_script(page, script, page.with_name(f"axe-{page.name}"))
        try:
            return json.loads(_dumped(common, copy, "axe-violations"))
        finally:
            copy.unlink()

    return check


@pytest.fixture
def phone(tmp_path):
    """``phone(page, width=375) -> dict``: the page laid out on a screen ``width`` CSS pixels
    wide (in an iframe: headless Chromium's window is never narrower than 500): ``width``,
    ``page`` (how wide the page scrolls) and ``past`` (elements reaching past the screen's
    edge outside a box that scrolls sideways)."""
    common = _browser(tmp_path)

    def lay_out(page: Path, width: int = 375) -> dict:
        copy = _with_script(page, _PHONE_PROBE, page.with_name(f"phone-{page.name}"))
        frame = tmp_path / f"frame-{page.name}"
        frame.write_text(_PHONE_FRAME % (copy.as_uri(), width), encoding="utf-8")
        try:
            return json.loads(_dumped([*common, "--window-size=600,900"], frame, "probe"))
        finally:
            copy.unlink()

    return lay_out


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


class MarkedRun:
    """A command run in a fresh process with a marker of its own in its environment, which
    every process it forks inherits: so the test can find them all, dead parent or not."""

    def __init__(self, argv: list[str], env: dict[str, str] | None = None) -> None:
        self.marker = f"MECHGRADE_TEST_RUN={uuid.uuid4().hex}".encode()
        name, value = self.marker.decode().split("=")
        self.process = subprocess.Popen(argv, stdin=subprocess.DEVNULL,
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                        env={**os.environ, **(env or {}), name: value})

    def pids(self) -> set[int]:
        """The live (not zombie) processes that carry the marker."""
        found = set()
        for entry in os.listdir("/proc"):
            if not entry.isdigit():
                continue
            try:
                with open(f"/proc/{entry}/stat", "rb") as stat:
                    if stat.read().rsplit(b")", 1)[1].split()[0] == b"Z":
                        continue
                with open(f"/proc/{entry}/environ", "rb") as environ:
                    if self.marker in environ.read().split(b"\0"):
                        found.add(int(entry))
            except (OSError, IndexError):
                continue
        return found

    def workers(self) -> set[int]:
        return self.pids() - {self.process.pid}

    def kill(self) -> None:
        """``kill -9`` of the process started (what the OOM killer does)."""
        self.process.kill()
        self.process.wait()

    def survivors(self, seconds: float = 5.0) -> set[int]:
        """The marked processes still alive after up to ``seconds``."""
        deadline = time.monotonic() + seconds
        while (alive := self.pids()) and time.monotonic() < deadline:
            time.sleep(0.05)
        return alive

    def output_closed(self, seconds: float = 5.0) -> bool:
        """Whether the run's stdout and stderr reach end of file within ``seconds`` (no process
        left holds them open)."""
        streams = [self.process.stdout, self.process.stderr]
        deadline = time.monotonic() + seconds
        while streams and time.monotonic() < deadline:
            ready, _, _ = select.select(streams, [], [], max(0.0, deadline - time.monotonic()))
            for stream in ready:
                if not os.read(stream.fileno(), 65536):
                    streams.remove(stream)
        return not streams

    def wait_for(self, condition, seconds: float = 120.0) -> None:
        deadline = time.monotonic() + seconds
        while not condition():
            if time.monotonic() > deadline or self.process.poll() is not None:
                err = self.process.stderr.read().decode() if self.process.poll() is not None \
                    else ""
                raise AssertionError(f"the run never got there (exit {self.process.poll()}) "
                                     f"{err}")
            time.sleep(0.05)

    def clean_up(self) -> None:
        for pid in self.pids():
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass
        if self.process.poll() is None:
            self.process.kill()
        self.process.wait()
        for stream in (self.process.stdout, self.process.stderr):
            stream.close()


@pytest.fixture
def marked_run():
    """``marked_run(argv, env=None) -> MarkedRun``; every process a run left is killed at the
    end of the test (a failing test must not leave workers running on a shared machine)."""
    runs: list[MarkedRun] = []

    def start(argv: list[str], env: dict[str, str] | None = None) -> MarkedRun:
        runs.append(MarkedRun(argv, env))
        return runs[-1]

    yield start
    for run in runs:
        run.clean_up()


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
