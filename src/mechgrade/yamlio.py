"""Safe YAML reading that remembers where every value came from.

Documents are composed with PyYAML's safe loader into plain Python values (dict, list, str,
int, float, bool, None); anchors and aliases are refused (no "billion laughs"), duplicate keys
are an error rather than silently overwritten, and files above a size cap are refused. Every
value's position is kept in a :class:`Document` so messages can say ``file:line:col``.

>>> doc = read_yaml_text("a:\\n  b: [1, 2]\\n", "x.yaml")
>>> doc.data
{'a': {'b': [1, 2]}}
>>> str(doc.where(("a", "b", 1)))
'x.yaml:2:10: a.b[1]'
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from .errors import Location, MechgradeError, SpecError
from .files import MAX_BYTES, read_text


Path_ = tuple  # a field path: tuple of str keys and int indices


def field_path(path: tuple) -> str:
    """``("objectives", 2, "find")`` -> ``"objectives[2].find"``."""
    out = ""
    for part in path:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out


@dataclass(frozen=True)
class Document:
    """Plain data read from YAML, plus the line and column of every value."""

    data: Any
    file: str
    marks: dict = field(default_factory=dict, compare=False, repr=False)

    def where(self, path: tuple) -> Location:
        """The location of the value at ``path`` (or of its nearest located parent)."""
        probe = tuple(path)
        while probe not in self.marks and probe:
            probe = probe[:-1]
        line, column = self.marks.get(probe, (None, None))
        return Location(self.file, line, column, field_path(path) or None)


class _Loader(yaml.SafeLoader):
    """Safe loader that refuses aliases (and so anchors are pointless)."""

    def compose_node(self, parent, index):
        if self.check_event(yaml.AliasEvent):
            event = self.peek_event()
            raise _YamlProblem("expected plain YAML, found an alias (*name); anchors and "
                               "aliases are not allowed", event.start_mark)
        return super().compose_node(parent, index)


class _YamlProblem(Exception):
    def __init__(self, message, mark):
        super().__init__(message)
        self.message = message
        self.mark = mark


def read_yaml(path: str | Path, error: type[MechgradeError] = SpecError,
              what: str = "a YAML file") -> Document:
    """Read a YAML file safely; errors are ``error`` with file:line:col."""
    text = read_text(path, what=what, error=error, max_bytes=MAX_BYTES)
    return read_yaml_text(text, str(path), error)


def read_yaml_text(text: str, file: str = "<text>",
                   error: type[MechgradeError] = SpecError) -> Document:
    """Read YAML from a string; see :func:`read_yaml`."""
    if len(text) > MAX_BYTES:
        raise error(f"expected at most {MAX_BYTES} characters of YAML, found {len(text)}",
                    where=Location(file))
    if "\x00" in text:
        raise error("expected text, found a NUL byte (is this a binary file?)",
                    where=Location(file))
    loader = _Loader(text)
    try:
        node = loader.get_single_node()
        marks: dict = {}
        data = _construct(node, (), marks, file, error) if node is not None else None
    except _YamlProblem as exc:
        raise error(exc.message, where=_mark(file, exc.mark)) from None
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        problem = exc.problem or exc.context or "invalid YAML"
        raise error(f"expected valid YAML, found a syntax error ({problem})",
                    where=_mark(file, mark)) from None
    except yaml.YAMLError as exc:
        raise error(f"expected valid YAML ({exc})", where=Location(file)) from None
    finally:
        loader.dispose()
    return Document(data, file, marks)


def _mark(file: str, mark) -> Location:
    if mark is None:
        return Location(file)
    return Location(file, mark.line + 1, mark.column + 1)


def _construct(node, path, marks, file, error):
    marks[path] = (node.start_mark.line + 1, node.start_mark.column + 1)
    if isinstance(node, yaml.MappingNode):
        out = {}
        for key_node, value_node in node.value:
            if not isinstance(key_node, yaml.ScalarNode):
                raise error("expected a plain key, found a list or mapping used as a key",
                            where=_mark(file, key_node.start_mark))
            if key_node.tag == "tag:yaml.org,2002:merge":
                raise error("expected plain YAML, found a merge key (<<)",
                            where=_mark(file, key_node.start_mark))
            key = _scalar(key_node)
            if key == "<<":
                raise error("expected plain YAML, found a merge key (<<)",
                            where=_mark(file, key_node.start_mark))
            key = str(key) if not isinstance(key, str) else key
            if key in out:
                raise error(f"expected each key once, found '{key}' again",
                            where=Location(file, key_node.start_mark.line + 1,
                                           key_node.start_mark.column + 1,
                                           field_path(path + (key,))))
            out[key] = _construct(value_node, path + (key,), marks, file, error)
        return out
    if isinstance(node, yaml.SequenceNode):
        return [_construct(item, path + (i,), marks, file, error)
                for i, item in enumerate(node.value)]
    return _scalar(node)


_SCALAR_LOADER = yaml.SafeLoader("")


def _scalar(node):
    value = _SCALAR_LOADER.construct_object(node)
    # Dates and binary blobs are not part of any mechgrade format: keep what was typed.
    if not isinstance(value, (str, int, float, bool, type(None))):
        return node.value
    return value
