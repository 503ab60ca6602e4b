"""The worked solution of a problem on a page: a fragment for feedback pages (rendered once per
problem or variant, then shared by every student's page), a page of its own
(``mechgrade solve --steps --format html``) and Markdown. The MathML and the SVG come
ready-made from :mod:`mechgrade.solve.worked`; nothing here imports sympy. The fragments are
made by :func:`~mechgrade.report.output.worked_html` and
:func:`~mechgrade.report.output.worked_markdown`.

>>> from mechgrade.solve.worked import WorkedSolution, WorkedStep
>>> from mechgrade.report.output import anchor
>>> w = WorkedSolution("p", "Pendulum", (WorkedStep("givens", "Givens", ("L = 2 m",)),), "<svg/>",
...                     places=(("L", "given_sign", "givens"),))
>>> print(steps_markdown(w).splitlines()[2])
## Pendulum
>>> f'id="{anchor("p", "givens")}"' in steps_html(w)
True
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .output import (_render, _template, markdown_escape, marker_defs, template_environment,
                     worked_html, worked_markdown)

if TYPE_CHECKING:  # the solver package loads sympy: a report only reads its dataclass
    from ..solve.worked import WorkedSolution


def steps_html(worked: WorkedSolution, templates_dir=None) -> str:
    """The worked solution as a page of its own (``steps.html.j2``)."""
    from markupsafe import Markup

    env = template_environment(templates_dir)
    markers: dict[str, str] = {}
    context = {"title": f"{worked.problem}: {worked.title}",
               "worked": worked_html(worked, templates_dir, env, markers)}
    context["markers"] = Markup(marker_defs(markers))
    return _render(_template(env, "steps.html.j2"), context)


def steps_markdown(worked: WorkedSolution) -> str:
    """The worked solution as a Markdown page (``mechgrade solve --steps --format md``)."""
    return f"# {markdown_escape(worked.problem)}\n\n" + worked_markdown(worked, 2)
