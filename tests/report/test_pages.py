"""The pages a student or an instructor opens, on every screen, printer and reader: a feedback
page with its worked solution, the one card of an unreadable submission, a problem sheet, a
dynamics worked solution and the class report pass axe-core's WCAG 2 A and AA rules in
headless Chromium, fit a phone's screen (what is wider scrolls in a box of its own) and print
a card, a figure or a step on one page.

The dynamics feedback pages of examples/hw3_dynamics are checked where that class is graded
(tests/cli/test_hw3_dynamics_cli.py).
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from mechgrade.cli import main
from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.run import grade_submissions
from mechgrade.grade.worked import shown_solutions
from mechgrade.report.class_report import write_class_report
from mechgrade.report.output import write_outputs
from mechgrade.resources import shipped_dir
from mechgrade.roster import read_roster

EXAMPLES = shipped_dir("examples")


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    """examples/hw1 graded once with its worked solutions (its due date is past), its class
    report, examples/hw2's sheets and the released pendulum's worked solution as a page:
    ``{name: path}``."""
    out = tmp_path_factory.mktemp("pages")
    hw1 = EXAMPLES / "hw1"
    assignment = load_assignment(hw1 / "assignment.yaml")
    report = grade_submissions(assignment, hw1 / "submissions",
                               read_roster(hw1 / "roster.csv"))
    write_outputs(report, out / "hw1", worked=shown_solutions(assignment, report))
    write_class_report(report, out / "class_report.html")
    hw2 = EXAMPLES / "hw2_variants"
    runner = CliRunner()
    handout = runner.invoke(main, ["handout", str(hw2 / "assignment.yaml"), "--roster",
                                   str(hw2 / "roster.csv"), "--out", str(out / "sheets")])
    assert handout.exit_code == 0, handout.output
    steps = runner.invoke(main, ["solve", str(EXAMPLES / "hw3_dynamics" / "pendulum_release.yaml"),
                                 "--steps", "--format", "html"])
    assert steps.exit_code == 0, steps.output
    (out / "steps.html").write_text(steps.output, encoding="utf-8")
    return {"feedback": out / "hw1" / "feedback" / "dan_wu.html",
            "unreadable": out / "hw1" / "feedback" / "ivy_binary.html",
            "class report": out / "class_report.html",
            "sheet": out / "sheets" / "20001.html",
            "dynamics steps": out / "steps.html"}


@pytest.mark.parametrize("name", [  # `pytest -m slow` checks the pages built like this one
    "dynamics steps", *(pytest.param(name, marks=pytest.mark.slow)
                        for name in ("feedback", "unreadable", "class report", "sheet"))])
def test_every_page_passes_axe_core_wcag_2_a_and_aa(pages, axe, name):
    assert axe(pages[name]) == []


@pytest.mark.parametrize("name", ["feedback", "unreadable", "class report", "sheet"])
def test_a_page_fits_a_phone_and_what_is_wider_scrolls_in_its_own_box(pages, phone, name):
    laid_out = phone(pages[name])
    assert laid_out["width"] == 375
    assert laid_out["past"] == [] and laid_out["page"] <= 375, laid_out


def test_every_page_has_a_main_landmark_and_a_viewport(pages):
    for name, page in pages.items():
        text = page.read_text(encoding="utf-8")
        assert text.count("<main>") == 1, name
        assert '<meta name="viewport" content="width=device-width, initial-scale=1">' in text


def test_every_equation_says_itself_and_every_picture_is_described_in_words(pages):
    for name in ("feedback", "dynamics steps"):
        text = pages[name].read_text(encoding="utf-8")
        assert text.count("<math ") == text.count("<math aria-label=") > 0, name
    feedback = pages["feedback"].read_text(encoding="utf-8")
    # an image's title and desc are its name and description (role="img")
    assert ('<svg viewBox="0 0 480 360" width="480" height="360" role="img" class="mechanism">'
            '<title>Acceleration of a pendulum tip: the mechanism at the instant</title>') in feedback
    assert ('<desc>Points O and A; a line joins A to O. Unit '
            'vectors x and y of frames N and A. Arrows: velocity (longest 14 ft/s), in blue; '
            'acceleration (longest 99 ft/s²), in red.</desc>') in feedback  # the problem's feet
    report = pages["class report"].read_text(encoding="utf-8")
    assert '<title id="histogram-title">Score distribution (out of 19)</title>' in report
    assert '<title id="success-title">Success per objective</title>' in report


PRINT_PROBE = """<script>
// every element of a kind kept on one page when printed: a print rule avoids breaking it
const whole = new Map();
for (const sheet of document.styleSheets) for (const media of sheet.cssRules)
  if (media.media && media.media.mediaText === "print")
    for (const rule of media.cssRules)
      if (rule.style && rule.style.breakInside === "avoid")
        for (const e of document.querySelectorAll(rule.selectorText)) whole.set(e, true);
const kinds = {cards: ".objective", figures: "figure", steps: ".ws-steps > li", tables: "tr"};
const out = document.createElement("pre"); out.id = "print";
out.textContent = JSON.stringify(Object.fromEntries(Object.entries(kinds).map(([k, s]) => {
  const all = [...document.querySelectorAll(s)];
  return [k, [all.length, all.filter(e => whole.get(e)).length]]; })));
document.body.append(out);
</script>"""


@pytest.mark.slow
def test_printing_keeps_a_card_a_figure_a_step_or_a_row_on_one_page(pages, in_browser):
    """Chromium's print stylesheets (page counts before and after are in the branch's note;
    they depend on the paper and are not asserted)."""
    found = {name: json.loads(in_browser(pages[name], PRINT_PROBE, "print"))
             for name in ("feedback", "class report", "sheet")}
    cards, figures, steps, _ = found["feedback"].values()
    assert cards[0] == cards[1] == 8 and figures[0] == figures[1] == 3
    assert steps[0] == steps[1] > 20
    report = found["class report"]
    assert report["figures"] == [2, 2] and report["tables"][0] == report["tables"][1] > 10
    assert found["sheet"]["figures"][0] == found["sheet"]["figures"][1] == 2


WHOLE_KEYS = """<script>
const out = document.createElement("pre"); out.id = "keys";
out.textContent = JSON.stringify([...document.querySelectorAll("%s")].filter(
  e => e.getClientRects().length !== 1).map(e => e.textContent));
document.body.append(out);
</script>"""


@pytest.mark.parametrize(("name", "keys"), [("unreadable", ".questions code"),
                                            ("class report", "code.key")])
def test_an_answer_key_is_never_broken_across_lines(pages, in_browser, name, keys):
    assert json.loads(in_browser(pages[name], WHOLE_KEYS % keys, "keys")) == []
