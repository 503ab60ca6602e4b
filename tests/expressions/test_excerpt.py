"""Quoting user text in reasons: bounded, marked, control characters made visible."""

import pytest
from hypothesis import given, strategies as st

from mechgrade.expressions.excerpt import excerpt


def test_marks_the_offending_part_with_context():
    assert excerpt("98.5.0 ft/s^2", 4, 6) == "'98.5«.0» ft/s^2'"
    assert excerpt("a" * 40 + "#" + "b" * 40, 40) == "'…aaaaaaaaaaaaaaaa«#»bbbbbbbbbbbbbbbb…'"


def test_unmarked_text_is_cut():
    assert excerpt("short") == "'short'"
    assert excerpt("x" * 1_000_000) == "'" + "x" * 32 + "…'"


@pytest.mark.parametrize("text, shown", [("98.5\r\n30", "'98.5«\\r»\\n30'"),
                                         ("a\u2029b", "'a«\\u2029»b'"), ("\x00", "'«\\x00»'")])
def test_control_characters_are_escaped(text, shown):
    assert excerpt(text, text.index(text.strip("ab9835.0")[:1] or text[0])) == shown


@given(st.text(max_size=5000), st.integers(0, 5000), st.integers(0, 5000))
def test_any_excerpt_is_short(text, start, length):
    assert len(excerpt(text)) <= 80
    assert len(excerpt(text, start, start + length)) <= 200
