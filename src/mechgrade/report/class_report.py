"""The class report: statistics of one grading run as a single self-contained HTML file.

:func:`class_statistics` computes everything into a frozen :class:`ClassReport` (charts as
inline SVG from matplotlib); :func:`render_class_report` hands it to
``templates/class_report.html.j2``, which only presents. Definitions (``docs/exports.md``):

* statistics use the students whose submission was graded (status ``graded``); missing and
  unreadable submissions are counted and listed, not averaged in as zeros;
* **success rate** of an objective: share of graded students whose answer is ``correct``;
* **difficulty** of a problem: mean over graded students of points earned / points possible
  (classical item facility: 1 = everybody full marks, 0 = nobody scored);
* **discrimination** of a problem: corrected item-total correlation, the Pearson correlation
  across graded students between the fraction earned on the problem and the total score on the
  *other* problems (for a right/wrong item this is the point-biserial). ``None`` with fewer than
  3 graded students or when either side does not vary.

>>> from mechgrade.grade.results import (AnswerResult, AssignmentInfo, GradeReport,
...                                      ObjectiveInfo, StudentResult)
>>> obj = ObjectiveInfo("p1", "v", "speed", 2.0)
>>> s = [StudentResult(f"s{i}", f"S{i}", "graded", p, 2.0,
...                    (AnswerResult("p1", "v", "x", "correct" if p else "incorrect", p, 2.0),))
...      for i, p in enumerate([2.0, 0.0])]
>>> stats = class_statistics(GradeReport(AssignmentInfo("hw", "HW"), (obj,), tuple(s)),
...                          charts=False)
>>> stats.objectives[0].success_rate, stats.problems[0].difficulty
(0.5, 0.5)
"""

from __future__ import annotations

import io
import math
import os
import re
import statistics
from collections import Counter
from dataclasses import dataclass
from html import escape

from ..errors import ExportError
from ..files import write_text
from ..grade.results import GradeReport, SkippedEntry, Status, StudentResult, Verdict
from .output import counted, format_points, noun, shorten

TOP = 5


@dataclass(frozen=True)
class Count:
    """A label seen ``count`` times; ``share`` is count / graded students."""

    label: str
    count: int
    share: float


@dataclass(frozen=True)
class ObjectiveStats:
    problem: str
    objective: str
    prompt: str
    max_points: float
    graded: int
    success_rate: float | None
    mean_fraction: float | None
    verdicts: tuple[Count, ...]
    wrong_answers: tuple[Count, ...]
    diagnoses: tuple[Count, ...]

    @property
    def key(self) -> str:
        """The key a student's answer goes under (``problem.objective``)."""
        return f"{self.problem}.{self.objective}"

    @property
    def title(self) -> str:
        """What the report calls the objective: its prompt, or its key without one."""
        return self.prompt or self.key


@dataclass(frozen=True)
class ProblemStats:
    problem: str
    max_points: float
    objectives: int
    difficulty: float | None
    discrimination: float | None


@dataclass(frozen=True)
class StudentIssue:
    """A student with a missing or unreadable submission or answers."""

    id: str
    name: str
    status: Status
    objectives: str
    detail: str


@dataclass(frozen=True)
class ClassReport:
    assignment_id: str
    title: str
    max_score: float
    students: int
    graded: int
    missing: int
    unreadable: int
    mean: float | None
    median: float | None
    stdev: float | None
    lowest: float | None
    highest: float | None
    histogram_svg: str
    success_svg: str
    objectives: tuple[ObjectiveStats, ...]
    problems: tuple[ProblemStats, ...]
    issues: tuple[StudentIssue, ...]
    not_evaluated: int = 0
    skipped: tuple[SkippedEntry, ...] = ()
    notes: tuple[str, ...] = ()
    internal_errors: tuple[str, ...] = ()
    failing_expects: tuple[str, ...] = ()  # graded anyway, one line each


def class_statistics(report: GradeReport, *, charts: bool = True) -> ClassReport:
    """All statistics of the class report (see module doc); ``charts=False`` skips the SVGs."""
    graded = [s for s in report.students if s.status == Status.GRADED]
    scores = [s.score for s in graded]
    max_score = sum(o.max_points for o in report.objectives) or \
        max((s.max_score for s in report.students), default=0.0)
    objectives = tuple(_objective_stats(o, graded) for o in report.objectives)
    problems = _problem_stats(report, graded)
    histogram = _histogram_svg(scores, max_score) if charts else ""
    success = _success_svg(objectives) if charts else ""
    return ClassReport(
        assignment_id=report.assignment.id, title=report.assignment.title, max_score=max_score,
        students=len(report.students), graded=len(graded),
        missing=sum(s.status == Status.MISSING for s in report.students),
        unreadable=sum(s.status == Status.UNREADABLE for s in report.students),
        mean=statistics.fmean(scores) if scores else None,
        median=statistics.median(scores) if scores else None,
        stdev=statistics.pstdev(scores) if len(scores) > 1 else None,
        lowest=min(scores, default=None), highest=max(scores, default=None),
        histogram_svg=histogram, success_svg=success, objectives=objectives,
        problems=problems, issues=_issues(report),
        not_evaluated=sum(s.status == Status.NOT_EVALUATED for s in report.students),
        skipped=report.skipped, notes=report.notes, internal_errors=report.internal_errors,
        failing_expects=tuple(map(str, report.failing_expects)))


def render_class_report(stats: ClassReport) -> str:
    """The HTML text of the class report (``templates/class_report.html.j2``)."""
    import jinja2
    from markupsafe import Markup

    from ..resources import shipped_dir

    env = jinja2.Environment(loader=jinja2.FileSystemLoader(shipped_dir("templates")),
                             autoescape=True, undefined=jinja2.StrictUndefined,
                             trim_blocks=True, lstrip_blocks=True)
    # scores and points as the feedback pages write them; a noun as its count needs it
    env.filters.update(points=format_points, noun=noun)
    template = env.get_template("class_report.html.j2")
    # The SVGs come from matplotlib, which escapes every text it draws; mark them as markup.
    return template.render(report=stats, histogram=Markup(stats.histogram_svg),
                           success=Markup(stats.success_svg))


def write_class_report(report: GradeReport, out_path: str | os.PathLike) -> None:
    """Compute the statistics of ``report`` and write the HTML file atomically."""
    write_text(out_path, render_class_report(class_statistics(report)))


def _answer(student: StudentResult, problem: str, objective: str):
    return next((a for a in student.answers
                 if a.problem == problem and a.objective == objective), None)


def _counts(labels: list[str], n: int) -> tuple[Count, ...]:
    ranked = sorted(Counter(labels).items(), key=lambda item: (-item[1], item[0]))
    return tuple(Count(label, count, count / n) for label, count in ranked[:TOP])


def load_mistake_label(row) -> str:
    """What a row of a free-body diagram (:class:`~mechgrade.grade.results.LoadResult`) got
    wrong, as the class report counts it (``""`` when right).

    >>> from mechgrade.expressions.loads import LoadKind
    >>> from mechgrade.grade.results import LoadResult
    >>> load_mistake_label(LoadResult("friction", "F_P", LoadKind.KINETIC_FRICTION, "P", None,
    ...                               ("missing",), ""))
    'missing: the kinetic friction F_P'
    >>> load_mistake_label(LoadResult("centrifugal force", None, None, "G", "...", ("extra",), ""))
    'extra: centrifugal force'
    """
    if not row.mistakes:
        return ""
    if row.load is None:
        return f"extra: {row.label}"
    return f"{', '.join(row.mistakes)}: the {row.kind} {row.load}"


def _objective_stats(objective, graded) -> ObjectiveStats:
    answers = [_answer(s, objective.problem, objective.objective) for s in graded]
    verdicts = [a.verdict if a is not None else Verdict.MISSING for a in answers]
    n = len(graded)
    wrong = [" ".join(a.answer.split()) for a in answers
             if a is not None and a.answer and a.verdict not in (Verdict.CORRECT, Verdict.UNREADABLE)]
    diagnoses = [a.diagnosis.strip() for a in answers
                 if a is not None and a.diagnosis and a.verdict != Verdict.CORRECT]
    diagnoses += [label for a in answers if a is not None
                  for label in dict.fromkeys(map(load_mistake_label, a.loads)) if label]
    fractions = [(a.points / objective.max_points) if a is not None and objective.max_points
                 else 0.0 for a in answers]
    return ObjectiveStats(
        objective.problem, objective.objective, objective.prompt, objective.max_points, n,
        success_rate=verdicts.count(Verdict.CORRECT) / n if n else None,
        mean_fraction=statistics.fmean(fractions) if n else None,
        verdicts=tuple(Count(v, verdicts.count(v), verdicts.count(v) / n)
                       for v in dict.fromkeys(verdicts)) if n else (),
        wrong_answers=_counts(wrong, n) if n else (),
        diagnoses=_counts(diagnoses, n) if n else ())


def _problem_stats(report, graded) -> tuple[ProblemStats, ...]:
    out = []
    problems = list(dict.fromkeys(o.problem for o in report.objectives))
    for problem in problems:
        mine = [o for o in report.objectives if o.problem == problem]
        possible = sum(o.max_points for o in mine)
        earned = []
        for s in graded:
            answers = [_answer(s, o.problem, o.objective) for o in mine]
            earned.append(sum(a.points for a in answers if a is not None))
        fractions = [e / possible if possible else 0.0 for e in earned]
        rest = [s.score - e for s, e in zip(graded, earned)]
        out.append(ProblemStats(problem, possible, len(mine),
                                difficulty=statistics.fmean(fractions) if graded else None,
                                discrimination=_correlation(fractions, rest)))
    return tuple(out)


def _correlation(xs: list[float], ys: list[float]) -> float | None:
    """Pearson correlation, or ``None`` for fewer than 3 pairs or a constant side."""
    if len(xs) < 3:
        return None
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    syy = sum((y - my) ** 2 for y in ys)
    if sxx <= 1e-12 or syy <= 1e-12:
        return None
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / math.sqrt(sxx * syy)


_SAID = {Verdict.UNREADABLE: "could not be read", Verdict.MISSING: "no answer"}


def _issues(report: GradeReport) -> tuple[StudentIssue, ...]:
    issues = []
    for s in report.students:
        if s.status != Status.GRADED:
            detail = "; ".join(s.messages) or ("no submission found" if s.status == Status.MISSING
                                               else "the submission could not be read")
            issues.append(StudentIssue(s.id, s.name, s.status, "all", detail))
            continue
        bad = [a for a in s.answers if a.verdict in (Verdict.UNREADABLE, Verdict.MISSING)]
        answered = {(a.problem, a.objective) for a in s.answers}
        absent = [o for o in report.objectives if (o.problem, o.objective) not in answered]
        if bad or absent:
            names = [f"{a.problem}.{a.objective} ({_SAID[a.verdict]})" for a in bad] + \
                    [f"{o.problem}.{o.objective} ({_SAID[Verdict.MISSING]})" for o in absent]
            # why each answer could not be read; "No answer was given." said nothing new
            details = [f"{a.problem}.{a.objective}: {a.feedback}" for a in bad
                       if a.feedback and a.verdict == Verdict.UNREADABLE] + list(s.messages)
            issues.append(StudentIssue(s.id, s.name, Status.GRADED, ", ".join(names),
                                       "; ".join(details)))
    return tuple(issues)


# --- charts -----------------------------------------------------------------------------------

_COLOURS = {Verdict.CORRECT: "#2e7d32", Verdict.PARTIAL: "#f9a825", Verdict.INCORRECT: "#c62828",
            None: "#9e9e9e"}
"""Each verdict's colour; ``None``: any other outcome (unreadable or missing)."""


def _pyplot():
    try:
        import matplotlib
    except ImportError:
        raise ExportError("the class report draws its charts with matplotlib, which is not "
                          "installed; install it with 'pip install matplotlib'") from None
    matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt
    return matplotlib, plt


def _svg(fig, salt: str, title: str, description: str) -> str:
    """The figure as inline SVG named ``title`` and described in words by ``description``
    (what a screen reader says of it), its ids starting with ``salt`` (two charts of one
    page both had ``figure_1``)."""
    matplotlib, plt = _pyplot()
    buffer = io.StringIO()
    with matplotlib.rc_context({"svg.hashsalt": salt}):
        fig.savefig(buffer, format="svg", bbox_inches="tight", metadata={"Date": None})
    plt.close(fig)
    text = buffer.getvalue()
    # Inline SVG in HTML needs neither the XML declaration nor the DOCTYPE, nor metadata.
    text = re.sub(r"^.*?(?=<svg)", "", text, flags=re.S).strip()
    text = re.sub(r"\s*<metadata>.*?</metadata>", "", text, count=1, flags=re.S)
    text = re.sub(r'(\bid="|url\(#|href="#)', rf"\g<1>{salt}-", text)
    return re.sub(r"<svg\b([^>]*)>", lambda m: (
        f'<svg{m.group(1)} role="img" aria-labelledby="{salt}-title {salt}-desc">'
        f'<title id="{salt}-title">{escape(title)}</title>'
        f'<desc id="{salt}-desc">{escape(description)}</desc>'), text, count=1)


def _style():
    matplotlib, _ = _pyplot()
    return matplotlib.rc_context({"svg.fonttype": "none", "text.parse_math": False,
                                  "font.family": "sans-serif", "font.size": 10,
                                  "axes.spines.top": False, "axes.spines.right": False})


def score_bins(top: float) -> list[float]:
    """The edges of the histogram's bins: one point wide, centred on whole scores, up to
    60 bins; wider (2, 5, 10, 20, ... points) on a longer scale.

    >>> len(score_bins(34)) - 1, score_bins(34)[:2], score_bins(34)[-1]
    (35, [-0.5, 0.5], 34.5)
    >>> score_bins(200)[1] - score_bins(200)[0]
    5.0
    """
    width = next(w for w in (10 ** k * m for k in range(12) for m in (1, 2, 5))
                 if top / w <= 60)
    count = math.ceil(top / width - 1e-9)
    return [(i - 0.5) * width for i in range(count + 2)]


def _histogram_svg(scores: list[float], max_score: float) -> str:
    _, plt = _pyplot()
    with _style():
        fig, ax = plt.subplots(figsize=(7, 2.8))
        top = max(max_score, max(scores, default=0.0), 1.0)
        edges = score_bins(top)
        counts, _, _ = ax.hist(scores, bins=edges, color="#1565c0", edgecolor="white")
        ax.set_xlabel(f"score (out of {format_points(top)})")
        ax.set_ylabel("students")
        ax.yaxis.get_major_locator().set_params(integer=True)
        ax.set_xlim(edges[0], edges[-1])
        if not scores:
            ax.text(0.5, 0.5, "no graded submissions", transform=ax.transAxes, ha="center")
        width = edges[1] - edges[0]
        # In words, bins of one point say each score as it is: 5.5 is drawn in the bar of 6
        # but was not scored 6
        said = ([f"{counted(n, 'student')} scored {format_points(score)}"
                 for score, n in sorted(Counter(scores).items())] if width == 1 else
                [f"{counted(int(n), 'student')} scored {format_points(low)} to "
                 f"{format_points(low + width)}" for low, n in zip(edges, counts) if n])
        return _svg(fig, "histogram", f"Score distribution (out of {format_points(top)})",
                    "; ".join(said) + "." if said else "No graded submissions.")


_KINDS = {Verdict.CORRECT: "correct", Verdict.PARTIAL: "partly correct",
          Verdict.INCORRECT: "incorrect",
          None: "unreadable or missing"}


def _success_svg(objectives: tuple[ObjectiveStats, ...]) -> str:
    _, plt = _pyplot()
    with _style():
        labels = [shorten(o.title, 48) for o in objectives]
        rows = list(range(len(objectives)))  # by place: two objectives may share a prompt
        fig, ax = plt.subplots(figsize=(7, 0.45 * max(len(labels), 1) + 1.0))
        left = [0.0] * len(objectives)
        said: list[list[str]] = [[] for _ in objectives]
        for key in (Verdict.CORRECT, Verdict.PARTIAL, Verdict.INCORRECT, None):
            shares = []
            for o in objectives:
                wanted = {c.label: c.share for c in o.verdicts}
                share = sum(v for k, v in wanted.items()
                            if (k == key) or (key is None and k not in _COLOURS))
                shares.append(100 * share)
            ax.barh(rows, shares, left=left, color=_COLOURS[key], label=_KINDS[key],
                    edgecolor="white")
            left = [a + b for a, b in zip(left, shares)]
            for words, share in zip(said, shares):
                if share:
                    words.append(f"{share:.0f} % {_KINDS[key]}")
        ax.set_yticks(rows, labels)
        ax.set_xlim(0, 100)
        ax.set_xlabel("% of graded students")
        ax.invert_yaxis()
        ax.legend(ncol=4, loc="lower center", bbox_to_anchor=(0.5, 1.0), frameon=False)
        return _svg(fig, "success", "Success per objective",
                    " ".join(f"{o.title}: {', '.join(words) or 'no graded answers'}."
                             for o, words in zip(objectives, said)))

