"""Numeric values of parsed expressions at sample points (numpy, never sympy).

>>> import numpy as np
>>> evaluate(reference_tree("L*sqrt(thetad**4)", ("L", "thetad")), {"L": np.array([2.0]), "thetad": np.array([-1.0])})
array([2.])
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..errors import ExpressionError
from . import syntax
from .excerpt import excerpt
from .functions import numpy_functions
from .syntax import Bin, Call, Name, Node, Num, Unary

def evaluate(node: Node, env: dict[str, np.ndarray]) -> np.ndarray:
    """Values of a checked tree at sample points (NaN where undefined); never calls sympy.

    The tree is bounded by the reader (size, depth, constant exponents), and numpy arithmetic
    overflows to ``inf`` rather than hanging, so this is safe on any readable answer.

    A constant expression gives the same value at every point (one value per sample point,
    always).

    >>> import numpy as np
    >>> evaluate(syntax.parse("2 L^2"), {"L": np.array([1.0, 3.0])})
    array([ 2., 18.])
    >>> evaluate(syntax.parse("1"), {"L": np.array([1.0, 3.0])})
    array([1., 1.])
    """
    count = len(next(iter(env.values()))) if env else 1
    with np.errstate(all="ignore"):
        values = _eval(node, env)
        if isinstance(values, np.ndarray) and values.shape == (count,) \
                and values.dtype == np.float64 and values.flags.owndata \
                and not any(values is given for given in env.values()):
            return values  # computed here, so already the caller's own copy
        return np.broadcast_to(np.asarray(values, dtype=float), (count,)).copy()


def _eval(node: Node, env: dict[str, np.ndarray]):
    """:func:`evaluate`'s walk: :func:`~mechgrade.expressions.syntax.fold`'s, with its leaves,
    calls and numpy's division and powers (inf or nan where Python would raise or go complex)
    written in, as judging an answer is mostly this walk (the commonest kinds first, told by
    their exact type)."""
    if type(node) is Bin:
        a, b = _eval(node.left, env), _eval(node.right, env)
        op = node.op
        if op == "**":
            return np.power(np.asarray(a, dtype=float), b)
        if op == "/":
            return np.divide(np.asarray(a, dtype=float), b)
        return syntax.PYTHON_OPERATORS[op](a, b)
    if type(node) is Name:
        if node.id == "pi":
            return math.pi
        if node.id in env:
            return env[node.id]
    elif type(node) is Num:
        return float(node.text)
    elif type(node) is Call:
        return numpy_functions()[node.func](*(np.asarray(_eval(a, env), dtype=float)
                                              for a in node.args))
    elif type(node) is Unary:
        return -_eval(node.operand, env)
    raise ExpressionError(f"expected an expression in the problem's symbols, found "
                          f"{excerpt(syntax.to_text(node))}")


@lru_cache(maxsize=256)
def reference_tree(expr: str, symbols: tuple[str, ...]) -> Node:
    """A solver-printed expression (sympy's text) read as a tree in ``symbols``."""
    node = syntax.parse(expr, attributes=False)
    unknown = syntax.names(node) - set(symbols) - {"pi", "E"}
    if unknown:
        raise ExpressionError(f"the reference uses names that are not its symbols: "
                              f"{', '.join(sorted(unknown))}")
    return node
