"""Print, for every problem in problems/: cold derivation time and one numeric evaluation.

Cold derivation = load the spec + build the sympy.physics model + lambdify (caches cleared);
numeric evaluation = solve the instant(s) (position, velocity, acceleration levels) and evaluate
every numeric objective with the plan already built; symbolic = the sympy solve of the
symbolic objectives; mistakes (dynamics problems) = working out the generated mistakes of every
numeric objective once, cold (each mistaken model derived and solved, each given slip solved).
Dynamics problems: see ``measure_dynamics``. Run: PYTHONPATH=src python bench/solve_timing.py [problems/...]
"""

from __future__ import annotations

import os
import statistics
import sys
import time
from pathlib import Path

from mechgrade.errors import MechgradeError
from mechgrade.mechanics import derive
from mechgrade.solve import kinematics_plan
from mechgrade.solve.instant import _givens, _instants, _symbolic_answer
from mechgrade.solve.numeric import solve_numeric
from mechgrade.solve.symbolic import _linear_solve, _simplify
from mechgrade.solve.symbolic import symbolic as solve_symbolic
from mechgrade.mechanics.dynamics import derive_kinetics
from mechgrade.solve.dynamics import (_kinetics_plan, _symbolic_result, kinetics_plan,
                                      solve_dynamics)
from mechgrade.solve.analysis import _analysis_plan, closed_forms
from mechgrade.solve.events import _at_event, _closed_form
from mechgrade.spec import load_problem
from mechgrade.solve import solve
from mechgrade.mechanics.dynamics_mutations import _mutations as _dynamics_mutations
from mechgrade.solve.dynamics_mutants import _generated

# Cold derivations are derived: the solver's disk cache stays off.
os.environ["MECHGRADE_NO_CACHE"] = "1"


def main(paths: list[str]) -> None:
    files = sorted(Path(p) for p in paths) if paths else sorted(Path("problems").glob("*.yaml"))
    print(f"{'problem':42s} {'cold derive':>12s} {'numeric eval':>13s} {'symbolic':>10s} "
          f"{'mistakes':>10s}")
    colds, evals, extras = [], [], []
    for path in files:
        try:
            cold, ev, symbolic, problem_id, *mistakes = measure(path)
        except MechgradeError as err:
            print(f"{path.stem:42s} error: {err}")
            continue
        colds.append(cold)
        if ev == ev:  # NaN when the problem has no numeric objective
            evals.append(ev)
        extras += mistakes
        extra = f"{mistakes[0] * 1e3:8.0f} ms" if mistakes else f"{'':>11s}"
        print(f"{problem_id:42s} {cold * 1e3:10.0f} ms {ev * 1e3:11.2f} ms {symbolic * 1e3:8.0f} ms"
              f" {extra}")
    print(f"{'median':42s} {statistics.median(colds) * 1e3:10.0f} ms "
          f"{statistics.median(evals) * 1e3:11.2f} ms {'':>11s}"
          + (f" {statistics.median(extras) * 1e3:8.0f} ms" if extras else ""))
    if extras:
        print(f"{'total generated mistakes (dynamics)':42s} {sum(extras):10.2f} s")


def measure(path: Path):
    derive.cache_clear()
    kinematics_plan.cache_clear()
    _simplify.cache_clear()  # a symbolic answer is timed as first derived
    start = time.perf_counter()
    problem = load_problem(path)
    if problem.dynamics is not None:
        return measure_dynamics(problem, start)
    p = kinematics_plan(problem)
    cold = time.perf_counter() - start
    groups = []
    for overrides, objectives in _instants(problem):
        givens = _givens(problem, None)
        givens.update({key: (g.key.node, g.si, g) for key, g in overrides.items()})
        numeric = {o.id for o in objectives if o.kind != "symbolic"}
        if numeric:
            groups.append((givens, numeric))
    runs = []
    if groups:
        for _ in range(20):
            start = time.perf_counter()
            for givens, numeric in groups:
                solve_numeric(problem, p, givens, numeric)
            runs.append(time.perf_counter() - start)
    givens = _givens(problem, None)
    start = time.perf_counter()
    for obj in problem.objectives:
        if obj.kind == "symbolic":
            solve_symbolic(problem, p.k, obj, givens)
    symbolic = time.perf_counter() - start
    return cold, statistics.median(runs) if runs else float("nan"), symbolic, problem.id


def measure_dynamics(problem, start: float):
    """Cold: load + kinematics + Newton-Euler balances + lambdify; numeric: the instant (or the
    work-energy state, or the integration to the event) and the kinetics, every numeric
    objective; symbolic: the sympy solve of the balances and the symbolic objectives."""
    derive_kinetics.cache_clear()
    _kinetics_plan.cache_clear()
    _analysis_plan.cache_clear()
    kinetics_plan(problem)
    cold = time.perf_counter() - start
    numeric = [o.id for o in problem.objectives if o.kind != "symbolic"]
    runs = []
    for _ in range(5 if numeric else 0):
        begin = time.perf_counter()
        solve_dynamics(problem, objectives=numeric)
        runs.append(time.perf_counter() - begin)
    symbolic = [o.id for o in problem.objectives if o.kind == "symbolic"]
    _linear_solve.cache_clear()
    _symbolic_result.cache_clear()
    _symbolic_answer.cache_clear()
    _simplify.cache_clear()
    _closed_form.cache_clear()
    closed_forms.cache_clear()
    _at_event.cache_clear()
    begin = time.perf_counter()
    if symbolic:
        solve_dynamics(problem, objectives=symbolic)
    symbolic_time = time.perf_counter() - begin
    _dynamics_mutations.cache_clear()
    _generated.cache_clear()
    begin = time.perf_counter()
    for result in solve(problem, objectives=numeric).results:
        tuple(result.generated_mistakes)
    return (cold, statistics.median(runs) if runs else float("nan"), symbolic_time, problem.id,
            time.perf_counter() - begin)


if __name__ == "__main__":
    main(sys.argv[1:])
