"""check lists the generated mistakes a tolerance cannot tell from the answer."""

import pytest

from mechgrade.check import check_problem
from mechgrade.resources import shipped_dir


def test_a_mistake_inside_the_tolerance_is_a_warning_with_the_separating_tolerance():
    report = check_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")
    assert report.passed and len(report.separations) == 1
    assert "'acc_mag'" in report.separations[0] and "{rel: 0.002}" in report.separations[0]


@pytest.mark.slow
def test_a_mistake_too_close_to_separate_is_said_so():
    report = check_problem(shipped_dir("problems") / "bowling_3_15_5_cylinder.yaml")
    assert any("no tolerance that still accepts four significant figures" in line
               for line in report.separations)


def test_a_problem_whose_mistakes_are_all_outside_has_no_separation_warning():
    report = check_problem(shipped_dir("problems") / "ruina_10_6_rotating_tube_velocity.yaml")
    assert report.separations == ()
