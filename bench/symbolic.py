"""Symbolic answers: mechgrade's check next to the naive ``simplify(sympify(a) - sympify(b)) == 0``.

Answers to the four symbolic objectives of ``bench/scale.py`` (its answer forms, each labelled
equivalent or not by hand) are judged three ways:

* naive: sympy's ``parse_expr`` (implicit products, ``^``) of both sides, ``simplify`` of the
  difference, one answer after the other;
* mechgrade in-process: :func:`mechgrade.grade.compare.assess` of every answer;
* mechgrade through a worker per core: every answer through a :class:`SandboxPool`, in
  batches (as a grading run judges them). Its CPU time is the parent's and the workers'
  together (Linux: ``/proc``), more than in-process judging costs: the workers' parallel
  gain shows in the wall clock only.

The figures are paired (bench/paired.py): a round times each side once, on the same number
of answers, the order of the sides turning round by round, and the ratio naive / mechgrade is
taken within the round; the median of the rounds' ratios is printed (min and max show the
spread a loaded machine gives). No call sees a text an earlier call has seen: every call's
answers are written anew (``k*(form)/k`` with a ``k`` no earlier call used), so neither side
answers from a cache of an earlier call. Two sets: answers as a class writes them (the same
forms many times over within a call, as a class's submissions are judged together) and every
answer written differently. Every side also gives the ratio of CPU time, which a loaded machine
disturbs less than the wall clock.

A verdict is right when "correct" goes with an equivalent answer and any other verdict with a
wrong one. Run: ``.venv/bin/python bench/symbolic.py [count] [rounds]`` (default 200, 7).
"""

from __future__ import annotations

import argparse
import itertools
import os
import random
import time
from pathlib import Path

import sympy
from sympy.parsing.sympy_parser import (convert_xor, implicit_multiplication_application,
                                        parse_expr, standard_transformations)

from mechgrade.grade.compare import assess

from mechgrade.grade.policy import GradingPolicy
from mechgrade.grade.sandbox import SandboxPool
from mechgrade.parallel import default_jobs
from mechgrade.solve import solve
from mechgrade.spec import load_problem
from paired import against, cpu_of, in_rounds, per_item_ms  # bench/paired.py, beside this script

PROBLEMS = Path(__file__).resolve().parents[1] / "problems"

# (problem file, objective): [(answer, equivalent to the reference?)]
FORMS = {
    ("bowling_3_15_4_pendulum", "acc_mag_symbolic"): [
        ("L*sqrt(thetad**4 + thetadd**2)", True), ("L sqrt(thetad^4 + thetadd^2)", True),
        ("sqrt(L^2 thetad^4 + L^2 thetadd^2)", True), ("L*(thetad^4 + thetadd^2)^(1/2)", True),
        ("L*thetad^2", False), ("L*sqrt(thetad^2 + thetadd^2)", False),
        ("-L*sqrt(thetad^4 + thetadd^2)", False), ("L*sqrt((thetad^2)^2 + thetadd^2)", True)],
    ("bowling_3_15_2_cannonball", "speed"): [
        ("sqrt(xd^2 + yd^2)", True), ("sqrt(xd**2+yd**2)", True), ("(xd^2 + yd^2)^(1/2)", True),
        ("xd + yd", False), ("sqrt(xd^2 - yd^2)", False), ("sqrt(yd^2 + xd^2)", True),
        ("xd^2 + yd^2", False)],
    ("bowling_3_15_5_cylinder", "vB_symbolic_x"): [
        ("-xd - r*thetad*sin(theta)", True), ("-(xd + r thetad sin(theta))", True),
        ("xd + r*thetad*sin(theta)", False), ("-xd - r*thetad*cos(theta)", False),
        ("-r*thetad*sin(theta) - xd", True), ("-xd + r*thetad*sin(theta)", False)],
    ("bowling_3_15_5_cylinder", "vB_symbolic_y"): [
        ("-yd + r*thetad*cos(theta)", True), ("r thetad cos(theta) - yd", True),
        ("yd - r*thetad*cos(theta)", False), ("-yd + r*thetad*sin(theta)", False),
        ("r*thetad*cos(theta)-yd", True), ("-yd + thetad*cos(theta)", False)],
}
TRANSFORMS = standard_transformations + (implicit_multiplication_application, convert_xor)
_FRESH = itertools.count(2)
"""Every multiplier ``k`` a call writes its answers with: none is used twice."""


def references() -> dict:
    out = {}
    for name in sorted({problem for problem, _ in FORMS}):
        solution = solve(load_problem(PROBLEMS / f"{name}.yaml"))
        for problem, objective in FORMS:
            if problem == name:
                out[problem, objective] = solution.result(objective)
    return out


def forms(count: int, seed: int) -> list[tuple[tuple[str, str], str, bool]]:
    """``count`` answers as a class writes them: the same few forms, many times over."""
    rng = random.Random(seed)
    keys = list(FORMS)
    return [(key, *rng.choice(FORMS[key])) for key in (rng.choice(keys) for _ in range(count))]


def as_a_class(count: int, seed: int) -> list[tuple[tuple[str, str], str, bool]]:
    """A class's answers written with a ``k`` no earlier call used: repeats within the call."""
    k = next(_FRESH)
    return [(key, f"{k}*({text})/{k}", right) for key, text, right in forms(count, seed)]


def all_different(count: int, seed: int) -> list[tuple[tuple[str, str], str, bool]]:
    """Every answer written with its own ``k``: no repeats, within the call or across."""
    return [(key, f"{k}*({text})/{k}", right)
            for (key, text, right), k in zip(forms(count, seed), _FRESH)]


def naive_equal(text: str, reference: str) -> bool:
    a = parse_expr(text, transformations=TRANSFORMS)
    b = parse_expr(reference, transformations=TRANSFORMS)
    return sympy.simplify(a - b) == 0


def compare(title: str, refs: dict, draw, count: int, rounds: int, pool: SandboxPool) -> None:
    """``rounds`` rounds of the three sides, each on answers of its own from ``draw``."""
    policy = GradingPolicy()

    def naive(batch):
        return ["correct" if naive_equal(text, refs[key].expr) else "incorrect"
                for key, text, _ in batch]

    def in_process(batch):
        return [assess(text, refs[key], policy).verdict for key, text, _ in batch]

    def pooled(batch):
        return [a.verdict for a in pool.assess_many([(text, refs[key], policy)
                                                     for key, text, _ in batch])]

    def pool_cpu() -> float:  # the parent's and the live workers'
        return time.process_time() + cpu_of(box._process.pid for box in pool.boxes
                                            if box._process is not None)

    sides = [("naive simplify(sympify(a) - sympify(b)) == 0", naive),
             ("mechgrade in-process, one by one", in_process),
             (f"mechgrade through {len(pool.boxes)} workers, batches", pooled, pool_cpu)]
    # each side its own new answers (the same forms: one seed a round), drawn untimed
    runs = in_rounds(sides, draw, count, rounds)
    print(f"{title}: {rounds} rounds of {count} answers a side, each side first in turn")
    base = runs[sides[0][0]]
    for label, *_ in sides:
        good = sum((v == "correct") == equivalent for run in runs[label]
                   for v, (_, _, equivalent) in zip(run.out, run.batch))
        line = f"  {label:<50} {per_item_ms(runs[label], count):8.3f} ms/answer"
        if label != sides[0][0]:
            line += (f"  naive/this {against(base, runs[label])},"
                     f" CPU {against(base, runs[label], cpu=True)}")
        print(f"{line}  {good}/{count * rounds} right")


def main(count: int = 200, rounds: int = 7) -> None:
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} (1 min) at the start")
    refs = references()
    policy = GradingPolicy()
    jobs = default_jobs()
    # first calls (imports, the objectives' sample points) outside the timing, on text no
    # timed call uses
    for key in FORMS:
        naive_equal("x", "x")
        assess("1", refs[key], policy)
    with SandboxPool(jobs) as pool:
        pool.assess_many([("1", refs[key], policy) for key in FORMS] * jobs)
        compare("as a class answers", refs, as_a_class, count, rounds, pool)
        compare("every answer written differently", refs, all_different, count, rounds, pool)
        print(f"worker restarts: {pool.restarts}; load average {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("count", nargs="?", type=int, default=200,
                        help="answers a side in each round (default 200)")
    parser.add_argument("rounds", nargs="?", type=int, default=7,
                        help="rounds of each set (default 7)")
    arguments = parser.parse_args()
    main(arguments.count, arguments.rounds)
