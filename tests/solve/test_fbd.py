"""Free-body diagrams as plain data: every load on every body at the solved instant, with
nothing of sympy in them (report and export read them without importing it)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from mechgrade.solve import solve
from mechgrade.solve.fbd import DiagramLoad, FreeBodyDiagram, Surface, free_body_diagrams
from mechgrade.spec import load_problem

ROOT = Path(__file__).resolve().parents[2]


def diagrams(name: str):
    problem = load_problem(ROOT / "problems" / f"{name}.yaml")
    return free_body_diagrams(problem, solve(problem))


def _plain(value) -> bool:
    if dataclasses.is_dataclass(value):
        return all(_plain(getattr(value, f.name)) for f in dataclasses.fields(value))
    if isinstance(value, tuple):
        return all(_plain(v) for v in value)
    return value is None or isinstance(value, (str, float, int, bool))


@pytest.mark.parametrize("name", ["pendulum_pin_reaction", "block_slides_on_cart",
                                  "rod_strikes_ledge", "two_mass_spring_chain",
                                  "cord_over_table_pulley", "flywheel_speed_drop"])
def test_a_diagram_is_plain_data_with_every_load_on_its_body(name):
    found = diagrams(name)
    assert found and all(isinstance(d, FreeBodyDiagram) and _plain(d) for d in found)
    for d in found:
        assert all(isinstance(load, DiagramLoad) and load.body == d.body for load in d.loads)
        points = dict(d.points)
        assert all(load.point is None or load.point in points for load in d.loads)


def test_the_pin_reaction_is_two_unknown_components_at_the_pin():
    (rod,) = diagrams("pendulum_pin_reaction")
    weight, pin = rod.loads
    assert (weight.kind, weight.point, weight.magnitude, weight.vector) == \
        ("weight", "G", "g*m", (0.0, -19.62, 0.0))
    assert (pin.kind, pin.point, pin.unknown, pin.components, pin.direction_texts) == \
        ("pin", "O", True, ("R_O_1", "R_O_2"), ("N.x", "N.y"))
    assert pin.vector == pytest.approx((-14.1878, 21.8134, 0.0), abs=1e-4)
    assert rod.down == (0.0, -1.0, 0.0) and rod.frame == "B" and rod.centre == "G"


def test_a_joint_and_friction_between_bodies_act_oppositely_on_each():
    block, cart = diagrams("block_slides_on_cart")
    on_block = {load.name: load for load in block.loads}
    on_cart = {load.name: load for load in cart.loads}
    for name in ("N_P", "F_P"):
        assert on_block[name].vector == pytest.approx(tuple(-c for c in on_cart[name].vector))
        assert (on_block[name].sign, on_cart[name].sign) == (1, -1)
    assert on_block["N_P"].surface == Surface("cart", (0.0, 1.0, 0.0))
    assert on_cart["N_P"].surface.on == "block"
    assert on_block["F_P"].magnitude == "N_P*mu"


def test_an_impact_diagram_shows_impulses():
    (rod,) = diagrams("rod_strikes_ledge")
    (ledge,) = rod.loads
    assert (ledge.kind, ledge.unit, ledge.surface.on) == ("normal", "N*s", "ground")
    assert ledge.vector == pytest.approx((0.0, 4.5, 0.0))


def test_a_couple_has_no_point():
    (flywheel,) = diagrams("flywheel_speed_drop")
    (punch,) = flywheel.loads
    assert (punch.kind, punch.point, punch.unit, punch.vector[2]) == \
        ("applied couple", None, "N*m", -1500.0)
    assert flywheel.down is None


def test_a_diagram_without_a_solved_state_keeps_its_structure():
    problem = load_problem(ROOT / "problems" / "pendulum_pin_reaction.yaml")
    solution = dataclasses.replace(solve(problem), state=())
    (rod,) = free_body_diagrams(problem, solution)
    assert [load.name for load in rod.loads] == ["gravity", "R_O"]
    assert all(load.vector is None for load in rod.loads)
    assert rod.loads[0].magnitude == "g*m" and rod.loads[0].magnitude_value is None


def test_at_the_event_where_a_slip_ends_the_loads_are_the_limit_just_before_it():
    # the marble's slip velocity is zero at the event: its kinetic friction has a direction
    # only in the limit, backwards along the motion it still opposes there
    marble, _ball = diagrams("ruina_9_22_marble_bowling_ball")
    _weight, normal, friction = marble.loads
    assert friction.name == "F_C" and friction.vector is not None
    assert friction.vector[0] == pytest.approx(-0.1 * 0.005 * 9.81, rel=1e-5)
    assert normal.vector[1] == pytest.approx(0.005 * 9.81, rel=1e-5)
    assert dict(marble.points)["C"] is not None
