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
     "y: expected only the fields none, found 'y'"),
    ({"oneOf": [{"type": "string"}, {"type": "array", "items": {"type": "string"}}]}, [1],
     "[0]: expected text, found 1"),
    ({"dependentRequired": {"book": ["note"]}}, {"book": 1},
     "(top level): expected a field 'note' with 'book', found none"),
    ({"propertyNames": {"pattern": "^[a-z]+$", "x-expected": "a lower-case name"}}, {"A": 1},
     "(top level): expected a lower-case name, found 'A'"),
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
