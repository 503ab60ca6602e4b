"""``mechgrade grade``: exit codes, the summary line, and bad input reported in one message."""

from __future__ import annotations

import json
import textwrap

import pytest
from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.resources import shipped_dir

EXAMPLE = shipped_dir("examples") / "hw1"
PENDULUM = shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"


def run(*args, jobs="1"):
    """``mechgrade grade`` with ``--jobs 1`` unless the test says otherwise: forked workers
    would each derive the problems again, cold (``jobs=None``: the command's default)."""
    args = [*map(str, args)]
    if jobs is not None and not {"--jobs", "-j"} & set(args):
        args += ["--jobs", jobs]
    return CliRunner().invoke(main, ["grade", *args])


def small_class(tmp_path):
    (tmp_path / PENDULUM.name).write_text(PENDULUM.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "hw.yaml").write_text(textwrap.dedent("""\
        id: hw
        title: HW
        problems: [{path: bowling_3_15_4_pendulum.yaml, objectives: [acc_mag]}]
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
                 EXAMPLE / "roster.csv", "--out", out, jobs=None)
    assert result.exit_code == 0, result.output
    assert result.stdout == (f"Graded 7 students (6 unreadable answers, 1 unreadable "
                             f"submission, 2 missing submissions, 1 skipped entry); wrote "
                             f"{out.as_posix()}/\n"
                             f"Skipped (not read as anyone's answers):\n"
                             f"  frank_empty/.keep: hidden (its name starts with '.')\n")
    first = _files(out)
    # run again in this process: the files are the same, and no worker derives the class again
    again = run(EXAMPLE / "assignment.yaml", EXAMPLE / "submissions", "--roster",
                EXAMPLE / "roster.csv", "--out", out, "--jobs", "1")
    assert again.exit_code == 0
    assert first == _files(out)
    assert len([p for p in first if str(p).startswith("feedback")]) == 20


def _files(folder):
    """Every output but the manifest (which records the run's time and arguments)."""
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file() and p.name != "manifest.json"}


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
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t"]


# --out holds one run's outputs: nothing stale, nothing racing, nothing half-written.


def _manifest(out):
    return json.loads((out / "manifest.json").read_text(encoding="utf-8"))


def test_a_regrade_of_fewer_students_removes_and_lists_the_pages_of_the_others(tmp_path):
    folder = small_class(tmp_path)
    out = tmp_path / "out"
    assert run(folder / "hw.yaml", folder / "subs", "--out", out).exit_code == 0
    (folder / "subs" / "bo.txt").unlink()
    result = run(folder / "hw.yaml", folder / "subs", "--out", out)
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in (out / "feedback").iterdir()) == [
        "ann.html", "ann.md", "cy.html", "cy.md"]
    assert result.stdout.splitlines()[1:] == [
        "Removed from the previous run (not written by this one):",
        "  feedback/bo.html", "  feedback/bo.md"]
    assert _manifest(out)["removed"] == ["feedback/bo.html", "feedback/bo.md"]


def test_the_manifest_records_the_run(tmp_path):
    import hashlib

    from mechgrade import __version__

    folder = small_class(tmp_path)
    out = tmp_path / "out"
    assert run(folder / "hw.yaml", folder / "subs", "--out", out, "--jobs", "1").exit_code == 0
    manifest = _manifest(out)
    assert manifest["mechgrade"] == __version__
    assert manifest["command"] == "mechgrade grade"
    assert manifest["arguments"] == {
        "assignment": str(folder / "hw.yaml"), "submissions_dir": str(folder / "subs"),
        "out_dir": str(out), "roster": None, "templates_dir": None, "jobs": 1,
        "accept_failing_expect": False, "submissions_format": None}
    assert manifest["started"] <= manifest["finished"]
    assert manifest["inputs"] == [
        {"role": "assignment", "path": str(folder / "hw.yaml"),
         "sha256": hashlib.sha256((folder / "hw.yaml").read_bytes()).hexdigest()},
        {"role": "problem", "path": str(folder / PENDULUM.name),
         "sha256": hashlib.sha256((folder / PENDULUM.name).read_bytes()).hexdigest()}]
    written = sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file())
    assert manifest["files"] == [name for name in written if name != "manifest.json"]
    assert manifest["kept"] == [] and manifest["removed"] == []


def test_files_of_the_instructors_own_in_out_are_kept_and_never_counted_as_outputs(tmp_path):
    folder = small_class(tmp_path)
    out = tmp_path / "out"
    assert run(folder / "hw.yaml", folder / "subs", "--out", out).exit_code == 0
    (out / "class.html").write_text("my report\n", encoding="utf-8")
    (out / "notes").mkdir()
    (out / "notes" / "late.txt").write_text("bo was late\n", encoding="utf-8")
    (out / "feedback" / "README").write_text("mine\n", encoding="utf-8")
    (out / "evil\x1b[2J.txt").write_text("a name that clears the screen\n", encoding="utf-8")
    result = run(folder / "hw.yaml", folder / "subs", "--out", out)
    assert result.exit_code == 0, result.output
    assert (out / "class.html").read_text(encoding="utf-8") == "my report\n"
    assert (out / "notes" / "late.txt").read_text(encoding="utf-8") == "bo was late\n"
    assert (out / "feedback" / "README").read_text(encoding="utf-8") == "mine\n"
    assert _manifest(out)["kept"] == ["class.html", "evil\x1b[2J.txt", "feedback/README",
                                      "notes/late.txt"]
    assert "class.html" not in _manifest(out)["files"]
    assert result.stdout.splitlines()[1:] == [
        "Kept (not written by mechgrade):", "  class.html", "  evil\\x1b[2J.txt",
        "  feedback/README", "  notes/late.txt"]


def test_outputs_of_an_earlier_version_without_a_manifest_are_replaced_whole(tmp_path):
    folder = small_class(tmp_path)
    out = tmp_path / "out"
    (out / "feedback").mkdir(parents=True)
    for name in ("results.json", "grades.csv", "results.csv", "feedback/gone.html",
                 "feedback/gone.md", "class.html"):
        (out / name).write_text("old\n", encoding="utf-8")
    result = run(folder / "hw.yaml", folder / "subs", "--out", out)
    assert result.exit_code == 0, result.output
    assert not (out / "feedback" / "gone.html").exists()
    assert (out / "class.html").read_text(encoding="utf-8") == "old\n"
    assert _manifest(out)["removed"] == ["feedback/gone.html", "feedback/gone.md"]


def test_a_folder_holding_something_else_is_refused_before_grading(tmp_path):
    folder = small_class(tmp_path)
    out = tmp_path / "course"
    (out / "photos").mkdir(parents=True)
    (out / "syllabus.pdf").write_bytes(b"%PDF")
    result = run(folder / "hw.yaml", folder / "subs", "--out", out)
    assert result.exit_code == 2
    assert result.stdout == ""
    assert result.stderr == (
        f"{out}: --out: expected a new or empty folder, or one 'mechgrade grade' wrote before "
        f"(it holds manifest.json), found 2 entries of something else (photos/, syllabus.pdf); "
        f"choose another --out\n")
    assert sorted(p.name for p in out.iterdir()) == ["photos", "syllabus.pdf"]


def test_a_folder_of_another_commands_outputs_is_refused(tmp_path):
    folder = small_class(tmp_path)
    out = tmp_path / "sheets"
    out.mkdir()
    (out / "manifest.json").write_text(json.dumps({"format": "mechgrade outputs 1",
                                                   "command": "mechgrade handout",
                                                   "files": ["givens.csv"]}),
                                       encoding="utf-8")
    (out / "givens.csv").write_text("id\n", encoding="utf-8")
    result = run(folder / "hw.yaml", folder / "subs", "--out", out)
    assert result.exit_code == 2
    assert result.stderr == (f"{out}: --out: expected a folder of 'mechgrade grade' outputs, "
                             f"found the outputs of 'mechgrade handout' (manifest.json); "
                             f"choose another --out\n")


def test_a_run_that_fails_while_writing_leaves_the_previous_outputs_whole(tmp_path,
                                                                          monkeypatch):
    from mechgrade.errors import OutputError
    from mechgrade.report import output

    folder = small_class(tmp_path)
    out = tmp_path / "out"
    assert run(folder / "hw.yaml", folder / "subs", "--out", out).exit_code == 0
    before = _files(out)
    (folder / "subs" / "ann.txt").write_text("bowling_3_15_4_pendulum.acc_mag = 12 ft/s^2\n",
                                             encoding="utf-8")
    written = []

    def fail_on_the_third_file(path, text, **kwargs):
        written.append(path)
        if len(written) == 3:
            raise OutputError("cannot write the file (No space left on device)")
        original(path, text, **kwargs)

    original = output.write_text
    monkeypatch.setattr(output, "write_text", fail_on_the_third_file)
    result = run(folder / "hw.yaml", folder / "subs", "--out", out, "--jobs", "1")
    assert result.exit_code == 2
    assert "No space left on device" in result.stderr
    assert _files(out) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "bowling_3_15_4_pendulum.yaml", "hw.yaml", "out", "subs"]


def test_a_second_run_into_a_folder_being_written_is_refused(tmp_path):
    import fcntl
    import os

    folder = small_class(tmp_path)
    out = tmp_path / "out"
    lock = tmp_path / ".out.mechgrade-lock"
    with open(lock, "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX)
        held.write(f"{os.getpid()}\n")
        held.flush()
        result = run(folder / "hw.yaml", folder / "subs", "--out", out)
    assert result.exit_code == 2
    assert result.stdout == ""
    assert result.stderr == (f"{out}: --out: expected a folder no other run is writing, found "
                             f"mechgrade process {os.getpid()} writing it; wait for that run "
                             f"to end, or choose another --out\n")
    assert not out.exists()


@pytest.mark.parametrize("where", ["subs", "subs/out", "subs/ann/deeper"])
def test_out_inside_the_submissions_folder_is_refused(tmp_path, where):
    folder = small_class(tmp_path)
    out = tmp_path / where
    result = run(folder / "hw.yaml", folder / "subs", "--out", out)
    assert result.exit_code == 2
    found = ("the submissions folder itself" if where == "subs"
             else f"a folder inside {folder / 'subs'}")
    assert result.stderr == (f"{out}: --out: expected a folder outside the submissions folder, "
                             f"found {found} (the next run would grade the outputs as "
                             f"students' work); choose another --out\n")
    assert sorted(p.name for p in (folder / "subs").iterdir()) == ["ann.txt", "bo.txt", "cy.txt"]


def test_out_holding_the_submissions_folder_is_refused(tmp_path):
    folder = small_class(tmp_path)
    result = run(folder / "hw.yaml", folder / "subs", "--out", tmp_path)
    assert result.exit_code == 2
    assert result.stderr == (f"{tmp_path}: --out: expected a folder that does not hold the "
                             f"submissions folder, found {folder / 'subs'} inside it (a run "
                             f"replaces --out whole); choose another --out\n")


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
