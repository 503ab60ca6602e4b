"""Print, per problem: cold derivation time, warm variant time and their ratio (target >= 1000).

Cold = load the spec, build the model and the solver plan and solve once, in a fresh process
(its imports done before the clock starts): what grading pays the first time it meets a
problem. Warm, a class = ``--students`` variants solved together (``solve_variants``, as
grading and ``check --variants`` do), per student. Warm, alone = ``solve`` with one student's
givens, the plan already built (the median over ``--alone`` students of the pair).

The machine may be shared: the sides are measured in pairs, a cold run and a warm class (the
cold run first in even pairs, the class first in odd ones) then ``--alone`` students alone,
``--pairs`` times, and each ratio printed is the median of the per-pair ratios (cold / warm
of the same pair). Every warm call gets variants no earlier call has seen (a class of new
students each time, after a first class that builds what a warm solve keeps: the reference
solve, the symbolic answers), so nothing is answered from memory that a real class would not
find there. Each warm call starts with the garbage collector's debts settled
(``gc.collect()``, untimed), as ``timeit`` isolates its runs: a full collection owed by
earlier work in this long-lived process is not charged to the next class.

Problems with a ``variants:`` section draw their variants (distinct draws only); for the
others a variant scales each parameter given (or, without any, each rate given) by a factor
in 0.8..1.2, all different: the same re-solve path (givens written as expressions of
them follow, as a drawn variant's do). A given whose change alone makes an
objective fail that the spec's own givens solve is held (two_mass_spring_chain's spring
lengths: an objective's own givens place the chain at its equilibrium for those lengths), so
a class times students who are answered, not failures; where every parameter is, the rates
given are scaled (a linkage's lengths fix the configuration given); where every one is, all are
scaled
(``n`` then says how few were answered). Only variants that solve every objective
count (``n``, of the last class); ``fast`` is how many of them the class's loop answered (a
group that fails a screen for one is answered alone inside it; the rest went through
``solve`` one by one).

Run: PYTHONPATH=src python bench/variants.py [--students N] [--pairs N] [--alone N]
[problem.yaml ...]
"""

from __future__ import annotations

import argparse
import gc
import itertools
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
from mechgrade.spec.solving import carried

# Cold is a true derivation: the solver's disk cache is off here and in the cold process.
os.environ["MECHGRADE_NO_CACHE"] = "1"

DEFAULT = sorted(Path("problems").glob("*.yaml")) + [
    Path("examples/hw2_variants/pendulum_variants.yaml")]

GOLDEN = (5 ** 0.5 - 1) / 2


def variant_stream(problem):
    """Students' givens overrides (SI), each different from every one before it: drawn, or
    the scalable givens each times its own factor in 0.8..1.2 (a low-discrepancy sequence)."""
    if problem.variants is not None:
        seen = set()
        for n in itertools.count():
            givens = dict(draw_variant(problem, "bench", str(n)).overrides)
            key = tuple(sorted(givens.items()))
            if key not in seen:
                seen.add(key)
                yield givens
            elif n > 100 * (len(seen) + 10):
                return  # the draws are exhausted
    parameters = {p.name for p in problem.parameters}
    plain = [g for g in problem.givens if g.value_expr is None and g.si]
    kinds = [kind for kind in ([g for g in plain if isinstance(g.key.node, Name)
                                and g.key.node.id in parameters],
                               [g for g in plain if isinstance(g.key.node, Prime)]) if kind]
    spec = _failing(problem, {})
    # scaled alone (by 1.1), a given must fail nothing the spec solves: the parameters that
    # do not, else the rates that do not (a linkage's lengths fix its given configuration)
    held = [[g for g in kind
             if (scaled := _failing(problem, _with_derived(
                 problem, {to_text(g.key.node): g.si * 1.1}))) is not None and scaled <= spec]
            for kind in kinds] if spec is not None else []
    scalable = next((kind for kind in held if kind), kinds[0] if kinds else [])
    if not scalable:
        return
    for n in itertools.count(1):
        yield _with_derived(problem, {
            to_text(g.key.node): g.si * (0.8 + 0.4 * ((n * GOLDEN + i * 0.37) % 1.0))
            for i, g in enumerate(scalable)})


def _with_derived(problem, scaled: dict) -> dict:
    """``scaled`` and the givens written as expressions of them worked out again (a spring's
    free length stated to hold the bar level follows its mass), as a drawn variant's are."""
    return scaled | carried({to_text(g.key.node): g for g in problem.givens}, scaled)


def _failing(problem, givens: dict) -> set[str] | None:
    """The objectives that fail with ``givens`` (``None``: the solve itself fails)."""
    try:
        return {f.id for f in solve(problem, givens=givens).failures}
    except MechgradeError:
        return None


def timed(call):
    """(seconds, result) of ``call()``, the garbage collector's debts settled first: a full
    collection owed by earlier work in this process (other problems, the students solved
    alone) would land in whichever call comes next and be charged to it (a fresh cold
    process owes none); the call still pays every collection its own allocations trigger."""
    gc.collect()
    start = time.perf_counter()
    result = call()
    return time.perf_counter() - start, result


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


def solved_fully(outcomes) -> int:
    return sum(not isinstance(o, MechgradeError) and not o.failures for o in outcomes)


def measure(path: Path, students: int, pairs: int, alone: int):
    problem = load_problem(path)
    stream = variant_stream(problem)
    first = list(itertools.islice(stream, students))
    if not first:
        return problem.id, cold_seconds(path), None
    solve_variants(problem, first)  # what a warm solve keeps: built once per run
    ratios, alone_ratios, colds, warms, singles = [], [], [], [], []
    for turn in range(pairs):
        variants = list(itertools.islice(stream, students))
        if len(variants) < students:
            break  # not enough distinct draws left for another class
        cold = cold_seconds(path) if turn % 2 == 0 else None
        seconds, outcomes = timed(lambda variants=variants: solve_variants(problem, variants))
        if cold is None:  # the warm class first in odd pairs
            cold = cold_seconds(path)
        warm = seconds / len(variants)
        colds.append(cold)
        warms.append(warm)
        ratios.append(cold / warm)
        mine = []
        for givens in itertools.islice(stream, alone):
            try:
                mine.append(timed(lambda givens=givens: solve(problem, givens=givens))[0])
            except MechgradeError:
                continue  # a synthetic variant may not assemble; drawn ones are verified
        if mine:
            singles.append(statistics.median(mine))
            alone_ratios.append(cold / singles[-1])
    if not ratios:
        return problem.id, cold_seconds(path), None
    template = _template(problem)
    fast = sum(template.covers(v) for v in variants) if template else 0
    return (problem.id, statistics.median(colds),
            (statistics.median(singles) if singles else float("nan"),
             statistics.median(alone_ratios) if alone_ratios else float("nan"),
             statistics.median(warms), statistics.median(ratios),
             solved_fully(outcomes), fast, len(ratios)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("paths", nargs="*", type=Path)
    parser.add_argument("--students", type=int, default=200)
    parser.add_argument("--pairs", type=int, default=3)
    parser.add_argument("--alone", type=int, default=10)
    args = parser.parse_args()
    print(f"(cold and a warm class measured in {args.pairs} alternating pairs, each class of "
          f"{args.students} new variants; ratio: the median of the per-pair ratios)")
    print(f"{'problem':40s} {'cold':>8s} {'warm alone':>11s} {'ratio':>7s} "
          f"{'warm, class':>12s} {'ratio':>7s}    n  fast")
    ratios, alone_ratios = [], []
    for path in args.paths or DEFAULT:
        try:
            pid, cold, warm = measure(path, args.students, args.pairs, args.alone)
        except MechgradeError as err:
            print(f"{path.stem:40s} error: {err}")
            continue
        if warm is None:
            print(f"{pid:40s} {cold * 1e3:6.0f}ms   (no variant to time: no givens to vary, or "
                  f"too few distinct draws)")
            continue
        alone, alone_ratio, together, ratio, n, fast, count = warm
        ratios.append(ratio)
        if alone_ratio == alone_ratio:  # not NaN: some student solved alone
            alone_ratios.append(alone_ratio)
        print(f"{pid:40s} {cold * 1e3:6.0f}ms {alone * 1e3:9.2f}ms {alone_ratio:6.0f}x "
              f"{together * 1e3:10.3f}ms {ratio:6.0f}x  {n:3d}  {fast:4d}"
              + ("" if count == args.pairs else f"  ({count} pairs)"), flush=True)
    print(f"{'alone ratio: median, worst':40s} {statistics.median(alone_ratios):29.0f}x "
          f"{min(alone_ratios):.0f}x")
    print(f"{'class ratio: median, worst':40s} {statistics.median(ratios):58.0f}x "
          f"{min(ratios):.0f}x  ({sum(r < 1000 for r in ratios)} of {len(ratios)} below 1000x)")


if __name__ == "__main__":
    main()
