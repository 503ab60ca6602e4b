"""A student's free-body diagram, written as text, read safely and judged load by load
against the model's diagram (:mod:`mechgrade.solve.fbd`) at the solved instant.

A diagram is loads separated by ``;`` (or line breaks), each ``label [at point]: vector``:
the label is the model's name for the load (``N_P``) or ordinary words (``weight``,
``normal force``, ``friction``, ``tension``, ``spring``, ``pin``...), the point one of the
problem's points (several, ``T at B1, B2``, for one load acting at each: a cord around a
pulley), the vector an expression along unit vectors (``i j k`` or ``î ĵ k̂`` for the
inertial frame's, ``A.x`` for a frame's) in the problem's symbols. Any other name is an
unknown of the student's own (``Ox``, ``N``), solved for from the loads it appears in.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.solve import solve
>>> from mechgrade.solve.derivation import derivation_instant
>>> problem = load_problem(shipped_dir("problems") / "block_sliding_down_incline.yaml")
>>> instant = derivation_instant(problem, solve(problem))
>>> judged = judge_diagram("weight: -m g j; normal: N A.y; friction: -mu_k N A.x", instant, "block")
>>> judged.verdict, judged.credit
(<Verdict.CORRECT: 'correct'>, 1.0)
>>> judged = judge_diagram("weight: -m g j; normal: N j; centrifugal force: m xd^2 i", instant, "block")
>>> [(row.label, [str(m) for m in row.mistakes]) for row in judged.rows]
[('weight', []), ('normal', ['wrong direction']), ('kinetic friction', ['missing']), ('centrifugal force', ['extra'])]
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from itertools import combinations

import numpy as np
from scipy.optimize import linear_sum_assignment

from ..errors import AnswerError, ExpressionError
from ..expressions import syntax
from ..expressions.excerpt import excerpt
from ..expressions.functions import StrEnum
from ..expressions.numeric import evaluate
from ..expressions.syntax import Attr, Bin, Call, Name, Node, Num, Prime, Unary
from ..solve import rules
from ..solve.derivation import AXES, DerivationInstant
from ..solve.fbd import DiagramLoad, FreeBodyDiagram
from ..spec.dynamics import LoadKind
from ..tolerance import parts, within
from .answers import rename_to_symbols
from .compare import Assessment, Judged, not_evaluated, unreadable
from .results import Verdict

MAX_LOADS = 20
"""The most loads one diagram may list."""
MAX_UNKNOWNS = 12
"""The most unknowns of the student's own one diagram may name."""
MAX_TEXT = 4000
REL = 0.01
"""A load is right when within 1 % of the model's (of its size), as a vector objective's
components are by default."""
DIRECTION_SLACK = 0.01
"""How far (as a fraction of a unit vector) a written direction may be from the model's."""


class LoadMistake(StrEnum):
    """What is wrong with one load of a diagram. Members equal their text."""

    MISSING = "missing"
    EXTRA = "extra"
    WRONG_POINT = "wrong point"
    WRONG_DIRECTION = "wrong direction"
    REVERSED = "reversed"
    WRONG_MAGNITUDE = "wrong magnitude"


@dataclass(frozen=True)
class StudentLoad:
    """One load as written: ``vector`` is ``offset + columns @ unknowns`` in inertial
    components (SI) at the instant, ``columns`` one per name of ``unknowns``."""

    label: str
    point: str | None
    text: str
    offset: tuple[float, float, float]
    columns: tuple[tuple[float, float, float], ...]
    unknowns: tuple[str, ...]

    @property
    def read_back(self) -> str:
        at = f" at {self.point}" if self.point else ""
        return f"{self.label}{at}: {self.text}"


@dataclass(frozen=True)
class DiagramAnswer:
    """A student's diagram of ``body``: its loads in the order written."""

    body: str
    loads: tuple[StudentLoad, ...]

    @property
    def read_back(self) -> str:
        return "; ".join(load.read_back for load in self.loads)


@dataclass(frozen=True)
class LoadRow:
    """One row of the judged diagram: a model load (``load``, its ``kind`` and ``point``) and
    the student's load matched to it (``answer``, ``None`` when missing), or an extra load
    (``load`` ``None``). ``mistakes`` is empty when the load is right."""

    label: str
    load: str | None
    kind: LoadKind | None
    point: str | None
    answer: str | None
    mistakes: tuple[LoadMistake, ...]
    feedback: str

    @property
    def right(self) -> bool:
        return not self.mistakes


@dataclass(frozen=True)
class DiagramJudgement(Judged):
    """A diagram judged: a row per load; credit is the share of rows that are right."""

    body: str
    rows: tuple[LoadRow, ...]
    read_back: str | None
    assessment: Assessment


# ---------------------------------------------------------------------------- reading


_POINT = r"[A-Za-z][A-Za-z0-9_]*"
_LOAD = re.compile(rf"^(?P<label>[^:]+?)(?:\s+at\s+(?P<points>{_POINT}(?:\s*(?:,|\s+and\s+)\s*"
                   rf"{_POINT})*))?\s*:(?P<vector>.*)$", re.S)
_LABEL = re.compile(r"[A-Za-z][A-Za-z0-9_' -]{0,39}")
_HATS = {"î": "x", "ĵ": "y", "k̂": "z", "i\u0302": "x", "j\u0302": "y"}
_PLAIN = {"i": "x", "j": "y", "k": "z"}


def read_diagram(text: str, instant: DerivationInstant, body: str) -> DiagramAnswer:
    """Read ``text`` as the free-body diagram of ``body``; :class:`AnswerError` says why not.

    >>> from mechgrade.spec import load_problem
    >>> from mechgrade.resources import shipped_dir
    >>> from mechgrade.solve import solve
    >>> from mechgrade.solve.derivation import derivation_instant
    >>> problem = load_problem(shipped_dir("problems") / "pendulum_pin_reaction.yaml")
    >>> instant = derivation_instant(problem, solve(problem))
    >>> read_diagram("weight at G: -m g ĵ; pin at O: Ox i + Oy j", instant, "rod").read_back
    'weight at G: -m*g*N.y; pin at O: Ox*N.x+Oy*N.y'
    >>> read_diagram("weight at Q: -m g j", instant, "rod")
    Traceback (most recent call last):
    ...
    mechgrade.errors.AnswerError: expected a point of the problem (G, O), found 'Q'
    """
    if len(text) > MAX_TEXT:
        raise AnswerError(f"expected a diagram of at most {MAX_TEXT} characters, "
                          f"found {len(text)}")
    parts = [p.strip() for p in re.split(r"[;\n\r]", text) if p.strip()]
    if not parts:
        raise AnswerError("expected loads such as 'weight at G: -m g j', found nothing")
    if len(parts) > MAX_LOADS:
        raise AnswerError(f"expected at most {MAX_LOADS} loads, found {len(parts)}")
    loads = [load for part in parts for load in _read_load(part, instant)]
    if len(loads) > MAX_LOADS:
        raise AnswerError(f"expected at most {MAX_LOADS} loads, found {len(loads)} (a load "
                          f"at several points counts once at each)")
    unknowns = {u for load in loads for u in load.unknowns}
    if len(unknowns) > MAX_UNKNOWNS:
        raise AnswerError(f"expected at most {MAX_UNKNOWNS} unknowns of your own, "
                          f"found {len(unknowns)}")
    return DiagramAnswer(body, tuple(loads))


def _read_load(text: str, instant: DerivationInstant) -> list[StudentLoad]:
    """The load ``text`` writes, once at each point it names (``T at B1, B2: T j``: one
    tension, one unknown, pulling at two points)."""
    found = _LOAD.match(text)
    if found is None:
        raise AnswerError(f"expected a load as 'label at point: vector', found "
                          f"{excerpt(text)} (no ':')")
    label = " ".join(found.group("label").split())
    if not _LABEL.fullmatch(label):
        raise AnswerError(f"expected a load's label of letters, digits and spaces, found "
                          f"{excerpt(label)}")
    at = re.split(r"\s*,\s*|\s+and\s+", found.group("points") or "")
    points = [name for name, _ in instant.points]
    for point in at:
        if point and point not in points:
            raise AnswerError(f"expected a point of the problem "
                              f"({', '.join(sorted(points))}), found {excerpt(point)}")
    twice = next((point for n, point in enumerate(at) if point in at[:n]), None)
    if twice is not None:
        raise AnswerError(f"expected each point of {excerpt(label)} once, found "
                          f"{excerpt(twice)} twice")
    vector = found.group("vector").strip()
    for hat, axis in _HATS.items():
        vector = vector.replace(hat, f" {instant.inertial_frame}.{axis} ")
    try:
        node = syntax.parse(vector, attributes=True)
    except ExpressionError as exc:
        raise AnswerError(f"{exc.message} (in {excerpt(label)})") from None
    symbols = tuple(name for name, _ in instant.values)
    node = _unit_names(node, instant, set(symbols))
    units = tuple(f"{frame}.{axis}" for frame, _ in instant.frames for axis in AXES)
    node, unknowns = rename_to_symbols(node, symbols + units)
    for name in unknowns:
        if name in instant.unvalued:
            raise AnswerError(f"expected symbols with a value at the problem's instant, found "
                              f"{excerpt(name)} (in {excerpt(label)}), which the problem "
                              f"leaves without one: write its value, or ask your instructor")
        if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", name):
            raise AnswerError(f"expected the problem's symbols or names of your own for "
                              f"unknowns, found {excerpt(name)} (in {excerpt(label)})")
    offset, columns = _linear_parts(node, instant, units, unknowns, label)
    return [StudentLoad(label, point or None, syntax.to_text(node), offset, columns, unknowns)
            for point in at]


def _unit_names(node: Node, instant: DerivationInstant, symbols: set[str]) -> Node:
    """``A.x`` as the name ``A.x`` (a frame's unit vector), a plain ``i j k`` that is not a
    symbol of the problem as the inertial frame's."""
    frames = {name for name, _ in instant.frames}
    if isinstance(node, Attr):
        if node.base not in frames or node.attr not in AXES:
            raise AnswerError(f"expected a unit vector such as {instant.inertial_frame}.x "
                              f"(frames {', '.join(sorted(frames))}), found "
                              f"{excerpt(node.base + '.' + node.attr)}")
        return Name(f"{node.base}.{node.attr}")
    if isinstance(node, Name) and node.id in _PLAIN and node.id not in symbols:
        return Name(f"{instant.inertial_frame}.{_PLAIN[node.id]}")
    if isinstance(node, Unary):
        return Unary(node.op, _unit_names(node.operand, instant, symbols))
    if isinstance(node, Bin):
        return Bin(node.op, _unit_names(node.left, instant, symbols),
                   _unit_names(node.right, instant, symbols))
    if isinstance(node, Call):
        return Call(node.func, tuple(_unit_names(a, instant, symbols) for a in node.args))
    assert isinstance(node, (Num, Name, Prime))
    return node


def _linear_parts(node: Node, instant: DerivationInstant, units: tuple[str, ...],
                  unknowns: tuple[str, ...], label: str):
    """The load's vector as ``offset + columns @ unknowns``, refused unless every term has
    one unit vector and at most one unknown, to the first power."""
    used = sorted(syntax.names(node) & set(units))
    if not used:
        raise AnswerError(f"expected a vector along unit vectors such as 'i', 'j' or "
                          f"'{instant.inertial_frame}.x', found none in {excerpt(label)}")
    rows: list[dict[str, float]] = [{}]
    rows += [{q: 1.0} for q in unknowns]
    for a in used:
        rows += [{a: 1.0}, {a: 1.7}]
        for q in unknowns:
            rows += [{a: 1.0, q: 1.0}, {a: 1.0, q: 1.7}]
        for q, r in combinations(unknowns, 2):
            rows.append({a: 1.0, q: 1.0, r: 1.0})
    rows += [{a: 1.0, b: 1.0} for a, b in combinations(used, 2)]
    env = {name: np.full(len(rows), value) for name, value in instant.values}
    for name in (*used, *unknowns):
        env[name] = np.array([row.get(name, 0.0) for row in rows])
    f = evaluate(node, env)
    value = dict(zip(map(_key, rows), f))
    scale = float(np.nanmax(np.abs(f))) if np.any(np.isfinite(f)) else 1.0

    def same(x: float, y: float) -> bool:
        return bool(np.isfinite(x) and np.isfinite(y) and abs(x - y) <= 1e-9 * max(scale, 1.0))

    offset = np.zeros(3)
    columns = np.zeros((len(unknowns), 3))
    if not same(value[_key({})], 0.0):
        raise AnswerError(f"expected every term of {excerpt(label)} along a unit vector, "
                          f"found a term with none")
    for q in unknowns:
        if not same(value[_key({q: 1.0})], 0.0):
            raise AnswerError(f"expected every term of {excerpt(label)} along a unit vector, "
                              f"found {excerpt(q)} alone")
    for a in used:
        direction = _unit(instant, a)
        g = value[_key({a: 1.0})]
        if not same(value[_key({a: 1.7})], 1.7 * g):
            raise AnswerError(f"expected {excerpt(label)} as a sum of terms each along one "
                              f"unit vector, found {a} not to the first power")
        h = {}
        for q in unknowns:
            h[q] = value[_key({a: 1.0, q: 1.0})] - g
            if not same(value[_key({a: 1.0, q: 1.7})] - g, 1.7 * h[q]):
                raise AnswerError(f"expected the unknowns of {excerpt(label)} to the first "
                                  f"power, found {excerpt(q)} otherwise")
        for q, r in combinations(unknowns, 2):
            if not same(value[_key({a: 1.0, q: 1.0, r: 1.0})] - g, h[q] + h[r]):
                raise AnswerError(f"expected at most one unknown in a term of "
                                  f"{excerpt(label)}, found {q} and {r} multiplied (names "
                                  f"that are not the problem's symbols are unknowns)")
        offset += g * direction
        for n, q in enumerate(unknowns):
            columns[n] += h[q] * direction
    for a, b in combinations(used, 2):
        if not same(value[_key({a: 1.0, b: 1.0})], value[_key({a: 1.0})] + value[_key({b: 1.0})]):
            raise AnswerError(f"expected {excerpt(label)} as a sum of terms each along one "
                              f"unit vector, found {a} and {b} multiplied")
    return _vec(offset), tuple(_vec(c) for c in columns)


def _key(row: dict[str, float]) -> tuple:
    return tuple(sorted(row.items()))


def _unit(instant: DerivationInstant, name: str) -> np.ndarray:
    frame, axis = name.split(".")
    vector = instant.unit_vector(frame, axis)
    if vector is None:
        raise AnswerError(f"expected unit vectors whose direction is known at the instant, "
                          f"found {name}")
    return np.array(vector)


def _vec(v) -> tuple[float, float, float]:
    return (float(v[0]) + 0.0, float(v[1]) + 0.0, float(v[2]) + 0.0)


# ---------------------------------------------------------------------------- judging


_WORDS: dict[str, frozenset[LoadKind]] = {
    "weight": frozenset({LoadKind.WEIGHT}), "gravity": frozenset({LoadKind.WEIGHT}),
    "normal": frozenset({LoadKind.NORMAL, LoadKind.CONTACT}),
    "contact": frozenset({LoadKind.CONTACT, LoadKind.NORMAL}),
    "friction": frozenset({LoadKind.STATIC_FRICTION, LoadKind.KINETIC_FRICTION}),
    "tension": frozenset({LoadKind.TENSION}), "cable": frozenset({LoadKind.TENSION}),
    "rope": frozenset({LoadKind.TENSION}), "string": frozenset({LoadKind.TENSION}),
    "spring": frozenset({LoadKind.SPRING}), "damper": frozenset({LoadKind.DAMPER}),
    "damping": frozenset({LoadKind.DAMPER}),
    "pin": frozenset({LoadKind.PIN, LoadKind.REACTION, LoadKind.CONTACT}),
    "hinge": frozenset({LoadKind.PIN, LoadKind.REACTION}),
    "reaction": frozenset({LoadKind.PIN, LoadKind.REACTION, LoadKind.CONTACT,
                           LoadKind.NORMAL}),
    "support": frozenset({LoadKind.PIN, LoadKind.REACTION, LoadKind.CONTACT}),
    "couple": frozenset({LoadKind.APPLIED_COUPLE}), "moment": frozenset({LoadKind.APPLIED_COUPLE}),
    "torque": frozenset({LoadKind.APPLIED_COUPLE}), "impulse": frozenset({LoadKind.IMPULSE}),
}
"""Ordinary words for a load and the kinds of model load they may name."""
_GENERIC: dict[str, frozenset[LoadKind]] = {
    "force": frozenset({LoadKind.APPLIED_FORCE}),
    "applied": frozenset({LoadKind.APPLIED_FORCE, LoadKind.APPLIED_COUPLE}),
    "push": frozenset({LoadKind.APPLIED_FORCE}), "pull": frozenset({LoadKind.APPLIED_FORCE}),
}
"""Words that name a kind only when no more specific word does (``normal force``)."""
_FICTITIOUS = {
    "centrifugal": "a centrifugal force is not a load in an inertial frame",
    "centripetal": "the centripetal force is the resultant of the loads, not a load of its own",
    "inertia": "an inertia force (-m a) is not a load in an inertial frame",
    "inertial": "an inertia force (-m a) is not a load in an inertial frame",
    "coriolis": "a Coriolis force is not a load in an inertial frame",
    "ma": "m a is the resultant of the loads, not a load of its own",
}
"""Words naming a force that is not a load at all, and why."""


def judge_diagram(text: str | None, instant: DerivationInstant, body: str) -> DiagramJudgement:
    """Read and judge ``text`` as the free-body diagram of ``body`` (see the module)."""
    if text is None or not text.strip():
        return DiagramJudgement(body, (), None, Assessment(Verdict.MISSING, 0.0, None,
                                                           "No answer was given.", None))
    if not instant.values or any(vectors is None for _, vectors in instant.frames):
        return DiagramJudgement(body, (), None, not_evaluated(
            "the model has no solved state to judge the diagram at"))
    try:
        answer = read_diagram(text, instant, body)
    except AnswerError as exc:
        return DiagramJudgement(body, (), None, unreadable(exc.message))
    return judge(answer, instant.diagram(body), instant)


def judge(answer: DiagramAnswer, model: FreeBodyDiagram,
          instant: DerivationInstant) -> DiagramJudgement:
    """Judge a read diagram against the model's: a row per model load, then a row per extra
    load, in the order written."""
    matched = _match(answer, model, instant)
    bound: dict[str, float] = {}
    rows: dict[int, LoadRow] = {}
    # reactions first: the unknowns of the student's own are solved from them
    order = sorted((s for s, m in matched.items() if m is not None),
                   key=lambda s: not matched[s].unknown)  # type: ignore[union-attr]
    scale = max((np.linalg.norm(m.vector) for m in model.loads if m.vector is not None),
                default=1.0)
    for s in order:
        m = matched[s]
        assert m is not None
        rows[id(m)] = _judge_load(answer.loads[s], m, model, instant, bound, float(scale))
    out = []
    for m in model.loads:
        if id(m) in rows:
            out.append(rows[id(m)])
        else:
            out.append(LoadRow(str(m.kind), m.name, m.kind, m.point, None,
                               (LoadMistake.MISSING,),
                               f"Missing: the {_describe(m)}."))
    for s, load in enumerate(answer.loads):
        if matched[s] is None:
            out.append(LoadRow(load.label, None, None, load.point, load.read_back,
                               (LoadMistake.EXTRA,), _extra_reason(load, answer.body)))
    right = sum(row.right for row in out)
    credit = right / len(out) if out else 0.0
    verdict = (Verdict.CORRECT if right == len(out) else Verdict.PARTIAL if right
               else Verdict.INCORRECT)
    wrong = [row.feedback for row in out if not row.right]
    feedback = " ".join(wrong) if wrong else f"Every load on {model.body} is right."
    return DiagramJudgement(model.body, tuple(out), answer.read_back,
                            Assessment(verdict, credit, None, feedback, answer.read_back))


def _words(label: str) -> list[str]:
    return [w for w in re.split(r"[\s_'-]+", label.lower()) if w]


def _kinds(label: str) -> frozenset[LoadKind] | None:
    """The kinds of load ``label`` names in ordinary words (``None``: none of them)."""
    words = _words(label)
    specific = frozenset().union(*(_WORDS.get(w, frozenset()) for w in words))
    if specific:
        return specific
    generic = frozenset().union(*(_GENERIC.get(w, frozenset()) for w in words))
    return generic or None


def _fictitious(label: str) -> str | None:
    return next((why for w in _words(label) for word, why in _FICTITIOUS.items() if w == word),
                None)


def _match(answer: DiagramAnswer, model: FreeBodyDiagram,
           instant: DerivationInstant) -> dict[int, DiagramLoad | None]:
    """Each student load's model load (``None``: extra): the model's own name first, then
    ordinary words (among loads of the kinds they name), then any other label (among loads at
    the point it gives). Within a stage, the pairing that has the most loads at their point,
    then the most loads right, then the closest fit (two springs on one block are told apart
    by their values, whichever is written first)."""
    free = list(model.loads)
    out: dict[int, DiagramLoad | None] = {}
    loads = list(enumerate(answer.loads))
    # the model's names: a name may be several loads (one cord pulling at two points, the
    # weights of a body's parts), paired like any other loads of one kind
    for name in dict.fromkeys(m.name for m in model.loads):
        named = [(s, load, None) for s, load in loads if load.label == name]
        _pair(named, [m for m in free if m.name == name], model, instant, out, at_point=False)
        free = _unpaired(free, out)
    for s, load in loads:
        if s not in out and _fictitious(load.label):  # not a load at all
            out[s] = None
    words = [(s, load, _kinds(load.label)) for s, load in loads if s not in out]
    by_word = [(s, load, kinds) for s, load, kinds in words if kinds is not None]
    _pair(by_word, free, model, instant, out, at_point=False)
    free = _unpaired(free, out)
    own = [(s, load, None) for s, load, kinds in words if kinds is None]
    _pair(own, free, model, instant, out, at_point=True)
    return out


def _unpaired(free: list[DiagramLoad], out: dict) -> list[DiagramLoad]:
    """``free`` but the loads paired in ``out`` (by identity: two parts' weights are equal)."""
    paired = {id(m) for m in out.values() if m is not None}
    return [m for m in free if id(m) not in paired]


_NO_PAIR = 1e9


def _pair(students: list, free: list[DiagramLoad], model: FreeBodyDiagram,
          instant: DerivationInstant, out: dict, at_point: bool) -> None:
    """Pair ``students`` (index, load, kinds or ``None`` for any) with ``free`` model loads
    into ``out``; a student load left unpaired is extra."""
    if not students:
        return
    cost = np.full((len(students), len(free)), _NO_PAIR)
    for i, (_, load, kinds) in enumerate(students):
        for j, m in enumerate(free):
            here = _same_point(load, m, model, instant)
            if (kinds is not None and m.kind not in kinds) or (at_point and not here):
                continue
            size = float(np.linalg.norm(m.vector)) if m.vector is not None else 0.0
            misfit = _misfit(load, m) / max(size, 1e-12)
            cost[i, j] = 100.0 * (not here) + 10.0 * (misfit > REL) + min(misfit, 1.0)
    rows, columns = linear_sum_assignment(cost) if free else ((), ())
    paired = {int(i): free[j] for i, j in zip(rows, columns) if cost[i, j] < _NO_PAIR}
    for i, (s, _, _) in enumerate(students):
        out[s] = paired.get(i)


def _misfit(load: StudentLoad, m: DiagramLoad) -> float:
    if m.vector is None:
        return 0.0
    target = np.array(m.vector) - np.array(load.offset)
    if not load.columns:
        return float(np.linalg.norm(target))
    a = np.array(load.columns).T
    u = np.linalg.lstsq(a, target, rcond=None)[0]
    return float(np.linalg.norm(a @ u - target))


def _same_point(load: StudentLoad, m: DiagramLoad, model: FreeBodyDiagram,
                instant: DerivationInstant) -> bool:
    if m.point is None:  # a couple is a free vector: wherever it is drawn
        return True
    if load.point is None:
        return model.frame is None  # a particle's loads all act at it
    if load.point == m.point:
        return True
    here, there = instant.point(load.point), instant.point(m.point)
    return here is not None and there is not None and \
        float(np.linalg.norm(np.subtract(here, there))) <= 1e-9


def _judge_load(load: StudentLoad, m: DiagramLoad, model: FreeBodyDiagram,
                instant: DerivationInstant, bound: dict[str, float], scale: float) -> LoadRow:
    mistakes: list[LoadMistake] = []
    notes: list[str] = []
    if not _same_point(load, m, model, instant):
        mistakes.append(LoadMistake.WRONG_POINT)
        notes.append(f"it acts at {m.point}, not at {load.point}" if load.point
                     else f"say where it acts: '{load.label} at ...'")
    free = [n for n, q in enumerate(load.unknowns) if q not in bound]
    vector = np.array(load.offset)
    for n, q in enumerate(load.unknowns):
        if q in bound:
            vector = vector + bound[q] * np.array(load.columns[n])
    if m.vector is None:
        return LoadRow(load.label, m.name, m.kind, m.point, load.read_back,
                       tuple(mistakes), _row_text(load, mistakes, notes,
                                                  "not judged (no value at the instant)"))
    target = np.array(m.vector)
    direction_wrong = False
    if free:
        a = np.array([load.columns[n] for n in free]).T
        u = np.linalg.lstsq(a, target - vector, rcond=None)[0]
        if m.unknown and not _same_span(a, m):
            direction_wrong = True
            notes.append(_span_note(a, m))
            if len(free) == 1 and np.linalg.norm(a) > 0:
                # the model's size along the student's direction, so that a load using this
                # unknown (friction's mu N) is judged on its own, not on a misfit N
                u = np.array([np.sign(a[:, 0] @ target or 1.0) * np.linalg.norm(target)
                              / np.linalg.norm(a)])
        for n, value in zip(free, u):
            bound[load.unknowns[n]] = float(value)
        vector = vector + a @ u
    size = float(np.linalg.norm(target))
    if direction_wrong:
        mistakes.append(LoadMistake.WRONG_DIRECTION)
    elif not within(float(np.linalg.norm(vector - target)), 0.0, 0.0, 1e-9 * scale + 1e-12) \
            and not within(float(np.linalg.norm(vector - target)), 0.0, 0.0, REL * size):
        mistakes += _vector_mistakes(vector, target, scale)
    return LoadRow(load.label, m.name, m.kind, m.point, load.read_back, tuple(mistakes),
                   _row_text(load, mistakes, notes))


def _vector_mistakes(s: np.ndarray, t: np.ndarray, scale: float) -> list[LoadMistake]:
    size_s, size_t = float(np.linalg.norm(s)), float(np.linalg.norm(t))
    tol = REL * size_t + 1e-9 * scale
    if float(np.linalg.norm(s + t)) <= tol:
        return [LoadMistake.REVERSED]
    if not parts(size_s, scale) or not parts(size_t, scale):
        return [LoadMistake.WRONG_MAGNITUDE]
    cosine = float(s @ t) / (size_s * size_t)
    if cosine >= 1 - REL ** 2 / 2:
        return [LoadMistake.WRONG_MAGNITUDE]
    if abs(size_s - size_t) <= tol:
        return [LoadMistake.WRONG_DIRECTION]
    if cosine <= -1 + REL ** 2 / 2:
        return [LoadMistake.REVERSED, LoadMistake.WRONG_MAGNITUDE]
    return [LoadMistake.WRONG_DIRECTION, LoadMistake.WRONG_MAGNITUDE]


def _same_span(a: np.ndarray, m: DiagramLoad) -> bool:
    """Whether the student's unknown directions (columns of ``a``) span the model's."""
    model = [np.array(d) for d in m.directions if d is not None]
    if not model:
        return True
    d = np.array(model).T
    return _inside(d, a) and _inside(a, d)


def _inside(x: np.ndarray, y: np.ndarray) -> bool:
    """Whether every column of ``x`` (normalised) lies in the span of ``y``'s columns: its
    part at right angles to them (along the null space of ``y``'s rows) is within
    :data:`DIRECTION_SLACK`."""
    across = rules.null_space(y.T)
    for column in x.T:
        size = np.linalg.norm(column)
        if size == 0:
            continue
        if np.linalg.norm(across.T @ (column / size)) > DIRECTION_SLACK:
            return False
    return True


def _span_note(a: np.ndarray, m: DiagramLoad) -> str:
    want = sum(d is not None for d in m.directions)
    have = rules.matrix_rank(a)
    if have > want:
        return f"the {m.kind} has {want} unknown direction{'s' * (want > 1)}, you gave {have}"
    if have < want:
        return f"the {m.kind} has {want} unknown directions, you gave {have}"
    return ""


def _row_text(load: StudentLoad, mistakes: list[LoadMistake], notes: list[str],
              extra: str = "") -> str:
    head = load.read_back.split(":")[0]
    if not mistakes:
        return f"{head}: right{(' (' + extra + ')') if extra else ''}."
    said = ", ".join(str(m) for m in mistakes)
    why = "; ".join(n for n in notes if n)
    return f"{head}: {said}{(' (' + why + ')') if why else ''}."


def _describe(m: DiagramLoad) -> str:
    at = f" at {m.point}" if m.point else ""
    return f"{m.kind} {m.name}{at}"


def _extra_reason(load: StudentLoad, body: str) -> str:
    why = _fictitious(load.label)
    if why:
        return f"Extra: {load.label} ({why})."
    if _kinds(load.label):
        return f"Extra: {load.label} (no other load of this kind acts on {body})."
    return f"Extra: {load.label} (no load acts like it on {body})."
