"""Mistakes applied to the model: each composition term dropped, other points and bases."""

from __future__ import annotations

from dataclasses import replace

import pytest
import sympy as sp

from mechgrade.grade.compare import assess
from mechgrade.expressions.syntax import parse, to_text
from mechgrade.mechanics.build import build
from mechgrade.mechanics.mutations import (_driver_speed, _gyration_for_radius,
                                           _rate_relation_inverted, _Reading,
                                           _start_term_left_out, _whole_speed_for_rate,
                                           _distance_rate_as_speed, described_from,
                                           mutations)
from mechgrade.spec.mistake_codes import MODEL_CODES as CODES
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.spec import load_problem


def _problem(name):
    return load_problem(shipped_dir("problems") / f"{name}.yaml")


def _codes(name, objective):
    return [m.code for m in mutations(_problem(name)) if m.objective == objective]


def test_a_point_moving_in_a_rotating_frame_has_every_acceleration_term_dropped():
    codes = _codes("ruina_10_4_10_7_rotating_tube_accel", "a_P_N")
    assert {"drop_tangential", "drop_centripetal", "drop_coriolis", "coriolis_half",
            "drop_relative_acc"} <= set(codes)


def test_a_point_fixed_in_its_body_has_no_coriolis_or_relative_terms():
    codes = _codes("bowling_3_15_4_pendulum", "acc_N")
    assert "drop_tangential" in codes and "drop_coriolis" not in codes \
        and "drop_relative_acc" not in codes


@pytest.mark.slow
def test_a_frame_turning_in_a_turning_frame_gives_the_relative_angular_velocity_mistake():
    assert "relative_omega" in _codes("ruina_10_11_wheel_on_rotating_rod", "v_P_N")


def test_dropped_terms_are_named_with_their_value_in_the_objectives_unit():
    result = solve(_problem("ruina_10_4_10_7_rotating_tube_accel")).result("a_P_N")
    coriolis = [m for m in result.generated_mistakes if m.code == "drop_coriolis"]
    assert coriolis[0].value == pytest.approx((-106.0, -40.0, 0.0))
    assert "Coriolis term 2 ω × v_rel" in coriolis[0].message \
        and "= (40, 0) ft/s^2" in coriolis[0].message


def test_a_point_on_a_circle_about_another_point_has_its_turning_terms_dropped():
    # B on the ramp: R F.x from the centre Q, F with no origin of its own
    problem = _problem("two_cars_relative_motion")
    model = build(problem)
    assert described_from(model, "B", "N") == [("F", "Q")]
    result = solve(problem).result("relative_acceleration")
    dropped = {m.code: m.value for m in result.generated_mistakes
               if m.code in ("drop_centripetal", "drop_tangential")}
    assert dropped["drop_centripetal"] == pytest.approx((1.732, -2.5, 0.0), abs=1e-3)
    assert dropped["drop_tangential"] == pytest.approx((-1.125, -3.449, 0.0), abs=1e-3)


def test_no_turning_frame_about_a_point_for_one_on_a_fixed_line_or_in_a_frame_with_an_origin():
    model = build(_problem("two_cars_relative_motion"))
    assert described_from(model, "A", "N") == []  # y N.y: along the fixed frame
    assert described_from(model, "B", "F") == []  # at rest in its own frame
    # the tube's frame has its own origin: moving_frames composes it already
    tube = build(_problem("ruina_10_4_10_7_rotating_tube_accel"))
    assert all(described_from(tube, p.name, "N") == [] for p in tube.problem.points)


def test_components_along_the_polar_frame_are_the_other_basis_mistake():
    result = solve(_problem("ruina_10_3_spiral_bug")).result("a_N")
    basis = [m for m in result.generated_mistakes if m.code == "other_basis"]
    assert basis[0].value == pytest.approx((-13.6342, 2.48143, 0.0), rel=1e-4)


@pytest.mark.slow
def test_a_position_term_left_out_is_half_the_side_for_half_the_diagonal():
    result = solve(_problem("bowling_P3_17_rocking_block")).result("vG_mag")
    by_value: dict[float, list[str]] = {}
    for m in result.generated_mistakes:
        by_value.setdefault(round(m.value, 6), []).append(m.code)
    # |β'| b/2 is also the A.x component of v_G: both families are kept, and both named
    assert by_value[4.2] == ["position_term"]
    assert by_value[2.45] == ["component_for_speed", "position_term"]
    assert _codes("bowling_P3_17_rocking_block", "vG_mag").count("position_term") == 2
    judged = assess("2.45 in/s", result)
    assert judged.diagnosis == ("a velocity component for the speed or a term of the position "
                                "left out")
    # one sentence a reading, each said once
    assert " Or: " in judged.feedback or " It is also what " in judged.feedback


def test_no_generated_mistake_equals_the_answer():
    result = solve(_problem("ruina_10_4_10_7_rotating_tube_accel")).result("a_Pprime_N")
    # at q = 0 frame B's components equal N's: that reading is no mistake at this instant
    assert all(m.code != "other_basis" for m in result.generated_mistakes)
    assert len(set(CODES)) == len(CODES)


def test_mistaken_givens_are_solved_again():
    result = solve(_problem("bowling_3_15_6_gears")).result("alpha_A_z")
    swap = [m for m in result.generated_mistakes if m.code == "given_swap"]
    assert swap[0].value == pytest.approx(10.8)


def test_the_magnitude_of_a_difference_taken_from_the_magnitudes():
    # cars at 25 m/s and 15 m/s, 60 deg apart: 25 + 15 and 25 - 15 for |v_B - v_A|
    result = solve(_problem("two_cars_relative_motion")).result("relative_speed")
    values = sorted(m.value for m in result.generated_mistakes if m.code == "mag_as_sum")
    assert values == pytest.approx([10.0, 40.0])


def test_an_acceleration_answered_zero_because_a_given_rate_is_constant():
    # x' = 200 m/s with x'' = 0: r'' and theta'' are not zero
    codes = {o: _codes("radar_tracks_airplane_polar", o) for o in ("r_ddot", "theta_ddot",
                                                                   "r_dot", "distance")}
    assert "zero_for_constant_rate" in codes["r_ddot"] and "zero_for_constant_rate" in \
        codes["theta_ddot"]
    assert "zero_for_constant_rate" not in codes["r_dot"] + codes["distance"]
    # x'' = 1.5 m/s^2 given: no rate is constant
    problem = _problem("rolling_wheel_rim_points")
    assert not [m for m in mutations(problem) if m.code == "zero_for_constant_rate"]


def test_a_motion_relative_to_a_turning_arm_is_read_with_a_term_of_its_composition_left_out():
    # B's acceleration along the slotted arm solved from a_B = a_O + α × r + ω × (ω × r)
    # + 2 ω × v_rel + a_rel with the arm's centripetal term s θ'² left out: a_rel - s θ'²
    result = solve(_problem("slotted_arm_crank_coriolis")).result("relative_acceleration")
    dropped = [m for m in result.generated_mistakes if m.code == "drop_centripetal"
               and "relative to frame S solved from its composition in N" in m.message]
    assert [m.value for m in dropped] == [pytest.approx(-2.418973, rel=1e-6)]
    # the inertial frame has no composition of its own: none of these for acc(P, N)
    assert not any("solved from its composition" in m.sentence for m in mutations(
        _problem("ruina_10_4_10_7_rotating_tube_accel")) if m.objective == "a_P_N")


def test_a_speed_from_terms_or_components_added_as_numbers_and_a_carried_frame_left_out():
    result = solve(_problem("airplane_crosswind_heading")).result("ground_speed")
    by_code: dict[str, list[float]] = {}
    for m in result.generated_mistakes:
        by_code.setdefault(m.code, []).append(round(float(m.value), 6))
    # the airspeed (240 km/h) and the wind's speed (60 km/h) added as numbers
    assert 300.0 in by_code["mag_as_sum"]
    # the air is carried by the wind without turning: the wind's velocity left out
    assert 240.0 in by_code["drop_transport_vel"]
    # on the arm turning about O: |r'| + |r θ'|, the polar components' sizes added
    polar = solve(_problem("collar_on_circle_rotating_rod")).result("speed")
    assert any(m.code == "mag_as_sum" and m.value == pytest.approx(2.4588, rel=1e-4)
               for m in polar.generated_mistakes)


def test_a_bodys_material_point_is_read_with_a_term_of_its_rigid_body_formula_left_out():
    # the rolling wheel's rim point at the contact: a = a_G + α × r + ω × (ω × r) = (0, 22.5);
    # the centre's own acceleration (1.5, 0) is another point's, α × r left out (1.5, 22.5)
    result = solve(_problem("rolling_wheel_rim_points")).result("acceleration_contact")
    by_code = {m.code: m.value for m in result.generated_mistakes}
    assert by_code["other_point"] == pytest.approx((1.5, 0.0, 0.0), abs=1e-9)
    assert by_code["drop_tangential"] == pytest.approx((1.5, 22.5, 0.0), abs=1e-9)
    assert "material point of W at C" in next(
        m.message for m in result.generated_mistakes if m.code == "drop_tangential")


@pytest.mark.slow
def test_a_radius_of_curvature_of_a_path_y_of_x_taken_without_its_slope_term():
    # y = x^2/b, b = 200 m, at x = 40 m: 1/y'' = 100 m and sqrt(1 + y'^2)/y'' = 107.7 m for
    # the 124.9 m of (1 + y'^2)^(3/2)/y''; the normal acceleration v^2/rho with them
    solution = solve(_problem("car_on_parabolic_road"))
    for objective, expected in (("radius_of_curvature", (100.0, 107.7033)),
                                ("normal_acceleration", (2.25, 2.089073))):
        found = [m for m in solution.result(objective).generated_mistakes
                 if m.code == "rho_without_slope"]
        assert [m.value for m in found] == pytest.approx(expected, rel=1e-6)
    assert "as 1/|y''|, without the slope term" in found[0].message
    # |a| is not read from the path's formula
    assert not _codes("car_on_parabolic_road", "acceleration_magnitude").count(
        "rho_without_slope")


@pytest.mark.slow
def test_a_path_not_given_as_y_of_x_has_no_slope_term_mistake():
    # a polar path (r and theta): no constraint gives one coordinate as a function of another
    assert not [m for m in mutations(_problem("ruina_10_3_spiral_bug"))
                if m.code == "rho_without_slope"]


@pytest.mark.slow
def test_an_angle_rate_fixed_by_the_constraints_read_as_the_drivers_given_rate():
    # the slotted arm's theta' answered with the crank's phi' = 4 rad/s
    problem = _problem("slotted_arm_crank_coriolis")
    found = [m for m in mutations(problem, "arm_angular_velocity") if m.code == "driver_rate"]
    assert [float(m.value) for m in found] == [4.0]
    assert found[0].sentence.startswith("Your value is phi' = 4 rad/s, the given rate of phi")
    # phi'' = 0 is given: no driver's rate to take for theta''; s' is no angle's rate
    assert not [m for o in ("arm_angular_acceleration", "sliding_rate")
                for m in mutations(problem, o) if m.code == "driver_rate"]



def _family(family, problem, objective):
    """One family's readings of one objective (that family alone: fast)."""
    model, obj = build(problem), problem.objective(objective)
    reading = _Reading(model, obj, model.language.value(obj.find.node))
    family(reading)
    return reading.out


def _gyration(problem, objective):
    return _family(_gyration_for_radius, problem, objective)


def test_a_drums_rate_read_with_its_radius_of_gyration_for_its_radius():
    # y = r phi links the block to the drum; k is only in the drum's inertia: w = v/k
    found = _gyration(_problem("drum_block_energy_us"), "drum_angular_velocity")
    assert [(m.code, str(m.value)) for m in found] == [("gyration_for_radius", "r*Abs(phid)/k")]
    assert "radius of gyration k of drum for the length r" in found[0].sentence


def test_no_radius_of_gyration_mistake_for_a_speed_or_a_rate_no_length_links():
    problem = _problem("drum_block_energy_us")
    assert _gyration(problem, "block_speed") == []
    # the cord's y = r phi taken away: no length links the drum's rate to the block
    assert _gyration(replace(problem, constraints=()), "drum_angular_velocity") == []


def test_a_sliders_speed_read_as_the_drivers_given_speed_in_its_own_sense():
    # a' = -2 m/s given at A; B's s' along its slot answered 2 m/s: the rod moved as a whole
    found = _family(_driver_speed, _problem("rod_in_two_slots_ic"), "velocity_B")
    assert [(m.code, str(m.value)) for m in found] == [("driver_speed", "2.0*sign(sd)")]
    assert found[0].sentence.startswith("Your value is s' = 2 m/s in size, the given rate of a")


def test_no_drivers_speed_for_an_angles_rate_the_drivers_own_or_its_own_point_located_again():
    problem = _problem("rod_in_two_slots_ic")
    assert _family(_driver_speed, problem, "angular_velocity") == []
    # asked for a' itself: the only given length rate is its own
    own = replace(problem.objective("velocity_B"), id="velocity_A",
                  find=replace(problem.objective("velocity_B").find, text="a'",
                               node=parse("a'")))
    assert _family(_driver_speed, replace(problem, objectives=(own,)), "velocity_A") == []
    # the airplane located two ways, x N.x + h N.y = r E.x: r' = x' is the whole speed for a
    # component (velocity_component_wrong), not a mechanism moving with its driver
    assert _family(_driver_speed, _problem("radar_tracks_airplane_polar"), "r_dot") == []


def test_a_polar_rate_read_with_the_points_whole_speed_along_its_direction():
    # x N.x + h N.y = r E.x with x' given: r' = v and theta' = v/r, in the answer's sense
    radar = _problem("radar_tracks_airplane_polar")
    (r_dot,) = _family(_whole_speed_for_rate, radar, "r_dot")
    (theta_dot,) = _family(_whole_speed_for_rate, radar, "theta_dot")
    assert (r_dot.code, str(r_dot.value)) == ("speed_for_component", "Abs(xd)*sign(rd)")
    assert theta_dot.code == "speed_for_component"
    assert theta_dot.sentence.startswith("Your value is θ̇ with the whole speed of the point "
                                         "that line_of_sight places")
    # solved: 200 m/s / 6000 m, the angle falling; and the pin of a crank in a turning slot,
    # s' = r phi' and theta' = r phi'/s
    for problem, objective, value in (("radar_tracks_airplane_polar", "theta_dot", -0.03333),
                                      ("slotted_arm_crank_coriolis", "sliding_rate", 0.8),
                                      ("slotted_arm_crank_coriolis", "arm_angular_velocity",
                                       1.512)):
        found = [m for m in solve(_problem(problem)).result(objective).generated_mistakes
                 if m.code == "speed_for_component"]
        assert [m.value for m in found] == [pytest.approx(value, rel=2e-4)]


def test_no_whole_speed_reading_where_the_other_side_moves_by_an_unknown_or_for_a_length():
    # B's slot: the rod's side moves with theta, whose rate is unknown (B's velocity is not
    # known before s' is)
    assert _family(_whole_speed_for_rate, _problem("rod_in_two_slots_ic"), "velocity_B") == []
    radar = _problem("radar_tracks_airplane_polar")
    assert _family(_whole_speed_for_rate, radar, "distance") == []
    # the airplane's rate x' no longer given: its velocity is not known
    unknown = replace(radar, givens=tuple(g for g in radar.givens if to_text(g.key.node) != "x'"))
    assert _family(_whole_speed_for_rate, unknown, "r_dot") == []


def test_a_ropes_slant_rate_read_as_the_whole_speed_of_its_moving_end():
    # sqrt(x^2 + h^2) + 2 (h - y) = L: the slant's rate taken as x' gives y' = x'/2 = 1 m/s
    truck = _problem("truck_hoists_crate_pulley")
    (found,) = _family(_distance_rate_as_speed, truck, "velocity")
    assert found.code == "speed_for_component"
    assert found.sentence.startswith("Your value is ẏ with the rate of the distance sqrt(x²+h²)")
    values = {"x": 4.0, "h": 3.0, "xd": 2.0, "yd": 0.8}
    assert float(found.value.subs({s: values[s.name] for s in found.value.free_symbols})) \
        == pytest.approx(1.0)


def test_no_slant_reading_for_a_position_a_second_rate_or_an_end_of_unknown_speed():
    truck = _problem("truck_hoists_crate_pulley")
    assert _family(_distance_rate_as_speed, truck, "height") == []
    assert _family(_distance_rate_as_speed, truck, "acceleration") == []
    unknown = replace(truck, givens=tuple(g for g in truck.givens
                                          if to_text(g.key.node) not in ("x'", "x''")))
    assert _family(_distance_rate_as_speed, unknown, "velocity") == []


def test_an_angular_acceleration_from_a_cords_read_as_a_r_for_a_over_r():
    found = _family(_rate_relation_inverted, _problem("drum_hoist_falling_block"),
                    "angular_acceleration")
    assert [(m.code, str(m.value)) for m in found] == [("rate_relation_inverted",
                                                        "1.0*phidd*r**2")]
    assert found[0].sentence.startswith("Your value multiplies by r = 0.25 m where")


def test_a_relation_inverted_multiplies_the_length_in_its_given_unit_and_only_for_an_angle():
    problem = _problem("drum_block_energy_us")  # r = 1 ft: the student's v r is v in ft/s
    (inverted,) = _family(_rate_relation_inverted, problem, "drum_angular_velocity")
    values = {s.name: s for s in inverted.value.free_symbols}
    assert float(inverted.value.subs({values["r"]: 0.3048, values["phid"]: 1.0})) \
        == pytest.approx(1.0)
    assert _family(_rate_relation_inverted, problem, "block_speed") == []


def test_a_distance_answered_without_a_term_of_its_start():
    # r starts at R + h: the apogee's altitude r - R (or r - h) for its distance from O
    found = _family(_start_term_left_out, _problem("satellite_apogee_speed"), "apogee_distance")
    assert [(m.code, str(m.value)) for m in found] == [("position_term", "-R + r"),
                                                       ("position_term", "-h + r")]
    assert found[0].sentence.startswith("Your value is r without R, a term of its start r = R + h")


def _asking(problem, find):
    """``problem`` with its first objective asking for ``find`` instead."""
    first = problem.objectives[0]
    asked = replace(first, find=replace(first.find, text=find, node=parse(find)))
    return replace(problem, objectives=(asked,) + problem.objectives[1:])


def test_no_start_term_to_leave_out_of_a_speed_an_angle_or_a_start_of_one_term():
    satellite = _problem("satellite_apogee_speed")
    assert _family(_start_term_left_out, satellite, "apogee_speed") == []
    assert _family(_start_term_left_out, _asking(satellite, "theta"), "apogee_distance") == []
    puck = _problem("puck_string_through_hole")  # r starts at r0 alone
    assert _family(_start_term_left_out, _asking(puck, "r"), "angular_velocity") == []


@pytest.mark.slow
@pytest.mark.parametrize("problem, objective, answer, label", [
    ("drum_block_energy_us", "drum_angular_velocity", "15.24 rad/s",
     "a radius of gyration read for a radius"),
    ("drum_hoist_falling_block", "angular_acceleration", "-1.251 rad/s^2",
     "v = r ω used as ω = v r"),
    ("rod_in_two_slots_ic", "velocity_B", "2 m/s", "the driver's speed for a connected point's"),
    ("satellite_apogee_speed", "apogee_distance", "2103 km", "a term of the position left out"),
    ("puck_string_through_hole", "angular_momentum", "1.6 kg*m^2/s",
     "the momentum m v for its moment r × m v"),
])
def test_a_students_kinematic_factor_slip_is_named_when_graded(problem, objective, answer,
                                                               label):
    judged = assess(answer, solve(_problem(problem)).result(objective))
    assert (judged.verdict, judged.diagnosis) == ("incorrect", label)


def test_a_second_derivative_from_a_force_balance_is_read_without_the_centripetal_term():
    # the smooth rod pushes nothing along itself: r'' - r θ'² = 0, so r'' = 0 without ω × (ω × r)
    problem = _problem("collar_slides_on_spinning_rod")
    found = [m for m in mutations(problem, "sliding_acceleration") if "force balance" in m.sentence]
    assert [m.code for m in found] == ["drop_centripetal"]  # the Coriolis term is across the rod
    values = {"rdd": 7.5, "r": 0.3, "thetad": 5.0}
    value = found[0].value.subs({s: values[s.name] for s in found[0].value.free_symbols})
    assert float(value) == pytest.approx(0.0)
    # the rate typeset as the other messages print it, not in the answer syntax (r'')
    assert found[0].sentence.startswith("Your value is r̈ from the force balance of collar")
    # a coordinate no force balance gives (a problem without bodies) has no such reading
    assert not any("force balance" in m.sentence
                   for m in mutations(_problem("radar_tracks_airplane_polar"), "r_ddot"))


def test_a_second_derivative_solved_from_a_constraint_without_a_coriolis_term_or_its_2():
    # h N.y + r C.x = s S.x twice differentiated: along S.y, s θ'' + 2 s' θ' is fixed by the crank
    found = {m.code: m.value for m in mutations(_problem("slotted_arm_crank_coriolis"),
                                                "arm_angular_acceleration")
             if "solved from the constraint" in m.sentence and "frame S" in m.sentence}
    symbols = {s.name: s for s in found["drop_coriolis"].free_symbols}
    thetadd, sd, thetad, s = (symbols[n] for n in ("thetadd", "sd", "thetad", "s"))
    assert sp.simplify(found["drop_coriolis"] - (thetadd + 2 * sd * thetad / s)) == 0
    assert sp.simplify(found["coriolis_half"] - (thetadd + sd * thetad / s)) == 0
    assert all(m.sentence.startswith("Your value is θ̈ solved from the constraint pin_in_slot")
               for m in mutations(_problem("slotted_arm_crank_coriolis"),
                                  "arm_angular_acceleration")
               if "solved from the constraint" in m.sentence)
    # a rate (not a second derivative) has no such reading
    assert not any("solved from the constraint" in m.sentence for m in mutations(
        _problem("slotted_arm_crank_coriolis"), "arm_angular_velocity"))
