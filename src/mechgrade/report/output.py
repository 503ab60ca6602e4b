"""Write a grading run's outputs: feedback for every student, ``results.json`` and the CSVs.

``out_dir`` receives ``results.json`` (the contract of :mod:`mechgrade.grade.results`),
``grades.csv`` and ``results.csv`` (written by the exporters registry) and
``feedback/<student>.html`` and ``feedback/<student>.md`` rendered by the Jinja templates
``feedback.html.j2`` and ``feedback.md.j2`` (``templates_dir`` overrides the shipped ones).
Templates only present: every value they show is prepared here. Every file is written to a
temporary file and moved into place, so a crash never leaves half a file.

>>> import tempfile, pathlib
>>> from mechgrade.grade.results import *
>>> report = GradeReport(AssignmentInfo("hw1", "Homework 1"),
...     (ObjectiveInfo("p", "v", "Speed of A.", 2.0),),
...     (StudentResult("ana", "Ana", "graded", 2.0, 2.0,
...         (AnswerResult("p", "v", "7 m/s", "correct", 2.0, 2.0, read_back="7 m/s"),)),))
>>> out = pathlib.Path(tempfile.mkdtemp())
>>> [p.relative_to(out).as_posix() for p in write_outputs(report, out).paths]
['results.json', 'grades.csv', 'results.csv', 'feedback/ana.html', 'feedback/ana.md']
"""

from __future__ import annotations

import multiprocessing
import re
import signal
from dataclasses import dataclass, replace
from enum import Enum
from functools import cached_property, lru_cache
from html import escape as html_escape
from pathlib import Path
from typing import TYPE_CHECKING, Any

from markupsafe import Markup

from ..errors import Location, MechgradeError, brief_exception
from ..files import json_text, safe_file_names, write_json, write_text
from ..export import EXPORTERS
from ..expressions.notation import textbook, textbook_html
from ..outfolder import OutputKind
from ..parallel import outcome, worker_started
from ..resources import shipped_dir
from ..grade.results import (ECF_DIAGNOSIS, EQUATIONS_OBJECTIVE, AnswerResult, GradeReport, Status, StudentResult,
                             Verdict)

if TYPE_CHECKING:  # the worked solutions come ready-made: reading them needs no solver
    from multiprocessing.connection import Connection
    from multiprocessing.process import BaseProcess

    from ..grade.worked import FeedbackSolutions
    from ..solve.worked import WorkedSolution

TEMPLATE_NAMES = ("feedback.html.j2", "feedback.md.j2")

GRADE_OUTPUTS = OutputKind("mechgrade grade", "results.json", (
    "results.json", "grades.csv", "results.csv", "feedback/*.html", "feedback/*.md"))
"""What ``mechgrade grade`` writes into ``--out`` (see :mod:`mechgrade.outfolder`)."""

VERDICT_LABELS = {
    Verdict.CORRECT: "Correct",
    Verdict.PARTIAL: "Partly correct",
    Verdict.INCORRECT: "Incorrect",
    Verdict.UNREADABLE: "Could not be read",
    Verdict.MISSING: "No answer",
    Verdict.NOT_EVALUATED: "Not evaluated",
}
STATUS_LABELS = {
    Status.GRADED: "Graded",
    Status.MISSING: "No submission",
    Status.UNREADABLE: "Submission could not be read",
    Status.CONFLICT: "Not graded: more than one match with the roster",
}


@dataclass(frozen=True)
class Written:
    """What :func:`write_outputs` wrote: the paths in order, and the report as written (a fault
    met while rendering one student's feedback is added to its ``internal_errors``)."""

    paths: tuple[Path, ...]
    report: GradeReport


def write_outputs(report: GradeReport, out_dir: str | Path, templates_dir: str | Path | None = None,
                  *, roster=None, jobs: int = 1,
                  worked: FeedbackSolutions | None = None) -> Written:
    """Write every output of ``report`` into ``out_dir``.

    With ``worked`` every feedback page shows the worked solution and picture of each
    problem (the student's own variant), each rendered once and shared by the pages, with
    the step where a student's named mistake happens highlighted.

    Rendering one student's feedback is one unit of work: a fault of mechgrade's there gives
    that student a short page saying so, and the other outputs are written as usual. The pages
    are rendered and written by this process and ``jobs - 1`` forked helpers (the files are the
    same for any ``jobs``). Raises :class:`~mechgrade.errors.MechgradeError` when a template is
    missing or broken (then no file is written), or the folder cannot be written.
    """
    out = Path(out_dir)
    env = template_environment(templates_dir)
    templates = [_template(env, name) for name in TEMPLATE_NAMES]
    try:
        (out / "feedback").mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise MechgradeError(f"cannot create the output folder ({exc.strerror or exc})",
                             where=_where(out)) from None
    count = len(report.students)
    bounds = [(low, min(low + PIECE_STUDENTS, count)) for low in range(0, count, PIECE_STUDENTS)]
    paths = [(out / "feedback" / (name + ".html"), out / "feedback" / (name + ".md"))
             for name in feedback_names(report)]
    # inherited by the forked helpers
    _RENDERING[:] = [_Rendering(report, tuple(templates), templates_dir, tuple(bounds),
                                tuple(paths))]
    _WORKED[:] = [_worked_pages(worked, env, templates_dir)] if worked is not None else []
    crew = _Crew(len(bounds), jobs)
    try:
        # results.json is made while the helpers render; made again if a page met a fault.
        results_text = outcome(_results_text)
        faults = crew.render()
        written: list[Path] = [out / "results.json"]
        if faults:
            report = replace(report, internal_errors=report.internal_errors + tuple(faults))
        if faults or not isinstance(results_text, str):
            write_json(written[0], report.to_json())  # raises the error with the file's name
        else:
            write_text(written[0], results_text)
        crew.start_writing()
        errors: list[tuple[int, MechgradeError]] = []
        for name, fmt in (("grades.csv", "grades-csv"), ("results.csv", "long-csv")):
            try:
                EXPORTERS[fmt](report, out / name, roster=roster)
            except MechgradeError as err:
                errors.append((-1, err))
                break
            written.append(out / name)
        crew.write(errors)
        if errors:
            raise min(errors, key=lambda e: e[0])[1]
    finally:
        crew.close()
        _RENDERING.clear()
        _WORKED.clear()
    written.extend(path for pair in paths for path in pair)
    return Written(tuple(written), report)


PIECE_STUDENTS = 25
"""Students whose pages a process renders and writes as one piece of work: pieces are claimed
one at a time, so that every process stays busy to the end whatever else it does."""


@dataclass(frozen=True)
class _Rendering:
    report: GradeReport
    templates: tuple
    templates_dir: str | Path | None
    bounds: tuple[tuple[int, int], ...]  # the students of each piece
    paths: tuple[tuple[Path, Path], ...]  # every student's (html, markdown) file


_RENDERING: list[_Rendering] = []
_WORKED: list = []  # the worked solutions and their fragments, rendered once per run


def _results_text() -> str:
    return json_text(_RENDERING[0].report.to_json())


class _Crew:
    """The feedback pages rendered and written by this process and ``jobs - 1`` forked helpers.

    Every process claims the next piece of students (:data:`PIECE_STUDENTS`) until none is
    left and keeps its pages; no page is written before every page has rendered, so a broken
    template stops the run with no page written (:meth:`render` raises the error of the first
    student it breaks for, whatever the number of processes). Then each process writes the
    pages it rendered (:meth:`write`). What a helper that died left undone is done here.
    """

    def __init__(self, pieces: int, jobs: int) -> None:
        self._pieces = pieces
        self._helpers: list[tuple[BaseProcess, Connection]] = []
        self._next: Any = None  # the next piece to claim, shared with the helpers
        self._claimed = 0  # ... or, without helpers, counted here
        self._done: dict[int, tuple[list[tuple[str, str]], list[str]]] = {}
        self._theirs: dict[int, list[int]] = {}  # the pieces each helper rendered
        helpers = min(jobs, pieces) - 1
        if helpers <= 0 or "fork" not in multiprocessing.get_all_start_methods():
            return
        context = multiprocessing.get_context("fork")
        try:
            self._next = context.Value("i", 0)
        except OSError:  # no shared memory (a locked-down /dev/shm): every page is done here
            return
        for _ in range(helpers):
            conn, child = context.Pipe()
            process = context.Process(target=_help, args=(self, child), daemon=True,
                                      name="mechgrade-pages")
            process.start()
            child.close()
            self._helpers.append((process, conn))

    def _claim(self) -> int | None:
        """The next piece nobody has claimed, or ``None`` when every piece is taken."""
        if self._next is None:
            piece, self._claimed = self._claimed, self._claimed + 1
        else:
            with self._next.get_lock():
                piece = self._next.value
                self._next.value = piece + 1
        return piece if piece < self._pieces else None

    def _stop_claims(self) -> None:
        if self._next is None:
            self._claimed = self._pieces
        else:
            with self._next.get_lock():
                self._next.value = self._pieces

    def render_claimed(self) -> tuple[dict, tuple[int, MechgradeError] | None]:
        """Render the pieces this process claims: ``{piece: (pages, faults)}``, and the
        ``(piece, error)`` of a broken template (which ends the claiming for every process)."""
        done: dict[int, tuple[list[tuple[str, str]], list[str]]] = {}
        while (piece := self._claim()) is not None:
            try:
                done[piece] = _render_students(_RENDERING[0].bounds[piece])
            except MechgradeError as err:
                self._stop_claims()
                return done, (piece, err)
        return done, None

    def render(self) -> list[str]:
        """Render every page (here and in the helpers); the faults met, in student order.
        Raises the :class:`MechgradeError` of a broken template."""
        self._done, error = self.render_claimed()
        errors = [error] if error else []
        faults = {piece: chunk_faults for piece, (_, chunk_faults) in self._done.items()}
        for me, (_, conn) in enumerate(self._helpers):
            message = _receive(conn)
            if message is not None and message[0] is _Say.RENDERED:
                faults.update(message[1])
                self._theirs[me] = sorted(message[1])
            elif message is not None and message[0] is _Say.ERROR:
                errors.append(message[1])
        first = min((piece for piece, _ in errors), default=self._pieces)
        for piece in range(first):  # a helper died: its pieces are done here
            if piece not in faults:
                try:
                    self._done[piece] = _render_students(_RENDERING[0].bounds[piece])
                except MechgradeError as err:
                    errors.append((piece, err))
                    break
                faults[piece] = self._done[piece][1]
        if errors:
            raise min(errors, key=lambda e: e[0])[1]
        return [fault for piece in sorted(faults) for fault in faults[piece]]

    def start_writing(self) -> None:
        """Tell the helpers to write the pages they rendered."""
        for _, conn in self._helpers:
            _tell(conn, _Say.WRITE)

    def write(self, errors: list[tuple[int, MechgradeError]]) -> None:
        """Write the pages rendered here and wait for the helpers' (writing here what a helper
        that died left), adding each piece's first error to ``errors`` as ``(piece, error)``."""
        for piece in sorted(self._done):
            self._write(piece, self._done[piece][0], errors)
        for me, (_, conn) in enumerate(self._helpers):
            message = _receive(conn)
            if message is not None and message[0] is _Say.ERROR:
                errors.append(message[1])
            elif message is None:
                for piece in self._theirs.get(me, ()):
                    self._write(piece, _render_students(_RENDERING[0].bounds[piece])[0],
                                errors)

    @staticmethod
    def _write(piece: int, pages: list[tuple[str, str]], errors: list) -> None:
        try:
            _write_piece(piece, pages)
        except MechgradeError as err:
            errors.append((piece, err))

    def close(self) -> None:
        """Let the helpers go (one still waiting to write is told to stop) and wait for them."""
        for process, conn in self._helpers:
            _tell(conn, _Say.STOP)
            conn.close()
            process.join()
        self._helpers = []


class _Say(Enum):
    """What the parent and a helper of :class:`_Crew` tell each other (a helper's news comes
    first in a tuple with what it carries)."""

    RENDERED = "rendered"  # a helper's pieces are rendered: their faults
    ERROR = "error"  # a helper met an error: (piece, error)
    WRITTEN = "written"  # a helper wrote its pages
    WRITE = "write"  # the parent: write what you rendered
    STOP = "stop"  # the parent: stop


def _help(crew: _Crew, conn: Connection) -> None:
    """A forked helper of :class:`_Crew`: render the pieces it claims, say how it went, and
    write them when told to."""
    worker_started()
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent decides when we stop
    done, error = crew.render_claimed()
    if error is not None:
        _tell(conn, (_Say.ERROR, error))
        return
    _tell(conn, (_Say.RENDERED, {piece: faults for piece, (_, faults) in done.items()}))
    if _receive(conn) is not _Say.WRITE:
        return
    for piece in sorted(done):
        try:
            _write_piece(piece, done[piece][0])
        except MechgradeError as err:
            _tell(conn, (_Say.ERROR, (piece, err)))
            return
    _tell(conn, (_Say.WRITTEN,))


def _receive(conn: Connection):
    try:
        return conn.recv()
    except (EOFError, OSError):
        return None


def _tell(conn: Connection, message) -> None:
    try:
        conn.send(message)
    except OSError:  # the other end is gone (and what a helper left undone is done here)
        pass


def _write_piece(piece: int, pages: list[tuple[str, str]]) -> None:
    rendering = _RENDERING[0]
    low, _ = rendering.bounds[piece]
    for (html_path, markdown_path), (html, markdown) in zip(rendering.paths[low:], pages):
        write_text(html_path, html)
        write_text(markdown_path, markdown)


def _render_students(bounds: tuple[int, int]) -> tuple[list[tuple[str, str]], list[str]]:
    """The (html, markdown) pages of the report's students ``bounds[0]:bounds[1]``, and the
    faults met (a broken template raises :class:`MechgradeError`)."""
    rendering = _RENDERING[0]
    report = rendering.report
    prompts = _prompts(report)
    pages: list[tuple[str, str]] = []
    faults: list[str] = []
    for student in report.students[bounds[0]:bounds[1]]:
        html, markdown = (_feedback_page(report, student, template, suffix, faults,
                                         prompts)
                          for template, suffix in zip(rendering.templates, (".html", ".md")))
        pages.append((html, markdown))
    return pages, faults


def _feedback_page(report: GradeReport, student: StudentResult, template, suffix: str,
                   faults: list[str], prompts: dict) -> str:
    try:
        context = _context(report, student, prompts, markdown=suffix == ".md",
                           names=_names(_WORKED[0].worked if _WORKED else None))
        if suffix == ".md":
            context = _escape_all(context)
        context.update(worked_context(_WORKED[0] if _WORKED else None, student, prompts,
                                      markdown=suffix == ".md"))
        return _render(template, context)
    except MechgradeError:
        raise  # a broken template is the instructor's to fix, for every student alike
    except Exception as exc:  # noqa: BLE001 - one student's page must not stop the others
        faults.append(f"feedback of '{student.id}' ({suffix[1:]}): {brief_exception(exc)}")
        text = (f"Your feedback page for {report.assignment.title} could not be produced "
                f"(internal error); your score is {format_points(student.score)} / "
                f"{format_points(student.max_score)}. Please tell your instructor.")
        return (f"<!DOCTYPE html><meta charset=\"utf-8\"><p>{html_escape(text)}</p>\n"
                if suffix == ".html" else markdown_escape(text) + "\n")


def template_environment(templates_dir: str | Path | None = None):
    """The Jinja environment of the feedback templates (shipped, or ``templates_dir``)."""
    import jinja2

    folder = Path(templates_dir) if templates_dir is not None else shipped_dir("templates")
    if not folder.is_dir():
        raise MechgradeError("expected a folder of templates, found none",
                             where=_where(folder))
    env = _environment_class()(
        loader=jinja2.FileSystemLoader(str(folder)), autoescape=True,
        undefined=jinja2.StrictUndefined, keep_trailing_newline=True, trim_blocks=True,
        lstrip_blocks=True)
    env.filters["css"] = compact_css
    return env


_CSS_COMMENT = re.compile(r"/\*.*?\*/", re.S)
_CSS_PUNCTUATION = re.compile(r" ?([{};,>]) ?|(:) ")


@lru_cache(maxsize=8)  # a page's sheet is the same for every student: made once
def compact_css(text: str) -> str:
    """A template's style sheet in fewer bytes (every student's page carries it): comments
    left out, white space one space, none around braces, semicolons, commas and child
    combinators or after a colon, no semicolon before a closing brace. Only for the
    templates' own style sheets: a space in a CSS string stays one.

    >>> compact_css("  .a > b { color: #000;  /* why */\\n  margin: 0 1px; }\\n  a, p { }")
    '.a>b{color:#000;margin:0 1px}a,p{}'
    """
    text = " ".join(_CSS_COMMENT.sub("", text).split())
    return _CSS_PUNCTUATION.sub(lambda m: m.group(1) or m.group(2), text).replace(";}", "}")


@lru_cache(maxsize=None)
def _environment_class():
    import jinja2

    class FieldsEnvironment(jinja2.Environment):
        """Jinja's environment, with ``row.verdict`` on a context dict looked up as its key
        first: Jinja tries the attribute first and pays for a raised ``AttributeError`` on
        every field shown, a third of the time a feedback page takes to render."""

        def getattr(self, obj, attribute):
            if type(obj) is dict:
                try:
                    return obj[attribute]
                except KeyError:
                    pass
            return super().getattr(obj, attribute)

    return FieldsEnvironment


def _template(env, name: str):
    import jinja2

    try:
        return env.get_template(name)
    except jinja2.TemplateNotFound:
        raise MechgradeError(f"expected a template '{name}', found none",
                             where=_where(Path(env.loader.searchpath[0]))) from None
    except jinja2.TemplateSyntaxError as exc:
        raise MechgradeError(f"expected a valid Jinja template, found an error ({exc.message})",
                             where=_where(Path(env.loader.searchpath[0]) / name, exc.lineno)
                             ) from None


def _render(template, context: dict) -> str:
    import jinja2

    try:
        return template.render(**context)
    except jinja2.UndefinedError as exc:
        raise MechgradeError(f"the template uses a value mechgrade does not provide "
                             f"({exc.message})", where=_where(Path(template.filename or
                                                                   template.name))) from None


def _where(path: Path, line: int | None = None):
    return Location(str(path), line)


def feedback_names(report: GradeReport) -> list[str]:
    """A safe, distinct file name (without suffix) for every student, in report order
    (:func:`mechgrade.files.safe_file_names` of the ids)."""
    return safe_file_names([student.id for student in report.students])


def feedback_context(report: GradeReport, student: StudentResult, *,
                     markdown: bool = False, worked: FeedbackSolutions | None = None,
                     templates_dir: str | Path | None = None) -> dict:
    """Everything a feedback template shows for one student, as ready-made text.

    With ``markdown`` every text is escaped for Markdown (the HTML template relies on Jinja's
    autoescaping instead), so a student's answer can never turn into markup. With ``worked``,
    the worked solutions (see :func:`worked_context`).
    """
    prompts = _prompts(report)
    context = _context(report, student, prompts, markdown, _names(worked))
    context = _escape_all(context) if markdown else context
    pages = (_worked_pages(worked, template_environment(templates_dir), templates_dir)
             if worked is not None else None)
    context.update(worked_context(pages, student, prompts, markdown=markdown))
    return context


@dataclass(frozen=True)
class WorkedPages:
    """A run's worked solutions with their HTML and Markdown fragments, by the solution's
    ``id()`` (each rendered once, whatever the number of students sharing it)."""

    worked: FeedbackSolutions
    html: dict
    markdown: dict
    markers: str = ""  # the arrowheads every fragment's figures share (:func:`marker_defs`)

    @cached_property
    def places(self) -> dict[int, tuple[dict, dict, dict]]:
        """By the solution's ``id()``: where each ``(objective, code)`` and each
        ``(objective, message)`` happens (as ``place`` and ``declared_place`` find them,
        the first of each) and the title of the step of each step's or row's anchor;
        looked up for every answer of every page."""
        out = {}
        for w in [*self.worked.solutions, *(w for _, _, w in self.worked.variants)]:
            titles: dict[str, str] = {}
            for step in w.steps:
                titles.setdefault(step.anchor, step.title)
                for row in step.rows:
                    titles.setdefault(row.anchor, step.title)
            out[id(w)] = ({(o, c): a for o, c, a in reversed(w.places)},
                          {(o, m): a for o, m, a in reversed(w.declared)}, titles)
        return out


def _worked_pages(worked: FeedbackSolutions, env, templates_dir) -> WorkedPages:
    if templates_dir is not None and not (Path(templates_dir) / "worked.html.j2").is_file():
        # a folder of one's own feedback templates: the worked solution as shipped
        env, templates_dir = template_environment(), None
    every = list(worked.solutions) + [w for _, _, w in worked.variants]
    markers: dict[str, str] = {}
    return WorkedPages(worked, {id(w): worked_html(w, templates_dir, env, markers)
                                for w in every},
                       {id(w): worked_markdown(w) for w in every}, marker_defs(markers))


def worked_context(pages: WorkedPages | None, student: StudentResult, prompts: dict, *,
                   markdown: bool = False) -> dict:
    """The worked-solution part of a feedback page: ``worked`` (each problem's fragment),
    ``highlight`` (for the HTML page: a style marking the steps where the student's named
    mistakes happen) and ``mistake_steps`` (objective key -> the link and title of that step).
    Empty lists and text without worked solutions."""
    if pages is None:
        return {"worked": [], "highlight": "", "mistake_steps": {}, "markers": ""}
    from markupsafe import Markup

    mine = pages.worked.for_student(student)
    by_problem = {w.problem: w for w in mine}
    marked: dict[str, dict[str, list[str]]] = {}  # step: mistake: the answers
    steps: dict[str, dict] = {}
    for answer in student.answers:
        worked = by_problem.get(answer.problem)
        code = pages.worked.code(answer.diagnosis)
        places, declared, titles = pages.places[id(worked)] if worked is not None else ({}, {}, {})
        place = None if worked is None or not answer.diagnosis else (
            places.get((answer.objective, code)) if code
            else declared.get((answer.objective, answer.diagnosis)))
        wrong_loads = [f"{row.label} {', '.join(row.mistakes)}" for row in answer.loads
                       if row.mistakes]
        if place is None and worked is not None and wrong_loads and worked.diagram_step:
            place = worked.diagram_step  # a free-body diagram's mistakes: the drawn diagrams
        said = answer.diagnosis or "; ".join(wrong_loads)
        if place is None and worked is not None and worked.equations_step and \
                answer.objective == EQUATIONS_OBJECTIVE and \
                answer.verdict in (Verdict.INCORRECT, Verdict.PARTIAL):
            place = worked.equations_step  # equations of motion wrong: the model's own
            said = shorten(answer.feedback, 100)
        if place is None:
            continue
        prompt = prompts.get((answer.problem, answer.objective)) or answer.objective
        title = titles.get(place, place)
        steps[f"{answer.problem}.{answer.objective}"] = {
            "href": "#" + anchor(answer.problem, place),
            "title": markdown_escape(title) if markdown else title}
        # a step's note names each mistake once, with the answers it is in
        marked.setdefault(anchor(answer.problem, place), {}).setdefault(
            said.rstrip(". "), []).append(f"“{shorten(prompt, 40)}”")
    notes = {ident: textbook("; ".join(
        f"{said}: your answer{'s' if len(asked) > 1 else ''} to {', '.join(asked)}"
        for said, asked in mistakes.items()), False) for ident, mistakes in marked.items()}
    fragments = pages.markdown if markdown else pages.html
    # the marked steps share their look (said once), each its own note
    highlight = "" if not marked else (
        ",".join(f"#{ident}" for ident in marked)
        + "{background:#fff4e5;outline:2px solid #f0b429}\n"
        + ",".join(f"#{ident}::before" for ident in marked)
        + "{display:block;color:#8d6b00;font-weight:600;font-size:.85rem;"
          "font-family:system-ui,sans-serif}\n"
        + "".join(f"#{ident}::before{{content:{_css_string(note)}}}\n"
                  for ident, note in notes.items()))
    return {"worked": [{"problem": w.problem, "fragment": fragments[id(w)]} for w in mine],
            "highlight": "" if markdown else Markup(highlight), "mistake_steps": steps,
            "markers": "" if markdown else Markup(pages.markers)}


@lru_cache(maxsize=4096)  # every answer's place on every page
def anchor(problem: str, step: str) -> str:
    """The page id of a step or row of ``problem``'s worked solution: a short tag of the
    problem (its id is in every step's and row's id: a page carries some 150 of them), then
    the step.

    >>> anchor("bowling 3.15", "acc-P-coriolis")
    'wcd9ad-acc-P-coriolis'
    """
    import zlib

    tag = f"w{zlib.crc32(problem.encode()) & 0xFFFFF:05x}"
    return re.sub(r"[^A-Za-z0-9_-]", "-", f"{tag}-{step}")


def worked_id(problem: str) -> str:
    """The page id of ``problem``'s worked solution.

    >>> worked_id("bowling 3.15")
    'ws-bowling-3-15'
    """
    return re.sub(r"[^A-Za-z0-9_-]", "-", f"ws-{problem}")


def worked_html(worked: WorkedSolution, templates_dir=None, env=None,
                markers: dict[str, str] | None = None):
    """The worked solution as an HTML fragment (``worked.html.j2``), safe markup. With
    ``markers``, its figures' arrowheads are left to the page (:func:`shared_markers`) and
    put in ``markers``; without, each figure keeps its own."""
    from markupsafe import Markup

    env = env if env is not None else template_environment(templates_dir)
    from .fbd import fbd_svg

    def figure(svg: str) -> Markup:
        return Markup(svg if markers is None else shared_markers(svg, markers))

    diagrams = [figure(fbd_svg(d, anchor(worked.problem, f"fbd-{d.body}")))
                for d in worked.diagrams]
    # a step or a row has an id only when a link may point to it (a mistake's place, the
    # diagrams, the equations): a page carries each id once a problem
    targets = {place for _, _, place in worked.places + worked.declared} | {
        worked.diagram_step, worked.equations_step}
    names = worked.names
    steps = [{"anchor": step.anchor, "target": step.anchor in targets,
              "title": Markup(textbook_html(step.title, False, names)),
              "lines": [Markup(textbook_html(line, True, names)) for line in step.lines],
              "rows": [{"anchor": row.anchor if row.anchor in targets else "", "text": row.text,
                        "caption": Markup(textbook_html(row.caption, False, names)),
                        "math": Markup(spoken_math(row.math, row.text, names))}
                       for row in step.rows],
              "diagrams": diagrams if step.anchor == worked.diagram_step else []}
             for step in worked.steps]
    context = {"w": {"id": worked_id(worked.problem), "tag": anchor(worked.problem, "")[:-1],
                     "title": worked.title,
                     "picture": figure(worked.picture) if worked.picture else "",
                     "steps": steps}}
    # an apostrophe needs no escape in text or in an attribute in double quotes (the only
    # kind the shipped template writes): every student's page carries some seventy of them
    html = _render(_template(env, "worked.html.j2"), context)
    return Markup(html if templates_dir is not None
                  else html.replace("&#39;", "'").replace("&#x27;", "'"))


_MARKER = re.compile(r'<marker id="([^"]+)"([^>]*)>(.*?)</marker>\n?', re.S)
_EMPTY_DEFS = re.compile(r"<defs>\s*</defs>\n?")


def shared_markers(svg: str, markers: dict[str, str]) -> str:
    """``svg`` without its arrowhead markers: each one it uses is named by what it draws and
    put in ``markers`` (id: definition), for the page to define once (:func:`marker_defs`)
    rather than every figure again. Only for the figures mechgrade draws.

    >>> found = {}
    >>> print(shared_markers('<svg><defs>\\n<marker id="f-k" refX="9"><path/></marker>\\n'
    ...                      '</defs>\\n<line marker-end="url(#f-k)"/></svg>', found))
    <svg><line marker-end="url(#mke98141fb)"/></svg>
    >>> found
    {'mke98141fb': '<marker id="mke98141fb" refX="9"><path/></marker>'}
    """
    import zlib

    def take(match: re.Match) -> str:
        old, attributes, body = match.groups()
        if f"url(#{old})" in svg:
            new = f"mk{zlib.crc32((attributes + body).encode()):08x}"
            markers[new] = f'<marker id="{new}"{attributes}>{body}</marker>'
            renamed[old] = new
        return ""

    renamed: dict[str, str] = {}
    out = _EMPTY_DEFS.sub("", _MARKER.sub(take, svg))
    for old, new in renamed.items():
        out = out.replace(f"url(#{old})", f"url(#{new})")
    return out


def marker_defs(markers: dict[str, str]) -> str:
    """The hidden SVG defining ``markers`` (:func:`shared_markers`) for a whole page.

    >>> marker_defs({"mk1": '<marker id="mk1"/>'})
    '<svg class="ws-defs" width="0" height="0" aria-hidden="true"><defs><marker id="mk1"/></defs></svg>'
    >>> marker_defs({})
    ''
    """
    if not markers:
        return ""
    return ('<svg class="ws-defs" width="0" height="0" aria-hidden="true"><defs>'
            + "".join(markers[k] for k in sorted(markers)) + "</defs></svg>")


def spoken_math(math: str, text: str, names: tuple[tuple[str, str], ...] = ()) -> str:
    """MathML labelled with its plain-text reading (``aria-label``), which a screen reader
    says for it: the dots of a rate are drawn as operators it would read as "bullet". A row
    lays its math out itself (the page's style), so ``display`` is left out; a dot or a hat
    is set over its letter as a script (Chromium sets an accent onto the letter's top: the
    dots of θ̇ on the θ).

    >>> print(spoken_math('<math display="block"><mover accent="true"><mi>x</mi><mo>∙</mo>'
    ...                   '</mover></math>', "v = x**2*y"))
    <math aria-label="v = x²·y"><mover><mi>x</mi><mo>∙</mo></mover></math>
    >>> spoken_math("<math></math>", "N_v_P = thetad*N.y").split('"')[1]
    'N v,P = θ̇·n-hat y'

    """
    label = html_escape(textbook(" ".join(text.split()), True, names), quote=True)
    return math.replace('<math display="block"', "<math", 1).replace(
        "<math", f'<math aria-label="{label}"', 1).replace('<mover accent="true">', "<mover>")


def worked_markdown(worked: WorkedSolution, level: int = 3) -> str:
    """The worked solution as Markdown: each step's text, its equations as the solver
    writes them (the picture and the MathML need the HTML page)."""
    hashes = "#" * level
    out = [f"{hashes} {markdown_escape(worked.title)}"]
    for step in worked.steps:
        out += ["", f"{hashes}# {markdown_escape(textbook(step.title, False, worked.names))}", ""]
        lines = [line for line in step.lines if line] + [
            f"{row.caption}: {row.text}" if row.caption else row.text for row in step.rows]
        out += [f"- {code_span(textbook(line, True, worked.names))}" for line in lines] \
            or ["(none)"]
    return "\n".join(out) + "\n"


def shorten(text: str, limit: int = 60) -> str:
    """``text`` on one line, cut with an ellipsis past ``limit`` characters.

    >>> shorten("The force of the pin on the rod", 20)
    'The force of the pi…'
    """
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit - 1].rstrip() + "…"


def _css_string(text: str) -> str:
    """``text`` as a CSS string: what could end the string or the style element escaped (a
    quote, a backslash, ``<`` and ``>``, a character that does not print), the rest as it is.

    >>> print(_css_string('a "b" </style> θ̇’s'))
    "a \\22 b\\22  \\3c /style\\3e  θ̇’s"
    """
    if text.isprintable():  # the common case: four characters to escape, by a table
        return '"' + text.translate(_CSS_ESCAPES) + '"'
    return '"' + "".join(f"\\{ord(c):x} " if c in '"\\<>' or not c.isprintable() else c
                         for c in text) + '"'


_CSS_ESCAPES = {ord(c): f"\\{ord(c):x} " for c in '"\\<>'}


def _prompts(report: GradeReport) -> dict:
    return {(o.problem, o.objective): o.prompt for o in report.objectives}


@lru_cache(maxsize=1 << 14)  # five a card, the same for many students
def _textbook_markup(text: str, rates: bool, names: tuple[tuple[str, str], ...]) -> Markup:
    return Markup(textbook_html(text, rates, names))


def _names(worked: FeedbackSolutions | None) -> dict[str, tuple[tuple[str, str], ...]]:
    """By problem, how a textbook spells its coordinates (known from its worked solution)."""
    return {w.problem: w.names for w in worked.solutions} if worked is not None else {}


def _context(report: GradeReport, student: StudentResult, prompts: dict,
             markdown: bool = False, names: dict | None = None) -> dict:
    spelled: tuple[tuple[str, str], ...] = ()

    def shown(text: str, rates: bool = True) -> str:
        # a model's names as a textbook writes them; what the student wrote stays as written
        return textbook(text, rates, spelled) if markdown \
            else _textbook_markup(text, rates, spelled)

    rows = []
    for answer in student.answers:
        spelled = (names or {}).get(answer.problem, ())
        rows.append({
            "problem": answer.problem,
            "objective": answer.objective,
            "key": f"{answer.problem}.{answer.objective}",
            "prompt": shown(prompts.get((answer.problem, answer.objective), ""), False),
            "answer": answer.answer if answer.answer is not None else "",
            "read_back": shown(answer.read_back or ""),
            "verdict": answer.verdict,
            "verdict_label": verdict_label(answer.verdict, answer.diagnosis),
            "points": format_points(answer.points),
            "max_points": format_points(answer.max_points),
            "diagnosis": shown(diagnosis_label(answer.diagnosis, answer.feedback), False),
            "feedback": shown(answer.feedback or "", False),
            # a right answer's "Correct." says nothing the verdict does not
            "explained": bool(answer.feedback or answer.diagnosis)
                         and (answer.verdict != Verdict.CORRECT or bool(answer.diagnosis)),
            "expected": shown(expected_shown(answer)),
            # a free-body diagram's rows, one per load
            "loads": [{"label": load.label if load.load is None or load.label == load.load
                       else f"{load.label} ({load.load})",
                       "point": load.point or "",
                       # the row names the load: the vector alone, as written
                       "answer": (load.answer or "").partition(": ")[2],
                       "verdict": Verdict.INCORRECT if load.mistakes else Verdict.CORRECT,
                       "judged": ", ".join(load.mistakes) if load.mistakes else "right"}
                      for load in answer.loads],
        })
    percent = (f"{100 * student.score / student.max_score:.0f}%" if student.max_score
               else "")
    return {
        "assignment": {"id": report.assignment.id, "title": report.assignment.title},
        "student": {
            "id": student.id,
            "name": student.name,
            "display_name": student.name or student.id,
            "status": student.status,
            "status_label": STATUS_LABELS.get(student.status, student.status),
            "score": format_points(student.score),
            "max_score": format_points(student.max_score),
            "percent": percent,
        },
        "messages": list(student.messages),
        "variant": ({"seed": student.variant.seed,
                     "givens": [{"problem": g.problem, "name": g.name, "value": g.text}
                                for g in student.variant.givens]}
                    if student.variant else None),
        "rows": rows,
        # one card for them all when no answer was read (15 cards said 15 times "could not
        # be read"), with the questions and the keys their answers go under
        "nothing_read": _nothing_read(student),
        "reveal": any(row["expected"] for row in rows),
        # what the answer key fails of its author's own tests, graded anyway
        "failing_expects": [prompts.get((f.problem, f.objective)) or f"{f.problem}.{f.objective}"
                            for f in report.failing_expects],
    }


def expected_shown(answer: AnswerResult) -> str:
    """The expected answer as a feedback page shows it: also in the unit the student wrote,
    when that is another (empty when answers are not revealed).

    >>> expected_shown(AnswerResult("p", "F", "8.27 lbf", "correct", 1.0, 1.0,
    ...                             expected="36.79 N", expected_in_answer_unit="8.27 lbf"))
    '36.79 N (8.27 lbf)'
    """
    if not answer.expected:
        return ""
    if answer.expected_in_answer_unit:
        return f"{answer.expected} ({answer.expected_in_answer_unit})"
    return answer.expected


NOTHING_READ = {
    Status.MISSING: "No answers were found for you, so {none} graded.",
    Status.UNREADABLE: "Your answers could not be read (see “About your submission”), so {none} "
                  "graded.",
}


def _nothing_read(student: StudentResult) -> str:
    """What the one card of a student none of whose answers was read says (empty when some
    answer was read).

    >>> from mechgrade.grade.results import StudentResult, AnswerResult
    >>> _nothing_read(StudentResult("ana", "", "missing", 0.0, 2.0,
    ...                             (AnswerResult("p", "v", None, "missing", 0.0, 2.0),)))
    'No answers were found for you, so the question was not graded.'
    """
    if student.status not in NOTHING_READ or any(a.answer is not None
                                                  for a in student.answers):
        return ""
    n = len(student.answers)
    # "none of the 1 question" read as a count, not a sentence
    return NOTHING_READ[student.status].format(
        none="the question was not" if n == 1 else f"none of the {n} questions was")


def counted(n: int, singular: str, plural: str | None = None) -> str:
    """``n`` and the noun, singular for one.

    >>> counted(1, "entry", "entries"), counted(3, "question"), counted(0, "student")
    ('1 entry', '3 questions', '0 students')
    """
    return f"{n} {noun(n, singular, plural)}"


def noun(n: int, singular: str, plural: str | None = None) -> str:
    """The noun for ``n`` of it: singular for one, else ``plural`` (default: with an s).

    >>> noun(1, "skipped entry", "skipped entries"), noun(2, "missing submission")
    ('skipped entry', 'missing submissions')
    """
    return singular if n == 1 else plural or singular + "s"


def verdict_label(verdict: Verdict, diagnosis: str | None) -> str:
    """The verdict as the page names it; credit earned through error carried forward says so
    (a wrong value under a bare "Correct" reads as a mistake of the grader's).

    >>> verdict_label("correct", "error carried forward")
    'Correct (error carried forward)'
    """
    label = VERDICT_LABELS.get(verdict, verdict)
    return (f"{label} ({ECF_DIAGNOSIS})"
            if diagnosis == ECF_DIAGNOSIS and verdict in (Verdict.CORRECT, Verdict.PARTIAL) else label)


def diagnosis_label(diagnosis: str | None, feedback: str | None) -> str:
    """The diagnosis as the bold lead of the feedback line, capitalised; empty when the
    feedback already says it (an author's mistake message is both; "Factor of 2: Your answer
    is off by a factor of 2."), so it is printed once.

    >>> diagnosis_label("sign error", "Your answer has the wrong sign.")
    'Sign error'
    >>> diagnosis_label("Only the centripetal part.", "Only the centripetal part.")
    ''
    >>> diagnosis_label("factor of 2", "Your answer is off by a factor of 2.")
    ''
    """
    text = (diagnosis or "").strip()
    if not text or text.rstrip(".").lower() in (feedback or "").lower():
        return ""
    return text[:1].upper() + text[1:]


# "_" inside a word (dan_wu) is never emphasis in CommonMark, so it is left readable.
_MD_SPECIAL = re.compile(r"([\\`*\[\]<>|~&#]|(?<![A-Za-z0-9])_|_(?![A-Za-z0-9]))")


@lru_cache(maxsize=1 << 16)  # prompts, verdicts and common answers repeat across students
def markdown_escape(text: str) -> str:
    """Text shown literally by any Markdown renderer (no markup, no raw HTML).

    >>> print(markdown_escape("<b>x</b> *y* `z` _w_ dan_wu"))
    \\<b\\>x\\</b\\> \\*y\\* \\`z\\` \\_w\\_ dan_wu
    """
    return _MD_SPECIAL.sub(r"\\\1", " ".join(text.split()))


_BACKTICKS = re.compile("`+")


def code_span(text: str) -> str:
    """``text`` as a Markdown code span, shown literally whatever it holds (an author's
    backtick cannot close it early and let what follows be read as markup or raw HTML): its
    fence is longer than any run of backticks inside, and spaced from them.

    >>> print(code_span("x = 1"), code_span("`a` <img>"))
    `x = 1` `` `a` <img> ``
    """
    text = " ".join(text.split())
    if "`" not in text:
        return f"`{text}`"
    fence = "`" * (max(map(len, _BACKTICKS.findall(text))) + 1)
    return f"{fence} {text} {fence}"


def _escape_all(value):
    if isinstance(value, str):
        return markdown_escape(value)
    if isinstance(value, dict):
        return {k: _escape_all(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_escape_all(v) for v in value]
    return value


@lru_cache(maxsize=4096)
def format_points(value: float) -> str:
    """Points without needless decimals.

    >>> format_points(2.0), format_points(1.5), format_points(0.3333)
    ('2', '1.5', '0.33')
    """
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text
