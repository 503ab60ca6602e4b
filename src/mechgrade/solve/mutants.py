"""The values typical conceptual mistakes give, for the grader to name them.

Two sources, both applied to the model and never to the answer: the model mutations of
:mod:`mechgrade.mechanics.mutations` (a term of the composition of motion dropped, another point,
another frame's unit vectors, a path quantity for its neighbour), evaluated at the solved
instant; and mistaken givens (an angle in degrees used as radians or read as its complement, a rate in rpm or deg/s used as
rad/s, a length read in the wrong unit, a rate's sign flipped), for which the instant is solved
again.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.solve import solve
>>> result = solve(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
...               ).result("acc_mag")
>>> [(m.code, round(m.value, 1)) for m in result.generated_mistakes][:2]
[('drop_tangential', 98.0), ('drop_centripetal', 10.0)]
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from functools import lru_cache
from typing import Callable, Collection, Mapping, Sequence

import numpy as np

from ..errors import MechgradeError
from ..expressions.syntax import Call, Name, Prime, to_text, walk
from ..spec.constraint_mutations import constraint_mutations, position_unchosen
from ..spec.model import Given, Objective, ObjectiveKind, Problem
from ..spec.solving import carried
from ..tolerance import PART, REFERENCE_ACCURACY, parts, within
from ..units import dimension, si_factor, to_si
from .columns import call
from .numeric import every_branch_columns, solve_numeric_columns
from .plan import KinematicsPlan, Mutant, kinematics_plan, lambdified_mutants, per_problem
from .result import ROUND_OFF, GeneratedMistake, ObjectiveResult

# sympy and the mechanics are imported by the functions that derive: a plan read from the disk
# cache carries its mutations compiled, and a warm check never imports them.


# a length unit a student may read as the base unit of its system
_LENGTH_SLIPS = {"mm": "m", "cm": "m", "km": "m", "in": "ft", "inch": "ft", "yd": "ft"}


def _lambdified(problem: Problem, p: KinematicsPlan, objective: str) -> tuple[Mutant, ...]:
    """The model mutations of a numeric objective, compiled with the plan or lambdified now:
    a plan compiles those of its own problem's objectives (a dynamics problem's kinematic
    part has none: its plan's are not the dynamics objectives')."""
    if p.mutants is not None and objective in p.mutants:
        return p.mutants[objective]
    return lambdified_mutants(problem, p, objective)


def model_mistake_table(problem: Problem, p: KinematicsPlan, states: np.ndarray, wanted) -> list:
    """The model mutations of the objectives in ``wanted`` at many instants at once
    (``states`` holds one state per column). One row per mutation: ``(mutation, objective,
    where it is defined (N), its values in the objective's unit (N x size), the dropped term's
    SI values (N lists of 3) or None, its values as a result shows them (N))``;
    :func:`model_mistake_at` makes the mistake of one instant. Objective by objective: only
    the wanted ones are derived and lambdified."""
    table = []
    for m in (item for o in problem.objectives if o.id in wanted
              for item in _lambdified(problem, p, o.id)):
        obj = problem.objective(m.objective)
        si = call(m.value, states, m.size)
        shown = (si / si_factor(obj.unit) + 0.0).T  # as in_unit, every column at once
        # (Python numbers made for every column at once: a class reads most of them)
        values = [tuple(v) for v in shown.tolist()] if obj.kind == ObjectiveKind.VECTOR \
            else shown[:, 0].tolist()
        table.append((m, obj, np.isfinite(si).all(axis=0), shown,
                      None if m.term is None else call(m.term, states, 3).T.tolist(), values))
    return table


def model_mistake_at(row, i: int) -> GeneratedMistake:
    """The mistake of :func:`model_mistake_table`'s ``row`` at instant ``i``."""
    m, obj, _, _, terms, values = row
    sentence = m.sentence if terms is None else m.sentence.replace(
        "{term}", _term_text(terms[i], obj, m.velocity))
    return GeneratedMistake(m.code, sentence, values[i])


def symbolic_mistakes(problem: Problem, obj: Objective, right,
                      givens: dict) -> tuple[GeneratedMistake, ...]:
    """The model mutations of a symbolic objective, each solved in the objective's symbols
    like the objective itself."""
    import sympy as sp

    from ..mechanics.mutations import mutations
    from .symbolic import symbolic

    k = kinematics_plan(problem).k
    out: list[GeneratedMistake] = []
    kept: list[tuple[str | None, object]] = [(None, right)]  # (family, expression)
    for m in mutations(problem, obj.id):
        if isinstance(m.value, sp.MatrixBase):
            continue
        try:
            expr, _ = symbolic(problem, k, obj, givens, expr=m.value)
        except MechgradeError:
            continue
        if not symbolic_kept(kept, m.code, expr, KINEMATIC_ZEROS):
            continue
        sentence = re.sub(r" = \{term\} along \w+", "", m.sentence)
        out.append(GeneratedMistake(m.code, sentence, None, sp.sstr(expr)))
    return tuple(out)


KINEMATIC_ZEROS = frozenset({"other_point"})
"""The families whose zero a symbolic answer of the kinematics keeps (a contact point at rest);
a mistaken dynamics model's zero is kept for none."""


def symbolic_kept(kept: list, code: str, expr, zeros: frozenset[str] = frozenset()) -> bool:
    """Whether a mistaken model's symbolic answer ``expr`` (of the family ``code``) is a
    mistake to keep after those ``kept`` (``(family, expression)``, the answer's family
    ``None``), as :func:`kept_mistakes` keeps a value: defined, not the answer nor one of its
    family already (another family's is: the grader names both), and not zero unless its
    family is one of ``zeros`` (a zero is what many mistakes give). A kept one is appended.

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> kept = [(None, 2 * x)]
    >>> [symbolic_kept(kept, c, e) for c, e in (("a", x), ("a", x), ("b", x), ("c", 0 * x),
    ...                                          ("d", 2 * x), ("e", 1 / (x - x)))]
    [True, False, True, False, False, False]
    """
    import sympy as sp

    from ..mechanics.symbols import identically_zero

    if expr.has(sp.zoo, sp.nan, sp.oo) or (code not in zeros and identically_zero(expr)) \
            or any(identically_zero(expr - e) for c, e in kept if c in (None, code)):
        return False
    kept.append((code, expr))
    return True


MutantValues = Callable[[Problem, Sequence[Mapping], set[str]],
                        Sequence[Mapping[str, np.ndarray] | None]]
"""The objectives asked (a set) of a mistaken model (a problem) at each instant of a
class's givens: their values, or ``None`` where that instant is not solved."""


def values_alone(problem: Problem, givens: Sequence[Mapping], wanted: set[str]
                 ) -> list[Mapping[str, np.ndarray] | None]:
    """The :data:`MutantValues` of :func:`~.numeric.solve_numeric_columns` (one instant as
    :func:`~.numeric.solve_numeric` solves it)."""
    return [None if isinstance(instant, MechgradeError) else instant.values
            for instant in solve_numeric_columns(problem, kinematics_plan(problem), givens,
                                                 wanted)]


def constraint_mistakes_columns(problem: Problem, givens: Sequence[Mapping], wanted: set[str],
                                solved: MutantValues = values_alone
                                ) -> list[dict[str, list[GeneratedMistake]]]:
    """The objectives in ``wanted`` solved again with one constraint mistaken
    (:mod:`mechgrade.spec.constraint_mutations`: a cord's strands counted once) at each
    instant of ``givens`` (one solve's, or a class's), each mistaken model's instants solved
    together by ``solved`` (a class's: those the mistaken model's own class solve vouches
    for, the others alone)."""
    out: list[dict[str, list[GeneratedMistake]]] = [{} for _ in givens]
    # the same copies for every solve of the problem, so their plans are found by identity
    for m in per_problem(constraint_mutations, problem):
        for found, instant in zip(out, solved(m.problem, givens, wanted)):
            if instant is None:
                continue  # a mistaken length no configuration reaches is no mistake
            for oid, values in instant.items():
                if oid in wanted and np.all(np.isfinite(values)):
                    found.setdefault(oid, []).append(GeneratedMistake(
                        m.code, m.sentence, _one(values, problem.objective(oid))))
    for found, branches in zip(out, _other_branches(problem, givens, wanted)):
        for oid, mistakes in branches.items():
            found.setdefault(oid, []).extend(mistakes)
    return out


OTHER_BRANCH = ("the other assembly branch: the mechanism solved in its mirror configuration "
                "(the other solution of the position equations), not the one drawn")


def _other_branches(problem: Problem, givens: Sequence[Mapping], wanted: set[str]
                    ) -> list[dict[str, list[GeneratedMistake]]]:
    """Each objective of ``wanted`` on every assembly branch of the position level other than
    the spec's (its guesses and branches dropped, :func:`~.numeric.every_branch_columns`);
    the spec's own root, the answer, is dropped as the answer's value later
    (:func:`kept_mistakes`)."""
    out: list[dict[str, list[GeneratedMistake]]] = [{} for _ in givens]
    free = per_problem(position_unchosen, problem)
    if free is None:
        return out
    for found, branches in zip(out, every_branch_columns(free, kinematics_plan(free), givens,
                                                         wanted)):
        if len(branches) < 2:
            continue  # one configuration only: no other branch
        for values in branches:
            for oid, v in values.items():
                if oid in wanted and np.all(np.isfinite(v)):
                    found.setdefault(oid, []).append(GeneratedMistake(
                        "other_assembly_branch", OTHER_BRANCH,
                        _one(v, problem.objective(oid))))
    return out


def misread(givens: Mapping, changes) -> dict:
    """``givens`` with each ``(key, mistaken SI value)`` of ``changes`` in place."""
    changed = dict(givens)
    for key, mistaken_si in changes:
        node, _, given = givens[key]
        changed[key] = (node, mistaken_si, replace(given, si=mistaken_si))
    return changed


def slips_of(givens: Mapping, parameters: set[str]):
    """``(code, ((key, mistaken SI value), ...), sentence)`` for each typical misreading: of
    one given, or two parameters of the same unit exchanged (a tooth ratio inverted)."""
    named = [(key, node, si, given) for key, (node, si, given) in givens.items()
             if given is not None]
    stated = {key: given for key, _, _, given in named}
    for key, node, si, given in named:
        fixed = isinstance(node, Name) and node.id in parameters
        for code, mistaken_si, sentence in _given_slips(node, si, given, fixed):
            yield code, _carried_into(stated, ((key, mistaken_si),)), sentence
    swappable = [(key, si, given) for key, node, si, given in named
                 if isinstance(node, Name) and node.id in parameters]
    for i, (key, si, given) in enumerate(swappable):
        for other, other_si, other_given in swappable[i + 1:]:
            if given.unit == other_given.unit and si != other_si and si and other_si:
                yield ("given_swap", _carried_into(stated, ((key, other_si), (other, si))),
                       f"Your value is what {key} and {other} exchanged gives ({key} = "
                       f"{other_given.text}, {other} = {given.text}): check which is which.")


def _carried_into(stated: Mapping[str, Given], changes: tuple) -> tuple:
    """``changes`` and, after them, the givens stated as expressions of the misread ones
    (``x': v2*cos(beta)``) worked out again (``stated``: the givens as written, by key): the
    slip carried into each given it feeds."""
    try:
        return changes + tuple(carried(stated, dict(changes)).items())
    except MechgradeError:  # a dependent given undefined when misread (a root of a negative)
        return changes


def _given_slips(node, si: float, given, fixed: bool):
    """``(code, mistaken SI value, sentence)`` for each way ``given`` is typically misread
    (``fixed``: a parameter, not a coordinate's value at the instant)."""
    name, unit, value = to_text(node), given.unit.strip(), given.value
    if unit in ("deg", "degree", "degrees", "°") and value != 0:
        yield ("given_deg_as_rad", value,
               f"Your value is what {name} = {given.text} gives when {value:g} is used as "
               "radians (a calculator in radian mode): convert degrees to radians.")
    if unit in ("deg", "degree", "degrees", "°") and 0 < value < 90 and value != 45:
        # the sine and cosine of an acute angle exchanged: the angle read from the other leg
        yield ("given_complement", math.radians(90 - value),
               f"Your value is what {name} = {90 - value:g} deg gives, the complement of "
               f"{given.text} (sin and cos exchanged): check which side of the angle each "
               "component lies on.")
    if fixed and unit in ("deg", "degree", "degrees", "°") and value != 0:
        # a fixed tilt or slope measured to the other side of its reference line (a
        # coordinate's angle sets the configuration the figure shows: not misread so)
        yield ("given_angle_sign", -si,
               f"Your value is what {name} = {-value:g} deg gives, {given.text} measured to "
               "the other side: check which way the angle turns from the line it is "
               "measured from.")
    order = _rate_order(unit)
    if order and any(u in unit for u in ("rpm", "rev", "deg", "Hz")) \
            and value != 0 and not math.isclose(value, si):
        yield ("given_rate_unit", value,
               f"Your value is what {name} = {given.text} gives when the number is used "
               f"as rad/s{'' if order == 1 else '²'}: convert it to radians per "
               "second first.")
    if unit in _LENGTH_SLIPS and value != 0:
        base = _LENGTH_SLIPS[unit]
        yield ("given_length_unit", to_si(value, base),
               f"Your value is what {name} = {given.text} gives when read as {value:g} "
               f"{base}: convert {unit} to {base}.")
    plain = _unconverted(unit)
    if plain is not None and value != 0 and not math.isclose(value * plain, si):
        yield ("given_unit", value * plain,
               f"Your value is what {name} = {given.text} gives when the number is used "
               f"as {'SI units' if plain == 1.0 else 'feet, pounds and seconds'}: convert "
               f"{unit} first.")
    if isinstance(node, Prime) and si != 0:
        yield ("given_sign", -si,
               f"Your value is what {name} with the opposite sign gives: check the "
               f"direction of {name} ({given.text}) against the positive sense of "
               f"{node.id}.")
    if isinstance(node, Prime) and node.order == 2 and si != 0:
        # the instant read as one of steady motion: a driver's acceleration dropped, its
        # rate kept (the velocity level is unchanged, every acceleration answer is not)
        kind = "angular acceleration" if _rate_order(unit) == 2 else "acceleration"
        yield ("given_acceleration_zero", 0.0,
               f"Your value is what the given {kind} of {node.id} ({name} = {given.text}) "
               "taken as zero gives: at this instant the motion is speeding up or slowing "
               "down, so keep that acceleration in every acceleration term.")


# units of the US customary system, and the one of its base units each is read as
_US_UNITS = {"ft": "ft", "in": "ft", "inch": "ft", "mi": "ft", "yd": "ft", "lb": "lb",
             "lbf": "lbf", "slug": "slug", "kip": "lbf", "hp": "ft*lbf/s", "s": "s",
             "min": "s", "h": "s", "hr": "s"}


@lru_cache(maxsize=64)
def _unconverted(unit: str) -> float | None:
    """The SI factor of the unit a given in ``unit`` is read in when its number is used
    without converting it: the coherent SI unit (kN/m as N/m, km/h as m/s, kW as W, ms as s),
    or the foot-pound-second one (lb/in as lb/ft); ``None`` when the unit is that already, or
    its slips are another family's (a length, an angle, a rate in rpm)."""
    words = re.findall(r"[A-Za-zµ]+", unit)
    if not words or unit in _LENGTH_SLIPS or any(
            w in ("deg", "degree", "degrees", "rad", "rpm", "rev", "Hz") for w in words):
        return None
    try:
        factor = si_factor(unit)
        if all(w in _US_UNITS for w in words) and any(w not in ("s", "min", "h", "hr")
                                                     for w in words):
            plain = si_factor(re.sub(r"[A-Za-z]+", lambda m: _US_UNITS[m.group(0)], unit))
        else:
            plain = 1.0
    except MechgradeError:
        return None
    return None if math.isclose(plain, factor) else plain


@lru_cache(maxsize=64)
def _rate_order(unit: str) -> int | None:
    """1 for an angular rate's unit (rpm, deg/s), 2 for an angular acceleration's, else
    ``None``: a coordinate's rate or a parameter (a flywheel's speed) alike."""
    try:
        dim = dimension(unit)
    except MechgradeError:
        return None
    return {dimension("1/s"): 1, dimension("1/s^2"): 2}.get(dim)


@lru_cache(maxsize=256)
def plausible_slips(problem: Problem) -> frozenset[str]:
    """The whole-answer slips of :mod:`mechgrade.grade.diagnose` that need something in the
    model to be plausible: a factor of g needs a ``g`` or a body (its weight); degrees for
    radians an angle in degrees; rpm or revolutions a rate in them; 60 a rate in rpm beside
    one per second; 746 for 550 hp in a problem in feet and pounds. Slips of the answer's own
    unit always are.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> sorted(plausible_slips(load_problem(shipped_dir("problems")
    ...                                     / "bowling_3_15_4_pendulum.yaml")))
    ['deg_as_rad', 'rad_as_deg']
    """
    units = " ".join([g.unit for g in problem.givens]
                     + [g.unit for o in problem.objectives for g in o.givens]
                     + [o.unit for o in problem.objectives])
    out = set()
    # a g, or a body whose weight m g a student may divide by for its mass (a boat's drag)
    if any(p.name in ("g", "g0") for p in problem.parameters) or problem.dynamics is not None:
        out.add("g")
    if "deg" in units or "°" in units:
        out |= {"deg_as_rad", "rad_as_deg"}
    if any(u in units for u in ("rpm", "rev", "Hz")):
        out |= {"rpm_rad", "rev_rad"}
    # per minute for per second: a rate in rpm beside one in Hz or per second
    if "rpm" in units and any(u in units for u in ("Hz", "rev/s", "rad/s")):
        out.add("min_s")
    # hp in the units of a problem in feet and pounds
    if re.search(r"\bhp\b", units) and re.search(r"\b(ft|lbf?|slug)\b", units):
        out.add("hp_746")
    # a natural frequency: the 2π between ω_n in rad/s and f in Hz (a period taken as 1/ω_n)
    if any(isinstance(n, Call) and n.func in ("omega_n", "mode_frequency")
           for o in problem.objectives for n in walk(o.find.node)):
        out.add("rev_rad")
    return frozenset(out)


GeneratedColumns = Mapping[str, Callable[[int], Sequence[GeneratedMistake]]]
"""Each objective's generated mistakes at every column, as a function of the column."""

Misreadings = Callable[[list[dict]], tuple[np.ndarray, dict[str, np.ndarray], np.ndarray]]
"""How a class reaches the instants of misread givens together (each a map of givens, only
its values read): which it vouches for, each objective's SI values there (size x count),
and which it refuses as one solve refuses them (givens that break the positions they fix);
:func:`generated_columns` solves the others one by one."""


def generated_columns(problem: Problem, p: KinematicsPlan, maps: Sequence[dict], X: np.ndarray,
                      ok: np.ndarray, values: Mapping[str, np.ndarray], numeric: Collection[str],
                      together: Misreadings | None = None,
                      mistaken_model: MutantValues = values_alone) -> GeneratedColumns:
    """Each objective of ``numeric``'s generated mistakes at every column ``ok`` (``maps``:
    its givens, ``X``: its state, ``values``: each objective's SI answers, size x N), as a
    function of the column: the model mutations there, each given misread (:func:`slips_of`;
    its instant reached by ``together`` where that vouches for it, else solved as
    :func:`~.numeric.solve_numeric_columns` solves it; one that cannot be solved is no
    mistake), each constraint mistaken (:func:`constraint_mistakes_columns`, its model's
    instants solved by ``mistaken_model``), kept by
    :func:`kept_columns`. The one way for one solve (a column of one) and a class.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve.instant import instant_givens
    >>> from mechgrade.solve.numeric import solve_numeric
    >>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    >>> p, givens = kinematics_plan(problem), instant_givens(problem, None, {})
    >>> instant = solve_numeric(problem, p, givens, {"acc_mag"})
    >>> at = generated_columns(problem, p, [givens], instant.state.values[:, None],
    ...                        np.ones(1, bool), {"acc_mag": instant.values["acc_mag"][:, None]},
    ...                        {"acc_mag"})["acc_mag"]
    >>> [(m.code, round(m.value, 1)) for m in at(0)][:2]
    [('drop_tangential', 98.0), ('drop_centripetal', 10.0)]
    """
    n = len(maps)
    parameters = {q.name for q in problem.parameters}
    table = model_mistake_table(problem, p, X[:p.index.size], numeric)
    changed, owner = [], []
    for i in np.flatnonzero(ok).tolist():
        for code, changes, sentence in slips_of(maps[i], parameters):
            changed.append((maps[i], changes))
            owner.append((i, code, sentence))
    asked = [oid for oid in values if oid in numeric]
    misreadings: dict[str, list[list[GeneratedMistake]]] = {oid: [[] for _ in range(n)]
                                                            for oid in asked}
    solved, misread_values = _misread_instants(problem, p, changed, set(numeric), together)
    for oid, v in misread_values.items():
        if oid not in misreadings:
            continue
        mistaken = shown(v, problem.objective(oid))
        for k in np.flatnonzero(solved & np.isfinite(v).all(axis=0)).tolist():
            i, code, sentence = owner[k]
            misreadings[oid][i].append(GeneratedMistake(code, sentence, mistaken[k]))
    chosen = np.flatnonzero(ok).tolist()
    for i, found in zip(chosen, constraint_mistakes_columns(
            problem, [maps[i] for i in chosen], set(numeric), mistaken_model)):
        for oid, mistakes in found.items():
            if oid in misreadings:
                misreadings[oid][i].extend(mistakes)
    out = {}
    for oid in asked:
        obj = problem.objective(oid)
        rows_ = [row for row in table if row[0].objective == oid]
        out[oid] = kept_columns(in_unit(values[oid], obj).T, rows_, misreadings[oid])
    return out


def _misread_instants(problem: Problem, p: KinematicsPlan, changed: list[tuple[dict, tuple]],
                      numeric: set[str], together: Misreadings | None
                      ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """The objectives ``numeric`` at each instant of misread givens (``changed``: the givens
    and their ``(key, mistaken SI value)`` changes): which were solved, and each objective's
    SI values (size x count). ``together`` reaches those it vouches for (a degenerate
    configuration is no reason to drop a mistake) and refuses those one solve refuses; the
    others are solved one by one."""
    if not changed:
        return np.zeros(0, dtype=bool), {}
    if together is not None:
        moved = []
        for givens, changes in changed:
            values = dict(givens)  # the stacked solve reads the keys and values only
            for key, mistaken_si in changes:
                values[key] = (givens[key][0], mistaken_si, None)
            moved.append(values)
        solved, found, refused = together(moved)
        solved, found = solved.copy(), dict(found)
    else:
        solved, found = np.zeros(len(changed), dtype=bool), {}
        refused = solved
    redo = np.flatnonzero(~solved & ~refused)
    instants = solve_numeric_columns(problem, p, [misread(*changed[i]) for i in redo], numeric)
    for i, instant in zip(redo.tolist(), instants):
        if isinstance(instant, MechgradeError):
            continue
        solved[i] = True
        for oid, v in instant.values.items():
            if oid in numeric:
                if oid not in found:
                    found[oid] = np.full((np.size(v), len(changed)), np.nan)
                found[oid][:, i] = v
    return solved, found


def kept_at(right, mistakes: Sequence[GeneratedMistake]) -> tuple[GeneratedMistake, ...]:
    """The ``mistakes`` :func:`kept_columns` keeps at one instant whose answer is ``right``
    (a value as a result shows it).

    >>> [m.value for m in kept_at(1.0, [GeneratedMistake("a", "s", 2.0),
    ...                                 GeneratedMistake("a", "s", 1.0)])]
    [2.0]
    """
    return kept_columns(np.atleast_1d(np.asarray(right, float))[None, :], [], [mistakes])(0)


def kept_columns(right: np.ndarray, rows_: Sequence, misread: Sequence[Sequence[GeneratedMistake]]
                 ) -> Callable[[int], tuple[GeneratedMistake, ...]]:
    """The generated mistakes kept at every instant of a class at once
    (``right``: the answer at each, N x size, in the objective's unit): the model mutations in
    ``rows_`` (:func:`model_mistake_table`'s rows of one objective), then each instant's
    ``misread`` givens, kept by :func:`kept_mistakes`. Returns instant ``i``'s as a function
    of ``i``.

    >>> keep = kept_columns(np.array([[1.0], [2.0]]), [], [
    ...     [GeneratedMistake("a", "s", 2.0)], [GeneratedMistake("a", "s", 2.0)]])
    >>> [[m.code for m in keep(i)] for i in (0, 1)]  # at the second, 2.0 is the answer
    [['a'], []]
    """
    n, size = right.shape
    if not rows_ and not any(misread):
        return lambda _i: ()
    V = np.stack([row[3] for row in rows_], axis=1) if rows_ else np.zeros((n, 0, size))
    exists = np.array([row[2] for row in rows_], dtype=bool).reshape(len(rows_), n).T
    codes = np.array([[row[0].code for row in rows_]] * n, dtype=object).reshape(n, len(rows_))
    # the model's mutations, then each instant's misread givens
    V, exists, codes = (np.concatenate(parts, axis=1) for parts in
                        zip((V, exists, codes), _stacked(misread, size)))
    keep = kept_mistakes(right, V, exists, codes)

    def at(i: int) -> tuple[GeneratedMistake, ...]:
        return tuple(model_mistake_at(rows_[j], i) if j < len(rows_)
                     else misread[i][j - len(rows_)] for j in np.flatnonzero(keep[i]).tolist())
    return at


def _stacked(columns: Sequence[Sequence[GeneratedMistake]], size: int
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The generated mistakes of every instant (a sequence each, values as shown) as
    :func:`kept_mistakes` reads them: their values (N x count x ``size``), where each exists
    (not past the end of its instant's, nor a value of another shape than ``size``), and
    their codes.

    >>> V, exists, codes = _stacked([[GeneratedMistake("sign", "s", 2.0)], []], 1)
    >>> V.shape, exists.tolist(), codes.tolist()
    ((2, 1, 1), [[True], [False]], [['sign'], ['']])
    """
    n, count = len(columns), max((len(c) for c in columns), default=0)
    V = np.full((n, count, size), np.nan)
    exists = np.zeros((n, count), dtype=bool)
    codes = np.full((n, count), "", dtype=object)
    for i, mistakes in enumerate(columns):
        for j, m in enumerate(mistakes):
            if size == 1 and isinstance(m.value, float):  # a scalar, as most are: no array
                V[i, j, 0], exists[i, j] = m.value, True
            elif type(m.value) is tuple and len(m.value) == size and all(
                    type(v) is float for v in m.value):  # a vector's components: no array
                V[i, j], exists[i, j] = m.value, True
            else:
                value = np.atleast_1d(np.asarray(m.value, float))
                if value.shape == (size,):
                    V[i, j], exists[i, j] = value, True
            codes[i, j] = m.code
    return V, exists, codes


def kept_mistakes(right: np.ndarray, V: np.ndarray, exists: np.ndarray, codes: np.ndarray,
                  first: int = 0) -> np.ndarray:
    """Which generated mistakes are kept, at every instant at once (``right``: the answer at
    each, N x size; ``V``: the mistakes' values in order, N x count x size; ``exists``: where
    each is defined; ``codes``: each one's family, N x count): each that differs from the
    answer, from every one of its family kept before it and from zero, and is no division by
    zero, as far as the reference can tell values apart. The ``first`` are kept whatever they
    are. Two families of one value are both kept: the grader names both. The one rule for one
    solve and a class (:func:`kept_columns`, :func:`kept_at`).

    A mistake's value comes from the answer's own quantities (a term dropped, a given
    misread, a model changed), so it carries the answer's noise; it is judged at the answer's
    scale, by the rules the answer itself is judged by:

    - within :data:`SAME` of the answer: the answer, no mistake here (a first stop found
      again in a motion started a millionth as fast, 1e-7 off);
    - at most :data:`~mechgrade.tolerance.PART` of the answer (round-off beside it: a term
      that cancels the answer to its last digits, a rate that an event makes zero), or shown
      as 0 (:data:`~.result.ROUND_OFF`): a zero, dropped but for :data:`ZERO_NAMES` (a zero
      is what many mistakes give);
    - an answer that is not 0 at most :data:`~mechgrade.tolerance.PART` of it (the answer
      round-off beside it): a division by a zero made of round-off (0/0 read as 1e14);
    - within :data:`SAME` of one of its family kept before it: that one.

    A unit slip's value may be a millionth of the answer and is kept. An integration whose
    event never happens names no time: its model is not solved
    (:func:`~.events.event_never_happens`), so it has no value here.

    >>> kept_mistakes(np.array([[1.0]]), np.array([[[2.0], [2.0 + 1e-9], [1.0], [0.0]]]),
    ...               np.ones((1, 4), bool), np.array([["a"] * 4])).tolist()
    [[True, False, False, False]]
    >>> kept_mistakes(np.array([[1.0]]), np.array([[[2.0], [2.0], [2.0], [0.0]]]),
    ...               np.ones((1, 4), bool),
    ...               np.array([["a", "b", "a", "drop_coriolis"]])).tolist()
    [[True, True, False, True]]
    >>> kept_mistakes(np.array([[6.5]]), np.array([[[1 + 4e-7], [4e-13], [-3e13], [5e-7]]]) * 6.5,
    ...               np.ones((1, 4), bool), np.array([["a", "b", "c", "d"]])).tolist()
    [[False, False, False, True]]
    """
    n, count = exists.shape
    with np.errstate(invalid="ignore", over="ignore"):
        norms = np.linalg.norm(V, axis=2)
        size = np.linalg.norm(right, axis=1)[:, None]
        scale = np.maximum(size, 1e-12)
        answer = np.linalg.norm(V - right[:, None, :], axis=2) <= \
            SAME * np.maximum(norms, scale) + 1e-12
        vague = exists & (~(np.abs(V) > ROUND_OFF).any(axis=2) | (norms <= PART * size))
        at = np.nonzero(vague)  # the few zeros: their families looked up one by one
        vague[at] = [code not in ZERO_NAMES for code in codes[at].tolist()]
        blown = (size > ROUND_OFF) & (size < PART * norms)
        keep = np.zeros((n, count), dtype=bool)
        keep[:, :first] = True
        for j in range(first, count):
            apart = np.linalg.norm(V[:, :j] - V[:, j:j + 1], axis=2)
            same = apart <= SAME * np.maximum(np.maximum(norms[:, :j], norms[:, j:j + 1]),
                                              1e-12) + 1e-12
            same &= codes[:, :j] == codes[:, j:j + 1]
            keep[:, j] = exists[:, j] & ~(same & keep[:, :j]).any(axis=1) & ~answer[:, j] \
                & ~vague[:, j] & ~blown[:, j]
    return keep


ZERO_NAMES = frozenset({"other_point", "reaction_as_static", "reaction_as_weight",
                        "restitution_ignored", "zero_for_constant_rate", "reaction_omitted",
                        "pin_impulse_omitted", "drop_centripetal", "drop_coriolis",
                        "angmom_along_axis", "strands_miscounted"})
"""Families whose zero value names the mistake (a contact point at rest, a support that holds
no sideways force at rest, a support left out, a pin's impulse left out, no energy lost in a
perfectly elastic impact, no acceleration at a steady rate, no tilt of an angular momentum
taken along ω, a load hoisted to the height the strands counted once give: a configuration of
the mistaken constraint solved again, not a term dropped): their zeros are kept, every other
family's dropped."""


SAME = REFERENCE_ACCURACY
"""Relative distance within which a mistake's value is the answer's or another mistake's (one
value): the reference is trusted to that (an integration to an event; a mistaken motion
started a millionth as fast, whose values the integrator's absolute tolerance 1e-12 then
holds to about 1e-6), and no tolerance may be tighter, so no student's answer tells values
closer than that apart."""


def shown(si: np.ndarray, obj: Objective) -> list:
    """An objective's SI values at every instant (size x N, one column each) in its unit, as
    its result gives them: a float each, or a vector's tuple of components.

    >>> from types import SimpleNamespace
    >>> shown(np.array([[0.5, 2.0]]), SimpleNamespace(unit="cm", kind=ObjectiveKind.SCALAR))
    [50.0, 200.0]
    """
    values = in_unit(si, obj).T.tolist()
    if obj.kind == ObjectiveKind.VECTOR:
        return [tuple(v) for v in values]
    return [v[0] for v in values]


def in_unit(si: np.ndarray, obj: Objective) -> np.ndarray:
    """SI values of an objective in its unit (a zero's sign dropped)."""
    return si / si_factor(obj.unit) + 0.0


def _one(si_values: np.ndarray, obj: Objective):
    """One instant's SI values of an objective as its result shows them (:func:`shown`)."""
    return shown(np.asarray(si_values, dtype=float).reshape(-1, 1), obj)[0]


@lru_cache(maxsize=256)
def _term_unit(unit: str, velocity: bool) -> str:
    """The unit a dropped term is shown in: the objective's when it is of the same kind."""
    per = "/s" if velocity else "/s^2"
    if dimension(unit) == dimension("m" + per):
        return unit
    if dimension(unit) == dimension("m"):  # a radius of curvature: its length unit
        return unit + per
    return "m" + per


def _term_text(si_values: Sequence[float], obj: Objective, velocity: bool) -> str:
    """A dropped term's components (a velocity's or an acceleration's), in the objective's
    unit when it is of the same kind."""
    unit = _term_unit(obj.unit, velocity)
    factor = si_factor(unit)
    shown = [float(v) / factor + 0.0 for v in si_values]  # from_si, as floats
    shown = [v if part else 0.0 for v, part in zip(shown, parts(shown).tolist())]
    written = shown[:2] if shown[2] == 0 else shown
    return "(" + ", ".join([f"{v:.4g}" for v in written]) + f") {unit}"


def inside_tolerance(result: ObjectiveResult, rel: float | None = None,
                     abs_: float | None = None) -> tuple[GeneratedMistake, ...]:
    """The generated mistakes of a numeric ``result`` within its tolerance (or ``rel``,
    ``abs_``): a student making one gets full credit.

    >>> r = ObjectiveResult("a", "scalar", "ft/s^2", 98.51, generated_mistakes=(
    ...     GeneratedMistake("drop_tangential", "...", 98.0),))
    >>> [m.code for m in inside_tolerance(r)], separating_rel(r)
    (['drop_tangential'], 0.002)
    """
    if result.value is None:
        return ()
    rel = result.rel if rel is None else rel
    abs_ = result.abs if abs_ is None else abs_
    right = np.atleast_1d(np.asarray(result.value, float))
    size = float(np.linalg.norm(right))
    return tuple(m for m in result.generated_mistakes if m.value is not None and within(
        np.atleast_1d(np.asarray(m.value, float)), right, rel, abs_, scale=size))


# a tolerance tighter than this would fail answers written to four significant figures
TIGHTEST_REL = 5e-4


def separating_rel(result: ObjectiveResult) -> float | None:
    """The relative tolerance (one significant figure, at most the objective's) that puts
    every generated mistake outside it; ``None`` when one is closer than :data:`TIGHTEST_REL`
    allows to separate, or none is inside. Half the nearest mistake's relative distance."""
    inside = inside_tolerance(result)
    if not inside:
        return None
    right = np.atleast_1d(np.asarray(result.value, float))
    size = float(np.linalg.norm(right))
    nearest = min(float(np.linalg.norm(np.atleast_1d(np.asarray(m.value, float)) - right))
                  for m in inside) / size if size else 0.0
    half = nearest / 2
    if half < TIGHTEST_REL:
        return None
    exponent = math.floor(math.log10(half))
    return min(result.rel, math.floor(half / 10 ** exponent) * 10 ** exponent)
