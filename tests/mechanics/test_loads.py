"""What the loads are: the free-body diagram in the model's symbols, the checks their kinds
make possible (each branch refused with its fix) and the physical bounds of the instant.
The slips an author makes are in tests/data/authoring_mistakes/dyn_*.yaml (run through the
CLI); these are the other branches."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest
import sympy as sp

from mechgrade.errors import SolveError, UnderdeterminedError
from mechgrade.mechanics.dynamics import derive_kinetics, free_body_loads
from mechgrade.mechanics.loads import Bounded, PhysicalBound
from mechgrade.solve import solve
from mechgrade.spec import load_problem_text

ROOT = Path(__file__).resolve().parents[2]
SLIPS = ROOT / "tests" / "data" / "authoring_mistakes"


def text(name: str) -> str:
    folder = SLIPS if name.startswith("dyn_") else ROOT / "problems"
    return (folder / f"{name}.yaml").read_text()


def swap(body: str, old: str, new: str) -> str:
    assert old in body, old
    return body.replace(old, new)


def refusal(body: str, kind=SolveError) -> str:
    with pytest.raises(kind) as info:
        derive_kinetics(load_problem_text(body, "p.yaml"))
    return str(info.value)


def test_gravity_across_down_is_refused():
    body = swap(text("dyn_gravity_against_down"), "gravity: g*N.y", "gravity: -g*N.x")
    assert "gravity '-g*N.x' points across the problem's down (down: -N.y)" in refusal(body)


def test_gravity_along_down_is_accepted():
    body = swap(text("dyn_gravity_against_down"), "gravity: g*N.y", "gravity: -g*N.y")
    assert free_body_loads(load_problem_text(body, "p.yaml"))[0].name == "gravity"


def test_a_weight_written_as_a_number_is_found_at_the_givens():
    body = swap(text("dyn_weight_twice"), "force: -m*g*N.y", "force: -W0*N.y")
    body = swap(body, "  g: m/s^2\n", "  g: m/s^2\n  W0: N\n")
    body = swap(body, "  g: 9.81 m/s^2\n", "  g: 9.81 m/s^2\n  W0: 19.62 N\n")
    assert "the force 'W' (-W0*N.y) is the weight of rod" in refusal(body)
    other = swap(body, "W0: 19.62 N", "W0: 10 N")  # a push that is not the weight
    assert derive_kinetics(load_problem_text(other, "p.yaml")) is not None


def test_a_spring_end_on_the_ground_must_be_fixed():
    body = swap(text("pendulum_pin_reaction"), "  reactions:\n",
                "  springs:\n    s: {between: [G, O], bodies: [ground, rod], stiffness: k}\n"
                "  reactions:\n")
    body = swap(body, "  g: m/s^2\n", "  g: m/s^2\n  k: N/m\n")
    body = swap(body, "  g: 9.81 m/s^2\n", "  g: 9.81 m/s^2\n  k: 10 N/m\n")
    assert "an end of spring 's' is on the ground at G, but G moves" in refusal(body)


def test_a_spring_end_offset_from_a_particle_moves_with_it():
    body = swap(text("two_mass_spring_chain"), "  P2: {from: O, position: x2*N.x}\n",
                "  P2: {from: O, position: x2*N.x}\n  H: {from: P2, position: L1*N.x}\n")
    body = swap(body, "between: [P1, P2], bodies: [block1, block2], stiffness",
                "between: [P1, H], bodies: [block1, block2], stiffness")
    assert derive_kinetics(load_problem_text(body, "p.yaml")) is not None


def test_a_pin_on_a_disk_whose_frame_does_not_turn_is_refused():
    body = swap(text("pendulum_pin_reaction"),
                "frame: B, inertia: {rod: {length: L, axis: y}}",
                "frame: N, inertia: {disk: {radius: L, axis: z}}")
    message = refusal(body)
    assert "the pin 'R_O' acts on rod at O, which is not a point of rod" in message
    assert "O - G is fixed in B, not in N: if rod turns with B, write frame: B" in message


def test_a_load_beyond_a_rods_ends_is_refused():
    body = swap(text("pendulum_pin_reaction"), "G: {from: O, position: -L/2*B.y}",
                "G: {from: O, position: -L*B.y}")
    assert "O, where 'R_O' acts on the rod 'rod', is 1.2 m from its centre G, beyond its " \
           "ends (0.6 m, half its length L)" in refusal(body)


def test_a_normal_force_on_a_moving_surface_names_it():
    body = swap(text("bead_on_rotating_hoop"), "kind: normal, surface: H,", "kind: normal,")
    message = refusal(body)
    assert "the normal force 'N_B' along E.z is not perpendicular to the surface at B" in message
    assert "if the surface itself moves, name it: surface: <frame or body>" in message


def test_a_coordinate_turning_no_bodys_frame_says_which_frame():
    body = swap(text("pendulum_pin_reaction"), "centre: G, frame: B, inertia: {rod: {length: L, "
                "axis: y}}", "centre: O, frame: N, inertia: {rod: {length: L, axis: y}}")
    body = swap(body, "at: O, directions", "at: O, directions")
    message = refusal(body, UnderdeterminedError)
    assert "coordinate 'theta' moves no mass" in message
    assert "theta turns frame B, which is no body's frame: if a body turns with it, write " \
           "frame: B for that body" in message


def test_a_coordinate_that_moves_no_mass_but_is_driven_is_accepted():
    body = swap(text("dyn_massless_junction"), "  xj': 0 m/s\n", "  xj': 0 m/s\n  xj'': 0 m/s^2\n")
    body = swap(body, "bodies: [ground, block], stiffness: k1", "bodies: [ground, ground], "
                "stiffness: k1")
    with pytest.raises(SolveError) as info:  # the spring's end J is then no point of the block
        derive_kinetics(load_problem_text(body, "p.yaml"))
    assert "moves no mass" not in str(info.value)


def test_a_students_mistaken_model_is_not_checked():
    problem = load_problem_text(text("dyn_mu_negative"), "p.yaml")
    mistaken = replace(problem, dynamics=replace(problem.dynamics, mistaken=True))
    assert derive_kinetics(mistaken).physical == ()
    assert solve(mistaken).result("accel").value == pytest.approx(7.02893, rel=1e-5)


@pytest.mark.parametrize("what, value, expected", [
    (Bounded.PULLING, -2.0, "the string 'T' would push: its tension is -2 N at this instant"),
    (Bounded.PUSHING, -2.0, "contact lost at A: the normal force 'T' would be -2 N (pulling)"),
    (Bounded.MASS, 0.0, "body 'T' has a mass of 0 N at this instant; expected a positive mass"),
    (Bounded.RESTITUTION, 1.5, "the coefficient of restitution at A is 1.5; expected a value "
                               "from 0 (plastic) to 1 (elastic)"),
])
def test_physical_bounds_name_the_value_and_the_fix(what, value, expected):
    bound = PhysicalBound(what, "T", sp.Integer(0), 0.0, 1.0 if what == Bounded.RESTITUTION
                          else None, strict=what == Bounded.MASS, point="A", unit="N",
                          direction="N.y")
    assert not bound.holds(value)
    assert bound.message(value).startswith(expected)
    assert bound.holds(0.5)


def test_the_diagram_puts_each_load_on_each_body_it_acts_on():
    cart = free_body_loads(load_problem_text(text("block_slides_on_cart"), "p.yaml"))
    on_cart = [(a.name, str(a.kind), a.sign, a.surface) for a in cart if a.body == "cart"]
    assert on_cart == [("gravity", "weight", 1, None), ("N_P", "normal", -1, "block"),
                       ("N_F", "normal", 1, "ground"), ("F_P", "kinetic friction", -1, "block")]
    chain = free_body_loads(load_problem_text(text("two_mass_spring_chain"), "p.yaml"))
    s2 = [a for a in chain if a.name == "s2"]
    assert [(a.body, a.point, str(a.kind)) for a in s2] == [("block1", "P1", "spring"),
                                                             ("block2", "P2", "spring")]
    assert sp.simplify(s2[0].directions[0] + s2[1].directions[0]) == sp.zeros(3, 1)


def test_a_bodys_parts_centred_at_one_point_weigh_as_one_and_elsewhere_apart():
    wheel = free_body_loads(load_problem_text(text("ruina_9_21_wheel_incline"), "p.yaml"))
    assert [(a.point, str(sp.factor(a.magnitude))) for a in wheel if a.name == "gravity"] == [
        ("G", "g*(2*M + m)")]
    hoop = free_body_loads(load_problem_text(text("unbalanced_hoop_rolls"), "p.yaml"))
    assert [(a.point, str(a.magnitude)) for a in hoop if a.name == "gravity"] == [
        ("G", "M*g"), ("Q", "g*m")]


def test_a_cord_pulls_each_end_along_its_own_segment():
    cord = free_body_loads(load_problem_text(text("cord_over_table_pulley"), "p.yaml"))
    ends = [(a.body, a.direction_texts, a.directions[0].T.tolist()) for a in cord
            if a.name == "T"]
    assert ends == [("A", ("N.x",), [[1, 0, 0]]), ("B", ("N.y",), [[0, 1, 0]])]
    couple = free_body_loads(load_problem_text(text("flywheel_speed_drop"), "p.yaml"))
    assert [(a.name, str(a.kind), a.point, a.force) for a in couple] == [
        ("punch", "applied couple", None, None)]
