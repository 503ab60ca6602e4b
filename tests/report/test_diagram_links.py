"""A free-body diagram with a load wrong links to the drawn diagrams of the worked solution, and
equations of motion with one wrong to its momentum balances."""

from __future__ import annotations

import re
import shutil

import pytest

from mechgrade.grade.assignment import load_assignment
from mechgrade.grade.run import grade_submissions
from mechgrade.grade.worked import feedback_solutions
from mechgrade.report.output import anchor, write_outputs
from mechgrade.resources import shipped_dir

HW4 = shipped_dir("examples") / "hw4_derivation"


@pytest.mark.slow  # grades a class and works out four problems' solutions (about 15 s)
def test_a_wrong_diagram_links_to_the_free_body_diagrams_step(tmp_path):
    folder = tmp_path / "hw4"
    shutil.copytree(HW4, folder)
    for student in [p for p in (folder / "submissions").iterdir()
                    if p.name not in ("carla", "mia", "kai")]:
        shutil.rmtree(student)
    assignment = load_assignment(HW4 / "assignment.yaml")
    report = grade_submissions(assignment, folder / "submissions")
    write_outputs(report, tmp_path / "out", worked=feedback_solutions(assignment, report))
    page = (tmp_path / "out" / "feedback" / "carla.html").read_text(encoding="utf-8")
    # carla left out the block's friction and reversed block2's tension
    link = f'<a href="#{anchor("block_sliding_down_incline", "kinetics-free-body-loads")}">'
    assert link in page
    assert f'<a href="#{anchor("atwood_machine", "kinetics-free-body-loads")}">' in page
    # the highlighted step says which loads
    assert "kinetic friction missing" in page.lower()
    assert "tension reversed, wrong magnitude" in page.lower()
    # the diagram she drew right (the rod) links nowhere, nor do right equations
    assert f'<a href="#{anchor("pendulum_pin_reaction", "kinetics-free-body-loads")}">' not in page
    # carla's Atwood equations: block 2's balance turned round; the momentum balances marked
    balances = f'<a href="#{anchor("atwood_machine", "kinetics-momentum-balances")}">'
    assert balances in page
    # her incline equations leave N open: the balances show the one missing
    assert f'<a href="#{anchor("block_sliding_down_incline", "kinetics-momentum-balances")}">' in page
    assert "The equations do not determine \u1e8d" in page  # ẍ, as the note writes it
    mia = (tmp_path / "out" / "feedback" / "mia.html").read_text(encoding="utf-8")
    # kai's equations are right: nothing links to the balances
    kai = (tmp_path / "out" / "feedback" / "kai.html").read_text(encoding="utf-8")
    assert not re.search(r'href="#w[0-9a-f]{5}-kinetics-momentum-balances"', kai)
    assert not re.search(r"#w[0-9a-f]{5}-kinetics-momentum-balances \{", kai)  # nor highlights them
    assert f'<a href="#{anchor("block_sliding_down_incline", "kinetics-momentum-balances")}">' in mia
    assert "the kinetic friction F<sub>P</sub> on block is missing from it" in mia
