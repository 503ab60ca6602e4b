"""The dynamics solver: answers, symbolic and numeric agreement, and the models it must refuse
(under-constrained, statically indeterminate, missing reactions, slipping, lost contact)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mechgrade.errors import InconsistentError, SolveError, UnderdeterminedError
from mechgrade.expressions.build import to_sympy
from mechgrade.expressions.syntax import parse, to_text
from mechgrade.solve import solve
from mechgrade.spec import load_problem, load_problem_text
from mechgrade.spec.validate import symbol_meanings

ROOT = Path(__file__).resolve().parents[2]
DYNAMICS = sorted(p for p in (ROOT / "problems").glob("*.yaml")
                  if "bodies:" in p.read_text())


def text(name: str) -> str:
    return (ROOT / "problems" / f"{name}.yaml").read_text()


def solve_text(body: str):
    return solve(load_problem_text(body, "p.yaml"))


def error_of(body: str, kind=SolveError, objectives=None) -> str:
    with pytest.raises(kind) as info:
        solution = solve(load_problem_text(body, "p.yaml"), objectives=objectives)
        for failure in solution.failures:
            raise failure.error
    return str(info.value)


@pytest.mark.parametrize("path", DYNAMICS, ids=[p.stem for p in DYNAMICS])
def test_symbolic_answers_agree_with_the_numeric_solution(path):
    """Each symbolic objective, evaluated at the givens, equals the same quantity solved
    numerically (the problem re-solved with the objective's find as a scalar)."""
    problem = load_problem(path)
    solution = solve(problem)
    for obj in problem.objectives:
        if obj.kind != "symbolic":
            continue
        reference, state = _numeric_value(problem, obj)
        values = {name: state[to_text(node)]
                  for name, node in symbol_meanings(problem, obj).items()}
        result = solution.result(obj.id)
        expr = to_sympy(parse(result.expr), lambda n, values=values: values[n.id], None)
        assert float(expr) == pytest.approx(reference, rel=1e-9, abs=1e-12), obj.id


def _numeric_value(problem, obj):
    """The objective solved as a scalar, and the solved state it was read in."""
    from dataclasses import replace
    twin = replace(obj, kind="scalar", symbols=(), expect=None, id=obj.id + "_numeric")
    solution = solve(replace(problem, objectives=(twin,)))
    return solution.result(twin.id).value, {s.name: s.si for s in solution.state}


def test_statically_indeterminate_model_names_the_reactions():
    body = text("ruina_9_19_falling_ladder").replace(
        "    N2: {kind: normal, body: ladder, at: B, direction: N.y}          # floor\n",
        "    N2: {kind: normal, body: ladder, at: B, direction: N.y}          # floor\n"
        "    N3: {body: ladder, at: B, direction: N.y}\n")
    message = error_of(body, UnderdeterminedError, objectives=["thetaddot_now"])
    assert "the model is statically indeterminate" in message
    assert "N2 (along N.y), N3 (along N.y)" in message
    assert message.startswith("p.yaml:")


def test_under_constrained_model_names_the_free_acceleration():
    body = text("atwood_machine").replace("coordinates:\n  y: m\n",
                                          "coordinates:\n  y: m\n  s: m\n")
    body = body.replace("  y': 0 m/s\n", "  y': 0 m/s\n  s: 0 m\n  s': 0 m/s\n")
    message = error_of(body, UnderdeterminedError, objectives=["a1"])
    assert "the model is under-constrained" in message and "do not determine s''" in message


def test_a_missing_reaction_is_an_inconsistency_naming_the_balance():
    body = text("pendulum_pin_reaction").replace(
        "  reactions:\n    R_O: {kind: pin, body: rod, at: O, directions: [N.x, N.y]}\n", "")
    body = body.replace("force(R_O)", "m*acc(G, N)")
    message = error_of(body, InconsistentError, objectives=["alpha"])
    assert "the equations of motion cannot all hold: 'body rod: N.x force balance'" in message


def test_a_given_acceleration_that_contradicts_the_loads_is_reported():
    body = text("atwood_machine").replace("  y': 0 m/s\n", "  y': 0 m/s\n  y'': 1 m/s^2\n")
    assert "cannot all hold" in error_of(body, InconsistentError, objectives=["a1"])


def test_static_friction_bound_violated_says_how_large_mu_must_be():
    body = text("block_on_turntable").replace("  mu_s: 0.6\n", "  mu_s: 0.3\n")
    message = error_of(body)
    assert "the block slips at P: sticking needs mu >= 0.493" in message
    assert "but mu = 0.3" in message


def test_kinetic_friction_without_slip_asks_for_static_friction():
    body = text("block_sliding_down_incline").replace("  x': 2 m/s\n", "  x': 0 m/s\n")
    assert "needs the contact at P to slip" in error_of(body)


def test_kinetic_friction_contact_that_would_pull_is_lost():
    body = text("block_sliding_down_incline").replace("gravity: -g*N.y", "gravity: g*N.y")
    assert "contact lost at P" in error_of(body)


def test_a_composite_part_that_moves_in_its_body_is_refused():
    body = text("ruina_9_21_wheel_incline").replace(
        "      - {mass: M, at: G, inertia: {disk: {radius: R, axis: z}}}\n"
        "      - {mass: M, at: G,",
        "      - {mass: M, at: G, inertia: {disk: {radius: R, axis: z}}}\n"
        "      - {mass: M, at: C,")
    assert "moves relative to its frame W" in error_of(body)


def test_parallel_axis_inertia_of_a_rod_with_a_point_mass():
    """A composite pendulum (rod plus a point mass at the tip) swings like its textbook
    inertia about the pin: (m L^2/3 + M L^2) theta'' = -(m L/2 + M L) g sin(theta)."""
    body = text("pendulum_pin_reaction").replace(
        "  rod: {mass: m, centre: G, frame: B, inertia: {rod: {length: L, axis: y}}}\n",
        "  rod:\n    frame: B\n    parts:\n"
        "      - {mass: m, at: G, inertia: {rod: {length: L, axis: y}}}\n"
        "      - {mass: m, at: T}\n").replace(
        "  G: {from: O, position: -L/2*B.y}\n",
        "  G: {from: O, position: -L/2*B.y}\n  T: {from: O, position: -L*B.y}\n")
    solution = solve_text(body)
    m, L, g, th = 2.0, 1.2, 9.81, np.radians(40)
    expected = -(m * L / 2 + m * L) * g * np.sin(th) / (m * L**2 / 3 + m * L**2)
    assert solution.result("alpha").value == pytest.approx(expected, rel=1e-12)
    assert solution.result("eom_symbolic").expr == "-9*g*sin(theta)/(8*L)"


def test_integration_conserves_energy_and_finds_the_event_to_1e_6():
    """The ladder released at 80 deg: mechanical energy at the lift-off event equals the
    start's (drift below 1e-9 relative), and the event angle is asin(2/3 sin 80 deg)."""
    solution = solve(load_problem(ROOT / "problems" / "ladder_wall_lift_off.yaml"))
    m, L, g = 12.0, 4.0, 9.81
    start = m * g * L / 2 * np.sin(np.radians(80))
    assert solution.result("energy_at_lift_off").value == pytest.approx(start, rel=1e-9)
    expected = np.degrees(np.arcsin(2 / 3 * np.sin(np.radians(80))))
    assert solution.result("theta_wall_contact_lost_deg").value == pytest.approx(expected,
                                                                                 rel=1e-8)


def test_rolling_time_is_the_same_for_a_marble_and_a_bowling_ball():
    """Sample 9.22: t* = 2 v0 / (7 mu g) does not depend on the radius or the mass."""
    body = text("ruina_9_23_ball_impulse_momentum")
    marble = solve_text(body).result("t_star").value
    bowling = solve_text(body.replace("  r: 0.1 m\n", "  r: 1.6 m\n").replace(
        "  m: 1 kg\n", "  m: 4096 kg\n")).result("t_star").value
    assert bowling == pytest.approx(marble, rel=1e-9)
    assert marble == pytest.approx(2 * 5 / (7 * 0.12 * 9.8), rel=1e-9)


def test_an_event_that_never_happens_is_reported():
    body = text("ladder_wall_lift_off").replace("max_time: 10 s", "max_time: 0.2 s")
    assert "does not happen within 0.2 s" in error_of(body)


def _rolls_on_past_its_slip() -> str:
    """The bowling ball asked to stop translating: its slip ends (t = 1.21 s) long before."""
    return text("ruina_9_23_ball_impulse_momentum").replace(
        "until: x' + r*phi' = 0", "until: x' = 0")


def test_a_slip_that_ends_and_sticks_before_the_event_is_refused_with_the_fix():
    error = error_of(_rolls_on_past_its_slip())
    assert "a kinetic-friction slip ends at t = 1.21477 s, before the event" in error
    assert "or the end of the slip as the event" in error


def test_an_integration_that_chatters_past_the_end_of_slip_is_stopped(monkeypatch):
    """Where the sticking is not recognised (a chatter of another cause), the one-by-one
    integrator's own limit stops it, with its own message."""
    from mechgrade.solve import events, phases

    monkeypatch.setattr(events, "MAX_CALLS", 4000)
    monkeypatch.setattr(phases._Columns, "stuck", lambda self, *args: {})
    assert "the integration stalls near t = 1.2" in error_of(_rolls_on_past_its_slip())


def test_symbolic_objective_of_an_integrated_motion_is_in_closed_form():
    """The distance slid before rolling: v0 t* - mu g t*^2/2 with t* = 2 v0/(7 mu g)."""
    body = text("ruina_9_23_ball_impulse_momentum").replace(
        "    find: x\n    kind: scalar\n    unit: m\n    expect: {value: 5.2061641}",
        "    find: x\n    kind: symbolic\n    unit: m\n    symbols: [v0, mu, g]\n"
        "    expect: {expr: 12*v0**2/(49*mu*g)}")
    result = solve_text(body).result("distance_to_pure_rolling")
    assert result.expr == "12*v0**2/(49*g*mu)"


def test_a_symbolic_answer_of_an_integration_declares_what_it_depends_on():
    body = text("ruina_9_23_ball_impulse_momentum").replace(
        "    find: x\n    kind: scalar\n    unit: m\n    expect: {value: 5.2061641}",
        "    find: x\n    kind: symbolic\n    unit: m\n    symbols: [v0]\n    expect: {expr: v0}")
    assert "which is not among its symbols (v0); add it to symbols" in error_of(body)


def test_work_energy_refuses_non_conservative_loads():
    body = text("ruina_9_20_ladder_energy").replace(
        "    N2: {kind: normal, body: ladder, at: B, direction: N.y}\n",
        "    N2: {kind: normal, body: ladder, at: B, direction: N.y}\n  friction:\n"
        "    F2: {body: ladder, at: B, normal: N2, mu: 0.3, kind: kinetic}\n")
    assert "work_energy needs conservative loads: F2" in error_of(body, objectives=[
        "vG_over_sqrt_gL"])


def test_work_energy_needs_the_sense_of_the_rate():
    body = text("ruina_9_20_ladder_energy").replace(
        "    sense: {theta': negative}             # falling\n", "")
    assert "give 'sense'" in error_of(body, objectives=["vG_over_sqrt_gL"])


def test_work_energy_refuses_an_unreachable_instant():
    body = text("ruina_9_20_ladder_energy").replace("  theta: 45 deg\n", "  theta: 85 deg\n")
    assert "cannot be reached from the start state" in error_of(body, objectives=[
        "vG_over_sqrt_gL"])


def test_work_energy_refuses_a_reaction_that_works():
    """A reaction pushing along the motion of its point is not workless."""
    body = text("ruina_9_20_ladder_energy").replace(
        "N1: {kind: normal, body: ladder, at: A, direction: N.x}",
        "N1: {body: ladder, at: A, direction: N.y}")  # reactions of unstated kind: no normal check
    body = body.replace("N2: {kind: normal, body: ladder, at: B, direction: N.y}",
                        "N2: {body: ladder, at: B, direction: N.x}")
    assert "does work at the instant" in error_of(body, objectives=["vG_over_sqrt_gL"])


def test_steps_show_the_parallel_axis_shift_balances_and_unknowns():
    from mechgrade.mechanics import derivation

    body = text("pendulum_pin_reaction").replace(
        "  rod: {mass: m, centre: G, frame: B, inertia: {rod: {length: L, axis: y}}}\n",
        "  rod:\n    frame: B\n    centre: O\n    parts:\n"
        "      - {mass: m, at: G, inertia: {rod: {length: L, axis: y}}}\n")
    sections = dict(derivation(load_problem_text(body, "p.yaml")))
    assert sections["Bodies"][1] == ("  part of mass m at G: I_G = [L**2*m/12, 0, 0; 0, 0, 0; "
                                     "0, 0, L**2*m/12]; shifted to O by r = - L/2*B.y: "
                                     "I + m (|r|^2 U - r r)")
    assert sections["Bodies"][2] == "  I_O (in B axes) = [L**2*m/3, 0, 0; 0, 0, 0; 0, 0, L**2*m/3]"
    assert "rod: gravity at G: - g*m*N.y; R_O at O: R_O_1*N.x + R_O_2*N.y" in \
        sections["Free-body loads"]
    assert sections["Solution"][1] == "unknowns: theta'', R_O (along N.x), R_O (along N.y) " \
                                      "(those not given)"
    assert "alpha: eom(theta) = thetadd" in sections["Objectives in the model's quantities"]


@pytest.mark.slow
def test_vibration_away_from_an_equilibrium_is_refused():
    body = text("damped_pendulum_vibration").replace("  theta: 0 rad\n", "  theta: 10 deg\n")
    message = error_of(body, objectives=["omega_n"])
    assert "objective 'omega_n' does not exist at this instant: the configuration is not an " \
           "equilibrium (theta'' is not zero at rest there)" in message


def test_vibration_needs_one_degree_of_freedom():
    body = text("two_mass_spring_chain").replace("find: ke(block2, N)\n    kind: scalar\n    unit: J",
                                                 "find: omega_n(x1)\n    kind: scalar\n    unit: rad/s")
    body = body.replace("expect: {value: 0.02}", "expect: {value: 1}")
    assert "omega_n and zeta need a single coordinate" in error_of(body)


def test_impulse_needs_an_impact_and_an_impact_reaction_is_no_force():
    body = text("ruina_9_26_billiard_cue")
    assert "impulse(P) needs an impact" in error_of(body.replace(
        "analysis:\n  impulse:\n    before: {x': 0 m/s, phi': 0 rad/s}           # at rest\n",
        ""))
    assert "ask for impulse(P)" in error_of(body.replace("mag(impulse(P))\n    kind: scalar\n"
                                                         "    unit: N*s",
                                                         "mag(force(P))\n    kind: scalar\n"
                                                         "    unit: N"))


def test_an_impact_does_not_change_the_configuration():
    body = text("ruina_9_26_billiard_cue").replace("before: {x': 0 m/s,", "before: {x: 0 m,")
    from mechgrade.errors import SpecError
    with pytest.raises(SpecError, match="expected a rate"):
        load_problem_text(body, "p.yaml")


def test_a_gripping_impact_conserves_angular_momentum_about_the_contact():
    """The rod's end sticks to the ledge: it turns about A with H_A conserved,
    (m L^2/3) w' = -m v0 L/2."""
    body = text("rod_strikes_ledge").replace(
        "P: {body: rod, at: A, direction: N.y}", "P: {body: rod, at: A, directions: [N.x, N.y]}")
    body = body.replace("      - {at: A, bodies: [rod, ground], direction: N.y, restitution: e}",
                        "      - {at: A, bodies: [rod, ground], directions: [N.x, N.y]}")
    solution = solve(load_problem_text(body, "p.yaml"), objectives=["omega_after"])
    assert solution.result("omega_after").value == pytest.approx(-3 * 4.0 / (2 * 1.2), rel=1e-12)


@pytest.mark.parametrize("old, new, message", [
    ("{at: A, bodies: [rod, ground]", "{at: Z, bodies: [rod, ground]", "unknown point 'Z'"),
    ("bodies: [rod, ground], direction", "bodies: [rod, floor], direction", "unknown body 'floor'"),
    ("direction: N.y, restitution: e}", "direction: L*N.y, restitution: e}",
     "expected a direction (a vector without units, e.g. N.y), found 'L*N.y'"),
    ("restitution: e}", "restitution: L}", "expected a pure number for the coefficient"),
])
def test_bad_impact_contact_is_located(old, new, message):
    from mechgrade.errors import SpecError
    with pytest.raises(SpecError) as info:
        load_problem_text(text("rod_strikes_ledge").replace(old, new), "p.yaml")
    assert message in str(info.value) and str(info.value).startswith("p.yaml:")


def test_design_of_an_unreachable_target_is_reported():
    body = text("ruina_9_21_wheel_incline").replace("= 0.2*g", "= 0.9*g")
    assert "design: no value of R near 0.15 (SI) makes dot(acc(G, N), A.x) = 0.9*g" in \
        error_of(body, objectives=["R_min"])


def test_design_parameter_must_not_be_given():
    from mechgrade.errors import SpecError
    body = text("ruina_9_21_wheel_incline").replace("  r: 0.1 m\n", "  r: 0.1 m\n  R: 0.2 m\n")
    with pytest.raises(SpecError, match="design 'find' must name a parameter that is not given"):
        load_problem_text(body, "p.yaml")


@pytest.mark.parametrize("find, name", [("dot(before(acc(P1, N)), N.y)", "before"),
                                        ("after(y'')", "after"),
                                        ("before(ke(block1, N))/(m1*d)", "before")])
def test_before_and_after_need_an_impact(find, name):
    body = text("atwood_machine").replace("find: y''", f"find: {find}", 1)
    assert f"{name}(...) needs an impact: 'analysis: impulse'" in error_of(body)


def test_before_and_after_read_a_scalar_across_the_impact():
    """The rod struck on its end by a ledge (e = 0.5) loses (1 - e^2) m v0^2 / 8: of
    24 J before, 19.5 J are left."""
    body = text("rod_strikes_ledge").replace("tags: [impact", """  - id: ke_before
    prompt: x
    find: before(ke(rod, N))
    kind: scalar
    unit: J
  - id: ke_after
    prompt: x
    find: after(ke(rod, N))
    kind: scalar
    unit: J
tags: [impact""")
    solution = solve_text(body)
    assert solution.result("ke_before").value == pytest.approx(24.0, rel=1e-12)
    assert solution.result("ke_after").value == pytest.approx(19.5, rel=1e-12)


def test_a_known_impulse_is_asked_for_as_an_impulse():
    body = text("rod_struck_on_ice").replace("find: dot(angvel(R, N), N.z)\n    kind: scalar\n"
                                             "    unit: rad/s",
                                             "find: mag(force(hammer))\n    kind: scalar\n"
                                             "    unit: N")
    assert "during an impact hammer is an impulse: ask for impulse(hammer)" in error_of(body)


def test_a_known_impulse_adds_to_the_impulsive_reactions():
    """The hammer's impulse acts with the impulsive reactions: the same blow on a rod pinned at
    its centre only spins it, and the pin takes no impulse (centre of percussion aside)."""
    body = text("rod_struck_on_ice").replace(
        "loads:\n", "loads:\n  reactions:\n    pin: {body: rod, at: G, directions: [N.x, N.y]}\n")
    body = body.replace("givens:\n", "givens:\n  x': 0 m/s\n  y': 0 m/s\n")
    solution = solve_text(body)
    assert solution.result("omega_after").value == pytest.approx(10.0)
    assert solution.result("vG_after").value == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)


@pytest.mark.slow
def test_symbolic_answer_of_an_integration_needs_constant_accelerations():
    body = text("ladder_wall_lift_off").replace(
        "    find: theta\n    kind: scalar\n    unit: deg\n    expect: {value: 41.036426}",
        "    find: theta\n    kind: symbolic\n    unit: deg\n    symbols: [g]\n"
        "    expect: {expr: g}", 1)
    message = error_of(body, objectives=["theta_wall_contact_lost_deg"])
    assert "needs accelerations that stay constant until the event" in message


def test_symbolic_answer_of_an_integration_needs_the_slip_direction():
    body = text("ruina_9_23_ball_impulse_momentum").replace(
        "  v0: m/s\n", "  v0: {unit: m/s, positive: false}\n")
    body = body.replace("    find: t\n    kind: scalar\n    unit: s\n",
                        "    find: t\n    kind: symbolic\n    unit: s\n"
                        "    symbols: [v0, mu, g]\n", 1)
    body = body.replace("      value: 1.2147716\n", "      expr: 2*v0/(7*mu*g)\n")
    message = error_of(body, objectives=["t_star"])
    assert "needs every slip's direction fixed" in message


def test_an_integration_in_closed_form_agrees_with_the_numerical_event():
    """Sample 9.23's event time from the closed form equals the integrated one."""
    body = text("ruina_9_23_ball_impulse_momentum").replace(
        "    find: t\n    kind: scalar\n    unit: s\n",
        "    find: t\n    kind: symbolic\n    unit: s\n    symbols: [v0, mu, g]\n", 1)
    body = body.replace("      value: 1.2147716\n", "      expr: 2*v0/(7*mu*g)\n")
    solution = solve_text(body)
    assert solution.result("t_star").expr == "2*v0/(7*g*mu)"
    t_numeric = solution.result("t_star_if_mu_0p2").value
    assert t_numeric == pytest.approx(2 * 5.0 / (7 * 0.2 * 9.8), rel=1e-8)


def test_a_mode_number_beyond_the_coordinates_is_refused():
    body = text("two_mass_spring_chain").replace("find: mode_frequency(2)", "find: mode_frequency(3)")
    assert "expected a mode number 1 to 2 (the coordinates), found '3'" in error_of(body)


def test_natural_modes_need_an_equilibrium():
    body = text("two_mass_spring_chain").replace(
        "    find: mode_frequency(1)\n    kind: scalar\n    unit: rad/s\n"
        "    givens: {x1: 0.5 m, x2: 1.3 m, \"x1'\": 0 m/s, \"x2'\": 0 m/s}   # the equilibrium\n",
        "    find: mode_frequency(1)\n    kind: scalar\n    unit: rad/s\n")
    message = error_of(body, objectives=["omega_1"])
    assert "objective 'omega_1' does not exist at this instant: the configuration is not an " \
           "equilibrium" in message


def test_natural_modes_need_unconstrained_coordinates():
    body = text("ruina_9_21_wheel_incline").replace(
        "    find: R\n    kind: scalar\n    unit: m\n",
        "    find: mode_frequency(1)\n    kind: scalar\n    unit: rad/s\n")
    assert "natural modes need coordinates without constraints" in error_of(body)


def test_a_mode_shape_is_a_ratio_of_the_coordinates_units():
    from mechgrade.errors import SpecError
    body = text("two_mass_spring_chain").replace(
        "find: mode_shape(1, x2, x1)\n    kind: scalar\n    unit: \"1\"",
        "find: mode_shape(1, x2, x1)\n    kind: scalar\n    unit: m")
    with pytest.raises(SpecError, match="dimension mismatch in objective 'mode_1_ratio'"):
        load_problem_text(body, "p.yaml")


def test_a_closed_form_event_needs_a_positive_time():
    body = text("ruina_9_23_ball_impulse_momentum").replace(
        "until: x' + r*phi' = 0", "until: x' + r*phi' = 2*v0")
    body = body.replace("    find: t\n    kind: scalar\n    unit: s\n",
                        "    find: t\n    kind: symbolic\n    unit: s\n"
                        "    symbols: [v0, mu, g]\n", 1)
    body = body.replace("      value: 1.2147716\n", "      expr: 2*v0/(7*mu*g)\n")
    assert "the event of the integrated motion has no closed-form time" in \
        error_of(body, objectives=["t_star"])


def test_a_closed_form_integration_needs_determined_accelerations():
    body = text("block_slides_on_cart").replace(
        "    N_F: {kind: normal, body: cart, at: K, direction: N.y}",
        "    N_F: {kind: normal, body: cart, at: K, direction: N.y}\n"
        "    N_G: {body: cart, at: K, direction: N.y}")
    body = body.replace("    find: t\n    kind: scalar\n    unit: s\n    expect: {value: 1.359157}",
                        "    find: t\n    kind: symbolic\n    unit: s\n    symbols: [v0, mu, g, m, M]\n"
                        "    expect: {expr: v0/(mu*g*(1 + m/M))}")
    assert "are not determined symbolically" in error_of(body, objectives=["t_slide"])


STUCK_ON_CART = """
id: p
title: A block carried by a pushed cart
source: test
statement: A push P0 on the cart; the block does not slip on it.
inertial: {frame: N, point: O}
points:
  B: {from: O, position: x*N.x + h*N.y}
  P: {from: B, position: -h/2*N.y}
  K: {from: O, position: X*N.x}
coordinates: {x: m, X: m}
parameters: {m: kg, M: kg, mu: "1", g: m/s^2, h: m, P0: N}
constraints:
  - name: stuck
    position: x = X
bodies:
  block: {mass: m, centre: B}
  cart: {mass: M, centre: K}
loads:
  gravity: -g*N.y
  forces:
    push: {body: cart, at: K, force: P0*N.x}
  reactions:
    N_P: {bodies: [block, cart], at: P, direction: N.y}
    N_F: {body: cart, at: K, direction: N.y}
  friction:
    F_P: {body: block, at: P, normal: N_P, mu: mu, kind: static, direction: N.x, surface: cart}
givens: {m: 2 kg, M: 8 kg, mu: 0.3, g: 9.81 m/s^2, h: 0.5 m, P0: 20 N, x: 0 m, X: 0 m,
         "x'": 1 m/s}
objectives:
  - id: friction
    prompt: The friction force on the block.
    find: force(F_P)
    kind: vector
    frame: N
    unit: N
  - id: cart_net
    prompt: The push plus the friction on the cart (the block's friction reversed).
    find: m*acc(B, N) + M*acc(K, N) - force(push)
    kind: vector
    frame: N
    unit: N
"""


def test_static_friction_between_two_bodies_acts_on_both():
    solution = solve_text(STUCK_ON_CART)
    assert solution.result("friction").value == pytest.approx((4.0, 0.0, 0.0))
    # the whole system's horizontal momentum changes by the push alone
    assert solution.result("cart_net").value[0] == pytest.approx(0.0, abs=1e-12)


def test_static_friction_between_two_bodies_is_bounded():
    message = error_of(STUCK_ON_CART.replace("P0: 20 N", "P0: 40 N"))
    assert "the block slips at P: sticking needs mu >= 0.4077" in message


def test_integrations_keep_their_energy_books():
    """The kinetic energy the friction between block and cart took is mu m g times the
    distance slid; the flywheel's lost energy is the punch's work M phi."""
    cart = solve(load_problem(ROOT / "problems" / "block_slides_on_cart.yaml"))
    lost, slid = cart.result("energy_lost").value, cart.result("slide_distance").value
    assert lost == pytest.approx(0.3 * 2 * 9.81 * slid, rel=1e-9)
    flywheel = solve(load_problem(ROOT / "problems" / "flywheel_speed_drop.yaml"))
    turned = np.radians(flywheel.result("turns_during_stroke").value)
    assert flywheel.result("energy_taken").value == pytest.approx(1500 * turned, rel=1e-9)


def test_a_problem_s_instants_are_reached_by_the_kind_its_analysis_names():
    from mechgrade.solve.dynamics import (DesignedInstant, IntegratedInstant, KineticInstant,
                                          kinetic_reach)

    pendulum = kinetic_reach(load_problem(ROOT / "problems" / "pendulum_pin_reaction.yaml"))
    flywheel = kinetic_reach(load_problem(ROOT / "problems" / "flywheel_speed_drop.yaml"))
    assert type(pendulum) is KineticInstant  # its rates given
    assert type(flywheel) is DesignedInstant and type(flywheel.inner) is IntegratedInstant


def test_a_design_newton_overshoots_is_bracketed_from_the_guess():
    # R = 0.618 m; from a guess of 4 m Newton's method on 0.1 w0 - 2 M T/(m R²) leaves for R < 0
    body = text("flywheel_speed_drop").replace("guess: 0.5 m", "guess: 4 m")
    solution = solve(load_problem_text(body, "p.yaml"), objectives=["R_needed"])
    assert solution.result("R_needed").value == pytest.approx(0.618039, rel=1e-6)


def test_a_designs_trial_values_reached_together_are_each_as_alone():
    """Newton's and the bracketing scan's values of the design parameter are the columns of
    one integration: each the state at the event its integration alone gives, or its error
    (R = 0: no inertia)."""
    from mechgrade.expressions.syntax import Name
    from mechgrade.solve.dynamics import kinetic_reach
    from mechgrade.solve.instant import instant_givens

    problem = load_problem(ROOT / "problems" / "flywheel_speed_drop.yaml")
    inner = kinetic_reach(problem).inner
    assert inner is not None
    given_map = instant_givens(problem, None, {})
    maps = [{**given_map, "R": (Name("R"), r, None)} for r in (0.3, 1.2, 0.0)]
    together = inner.at_events(maps)
    for given, x in zip(maps[:2], together):
        assert isinstance(x, np.ndarray)
        np.testing.assert_allclose(x, inner.reached(given, None).x, rtol=1e-12)
    with pytest.raises(UnderdeterminedError) as alone:
        inner.reached(maps[2], None)
    assert str(together[2]) == str(alone.value)


@pytest.mark.parametrize("mu, v0", [(0.2, 4.0), (0.25, 5.0), (0.3, 3.0), (0.3, 4.0),
                                    (0.35, 6.5)])
def test_friction_whose_slip_ends_at_the_event_is_its_limit_just_before(mu, v0):
    # force(F_P) at the event where the slip ends: its direction is 0/0 there, and these
    # givens gave +mu m g or "undefined" as rounding fell; the limit just before is -mu m g
    problem = load_problem(ROOT / "problems" / "block_slides_on_cart.yaml")
    solution = solve(problem, givens={"mu": mu, "v0": v0}, objectives=["friction_on_block"])
    assert not solution.failures
    force = solution.result("friction_on_block").value
    assert np.allclose(force, (-mu * 2 * 9.81, 0, 0), rtol=1e-7, atol=1e-9)


THREE_CARTS = (ROOT / "tests" / "data" / "vibration" / "three_carts_at_rest.yaml").read_text()


def _three_carts_with(objective: str) -> str:
    return THREE_CARTS + objective


@pytest.mark.parametrize("objective,message", [
    ("  - {id: w, prompt: w, find: mode_frequency(1), kind: symbolic, unit: rad/s,\n"
     "     symbols: [k1, m1]}\n",
     "p.yaml:67:5: objectives[3]: natural modes in symbols are worked out for one or two "
     "coordinates; this problem has 3: expected 'kind: scalar' (worked out with numbers), "
     "found 'kind: symbolic'"),
    ("  - {id: z, prompt: z, find: mode_damping(1), kind: symbolic, unit: '1',\n"
     "     symbols: [c, k1, m1]}\n",
     "p.yaml:67:5: objectives[3]: a mode's damping ratio in symbols is worked out for one "
     "coordinate; this problem has 3: expected 'kind: scalar' (worked out with numbers), "
     "found 'kind: symbolic'"),
    ("  - {id: w, prompt: w, find: mode_frequency(4), kind: scalar, unit: rad/s}\n",
     "p.yaml:67:5: objectives[3]: expected a mode number 1 to 3 (the coordinates), found '4'"),
    ("  - {id: r, prompt: r, find: 'mode_shape(1.5, x3, x1)', kind: scalar, unit: '1'}\n",
     "p.yaml:67:5: objectives[3]: expected a mode number 1 to 3 (the coordinates), found "
     "'1.5'"),
], ids=["symbolic-frequency", "symbolic-damping", "mode-beyond", "mode-not-whole"])
def test_natural_modes_of_three_coordinates_refuse_what_they_cannot_give(objective, message):
    assert error_of(_three_carts_with(objective)) == message


@pytest.mark.slow
def test_natural_modes_of_three_coordinates_exist_only_about_an_equilibrium_and_not_free():
    """Worked out with numbers: the three-cart chain's values are those of
    problems/three_cart_chain_vibration.yaml (independently derived); an overdamped mode has
    the damping ratio of its two real roots (c = 2000 N s/m: -666.317 and -0.200120, the real
    roots of det(l^2 M + l C + K) by numpy.roots, zeta 28.8599; its product 133.3 puts it
    between the pairs at 9.02 and 19.2 rad/s); a state away from equilibrium, or the damping
    ratio of a mode that moves freely (k1 = 0), is refused where the objective is."""
    body = _three_carts_with(
        "  - {id: away, prompt: a, find: mode_frequency(1), kind: scalar, unit: rad/s,\n"
        "     givens: {x1: 0.1 m}}\n"
        "  - {id: overdamped, prompt: o, find: mode_damping(2), kind: scalar, unit: '1',\n"
        "     givens: {c: 2000 N*s/m}}\n"
        "  - {id: free, prompt: f, find: mode_damping(1), kind: scalar, unit: '1',\n"
        "     givens: {k1: 0 N/m}}\n")
    solution = solve(load_problem_text(body, "p.yaml"))
    assert [round(solution.result(i).value, 6) for i in ("omega_3", "zeta_1")] == \
        [20.510677, 0.056460]
    assert solution.result("overdamped").value == pytest.approx(28.85993453, rel=1e-8)
    errors = {f.id: str(f.error) for f in solution.failures}
    assert errors == {
        "away": "p.yaml:67:5: objectives[3]: objective 'away' does not exist at this instant: "
                "the configuration is not an equilibrium (a second rate is not zero at rest "
                "there): give the equilibrium's coordinates and zero rates among the "
                "objective's givens",
        "free": "p.yaml:71:5: objectives[5]: objective 'free' does not exist at this instant: "
                "mode 1 moves freely (its natural frequency is zero: a rigid-body motion), so "
                "it has no damping ratio"}


GUN_RECOIL = ROOT / "tests" / "data" / "vibration" / "gun_recoil_critical_damping.yaml"


@pytest.mark.parametrize("k, m", [(18e3, 800.0), (13.69, 1.0), (400.0, 3.0), (1e4, 7.0)])
def test_a_design_finds_the_damper_coefficient_for_critical_damping(k, m):
    """mode_damping(1) = 1 is solved for c: 2 sqrt(k m) by hand. The damping ratio is
    continuous through 1 (numpy's double root comes out real, or a pair ~1e-8 off the axis,
    as k and m fall), where it used to jump to undefined and Newton found no root."""
    solution = solve(load_problem(GUN_RECOIL), givens={"k": k, "m": m},
                     objectives=["c_critical", "omega_n"])
    assert not solution.failures
    assert solution.result("c_critical").value == pytest.approx(2 * np.sqrt(k * m), rel=1e-9)
    assert solution.result("omega_n").value == pytest.approx(np.sqrt(k / m), rel=1e-12)


def test_an_overdamped_and_an_underdamped_single_mode_have_their_damping_ratios():
    # c / (2 sqrt(k m)) by hand: 10000/7589.47 and 5000/7589.47
    solution = solve(load_problem(GUN_RECOIL), objectives=["zeta_overdamped",
                                                           "zeta_underdamped"])
    critical = 2 * np.sqrt(18e3 * 800.0)
    assert [solution.result(i).value for i in ("zeta_overdamped", "zeta_underdamped")] == \
        pytest.approx([10e3 / critical, 5e3 / critical], rel=1e-12)


def test_natural_modes_in_symbols_too_large_to_finish_are_refused(monkeypatch):
    from mechgrade.mechanics import dynamics
    monkeypatch.setattr(dynamics, "SYMBOLIC_MODE_OPS", 0)
    body = text("two_mass_spring_chain").replace(
        "find: mode_frequency(1)\n    kind: scalar\n",
        "find: mode_frequency(1)\n    kind: symbolic\n    symbols: [k1, k2, m1, m2]\n").replace(
        "    expect: {value: 5.0}\n", "")
    assert error_of(body) == (
        "p.yaml:95:5: objectives[7]: natural modes in symbols are out of reach for this model "
        "(an entry of its stiffness matrix has 34 operations, more than 0): expected "
        "'kind: scalar' (worked out with numbers), found 'kind: symbolic'")


def test_an_acceleration_read_as_a_slip_ends_keeps_the_digits_of_its_friction_direction():
    """The cart's acceleration is read just before the block stops slipping on it, where the
    slip (5e-9 m/s) is small beside the speeds (1 m/s): the balances' u/|u| written as one
    sum per speed lost 1e-8 of it (0.7357499927)."""
    solution = solve(load_problem_text(text("block_slides_on_cart"), "p.yaml"))
    value = {r.id: r.value for r in solution.results}["cart_acceleration"]
    assert value == pytest.approx(0.3 * 2.0 * 9.81 / 8.0, rel=1e-13)


def test_three_carts_residuals_are_compiled_per_spring_with_the_expanded_balances_values():
    """Each spring's force k l (1 - a/|l|) as one product has fewer operations than the
    balances expanded (4-5 terms over |l| each): the residual of an instant and the
    integration's right-hand side (each |l| a mode times l) are compiled from that form,
    and their values are the expanded balances' at any state."""
    from inspect import getsource

    import sympy as sp

    from mechgrade.solve.dynamics import kinetics_plan
    from mechgrade.solve.motion import _operations, _switches, cheaper

    def operations(f) -> int:  # arithmetic in the compiled source
        return sum(getsource(f).count(c) for c in "+-*/")

    plan = kinetics_plan(load_problem(ROOT / "problems" / "three_cart_chain_vibration.yaml"))
    kin = plan.kin
    constraints = [e.expr for e in kin.constraints]
    expanded = sp.Matrix([e.expr for e in kin.written] + constraints)
    compact = sp.Matrix(list(kin.compact) + constraints)
    assert _operations(cheaper(compact, expanded)) < _operations(expanded)
    written = sp.lambdify(plan.symbols, expanded, modules="numpy", cse=True)
    switching = _switches(plan)
    assert operations(plan.residual) < operations(written)
    assert operations(switching.residual) < operations(written)
    rng = np.random.default_rng(7)
    for _ in range(20):
        state = rng.uniform(0.1, 3.0, len(plan.symbols)) * rng.choice([-1.0, 1.0],
                                                                       len(plan.symbols))
        want = np.asarray(written(*state), dtype=float).ravel()
        modes = np.sign(np.asarray(switching.speeds(*state), dtype=float))
        for got in (plan.residual(*state), switching.residual(*state, *modes)):
            assert np.asarray(got, dtype=float).ravel() == pytest.approx(
                want, rel=1e-12, abs=1e-12 * np.abs(want).max())
