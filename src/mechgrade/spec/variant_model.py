"""Per-student variants as the problem model holds them (read by :mod:`.variants`).

Kinds of draw are types: :class:`SteppedRange`, :class:`RoundedRange`, :class:`Choices`,
:class:`Integers`; all values are in the drawn given's unit.
"""

from __future__ import annotations

import math
import operator
import re
from dataclasses import dataclass, field
from typing import Callable, Mapping, Union

from ..errors import Location, SpecError
from ..expressions.syntax import Name, Node, Prime, fold, to_text, walk

COMPARISONS: dict[str, Callable[[float, float], bool]] = {
    "<=": operator.le, ">=": operator.ge, "<": operator.lt, ">": operator.gt,
    "!=": operator.ne}
COMPARISON = re.compile(r"<=|>=|!=|<|>")
PLACEHOLDER = re.compile(r"\{([^{}]+)\}")
"""``{L}`` in a statement: the given's value, with its unit."""


@dataclass(frozen=True)
class SteppedRange:
    """A value ``low + i*step`` up to ``high``, each equally likely (all in ``unit``)."""

    key: str
    unit: str
    low: float
    high: float
    step: float
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class RoundedRange:
    """A value uniform in ``[low, high]`` rounded to ``sig_figs`` significant figures."""

    key: str
    unit: str
    low: float
    high: float
    sig_figs: int
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Choices:
    """One of ``values``, each equally likely."""

    key: str
    unit: str
    values: tuple[float, ...]
    where: Location = field(default_factory=Location, compare=False)


@dataclass(frozen=True)
class Integers:
    """An integer from ``low`` to ``high`` inclusive."""

    key: str
    unit: str
    low: int
    high: int
    where: Location = field(default_factory=Location, compare=False)


Draw = Union[SteppedRange, RoundedRange, Choices, Integers]


@dataclass(frozen=True)
class Requirement:
    """``left op right`` over the givens (SI values): a draw that fails it is drawn again."""

    text: str
    left: Node
    op: str
    right: Node
    where: Location = field(default_factory=Location, compare=False)

    def holds(self, values: Mapping[str, float]) -> bool:
        """Whether the condition holds for the givens' SI ``values`` (keyed like ``theta'``).

        >>> from mechgrade.spec.variants import read_requirement
        >>> r = read_requirement("L2 > 2*L1", Location())
        >>> r.holds({"L1": 1.0, "L2": 2.5}), r.holds({"L1": 1.0, "L2": 1.5})
        (True, False)
        """
        def resolve(node):
            if isinstance(node, Name) and node.id == "pi":
                return math.pi
            return values[to_text(node)]

        def call(func, _args):
            raise SpecError(f"expected arithmetic of givens in a condition, found {func}()",
                            where=self.where)

        try:
            left = fold(self.left, number=lambda n: n.value, resolve=resolve, call=call)
            right = fold(self.right, number=lambda n: n.value, resolve=resolve, call=call)
        except (ZeroDivisionError, OverflowError, ValueError):
            return False
        return bool(COMPARISONS[self.op](left, right))

    @property
    def names(self) -> set[str]:
        return {to_text(n) for side in (self.left, self.right) for n in walk(side)
                if isinstance(n, (Name, Prime)) and not (isinstance(n, Name) and n.id == "pi")}


@dataclass(frozen=True)
class Limits:
    """The declared range of a given, a solved quantity or an objective (``name``), in
    ``unit``; either end may be open (``None``)."""

    name: str
    unit: str
    low: float | None
    high: float | None
    where: Location = field(default_factory=Location, compare=False)

    def contains(self, value: float) -> bool:
        """Whether ``value`` (in ``unit``) lies in the bound, ends included.

        >>> Limits("x", "m", 0.0, None).contains(-1.0)
        False
        """
        return ((self.low is None or value >= self.low)
                and (self.high is None or value <= self.high))


@dataclass(frozen=True)
class Variants:
    """The ``variants:`` section: draws, conditions and bounds."""

    draws: tuple[Draw, ...]
    requires: tuple[Requirement, ...] = ()
    bounds: tuple[Limits, ...] = ()
    where: Location = field(default_factory=Location, compare=False)
