"""Gradescope autograder ``results.json``.

Gradescope runs ``/autograder/run_autograder`` once per submission and uploads
``/autograder/results/results.json``. Per Gradescope's autograder specification the document
has a top-level ``score`` (it overrides the sum of the tests), ``output``, ``visibility`` and
``tests``: a list of objects with ``score``, ``max_score``, ``status`` (``"passed"`` or
``"failed"``), ``name``, ``number``, ``output`` and ``visibility``. mechgrade writes one test per
objective and sets every ``*_format`` to ``"text"`` so student text is never rendered as HTML.

Students can resubmit without limit, so whatever a test shows before the due date can be
harvested (an upload answering ``0`` everywhere would collect every expected answer): an
expected answer (an assignment with ``reveal_answers``) is in a test of its own, shown only
after the due date. A first test, always visible, says what was read, so a student whose tests
are shown after the due date still knows the upload was read.

With one student in the report the file is written at ``out_path``; with several, ``out_path``
is a folder that receives ``<student id>.json`` per student (for inspection; Gradescope itself
always grades one submission at a time).

>>> from mechgrade.grade.results import (AnswerResult, AssignmentInfo, GradeReport,
...                                      ObjectiveInfo, StudentResult)
>>> obj = ObjectiveInfo("p1", "v_B", "Speed of B", 2.0)
>>> ans = AnswerResult("p1", "v_B", "3*omega", "correct", 2.0, 2.0)
>>> s = StudentResult("s1", "Ada", "graded", 2.0, 2.0, (ans,))
>>> doc = gradescope_results(GradeReport(AssignmentInfo("hw1", "HW 1"), (obj,), (s,)), s)
>>> doc["score"], doc["tests"][1]["status"], doc["tests"][1]["name"]
(2.0, 'passed', 'p1/v_B: Speed of B')
>>> print(doc["tests"][0]["output"])
Answers read (1 of 1):
  p1/v_B = 3*omega
Score: 2 / 2 points
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import ExportError
from ..grade.results import GradeReport, Status, StudentResult, Verdict
from ..roster import Roster
from ..files import safe_file_names
from .cells import format_points, write_json
from .common import answers_by_objective, has_submission, max_score, objective_label
from .options import ExportOptions, Visibility


def export_gradescope(report: GradeReport, out_path: str | os.PathLike, *,
                      roster: Roster | None = None,  # noqa: ARG001 - every exporter's signature
                      options: ExportOptions = ExportOptions()) -> tuple[str, ...]:
    """Write Gradescope ``results.json`` (see module doc). The roster is not used."""
    if not report.students:
        raise ExportError("expected at least one student in the results for a Gradescope "
                          "results.json, found none")
    if not writes_folder(report):
        write_json(out_path, gradescope_results(report, report.students[0], options))
        return ()
    folder = Path(out_path)
    try:
        folder.mkdir(exist_ok=True)
    except OSError as err:
        raise ExportError(f"{folder}: expected a folder for one results.json per student, "
                          f"could not make it: {err.strerror}") from None
    names = safe_file_names([student.id for student in report.students])
    for student, name in zip(report.students, names):
        write_json(folder / f"{name}.json", gradescope_results(report, student, options))
    return ()


def writes_folder(report: GradeReport) -> bool:
    """Whether the export of ``report`` is a folder (one file per student): several students."""
    return len(report.students) > 1


def gradescope_failure(message: str, options: ExportOptions = ExportOptions()) -> dict:
    """A ``results.json`` for a run that could not grade at all (a broken assignment): score 0
    and the reason, so Gradescope shows it instead of a generic autograder failure.

    >>> gradescope_failure("assignment.yaml:3:1: problems: expected a list")["score"]
    0.0
    """
    return {"score": 0.0, "output": f"The autograder could not grade this submission: "
                                    f"{message}", "output_format": "text",
            "visibility": options.gradescope_visibility.value, "tests": []}


RECEIPT = "Submission received"
EXPECTED_VISIBILITY = {Visibility.VISIBLE: Visibility.AFTER_DUE_DATE,
                       Visibility.AFTER_DUE_DATE: Visibility.AFTER_DUE_DATE,
                       Visibility.AFTER_PUBLISHED: Visibility.AFTER_PUBLISHED,
                       Visibility.HIDDEN: Visibility.HIDDEN}
"""The visibility of the tests holding expected answers, for each chosen visibility: never
before the due date (students resubmit without limit and would harvest them)."""


def gradescope_results(report: GradeReport, student: StudentResult,
                       options: ExportOptions = ExportOptions()) -> dict:
    """The Gradescope ``results.json`` document of one student.

    Its tests: first a receipt, always visible, saying what was read (and the score, when the
    other tests are visible too: Gradescope hides the total while any test is hidden); then
    one test per objective (``options.gradescope_visibility``: the answer as read, verdict,
    points, diagnosis); then, when the assignment reveals answers, one test per objective with
    the expected answer, shown only after the due date (:data:`EXPECTED_VISIBILITY`).
    """
    visibility = options.gradescope_visibility
    total = max_score(report) or student.max_score
    tests = [_receipt(report, student, visibility, total)]
    expected = []
    for objective, answer in answers_by_objective(report, student):
        lines = [f"Your answer: {answer.answer}" if answer.answer is not None
                 else "Your answer: (none found)"]
        if answer.read_back and answer.read_back != answer.answer:
            lines.append(f"Read as: {answer.read_back}")
        lines.append(f"Verdict: {answer.verdict.replace('_', ' ')}")
        lines.extend(text for text in (answer.diagnosis, answer.feedback) if text)
        name = objective_label(objective)
        title = f"{name}: {objective.prompt}" if objective.prompt else name
        tests.append({
            "name": title,
            "number": str(len(tests)),
            "score": float(answer.points),
            "max_score": float(answer.max_points),
            "status": "passed" if answer.verdict == Verdict.CORRECT else "failed",
            "output": "\n".join(lines),
            "visibility": visibility.value,
        })
        if answer.expected is not None:
            expected.append({"name": f"{name}: expected answer",
                             "output": f"Expected: {answer.expected}",
                             "visibility": EXPECTED_VISIBILITY[visibility].value})
    for test in expected:
        tests.append({**test, "number": str(len(tests))})
    summary = [f"{report.assignment.title}: {format_points(student.score)} / "
               f"{format_points(total)} points"]
    if not has_submission(student):
        summary.append("No submission was found.")
    elif student.status == Status.UNREADABLE:
        summary.append("The submission could not be read.")
    summary.extend(student.messages)
    return {
        "score": float(student.score),
        "output": "\n".join(summary),
        "output_format": "text",
        "test_output_format": "text",
        "test_name_format": "text",
        "visibility": visibility.value,
        "tests": tests,
    }


_LATER = {Visibility.AFTER_DUE_DATE: "after the due date",
          Visibility.AFTER_PUBLISHED: "when the grades are published",
          Visibility.HIDDEN: "by your instructor only"}


def _receipt(report: GradeReport, student: StudentResult, visibility: Visibility,
             total: float) -> dict:
    """The always-visible test that says what the autograder read (no points of its own)."""
    lines = list(student.messages)
    answered = [(o, a) for o, a in answers_by_objective(report, student)
                if (a.answer or "").strip()]
    if not has_submission(student):
        lines.append("No submission was found.")
    elif student.status == Status.UNREADABLE:
        lines.append("The submission could not be read.")
    else:
        lines.append(f"Answers read ({len(answered)} of {len(report.objectives)}):")
        lines.extend(f"  {objective_label(o)} = {a.answer}" for o, a in answered)
    if visibility is Visibility.VISIBLE:
        lines.append(f"Score: {format_points(student.score)} / {format_points(total)} points")
    else:
        lines.append(f"The score and the verdicts are shown {_LATER[visibility]}.")
    read = has_submission(student) and student.status == Status.GRADED
    return {"name": RECEIPT, "number": "0", "status": "passed" if read else "failed",
            "output": "\n".join(lines), "visibility": "visible"}
