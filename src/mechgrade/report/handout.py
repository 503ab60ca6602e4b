"""Write problem sheets: one HTML and one Markdown page per student, and ``givens.csv``.

Pages come from the Jinja templates ``handout.html.j2`` and ``handout.md.j2`` (``templates_dir``
overrides the shipped ones); ``<student>.txt`` is the student's answer file to fill in and hand
in, every answer key on a line of its own (named as the sheets and the feedback pages are);
``givens.csv`` lists every student's drawn givens, one row per student, for the instructor.

>>> import tempfile, pathlib
>>> from mechgrade.grade.sheets import *
>>> from mechgrade.grade.results import VariantGiven
>>> sheet = Sheet("hw2", "Homework 2", "20001", "Ana", "fall", (SheetProblem(
...     "p", "Pendulum", "Length 2 m.", (VariantGiven("p", "L", 2.0, "m"),),
...     (Question("p.speed", "Speed of the tip.", "m/s"),)),))
>>> out = pathlib.Path(tempfile.mkdtemp())
>>> [p.name for p in write_handouts((sheet,), out)]
['20001.html', '20001.md', '20001.txt', 'givens.csv']
>>> print((out / "20001.txt").read_text())
# Homework 2: answers of Ana (id 20001)
# Hand in this file, named 20001.txt: write each answer after its '=', as the
# line above it says. A line starting with # is not read.
<BLANKLINE>
# Pendulum
# 1. Speed of the tip. In m/s.
p.speed =
<BLANKLINE>
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
from ..grade.results import EXAMPLE_NUMBER
from ..grade.sheets import Question, Sheet
from ..outfolder import OutputKind
from ..spec.model import ObjectiveKind
from .output import _render, _template, _where, markdown_escape, template_environment

HANDOUT_TEMPLATES = ("handout.html.j2", "handout.md.j2")

HANDOUT_OUTPUTS = OutputKind("mechgrade handout", "givens.csv", ("*.html", "*.md", "givens.csv"))
"""What ``mechgrade handout`` writes into ``--out`` (see :mod:`mechgrade.outfolder`). The
patterns read only folders written before manifests, which held no answer files: a ``.txt``
beside such sheets is the instructor's."""


def write_handouts(sheets: tuple[Sheet, ...], out_dir: str | Path,
                   templates_dir: str | Path | None = None) -> tuple[Path, ...]:
    """Write every sheet (``<student>.html``, ``<student>.md``), answer file
    (``<student>.txt``) and ``givens.csv`` into ``out_dir``; returns the paths written.
    Raises :class:`MechgradeError`."""
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
            write_text(path, _render(template, sheet_context(sheet, suffix == ".md",
                                                             name + ".txt")))
            written.append(path)
        written.append(out / (name + ".txt"))
        write_text(written[-1], answer_file(sheet, name + ".txt"))
    written.append(out / "givens.csv")
    write_csv(written[-1], givens_table(sheets))
    return tuple(written)


def sheet_context(sheet: Sheet, markdown: bool = False, answer_file_name: str = "") -> dict:
    """What a handout template shows (every text escaped for Markdown with ``markdown``);
    ``answer_file_name`` the file the student hands in (default: ``<student id>.txt``).

    >>> from mechgrade.grade.sheets import Sheet
    >>> sheet_context(Sheet("hw", "Hw *2*", "a_", "", "s", ()), markdown=True)["title"]
    'Hw \\\\*2\\\\*'
    """
    from markupsafe import Markup

    text = markdown_escape if markdown else (lambda value: value)
    first = next((q for p in sheet.problems for q in p.questions), None)
    return {
        "title": text(sheet.assignment_title),
        "student": {"id": text(sheet.student_id),
                    "name": text(sheet.student_name or sheet.student_id)},
        # numbers drawn for this student (else everyone's sheet is the same)
        "own_numbers": any(p.givens for p in sheet.problems),
        "answer_file": text(answer_file_name or safe_file_names([sheet.student_id])[0]
                            + ".txt"),
        # one line of the answer file, as an example of its form
        "example": (f"{first.key} = {example_answer(first)}".rstrip() if first else ""),
        "problems": [{
            "id": text(p.id), "title": text(p.title), "statement": text(p.statement),
            "paragraphs": [text(part) for part in paragraphs(p.statement)],
            "givens": [{"name": text(g.name), "value": text(g.text)} for g in p.givens],
            "questions": [{"key": text(q.key), "prompt": text(q.prompt), "unit": text(q.unit),
                           "how": text(how_to_answer(q))} for q in p.questions],
            # SVG drawn by mechgrade from the model (never from student text); HTML only
            "picture": "" if markdown else Markup(p.picture),
        } for p in sheet.problems],
    }


def how_to_answer(question: Question) -> str:
    """What the answer to ``question`` is written as, for the sheet.

    >>> how_to_answer(Question("p.v", "Speed.", "ft/s"))
    'In ft/s.'
    >>> how_to_answer(Question("p.a", "Acceleration.", "m/s^2", ObjectiveKind.VECTOR))
    'In m/s^2, as components in brackets: (x, y, z).'
    >>> how_to_answer(Question("p.a", "In symbols.", "m/s^2", ObjectiveKind.SYMBOLIC))
    'As an expression, without a unit.'
    """
    if question.kind == ObjectiveKind.SYMBOLIC:
        return "As an expression, without a unit."
    shape = ", as components in brackets: (x, y, z)" if question.kind == ObjectiveKind.VECTOR \
        else ""
    if question.unit:
        return f"In {question.unit}{shape}."
    return f"A number{shape}." if shape else "A number without a unit."


def example_answer(question: Question) -> str:
    """An answer written as the sheet asks for it, its number no hint.

    >>> example_answer(Question("p.a", "Acceleration.", "m/s^2", ObjectiveKind.VECTOR))
    '(12.5, -3) m/s^2'
    """
    if question.kind == ObjectiveKind.SYMBOLIC:
        return ""
    value = f"({EXAMPLE_NUMBER}, -3)" if question.kind == ObjectiveKind.VECTOR \
        else EXAMPLE_NUMBER
    return f"{value} {question.unit}".rstrip()


def answer_file(sheet: Sheet, name: str) -> str:
    """The answer file of ``sheet``, to fill in and hand in as ``name``: every question as a
    comment, then its key and ``=``, in the sheet's order (the grader reads ``key = answer``
    lines, and ``#`` starts a comment: :mod:`mechgrade.grade.submissions`)."""
    who = sheet.student_name or sheet.student_id
    lines = [f"# {_comment(sheet.assignment_title)}: answers of {_comment(who)} "
             f"(id {_comment(sheet.student_id)})",
             f"# Hand in this file, named {name}: write each answer after its '=', as the",
             "# line above it says. A line starting with # is not read."]
    for problem in sheet.problems:
        lines += ["", f"# {_comment(problem.title)}"]
        for number, question in enumerate(problem.questions, start=1):
            lines += [f"# {number}. {_comment(question.prompt)} {how_to_answer(question)}",
                      f"{question.key} ="]
    return "\n".join(lines) + "\n"


def _comment(text: str) -> str:
    """``text`` on one line, safe inside a comment line of the answer file."""
    return " ".join(text.split())


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
