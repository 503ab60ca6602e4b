"""The solver's answers before and after a change: record them once, compare them later.

For every problem of ``problems/`` and of the examples this dumps what ``mechgrade solve
--format json`` prints (:func:`mechgrade.cli.solve.solution_json`), every objective's
generated mistakes (code, value or expression) and, for a problem with something to vary,
the solutions :func:`~mechgrade.solve.batch.solve_variants` gives a class of distinct
variants (drawn, or its parameters scaled) and those :func:`~mechgrade.solve.solve` gives
the first few alone. ``compare`` reads a recorded dump and says where the answers now differ:
numbers by more than ``--rel`` (default 1e-9) relative, any text or structure at all.
With ``--state-scale`` a value of the state at the instant is read against the largest value
of its dimension in that state: a value that is zero in exact arithmetic (a rate at a turning
point reached by integration) carries the integrator's error, some 1e-11 of the motion's own
speeds, which no relative test of the zero itself can hold.

Run (the disk cache off, as the tests):
    MECHGRADE_NO_CACHE=1 .venv/bin/python bench/parity.py record /tmp/before.json
    MECHGRADE_NO_CACHE=1 .venv/bin/python bench/parity.py compare /tmp/before.json
    .venv/bin/python bench/parity.py diff /tmp/before.json /tmp/after.json   # two records
    PYTHONPATH=/other/checkout/src .venv/bin/python bench/parity.py record /tmp/other.json
    # this script and problems, another checkout's solver; --no-mistakes: solutions only

``diff`` compares two records (say, one of main and one of a branch, each recorded from its
own checkout while the other is worked on) without solving anything.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import sys
from pathlib import Path

os.environ.setdefault("MECHGRADE_NO_CACHE", "1")

from mechgrade.cli.solve import solution_json
from mechgrade.errors import MechgradeError
from mechgrade.expressions.syntax import Name, Prime, to_text
from mechgrade.grade.variants import draw_variant
from mechgrade.solve import solve
from mechgrade.solve.batch import solve_variants
from mechgrade.spec import load_problem
from mechgrade.units import dimension

ROOT = Path(__file__).resolve().parents[1]
PATHS = sorted((ROOT / "problems").glob("*.yaml")) + sorted(
    p for p in (ROOT / "examples").glob("*/*.yaml") if p.name != "assignment.yaml")


def variants_of(problem, count: int) -> list[dict[str, float]]:
    """``count`` distinct students' givens overrides (SI): drawn, or the parameters given
    (else the rates given) scaled by distinct factors in 0.8..1.2."""
    if problem.variants is not None:
        return [dict(draw_variant(problem, "parity", str(n)).overrides) for n in range(count)]
    parameters = {p.name for p in problem.parameters}
    plain = [g for g in problem.givens if g.value_expr is None and g.si]
    scalable = ([g for g in plain if isinstance(g.key.node, Name)
                 and g.key.node.id in parameters]
                or [g for g in plain if isinstance(g.key.node, Prime)])
    return [{to_text(g.key.node): g.si * (0.8 + 0.4 * ((n * 0.6180339887 + 0.37 * i) % 1.0))
             for i, g in enumerate(scalable)} for n in range(1, count + 1) if scalable]


def _mistakes(solution) -> dict:
    return {r.id: [[m.code, m.value if not isinstance(m.value, tuple) else list(m.value),
                    m.expr, m.message] for m in r.generated_mistakes]
            for r in solution.results}


MISTAKES = True  # --no-mistakes: the solutions alone (a dynamics problem's mistakes are slow)


def _outcome(problem, outcome) -> dict:
    if isinstance(outcome, MechgradeError):
        return {"error": f"{type(outcome).__name__}: {outcome}"}
    entry = {"solution": solution_json(problem, outcome)}
    if MISTAKES:
        entry["generated"] = _mistakes(outcome)
    return entry


def dump(path: Path, count: int, alone: int) -> dict:
    problem = load_problem(path)
    try:
        entry = _outcome(problem, solve(problem))
    except MechgradeError as err:
        entry = _outcome(problem, err)
    variants = variants_of(problem, count)
    if variants:
        entry["class"] = [_outcome(problem, o) for o in solve_variants(problem, variants)]
        entry["alone"] = []
        for givens in variants[:alone]:
            try:
                entry["alone"].append(_outcome(problem, solve(problem, givens=givens)))
            except MechgradeError as err:
                entry["alone"].append(_outcome(problem, err))
    return entry


_PLACE = re.compile(r"/[^ :']*/(?=(problems|examples)/)")
_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def _dimension(unit: str):
    """The dimension of a state's unit as printed (``km / s`` and ``km/s`` alike)."""
    try:
        return dimension(unit)
    except MechgradeError:  # a unit this bench cannot read is its own dimension
        return unit


def _state_scales(state: list) -> list[float]:
    """Each entry's scale: the largest size of a value of its dimension in ``state``."""
    dims = [_dimension(e.get("unit", "")) for e in state]
    sizes = [abs(e["value"]) if isinstance(e.get("value"), (int, float)) else 0.0
             for e in state]
    return [max((s for d2, s in zip(dims, sizes) if d2 == d), default=0.0) for d in dims]


def differences(a, b, rel: float, where: str = "", scale: float = 0.0,
                state_scale: bool = False) -> list[str]:
    """Where ``a`` and ``b`` differ: numbers beyond ``rel`` of the larger (or of ``scale``);
    texts whose words differ, or whose numbers (printed to a few figures) differ beyond the
    figures they show. ``state_scale``: a state's values against their dimension's scale.

    >>> differences({"state": [{"value": 8.0, "unit": "km / s"}, {"value": 2e-12,
    ...     "unit": "km/s"}]}, {"state": [{"value": 8.0, "unit": "km / s"}, {"value": 9e-11,
    ...     "unit": "km/s"}]}, 1e-9, "x", state_scale=True)
    []
    """
    if isinstance(a, bool) or isinstance(b, bool) or a is None or b is None:
        return [] if a == b else [f"{where}: {a!r} != {b!r}"]
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if math.isnan(a) and math.isnan(b):
            return []
        # a zero found to rounding (1e-15) is that zero
        ok = abs(a - b) <= rel * max(abs(a), abs(b), scale) + 1e-13 or a == b
        return [] if ok else [f"{where}: {a!r} != {b!r}"]
    if isinstance(a, str) and isinstance(b, str):
        a, b = _PLACE.sub("", a), _PLACE.sub("", b)  # the folder the files were read from
        if a == b:
            return []
        if _NUMBER.sub("#", a) == _NUMBER.sub("#", b):
            # the same sentence; its numbers rounded to what it prints (4 to 6 figures)
            pairs = zip(_NUMBER.findall(a), _NUMBER.findall(b))
            if all(math.isclose(float(x), float(y), rel_tol=2e-4, abs_tol=1e-9)
                   for x, y in pairs):
                return []
        return [f"{where}: {a!r} != {b!r}"]
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{where}: {len(a)} items != {len(b)}: {a!r} / {b!r}"]
        scales = _state_scales(a) if state_scale and where.endswith(".state") else [scale] * len(a)
        return [d for i, (x, y) in enumerate(zip(a, b))
                for d in differences(x, y, rel, f"{where}[{i}]", scales[i], state_scale)]
    if isinstance(a, dict) and isinstance(b, dict):
        if list(a) != list(b):
            return [f"{where}: keys {list(a)} != {list(b)}"]
        return [d for k in a
                for d in differences(a[k], b[k], rel, f"{where}.{k}", scale, state_scale)]
    return [f"{where}: {a!r} != {b!r}"]


def diff(before_file: Path, after_files: list[Path], rel: float,
         state_scale: bool = False) -> int:
    """Print where the records in ``after_files`` differ from ``before_file`` for the problems
    both hold (and which only one holds); 1 when they differ anywhere, else 0."""
    before = json.loads(before_file.read_text())
    after: dict = {}
    for f in after_files:
        after.update(json.loads(f.read_text()))
    found = 0
    for key in sorted(set(before) | set(after)):
        if key not in before or key not in after:
            print(f"{key}: recorded in {before_file if key in before else 'the other'} only")
            continue
        diffs = differences(before[key], after[key], rel, key, state_scale=state_scale)
        found += len(diffs)
        for d in diffs[:10]:
            print(d)
    both = len(set(before) & set(after))
    print(f"{both} problems recorded in both compared, {found} differences")
    return 1 if found else 0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("action", choices=["record", "compare", "diff"])
    parser.add_argument("file", type=Path)
    parser.add_argument("--variants", type=int, default=24)
    parser.add_argument("--alone", type=int, default=3)
    parser.add_argument("--rel", type=float, default=1e-9)
    parser.add_argument("--state-scale", action="store_true",
                        help="read a state's values against their dimension's largest value")
    parser.add_argument("--no-mistakes", action="store_true",
                        help="record or compare the solutions without their generated mistakes")
    parser.add_argument("paths", nargs="*", type=Path)
    args = parser.parse_intermixed_args()
    global MISTAKES
    MISTAKES = not args.no_mistakes
    if args.action == "diff":
        sys.exit(diff(args.file, args.paths, args.rel, args.state_scale))
    paths = args.paths or PATHS
    before = json.loads(args.file.read_text()) if args.action == "compare" else {}
    now = {}
    found = 0
    for path in paths:
        key = str(path.relative_to(ROOT) if path.is_absolute() else path)
        now[key] = entry = dump(path, args.variants, args.alone)
        if args.action == "record":  # written after each problem: a record cut short keeps them
            args.file.write_text(json.dumps(now, indent=1))
            print(key, file=sys.stderr, flush=True)
            continue
        if key not in before:
            print(f"{key}: not recorded", flush=True)
            continue
        diffs = differences(before[key], json.loads(json.dumps(entry)), args.rel, key,
                            state_scale=args.state_scale)
        found += len(diffs)
        for d in diffs[:10]:
            print(d)
        if len(diffs) > 10:
            print(f"{key}: ... {len(diffs) - 10} more")
        print(f"{key}: {len(diffs)} differences", flush=True)
    if args.action == "record":
        args.file.write_text(json.dumps(now, indent=1))
        print(f"recorded {len(now)} problems in {args.file}")
        return
    print(f"{len(now)} problems compared, {found} differences")
    sys.exit(1 if found else 0)


if __name__ == "__main__":
    main()
