"""Write problem sheets: one HTML and one Markdown page per student, and ``givens.csv``.

Pages come from the Jinja templates ``handout.html.j2`` and ``handout.md.j2`` (``templates_dir``
overrides the shipped ones); ``givens.csv`` lists every student's drawn givens, one row per
student, for the instructor.

>>> import tempfile, pathlib
>>> from mechgrade.grade.sheets import *
>>> from mechgrade.grade.results import VariantGiven
>>> sheet = Sheet("hw2", "Homework 2", "20001", "Ana", "fall", (SheetProblem(
...     "p", "Pendulum", "Length 2 m.", (VariantGiven("p", "L", 2.0, "m"),),
...     (Question("p.speed", "Speed of the tip.", "m/s"),)),))
>>> out = pathlib.Path(tempfile.mkdtemp())
>>> [p.name for p in write_handouts((sheet,), out)]
['20001.html', '20001.md', 'givens.csv']
>>> print((out / "givens.csv").read_text().strip())
id,name,seed,p.L,p.L unit,p draw
20001,Ana,fall,2,m,0
"""

from __future__ import annotations

import re
from pathlib import Path

from ..errors import MechgradeError
from ..export.cells import write_csv
from ..files import safe_file_names, write_text
from ..grade.sheets import Sheet
from ..outfolder import OutputKind
from .output import _render, _template, _where, markdown_escape, template_environment

HANDOUT_TEMPLATES = ("handout.html.j2", "handout.md.j2")

HANDOUT_OUTPUTS = OutputKind("mechgrade handout", "givens.csv", ("*.html", "*.md", "givens.csv"))
"""What ``mechgrade handout`` writes into ``--out`` (see :mod:`mechgrade.outfolder`)."""


def write_handouts(sheets: tuple[Sheet, ...], out_dir: str | Path,
                   templates_dir: str | Path | None = None) -> tuple[Path, ...]:
    """Write every sheet (``<student>.html``, ``<student>.md``) and ``givens.csv`` into
    ``out_dir``; returns the paths written. Raises :class:`MechgradeError`."""
    out = Path(out_dir)
    env = template_environment(templates_dir)
    templates = [_template(env, name) for name in HANDOUT_TEMPLATES]
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise MechgradeError(f"cannot create the output folder ({exc.strerror or exc})",
                             where=_where(out)) from None
    written = []
    for sheet, name in zip(sheets, safe_file_names([s.student_id for s in sheets])):
        for template, suffix in zip(templates, (".html", ".md")):
            path = out / (name + suffix)
            write_text(path, _render(template, sheet_context(sheet, suffix == ".md"),
                                     templates_dir))
            written.append(path)
    written.append(out / "givens.csv")
    write_csv(written[-1], givens_table(sheets))
    return tuple(written)


def sheet_context(sheet: Sheet, markdown: bool = False) -> dict:
    """What a handout template shows (every text escaped for Markdown with ``markdown``).

    >>> from mechgrade.grade.sheets import Sheet
    >>> sheet_context(Sheet("hw", "Hw *2*", "a_", "", "s", ()), markdown=True)["title"]
    'Hw \\\\*2\\\\*'
    """
    from markupsafe import Markup

    text = markdown_escape if markdown else (lambda value: value)
    return {
        "title": text(sheet.assignment_title),
        "student": {"id": text(sheet.student_id),
                    "name": text(sheet.student_name or sheet.student_id)},
        "problems": [{
            "id": text(p.id), "title": text(p.title), "statement": text(p.statement),
            "paragraphs": [text(part) for part in paragraphs(p.statement)],
            "givens": [{"name": text(g.name), "value": text(g.text)} for g in p.givens],
            "questions": [{"key": text(q.key), "prompt": text(q.prompt), "unit": text(q.unit)}
                          for q in p.questions],
            # SVG drawn by mechgrade from the model (never from student text); HTML only
            "picture": "" if markdown else Markup(p.picture),
        } for p in sheet.problems],
    }


def paragraphs(statement: str) -> list[str]:
    """A statement's paragraphs (parted by blank lines), each one line: a spec wraps its
    prose to the file's width, a page to the reader's.

    >>> paragraphs("A rod of length\\nL turns.\\n\\nFind its speed.\\n")
    ['A rod of length L turns.', 'Find its speed.']
    """
    parts = re.split(r"\n\s*\n", statement.strip())
    return [" ".join(part.split()) for part in parts if part.strip()]


def givens_table(sheets: tuple[Sheet, ...]) -> list[list[object]]:
    """``givens.csv``: id, name, seed, then each drawn given's value and unit and each
    problem's draw number (a redrawn variant has a draw above 0)."""
    columns: list[tuple[str, str]] = []
    for sheet in sheets[:1]:
        for problem in sheet.problems:
            columns += [(problem.id, g.name) for g in problem.givens]
    header: list[object] = ["id", "name", "seed"]
    problems = list(dict.fromkeys(pid for pid, _ in columns))
    for pid, name in columns:
        header += [f"{pid}.{name}", f"{pid}.{name} unit"]
    header += [f"{pid} draw" for pid in problems]
    rows: list[list[object]] = [header]
    for sheet in sheets:
        values = {(p.id, g.name): g for p in sheet.problems for g in p.givens}
        row: list[object] = [sheet.student_id, sheet.student_name, sheet.seed]
        for key in columns:
            given = values[key]
            row += [f"{given.value:g}", given.text[len(f"{given.value:g}"):].strip()]
        draws = {p.id: p.givens[0].draw for p in sheet.problems if p.givens}
        row += [draws[pid] for pid in problems]
        rows.append(row)
    return rows
