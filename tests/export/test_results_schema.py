"""results.json is checked against its shipped JSON Schema, with located messages."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import pytest

from mechgrade.errors import ExportError
from mechgrade.export import read_results, results_schema
from mechgrade.grade.results import STATUSES, VERDICTS

DATA = Path(__file__).parent.parent / "data" / "export"
GOOD = json.loads((DATA / "results.json").read_text(encoding="utf-8"))


def test_the_schema_enums_are_the_statuses_and_verdicts_of_grade_results():
    defs = results_schema()["$defs"]
    assert tuple(defs["student"]["properties"]["status"]["enum"]) == STATUSES
    assert tuple(defs["answer"]["properties"]["verdict"]["enum"]) == VERDICTS


def test_a_results_json_written_by_mechgrade_passes(tmp_path):
    path = tmp_path / "results.json"
    path.write_text(json.dumps(GOOD), encoding="utf-8")
    assert len(read_results(path).students) == 7


def test_an_expected_answer_in_the_students_unit_is_read(tmp_path):
    doc = copy.deepcopy(GOOD)  # GOOD itself was written before answers kept it
    doc["students"][0]["answers"][0].update(expected="36.79 N", expected_in_answer_unit="8.27 lbf")
    path = tmp_path / "results.json"
    path.write_text(json.dumps(doc), encoding="utf-8")
    answer = read_results(path).students[0].answers[0]
    assert (answer.expected, answer.expected_in_answer_unit) == ("36.79 N", "8.27 lbf")


def set_in(doc, path, value):
    target = doc
    for part in path[:-1]:
        target = target[part]
    if value is DELETE:
        del target[path[-1]]
    else:
        target[path[-1]] = value


DELETE = object()


@pytest.mark.parametrize("path, value, message", [
    (("students", 3, "status"), "absent",
     "students[3].status: expected one of graded, missing, unreadable, not_evaluated, conflict, found "
     "'absent'"),
    (("students", 2, "answers", 0, "verdict"), "great",
     "students[2].answers[0].verdict: expected one of correct, partial, incorrect, unreadable, "
     "missing, not_evaluated, found 'great'"),
    (("students", 1, "score"), "5", "students[1].score: expected a number, found '5'"),
    (("students", 1, "score"), True, "students[1].score: expected a number, found true"),
    (("students", 0, "id"), DELETE, "students[0]: expected a field 'id', found none"),
    (("students", 0, "answers", 1, "answer"), 3,
     "students[0].answers[1].answer: expected text or null, found 3"),
    (("students", 0, "messages"), ["ok", 4], "students[0].messages[1]: expected text, found 4"),
    (("students", 0, "identity"), {"email": 5},
     "students[0].identity.email: expected text, found 5"),
    (("students", 0, "grade"), 3,
     "students[0].grade: expected only the fields id, name, status, score, max_score, answers, "
     "messages, identity, variant, found 'grade'"),
    (("students", 0, "answers", 0, "expected_in_answer_unit"), 8.27,
     "students[0].answers[0].expected_in_answer_unit: expected text or null, found 8.27"),
    (("assignment",), DELETE, "expected a field 'assignment', found none"),
    (("assignment", "title"), None, "assignment.title: expected text, found null"),
    (("objectives", 0, "max_points"), DELETE,
     "objectives[0]: expected a field 'max_points', found none"),
    (("skipped",), [{"path": "x"}], "skipped[0]: expected a field 'reason', found none"),
    (("notes",), "a note", "notes: expected a list, found 'a note'"),
    (("extra",), 1, "extra: expected only the fields assignment, objectives, students, skipped, notes, "
                    "internal_errors, failing_expects, found 'extra'"),
])
def test_each_violation_is_one_located_message(tmp_path, path, value, message):
    doc = copy.deepcopy(GOOD)
    set_in(doc, path, value)
    bad = tmp_path / "results.json"
    bad.write_text(json.dumps(doc), encoding="utf-8")
    with pytest.raises(ExportError) as caught:
        read_results(bad)
    assert str(caught.value) == f"{bad}: {message}"


def test_a_document_that_is_not_a_mapping_is_refused(tmp_path):
    bad = tmp_path / "results.json"
    bad.write_text("[1, 2, 3]", encoding="utf-8")
    with pytest.raises(ExportError) as caught:
        read_results(bad)
    assert str(caught.value) == f"{bad}: expected a mapping, found a list of 3"


def test_the_first_violation_in_document_order_is_reported(tmp_path):
    doc = copy.deepcopy(GOOD)
    doc["students"][5]["status"] = "x"
    doc["students"][2]["status"] = "y"
    bad = tmp_path / "results.json"
    bad.write_text(json.dumps(doc), encoding="utf-8")
    with pytest.raises(ExportError, match=r"students\[2\]\.status: .*found 'y'$"):
        read_results(bad)
