"""Mistakes of kinetics applied to the model: only where the model has the ingredient, each
named with its term's value and the step of the worked solution where it happens."""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import pytest

from mechgrade.check import separation_findings
from mechgrade.grade.compare import assess
from mechgrade.grade.diagnose import GENERATED_CODES, LABELS
from mechgrade.mechanics.dynamics import kinetics_derivation
from mechgrade.mechanics.build import build
from mechgrade.mechanics.dynamics_mutations import FAMILIES, dynamics_mutations, moment_arm_omitted
from mechgrade.spec.mistake_codes import DYNAMICS_CODES as CODES, MODEL_CODES
from mechgrade.resources import shipped_dir
from mechgrade.solve import solve
from mechgrade.spec import load_problem
from mechgrade.spec.load import load_problem_text
from mechgrade.spec.language import FUNCTIONS
from mechgrade.spec.model import Tolerance
from mechgrade.expressions.syntax import parse
from library import library_problem as _problem

DYNAMICS = sorted(p.stem for p in shipped_dir("problems").glob("*.yaml")
                  if _problem(p.stem).dynamics is not None)


@lru_cache(maxsize=None)
def _solution(name):
    return solve(_problem(name))


def _codes(name):
    return {m.code for m in dynamics_mutations(_problem(name))}


def _generated(name, objective, code):
    return [m for m in _solution(name).result(objective).generated_mistakes if m.code == code]


def test_every_family_is_registered_once_and_every_code_has_a_label():
    assert len(set(FAMILIES)) == len(FAMILIES) and len(set(CODES)) == len(CODES)
    assert set(CODES) <= set(GENERATED_CODES) and set(CODES) <= set(LABELS)
    found = {m.code for name in DYNAMICS for m in dynamics_mutations(_problem(name))}
    # a kinematic term left out of a balance (the Coriolis term) keeps its kinematic code, a
    # rate before an impact misread a given's
    assert set(CODES) <= found <= set(CODES) | set(MODEL_CODES) | {"given_sign"}


def test_a_family_is_generated_only_where_the_model_has_its_ingredient():
    # no gravity load: no weight mistakes; no friction: no friction mistakes
    assert not _codes("rod_strikes_ledge") & {"weight_omitted", "mass_for_weight",
                                              "friction_reversed"}
    assert _codes("rod_strikes_ledge") == {"restitution_ignored", "restitution_component",
                                           "given_sign"}
    # a pin: the parallel-axis term; no pin, no rolling contact (a sliding ladder): none
    assert "central_inertia_at_pivot" in _codes("pendulum_pin_reaction")
    assert "central_inertia_at_pivot" not in _codes("ruina_9_19_falling_ladder")
    # a string over a pulley between two bodies: the tension taken as a weight
    assert "tension_as_weight" in _codes("atwood_machine")
    assert "tension_as_weight" not in _codes("yo_yo_unwinding")
    # a body that does not turn, braking on two contacts: the weight transfer
    assert "weight_transfer_ignored" in _codes("car_braking_weight_transfer")
    assert "normal_from_weight" in _codes("block_sliding_down_incline")
    assert "normal_from_weight" not in _codes("car_braking_weight_transfer")
    assert not dynamics_mutations(_problem("bowling_3_15_4_pendulum"))
    # friction between two bodies: the one slid on taken as fixed; on the ground: no such
    assert "surface_taken_fixed" in _codes("block_slides_on_cart")
    assert "surface_taken_fixed" not in _codes("block_sliding_down_incline")
    # an energy adding two bodies' kinetic energies: each left out; one body's: none
    assert "body_ke_omitted" in _codes("block_slides_on_cart")
    assert "body_ke_omitted" not in _codes("flywheel_speed_drop")
    # a known blow away from the centre of a body that turns; an impact with no known blow
    assert "impulse_moment_omitted" in _codes("rod_struck_on_ice")
    assert "impulse_moment_omitted" not in _codes("rod_strikes_ledge")


def test_the_mistaken_model_is_a_copy():
    problem = _problem("pendulum_pin_reaction")
    mutated = next(m.problem for m in dynamics_mutations(problem) if m.code == "weight_omitted")
    assert problem.dynamics.gravity is not None and mutated.dynamics.gravity is None
    assert mutated.frames == problem.frames and mutated.points == problem.points


@pytest.mark.parametrize("name", DYNAMICS)
def test_every_mistake_is_anchored_to_a_step_of_the_worked_solution(name):
    problem = _problem(name)
    sections = {section for section, _ in kinetics_derivation(problem)}
    assert all(m.step in sections for m in dynamics_mutations(problem))


def test_the_parallel_axis_mistake_is_named_with_its_term():
    (mistake,) = _generated("pendulum_pin_reaction", "alpha", "central_inertia_at_pivot")
    # I_G alpha = -m g L/2 sin(theta): alpha = -6 g sin(40 deg)/L
    assert mistake.value == pytest.approx(-31.52873, rel=1e-5)
    assert "about its mass centre G" in mistake.message \
        and "m d² = 0.72 kg*m^2" in mistake.message
    assert mistake.step == "Bodies"
    (slip,) = _generated("pendulum_pin_reaction", "alpha", "given_deg_as_rad")
    assert slip.step == "Coordinates"


def test_friction_turned_round_and_the_normal_force_taken_as_the_weight():
    (reversed_,) = _generated("block_sliding_down_incline", "accel", "friction_reversed")
    (weight,) = _generated("block_sliding_down_incline", "accel", "normal_from_weight")
    assert reversed_.value == pytest.approx(9.81 * (0.5 + 0.25 * 3 ** 0.5 / 2))
    assert weight.value == pytest.approx(9.81 * (0.5 - 0.25))
    assert "μ N = 8.496 N" in reversed_.message and "N_P = 33.98 N" in weight.message


def test_the_weight_left_out_of_the_force_balance_of_a_pin():
    mistakes = _generated("pendulum_pin_reaction", "pin_force", "weight_omitted")
    # R_O = m a_G - m g: without the weight, m a_G, with the right angular acceleration
    assert any(m.value == pytest.approx((-14.18783, 2.19340, 0.0), rel=1e-5)
               and "out of the force balance that gives R_O" in m.message for m in mistakes)


@pytest.mark.slow
def test_a_reaction_read_as_the_weight_is_read_in_the_right_model():
    (floor,) = _generated("ladder_wall_lift_off", "floor_reaction", "reaction_as_weight")
    assert floor.value == pytest.approx(12 * 9.81)


def test_restitution_replaced_by_one_and_by_zero():
    values = sorted(m.value for m in _generated("rod_strikes_ledge", "omega_after",
                                                "restitution_ignored"))
    assert values == pytest.approx([-10.0, -5.0])


@pytest.mark.slow
def test_a_mistake_that_changes_nothing_here_is_no_mistake():
    # g = 1 m/s^2 in the problem: the mass is the weight, so the slip gives the answer
    assert "mass_for_weight" in _codes("ruina_9_20_ladder_energy")
    assert not _generated("ruina_9_20_ladder_energy", "vG_over_sqrt_gL", "mass_for_weight")


def test_a_student_making_the_mistake_is_told_so():
    judged = assess("6.54 m/s^2", _solution("atwood_machine").result("a1"))
    assert judged.verdict != "correct" and judged.diagnosis == LABELS["tension_as_weight"]
    assert "weight of block2 (m g = 49.05 N)" in judged.feedback


@pytest.mark.slow
def test_a_given_slip_that_is_also_a_factor_names_only_the_factor():
    # m1 = 2 m2: block 2's kinetic energy with the masses exchanged is m2 v2^2, twice it
    result = _solution("two_mass_spring_chain").result("ke2")
    assert any(m.code == "given_swap" and m.value == pytest.approx(0.04)
               for m in result.generated_mistakes)
    assert assess("0.04 J", result).diagnosis == "factor of 2"


def test_check_reports_a_dynamics_mistake_inside_the_tolerance():
    problem = _problem("atwood_machine")
    wide = replace(problem, objectives=tuple(
        replace(o, tolerance=Tolerance(rel=0.3)) if o.id == "tension" else o
        for o in problem.objectives))
    findings = [w.message for w in separation_findings(wide, solve(wide))]
    # m1 g is 20 % below the tension: half of that separates them
    assert any("'tension'" in f and "tension_as_weight gives 29.43" in f
               and "{rel: 0.1}" in f for f in findings), findings


def test_generated_mistakes_are_worked_out_only_when_looked_at():
    from mechgrade.solve import dynamics_mutants

    problem = _problem("pendulum_pin_reaction")
    givens = {"theta'": 2.5}
    before = dynamics_mutants._generated.cache_info().misses
    solution = solve(problem, givens=givens)
    assert dynamics_mutants._generated.cache_info().misses == before
    mistakes = solution.result("alpha").generated_mistakes
    assert any(m.code == "central_inertia_at_pivot" for m in mistakes)
    assert dynamics_mutants._generated.cache_info().misses == before + 1
    # the same problem and givens again: kept
    assert tuple(solve(problem, givens=givens).result("alpha").generated_mistakes) \
        == tuple(mistakes)
    assert dynamics_mutants._generated.cache_info().misses == before + 1


def test_a_solution_with_its_mistakes_still_to_work_out_pickles():
    import pickle

    solution = solve(_problem("rod_strikes_ledge"))
    copy = pickle.loads(pickle.dumps(solution))
    assert copy == solution
    # e = 1, e = 0, and e on the tangential component instead (the normal one reversed
    # unscaled: e = 1's value again, the rod having no tangential velocity), and the rod's
    # rate before the impact reversed
    assert [m.code for m in copy.result("vG_after").generated_mistakes] \
        == ["restitution_ignored", "restitution_ignored", "restitution_component",
            "given_sign"]


@pytest.mark.slow
def test_the_body_slid_on_taken_as_fixed_stops_the_slider_on_it():
    # the cart at rest: the block stops in v0/(μ g) = 5/(0.3 × 9.81) s, all of ½ m v0² lost
    assert [round(m.value, 4) for m in _generated("block_slides_on_cart", "t_slide",
                                                  "surface_taken_fixed")] == [1.6989]
    assert [round(m.value, 4) for m in _generated("block_slides_on_cart", "energy_lost",
                                                  "surface_taken_fixed")] == [25.0]
    # the friction on the block is μ N in both models (and has no direction where it
    # stops on the ground): no force is read from the mistaken model
    assert not _generated("block_slides_on_cart", "friction_on_block", "surface_taken_fixed")
    judged = assess("1.70 s", _solution("block_slides_on_cart").result("t_slide"))
    assert judged.diagnosis == LABELS["surface_taken_fixed"]
    assert "cart taken as fixed" in judged.feedback


@pytest.mark.slow
def test_one_body_kinetic_energy_left_out_of_the_system_energy():
    # ½ m v0² - ½ M v² (the block's ½ m v² left out) and ½ m v0² - ½ m v² (the cart's)
    assert sorted(round(m.value, 6) for m in _generated("block_slides_on_cart", "energy_lost",
                                                        "body_ke_omitted")) == [21.0, 24.0]
    judged = assess("24 J", _solution("block_slides_on_cart").result("energy_lost"))
    assert judged.diagnosis == LABELS["body_ke_omitted"]
    assert "kinetic energy of cart (= 4 J)" in judged.feedback


def test_a_blow_taken_at_the_mass_centre_sets_nothing_spinning():
    # the far end then moves with the centre, J/m = 2 m/s; no spin is no value to name
    assert [m.value for m in _generated("rod_struck_on_ice", "vB_after",
                                        "impulse_moment_omitted")] == [(0.0, 2.0, 0.0)]
    assert not _generated("rod_struck_on_ice", "omega_after", "impulse_moment_omitted")
    judged = assess("(0, 2) m/s", _solution("rod_struck_on_ice").result("vB_after"))
    # ω × r left out of v_B = v_G + ω × r gives the same value: both are named
    assert judged.diagnosis == f"{LABELS['impulse_moment_omitted']} or {LABELS['drop_omega_r']}"
    assert "0.6 m from G" in judged.feedback


def test_the_only_reaction_on_a_body_read_as_its_static_value():
    # R_O - m a_G: the pin holds the rod's weight m g = 19.62 N as if it did not swing; held
    # by its weight alone, that is the weight
    static = [m for m in _generated("pendulum_pin_reaction", "pin_force", "reaction_as_weight")
              if "as if it did not accelerate" in m.message]
    assert [m.value for m in static] == [pytest.approx((0.0, 19.62, 0.0), abs=1e-9)]
    assert "m a_G = 14.36 N" in static[0].message
    judged = assess("(0, 19.62) N", _solution("pendulum_pin_reaction").result("pin_force"))
    assert judged.diagnosis == LABELS["reaction_as_weight"]
    # with a spring on it too, its static value is no weight
    (spring,) = _generated("bar_swings_down_spring_energy", "pin_force", "reaction_as_static")
    assert spring.value == pytest.approx((0.0, 17.05, 0.0), abs=1e-9)


def test_a_turning_body_taken_as_a_particle_at_its_mass_centre():
    # a rod pinned at its end: m (L/2)^2 for m L^2/3, the angular acceleration 4/3 as large
    right = _solution("pendulum_pin_reaction").result("alpha").value
    particle = [m for m in _generated("pendulum_pin_reaction", "alpha", "other_shape_inertia")
                if "as a particle" in m.message]
    assert [m.value for m in particle] == [pytest.approx(right * 4 / 3)]


def test_a_rotor_turning_in_space_has_its_disk_read_as_a_ring():
    # a gyroscope's disk (m r^2/2 about its axle) as a hoop, m r^2: the precession rate halved
    right = _solution("gyroscope_steady_precession").result("precession_rate").value
    (ring,) = _generated("gyroscope_steady_precession", "precession_rate", "other_shape_inertia")
    assert ring.value == pytest.approx(right / 2, rel=1e-6)
    assert "thin ring (m r²) for a uniform disk of radius r" in ring.message


def test_no_other_shape_for_a_disk_that_does_not_turn_or_spin_in_its_mount(tmp_path):
    # the gyroscope's rotor held in a frame that keeps its orientation: no inertia read
    text = (shipped_dir("problems") / "gyroscope_steady_precession.yaml").read_text("utf-8")
    text = text.replace("origin: G}", "origin: G}\n  F: {parent: N, rotation: {axis: z, "
                        "angle: 0}}").replace("frame: D,", "frame: F,")
    (tmp_path / "held.yaml").write_text(text, encoding="utf-8")
    assert "other_shape_inertia" not in {m.code for m in dynamics_mutations(
        load_problem(tmp_path / "held.yaml"))}
    # a disk fixed askew on a turning shaft does not spin in its mount: a ring's inertia there
    # gives exactly what the couple over b for 2 b gives, and is not read
    assert "other_shape_inertia" not in _codes("disk_on_bent_shaft")


def test_a_motion_at_constant_power_read_as_uniformly_accelerated_between_its_ends():
    # 10 to 25 m/s in 5.25 s: the mean 17.5 m/s times 5.25 s, and 97.5 m over 17.5 m/s
    (distance,) = _generated("car_constant_power_acceleration", "distance", "mean_of_end_rates")
    (time,) = _generated("car_constant_power_acceleration", "time", "mean_of_end_rates")
    assert (distance.value, time.value) == (pytest.approx(91.875), pytest.approx(97.5 / 17.5))
    assert distance.message.startswith("Your value takes the motion as uniformly accelerated")


def test_a_launch_read_at_its_final_speed_throughout():
    # 0.1 m over the 4 m/s the puck leaves with: 0.025 s (the answer is a quarter period)
    (end,) = _generated("spring_launcher_a_of_x", "time", "end_speed_throughout")
    assert end.value == pytest.approx(0.025)
    assert end.message.startswith("Your value takes the motion at its final speed throughout")


def test_no_reading_over_a_zero_the_event_fixes():
    # a block that stops (x' = 0) read at its final speed throughout: the time over 0 (it was
    # the rounding of the event's state, 1.6e7 s); one back where it started (x = 0 from 0):
    # the time as no distance over a speed (it was 2e-7 s)
    assert not _generated("block_between_two_springs", "first_stop", "end_speed_throughout")
    assert not _generated("block_between_two_springs", "amplitude", "end_speed_throughout")
    for code in ("mean_of_end_rates", "end_speed_throughout"):
        assert not _generated("damped_block_positions", "time_back", code)


def test_no_mean_of_end_rates_without_a_stated_starting_rate_or_along_two_coordinates():
    # the launcher starts from a deflection alone; the satellite moves along r and theta
    assert "mean_of_end_rates" not in _codes("spring_launcher_a_of_x")
    assert not {"mean_of_end_rates", "end_speed_throughout"} & _codes("satellite_apogee_speed")


def test_a_side_force_read_as_the_weight_another_reaction_of_the_body_carries():
    # the collar's N_side (across the rod) taken as m g, which N_up carries
    (side,) = _generated("collar_slides_on_spinning_rod", "side_force", "reaction_as_weight")
    assert side.value == pytest.approx(4.905)
    assert "the weight goes to N_up, along the vertical" in side.message
    # a collar on a vertical rod: its one reaction is across the weight, and nothing else of
    # the collar carries the weight (the spring and the motion do)
    assert not _generated("collar_spring_vertical_rod", "rod_force", "reaction_as_weight")


def test_a_pucks_transverse_speed_kept_instead_of_its_angular_momentum():
    # r0 w0 / r = 0.8 x 2 / 0.4 = 4 rad/s (the answer, r0^2 w0 / r^2, is 8)
    (kept,) = _generated("puck_string_through_hole", "angular_velocity", "transverse_speed_kept")
    assert kept.value == pytest.approx(4.0)
    assert kept.message.startswith("Your value keeps the transverse speed r θ̇ of P from the start")
    # asked for no angle's rate (the satellite), or not integrated from a start: no reading
    assert "transverse_speed_kept" not in _codes("satellite_apogee_speed")
    assert "transverse_speed_kept" not in _codes("collar_slides_on_spinning_rod")


def test_a_coupling_read_with_the_kinetic_energy_kept():
    # 20 Mg at 1.5 m/s couples to 30 Mg at rest: sqrt(20 x 1.5^2 / 50) m/s, not 0.6
    (kept,) = _generated("freight_cars_couple", "velocity_after", "energy_kept_in_coupling")
    assert kept.value == pytest.approx(0.9 ** 0.5)
    # an impact with restitution (the pucks bounce apart) is no coupling
    assert "energy_kept_in_coupling" not in _codes("pucks_oblique_impact")


def test_a_disks_parallel_axis_term_written_with_its_radius_for_the_pins_distance():
    # hung 100 mm from its centre: I_G + m r^2 for I_G + m d^2 (r = 200 mm)
    (radius,) = _generated("disk_pendulum_period", "omega_n", "parallel_axis_with_radius")
    assert radius.value == pytest.approx(4.0435, rel=1e-4)
    assert "the term is m d², d the distance from G to O" in radius.message
    # pinned at its rim the radius is the pin's distance; a rod has no radius
    assert "parallel_axis_with_radius" not in _codes("disk_pinned_at_rim_released")
    assert "parallel_axis_with_radius" not in _codes("pendulum_pin_reaction")


def test_a_given_radius_of_gyration_taken_as_a_uniform_disk_of_the_strings_radius():
    # the yo-yo's m k^2 (k = 3 r) taken as m r^2/2: a = g r^2/(r^2/2 + r^2) = 2 g/3
    (disk,) = [m for m in _generated("yo_yo_unwinding", "accel", "other_shape_inertia")
               if "uniform disk" in m.message]
    assert disk.value == pytest.approx(-6.54, rel=1e-6)
    assert "I = 0.00018 kg*m^2" in disk.message


def test_restitution_applied_to_the_tangential_component_of_a_smooth_impact():
    # 20 m/s at 30 deg onto a smooth floor, e = 0.7: (17.32, 7) after; e on both components
    # gives (0.7 x 17.32, 7), kept in sense or reversed; e on the tangential component
    # instead, the normal one reversed unscaled, (0.7 x 17.32, 10)
    values = [m.value for m in _generated("ball_bounces_oblique_floor", "velocity_after",
                                          "restitution_component")]
    assert sorted(values) == [pytest.approx((-12.1244, 7.0, 0.0), rel=1e-4),
                              pytest.approx((12.1244, 7.0, 0.0), rel=1e-4),
                              pytest.approx((12.1244, 10.0, 0.0), rel=1e-4)]
    result = _solution("ball_bounces_oblique_floor").result("velocity_after")
    assert assess("(12.12, 10, 0) m/s", result).diagnosis == LABELS["restitution_component"]
    # the right answer, and the normal component left unreversed, are not this family
    assert assess("(17.32, 7, 0) m/s", result).diagnosis is None
    assert assess("(17.32, -7, 0) m/s", result).diagnosis != LABELS["restitution_component"]


def test_no_energy_lost_names_the_perfectly_elastic_impact():
    # a zero of e = 1 is kept: it is what "kinetic energy conserved" gives
    judged = assess("0 J", _solution("pucks_oblique_impact").result("energy_lost"))
    assert judged.diagnosis == LABELS["restitution_ignored"]


def test_restitution_applied_to_each_particles_own_tangential_velocity():
    # B's tangential (N.y) velocity -3.464 m/s reversed and scaled, as off a wall: +2.771
    result = _solution("pucks_oblique_impact").result("velocity_B")
    assert assess("(3.181, 2.771, 0) m/s", result).diagnosis == LABELS["restitution_component"]
    assert assess("(3.181, -3.464, 0) m/s", result).diagnosis is None
    assert assess("(3.181, 3.464, 0) m/s", result).diagnosis != LABELS["restitution_component"]


def test_the_damper_left_out_gives_the_undamped_response():
    # the first peak of the undamped block: v0/omega_n = 50 mm a quarter period pi/(2 omega_n)
    undamped, decay = _generated("damped_block_first_peak", "peak_displacement",
                                 "damping_omitted")
    assert undamped.value == pytest.approx(50.0, rel=1e-6)
    assert "c = 40 N*s/m" in undamped.message
    # at the damped frequency without the decay: v0/omega_d = 51.03 mm, pi/(2 omega_d)
    assert decay.value == pytest.approx(1000 / (400 - 16) ** 0.5, rel=1e-6)
    assert "ω_d = 19.6 rad/s" in decay.message
    result = _solution("damped_block_first_peak").result("time_to_peak")
    assert assess("0.08016 s", result).diagnosis == LABELS["damping_omitted"]
    # the right answer, and a spring left out (4.18 s), are not this family
    assert assess("0.06988 s", result).diagnosis is None
    assert assess("4.18 s", result).diagnosis != LABELS["damping_omitted"]
    # the spring's own force has no value in the softer spring's model
    forces = _generated("damped_block_first_peak", "spring_force", "damping_omitted")
    assert [m.value for m in forces] == [pytest.approx(100.0, rel=1e-6)]


def test_two_springs_holding_a_block_from_either_side_combined_in_series():
    assert "springs_in_series" not in _codes("damped_block_first_peak")  # one spring
    (series,) = _generated("block_between_two_springs", "amplitude", "springs_in_series")
    assert series.value == pytest.approx(44.7214, rel=1e-5)


def test_two_springs_meeting_at_a_massless_joint_combined_as_if_in_parallel():
    (parallel,) = [m for m in dynamics_mutations(_problem("block_on_springs_in_series"))
                   if m.code == "springs_in_series"]
    assert "as if in parallel (k = k1 + k2)" in parallel.sentence
    assert parallel.term.text == "(k1) * (k2)/((k1) + (k2))"
    # stiffened so that in series they act as k1 + k2, the joint's share unchanged
    assert [s.stiffness.text for s in parallel.problem.dynamics.springs] == [
        "(k1)*((k1) + (k2))**2/((k1) * (k2))", "(k2)*((k1) + (k2))**2/((k1) * (k2))"]


@pytest.mark.slow
def test_series_springs_combined_in_parallel_give_the_frequency_of_k1_plus_k2():
    (parallel,) = _generated("block_on_springs_in_series", "omega_n", "springs_in_series")
    assert parallel.value == pytest.approx(15.0, rel=1e-6)  # sqrt((600 + 300)/4)


def test_the_reactions_of_a_shaft_in_two_bearings_taken_as_their_static_values():
    # the weight 39.24 N alone at A (its axial support), without the couple of the tilted disk
    (static,) = _generated("disk_on_bent_shaft", "bearing_A", "reaction_as_static")
    assert static.value == pytest.approx((0.0, 0.0, 39.24), abs=1e-9)
    # where the motion is not prescribed (no second rate given) the static model has none:
    # not made at all
    assert "reaction_as_static" not in _codes("atwood_machine") | _codes(
        "block_sliding_down_incline")
    # an integrated motion or an energy balance finds the motion from the masses it takes
    # as zero: not made at all (the sliding ladder's would integrate 10 s for nothing)
    assert "reaction_as_static" not in _codes("ladder_wall_lift_off") | _codes(
        "ruina_9_19_falling_ladder") | _codes("crate_pushed_impulse_momentum")


@pytest.mark.slow
def test_the_weight_written_for_the_mass_in_the_problems_own_units():
    # W = 10 lb used as 10 slug with k = 240 lb/ft: omega_n = sqrt(240/10) rad/s
    (heavy,) = _generated("block_on_spring_us_units", "omega_n", "weight_for_mass")
    assert heavy.value == pytest.approx(24 ** 0.5, rel=1e-6)
    # 25 kg used as its weight 245.25 (N) with k = 400 kN/m
    (heavy,) = _generated("motor_on_beam_resonance", "omega_n", "weight_for_mass")
    assert heavy.value == pytest.approx((400e3 / (25 * 9.81)) ** 0.5, rel=1e-6)


def test_a_movable_pulleys_two_strands_counted_once():
    # yA + yB = c0 for yA + 2 yB = c0 (mA = 10 kg, mB = 30 kg, B hung on two strands): the
    # blocks move together, (2 mA + mB) a = (mB - 2 mA) g, a = g/5
    (once,) = [m for m in _generated("movable_pulley_two_blocks", "accel_A", "strands_miscounted")
               if "length of" in m.message]
    assert once.value == pytest.approx(1.962, rel=1e-6)
    assert "counts yB once in the length of cord_length" in once.message
    assert "strands_miscounted" not in _codes("atwood_machine")  # one strand each side


@pytest.mark.slow  # integrates a heavy problem's mistaken motion (16 s)
def test_the_initial_speed_left_out_starts_the_motion_from_rest():
    # 300 N at 30 deg below the horizontal for 4 s from rest, not from 2 m/s
    (rest,) = _generated("crate_pushed_impulse_momentum", "speed", "initial_speed_omitted")
    assert rest.value == pytest.approx(7.41261 - 2.0, rel=1e-5)
    assert "x' = 2 m/s (v0)" in rest.message
    # released at 0.5 m/s from 20 mm: from rest it stops at once, at 20 mm
    (rest,) = _generated("block_between_two_springs", "amplitude", "initial_speed_omitted")
    assert rest.value == pytest.approx(20.0, rel=1e-6)


def test_a_motion_that_starts_from_rest_has_no_initial_speed_to_leave_out():
    assert "initial_speed_omitted" not in _codes("spring_launcher_a_of_x")
    assert "initial_speed_omitted" not in _codes("pendulum_pin_reaction")


def test_a_quantity_that_varies_along_the_motion_read_at_its_start():
    # the drag c v0^2 at 12 m/s, not at the event's 4 m/s
    (start,) = _generated("boat_coasting_quadratic_drag", "deceleration", "value_at_start")
    assert start.value == pytest.approx(-7.2, rel=1e-5)
    # the coordinates and the time start from the spec's own values: not read there
    assert not _generated("boat_coasting_quadratic_drag", "distance", "value_at_start")
    assert "value_at_start" not in _codes("pendulum_pin_reaction")  # no motion integrated


def test_a_force_that_depends_on_the_speed_taken_constant_at_its_start():
    # the drive P/v1 = 6000 N constant from 10 to 25 m/s: t = m (v2 - v1)/F, s = m (v2² - v1²)/(2F)
    (time,) = _generated("car_constant_power_acceleration", "time", "force_taken_constant")
    (distance,) = _generated("car_constant_power_acceleration", "distance",
                             "force_taken_constant")
    assert (time.value, distance.value) == (pytest.approx(3.0), pytest.approx(52.5))
    assert "traction constant" in time.message
    # the force itself keeps its starting value: that is the value read at the start
    assert not _generated("car_constant_power_acceleration", "force_at_25",
                          "force_taken_constant")
    # a push that does not depend on the state is constant already
    assert "force_taken_constant" not in _codes("crate_pushed_impulse_momentum")


def test_a_power_divided_by_the_efficiency_read_multiplied_by_it():
    # the engine's power P_drive/eta with eta = 0.85, read as P_drive*eta
    (inverted,) = _generated("car_climbs_grade_power", "engine_power", "efficiency_inverted")
    assert inverted.value == pytest.approx(74.93918 * 0.85 ** 2, rel=1e-6)
    assert "multiplies the power by the efficiency eta = 0.85" in inverted.message
    # the power delivered itself has no efficiency in it
    assert not _generated("car_climbs_grade_power", "wheel_power", "efficiency_inverted")


@pytest.mark.slow
def test_a_mistaken_model_keeps_static_friction_between_two_bodies_equal_and_opposite():
    # the disk rolling on the pulled plank, with a hoop's inertia: the friction m A/2 still
    # pulls the plank back, A = P/(M + m/2) = 60/13 (not P/M, the friction lost)
    (hoop,) = _generated("disk_rolls_on_pulled_plank", "plank_acceleration",
                         "other_shape_inertia")
    assert hoop.value == pytest.approx(60 / 13, rel=1e-9)
    # and the weight left out changes nothing along the plank: no such mistake is kept
    assert not _generated("disk_rolls_on_pulled_plank", "plank_acceleration", "weight_omitted")


def test_a_reaction_read_as_the_weight_is_read_so_in_its_power_too():
    # the cable's power at the cab's speed with the tension taken as the 3000 lbf weight
    (power,) = _generated("elevator_motor_power", "power_to_cab", "reaction_as_weight")
    assert power.value == pytest.approx(65.4545, rel=1e-5)
    (through,) = _generated("elevator_motor_power", "motor_power", "reaction_as_weight")
    assert through.value == pytest.approx(87.2727, rel=1e-5)


def test_an_impact_on_a_pinned_body_has_the_central_inertia_used_about_the_pin():
    # the ball striking the hanging rod: angular momentum about the pin with M L^2/12 for
    # M L^2/3 (ω' = 6.508 rad/s, not 2.477)
    (mistake,) = _generated("ball_strikes_hanging_rod", "omega_after", "central_inertia_at_pivot")
    assert mistake.value == pytest.approx(6.508475, rel=1e-6)
    # a free rod struck on ice has no pin: none
    assert "central_inertia_at_pivot" not in _codes("rod_strikes_ledge")


def test_a_tension_taken_as_a_weight_acts_on_every_strand_and_is_shared_by_the_strands_held():
    values = sorted(round(m.value, 4) for m in _generated("movable_pulley_two_blocks", "tension",
                                                          "tension_as_weight"))
    # A's weight 98.1 N (on both of B's strands), or B's 294.3 N shared by its two: 147.15 N
    assert values == [98.1, 147.15]
    (on_b,) = [m for m in _generated("movable_pulley_two_blocks", "accel_B", "tension_as_weight")
               if round(m.value, 4) == -3.27]
    assert "in the balance of blockB" in on_b.message


def test_a_cord_pulling_a_body_through_two_strands_counted_once_in_its_balance():
    # B on the movable pulley pulled by T instead of 2 T: 50 a_B = -196.2 N, a_B = -3.924
    pulls = [m for m in _generated("movable_pulley_two_blocks", "accel_B", "strands_miscounted")
             if "strands hold blockB" in m.message]
    assert [m.value for m in pulls] == [pytest.approx(-3.924, rel=1e-9)]
    # an Atwood machine's cord pulls each block once: nothing to miscount
    assert not [m for m in dynamics_mutations(_problem("atwood_machine"))
                if m.code == "strands_miscounted"]



def test_a_spring_left_out_only_where_there_is_a_spring():
    assert "spring_omitted" in _codes("collar_spring_vertical_rod")
    assert "spring_omitted" not in _codes("pendulum_pin_reaction")


def test_a_load_is_moved_only_on_a_turning_body():
    assert "load_at_other_point" in _codes("bar_swings_down_spring_energy")
    assert "load_at_other_point" not in _codes("collar_spring_vertical_rod")


def test_static_friction_as_mu_m_g_is_read_only_where_friction_does_not_slip():
    static = [m for m in dynamics_mutations(_problem("cylinder_pulled_rolls"))
              if m.code == "normal_from_weight"]
    assert [oid for m in static for oid, _ in m.readings] == ["friction", "mu_needed"]
    assert not any(m.readings for m in dynamics_mutations(_problem("block_sliding_down_incline"))
                   if m.code == "normal_from_weight")


def test_a_static_friction_is_read_in_the_other_sense_only_where_an_objective_reads_it():
    (reversed_,) = [m for m in dynamics_mutations(_problem("cylinder_pulled_rolls"))
                    if m.code == "friction_reversed"]
    assert [(oid, e.text) for oid, e in reversed_.readings] == [
        ("friction", "dot(-force(F_C), N.x)"), ("mu_needed", "mag(-force(F_C))/mag(force(N_C))")]
    # kinetic friction is turned round in the model, not read
    assert not any(m.readings for m in dynamics_mutations(_problem("block_sliding_down_incline"))
                   if m.code == "friction_reversed")


def test_a_springs_force_read_as_the_weight_of_the_body_it_holds():
    (held,) = [m for m in dynamics_mutations(_problem("bar_on_spring_vibration"))
               if m.code == "reaction_as_weight" and "spring" in m.sentence]
    assert [(oid, e.text) for oid, e in held.readings] == [
        ("spring_force", "dot(m*mag(-g*N.y)*force(spring)/mag(force(spring)), N.y)")]
    # no objective reads the spring's force: no reading
    assert not [m for m in dynamics_mutations(_problem("spring_launcher_a_of_x"))
                if m.code == "reaction_as_weight"]


def test_a_contact_is_taken_smooth_only_where_it_rolls():
    assert "contact_taken_smooth" in _codes("cylinder_pulled_rolls")
    assert "contact_taken_smooth" not in _codes("block_sliding_down_incline")


def _bar_with_its_weight_at_the_end():
    # the bar (5 kg, 1.2 m) swings down a quarter turn about O with its weight taken at the end
    # A: m g L = 1/2 I_O w^2 + the spring's gain (k = 20 N/m, stretch 1.0 m -> 1.6 m)
    m, L, g, k = 5.0, 1.2, 9.81, 20.0
    return ((m * g * L - k * (1.6 ** 2 - 1.0 ** 2) / 2) / (m * L ** 2 / 3 / 2)) ** 0.5


@pytest.mark.slow
@pytest.mark.parametrize("problem,objective,answer,code", [
    # the collar falls h = 0.3 m; without the spring v = sqrt(2 g h)
    ("collar_spring_vertical_rod", "speed", f"{(2 * 9.81 * 0.3) ** 0.5:.4g} m/s",
     "spring_omitted"),
    ("bar_swings_down_spring_energy", "angular_velocity",
     f"{_bar_with_its_weight_at_the_end():.4g} rad/s", "load_at_other_point"),
    # the cylinder (20 kg, mu = 0.2) rolls forward; its friction acts backward
    ("cylinder_pulled_rolls", "friction", f"{-0.2 * 20 * 9.81:.4g} N", "normal_from_weight"),
    # pulled by P = 60 N at its centre it slides without friction: a = P/m
    ("cylinder_pulled_rolls", "acceleration", f"{60 / 20:.4g} m/s^2", "contact_taken_smooth"),
    # the spring's energy from its whole length 0.5 m: (1/2) 200 0.5^2 (its model, the
    # energy more than the collar's fall gives, has no motion)
    ("collar_spring_vertical_rod", "spring_energy", "25 J", "spring_free_length_omitted"),
    # the spring holding the bar level (44.15 N, with the pin) taken to carry its weight
    ("bar_on_spring_vibration", "spring_force", "58.86 N", "reaction_as_weight"),
    # the floor's friction (-20 N, backward) drawn forward
    ("cylinder_pulled_rolls", "friction", "20 N", "friction_reversed"),
])
def test_the_new_families_name_their_value(problem, objective, answer, code):
    judged = assess(answer, _solution(problem).result(objective))
    assert judged.diagnosis == LABELS[code]


def test_a_frequency_in_hertz_and_a_period_read_the_other_way_up():
    # f = omega_n/(2 pi) = 4.424 Hz answered 2 pi/omega_n = 0.2260 s, and the reverse
    problem = _problem("block_on_spring_us_units")
    readings = {m.readings[0][0]: m.readings[0][1].text for m in dynamics_mutations(problem)
                if m.code == "period_for_frequency"}
    assert readings == {"frequency": "2*pi/omega_n(y)", "period": "omega_n(y)/(2*pi)"}
    # an objective without 2 pi in it (omega_n itself) is not read so
    assert "omega_n" not in readings


def test_a_springs_energy_from_its_whole_length_is_read_in_the_right_model():
    (read,) = [m for m in dynamics_mutations(_problem("bar_swings_down_spring_energy"))
               if m.code == "spring_free_length_omitted" and m.readings]
    assert [(oid, e.text) for oid, e in read.readings] == [
        ("spring_energy", "k*mag(pos(D, A))**2/2")]
    # no objective reads the spring's energy: no reading
    assert not [m for m in dynamics_mutations(_problem("damped_block_first_peak"))
                if m.code == "spring_free_length_omitted" and m.readings]


def test_a_springs_energy_taken_from_the_change_of_its_stretch_in_a_work_energy_balance():
    # the spring DA is counted from its length at the start, |DA| = sqrt(H^2 + L^2) at
    # theta = 0, instead of its free length L0; its force (the pin's) keeps the free length
    (changed,) = [m for m in dynamics_mutations(_problem("bar_swings_down_spring_energy"))
                  if m.code == "spring_energy_from_change"]
    assert changed.problem.dynamics.springs[0].length.text == "sqrt(H**2 + L**2)"
    assert [o.id for o in changed.problem.objectives] == ["angular_velocity", "spring_energy"]


@pytest.mark.slow
def test_a_springs_energy_from_the_change_of_its_stretch_gives_the_students_speed():
    # (1/2) k (s2 - s1)^2 = 3.6 J for the 25.6 J - 10 J of the right balance: 4.640 rad/s
    (changed,) = _generated("bar_swings_down_spring_energy", "angular_velocity",
                            "spring_energy_from_change")
    assert changed.value == pytest.approx(4.639504, rel=1e-5)
    assert "the stretch s1 = 1 m at the start" in changed.message
    # an integrated motion (the launcher) is no work-energy balance
    assert "spring_energy_from_change" not in _codes("spring_launcher_a_of_x")


def test_a_push_on_a_lever_taken_at_the_pad_or_exchanged_with_it():
    # the push P at C and the pad's N_B at B on the lever: P taken at B (N = P), or the two
    # exchanged (N = P b/(b + c)); the pin A, with two directions, is never taken
    moved = [m for m in dynamics_mutations(_problem("flywheel_lever_brake"))
             if m.code == "load_at_other_point"][:2]
    assert [m.problem.dynamics.forces[0].at for m in moved] == ["B", "B"]
    pad = [[a.at for a in r.acts if a.on == "lever"] for m in moved
           for r in m.problem.dynamics.reactions if r.name == "N_B"]
    assert pad == [["B"], ["C"]]
    assert moved[0].sentence.startswith("Your value takes the force push on lever at B")


@pytest.mark.slow
def test_a_push_on_a_lever_taken_at_the_pad_gives_the_normal_force_p():
    values = sorted(m.value for m in _generated("flywheel_lever_brake", "normal_force",
                                                "load_at_other_point"))
    assert values == pytest.approx([40.0, 100.0, 150.0])


def test_an_oblique_impact_of_two_pucks_taken_head_on():
    # A at 6 m/s and B at 4 m/s, each oblique to the line of centres N.x: their whole speeds
    # taken along it, in the sense of their components there, nothing across it
    (head_on,) = [m for m in dynamics_mutations(_problem("pucks_oblique_impact"))
                  if m.code == "impact_taken_head_on"]
    starts = {s.key.text: s.value.text for s in head_on.problem.dynamics.analysis.start}
    assert starts["yA'"] == starts["yB'"] == "0"
    assert starts["xB'"] == ("(-vB*cos(pi/3))/abs(-vB*cos(pi/3))*sqrt((-vB*sin(pi/3))^2 + "
                             "(-vB*cos(pi/3))^2)")


@pytest.mark.slow
def test_an_oblique_impact_taken_head_on_gives_the_whole_speeds_exchange():
    (head_on,) = _generated("pucks_oblique_impact", "velocity_A", "impact_taken_head_on")
    assert head_on.value == pytest.approx((-4.8, 0.0, 0.0), abs=1e-9)
    # a rod struck at a point turns: no particle impact to take head-on
    assert "impact_taken_head_on" not in _codes("rod_strikes_ledge")


def test_a_particles_angular_momentum_read_without_its_arm():
    # H_O = m r^2 theta' of the puck on its cord answered m r theta' = m v across OP
    problem = _problem("puck_string_through_hole")
    (arm,) = moment_arm_omitted(problem, build(problem))
    assert [(oid, find.text) for oid, find in arm.readings] == [
        ("angular_momentum", "dot(cross(unit(pos(P, O)), momentum(puck, N)), N.z)")]
    assert (arm.code, arm.term.text, arm.term_unit) == ("moment_arm_omitted", "mag(pos(P, O))", "m")


def test_no_arm_to_drop_from_a_rigid_bodys_spin_or_a_particle_at_the_point():
    disk = _problem("disk_on_bent_shaft")  # I omega of a disk: no single arm
    assert list(moment_arm_omitted(disk, build(disk))) == []
    puck = _problem("puck_string_through_hole")
    objectives = tuple(replace(o, find=replace(o.find, text="dot(angmom(puck, P, N), N.z)",
                                                node=parse("dot(angmom(puck, P, N), N.z)",
                                                           functions=FUNCTIONS)))
                       if o.id == "angular_momentum" else o for o in puck.objectives)
    about_itself = replace(puck, objectives=objectives)  # about the puck's own place: no arm
    assert list(moment_arm_omitted(about_itself, build(about_itself))) == []


def test_a_pin_left_out_reads_its_force_zero_and_the_mass_centre_falling_freely():
    # the disk released on its rim pin: R_O = 0 and a_G = g (the free fall), read in the right
    # model; a body a spring also loads (the bar) does not fall freely without its pin
    (free,) = [m for m in dynamics_mutations(_problem("disk_pinned_at_rim_released"))
               if m.code == "reaction_omitted"]
    assert dict((oid, e.text) for oid, e in free.readings) == {
        "pin_force": "0*(-g*N.y)", "centre_acceleration": "-g*N.y"}
    assert "R_O = 0" in free.sentence
    assert "reaction_omitted" not in _codes("bar_swings_down_spring_energy")


@pytest.mark.slow
def test_a_disk_falling_freely_is_named_with_the_particle_that_gives_the_same_value():
    judged = assess("(0, -9.81, 0) m/s^2", _solution("disk_pinned_at_rim_released")
                    .result("centre_acceleration"))
    assert judged.diagnosis == (f"{LABELS['reaction_omitted']} or "
                                f"{LABELS['other_shape_inertia']}")


def test_a_push_given_beyond_the_pad_taken_that_far_from_the_pin():
    # C is given c beyond the pad B: the push taken c from the pin A (N b = P c, 150 N)
    (arm,) = [m for m in dynamics_mutations(_problem("flywheel_lever_brake"))
              if m.code == "load_at_other_point" and m.step == "Momentum balances"]
    moved = arm.problem.dynamics.forces[0].at
    point = next(p for p in arm.problem.points if p.name == moved)
    assert (moved, point.origin, point.position.text) == ("C_from_A", "A", "c*N.x")
    assert arm.sentence.startswith("Your value measures the arm of push about the pin A from B")
    # a push given from the pin itself has no pad to measure from (the pendulum's has no pad)
    assert not [m for m in dynamics_mutations(_problem("disk_pinned_at_rim_released"))
                if m.code == "load_at_other_point" and m.step == "Momentum balances"]


@pytest.mark.slow
def test_a_push_given_beyond_the_pad_taken_that_far_from_the_pin_gives_p_c_over_b():
    # N b = P c: 150 N, which R and c exchanged give too: both are said
    judged = assess("150 N", _solution("flywheel_lever_brake").result("normal_force"))
    assert judged.diagnosis == f"{LABELS['load_at_other_point']} or {LABELS['given_swap']}"


def test_an_impact_on_a_pinned_rod_with_linear_momentum_conserved_through_the_pin():
    # the ball strikes the rod hanging on its pin O: R_O left out with the rod's angular
    # impulse-momentum balance (m v0 = m v + M (L/2) w), and the pin's impulse read as zero
    model, zero = [m for m in dynamics_mutations(_problem("ball_strikes_hanging_rod"))
                   if m.code == "pin_impulse_omitted"]
    d = model.problem.dynamics
    assert [r.name for r in d.reactions] == ["J"] and d.unbalanced == ("rod",)
    assert [o.id for o in model.problem.objectives] == ["omega_after", "ball_velocity_after"]
    assert dict((oid, e.text) for oid, e in zero.readings) == {"pin_impulse": "0*N.x"}
    # no pin in the impact (a rod on ice struck by a blow): nothing to conserve through it
    assert "pin_impulse_omitted" not in _codes("rod_struck_on_ice")


@pytest.mark.slow
def test_linear_momentum_conserved_through_the_pin_gives_the_rods_spin():
    # m v0 = m v + M (L/2) w with v - 0.9 w = -e v0: w = 7.8/(2.4 + 0.45) = 2.7368 rad/s
    (through,) = _generated("ball_strikes_hanging_rod", "omega_after", "pin_impulse_omitted")
    m, M, L, d, v0, e = 0.5, 4.0, 1.2, 0.9, 8.0, 0.6
    assert through.value == pytest.approx((m * v0 + m * e * v0) / (m * d + M * L / 2))
    assert "as if the pin O gave no impulse" in through.message


def test_a_rolling_hoops_kinetic_energy_taken_as_its_parts_spins_alone():
    # the hoop (M, a ring of R) with a small mass m at its rim rolls: its parts massless, the
    # ring keeping its spin M R^2 about z, the small mass nothing; the weights kept as forces
    (spin,) = [m for m in dynamics_mutations(_problem("unbalanced_hoop_rolls"))
               if m.code == "translational_ke_omitted"]
    d = spin.problem.dynamics
    ring, small = d.bodies[0].parts
    assert (ring.mass.text, ring.shape.entries[0][0], ring.shape.entries[0][1].text) == (
        "0", "zz", "(1)*(M)*(R)^2")
    assert small.mass.text == "0" and small.shape is None
    assert d.gravity is None and [(f.at, f.force.text) for f in d.forces] == [
        ("G", "(M)*(-g*N.y)"), ("Q", "(m)*(-g*N.y)")]
    # a bar swinging on a fixed pin: its ½ I_G ω² is the parallel-axis mistake, not this one
    assert "translational_ke_omitted" not in _codes("bar_swings_down_spring_energy")


@pytest.mark.slow
def test_a_rolling_hoops_spin_alone_gives_the_students_speed():
    # m g (2 R) = ½ M R² ω²: ω = sqrt(2 · 9.81 · 1.0 / (4 · 0.25)) = 4.429 rad/s
    (spin,) = _generated("unbalanced_hoop_rolls", "angular_velocity", "translational_ke_omitted")
    assert spin.value == pytest.approx((2 * 1.0 * 9.81 * 1.0 / (4.0 * 0.25)) ** 0.5)


def test_a_slipping_hoop_taken_to_roll_and_its_angular_acceleration_read_as_a_over_r():
    # the hoop slides down the incline (kinetic friction F_C): taken to roll, F_C becomes an
    # unknown along the incline with the rolling condition, phi' left to it; and -phi'' is
    # read from the centre's acceleration by the rolling relation (alpha = a/r)
    reading, model = [m for m in dynamics_mutations(_problem("hoop_slips_down_incline"))
                      if m.code == "rolling_assumed"]
    assert dict((oid, e.text) for oid, e in reading.readings) == {
        "angular_acceleration": "-(-dot(acc(G, N), cross(N.z, pos(C, G)))/dot(pos(C, G), pos(C, G)))"}
    p = model.problem
    assert p.constraints[-1].lhs.text == "vel(coincident(C, W), N)"
    assert "phi'" not in {g.key.text for g in p.givens} and not p.dynamics.friction
    assert [r.name for r in p.dynamics.reactions] == ["N_C", "F_C"]
    # a cylinder that rolls already (static friction) is not taken to roll
    assert "rolling_assumed" not in _codes("cylinder_pulled_rolls")


@pytest.mark.slow
def test_a_slipping_hoop_taken_to_roll_accelerates_at_half_g_sin_beta():
    import math
    (rolls,) = _generated("hoop_slips_down_incline", "acceleration", "rolling_assumed")
    assert rolls.value == pytest.approx(9.81 * math.sin(math.radians(40)) / 2)


def test_a_vibration_started_from_zero_instead_of_its_initial_displacement():
    # the block between two springs starts at x0 = 20 mm with v0: started from x = 0 instead
    (zero,) = [m for m in dynamics_mutations(_problem("block_between_two_springs"))
               if m.code == "initial_displacement_omitted"]
    starts = {s.key.text: s.value.text for s in zero.problem.dynamics.analysis.start}
    assert starts == {"x": "0", "x'": "v0"} and zero.term.text == "x0"
    # no spring (a satellite's orbit from r = R + h): no vibration to start elsewhere
    assert "initial_displacement_omitted" not in _codes("satellite_apogee_speed")


@pytest.mark.slow
def test_a_vibration_started_from_zero_reaches_v0_over_omega_n_a_quarter_period_on():
    import math
    wn = math.sqrt(8000 / 12)
    (amplitude,) = _generated("block_between_two_springs", "amplitude",
                              "initial_displacement_omitted")
    (stop,) = _generated("block_between_two_springs", "first_stop", "initial_displacement_omitted")
    assert (amplitude.value, stop.value) == pytest.approx((0.5 / wn * 1000, math.pi / 2 / wn),
                                                          rel=1e-5)



def test_a_reaction_across_a_turning_rod_is_read_without_the_coriolis_term():
    found = {(m.code, m.readings[0][0]) for m in dynamics_mutations(
        _problem("collar_slides_on_spinning_rod")) if "oriolis" in m.code}
    assert found == {("drop_coriolis", "side_force"), ("coriolis_half", "side_force")}
    # said in plain words, the 2 forgotten said as such
    half = next(m for m in dynamics_mutations(_problem("collar_slides_on_spinning_rod"))
                if m.code == "coriolis_half")
    assert half.sentence.startswith("Your value takes N_side from the balance of collar along "
                                    "N_side's direction with the Coriolis term taken as "
                                    "ω × v_rel, without its 2: sliding along frame E")
    # a pendulum turns with no frame sliding on it: no relative velocity, no Coriolis term
    assert not [m for m in dynamics_mutations(_problem("pendulum_pin_reaction"))
                if "oriolis" in m.code]


@pytest.mark.slow
def test_a_reaction_across_a_turning_rod_read_without_the_coriolis_term_or_its_2():
    # N_side = 2 m r' θ' = 6 N: 0 N without the Coriolis term, 3 N without its 2
    result = _solution("collar_slides_on_spinning_rod")
    side = result.result("side_force")
    assert {(m.code, round(m.value, 6)) for m in side.generated_mistakes
            if "oriolis" in m.code} == {("drop_coriolis", 0.0), ("coriolis_half", 3.0)}
    assert [m.value for m in result.result("drive_moment").generated_mistakes
            if m.code == "coriolis_half"] == [pytest.approx(0.9)]
    assert assess("6 N", side).diagnosis is None  # the answer itself
    assert assess("-6 N", side).diagnosis != "Coriolis term without its factor 2"
    # the force along the rod's axis (N_up, with the weight) has no Coriolis part
    assert not [m for m in dynamics_mutations(_problem("collar_slides_on_spinning_rod"))
                if "oriolis" in m.code and "N_up" in m.sentence]

def test_a_springs_energy_without_its_half_is_a_spring_twice_as_stiff_in_the_energies():
    (half,) = [m for m in dynamics_mutations(_problem("spring_launcher_a_of_x"))
               if m.code == "spring_energy_half_omitted"]
    assert half.problem.dynamics.springs[0].stiffness.text == "2*(k)"
    # the speed and energy an energy balance gives; not the time of the push
    assert [o.id for o in half.problem.objectives] == ["speed", "kinetic_energy"]
    # the rod's force keeps k s: not read
    (collar,) = [m for m in dynamics_mutations(_problem("collar_spring_vertical_rod"))
                 if m.code == "spring_energy_half_omitted"]
    assert [o.id for o in collar.problem.objectives] == ["speed", "spring_energy"]


def test_a_spring_taken_constant_at_its_starting_force_only_in_an_integrated_motion():
    (constant,) = [m for m in dynamics_mutations(_problem("spring_launcher_a_of_x"))
                   if m.code == "force_taken_constant"]
    d = constant.problem.dynamics
    # k delta (its length L0 - delta at the start) pushing the puck along N.x, the whole
    # stroke long
    (force,) = d.forces
    assert not d.springs and (force.on, force.at) == ("puck", "P")
    assert force.force.text.endswith("*N.x") and "Abs(L0 - delta)" in force.force.text
    assert [o.id for o in constant.problem.objectives] == ["speed", "time"]
    # a work-energy balance has no stroke to integrate
    assert "force_taken_constant" not in _codes("collar_spring_vertical_rod")


@pytest.mark.slow
def test_a_spring_taken_constant_and_its_energy_without_the_half_name_the_launchers_answers():
    # constant k d/m over d: t = sqrt(2 m/k) = 0.03536 s; k d^2 = m v^2/2: v = 5.657 m/s,
    # which both readings give
    solution = _solution("spring_launcher_a_of_x")
    assert assess("0.03536 s", solution.result("time")).diagnosis == \
        LABELS["force_taken_constant"]
    assert assess("5.657 m/s", solution.result("speed")).diagnosis == \
        f"{LABELS['spring_energy_half_omitted']} or {LABELS['force_taken_constant']}"
    assert assess("0.03927 s", solution.result("time")).diagnosis is None


def test_a_tilted_disks_angular_momentum_taken_along_its_angular_velocity_or_its_axis():
    # I_axis = m r^2/2 = 0.045 kg m^2 at 60 rad/s: 2.7 along the shaft (the tilt 0 deg), or
    # along the disk's axis, tilted 10 deg
    solution = _solution("disk_on_bent_shaft")
    label = LABELS["angmom_along_axis"]
    for answer in ("(0, 0, 2.7) kg*m^2/s", "(0, -0.4689, 2.659) kg*m^2/s"):
        assert assess(answer, solution.result("angular_momentum")).diagnosis == label
    for answer in ("0 deg", "10 deg"):
        assert assess(answer, solution.result("tilt_of_angular_momentum")).diagnosis == label
    (along_omega, _) = _generated("disk_on_bent_shaft", "angular_momentum", "angmom_along_axis")
    assert "I = 0.045 kg*m^2" in along_omega.message


def test_a_disk_spinning_about_its_own_axis_has_no_angular_momentum_to_tilt(tmp_path):
    text = (shipped_dir("problems") / "disk_on_bent_shaft.yaml").read_text(encoding="utf-8")
    untilted = tmp_path / "disk_on_straight_shaft.yaml"
    untilted.write_text(text.replace("{axis: x, angle: beta}", "{axis: x, angle: 0}"),
                        encoding="utf-8")
    assert "angmom_along_axis" in _codes("disk_on_bent_shaft")
    assert "angmom_along_axis" not in {m.code for m in dynamics_mutations(
        load_problem(untilted))}


@pytest.mark.parametrize("name, objective, answer, code, words, elsewhere", [
    # (k1 + k2) A = 8000 N/m x 27.84 mm, toward the middle; one spring on the bar: no other
    # spring to add; a spring between two blocks is not in parallel with the wall's
    ("block_between_two_springs", "right_spring_force", "-222.7 N", "spring_force_as_resultant",
     ("springs left and right together on block (222.7 N)",),
     ("bar_on_spring_vibration", "two_mass_spring_chain")),
    # 2 m g R = (M + M + m) v^2/2 with v = R w: w = 2.953 rad/s; a one-part body, or parts all
    # at the centre (a wheel and its hubs): none to move there
    ("unbalanced_hoop_rolls", "angular_velocity", "2.953 rad/s", "part_moving_with_centre",
     ("the mass at Q as moving with the centre G of wheel", "0.5 m from G"),
     ("disk_rolls_on_pulled_plank", "ruina_9_21_wheel_incline")),
    # friction alone decelerates the block: a = -mu_k g cos(30 deg) = -0.25 x 9.81 x 0.866;
    # friction on a level surface (the weight all across it), and no friction: no slope
    ("block_sliding_down_incline", "accel", "-2.124 m/s^2", "weight_along_surface_omitted",
     ("weight of block kept only across the surface it rubs on",),
     ("block_on_turntable", "pendulum_pin_reaction")),
])
def test_a_family_names_its_mistake_and_stays_out_of_problems_without_its_ingredient(
        name, objective, answer, code, words, elsewhere):
    assert assess(answer, _solution(name).result(objective)).diagnosis == LABELS[code]
    (mistake,) = _generated(name, objective, code)
    assert all(w in mistake.message for w in words)
    assert not any(code in _codes(other) for other in elsewhere)


def test_the_striking_car_taken_to_stop_passes_its_whole_momentum_on():
    # m1 v0 = m2 v2: v2 = 20 Mg x 1.5 m/s / 30 Mg = 1 m/s, the impulse m1 v0 = 30 kN s
    solution = _solution("freight_cars_couple")
    label = LABELS["striker_stops"]
    assert assess("1 m/s", solution.result("velocity_after")).diagnosis == label
    assert assess("(30, 0, 0) kN*s", solution.result("impulse_on_second")).diagnosis == label
    (mistake,) = _generated("freight_cars_couple", "velocity_after", "striker_stops")
    assert "takes car1 to stop in the impact at C" in mistake.message
    # two moving pucks, and an impact on the ground: no particle at rest to be struck
    assert "striker_stops" not in _codes("pucks_oblique_impact")
    assert "striker_stops" not in _codes("rod_strikes_ledge")


def test_the_damped_frequency_given_for_the_natural_one_is_named_where_it_differs():
    # a dashpot 10 times stronger: zeta = 1.399 would not oscillate; 5 times: zeta = 0.6995,
    # omega_d = 4.2888 x sqrt(1 - 0.6995^2) = 3.065 rad/s
    body = (shipped_dir("problems") / "damped_pendulum_vibration.yaml").read_text(
        encoding="utf-8").replace("c: 0.6 N*s/m", "c: 3 N*s/m")
    problem = load_problem_text(body)
    result = solve(problem).result("omega_n")
    assert assess("3.065 rad/s", result).diagnosis == LABELS["damped_for_natural"]
    # a weak dashpot: omega_d = 4.247 rad/s is within the tolerance of omega_n, a right answer
    judged = assess("4.247 rad/s", _solution("damped_pendulum_vibration").result("omega_n"))
    assert judged.diagnosis is None and judged.credit == 1
    assert "damped_for_natural" in _codes("damped_pendulum_vibration")
    assert "damped_for_natural" not in _codes("bar_on_spring_vibration")
