"""The solver derives answers from the model, and names what is missing or conflicting."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mechgrade.errors import InconsistentError, SolveError, UnderdeterminedError
from mechgrade.solve import solve
from mechgrade.spec import load_problem_text

BASE = (Path(__file__).resolve().parents[1] / "data" / "spec" / "base.yaml").read_text()

SLIDER = """
id: slider
title: Slider-crank
statement: A crank OA (length r) drives a rod AB (length L) whose end B slides on the x axis.
inertial: {frame: N, point: O}
frames:
  C: {parent: N, rotation: {axis: z, angle: theta}, origin: O}
  R: {parent: N, rotation: {axis: z, angle: -phi}, origin: A}
points:
  A: {from: O, position: r*C.x}
  B: {from: A, position: L*R.x}
coordinates: {theta: rad, phi: rad, x: m}
parameters: {r: m, L: m}
constraints:
  - {name: loop, position: "pos(B, O) = x*N.x"}
givens:
  r: 0.1 m
  L: 0.3 m
  theta: 90 deg
  theta': 10 rad/s
  theta'': 0 rad/s^2
guesses:
  phi: 20 deg
  x: 0.3 m
objectives:
  - {id: x, prompt: Slider position., find: x, kind: scalar, unit: m}
  - {id: v_B, prompt: Slider speed., find: "dot(vel(B, N), N.x)", kind: scalar, unit: m/s}
  - {id: phi_deg, prompt: Rod angle., find: phi, kind: scalar, unit: deg}
  - {id: a_B, prompt: Slider acceleration., find: "dot(acc(B, N), N.x)", kind: scalar, unit: m/s^2}
"""


def load(text):
    return load_problem_text(text, "p.yaml")


def test_position_constraints_are_solved_near_the_guesses():
    solution = solve(load(SLIDER))
    phi = math.asin(0.1 / 0.3)
    assert solution.result("x").value == pytest.approx(0.3 * math.cos(phi))
    assert solution.result("phi_deg").value == pytest.approx(math.degrees(phi))
    # At theta = 90 deg the rod does not turn (phi' = 0), so B moves with the crank pin: -r theta'
    v_expected = -0.1 * 10
    assert solution.result("v_B").value == pytest.approx(v_expected)
    # With theta'' = 0 at theta = 90 deg: phi'' = -r theta'^2 / (L cos phi), x'' = r theta'^2 tan phi
    a_expected = 0.1 * 10 ** 2 * math.tan(phi)
    assert solution.result("a_B").value == pytest.approx(a_expected, rel=1e-6)


def test_a_rate_nothing_fixes_is_named():
    problem = load(BASE.replace("  theta': 3 rad/s\n", ""))
    with pytest.raises(UnderdeterminedError) as info:
        solve(problem)
    assert str(info.value) == ("p.yaml:18:5: objectives[0]: objective 'speed' is not determined "
                               "by the givens: give a value for theta' (velocity level)")


def test_a_coordinate_the_objective_ignores_may_stay_free():
    solution = solve(load(BASE.replace("  theta: 30 deg\n", "")))
    assert solution.result("speed").value == pytest.approx(6.0)
    assert "theta" not in [s.name for s in solution.state]


def test_a_missing_coordinate_the_objective_needs_is_named():
    text = BASE.replace("  theta: 30 deg\n", "").replace(
        "find: speed(P, N)", "find: dot(vel(P, N), N.x)").replace("{value: 6}", "{value: -3}")
    with pytest.raises(UnderdeterminedError, match=r"give a value for theta \(position level\)"):
        solve(load(text))


def test_conflicting_position_givens_are_named():
    text = SLIDER.replace("guesses:\n  phi: 20 deg\n  x: 0.3 m", "  x: 0.2 m\n  phi: 10 deg")
    with pytest.raises(InconsistentError) as info:
        solve(load(text))
    message = info.value.message
    assert message.startswith("the givens conflict at the position level: 'loop (N.x component)'")
    assert "x = 0.2 m" in message and "phi = 10 deg" in message


def test_conflicting_rate_givens_are_named():
    text = SLIDER.replace("  theta'': 0 rad/s^2", "  theta'': 0 rad/s^2\n  x': 5 m/s")
    with pytest.raises(InconsistentError, match="at the velocity level: 'loop"):
        solve(load(text))


def test_a_given_can_be_any_expression_linear_in_the_rates():
    text = BASE.replace("  theta': 3 rad/s\n", "  \"dot(vel(P, N), A.y)\": 8 m/s\n")
    solution = solve(load(text))
    assert solution.result("speed").value == pytest.approx(8.0)
    assert {s.name: s.value for s in solution.state}["theta'"] == pytest.approx(4.0)


def test_givens_can_be_overridden_per_call():
    problem = load(BASE)
    assert solve(problem, givens={"theta'": 5.0}).result("speed").value == pytest.approx(10.0)
    with pytest.raises(UnderdeterminedError):
        solve(problem, givens={"theta'": None})


def test_a_class_reads_each_variants_givens_as_it_alone_would():
    from mechgrade.solve.instant import class_givens

    problem = load(SLIDER)
    variants = [{"theta": math.pi / 3, "r": 0.1}, {"theta": None}, {"theta ": math.pi / 3},
                {"theta": math.pi / 3, "theta ": math.pi / 2}, None]
    together = class_givens(problem, variants)
    assert together == [class_givens(problem, [v])[0] for v in variants]
    replaced, removed, spelt, twice, spec = together
    assert replaced["theta"][2].text == "60 deg" and replaced["theta"][2].unit == "deg"
    assert replaced["r"][2] is spec["r"][2]  # a value the spec gives keeps its given
    assert "theta" not in removed and spelt["theta"] == replaced["theta"]
    assert twice["theta"][1] == math.pi / 2 and twice["theta"][2].text == "90 deg"


def test_prescribed_motion_in_time():
    text = """
id: cycloid
title: Cycloid
statement: A rim point of a disk of radius R rolling at speed v.
inertial: {frame: N, point: O}
points:
  P: {from: O, position: x*N.x + y*N.y}
coordinates: {x: m, y: m}
parameters: {R: m, v: m/s}
constraints:
  - {name: path_x, position: "x = R*(v*t/R - sin(v*t/R))"}
  - {name: path_y, position: "y = R*(1 - cos(v*t/R))"}
givens:
  R: 1 m
  v: 1 m/s
  t: {value: pi/2, unit: s}
objectives:
  - {id: v, prompt: Velocity., find: "vel(P, N)", kind: vector, frame: N, unit: m/s}
  - {id: rho, prompt: Radius of curvature., find: "rho(P, N)", kind: scalar, unit: m}
"""
    solution = solve(load(text))
    assert solution.result("v").value == pytest.approx((1.0, 1.0, 0.0))
    assert solution.result("rho").value == pytest.approx(4 * math.sin(math.pi / 4))


def test_an_undefined_objective_is_reported():
    text = BASE.replace("theta': 3 rad/s", "theta': 0 rad/s").replace(
        "find: speed(P, N)\n    kind: scalar\n    unit: m/s",
        "find: tangent(P, N)\n    kind: vector\n    frame: N\n    unit: '1'").replace(
        "{value: 6}", "{components: [0, 1]}")
    with pytest.raises(SolveError, match="objective 'speed' is undefined at this instant"):
        solve(load(text))


def test_symbolic_answer_in_declared_symbols():
    text = BASE + """  - id: speed_symbolic
    prompt: Speed in terms of L and thetad.
    find: speed(P, N)
    kind: symbolic
    unit: m/s
    symbols: [L, thetad]
"""
    assert solve(load(text)).result("speed_symbolic").expr == "L*Abs(thetad)"


def test_symbolic_answer_may_not_hide_a_given_with_units():
    text = BASE + """  - id: speed_symbolic
    prompt: Speed in terms of thetad only.
    find: speed(P, N)
    kind: symbolic
    unit: m/s
    symbols: [thetad]
"""
    solution = solve(load(text))
    assert solution.result("speed").value == pytest.approx(6.0)
    with pytest.raises(SolveError, match="depends on L, which is not among its symbols"):
        solution.result("speed_symbolic")


def test_symbolic_answer_substitutes_given_angles():
    text = BASE + """  - id: vx
    prompt: x-velocity in terms of L and thetad.
    find: dot(vel(P, N), N.x)
    kind: symbolic
    unit: m/s
    symbols: [L, thetad]
"""
    assert solve(load(text)).result("vx").expr == "-L*thetad/2"


def test_symbolic_position_constraint_is_solved():
    text = """
id: mound
title: Ball rolling over a mound
statement: Arc-length relation.
inertial: {frame: N, point: O}
coordinates: {alpha: rad, phi: rad}
parameters: {R: m, r: m}
constraints:
  - {name: arc, position: "(R + r)*alpha = r*phi"}
givens:
  R: 1 m
  r: 0.1 m
  phi: 30 deg
objectives:
  - {id: alpha, prompt: Angle., find: alpha, kind: symbolic, unit: rad, symbols: [r, R, phi]}
  - {id: alpha_deg, prompt: Angle., find: alpha, kind: scalar, unit: deg}
"""
    solution = solve(load(text))
    assert solution.result("alpha").expr == "phi*r/(R + r)"
    assert solution.result("alpha_deg").value == pytest.approx(30 / 11)


def test_mistaken_models_are_evaluated():
    text = BASE.replace("    expect: {value: 6}",
                        "    mistakes:\n      - find: 2*L*theta'\n        message: doubled\n"
                        "        credit: 0.2\n    expect: {value: 6}")
    result = solve(load(text)).result("speed")
    assert result.mistakes[0].value == pytest.approx(12.0)
    assert (result.mistakes[0].message, result.mistakes[0].credit) == ("doubled", 0.2)


def test_an_objective_can_be_asked_at_its_own_instant():
    text = BASE + """  - id: speed_later
    prompt: Speed when the pendulum turns at 5 rad/s.
    givens: {"theta'": 5 rad/s}
    find: speed(P, N)
    kind: scalar
    unit: m/s
"""
    solution = solve(load(text))
    assert solution.result("speed").value == pytest.approx(6.0)
    assert solution.result("speed_later").value == pytest.approx(10.0)
    assert {s.name: s.value for s in solution.state}["theta'"] == pytest.approx(3.0)


def test_an_expression_given_unknown_to_the_spec_cannot_be_added_later():
    with pytest.raises(SolveError, match=r"cannot give 'dot\(vel\(P, N\), N.x\)'"):
        solve(load(BASE), givens={"dot(vel(P, N), N.x)": 1.0})


def test_an_instantaneous_centre_needs_planar_motion():
    text = """
id: screw
title: A body that spins and slides along its spin axis
statement: Frame A spins about N.z while its origin C rises along N.z.
inertial: {frame: N, point: O}
frames:
  A: {parent: N, rotation: {axis: z, angle: theta}, origin: C}
points:
  C: {from: O, position: z*N.z}
  P: {from: C, position: r*A.x}
coordinates: {theta: rad, z: m}
parameters: {r: m}
givens: {r: 1 m, theta: 0 deg, z: 0 m, "theta'": 2 rad/s, "z'": VZ}
objectives:
  - {id: ic, prompt: Centre., find: "pos(ic(A, N), C)", kind: vector, frame: N, unit: m}
"""
    planar = solve(load(text.replace("VZ", "0 m/s")))
    assert planar.result("ic").value == pytest.approx((0.0, 0.0, 0.0))
    with pytest.raises(SolveError, match="objective 'ic' does not exist at this instant: body A "
                                         "has no point of zero velocity in N"):
        solve(load(text.replace("VZ", "1 m/s")))


def test_only_the_objectives_asked_for_are_solved():
    text = BASE.replace("  theta'': 1 rad/s^2\n", "") + """  - id: accel
    prompt: Acceleration magnitude (needs theta'').
    find: mag(acc(P, N))
    kind: scalar
    unit: m/s^2
"""
    problem = load(text)
    with pytest.raises(UnderdeterminedError, match="'accel'"):
        solve(problem).result("accel")
    with pytest.raises(UnderdeterminedError, match="'accel'"):
        solve(problem, objectives=["accel"])
    solution = solve(problem, objectives=["speed"])
    assert [r.id for r in solution.results] == ["speed"]
    with pytest.raises(SolveError, match="no objective 'nope'"):
        solve(problem, objectives=["nope"])


@pytest.mark.parametrize("name", ["bowling_3_15_4_pendulum", "ruina_9_24_momentum_projection"])
def test_asking_for_no_objective_solves_nothing_and_fails_nothing(name):
    from mechgrade.resources import shipped_dir
    from mechgrade.spec import load_problem

    solution = solve(load_problem(shipped_dir("problems") / f"{name}.yaml"), objectives=())
    assert solution.results == () and solution.failures == ()


def _pendulum():
    from mechgrade.resources import shipped_dir
    from mechgrade.spec import load_problem

    return load_problem(shipped_dir("problems") / "bowling_3_15_4_pendulum.yaml")


def test_one_loop_answers_every_column_a_step_answers_alone_as_one_solve_does():
    from mechgrade.solve.instant import (GivenInstant, _instants, answer_alone, drive_columns,
                                         kinematics_plan)

    problem = _pendulum()
    reach = GivenInstant(problem, kinematics_plan(problem))

    def second_apart(maps, chosen, overrides, columns):
        answer_alone(problem, reach, maps, chosen, overrides, columns, [0, 2])
        # as a class's step answers a variant that fails a screen together
        answer_alone(problem, reach, maps, chosen, overrides, columns, [1])

    variants = [{"L": 0.5}, {"L": 1.0}, {"L": 2.0}]
    steps = [(overrides, group, second_apart) for overrides, group in _instants(problem)]
    a, b, c = drive_columns(problem, problem, reach.plan, (), steps, variants, {"acc_mag"})
    assert b == solve(problem, givens=variants[1], objectives={"acc_mag"})
    assert c.result("acc_mag").value == pytest.approx(4 * a.result("acc_mag").value)


def test_a_column_whose_value_is_undefined_fails_that_objective_alone():
    import numpy as np

    from mechgrade.solve.instant import group_results, instant_givens

    problem = _pendulum()
    asked = [problem.objective("acc_mag")]
    givens = instant_givens(problem, None, {})
    (right, fine), (none, lost) = group_results(
        problem, asked, [givens] * 2, {"acc_mag": np.array([[1.0, np.inf]])}, {},
        [{}, {}], [0, 1])
    assert list(right) == ["acc_mag"] and not fine
    assert not none
    assert "objective 'acc_mag' is undefined at this instant" in str(lost["acc_mag"])


def test_a_class_derives_a_symbolic_answer_once_per_what_it_depends_on():
    from mechgrade.solve.instant import group_results, instant_givens, symbolic_dependence

    problem = _pendulum()
    oid = "acc_mag_symbolic"
    derived = []

    def symbolic(problem_, objective_id, givens):
        derived.append(givens)
        return solve(problem_, objectives=[objective_id]).result(objective_id)

    maps = [instant_givens(problem, {"L": L}, {}) for L in (0.5, 1.0, 2.0)]
    assert len({symbolic_dependence(problem, m, oid) for m in maps}) == 1
    out = group_results(problem, [problem.objective(oid)], maps, {}, {}, [{}] * 3,
                        [0, 1, 2], symbolic)
    assert len(derived) == 1
    assert {results[oid].expr for results, _ in out} == {"L*sqrt(thetad**4 + thetadd**2)"}


def test_the_author_units_of_a_problem_are_worked_out_once():
    """Every refusal listing roots reads them (a class refuses hundreds of misread givens)."""
    from mechgrade.resources import shipped_dir
    from mechgrade.solve.levels import author_units
    from mechgrade.solve.plan import kinematics_plan
    from mechgrade.spec import load_problem

    problem = load_problem(shipped_dir("problems") / "airplane_crosswind_heading.yaml")
    p = kinematics_plan(problem)
    units = author_units(problem, p)
    assert units is author_units(problem, p)
    assert units[p.index.position("w'")] == "km / h"  # as its given is written


def test_a_state_value_that_is_round_off_of_its_dimension_reads_zero():
    """At apogee r' is zero in exact arithmetic; integrated it carries ~1e-12 of the speeds."""
    from mechgrade.resources import shipped_dir
    from mechgrade.spec import load_problem

    problem = load_problem(shipped_dir("problems") / "satellite_apogee_speed.yaml")
    state = {s.name: s for s in solve(problem, objectives=("apogee_speed",)).state}
    assert (state["r'"].value, state["r'"].si) == (0.0, 0.0)
    assert state["theta'"].si == pytest.approx(7.650669e-4, rel=1e-6)  # alone in its dimension
    assert state["r''"].si < 0


def test_an_authors_given_is_reported_as_written_however_small_beside_its_dimension():
    text = """
id: tiny_given
title: A tiny given rate beside a large one
statement: P moves in the plane.
inertial: {frame: N, point: O}
points:
  P: {from: O, position: x*N.x + y*N.y}
coordinates:
  x: m
  y: m
givens:
  x: 1 m
  y: 2 m
  x': 5 m/s
  y': 1e-12 m/s
objectives:
  - id: vP
    prompt: The velocity of P.
    find: vel(P, N)
    kind: vector
    unit: m/s
    frame: N
"""
    state = {s.name: s for s in solve(load_problem_text(text, "p.yaml")).state}
    assert (state["y'"].value, state["y'"].si) == (1e-12, 1e-12)
