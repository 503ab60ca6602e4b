"""Kinematic mistakes of sense and of the triangle: ω × r the other way round, an angle read
from the other leg, two velocity terms added as if at right angles."""

from __future__ import annotations

from functools import lru_cache

import pytest

from mechgrade.grade.compare import assess
from mechgrade.grade.diagnose import LABELS
from mechgrade.mechanics.mutations import mutations
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.spec import load_problem


@lru_cache(maxsize=None)
def _problem(name):
    return load_problem(shipped_dir("problems") / f"{name}.yaml")


def _values(name, objective, code):
    return [m.value for m in solve(_problem(name)).result(objective).generated_mistakes
            if m.code == code]


def test_omega_cross_r_taken_the_other_way_round_on_a_rolling_wheel():
    # v_P = v_G + ω × r = (3, 0) + (2.121, -2.121); the other way: (0.879, 2.121)
    (value,) = _values("rolling_wheel_rim_points", "velocity_P", "omega_reversed")
    assert value == pytest.approx((3 - 1.5 * 2 ** 0.5, 1.5 * 2 ** 0.5, 0.0))
    judged = assess("(0.8787, 2.121, 0) m/s",
                    solve(_problem("rolling_wheel_rim_points")).result("velocity_P"))
    assert judged.diagnosis == LABELS["omega_reversed"]


def test_no_omega_reversed_where_the_frame_does_not_turn():
    # the air is carried by the wind without turning: no ω × r to reverse
    assert "omega_reversed" not in [m.code for m in mutations(_problem(
        "airplane_crosswind_heading")) if m.objective == "ground_speed"]


def test_an_angle_from_atan2_read_from_the_other_leg_is_its_complement():
    (value,) = _values("airplane_crosswind_heading", "heading", "angle_complement")
    assert value == pytest.approx(90 - 14.477512, abs=1e-5)
    # a speed is no angle: no complement
    assert not _values("airplane_crosswind_heading", "ground_speed", "angle_complement")


def test_the_winds_and_the_airspeed_added_as_if_at_right_angles():
    # √(240² + 60²) = 247.4 km/h; the ground speed is √(240² - 60²) = 232.4 km/h
    assert any(v == pytest.approx((240 ** 2 + 60 ** 2) ** 0.5)
               for v in _values("airplane_crosswind_heading", "ground_speed", "mag_as_sum"))


def test_a_midpoints_speed_taken_as_the_mean_of_the_end_speeds():
    # the rod's ends move at 2 and 1.793 m/s: their mean 1.897 m/s, G's speed 1.753 m/s
    values = _values("rod_in_two_slots_ic", "speed_G", "mag_as_sum")
    assert any(v == pytest.approx((2 + 1.793150944) / 2) for v in values)
    # the airplane is the midpoint of no two points: no mean of speeds
    assert not any("mean of the speeds" in m.sentence for m in mutations(
        _problem("airplane_crosswind_heading")))
