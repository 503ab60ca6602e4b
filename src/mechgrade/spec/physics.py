"""Whether a problem's numbers make physical sense, judged when the file is loaded.

Refused: a tolerance tighter than the reference's own numerical accuracy (no answer could
match the last digits of a floating-point reference). Warned, naming both numbers and the
standard value in the author's units: standard gravity written in the wrong unit
(``g: 9.81 ft/s^2``), a mass a thousand times off another body's and written in another unit
(a 2 g block on an 8 kg cart), a body denser or lighter than any material for its size (a
2 kg rod 1.2 mm long).

>>> from mechgrade.spec import load_problem_text
>>> from mechgrade.resources import shipped_dir
>>> text = (shipped_dir("problems") / "pendulum_pin_reaction.yaml").read_text()
>>> problem = load_problem_text(text.replace("g: 9.81 m/s^2", "g: 9.81 ft/s^2"), "p.yaml")
>>> print(problem.warnings[-1].message)  # doctest: +NORMALIZE_WHITESPACE
g = 9.81 ft/s^2 is 2.99 m/s^2, not standard gravity: 9.81 is g in m/s^2; in ft/s^2 it is
32.17 (expected g: 32.17 ft/s^2, or g: 9.81 m/s^2)
"""

from __future__ import annotations

import math
import re

from ..errors import AuthorWarning, SpecError
from ..expressions.syntax import Name, constant_value, walk
from ..tolerance import REFERENCE_ACCURACY
from ..units import from_si
from .dynamics import Block
from .model import Expr, Given, Problem

STANDARD_GRAVITY = 9.80665
"""m/s^2."""

_GRAVITY_UNITS = ("m/s^2", "ft/s^2", "in/s^2", "cm/s^2", "mm/s^2")
_DENSITIES = (1.0, 25000.0)
"""kg/m^3: lighter than air below, denser than osmium (22 600) above."""
_MASS_RATIO = 1000.0


def tolerance_errors(problem: Problem) -> list[SpecError]:
    """Each objective whose tolerance is tighter than the reference's own accuracy
    (:data:`~mechgrade.tolerance.REFERENCE_ACCURACY`) with no absolute tolerance beside it.

    >>> from mechgrade.spec import load_problem_text
    >>> from mechgrade.resources import shipped_dir
    >>> text = (shipped_dir("problems") / "pendulum_pin_reaction.yaml").read_text()
    >>> load_problem_text(text.replace("unit: rad/s^2\\n", "unit: rad/s^2\\n    tolerance: "
    ...                                "{rel: 0}\\n", 1), "p.yaml")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechgrade.errors.SpecError: p.yaml:...: objectives[0].tolerance: expected a tolerance no tighter than ...
    """
    out = []
    for objective in problem.objectives:
        tol = objective.tolerance
        if tol.rel >= REFERENCE_ACCURACY or tol.abs > 0:
            continue
        where = tol.where if tol.where.file else objective.where
        out.append(SpecError(
            f"expected a tolerance no tighter than the reference's own accuracy "
            f"({REFERENCE_ACCURACY:g} of the answer), found rel: {tol.rel:g} and no abs: no "
            "answer could match the last digits of a floating-point reference, so every "
            "student would get zero; write rel: 0.01 (1 %, the default) or leave tolerance out "
            "(abs: gives an absolute one, in the objective's unit)", where=where))
    return out


def given_value_hint(text: str, data: dict) -> str | None:
    """Why a given's value that is neither a quantity nor an expression of other givens is
    refused, when the cause is a known slip: a percentage, or a parameter the design solves
    for (a given is known before the design, so it cannot depend on it).

    >>> given_value_hint("50 %", {})
    "expected a number, found the percentage '50 %': write the ratio 0.5"
    >>> given_value_hint("R/2", {"analysis": {"design": {"find": "R"}}})  # doctest: +ELLIPSIS
    "expected a number with a unit, found 'R/2', which uses R, the parameter ..."
    """
    stripped = text.strip()
    if stripped.endswith("%"):
        try:
            ratio = float(stripped[:-1]) / 100
        except ValueError:
            ratio = None
        write = f"the ratio {ratio:g}" if ratio is not None else "the ratio (50 % is 0.5)"
        return f"expected a number, found the percentage '{stripped}': write {write}"
    design = ((data.get("analysis") or {}).get("design") or {}) if isinstance(data, dict) \
        else {}
    find = design.get("find") if isinstance(design, dict) else None
    if isinstance(find, str) and re.search(rf"\b{re.escape(find)}\b", stripped):
        return (f"expected a number with a unit, found '{stripped}', which uses {find}, the "
                "parameter analysis: design solves for: a given is known before the design, "
                f"so it cannot depend on {find}; give it a number (the design varies {find} "
                f"alone), or put {find} in the geometry where it belongs (a point's position)")
    return None


def plausibility_warnings(problem: Problem) -> tuple[AuthorWarning, ...]:
    """Magnitudes implausible for their unit system next to the others (see the module)."""
    if problem.dynamics is None:
        return ()
    return (*_gravity(problem), *_masses(problem), *_densities(problem))


def _given(problem: Problem, expr: Expr) -> Given | None:
    """The given of the parameter ``expr`` is (a bare name), if any."""
    if not isinstance(expr.node, Name):
        return None
    return next((g for g in problem.givens
                 if isinstance(g.key.node, Name) and g.key.node.id == expr.node.id), None)


def _si(problem: Problem, expr: Expr) -> float | None:
    """``expr``'s value in SI: a given parameter's, or a number's (read as SI)."""
    given = _given(problem, expr)
    if given is not None:
        return given.si
    return constant_value(expr.node)


def _gravity(problem: Problem) -> list[AuthorWarning]:
    d = problem.dynamics
    assert d is not None
    if d.gravity is None:
        return []
    params = {p.name for p in problem.parameters}
    names = {n.id for n in walk(d.gravity.node) if isinstance(n, Name) and n.id in params}
    if len(names) != 1:
        return []
    (name,) = names
    given = next((g for g in problem.givens
                  if isinstance(g.key.node, Name) and g.key.node.id == name), None)
    if given is None or not given.unit or abs(given.si / STANDARD_GRAVITY - 1) <= 0.02:
        return []
    written = given.text.split(None, 1)[-1]  # the unit as the author wrote it
    for unit in _GRAVITY_UNITS:
        standard = from_si(STANDARD_GRAVITY, unit)
        if abs(given.value / standard - 1) <= 0.02:
            own = from_si(STANDARD_GRAVITY, given.unit)
            return [AuthorWarning(
                f"{name} = {given.text} is {given.si:.3g} m/s^2, not standard gravity: "
                f"{given.value:g} is g in {unit}; in {written} it is {own:.4g} (expected "
                f"{name}: {own:.4g} {written}, or {name}: {given.value:g} {unit})",
                given.where)]
    return []


def _masses(problem: Problem) -> list[AuthorWarning]:
    """A pair of bodies whose masses differ a thousandfold and are written in different
    units, neither vouched for by a plausible density for its shape."""
    d = problem.dynamics
    assert d is not None
    masses = []
    for body in d.bodies:
        if len(body.parts) != 1 or _density(problem, body.parts[0]) is not None:
            continue  # a composite, or a shape whose size vouches for (or against) its mass
        given = _given(problem, body.parts[0].mass)
        if given is not None and given.unit and given.si > 0:
            masses.append((body.name, given))
    out: list[AuthorWarning] = []
    for i, (a, ga) in enumerate(masses):
        for b, gb in masses[i + 1:]:
            light, heavy = ((a, ga), (b, gb)) if ga.si < gb.si else ((b, gb), (a, ga))
            ratio = heavy[1].si / light[1].si
            if ratio < _MASS_RATIO or ga.unit == gb.unit:
                continue
            odd, other = _odd_one_out(problem, light, heavy)
            out.append(AuthorWarning(
                f"the mass of {light[0]}, {light[1].key.text} = {light[1].text}, is 1/"
                f"{ratio:.4g} of {heavy[0]}'s {heavy[1].key.text} = {heavy[1].text}, in another "
                f"unit: implausible next to it; expected masses in one unit system (did you "
                f"mean {odd[1].key.text}: {odd[1].value:g} {other[1].unit}?)", odd[1].where))
    return out


def _odd_one_out(problem: Problem, light, heavy):
    """Of two masses in different units, the one whose unit does not go with the problem's
    lengths (a gram among metres), else the lighter; and the other."""
    lengths = [g.unit for g in problem.givens if g.unit and _is_length(g.unit)]
    system = {"m": "kg", "mm": "kg", "km": "kg", "cm": "g", "ft": "lb", "in": "lb"}
    anchor = system.get(max(set(lengths), key=lengths.count)) if lengths else None
    if anchor is not None and heavy[1].unit.startswith(anchor[:2]) \
            and not light[1].unit.startswith(anchor[:2]):
        return light, heavy
    if anchor is not None and light[1].unit.startswith(anchor[:2]) \
            and not heavy[1].unit.startswith(anchor[:2]):
        return heavy, light
    return light, heavy


def _is_length(unit: str) -> bool:
    return unit.strip() in ("m", "mm", "km", "cm", "ft", "in")


def _density(problem: Problem, part) -> tuple[float, float] | None:
    """The least and greatest density (kg/m^3) a part's mass and shape allow, the shape's
    proportions taken as generously as its name does (its ``volumes``); ``None`` when
    unknown."""
    mass = _si(problem, part.mass)
    if part.shape is None or mass is None or mass <= 0:
        return None
    volumes = part.shape.volumes(lambda e: _si(problem, e))
    if volumes is None:
        return None
    largest, smallest = volumes
    return mass / largest, (mass / smallest if smallest else math.inf)


def _densities(problem: Problem) -> list[AuthorWarning]:
    d = problem.dynamics
    assert d is not None
    out = []
    for b in d.bodies:
        for part in b.parts:
            bounds = _density(problem, part)
            if bounds is None:
                continue
            least, most = bounds
            shape = type(part.shape).__name__.lower()
            size = next(e for e in vars(part.shape).values() if isinstance(e, Expr)) \
                if not isinstance(part.shape, Block) else part.shape.sides[0]
            mass, length = _written(problem, part.mass), _written(problem, size)
            if least > _DENSITIES[1]:
                out.append(AuthorWarning(
                    f"body '{b.name}': a {shape} of mass {mass} and {size.text} = {length} "
                    f"would be at least {least:.3g} kg/m^3, denser than any material (osmium: "
                    "22600 kg/m^3): a unit slip? (expected its size and mass in one unit "
                    "system)", part.where))
            elif most < _DENSITIES[0]:
                out.append(AuthorWarning(
                    f"body '{b.name}': a {shape} of mass {mass} and {size.text} = {length} "
                    f"would be at most {most:.3g} kg/m^3, lighter than air (1.2 kg/m^3): a unit "
                    "slip? (expected its size and mass in one unit system)", part.where))
    return out


def _written(problem: Problem, expr: Expr) -> str:
    given = _given(problem, expr)
    return given.text if given is not None else expr.text
