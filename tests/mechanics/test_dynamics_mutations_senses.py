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
