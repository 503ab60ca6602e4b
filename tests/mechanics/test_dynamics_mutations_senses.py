"""Kinetics mistakes of sense and sign: an acceleration, a velocity or a spring's work taken
the other way, read in the right model or solved again."""

from __future__ import annotations

from functools import lru_cache

from mechgrade.grade.compare import assess
from mechgrade.grade.diagnose import LABELS
from mechgrade.mechanics.dynamics_mutations import dynamics_mutations
from mechgrade.solve import solve
from library import library_problem as _problem


@lru_cache(maxsize=None)
def _solution(name):
    return solve(_problem(name))


def _values(name, objective, code):
    return [m.value for m in _solution(name).result(objective).generated_mistakes
            if m.code == code]


def test_a_falling_block_taken_to_accelerate_upward_gives_m_g_plus_m_a():
    # T = m (g - a) = 96.1 N for the block falling at 5.005 m/s²; m (g + a) = 296.3 N
    (value,) = _values("drum_hoist_falling_block", "tension", "acceleration_reversed")
    assert abs(value - 20 * (9.81 + 5.005102)) < 1e-3
    judged = assess("296.3 N", _solution("drum_hoist_falling_block").result("tension"))
    assert judged.diagnosis == LABELS["acceleration_reversed"]


def test_no_acceleration_reversed_where_nothing_accelerates_along_the_reaction():
    # the crate slides along the floor: its normal force has no m a_G to reverse
    assert not _values("crate_pushed_impulse_momentum", "normal", "acceleration_reversed")
    # a drum on its axle does not move: no reading of its bearing's force
    assert all(m.code != "acceleration_reversed" or "drum along" not in m.sentence
               for m in dynamics_mutations(_problem("drum_hoist_falling_block")))


def test_the_incoming_velocitys_sense_ignored_gives_m_v2_minus_m_v1_along_the_axis():
    # the ball comes in at -40 m/s along x: taken as +40, the impulse is m (43.30 - 40) along x
    (value,) = [m.value for m in _solution("baseball_bat_impulse").result("impulse")
                .generated_mistakes if "just before the impact" in m.message]
    assert abs(value[0] - 0.145 * (50 * 3 ** 0.5 / 2 - 40)) < 1e-9
    judged = assess("(0.4787, 3.625, 0) N*s", _solution("baseball_bat_impulse").result("impulse"))
    assert judged.diagnosis == LABELS["given_sign"] and "just before the impact" in judged.feedback


def test_no_sense_reversed_for_a_rate_at_rest_before_the_impact():
    # the ball's y' is 0 before the bat: one mistaken model, for x' only
    mutations = [m for m in dynamics_mutations(_problem("baseball_bat_impulse"))
                 if m.code == "given_sign"]
    assert len(mutations) == 1 and mutations[0].sentence.startswith("Your value is what x'")


def test_an_impulse_from_the_speeds_added_or_subtracted_as_numbers():
    # m (50 + 40) and m (50 - 40), in the magnitude and in the average force it gives
    assert [round(v, 6) for v in sorted(_values("baseball_bat_impulse", "impulse_magnitude",
                                                "mag_as_sum"))] == [1.45, 13.05]
    assert [round(v, 6) for v in sorted(_values("baseball_bat_impulse", "average_force",
                                                "mag_as_sum"))] == [966.666667, 8700.0]


def test_no_impulse_from_speeds_for_a_body_in_a_contact():
    # the pucks' impact is a contact between two bodies: its impulse is not one body's alone
    assert all(m.code != "mag_as_sum" or "momenta" not in m.sentence
               for m in dynamics_mutations(_problem("pucks_oblique_impact")))


def test_a_springs_work_counted_as_helping_the_fall():
    # ½ m v² = m g h - 3 J (the spring stretches from 0.1 m to 0.2 m); + 3 J: 2.981 m/s
    (value,) = _values("collar_spring_vertical_rod", "speed", "spring_work_reversed")
    assert abs(value - (2 * 9.81 * 0.3 + 3.0) ** 0.5) < 1e-6
    # a force is not read from the energy: the rod's push is no spring work mistake
    assert not _values("collar_spring_vertical_rod", "rod_force", "spring_work_reversed")


def test_no_spring_work_reversed_outside_a_work_energy_balance():
    assert not _values("block_between_two_springs", "amplitude", "spring_work_reversed")


def test_an_incoming_rate_reversed_that_flips_the_whole_answer_is_said_as_a_sign_error():
    # the ball's rebound is linear in its speed before: reversed, the whole answer flips
    result = _solution("ball_strikes_hanging_rod").result("ball_velocity_after")
    judged = assess(f"{-result.value:.4g} {result.unit}", result)
    assert judged.diagnosis == "sign error"


def test_sines_and_cosines_exchanged_in_the_velocities_before_an_impact():
    # every velocity's components written from the other axis: (-3.981, -5.196) for A
    values = _values("pucks_oblique_impact", "velocity_A", "angle_complement")
    assert any(abs(v[0] + 3.981230) < 1e-5 and abs(v[1] + 5.196152) < 1e-5 for v in values)
    # the bat's ball comes in along x: no angle in its rates before, none exchanged
    assert not _values("baseball_bat_impulse", "impulse", "angle_complement")


def test_a_slanted_pushs_downward_part_taken_upward():
    # N = m g - P sin 30° = 340.5 N: less friction, 14.61 m/s after 4 s
    assert 340.5 in [round(v, 6) for v in _values("crate_pushed_impulse_momentum", "normal",
                                                  "force_component_reversed")]
    assert any(abs(v - 14.6126) < 1e-3 for v in _values(
        "crate_pushed_impulse_momentum", "speed", "force_component_reversed"))


def test_no_force_component_reversed_without_an_applied_force_slanted_to_a_reaction():
    # the cylinder's pull is along the floor, across its normal force: nothing to reverse
    assert not any(m.code == "force_component_reversed"
                   for m in dynamics_mutations(_problem("cylinder_pulled_rolls")))
