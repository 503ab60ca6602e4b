"""The worked solution and the picture inside each student's feedback page: when the
assignment shows them, the student's own numbers, and the step where their mistake happens."""

from __future__ import annotations

import json
from datetime import datetime, timezone

import pytest

from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.run import grade_submissions
from mechgrade.grade.worked import feedback_solutions, shown_solutions
from mechgrade.report.output import write_outputs
from mechgrade.expressions.notation import textbook
from mechgrade.report.output import anchor
from mechgrade.resources import shipped_dir

PROBLEMS = shipped_dir("problems")
PENDULUM = "bowling_3_15_4_pendulum"
CENTRIPETAL_ROW = anchor(PENDULUM, "acc-A-omega_omega_r")


def _class(tmp_path, policy: str = "", due: str | None = None):
    (tmp_path / "hw.yaml").write_text(
        f"id: hw\ntitle: Homework\nproblems:\n  - {PROBLEMS / (PENDULUM + '.yaml')}\n"
        f"  - path: {PROBLEMS / 'ruina_10_4_10_7_rotating_tube_accel.yaml'}\n"
        f"    objectives: [a_P_N]\n" + (f"due: {due}\n" if due else "")
        + (f"policy: {{worked_solution: {policy}}}\n" if policy else ""), encoding="utf-8")
    for student, acc_mag, a_p in (("ana", "98.5 ft/s^2", "-66 i - 40 j"),
                                  ("zoe", "10 ft/s^2", "-66 i - 40 j"),
                                  ("max", "98.5 ft/s^2", "-106 i - 40 j")):  # no Coriolis
        folder = tmp_path / "submissions" / student
        folder.mkdir(parents=True)
        (folder / "answers.yaml").write_text(
            f"{PENDULUM}:\n  acc_mag: {acc_mag}\nruina_10_4_10_7_rotating_tube_accel:\n"
            f"  a_P_N: {a_p} ft/s^2\n", encoding="utf-8")
    assignment = load_assignment(tmp_path / "hw.yaml")
    return assignment, grade_submissions(assignment, tmp_path / "submissions")


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """A class graded once, its pages written with the worked solutions: (folder, report)."""
    folder = tmp_path_factory.mktemp("class")
    assignment, report = _class(folder, "always")
    out = folder / "out"
    write_outputs(report, out, worked=shown_solutions(assignment, report))
    return out / "feedback", report


def test_every_page_shows_the_worked_solution_and_the_picture_inline(graded):
    feedback, _ = graded
    for name in ("ana", "zoe"):
        page = (feedback / f"{name}.html").read_text(encoding="utf-8")
        # a picture each, and the arrowheads they share defined once for the page
        assert page.count('<article class="ws"') == 2 and page.count('class="mechanism"') == 2
        assert page.count('<svg class="ws-defs"') == 1
        assert f'id="{CENTRIPETAL_ROW}"' in page and "<math" in page
        # an id only where a link may point: the step around that row is no mistake's place
        assert f'id="{anchor(PENDULUM, "acc-A")}"' not in page
        assert "<script" not in page and "src=" not in page  # offline, nothing to fetch
        markdown = (feedback / f"{name}.md").read_text(encoding="utf-8")
        assert "## Worked solution" in markdown and "### Givens and what is asked" in markdown


def test_the_step_where_the_students_mistake_happens_is_highlighted_and_linked(graded):
    feedback, report = graded
    zoe = next(s for s in report.students if s.id == "zoe")
    # a_t for |a| is the same value: both named, the step of the first (the nearer) marked
    assert zoe.answers[0].diagnosis == ("centripetal term ω × (ω × r) left out or tangential "
                                        "acceleration for the whole")
    page = (feedback / "zoe.html").read_text(encoding="utf-8")
    assert _highlighted(page, CENTRIPETAL_ROW)
    assert f'<a href="#{CENTRIPETAL_ROW}">See where this happens in the worked solution: ' \
           f"The acceleration of A in N" in page
    assert f'id="{CENTRIPETAL_ROW}"' in page
    markdown = (feedback / "zoe.md").read_text(encoding="utf-8")
    assert "- Where this happens in the worked solution: The acceleration of A in N" in markdown
    # a right answer marks nothing
    assert f'href="#{anchor(PENDULUM, "")}' not in (feedback / "ana.html").read_text(encoding="utf-8")


def test_an_authors_mistake_with_a_generated_mistakes_value_marks_its_step_too(graded):
    feedback, report = graded
    max_ = next(s for s in report.students if s.id == "max")
    # the problem's author declared this mistake: their message is the diagnosis
    assert max_.answers[-1].diagnosis == "The Coriolis term 2 omega x v_rel is missing."
    row = anchor("ruina_10_4_10_7_rotating_tube_accel", "acc-P-coriolis")
    page = (feedback / "max.html").read_text(encoding="utf-8")
    assert _highlighted(page, row) and f'<a href="#{row}">' in page


def _highlighted(page: str, ident: str) -> bool:
    """Whether the page's highlight rule (one for every marked step) marks ``ident``."""
    rule = next((line for line in page.splitlines() if "{background:#fff4e5" in line), "")
    return f"#{ident}" in rule.partition("{")[0].split(",")


@pytest.mark.parametrize("policy, due, shown", [
    ("never", "2020-01-01", False),
    ("", "2020-01-01", True),          # the default: after the due date
    ("", "2999-01-01", False),
    ("", None, False),                 # no due date: not known to have passed
    ("always", "2999-01-01", True),
])
def test_the_assignment_decides_whether_pages_show_it(tmp_path, policy, due, shown):
    assignment, report = _class(tmp_path, policy, due)
    worked = shown_solutions(assignment, report)
    assert (worked is not None) is shown
    write_outputs(report, tmp_path / "out", worked=worked)
    page = (tmp_path / "out" / "feedback" / "zoe.html").read_text(encoding="utf-8")
    assert ("Worked solution" in page) is shown and ("<svg" in page) is shown


def test_the_due_date_is_compared_with_the_time_the_pages_are_made(tmp_path):
    assignment, report = _class(tmp_path, "after_due_date", "2026-11-20T18:00-05:00")
    before = datetime(2026, 11, 20, 22, 59, tzinfo=timezone.utc)
    after = datetime(2026, 11, 20, 23, 0, tzinfo=timezone.utc)
    assert shown_solutions(assignment, report, before) is None
    assert shown_solutions(assignment, report, after) is not None


def test_each_variant_is_worked_once_and_each_student_sees_their_own_numbers(tmp_path):
    folder = shipped_dir("examples") / "hw2_variants"
    assignment = load_assignment(folder / "assignment.yaml")
    from mechgrade.roster import read_roster

    report = grade_submissions(assignment, folder / "submissions",
                               read_roster(folder / "roster.csv"))
    worked = feedback_solutions(assignment, report)
    draws = {tuple(g for g in s.variant.givens if g.problem == "pendulum_variants")
             for s in report.students}
    assert len(worked.variants) == len(draws) == len(report.students)
    write_outputs(report, tmp_path, worked=worked)
    results = json.loads((tmp_path / "results.json").read_text(encoding="utf-8"))
    for student in results["students"]:
        name = next(p for p in (tmp_path / "feedback").glob("*.md")
                    if f"({student['id']})" in p.read_text(encoding="utf-8")
                    or p.stem == student["id"])
        text = name.read_text(encoding="utf-8")
        worked_part = text[text.index("## Worked solution"):]
        for given in student["variant"]["givens"]:
            if given["problem"] == "pendulum_variants":
                assert f"`{textbook(given['name'])} = {given['value']:g} " in worked_part


PROBE = """<script>
const box = e => { const r = e.getBoundingClientRect(); return [r.width, r.height]; };
const marked = document.getElementById("%s");
document.body.setAttribute("data-probe", JSON.stringify({
  math: [...document.querySelectorAll(".ws math")].map(m => [getComputedStyle(m).display,
                                                              ...box(m)]),
  scripts: [...document.querySelectorAll(".ws mmultiscripts")].map(
    m => box(m)[0] - box(m.firstElementChild)[0]),
  pictures: [...document.querySelectorAll(".ws-picture svg")].map(box),
  labels: [...document.querySelectorAll(".ws-picture svg text")].map(t => t.getBBox().width),
  marked: box(marked),
  note: getComputedStyle(marked, "::before").content,
  background: getComputedStyle(marked).backgroundColor,
}));
</script>
</body>"""


@pytest.mark.slow
def test_chromium_lays_out_the_mathml_the_picture_and_the_highlight(graded, tmp_path, chromium):
    import html

    feedback, _ = graded
    page = (feedback / "zoe.html").read_text(encoding="utf-8")
    # the probe measures the page as laid out; the page itself has no script
    probe = tmp_path / "zoe_probe.html"
    probe.write_text(page.replace("</body>", PROBE % CENTRIPETAL_ROW), encoding="utf-8")
    dom, log = chromium(probe)
    found = json.loads(html.unescape(dom.split('data-probe="', 1)[1].split('"', 1)[0]))
    assert found["math"] and all(display.endswith("math") and width > 0 and height > 0
                                 for display, width, height in found["math"])
    assert found["scripts"] and all(extra > 0 for extra in found["scripts"])  # ^N v^A
    assert len(found["pictures"]) == 2 and all(w > 200 and h > 150
                                               for w, h in found["pictures"])
    assert found["labels"] and all(width > 0 for width in found["labels"])
    assert found["marked"][0] > 0 and found["marked"][1] > 0
    assert "centripetal term" in found["note"].lower() and found["background"] != "rgba(0, 0, 0, 0)"
    assert "Uncaught" not in log and ":CONSOLE" not in log
