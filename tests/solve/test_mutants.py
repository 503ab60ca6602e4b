"""Mistaken givens: the instant solved again with a given misread."""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from mechgrade.grade.compare import assess
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.solve.mutants import kept_at, kept_columns
from mechgrade.solve.result import GeneratedMistake
from mechgrade.spec import load_problem

PENDULUM = shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml"


def _generated(problem, objective, code):
    return [m for m in solve(problem).result(objective).generated_mistakes if m.code == code]


def test_a_rate_in_rpm_used_as_rad_per_second_is_a_mistake():
    problem = load_problem(PENDULUM)
    rpm = 7 * 60 / (2 * 3.141592653589793)
    givens = tuple(replace(g, value=rpm, unit="rpm", text=f"{rpm:.6g} rpm")
                   if g.key.text == "theta'" else g for g in problem.givens)
    (slip,) = _generated(replace(problem, givens=givens), "acc_A", "given_rate_unit")
    assert slip.value[0] == pytest.approx(-2 * rpm ** 2)
    assert "theta' = 66.8451 rpm" in slip.message and "rad/s" in slip.message


def test_an_angle_in_degrees_used_as_radians_is_a_mistake():
    (slip,) = _generated(load_problem(PENDULUM), "acc_N", "given_deg_as_rad")
    assert "30 is used as radians" in slip.message


def test_each_nonzero_rate_has_its_sign_flipped():
    flipped = _generated(load_problem(PENDULUM), "acc_A", "given_sign")
    # theta' squared: flipping it changes nothing and is no mistake; theta'' flips the y part
    assert [m.value for m in flipped] == [pytest.approx((-98.0, -10.0, 0.0))]


def test_an_acute_angle_in_degrees_read_as_its_complement_is_a_mistake():
    (slip,) = _generated(load_problem(PENDULUM), "acc_N", "given_complement")
    # theta = 60 deg for 30: sin and cos exchanged in e_x = (cos, sin), e_y = (-sin, cos)
    c, s = 0.5, 3 ** 0.5 / 2
    assert slip.value[:2] == pytest.approx((-98 * c - 10 * s, -98 * s + 10 * c))
    assert "theta = 60 deg" in slip.message and "complement of 30 deg" in slip.message


def test_an_angle_of_45_degrees_has_no_complement_slip():
    problem = load_problem(PENDULUM)
    givens = tuple(replace(g, value=45.0, text="45 deg") if g.key.text == "theta" else g
                   for g in problem.givens)
    assert _generated(replace(problem, givens=givens), "acc_N", "given_complement") == []


@pytest.mark.slow
def test_a_parameter_rate_in_rpm_used_as_rad_per_second_is_a_mistake():
    # the flywheel's w0 = 300 rpm is a parameter, not a coordinate's rate; the mistaken design
    # (R = 0.2 m) is out of the secant's reach from the author's guess, 0.5 m
    problem = load_problem(shipped_dir("problems") / "flywheel_speed_drop.yaml")
    (slip,) = _generated(problem, "R_needed", "given_rate_unit")
    assert slip.value == pytest.approx(0.2, rel=1e-9)
    assert "w0 = 300 rpm" in slip.message and "rad/s" in slip.message


def test_a_kinematic_objective_of_a_dynamics_problem_gets_another_points_velocity():
    # after the blow v_G = J/m = 2 m/s, ω = 6 J/(m L) = 10 rad/s: the struck end A moves at
    # v_G + ω L/2 = 8 m/s, the velocity asked is B's
    problem = load_problem(shipped_dir("problems") / "rod_struck_on_ice.yaml")
    values = [m.value for m in _generated(problem, "vB_after", "other_point")]
    assert pytest.approx((0.0, 8.0, 0.0)) in values


def test_a_kinematic_objective_of_a_dynamics_problem_gets_another_frames_components():
    # v2 = v2t e_t + v2n e_n with theta = 60 deg: (-17.32, -10) along E copied as i, j
    problem = load_problem(shipped_dir("problems") / "ruina_9_25_units_matrix.yaml")
    (basis,) = _generated(problem, "v2_N", "other_basis")
    assert basis.value == pytest.approx((-20 * 3 ** 0.5 / 2, -10.0, 0.0))
    assert "frame E" in basis.message


def test_a_given_whose_unit_is_not_converted_is_read_in_its_systems_base_unit():
    # the contact time 1.5 ms used as 1.5 s: the average force a thousand times too small,
    # named by its unit (ms), not as a slip of mm
    problem = load_problem(shipped_dir("problems") / "baseball_bat_impulse.yaml")
    (slip,) = _generated(problem, "average_force", "given_unit")
    result = solve(problem).result("average_force")
    assert slip.value == pytest.approx(result.value / 1000)
    judged = assess(f"{slip.value:.4g} N", result)
    assert (judged.diagnosis, judged.feedback) == (
        "given's unit not converted",
        "Your value is what tc = 1.5 ms gives when the number is used as SI units: convert ms "
        "first.")


@pytest.mark.parametrize("unit, base", [("lbf/in", "lbf/ft"), ("kN/m", "N/m"), ("km/h", "m/s"),
                                        ("mm/s", "m/s"), ("hp", "ft*lbf/s")])
def test_the_unit_a_number_is_read_in_when_it_is_not_converted(unit, base):
    from mechgrade.solve.mutants import _unconverted
    from mechgrade.units import si_factor
    assert _unconverted(unit) == pytest.approx(si_factor(base))


@pytest.mark.parametrize("unit", ["N/m", "ft/s", "mm", "rpm", "deg", "lb*s/ft"])
def test_a_unit_of_its_systems_base_or_with_a_slip_of_its_own_has_none(unit):
    from mechgrade.solve.mutants import _unconverted
    assert _unconverted(unit) is None


def test_a_misread_angle_is_carried_into_the_rates_stated_from_it():
    # x' = v2 cos(beta), y' = v2 sin(beta): beta = 30 deg read as 60 deg moves both
    problem = load_problem(shipped_dir("problems") / "baseball_bat_impulse.yaml")
    (slip,) = _generated(problem, "impulse", "given_complement")
    assert slip.value == pytest.approx((0.145 * (50 * 0.5 + 40), 0.145 * 50 * 0.75 ** 0.5, 0.0))


def test_a_misreading_that_leaves_a_stated_given_undefined_misreads_the_given_alone():
    from mechgrade.expressions.syntax import parse
    from mechgrade.solve.instant import instant_givens
    from mechgrade.solve.mutants import _carried_into
    problem = load_problem(shipped_dir("problems") / "baseball_bat_impulse.yaml")
    givens = instant_givens(problem, {}, {})
    node, si, given = givens["x'"]
    root = replace(given, text="sqrt(v2*tc)", value_expr=replace(
        given.value_expr, text="sqrt(v2*tc)", node=parse("sqrt(v2*tc)")))
    givens["x'"] = (node, si, root)
    stated = {key: given for key, (_, _, given) in givens.items() if given is not None}
    assert _carried_into(stated, (("v2", -50.0),)) == (("v2", -50.0),)
    assert dict(_carried_into(stated, (("v2", 50.0),)))["x'"] == pytest.approx((50 * 1.5e-3) ** 0.5)


def test_a_natural_frequency_makes_the_two_pi_between_rad_per_s_and_hertz_plausible():
    from mechgrade.solve.mutants import plausible_slips
    assert "rev_rad" in plausible_slips(load_problem(shipped_dir("problems")
                                                     / "disk_pendulum_period.yaml"))
    # a problem without a frequency or a rate in revolutions: no 2π slip
    assert "rev_rad" not in plausible_slips(load_problem(shipped_dir("problems")
                                                         / "pendulum_pin_reaction.yaml"))
    # rpm beside Hz: per minute for per second; hp in a problem in feet and pounds: 746
    motor = plausible_slips(load_problem(shipped_dir("problems") / "motor_on_beam_resonance.yaml"))
    elevator = plausible_slips(load_problem(shipped_dir("problems")
                                            / "elevator_motor_power.yaml"))
    assert "min_s" in motor and "hp_746" not in motor
    assert "hp_746" in elevator and "min_s" not in elevator
    assert not {"min_s", "hp_746"} & plausible_slips(load_problem(
        shipped_dir("problems") / "car_climbs_grade_power.yaml"))


def test_a_body_makes_a_factor_of_g_plausible_without_a_g_in_the_model():
    from mechgrade.solve.mutants import plausible_slips
    # a boat slowed by drag alone: its weight m g is still what a student may divide by
    assert "g" in plausible_slips(load_problem(shipped_dir("problems")
                                               / "boat_coasting_quadratic_drag.yaml"))
    # kinematics alone (a radar tracking an airplane): no weight, no g
    assert "g" not in plausible_slips(load_problem(shipped_dir("problems")
                                                   / "radar_tracks_airplane_polar.yaml"))


def test_a_generated_mistake_is_kept_alike_at_one_instant_and_in_a_class():
    # one rule (kept_mistakes) read through one stacking of the mistakes: the answer's own
    # value, a repeat of its family and a value of another shape are dropped, at one instant
    # (kept_at) as at each instant of a class
    mistakes = [GeneratedMistake("sign", "s", 2.0), GeneratedMistake("sign", "s", 2.0),
                GeneratedMistake("half_factor", "h", 1.0), GeneratedMistake("vector", "v",
                                                                           (1.0, 2.0, 3.0)),
                GeneratedMistake("half_factor", "h", 4.0)]
    alone = kept_at(1.0, mistakes)
    keep = kept_columns(np.array([[1.0], [1.0], [1.0]]), [], [mistakes, mistakes[:1], []])
    assert [m.value for m in alone] == [2.0, 4.0]
    assert [[m.value for m in keep(i)] for i in range(3)] == [[2.0, 4.0], [2.0], []]


def test_a_vector_mistake_is_stacked_as_its_components_read_as_an_array():
    # a vector's components taken as they are (no array made per mistake) and the general
    # rule (one array per value) stack every value alike: components of another count, a
    # whole number among them, a scalar where a vector is wanted
    from mechgrade.solve.mutants import _stacked

    values = [(1.0, -2.5, 0.0), (1.0, 2.0), (1, 2.0, 3.0), 4.0, (-0.0, 5e-324, 1e300)]
    V, exists, _ = _stacked([[GeneratedMistake("v", "s", v) for v in values]], 3)
    assert exists.tolist() == [[True, False, True, False, True]]
    for j, v in enumerate(values):
        if exists[0, j]:
            expected = np.atleast_1d(np.asarray(v, float))
            assert V[0, j].tobytes() == expected.tobytes()  # the same bits, a zero's sign too
    assert np.isnan(V[0, [1, 3]]).all()


@pytest.mark.slow  # derives the problem and its mistaken copy (3 s)
def test_a_cords_strands_counted_once_is_named_in_a_problem_without_bodies():
    # sqrt(x^2 + h^2) + (h - y) = L: the crate moves at the hitch's rate along the cord, 1.6 m/s
    result = solve(load_problem(shipped_dir("problems") / "truck_hoists_crate_pulley.yaml"))
    for objective, mistaken, right, other in (("velocity", "1.6 m/s", "0.8 m/s", "1 m/s"),
                                              ("acceleration", "0.288 m/s^2", "0.144 m/s^2",
                                               "0.2 m/s^2")):
        (once,) = [m for m in result.result(objective).generated_mistakes
                   if m.code == "strands_miscounted"]
        assert once.value == pytest.approx(2 * result.result(objective).value, rel=1e-9)
        assert assess(mistaken, result.result(objective)).diagnosis \
            == "a cord's strands miscounted"
        assert assess(right, result.result(objective)).verdict == "correct"
        assert assess(other, result.result(objective)).diagnosis != "a cord's strands miscounted"
    # y = h - (L - s) = 0 is where the one-strand cord puts the crate: a configuration of the
    # mistaken cord, kept although zero
    assert assess("0 m", result.result("height")).diagnosis == "a cord's strands miscounted"


@pytest.mark.slow  # derives the problem and its two mistaken copies (4 s)
def test_a_rack_taken_at_rest_moves_the_instant_centre_to_its_mesh_point():
    result = solve(load_problem(shipped_dir("problems") / "gear_between_two_racks.yaml"))
    ic = result.result("instant_centre")
    assert sorted(m.value[1] for m in ic.generated_mistakes
                  if m.code == "surface_taken_fixed") == [pytest.approx(-150), pytest.approx(150)]
    assert assess("(0, -150, 0) mm", ic).diagnosis == "the body slid on taken as fixed"
    assert assess("(0, -50, 0) mm", ic).verdict == "correct"
    assert assess("(0, 50, 0) mm", ic).diagnosis == "sign error"  # above the centre: not a rack


BRANCHES = Path(__file__).parents[1] / "data" / "branches"


@pytest.mark.slow  # derives the four-bar and its copy without guesses (3 s)
def test_the_other_assembly_branch_of_a_four_bar_is_named():
    # the guesses pick the open assembly (psi' = 2.1744 rad/s); the crossed one, solved by
    # hand from the loop closure, turns the rocker at -3.6029 rad/s
    result = solve(load_problem(BRANCHES / "fourbar_with_guesses.yaml")).result("omega_rocker")
    (other,) = [m for m in result.generated_mistakes if m.code == "other_assembly_branch"]
    assert result.value == pytest.approx(2.174365, rel=1e-6)
    assert other.value == pytest.approx(-3.602937, rel=1e-6)
    assert assess("-3.603 rad/s", result).diagnosis \
        == "the other assembly branch (the mechanism's mirror configuration)"
    assert assess("2.174 rad/s", result).verdict == "correct"


@pytest.mark.slow  # derives the problem and its copy without guesses (3 s)
def test_a_coordinate_read_another_way_is_no_other_assembly_branch():
    # the slotted arm at theta + half a turn with s reversed puts every point at the same
    # place: the same configuration, no other branch (its rates only change sign)
    result = solve(load_problem(shipped_dir("problems") / "slotted_arm_crank_coriolis.yaml"))
    assert not [m for r in result.results for m in r.generated_mistakes
                if m.code == "other_assembly_branch"]


def test_a_given_nonzero_angular_acceleration_taken_as_zero_is_a_mistake():
    # theta'' = 5 rad/s^2 dropped: only the centripetal part -L theta'^2 = -98 is left
    (slip,) = _generated(load_problem(PENDULUM), "acc_A", "given_acceleration_zero")
    assert slip.value == pytest.approx((-98.0, 0.0, 0.0))
    assert "angular acceleration" in slip.message and "5 rad/s^2" in slip.message


def test_a_given_first_rate_or_zero_second_rate_is_not_taken_as_zero():
    problem = load_problem(PENDULUM)
    givens = tuple(replace(g, value=0.0, si=0.0, text="0 rad/s^2") if g.key.text == "theta''" else g
                   for g in problem.givens)
    # theta' = 7 rad/s is a first rate: never dropped by this family; theta'' = 0 already is
    assert _generated(replace(problem, givens=givens), "acc_A", "given_acceleration_zero") == []


def test_a_mistake_within_the_references_accuracy_of_the_answer_is_the_answer():
    # a first stop found again in a motion started a millionth as fast (three_cart's initial
    # speed omitted): 1.06e-7 off the answer, integration noise, not a mistake; 2e-6 off is one
    mistakes = [GeneratedMistake("initial_speed_omitted", "s", 119.92976781240235),
                GeneratedMistake("damping_omitted", "d", 119.93027015905558)]
    assert [m.code for m in kept_at(119.92975512634762, mistakes)] == ["damping_omitted"]


def test_a_mistake_that_is_round_off_beside_the_answer_is_a_zero():
    # satellite: the radial speed at apogee, zero by the event, left by ω × r dropped
    # (2.7e-12 km/s beside 6.5 km/s); a unit slip at a millionth of the answer is kept
    mistakes = [GeneratedMistake("drop_omega_r", "s", 2.6722517532107305e-12),
                GeneratedMistake("component_for_speed", "c", (-2.673e-12, 0.0, 0.0)),
                GeneratedMistake("given_unit", "u", 6.5e-6)]
    assert [m.code for m in kept_at(6.488223320730449, mistakes[:1] + mistakes[2:])] \
        == ["given_unit"]
    assert kept_at((6.488223320730449, 0.0, 0.0), mistakes[1:2]) == ()


def test_a_mistake_that_divides_by_a_round_off_zero_names_nothing():
    # ruina_9_22 with rolling assumed: both slip times are 0, their ratio noise over noise;
    # an answer shown as 0 has no scale to judge by, and a mistake beside it is kept
    mistakes = [GeneratedMistake("rolling_assumed", "r", -264773250397302.94),
                GeneratedMistake("given_length_unit", "l", 1e6)]
    assert [m.code for m in kept_at(1.000000000000371, mistakes)] == ["given_length_unit"]
    assert [m.code for m in kept_at(-1.3e-15, mistakes[:1])] == ["rolling_assumed"]


@pytest.mark.slow  # solves ruina_9_22's mistaken models alone and in a class (10 s)
def test_single_solve_and_class_keep_no_mistake_made_of_noise():
    # the same rule for one solve and each column of a class (kept_columns)
    from mechgrade.solve.batch import solve_variants

    problem = load_problem(shipped_dir("problems") / "ruina_9_22_marble_bowling_ball.yaml")
    alone = solve(problem).result("ratio_t_star_bowling_over_marble")
    (column,) = solve_variants(problem, [{}])
    together = column.result("ratio_t_star_bowling_over_marble")
    for result in (alone, together):
        codes = [m.code for m in result.generated_mistakes]
        assert "rolling_assumed" not in codes
        assert all(abs(m.value) < 1e6 for m in result.generated_mistakes)
    assert [m.code for m in alone.generated_mistakes] \
        == [m.code for m in together.generated_mistakes]


def test_an_integration_whose_event_never_happens_names_no_time():
    # the boat's drag left out: it never slows to v1, so that model gives no time (its
    # solve fails), alone and in a class; the drag taken constant does reach it
    from mechgrade.solve.batch import solve_variants

    problem = load_problem(shipped_dir("problems") / "boat_coasting_quadratic_drag.yaml")
    for solution in (solve(problem), solve_variants(problem, [{}])[0]):
        codes = [m.code for m in solution.result("time").generated_mistakes]
        assert "force_taken_constant" in codes
        assert not {"force_omitted", "initial_speed_omitted"} & set(codes)
