"""``mechgrade check``: validate problem files and run their ``expect:`` tests."""

from __future__ import annotations

import click

from ..check import check_paths, problem_files
from ..errors import SpecError
from .common import main, reports_errors


@main.command("check")
@click.argument("paths", nargs=-1, required=True, type=click.Path())
@click.option("-v", "--verbose", is_flag=True, help="Also show passing tests and book notes.")
@reports_errors
def check_command(paths: tuple[str, ...], verbose: bool) -> None:
    """Validate problem files (or folders of them) and run every expect: test.

    Every error of a file is listed, one per line, in file order; warnings follow the tests.
    Exits 0 only if every file loads, solves and passes its tests (warnings do not fail).
    """
    if not problem_files(paths):
        raise SpecError(f"expected problem files (*.yaml), found none in {', '.join(paths)}")
    failures = 0
    reports = check_paths(paths)
    for report in reports:
        if report.error:
            failures += 1
            click.echo(f"FAIL {report.path}")
            for line in report.error.splitlines() + list(report.warnings):
                click.echo(f"  {line}")
            continue
        bad = [o for o in report.outcomes if not o.passed]
        failed = bool(bad or report.faults)
        failures += failed
        status = "FAIL" if failed else "ok  "
        click.echo(f"{status} {report.path} ({len(report.outcomes)} tests, DOF {report.dof})")
        for outcome in report.outcomes:
            if not outcome.passed or verbose:
                mark = "FAIL" if not outcome.passed else "pass"
                click.echo(f"  {mark} {outcome.objective}: {outcome.message}")
            if verbose and outcome.book:
                click.echo(f"       book prints: {outcome.book}")
            if verbose and outcome.note:
                click.echo(f"       note: {outcome.note}")
        for line in report.faults + report.warnings + report.separations:
            click.echo(f"  {line}")
        if verbose and report.untested:
            click.echo(f"  untested: {', '.join(report.untested)}")
        if verbose and report.state:
            click.echo("  state at the instant: " + "; ".join(report.state))
    click.echo(f"{len(reports)} file(s), {failures} failing")
    if failures:
        raise SystemExit(1)
