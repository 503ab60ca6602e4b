"""Check a built problem: every name defined, every expression well-kinded and dimensionally
consistent, frames and points forming trees, objectives answerable in their units.

Every independent error is collected (:func:`problem_errors`), each a :class:`SpecError`
located at the offending value or name; an error about a name whose definition already failed
to load is left out, so one mistake gives one message. Nothing here solves anything.
"""

from __future__ import annotations

import dataclasses
import math
import re
from contextlib import contextmanager
from enum import Enum
from functools import lru_cache

from ..errors import ExpressionError, Location, SpecError, UnitError
from ..expressions.dimensions import DimensionError, Kind, Type, infer
from ..expressions.syntax import (MATH_FUNCTIONS, Attr, Call, Name, Node, Num, Prime, parse,
                                  to_text)
from ..schema_errors import did_you_mean, number_problem
from ..units import (describe_dimension, dimension, dimensionless, normalize_unit, registry,
                     time_dimension)
from .dynamics import argument_dimension, check_dynamics
from .language import FUNCTIONS
from .model import TIME, Expect, Expr, Given, Objective, ObjectiveKind, Problem

DYNAMICS_KINDS = (Kind.BODY, Kind.LOAD, Kind.BODY_OR_SPRING, Kind.COORDINATE)
RESERVED = {TIME, "pi"} | set(MATH_FUNCTIONS) | set(FUNCTIONS)


_NUMBER_THEN_NAME = re.compile(r"(?<![\w.])(\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)\s*([A-Za-z_]\w*)(?![\w(])")
"""A number followed by a name (``4 s``, ``0.2m``): a quantity, if the name is a unit."""


class _Quiet(SpecError):
    """An error caused by an earlier one (an undefined name whose definition failed)."""


def unknown_name(what: str, name: str, known, context: str = "") -> str:
    """The one wording of a name that is not defined, with the closest known one.

    >>> unknown_name("frame", "NN", ["N", "A"])
    "unknown frame 'NN'; did you mean 'N'? (expected one of: N, A)"
    """
    known = list(known)
    return (f"unknown {what} '{name}'{context}{did_you_mean(name, known)} (expected one of: "
            f"{', '.join(known) or 'none'})")


@lru_cache(maxsize=256)
def is_angle_unit(unit: str) -> bool:
    """Whether ``unit`` measures an angle (rad, deg, turn ...), not a pure number (kept per
    unit: each variant of a position asked ``when`` asks it of its coordinate again).

    >>> is_angle_unit("deg"), is_angle_unit("rad"), is_angle_unit(""), is_angle_unit("rad/s")
    (True, True, False, False)
    """
    ureg = registry()
    canonical = normalize_unit(unit)
    if not canonical:
        return False
    root = ureg.Quantity(1.0, ureg.parse_units(canonical)).to_root_units().units
    return dict(root._units) == {"radian": 1}


def bare_angle_message(text: str) -> str:
    """The message for an angle written without its unit; it shows both fixes.

    >>> bare_angle_message("40")
    'expected an angle with its unit, found the bare number 40; write `40 deg` or `0.698 rad`'
    """
    radians = math.radians(float(text))
    return (f"expected an angle with its unit, found the bare number {text}; write "
            f"`{text} deg` or `{radians:.3g} rad`")


def rate_symbol_names(problem: Problem) -> dict[str, tuple[str, int]]:
    """Plain names of coordinates and their rates: ``theta`` -> (theta, 0), ``thetad`` ->
    (theta, 1), ``thetadd`` -> (theta, 2). These are the names symbolic answers use.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> sorted(rate_symbol_names(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")))
    ['theta', 'thetad', 'thetadd']
    """
    out = {}
    for c in problem.coordinates:
        out[c.name] = (c.name, 0)
        out[c.name + "d"] = (c.name, 1)
        out[c.name + "dd"] = (c.name, 2)
    return out


class _Checker:
    def __init__(self, problem: Problem, broken: frozenset[str] = frozenset()):
        self.p = problem
        self.frames = {f.name: f for f in problem.frames}
        self.points = {p.name: p for p in problem.points}
        self.coords = {c.name: c for c in problem.coordinates}
        self.params = {p.name: p for p in problem.parameters}
        self.broken = broken
        self.errors: list[SpecError] = []

    @contextmanager
    def each(self):
        """Record a SpecError raised inside and go on with the next item."""
        try:
            yield
        except _Quiet:
            pass
        except SpecError as err:
            self.errors.append(err)

    def quiet_if_broken(self, name: str, *sections: str) -> None:
        """Stay silent about ``name`` if its definition (or its whole section) failed."""
        if name in self.broken or any(f"{s}:*" in self.broken for s in sections):
            raise _Quiet(name)

    # ------------------------------------------------------------------ names

    def check_names(self) -> None:
        p = self.p
        for group, items in (("frame", p.frames), ("point", p.points),
                             ("coordinate", p.coordinates), ("parameter", p.parameters)):
            for item in items:
                if item.name in RESERVED:
                    self.errors.append(SpecError(
                        f"'{item.name}' is reserved (time, pi or a function name); expected "
                        f"another {group} name", where=item.where))
        for c in p.coordinates:
            if c.name in self.params:
                self.errors.append(SpecError(
                    f"'{c.name}' is both a coordinate and a parameter; expected distinct names",
                    where=c.where))
        scalars = set(self.coords) | set(self.params)
        for item in list(p.frames) + list(p.points):
            if item.name in scalars:
                self.errors.append(SpecError(
                    f"'{item.name}' names a frame or point and also a coordinate or parameter; "
                    "expected distinct names", where=item.where))
        rates = rate_symbol_names(p)
        for group, items in (("parameter", p.parameters), ("coordinate", p.coordinates)):
            for item in items:
                if item.name in rates and rates[item.name][1] > 0:
                    self.errors.append(SpecError(
                        f"{group} '{item.name}' clashes with the rate name of coordinate "
                        f"'{rates[item.name][0]}'; expected another name", where=item.where))

    # ------------------------------------------------------------------ trees

    def check_frames(self) -> None:
        inertial = self.p.inertial_frame
        for items, name, what in ((self.p.points, self.p.inertial_point, "point"),
                                  (self.p.frames, inertial, "frame")):
            for item in items[1:]:
                if item.name == name:
                    self.errors.append(SpecError(
                        f"'{name}' is the inertial {what}; expected it under 'inertial' only, "
                        f"not also under {what}s", where=item.where))
        parented = True
        for frame in self.p.frames:
            if frame.name == inertial:
                continue
            parent = frame.parent
            assert parent is not None  # the loader requires a parent of every other frame
            with self.each():
                if parent not in self.frames:
                    parented = False
                    self.quiet_if_broken(parent, "frames")
                    raise SpecError(unknown_name("parent frame", parent, self.frames),
                                    where=frame.parent_where)
            with self.each():
                if frame.origin is not None and frame.origin not in self.points:
                    self.quiet_if_broken(frame.origin, "points")
                    raise SpecError(unknown_name("origin point", frame.origin, self.points),
                                    where=frame.origin_where)
            for rotation in frame.rotations:
                with self.each():
                    self.expect_type(rotation.angle, Type(Kind.SCALAR, dimensionless()), "an angle")
        for frame in self.p.frames[1:] if parented else ():
            cycle = _cycle(frame.name, lambda f: self.frames[f].parent, inertial)
            if cycle:
                self.errors.append(SpecError(
                    f"frame '{frame.name}' is oriented through a cycle of parents ({cycle}); "
                    f"expected a tree rooted at '{inertial}'", where=frame.where))

    def check_points(self) -> None:
        chained = True
        for point in self.p.points:
            if point.origin is None:
                continue
            # Only the inertial point (no origin, skipped above) has no position.
            assert point.position is not None
            with self.each():
                if point.origin not in self.points:
                    chained = False
                    self.quiet_if_broken(point.origin, "points")
                    raise SpecError(unknown_name("point", point.origin, self.points,
                                                 " in 'from'"), where=point.origin_where)
            with self.each():
                self.expect_type(point.position, Type(Kind.VECTOR, dimension("m")),
                                 "a position vector (a length times unit vectors, e.g. L*A.x)")
        for point in self.p.points[1:] if chained else ():
            cycle = _cycle(point.name, lambda q: self.points[q].origin, self.p.inertial_point)
            if cycle:
                self.errors.append(SpecError(
                    f"point '{point.name}' is located through a cycle ({cycle}); expected a "
                    f"chain ending at '{self.p.inertial_point}'", where=point.where))

    # ------------------------------------------------------------------ sections

    def check_constraints(self) -> None:
        names = set()
        for c in self.p.constraints:
            if c.name in names:
                self.errors.append(SpecError(f"constraint name '{c.name}' used twice; expected "
                                             "unique names", where=c.where))
            names.add(c.name)
            with self.each():
                left, right = self.type_of(c.lhs), self.type_of(c.rhs)
                self._same(left, right, c.lhs, "both sides of the equation")

    def check_givens(self) -> None:
        self.check_given_list(self.p.givens)
        for guess in self.p.guesses:
            with self.each():
                node = guess.key.node
                if not (isinstance(node, Name) and
                        (node.id in self.coords or node.id in self.params)):
                    if isinstance(node, Name):
                        self.quiet_if_broken(node.id, "coordinates", "parameters")
                    raise SpecError(f"expected a coordinate or parameter to guess, found "
                                    f"'{guess.key.text}'", where=guess.where)
                self._bare_angle(guess)
                self._dims_match(dimension(guess.unit), self.type_of(guess.key).dim,
                                 guess.where, f"the guess for '{guess.key.text}'")

    def check_given_list(self, givens: tuple[Given, ...]) -> None:
        seen: dict[str, Given] = {}
        for given in givens:
            with self.each():
                self.check_given(given, seen)

    def check_given(self, given: Given, seen: dict[str, Given]) -> None:
        node = given.key.node
        t = self.type_of(given.key)
        if t.kind != Kind.SCALAR:
            raise SpecError(f"expected a scalar quantity as a given's name, found a "
                            f"{t.kind} ('{given.key.text}')", where=given.where)
        canonical = to_text(node)
        if canonical in seen:
            raise SpecError(f"'{canonical}' is given twice", where=given.where)
        seen[canonical] = given
        if given.value_expr is not None and math.isnan(given.si):
            return  # an expression of other givens that could not be worked out: said already
        self._bare_angle(given)
        if _bare(given) and t.dim != dimensionless():
            unit = self._natural_unit(node)
            raise SpecError(f"expected a value with its unit ({describe_dimension(t.dim)}), "
                            f"found the bare number {given.text}"
                            + (f"; write `{given.text} {unit}`" if unit else ""),
                            where=given.where)
        self._dims_match(dimension(given.unit), t.dim, given.where,
                         f"the value of '{given.key.text}'")

    def _bare_angle(self, given) -> None:
        """A bare number for an angle is refused: degrees or radians cannot be told apart."""
        node = given.key.node
        declared = (self.coords.get(node.id) or self.params.get(node.id)
                    if isinstance(node, Name) else None)
        if declared is not None and _bare(given) and given.value != 0 \
                and is_angle_unit(declared.unit):
            raise SpecError(bare_angle_message(given.text), where=given.where)

    def _natural_unit(self, node: Node) -> str | None:
        """The unit a bare given for ``node`` most likely meant (for the message)."""
        if isinstance(node, Name):
            declared = self.coords.get(node.id) or self.params.get(node.id)
            return declared.unit if declared else None
        if isinstance(node, Prime) and node.id in self.coords:
            return f"{self.coords[node.id].unit}/s" + ("^2" if node.order == 2 else "")
        return None

    def check_objectives(self) -> None:
        ids = set()
        for obj in self.p.objectives:
            if obj.id in ids:
                self.errors.append(SpecError(f"objective id '{obj.id}' used twice; expected "
                                             "unique ids", where=obj.where))
            ids.add(obj.id)
        for obj in self.p.objectives:
            self.check_objective(obj, ids)

    def check_objective(self, obj: Objective, ids: set[str]) -> None:
        t = None
        with self.each():
            found = self.type_of(obj.find)
            want = Kind.VECTOR if obj.kind == ObjectiveKind.VECTOR else Kind.SCALAR
            if found.kind != want:
                raise SpecError(f"expected a {want} expression for a {obj.kind} objective, "
                                f"found a {found.kind} ('{obj.find.text}')",
                                where=obj.find.where)
            t = found
            self._dims_match(t.dim, dimension(obj.unit), obj.find.where,
                             f"objective '{obj.id}' (unit '{obj.unit}')")
        with self.each():
            if obj.kind == ObjectiveKind.VECTOR and obj.frame is None:
                raise SpecError("a vector objective needs 'frame': the frame whose unit vectors "
                                "its components are in", where=obj.where)
            if obj.frame is not None and obj.frame not in self.frames:
                self.quiet_if_broken(obj.frame, "frames")
                raise SpecError(unknown_name("frame", obj.frame, self.frames),
                                where=obj.frame_where)
        with self.each():
            if obj.kind == ObjectiveKind.SYMBOLIC and not obj.symbols:
                raise SpecError("a symbolic objective needs 'symbols': the names its answer is "
                                "written in", where=obj.where)
            if obj.kind != ObjectiveKind.SYMBOLIC and obj.symbols:
                raise SpecError("'symbols' belongs to symbolic objectives only", where=obj.where)
        for decl in obj.symbols:
            with self.each():
                self.symbol_meaning(decl)
        for mistake in obj.mistakes if t is not None else ():
            with self.each():
                mt = self.type_of(mistake.find)
                self._same(t, mt, mistake.find, f"the mistaken model of '{obj.id}'")
        for j, dep in enumerate(obj.depends_on):
            with self.each():
                if dep not in ids or dep == obj.id:
                    self.quiet_if_broken(dep)
                    where = obj.depends_where[j] if j < len(obj.depends_where) else obj.where
                    others = sorted(ids - {obj.id})
                    raise SpecError(f"depends_on names unknown objective '{dep}'"
                                    f"{did_you_mean(dep, others)} (expected one of: "
                                    f"{', '.join(others) or 'none'})", where=where)
        self.check_given_list(obj.givens)
        if obj.expect is not None:
            with self.each():
                self.check_expect(obj, obj.expect)

    def symbol_meaning(self, decl) -> Node:
        """The spec quantity (a Name or Prime node) a declared symbol stands for."""
        node = decl.means.node
        if isinstance(node, Name) and node.id == decl.name:
            rates = rate_symbol_names(self.p)
            if decl.name in self.params or decl.name in self.coords:
                return node
            if decl.name in rates:
                base, order = rates[decl.name]
                return Prime(base, order)
            raise SpecError(f"symbol '{decl.name}' is not a parameter, coordinate or rate "
                            f"name (such as thetad); write it as {{{decl.name}: \"q'\"}} to say "
                            "what it stands for", where=decl.means.where)
        if isinstance(node, Name) and (node.id in self.params or node.id in self.coords):
            return node
        if isinstance(node, Prime) and node.id in self.coords and node.order <= 2:
            return node
        raise SpecError(f"expected symbol '{decl.name}' to stand for a parameter, coordinate "
                        f"or rate, found '{decl.means.text}'", where=decl.means.where)

    def check_expect(self, obj: Objective, e: Expect) -> None:
        shape = {ObjectiveKind.SCALAR: "value", ObjectiveKind.VECTOR: "components",
                 ObjectiveKind.SYMBOLIC: "expr"}[obj.kind]
        given = "value" if e.value is not None else "components" if e.components else "expr"
        if given != shape:
            raise SpecError(f"expected 'expect.{shape}' for a {obj.kind} objective, found "
                            f"'expect.{given}'", where=e.where)
        if e.unit is not None:
            self._dims_match(dimension(obj.unit), dimension(e.unit), e.where,
                             f"expect.unit of '{obj.id}'")
        if e.expr is not None:
            try:
                node = parse(e.expr)
            except ExpressionError as err:
                raise SpecError(f"expect.expr: {err.message}", where=e.where) from None
            allowed = {d.name for d in obj.symbols} | {"pi"}
            unknown = sorted({n.id for n in _walk_names(node)} - allowed)
            if unknown:
                raise SpecError(f"expect.expr uses '{unknown[0]}', which is not among the "
                                f"objective's symbols ({', '.join(sorted(allowed - {'pi'}))})",
                                where=e.where)

    # ------------------------------------------------------------------ typing

    def expect_type(self, expr: Expr, want: Type, what: str) -> None:
        t = self.type_of(expr)
        if t.kind != want.kind and t.kind != Kind.ZERO:
            raise SpecError(f"expected {what}, found a {t.kind} ('{expr.text}')",
                            where=expr.where)
        if t.kind != Kind.ZERO:
            self._dims_match(t.dim, want.dim, expr.where, f"'{expr.text}'")

    def type_of(self, expr: Expr) -> Type:
        self._no_quantity(expr)
        try:
            return self._type(expr.node)
        except SpecError as err:
            raise type(err)(err.message, where=expr.where) from None
        except DimensionError as err:
            raise SpecError(err.message, where=expr.where) from None

    def _type(self, node: Node, inside_pos: bool = False) -> Type:
        return infer(node, self._leaf, lambda call: self._call(call, inside_pos))

    def _leaf(self, node: Node) -> Type:
        if isinstance(node, Name):
            if node.id == TIME:
                return Type(Kind.SCALAR, time_dimension())
            if node.id in self.coords:
                return Type(Kind.SCALAR, dimension(self.coords[node.id].unit))
            if node.id in self.params:
                return Type(Kind.SCALAR, dimension(self.params[node.id].unit))
            if node.id in self.points or node.id in self.frames:
                what = "point" if node.id in self.points else "frame"
                raise SpecError(f"'{node.id}' is a {what}; expected a scalar or vector here "
                                f"(use it inside a function such as vel(P, N))")
            self.quiet_if_broken(node.id, "coordinates", "parameters")
            known = sorted(set(self.coords) | set(self.params))
            raise SpecError(f"unknown name '{node.id}'{self._name_hint(node.id, known)} "
                            f"(expected a coordinate, parameter, t or pi; known: "
                            f"{', '.join(known)})")
        if isinstance(node, Prime):
            if node.id not in self.coords:
                self.quiet_if_broken(node.id, "coordinates")
                raise SpecError(f"expected a coordinate before the prime, found '{node.id}'"
                                f"{did_you_mean(node.id, self.coords)} "
                                f"(coordinates: {', '.join(self.coords) or 'none'})")
            if node.order > 2:
                raise SpecError("expected at most a second time derivative (q'')")
            return Type(Kind.SCALAR, dimension(self.coords[node.id].unit)
                        * time_dimension() ** -node.order)
        if isinstance(node, Attr):
            if node.base not in self.frames:
                self.quiet_if_broken(node.base, "frames")
                raise SpecError(f"unknown frame '{node.base}' in '{node.base}.{node.attr}'"
                                f"{did_you_mean(node.base, self.frames)} "
                                f"(frames: {', '.join(self.frames)})")
            return Type(Kind.VECTOR, dimensionless())
        raise SpecError(f"unexpected expression {node!r}")  # pragma: no cover

    def _call(self, node: Call, inside_pos: bool) -> Type:
        """The type of a call of an objective function (math functions are typed by
        :func:`~mechgrade.expressions.dimensions.infer`)."""
        sig = FUNCTIONS[node.func]
        if len(node.args) != len(sig.args):
            raise SpecError(f"expected {len(sig.args)} arguments for {node.func}(...) "
                            f"({sig.doc}), found {len(node.args)}")
        if node.func == "ic" and not inside_pos:
            raise SpecError("ic(A, F) is a point: use it as pos(ic(A, F), P)")
        dims = []
        for arg, kind in zip(node.args, sig.args):
            dims.append(self._argument(node.func, arg, kind))
        self._needs_origin(node)
        result = sig.result
        if result == Kind.QUANTITY:  # the kind of its argument
            result = self._type(node.args[0], inside_pos=False).kind
        return Type(result, sig.dim(tuple(dims)))

    def _argument(self, func: str, arg: Node, kind: Kind):
        if kind == Kind.FRAME:
            if not (isinstance(arg, Name) and arg.id in self.frames):
                hint = ""
                if isinstance(arg, Name):
                    self.quiet_if_broken(arg.id, "frames")
                    hint = did_you_mean(arg.id, self.frames)
                raise SpecError(f"expected a frame as argument of {func}(...), found "
                                f"'{to_text(arg)}'{hint} (frames: {', '.join(self.frames)})")
            return dimensionless()
        if kind == Kind.POINT:
            if isinstance(arg, Name):
                if arg.id not in self.points:
                    self.quiet_if_broken(arg.id, "points")
                    raise SpecError(f"expected a point as argument of {func}(...), found "
                                    f"'{arg.id}'{did_you_mean(arg.id, self.points)} "
                                    f"(points: {', '.join(self.points)})")
                return dimension("m")
            if isinstance(arg, Call) and arg.func in FUNCTIONS and \
                    FUNCTIONS[arg.func].result == Kind.POINT:
                return self._type(arg, inside_pos=(func == "pos")).dim
            raise SpecError(f"expected a point as argument of {func}(...), found "
                            f"'{to_text(arg)}'")
        if kind in DYNAMICS_KINDS:
            if self.p.dynamics is None and isinstance(arg, Name):
                self.quiet_if_broken(arg.id, "dynamics")  # its section's error is reported
            return argument_dimension(self.p, func, arg, kind)
        t = self._type(arg, inside_pos=False)
        if t.kind == Kind.ZERO and kind == Kind.VECTOR:
            return t.dim
        if kind == Kind.QUANTITY and t.kind in (Kind.SCALAR, Kind.VECTOR, Kind.ZERO):
            return t.dim
        if t.kind != kind:
            raise SpecError(f"expected a {kind} as argument of {func}(...), found a {t.kind} "
                            f"('{to_text(arg)}')")
        return t.dim

    def _needs_origin(self, node: Call) -> None:
        index = FUNCTIONS[node.func].origin_of
        if index is None:
            return
        arg = node.args[index]
        # The argument's kind was checked first: a frame argument is a Name.
        frame = self.frames.get(arg.id) if isinstance(arg, Name) else None
        if frame is None:
            return
        if frame.name != self.p.inertial_frame and frame.origin is None:
            raise SpecError(f"{node.func}(...) needs a point fixed in frame '{frame.name}': "
                            f"give the frame an 'origin'")

    # ------------------------------------------------------------------ helpers

    def _no_quantity(self, expr: Expr) -> None:
        """Refuse a number written with a unit (``until: t = 4 s``): expressions hold names,
        and a value with its unit belongs under ``givens:``."""
        names = {n.id for n in _walk_names(expr.node)}
        for match in _NUMBER_THEN_NAME.finditer(expr.text):
            name = match.group(2)
            if name not in names or name in self.coords or name in self.params or \
                    name == TIME:
                continue  # an angle's '30 deg' is read as its value already
            try:
                normalize_unit(name)
            except UnitError:
                continue
            raise SpecError(f"expected names in an expression, found '{match.group(0)}', a "
                            f"value with its unit: declare a parameter (say T: {name}), give "
                            f"its value under givens (T: {match.group(0)}) and write T here",
                            where=expr.where)

    def _name_hint(self, name: str, known) -> str:
        """"did you mean" for an unknown name; a rate written ``thetad`` gets ``theta'``."""
        for suffix, primes in (("dd", "''"), ("d", "'")):
            if name.endswith(suffix) and name[:-len(suffix)] in self.coords:
                return f"; did you mean \"{name[:-len(suffix)]}{primes}\"?"
        return did_you_mean(name, known)

    def _same(self, a: Type, b: Type, expr: Expr, what: str) -> None:
        kinds = {a.kind, b.kind} - {Kind.ZERO}
        if len(kinds) > 1:
            raise SpecError(f"expected {what} to be of the same kind, found a {a.kind} and a "
                            f"{b.kind}", where=expr.where)
        if Kind.ZERO not in (a.kind, b.kind):
            self._dims_match(a.dim, b.dim, expr.where, what)

    @staticmethod
    def _dims_match(found, expected, where, what: str) -> None:
        if found != expected:
            raise SpecError(f"dimension mismatch in {what}: expected "
                            f"{describe_dimension(expected)}, found {describe_dimension(found)}",
                            where=where)


def _cycle(start: str, step, root: str) -> str | None:
    """``"A -> B -> A"`` if following ``step`` from ``start`` loops before reaching ``root``."""
    chain = [start]
    current = step(start)
    while current != root:
        if current in chain:
            return " -> ".join(chain + [current])
        chain.append(current)
        current = step(current)
    return None


def _bare(given) -> bool:
    """Whether a given was written as a number without a unit."""
    if given.unit:
        return False
    try:
        float(given.text)
    except ValueError:
        return False
    return True


def _walk_names(node: Node):
    from ..expressions.syntax import walk
    return [n for n in walk(node) if isinstance(n, Name)]


def problem_errors(problem: Problem, broken: frozenset[str] = frozenset()) -> list[SpecError]:
    """Every semantic error in ``problem``; names in ``broken`` failed to load and are not
    reported again (``"frames:*"`` stands for a whole section)."""
    checker = _Checker(problem, broken)
    checker.check_names()
    checker.check_frames()
    checker.check_points()
    checker.check_constraints()
    checker.check_givens()
    checker.check_objectives()
    try:
        check_dynamics(problem, checker)
    except SpecError as err:  # the dynamics checks stop at their first error
        checker.errors.append(err)
    return checker.errors + magnitude_errors(problem)


def magnitude_errors(problem: Problem) -> list[SpecError]:
    """One error for each item of ``problem`` holding a number no file may hold
    (:func:`mechgrade.schema_errors.number_problem`): a value written with a unit and taken
    to SI units (``L: 1.0e300 ft``), a given worked out from others, a number in an
    expression. The numbers written as YAML numbers were refused with the schema already.

    Every number of the model is walked, so a field added later is checked too; an item is
    located at its own ``where`` (else its owner's), and reported once.

    >>> from mechgrade.spec import load_problem_text
    >>> from mechgrade.resources import shipped_dir
    >>> text = (shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml").read_text()
    >>> load_problem_text(text.replace("L: 2 ft", "L: 1.0e300 ft"), "p.yaml")
    Traceback (most recent call last):
    ...
    mechgrade.errors.SpecError: p.yaml:21:6: givens.L: expected a number of magnitude at most 1e+40 in SI units, found '1.0e300 ft'
    """
    errors: list[SpecError] = []
    reported: set[int] = set()
    todo: list[tuple[object, object, Location]] = [(problem, problem, Location(problem.path))]
    while todo:
        value, owner, where = todo.pop()
        if isinstance(value, (str, bool, Enum, Location)) or value is None:
            continue
        if isinstance(value, Num):
            value = value.value
        if isinstance(value, (int, float)):
            message = _number_message(value, owner)
            if message is not None and id(owner) not in reported:
                reported.add(id(owner))
                errors.append(SpecError(message, where=where))
        elif isinstance(value, (tuple, list)):
            todo.extend((item, owner, where) for item in reversed(value))
        elif isinstance(value, dict):
            todo.extend((item, owner, where) for item in value.values())
        elif dataclasses.is_dataclass(value) and not _unresolved(value):
            own = getattr(value, "where", None)
            where = own if isinstance(own, Location) and own.file else where
            todo.extend((getattr(value, f.name), value, where)
                        for f in reversed(dataclasses.fields(value)))
    return errors


def _number_message(value: float, owner: object) -> str | None:
    """:func:`number_problem`'s message for a number of ``owner``: a given is shown as
    written, its value judged in SI units."""
    if isinstance(owner, Given):
        return number_problem(value, repr(owner.text), "SI units")
    return number_problem(value)


def _unresolved(item: object) -> bool:
    """A given written as an expression that could not be worked out (its error says why)."""
    return isinstance(item, Given) and item.value_expr is not None and math.isnan(item.si)


def symbol_meanings(problem: Problem, objective: Objective) -> dict[str, Node]:
    """Each declared symbol of a symbolic objective -> the Name/Prime node it stands for."""
    checker = _Checker(problem)
    return {d.name: checker.symbol_meaning(d) for d in objective.symbols}
