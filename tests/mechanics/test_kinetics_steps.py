"""The kinetics steps of the worked solution: textbook order, MathML with dotted rates and
reactions named by their axes, the balances a textbook writes (along a contact's normal, about
a fixed pivot), the work-energy balance term by term, and the mistakes each row is where."""

from __future__ import annotations

import pytest

from mechgrade.mechanics.kinetics_steps import kinetics_steps
from mechgrade.resources import shipped_dir
from mechgrade.spec import load_problem

PROBLEMS = shipped_dir("problems")


@pytest.fixture(scope="module")
def pendulum():
    problem = load_problem(shipped_dir("examples") / "hw3_dynamics" / "pendulum_release.yaml")
    return {s.anchor: s for s in kinetics_steps(problem)}


def rows(step):
    return {r.anchor: r for r in step.rows}


def test_the_inertia_is_a_matrix_and_the_loads_are_vectors(pendulum):
    inertia = rows(pendulum["kinetics-bodies"])["inertia-rod"]
    assert inertia.math.count("<mtr>") == 3 and "<mfrac>" in inertia.math
    assert inertia.text == "I_G = [L**2*m/12, 0, 0; 0, 0, 0; 0, 0, L**2*m/12]"
    loads = rows(pendulum["kinetics-free-body-loads"])
    assert loads["load-rod-R_O"].math.count("<mi>O,x</mi>") == 1
    assert loads["load-rod-gravity"].codes == ("weight_omitted", "mass_for_weight",
                                               "weight_for_mass", "load_at_other_point")


def test_the_rates_are_dotted_and_no_reaction_is_numbered(pendulum):
    for step in pendulum.values():
        for row in step.rows:
            assert "thetad" not in row.math and "R_O_1" not in row.math, row.anchor
    balances = pendulum["kinetics-momentum-balances"].rows
    assert any("\u2219\u2219" in r.math for r in balances)  # θ̈: two dots over θ


def test_a_body_on_a_fixed_pivot_has_its_moment_balance_about_it(pendulum):
    pivot = rows(pendulum["kinetics-momentum-balances"])["balance-pivot-rod-O"]
    assert pivot.caption == "rod: moment balance about the fixed pivot O (N.z component)"
    assert pivot.text == "-L**2*m*thetadd/3 - L*g*m*sin(theta)/2 = 0"
    assert "central_inertia_at_pivot" in pivot.codes


def test_the_work_energy_balance_is_written_term_by_term(pendulum):
    energy = rows(pendulum["kinetics-work-energy"])
    assert [r.text for r in energy.values()] == [
        "T1 + V1 + U12 = T2 + V2", "T1 = 0, V1 = -L*g*m*cos(theta0)/2",
        "T2 = L**2*m*thetad**2/6", "V2 = -L*g*m*cos(theta)/2"]
    assert "rotational_ke_omitted" in energy["energy-T2"].codes


def test_the_normal_force_has_the_balance_along_its_normal():
    steps = kinetics_steps(load_problem(PROBLEMS / "block_sliding_down_incline.yaml"))
    (balances,) = [s for s in steps if s.anchor == "kinetics-momentum-balances"]
    normal = balances.rows[0]
    assert normal.anchor == "balance-normal-block-N_P" and "normal_from_weight" in normal.codes
    assert (normal.caption, normal.text) == ("block: along the normal of N_P (A.y)",
                                             "N_P - g*m*cos(beta) = 0")
    assert not any(s.anchor == "kinetics-work-energy" for s in steps)
    # and along the incline: the textbook's axes, the normal's frame (A), not only N's
    surface = balances.rows[1]
    assert surface.anchor == "balance-surface-block-N_P"
    assert (surface.caption, surface.text) == ("block: along the surface of N_P (A.x)",
                                               "-N_P*mu_k*xd/Abs(xd) + g*m*sin(beta) - m*xdd = 0")


def test_a_normal_along_the_fixed_axes_adds_no_surface_balance():
    steps = kinetics_steps(load_problem(PROBLEMS / "cylinder_pulled_rolls.yaml"))
    (balances,) = [s for s in steps if s.anchor == "kinetics-momentum-balances"]
    assert not any(r.anchor.startswith("balance-surface") for r in balances.rows)


def test_the_math_holds_only_printable_characters(pendulum):
    # a terminal shows a non-printable character (a no-break space) escaped, as "\xa0"
    for step in pendulum.values():
        for row in step.rows:
            assert row.math.isprintable(), (row.anchor, row.math)


def test_a_rows_caption_is_its_own_text_not_part_of_its_equation(pendulum):
    # the page sets the caption in words before the equation (and a screen reader says the
    # equation alone after it): the MathML is the equation's
    row = rows(pendulum["kinetics-free-body-loads"])["load-rod-R_O"]
    assert row.caption == "rod, pin reaction R_O at O (unknown)"
    assert "<mtext>" not in row.math and not row.text.startswith("rod")
