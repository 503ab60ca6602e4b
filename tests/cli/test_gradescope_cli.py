"""`mechgrade gradescope` grades one submission and always leaves a results.json."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import textwrap
import zipfile
from pathlib import Path

import pytest
from click.testing import CliRunner
from gradescope_results import check_results, student_view

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
    check_results(data)  # Gradescope's specification (tests/lms/gradescope_results.py)
    receipt, *graded = data["tests"]
    assert receipt["name"] == "Submission received" and "Score: 19 / 19 points" in \
        receipt["output"]
    assert len(graded) == 8 + 8  # a test per objective, then its expected answer
    assert {t["status"] for t in graded[:8]} == {"passed"}
    for test in graded[:8]:
        assert isinstance(test["score"], float) and isinstance(test["max_score"], float)
        assert set(test) == {"name", "number", "score", "max_score", "status", "output",
                             "visibility"}
    assert {t["visibility"] for t in graded[8:]} == {"after_due_date"}


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


@pytest.mark.parametrize("metadata, message", [
    ('{"users": {"sid": "1"}}', "users: expected a list of users, found a mapping"),
    ('{"users": [5]}', "users[0]: expected a user (a mapping with sid, email, name), found a "
                       "whole number"),
    ('[{"sid": "1"}]', "expected a mapping (Gradescope's submission metadata), found a list"),
    ('{"users": [{"sid": ["1"]}]}', "users[0].sid: expected text or a whole number, found a "
                                    "list"),
    ('{"users": [{"sid": NaN}]}', "users[0].sid: expected a finite number, found NaN"),
    ('{"users": [{"sid": 1' + "0" * 4999 + '}]}',
     "users[0].sid: expected a finite number, found 100000000000...0000 (5000 characters), "
     "longer than 400 characters"),
    ('{"users": [' + "[" * 100_000, "1:110: expected JSON nested at most 100 levels deep, "
                                    "found deeper nesting"),
    ('{"users": [', "1:12: expected JSON, found invalid JSON: Expecting value"),
    (None, "expected Gradescope's submission metadata (JSON), found a FIFO (named pipe), not a "
           "regular file"),
])
def test_unreadable_metadata_still_writes_results_saying_why(tmp_path, metadata, message):
    # The metadata names the student, whose id decides the variant graded: a guess would
    # grade another student's numbers, so the run stops, and Gradescope shows why.
    shutil.copytree(ADA, tmp_path / "sub")
    meta = tmp_path / "meta.json"
    if metadata is None:
        os.mkfifo(meta)
    else:
        meta.write_text(metadata)
    outcome, data = run(tmp_path)
    located = f"{meta}:{message}" if message[0].isdigit() else f"{meta}: {message}"
    assert outcome.exit_code == 2
    assert outcome.output == located + "\n"
    assert data == {"score": 0.0, "output": "The autograder could not grade this submission: "
                                            + located, "output_format": "text",
                    "visibility": "visible", "tests": []}


def test_without_metadata_the_submission_is_graded_as_submission(tmp_path):
    shutil.copytree(ADA, tmp_path / "sub")
    outcome, data = run(tmp_path)
    assert outcome.exit_code == 0
    assert outcome.output == f"submission: 19 / 19 points; wrote {tmp_path / 'results.json'}\n"
    assert data["score"] == 19.0


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
    assert {t["visibility"] for t in data["tests"][1:]} == {"after_due_date"}
    assert data["tests"][0]["visibility"] == "visible"  # what was read, shown at once


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


def test_an_empty_upload_is_never_shown_the_expected_answers_before_the_due_date(tmp_path):
    (tmp_path / "sub").mkdir()
    _, data = run_with(tmp_path)
    before = student_view(data)  # what the student sees (tests/lms/gradescope_results.py)
    assert "Expected" not in before.text()
    assert "No submission was found." in before.tests[0]["output"]
    # and never after it either: the grader keeps no expected answer for what was not answered
    assert "Expected" not in json.dumps(data)


def test_an_upload_of_answers_sees_verdicts_and_what_was_read_but_no_expected_answer(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "answers.txt").write_text(
        "bowling_3_15_4_pendulum.acc_mag = 1 ft/s^2\n"
        "bowling_3_15_8_connected_blocks.xdot =   \n")
    _, data = run_with(tmp_path)
    view = student_view(data)
    assert "Expected" not in view.text()
    assert "Answers read (1 of 8):\n  bowling_3_15_4_pendulum/acc_mag = 1 ft/s^2" in view.text()
    assert "Verdict: incorrect" in view.text() and not view.total_shown
    assert "Score: 0 / 19 points" in view.tests[0]["output"]  # the receipt says it instead
    after = student_view(data, due_passed=True)
    assert after.total_shown and after.text().count("Expected: ") == 1


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


def documented_script(name: str) -> str:
    """The script ``name`` exactly as docs/exports.md shows it (a ```sh block naming it)."""
    text = (ROOT / "docs" / "exports.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```sh\n(.*?)```", text, re.S)
    (script,) = [b for b in blocks if b.splitlines()[1].startswith(f"# {name}:")]
    return script


SHIMS = {
    # Gradescope's image has apt-get, python3 and a network; the test stands in for them and
    # runs the real mechgrade of this checkout in the venv setup.sh makes.
    "apt-get": 'echo "apt-get $*" >> "$SHIM_LOG"\n',
    "python3": textwrap.dedent("""\
        if [ "$1" = "-m" ] && [ "$2" = "venv" ]; then
            mkdir -p "$3/bin"
            pip='echo "pip $*" >> "$SHIM_LOG"; [ -f "$2/pyproject.toml" ]'
            printf '#!/usr/bin/env bash\\n%s\\n' "$pip" > "$3/bin/pip"
            chmod +x "$3/bin/pip"
            ln -s "$MECHGRADE" "$3/bin/mechgrade"
            exit 0
        fi
        exit 1
        """),
}


@pytest.mark.slow
def test_documented_setup_and_run_autograder_grade_a_zipped_upload(tmp_path):
    root = tmp_path / "autograder"
    source = root / "source"
    source.mkdir(parents=True)
    for name in ("setup.sh", "run_autograder"):
        (source / name).write_text(documented_script(name))
        (source / name).chmod(0o755)
    copy = source / "mechgrade"
    copy.mkdir()
    shutil.copy(ROOT / "pyproject.toml", copy)
    for folder in ("examples", "problems"):
        shutil.copytree(ROOT / folder, copy / folder)
    shims = tmp_path / "shims"
    shims.mkdir()
    for name, body in SHIMS.items():
        (shims / name).write_text("#!/usr/bin/env bash\n" + body)
        (shims / name).chmod(0o755)
    env = {**os.environ, "AUTOGRADER_ROOT": str(root), "SHIM_LOG": str(tmp_path / "log"),
           "PATH": f"{shims}{os.pathsep}{os.environ['PATH']}",
           "MECHGRADE": str(Path(sys.executable).with_name("mechgrade"))}
    setup = subprocess.run(["bash", str(source / "setup.sh")], env=env, cwd=source,
                           capture_output=True, text=True, timeout=60)
    assert setup.returncode == 0, setup.stderr
    assert (tmp_path / "log").read_text().splitlines() == [
        "apt-get update", "apt-get install -y python3-pip python3-venv",
        f"pip install {copy}"]
    (root / "submission").mkdir()
    with zipfile.ZipFile(root / "submission" / "hw1.zip", "w") as archive:
        archive.writestr("hw1/answers.yaml", (ADA / "answers.yaml").read_bytes())
    (root / "submission_metadata.json").write_text(json.dumps(
        {"users": [{"name": "Ada Lovelace", "sid": "10001", "email": "ada@uni.example"}]}))
    run = subprocess.run(["bash", str(source / "run_autograder")], env=env, cwd=source,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout == (f"10001: 19 / 19 points (read hw1.zip/hw1/answers.yaml); wrote "
                          f"{root / 'results' / 'results.json'}\n")
    data = json.loads((root / "results" / "results.json").read_text())
    assert data["score"] == 19.0 and data["visibility"] == "after_due_date"
    assert len(data["tests"]) == 1 + 8 + 8
