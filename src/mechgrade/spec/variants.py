"""The ``variants:`` section of a problem: how each student's givens are drawn.

Every drawn key is a given of the problem (its value in ``givens:`` is the reference variant
and sets the unit); it is drawn from a range with a ``step`` or a number of ``sig_figs``, from
a list of ``choices`` or from ``integers``. ``require:`` lists conditions on the drawn givens
(``L2 > L1``, values in SI units), read by mechgrade's expression reader. ``bounds:`` declares
the range of a given, a solved quantity or an objective's answer that every variant must keep.
The statement may show a given's value with ``{L}``.

>>> from mechgrade.spec import load_problem_text
>>> problem = load_problem_text('''
... id: p
... title: Pendulum
... statement: A pendulum of length {L} turns at {theta'}.
... inertial: {frame: N, point: O}
... frames: {A: {parent: N, rotation: {axis: z, angle: theta}, origin: O}}
... points: {P: {from: O, position: L*A.x}}
... coordinates: {theta: rad}
... parameters: {L: m}
... givens: {theta: 30 deg, L: 2 m, "theta'": 3 rad/s, "theta''": 0 rad/s^2}
... variants:
...   draw:
...     L: {from: 1 m, to: 3 m, step: 0.1 m}
...     "theta'": {choices: [2 rad/s, 3 rad/s]}
...   require: [L > 1.05]
... objectives:
...   - {id: speed, prompt: Speed, find: "speed(P, N)", kind: scalar, unit: m/s}
... ''')
>>> [(d.key, type(d).__name__) for d in problem.variants.draws]
[('L', 'SteppedRange'), ("theta'", 'Choices')]
>>> problem.variants.requires[0].text
'L > 1.05'
"""

from __future__ import annotations

import re

from typing import Mapping

from ..errors import ExpressionError, Location, SpecError, UnitError
from ..expressions.syntax import parse, to_text
from ..units import from_si, parse_quantity, same_dimension, to_si
from .model import Given
from .validate import did_you_mean
from .variant_model import (COMPARISON, PLACEHOLDER, Choices, Draw, Integers, Limits,
                            Requirement, RoundedRange, SteppedRange, Variants)

__all__ = ["PLACEHOLDER", "Choices", "Draw", "Integers", "Limits", "Requirement", "RoundedRange",
           "SteppedRange", "Variants", "read_requirement", "read_variants"]


def read_requirement(text: str, where: Location) -> Requirement:
    """A condition ``left op right`` (``op`` one of ``< <= > >= !=``); raises SpecError.

    >>> read_requirement("L2 >= L1 + 0.1", Location()).op
    '>='
    >>> read_requirement("L2 = L1", Location("p.yaml", 3, 5, "variants.require[0]"))
    Traceback (most recent call last):
    ...
    mechgrade.errors.SpecError: p.yaml:3:5: variants.require[0]: expected a condition 'left < right' (one of <, <=, >, >=, !=), found 'L2 = L1'
    """
    parts = COMPARISON.split(text)
    ops = COMPARISON.findall(text)
    if len(ops) != 1:
        raise SpecError(f"expected a condition 'left < right' (one of <, <=, >, >=, !=), "
                        f"found {text!r}", where=where)
    try:
        left, right = (parse(side, attributes=False) for side in parts)
    except ExpressionError as err:
        raise SpecError(f"expected a condition 'left < right': {err.message}",
                        where=where) from None
    return Requirement(text.strip(), left, ops[0], right, where)


def read_variants(data: dict, givens: tuple[Given, ...], names: Mapping[str, str], where,
                  statement: str = "", usable=lambda *_: True
                  ) -> tuple[Variants | None, list[SpecError]]:
    """The ``variants:`` section of a problem's data (already schema-checked), and every
    error found in it. ``where(*path)`` locates a value; ``names`` maps what a bound may
    name (objective ids, coordinates and their rates, parameters, ``t``) to its unit; entries where
    ``usable(*path)`` is false had schema errors and are left out.
    """
    section = data.get("variants")
    if not section:
        return None, []
    errors: list[SpecError] = []
    by_key = {to_text(g.key.node): g for g in givens}
    draws = []
    for key, spec in (section.get("draw") or {}).items():
        if not usable("variants", "draw", key):
            continue
        try:
            draws.append(_draw(str(key), spec, by_key, where))
        except SpecError as err:
            errors.append(err)
    requires = []
    drawn = {d.key for d in draws}
    for i, text in enumerate(section.get("require") or []):
        if not usable("variants", "require", i):
            continue
        here = where("variants", "require", i)
        try:
            requirement = read_requirement(str(text), here)
        except SpecError as err:
            errors.append(err)
            continue
        unknown = sorted(requirement.names - set(by_key))
        for name in unknown:
            errors.append(SpecError(f"expected a given in the condition ({', '.join(by_key)}), "
                                    f"found '{name}'{did_you_mean(name, by_key)}", where=here))
        if not unknown and not requirement.names & drawn:
            errors.append(SpecError(f"expected a condition on a drawn given "
                                    f"({', '.join(sorted(drawn))}), found {text!r}",
                                    where=here))
        requires.append(requirement)
    bounds = []
    for name, spec in (section.get("bounds") or {}).items():
        if not usable("variants", "bounds", name):
            continue
        if str(name) not in names:
            errors.append(SpecError(
                f"expected an objective, coordinate, rate or parameter to bound, found "
                f"'{name}'{did_you_mean(str(name), names)}",
                where=where("variants", "bounds", name)))
            continue
        try:
            bounds.append(_bound(str(name), spec, names[str(name)], where))
        except SpecError as err:
            errors.append(err)
    shown = set()
    for found in PLACEHOLDER.findall(statement):
        key = found.strip().replace(" ", "")
        shown.add(key)
        if key not in by_key:
            errors.append(SpecError(f"expected a given between braces in the statement "
                                    f"({', '.join(by_key)}), found '{{{found}}}'"
                                    f"{did_you_mean(key, by_key)}", where=where("statement")))
    prose = PLACEHOLDER.sub(" ", statement)
    for draw in draws:
        text = by_key[draw.key].text
        if draw.key not in shown and text and re.search(
                rf"(?<![\w.]){re.escape(text)}(?![\w])", prose):
            # the sheet would tell every student the reference value beside their own
            errors.append(SpecError(
                f"expected {{{draw.key}}} where the statement gives the drawn value of "
                f"{draw.key} (each student's own), found its reference value '{text}'",
                where=where("statement")))
    return Variants(tuple(draws), tuple(requires), tuple(bounds), where("variants")), errors


def _draw(key: str, spec: dict, givens: Mapping[str, Given], where) -> Draw:
    here = where("variants", "draw", key)
    canonical = key.replace(" ", "")
    given = givens.get(canonical)
    if given is None:
        raise SpecError(f"expected a given of the problem to draw ({', '.join(givens)}), found "
                        f"'{key}'{did_you_mean(canonical, givens)}", where=here)
    unit = given.unit

    def value(raw, *path) -> float:
        return _in_unit(raw, unit, where("variants", "draw", key, *path))

    kinds = [k for k in ("from", "choices", "integers") if k in spec]
    if len(kinds) > 1:
        raise SpecError(f"expected only one of from, choices, integers, found "
                        f"{', '.join(kinds)}", where=here)
    if not kinds:
        raise SpecError("expected one of the keys from (with to), choices, integers",
                        where=here)
    if "choices" in spec:
        return Choices(canonical, unit, tuple(value(v, "choices", i)
                                              for i, v in enumerate(spec["choices"])), here)
    if "integers" in spec:
        low, high = spec["integers"]
        if low > high:
            raise SpecError(f"expected integers [low, high] with low <= high, found "
                            f"[{low}, {high}]", where=where("variants", "draw", key, "integers"))
        return Integers(canonical, unit, int(low), int(high), here)
    low, high = value(spec["from"], "from"), value(spec.get("to"), "to")
    if not low < high:
        raise SpecError(f"expected 'from' below 'to', found {low:g} and {high:g} {unit}".rstrip(),
                        where=here)
    if ("step" in spec) == ("sig_figs" in spec):
        raise SpecError("expected exactly one of 'step' and 'sig_figs' with a range",
                        where=here)
    if "sig_figs" in spec:
        return RoundedRange(canonical, unit, low, high, int(spec["sig_figs"]), here)
    step = value(spec["step"], "step")
    if not step > 0:
        raise SpecError(f"expected a positive step, found {spec['step']!r}",
                        where=where("variants", "draw", key, "step"))
    return SteppedRange(canonical, unit, low, high, step, here)


def _in_unit(raw, unit: str, where: Location, whose: str = "the given's unit") -> float:
    """A value written with a unit (or bare, read in ``unit``) converted to ``unit``."""
    if raw is None:
        raise SpecError("expected 'to' with 'from' (a range needs both ends)", where=where)
    if isinstance(raw, bool):
        raise SpecError(f"expected a number with a unit, found {str(raw).lower()}",
                        where=where)
    try:
        q = parse_quantity(str(raw))
    except UnitError as err:
        raise SpecError(err.message, where=where) from None
    if not q.unit or q.unit == unit:
        return q.value
    if not same_dimension(q.unit, unit or "1"):
        raise SpecError(f"expected a value in units like {unit or 'a pure number'} ({whose}), "
                        f"found {raw!r}", where=where)
    return from_si(to_si(q.value, q.unit), unit) if unit else to_si(q.value, q.unit)


def _bound(name: str, spec: dict, unit: str, where) -> Limits:
    """A bound in the unit of the quantity it bounds (``unit``; a bare number is in it)."""
    here = where("variants", "bounds", name)
    values = {}
    for end in ("min", "max"):
        if end not in spec:
            continue
        values[end] = _in_unit(spec[end], unit, where("variants", "bounds", name, end),
                               f"the unit of {_quoted(name)}")
    low, high = values.get("min"), values.get("max")
    if low is not None and high is not None and low > high:
        raise SpecError(f"expected min <= max, found {low:g} > {high:g}", where=here)
    return Limits(name, unit, low, high, here)


def _quoted(name: str) -> str:
    """``'x'``, or ``"x'"`` for a rate (its prime would end single quotes)."""
    return f'"{name}"' if "'" in name else f"'{name}'"
