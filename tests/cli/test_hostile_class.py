"""A class folder built to break the grader (tests/data/hostile/make_corpus.py), graded through
the CLI with its roster: the run finishes, every entry is accounted for, every output is valid
and stable, nothing is written outside ``--out``, roster conflicts are listed and never
exported as grades, what a file repeats is not repeated in every output, names holding
terminal control sequences are printed escaped, and a solver's cache folder edited by others
changes no result."""

from __future__ import annotations

import csv
import hashlib
import importlib.util
import io
import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.files import clean_text
from mechgrade.resources import shipped_dir

CORPUS = Path(__file__).parents[1] / "data" / "hostile" / "make_corpus.py"


def _corpus_module():
    spec = importlib.util.spec_from_file_location("make_corpus", CORPUS)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def hostile(tmp_path_factory):
    corpus = _corpus_module()
    top = tmp_path_factory.mktemp("hostile")
    corpus.build(top / "class")
    problem = shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"
    (top / "p.yaml").write_bytes(problem.read_bytes())
    (top / "hw.yaml").write_text(textwrap.dedent("""\
        id: hw
        title: Hostile class
        problems: [p.yaml]
        """), encoding="utf-8")
    (top / "roster.csv").write_text(corpus.ROSTER, encoding="utf-8")
    before = _snapshot(top)
    command = ["grade", str(top / "hw.yaml"), str(top / "class"), "--out", str(top / "out"),
               "--roster", str(top / "roster.csv")]
    first = CliRunner().invoke(main, command)
    outputs = _outputs(top / "out")
    # again in this process (no worker derives the problem again): the same outputs
    again = CliRunner().invoke(main, [*command, "--jobs", "1"])
    yield {"top": top, "first": first, "again": again, "outputs": outputs,
           "before": before, "after": _snapshot(top), "corpus": corpus}
    corpus.unlock(top / "class")


def _snapshot(top: Path) -> dict[str, tuple[int, int]]:
    """Every path below ``top`` but ``out/``, with its size and modification time."""
    found = {}
    for folder, dirs, files in os.walk(top, followlinks=False):
        for name in dirs + files:
            path = os.path.join(folder, name)
            rel = os.path.relpath(path, top)
            if rel == "out" or rel.startswith("out" + os.sep):
                continue
            info = os.lstat(path)
            found[rel] = (info.st_size, info.st_mtime_ns)
    return found


def _outputs(out: Path) -> dict[str, str]:
    """Every output but the manifest (which records the run's time)."""
    return {p.relative_to(out).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(out.rglob("*")) if p.is_file() and p.name != "manifest.json"}


def test_the_run_finishes_without_a_traceback(hostile):
    result = hostile["first"]
    assert result.exception is None or isinstance(result.exception, SystemExit)
    assert "Traceback" not in result.output
    assert result.exit_code == 0, result.stdout
    assert result.stdout.startswith("Graded ")


def test_every_entry_of_the_folder_is_a_student_or_skipped(hostile):
    data = json.loads((hostile["top"] / "out" / "results.json").read_bytes().decode("utf-8"))
    ids = {s["id"] for s in data["students"]}
    skipped = {e["path"] for e in data["skipped"]}
    for name in os.listdir(os.fsencode(hostile["top"] / "class")):
        shown = clean_text(os.fsdecode(name))
        stem = shown.rsplit(".", 1)[0] if "." in shown[1:] else shown
        assert shown in skipped or shown in ids or stem in ids, shown
    assert hostile["corpus"].EXPECTED_SKIPPED <= skipped
    assert {"bad\\xe9name", "Zo\u00eb", "Zoe\u0308", " spaced ", "new\nline"} <= ids
    assert any("differ only in Unicode form" in note for note in data["notes"])
    assert any("copycat/answers.yaml" in note for note in data["notes"])
    assert data["internal_errors"] == []


def test_every_output_is_valid_utf8_json_and_csv(hostile):
    out = hostile["top"] / "out"
    data = json.loads((out / "results.json").read_bytes().decode("utf-8"))
    for name in ("grades.csv", "results.csv"):
        rows = list(csv.reader(io.StringIO((out / name).read_bytes().decode("utf-8"),
                                           newline="")))
        assert len({len(row) for row in rows}) == 1, name
    grades = list(csv.reader(io.StringIO((out / "grades.csv").read_text("utf-8"), newline="")))
    assert len(grades) == len(data["students"]) + 1
    pages = sorted((out / "feedback").iterdir())
    assert len(pages) == 2 * len(data["students"])
    for page in pages:
        page.read_bytes().decode("utf-8")
        assert not page.name.startswith(("-", "."))


def test_a_rerun_writes_byte_identical_outputs(hostile):
    assert hostile["again"].exit_code == hostile["first"].exit_code
    assert _outputs(hostile["top"] / "out") == hostile["outputs"]


def test_nothing_is_written_outside_out(hostile):
    assert hostile["after"] == hostile["before"]
    assert not Path("PWNED").exists()


def test_the_class_report_lists_what_was_skipped(hostile):
    out = hostile["top"] / "out"
    result = CliRunner().invoke(main, ["report", str(out / "results.json"), "--out",
                                       str(out / "class.html")])
    assert result.exit_code == 0, result.output
    html = (out / "class.html").read_text(encoding="utf-8")
    assert "__MACOSX" in html and "made by macOS when zipping" in html
    assert "differ only in Unicode form" in html


@pytest.mark.parametrize("fmt", ["canvas", "moodle", "gradescope", "grades-csv", "long-csv",
                                 "json"])
def test_every_export_of_the_hostile_class_is_written(hostile, fmt):
    out = hostile["top"] / "out"
    roster = shipped_dir("examples") / "hw1" / "roster.csv"
    target = hostile["top"] / f"export_{fmt}"
    result = CliRunner().invoke(main, ["export", str(out / "results.json"), "--format", fmt,
                                       "--roster", str(roster), "--out", str(target)])
    assert result.exit_code == 0, result.output
    for path in [target] if target.is_file() else sorted(target.iterdir()):
        path.read_bytes().decode("utf-8-sig")
        assert not path.name.startswith(("-", "."))


# --- outputs: nothing stale, nothing racing, nothing left running


def test_a_regrade_of_two_students_into_the_hostile_outputs_leaves_only_theirs(hostile):
    import shutil

    top = hostile["top"]
    out = top / "regrade"
    shutil.copytree(top / "out", out, symlinks=True)
    previous = set(json.loads((out / "manifest.json").read_text(encoding="utf-8"))["files"])
    two = top / "two"
    for name in ("ana", "ben"):
        (two / name).mkdir(parents=True)
        (two / name / "answers.yaml").write_text("bowling_3_15_4_pendulum:\n  acc_mag: 98.5 "
                                                 "ft/s^2\n", encoding="utf-8")
    result = CliRunner().invoke(main, ["grade", str(top / "hw.yaml"), str(two), "--out",
                                       str(out), "--jobs", "1"])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in (out / "feedback").iterdir()) == [
        "ana.html", "ana.md", "ben.html", "ben.md"]
    manifest = json.loads((out / "manifest.json").read_text(encoding="utf-8"))
    assert set(manifest["removed"]) == previous - set(manifest["files"])
    assert len(manifest["removed"]) > 100
    assert set(manifest["kept"]) <= {"class.html"}  # the class report a test wrote there
    lines = result.stdout.splitlines()
    start = lines.index("Removed from the previous run (not written by this one):")
    assert lines[start + 51] == (f"  ... and {len(manifest['removed']) - 50} more (all in "
                                 f"manifest.json)")
    assert all(line.isprintable() for line in lines)
    assert not [p for p in top.iterdir() if p.name.startswith(".regrade")]


SLOW_PAGE = "{% for i in range(10 ** 10) %}{% endfor %}{{ student.id }}\n"


@pytest.mark.slow
def test_a_run_killed_while_writing_leaves_no_worker_and_the_previous_outputs(tmp_path,
                                                                              marked_run):
    """``kill -9`` (the OOM killer) of a run whose page helper is busy: no worker outlives it,
    its output streams reach their end, and --out still holds the previous run's outputs; a
    second run started meanwhile into the same --out is refused."""
    import subprocess
    import sys
    import time

    (tmp_path / "p.yaml").write_bytes(
        (shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml").read_bytes())
    (tmp_path / "hw.yaml").write_text("id: hw\ntitle: HW\nproblems: [{path: p.yaml, "
                                      "objectives: [acc_mag]}]\n", encoding="utf-8")
    for n in range(30):  # two pieces of pages: a helper process renders one of them
        (tmp_path / "subs" / f"s{n:02d}").mkdir(parents=True)
        (tmp_path / "subs" / f"s{n:02d}" / "answers.txt").write_text(
            "bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2\n", encoding="utf-8")
    (tmp_path / "slow").mkdir()
    (tmp_path / "slow" / "feedback.html.j2").write_text(SLOW_PAGE, encoding="utf-8")
    (tmp_path / "slow" / "feedback.md.j2").write_text("{{ student.id }}\n", encoding="utf-8")
    out = tmp_path / "out"
    out.mkdir()
    (out / "manifest.json").write_text(json.dumps({
        "format": "mechgrade outputs 1", "command": "mechgrade grade",
        "files": ["results.json"]}), encoding="utf-8")
    (out / "results.json").write_text("the previous run's\n", encoding="utf-8")
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    command = [sys.executable, "-m", "mechgrade", "grade", str(tmp_path / "hw.yaml"),
               str(tmp_path / "subs"), "--out", str(out)]
    run = marked_run([*command, "--jobs", "2", "--templates", str(tmp_path / "slow")])
    first_seen: dict[int, float] = {}

    def a_worker_is_busy() -> bool:  # the page helper: the run's one long-lived worker
        now = time.monotonic()
        workers = run.workers()
        for pid in workers:
            first_seen.setdefault(pid, now)
        return any(now - first_seen[pid] > 1.0 for pid in workers)

    run.wait_for(a_worker_is_busy)
    second = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert second.returncode == 2
    assert second.stderr == (f"{out}: --out: expected a folder no other run is writing, found "
                             f"mechgrade process {run.process.pid} writing it; wait for that "
                             f"run to end, or choose another --out\n")
    run.kill()
    assert run.survivors() == set()
    assert run.output_closed()
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


def _results(hostile) -> dict:
    return json.loads((hostile["top"] / "out" / "results.json").read_bytes().decode("utf-8"))


def test_roster_conflicts_are_listed_and_no_folder_is_anyones(hostile):
    data = _results(hostile)
    conflicts = [(s["id"], s["name"]) for s in data["students"] if s["status"] == "conflict"]
    assert sorted(conflicts) == sorted([("cy", "Cy Cole"), ("101", "Dee Dunn"), ("CY", ""),
                                        ("cy", ""), ("101", ""), ("dee", "")])
    notes = [n for n in data["notes"] if n.startswith("roster conflict: ")]
    assert [n.split(";")[0] for n in notes] == [
        "roster conflict: 'CY' matches Cy Cole (cy) by id and email user name",
        "roster conflict: '101' matches Dee Dunn (101) by id"]
    summary = hostile["first"].stdout
    assert "6 in roster conflicts (students and folders)" in summary.splitlines()[0]
    assert all(note in summary for note in notes)
    ana = next(s for s in data["students"] if s["name"] == "Ana Able")
    assert (ana["id"], ana["status"]) == ("ana", "graded")


def test_students_in_roster_conflicts_are_not_exported_as_zero(hostile):
    top = hostile["top"]
    out = top / "out"
    result = CliRunner().invoke(main, ["export", str(out / "results.json"), "--format",
                                       "grades-csv", "--roster", str(top / "roster.csv"),
                                       "--out", str(top / "conflicts.csv")])
    assert result.exit_code == 0, result.output
    rows = list(csv.reader(io.StringIO((top / "conflicts.csv").read_text("utf-8"),
                                       newline="")))
    named = {row[1]: (row[2], row[-2]) for row in rows[1:] if row[1]}
    assert named["Cy Cole"] == ("conflict", "") and named["Dee Dunn"] == ("conflict", "")
    assert named["No Body"] == ("missing", "0")
    moodle = CliRunner().invoke(main, ["export", str(out / "results.json"), "--format",
                                       "moodle", "--roster", str(top / "roster.csv"),
                                       "--out", str(top / "moodle.csv")])
    assert moodle.exit_code == 0, moodle.output
    imported = (top / "moodle.csv").read_text("utf-8")
    assert "cy@uni.edu" not in imported and "dee@uni.edu" not in imported
    held = (top / "moodle.unmatched.csv").read_text("utf-8")
    assert held.count("roster conflict: ") == 6


def test_what_a_file_repeats_is_not_repeated_in_every_output(hostile):
    """A key answered thousands of times, thousands of unreadable lines, repeated JSON keys,
    answers that are not text and thousands of stray files: each student's record stays small
    (one message per repeat made a 256 KiB file 1.2 MB of results)."""
    data = _results(hostile)
    amplifiers = [s for s in data["students"] if s["id"].startswith("amp_")]
    assert len(amplifiers) == 5
    for student in amplifiers:
        assert len(student["messages"]) <= 25, student["id"]
        assert len(json.dumps(student)) < 8_000, student["id"]
    stray = [e for e in data["skipped"] if e["path"].startswith("amp_stray/")]
    assert len(stray) == 11 and stray[0]["reason"].startswith("2990 more entries")
    page = hostile["top"] / "out" / "feedback" / "amp_stray.html"
    assert page.stat().st_size < 20_000


def test_names_holding_terminal_sequences_are_printed_escaped(hostile):
    printed = hostile["first"].stdout + hostile["first"].stderr
    for control in ("\x1b", "\x07", "\x9b"):
        assert control not in printed
    assert "\r" not in hostile["first"].stdout
    for shown in ("\\x1b]0;owned\\x07title.pdf", "\\x1b[2J\\x1b[8mhidden.pdf", "\\rcr.pdf",
                  "\\x9b31mred.pdf"):
        assert f"  {shown}: not a submission" in hostile["first"].stdout


def test_a_gradescope_upload_full_of_stray_files_and_control_sequences_stays_small(hostile):
    top = hostile["top"]
    upload = top / "upload"
    upload.mkdir()
    (upload / "answers.txt").write_text(
        "bowling_3_15_4_pendulum.acc_mag = 98.5 ft/s^2\n" * 3000, encoding="utf-8")
    for i in range(3000):
        (upload / f"scan{i:04d}.pdf").write_bytes(b"")
    (top / "metadata.json").write_text(json.dumps(
        {"users": [{"sid": "\x1b]0;owned\x07s1", "name": "\x1b[2JEve"}]}), encoding="utf-8")
    result = CliRunner().invoke(main, ["gradescope", str(top / "hw.yaml"), "--submission",
                                       str(upload), "--results", str(top / "gs.json"),
                                       "--metadata", str(top / "metadata.json")])
    assert result.exit_code == 0, result.output
    assert result.stdout.startswith("\\x1b]0;owned\\x07s1: ")
    assert "\x1b" not in result.output
    assert (top / "gs.json").stat().st_size < 20_000


# ---------------------------------------------------------------------------- the cache folder
# Whoever may write the solver's cache folder (another user, a careless script) edits every
# entry it holds, swaps some for a pipe, an endless file or one too large, and leaves files of
# the user's beside them: a real grading run still writes the results it writes with no cache,
# in bounded time and memory, and removes nothing of the user's.

HW3 = shipped_dir("examples") / "hw3_dynamics"
PENDULUM_ONLY = Path(__file__).parents[1] / "data" / "cache" / "assignment.yaml"
GRADE = """\
import resource, sys
resource.setrlimit(resource.RLIMIT_AS, (6 << 30, 6 << 30))
from mechgrade.cli import main
main(sys.argv[1:], prog_name="mechgrade")
"""


def _graded(top: Path, name: str, folder: Path, assignment: Path = PENDULUM_ONLY,
            submissions: Path = HW3 / "submissions"):
    env = {k: v for k, v in os.environ.items() if k != "MECHGRADE_NO_CACHE"}
    env["MECHGRADE_CACHE_DIR"] = str(folder)
    done = subprocess.run(
        [sys.executable, "-c", GRADE, "grade", str(assignment), str(submissions),
         "--out", str(top / name), "--jobs", "2"],
        capture_output=True, text=True, env=env, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    return done, (top / name / "results.json").read_bytes()


def _edited(data):
    """An entry's data as a hostile editor leaves it: every number and answer changed."""
    if isinstance(data, dict) and "levels" in data:  # a plan: its functions give half
        for row in data["objectives"]:
            head, _, value = row[1].rpartition("return ")
            row[1] = f"{head}return 0.5*({value.strip()})\n"
        return data
    if isinstance(data, dict) and "results" in data:  # a solution: numbers turned round
        for result in data["results"]:
            value = result["value"]
            result["value"] = [-v for v in value] if isinstance(value, list) else \
                None if value is None else -value
            if result["expr"] is not None:
                result["expr"] = "0"
        return data
    if isinstance(data, dict) and "expr" in data:  # a symbolic answer
        return {**data, "expr": "0"}
    return {"alone": False}


@pytest.fixture(scope="module")
def tampered_cache(tmp_path_factory):
    top = tmp_path_factory.mktemp("cache-class")
    folder = top / "cache"
    _, cold = _graded(top, "cold", folder)
    solutions = []
    for path in sorted((folder / "entries").glob("*.json"), key=lambda p: p.stat().st_size):
        head, body = path.read_bytes().split(b"\n", 1)
        data = json.loads(body)
        if "results" in data:
            solutions.append(path)
        path.write_bytes(head + b"\n" + json.dumps(_edited(data)).encode())
    assert len(solutions) >= 4  # its own givens', and those its answers carried forward ask
    # the smaller ones (answers carried forward) swapped for a pipe, an endless file and one
    # too large; the solution at the problem's own givens and the plan stay, edited
    solutions[0].unlink()
    os.mkfifo(solutions[0], 0o600)
    solutions[1].unlink()
    solutions[1].symlink_to("/dev/zero")
    solutions[2].write_bytes(b"[" + b"0," * 5_000_000 + b"0]")
    mine = {"results.json": b"{}", "backup.json": b"[]", "entries/notes.json": b"{}"}
    for name, data in mine.items():
        (folder / name).write_bytes(data)
    tampered, after = _graded(top, "tampered", folder)
    again, warm = _graded(top, "again", folder)
    return {"cold": cold, "tampered": after, "warm": warm, "runs": (tampered, again),
            "folder": folder, "mine": mine}


@pytest.mark.slow  # three gradings of a class through subprocesses
def test_a_tampered_cache_folder_changes_no_result(tampered_cache):
    assert tampered_cache["tampered"] == tampered_cache["cold"]
    assert tampered_cache["warm"] == tampered_cache["cold"]  # what it wrote again reads back


@pytest.mark.slow  # three gradings of a class through subprocesses
def test_a_tampered_cache_folder_is_no_warning_and_loses_no_file_of_the_users(tampered_cache):
    for run in tampered_cache["runs"]:
        assert "cache" not in run.stderr
    for name, data in tampered_cache["mine"].items():
        assert (tampered_cache["folder"] / name).read_bytes() == data


@pytest.mark.slow
def test_a_cache_folder_others_may_write_is_one_warning_of_a_grading_run(hostile, tmp_path):
    # the run's workers (two) find the same folder and say nothing: only the command prints
    shared = tmp_path / "shared"
    shared.mkdir()
    shared.chmod(0o777)
    answers = tmp_path / "class" / "ann" / "answers.yaml"
    answers.parent.mkdir(parents=True)
    answers.write_text("bowling_3_15_4_pendulum:\n  acc_mag: 98.5 ft/s^2\n", encoding="utf-8")
    done, results = _graded(tmp_path, "out", shared, hostile["top"] / "hw.yaml",
                            tmp_path / "class")
    assert [line for line in done.stderr.splitlines() if "cache" in line] == [
        f"warning: cache folder {shared} may be written by other users (mode 777): not using "
        f"the cache in this run (make it private with 'chmod 700 {shared}', or set "
        "MECHGRADE_CACHE_DIR to a private folder)"]
    assert json.loads(results)["students"][0]["score"] > 0
    assert list(shared.iterdir()) == []
