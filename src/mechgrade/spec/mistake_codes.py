"""The codes of the mistake families the solver generates: keys of an assignment's
``partial_credit.diagnoses`` and of the worked solution's highlighted steps.

They are plain names, kept apart from the families that produce them (``mechanics.mutations``,
``mechanics.dynamics_mutations``, ``solve.mutants``), so that reading an assignment never
imports the symbolic core.

>>> "drop_coriolis" in MODEL_CODES and "weight_omitted" in DYNAMICS_CODES
True
"""

from __future__ import annotations

ACCELERATION_CODES = ("drop_transport_acc", "drop_tangential", "drop_centripetal",
                      "drop_coriolis", "coriolis_half", "drop_relative_acc")
"""Kinematic mutations that drop or misweigh a term of an acceleration."""

VELOCITY_CODES = ("drop_transport_vel", "drop_omega_r", "drop_relative_vel")
"""Kinematic mutations that drop a term of a velocity."""

MODEL_CODES = ACCELERATION_CODES + VELOCITY_CODES + (
    "relative_omega", "other_point", "other_basis", "acc_t_for_acc", "acc_n_for_acc",
    "acc_for_acc_t", "acc_for_acc_n", "rho_formula", "rho_without_slope",
    "component_for_speed", "mag_as_sum",
    "position_term", "zero_for_constant_rate", "driver_rate", "gyration_for_radius",
    "driver_speed", "rate_relation_inverted",
    "omega_reversed", "angle_complement", "speed_for_component")
"""Family codes of the kinematic model mutations (:mod:`mechgrade.mechanics.mutations`)."""

DYNAMICS_CODES = (
    "weight_omitted", "mass_for_weight", "central_inertia_at_pivot", "friction_reversed",
    "normal_from_weight", "weight_transfer_ignored", "tension_as_weight", "reaction_as_weight",
    "rotational_ke_omitted", "restitution_ignored", "other_shape_inertia",
    "spring_free_length_omitted", "surface_taken_fixed", "body_ke_omitted",
    "impulse_moment_omitted", "moment_arm_omitted", "reaction_as_static", "inertia_omitted",
    "acceleration_reversed", "spring_work_reversed",
    "force_component_reversed",
    "restitution_component", "damping_omitted", "force_omitted", "springs_in_series",
    "weight_for_mass", "strands_miscounted", "initial_speed_omitted",
    "value_at_start", "force_taken_constant", "efficiency_inverted", "spring_omitted",
    "load_at_other_point", "contact_taken_smooth", "period_for_frequency",
    "spring_energy_from_change", "impact_taken_head_on", "reaction_omitted",
    "pin_impulse_omitted", "translational_ke_omitted", "rolling_assumed",
    "initial_displacement_omitted", "spring_energy_half_omitted", "angmom_along_axis",
    "spring_force_as_resultant", "part_moving_with_centre",
    "striker_stops", "mean_of_end_rates",
    "end_speed_throughout", "transverse_speed_kept", "energy_kept_in_coupling",
    "parallel_axis_with_radius", "weight_along_surface_omitted",
    "damped_for_natural")
"""Family codes of the dynamics mutations (:mod:`mechgrade.mechanics.dynamics_mutations`)."""

GIVEN_CODES = ("given_deg_as_rad", "given_complement", "given_rate_unit", "given_length_unit",
               "given_sign", "given_swap", "given_unit", "given_angle_sign",
               "given_acceleration_zero")
"""Family codes of mistaken givens (:mod:`mechgrade.solve.mutants`)."""

BRANCH_CODES = ("other_assembly_branch",)
"""Family codes of another root of the position level than the spec's
(:mod:`mechgrade.solve.mutants`)."""
