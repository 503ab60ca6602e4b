"""``mechgrade export-questions``: an assignment's objectives as quiz questions for an LMS."""

from __future__ import annotations

from pathlib import Path

import click

from .common import main, reports_errors, say, warn_about_the_cache

FORMATS = ("canvas-qti", "moodle-xml")
DEFAULT_VARIANTS = 20


@main.command("export-questions")
@click.argument("assignment", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--format", "fmt", required=True, type=click.Choice(FORMATS),
              help="canvas-qti: a QTI package for Canvas's quiz import; moodle-xml: Moodle's "
                   "question XML.")
@click.option("--variants", "count", type=click.IntRange(1, 500), default=DEFAULT_VARIANTS,
              show_default=True, help="Variants drawn, verified and solved per problem that "
                                      "draws its givens.")
@click.option("--out", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="File to write (default: <assignment id>-questions.zip or .xml).")
@reports_errors
def export_questions(assignment: Path, fmt: str, count: int, out: Path | None) -> None:
    """Write ASSIGNMENT's objectives as quiz questions for Canvas (QTI) or Moodle (XML), each
    problem with its own verified variants."""
    # Here, not at the top: sympy and the solver load only when a run starts (not for --help).
    from ..export.questions import DEFAULT_SUFFIX, QUESTION_WRITERS
    from ..grade.assignment import load_assignment
    from ..grade.questions import EssayItem, question_bank
    from ..grade.run import plan_assignment

    spec = load_assignment(assignment)
    warn_about_the_cache()
    bank = question_bank(plan_assignment(spec), count)
    out = out if out is not None else Path(f"{spec.id}-questions{DEFAULT_SUFFIX[fmt]}")
    for note in QUESTION_WRITERS[fmt](bank, out):
        say(f"note: {note}", err=True)
    essays = sum(isinstance(item, EssayItem) for item in bank.items)
    numbers = len(bank.items) - essays
    say(f"wrote {numbers} numerical question{'s' * (numbers != 1)} "
        f"({bank.variants} variant{'s' * (bank.variants != 1)} each where the problem draws "
        f"its givens) and {essays} essay question{'s' * (essays != 1)} (graded by mechgrade "
        f"from the quiz's responses) to {out}")
