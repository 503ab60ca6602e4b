"""Fuzz the answer reader and the comparison in-process: generated answer texts (mixes of digits,
units, operators, unicode, control characters, huge exponents, long strings) through
``read_answer`` and ``assess``, for scalar, vector, planar-rotation and symbolic objectives.

Prints the rate (answers per second), the count of exceptions other than ``AnswerError`` (must
be 0), the longest reason, and the slowest answer's time and an excerpt of its text.

Run: ``PYTHONPATH=src python bench/answer_fuzz.py [count] [seed]`` (default 100000, seed 7).
"""

from __future__ import annotations

import random
import sys
import time
import traceback

from mechgrade.errors import AnswerError
from mechgrade.expressions.excerpt import excerpt
from mechgrade.grade.answers import read_answer
from mechgrade.grade.compare import assess
from mechgrade.solve.result import ObjectiveResult

OBJECTIVES = (
    ObjectiveResult("acc", "scalar", "ft/s^2", 98.51),
    ObjectiveResult("a_P", "vector", "ft/s^2", (-66.0, -40.0, 0.0), frame="N"),
    ObjectiveResult("w", "vector", "rad/s", (0.0, 0.0, -0.5), frame="N"),
    ObjectiveResult("q", "scalar", "deg", 30.0),
    ObjectiveResult("n", "scalar", "", 0.0, abs=0.01),
    ObjectiveResult("a", "symbolic", "m/s^2", expr="L*sqrt(thetad**4 + thetadd**2)",
                    symbols=("L", "thetad", "thetadd"), symbol_units=("m", "rad/s", "rad/s^2")),
    ObjectiveResult("x", "symbolic", "m", expr="Abs(x) + E", symbols=("x", "E", "j"),
                    symbol_units=("m", "m", "m")),
)

PIECES = (
    # numbers
    "98.5", "-66", "1 000", "3 002.28", "0.00", ".5", "4.9e1", "9.85e1.5", "98..5", "1e",
    "1e999", "1e-999", "4.9 x 10^1", "2E+3", "3j", "12 345", "0", "-0", "+", "-", "- -",
    # units
    "ft/s^2", "m/s²", "ft//s^2", "fts^-2", "ft/s-2", "*ft", "g0", "g_0", "°C", "degC", "K", "e",
    "rad/s", "rpm", "deg", "°", "kg m²/s²", "N*m", "Nm", "m s-2", "[ft/s^2]", "cw", "ccw",
    # vectors and expressions
    "i", "j", "k", "î", "N.x", "Y_A", "(", ")", "<", ">", "[", "]", ",", "(-66, -40)",
    "sqrt(2)/2", "pi", "π", "θ̇", "theta''", "L", "thetad", "x", "E", "exp(", "exp(exp(exp(100)))",
    "sqrt(-2)", "1/(R-r)", "abs(x)", "^", "**", "*", "/", "9**9**9", "log(0)", "atan2(1, 2)",
    "a =", "=", "#", "__import__('os')", "lambda: 0", "'", '"',
    # forms read as students type them (issue 18)
    "12,5", "1,250", "(-12.00)", "-(0.05)", "at", "126.87°", "5 m/s at 126.87°", "√", "√2gh",
    "2π√(L/g)", "e^(-ζωt)", "ζ", "ω", "2gh", "3g/2L", "v^2/2g", "sin(30°)", "sin(30)", "dpt",
    "G", "gauss", "2 × L",
    # unicode, whitespace and control characters
    " ", "  ", "\t", "\n", "\r\n", "\u2028", "\u2029", "\x00", "\x1a", "\x85", "\u00a0", "\u2009",
    "\u202f", "−", "–", "×", "·", "½", "\ufffd", "\U0001f600", "ﬁ", "٣", "𝟗",
)


def generated(count: int, seed: int):
    """``count`` answer texts; deterministic for a seed (no hypothesis, no files)."""
    rng = random.Random(seed)
    for index in range(count):
        roll = rng.random()
        if roll < 0.6:
            parts = [rng.choice(PIECES) for _ in range(rng.randint(1, 8))]
            text = rng.choice(("", " ")).join(parts)
        elif roll < 0.8:
            text = "".join(chr(rng.randint(0, 0x2FFF)) for _ in range(rng.randint(0, 40)))
        elif roll < 0.9:
            text = f"{rng.uniform(-1e3, 1e3):.{rng.randint(0, 8)}g}e{rng.randint(-400, 400)} " \
                   + rng.choice(PIECES)
        elif roll < 0.99:
            text = rng.choice(PIECES) * rng.randint(50, 400)
        else:
            text = rng.choice("9(-x ") * rng.randint(1_000, 100_000)
        yield index, text


def main(count: int = 100_000, seed: int = 7) -> int:
    failures: list[tuple[str, str]] = []
    slowest = (0.0, "", OBJECTIVES[0])
    longest = ""
    start = time.perf_counter()
    for index, text in generated(count, seed):
        objective = OBJECTIVES[index % len(OBJECTIVES)]
        began = time.perf_counter()
        try:
            try:
                read_answer(text, objective)
            except AnswerError as exc:
                longest = max(longest, exc.message, key=len)
            judged = assess(text, objective)
            longest = max(longest, judged.feedback, judged.diagnosis or "", key=len)
        except Exception:  # noqa: BLE001 - counting exactly these is the point
            failures.append((text, traceback.format_exc(limit=3)))
        took = time.perf_counter() - began
        if took > slowest[0]:
            slowest = (took, text, objective)
    elapsed = time.perf_counter() - start
    print(f"answers: {count} (seed {seed}) in {elapsed:.1f} s: {count / elapsed:,.0f} answers/s")
    print(f"exceptions other than AnswerError: {len(failures)}")
    print(f"longest reason: {len(longest)} characters: {longest!r}")
    again = time.perf_counter()
    assess(slowest[1], slowest[2])  # timed again: a real cost, or a one-off stall (GC)?
    again = time.perf_counter() - again
    print(f"slowest answer: {slowest[0] * 1000:.1f} ms (again: {again * 1000:.1f} ms): "
          f"{excerpt(slowest[1])} ({len(slowest[1])} characters, objective {slowest[2].id})")
    for text, trace in failures[:5]:
        print(f"--- {excerpt(text)}\n{trace}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*(int(a) for a in sys.argv[1:3])))
