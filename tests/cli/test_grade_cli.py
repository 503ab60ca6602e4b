"""``mechgrade grade``: exit codes, the summary line, and bad input reported in one message."""

from __future__ import annotations

import json
import textwrap

from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.resources import shipped_dir

EXAMPLE = shipped_dir("examples") / "hw1"
PENDULUM = shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"


def run(*args):
    return CliRunner().invoke(main, ["grade", *map(str, args)])


def small_class(tmp_path):
    (tmp_path / "p.yaml").write_text(PENDULUM.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "hw.yaml").write_text(textwrap.dedent("""\
        id: hw
        title: HW
        problems: [{path: p.yaml, objectives: [acc_mag]}]
        """), encoding="utf-8")
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "ann.txt").write_text("bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2\n",
                                  encoding="utf-8")
    (subs / "bo.txt").write_text("bowling_3_15_4_pendulum.acc_mag = lots\n", encoding="utf-8")
    (subs / "cy.txt").write_bytes(b"\x00\x00")
    return tmp_path


def test_grade_writes_outputs_and_a_summary(tmp_path):
    folder = small_class(tmp_path)
    out = tmp_path / "out"
    result = run(folder / "hw.yaml", folder / "subs", "--out", out)
    assert result.exit_code == 0, result.output
    assert result.stdout == (f"Graded 2 students (1 unreadable answer, 1 unreadable submission, "
                             f"0 missing submissions); wrote {out.as_posix()}/\n")
    assert result.stderr.startswith("Grading")
    data = json.loads((out / "results.json").read_text(encoding="utf-8"))
    assert [(s["id"], s["status"], s["score"]) for s in data["students"]] == [
        ("ann", "graded", 1.0), ("bo", "graded", 0.0), ("cy", "unreadable", 0.0)]
    assert (out / "feedback" / "bo.html").is_file() and (out / "grades.csv").is_file()


def test_bad_assignment_is_one_message_and_exit_2(tmp_path):
    folder = small_class(tmp_path)
    (folder / "hw.yaml").write_text("id: hw\ntitle: HW\nproblems: [gone.yaml]\n",
                                    encoding="utf-8")
    result = run(folder / "hw.yaml", folder / "subs", "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert result.stdout == ""
    assert result.stderr == (f"{folder / 'hw.yaml'}:3:12: problems[0]: expected a problem file "
                             f"(relative to the assignment file), found no file at "
                             f"'{folder / 'gone.yaml'}'\n")
    assert not (tmp_path / "out").exists()


def test_bad_roster_is_one_message_and_exit_2(tmp_path):
    folder = small_class(tmp_path)
    (folder / "roster.csv").write_bytes(b"\xff\xfe\x00garbage")
    result = run(folder / "hw.yaml", folder / "subs", "--out", tmp_path / "out", "--roster",
                 folder / "roster.csv")
    assert result.exit_code == 2
    assert result.stderr.startswith(str(folder / "roster.csv"))
    assert len(result.stderr.splitlines()) == 1


def test_missing_submissions_folder_is_a_usage_error(tmp_path):
    folder = small_class(tmp_path)
    result = run(folder / "hw.yaml", folder / "nowhere", "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert "Path" in result.stderr and "does not exist" in result.stderr


def test_out_is_required(tmp_path):
    folder = small_class(tmp_path)
    result = run(folder / "hw.yaml", folder / "subs")
    assert result.exit_code == 2
    assert "Missing option '--out'" in result.stderr


def test_templates_option_overrides_feedback(tmp_path):
    folder = small_class(tmp_path)
    templates = tmp_path / "t"
    templates.mkdir()
    (templates / "feedback.html.j2").write_text("{{ student.id }} {{ student.score }}\n",
                                                encoding="utf-8")
    (templates / "feedback.md.j2").write_text("{{ student.id }}\n", encoding="utf-8")
    result = run(folder / "hw.yaml", folder / "subs", "--out", tmp_path / "out", "--templates",
                 templates)
    assert result.exit_code == 0, result.output
    assert (tmp_path / "out" / "feedback" / "ann.html").read_text(encoding="utf-8") == "ann 1\n"


def test_readme_command_on_the_example_class(tmp_path):
    out = tmp_path / "out"
    result = run(EXAMPLE / "assignment.yaml", EXAMPLE / "submissions", "--roster",
                 EXAMPLE / "roster.csv", "--out", out)
    assert result.exit_code == 0, result.output
    assert result.stdout == (f"Graded 7 students (6 unreadable answers, 1 unreadable "
                             f"submission, 2 missing submissions, 1 skipped entry); wrote "
                             f"{out.as_posix()}/\n"
                             f"Skipped (not read as anyone's answers):\n"
                             f"  frank_empty/.keep: hidden (its name starts with '.')\n")
    first = {p.relative_to(out): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}
    again = run(EXAMPLE / "assignment.yaml", EXAMPLE / "submissions", "--roster",
                EXAMPLE / "roster.csv", "--out", out)
    assert again.exit_code == 0
    assert first == {p.relative_to(out): p.read_bytes() for p in sorted(out.rglob("*"))
                     if p.is_file()}
    assert len([p for p in first if str(p).startswith("feedback")]) == 20


def _files(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def test_outputs_are_byte_identical_for_any_number_of_jobs(tmp_path):
    outs = []
    for jobs in (1, 2, 3):
        out = tmp_path / f"out{jobs}"
        result = CliRunner().invoke(main, ["grade", str(EXAMPLE / "assignment.yaml"),
                                           str(EXAMPLE / "submissions"), "--roster",
                                           str(EXAMPLE / "roster.csv"), "--out", str(out),
                                           "--jobs", str(jobs)])
        assert result.exit_code == 0, result.output
        outs.append(_files(out))
    assert len(outs[0]) > 10 and any("feedback/" in name for name in outs[0])
    assert outs[0] == outs[1] == outs[2]


def test_jobs_must_be_positive(tmp_path):
    folder = small_class(tmp_path)
    result = run(folder / "hw.yaml", folder / "subs", "--out", tmp_path / "out", "--jobs", "0")
    assert result.exit_code == 2 and "--jobs" in result.stderr


def test_a_template_failing_in_a_worker_is_one_message_and_nothing_is_written(tmp_path):
    templates = tmp_path / "t"
    templates.mkdir()
    (templates / "feedback.html.j2").write_text("{{ student.grade_letter }}", encoding="utf-8")
    (templates / "feedback.md.j2").write_text("x", encoding="utf-8")
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["grade", str(EXAMPLE / "assignment.yaml"),
                                       str(EXAMPLE / "submissions"), "--out", str(out),
                                       "--templates", str(templates), "--jobs", "2"])
    assert result.exit_code == 2
    message = result.stderr.splitlines()[-1]
    assert "feedback.html.j2: the template uses a value mechgrade does not provide" in message
    assert "Traceback" not in result.stderr
    assert not (out / "results.json").exists() and not list((out / "feedback").iterdir())


def test_grade_takes_an_lms_download_zip_directly(tmp_path):
    import zipfile

    folder = small_class(tmp_path)
    with zipfile.ZipFile(tmp_path / "canvas.zip", "w") as archive:
        archive.writestr("ann_101_9001_answers.txt",
                         "bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2\n")
        archive.writestr("bo_late_102_9002_my answers.txt",
                         "bowling_3_15_4_pendulum.acc_mag = 9 ft/s^2\n")
        archive.writestr("../103_9003_answers.txt", "x")
    out = tmp_path / "out"
    result = run(folder / "hw.yaml", tmp_path / "canvas.zip", "--out", out, "-j", "1")
    assert result.exit_code == 0, result.output
    assert result.stdout == (
        "Graded 2 students (0 unreadable answers, 0 missing submissions, 1 skipped entry); "
        f"wrote {out.as_posix()}/\n"
        "Skipped (not read as anyone's answers):\n"
        "  canvas.zip/../103_9003_answers.txt: its name climbs out of the zip (..); it was not "
        "read\n")
    scores = {s["id"]: s["score"] for s in json.loads((out / "results.json").read_text())
              ["students"]}
    assert scores == {"101": 1.0, "102": 0.0}  # one point per objective by default


def test_a_file_named_as_a_folder_of_submissions_is_refused(tmp_path):
    folder = small_class(tmp_path)
    (tmp_path / "x.zip").write_bytes(b"PK")
    result = run(folder / "hw.yaml", tmp_path / "x.zip", "--out", tmp_path / "out",
                 "--submissions-format", "folder")
    assert result.exit_code == 2
    assert result.stderr == f"{tmp_path / 'x.zip'}: expected a folder of submissions, found a " \
                            "file\n"
