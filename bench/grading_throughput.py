"""Answers per second: mechgrade's judging (in-process and in the bounded worker) next to a naive
``sympy.simplify(a - b) == 0`` checker, on the same numeric and symbolic answers.

Run: ``PYTHONPATH=src python bench/grading_throughput.py [count]``
"""

from __future__ import annotations

import random
import sys
import time

import sympy

from mechgrade.expressions.build import to_sympy
from mechgrade.expressions.syntax import parse
from mechgrade.grade.compare import assess
from mechgrade.grade.policy import GradingPolicy
from mechgrade.grade.sandbox import Sandbox
from mechgrade.solve.result import ObjectiveResult

ACC = ObjectiveResult("acc", "scalar", "ft/s^2", 98.51)
SYM = ObjectiveResult("a", "symbolic", "m/s^2", expr="L*sqrt(thetad**4 + thetadd**2)",
                      symbols=("L", "thetad", "thetadd"), symbol_units=("m", "rad/s", "rad/s^2"))
SYMBOLIC_FORMS = ["L*sqrt(thetad**4 + thetadd**2)", "sqrt(L^2 thetad^4 + L^2 thetadd^2)",
                  "L*(thetad^4 + thetadd^2)^(1/2)", "L*thetad^2", "2*L*sqrt(thetad^4+thetadd^2)",
                  "L*sqrt((thetad^2)^2 + thetadd^2)", "L*(thetad^2 + thetadd)",
                  "-L*sqrt(thetad^4 + thetadd^2)"]


def numeric_answers(count: int) -> list[str]:
    rng = random.Random(1)
    units = [("ft/s^2", 1.0), ("m/s^2", 0.3048), ("in/s^2", 12.0)]
    out = []
    for _ in range(count):
        unit, factor = rng.choice(units)
        out.append(f"{98.51 * factor * rng.uniform(0.97, 1.03):.4g} {unit}")
    return out


def symbolic_answers(count: int) -> list[str]:
    rng = random.Random(2)
    return [rng.choice(SYMBOLIC_FORMS) for _ in range(count)]


def naive_numeric(text: str) -> bool:
    number = float(text.split()[0])
    return sympy.simplify(sympy.Float(number) - sympy.Float(98.51)) == 0


_NAIVE_SYMBOLS = {s: sympy.Symbol(s, real=True) for s in SYM.symbols}
_NAIVE_REFERENCE = to_sympy(parse(SYM.expr), lambda n: _NAIVE_SYMBOLS[n.id])


def naive_symbolic(text: str) -> bool:
    student = to_sympy(parse(text), lambda n: _NAIVE_SYMBOLS[n.id])
    return sympy.simplify(student - _NAIVE_REFERENCE) == 0


def rate(label: str, func, answers: list[str]) -> None:
    start = time.perf_counter()
    for text in answers:
        func(text)
    elapsed = time.perf_counter() - start
    print(f"  {label:<34} {len(answers) / elapsed:10.1f} answers/s  ({len(answers)} in "
          f"{elapsed:.2f} s)")


def main(count: int) -> None:
    policy = GradingPolicy()
    numeric, symbolic = numeric_answers(count), symbolic_answers(count)
    naive_count = max(10, count // 10)
    with Sandbox(seconds=10) as box:
        box.assess("98.5 ft/s^2", ACC, policy)  # start the worker outside the timing
        for label, result, answers, naive in (("numeric", ACC, numeric, naive_numeric),
                                              ("symbolic", SYM, symbolic, naive_symbolic)):
            print(f"{label} answers:")
            rate("mechgrade assess (in-process)", lambda t, result=result: assess(t, result, policy), answers)
            rate("mechgrade Sandbox (one worker)", lambda t, result=result: box.assess(t, result, policy),
                 answers)
            rate("naive sympy.simplify(a - b) == 0", naive, answers[:naive_count])
        print(f"worker restarts: {box.restarts}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 2000)
