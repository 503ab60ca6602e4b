"""Print, per problem: cold derivation time, warm variant time and their ratio (target >= 1000).

Cold = load the spec, build the model and the solver plan and solve once, in a fresh process
(its imports done before the clock starts): what grading pays the first time it meets a problem. Warm, one at a time = ``solve`` with one student's givens, the plan already built
(the median over the first ``--alone`` students, each a new variant). Warm, a class = the
variants of all ``--students`` students solved together (``solve_variants``, as grading and
``check --variants`` do), per student, the fastest of three runs. Problems with a ``variants:`` section draw their
variants; for the others a variant scales each parameter given (or, without any, each rate
given) by 0.8..1.2: the same re-solve path. Only variants that solve every objective count
(``n``); ``fast`` is how many of them the stacked path solved (the rest went one by one).

Run: PYTHONPATH=src python bench/variants.py [--students N] [--alone N] [problem.yaml ...]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from mechgrade.errors import MechgradeError
from mechgrade.expressions.syntax import Name, Prime, to_text
from mechgrade.grade.variants import draw_variant
from mechgrade.solve import solve
from mechgrade.solve.batch import _template, solve_variants
from mechgrade.spec import load_problem

# Cold is a true derivation: the solver's disk cache is off here and in the cold process.
os.environ["MECHGRADE_NO_CACHE"] = "1"

DEFAULT = sorted(Path("problems").glob("*.yaml")) + [
    Path("examples/hw2_variants/pendulum_variants.yaml")]


def variants_of(problem, count: int) -> list[dict[str, float]]:
    """``count`` students' givens overrides (SI)."""
    if problem.variants is not None:
        return [dict(draw_variant(problem, "bench", str(n)).overrides) for n in range(count)]
    parameters = {p.name for p in problem.parameters}
    plain = [g for g in problem.givens if g.value_expr is None and g.si]
    scalable = ([g for g in plain if isinstance(g.key.node, Name)
                 and g.key.node.id in parameters]
                or [g for g in plain if isinstance(g.key.node, Prime)])
    return [{to_text(g.key.node): g.si * (0.8 + 0.4 * ((7 * n + i) % 11) / 10)
             for i, g in enumerate(scalable)} for n in range(1, count + 1)]


def timed(call):
    """(seconds, result) of ``call()``."""
    start = time.perf_counter()
    result = call()
    return time.perf_counter() - start, result


def clear_caches() -> None:
    """Forget every derivation and lambdified plan (the solver's and the mechanics' caches;
    the unit registry and the parser's tables stay: they are start-up, not derivation)."""
    for name, module in list(sys.modules.items()):
        if name.startswith(("mechgrade.mechanics", "mechgrade.solve")):
            for value in list(vars(module).values()):
                if callable(getattr(value, "cache_clear", None)):
                    value.cache_clear()


COLD = """
import sys, time
from mechgrade.solve import solve
from mechgrade.spec import load_problem
import mechgrade.solve.dynamics, mechgrade.solve.events, sympy.physics.mechanics, scipy.integrate
start = time.perf_counter()
solve(load_problem(sys.argv[1]))
print(time.perf_counter() - start)
"""


def cold_seconds(path: Path) -> float:
    """Load and solve ``path`` in a fresh process, timed after the imports."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(Path(__file__).parents[1] / "src"),
                                                      env.get("PYTHONPATH")]))
    done = subprocess.run([sys.executable, "-c", COLD, str(path)], capture_output=True,
                          text=True, env=env, check=True)
    return float(done.stdout.split()[-1])


def measure(path: Path, students: int, alone: int):
    clear_caches()
    cold = cold_seconds(path)
    problem = load_problem(path)
    solve(problem)
    overrides = [g for g in variants_of(problem, students) if g]
    warm = []
    solved = []
    for givens in overrides:
        try:
            seconds, solution = timed(lambda: solve(problem, givens=givens))
        except MechgradeError:
            continue  # a synthetic variant may not assemble; drawn ones are verified
        if not solution.failures:
            solved.append(givens)
            if len(warm) < alone:
                warm.append(seconds)
    if not solved:
        return problem.id, cold, float("nan"), float("nan"), 0, 0
    solve_variants(problem, solved[:2])  # the reference kept for the variants: once per run
    # the fastest of three runs: on a loaded machine the others measure the load
    together = min(timed(lambda: solve_variants(problem, solved))[0] for _ in range(3))
    template = _template(problem)
    fast = sum(s is not None for s in template.solve(solved)) if template else 0
    return (problem.id, cold, statistics.median(warm), together / len(solved), len(solved),
            fast)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("paths", nargs="*", type=Path)
    parser.add_argument("--students", type=int, default=200)
    parser.add_argument("--alone", type=int, default=20)
    args = parser.parse_args()
    print(f"{'problem':40s} {'cold':>8s} {'warm alone':>11s} {'ratio':>7s} "
          f"{'warm, class':>12s} {'ratio':>7s}    n  fast")
    ratios = []
    for path in args.paths or DEFAULT:
        try:
            pid, cold, alone, together, n, fast = measure(path, args.students, args.alone)
        except MechgradeError as err:
            print(f"{path.stem:40s} error: {err}")
            continue
        if not n:
            print(f"{pid:40s} {cold * 1e3:6.0f}ms   (no variant to time: no givens to vary, or "
                  f"none solved)")
            continue
        ratios.append(cold / together)
        print(f"{pid:40s} {cold * 1e3:6.0f}ms {alone * 1e3:9.2f}ms {cold / alone:6.0f}x "
              f"{together * 1e3:10.3f}ms {cold / together:6.0f}x  {n:3d}  {fast:4d}")
    print(f"{'class ratio: median, worst':40s} {statistics.median(ratios):58.0f}x "
          f"{min(ratios):.0f}x")


if __name__ == "__main__":
    main()
