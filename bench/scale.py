"""Grading at scale: ``mechgrade grade`` on generated classes next to the floor of the work.

Each class has 12 graded objectives (4 symbolic) from the shipped problems: the hw1 example's
eight plus the cannonball's speed and three of the cylinder's. Every student writes an
``answers.yaml`` with a random mix of right, rounded, wrong-unit, sign-flipped, missing and
alternative symbolic answers (fixed seed, so a run is repeatable).

The floor is a script that only walks the submission folders and ``yaml.safe_load``s each
answers file: the least any grader must do. Both run as fresh processes; "cores" is the CPU
time of the process and its workers (user + sys) over the wall time. The two run in pairs,
``--repeat`` pairs, the order turning pair by pair (so other load on the machine falls on both
alike); the times shown are the medians, each ratio the median of the per-pair ratios. The
CPU columns compare the work done, which other load on the machine changes less than the
wall time.

Run: ``.venv/bin/python bench/scale.py [sizes...] [--jobs N]`` (default sizes 100 1000 5000).

``--dynamics`` grades another class instead: every student has their own numbers (a
``variants:`` section) of a problem that integrates the motion to an event
(``bench/data/cart_variants.yaml``: a block sliding on a cart until it stops sliding), and
answers every objective wrongly but near the answer, so that each student's generated
mistakes (the mistaken models solved for that student's numbers) are worked out. Each run of
it is cold: the solver's disk cache is a new empty folder.

``--phases`` times the steps of a run instead, in this process, through the library's public
functions one after the other (so reading does not overlap solving as in ``mechgrade grade``):
importing the solver, loading the assignment and its problems, reading (started first, as in a
run), solving (``plan_assignment``), judging (``grade_plan``) and writing the outputs, each with
its wall and CPU time (this process and its workers), and the total without the solving (what a
run costs once solving is cached).

``--pages`` measures the feedback pages instead: the hw3 dynamics example
(``examples/hw3_dynamics``) graded in this process with its worked solution shown (the
assignment's ``policy.worked_solution: always``), then every student's HTML page rendered
``--repeat`` times; it prints each page's size in bytes and its median render time. Pair it
with another checkout (``PYTHONPATH=<checkout>/src python bench/scale.py --pages``), run in turn,
or let ``--against <checkout>`` do it: both sides run in turn ``--rounds`` times (fresh
processes, this script with the other checkout's ``src`` first on the path), and each page's
size, its size against the other's and the median over the rounds of its render time's ratio
are printed.
"""

from __future__ import annotations

import argparse
import os
import random
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PROBLEMS = ROOT / "problems"
# one folder per checkout: the assignment names this checkout's problems, and two checkouts
# benchmarking at once must not grade into each other's output folders
WORK = Path(tempfile.gettempdir()) / f"mechgrade-bench-scale-{zlib.crc32(bytes(ROOT)):08x}"

ASSIGNMENT = f"""\
id: scale
title: Scale benchmark
problems:
  - {PROBLEMS / 'bowling_3_15_4_pendulum.yaml'}
  - path: {PROBLEMS / 'bowling_3_15_8_connected_blocks.yaml'}
    objectives: [xdot, rod_omega_z, P_ZA_frameA]
  - path: {PROBLEMS / 'ruina_10_4_10_7_rotating_tube_accel.yaml'}
    objectives: [a_P_N]
  - path: {PROBLEMS / 'bowling_3_15_2_cannonball.yaml'}
    objectives: [speed]
  - path: {PROBLEMS / 'bowling_3_15_5_cylinder.yaml'}
    objectives: [vB_mag, vB_symbolic_x, vB_symbolic_y]
points:
  default: 2
policy:
  reveal_answers: true
  missing_unit: {{action: penalize, credit: 0.5}}
  partial_credit:
    diagnoses: {{sign: 0.5, swapped: 0.5, deg_as_rad: 0.25, cm_m: 0.25}}
  ecf: {{enabled: true, credit: 1.0}}
"""

# (problem, objective): answer makers (rng -> text); numbers are the reference values.
SCALARS = {
    ("bowling_3_15_4_pendulum", "acc_mag"): (98.5089, [("ft/s^2", 1.0), ("m/s^2", 0.3048)]),
    ("bowling_3_15_8_connected_blocks", "xdot"): (-7.66598, [("m/s", 1.0), ("ft/s", 1 / 0.3048)]),
    ("bowling_3_15_8_connected_blocks", "rod_omega_z"): (73.3429, [("rad/s", 1.0),
                                                                   ("rpm", 60 / 6.283185)]),
    ("bowling_3_15_5_cylinder", "vB_mag"): (5.00368, [("m/s", 1.0), ("cm/s", 100.0)]),
}
VECTORS = {
    ("bowling_3_15_4_pendulum", "acc_N"): ((-89.8705, -40.3397), "ft/s^2", "N"),
    ("bowling_3_15_4_pendulum", "acc_A"): ((-98.0, 10.0), "ft/s^2", "A"),
    ("bowling_3_15_8_connected_blocks", "P_ZA_frameA"): ((-0.104522, 0.0), "m", "A"),
    ("ruina_10_4_10_7_rotating_tube_accel", "a_P_N"): ((-66.0, -40.0), "ft/s^2", "N"),
}
SYMBOLIC = {
    ("bowling_3_15_4_pendulum", "acc_mag_symbolic"): [
        "L*sqrt(thetad**4 + thetadd**2)", "L sqrt(thetad^4 + thetadd^2)",
        "sqrt(L^2 thetad^4 + L^2 thetadd^2)", "L*(thetad^4 + thetadd^2)^(1/2)", "L*thetad^2",
        "L*sqrt(thetad^2 + thetadd^2)", "-L*sqrt(thetad^4 + thetadd^2)",
        "L*sqrt((thetad^2)^2 + thetadd^2)"],
    ("bowling_3_15_2_cannonball", "speed"): [
        "sqrt(xd^2 + yd^2)", "sqrt(xd**2+yd**2)", "(xd^2 + yd^2)^(1/2)", "xd + yd",
        "sqrt(xd^2 - yd^2)", "sqrt(yd^2 + xd^2)", "xd^2 + yd^2"],
    ("bowling_3_15_5_cylinder", "vB_symbolic_x"): [
        "-xd - r*thetad*sin(theta)", "-(xd + r thetad sin(theta))", "xd + r*thetad*sin(theta)",
        "-xd - r*thetad*cos(theta)", "-r*thetad*sin(theta) - xd", "-xd + r*thetad*sin(theta)"],
    ("bowling_3_15_5_cylinder", "vB_symbolic_y"): [
        "-yd + r*thetad*cos(theta)", "r thetad cos(theta) - yd", "yd - r*thetad*cos(theta)",
        "-yd + r*thetad*sin(theta)", "r*thetad*cos(theta)-yd", "-yd + thetad*cos(theta)"],
}


DYNAMICS_ASSIGNMENT = f"""\
id: scale-dynamics
title: Scale benchmark, dynamics with variants
problems:
  - {ROOT / 'bench' / 'data' / 'cart_variants.yaml'}
variants:
  seed: scale
  redraw: true
points:
  default: 2
policy:
  reveal_answers: true
"""

# objective: (a plausible range of the answer, its unit)
DYNAMICS = {"t_slide": ((0.3, 3.0), "s"), "common_speed": ((0.3, 3.0), "m/s"),
            "slide_distance": ((0.5, 6.0), "m"), "energy_lost": ((3.0, 60.0), "J"),
            "cart_acceleration": ((0.2, 4.0), "m/s^2")}


def dynamics_answers_yaml(rng: random.Random) -> str:
    lines = ["# generated by bench/scale.py", "cart_variants:"]
    for objective, ((low, high), unit) in DYNAMICS.items():
        lines.append(f"  {objective}: '{rng.uniform(low, high):.4g} {unit}'")
    lines.append(f"  friction_on_block: '({-rng.uniform(1.0, 20.0):.3g}, 0, 0) N'")
    lines.append("  t_slide_symbolic: 'M*v0/(mu*g*(m + M))'")
    return "\n".join(lines) + "\n"


def scalar_answer(rng: random.Random, value: float, units) -> str:
    unit, factor = rng.choice(units)
    roll = rng.random()
    if roll < 0.1:
        value = -value
    elif roll < 0.2:
        value *= rng.uniform(0.5, 1.5)
    text = f"{value * factor * rng.uniform(0.999, 1.001):.{rng.choice((3, 4))}g}"
    return text if rng.random() < 0.05 else f"{text} {unit}"


def vector_answer(rng: random.Random, comps, unit: str, frame: str) -> str:
    comps = list(comps)
    roll = rng.random()
    if roll < 0.1:
        comps.reverse()
    elif roll < 0.2:
        comps = [-c for c in comps]
    shown = [f"{c * rng.uniform(0.999, 1.001):.3g}" for c in comps]
    if frame != "N" or rng.random() < 0.5:
        return f"({', '.join(shown)}) {unit}"
    return f"{shown[0]} i + {shown[1]} j {unit}".replace("+ -", "- ")


def answers_yaml(rng: random.Random) -> str:
    per_problem: dict[str, list[str]] = {}

    def put(key, text):
        if rng.random() < 0.03:
            return  # left blank
        problem, objective = key
        quoted = text.replace("'", "''")
        per_problem.setdefault(problem, []).append(f"  {objective}: '{quoted}'")

    for key, (value, units) in SCALARS.items():
        put(key, scalar_answer(rng, value, units))
    for key, (comps, unit, frame) in VECTORS.items():
        put(key, vector_answer(rng, comps, unit, frame))
    for key, forms in SYMBOLIC.items():
        put(key, rng.choice(forms))
    lines = ["# generated by bench/scale.py"]
    for problem, entries in per_problem.items():
        lines.append(f"{problem}:")
        lines.extend(entries)
    return "\n".join(lines) + "\n"


def make_class(size: int, dynamics: bool = False) -> Path:
    """The class folder for ``size`` students (generated once, reused)."""
    folder = WORK / (f"dynamics{size}" if dynamics else f"class{size}")
    done = folder / ".complete"
    if done.exists():
        return folder
    shutil.rmtree(folder, ignore_errors=True)
    rng = random.Random(size)
    subs = folder / "submissions"
    for i in range(size):
        student = subs / f"s{i:05d}"
        student.mkdir(parents=True)
        (student / "answers.yaml").write_text(
            (dynamics_answers_yaml if dynamics else answers_yaml)(rng), encoding="utf-8")
    (folder / "assignment.yaml").write_text(DYNAMICS_ASSIGNMENT if dynamics else ASSIGNMENT,
                                            encoding="utf-8")
    done.touch()
    return folder


FLOOR = """\
import os, sys, yaml
count = 0
for root, dirs, files in os.walk(sys.argv[1]):
    dirs.sort()
    for name in sorted(files):
        if name.endswith(".yaml"):
            with open(os.path.join(root, name), encoding="utf-8") as handle:
                yaml.safe_load(handle)
            count += 1
print(count)
"""


def timed(command: list[str], env: dict | None = None) -> tuple[float, float]:
    """(wall seconds, CPU seconds of the process and its children) of one run."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                          env=env)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 3):
        raise SystemExit(f"{' '.join(command)} failed ({done.returncode}):\n{done.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def graded(command: list[str], out: Path, cold: bool) -> tuple[float, float]:
    """:func:`timed` of ``mechgrade grade`` into a new ``out``; ``cold``: with a new, empty disk
    cache."""
    shutil.rmtree(out, ignore_errors=True)
    if not cold:
        return timed(command)
    cache = tempfile.mkdtemp()
    try:
        return timed(command, dict(os.environ, MECHGRADE_CACHE_DIR=cache))
    finally:
        shutil.rmtree(cache, ignore_errors=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sizes", nargs="*", type=int, default=[100, 1000, 5000])
    parser.add_argument("--jobs", type=int, default=None, help="pass --jobs to mechgrade grade")
    parser.add_argument("--repeat", type=int, default=3,
                        help="pairs of runs (grade, floor), the order turning pair by pair; "
                             "medians shown")
    parser.add_argument("--dynamics", action="store_true",
                        help="grade the class with per-student numbers of an integrated "
                             "motion, cold (see the docstring)")
    parser.add_argument("--phases", action="store_true",
                        help="time the steps of one run in this process (see the docstring)")
    parser.add_argument("--pages", action="store_true",
                        help="size and render time of hw3's feedback pages (see the docstring)")
    parser.add_argument("--against", type=Path, default=None, metavar="CHECKOUT",
                        help="with --pages: against another checkout's pages, in turn")
    parser.add_argument("--rounds", type=int, default=3, help="with --against: turns of each")
    args = parser.parse_args()
    if args.pages and args.against is not None:
        compare_pages(args.against, args.repeat, args.rounds)
        return
    if args.pages:
        pages(args.repeat)
        return
    if args.phases:
        for size in args.sizes:
            phases(size, args.jobs)
        return
    python = sys.executable
    mechgrade = [python, "-m", "mechgrade"]
    print(f"{'students':>8} {'grade s':>8} {'floor s':>8} {'ratio':>6} {'cores':>6}  "
          f"{'grade cpu s':>11} {'floor cpu s':>11} {'cpu ratio':>9}")
    for size in args.sizes:
        folder = make_class(size, args.dynamics)
        out = folder / "out"
        command = mechgrade + ["grade", str(folder / "assignment.yaml"),
                               str(folder / "submissions"), "--out", str(out)]
        if args.jobs is not None:
            command += ["--jobs", str(args.jobs)]
        floor = [python, "-c", FLOOR, str(folder / "submissions")]
        pairs = []
        for turn in range(args.repeat):
            if turn % 2:
                floor_run, run = timed(floor), graded(command, out, args.dynamics)
            else:
                run, floor_run = graded(command, out, args.dynamics), timed(floor)
            pairs.append((run, floor_run))
        wall, cpu = (statistics.median(run[i] for run, _ in pairs) for i in (0, 1))
        floor_wall, floor_cpu = (statistics.median(f[i] for _, f in pairs) for i in (0, 1))
        ratio, cpu_ratio = (statistics.median(run[i] / f[i] for run, f in pairs) for i in (0, 1))
        cores = statistics.median(run[1] / run[0] for run, _ in pairs)
        print(f"{size:>8} {wall:>8.2f} {floor_wall:>8.2f} {ratio:>6.2f} "
              f"{cores:>6.2f}  {cpu:>11.2f} {floor_cpu:>11.2f} "
              f"{cpu_ratio:>9.2f}", flush=True)


def _cpu() -> float:
    own, children = (resource.getrusage(who) for who in (resource.RUSAGE_SELF,
                                                         resource.RUSAGE_CHILDREN))
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def phases(size: int, jobs: int | None) -> None:
    """Print the wall and CPU seconds of each step of grading ``size`` students."""
    folder = make_class(size)
    out = folder / "out-phases"
    shutil.rmtree(out, ignore_errors=True)
    rows: list[tuple[str, float, float]] = []

    def step(name, work):
        wall, cpu = time.perf_counter(), _cpu()
        value = work()
        rows.append((name, time.perf_counter() - wall, _cpu() - cpu))
        return value

    step("import the solver", lambda: __import__("mechgrade.solve"))
    from mechgrade.grade.assignment import load_assignment
    from mechgrade.grade.run import grade_plan, plan_assignment
    from mechgrade.grade.submissions import read_submissions
    from mechgrade.grade.worked import shown_solutions
    from mechgrade.parallel import default_jobs
    from mechgrade.report.output import write_outputs
    from mechgrade.spec import load_problem

    jobs = jobs or default_jobs()
    spec = step("load the assignment", lambda: load_assignment(folder / "assignment.yaml"))
    problems = step("load the problems",
                    lambda: tuple(load_problem(ref.path) for ref in spec.problems))
    keys = {f"{p.id}.{objective}" for ref, p in zip(spec.problems, problems)
            for objective in ref.objectives or [o.id for o in p.objectives]}
    subs = step("read", lambda: read_submissions(folder / "submissions", keys=keys, jobs=jobs))
    plan = step("solve", lambda: plan_assignment(spec, problems=problems, jobs=jobs))
    report = step("judge", lambda: grade_plan(plan, subs, jobs=jobs))
    step("write the outputs", lambda: write_outputs(
        report, out, jobs=jobs, worked=shown_solutions(spec, report)))
    print(f"{size} students, --jobs {jobs}")
    print(f"  {'step':<22} {'wall s':>7} {'cpu s':>7}")
    for name, wall, cpu in rows:
        print(f"  {name:<22} {wall:>7.2f} {cpu:>7.2f}")
    total = [sum(r[i] for r in rows) for i in (1, 2)]
    solve = next(r for r in rows if r[0] == "solve")
    print(f"  {'total':<22} {total[0]:>7.2f} {total[1]:>7.2f}")
    print(f"  {'total but solving':<22} {total[0] - solve[1]:>7.2f} {total[1] - solve[2]:>7.2f}",
          flush=True)


def pages(repeat: int) -> None:
    """Print the size and the median render time of each hw3 feedback page, worked solution
    shown."""
    import inspect

    import mechgrade
    from mechgrade.grade.assignment import load_assignment
    from mechgrade.grade.run import grade_plan, plan_assignment
    from mechgrade.grade.submissions import read_submissions
    from mechgrade.grade.worked import feedback_solutions
    from mechgrade.report.output import (_context, _prompts, _render, _template, _worked_pages,
                                         feedback_names, template_environment, worked_context)
    from mechgrade.resources import shipped_dir
    from mechgrade.roster import read_roster
    from mechgrade.spec import load_problem

    example = shipped_dir("examples") / "hw3_dynamics"
    text = (example / "assignment.yaml").read_text(encoding="utf-8")
    text = text.replace("../../problems/", f"{shipped_dir('problems')}/")
    text = text.replace("  - pendulum_release.yaml", f"  - {example / 'pendulum_release.yaml'}")
    text = text.replace("policy:\n", "policy:\n  worked_solution: always\n")
    WORK.mkdir(parents=True, exist_ok=True)
    (WORK / "hw3.yaml").write_text(text, encoding="utf-8")
    spec = load_assignment(WORK / "hw3.yaml")
    problems = tuple(load_problem(ref.path) for ref in spec.problems)
    plan = plan_assignment(spec, problems=problems)
    keys = {f"{p.id}.{objective}" for ref, p in zip(spec.problems, problems)
            for objective in ref.objectives or [o.id for o in p.objectives]}
    subs = read_submissions(example / "submissions", keys=keys)
    report = grade_plan(plan, subs, read_roster(example / "roster.csv"))
    env = template_environment()
    worked = _worked_pages(feedback_solutions(spec, report), env, None)
    template = _template(env, "feedback.html.j2")
    prompts = _prompts(report)
    # a checkout from before the render took no templates folder
    folder = (None,) * (len(inspect.signature(_render).parameters) - 2)
    print(f"mechgrade from {Path(mechgrade.__file__).parents[2]}")
    print(f"  {'student':<14} {'bytes':>7} {'render ms':>10}")
    for name, student in zip(feedback_names(report), report.students):
        times = []
        for _ in range(repeat):
            start = time.perf_counter()
            context = _context(report, student, prompts)
            context.update(worked_context(worked, student, prompts))
            html = _render(template, context, *folder)
            times.append(time.perf_counter() - start)
        print(f"  {name:<14} {len(html.encode()):>7} {statistics.median(times) * 1e3:>10.2f}",
              flush=True)


def compare_pages(other: Path, repeat: int, rounds: int) -> None:
    """Print each hw3 page's size here and in the ``other`` checkout, and the median over
    ``rounds`` of the ratio of its render times (here / there), the two run in turn."""

    def measured(src: Path | None) -> dict[str, tuple[int, float]]:
        env = dict(os.environ)
        if src is not None:
            env["PYTHONPATH"] = str(src)
        done = subprocess.run([sys.executable, __file__, "--pages", "--repeat", str(repeat)],
                              capture_output=True, text=True, env=env, check=True)
        rows = [line.split() for line in done.stdout.splitlines()]
        return {r[0]: (int(r[1]), float(r[2])) for r in rows if len(r) == 3 and r[1].isdigit()}

    turns = [(measured(other.resolve() / "src"), measured(None)) for _ in range(rounds)]
    there, here = turns[0]
    print(f"this checkout against {other} ({rounds} rounds in turn, {repeat} renders each)")
    print(f"  {'student':<14} {'bytes':>7} {'there':>7} {'size':>7} {'render':>7}")
    for name, (size, _) in here.items():
        ratios = [h[name][1] / t[name][1] for t, h in turns]
        print(f"  {name:<14} {size:>7} {there[name][0]:>7} "
              f"{100 * (size / there[name][0] - 1):>+6.1f}% "
              f"{statistics.median(ratios):>6.2f}x", flush=True)


if __name__ == "__main__":
    main()
