"""``mechgrade new``: write a commented starting spec that passes ``mechgrade check``."""

from __future__ import annotations

import click

from ..spec.starter import TEMPLATES, write_starter
from .common import main, reports_errors, say


@main.command("new")
@click.argument("problem_id", metavar="ID")
@click.option("--template", type=click.Choice(TEMPLATES), default=TEMPLATES[0],
              show_default=True, help="The kind of problem to start from.")
@click.option("--out", type=click.Path(file_okay=False), default=".", show_default=True,
              help="The folder to write ID.yaml into (it must exist).")
@reports_errors
def new_command(problem_id: str, template: str, out: str) -> None:
    """Write ID.yaml, a commented starting spec that passes `mechgrade check` as written.

    ID is letters, digits and '_', starting with a letter. An existing file is never
    overwritten.
    """
    path = write_starter(problem_id, template, out)
    say(f"wrote {path} (template {template})")
    say(f"next: edit it, and watch it with `mechgrade check --watch {path}`")
