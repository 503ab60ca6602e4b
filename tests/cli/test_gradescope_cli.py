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
