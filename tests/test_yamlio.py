"""YAML is read safely and every value keeps its file position."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

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
    ("a: [1, 2\n", "f.yaml:1:4: unclosed '[': expected ',' or ']' after an item, found the end of the file on line 2"),
    ("<<: {a: 1}\n", "f.yaml:1:1: expected plain YAML, found a merge key (<<)"),
    ("? [a]\n: 1\n", "expected a plain key, found a list or mapping used as a key"),
    ("a: \x00\n", "expected text, found a NUL byte"),
    ("!!python/object:os.system x\n", "expected plain YAML, found the tag "
                                       "'!!python/object:os.system'; tags are not allowed"),
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


@pytest.mark.parametrize("text, message", [
    ("a: " + "[" * 5000 + "]" * 5000 + "\n",
     "f.yaml:1:67: expected lists and mappings nested at most 64 deep, found deeper nesting"),
    ("a: " + "{b: " * 3000 + "1" + "}" * 3000 + "\n",
     "f.yaml:1:253: expected lists and mappings nested at most 64 deep, found deeper nesting"),
    ("a: x\x07y\n", "f.yaml:1:5: expected printable text, found BEL (U+0007); delete it"),
    ("a: 1\nb: '\x1b[31m'\n", "f.yaml:2:5: expected printable text, found ESC (U+001B); delete it"),
    ("a: x\x7f\n", "f.yaml:1:5: expected printable text, found DEL (U+007F); delete it"),
    ("a: x\x85y\n", "f.yaml:1:5: expected printable text, found NEL (U+0085); delete it"),
    ("a: \x9b\n", "f.yaml:1:4: expected printable text, found a control character (U+009B); delete it"),
    ("a: 1\nb: x\ufffe\n", "f.yaml:2:5: expected printable text, found the noncharacter U+FFFE; delete it"),
    ("\uffff: 1\n", "f.yaml:1:1: expected printable text, found the noncharacter U+FFFF; delete it"),
    ("a: '\ud800'\n", "f.yaml:1:5: expected printable text, found a lone surrogate (U+D800); delete it"),
    ("a: " + "9" * 5000 + "\n",
     "f.yaml:1:4: expected a number of at most 100 digits, found one of 5000 (quote it if it is text)"),
    ("a: [1, 0x" + "f" * 5000 + "]\n",
     "f.yaml:1:8: expected a number of at most 100 digits, found one of 5002 (quote it if it is text)"),
])
def test_parser_limits_are_located_errors(text, message):
    with pytest.raises(SpecError) as info:
        read_yaml_text(text, "f.yaml")
    assert str(info.value) == message


def test_a_quoted_long_number_is_text():
    assert read_yaml_text("a: '" + "9" * 5000 + "'").data == {"a": "9" * 5000}


@pytest.mark.parametrize("text, message", [
    ("a:\n\tb: 1\n", "f.yaml:2:1: tabs are not allowed, use spaces"),
    ("a:\n    b: 1\n   c: 2\n", "f.yaml:3:4: indentation: this line is indented 3 spaces, the key above 4"),
    ("a:\n  b: 1\n   c: 2\n", "f.yaml:3:4: indentation: this line is indented 3 spaces, the key above 2"),
    ("a: 'abc\nb: 1\n", "f.yaml:1:4: unclosed quote: the ' opened here is never closed"),
    ('a: "abc\nb: 1\n', 'f.yaml:1:4: unclosed quote: the " opened here is never closed'),
    ("a: [1, 2\nb: 1\n", "f.yaml:1:4: unclosed '[': expected ',' or ']' after an item, found ':' on line 2"),
    ("a: {x: 1\nb: 1\n", "f.yaml:1:4: unclosed '{': expected ',' or '}' after an item, found ':' on line 2"),
    ("a: [1, 2]]\n", "f.yaml:1:10: found ']' with no bracket open to close"),
    ("a:1\nb: 2\n", "f.yaml:1:2: expected a space after ':' in 'a:1' (write 'a: 1')"),
    ("a: 1\nb:2\nc: 3\n", "f.yaml:2:2: expected a space after ':' in 'b:2' (write 'b: 2')"),
    ("a: b: c\n", "f.yaml:1:5: expected one 'key: value' per line, found a second ': ' in a value; put the value in quotes"),
    ("a:\n  b: x\nc: d: e\n", "f.yaml:3:5: expected one 'key: value' per line, found a second ': ' in a value; put the value in quotes"),
    ("a:\n  - x: 1\n    y: 2\n   z: 3\n", "f.yaml:4:4: indentation: this line is indented 3 spaces, the key above 4"),
    ("a:\n  b:\n   c: 1\n  d: 2\n e: 3\n", "f.yaml:5:2: indentation: this line is indented 1 space, the key above 2"),
    ("title: 'Pendulum\nid: p\nx: 'y'\n", "f.yaml:1:8: unclosed quote: the ' opened here is closed only on line 3"),
])
def test_syntax_errors_in_plain_words(text, message):
    with pytest.raises(SpecError) as info:
        read_yaml_text(text, "f.yaml")
    assert str(info.value) == message


def test_any_reader_failure_becomes_the_callers_error(monkeypatch):
    from mechgrade.errors import SubmissionError
    from mechgrade import yamlio

    def broken(self):
        raise MemoryError("out of memory")

    monkeypatch.setattr(yamlio._Refusals, "get_single_node", broken)
    with pytest.raises(SubmissionError) as info:
        read_yaml_text("a: 1\n", "s.yaml", SubmissionError)
    assert str(info.value) == ("s.yaml: expected valid YAML, found something the reader cannot "
                               "handle (MemoryError: out of memory)")


def test_scalars_keep_their_written_text():
    doc = read_yaml_text("v: 98.510\nc: [1.50, -0]\n")
    assert doc.text(("v",)) == "98.510" and doc.text(("c", 0)) == "1.50"


def test_limits_use_the_callers_error_class():
    from mechgrade.errors import SubmissionError
    for text in ("a: " + "[" * 3000 + "]" * 3000, "a: \x1b", "a: " + "1" * 5000, "a:\n\tb: 1"):
        with pytest.raises(SubmissionError):
            read_yaml_text(text, "answers.yaml", SubmissionError)


@pytest.mark.parametrize("text, column", [
    ("v: !!python/object/apply:os.system ['touch x']\n", 4),
    ("v: !!str 98.5\n", 4),
    ("v: !custom [1]\n", 4),
])
def test_explicit_tags_are_refused(text, column):
    with pytest.raises(SpecError) as info:
        read_yaml_text(text, "t.yaml")
    assert str(info.value).startswith(f"t.yaml:1:{column}: expected plain YAML, found the tag ")
    assert str(info.value).endswith("; tags are not allowed")


def _tables(loader, text):
    from mechgrade import yamlio

    try:
        doc = yamlio._read(loader, text, "f.yaml", SpecError)
    except SpecError as err:
        return str(err)
    return doc.data, doc.marks, doc.texts, doc.keys


SHIPPED_YAML = sorted(str(p) for folder in ("problems", "examples")
                      for p in (Path(__file__).resolve().parents[1] / folder).rglob("*.yaml"))


@pytest.mark.parametrize("text", [
    "a: {frame: , point: O}\n", "p: {from: O, position: ,L*A.x}\n", "a: {axis?: z}\n",
    "a: [x?, 1]\n", "a:\n  b:\n  c: 1\n", "- \n- x\n", "k: 'it''s'\nv: \"\\u00e9\\n\"\n",
    "v: 7.10  # typed\nw: [1.50, -0, .5]\n", "t: |\n  two\n  lines\n", "é: ü\n  more\n",
])
def test_the_libyaml_reader_reads_as_the_python_reader(text):
    from mechgrade import yamlio

    if not yaml.__with_libyaml__:
        pytest.skip("PyYAML without libyaml")
    assert yamlio._CLoader is not None  # libyaml is there: the fast reader must be used
    fast = _tables(yamlio._CLoader, text)
    # where libyaml would differ it refuses, and read_yaml_text reads the text again
    assert fast == _tables(yamlio._Loader, text) or isinstance(fast, str)
    try:
        doc = read_yaml_text(text, "f.yaml")
        public = doc.data, doc.marks, doc.texts, doc.keys
    except SpecError as err:
        public = str(err)
    assert public == _tables(yamlio._Loader, text)


@pytest.mark.slow
def test_the_shipped_files_read_the_same_with_libyaml():
    from mechgrade import yamlio

    if not yaml.__with_libyaml__:
        pytest.skip("PyYAML without libyaml")
    assert yamlio._CLoader is not None  # libyaml is there: the fast reader must be used
    assert SHIPPED_YAML
    for path in SHIPPED_YAML:
        text = Path(path).read_text(encoding="utf-8")
        if yamlio.libyaml_reads(text):  # a text with a tab is only read by PyYAML's reader
            assert _tables(yamlio._CLoader, text) == _tables(yamlio._Loader, text), path


def test_a_date_that_does_not_exist_is_kept_as_typed_for_its_field_to_refuse():
    assert read_yaml_text("due: 2026-02-30\nday: 2026-02-28\n", "f.yaml").data == {
        "due": "2026-02-30", "day": "2026-02-28"}


def test_a_reader_refusing_the_text_itself_is_located(monkeypatch):
    """What PyYAML's reader refuses as it is made (before parsing) is the caller's error too."""
    from mechgrade import yamlio

    monkeypatch.setattr(yamlio, "_UNPRINTABLE", yamlio.re.compile("(?!)"))
    with pytest.raises(SpecError) as info:
        read_yaml_text("a: 1\nb: x\ufffe\n", "f.yaml")
    assert str(info.value) == ("f.yaml:2:5: expected printable text, found a character YAML "
                               "does not allow (U+FFFE); delete it")
