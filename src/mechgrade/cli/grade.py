"""``mechgrade grade``: grade a folder of submissions and write feedback, results and grades."""

from __future__ import annotations

import atexit
import gc
import sys
from pathlib import Path

import click

from ..files import visible_text
from ..grade.submissions import SubmissionFormat
from ..grade.results import Status, Verdict
from ..roster import read_roster
from .common import (INTERNAL_ERROR_EXIT, claim_out, listed, main, output_lines,
                     reports_errors, run_arguments, run_inputs, say, warn_about_the_cache)


@main.command("grade")
@click.argument("assignment", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.argument("submissions_dir", type=click.Path(exists=True, path_type=Path))
@click.option("--out", "out_dir", required=True, type=click.Path(file_okay=False, path_type=Path),
              help="Folder for results.json, grades.csv, results.csv and feedback/.")
@click.option("--roster", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              help="Class roster: Canvas or Moodle gradebook export, or a plain CSV.")
@click.option("--templates", "templates_dir",
              type=click.Path(exists=True, file_okay=False, path_type=Path),
              help="Folder with feedback.html.j2 and feedback.md.j2 to use instead of the "
                   "shipped templates.")
@click.option("--jobs", "-j", type=click.IntRange(min=1), default=None,
              help="Processes to grade with (default: one per core). The outputs are the same "
                   "for any number.")
@click.option("--submissions-format", type=click.Choice([f.value for f in SubmissionFormat]),
              default=None,
              help="What SUBMISSIONS_DIR is (default: detected): a folder, an LMS's download "
                   "zip or a quiz's responses CSV.")
@click.option("--accept-failing-expect", is_flag=True,
              help="Grade even if a problem fails its own expect: tests (refused otherwise); "
                   "every output records the tests it fails.")
@reports_errors
def grade(assignment: Path, submissions_dir: Path, out_dir: Path, roster: Path | None,
          templates_dir: Path | None, jobs: int | None, submissions_format: str | None,
          accept_failing_expect: bool) -> None:
    """Grade every submission in SUBMISSIONS_DIR against ASSIGNMENT.

    SUBMISSIONS_DIR is a folder, or what an LMS hands out: a Canvas, Moodle or Gradescope
    download zip, or a Canvas or Moodle quiz's responses CSV.

    A bad assignment stops with one message (exit code 2); a bad submission never stops the
    run: it is reported in that student's feedback and in the summary.
    """
    # Here, not at the top: sympy and the solver load only when a run starts (not for --help).
    from ..grade.assignment import load_assignment
    from ..grade.run import grade_submissions
    from ..outfolder import check_apart
    from ..parallel import default_jobs
    from ..report.output import GRADE_OUTPUTS, TEMPLATE_NAMES, write_outputs

    check_apart(out_dir, submissions_dir)
    folder = claim_out(out_dir, GRADE_OUTPUTS)  # locked now: a second run is refused at once
    jobs = jobs if jobs is not None else default_jobs()
    spec = load_assignment(assignment)
    warn_about_the_cache()
    class_roster = read_roster(roster) if roster is not None else None
    bar = None

    def progress(done: int, total: int) -> None:
        nonlocal bar
        if bar is None:
            bar = click.progressbar(length=total, label="Grading", file=sys.stderr,
                                    show_pos=True)
            bar.__enter__()
        bar.update(done - bar.pos)

    try:
        report = grade_submissions(spec, submissions_dir, class_roster, progress=progress,
                                   jobs=jobs, submissions_format=(
                                       None if submissions_format is None
                                       else SubmissionFormat(submissions_format)),
                                   accept_failing_expect=accept_failing_expect)
    finally:
        if bar is not None:
            bar.__exit__(None, None, None)
    # Imported once graded: it loads the solver, which the processes forked at the start
    # of grading (reading the submissions) do without.
    from ..grade.worked import shown_solutions

    worked = shown_solutions(spec, report)  # the assignment's worked_solution rule
    report = write_outputs(report, folder.staging, templates_dir, roster=class_roster,
                           jobs=jobs, worked=worked).report
    done = folder.commit(run_arguments(), inputs=run_inputs(
        assignment=assignment, spec=spec, roster=roster, templates_dir=templates_dir,
        template_names=TEMPLATE_NAMES))
    say(summary(report, out_dir, done))
    # At exit the interpreter's last collection need not walk every object of the run
    # (a tenth of a second or more); registered once, whatever runs in this process.
    atexit.unregister(gc.freeze)
    atexit.register(gc.freeze)
    if report.internal_errors:
        sys.exit(INTERNAL_ERROR_EXIT)


def summary(report, out_dir: Path, done=None) -> str:
    """The run summary: the count line, then every skipped entry, note and internal error, and
    what replacing ``--out`` removed and kept (``done``)."""
    lines = [summary_line(report, out_dir)]
    for title, items in (
            ("Graded although the problems fail these expect: tests (--accept-failing-expect)",
             [str(f) for f in report.failing_expects]),
            ("Skipped (not read as anyone's answers)",
             [f"{e.path}: {e.reason}" for e in report.skipped]),
            ("Notes", list(report.notes)),
            ("Internal errors (not evaluated; please report them)",
             list(report.internal_errors))):
        lines.extend(listed(title, items, "results.json"))
    lines.extend(output_lines(done) if done is not None else ())
    return "\n".join(visible_text(line) for line in lines)


def summary_line(report, out_dir: Path) -> str:
    """``Graded 6 students (2 unreadable answers, 1 missing submission); wrote out/.``"""
    graded = sum(1 for s in report.students if s.status == Status.GRADED)
    unreadable_students = sum(1 for s in report.students if s.status == Status.UNREADABLE)
    missing = sum(1 for s in report.students if s.status == Status.MISSING)
    not_evaluated = sum(1 for s in report.students if s.status == Status.NOT_EVALUATED)
    unreadable = sum(1 for s in report.students if s.status == Status.GRADED
                     for a in s.answers if a.verdict == Verdict.UNREADABLE)
    parts = [_count(unreadable, "unreadable answer")]
    if unreadable_students:
        parts.append(_count(unreadable_students, "unreadable submission"))
    parts.append(_count(missing, "missing submission"))
    if not_evaluated:
        parts.append(f"{_count(not_evaluated, 'student')} not evaluated")
    conflicts = sum(1 for s in report.students if s.status == Status.CONFLICT)
    if conflicts:
        parts.append(f"{conflicts} in roster conflicts (students and folders)")
    if report.skipped:
        parts.append(_count(len(report.skipped), "skipped entry", "skipped entries"))
    return (f"Graded {_count(graded, 'student')} ({', '.join(parts)}); "
            f"wrote {out_dir.as_posix().rstrip('/')}/")


def _count(n: int, noun: str, plural: str | None = None) -> str:
    return f"{n} {noun if n == 1 else plural or noun + 's'}"
