"""`mechgrade solve` and `mechgrade check` as a user runs them: exact text and exit codes."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from mechgrade.cli import main

ROOT = Path(__file__).resolve().parents[2]
PENDULUM = str(ROOT / "problems" / "bowling_3_15_4_pendulum.yaml")
BASE = (ROOT / "tests" / "data" / "spec" / "base.yaml").read_text()


def run(*args):
    return CliRunner().invoke(main, list(args))


def test_solve_prints_each_objective_with_its_unit():
    result = run("solve", PENDULUM)
    assert result.exit_code == 0
    assert result.output.splitlines() == [
        "bowling_3_15_4_pendulum: Acceleration of a pendulum tip",
        "  acc_mag           98.5089 ft/s^2",
        "  acc_N             (-89.8705, -40.3397, 0) ft/s^2 in N",
        "  acc_A             (-98, 10, 0) ft/s^2 in A",
        "  acc_mag_symbolic  L*sqrt(thetad**4 + thetadd**2)   [ft/s^2; in L, thetad, thetadd]",
        "State at the instant",
        "  theta = 30 deg",
        "  L = 2 ft",
        "  theta' = 7 rad / s",
        "  theta'' = 5 rad / s ** 2",
    ]


def test_solve_json_is_the_documented_contract():
    result = run("solve", PENDULUM, "--format", "json")
    assert result.exit_code == 0
    data = json.loads(result.output)
    assert data["problem"] == "bowling_3_15_4_pendulum"
    assert data["objectives"]["acc_N"]["frame"] == "N"
    assert data["objectives"]["acc_N"]["unit"] == "ft/s^2"
    assert len(data["objectives"]["acc_N"]["value"]) == 3
    assert data["objectives"]["acc_mag"]["expr"] is None
    assert data["failures"] == {} and data["warnings"] == []
    assert {"name": "theta", "value": 30.0, "unit": "deg", "given": True} in data["state"]
    assert data["objectives"]["acc_mag_symbolic"] == {
        "value": None, "unit": "ft/s^2", "frame": None,
        "expr": "L*sqrt(thetad**4 + thetadd**2)"}
    for entry in data["objectives"].values():
        assert set(entry) == {"value", "unit", "frame", "expr"}


def test_solve_steps_follow_the_write_up_order():
    result = run("solve", PENDULUM, "--steps")
    assert result.exit_code == 0
    sections = [line for line in result.output.splitlines() if line and not line[0].isspace()]
    assert sections[1:] == ["Frames", "Points", "Coordinates", "Parameters", "Constraints",
                            "Degrees of freedom", "Velocities", "Accelerations",
                            "Objectives", "State at the instant"]
    assert "  N_V_A = L*thetad*A.y" in result.output


def test_check_passes_a_good_file():
    result = run("check", PENDULUM)
    assert result.exit_code == 0
    assert result.output.splitlines()[-1] == "1 file(s), 0 failing"


def test_bad_problem_file_gives_one_message_and_exit_2(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(BASE.replace("position: L*A.x", "position: L*Q.x"))
    result = run("solve", str(bad))
    assert result.exit_code == 2
    assert result.output == (f"{bad}:8:26: points.P.position: unknown frame 'Q' in 'Q.x' "
                             "(frames: N, A)\n")


def test_missing_problem_file_exit_2(tmp_path):
    result = run("solve", str(tmp_path / "nope.yaml"))
    assert result.exit_code == 2
    assert result.output.endswith("nope.yaml: expected a problem file (YAML), found no such file\n")
    assert "Traceback" not in result.output


def test_check_reports_a_failing_expect_and_exits_1(tmp_path):
    bad = tmp_path / "base.yaml"
    bad.write_text(BASE.replace("{value: 6}", "{value: 7}"))
    result = run("check", str(bad))
    assert result.exit_code == 1
    assert result.output.splitlines() == [
        f"FAIL {bad} (1 tests, DOF 1)",
        "  FAIL speed: 6 != expected 7 m/s (±0.5, from the digits written)",
        "1 file(s), 1 failing",
    ]


def test_check_reports_a_broken_file_among_good_ones(tmp_path):
    (tmp_path / "good.yaml").write_text(BASE.replace("id: base", "id: good"))
    (tmp_path / "broken.yaml").write_text(BASE.replace("  theta': 3 rad/s\n", "")
                                          .replace("id: base", "id: broken"))
    result = run("check", str(tmp_path))
    assert result.exit_code == 1
    assert result.output.splitlines() == [
        f"FAIL {tmp_path / 'broken.yaml'}",
        f"  {tmp_path / 'broken.yaml'}:18:5: objectives[0]: objective 'speed' is not determined "
        "by the givens: "
        "give a value for theta' (velocity level)",
        f"ok   {tmp_path / 'good.yaml'} (1 tests, DOF 1)",
        "2 file(s), 1 failing",
    ]


def test_check_of_an_empty_folder_exit_2(tmp_path):
    result = run("check", str(tmp_path))
    assert result.exit_code == 2
    assert result.output == f"expected problem files (*.yaml), found none in {tmp_path}\n"


def test_check_lists_every_error_of_a_file_and_its_warnings(tmp_path):
    bad = tmp_path / "three.yaml"
    bad.write_text(BASE.replace("parent: N", "parent: NN").replace("L: 2 m", "L: 2 s")
                   .replace("kind: scalar", "kind: scalr"))
    unsolvable = tmp_path / "unsolvable.yaml"
    unsolvable.write_text(BASE.replace("  theta': 3 rad/s\n", ""))
    result = run("check", str(tmp_path))
    assert result.exit_code == 1
    assert result.output.splitlines() == [
        f"FAIL {bad}",
        f"  {bad}:6:15: frames.A.parent: unknown parent frame 'NN'; did you mean 'N'? (expected "
        "one of: N, A)",
        f"  {bad}:15:6: givens.L: dimension mismatch in the value of 'L': expected a length "
        "([length]), found a time ([time])",
        f"  {bad}:22:11: objectives[0].kind: expected one of scalar, vector, symbolic, found "
        "'scalr'; did you mean 'scalar'?",
        f"FAIL {unsolvable}",
        f"  {unsolvable}:18:5: objectives[0]: objective 'speed' is not determined by the "
        "givens: give a value for theta' (velocity level)",
        f"  {unsolvable}:1:5: id: warning: id 'base' differs from the file name 'unsolvable'; "
        "expected them equal (rename the file or write id: unsolvable)",
        "2 file(s), 2 failing",
    ]


def test_solve_json_lists_failures_beside_the_answers_and_exits_2():
    path = ROOT / "tests" / "data" / "authoring_mistakes" / "solve_one_objective_fails.yaml"
    result = CliRunner().invoke(main, ["solve", str(path), "--format", "json"])
    assert result.exit_code == 2
    data = json.loads(result.output)
    assert data["objectives"]["speed"]["value"] == 6.0
    assert list(data["failures"]) == ["accel"]
    assert data["failures"]["accel"].endswith("give a value for theta'' (acceleration level)")


def test_check_reports_a_failing_objective_beside_the_passing_ones_and_the_state():
    path = ROOT / "tests" / "data" / "authoring_mistakes" / "solve_one_objective_fails.yaml"
    result = CliRunner().invoke(main, ["check", "-v", str(path)])
    assert result.exit_code == 1
    assert result.output.splitlines() == [
        f"FAIL {path} (1 tests, DOF 1)",
        "  pass speed: 6 ~ expected 6 m/s",
        f"  {path}:28:5: objectives[1]: objective 'accel' is not determined by the givens: give "
        "a value for theta'' (acceleration level)",
        "  state at the instant: theta = 30 deg; L = 2 m; theta' = 3 rad / s",
        "1 file(s), 1 failing",
    ]


def test_a_bug_is_one_line_and_exit_3_never_a_traceback(monkeypatch):
    import mechgrade.cli.solve as solve_cli

    def broken(path):
        raise KeyError("body")

    monkeypatch.setattr(solve_cli, "load_problem", broken)
    result = CliRunner().invoke(main, ["solve", "problems/bowling_3_15_4_pendulum.yaml"])
    assert result.exit_code == 3
    assert result.stderr == ("internal error: KeyError: 'body'; please report it with the "
                             "command and files that caused it (set MECHGRADE_DEBUG=1 for the "
                             "traceback)\n")


# ---------------------------------------------------------------------------- the solver's cache


def with_cache(folder, **settings):
    return {"MECHGRADE_NO_CACHE": None, "MECHGRADE_CACHE_DIR": str(folder), **settings}


@pytest.mark.parametrize("command", ["check", "solve"])
def test_a_cache_folder_others_may_write_is_one_warning_and_the_command_runs(command, tmp_path):
    shared = tmp_path / "shared"
    shared.mkdir()
    shared.chmod(0o777)
    result = CliRunner().invoke(main, [command, PENDULUM], env=with_cache(shared))
    assert result.exit_code == 0, result.output
    assert result.stderr == (
        f"warning: cache folder {shared} may be written by other users (mode 777): not using "
        f"the cache in this run (make it private with 'chmod 700 {shared}', or set "
        "MECHGRADE_CACHE_DIR to a private folder)\n")
    assert list(shared.iterdir()) == []


@pytest.mark.parametrize("value", ["nan", "inf", "1e308", "-1", "abc"])
def test_a_cache_size_that_is_not_a_number_of_megabytes_is_one_message_and_exit_2(
        value, tmp_path):
    result = CliRunner().invoke(main, ["check", PENDULUM],
                                env=with_cache(tmp_path / "c", MECHGRADE_CACHE_MAX_MB=value))
    assert result.exit_code == 2
    assert result.stderr == (
        f"MECHGRADE_CACHE_MAX_MB: expected a number of megabytes from 0 to 1000000, found "
        f"{value!r}; set it to a number such as 200, or unset it for the default (200)\n")
    assert result.stdout == ""


def test_a_relative_cache_folder_is_one_message_and_exit_2():
    result = CliRunner().invoke(main, ["solve", PENDULUM], env=with_cache("rel/cache"))
    assert result.exit_code == 2
    assert result.stderr.startswith("MECHGRADE_CACHE_DIR: expected an absolute path to a "
                                    "folder, found 'rel/cache'; write it in full (")
