"""A mistaken model that changes only numbers, as other values of the right model's parameters.

A mistaken copy of a problem (:mod:`.dynamics_mutations`) that differs from ``base`` only in
some expressions, each the base's expression of one parameter ``s`` (``m``, ``-g*N.y``, linear
in it) times a constant factor (``(m)*mag(-g*N.y)``, ``(-g*N.y)/mag(-g*N.y)``; zero where an
optional one is left out: the weight), where ``s`` appears nowhere else in the problem, is
``base`` with ``s`` worth ``s`` times that factor: its balances are the base's, solved with
other givens, not derived and lambdified again. Decided by the structure of the two problems,
whichever family made the copy.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.mechanics.dynamics_mutations import dynamics_mutations, unchanged_copy
>>> problem = load_problem(shipped_dir("problems") / "ladder_wall_lift_off.yaml")
>>> copies = {m.code: m.problem for m in dynamics_mutations(problem) if m.problem}
>>> revaluation(unchanged_copy(problem), copies["weight_for_mass"])
(('g', 1), ('m', g*m))
>>> revaluation(unchanged_copy(problem), copies["weight_omitted"])
(('g', 0),)
>>> revaluation(unchanged_copy(problem), copies["value_at_start"]) is None
True
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, replace
from functools import lru_cache

import sympy as sp

from ..errors import MechgradeError
from ..expressions.syntax import Bin, Name, Num, walk
from ..spec.dynamics import Force
from ..spec.model import Expr, Given, ObjectiveKind, Parameter, Problem
from .build import Model, build


@lru_cache(maxsize=256)
def revaluation(base: Problem, mistaken: Problem) -> tuple[tuple[str, sp.Expr], ...] | None:
    """``(parameter, its value in the base's parameters)`` for each parameter that takes
    another value in ``mistaken`` (the base's numeric objectives it keeps, read with these
    values, give its answers); ``None`` when ``mistaken`` is not ``base`` with numbers
    changed."""
    if not set(mistaken.objectives) <= set(base.objectives) \
            or base.parameters != mistaken.parameters:
        return None
    changed: list[tuple[Expr, Expr | None]] = []
    elsewhere: set[str] = set()
    if not _alike(dataclasses.replace(base, objectives=(), parameters=()),
                  dataclasses.replace(mistaken, objectives=(), parameters=()), changed,
                  elsewhere):
        return None
    for objective in mistaken.objectives:
        if objective.kind != ObjectiveKind.SYMBOLIC:  # a symbolic answer keeps its symbols
            _alike(objective, objective, changed, elsewhere)
    parameters = {q.name for q in base.parameters}
    if not changed or _changed_names(changed) & elsewhere:
        return None
    model = _model(base)
    known = {model.language.value(Name(q)) for q in parameters}
    values: dict[str, sp.Expr] = {}
    for old, new in changed:
        names = {n.id for n in walk(old.node) if isinstance(n, Name)}
        if len(names) != 1 or not names <= parameters:
            return None
        name = names.pop()
        factor = _factor(model, old, new, model.language.value(Name(name)))
        if factor is None or not factor.free_symbols <= known \
                or values.get(name, factor) != factor:
            return None
        values[name] = factor
    return tuple(sorted((name, sp.simplify(model.language.value(Name(name)) * factor))
                        for name, factor in values.items()))


@lru_cache(maxsize=64)
def common_models(base: Problem, copies: tuple[Problem, ...]
                  ) -> tuple[tuple[Problem, tuple[tuple[str, sp.Expr], ...]] | None, ...]:
    """For each of ``copies`` (mistaken copies of ``base``), the one model it shares with the
    others that differ from it only in expressions of ``base``'s parameters (the coefficient
    of restitution of each contact: e and -e, e and e, 1 and -e), each such expression a
    parameter of its own, and its values in ``base``'s parameters; ``None`` for a copy that
    differs from every other in more. Their balances are derived and lambdified once.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.mechanics.dynamics_mutations import dynamics_mutations
    >>> problem = load_problem(shipped_dir("problems") / "rod_strikes_ledge.yaml")
    >>> copies = tuple(m.problem for m in dynamics_mutations(problem)
    ...                if m.code == "restitution_component")
    >>> [values for _, values in common_models(problem, copies)]
    [(('mistaken_0', e), ('mistaken_1', -e)), (('mistaken_0', e), ('mistaken_1', e)), \
(('mistaken_0', 1), ('mistaken_1', -e))]
    """
    groups: list[list[int]] = []
    for i, copy in enumerate(copies):
        group = next((g for g in groups if _common(copies[g[0]], (copy,)) is not None), None)
        if group is None:
            groups.append([i])
        else:
            group.append(i)
    out: list[tuple[Problem, tuple[tuple[str, sp.Expr], ...]] | None] = [None] * len(copies)
    groups = [g for g in groups if len(g) > 1]
    if not groups:
        return tuple(out)
    model = _model(base)
    parameters = {model.language.value(Name(q.name)) for q in base.parameters}
    prefix = _prefix(base)
    for group in groups:
        members = tuple(copies[i] for i in group)
        slots: list[tuple[Expr, ...]] = []
        common = _common(members[0], members[1:], slots, prefix)
        if common is None:
            continue
        try:
            values = [[model.language.value(e.node) for e in slot] for slot in slots]
        except MechgradeError:
            continue  # a slot the kinematics cannot read (a force): not a number
        if any(not isinstance(v, sp.Basic) or not model.plain(v).free_symbols <= parameters
               for slot in values for v in slot):
            continue  # a slot that is not a number of the parameters (a vector, a rate)
        names = [f"{prefix}{k}" for k in range(len(slots))]
        common = replace(common, parameters=common.parameters + tuple(
            Parameter(name, "1", positive=False) for name in names),
            givens=common.givens + tuple(
                Given(Expr(name, Name(name)), 0.0, "1", 0.0, "0") for name in names))
        for k, i in enumerate(group):
            out[i] = (common, tuple((name, model.plain(values[j][k]))
                                    for j, name in enumerate(names)))
    return tuple(out)


def _prefix(base: Problem) -> str:
    """A start of names that none of ``base``'s starts with (``mistaken_``, then
    ``mistaken__``...)."""
    used: set[str] = set()
    _alike(base, base, [], used)
    prefix = "mistaken_"
    while any(name.startswith(prefix) for name in used):
        prefix += "_"
    return prefix


def _common(first: Problem, others: tuple[Problem, ...],
            slots: list[tuple[Expr, ...]] | None = None, prefix: str = "") -> Problem | None:
    """``first`` with each expression in which one of ``others`` differs from it a name of its
    own (``prefix`` and ``k``, ``slots[k]`` its expressions in each), and each force in which
    they differ in more (its point) there in each one's version, each version times a name of
    its own (1 where a copy has it, else 0); ``None`` where they differ in more, or in their
    objectives."""
    if any(o.objectives != first.objectives for o in others):
        return None
    try:
        return _held(first, others, _Held(slots if slots is not None else [], prefix,
                                          first.objectives))
    except _Differs:
        return None


class _Differs(Exception):
    """Two copies differ in more than expressions and forces."""


@dataclass
class _Held:
    slots: list[tuple[Expr, ...]]
    prefix: str
    objectives: tuple

    def name(self, exprs: tuple[Expr, ...]) -> str:
        self.slots.append(exprs)
        return f"{self.prefix}{len(self.slots) - 1}"

    def named(self) -> set[str]:
        """The names the objectives read (a force they name is not split in versions)."""
        out: set[str] = set()
        _alike(self.objectives, self.objectives, [], out)
        return out


_ONE, _ZERO = Expr("1", Num("1")), Expr("0", Num("0"))


def _held(a, others: tuple, held: _Held):
    if all(o == a for o in others):  # most of two copies is the same objects
        return a
    if isinstance(a, Expr):
        if any(not isinstance(o, Expr) for o in others):
            raise _Differs
        if all(o.node == a.node for o in others):
            return a
        name = held.name((a, *others))
        return Expr(name, Name(name), a.where)
    if any(type(o) is not type(a) for o in others):
        raise _Differs
    if isinstance(a, tuple):
        if any(len(o) != len(a) for o in others):
            raise _Differs
        out: list = []
        for i, x in enumerate(a):
            count = len(held.slots)
            try:
                out.append(_held(x, tuple(o[i] for o in others), held))
            except _Differs:
                del held.slots[count:]
                out += _versions(x, tuple(o[i] for o in others), held)
        return tuple(out)
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        return dataclasses.replace(a, **{
            f.name: _held(getattr(a, f.name), tuple(getattr(o, f.name) for o in others), held)
            for f in dataclasses.fields(a) if f.compare and f.init})
    if any(o != a for o in others):
        raise _Differs
    return a


def _versions(a, others: tuple, held: _Held) -> list[Force]:
    """Each version of a force (``a`` in the first copy, ``others`` in the rest) times a name
    of its own, worth 1 in the copies that have it and 0 in the others."""
    if not isinstance(a, Force) or a.name in held.named():
        raise _Differs
    each = (a, *others)
    out: list[Force] = []
    for version in dict.fromkeys(each):
        factor = held.name(tuple(_ONE if f == version else _ZERO for f in each))
        out.append(replace(version, name=f"{held.prefix}{version.name}~{len(out)}",
                           force=Expr(f"{factor}*({version.force.text})",
                                      Bin("*", Name(factor), version.force.node),
                                      version.force.where)))
    return out


@lru_cache(maxsize=64)
def _model(base: Problem) -> Model:
    """``base``'s model, built once for every copy compared with it."""
    return build(base)


def _changed_names(changed: list[tuple[Expr, Expr | None]]) -> set[str]:
    return {n.id for old, _ in changed for n in walk(old.node) if isinstance(n, Name)}


def _alike(a, b, changed: list, elsewhere: set[str]) -> bool:
    """Whether ``a`` and ``b`` differ in expressions only (each pair that differs appended to
    ``changed``; the names of the others, and every other text, put in ``elsewhere``)."""
    if isinstance(a, Expr) and isinstance(b, (Expr, type(None))):
        if isinstance(b, Expr) and a.node == b.node:
            elsewhere.update(n.id for n in walk(a.node) if isinstance(n, Name))
        else:
            changed.append((a, b))  # an optional one left out (gravity) is worth zero
        return True
    if isinstance(a, Given) and a == b and a.value_expr is None and isinstance(a.key.node, Name):
        return True  # a plain given: the value the mistaken model replaces
    if type(a) is not type(b):
        return False
    if isinstance(a, (tuple, list)):
        return len(a) == len(b) and all(_alike(x, y, changed, elsewhere) for x, y in zip(a, b))
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_alike(a[k], b[k], changed, elsewhere) for k in a)
    if dataclasses.is_dataclass(a):
        # a unit ("m") names no parameter
        return all(_alike(getattr(a, f.name), getattr(b, f.name), changed,
                          elsewhere if f.name != "unit" else set())
                   for f in dataclasses.fields(a) if f.compare)
    if isinstance(a, str):
        elsewhere.add(a)
    return a == b


def _factor(model, old: Expr, new: Expr | None, symbol: sp.Symbol) -> sp.Expr | None:
    """The constant by which ``new`` is ``old`` (scalars, or parallel vectors; zero where
    ``new`` is left out), ``old`` linear in ``symbol``; ``None`` when there is none."""
    a = _components(model, old)
    b = [sp.Integer(0)] * len(a or ()) if new is None else _components(model, new)
    if a is None or b is None or len(a) != len(b):
        return None
    factors = set()
    for x, y in zip(a, b):
        if x == 0:
            if y != 0:
                return None
            continue
        if sp.simplify(x.subs(symbol, 2 * symbol) - 2 * x) != 0:
            return None
        factors.add(sp.simplify(y / x))
    if len(factors) != 1:
        return None
    factor = factors.pop()
    return None if factor.has(sp.zoo, sp.nan, sp.oo) else factor


def _components(model, e: Expr) -> list | None:
    value = model.language.value(e.node)
    if isinstance(value, sp.Basic):
        return [model.plain(value)]
    to_matrix = getattr(value, "to_matrix", None)
    return None if to_matrix is None else [model.plain(c) for c in to_matrix(model.inertial)]
