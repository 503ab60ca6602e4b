"""``mechgrade check --watch``: re-check on save with the solved values, stop cleanly."""

from __future__ import annotations

import threading
import time
import types

import pytest
from click.testing import CliRunner

import mechgrade.check
from mechgrade.cli import main
from mechgrade.spec.starter import write_starter

REAL_SLEEP = time.sleep

RUN_1 = """\
ok   {path} (3 tests, DOF 1)
  pass vel_C: (1, 0, 0) ~ expected (1.000, 0, 0) m/s in frame N
  pass vel_top: (2, 0, 0) ~ expected (2.000, 0, 0) m/s in frame N
  pass acc_contact: (0, 5, 0) ~ expected (0, 5.000, 0) m/s^2 in frame N
  state at the instant: x = 0 m; theta = 0 deg; R = 0.2 m; x' = 1 m/s   (solved); \
theta' = -5 rad / s; x'' = 0 m/s^2   (solved); theta'' = 0 rad / s ** 2
  solved values:
    vel_C        (1, 0, 0) m/s in frame N
    vel_top      (2, 0, 0) m/s in frame N
    acc_contact  (0, 5, 0) m/s^2 in frame N
"""

RUN_2 = """\
FAIL {path} (3 tests, DOF 1)
  FAIL vel_C: (1.2, 0, 0) != expected (1.000, 0, 0) m/s in frame N
  FAIL vel_top: (2.4, 0, 0) != expected (2.000, 0, 0) m/s in frame N
  FAIL acc_contact: (0, 7.2, 0) != expected (0, 5.000, 0) m/s^2 in frame N
  state at the instant: x = 0 m; theta = 0 deg; R = 0.2 m; x' = 1.2 m/s   (solved); \
theta' = -6 rad / s; x'' = 0 m/s^2   (solved); theta'' = 0 rad / s ** 2
  solved values:
    vel_C        (1.2, 0, 0) m/s in frame N
    vel_top      (2.4, 0, 0) m/s in frame N
    acc_contact  (0, 7.2, 0) m/s^2 in frame N
"""


@pytest.fixture
def spec(tmp_path):
    return write_starter("disk", "rolling", tmp_path)


def patch_sleep(monkeypatch, sleep):
    """Replace the watcher's pause between looks (only in mechgrade.check); a watch that
    never sees the change is stopped after about 30 s instead of hanging the suite."""
    calls = iter(range(600))

    def bounded(seconds):
        if next(calls, None) is None:
            raise KeyboardInterrupt
        sleep(seconds)

    monkeypatch.setattr(mechgrade.check, "time", types.SimpleNamespace(sleep=bounded))


def watch(*args):
    return CliRunner().invoke(main, ["check", "--watch", *args, "--interval", "0.05"])


def test_a_save_is_rechecked_with_its_solved_values(spec, monkeypatch):
    looked = threading.Event()

    def sleep(seconds):
        looked.set()  # the first look is done: a change now is a save to report
        REAL_SLEEP(seconds)

    def editor():
        looked.wait(timeout=60)
        text = spec.read_text(encoding="utf-8")
        spec.write_text(text.replace("theta': -5 rad/s", "theta': -6 rad/s"), encoding="utf-8")

    patch_sleep(monkeypatch, sleep)
    thread = threading.Thread(target=editor)
    thread.start()
    result = watch(str(spec), "--max-runs", "2")
    thread.join()
    assert result.output == (RUN_1.format(path=spec)
                             + f"-- run 1 done; watching {spec} (Ctrl-C to stop)\n"
                             + RUN_2.format(path=spec) + "stopped after 2 run(s)\n")
    assert result.exit_code == 0


def test_only_the_changed_file_is_rechecked(spec, monkeypatch):
    other = write_starter("plate", "rigid-body", spec.parent)
    looked = threading.Event()

    def sleep(seconds):
        looked.set()
        REAL_SLEEP(seconds)

    def editor():
        looked.wait(timeout=60)
        spec.write_text(spec.read_text(encoding="utf-8") + "# edited\n", encoding="utf-8")

    patch_sleep(monkeypatch, sleep)
    thread = threading.Thread(target=editor)
    thread.start()
    result = watch(str(spec.parent), "--max-runs", "2")
    thread.join()
    second = result.output.split("(Ctrl-C to stop)\n")[1]
    assert second == RUN_1.format(path=spec) + "stopped after 2 run(s)\n"
    assert str(other) in result.output.split("(Ctrl-C to stop)\n")[0]


def test_ctrl_c_stops_cleanly_with_exit_0(spec, monkeypatch):
    def interrupt(seconds):
        raise KeyboardInterrupt

    patch_sleep(monkeypatch, interrupt)
    result = watch(str(spec))
    assert result.output == (RUN_1.format(path=spec)
                             + f"-- run 1 done; watching {spec} (Ctrl-C to stop)\n\n"
                             + "stopped after 1 run(s)\n")
    assert result.exit_code == 0


def test_a_failing_spec_is_shown_not_an_exit(spec):
    spec.write_text(spec.read_text(encoding="utf-8").replace("0.2 m", "0.24 m"), encoding="utf-8")
    result = watch(str(spec), "--max-runs", "1")
    assert result.output.startswith(f"FAIL {spec} (3 tests, DOF 1)\n")
    assert result.output.endswith("stopped after 1 run(s)\n")
    assert result.exit_code == 0


def test_watching_nothing_is_bad_input(tmp_path):
    result = watch(str(tmp_path))
    assert result.output == f"expected problem files (*.yaml), found none in {tmp_path}\n"
    assert result.exit_code == 2


def test_max_runs_must_be_positive(spec):
    result = watch(str(spec), "--max-runs", "0")
    assert result.exit_code == 2
    assert "0 is not in the range x>=1" in result.output


def test_watch_options_without_watch_are_a_usage_error(spec):
    result = CliRunner().invoke(main, ["check", str(spec), "--max-runs", "2"])
    assert result.exit_code == 2
    assert "Error: --max-runs and --interval need --watch" in result.output
