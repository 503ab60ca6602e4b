"""`mechgrade gradescope` grades one submission and always leaves a results.json."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

from click.testing import CliRunner

from mechgrade.cli import main

ROOT = Path(__file__).resolve().parents[2]
ASSIGNMENT = ROOT / "examples" / "hw1" / "assignment.yaml"
ADA = ROOT / "examples" / "hw1" / "submissions" / "ada_lovelace"


def run(tmp_path, assignment=ASSIGNMENT, submission=None):
    results = tmp_path / "results.json"
    args = ["gradescope", str(assignment), "--submission", str(submission or tmp_path / "sub"),
            "--results", str(results), "--metadata", str(tmp_path / "meta.json")]
    outcome = CliRunner().invoke(main, args)
    data = json.loads(results.read_text()) if results.exists() else None
    return outcome, data


def test_a_submission_is_graded_into_gradescope_results(tmp_path):
    shutil.copytree(ADA, tmp_path / "sub")
    (tmp_path / "meta.json").write_text(json.dumps({"users": [{"name": "Ada Lovelace",
                                                                "sid": "10001"}]}))
    outcome, data = run(tmp_path)
    assert outcome.exit_code == 0
    assert outcome.output == f"10001: 19 / 19 points; wrote {tmp_path / 'results.json'}\n"
    assert data["score"] == 19.0
    assert len(data["tests"]) == 8
    assert {t["status"] for t in data["tests"]} == {"passed"}
    for test in data["tests"]:
        assert isinstance(test["score"], float) and isinstance(test["max_score"], float)
        assert set(test) == {"name", "number", "score", "max_score", "status", "output",
                             "visibility"}


def test_an_empty_upload_scores_zero_and_says_so(tmp_path):
    (tmp_path / "sub").mkdir()
    outcome, data = run(tmp_path)
    assert outcome.exit_code == 0
    assert data["score"] == 0.0
    assert "No submission was found." in data["output"]
    assert {t["status"] for t in data["tests"]} == {"failed"}


def test_a_broken_assignment_still_writes_results_and_exits_2(tmp_path):
    broken = tmp_path / "hw.yaml"
    broken.write_text("id: hw\ntitle: HW\nproblems: 3\n")
    outcome, data = run(tmp_path, assignment=broken)
    assert outcome.exit_code == 2
    assert "hw.yaml" in outcome.output and "Traceback" not in outcome.output
    assert data["score"] == 0.0 and data["tests"] == []
    assert data["output"].startswith("The autograder could not grade this submission: ")


def run_with(tmp_path, *extra):
    results = tmp_path / "results.json"
    args = ["gradescope", str(ASSIGNMENT), "--submission", str(tmp_path / "sub"),
            "--results", str(results), "--metadata", str(tmp_path / "meta.json"), *extra]
    outcome = CliRunner().invoke(main, args)
    return outcome, json.loads(results.read_text())


def test_visibility_option_reaches_the_results_and_every_test(tmp_path):
    shutil.copytree(ADA, tmp_path / "sub")
    outcome, data = run_with(tmp_path, "--visibility", "after_due_date")
    assert outcome.exit_code == 0
    assert data["visibility"] == "after_due_date"
    assert {t["visibility"] for t in data["tests"]} == {"after_due_date"}


def test_a_broken_assignment_keeps_the_chosen_visibility(tmp_path):
    broken = tmp_path / "hw.yaml"
    broken.write_text("id: hw\ntitle: HW\nproblems: 3\n")
    args = ["gradescope", str(broken), "--submission", str(tmp_path / "sub"), "--results",
            str(tmp_path / "r.json"), "--metadata", str(tmp_path / "m.json"),
            "--visibility", "hidden"]
    assert CliRunner().invoke(main, args).exit_code == 2
    assert json.loads((tmp_path / "r.json").read_text())["visibility"] == "hidden"


def test_an_unknown_visibility_is_refused(tmp_path):
    outcome = CliRunner().invoke(main, ["gradescope", str(ASSIGNMENT), "--visibility", "public"])
    assert outcome.exit_code == 2 and "'public' is not one of" in outcome.output


def expected_lines(data) -> dict[str, list[str]]:
    return {t["name"].split(":")[0]: [line for line in t["output"].splitlines()
                                      if line.startswith("Expected: ")] for t in data["tests"]}


def test_an_empty_upload_is_never_shown_the_expected_answers(tmp_path):
    (tmp_path / "sub").mkdir()
    _, data = run_with(tmp_path)
    assert all(lines == [] for lines in expected_lines(data).values())
    assert "Expected" not in json.dumps(data)


def test_expected_answers_are_shown_only_for_the_objectives_answered(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "answers.txt").write_text(
        "bowling_3_15_4_pendulum.acc_mag = 1 ft/s^2\n"
        "bowling_3_15_8_connected_blocks.xdot =   \n")
    _, data = run_with(tmp_path)
    shown = {name for name, lines in expected_lines(data).items() if lines}
    assert shown == {"bowling_3_15_4_pendulum/acc_mag"}


def zip_of(path, members: dict[str, bytes]) -> None:
    import zipfile
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in members.items():
            archive.writestr(name, data)


def test_a_zipped_folder_is_found_and_the_file_read_is_reported(tmp_path):
    (tmp_path / "sub").mkdir()
    zip_of(tmp_path / "sub" / "hw1.zip",
           {"hw1/answers.yaml": (ADA / "answers.yaml").read_bytes(),
            "__MACOSX/hw1/._answers.yaml": b"\0\0junk"})
    outcome, data = run_with(tmp_path)
    assert outcome.exit_code == 0
    assert outcome.output == (f"submission: 19 / 19 points (read hw1.zip/hw1/answers.yaml); "
                              f"wrote {tmp_path / 'results.json'}\n")
    assert data["score"] == 19.0
    assert "read 'hw1.zip/hw1/answers.yaml' as the answers file" in data["output"].splitlines()


def test_a_renamed_single_file_is_read_and_named(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "my_answers.txt").write_bytes(
        (ROOT / "examples/hw1/submissions/bob_roe/answers.txt").read_bytes())
    outcome, data = run_with(tmp_path)
    assert outcome.output.startswith("submission: 14 / 19 points (read my_answers.txt); ")
    assert "read 'my_answers.txt' as the answers file" in data["output"]
