"""``mechgrade handout``: each student's problem sheet with their own numbers."""

from __future__ import annotations

from pathlib import Path

import click

from ..grade.assignment import load_assignment
from ..grade.run import plan_assignment
from ..grade.variants import handout_sheets
from ..report.handout import write_handouts
from ..roster import read_roster
from .common import main, reports_errors, say, warn_about_the_cache


@main.command("handout")
@click.argument("assignment", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--roster", required=True,
              type=click.Path(exists=True, dir_okay=False, path_type=Path),
              help="Class roster (Canvas, Moodle or plain CSV): one sheet per student.")
@click.option("--out", "out_dir", required=True, type=click.Path(file_okay=False, path_type=Path),
              help="Folder for <student>.html, <student>.md and givens.csv.")
@click.option("--templates", "templates_dir",
              type=click.Path(exists=True, file_okay=False, path_type=Path),
              help="Folder with handout.html.j2 and handout.md.j2 to use instead of the "
                   "shipped templates.")
@reports_errors
def handout(assignment: Path, roster: Path, out_dir: Path, templates_dir: Path | None) -> None:
    """Write every roster student's sheet for ASSIGNMENT, with their own numbers, and
    givens.csv (every student's givens) for the instructor.

    A student's numbers come from the assignment's variants seed and their roster id: the
    same numbers grading uses.
    """
    spec = load_assignment(assignment)
    warn_about_the_cache()
    plan = plan_assignment(spec)
    students = [(s.id, s.name) for s in read_roster(roster).students]
    written = write_handouts(handout_sheets(plan, students), out_dir, templates_dir)
    say(f"Wrote {len(students)} sheets and givens.csv to {out_dir}/ "
        f"({len(written)} files)")
