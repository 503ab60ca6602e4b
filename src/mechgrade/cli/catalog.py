"""``mechgrade catalog``: write a browsable HTML catalogue of problem files."""

from __future__ import annotations

import click

from ..check import problem_files
from ..errors import SpecError
from ..report.catalog import write_catalog
from ..grade.catalog import catalog_entries
from .common import main, reports_errors, say


@main.command("catalog")
@click.argument("paths", nargs=-1, required=True, type=click.Path())
@click.option("--out", "out_dir", required=True, type=click.Path(file_okay=False),
              help="Folder to write index.html and problems/<id>.html into.")
@click.option("--templates", "templates_dir", type=click.Path(file_okay=False), default=None,
              help="Folder of Jinja templates replacing the shipped catalog_*.html.j2.")
@reports_errors
def catalog_command(paths: tuple[str, ...], out_dir: str, templates_dir: str | None) -> None:
    """Write a browsable HTML catalogue of the problems in PATHS (files or folders).

    index.html lists every problem with its topics (the spec's tags:) and how it is analysed,
    with filters; problems/<id>.html shows one problem: statement, picture, objectives with
    their answers, worked solution and the variants it draws. A file that does not load or
    solve is listed with its error on the index and on stderr, the others are still written,
    and the command exits 1.
    """
    files = problem_files(paths)
    if not files:
        raise SpecError(f"expected problem files (*.yaml), found none in {', '.join(paths)}")
    entries, faults = catalog_entries(files)
    written = write_catalog(entries, faults, out_dir, templates_dir)
    unsolved = [(e, o) for e in entries for o in e.failures]
    for fault in faults:
        say(fault.message, err=True)
    for _, objective in unsolved:
        say(objective.answer, err=True)  # the solver's message says where and why
    say(f"wrote {written[0]} and {len(written) - 1} problem page(s); "
               f"{len(faults)} file(s) could not be shown")
    if faults or unsolved:
        raise SystemExit(1)
