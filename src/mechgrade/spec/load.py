"""Load a problem file: safe YAML, JSON Schema, then names, kinds and dimensions.

>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
>>> problem.id, [c.name for c in problem.coordinates]
('bowling_3_15_4_pendulum', ['theta'])
"""

from __future__ import annotations

import json
import math
from functools import lru_cache
from pathlib import Path

import jsonschema

from ..errors import ExpressionError, Location, SpecError, UnitError
from ..expressions.syntax import Name, parse
from ..units import normalize_unit, parse_quantity, to_si
from ..yamlio import Document, read_yaml, read_yaml_text
from .dynamics import read_dynamics
from .language import FUNCTIONS
from .model import (Constraint, Coordinate, Expect, Expr, Frame, Given, Mistake, Objective,
                    Parameter, Point, Problem, Rotation, SymbolDecl, Tolerance)
from .solving import (check_solving, expand, given_expression, read_branches, read_definitions,
                      read_unknowns, resolve_given_values)
from .validate import RESERVED, validate_problem

SCHEMA_PATH = Path(__file__).with_name("problem.schema.json")


@lru_cache(maxsize=1)
def problem_schema() -> dict:
    """The JSON Schema of problem files (also shipped as ``spec/problem.schema.json``)."""
    return json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))


def load_problem(path: str | Path) -> Problem:
    """Read, check and return the problem in ``path``; raise :class:`SpecError` if it is bad."""
    return problem_from_document(read_yaml(path, SpecError, "a problem file (YAML)"))


def load_problem_text(text: str, name: str = "<problem>") -> Problem:
    """Like :func:`load_problem` for YAML text already in memory."""
    return problem_from_document(read_yaml_text(text, name, SpecError))


def problem_from_document(doc: Document) -> Problem:
    _check_schema(doc)
    problem = _Builder(doc).build()
    validate_problem(problem)
    return problem


# ---------------------------------------------------------------------------- schema


def _check_schema(doc: Document) -> None:
    if not isinstance(doc.data, dict):
        found = "an empty file" if doc.data is None else f"a {type(doc.data).__name__}"
        raise SpecError(f"expected a mapping of problem fields (id, title, ...), found {found}",
                        where=doc.where(()))
    validator = jsonschema.Draft202012Validator(problem_schema())
    errors = list(validator.iter_errors(doc.data))
    if not errors:
        return

    def order(err):
        where = doc.where(tuple(err.absolute_path))
        return (where.line or 0, where.column or 0, -len(err.absolute_path))

    err = min(errors, key=order)
    path = tuple(err.absolute_path)
    if err.validator == "additionalProperties" and isinstance(err.instance, dict):
        extra = sorted(set(err.instance) - set(err.schema.get("properties", {})))
        path += (extra[0],) if extra else ()
    raise SpecError(_schema_message(err), where=doc.where(path))


def _schema_message(err: jsonschema.ValidationError) -> str:
    kind = err.validator
    inst = err.instance
    schema = err.schema
    if kind == "additionalProperties":
        allowed = sorted(schema.get("properties", {}))
        extra = sorted(set(inst) - set(allowed))
        listing = ", ".join(allowed) if allowed else "none"
        return f"unknown key '{extra[0]}' (expected one of: {listing})"
    if kind == "required":
        missing = [r for r in err.validator_value if r not in inst]
        return f"missing required key '{missing[0]}'"
    if kind == "type":
        expected = err.validator_value
        expected = " or ".join(expected) if isinstance(expected, list) else expected
        return f"expected {_article(expected)}, found {_describe(inst)}"
    if kind == "enum":
        options = ", ".join(str(v) for v in err.validator_value)
        return f"expected one of: {options}; found {inst!r}"
    if kind == "pattern":
        if err.validator_value.startswith("^[^=]"):
            return f"expected an equation 'left = right', found {inst!r}"
        return (f"expected a name made of letters, digits and '_' starting with a letter, "
                f"found {inst!r}")
    if kind in ("minItems", "maxItems", "minLength", "minProperties", "maxProperties"):
        return f"expected {kind[:3]} {err.validator_value} item(s), found {_describe(inst)}"
    if kind in ("minimum", "maximum", "exclusiveMinimum"):
        return f"expected a number within bounds ({kind} {err.validator_value}), found {inst!r}"
    if kind == "oneOf":
        required = [sub.get("required", [None])[0] for sub in err.validator_value
                    if "required" in sub]
        if required and isinstance(inst, dict):
            present = [r for r in required if r in inst]
            if len(present) > 1:
                return f"expected only one of {', '.join(required)}, found {', '.join(present)}"
            if not present:
                return f"expected one of the keys {', '.join(required)}"
        best = jsonschema.exceptions.best_match(err.context) if err.context else None
        if best is not None:
            return _schema_message(best)
        return f"expected a valid value, found {_describe(inst)}"
    if kind == "dependentRequired":
        return "a 'book' answer needs a 'note' explaining the discrepancy"
    if kind == "propertyNames":
        return f"expected a name made of letters, digits and '_', found {inst!r}"
    return err.message


def _article(word: str) -> str:
    words = {"object": "a mapping", "array": "a list", "string": "a string",
             "number": "a number", "integer": "an integer", "boolean": "true or false",
             "string or number": "a string or number", "string or integer": "a string"}
    return words.get(word, word)


def _describe(value) -> str:
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return f"a list of {len(value)}"
    if isinstance(value, str):
        return repr(value[:40])
    return repr(value)


# ---------------------------------------------------------------------------- building


class _Builder:
    def __init__(self, doc: Document):
        self.doc = doc
        self.data = doc.data
        self.definitions: dict = {}
        for d in read_definitions(self.data, self.expr, self.where):
            self.definitions[d.name] = d.expr.node

    def where(self, *path) -> Location:
        return self.doc.where(tuple(path))

    def expr(self, text, *path) -> Expr:
        where = self.where(*path)
        if isinstance(text, bool):
            raise SpecError(f"expected an expression, found {str(text).lower()}", where=where)
        text = str(text)
        try:
            node = parse(text, functions=FUNCTIONS)
        except ExpressionError as err:
            raise SpecError(err.message, where=where) from None
        return Expr(text, expand(node, self.definitions), where)

    def equation(self, text: str, *path) -> tuple[Expr, Expr]:
        left, right = text.split("=")
        where = self.where(*path)
        exprs = []
        for side in (left, right):
            try:
                node = expand(parse(side, functions=FUNCTIONS), self.definitions)
                exprs.append(Expr(side.strip(), node, where))
            except ExpressionError as err:
                raise SpecError(err.message, where=where) from None
        return exprs[0], exprs[1]

    def unit(self, text, *path) -> str:
        """The unit as the author wrote it, once it is known to be valid."""
        try:
            normalize_unit(str(text))
        except UnitError as err:
            raise SpecError(err.message, where=self.where(*path)) from None
        return str(text).strip()

    def build(self) -> Problem:
        d = self.data
        inertial = d["inertial"]
        frames = [Frame(inertial["frame"], None, (), inertial["point"],
                        self.where("inertial", "frame"))]
        for name, spec in (d.get("frames") or {}).items():
            if "rotation" in spec:
                rotations = (self.rotation(spec["rotation"], "frames", name, "rotation"),)
            else:
                rotations = tuple(self.rotation(r, "frames", name, "rotations", i)
                                  for i, r in enumerate(spec["rotations"]))
            frames.append(Frame(name, spec["parent"], rotations, spec.get("origin"),
                                self.where("frames", name)))
        points = [Point(inertial["point"], None, None, self.where("inertial", "point"))]
        for name, spec in (d.get("points") or {}).items():
            points.append(Point(name, spec["from"],
                                self.expr(spec["position"], "points", name, "position"),
                                self.where("points", name)))
        coordinates = tuple(Coordinate(name, self.unit(unit, "coordinates", name),
                                       self.where("coordinates", name))
                            for name, unit in (d.get("coordinates") or {}).items())
        parameters = []
        for name, spec in (d.get("parameters") or {}).items():
            if isinstance(spec, dict):
                parameters.append(Parameter(name, self.unit(spec["unit"], "parameters", name,
                                                            "unit"),
                                            spec.get("positive", True),
                                            self.where("parameters", name)))
            else:
                parameters.append(Parameter(name, self.unit(spec, "parameters", name), True,
                                            self.where("parameters", name)))
        constraints = tuple(self.constraint(c, i) for i, c in enumerate(d.get("constraints") or []))
        givens = tuple(self.given(k, v, "givens") for k, v in (d.get("givens") or {}).items())
        guesses = tuple(self.given(k, v, "guesses") for k, v in (d.get("guesses") or {}).items())
        givens = resolve_given_values(givens, coordinates, tuple(parameters))
        objectives = tuple(self.objective(o, i) for i, o in enumerate(d["objectives"]))
        unknowns = read_unknowns(d, self.expr)
        branches = read_branches(d, self.expr, self.where)
        definitions = read_definitions(d, self.expr, self.where)
        check_solving(coordinates, parameters, givens, unknowns, branches, definitions,
                      RESERVED | {f.name for f in frames} | {p.name for p in points})
        return Problem(
            id=d["id"], title=d["title"], statement=d["statement"].strip(),
            source=d.get("source", ""), inertial_frame=inertial["frame"],
            inertial_point=inertial["point"], frames=tuple(frames), points=tuple(points),
            coordinates=coordinates, parameters=tuple(parameters), constraints=constraints,
            givens=givens, guesses=guesses, objectives=objectives,
            consistency=float(d.get("consistency", 5e-3)), path=self.doc.file,
            unknowns=unknowns, branches=branches, definitions=definitions,
            dynamics=read_dynamics(d, self.expr, self.where))

    def rotation(self, spec: dict, *path) -> Rotation:
        return Rotation(spec["axis"], self.expr(spec["angle"], *path, "angle"))

    def constraint(self, spec: dict, i: int) -> Constraint:
        name = spec["name"]
        where = self.where("constraints", i)
        if "rolling" in spec:
            r = spec["rolling"]
            contact, body, surface = r["contact"], r["body"], r["surface"]
            # Rolling without slip: the body's material point at the contact moves with the
            # surface's material point there.
            left = f"vel(coincident({contact}, {body}), {self.data['inertial']['frame']})"
            right = f"vel(coincident({contact}, {surface}), {self.data['inertial']['frame']})"
            lhs = self.expr(left, "constraints", i, "rolling")
            rhs = self.expr(right, "constraints", i, "rolling")
            return Constraint(name, "velocity", lhs, rhs, where)
        level = "position" if "position" in spec else "velocity"
        lhs, rhs = self.equation(spec[level], "constraints", i, level)
        return Constraint(name, level, lhs, rhs, where)

    def given(self, key: str, value, *section) -> Given:
        key_expr = self.expr(key, *section, key)
        where = self.where(*section, key)
        if isinstance(value, dict):
            number = self._number(value["value"], where)
            unit = self.unit(value.get("unit", ""), *section, key, "unit")
            text = f"{value['value']} {value.get('unit', '')}".strip()
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            number, unit, text = float(value), "", str(value)
        else:
            try:
                q = parse_quantity(str(value))
            except UnitError as err:
                value_expr = given_expression(str(value), self.data.get("givens") or {},
                                              self.expr, section, key)
                if value_expr is not None:
                    return Given(key_expr, math.nan, "", math.nan, str(value), where,
                                 value_expr=value_expr)
                raise SpecError(err.message, where=where) from None
            number, unit, text = q.value, q.unit, str(value)
        return Given(key_expr, number, unit, to_si(number, unit), text, where)

    def _number(self, value, where: Location) -> float:
        from ..expressions.syntax import constant_value
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return float(value)
        try:
            number = constant_value(parse(str(value)))
        except ExpressionError as err:
            raise SpecError(err.message, where=where) from None
        if number is None:
            raise SpecError(f"expected a number or a constant expression such as pi/2, "
                            f"found {value!r}", where=where)
        return number

    def objective(self, spec: dict, i: int) -> Objective:
        path = ("objectives", i)
        symbols = []
        for j, entry in enumerate(spec.get("symbols") or []):
            if isinstance(entry, dict):
                (name, means), = entry.items()
                symbols.append(SymbolDecl(name, self.expr(means, *path, "symbols", j)))
            else:
                symbols.append(SymbolDecl(entry, Expr(entry, Name(entry),
                                                      self.where(*path, "symbols", j))))
        tol = spec.get("tolerance") or {}
        expect = None
        if "expect" in spec:
            e = spec["expect"]
            ewhere = self.where(*path, "expect")
            expect = Expect(
                value=e.get("value"),
                components=tuple(float(c) for c in e["components"]) if "components" in e else None,
                expr=str(e["expr"]) if "expr" in e else None,
                unit=self.unit(e["unit"], *path, "expect", "unit") if "unit" in e else None,
                book=str(e["book"]) if "book" in e else None,
                note=e.get("note"), where=ewhere)
        mistakes = tuple(
            Mistake(self.expr(m["find"], *path, "mistakes", j, "find"), m["message"],
                    float(m.get("credit", 0.0)))
            for j, m in enumerate(spec.get("mistakes") or []))
        return Objective(
            id=spec["id"], prompt=spec["prompt"].strip(),
            find=self.expr(spec["find"], *path, "find"), kind=spec["kind"],
            unit=self.unit(spec["unit"], *path, "unit"), frame=spec.get("frame"),
            symbols=tuple(symbols),
            tolerance=Tolerance(float(tol.get("rel", 0.01)), float(tol.get("abs", 0.0))),
            expect=expect, mistakes=mistakes, depends_on=tuple(spec.get("depends_on") or ()),
            givens=tuple(self.given(k, v, *path, "givens")
                         for k, v in (spec.get("givens") or {}).items()),
            where=self.where(*path))
