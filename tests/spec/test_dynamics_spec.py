"""The bodies: and loads: sections: every validation branch gives one located message."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechgrade.errors import SpecError
from mechgrade.spec import load_problem_text

ROOT = Path(__file__).resolve().parents[2]
PENDULUM = (ROOT / "problems" / "pendulum_pin_reaction.yaml").read_text()
INCLINE = (ROOT / "problems" / "block_sliding_down_incline.yaml").read_text()
CHAIN = (ROOT / "problems" / "two_mass_spring_chain.yaml").read_text()
CART = (ROOT / "problems" / "block_slides_on_cart.yaml").read_text()
ICE = (ROOT / "problems" / "rod_struck_on_ice.yaml").read_text()
TURNTABLE = (ROOT / "problems" / "block_on_turntable.yaml").read_text()
LADDER = (ROOT / "problems" / "ruina_9_20_ladder_energy.yaml").read_text()
LIFT_OFF = (ROOT / "problems" / "ladder_wall_lift_off.yaml").read_text()
HOOP = (ROOT / "problems" / "unbalanced_hoop_rolls.yaml").read_text()


def error_of(text: str) -> str:
    with pytest.raises(SpecError) as info:
        load_problem_text(text, "p.yaml")
    return str(info.value)


CASES = [
    ("reaction on no body", PENDULUM, "R_O: {kind: pin, body: rod, at: O,", "R_O: {kind: pin,",
     "p.yaml:26:10: loads.reactions.R_O: expected one of the fields body (with at), bodies "
     "(with at), acts, found none of them"),
    ("joint without its point", PENDULUM, "R_O: {kind: pin, body: rod, at: O,",
     "R_O: {kind: pin, bodies: [rod, rod],",
     "p.yaml:26:10: loads.reactions.R_O: expected a field 'at' with 'bodies', found none"),
    ("body named like a point", PENDULUM, "  rod: {mass: m", "  G: {mass: m",
     "bodies.G: 'G' names a body and something else already"),
    ("unknown centre", PENDULUM, "centre: G, frame: B", "centre: Q, frame: B",
     "unknown point 'Q' in 'centre'"),
    ("unknown body frame", PENDULUM, "centre: G, frame: B", "centre: G, frame: K",
     "unknown frame 'K' (frames: B, N)"),
    ("particle with inertia", PENDULUM, "centre: G, frame: B, ", "centre: G, ",
     "body 'rod' has an inertia but no 'frame'"),
    ("mass without units of mass", PENDULUM, "rod: {mass: m,", "rod: {mass: L,",
     "dimension mismatch in 'L' (a mass)"),
    ("shape size not a length", PENDULUM, "rod: {length: L,", "rod: {length: m,",
     "dimension mismatch in 'm' (a length)"),
    ("block side not a length", PENDULUM, "inertia: {rod: {length: L, axis: y}}",
     "inertia: {block: {sides: [L, L, m]}}", "dimension mismatch in 'm' (a length)"),
    ("cylinder length not a length", PENDULUM, "inertia: {rod: {length: L, axis: y}}",
     "inertia: {cylinder: {radius: L, length: m, axis: y}}",
     "dimension mismatch in 'm' (a length)"),
    ("explicit inertia in wrong units", PENDULUM, "inertia: {rod: {length: L, axis: y}}",
     "inertia: {about_centre: {xx: m, zz: m*L}}", "(a moment of inertia)"),
    ("unknown shape key", PENDULUM, "inertia: {rod: {length: L, axis: y}}",
     "inertia: {cone: {length: L}}", "bodies.rod.inertia.cone: expected only the fields rod, ring, disk, cylinder, sphere, "
     "shell, block, about_centre, found 'cone'"),
    ("mass without centre", PENDULUM, "mass: m, centre: G,", "mass: m,",
     "body 'rod' has a mass but no 'centre'"),
    ("both mass and parts", PENDULUM, "rod: {mass: m,", "rod: {parts: [], mass: m,",
     "expected only one of the fields mass, parts, found mass and parts"),
    ("gravity as a scalar", PENDULUM, "gravity: -g*N.y", "gravity: -g",
     "expected the gravitational acceleration as a vector"),
    ("gravity not an acceleration", PENDULUM, "gravity: -g*N.y", "gravity: -L*N.y",
     "dimension mismatch in '-L*N.y'"),
    ("reaction on an unknown body", PENDULUM, "body: rod, at: O", "body: bar, at: O",
     "unknown body 'bar' (bodies: ground, rod)"),
    ("reaction at an unknown point", PENDULUM, "body: rod, at: O", "body: rod, at: Z",
     "unknown point 'Z' in 'at'"),
    ("direction with units", PENDULUM, "directions: [N.x, N.y]", "directions: [L*N.x, N.y]",
     "(a direction (a vector without units, e.g. N.x))"),
    ("reaction without direction", PENDULUM, ", directions: [N.x, N.y]}", "}",
     "expected one of the fields direction, directions, found none of them"),
    ("yaml 'on' key", PENDULUM, "body: rod, at: O", "on: rod, at: O",
     "loads.reactions.R_O.True: expected only the fields kind, surface, body, bodies, at, "
     "direction, directions, acts, found 'True'"),
    ("friction normal not a reaction", INCLINE, "normal: N_P", "normal: block",
     "friction 'F_P': 'normal' must name a reaction with one direction"),
    ("friction coefficient with units", INCLINE, "mu: mu_k", "mu: g",
     "dimension mismatch in 'g' (a friction coefficient)"),
    ("kinetic friction on an unknown surface", INCLINE, "kind: kinetic}",
     "kind: kinetic, surface: K}", "unknown surface 'K' (frames or bodies: A, N, block)"),
    ("friction between bodies pressed by a one-body normal", CART,
     "N_P: {kind: normal, bodies: [block, cart], at: P,", "N_P: {kind: normal, body: block, at: P,",
     "friction 'F_P' between block and cart: its normal 'N_P' must act on both bodies"),
    ("friction of a body on itself", CART, "surface: cart}", "surface: block}",
     "friction 'F_P' between block and block"),
    ("static friction on a frame", TURNTABLE, "kind: static,", "kind: static, surface: B,",
     "unknown surface 'B' (bodies: block)"),
    ("known impulse without an impact", ICE,
     "analysis:\n  impulse:\n    before: {x': 0 m/s, y': 0 m/s, theta': 0 rad/s}   # at rest\n", "",
     "loads.impulses.hammer: the known impulse 'hammer' acts during an impact only"),
    ("known impulse in newtons", ICE, "impulse: J*N.y}", "impulse: J/L*N.y}",
     "(an impulse vector)"),
    ("known impulse on an unknown body", ICE, "hammer: {body: rod,", "hammer: {body: bat,",
     "unknown body 'bat' (bodies: rod)"),
    ("before of a scalar is a scalar", ICE, "find: dot(angvel(R, N), N.z)",
     "find: dot(before(mag(vel(G, N))), N.z)", "expected a vector as argument of dot(...), "
     "found a scalar ('before(mag(vel(G, N)))')"),
    ("spring stiffness units", CHAIN, "stiffness: k1", "stiffness: m1",
     "dimension mismatch in 'm1' (a stiffness)"),
    ("spring free length units", CHAIN, "length: L1", "length: k1",
     "dimension mismatch in 'k1' (a free length)"),
    ("damper coefficient units", CHAIN, "coefficient: c", "coefficient: k1",
     "dimension mismatch in 'k1' (a damping coefficient)"),
    ("spring on an unknown body", CHAIN, "bodies: [ground, block1]", "bodies: [wall, block1]",
     "unknown body 'wall'"),
    ("loads without bodies", CHAIN, "bodies:\n  block1: {mass: m1, centre: P1}\n  block2: {mass: m2, centre: P2}\n",
     "", "'loads' needs bodies: expected a 'bodies' section"),
    ("weight as a force beside gravity", PENDULUM, "  reactions:\n",
     "  forces:\n    W: {kind: weight, body: rod, at: G, force: -m*g*N.y}\n  reactions:\n",
     "loads.forces.W: the weight 'W' on rod is given twice: as this force and by 'gravity: "
     "-g*N.y', which acts on every body; expected it once"),
    ("gravity's magnitude without down", PENDULUM, "gravity: -g*N.y", "gravity: g",
     "found the magnitude 'g'; give its direction as well: down: -N.y"),
    ("down with units", PENDULUM, "gravity: -g*N.y", "gravity: g\n  down: -L*N.y",
     "(the direction of 'down' (a vector without units, e.g. -N.y))"),
    ("unknown reaction kind", PENDULUM, "kind: pin,", "kind: hinge,",
     "loads.reactions.R_O.kind: expected one of normal, pin, tension, contact, applied"),
    ("tension along two directions", PENDULUM, "kind: pin,", "kind: tension,",
     "the tension 'R_O' pulls along its string: expected one direction, found 2"),
    ("normal force over pulleys", PENDULUM, "R_O: {kind: pin, body: rod, at: O, directions: "
     "[N.x, N.y]}", "R_O: {kind: normal, direction: N.y, acts: [{body: rod, at: O}, "
     "{body: rod, at: G}]}", "a normal force acts at one point: expected 'body' and 'at'"),
    ("surface of a pin", PENDULUM, "kind: pin,", "kind: pin, surface: ground,",
     "'surface' belongs to a normal force or a contact; 'R_O' is a pin"),
    ("unknown surface of a normal force", PENDULUM, "kind: pin,", "kind: normal, surface: K,",
     "unknown surface 'K' of 'R_O' (expected ground, a frame or a body: B, N, ground, rod)"),
    ("joint on a surface other than its second body", CART,
     "N_P: {kind: normal, bodies: [block, cart], at: P,",
     "N_P: {kind: normal, surface: ground, bodies: [block, cart], at: P,",
     "the joint 'N_P' between block and cart is on cart: expected surface: cart or none, "
     "found surface: ground"),
    ("friction pressed by a pin", INCLINE, "N_P: {kind: normal,", "N_P: {kind: pin,",
     "friction 'F_P': its normal 'N_P' is a pin; expected the normal force pressing the "
     "surfaces together at P (a reaction with kind: normal)"),
    ("cord end's direction on components", PENDULUM,
     "R_O: {kind: pin, body: rod, at: O, directions: [N.x, N.y]}",
     "R_O: {directions: [N.x, N.y], acts: [{body: rod, at: O, direction: N.y}]}",
     "'R_O': an end with its own direction belongs to a cord (one unknown tension): expected "
     "one 'direction', found 2"),
    ("cord end's direction with units", PENDULUM,
     "R_O: {kind: pin, body: rod, at: O, directions: [N.x, N.y]}",
     "R_O: {direction: N.x, acts: [{body: rod, at: O, direction: L*N.y}]}",
     "(a direction (a vector without units, e.g. N.x))"),
    ("static friction without directions", TURNTABLE, ", directions: [B.x, B.y]}", "}",
     "loads.friction.F_P: static friction 'F_P' needs the directions of its unknown "
     "components: expected directions: [N.x, N.y] (in a planar problem the one in the plane "
     "of motion), the tangents to the surface at P, found none"),
    ("force of an unknown load", PENDULUM, "find: force(R_O)", "find: force(R_Q)",
     "expected a load as argument of force(...), found 'R_Q' (known: R_O)"),
    ("eom of a parameter", PENDULUM, "find: eom(theta)\n    kind: scalar",
     "find: eom(L)\n    kind: scalar", "expected a coordinate as argument of eom(...)"),
    ("pe of a reaction", PENDULUM, "find: dot(force(R_O), B.y)", "find: pe(R_O)",
     "expected a body or spring as argument of pe(...)"),
    ("force in the wrong unit", PENDULUM, "find: dot(force(R_O), B.y)\n    kind: scalar\n    unit: N",
     "find: dot(force(R_O), B.y)\n    kind: scalar\n    unit: J", "dimension mismatch"),
    ("before of a point", ICE, "find: vel(G, N)", "find: before(G)",
     "p.yaml:43:11: objectives[0].find: 'G' is a point; expected a scalar or vector here"),
    ("after of two quantities", ICE, "find: vel(G, N)", "find: after(vel(G, N), 2)",
     "expected 1 arguments for after(...) (after(x): scalar or vector x with the rates just "
     "after the impact (analysis: impulse; x alone means the same)), found 2"),
    ("an objective's own second rate under integrate", CART, "    expect: {value: 1.359157}\n",
     "    expect: {value: 1.359157}\n    givens: {x'': 1 m/s^2}\n",
     "p.yaml:54:19: objectives[0].givens.x'': expected parameters and one of the time t, a "
     "coordinate or a rate (q, q') among an objective's own givens under 'analysis: "
     "integrate', found 'x'': 1 m/s^2'; the motion is integrated from 'from:' (the instant is "
     "where the given first holds, else the event, when x' = X')"),
    ("an objective's instant fixed twice under integrate", CART,
     "    expect: {value: 1.359157}\n",
     "    expect: {value: 1.359157}\n    givens: {t: 0.1 s, x: 0.2 m}\n",
     "objectives[0].givens.x: expected one given fixing the instant of objective 't_slide' "
     "on the integrated motion (the time t, a coordinate or a rate), found 't' and 'x'; keep "
     "one of them"),
    ("a symbolic objective at another instant under integrate", CART,
     "    expect: {expr: M*v0/(mu*g*(m + M))}\n",
     "    expect: {expr: M*v0/(mu*g*(m + M))}\n    givens: {x': 1 m/s}\n",
     "objectives[1].givens.x': a symbolic objective of an integrated motion is answered at "
     "the event, when x' = X' (in closed form), found 'x': 1 m/s'; ask for a scalar or a "
     "vector at that instant"),
    ("a symbolic objective asked 'when' under integrate", CART,
     "    expect: {expr: M*v0/(mu*g*(m + M))}\n",
     "    expect: {expr: M*v0/(mu*g*(m + M))}\n    when: x' = 1 m/s\n",
     "objectives[1].when: objective 't_slide_symbolic': 'when: x' = 1 m/s' is an instant of "
     "the motion integrated numerically: expected kind: scalar or vector, found kind: "
     "symbolic (or end the motion there with 'until: x' = 1 m/s')"),
    ("a position asked 'when' without an analysis", PENDULUM,
     "    find: eom(theta)\n    kind: scalar",
     "    find: eom(theta)\n    when: dot(force(R_O), N.y) = 0\n    kind: scalar",
     "p.yaml:37:11: objectives[0].when: objective 'alpha': 'when: dot(force(R_O), N.y) = 0' is "
     "the position the motion from a work_energy start reaches, or the first instant an "
     "integrated motion reaches where it holds; expected 'analysis: work_energy' or "
     "'analysis: integrate', found no analysis: add one with the start state ('from')"),
    ("a position asked 'when' with constraints", HOOP, "    find: abs(phi')\n",
     "    find: abs(phi')\n    when: phi = -pi/2\n",
     "objectives[0].when: objective 'angular_velocity': 'when: phi = -pi/2' needs one "
     "coordinate without constraints (its rate follows from the energy balance as a function "
     "of the position), found 2 coordinates and 1 constraints; ask at a given position "
     "instead (givens: {x: ...})"),
    ("a position asked 'when' and given", LADDER,
     "    when: dot(force(N1), N.x) = 0\n    kind: scalar",
     "    when: dot(force(N1), N.x) = 0\n    givens: {theta: 50 deg}\n    kind: scalar",
     "objectives[5].givens.theta: objective 'theta_wall_lost_deg': 'when: dot(force(N1), N.x) "
     "= 0' fixes the position, found also 'theta: 50 deg' among its givens; keep one of them"),
    ("a position asked 'when' of unlike sides", LADDER,
     "    when: dot(force(N1), N.x) = 0\n    kind: scalar",
     "    when: dot(force(N1), N.x) = L\n    kind: scalar",
     "p.yaml:81:11: objectives[5].when: dimension mismatch in both sides of 'when': expected a "
     "length ([length]), found a force ([mass]·[length]/[time]²)"),
]


@pytest.mark.parametrize("base, old, new, message", [c[1:] for c in CASES],
                         ids=[c[0] for c in CASES])
def test_bad_dynamics_section_gives_located_message(base, old, new, message):
    assert old in base
    err = error_of(base.replace(old, new, 1))
    assert message in err
    assert err.startswith("p.yaml:")


def test_a_composite_body_reads_its_parts():
    from mechgrade.spec import load_problem
    from mechgrade.spec.dynamics import Disk

    wheel = load_problem(ROOT / "problems" / "ruina_9_21_wheel_incline.yaml").dynamics.body("wheel")
    assert [p.mass.text for p in wheel.parts] == ["m", "M", "M"]
    assert all(isinstance(p.shape, Disk) for p in wheel.parts)
    assert wheel.centre == "G"


def test_a_reaction_without_kind_keeps_a_kind_read_from_its_form():
    """Specs written before kind: stay valid: a cord over pulleys is a tension, a friction's
    normal a normal force, any other a reaction of unstated kind."""
    text = PENDULUM.replace("kind: pin, ", "")
    assert load_problem_text(text, "p.yaml").dynamics.kind("R_O") == "reaction"
    incline = load_problem_text(INCLINE.replace("kind: normal, ", ""), "p.yaml").dynamics
    assert incline.kind("N_P") == "normal" and incline.reactions[0].contact_surface == "ground"
    cart = load_problem_text(CART, "p.yaml").dynamics
    assert cart.kind("N_P") == "normal" and cart.load("N_P").contact_surface == "cart"


def test_gravity_written_as_its_magnitude_points_down():
    d = load_problem_text(PENDULUM.replace("gravity: -g*N.y", "gravity: g\n  down: -N.y"),
                          "p.yaml").dynamics
    assert (d.gravity.text, d.down.text) == ("(g)*(-N.y)", "-N.y")


SERIES = (ROOT / "problems" / "block_on_springs_in_series.yaml").read_text()


def test_from_may_leave_out_a_coordinate_that_locates_a_massless_junction_only():
    from mechgrade.spec.dynamics import junction_coordinates
    problem = load_problem_text(SERIES, "p.yaml")
    assert [b.name for b in problem.dynamics.junctions] == ["node"]
    assert junction_coordinates(problem) == ("xj",)


def test_from_needs_a_coordinate_that_also_locates_a_body_with_mass():
    # the block located from the joint: xj moves a mass, so 'from' must give it
    body = SERIES.replace("P: {from: O, position: x*N.x}", "P: {from: J, position: (x - xj)*N.x}")
    assert error_of(body).endswith("'from' needs every coordinate (rates default to 0): "
                                   "missing xj")


def test_from_needs_every_coordinate_of_a_problem_without_junctions():
    body = SERIES.replace("  node: {mass: 0, centre: J}", "  node: {mass: m, centre: J}")
    assert error_of(body).endswith("'from' needs every coordinate (rates default to 0): "
                                   "missing xj")
