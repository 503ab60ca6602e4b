"""``mechgrade check``: validate problem files and run their ``expect:`` tests."""

from __future__ import annotations

import click

from ..check import CheckReport, check_paths, check_problem, problem_files, watch
from ..errors import SpecError
from .common import main, reports_errors, say, warn_about_the_cache


@main.command("check")
@click.argument("paths", nargs=-1, required=True, type=click.Path())
@click.option("-v", "--verbose", is_flag=True, help="Also show passing tests and book notes.")
@click.option("--watch", "watching", is_flag=True,
              help="Re-check each file when it is saved and show its solved values; Ctrl-C stops.")
@click.option("--max-runs", type=click.IntRange(min=1),
              help="With --watch: stop after this many runs (the first check is run 1).")
@click.option("--interval", type=click.FloatRange(min=0.01),
              help="With --watch: seconds between looks at the files [default: 0.5].")
@click.option("--variants", "variant_count", type=click.IntRange(0, 100_000), default=200,
              show_default=True, help="Variants drawn and verified per problem with a "
                                      "variants: section (0: none).")
@reports_errors
def check_command(paths: tuple[str, ...], verbose: bool, watching: bool, max_runs: int | None,
                  interval: float | None, variant_count: int) -> None:
    """Validate problem files (or folders of them) and run every expect: test.

    Every error of a file is listed, one per line, in file order; warnings follow the tests.
    Exits 0 only if every file loads, solves and passes its tests (warnings do not fail).
    With --watch, checks every file, then each file again when it changes (the -v output plus
    its solved values), until Ctrl-C or --max-runs; it then exits 0.
    """
    if not watching and (max_runs is not None or interval is not None):
        raise click.UsageError("--max-runs and --interval need --watch")
    if not problem_files(paths):
        raise SpecError(f"expected problem files (*.yaml), found none in {', '.join(paths)}")
    warn_about_the_cache()
    if watching:
        _watch(paths, max_runs, 0.5 if interval is None else interval, variant_count)
        return
    reports = check_paths(paths)
    failures = sum(_print_report(report, verbose, variant_count=variant_count)
                   for report in reports)
    say(f"{len(reports)} file(s), {failures} failing")
    if failures:
        raise SystemExit(1)


def _watch(paths: tuple[str, ...], max_runs: int | None, interval: float,
           variant_count: int) -> None:
    """Check on every save until Ctrl-C or ``max_runs``; a failing spec is shown, not an exit."""
    runs = 0
    try:
        for changed in watch(paths, interval):
            runs += 1
            for path in changed:
                _print_report(check_problem(path), verbose=True, values=True,
                              variant_count=variant_count)
            if max_runs is not None and runs >= max_runs:
                break
            say(f"-- run {runs} done; watching {', '.join(paths)} (Ctrl-C to stop)")
    except KeyboardInterrupt:
        say("")
    say(f"stopped after {runs} run(s)")


def _print_report(report: CheckReport, verbose: bool, values: bool = False,
                  variant_count: int = 0) -> bool:
    """Print one file's report (with ``variant_count`` variants drawn and verified, for a
    problem with variants); whether it failed."""
    if report.error:
        say(f"FAIL {report.path}")
        for line in report.error.splitlines() + list(report.warnings):
            say(f"  {line}")
        return True
    bad = [o for o in report.outcomes if not o.passed]
    refused = []
    if variant_count and report.variants:
        from ..grade.variants import variant_lines  # drawing variants: only for such problems

        refused = variant_lines(report.path, variant_count)
    failed = bool(bad or report.faults or refused)
    status = "FAIL" if failed else "ok  "
    say(f"{status} {report.path} ({len(report.outcomes)} tests, DOF {report.dof})")
    for outcome in report.outcomes:
        if not outcome.passed or verbose:
            mark = "FAIL" if not outcome.passed else "pass"
            say(f"  {mark} {outcome.objective}: {outcome.message}")
        if verbose and outcome.book:
            say(f"       book prints: {outcome.book}")
        if verbose and outcome.note:
            say(f"       note: {outcome.note}")
    for line in (*report.faults, *report.warnings, *report.separations, *refused):
        say(f"  {line}")
    if verbose and report.untested:
        say(f"  untested: {', '.join(report.untested)}")
    if verbose and report.state:
        say("  state at the instant: " + "; ".join(report.state))
    if values and report.results:
        from .solve import value_text  # imports the mechanics (sympy): only when watching

        say("  solved values:")
        width = max(len(r.id) for r in report.results)
        for result in report.results:
            say(f"    {result.id.ljust(width)}  {value_text(result)}")
    return failed
