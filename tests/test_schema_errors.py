"""The one JSON-Schema error translator: every keyword in the located 'expected, found' style."""

from __future__ import annotations

import pytest

from mechgrade.schema_errors import describe, field_text, schema_problems


@pytest.mark.parametrize("schema, data, text", [
    ({"type": "object"}, [1], "(top level): expected a mapping, found a list of 1"),
    ({"type": ["string", "null"]}, 2, "(top level): expected text or null, found 2"),
    ({"type": "integer"}, 2.5, "(top level): expected a whole number, found 2.5"),
    ({"enum": ["a", "b"]}, "c", "(top level): expected one of a, b, found 'c'"),
    ({"const": "x"}, "y", "(top level): expected 'x', found 'y'"),
    ({"minimum": 0}, -1, "(top level): expected a number >= 0, found -1"),
    ({"exclusiveMinimum": 0}, 0, "(top level): expected a number > 0, found 0"),
    ({"maximum": 1}, 2, "(top level): expected a number <= 1, found 2"),
    ({"minItems": 1}, [], "(top level): expected at least 1 item(s), found an empty list"),
    ({"maxItems": 1}, [1, 2], "(top level): expected at most 1 item(s), found a list of 2"),
    ({"minLength": 1}, "", "(top level): expected at least 1 character(s), found empty text"),
    ({"maxLength": 2}, "abc", "(top level): expected at most 2 character(s), found 3 characters"),
    ({"minProperties": 1}, {}, "(top level): expected at least 1 field(s), found an empty mapping"),
    ({"pattern": "^[a-z]+$"}, "A1", "(top level): expected text matching ^[a-z]+$, found 'A1'"),
    ({"pattern": "^[^=]+=[^=]+$", "x-expected": "an equation 'left = right'"}, "x",
     "(top level): expected an equation 'left = right', found 'x'"),
    ({"properties": {"a": {"properties": {"b": {"type": "string"}}}}}, {"a": {"b": 1}},
     "a.b: expected text, found 1"),
    ({"items": {"required": ["id"]}}, [{"id": 1}, {}], "[1]: expected a field 'id', found none"),
    ({"additionalProperties": False, "patternProperties": {"^x_": {}}}, {"x_a": 1, "y": 2},
     "y: expected only the fields named like ^x_, found 'y'"),
    ({"oneOf": [{"type": "string"}, {"type": "array", "items": {"type": "string"}}]}, [1],
     "[0]: expected text, found 1"),
    ({"oneOf": [{"type": "number"}, {"type": "integer"}]}, 3,
     "(top level): expected a value that fits one of 2 alternatives, found 3, which fits "
     "several"),
    ({"dependentRequired": {"book": ["note"]}}, {"book": 1},
     "(top level): expected a field 'note' with 'book', found none"),
    ({"dependentRequired": {"book": ["note"]},
      "properties": {"note": {"description": "Why the book differs."}}}, {"book": 1},
     "(top level): expected a field 'note' (why the book differs) with 'book', found none"),
    ({"propertyNames": {"pattern": "^[a-z]+$", "x-expected": "a lower-case name"}}, {"A": 1},
     "A: expected a lower-case name, found 'A'"),
    ({"multipleOf": 2}, 3,
     "(top level): expected a value valid for the schema keyword 'multipleOf' (2), found 3"),
])
def test_every_keyword_has_an_expected_found_message(schema, data, text):
    (problem,) = schema_problems(schema, data)
    assert str(problem) == text


def test_problems_come_in_document_order():
    schema = {"items": {"type": "string"}}
    assert [p.field for p in schema_problems(schema, [1, "a", 2] + ["b"] * 9 + [3])] == \
        ["[0]", "[2]", "[12]"]


def test_valid_data_has_no_problems():
    assert schema_problems({"type": "string"}, "x") == ()


def test_field_text_and_describe():
    assert field_text(("a", 0, "b", 10)) == "a[0].b[10]"
    assert describe(False) == "false" and describe(1.5) == "1.5"


CHOICE = {"oneOf": [{"required": ["rotation"]}, {"required": ["rotations"]},
                    {"required": ["bodies", "at"]}]}


@pytest.mark.parametrize("data, text", [
    ({"rotation": 1, "rotations": 2},
     "(top level): expected only one of the fields rotation, rotations, bodies, found rotation "
     "and rotations"),
    ({}, "(top level): expected one of the fields rotation, rotations, bodies (with at), found "
         "none of them"),
    ({"bodies": 1}, "(top level): expected a field 'at' with 'bodies', found none"),
])
def test_a_choice_between_fields_says_which_fields(data, text):
    (problem,) = schema_problems(CHOICE, data)
    assert str(problem) == text


def test_alternative_types_are_listed_together():
    schema = {"oneOf": [{"type": "string"}, {"type": "number"}, {"type": "object"}]}
    (problem,) = schema_problems(schema, [1])
    assert problem.message == "expected text, a number or a mapping, found a list of 1"


def test_a_misspelt_required_field_is_one_problem_with_a_suggestion():
    schema = {"required": ["title", "id"], "additionalProperties": False,
              "properties": {"title": {}, "id": {}}}
    problems = schema_problems(schema, {"titel": "x"})
    assert [str(p) for p in problems] == [
        "(top level): expected a field 'id', found none",
        "titel: expected only the fields title, id, found 'titel'; did you mean 'title'?"]
    assert problems[1].at_key and problems[1].meant == "title"
    assert problems[0].missing == "id"


def test_an_enum_value_gets_the_closest_choice():
    (problem,) = schema_problems({"enum": ["scalar", "vector"]}, "scalr")
    assert problem.message == "expected one of scalar, vector, found 'scalr'; did you mean 'scalar'?"


def test_a_badly_formed_key_is_located_at_the_key():
    schema = {"propertyNames": {"pattern": "^[a-z]+$"}}
    (problem,) = schema_problems({"properties": {"a": schema}}, {"a": {"B2": 1}})
    assert problem.path == ("a", "B2") and problem.at_key


@pytest.mark.parametrize("schema, data, text", [
    ({"type": "number"}, float("nan"), "(top level): expected a finite number, found nan (not a "
                                       "number)"),
    ({"maximum": 1}, float("inf"), "(top level): expected a finite number, found inf (infinite)"),
    ({"items": {"type": "string"}}, ["a", -float("inf")],
     "[1]: expected a finite number, found -inf (infinite)"),
    ({}, {"a": {"b": 1e300}}, "a.b: expected a number of magnitude at most 1e+40, found 1e+300"),
    ({}, [10 ** 60], "[0]: expected a number of magnitude at most 1e+40, found a number of 61 "
                     "digits"),
    ({}, 1e-300, "(top level): expected zero or a number of magnitude at least 1e-40, found "
                 "1e-300"),
])
def test_numbers_no_file_may_hold_are_one_problem_each(schema, data, text):
    assert [str(p) for p in schema_problems(schema, data)] == [text]


def test_a_deeply_nested_document_is_walked_for_numbers():
    data: list = [float("nan")]
    for _ in range(5000):
        data = [data]
    (problem,) = [p for p in schema_problems({}, data)]
    assert len(problem.path) == 5001 and problem.message.startswith("expected a finite number")
