"""``mechgrade grade`` refuses a problem that fails its own ``expect:`` tests (every student
would be graded against a reference its author says is wrong); ``--accept-failing-expect``
grades it, and every output records the tests it fails."""

from __future__ import annotations

import json
import textwrap

import pytest
from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.resources import shipped_dir

PENDULUM = shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"
SAYS = "acc_mag: 98.5089 != expected 97.51 ft/s^2 (±0.005, from the digits written)"


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    top = tmp_path_factory.mktemp("failing")
    text = PENDULUM.read_text(encoding="utf-8").replace("expect: {value: 98.51}",
                                                         "expect: {value: 97.51}")
    (top / PENDULUM.name).write_text(text, encoding="utf-8")
    (top / "hw.yaml").write_text(textwrap.dedent("""\
        id: hw
        title: HW
        problems: [{path: bowling_3_15_4_pendulum.yaml, objectives: [acc_mag]}]
        """), encoding="utf-8")
    (top / "subs").mkdir()
    (top / "subs" / "ann.txt").write_text("bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2\n",
                                          encoding="utf-8")
    return top


@pytest.fixture(scope="module")
def accepted(folder):
    out = folder / "accepted"
    result = CliRunner().invoke(main, ["grade", str(folder / "hw.yaml"), str(folder / "subs"),
                                       "--out", str(out), "--accept-failing-expect", "--jobs", "1"])
    return result, out


def test_a_spec_failing_its_own_test_is_refused_before_grading(folder):
    out = folder / "refused"
    result = CliRunner().invoke(main, ["grade", str(folder / "hw.yaml"), str(folder / "subs"),
                                       "--out", str(out)])
    assert result.exit_code == 2
    assert result.stdout == ""
    assert result.stderr == (
        f"{folder / PENDULUM.name}:30:13: objectives[0].expect: expected the solver to pass this "
        f"expect: test before grading, found {SAYS}; fix the problem file (mechgrade check "
        f"shows it) or grade anyway with --accept-failing-expect\n")
    assert not out.exists()


def test_graded_anyway_the_summary_and_results_record_it(folder, accepted):
    result, out = accepted
    assert result.exit_code == 0, result.output
    where = f"{folder / PENDULUM.name}:30:13: objectives[0].expect"
    assert result.stdout.splitlines()[1:] == [
        "Graded although the problems fail these expect: tests (--accept-failing-expect):",
        f"  {where}: {SAYS}"]
    data = json.loads((out / "results.json").read_text(encoding="utf-8"))
    assert data["failing_expects"] == [{
        "problem": "bowling_3_15_4_pendulum", "objective": "acc_mag", "where": where,
        "message": SAYS.split(": ", 1)[1]}]


def test_graded_anyway_the_feedback_pages_say_so_without_the_answer(accepted):
    _, out = accepted
    html = (out / "feedback" / "ann.html").read_text(encoding="utf-8")
    markdown = (out / "feedback" / "ann.md").read_text(encoding="utf-8")
    for page in (" ".join(html.split()), markdown):
        assert "fail their author&#39;s own checks" in page or \
            "fail their author's own checks" in page
        # the question as the student reads it, not its key
        assert "- Magnitude of the tip's absolute acceleration.\n" in page or \
            "<li>Magnitude of the tip&#39;s absolute acceleration.</li>" in page
        assert "97.51" not in page


def test_graded_anyway_the_class_report_and_exports_say_so(folder, accepted):
    _, out = accepted
    report = CliRunner().invoke(main, ["report", str(out / "results.json"), "--out",
                                       str(folder / "class.html")])
    assert report.exit_code == 0, report.output
    html = (folder / "class.html").read_text(encoding="utf-8")
    assert 'id="failing-expects"' in html and "acc_mag: 98.5089 != expected 97.51" in html
    export = CliRunner().invoke(main, ["export", str(out / "results.json"), "--format",
                                       "grades-csv", "--out", str(folder / "grades.csv")])
    assert export.exit_code == 0, export.output
    assert (f"warning: graded although the problem fails this expect: test "
            f"(--accept-failing-expect): {folder / PENDULUM.name}:30:13: objectives[0].expect: "
            f"{SAYS}") in export.stderr


def test_the_gradescope_autograder_refuses_without_showing_the_values(folder):
    results = folder / "gs_refused.json"
    result = CliRunner().invoke(main, ["gradescope", str(folder / "hw.yaml"), "--submission",
                                       str(folder / "subs"), "--results", str(results),
                                       "--metadata", str(folder / "none.json")])
    assert result.exit_code == 2
    assert SAYS in result.stderr and "--accept-failing-expect" in result.stderr
    shown = json.loads(results.read_text(encoding="utf-8"))
    assert shown["score"] == 0.0
    assert shown["output"] == ("The autograder could not grade this submission: the answer key "
                               "fails its author's own checks (bowling_3_15_4_pendulum · "
                               "acc_mag); please tell your instructor")


def test_the_gradescope_autograder_grades_anyway_and_says_so(folder):
    upload = folder / "upload"
    upload.mkdir()
    (upload / "answers.txt").write_text("bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2\n",
                                        encoding="utf-8")
    results = folder / "gs_accepted.json"
    result = CliRunner().invoke(main, ["gradescope", str(folder / "hw.yaml"), "--submission",
                                       str(upload), "--results", str(results), "--metadata",
                                       str(folder / "none.json"), "--accept-failing-expect"])
    assert result.exit_code == 0, result.output
    shown = json.loads(results.read_text(encoding="utf-8"))
    assert shown["score"] == 1.0
    assert ("fail their author's own checks; your instructor graded them anyway, and their "
            "points may change: bowling_3_15_4_pendulum · acc_mag.") in shown["output"]
    assert "97.51" not in json.dumps(shown)
