"""Formula-injection neutralising and CSV round trips."""

from __future__ import annotations

import csv
import io

import pytest
from hypothesis import given, strategies as st

from mechgrade.export.cells import csv_text, format_points, safe_cell, write_csv


@pytest.mark.parametrize("text", ["=1+1", "+1+2", "-x*omega", "@SUM(A1)", "\tx", "\rx",
                                  "＝1+1", "=HYPERLINK(\"http://x\")", "-", "+5", "--1"])
def test_formula_starts_are_prefixed_with_a_quote(text):
    assert safe_cell(text) == "'" + text


@pytest.mark.parametrize("text", ["-3", "-0.5", "-.5", "-1e-3", "12", "Émilie", "a=b", " =1",
                                  "O'Brien, Seán", ""])
def test_negative_numbers_and_plain_text_stay_as_they_are(text):
    assert safe_cell(text) == text


def test_numbers_are_written_as_short_decimals():
    assert [safe_cell(v) for v in (3.0, -2.5, 0.1 + 0.2, None, True)] == \
        ["3", "-2.5", "0.3", "", "true"]
    assert format_points(1e-9) == "0"


@given(st.lists(st.lists(st.text(), min_size=1, max_size=4), min_size=1, max_size=5))
def test_any_text_round_trips_through_csv_once_neutralised(rows):
    back = list(csv.reader(io.StringIO(csv_text(rows), newline="")))
    assert back == [[safe_cell(cell) for cell in row] for row in rows]


def test_excel_bom_option_writes_a_bom(tmp_path):
    write_csv(tmp_path / "a.csv", [["Zoë"]], excel_bom=True)
    write_csv(tmp_path / "b.csv", [["Zoë"]])
    assert (tmp_path / "a.csv").read_bytes() == b"\xef\xbb\xbfZo\xc3\xab\r\n"
    assert (tmp_path / "b.csv").read_bytes() == b"Zo\xc3\xab\r\n"
