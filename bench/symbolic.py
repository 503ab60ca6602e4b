"""Symbolic answers: mechgrade's check next to the naive ``simplify(sympify(a) - sympify(b)) == 0``.

1,000 answers to the four symbolic objectives of ``bench/scale.py`` (its answer forms, each
labelled equivalent or not by hand), drawn with repeats as in a real class. Timed on the same
answers:

* naive: sympy's ``parse_expr`` (implicit products, ``^``) of both sides, ``simplify`` of the
  difference, one answer after the other;
* mechgrade in-process: :func:`mechgrade.grade.compare.assess` of every answer;
* mechgrade through the worker: every answer through one bounded :class:`Sandbox`, one answer
  per round trip (as grading did before batches) and in batches (a repeated answer is judged
  once);
* mechgrade through a worker per core: every answer through a :class:`SandboxPool`.

Then again on 1,000 answers each written differently (``k*(form)/k``), which shows the cost of
judging itself, without repeats. mechgrade's times are the fastest of three runs (each run of the
second set on answers written differently again); the naive check runs once.

A verdict is right when "correct" goes with an equivalent answer and any other verdict with a
wrong one. Run: ``.venv/bin/python bench/symbolic.py [count]``.
"""

from __future__ import annotations

import random
import sys
import time
from pathlib import Path

import sympy
from sympy.parsing.sympy_parser import (convert_xor, implicit_multiplication_application,
                                        parse_expr, standard_transformations)

from mechgrade.grade.compare import Policy, assess
from mechgrade.grade.sandbox import Sandbox, SandboxPool
from mechgrade.parallel import default_jobs
from mechgrade.solve import solve
from mechgrade.spec import load_problem

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


def references() -> dict:
    out = {}
    for name in sorted({problem for problem, _ in FORMS}):
        solution = solve(load_problem(PROBLEMS / f"{name}.yaml"))
        for problem, objective in FORMS:
            if problem == name:
                out[problem, objective] = solution.result(objective)
    return out


def answers(count: int) -> list[tuple[tuple[str, str], str, bool]]:
    """Answers as a class writes them: the same few forms, many times over."""
    rng = random.Random(7)
    keys = list(FORMS)
    return [(key, *rng.choice(FORMS[key])) for key in (rng.choice(keys) for _ in range(count))]


def distinct_answers(count: int, start: int = 2) -> list[tuple[tuple[str, str], str, bool]]:
    """Every answer written differently (``k*(form)/k``, ``k`` from ``start``), so none is
    judged from another."""
    return [(key, f"{i + start}*({text})/{i + start}", equivalent)
            for i, (key, text, equivalent) in enumerate(answers(count))]


def naive_equal(text: str, reference: str) -> bool:
    a = parse_expr(text, transformations=TRANSFORMS)
    b = parse_expr(reference, transformations=TRANSFORMS)
    return sympy.simplify(a - b) == 0


def timed(func):
    start = time.perf_counter()
    value = func()
    return time.perf_counter() - start, value


def best(func, samples, repeats: int = 3):
    """The fastest of ``repeats`` runs of ``func`` (on a loaded machine the others measure
    the load), each on its own list of answers from ``samples(run)``; the first run's
    verdicts."""
    runs = []
    for run in range(repeats):
        batch = samples(run)  # drawn outside the timing
        runs.append(timed(lambda: func(batch)))
    return min(seconds for seconds, _ in runs), runs[0][1]


def compare(title: str, refs: dict, sample, others) -> None:
    """``sample`` timed once with the naive check and ``others(run)`` (``sample`` itself
    first, then answers that do not repeat earlier runs' texts when it is the distinct set)
    with mechgrade's, fastest of three."""
    policy = Policy()
    truth = [equivalent for _, _, equivalent in sample]
    jobs = default_jobs()

    def items_of(run):
        return [(text, refs[key], policy) for key, text, _ in others(run)]

    items = items_of(0)
    naive_s, naive = timed(lambda: [naive_equal(text, refs[key].expr)
                                    for key, text, _ in sample])
    inproc_s, inproc = best(lambda batch: [assess(*item) for item in batch], items_of)
    with Sandbox() as box:
        box.assess("0", refs[sample[0][0]], policy)  # start the worker outside the timing
        single_s, single = best(lambda batch: [box.assess(*item) for item in batch], items_of)
        worker_s, worker = best(box.assess_many, items_of)
    with SandboxPool(jobs) as pool:
        pool.assess_many(items[:jobs])  # start the workers outside the timing
        pool_s, pooled = best(pool.assess_many, items_of)

    def right(verdicts) -> str:
        good = sum((v == "correct") == t for v, t in zip(verdicts, truth))
        return f"{good}/{len(truth)} right"

    distinct = len(set(items))
    print(f"{title}: {len(items)} symbolic answers ({distinct} distinct), {jobs} cores")
    rows = [("naive simplify(sympify(a) - sympify(b)) == 0", naive_s,
             right(["correct" if n else "incorrect" for n in naive])),
            ("mechgrade in-process, one by one", inproc_s, right([a.verdict for a in inproc])),
            ("mechgrade through the worker, one answer a trip", single_s,
             right([a.verdict for a in single])),
            ("mechgrade through the worker, batches", worker_s,
             right([a.verdict for a in worker])),
            (f"mechgrade through {jobs} workers, batches", pool_s,
             right([a.verdict for a in pooled]))]
    for label, seconds, verdicts in rows:
        print(f"  {label:<50} {seconds:7.3f} s  {naive_s / seconds:7.1f}x  {verdicts}")


def main(count: int) -> None:
    refs = references()
    sample = answers(count)
    compare("as a class answers", refs, sample, lambda run: sample)
    compare("every answer written differently", refs, distinct_answers(count),
            lambda run: distinct_answers(count, 2 + run * count))


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1000)
