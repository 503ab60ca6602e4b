"""Write a browsable catalogue of problems: ``index.html`` (every problem with its topics and
analyses, filters to narrow the list, the files that could not be shown) and one page per
problem in ``problems/`` (statement, picture, objectives with their answers, worked solution,
variants), from the Jinja templates ``catalog_index.html.j2`` and ``catalog_problem.html.j2``
(``templates_dir`` overrides the shipped ones). The entries come ready-made from
:mod:`mechgrade.grade.catalog`; nothing here imports sympy.

>>> import tempfile, pathlib
>>> from mechgrade.grade.catalog import CatalogFault
>>> out = pathlib.Path(tempfile.mkdtemp())
>>> [p.relative_to(out).as_posix() for p in write_catalog((), (CatalogFault("x.yaml", "bad"),), out)]
['index.html']
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import MechgradeError
from ..files import safe_file_names, write_text
from ..grade.results import unit_text
from ..spec.variant_model import Choices, Draw, Integers, RoundedRange, SteppedRange
from .handout import paragraphs
from .output import _render, _template, _where, template_environment, worked_html

if TYPE_CHECKING:  # the entries come ready-made: reading them needs no solver
    from ..grade.catalog import CatalogEntry, CatalogFault

CATALOG_TEMPLATES = ("catalog_index.html.j2", "catalog_problem.html.j2")


def write_catalog(entries: tuple[CatalogEntry, ...], faults: tuple[CatalogFault, ...],
                  out_dir: str | Path, templates_dir: str | Path | None = None
                  ) -> tuple[Path, ...]:
    """Write ``index.html`` and ``problems/<id>.html`` for every entry into ``out_dir``; the
    index lists ``faults`` too. Returns the paths written. Raises :class:`MechgradeError`."""
    out = Path(out_dir)
    env = template_environment(templates_dir)
    index, page = (_template(env, name) for name in CATALOG_TEMPLATES)
    try:
        (out / "problems").mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise MechgradeError(f"cannot create the output folder ({exc.strerror or exc})",
                             where=_where(out)) from None
    names = safe_file_names([e.id for e in entries])
    written = [out / "index.html"]
    write_text(written[0], _render(index, index_context(entries, faults, names)))
    for entry, name in zip(entries, names):
        path = out / "problems" / f"{name}.html"
        context = problem_context(entry, worked_html(replace(entry.worked, picture=""),
                                                     templates_dir, env))
        write_text(path, _render(page, context))
        written.append(path)
    return tuple(written)


def index_context(entries, faults, names) -> dict:
    """What ``catalog_index.html.j2`` shows: the problems, every topic and analysis once (for
    the filters), and the faults."""
    topics = sorted({t for e in entries for t in e.tags})
    kinds = list(dict.fromkeys(a.value for e in entries for a in e.analyses))
    return {
        "title": "Problem catalogue",
        "count": len(entries),
        "topics": [{"value": t, "label": t.replace("-", " ")} for t in topics],
        "analyses": kinds,
        "problems": [{
            "id": e.id, "title": e.title, "href": f"problems/{name}.html",
            "tags": [{"value": t, "label": t.replace("-", " ")} for t in e.tags],
            "analyses": [a.value for a in e.analyses],
            "objectives": len(e.objectives),
            "variants": bool(e.variants),
            "failures": len(e.failures),
            "search": " ".join((e.id, e.title, e.statement, *e.tags)).lower(),
        } for e, name in zip(entries, names)],
        "faults": [{"file": f.file, "message": f.message} for f in faults],
    }


def problem_context(entry: CatalogEntry, worked) -> dict:
    """What ``catalog_problem.html.j2`` shows for one problem (``worked``: its worked solution
    as safe markup, without the picture, which the page shows beside the statement)."""
    from markupsafe import Markup

    return {
        "title": f"{entry.id}: {entry.title}",
        "heading": entry.title,
        "id": entry.id,
        "source": entry.source,
        "file": entry.file,
        "statement": paragraphs(entry.statement),
        "tags": [t.replace("-", " ") for t in entry.tags],
        "analyses": [a.value for a in entry.analyses],
        # trusted: generated from the problem file's model, never from student text
        "picture": Markup(entry.worked.picture),
        "objectives": [{"id": o.id, "prompt": o.prompt, "kind": o.kind, "answer": o.answer,
                        "solved": o.solved} for o in entry.objectives],
        "variants": [draw_text(d) for d in entry.variants],
        "requires": list(entry.requires),
        "warnings": list(entry.warnings),
        "worked": worked,
    }


def draw_text(draw: Draw) -> str:
    """What a drawn given ranges over, in its unit.

    >>> draw_text(Choices("theta", "deg", (20.0, 30.0)))
    'theta: one of 20, 30 deg'
    >>> draw_text(SteppedRange("L", "ft", 1.5, 4.0, 0.1))
    'L: from 1.5 to 4 ft in steps of 0.1 ft'
    """
    unit = "" if draw.unit in ("", "1") else " " + unit_text(draw.unit)
    if isinstance(draw, SteppedRange):
        text = f"from {draw.low:g} to {draw.high:g}{unit} in steps of {draw.step:g}{unit}"
    elif isinstance(draw, RoundedRange):
        text = (f"from {draw.low:g} to {draw.high:g}{unit}, rounded to {draw.sig_figs} "
                "significant figures")
    elif isinstance(draw, Choices):
        text = "one of " + ", ".join(f"{v:g}" for v in draw.values) + unit
    elif isinstance(draw, Integers):
        text = f"a whole number from {draw.low} to {draw.high}{unit}"
    else:  # a new kind of draw must say how it reads
        raise TypeError(f"no text for a draw of kind {type(draw).__name__}")
    return f"{draw.key}: {text}"
