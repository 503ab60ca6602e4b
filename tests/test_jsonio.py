"""A JSON document from elsewhere: numbers that are not finite, absurd integers and absurd
nesting are refused at their place, never read as nan or ending in an internal error."""

from __future__ import annotations

import pytest

from mechgrade.errors import ExportError
from mechgrade.jsonio import MAX_DEPTH, read_json, read_json_text


@pytest.mark.parametrize("number, found", [
    ("NaN", "NaN"),
    ("Infinity", "Infinity"),
    ("-Infinity", "-Infinity"),
    ("1e400", "1e400, beyond the largest floating-point number"),
    ("-1" + "0" * 320, "-10000000000...0000 (322 characters), beyond the largest "
                       "floating-point number"),
    ("1" + "0" * 4999, "100000000000...0000 (5000 characters), longer than 400 characters"),
])
def test_a_number_that_is_no_finite_float_is_refused_at_its_field(number, found):
    text = f'{{"students": [{{"score": 1}}, {{"score": {number}}}]}}'
    with pytest.raises(ExportError) as caught:
        read_json_text(text, "results.json", error=ExportError)
    assert str(caught.value) == f"results.json: students[1].score: expected a finite number, " \
                                f"found {found}"


def test_the_first_refused_number_in_document_order_is_reported():
    with pytest.raises(ExportError, match=r"^r.json: a\[0\]: .* found NaN$"):
        read_json_text('{"a": [NaN, Infinity], "b": Infinity}', "r.json", error=ExportError)


def test_finite_numbers_large_and_small_are_read():
    assert read_json_text('{"a": [1e308, -5e-324, 123456789012345678901234567890]}', "r.json",
                          error=ExportError) == {"a": [1e308, -5e-324,
                                                       123456789012345678901234567890]}


@pytest.mark.parametrize("depth", [MAX_DEPTH + 1, 100_000])
def test_nesting_deeper_than_the_limit_is_refused_at_its_line_and_column(depth):
    text = '{"students": [],\n "x": ' + "[" * depth + "]" * depth + "}"
    with pytest.raises(ExportError) as caught:
        read_json_text(text, "r.json", error=ExportError)
    # the top mapping is level 1; the bracket opening level MAX_DEPTH + 1 is at column
    # 7 + MAX_DEPTH - 1 of line 2
    assert str(caught.value) == f"r.json:2:{6 + MAX_DEPTH}: expected JSON nested at most " \
                                f"{MAX_DEPTH} levels deep, found deeper nesting"


def test_brackets_inside_strings_do_not_count_as_nesting():
    text = '{"x": "' + "[" * 500 + '", "y": ' + "[" * (MAX_DEPTH - 1) + "]" * (MAX_DEPTH - 1) \
        + "}"
    assert read_json_text(text, "r.json", error=ExportError)["x"] == "[" * 500


def test_invalid_json_is_located_and_names_what_was_expected(tmp_path):
    path = tmp_path / "meta.json"
    path.write_text('{"users": [\n')
    with pytest.raises(ExportError) as caught:
        read_json(path, what="metadata", error=ExportError, max_bytes=100,
                  content="JSON (metadata)")
    assert str(caught.value) == f"{path}:2:1: expected JSON (metadata), found invalid JSON: " \
                                "Expecting value"
