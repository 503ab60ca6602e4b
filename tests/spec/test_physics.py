"""Numbers that make no physical sense: a tolerance tighter than the reference (refused) and
magnitudes implausible for their unit system (warned, both numbers named)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import get_args

import pytest

from mechgrade.errors import SpecError
from mechgrade.expressions.syntax import Name
from mechgrade.spec import load_problem_text
from mechgrade.spec.dynamics import (Block, Cylinder, Disk, Explicit, Ring, Rod, Shape, Shell,
                                     Sphere)
from mechgrade.spec.model import Expr

ROOT = Path(__file__).resolve().parents[2]


def text(name: str) -> str:
    return (ROOT / "problems" / f"{name}.yaml").read_text()


def warnings_of(body: str) -> list[str]:
    problem_id = next(line for line in body.splitlines() if line.startswith("id: "))[4:]
    return [w.message for w in load_problem_text(body, f"{problem_id}.yaml").warnings]


def test_a_tolerance_with_a_small_absolute_part_is_accepted_at_load():
    body = text("pendulum_pin_reaction").replace("    unit: rad/s^2\n",
                                                 "    unit: rad/s^2\n    tolerance: {rel: 0, "
                                                 "abs: 0.01}\n", 1)
    assert load_problem_text(body, "pendulum_pin_reaction.yaml").objectives[0].tolerance.abs \
        == 0.01


def test_a_relative_tolerance_below_the_reference_accuracy_is_refused():
    body = text("pendulum_pin_reaction").replace("    unit: rad/s^2\n",
                                                 "    unit: rad/s^2\n    tolerance: {rel: "
                                                 "1.0e-9}\n", 1)
    with pytest.raises(SpecError, match=r"objectives\[0\]\.tolerance: expected a tolerance no "
                                        r"tighter than the reference's own accuracy \(1e-06 of "
                                        r"the answer\), found rel: 1e-09 and no abs"):
        load_problem_text(body, "p.yaml")


@pytest.mark.parametrize("written, expected", [
    ("32.2 m/s^2", "g = 32.2 m/s^2 is 32.2 m/s^2, not standard gravity: 32.2 is g in ft/s^2; "
                   "in m/s^2 it is 9.807 (expected g: 9.807 m/s^2, or g: 32.2 ft/s^2)"),
    ("981 m/s^2", "g = 981 m/s^2 is 981 m/s^2, not standard gravity: 981 is g in cm/s^2"),
])
def test_standard_gravity_in_another_unit_is_warned(written, expected):
    found = warnings_of(text("pendulum_pin_reaction").replace("g: 9.81 m/s^2", f"g: {written}"))
    assert any(w.startswith(expected) for w in found), found


@pytest.mark.parametrize("name, old, new", [
    ("ruina_9_20_ladder_energy", None, None),       # g: 1 m/s^2 on purpose
    ("ruina_9_23_ball_impulse_momentum", None, None),  # 9.8 m/s^2
    ("ruina_9_22_marble_bowling_ball", None, None),  # 5 g beside 20.48 kg: both spheres fit
    ("pendulum_pin_reaction", "g: 9.81 m/s^2", "g: 32.174 ft/s^2"),
])
def test_plausible_magnitudes_are_not_warned(name, old, new):
    body = text(name) if old is None else text(name).replace(old, new)
    assert warnings_of(body) == []


def test_a_body_lighter_than_air_for_its_size_is_warned():
    body = text("ruina_9_23_ball_impulse_momentum").replace("  m: 1 kg\n", "  m: 1 g\n")
    body = body.replace("  r: 0.1 m\n", "  r: 1 m\n")
    (found,) = warnings_of(body)
    assert found.startswith("body 'ball': a sphere of mass 1 g and r = 1 m would be at most "
                            "0.000239 kg/m^3, lighter than air")


def test_every_shape_bounds_its_own_volume_from_its_sizes():
    metres = Expr("a", Name("a"))
    shapes = [Rod(metres, "x"), Ring(metres, "z"), Disk(metres, "z"),
              Cylinder(metres, metres, "z"), Sphere(metres), Shell(metres),
              Block((metres, metres, metres)), Explicit((("xx", metres),))]
    assert {type(s) for s in shapes} == set(get_args(Shape))
    got = {type(s).__name__: s.volumes(lambda e: 2.0) for s in shapes}
    expected = {
        "Rod": (2 * math.pi, 2 * math.pi * 1e-6), "Ring": (16 * math.pi, 8 * math.pi / 1000),
        "Disk": (16 * math.pi, 8 * math.pi / 1000), "Cylinder": (8 * math.pi, 8 * math.pi),
        "Sphere": (32 / 3 * math.pi,) * 2, "Shell": (32 / 3 * math.pi, 0.0),
        "Block": (8.0, 8.0), "Explicit": None}
    assert got == {name: v and pytest.approx(v) for name, v in expected.items()}
    assert [s.volumes(lambda e: None) for s in shapes] == [None] * len(shapes)
