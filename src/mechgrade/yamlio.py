"""Safe YAML reading that remembers where every value came from.

Documents are composed with PyYAML's safe loader (on libyaml's parser where PyYAML has it; the
pure-Python one words the messages) into plain Python values (dict, list, str, int, float, bool,
None); anchors and aliases are refused (no "billion laughs"), duplicate keys are an error
rather than silently overwritten, and files above a size cap are refused. Every value's
position is kept in a :class:`Document` so messages can say ``file:line:col``.

Whatever goes wrong while reading becomes the caller's error class with a location: control
characters, nesting deeper than :data:`MAX_DEPTH`, integers longer than :data:`MAX_INT_DIGITS`,
and syntax errors, the common ones (tabs, indentation, unclosed quotes and brackets, a missing
space after ``:``) in plain words.

>>> doc = read_yaml_text("a:\\n  b: [1, 2]\\n", "x.yaml")
>>> doc.data
{'a': {'b': [1, 2]}}
>>> str(doc.where(("a", "b", 1)))
'x.yaml:2:10: a.b[1]'
>>> read_yaml_text("a:\\n  b: 1\\n   c: 2\\n", "x.yaml")
Traceback (most recent call last):
...
mechgrade.errors.SpecError: x.yaml:3:4: indentation: this line is indented 3 spaces, the key above 2
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import re

import yaml

from .errors import Location, MechgradeError, SpecError
from .files import MAX_BYTES, read_text


Path_ = tuple  # a field path: tuple of str keys and int indices

MAX_DEPTH = 64
"""Deepest nesting of lists and mappings accepted (PyYAML composes recursively)."""

MAX_INT_DIGITS = 100
"""Longest integer accepted; Python refuses to convert more than 4300 digits anyway."""

# C0 controls except tab, newline and carriage return; DEL; C1 controls (U+0085, NEL, is a
# YAML line break that silently splits a line, so it is refused too).
_CONTROL = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f]")
_CONTROL_NAMES = {0x00: "NUL", 0x07: "BEL", 0x08: "BS", 0x0B: "VT", 0x0C: "FF", 0x1B: "ESC",
                  0x7F: "DEL", 0x85: "NEL"}
# The rest of what YAML does not allow: lone surrogates (a file's bytes that are not UTF-8,
# kept by Python) and the noncharacters U+FFFE and U+FFFF.
_UNPRINTABLE = re.compile("[\ud800-\udfff\ufffe\uffff]")


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
    texts: dict = field(default_factory=dict, compare=False, repr=False)
    keys: dict = field(default_factory=dict, compare=False, repr=False)

    def where(self, path: tuple) -> Location:
        """The location of the value at ``path`` (or of its nearest located parent)."""
        probe = tuple(path)
        while probe not in self.marks and probe:
            probe = probe[:-1]
        line, column = self.marks.get(probe, (None, None))
        return Location(self.file, line, column, field_path(path) or None)

    def where_key(self, path: tuple) -> Location:
        """The location of the key that ends ``path`` (a name being defined), else its value.

        >>> str(read_yaml_text("a:\\n  b: 1", "x.yaml").where_key(("a", "b")))
        'x.yaml:2:3: a.b'
        """
        if tuple(path) not in self.keys:
            return self.where(path)
        line, column = self.keys[tuple(path)]
        return Location(self.file, line, column, field_path(path) or None)

    def text(self, path: tuple) -> str | None:
        """The scalar at ``path`` exactly as written (``98.510`` keeps its last zero).

        >>> read_yaml_text("v: 98.510").text(("v",))
        '98.510'
        """
        return self.texts.get(tuple(path))


class _Refusals(yaml.composer.Composer):
    """Composition that refuses aliases (and so anchors are pointless) and explicit tags, and
    counts the depth (PyYAML composes recursively)."""

    depth = 0
    # the parser's, mixed into the loader class beside this one
    check_event: Callable[..., bool]
    peek_event: Callable[[], Any]

    def compose_node(self, parent, index):
        if self.check_event(yaml.AliasEvent):
            event = self.peek_event()
            raise _YamlProblem("expected plain YAML, found an alias (*name); anchors and "
                               "aliases are not allowed", event.start_mark)
        tag = getattr(self.peek_event(), "tag", None)
        if tag not in (None, "!"):
            # The safe loader would drop a '!!python/...' tag and keep its value: a misread.
            shown = tag.replace("tag:yaml.org,2002:", "!!", 1)[:40]
            raise _YamlProblem(f"expected plain YAML, found the tag '{shown}'; tags are "
                               f"not allowed", self.peek_event().start_mark)
        self.depth += 1
        try:
            if self.depth > MAX_DEPTH:
                raise _YamlProblem(f"expected lists and mappings nested at most {MAX_DEPTH} "
                                   f"deep, found deeper nesting", self.peek_event().start_mark)
            return super().compose_node(parent, index)
        finally:
            self.depth -= 1


class _Loader(_Refusals, yaml.SafeLoader):
    """The pure-Python safe loader with :class:`_Refusals`: its error messages are the ones
    shown (their wording and positions are what :func:`_syntax_message` reads)."""


CParser: Any = None
try:
    from yaml import cyaml as _cyaml

    # not in cyaml's __all__ (nor its type stubs): yaml.CParser does not exist
    CParser = getattr(_cyaml, "CParser")  # noqa: B009 - see above: unknown to the stubs
except ImportError:  # pragma: no cover - PyYAML built without libyaml
    pass
_CLoader: Any = None

if CParser is not None:
    class _LibyamlLoader(_Refusals, CParser, yaml.constructor.SafeConstructor,
                   yaml.resolver.Resolver):
        """libyaml's parser (several times faster than PyYAML's own) under the same
        :class:`_Refusals` composition. Only documents it reads without objection are kept
        from it; anything else is read again by :class:`_Loader` for the message."""

        flow = 0  # flow collections ([...], {...}) open around the node being composed

        def __init__(self, stream):
            CParser.__init__(self, stream)
            yaml.composer.Composer.__init__(self)
            yaml.constructor.SafeConstructor.__init__(self)
            yaml.resolver.Resolver.__init__(self)

        def compose_scalar_node(self, anchor):
            event = self.peek_event()
            if self.flow and not event.style and (not event.value or "?" in event.value):
                # libyaml places an empty value in a flow collection one column further on,
                # and takes a '?' inside one where PyYAML refuses it
                raise _YamlProblem("a plain value PyYAML reads otherwise", event.start_mark)
            return super().compose_scalar_node(anchor)

        def compose_sequence_node(self, anchor):
            return self._nested(super().compose_sequence_node, anchor)

        def compose_mapping_node(self, anchor):
            return self._nested(super().compose_mapping_node, anchor)

        def _nested(self, compose, anchor):
            flow = bool(self.peek_event().flow_style)
            self.flow += flow
            try:
                return compose(anchor)
            finally:
                self.flow -= flow

    _CLoader = _LibyamlLoader


def libyaml_reads(text: str) -> bool:
    r"""Whether ``text`` is read by libyaml's parser (when PyYAML has it): libyaml accepts
    tabs where PyYAML refuses them, and places marks differently around a byte order mark,
    so such texts go to the pure-Python reader only.

    >>> libyaml_reads("a: 1\n") == (_CLoader is not None), libyaml_reads("a:\t1\n")
    (True, False)
    """
    return _CLoader is not None and "\t" not in text and "\ufeff" not in text


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
    control = _CONTROL.search(text)
    if control:
        code = ord(control.group())
        name = _CONTROL_NAMES.get(code, "a control character")
        raise error(f"expected printable text, found {name} (U+{code:04X}); delete it",
                    where=_place(file, text, control.start()))
    unprintable = _UNPRINTABLE.search(text)
    if unprintable:
        code = ord(unprintable.group())
        name = (f"the noncharacter U+{code:04X}" if code >= 0xFFFE
                else f"a lone surrogate (U+{code:04X})")
        raise error(f"expected printable text, found {name}; delete it",
                    where=_place(file, text, unprintable.start()))
    if libyaml_reads(text):
        try:
            return _read(_CLoader, text, file, error)
        except Exception:  # noqa: BLE001 - read again below, for the exact message
            pass
    return _read(_Loader, text, file, error)


def _place(file: str, text: str, index: int) -> Location:
    """The location of the character at ``index`` of ``text``."""
    line = text.count("\n", 0, index) + 1
    return Location(file, line, index - (text.rfind("\n", 0, index) + 1) + 1)


def _read(loader_class, text: str, file: str, error: type[MechgradeError]) -> Document:
    try:
        loader = loader_class(text)  # PyYAML's reader checks every character here
    except yaml.reader.ReaderError as exc:
        raise error(f"expected printable text, found a character YAML does not allow "
                    f"(U+{exc.character if isinstance(exc.character, int) else 0:04X}); "
                    f"delete it", where=_place(file, text, exc.position)) from None
    except Exception as exc:  # noqa: BLE001 - the boundary: nothing else may escape a read
        raise error(f"expected valid YAML, found something the reader cannot handle "
                    f"({type(exc).__name__}: {str(exc)[:80]})", where=Location(file)) from None
    marks: dict = {}
    texts: dict = {}
    keys: dict = {}
    try:
        node = loader.get_single_node()
        data = _construct(node, (), (marks, texts, keys), file, error) if node is not None else None
    except error:
        raise
    except _YamlProblem as exc:
        raise error(exc.message, where=_mark(file, exc.mark)) from None
    except yaml.MarkedYAMLError as exc:
        message, mark = _syntax_message(text.splitlines(), exc)
        raise error(message, where=_mark(file, mark)) from None
    except RecursionError:
        raise error(f"expected lists and mappings nested at most {MAX_DEPTH} deep, found "
                    "deeper nesting", where=Location(file)) from None
    except Exception as exc:  # noqa: BLE001 - the boundary: nothing else may escape a read
        raise error(f"expected valid YAML, found something the reader cannot handle "
                    f"({type(exc).__name__}: {str(exc)[:80]})", where=Location(file)) from None
    finally:
        loader.dispose()
    return Document(data, file, marks, texts, keys)


_GLUED_COLON = re.compile(r"^(\s*(?:-\s+)?)([A-Za-z_][\w']*):(?=[^\s:/])(\S.*)$")


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip(" "))


_SCALAR_PAIR = re.compile(r"^\s*(?:-\s+)?[^\s:#][^:#]*:\s+[^\s|>#]")


def _spaces(count: int) -> str:
    return f"{count} space" + ("" if count == 1 else "s")


_OPENING_QUOTE = re.compile(r"""^\s*(?:-\s+)?[^'"#:]+:\s+(['"])""")


def _quote_left_open(lines: list[str], line: int) -> tuple[int, int] | None:
    """Where a value's quote opened on an earlier line and ran on to ``line``, where the next
    quote of its kind closed it (so the rest of that line no longer parses)."""
    for number in range(line - 1, -1, -1):
        match = _OPENING_QUOTE.match(lines[number])
        if not match:
            continue
        quote = match.group(1)
        rest = [lines[number][match.end(1):]] + lines[number + 1:line + 1]
        closes = next((offset for offset, text in enumerate(rest)
                       if quote in (text.replace("''", "") if quote == "'"
                                    else re.sub(r'\\.', "", text))), None)
        if closes == 0:
            continue  # a complete quoted value: look further up
        return (number, match.start(1)) if closes is not None and number + closes == line \
            else None
    return None


def _syntax_message(lines: list[str], exc: yaml.MarkedYAMLError):
    """Plain words (and the mark to point at) for a PyYAML syntax error."""
    problem, context = exc.problem or "", exc.context or ""
    mark = exc.problem_mark or exc.context_mark or yaml.Mark("", 0, 0, 0, None, 0)
    opened = exc.context_mark
    if "'\\t'" in problem or "'\t'" in problem:
        return "tabs are not allowed, use spaces", mark
    for number in range(min(mark.line, len(lines) - 1), max(mark.line - 3, -1), -1):
        glued = _GLUED_COLON.match(lines[number])
        if glued:
            lead, key, rest = glued.groups()
            at = yaml.Mark("", 0, number, len(lead) + len(key), None, 0)
            return (f"expected a space after ':' in '{key}:{rest}' (write '{key}: {rest}')", at)
    if "quoted scalar" in context and opened is not None:
        quote = lines[opened.line][opened.column]
        return f"unclosed quote: the {quote} opened here is never closed", opened
    if "flow sequence" in context or "flow mapping" in context:
        bracket, close = ("[", "]") if "sequence" in context else ("{", "}")
        found = problem.split("but got ")[-1] if "but got" in problem else "'<stream end>'"
        found = "the end of the file" if found == "'<stream end>'" else found
        return (f"unclosed '{bracket}': expected ',' or '{close}' after an item, found "
                f"{found} on line {mark.line + 1}", opened or mark)
    if "mapping values are not allowed" in problem or "block end" in problem:
        opened_at = _quote_left_open(lines, mark.line)
        if opened_at is not None:
            number, column = opened_at
            at = yaml.Mark("", 0, number, column, None, 0)
            return (f"unclosed quote: the {lines[number][column]} opened here is closed only "
                    f"on line {mark.line + 1}", at)
    stray = re.search(r"but found '([\]}])'", problem)
    if stray:
        return f"found '{stray.group(1)}' with no bracket open to close", mark
    if ("block end" in problem or "mapping values are not allowed" in problem) \
            and mark.line < len(lines):
        here = _indent(lines[mark.line])
        above = next((lines[i] for i in range(mark.line - 1, -1, -1)
                      if lines[i].strip() and not lines[i].lstrip().startswith("#")), None)
        # A line indented past a finished "key: value" (read as the value's continuation), or
        # dedented to a level no key above has.
        misplaced = above is not None and (
            here > _indent(above) and _SCALAR_PAIR.match(above) if "mapping values" in problem
            else here != _indent(above))
        if misplaced and above is not None:
            at = yaml.Mark("", 0, mark.line, here, None, 0)
            return (f"indentation: this line is indented {_spaces(here)}, the key above "
                    f"{_indent(above)}", at)
        if "mapping values" in problem:
            return ("expected one 'key: value' per line, found a second ': ' in a value; "
                    "put the value in quotes", mark)
    return f"expected valid YAML, found a syntax error ({problem or context})", mark


def _mark(file: str, mark) -> Location:
    if mark is None:
        return Location(file)
    return Location(file, mark.line + 1, mark.column + 1)


def _construct(node, path, tables, file, error):
    marks, texts, keys = tables
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
            key = _scalar(key_node, file, error)
            if key == "<<":
                raise error("expected plain YAML, found a merge key (<<)",
                            where=_mark(file, key_node.start_mark))
            key = str(key) if not isinstance(key, str) else key
            if key in out:
                raise error(f"expected each key once, found '{key}' again",
                            where=Location(file, key_node.start_mark.line + 1,
                                           key_node.start_mark.column + 1,
                                           field_path(path + (key,))))
            keys[path + (key,)] = (key_node.start_mark.line + 1, key_node.start_mark.column + 1)
            out[key] = _construct(value_node, path + (key,), tables, file, error)
        return out
    if isinstance(node, yaml.SequenceNode):
        return [_construct(item, path + (i,), tables, file, error)
                for i, item in enumerate(node.value)]
    texts[path] = node.value
    return _scalar(node, file, error)


_SCALAR_LOADER = yaml.SafeLoader("")


def _scalar(node, file, error):
    if node.tag == "tag:yaml.org,2002:int":
        digits = sum(ch.isalnum() for ch in node.value)
        if digits > MAX_INT_DIGITS:
            raise error(f"expected a number of at most {MAX_INT_DIGITS} digits, found one of "
                        f"{digits} (quote it if it is text)", where=_mark(file, node.start_mark))
    # Dates and binary blobs are not part of any mechgrade format: keep what was typed (not
    # even built: a date that does not exist, 2026-02-30, is the field's reader's to refuse).
    if node.tag in ("tag:yaml.org,2002:timestamp", "tag:yaml.org,2002:binary"):
        return node.value
    value = _SCALAR_LOADER.construct_object(node)
    if not isinstance(value, (str, int, float, bool, type(None))):
        return node.value
    return value
