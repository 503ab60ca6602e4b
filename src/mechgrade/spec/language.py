"""The objective language: the functions of points, frames, vectors, bodies and loads usable
in spec expressions, with their types.

Each function fixes its argument kinds and its result's kind and dimension, so a spec can be
checked (names, kinds, dimensions) before anything is solved. The entries are those of the
language's one table (:mod:`mechgrade.expressions.functions`); the mechanics core implements
exactly these names.

>>> sorted(FUNCTIONS)[:4]
['acc', 'acc_n', 'acc_t', 'after']
>>> FUNCTIONS["vel"].args == ("point", "frame")
True
"""

from __future__ import annotations

from ..expressions.functions import OBJECTIVE_FUNCTIONS, ObjectiveFunction

FUNCTIONS: dict[str, ObjectiveFunction] = OBJECTIVE_FUNCTIONS
