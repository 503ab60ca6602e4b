"""The one translator of JSON Schema errors into mechgrade's messages.

Every file mechgrade checks against a JSON Schema (problem files, assignments, ``results.json``)
reports a violation the same way: where (the path to the field, ``students[3].status``), what
was expected and what was found, with the closest known name when a name is misspelt. A schema
can word what it expects in its own terms with the annotation ``"x-expected"`` on the failing
sub-schema (``"x-expected": "an equation 'left = right'"``), which replaces the generic wording
of any keyword, and a mapping that takes keys by pattern can word them with ``"x-fields"``.

>>> schema = {"type": "object", "required": ["id"], "additionalProperties": False,
...           "properties": {"id": {"type": "string"},
...                          "status": {"enum": ["graded", "missing"]}}}
>>> for problem in schema_problems(schema, {"id": 3, "status": "gradd", "x": 1}):
...     print(problem)
id: expected text, found 3
status: expected one of graded, missing, found 'gradd'; did you mean 'graded'?
x: expected only the fields id, status, found 'x'

Every number a checked file holds is finite and of a magnitude no physical value reaches
(:func:`number_problem`): JSON has no NaN or infinity, and YAML's ``.nan`` and ``.inf`` never
mean anything in a mechgrade file.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import jsonschema

Path = tuple[str | int, ...]

_TYPES = {"object": "a mapping", "array": "a list", "string": "text", "number": "a number",
          "integer": "a whole number", "boolean": "true or false", "null": "null"}
_SIGNS = {"minimum": ">=", "maximum": "<=", "exclusiveMinimum": ">", "exclusiveMaximum": "<"}
_BOUNDS = {"minItems": ("at least", "item(s)"), "maxItems": ("at most", "item(s)"),
           "minProperties": ("at least", "field(s)"), "maxProperties": ("at most", "field(s)")}


LARGEST = 1e40
"""The largest magnitude of a number in a file mechgrade reads (and, for a problem file, of
each value in SI units): far beyond any physical quantity a dynamics problem gives (the Sun's
mass is 2e30 kg), and far enough inside the float range (1.8e308) that a product of seven such
numbers stays finite."""

SMALLEST = 1e-40
"""The smallest magnitude of a number other than zero (Planck's constant is 6.6e-34 J s): a
product of seven such numbers stays a normal float, not zero."""


def number_problem(value: float, found: str | None = None, unit: str = "") -> str | None:
    """Why ``value`` is not a number a file may hold (not finite, of a magnitude above
    :data:`LARGEST`, or other than zero below :data:`SMALLEST`) as ``expected ..., found
    ...``; ``None`` when it is one. ``found`` words the value as written; ``unit`` names the units
    ``value`` is in.

    >>> number_problem(2.5), number_problem(float("nan"))
    (None, 'expected a finite number, found nan (not a number)')
    >>> number_problem(3.048e299, "'1e300 ft'", "SI units")
    "expected a number of magnitude at most 1e+40 in SI units, found '1e300 ft'"
    """
    if isinstance(value, float) and not math.isfinite(value):
        return f"expected a finite number, found {found or describe(value)}"
    if abs(value) > LARGEST:
        return (f"expected a number of magnitude at most {LARGEST:g}{f' in {unit}' * bool(unit)}"
                f", found {found or describe(value)}")
    if value and abs(value) < SMALLEST:
        return (f"expected zero or a number of magnitude at least {SMALLEST:g}"
                f"{f' in {unit}' * bool(unit)}, found {found or describe(value)}")
    return None


@dataclass(frozen=True)
class SchemaProblem:
    """One violation: ``path`` to the offending value and the message ``expected ..., found``.

    ``at_key`` says the path ends at a mapping key (an unknown or badly formed name), best shown
    at the key itself; ``missing`` names the required field absent from the mapping at ``path``;
    ``meant`` is the known field an unknown key most likely misspells.
    """

    path: Path
    message: str
    at_key: bool = False
    missing: str | None = None
    meant: str | None = None

    @property
    def field(self) -> str:
        """The path as text, ``students[3].status`` (empty at the top level)."""
        return field_text(self.path)

    def __str__(self) -> str:
        return f"{self.field or '(top level)'}: {self.message}"


def field_text(path: Path) -> str:
    """``("students", 3, "status")`` as ``students[3].status``.

    >>> field_text(("students", 3, "status")), field_text(())
    ('students[3].status', '')
    """
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text


def closest(name: object, known: Iterable[object]) -> str | None:
    """The known name closest to ``name`` (a likely misspelling of it), else None.

    >>> closest("vell", ["vel", "acc"]), closest("zzz", ["vel"])
    ('vel', None)
    """
    close = difflib.get_close_matches(str(name), sorted({str(k) for k in known}), n=1,
                                      cutoff=0.6)
    return close[0] if close else None


def did_you_mean(name: object, known: Iterable[object]) -> str:
    """``"; did you mean 'x'?"`` when ``known`` holds a name close to ``name``, else ``""``.

    >>> did_you_mean("vell", ["vel", "acc"])
    "; did you mean 'vel'?"
    >>> did_you_mean("zzz", ["vel"])
    ''
    """
    meant = closest(name, known)
    if meant is None:
        return ""
    quote = '"' if "'" in meant else "'"
    return f"; did you mean {quote}{meant}{quote}?"


def schema_problems(schema: dict, data: object) -> tuple[SchemaProblem, ...]:
    """Every violation of ``schema`` by ``data``, in document order (the first is the one to
    report when only one is). A misspelt required field is one mistake: the unknown key with
    its suggestion is reported, not also the missing field it was meant to be."""
    # imported here: jsonschema takes longer to import than click, and `--help` needs neither
    import jsonschema

    errors = jsonschema.Draft202012Validator(schema).iter_errors(data)
    numbers = _number_problems(data)
    spoilt = {p.path for p in numbers}  # a keyword's failure on such a number says less
    problems = [problem for err in errors for problem in _explain(err)
                if problem.path not in spoilt] + numbers
    meant = {(p.path[:-1], p.meant) for p in problems if p.meant}
    kept = [p for p in problems if not p.missing or (p.path, p.missing) not in meant]
    return tuple(sorted(dict.fromkeys(kept), key=lambda p: _order(p.path)))


def _number_problems(data: object) -> list[SchemaProblem]:
    """A problem for every number of ``data`` :func:`number_problem` refuses (walked without
    recursion: a document read from JSON may be nested deeply)."""
    out = []
    todo: list[tuple[Path, object]] = [((), data)]
    while todo:
        path, value = todo.pop()
        if isinstance(value, dict):
            todo.extend((path + (key,), item) for key, item in value.items())
        elif isinstance(value, list):
            todo.extend((path + (i,), item) for i, item in enumerate(value))
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            message = number_problem(value)
            if message is not None:
                out.append(SchemaProblem(path, message))
    return out


def _explain(err: jsonschema.ValidationError) -> list[SchemaProblem]:
    """One jsonschema error as the problems it stands for (one per unknown or missing key)."""
    path: Path = tuple(err.absolute_path)
    kind, wanted, found, schema = _parts(err)
    if "propertyNames" in err.relative_schema_path:
        # The offending value is a key of the mapping at ``path``: locate it at the key.
        return [SchemaProblem(path + (found,), _message(err), at_key=True)]
    if kind == "required":
        return [SchemaProblem(path, f"expected a field '{name}', found none", missing=name)
                for name in wanted if name not in found]
    if kind == "additionalProperties" and isinstance(schema, dict):
        return _unknown_keys(path, schema, found)
    if kind in ("oneOf", "anyOf"):
        return _alternatives(err, path)
    return [SchemaProblem(path, _message(err))]


def _message(err: jsonschema.ValidationError) -> str:
    """The ``expected ..., found ...`` message of one keyword's failure at one value."""
    kind, wanted, found, schema = _parts(err)
    if isinstance(schema, dict) and "x-expected" in schema:
        return f"expected {schema['x-expected']}, found {describe(found)}"
    if kind == "dependentRequired":
        key, missing = next((k, m) for k, needed in wanted.items() if k in found
                            for m in needed if m not in found)
        # A field needed only because of another says what it is for (its description).
        about = schema.get("properties", {}).get(missing, {}).get("description", "")
        about = f" ({about[:1].lower()}{about[1:].rstrip('.')})" if about else ""
        return f"expected a field '{missing}'{about} with '{key}', found none"
    if kind == "type":
        return f"expected {_types(wanted)}, found {describe(found)}"
    if kind == "enum":
        hint = did_you_mean(found, wanted) if isinstance(found, str) else ""
        return f"expected one of {', '.join(str(v) for v in wanted)}, found {describe(found)}{hint}"
    if kind == "const":
        return f"expected {wanted!r}, found {describe(found)}"
    if kind in _SIGNS:
        return f"expected a number {_SIGNS[kind]} {wanted:g}, found {describe(found)}"
    if kind in _BOUNDS:
        bound, noun = _BOUNDS[kind]
        return f"expected {bound} {wanted} {noun}, found {describe(found)}"
    if kind in ("minLength", "maxLength"):
        bound = "at least" if kind == "minLength" else "at most"
        return (f"expected {bound} {wanted} character(s), found "
                f"{f'{len(found)} characters' if found else 'empty text'}")
    if kind == "pattern":
        return f"expected text matching {wanted}, found {describe(found)}"
    return (f"expected a value valid for the schema keyword {kind!r} ({wanted!r}), found "
            f"{describe(found)}")


def _parts(err: jsonschema.ValidationError) -> tuple[str, Any, Any, Any]:
    """The keyword, its value in the schema, the value found and the failing sub-schema (typed
    as possibly unset by jsonschema; always set on a reported error)."""
    return str(err.validator), err.validator_value, err.instance, err.schema


def _types(wanted: str | list[str]) -> str:
    """``["string", "number", "object"]`` as ``text, a number or a mapping``."""
    words = [_TYPES.get(t, t) for t in ([wanted] if isinstance(wanted, str) else wanted)]
    return " or ".join(words) if len(words) <= 2 else f"{', '.join(words[:-1])} or {words[-1]}"


def _unknown_keys(path: Path, schema: dict, found: dict) -> list[SchemaProblem]:
    """One problem per key the mapping does not take, located at the key, with the closest
    field it takes; ``"x-fields"`` words the fields a mapping takes by pattern."""
    allowed = list(schema.get("properties", {}))
    patterns = list(schema.get("patternProperties", {}))
    listing = schema.get("x-fields") or ", ".join(allowed) or (
        f"named like {', '.join(patterns)}" if patterns else "none")
    out = []
    for key in found:
        if key in allowed or any(re.search(p, str(key)) for p in patterns):
            continue
        out.append(SchemaProblem(path + (key,), f"expected only the fields {listing}, found "
                                                f"'{key}'{did_you_mean(key, allowed)}",
                                 at_key=True, meant=closest(key, allowed)))
    return out


def _alternatives(err: jsonschema.ValidationError, path: Path) -> list[SchemaProblem]:
    """A failed ``oneOf``/``anyOf``: a choice between sets of fields is worded as such; else the
    branch that got furthest into the value is the one the author meant."""
    _, branches, found, _ = _parts(err)
    choices = [branch["required"] for branch in branches
               if isinstance(branch, dict) and set(branch) == {"required"}]
    if choices and len(choices) == len(branches) and isinstance(found, dict):
        return [_choice(path, choices, found)]
    context = list(err.context or ())
    if not context:  # a oneOf that several alternatives fit
        return [SchemaProblem(path, f"expected a value that fits one of {len(branches)} "
                                    f"alternatives, found {describe(found)}, which fits several")]
    if all(e.validator == "type" and e.absolute_path == err.absolute_path for e in context):
        wanted = [_parts(e)[1] for e in context]
        types = [t for w in wanted for t in ([w] if isinstance(w, str) else w)]
        return [SchemaProblem(path, f"expected {_types(list(dict.fromkeys(types)))}, found "
                                    f"{describe(found)}")]
    return _explain(max(context, key=lambda e: (len(e.absolute_path), e.validator != "type")))


def _choice(path: Path, choices: list[list[str]], found: dict[str, Any]) -> SchemaProblem:
    """A mapping that takes exactly one of several sets of fields (``rotation`` or
    ``rotations``; ``body`` with ``at``, ``bodies`` with ``at``, or ``acts``)."""
    chosen = [fields for fields in choices if fields[0] in found]
    if len(chosen) == 1:
        # The set begun is the one meant; it failed, so one of its fields is missing.
        missing = next(name for name in chosen[0] if name not in found)
        return SchemaProblem(path, f"expected a field '{missing}' with '{chosen[0][0]}', "
                                   f"found none", missing=missing)
    if chosen:
        firsts = [fields[0] for fields in chosen]
        return SchemaProblem(path, f"expected only one of the fields "
                                   f"{', '.join(c[0] for c in choices)}, found "
                                   f"{', '.join(firsts[:-1])} and {firsts[-1]}")
    names = [fields[0] + (f" (with {', '.join(fields[1:])})" if len(fields) > 1 else "")
             for fields in choices]
    return SchemaProblem(path, f"expected one of the fields {', '.join(names)}, found none "
                               f"of them")


def describe(value: object) -> str:
    """A found value, briefly: ``'text'``, ``3``, ``true``, ``null``, ``a list of 2``.

    >>> describe("x" * 50), describe([]), describe({"a": 1}), describe({}), describe(None)
    ("'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx...'", 'an empty list', 'a mapping', 'an empty mapping', 'null')
    """
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, dict):
        return "a mapping" if value else "an empty mapping"
    if isinstance(value, list):
        return f"a list of {len(value)}" if value else "an empty list"
    if isinstance(value, str):
        return repr(value if len(value) <= 40 else value[:37] + "...") if value \
            else "empty text"
    if isinstance(value, float) and not math.isfinite(value):
        return f"{value!r} ({'not a number' if math.isnan(value) else 'infinite'})"
    if isinstance(value, int) and abs(value) > LARGEST:
        return f"a number of {len(str(abs(value)))} digits"
    return repr(value)


def _order(path: Path) -> tuple:
    return tuple((0, part, "") if isinstance(part, int) else (1, 0, part) for part in path)
