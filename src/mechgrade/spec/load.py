"""Load a problem file: safe YAML, JSON Schema, then names, kinds and dimensions.

>>> from mechgrade.resources import shipped_dir
>>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
>>> problem.id, [c.name for c in problem.coordinates]
('bowling_3_15_4_pendulum', ['theta'])
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import replace
from functools import lru_cache
from pathlib import Path

from ..errors import AuthorWarning, ExpressionError, Location, SpecError, SpecErrors, UnitError
from ..expressions.syntax import MATH_FUNCTIONS, Name, Num, Unary, constant_value, parse
from ..schema_errors import SchemaProblem, did_you_mean, schema_problems
from ..units import normalize_unit, parse_quantity, to_si
from ..yamlio import Document, read_yaml, read_yaml_text
from .dynamics import read_dynamics
from .language import FUNCTIONS
from .model import (CONSISTENCY, Constraint, ConstraintLevel, Coordinate, Expect, Expr, Frame, Given, Mistake,
                    Objective, Parameter, Point, Problem, Rotation, SymbolDecl, Tolerance)
from .solving import (check_solving, expand, given_expression, read_branches, read_definitions,
                      read_unknowns, resolve_given_values)
from .physics import given_value_hint, plausibility_warnings, tolerance_errors
from .validate import RESERVED, bare_angle_message, is_angle_unit, problem_errors

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
    """Check ``doc`` against the schema, build the model and validate it, collecting every
    independent error; raise them all at once (:class:`SpecErrors` when there are several)."""
    if not isinstance(doc.data, dict):
        found = "an empty file" if doc.data is None else f"a {type(doc.data).__name__}"
        raise SpecError(f"expected a mapping of problem fields (id, title, ...), found {found}",
                        where=doc.where(()))
    errors, broken = _schema_errors(doc)
    builder = _Builder(doc, broken)
    problem = builder.build()
    errors += builder.errors
    if problem is not None:
        errors += problem_errors(problem, frozenset(builder.broken_names))
        errors += tolerance_errors(problem)
    _raise_all(errors)
    assert problem is not None  # build() gives None only after a schema error, raised above
    return replace(problem, warnings=problem.warnings + plausibility_warnings(problem))


def _raise_all(errors: list[SpecError]) -> None:
    """Raise nothing, the one error, or :class:`SpecErrors` holding all of them (each message
    once)."""
    seen, kept = set(), []
    for err in errors:
        if str(err) not in seen:
            seen.add(str(err))
            kept.append(err)
    if len(kept) == 1:
        raise kept[0]
    if kept:
        raise SpecErrors(kept)


# ---------------------------------------------------------------------------- schema


def _schema_errors(doc: Document) -> tuple[list[SpecError], set[tuple]]:
    """Every schema error of ``doc`` (worded by :mod:`mechgrade.schema_errors`), and the paths
    of the values they make unusable."""
    errors, broken = [], set()
    for problem in schema_problems(problem_schema(), doc.data):
        where = doc.where_key(problem.path) if problem.at_key else doc.where(problem.path)
        errors.append(SpecError(problem.message, where=where))
        broken.add(_unusable(problem))
    return errors, broken


def _unusable(problem: SchemaProblem) -> tuple:
    """The path a schema problem makes unusable. An unknown or badly formed key spoils its
    mapping (later uses of the name the author meant stay quiet); a missing or unknown
    top-level field only itself."""
    if problem.at_key and len(problem.path) > 1:
        return problem.path[:-1]
    if problem.missing and not problem.path:
        return (problem.missing,)
    return problem.path


# ---------------------------------------------------------------------------- building


class _Builder:
    """Builds the model item by item; an item whose building fails is left out and its name
    remembered, so later checks do not report the same mistake again as an undefined name."""

    def __init__(self, doc: Document, broken: set[tuple]):
        self.doc = doc
        self.data = doc.data
        self.broken = broken
        self.errors: list[SpecError] = []
        self.broken_names: set[str] = set()
        self.definitions: dict = {}
        self.definition_items = (self.attempt(read_definitions, self.data, self.expr, self.where)
                                 if self.usable("define") else None) or ()
        # A definition that reuses a name is reported by check_solving; expanding it would only
        # add errors about the name it shadows.
        taken = RESERVED | {name for section in ("frames", "points", "coordinates", "parameters")
                            if isinstance(self.data.get(section), dict)
                            for name in self.data[section]}
        for d in self.definition_items:
            if d.name not in taken:
                self.definitions[d.name] = d.expr.node

    def where(self, *path) -> Location:
        return self.doc.where(tuple(path))

    def usable(self, *path) -> bool:
        """Whether no schema error lies at or under ``path``."""
        return not any(b[:len(path)] == path for b in self.broken)

    def attempt(self, build, *args):
        """``build(*args)``, or None after recording its error."""
        try:
            return build(*args)
        except SpecError as err:
            self.errors.append(err)
            return None

    def named(self, section: str, build) -> list:
        """``build(name, spec)`` for each entry of a section of named items; the names of
        entries that fail (or have schema errors) are remembered as broken."""
        out = []
        for name, spec in self.section(section, {}).items():
            item = self.attempt(build, name, spec) if self.usable(section, name) else None
            if item is None:
                self.broken_names.add(name)
            else:
                out.append(item)
        return out

    def section(self, name: str, empty):
        """The section's value, or ``empty`` (and every name in it unknown) if it is broken."""
        if (name,) in self.broken:
            self.broken_names.add(f"{name}:*")
            return empty
        return self.data.get(name) or empty

    def expr(self, text, *path) -> Expr:
        where = self.where(*path)
        if isinstance(text, bool):
            raise SpecError(f"expected an expression, found {str(text).lower()}", where=where)
        text = str(text)
        try:
            node = parse(text, functions=FUNCTIONS)
        except ExpressionError as err:
            raise SpecError(_with_hint(err.message, text), where=where) from None
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
                raise SpecError(_with_hint(err.message, side), where=where) from None
        return exprs[0], exprs[1]

    def unit(self, text, *path) -> str:
        """The unit as the author wrote it, once it is known to be valid."""
        try:
            normalize_unit(str(text))
        except UnitError as err:
            raise SpecError(_unit_hint(err.message), where=self.where(*path)) from None
        return str(text).strip()

    def angle(self, value, *path) -> Expr:
        """A rotation angle: an expression, or a number with an angle unit (``25 deg``)."""
        where = self.where(*path)
        if isinstance(value, str):
            try:
                q = parse_quantity(value)
            except UnitError:
                q = None
            if q is not None and q.unit:
                if not is_angle_unit(q.unit):
                    raise SpecError(f"expected an angle such as '25 deg', found {value!r}",
                                    where=where)
                return Expr(value, Num(repr(to_si(q.value, q.unit))), where)
        expr = self.expr(value, *path)
        number = _literal(expr.node)
        if number is not None and number != 0:
            raise SpecError(bare_angle_message(expr.text), where=where)
        return expr

    def build(self) -> Problem | None:
        d = self.data
        if not self.usable("inertial"):
            return None
        inertial = d["inertial"]
        frames = [Frame(inertial["frame"], None, (), inertial["point"],
                        self.doc.where_key(("inertial", "frame")))]
        frames += self.named("frames", self.frame)
        points = [Point(inertial["point"], None, None, self.doc.where_key(("inertial", "point")))]
        points += self.named("points", self.point)
        coordinates = self.named("coordinates", self.coordinate)
        parameters = self.named("parameters", self.parameter)
        constraints = [self.attempt(self.constraint, c, i)
                       for i, c in enumerate(self.section("constraints", []))
                       if self.usable("constraints", i)]
        givens = [self.attempt(self.given, k, v, "givens")
                  for k, v in self.section("givens", {}).items() if self.usable("givens", k)]
        guesses = [self.attempt(self.given, k, v, "guesses")
                   for k, v in self.section("guesses", {}).items() if self.usable("guesses", k)]
        objectives = []
        for i, spec in enumerate(self.section("objectives", [])):
            objective = self.objective(spec, i) if self.usable("objectives", i) else None
            if objective is None:
                if isinstance(spec, dict) and isinstance(spec.get("id"), str):
                    self.broken_names.add(spec["id"])
            else:
                objectives.append(objective)
        givens = [g for g in givens if g is not None]
        resolved = self.attempt(resolve_given_values, tuple(givens), tuple(coordinates),
                                tuple(parameters))
        givens = list(resolved) if resolved is not None else givens
        unknowns = (self.attempt(read_unknowns, d, self.expr) if self.usable("unknown")
                    else None) or ()
        branches = (self.attempt(read_branches, d, self.expr, self.where)
                    if self.usable("branch") else None) or ()
        self.attempt(check_solving, tuple(coordinates), tuple(parameters), tuple(givens),
                     unknowns, branches, self.definition_items,
                     RESERVED | {f.name for f in frames} | {p.name for p in points})
        variants = self.variants(givens, objectives, coordinates, parameters)
        problem_id = d.get("id") if self.usable("id") else ""
        return Problem(
            id=problem_id, title=d.get("title", "") if self.usable("title") else "",
            statement=str(d.get("statement", "")).strip(),
            source=d.get("source", ""), inertial_frame=inertial["frame"],
            inertial_point=inertial["point"], frames=tuple(frames), points=tuple(points),
            coordinates=tuple(coordinates), parameters=tuple(parameters),
            constraints=tuple(c for c in constraints if c is not None),
            givens=tuple(g for g in givens if g is not None),
            guesses=tuple(g for g in guesses if g is not None), objectives=tuple(objectives),
            consistency=float(d.get("consistency", CONSISTENCY)) if self.usable("consistency")
            else CONSISTENCY,
            path=self.doc.file, unknowns=unknowns, branches=branches,
            definitions=self.definition_items, warnings=self.warnings(problem_id),
            variants=variants, dynamics=self.dynamics(),
            tags=tuple(d.get("tags", ())) if self.usable("tags") else ())

    def dynamics(self):
        """The ``bodies:``, ``loads:`` and ``analysis:`` sections (:mod:`.dynamics`)."""
        dynamics = (self.attempt(read_dynamics, self.data, self.expr, self.where)
                    if all(self.usable(k) for k in ("bodies", "loads", "analysis")) else None)
        if dynamics is None and any(k in self.data for k in ("bodies", "loads")):
            self.broken_names.add("dynamics:*")  # uses of its bodies and loads stay quiet
        return dynamics

    def variants(self, givens, objectives, coordinates, parameters):
        """The ``variants:`` section (:mod:`.variants`); its errors join the others."""
        if not self.usable("variants") or not self.usable("givens"):
            return None
        from .variants import read_variants

        names = {"t": "s", **{o.id: o.unit for o in objectives},
                 **{p.name: p.unit for p in parameters}}
        for c in coordinates:
            base = f"({c.unit})" if any(ch in c.unit for ch in "/* ") else c.unit or "1"
            names.update({c.name: c.unit, c.name + "'": f"{base}/s",
                          c.name + "''": f"{base}/s^2"})
        variants, errors = read_variants(self.data, tuple(givens), names, self.where,
                                         str(self.data.get("statement", "")), self.usable)
        self.errors += errors
        return variants

    def warnings(self, problem_id) -> tuple[AuthorWarning, ...]:
        stem = Path(self.doc.file).stem
        if not problem_id or Path(self.doc.file).suffix not in (".yaml", ".yml") \
                or stem == problem_id:
            return ()
        return (AuthorWarning(f"id '{problem_id}' differs from the file name '{stem}'; "
                              f"expected them equal (rename the file or write id: {stem})",
                              self.where("id")),)

    def frame(self, name: str, spec: dict) -> Frame:
        rotations: tuple[Rotation, ...]
        if "rotation" in spec:
            rotations = (self.rotation(spec["rotation"], "frames", name, "rotation"),)
        else:
            rotations = tuple(self.rotation(r, "frames", name, "rotations", i)
                              for i, r in enumerate(spec["rotations"]))
        return Frame(name, spec["parent"], rotations, spec.get("origin"),
                     self.doc.where_key(("frames", name)),
                     parent_where=self.where("frames", name, "parent"),
                     origin_where=self.where("frames", name, "origin"))

    def point(self, name: str, spec: dict) -> Point:
        return Point(name, spec["from"], self.expr(spec["position"], "points", name, "position"),
                     self.doc.where_key(("points", name)),
                     origin_where=self.where("points", name, "from"))

    def coordinate(self, name: str, unit) -> Coordinate:
        return Coordinate(name, self.unit(unit, "coordinates", name),
                          self.doc.where_key(("coordinates", name)))

    def parameter(self, name: str, spec) -> Parameter:
        where = self.doc.where_key(("parameters", name))
        if isinstance(spec, dict):
            return Parameter(name, self.unit(spec["unit"], "parameters", name, "unit"),
                             spec.get("positive", True), where)
        return Parameter(name, self.unit(spec, "parameters", name), True, where)

    def rotation(self, spec: dict, *path) -> Rotation:
        return Rotation(spec["axis"], self.angle(spec["angle"], *path, "angle"))

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
            return Constraint(name, ConstraintLevel.VELOCITY, lhs, rhs, where)
        level = ConstraintLevel.POSITION if "position" in spec else ConstraintLevel.VELOCITY
        lhs, rhs = self.equation(spec[level.value], "constraints", i, level.value)
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
                raise SpecError(given_value_hint(str(value), self.data)
                                or _unit_hint(err.message), where=where) from None
            number, unit, text = q.value, q.unit, str(value)
        return Given(key_expr, number, unit, to_si(number, unit), text, where)

    def _number(self, value, where: Location) -> float:
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

    def objective(self, spec: dict, i: int) -> Objective | None:
        path = ("objectives", i)
        failed = False

        def part(build, *args):
            nonlocal failed
            out = self.attempt(build, *args)
            failed = failed or out is None
            return out

        symbols = []
        for j, entry in enumerate(spec.get("symbols") or []):
            if isinstance(entry, dict):
                (name, means), = entry.items()
                symbols.append(SymbolDecl(name, part(self.expr, means, *path, "symbols", j)))
            else:
                symbols.append(SymbolDecl(entry, Expr(entry, Name(entry),
                                                      self.where(*path, "symbols", j))))
        tol = spec.get("tolerance") or {}
        expect = part(self.expect, spec["expect"], *path) if "expect" in spec else None
        mistakes = tuple(
            Mistake(part(self.expr, m["find"], *path, "mistakes", j, "find"), m["message"],
                    float(m.get("credit", 0.0)), self.where(*path, "mistakes", j))
            for j, m in enumerate(spec.get("mistakes") or []))
        find = part(self.expr, spec["find"], *path, "find")
        unit = part(self.unit, spec["unit"], *path, "unit")
        givens = tuple(part(self.given, k, v, *path, "givens")
                       for k, v in (spec.get("givens") or {}).items())
        when = part(self.equation, spec["when"], *path, "when") \
            if "when" in spec else None
        if failed:
            return None
        return Objective(
            id=spec["id"], prompt=spec["prompt"].strip(), find=find, kind=spec["kind"],
            unit=unit, frame=spec.get("frame"), symbols=tuple(symbols),
            tolerance=Tolerance(float(tol.get("rel", 0.01)), float(tol.get("abs", 0.0)),
                                self.where(*path, "tolerance")),
            expect=expect, mistakes=mistakes, depends_on=tuple(spec.get("depends_on") or ()),
            givens=givens, when=when, where=self.where(*path),
            frame_where=self.where(*path, "frame"),
            depends_where=tuple(self.where(*path, "depends_on", j)
                                for j in range(len(spec.get("depends_on") or ()))))

    def expect(self, e: dict, *path) -> Expect:
        path = path + ("expect",)
        components = None
        if "components" in e:
            components = tuple(float(c) for c in e["components"])
        return Expect(
            value=e.get("value"), components=components,
            expr=str(e["expr"]) if "expr" in e else None,
            unit=self.unit(e["unit"], *path, "unit") if "unit" in e else None,
            book=str(e["book"]) if "book" in e else None,
            note=e.get("note"), where=self.where(*path),
            written=(self._written(e["value"], *path, "value") if "value" in e else
                     tuple(self._written(c, *path, "components", j)
                           for j, c in enumerate(e["components"])) if components else None))

    def _written(self, value, *path) -> str:
        return self.doc.text(path) or repr(value)


def _literal(node) -> float | None:
    """The value of a bare number literal (``25`` or ``-25``), else None."""
    if isinstance(node, Unary) and isinstance(node.operand, Num):
        return -node.operand.value
    if isinstance(node, Num):
        return node.value
    return None


_CALL = re.compile(r"\b([A-Za-z]\w*)\s*\(")
_UNKNOWN_UNIT = re.compile(r"\('(\w+)' is not a unit\)$")
COMMON_UNITS = ("m", "meter", "metre", "cm", "mm", "km", "ft", "foot", "inch", "in", "mi", "s",
                "second", "ms", "min", "h", "hr",
                "rad", "deg", "degree", "radian", "revolution", "turn", "rpm", "kg", "g", "lb",
                "N", "lbf", "J", "W", "Hz", "mph", "kph", "knot", "yd")


def _with_hint(message: str, text: str) -> str:
    """An expression error; when a call names an unknown function, say so, with the closest
    known name (the reader alone would see a product of a name and a parenthesis)."""
    known = set(FUNCTIONS) | set(MATH_FUNCTIONS)
    for name in _CALL.findall(text):
        if name not in known:
            hint = did_you_mean(name, known)
            if hint:
                return f"unknown function '{name}(...)'{hint}"
    return message


def _unit_hint(message: str) -> str:
    match = _UNKNOWN_UNIT.search(message)
    return message + did_you_mean(match.group(1), COMMON_UNITS) if match else message
