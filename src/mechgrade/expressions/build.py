"""Turn a checked syntax tree into sympy objects, by construction (no ``sympify`` of text).

>>> import sympy
>>> from mechgrade.expressions.syntax import parse
>>> xd, yd = sympy.symbols("xd yd", real=True)
>>> to_sympy(parse("sqrt(xd^2 + yd^2)"), lambda n: {"xd": xd, "yd": yd}[n.id])
sqrt(xd**2 + yd**2)
"""

from __future__ import annotations

from typing import Callable

import sympy

from ..errors import ExpressionError
from .functions import sympy_functions
from .syntax import Name, Node, Num, fold, to_text

def number(node: Num) -> sympy.Expr:
    """A literal as sympy: integers exact, decimals as floats.

    >>> number(Num("3")), number(Num("0.5"))
    (3, 0.500000000000000)
    """
    text = node.text
    if all(c.isdigit() for c in text):
        return sympy.Integer(int(text))
    return sympy.Float(float(text))


def to_sympy(node: Node, resolve: Callable[[Node], object],
             call: Callable[[str, tuple], object] | None = None):
    """Build the sympy value of ``node``.

    ``resolve`` maps :class:`Name`, :class:`Prime` and :class:`Attr` nodes to values (it
    should raise :class:`KeyError` for unknown names); ``call`` handles functions outside the
    math table: it receives the function name and the argument *trees* (arguments may be
    points or frames, which only the caller knows how to read). Arithmetic uses Python
    operators, so sympy.physics vectors pass through unchanged.
    """
    def leaf(n: Node):
        if isinstance(n, Name) and n.id == "pi":
            return sympy.pi
        try:
            return resolve(n)
        except KeyError:
            raise ExpressionError(f"expected a known name, found '{to_text(n)}'") from None

    def function(func: str, args: tuple):
        implementation = sympy_functions().get(func)
        if implementation is not None:
            return implementation(*(to_sympy(a, resolve, call) for a in args))
        if call is None:
            raise ExpressionError(f"expected a math function, found '{func}(...)'")
        return call(func, args)

    return fold(node, number=number, resolve=leaf, call=function)
