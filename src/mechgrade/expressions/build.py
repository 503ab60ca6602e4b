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
from .syntax import MATH_FUNCTIONS, Attr, Bin, Call, Name, Node, Num, Prime, Unary

SYMPY_FUNCTIONS: dict[str, Callable] = {
    "sin": sympy.sin, "cos": sympy.cos, "tan": sympy.tan, "cot": sympy.cot,
    "sec": sympy.sec, "csc": sympy.csc, "asin": sympy.asin, "acos": sympy.acos,
    "atan": sympy.atan, "atan2": sympy.atan2, "sinh": sympy.sinh, "cosh": sympy.cosh,
    "tanh": sympy.tanh, "sqrt": sympy.sqrt, "exp": sympy.exp, "log": sympy.log,
    "abs": sympy.Abs, "sign": sympy.sign,
}
assert {canonical for canonical, _ in MATH_FUNCTIONS.values()} == set(SYMPY_FUNCTIONS)


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
    if isinstance(node, Num):
        return number(node)
    if isinstance(node, Name) and node.id == "pi":
        return sympy.pi
    if isinstance(node, (Name, Prime, Attr)):
        try:
            return resolve(node)
        except KeyError:
            from .syntax import to_text
            raise ExpressionError(f"expected a known name, found '{to_text(node)}'") from None
    if isinstance(node, Unary):
        return -to_sympy(node.operand, resolve, call)
    if isinstance(node, Bin):
        left = to_sympy(node.left, resolve, call)
        right = to_sympy(node.right, resolve, call)
        if node.op == "+":
            return left + right
        if node.op == "-":
            return left - right
        if node.op == "*":
            return left * right
        if node.op == "/":
            return left / right
        return left ** right
    if isinstance(node, Call):
        if node.func in SYMPY_FUNCTIONS:
            return SYMPY_FUNCTIONS[node.func](*(to_sympy(a, resolve, call) for a in node.args))
        if call is None:
            raise ExpressionError(f"expected a math function, found '{node.func}(...)'")
        return call(node.func, node.args)
    raise ExpressionError(f"expected an expression, found {node!r}")  # pragma: no cover
