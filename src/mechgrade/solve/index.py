"""Where each quantity of a problem sits in the state vectors the numeric solver works on.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> from mechgrade.mechanics import derive
>>> problem = load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
>>> index = SymbolIndex.of(derive(problem))
>>> index.spelling(index.rates(1)[0]), index.level_of(index.rates(2)[0])
("theta'", 2)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Callable

from ..spec.model import TIME

if TYPE_CHECKING:
    import sympy as sp

    from ..mechanics import Kinematics


@dataclass(frozen=True)
class SymbolIndex:
    """The state vector's layout: coordinates, parameters and time (the configuration), then
    the first and second rates of the coordinates. ``names[i]`` is the spelling in a spec
    (``theta``, ``theta'``, ``t``) of the quantity at position ``i``; ``symbols[i]`` its plain
    sympy symbol, taken from the kinematics ``source()`` gives when first read (a plan read
    from the disk cache is solved without them)."""

    names: tuple[str, ...]
    coordinates: tuple[str, ...]
    parameters: tuple[str, ...]
    source: Callable[[], Kinematics] = field(compare=False, repr=False)

    @classmethod
    def of(cls, k: Kinematics) -> "SymbolIndex":
        params = tuple(name for name, _ in k.parameters)
        names = (k.coordinates + params + (TIME,) + tuple(c + "'" for c in k.coordinates)
                 + tuple(c + "''" for c in k.coordinates))
        return cls(names, k.coordinates, params, source=lambda: k)

    @cached_property
    def symbols(self) -> tuple[sp.Symbol, ...]:
        k = self.source()
        return k.q + tuple(s for _, s in k.parameters) + (k.time,) + k.qd + k.qdd

    @property
    def n(self) -> int:
        """How many coordinates."""
        return len(self.coordinates)

    @property
    def size(self) -> int:
        return len(self.names)

    @property
    def config(self) -> range:
        """Positions of the position-level quantities: coordinates, parameters, time."""
        return range(self.n + len(self.parameters) + 1)

    @property
    def time(self) -> int:
        return self.n + len(self.parameters)

    def rates(self, level: int) -> range:
        """Positions of the first (``level`` 1) or second (2) rates."""
        start = len(self.config) + (level - 1) * self.n
        return range(start, start + self.n)

    def level_of(self, i: int) -> int:
        return 0 if i in self.config else 1 if i in self.rates(1) else 2

    def unknowns(self, level: int) -> range:
        """The quantities solved at ``level``."""
        return self.config if level == 0 else self.rates(level)

    def is_parameter(self, i: int) -> bool:
        return self.n <= i < self.time

    def coordinate_of(self, i: int) -> str | None:
        """The coordinate a coordinate or rate position belongs to (``None`` otherwise)."""
        if i < self.n:
            return self.coordinates[i]
        if i >= len(self.config):
            return self.coordinates[(i - len(self.config)) % self.n]
        return None

    def spelling(self, i: int) -> str:
        return self.names[i]

    def position(self, name: str) -> int:
        return self.names.index(name)
