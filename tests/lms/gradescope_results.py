"""Gradescope's autograder ``results.json``, re-implemented for the tests from its
specification (gradescope/autograder_samples ``docs/specs.md`` at commit af5dee4):

* the document's fields and their types ("Output format", lines 37-73);
* visibility: ``hidden`` never shown, ``after_due_date`` after the due date,
  ``after_published`` once published, ``visible`` always; a test's own ``visibility``
  overrides the top level's (lines 90-106); while any test is hidden the student does not
  see the total score (lines 108-109);
* a test's status, when not given: passed when it scored its ``max_score`` (lines 124-131);
* the ``*_format`` values (lines 162-174).
"""

from __future__ import annotations

from dataclasses import dataclass

VISIBILITIES = ("hidden", "after_due_date", "after_published", "visible")
FORMATS = ("text", "html", "simple_format", "md", "ansi")
_TOP = {"score": (int, float), "execution_time": (int, float), "output": str,
        "output_format": str, "test_output_format": str, "test_name_format": str,
        "visibility": str, "stdout_visibility": str, "extra_data": dict, "tests": list,
        "leaderboard": list}
_TEST = {"score": (int, float), "max_score": (int, float), "status": str, "name": str,
         "name_format": str, "number": str, "output": str, "output_format": str, "tags": list,
         "visibility": str, "extra_data": dict}


def check_results(doc: dict) -> None:
    """Fail (``AssertionError`` naming the field) unless ``doc`` is a results.json as the
    specification describes it: known fields of the documented types, a ``score`` at the top
    or on every test, visibilities and formats among the documented values."""
    assert isinstance(doc, dict), "results.json: expected an object"
    for key, value in doc.items():
        assert key in _TOP, f"results.json: unknown field {key!r}"
        assert isinstance(value, _TOP[key]) and not isinstance(value, bool), \
            f"results.json: {key}: expected {_TOP[key]}, found {value!r}"
    tests = doc.get("tests", [])
    assert "score" in doc or (tests and all("score" in t for t in tests)), \
        "results.json: a score is required at the top or on every test"
    for field in ("visibility", "stdout_visibility"):
        assert doc.get(field, "visible") in VISIBILITIES, f"results.json: {field}"
    for field in ("output_format", "test_output_format", "test_name_format"):
        assert doc.get(field, "text") in FORMATS, f"results.json: {field}"
    for i, test in enumerate(tests):
        assert isinstance(test, dict), f"tests[{i}]: expected an object"
        for key, value in test.items():
            assert key in _TEST, f"tests[{i}]: unknown field {key!r}"
            assert isinstance(value, _TEST[key]) and not isinstance(value, bool), \
                f"tests[{i}].{key}: expected {_TEST[key]}, found {value!r}"
        assert test.get("status", "passed") in ("passed", "failed"), f"tests[{i}].status"
        assert test.get("visibility", "visible") in VISIBILITIES, f"tests[{i}].visibility"


@dataclass(frozen=True)
class StudentView:
    """What the student sees: the tests shown (in order), whether the total is shown."""

    tests: tuple[dict, ...]
    total_shown: bool
    score: float | None

    def text(self) -> str:
        """Every name and output the student can read, one after the other."""
        return "\n".join(f"{t.get('name', '')}\n{t.get('output', '')}" for t in self.tests)


def shown(visibility: str, *, due_passed: bool, published: bool) -> bool:
    return {"hidden": False, "after_due_date": due_passed, "after_published": published,
            "visible": True}[visibility]


def student_view(doc: dict, *, due_passed: bool = False, published: bool = False
                 ) -> StudentView:
    """What a student sees of ``doc`` (checked first with :func:`check_results`)."""
    check_results(doc)
    default = doc.get("visibility", "visible")
    tests = doc.get("tests", [])
    visible = tuple(t for t in tests if shown(t.get("visibility", default),
                                              due_passed=due_passed, published=published))
    total_shown = len(visible) == len(tests)
    score = doc.get("score", sum(t.get("score", 0) for t in tests))
    return StudentView(visible, total_shown, float(score) if total_shown else None)


def status(test: dict) -> str:
    """A test's status as Gradescope shows it."""
    if "status" in test:
        return test["status"]
    return "passed" if test.get("score") == test.get("max_score") else "failed"
