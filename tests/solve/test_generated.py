"""Functions read back from the disk cache are compiled only when they are one bounded function
of numbers, as sympy's numpy printer writes them: nothing that runs other code, hangs, exhausts
memory or gives a complex number (issue 18), whoever wrote the source."""

from __future__ import annotations

import re

import pytest

from mechgrade.solve import generated


@pytest.mark.parametrize("source, why", [
    ("import os\n", "expected one function definition"),
    ("def f(x):\n    return x.__class__\n", "Attribute is not allowed"),
    ("def f(x):\n    return open('f')\n", "only calls of numpy functions are allowed"),
    ("def f(x):\n    return y\n", "name 'y' is not allowed"),
    ("def f(x):\n    return 'text'\n", "only real numeric constants are allowed"),
    ("def f(x):\n    return [i for i in x]\n", "is not allowed"),
    ("def f(x):\n    x[0] = 1\n    return x\n", "statement Assign is not allowed"),
    ("def f(x):\n    return sin(x)(x)\n", "only calls of numpy functions are allowed"),
    ("def f(x, *a):\n    return x\n", "plain positional arguments"),
    ("def f(x):\n    pass\n", "end in a return"),
])
def test_generated_source_other_than_numpy_arithmetic_is_refused(source, why):
    with pytest.raises(generated.UnsafeSource, match=why):
        generated.numpy_function(source)


@pytest.mark.parametrize("source, why", [
    ("def f(x):\n    return 10**10**10\n", "a constant larger than"),
    ("def f(x):\n    x0 = 9**9\n    return x0**x0*x\n", "a constant larger than"),
    ("def f(x):\n    return x*(2**40*2**40)\n", "a constant larger than"),
    ("def f(x):\n    return 10.0**400*x\n", "cannot be worked out"),
    ("def f(x):\n    return x*(1/(1 - 1))\n", "cannot be worked out"),
    ("def f(x):\n    return zeros((20000, 20000))\n", "arrays of at most 10000 elements"),
    ("def f(x):\n    return array([[x]*100000000])\n", "List is not allowed"),
    ("def f(x):\n    return sin([x, x])*cos([[x], [x]])\n", "List is not allowed"),
    ("def f(x):\n    return array([[x]]) + x\n", "arrays are allowed only as what"),
    ("def f(x):\n    x0 = zeros((100, 100))\n    return x0\n", "arrays are allowed only as"),
    ("def f(x):\n    return array([[x, x], [x]])\n", "one length"),
    ("def f(x):\n    return " + "+".join(["x"] * 100_000) + "\n", "at most 100000 characters"),
    ("def f(x):\n    return " + "+".join(["x"] * 1000) + "\n", "nested at most 200 deep"),
    ("def f(x):\n    return " + "-" * 10_000 + "x\n", "expected the source of a function"),
    ("def f(x):\n    return 1j*x\n", "only real numeric constants"),
    ("def f(x):\n    return (-8.0)**(1/3)*x\n", "only real numeric constants"),
    ("def f(x):\n    return array([[nan]])\n", "name 'nan' is not allowed"),
    ("def f(x):\n    return inf*x\n", "name 'inf' is not allowed"),
    ("def f(x):\n    return 1e308*10*x\n", "only finite constants"),
    ("def f(x):\n    return sin(x, x)\n", "sin with its own number of arguments"),
    ("def f(x):\n    return select([x > 0], [x, x])\n", "two lists of one length"),
    ("def f(x):\n    sin = x\n    return sin\n", "name 'sin' may not be bound"),
])
def test_generated_source_that_could_hang_exhaust_memory_or_mislead_is_refused(source, why):
    with pytest.raises(generated.UnsafeSource, match=re.escape(why)):
        generated.numpy_function(source)


def test_what_sympy_prints_for_a_piecewise_is_accepted():
    f = generated.numpy_function("def f(x):\n    return array([[(select([less(x, 0),equal(x, 0),"
                             "True], [0,1/2,1], default=nan))], [sign(x)]])\n")
    assert f(-2.0).tolist() == [[0.0], [-1.0]] and f(0.0).tolist() == [[0.5], [0.0]]


def test_a_symbol_may_shadow_a_numpy_constant_but_not_a_function():
    # a coefficient of restitution named e
    f = generated.numpy_function("def f(e, x):\n    return e*x + pi\n")
    assert f(0.5, 2.0) == pytest.approx(1 + 3.141592653589793)
    with pytest.raises(generated.UnsafeSource, match="name 'cos' may not be bound"):
        generated.numpy_function("def f(cos, x):\n    return cos(x)\n")


@pytest.mark.parametrize("power", [2, 3, -2, -3, 1.5, "1/3", "x"])
def test_a_compiled_function_gives_numbers_the_bits_it_gives_an_array(power):
    """``**`` on numbers is the C library's pow, which differs from numpy's loop in the last
    bit now and then: a single solve (numbers) and a class (arrays) must agree."""
    import numpy as np
    import sympy as sp

    x, y = sp.symbols("x y")
    exponent = x if power == "x" else sp.sympify(power)
    f = generated.lambdified([x, y], (y + x) ** exponent * y ** exponent / (1 + x ** 2))
    values = np.random.default_rng(0).uniform(0.5, 40.0, (2, 2000))
    arrays = f(values[0], values[1])
    numbers = [f(a, b) for a, b in values.T.tolist()]
    assert np.array_equal(arrays, numbers)
