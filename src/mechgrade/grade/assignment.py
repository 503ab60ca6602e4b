"""Read an assignment file: which problems, how many points, and the grading policy.

An assignment is a YAML file validated by the JSON Schema shipped beside this module
(``assignment.schema.json``); every problem it lists is a path relative to the assignment file.
Errors say ``file:line:col: field.path: message``; when a file has several, each is one line.

>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> _ = (folder / "p.yaml").write_text("id: p\\n")
>>> _ = (folder / "hw.yaml").write_text(
...     "id: hw1\\ntitle: Homework 1\\nproblems: [p.yaml]\\npoints: {default: 2, p.speed: 5}\\n")
>>> hw = load_assignment(folder / "hw.yaml")
>>> hw.id, hw.points_for("p", "speed"), hw.points_for("p", "other"), hw.policy.ecf.enabled
('hw1', 5.0, 2.0, True)
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from datetime import date, datetime, time, timezone
from functools import lru_cache
from pathlib import Path

from ..errors import AssignmentError, Location
from ..yamlio import Document, read_yaml
from .policy import ErrorCarriedForward, GradingPolicy, MissingUnit, ShowWorked

SCHEMA_FILE = Path(__file__).with_name("assignment.schema.json")


@dataclass(frozen=True)
class ProblemRef:
    """One problem of the assignment: its file and, optionally, the objectives graded."""

    path: Path
    objectives: tuple[str, ...] | None = None  # None: every objective of the problem
    diagrams: tuple[str, ...] = ()  # bodies whose free-body diagram is graded (body.fbd)
    equations: bool = False  # whether its equations of motion are graded (equations)
    where: Location = field(default_factory=Location, compare=False)
    steps: tuple[tuple[str, tuple[str, ...]], ...] = ()  # (objective, its steps in order)
    steps_where: tuple[tuple[str, Location], ...] = field(default=(), compare=False)

    def steps_of(self, objective_id: str) -> tuple[str, ...]:
        """The steps ``objective_id``'s write-up is graded in (``()``: none).

        >>> ProblemRef(Path("p.yaml"), steps=(("omega", ("xdot",)),)).steps_of("omega")
        ('xdot',)
        """
        return dict(self.steps).get(objective_id, ())

    def where_steps(self, objective_id: str) -> Location:
        """Where ``steps.<objective_id>`` was written."""
        return dict(self.steps_where).get(objective_id, self.where)


@dataclass(frozen=True)
class VariantPolicy:
    """How students' variants are drawn: ``seed`` (with the student id) decides the numbers;
    ``redraw`` refuses draws that fail verification and takes the next one."""

    seed: str = ""
    redraw: bool = False


@dataclass(frozen=True)
class Assignment:
    """A validated assignment file. ``points`` maps ``"problem_id.objective_id"`` to points."""

    id: str
    title: str
    path: Path
    problems: tuple[ProblemRef, ...]
    default_points: float = 1.0
    points: tuple[tuple[str, float], ...] = ()
    policy: GradingPolicy = GradingPolicy()
    variants: VariantPolicy = VariantPolicy()
    due: datetime | None = None  # timezone-aware
    points_where: tuple[tuple[str, Location], ...] = field(default=(), compare=False, repr=False)

    def points_for(self, problem_id: str, objective_id: str) -> float:
        """The maximum points of one objective (its own entry, else ``points.default``)."""
        key = f"{problem_id}.{objective_id}"
        for name, value in self.points:
            if name == key:
                return value
        return self.default_points

    @property
    def variant_seed(self) -> str:
        """The seed students' variants are drawn with: ``variants.seed``, else the id."""
        return self.variants.seed or self.id

    def shows_worked_solution(self, now: datetime) -> bool:
        """Whether feedback made at ``now`` (timezone-aware) shows the worked solutions:
        ``always``; ``never``; ``after_due_date`` (the default) once ``due`` has passed, and
        never without a ``due`` date, since the worked solution reveals every answer.

        >>> from datetime import datetime, timezone
        >>> due = datetime(2026, 11, 20, 23, 59, tzinfo=timezone.utc)
        >>> before, after = due.replace(hour=12), due.replace(day=21)
        >>> hw = Assignment("hw", "Homework", Path("hw.yaml"), (), due=due)
        >>> hw.shows_worked_solution(before), hw.shows_worked_solution(after)
        (False, True)
        >>> Assignment("hw", "Homework", Path("hw.yaml"), ()).shows_worked_solution(after)
        False
        """
        rule = self.policy.worked_solution
        if rule == ShowWorked.AFTER_DUE_DATE:
            return self.due is not None and now >= self.due
        return rule == ShowWorked.ALWAYS

    def where_points(self, key: str) -> Location:
        """Where ``points.<key>`` was written (for messages about unknown objectives)."""
        for name, where in self.points_where:
            if name == key:
                return where
        return Location(str(self.path), field=f"points.{key}")


@lru_cache(maxsize=1)
def schema() -> dict:
    """The JSON Schema of assignment files (shipped with the package)."""
    return json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))


def load_assignment(path: str | Path) -> Assignment:
    """Read and validate an assignment file; raises :class:`AssignmentError`."""
    path = Path(path)
    doc = read_yaml(path, error=AssignmentError, what="an assignment file (YAML)")
    problems_ = _validate(doc)
    data = doc.data
    points = data.get("points") or {}
    policy = data.get("policy") or {}
    keys = sorted(k for k in points if k != "default")
    return Assignment(
        id=data["id"],
        title=data["title"],
        path=path,
        problems=problems_,
        default_points=float(points.get("default", 1.0)),
        points=tuple((k, float(points[k])) for k in keys),
        policy=_policy(policy),
        points_where=tuple((k, doc.where(("points", k))) for k in keys),
        variants=VariantPolicy(str((data.get("variants") or {}).get("seed", "")),
                               bool((data.get("variants") or {}).get("redraw", False))),
        due=_due(data["due"]) if "due" in data else None,
    )


def _policy(policy: dict) -> GradingPolicy:
    """The ``policy:`` of an assignment file (checked by :func:`_validate`) as the grading
    policy: a written figure or a missing unit keeps ``credit``, so loses ``1 - credit``.

    >>> p = _policy({"sig_figs": {"figures": 3, "credit": 0.8},
    ...              "missing_unit": {"action": "penalize", "credit": 0.5}})
    >>> p.written_sig_figs, round(p.written_sig_figs_deduction, 2), p.missing_unit, p.missing_unit_deduction
    (3, 0.2, <MissingUnit.ASSUME: 'assume'>, 0.5)
    """
    tolerance = policy.get("tolerance") or {}
    sig = policy.get("sig_figs")
    missing = policy.get("missing_unit") or {}
    action = missing.get("action", "reject")
    partial = policy.get("partial_credit") or {}
    ecf = policy.get("ecf") or {}
    return GradingPolicy(
        reveal_answers=bool(policy.get("reveal_answers", False)),
        worked_solution=ShowWorked(policy.get("worked_solution", ShowWorked.AFTER_DUE_DATE)),
        rel=_float_or_none(tolerance.get("rel")),
        abs=_float_or_none(tolerance.get("abs")),
        sig_figs=int(tolerance["sig_figs"]) if "sig_figs" in tolerance else None,
        separate_mistakes=bool(tolerance.get("separate_mistakes", False)),
        written_sig_figs=int(sig["figures"]) if sig is not None else None,
        written_sig_figs_strict=bool(sig.get("strict", False)) if sig is not None else False,
        written_sig_figs_deduction=(1.0 - float(sig.get("credit", 0.75)) if sig is not None
                                    else 0.25),
        # "assume" is "penalize" keeping full credit; "reject" refuses (its deduction unused)
        missing_unit=MissingUnit.REJECT if action == "reject" else MissingUnit.ASSUME,
        missing_unit_deduction=(GradingPolicy.missing_unit_deduction if action == "reject"
                                else 1.0 - float(missing.get("credit", 0.75))
                                if action == "penalize" else 0.0),
        partial_credit=(tuple(sorted((str(k), float(v))
                                     for k, v in (partial.get("diagnoses") or {}).items()))
                        if partial.get("enabled", True) else ()),
        ecf=ErrorCarriedForward(bool(ecf.get("enabled", True)), float(ecf.get("credit", 1.0))),
    )


def _due(text: str) -> datetime:
    """A ``due`` field (checked by :func:`_validate`) as a timezone-aware time: a date is the
    end of that day, a time without an offset is UTC.

    >>> _due("2026-11-20").isoformat(), _due("2026-11-20T18:00-05:00").isoformat()
    ('2026-11-20T23:59:59+00:00', '2026-11-20T18:00:00-05:00')
    """
    if not re.fullmatch(r"\d{4}-\d{2}-\d{2}([T ]\d{2}:\d{2}(:\d{2})?(Z|[+-]\d{2}:\d{2})?)?",
                        text):
        raise ValueError(text)
    if len(text) == 10:
        moment = datetime.combine(date.fromisoformat(text), time(23, 59, 59))
    else:
        moment = datetime.fromisoformat(text.replace("Z", "+00:00"))
    return moment if moment.tzinfo is not None else moment.replace(tzinfo=timezone.utc)


def _float_or_none(value) -> float | None:
    return None if value is None else float(value)


def _validate(doc: Document) -> tuple[ProblemRef, ...]:
    """Schema check, then the checks a schema cannot make (files exist, no repeats)."""
    from ..schema_errors import describe, schema_problems

    problems_: list[AssignmentError] = []
    if not isinstance(doc.data, dict):
        raise AssignmentError(f"expected a mapping of fields (id, title, problems...), found "
                              f"{describe(doc.data)}", where=doc.where(()))
    for problem in schema_problems(schema(), doc.data):
        where = doc.where_key(problem.path) if problem.at_key else doc.where(problem.path)
        problems_.append(AssignmentError(problem.message, where=where))
    refs: list[ProblemRef] = []
    if not problems_:
        base = doc.file and Path(doc.file).parent
        seen: dict[Path, int] = {}
        for i, item in enumerate(doc.data["problems"]):
            text = item if isinstance(item, str) else item["path"]
            where = doc.where(("problems", i) if isinstance(item, str) else ("problems", i, "path"))
            target = (Path(base) / text)
            if not target.is_file():
                problems_.append(AssignmentError(
                    f"expected a problem file (relative to the assignment file), found no file "
                    f"at '{target}'", where=where))
                continue
            resolved = target.resolve()
            if resolved in seen:
                problems_.append(AssignmentError(
                    f"expected each problem once, found '{text}' again (also problems[{seen[resolved]}])",
                    where=where))
                continue
            seen[resolved] = i
            objectives = None
            if isinstance(item, dict) and "objectives" in item:
                objectives = tuple(item["objectives"])
                dup = sorted({o for o in objectives if objectives.count(o) > 1})
                if dup:
                    problems_.append(AssignmentError(
                        f"expected each objective once, found '{dup[0]}' more than once",
                        where=doc.where(("problems", i, "objectives"))))
            diagrams = tuple(item.get("diagrams", ())) if isinstance(item, dict) else ()
            equations = bool(item.get("equations", False)) if isinstance(item, dict) else False
            if objectives == () and not diagrams and not equations:
                problems_.append(AssignmentError(
                    "expected at least 1 item(s) (none only beside diagrams: or equations:), "
                    "found an empty "
                    "list", where=doc.where(("problems", i, "objectives"))))
            dup = sorted({b for b in diagrams if diagrams.count(b) > 1})
            if dup:
                problems_.append(AssignmentError(
                    f"expected each body's diagram once, found '{dup[0]}' more than once",
                    where=doc.where(("problems", i, "diagrams"))))
            steps = item.get("steps", {}) if isinstance(item, dict) else {}
            for objective_id, chain in steps.items():
                dup = sorted({s for s in chain if chain.count(s) > 1})
                if dup:
                    problems_.append(AssignmentError(
                        f"expected each step once, found '{dup[0]}' more than once",
                        where=doc.where(("problems", i, "steps", objective_id))))
                if objective_id in chain:
                    problems_.append(AssignmentError(
                        f"expected the steps before objective '{objective_id}', found "
                        f"'{objective_id}' itself among them",
                        where=doc.where(("problems", i, "steps", objective_id))))
                nested = [s for s in chain if s in steps]
                if nested:
                    problems_.append(AssignmentError(
                        f"expected steps without steps of their own, found '{nested[0]}' "
                        f"(list all of its steps under '{objective_id}' instead)",
                        where=doc.where(("problems", i, "steps", objective_id))))
            refs.append(ProblemRef(
                target, objectives, diagrams, equations, where,
                tuple((k, tuple(v)) for k, v in steps.items()),
                tuple((k, doc.where(("problems", i, "steps", k))) for k in steps)))
        if "due" in doc.data:
            try:
                _due(doc.data["due"])
            except ValueError:
                problems_.append(AssignmentError(
                    f"expected a date (2026-11-20) or a date and time (2026-11-20T23:59, "
                    f"with an offset such as +01:00 or Z, else UTC), found "
                    f"'{doc.data['due']}'", where=doc.where(("due",))))
        from .diagnose import CODES

        diagnoses = ((doc.data.get("policy") or {}).get("partial_credit") or {}).get("diagnoses")
        for code in diagnoses or {}:
            if code not in CODES:
                problems_.append(AssignmentError(
                    f"expected a diagnosis code ({', '.join(CODES)}), found '{code}'",
                    where=doc.where(("policy", "partial_credit", "diagnoses", code))))
    if problems_:
        problems_.sort(key=lambda e: (e.where.line or 0, e.where.column or 0, str(e)))
        first = problems_[0]
        rest = "".join(f"\n{e}" for e in problems_[1:])
        raise AssignmentError(first.message + rest, where=first.where)
    return tuple(refs)


