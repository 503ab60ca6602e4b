"""The class report counts the loads students left out of or turned round in their equations
of motion ("left out of an equation: the kinetic friction F_P on block", 2 of 3)."""

from __future__ import annotations

from mechgrade.grade.equations import judge_equations
from mechgrade.grade.results import (AnswerResult, AssignmentInfo, GradeReport, ObjectiveInfo,
                                     Status, StudentResult)
from mechgrade.report.class_report import class_statistics
from mechgrade.solve.derivation import MotionSamples, SampledLoad
from mechgrade.spec.dynamics import LoadKind

# a block pulled by a spring (k x) and held back by a friction (mu m g), at three states
STATES = ((0.5, 2.0, 9.81, 10.0, 0.2, -1.0, 0.0), (0.4, 3.0, 9.0, 12.0, 0.3, -1.0, 0.0),
          (0.6, 1.5, 9.5, 8.0, 0.25, -1.0, 0.0))
SAMPLES = MotionSamples(
    ("x", "m", "g", "k", "mu", "xd"), ("xdd",), (),
    tuple((*s[:6], (-s[3] * s[0] - s[4] * s[1] * s[2]) / s[1]) for s in STATES),
    (SampledLoad("F_s", LoadKind.SPRING, "block", (tuple(-s[3] * s[0] for s in STATES),)),
     SampledLoad("F_f", LoadKind.KINETIC_FRICTION, "block",
                 (tuple(-s[4] * s[1] * s[2] for s in STATES),))))


def test_the_class_report_counts_the_loads_left_out_of_equations():
    texts = {"ana": "m x'' = -k x - mu m g", "ben": "m x'' = -k x", "cy": "m x'' = -k x"}
    answers = {sid: judge_equations(text, SAMPLES).assessment for sid, text in texts.items()}
    assert answers["ben"].diagnosis == ("left out of an equation: the kinetic friction F_f on "
                                        "block")
    students = tuple(StudentResult(sid, sid, Status.GRADED, 2.0 * a.credit, 2.0, (AnswerResult(
        "p", "equations", texts[sid], a.verdict, 2.0 * a.credit, 2.0, a.diagnosis,
        a.feedback),)) for sid, a in answers.items())
    report = GradeReport(AssignmentInfo("hw", "HW"),
                         (ObjectiveInfo("p", "equations", "The equations of motion.", 2.0),),
                         students)
    (stats,) = class_statistics(report, charts=False).objectives
    assert [(c.label, c.count) for c in stats.diagnoses] == [
        ("left out of an equation: the kinetic friction F_f on block", 2)]
