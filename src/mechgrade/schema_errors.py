"""The one translator of JSON Schema errors into mechgrade's messages.

Every file mechgrade checks against a JSON Schema (problem files, assignments, ``results.json``)
reports a violation the same way: where (the path to the field, ``students[3].status``), what
was expected and what was found. A schema can word what it expects in its own terms with the
annotation ``"x-expected"`` on the failing sub-schema (``"x-expected": "an equation 'left =
right'"``), which replaces the generic wording of any keyword, and a mapping that takes keys by
pattern can word them with ``"x-fields"``.

>>> schema = {"type": "object", "required": ["id"], "additionalProperties": False,
...           "properties": {"id": {"type": "string"},
...                          "status": {"enum": ["graded", "missing"]}}}
>>> for problem in schema_problems(schema, {"id": 3, "status": "great", "x": 1}):
...     print(problem)
id: expected text, found 3
status: expected one of graded, missing, found 'great'
x: expected only the fields id, status, found 'x'
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import jsonschema

Path = tuple[str | int, ...]

_TYPES = {"object": "a mapping", "array": "a list", "string": "text", "number": "a number",
          "integer": "a whole number", "boolean": "true or false", "null": "null"}


@dataclass(frozen=True)
class SchemaProblem:
    """One violation: ``path`` to the offending value and the message ``expected ..., found``."""

    path: Path
    message: str

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


def schema_problems(schema: dict, data: object) -> tuple[SchemaProblem, ...]:
    """Every violation of ``schema`` by ``data``, in document order (the first is the one to
    report when only one is)."""
    # imported here: jsonschema takes longer to import than click, and `--help` needs neither
    import jsonschema

    errors = jsonschema.Draft202012Validator(schema).iter_errors(data)
    problems = [explain(err) for err in errors]
    return tuple(sorted(problems, key=lambda p: _order(p.path)))


def explain(err: jsonschema.ValidationError) -> SchemaProblem:
    """One jsonschema error as a :class:`SchemaProblem`."""
    path: Path = tuple(err.absolute_path)
    kind, wanted, found, schema = err.validator, err.validator_value, err.instance, err.schema
    if isinstance(schema, dict) and "x-expected" in schema and kind != "required":
        return SchemaProblem(path, f"expected {schema['x-expected']}, found {describe(found)}")
    if kind == "required":
        missing = next(name for name in wanted if name not in found)
        return SchemaProblem(path, f"expected a field '{missing}', found none")
    if kind == "dependentRequired":
        key, missing = next((k, m) for k, needed in wanted.items() if k in found
                            for m in needed if m not in found)
        return SchemaProblem(path, f"expected a field '{missing}' with '{key}', found none")
    if kind == "additionalProperties":
        # Located at the unknown key itself; "x-fields" words what else a mapping takes.
        allowed = list(schema.get("properties", {}))
        patterns = schema.get("patternProperties", {})
        extra = next(key for key in found if key not in allowed
                     and not any(re.search(p, key) for p in patterns))
        listing = schema.get("x-fields") or (", ".join(allowed) if allowed else "none")
        return SchemaProblem(path + (extra,),
                             f"expected only the fields {listing}, found '{extra}'")
    if kind == "type":
        types = wanted if isinstance(wanted, list) else [wanted]
        return SchemaProblem(path, f"expected {' or '.join(_TYPES.get(t, t) for t in types)}, "
                                   f"found {describe(found)}")
    if kind == "enum":
        return SchemaProblem(path, f"expected one of {', '.join(str(v) for v in wanted)}, "
                                   f"found {describe(found)}")
    if kind == "const":
        return SchemaProblem(path, f"expected {wanted!r}, found {describe(found)}")
    if kind in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"):
        sign = {"minimum": ">=", "maximum": "<=", "exclusiveMinimum": ">",
                "exclusiveMaximum": "<"}[kind]
        return SchemaProblem(path, f"expected a number {sign} {wanted:g}, found "
                                   f"{describe(found)}")
    if kind in ("minItems", "maxItems"):
        bound = "at least" if kind == "minItems" else "at most"
        return SchemaProblem(path, f"expected {bound} {wanted} item(s), found {describe(found)}")
    if kind in ("minLength", "maxLength"):
        bound = "at least" if kind == "minLength" else "at most"
        return SchemaProblem(path, f"expected {bound} {wanted} character(s), found "
                                   f"{len(found) if found else 'empty text'}"
                                   f"{' characters' if found else ''}")
    if kind in ("minProperties", "maxProperties"):
        bound = "at least" if kind == "minProperties" else "at most"
        return SchemaProblem(path, f"expected {bound} {wanted} field(s), found "
                                   f"{describe(found)}")
    if kind == "pattern":
        return SchemaProblem(path, f"expected text matching {wanted}, found {describe(found)}")
    if kind in ("oneOf", "anyOf") and err.context:
        # The branch that got furthest into the value is the one the author meant.
        return explain(max(err.context,
                           key=lambda e: (len(e.absolute_path), e.validator != "type")))
    return SchemaProblem(path, f"expected a value valid for the schema keyword {kind!r} "
                               f"({wanted!r}), found {describe(found)}")


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
    return repr(value)


def _order(path: Path) -> tuple:
    return tuple((0, part, "") if isinstance(part, int) else (1, 0, part) for part in path)
