"""One inference of kinds and dimensions, worded for the spec's author and for the student."""

from __future__ import annotations

import re

import pytest

from mechgrade.expressions.dimensions import DimensionError, Kind, Type, infer
from mechgrade.expressions.syntax import parse
from mechgrade.grade.compare import DimensionMismatch, expression_dimension
from mechgrade.units import dimension

UNITS = {"L": "m", "thetad": "rad/s", "theta": "rad", "t": "s"}


def typed(text: str) -> Type:
    return infer(parse(text, attributes=True),
                 lambda n: Type(Kind.VECTOR, dimension("")) if not hasattr(n, "id")
                 else Type(Kind.SCALAR, dimension(UNITS[n.id])))


@pytest.mark.parametrize("text, unit", [
    ("L*thetad^2", "m/s^2"),
    ("sqrt(L^2*thetad^4)", "m/s^2"),
    ("L*sin(theta)", "m"),
    ("abs(L)/t", "m/s"),
    ("sign(L)*thetad", "1/s"),  # the sign of any quantity is a pure number
    ("atan2(L, 2*L)", ""),
    ("L + 0", "m"),  # zero adds to anything
    ("theta^theta*t", "s"),  # a pure number to any pure-number power
])
def test_consistent_expressions_have_their_dimension(text, unit):
    assert typed(text).dim == dimension(unit)
    assert expression_dimension(parse(text), UNITS) == dimension(unit)


@pytest.mark.parametrize("text, author, student", [
    ("L + thetad", "cannot add a length ([length]) and an angular velocity or rate "
     "(1/[time]) in 'L+thetad'", "adds a length ([length]) to an angular velocity or rate "
     "(1/[time])"),
    ("L - t", "cannot add a length ([length]) and a time ([time]) in 'L-t'",
     "subtracts a length ([length]) and a time ([time])"),
    ("sin(L)", "sin(...) needs a pure number or angle, found a length ([length])",
     "takes sin of a length ([length]), which needs a pure number"),
    ("atan2(L, t)", "atan2(y, x) needs y and x in the same dimension",
     "compares quantities of different dimensions in atan2"),
    ("theta^L", "expected a pure-number exponent in 'theta**L'",
     "raises a quantity with units to a variable power"),
    ("L^theta", "a quantity with units needs a constant exponent in 'L**theta'",
     "raises a quantity with units to a variable power"),
    ("L/0", "expected a nonzero scalar divisor in 'L/0'", "divides by zero"),
])
def test_one_rule_two_wordings(text, author, student):
    with pytest.raises(DimensionError) as info:
        typed(text)
    assert (info.value.message, info.value.student) == (author, student)
    with pytest.raises(DimensionMismatch, match=f"^{re.escape(student)}$"):
        expression_dimension(parse(text), UNITS)


@pytest.mark.parametrize("text, message", [
    ("N.x + L", "cannot add a vector and a scalar in 'N.x+L'"),
    ("N.x*N.y", "cannot multiply two vectors in 'N.x*N.y'; expected dot(u, v) or cross(u, v)"),
    ("L/N.x", "expected a nonzero scalar divisor in 'L/N.x'"),
    ("N.x^2", "cannot raise a vector to a power in 'N.x**2'"),
    ("sqrt(N.x)", "sqrt(...) takes a scalar, found a vector (use mag(v) or dot(u, v))"),
])
def test_vectors_follow_the_kind_rules(text, message):
    with pytest.raises(DimensionError) as info:
        typed(text)
    assert info.value.message == message == info.value.student


def test_vector_arithmetic_keeps_the_kind():
    assert typed("L*N.x - 0").kind == Kind.VECTOR
    assert typed("0*N.x").kind == Kind.ZERO
    assert typed("L*N.x/t") == Type(Kind.VECTOR, dimension("m/s"))


def test_a_located_dimension_error_keeps_both_wordings():
    from mechgrade.errors import Location

    with pytest.raises(DimensionError) as info:
        typed("L - t")
    located = info.value.located(Location("p.yaml", 3, 4, "find"))
    assert str(located) == "p.yaml:3:4: find: cannot add a length ([length]) and a time " \
        "([time]) in 'L-t'"
    assert located.student == "subtracts a length ([length]) and a time ([time])"


def test_kept_descriptions_follow_pints_order_and_powers():
    from mechgrade.expressions.dimensions import described
    from mechgrade.units import describe_dimension, dimension

    length = dimension("m")
    for dim in (dimension("N"), dimension("lbf"), dimension("N") / dimension("s"),
                dimension("lbf") / dimension("s"), length * length, length ** 0.5, dimension("")):
        assert described(dim) == describe_dimension(dim)
        assert described(dim) == describe_dimension(dim)  # and again, from the kept text
