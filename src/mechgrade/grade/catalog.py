"""A problem as a catalogue shows it: its statement, topics, how it is analysed, the answers,
the worked solution (with its picture) and the variants it draws, all ready-made for
:mod:`mechgrade.report.catalog`, which renders them without sympy. Built here, beside the
students' sheets, because a problem with variants shows its statement with its own givens.

>>> from mechgrade.resources import shipped_dir
>>> entry = catalog_entry(shipped_dir("problems") / "atwood_machine.yaml")
>>> entry.id, [a.value for a in entry.analyses], entry.objectives[0].answer
('atwood_machine', ['kinetics at an instant'], '2.4525 m/s^2')
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from pathlib import Path

from ..errors import MechgradeError
from ..expressions.syntax import Call, Node
from ..solve import solve
from ..solve.worked import WorkedSolution, answer_text, worked_solution
from ..spec import load_problem
from ..spec.dynamics import Impulse, Integration, WorkEnergy
from ..spec.model import ObjectiveKind
from ..spec.model import Problem
from ..spec.variant_model import Draw
from .variants import statement

_VIBRATION_CALLS = frozenset({"omega_n", "zeta", "mode_frequency", "mode_damping",
                              "mode_shape"})


class Approach(Enum):
    """How a problem's instant is reached and what is worked out there: the catalogue's second
    way of filing problems (the first is the author's ``tags:``)."""

    KINEMATICS = "kinematics"
    INSTANT = "kinetics at an instant"
    WORK_ENERGY = "work and energy"
    INTEGRATION = "motion integrated in time"
    IMPACT = "impact"
    DESIGN = "design (a parameter solved for)"
    VIBRATION = "vibration about an equilibrium"


@dataclass(frozen=True)
class CatalogObjective:
    """One objective as listed: what is asked and the reference answer (or why it has none)."""

    id: str
    prompt: str
    kind: ObjectiveKind
    answer: str
    solved: bool = True


@dataclass(frozen=True)
class CatalogEntry:
    """One problem's page: ``statement`` with the problem's own givens written in,
    ``variants`` the draws of its givens, ``requires`` the conditions on a draw; ``worked`` the
    worked solution at the problem's own givens."""

    id: str
    title: str
    source: str
    statement: str
    file: str
    tags: tuple[str, ...]
    analyses: tuple[Approach, ...]
    objectives: tuple[CatalogObjective, ...]
    worked: WorkedSolution
    variants: tuple[Draw, ...] = ()
    requires: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()

    @property
    def failures(self) -> tuple[CatalogObjective, ...]:
        """The objectives that could not be solved."""
        return tuple(o for o in self.objectives if not o.solved)


@dataclass(frozen=True)
class CatalogFault:
    """A problem file the catalogue could not show, and the one message saying why."""

    file: str
    message: str


def catalog_entry(path: str | Path) -> CatalogEntry:
    """Load, solve and present the problem in ``path``; a bad file raises its
    :class:`~mechgrade.errors.MechgradeError` (see :func:`catalog_entries`)."""
    problem = load_problem(path)
    solution = solve(problem)
    results = {r.id: r for r in solution.results}
    failed = {f.id: str(f.error) for f in solution.failures}
    objectives = tuple(
        CatalogObjective(o.id, o.prompt, o.kind, answer_text(results[o.id]))
        if o.id in results else
        CatalogObjective(o.id, o.prompt, o.kind, failed.get(o.id, "not solved"), False)
        for o in problem.objectives)
    variants = problem.variants
    return CatalogEntry(
        id=problem.id, title=problem.title, source=problem.source,
        statement=statement(problem), file=str(path), tags=problem.tags,
        analyses=analyses(problem), objectives=objectives,
        worked=worked_solution(problem, solution),
        variants=variants.draws if variants else (),
        requires=tuple(r.text for r in variants.requires) if variants else (),
        warnings=tuple(str(w) for w in problem.warnings + solution.warnings))


def catalog_entries(paths) -> tuple[tuple[CatalogEntry, ...], tuple[CatalogFault, ...]]:
    """Every problem of ``paths`` that loads and solves, and one fault for each that does not
    (one bad file never stops the others)."""
    entries, faults = [], []
    for path in paths:
        try:
            entries.append(catalog_entry(path))
        except MechgradeError as err:
            faults.append(CatalogFault(str(path), str(err)))
    return tuple(entries), tuple(faults)


def analyses(problem: Problem) -> tuple[Approach, ...]:
    """How ``problem`` is analysed, from its model (never from its tags).

    >>> from mechgrade.resources import shipped_dir
    >>> p = load_problem(shipped_dir("problems") / "damped_pendulum_vibration.yaml")
    >>> [a.name for a in analyses(p)]
    ['INSTANT', 'VIBRATION']
    """
    dynamics = problem.dynamics
    if dynamics is None:
        found = [Approach.KINEMATICS]
    else:
        kind = {WorkEnergy: Approach.WORK_ENERGY, Integration: Approach.INTEGRATION,
                Impulse: Approach.IMPACT}
        found = [kind.get(type(dynamics.analysis), Approach.INSTANT)]
        if dynamics.design is not None:
            found.append(Approach.DESIGN)
    if any(_calls(o.find.node) & _VIBRATION_CALLS for o in problem.objectives):
        found.append(Approach.VIBRATION)
    return tuple(found)


def _calls(node: Node) -> set[str]:
    """The names of the functions called in ``node``."""
    found = set()
    if isinstance(node, Call):
        found.add(node.func)
        for arg in node.args:
            found |= _calls(arg)
    for child in ("left", "right", "operand"):
        if getattr(node, child, None) is not None:
            found |= _calls(getattr(node, child))
    return found
