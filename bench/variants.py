"""Print, per problem: cold derivation time, warm variant time and their ratio (target >= 1000).

Cold = load the spec, build the model and the solver plan (caches cleared) and solve once;
warm variant = solve the same problem with one student's givens, the plan already built (the
median over ``--students`` students, each a new variant). Problems with a ``variants:`` section
draw their variants; for the others a variant scales each parameter given (or, without any,
each rate given) by 0.8..1.2: the same re-solve path. Only variants that solve every objective
are timed (``n``). ``numeric`` times the warm solve without the symbolic objectives, which sympy
re-solves whenever a variant changes a given they depend on.

Run: PYTHONPATH=src python bench/variants.py [--students N] [problem.yaml ...]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

from mechgrade.errors import MechgradeError
from mechgrade.expressions.syntax import Name, Prime, to_text
from mechgrade.grade.variants import draw_variant
from mechgrade.solve import solve
from mechgrade.spec import load_problem

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


def measure(path: Path, students: int):
    clear_caches()
    problem = None

    def cold_run():
        nonlocal problem
        problem = load_problem(path)
        solve(problem)

    cold, _ = timed(cold_run)
    overrides = [g for g in variants_of(problem, students) if g]
    numeric = [o.id for o in problem.objectives if o.kind != "symbolic"]
    warm, warm_numeric = [], []
    for givens in overrides:
        try:
            seconds, solution = timed(lambda: solve(problem, givens=givens))
            if solution.failures:
                continue
            warm.append(seconds)
            if numeric:
                warm_numeric.append(timed(lambda: solve(problem, givens=givens,
                                                        objectives=numeric))[0])
        except MechgradeError:
            continue  # a synthetic variant may not assemble; drawn ones are verified
    return problem.id, cold, statistics.median(warm) if warm else float("nan"), \
        statistics.median(warm_numeric) if warm_numeric else float("nan"), len(warm)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("paths", nargs="*", type=Path)
    parser.add_argument("--students", type=int, default=30)
    args = parser.parse_args()
    print(f"{'problem':42s} {'cold':>9s} {'warm':>10s} {'numeric':>10s} {'ratio':>8s} "
          f"{'ratio num':>9s}  n")
    ratios = []
    for path in args.paths or DEFAULT:
        try:
            pid, cold, warm, num, n = measure(path, args.students)
        except MechgradeError as err:
            print(f"{path.stem:42s} error: {err}")
            continue
        if not n:
            print(f"{pid:42s} {cold * 1e3:7.0f}ms   (no variant to time: no givens to vary, or "
                  f"none solved)")
            continue
        ratio = cold / warm
        ratios.append(ratio)
        print(f"{pid:42s} {cold * 1e3:7.0f}ms {warm * 1e3:8.2f}ms {num * 1e3:8.2f}ms "
              f"{ratio:7.0f}x {cold / num:8.0f}x  {n}")
    print(f"{'median ratio':42s} {statistics.median(ratios):47.0f}x")


if __name__ == "__main__":
    main()
