"""``mechgrade schema``: where the problem-spec JSON Schema is, for editors."""

from __future__ import annotations

import click

from ..files import write_text
from ..spec.load import SCHEMA_PATH
from .common import main, reports_errors, say


@main.command("schema")
@click.option("--out", type=click.Path(), help="Write a copy of the schema to this file.")
@reports_errors
def schema_command(out: str | None) -> None:
    """Print the path of the problem-spec JSON Schema, or write a copy of it to --out.

    Point an editor's YAML support at it to get completion, descriptions and errors while
    writing a problem file (docs/spec.md, "Editor set-up").
    """
    if out is None:
        say(str(SCHEMA_PATH))
        return
    write_text(out, SCHEMA_PATH.read_text(encoding="utf-8"))
    say(f"wrote {out}")
