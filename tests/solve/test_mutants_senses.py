"""Mistaken givens of sense: an angle measured to the other side of its reference line."""

from __future__ import annotations

import pytest

from mechgrade.grade.compare import assess
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.spec import load_problem


def _result(name, objective):
    return solve(load_problem(shipped_dir("problems") / f"{name}.yaml")).result(objective)


def test_a_disks_tilt_measured_to_the_other_side_turns_h_across_the_shaft():
    result = _result("disk_on_bent_shaft", "angular_momentum")
    (value,) = [m.value for m in result.generated_mistakes if m.code == "given_angle_sign"]
    assert value == pytest.approx((0.0, -result.value[1], result.value[2]))
    judged = assess("(0, 0.2309, 2.659) kg*m^2/s", result)
    assert judged.diagnosis == "given angle measured to the other side"


def test_no_angle_sign_for_a_problem_without_an_angle_in_degrees():
    result = _result("drum_hoist_falling_block", "tension")
    assert not [m for m in result.generated_mistakes if m.code == "given_angle_sign"]


def test_no_angle_sign_for_a_coordinates_angle_at_the_instant():
    # the crank's phi = 30 deg sets the configuration: phi = -30 deg puts the pin's velocity
    # along the slot (r ω, a velocity component mistake's value): not read as a misread angle
    result = _result("slotted_arm_crank_coriolis", "sliding_rate")
    assert not [m for m in result.generated_mistakes if m.code == "given_angle_sign"]
