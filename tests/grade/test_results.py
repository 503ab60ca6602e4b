"""Verdicts and statuses are enums whose members are the very strings the written files hold."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import pytest

from mechgrade.expressions.loads import LoadKind
from mechgrade.files import json_text
from mechgrade.grade.results import GradeReport, Status, Verdict
from mechgrade.report.output import write_outputs

GOOD = json.loads((Path(__file__).parent.parent / "data" / "export" / "results.json")
                  .read_text(encoding="utf-8"))


def _as_plain_strings(report: GradeReport) -> GradeReport:
    """The same report with every verdict and status a plain ``str`` (as before the enums)."""
    return replace(report, students=tuple(
        replace(s, status=str(s.status.value), answers=tuple(
            replace(a, verdict=str(a.verdict.value)) for a in s.answers))
        for s in report.students))


def test_a_read_results_json_holds_enum_members():
    report = GradeReport.from_json(GOOD)
    assert {type(s.status) for s in report.students} == {Status}
    assert {type(a.verdict) for s in report.students for a in s.answers} == {Verdict}
    assert {a.verdict for s in report.students for a in s.answers} >= {Verdict.CORRECT,
                                                                        Verdict.MISSING}


def test_an_unknown_verdict_is_refused_when_read():
    doc = json.loads(json.dumps(GOOD))
    doc["students"][0]["answers"][0]["verdict"] = "right"
    with pytest.raises(ValueError, match=r"AnswerResult.verdict: expected a Verdict, found 'right'"):
        GradeReport.from_json(doc)


def test_every_written_file_is_byte_identical_to_one_written_from_plain_strings(tmp_path):
    report = GradeReport.from_json(GOOD)
    plain = _as_plain_strings(report)
    assert json_text(report.to_json()) == json_text(plain.to_json())
    write_outputs(report, tmp_path / "enum")
    write_outputs(plain, tmp_path / "text")
    written = sorted(p.relative_to(tmp_path / "enum")
                     for p in (tmp_path / "enum").rglob("*") if p.is_file())
    assert Path("results.json") in written and Path("grades.csv") in written
    assert any(p.suffix == ".html" for p in written)
    for name in written:
        assert (tmp_path / "enum" / name).read_bytes() == (tmp_path / "text" / name).read_bytes(), name


def test_a_verdict_is_shown_as_its_text_wherever_it_is_formatted():
    assert (str(Verdict.NOT_EVALUATED), f"{Verdict.PARTIAL:>8}", "%s" % Status.CONFLICT) == \
        ("not_evaluated", " partial", "conflict")
    assert json.dumps([Verdict.CORRECT, Status.GRADED]) == '["correct", "graded"]'


def test_results_json_keeps_its_shape_through_the_codec():
    from mechgrade.grade.results import (AnswerResult, AssignmentInfo, FailingExpect,
                                         StudentResult, StudentVariant, VariantGiven)

    student = StudentResult("s1", "Ada", Status.GRADED, 2.0, 3.0,
                            (AnswerResult("p", "v", "7 m/s", Verdict.PARTIAL, 2.0, 3.0),),
                            identity=(("email", "ada@x"), ("sis", "42")))
    plain = GradeReport(AssignmentInfo("hw", "HW"), (), (student,))
    data = plain.to_json()
    assert data["students"][0]["identity"] == {"email": "ada@x", "sis": "42"}
    # written only when there is one: files without them read as before
    assert "variant" not in data["students"][0] and "failing_expects" not in data
    full = replace(plain, students=(replace(student, variant=StudentVariant(
        "seed", (VariantGiven("p", "a", 1.5, "m"),))),),
        failing_expects=(FailingExpect("p", "v", "p.yaml:3:1", "7 != 8"),))
    data = json.loads(json.dumps(full.to_json()))
    assert data["students"][0]["variant"]["givens"][0]["value"] == 1.5
    assert GradeReport.from_json(data) == full


def test_a_results_json_without_names_or_objectives_is_read_with_them_empty():
    report = GradeReport.from_json({"assignment": {"id": "a", "title": "A"}, "students": [
        {"id": "s", "status": "missing", "score": 0, "max_score": 1}]})
    assert (report.objectives, report.students[0].name) == ((), "")


def test_a_value_of_another_type_in_results_json_is_refused():
    from mechgrade.codec import CodecError

    doc = json.loads(json.dumps(GOOD))
    doc["students"][0]["identity"] = {"email": 3}
    with pytest.raises(CodecError, match=r"StudentResult.identity: expected a text, found int"):
        GradeReport.from_json(doc)


def _with_a_diagram(kind: str) -> dict:
    """GOOD with its first answer a free-body diagram of one row of load kind ``kind``."""
    doc = json.loads(json.dumps(GOOD))
    doc["students"][0]["answers"][0]["loads"] = [
        {"label": "friction", "load": "F_P", "kind": kind, "point": "P", "answer": None,
         "mistakes": ["missing"], "feedback": ""}]
    return doc


def test_a_diagrams_load_kind_is_read_as_its_member_and_written_as_its_text():
    doc = _with_a_diagram("kinetic friction")
    report = GradeReport.from_json(doc)
    row = report.students[0].answers[0].loads[0]
    assert row.kind is LoadKind.KINETIC_FRICTION
    assert report.to_json()["students"][0]["answers"][0]["loads"] == \
        doc["students"][0]["answers"][0]["loads"]


def test_an_unknown_load_kind_is_refused_when_read():
    with pytest.raises(ValueError, match=r"LoadResult.kind: expected one of LoadKind, NoneType"):
        GradeReport.from_json(_with_a_diagram("drag"))
