"""Answers per second: mechgrade's judging (in-process and in the bounded worker) next to a naive
``sympy.simplify(a - b) == 0`` checker, on numeric and symbolic answers.

The sides are paired (bench/paired.py): each round judges ``count`` answers on every side, the
order of the sides turning round by round, and each ratio is the median of the per-round
ratios. Every call gets answers no earlier call has seen (numbers drawn anew, symbolic forms
written ``k*(form)/k`` with a ``k`` of their own), so no side answers from a cache.

Run: ``PYTHONPATH=src python bench/grading_throughput.py [count] [rounds]`` (default 200, 5)
"""

from __future__ import annotations

import itertools
import random
import sys

import sympy

from mechgrade.expressions.build import to_sympy
from mechgrade.expressions.syntax import parse
from mechgrade.grade.compare import assess
from mechgrade.grade.policy import GradingPolicy
from mechgrade.grade.sandbox import Sandbox
from mechgrade.solve.result import ObjectiveResult
from paired import against, in_rounds, per_item_ms  # bench/paired.py, beside this script

ACC = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51)
SYM = ObjectiveResult("a", "symbolic", "m/s^2", expr="L*sqrt(thetad**4 + thetadd**2)",
                      symbols=("L", "thetad", "thetadd"), symbol_units=("m", "rad/s", "rad/s^2"))
SYMBOLIC_FORMS = ["L*sqrt(thetad**4 + thetadd**2)", "sqrt(L^2 thetad^4 + L^2 thetadd^2)",
                  "L*(thetad^4 + thetadd^2)^(1/2)", "L*thetad^2", "2*L*sqrt(thetad^4+thetadd^2)",
                  "L*sqrt((thetad^2)^2 + thetadd^2)", "L*(thetad^2 + thetadd)",
                  "-L*sqrt(thetad^4 + thetadd^2)"]


_FRESH = itertools.count(2)
"""Every multiplier ``k`` a symbolic answer is written with: none is used twice."""
_SEEN: set[str] = set()
"""Every numeric answer written so far: none is written twice."""


def numeric_answers(count: int, seed: int) -> list[str]:
    rng = random.Random(seed)
    units = [("ft/s^2", 1.0), ("m/s^2", 0.3048), ("in/s^2", 12.0)]
    out: list[str] = []
    while len(out) < count:
        unit, factor = rng.choice(units)
        text = f"{98.51 * factor * rng.uniform(0.97, 1.03):.6g} {unit}"
        if text not in _SEEN:
            _SEEN.add(text)
            out.append(text)
    return out


def symbolic_answers(count: int, seed: int) -> list[str]:
    rng = random.Random(seed)
    return [f"{k}*({rng.choice(SYMBOLIC_FORMS)})/{k}" for _, k in zip(range(count), _FRESH)]


def naive_numeric(text: str) -> bool:
    number = float(text.split()[0])
    return sympy.simplify(sympy.Float(number) - sympy.Float(98.51)) == 0


_NAIVE_SYMBOLS = {s: sympy.Symbol(s, real=True) for s in SYM.symbols}
_NAIVE_REFERENCE = to_sympy(parse(SYM.expr), lambda n: _NAIVE_SYMBOLS[n.id])


def naive_symbolic(text: str) -> bool:
    student = to_sympy(parse(text), lambda n: _NAIVE_SYMBOLS[n.id])
    return sympy.simplify(student - _NAIVE_REFERENCE) == 0


def main(count: int = 200, rounds: int = 5) -> None:
    policy = GradingPolicy()
    with Sandbox(seconds=10) as box:
        box.assess("98.5 ft/s^2", ACC, policy)  # start the worker outside the timing
        for label, result, draw, naive in (("numeric", ACC, numeric_answers, naive_numeric),
                                           ("symbolic", SYM, symbolic_answers, naive_symbolic)):
            assess(draw(1, -1)[0], result, policy)  # first calls outside the timing
            naive(draw(1, -1)[0])
            sides = [("naive sympy.simplify(a - b) == 0", lambda b, f=naive: [f(t) for t in b]),
                     ("mechgrade assess (in-process)",
                      lambda b, r=result: [assess(t, r, policy) for t in b]),
                     ("mechgrade Sandbox (one worker)",
                      lambda b, r=result: [box.assess(t, r, policy) for t in b])]
            runs = in_rounds(sides, draw, count, rounds)
            print(f"{label} answers: {rounds} rounds of {count} a side, each side first in turn")
            base = runs[sides[0][0]]
            for side, _ in sides:
                line = f"  {side:<34} {1000 / per_item_ms(runs[side], count):10.1f} answers/s"
                if side != sides[0][0]:
                    line += f"  naive/this {against(base, runs[side])}"
                print(line)
        print(f"worker restarts: {box.restarts}")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
