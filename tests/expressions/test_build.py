"""Trees become sympy objects by construction."""

from __future__ import annotations

import pytest
import sympy as sp

from mechgrade.errors import ExpressionError
from mechgrade.expressions.build import to_sympy
from mechgrade.expressions.syntax import parse

x, L = sp.symbols("x L", real=True)
TABLE = {"x": x, "L": L}


def build(text):
    return to_sympy(parse(text), lambda n: TABLE[n.id])


def test_arithmetic_and_functions():
    assert build("2 L sin(x)^2 + pi") == 2 * L * sp.sin(x) ** 2 + sp.pi
    assert build("abs(x)/sqrt(L)") == sp.Abs(x) / sp.sqrt(L)
    assert build("0.5 x") == sp.Float(0.5) * x


def test_unknown_name_is_an_expression_error():
    with pytest.raises(ExpressionError, match="expected a known name, found 'y'"):
        build("y + 1")


def test_calls_outside_the_math_table_need_a_handler():
    node = parse("vel(x, L)", functions=["vel"])
    with pytest.raises(ExpressionError, match="expected a math function, found 'vel"):
        to_sympy(node, lambda n: TABLE[n.id])
    def add(func, args):
        return sum(to_sympy(a, lambda n: TABLE[n.id]) for a in args)

    assert to_sympy(node, lambda n: TABLE[n.id], add) == x + L
