"""The kinematics core builds the textbook model: frames, points, constraints, objectives."""

from __future__ import annotations

import math

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from mechgrade.mechanics import derivation, derive
from mechgrade.solve import solve
from mechgrade.spec import load_problem_text

PENDULUM = """
id: pendulum
title: Pendulum
statement: A pendulum.
inertial: {frame: N, point: O}
frames:
  A: {parent: N, rotation: {axis: z, angle: theta}, origin: O}
points:
  P: {from: O, position: L*A.x}
coordinates: {theta: rad}
parameters: {L: m}
givens: {L: 2 m}
objectives:
  - {id: a, prompt: Acceleration., find: "acc(P, N)", kind: vector, frame: N, unit: m/s^2}
"""

GYRO = """
id: gyro
title: Body-fixed z-x rotation
statement: A disk precessing (psi about N.z) and nutating (theta about the new x).
inertial: {frame: N, point: O}
frames:
  B: {parent: N, rotations: [{axis: z, angle: psi}, {axis: x, angle: theta}], origin: O}
points:
  P: {from: O, position: r*B.y}
coordinates: {psi: rad, theta: rad}
parameters: {r: m}
givens:
  r: 1 m
  psi: 0 deg
  theta: 90 deg
  psi': 2 rad/s
  theta': 3 rad/s
  psi'': 0 rad/s^2
  theta'': 0 rad/s^2
objectives:
  - {id: w, prompt: Angular velocity., find: "angvel(B, N)", kind: vector, frame: B, unit: rad/s}
  - {id: v, prompt: Velocity of P., find: "vel(P, N)", kind: vector, frame: N, unit: m/s}
"""


def test_rates_are_plain_symbols_named_by_the_textbook_convention():
    k = derive(load_problem_text(PENDULUM))
    L, theta, thetad, thetadd = sp.symbols("L theta thetad thetadd")
    ax, ay, _ = k.objective("a")
    expected_x = -L * thetad ** 2 * sp.cos(theta) - L * thetadd * sp.sin(theta)
    assert sp.simplify(ax.subs({s: sp.Symbol(str(s)) for s in ax.free_symbols}) - expected_x) == 0
    assert [str(s) for s in k.q + k.qd + k.qdd] == ["theta", "thetad", "thetadd"]


@settings(max_examples=25)
@given(theta=st.floats(-3, 3), rate=st.floats(-10, 10), accel=st.floats(-10, 10))
def test_pendulum_acceleration_matches_the_closed_form(theta, rate, accel):
    problem = load_problem_text(PENDULUM)
    solution = solve(problem, givens={"theta": theta, "theta'": rate, "theta''": accel})
    ax, ay, az = solution.result("a").value
    assert ax == pytest.approx(-2 * rate ** 2 * math.cos(theta) - 2 * accel * math.sin(theta),
                               abs=1e-9)
    assert ay == pytest.approx(-2 * rate ** 2 * math.sin(theta) + 2 * accel * math.cos(theta),
                               abs=1e-9)
    assert az == 0


def test_body_fixed_rotation_sequence():
    solution = solve(load_problem_text(GYRO))
    # omega = psi' N.z + theta' B.x; after theta = 90 deg about x (psi = 0), B.y = N.z and
    # B.z = -N.y, so omega = 3 B.x + 2 B.y.
    assert solution.result("w").value == pytest.approx((3.0, 2.0, 0.0), abs=1e-12)
    # v_P = omega x r B.y = 3 r B.z = -3 N.y (r = 1 m).
    assert solution.result("v").value == pytest.approx((0.0, -3.0, 0.0), abs=1e-12)


def test_derivation_lists_the_write_up_sections():
    sections = dict(derivation(load_problem_text(GYRO), dof=2))
    assert sections["Frames"] == ("N: inertial frame; inertial point O",
                                  "B: from N by psi about N.z, then theta about the new x; "
                                  "origin O")
    assert sections["Points"] == ("P_OP = r*B.y",)
    assert sections["Degrees of freedom"] == ("2 coordinates - 0 independent scalar "
                                              "constraints = 2",)


def test_every_function_of_the_objective_language_is_implemented():
    from mechgrade.expressions.functions import OBJECTIVE_FUNCTIONS, Kind
    from mechgrade.mechanics.dynamics import DynamicsInterpreter

    # point-valued functions (coincident, ic) are read by vel/acc/pos, not called directly
    valued = {name for name, f in OBJECTIVE_FUNCTIONS.items() if f.result != Kind.POINT}
    assert set(DynamicsInterpreter.functions) == valued
