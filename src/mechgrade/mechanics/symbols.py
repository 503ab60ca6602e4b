"""Plain symbols of a problem: coordinates as ``dynamicsymbols`` while building, and as plain
``theta``, ``thetad``, ``thetadd`` symbols in everything handed on.

>>> from mechgrade.spec import load_problem
>>> from mechgrade.resources import shipped_dir
>>> s = Symbols(load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"))
>>> s.q, s.qd
((theta,), (thetad,))
"""

from __future__ import annotations

import random

import sympy as sp
from sympy.physics.vector import Vector, dynamicsymbols

from ..spec.model import Problem

TIME_SYMBOL = dynamicsymbols._t


class Symbols:
    """The sympy symbols of one problem's coordinates, rates and parameters."""

    def __init__(self, problem: Problem):
        t = TIME_SYMBOL
        self.dyn = {c.name: dynamicsymbols(c.name, real=True) for c in problem.coordinates}
        self.params = {p.name: sp.Symbol(p.name, positive=True) if p.positive
                       else sp.Symbol(p.name, real=True) for p in problem.parameters}
        names = [c.name for c in problem.coordinates]
        self.q = tuple(sp.Symbol(n, real=True) for n in names)
        self.qd = tuple(sp.Symbol(n + "d", real=True) for n in names)
        self.qdd = tuple(sp.Symbol(n + "dd", real=True) for n in names)
        self._plain = {}
        for name, qs, qds, qdds in zip(names, self.q, self.qd, self.qdd):
            f = self.dyn[name]
            self._plain[f.diff(t, 2)] = qdds
            self._plain[f.diff(t)] = qds
            self._plain[f] = qs

    def plain(self, expr):
        """Rewrite dynamicsymbols and their derivatives as plain symbols (derivatives first)."""
        if isinstance(expr, Vector):
            return expr.applyfunc(lambda e: as_expr(e).xreplace(self._plain))
        return as_expr(expr).xreplace(self._plain)


def as_expr(value) -> sp.Expr:
    """A sympy expression for a sympy object or a plain Python number (never text)."""
    if isinstance(value, bool) or isinstance(value, str):
        raise TypeError(f"expected a number or sympy expression, found {value!r}")
    if isinstance(value, int):
        return sp.Integer(value)
    if isinstance(value, float):
        return sp.Float(value)
    return value




def identically_zero(expr: sp.Expr) -> bool:
    """Whether ``expr`` is zero for all values (checked at random points, then exactly)."""
    expr = as_expr(expr)
    if expr == 0:
        return True
    symbols = sorted(expr.free_symbols, key=str)
    rng = random.Random(7)
    for _ in range(3):
        point = {s: rng.uniform(0.3, 1.7) for s in symbols}
        value = complex(as_expr(expr.xreplace(point)).evalf())
        if abs(value) > 1e-9:
            return False
    return True


def without_deltas(expr):
    """``expr`` (or a matrix of them) with ``DiracDelta`` terms dropped: ``d/dt sign(u) = 2
    DiracDelta(u) u'`` (a length ``|u|`` differentiated twice, as in a massless junction's
    balance) is zero wherever the direction ``u/|u|`` is defined.

    >>> u = sp.Symbol("u", real=True)
    >>> without_deltas(sp.diff(sp.Abs(u), u, 2) + u)
    u
    """
    return expr.replace(lambda e: isinstance(e, sp.DiracDelta), lambda *_: sp.Integer(0))
