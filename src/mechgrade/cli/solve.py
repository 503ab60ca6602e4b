"""``mechgrade solve``: print a problem's reference answers (text or JSON), or its derivation."""

from __future__ import annotations

import json

import click

from ..files import write_text
from ..mechanics import derivation
from ..solve.worked import answer_text as value_text
from ..solve import solve as solve_problem
from ..spec import load_problem
from ..spec.model import ObjectiveKind
from .common import main, reports_errors, say, warn_about_the_cache


def solution_json(problem, solution) -> dict:
    """The public ``--format json`` document (see docs/cli.md)."""
    objectives = {}
    for r in solution.results:
        value = r.value if r.kind != ObjectiveKind.VECTOR else list(r.value)
        objectives[r.id] = {"value": value, "unit": r.unit, "frame": r.frame, "expr": r.expr}
    return {"problem": problem.id, "objectives": objectives,
            "failures": {f.id: str(f.error) for f in solution.failures},
            "state": [{"name": v.name, "value": v.value, "unit": v.unit, "given": v.given}
                      for v in solution.state],
            "warnings": [str(w) for w in problem.warnings + solution.warnings]}


@main.command("solve")
@click.argument("problem_file", type=click.Path(dir_okay=False))
@click.option("--format", "fmt", type=click.Choice(["text", "json", "html", "md"]),
              default="text", show_default=True,
              help="Output format (html and md are the worked derivation: --steps).")
@click.option("--steps", is_flag=True, help="Print the derivation in the write-up order.")
@click.option("--plot", type=click.Path(dir_okay=False), default=None,
              help="Also draw the mechanism at the instant as an SVG file.")
@reports_errors
def solve_command(problem_file: str, fmt: str, steps: bool, plot: str | None) -> None:
    """Solve PROBLEM_FILE and print each objective's reference answer."""
    problem = load_problem(problem_file)
    warn_about_the_cache()
    solution = solve_problem(problem)
    if plot:
        from ..solve.picture import picture_svg, scene

        write_text(plot, picture_svg(scene(problem, solution)))
    failed = {f.id: f.error for f in solution.failures}
    if fmt == "json":
        say(json.dumps(solution_json(problem, solution), indent=2))
    elif fmt in ("html", "md"):
        # the write-up's templates are only needed here
        from ..report.worked import steps_html, steps_markdown
        from ..solve.worked import worked_solution

        worked = worked_solution(problem, solution)
        say(steps_html(worked) if fmt == "html" else steps_markdown(worked), nl=False)
    else:
        _print_text(problem, solution, failed, steps)
    if failed:
        click.get_current_context().exit(next(iter(failed.values())).exit_code)


def _objective_lines(problem, solution, failed) -> list[str]:
    results = {r.id: r for r in solution.results}
    ids = [o.id for o in problem.objectives if o.id in results or o.id in failed]
    width = max(len(i) for i in ids)
    return [f"{oid.ljust(width)}  " + (value_text(results[oid]) if oid in results
                                       else f"error: {failed[oid]}") for oid in ids]


def _print_text(problem, solution, failed, steps: bool) -> None:
    say(f"{problem.id}: {problem.title}")
    if steps:
        for section, lines in derivation(problem, solution.dof):
            say(f"\n{section}")
            for line in lines or ("(none)",):
                say(f"  {line}")
        say("\nObjectives")
    for line in _objective_lines(problem, solution, failed):
        say(f"  {line}")
    if solution.state:
        say("State at the instant")
        for s in solution.state:
            say(f"  {s}")
    for warning in problem.warnings + solution.warnings:
        say(str(warning))
    from ..check import tolerance_faults  # check refuses these; solve says so

    for fault in tolerance_faults(problem, solution):
        say(fault)
