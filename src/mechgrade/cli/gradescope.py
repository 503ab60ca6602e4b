"""``mechgrade gradescope``: run as a Gradescope autograder for one submission."""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import click

from ..errors import MechgradeError, brief_exception
from ..files import write_json
from ..export.gradescope import gradescope_failure, gradescope_results
from ..export.options import ExportOptions, Visibility
from ..grade.upload import read_upload, submitter
from ..grade.assignment import load_assignment
from ..grade.run import failing_expects, failing_expects_error, grade_plan, plan_assignment
from ..grade.submissions import SubmissionSet
from .common import INTERNAL_ERROR_EXIT, UserFailure, main, say, warn_about_the_cache


@main.command("gradescope")
@click.argument("assignment", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--submission", "submission_dir", default="/autograder/submission",
              show_default=True, type=click.Path(file_okay=False, path_type=Path),
              help="The student's upload: answers.yaml (.json, .txt), a renamed answers file "
                   "or a zipped folder holding one.")
@click.option("--results", "results_path", default="/autograder/results/results.json",
              show_default=True, type=click.Path(dir_okay=False, path_type=Path),
              help="Where Gradescope expects results.json.")
@click.option("--metadata", "metadata_path", default="/autograder/submission_metadata.json",
              show_default=True, type=click.Path(dir_okay=False, path_type=Path),
              help="Gradescope's submission metadata (names the student; optional).")
@click.option("--visibility", type=click.Choice([v.value for v in Visibility]),
              default="visible", show_default=True,
              help="Visibility of the results and tests; 'after_due_date' keeps revealed "
                   "answers from students until the due date.")
@click.option("--accept-failing-expect", is_flag=True,
              help="Grade even if a problem fails its own expect: tests (refused otherwise); "
                   "the student's results say so.")
def gradescope(assignment: Path, submission_dir: Path, results_path: Path,
               metadata_path: Path, visibility: str, accept_failing_expect: bool) -> None:
    """Grade one Gradescope submission against ASSIGNMENT and write results.json.

    A broken assignment or unreadable metadata still writes a results.json that says why
    (score 0), and exits 2.
    """
    options = ExportOptions(gradescope_visibility=Visibility(visibility))
    try:
        student, name = submitter(metadata_path)
        spec = load_assignment(assignment)
        warn_about_the_cache()
        plan = plan_assignment(spec)
        failing = failing_expects(plan)
        if failing and not accept_failing_expect:
            # the student sees which questions, never the values check compares
            _write_failure(results_path, f"the answer key fails its author's own checks "
                                         f"({_questions(failing)}); please tell your instructor",
                           options)
            raise UserFailure(str(failing_expects_error(failing)))
        upload = read_upload(submission_dir, student, keys=plan.keys)
        report = grade_plan(plan, SubmissionSet(submission_dir, (upload.submission,)),
                            accept_failing_expect=True)
        result = report.students[0]
        if name and not result.name:
            result = replace(result, name=name)
        if failing:
            result = replace(result, messages=(
                f"The reference answers to these questions fail their author's own checks; "
                f"your instructor graded them anyway, and their points may change: "
                f"{_questions(failing)}.", *result.messages))
        write_json(results_path, gradescope_results(report, result, options))
    except MechgradeError as err:
        _write_failure(results_path, str(err), options)
        raise UserFailure(str(err)) from None
    except UserFailure:
        raise
    except Exception as exc:  # noqa: BLE001 - Gradescope must always get a results.json
        message = (f"internal error while grading this submission: {brief_exception(exc)}; "
                   f"please tell your instructor")
        _write_failure(results_path, message, options)
        say(message, err=True)
        sys.exit(INTERNAL_ERROR_EXIT)
    read = f" (read {upload.read_from})" if upload.read_from else ""
    say(f"{student}: {result.score:g} / {result.max_score:g} points{read}; wrote "
        f"{results_path}")


def _questions(failing) -> str:
    return ", ".join(f"{f.problem} · {f.objective}" for f in failing)


def _write_failure(results_path: Path, message: str, options: ExportOptions) -> None:
    try:
        write_json(results_path, gradescope_failure(message, options))
    except MechgradeError:
        pass  # the message still reaches the autograder log through stderr
