"""The spec sections that tell the solver what to solve for and which root to take:
``unknown:`` (parameters or ``t`` solved from the givens), ``branch:`` (the root wanted),
``define:`` (named intermediate quantities), and givens whose value is an expression of
other givens (``x: L/2``).

>>> from mechgrade.expressions.syntax import parse, to_text
>>> defs = {"r_AB": parse("pos(B, A)", functions={"pos"})}
>>> to_text(expand(parse("mag(r_AB)/2", functions={"mag"}), defs))
'mag(pos(B, A))/2'
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, Mapping

from ..errors import SpecError, UnitError
from ..expressions.functions import CONSTANT_FUNCTIONS
from ..expressions.syntax import Name, Node, Num, Prime, fold, to_text, walk
from ..units import from_si, registry, si_unit
from .model import TIME, Branch, Coordinate, Definition, Expr, Given, Parameter, Root

_FUNCTIONS = CONSTANT_FUNCTIONS  # the one-argument functions a given's value may use


def expand(node: Node, definitions: Mapping[str, Node]) -> Node:
    """``node`` with every name of ``definitions`` replaced by the tree it stands for."""
    if not definitions:
        return node
    if isinstance(node, Name):
        return definitions.get(node.id, node)
    fields = getattr(node, "__dataclass_fields__", {})
    changes: dict[str, Any] = {}
    for name in fields:
        value = getattr(node, name)
        if isinstance(value, tuple) and value and all(hasattr(v, "__dataclass_fields__")
                                                      for v in value):
            changes[name] = tuple(expand(v, definitions) for v in value)
        elif hasattr(value, "__dataclass_fields__"):
            changes[name] = expand(value, definitions)
    return replace(node, **changes) if changes else node


def read_definitions(data: dict, expr, where) -> tuple[Definition, ...]:
    """``define:`` in order; ``expr(text, *path)`` reads an expression (earlier definitions
    already expanded), ``where(*path)`` locates a field."""
    out = []
    for name, text in (data.get("define") or {}).items():
        out.append(Definition(name, expr(text, "define", name), where("define", name)))
    return tuple(out)


def read_unknowns(data: dict, expr) -> tuple[Expr, ...]:
    return tuple(expr(name, "unknown", i) for i, name in enumerate(data.get("unknown") or []))


def read_branches(data: dict, expr, where) -> tuple[Branch, ...]:
    return tuple(Branch(expr(key, "branch", key), Root(rule), where("branch", key))
                 for key, rule in (data.get("branch") or {}).items())


def check_solving(coordinates, parameters, givens, unknowns, branches, definitions,
                  reserved) -> None:
    """Names in ``unknown:``, ``branch:`` and ``define:`` make sense together."""
    params = {p.name for p in parameters}
    coords = {c.name for c in coordinates}
    given = {to_text(g.key.node) for g in givens}
    for u in unknowns:
        name = u.text.strip()
        if name != TIME and name not in params:
            raise SpecError(f"expected a parameter or t to solve for, found '{name}' "
                            "(coordinates that are not given are always solved for)",
                            where=u.where)
        if name in given:
            raise SpecError(f"'{name}' is both given and unknown; expected one of them",
                            where=u.where)
    solvable = coords | {u.text.strip() for u in unknowns}
    for b in branches:
        node = b.key.node
        ok = (isinstance(node, Name) and node.id in solvable) or \
            (isinstance(node, Prime) and node.id in coords)
        if not ok:
            raise SpecError(f"expected a coordinate, a rate (theta') or a quantity listed under "
                            f"unknown: as a branch, found '{b.key.text}'", where=b.where)
    for d in definitions:
        if d.name in coords | params or d.name in reserved:
            raise SpecError(f"'{d.name}' is already a name of the problem or of the language; "
                            "expected another name for the definition", where=d.where)


def given_expression(text: str, givens: Mapping, expr, section: tuple, key: str) -> Expr | None:
    """The value of a given in ``givens:`` written as an expression of other givens
    (``x: L/2``), or ``None`` when ``text`` is not one (then it is a malformed quantity)."""
    if section != ("givens",):
        return None
    try:
        value = expr(text, *section, key)
    except SpecError:
        return None
    keys = {str(k).replace(" ", "") for k in givens}
    names = {to_text(n) for n in walk(value.node) if isinstance(n, (Name, Prime))}
    return value if names and names - {"pi"} <= keys else None


def given_unit(key: Node, coordinates: tuple[Coordinate, ...],
               parameters: tuple[Parameter, ...]) -> str | None:
    """The unit of a coordinate, rate, parameter or time key (``None`` for other keys)."""
    units = {c.name: c.unit for c in coordinates}
    units.update({p.name: p.unit for p in parameters})
    if isinstance(key, Name):
        return "s" if key.id == TIME else units.get(key.id)
    if isinstance(key, Prime) and key.id in units:
        base = units[key.id] or "1"
        base = f"({base})" if any(c in base for c in "/* ") else base
        return f"{base}/s" if key.order == 1 else f"{base}/s^{key.order}"
    return None


def resolve_given_values(givens: tuple[Given, ...], coordinates, parameters) -> tuple[Given, ...]:
    """Givens whose value is an expression (``value`` NaN, ``text`` the expression) evaluated
    from the other givens, in the key's unit; a cycle or an unknown name is an error."""
    pending = {to_text(g.key.node): g for g in givens if math.isnan(g.si)}
    if not pending:
        return givens
    ureg = registry()
    done = {to_text(g.key.node): ureg.Quantity(g.si, si_unit(g.unit) or "dimensionless")
            for g in givens if not math.isnan(g.si)}
    resolved = {}
    while pending:
        progress = False
        for key, g in list(pending.items()):
            assert g.value_expr is not None  # a NaN value stands for an expression
            node = g.value_expr.node
            needed = {to_text(n) for n in walk(node) if isinstance(n, (Name, Prime))
                      and not (isinstance(n, Name) and n.id == "pi")}
            if needed - set(done):  # another expression given first
                continue
            unit = given_unit(g.key.node, coordinates, parameters)
            if unit is None:
                raise SpecError("expected a number with a unit for a given that is an "
                                "expression; only coordinates, rates, parameters and t may "
                                "be given as expressions of other givens", where=g.where)
            quantity = _evaluate(node, done, g)
            target = ureg.Quantity(1.0, si_unit(unit) or "dimensionless")
            if quantity.dimensionality != target.dimensionality:
                raise SpecError(f"expected '{g.text}' to have the dimension of {unit or '1'} "
                                f"(the unit of '{key}'), found {quantity.units:~}",
                                where=g.where)
            si = float(quantity.to_base_units().magnitude)
            resolved[key] = replace(g, value=from_si(si, unit), unit=unit, si=si)
            done[key] = quantity
            del pending[key]
            progress = True
        if not progress:
            first = next(iter(pending.values()))
            raise SpecError(f"the givens {', '.join(pending)} are defined in terms of each "
                            "other; expected a value for at least one", where=first.where)
    return tuple(resolved.get(to_text(g.key.node), g) for g in givens)


def carried(givens: Mapping[str, Given], changed: Mapping[str, float]) -> dict[str, float]:
    """The SI values of the givens written as expressions of other givens (``x': v2*cos(beta)``)
    once the givens in ``changed`` (key text -> SI value) take those values: a misread given
    carried into every given stated from it. Givens that depend on none of ``changed`` keep
    their value and are left out.

    >>> from mechgrade.spec.model import Expr
    >>> from mechgrade.expressions.syntax import parse
    >>> v = Given(Expr("v", parse("v")), 2.0, "m/s", 2.0, "2 m/s")
    >>> t = Given(Expr("t", parse("t")), 3.0, "s", 3.0, "3 s")
    >>> x = Given(Expr("x", parse("x")), 6.0, "m", 6.0, "v*t", value_expr=Expr("v*t", parse("v*t")))
    >>> carried({"v": v, "t": t, "x": x}, {"v": 5.0})
    {'x': 15.0}

    A given that the change leaves undefined (the root of a negative) is an error:

    >>> r = Given(Expr("r", parse("r")), 2.0, "m", 2.0, "sqrt(v*t)",
    ...           value_expr=Expr("sqrt(v*t)", parse("sqrt(v*t)")))
    >>> carried({"v": v, "t": t, "r": r}, {"v": -5.0})
    Traceback (most recent call last):
    ...
    mechgrade.errors.SpecError: cannot evaluate 'sqrt(v*t)' with v changed: found ...
    """
    if all(g.value_expr is None for g in givens.values()):
        return {}  # nothing stated from another given (and no quantity to build for each)
    ureg = registry()
    done = {key: ureg.Quantity(changed.get(key, g.si), si_unit(g.unit) or "dimensionless")
            for key, g in givens.items()}
    out: dict[str, float] = {}
    moved = set(changed)
    for _ in range(len(givens)):  # a chain of expression givens, one link per pass
        progress = False
        for key, g in givens.items():
            if g.value_expr is None or key in changed or key in out:
                continue
            needed = {to_text(n) for n in walk(g.value_expr.node) if isinstance(n, (Name, Prime))}
            if not needed & moved or not needed <= set(done) | {"pi"}:
                continue
            magnitude = _evaluate(g.value_expr.node, done, g).to_base_units().magnitude
            if isinstance(magnitude, complex) or not math.isfinite(magnitude):
                raise SpecError(f"cannot evaluate '{g.text}' with "
                                f"{', '.join(sorted(changed))} changed: found {magnitude}",
                                where=g.where)
            out[key] = float(magnitude)
            done[key] = ureg.Quantity(out[key], si_unit(g.unit) or "dimensionless")
            moved.add(key)
            progress = True
        if not progress:
            break
    return out


def _evaluate(node: Node, values: Mapping, g: Given):
    ureg = registry()

    def number(n: Num):
        return ureg.Quantity(n.value, "dimensionless")

    def resolve(n):
        if isinstance(n, Name) and n.id == "pi":
            return ureg.Quantity(math.pi, "dimensionless")
        return values[to_text(n)]

    def call(func: str, args: tuple):
        if func not in _FUNCTIONS or len(args) != 1:
            raise SpecError(f"expected arithmetic of givens and {', '.join(sorted(_FUNCTIONS))} "
                            f"in a given's value, found {func}()", where=g.where)
        inner = fold(args[0], number=number, resolve=resolve, call=call)
        if func in ("sqrt", "abs"):
            return inner ** 0.5 if func == "sqrt" else abs(inner)
        magnitude = inner.to("dimensionless").magnitude
        return ureg.Quantity(_FUNCTIONS[func](magnitude), "dimensionless")

    try:
        return fold(node, number=number, resolve=resolve, call=call)
    except (UnitError, ValueError, ZeroDivisionError, TypeError) as err:
        # pint's DimensionalityError (adding a length to a time) is a TypeError
        raise SpecError(f"cannot evaluate '{g.text}': {err}", where=g.where) from None


__all__ = ["carried", "check_solving", "expand", "given_unit", "read_branches",
           "read_definitions", "read_unknowns", "resolve_given_values"]
