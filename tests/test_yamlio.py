"""YAML is read safely and every value keeps its file position."""

from __future__ import annotations

import pytest

from mechgrade.errors import SpecError
from mechgrade.yamlio import MAX_BYTES, field_path, read_yaml, read_yaml_text


def test_positions_are_kept():
    doc = read_yaml_text("a:\n  - x: 1\n  - y: [2, 3]\n", "f.yaml")
    assert doc.data == {"a": [{"x": 1}, {"y": [2, 3]}]}
    assert str(doc.where(("a", 1, "y", 1))) == "f.yaml:3:12: a[1].y[1]"
    assert field_path(("objectives", 2, "find")) == "objectives[2].find"


@pytest.mark.parametrize("text, message", [
    ("a: &x 1\nb: *x\n", "f.yaml:2:4: expected plain YAML, found an alias"),
    ("a: 1\na: 2\n", "f.yaml:2:1: a: expected each key once, found 'a' again"),
    ("a: [1, 2\n", "f.yaml:2:1: expected valid YAML, found a syntax error"),
    ("<<: {a: 1}\n", "f.yaml:1:1: expected plain YAML, found a merge key (<<)"),
    ("? [a]\n: 1\n", "expected a plain key, found a list or mapping used as a key"),
    ("a: \x00\n", "expected text, found a NUL byte"),
    ("!!python/object:os.system x\n", "expected valid YAML, found a syntax error"),
])
def test_unsafe_or_broken_yaml_is_refused(text, message):
    with pytest.raises(SpecError) as info:
        read_yaml_text(text, "f.yaml")
    assert message in str(info.value)


def test_dates_stay_text():
    assert read_yaml_text("d: 2024-01-01\n").data == {"d": "2024-01-01"}


def test_size_cap_and_encoding(tmp_path):
    big = tmp_path / "big.yaml"
    big.write_text("a: " + "x" * (MAX_BYTES + 1))
    with pytest.raises(SpecError, match="expected a YAML file of at most"):
        read_yaml(big)
    latin = tmp_path / "latin.yaml"
    latin.write_bytes("a: caf\xe9\n".encode("latin-1"))
    with pytest.raises(SpecError, match="expected UTF-8 text, found byte 0xe9, which is not UTF-8"):
        read_yaml(latin)
    bom = tmp_path / "bom.yaml"
    bom.write_bytes("\ufeffa: 1\n".encode("utf-8"))
    assert read_yaml(bom).data == {"a": 1}
