"""What a student sees of a dynamics problem (issue 20 §1–§3), in headless Chromium: the hw3
feedback pages with their worked solutions show each body's free-body diagram with one group
of arrows per load, every kinetics step in MathML with no code in the visible text, and each
kinetic diagnosis linked to its highlighted step; the page passes axe-core. The SVG itself is
checked without a browser on examples the drawing has to get right."""

from __future__ import annotations

import json
import re

import pytest

from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.diagnose import LABELS
from mechgrade.grade.run import grade_submissions
from mechgrade.grade.worked import feedback_solutions
from mechgrade.report.fbd import fbd_description, fbd_svg
from mechgrade.report.output import write_outputs
from mechgrade.resources import shipped_dir
from mechgrade.roster import read_roster
from mechgrade.solve import solve
from mechgrade.solve.fbd import DiagramLoad, FreeBodyDiagram, Outline, free_body_diagrams
from mechgrade.spec import load_problem
from mechgrade.spec.dynamics import LoadKind, OutlineKind
from mechgrade.spec.mistake_codes import DYNAMICS_CODES

HW3 = shipped_dir("examples") / "hw3_dynamics"
PROBLEMS = shipped_dir("problems")
KINETIC_LABELS = {LABELS[c] for c in DYNAMICS_CODES}
CODE = re.compile(r"\*\*|\w ?\* ?\w|Abs\(|thetad|_1|\bxd\b|mu_k|\beom\(|\bdot\(|kg\*m")
"""Code text no student should read: a power or a product as code, sympy's names, the model's
names of rates and subscripted symbols, the spec's calls."""


@pytest.fixture(scope="module")
def hw3(tmp_path_factory):
    """examples/hw3_dynamics graded with every problem's worked solution shown:
    ``(feedback folder, results, {problem: [loads per body]}, {problem: [the places of its
    kinetics steps among its steps]})``."""
    out = tmp_path_factory.mktemp("hw3fbd")
    assignment = load_assignment(HW3 / "assignment.yaml")
    report = grade_submissions(assignment, HW3 / "submissions", read_roster(HW3 / "roster.csv"))
    worked = feedback_solutions(assignment, report)
    write_outputs(report, out, worked=worked)
    loads = {w.problem: [len(d.loads) for d in w.diagrams] for w in worked.solutions}
    # a step has an id only when a link may target it: the kinetics steps by their places
    kinetics = {w.problem: [i for i, s in enumerate(w.steps) if s.anchor.startswith("kinetics-")]
                for w in worked.solutions}
    return (out / "feedback", json.loads((out / "results.json").read_text("utf-8")), loads,
            kinetics)


PROBE = """<script>
const articles = [...document.querySelectorAll("article.ws")];
const hidden = e => e.closest("svg, math, style, script");
const out = {
  problems: articles.map(a => ({
    id: a.id,
    diagrams: [...a.querySelectorAll("svg.fbd")].map(s => [...s.querySelectorAll("g.load")]
      .map(g => g.querySelectorAll(".arrow").length)),
    steps: [...a.querySelectorAll(".ws-steps > li")].map(s => s.querySelectorAll("math").length),
    text: a.innerText.replace(/\\s+/g, " ")})),
  expected: [...document.querySelectorAll(".objective dt")].filter(t => t.innerText === "Expected")
    .map(t => t.nextElementSibling.innerText),
  // the whole page as read, but for what the student wrote (shown as they wrote it)
  visible: (() => { const copy = document.body.cloneNode(true);
    [...copy.querySelectorAll("dt")].filter(t => t.textContent === "Your answer")
      .forEach(t => t.nextElementSibling.remove());
    copy.querySelectorAll("svg, math, style, script").forEach(e => e.remove());
    return copy.textContent.replace(/\\s+/g, " "); })(),
  // what a screen reader says for the math and the figures
  labels: [...document.querySelectorAll("[aria-label], svg title, svg desc")]
    .map(e => e.getAttribute("aria-label") || e.textContent),
  // every arrowhead a figure asks for is defined on the page
  unresolved: [...document.querySelectorAll("[marker-end]")].map(e => e.getAttribute("marker-end"))
    .filter(u => !document.getElementById(u.slice(5, -1))),
  links: [...document.querySelectorAll(".step-link a")].map(l => {
    const target = document.getElementById(l.getAttribute("href").slice(1));
    return [l.closest("section").id, target ? getComputedStyle(target).backgroundColor : null];
  }),
};
const pre = document.createElement("pre"); pre.id = "fbd"; pre.textContent = JSON.stringify(out);
document.body.append(pre);
</script>"""


@pytest.mark.slow
@pytest.mark.parametrize("student", ["carla_diaz", "dan_wu", "femi_adeyemi"])
def test_a_dynamics_page_shows_diagrams_math_and_linked_kinetic_diagnoses(hw3, in_browser,
                                                                          axe, student):
    feedback, results, loads, kinetics = hw3
    page = feedback / f"{student}.html"
    found = json.loads(in_browser(page, PROBE, "fbd"))
    assert [p["id"] for p in found["problems"]] == [f"ws-{name}" for name in loads]
    for problem in found["problems"]:
        name = problem["id"].removeprefix("ws-")
        # one diagram per body, one group of arrows per load, each with an arrow
        assert [len(d) for d in problem["diagrams"]] == loads[name]
        assert all(n >= 1 for d in problem["diagrams"] for n in d)
        assert kinetics[name] and len(problem["steps"]) > max(kinetics[name]), problem
        assert all(problem["steps"][i] > 0 for i in kinetics[name]), problem
        assert not CODE.findall(problem["text"]), name
    assert found["expected"] and not any(CODE.search(e) for e in found["expected"])
    assert not CODE.findall(found["visible"])
    assert found["labels"] and not [label for label in found["labels"] if CODE.search(label)]
    assert found["unresolved"] == []
    diagnosed = {f"{a['problem']}.{a['objective']}"
                 for s in results["students"] if s["id"] == student
                 for a in s["answers"] if a.get("diagnosis") in KINETIC_LABELS}
    assert diagnosed
    highlighted = {key for key, colour in found["links"] if colour == "rgb(255, 244, 229)"}
    assert diagnosed <= highlighted
    assert axe(page) == []


def test_the_diagram_of_the_pendulum_draws_the_rod_and_a_labelled_arrow_per_load():
    problem = load_problem(HW3 / "pendulum_release.yaml")
    (rod,) = free_body_diagrams(problem, solve(problem))
    (outline,) = rod.outline
    assert (outline.kind, outline.sizes, outline.axis) == (OutlineKind.ROD, (1.2,), "y")
    svg = fbd_svg(rod, "hw3-rod")
    assert svg.count('class="load ') == 2 and svg.count('<line class="arrow"') == 3
    # the pin's reaction is unknown: its group is drawn dashed (class u) and marked ?
    assert svg.count('<g class="load u"') == 1 and svg.count(" ?</tspan>") == 2
    assert '<title>Free-body diagram of rod</title>' in svg
    assert fbd_description(rod) == (
        "Body rod, a rod 1.2 m long, with 2 loads: the weight W = 19.6 N at G, downward; the "
        "pin reaction R O at O, unknown (drawn dashed, marked ?), as its components along "
        "n-hat x and n-hat y.")


def _load(name, kind, vector, unknown=False, point="P"):
    return DiagramLoad(name, kind, "b", point, vector, "N", unknown, (name,) if unknown else (),
                       (vector,), ("N.y",), "", None if unknown else 5.0, None)


def _arrows(svg: str) -> list[tuple[float, ...]]:
    import re
    return [tuple(float(v) for v in m) for m in re.findall(
        r'<line class="arrow" x1="([-\d.]+)" y1="([-\d.]+)" x2="([-\d.]+)" y2="([-\d.]+)"', svg)]


def test_collinear_arrows_at_one_point_are_drawn_side_by_side():
    particle = Outline(OutlineKind.PARTICLE, "P", (), "", None)
    d = FreeBodyDiagram("b", None, "P", (("P", (0.0, 0.0, 0.0)),),
                        (_load("s1", LoadKind.SPRING, (-1.0, 0.0, 0.0)),
                         _load("c", LoadKind.DAMPER, (-2.0, 0.0, 0.0))),
                        None, "N", (particle,))
    first, second = _arrows(fbd_svg(d, "b"))
    assert first[1] == first[3] and second[1] == second[3] and abs(first[1] - second[1]) >= 10


def test_a_component_along_the_page_normal_is_a_dot_or_a_cross():
    particle = Outline(OutlineKind.PARTICLE, "P", (), "", None)
    d = FreeBodyDiagram("b", None, "P", (("P", (0.0, 0.0, 0.0)),),
                        (_load("R", LoadKind.REACTION, (0.0, 0.0, 1.0), unknown=True),
                         _load("Q", LoadKind.APPLIED_FORCE, (0.0, 0.0, -3.0))),
                        None, "N", (particle,))
    svg = fbd_svg(d, "b")
    assert _arrows(svg) == [] and 'class="arrow out-of-page"' in svg \
        and 'class="arrow into-page"' in svg


def test_a_problem_in_feet_labels_its_loads_in_pounds_force():
    problem = load_problem(PROBLEMS / "block_on_spring_us_units.yaml")
    (block,) = free_body_diagrams(problem, solve(problem))
    assert ("N", "lbf", pytest.approx(4.4482216)) in block.shown_units
    svg, words = fbd_svg(block, "us"), fbd_description(block)
    assert "W = 10 lbf" in svg and " N<" not in svg and "10 lbf" in words
    # the values the grader judges stay in SI
    (weight,) = [load for load in block.loads if load.kind == LoadKind.WEIGHT]
    assert weight.unit == "N" and weight.magnitude_value == pytest.approx(44.482216)


def test_a_body_given_by_its_inertia_entries_is_drawn_as_a_box_its_loads_clear_of_it():
    body = Outline(OutlineKind.BODY, "P", (), "", None)
    d = FreeBodyDiagram("drum", None, "P", (("P", (0.0, 0.0, 0.0)),),
                        (_load("W", LoadKind.APPLIED_FORCE, (0.0, -1.0, 0.0)),), None, "N", (body,))
    svg = fbd_svg(d, "d")
    assert '<rect class="body"' in svg and '<circle class="body"' not in svg
    ((x1, y1, _, y2),) = _arrows(svg)
    assert (x1, y1) == (0.0, 20.0) and y2 > y1  # from the box's edge, downward
