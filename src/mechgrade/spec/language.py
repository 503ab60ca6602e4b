"""The objective language: kinematics functions usable in spec expressions, with their types.

Every function takes points, frames, vectors or scalars and returns one of them; the table
below fixes the argument kinds and the result's kind and dimension, so a spec can be checked
(names, kinds, dimensions) before anything is solved. The mechanics core implements exactly
these names.

>>> sorted(FUNCTIONS)[:4]
['acc', 'acc_n', 'acc_t', 'angacc']
>>> FUNCTIONS["vel"].args
('point', 'frame')
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from ..units import dimension, dimensionless


def _length():
    return dimension("m")


def _per_time(power: int = 1):
    return dimension("s") ** -power


@dataclass(frozen=True)
class Signature:
    """Argument kinds, result kind, the rule giving the result's dimension, and a description."""

    args: tuple[str, ...]
    result: str
    dim: Callable[[tuple], object]
    doc: str


def _fixed(unit: str):
    return lambda dims: dimension(unit)


FUNCTIONS: dict[str, Signature] = {
    "pos": Signature(("point", "point"), "vector", _fixed("m"),
                     "pos(P, Q): position of point P relative to point Q"),
    "vel": Signature(("point", "frame"), "vector", _fixed("m/s"),
                     "vel(P, F): velocity of P as seen in frame F"),
    "acc": Signature(("point", "frame"), "vector", _fixed("m/s^2"),
                     "acc(P, F): acceleration of P as seen in frame F"),
    "angvel": Signature(("frame", "frame"), "vector", _fixed("1/s"),
                        "angvel(A, F): angular velocity of frame A in frame F"),
    "angacc": Signature(("frame", "frame"), "vector", _fixed("1/s^2"),
                        "angacc(A, F): angular acceleration of frame A in frame F"),
    "dt": Signature(("vector", "frame"), "vector", lambda dims: dims[0] * _per_time(),
                    "dt(v, F): time derivative of vector v taken in frame F"),
    "mag": Signature(("vector",), "scalar", lambda dims: dims[0],
                     "mag(v): magnitude of v"),
    "dot": Signature(("vector", "vector"), "scalar", lambda dims: dims[0] * dims[1],
                     "dot(u, v): dot product"),
    "cross": Signature(("vector", "vector"), "vector", lambda dims: dims[0] * dims[1],
                       "cross(u, v): cross product"),
    "unit": Signature(("vector",), "vector", lambda dims: dimensionless(),
                      "unit(v): unit vector along v"),
    "speed": Signature(("point", "frame"), "scalar", _fixed("m/s"),
                       "speed(P, F): speed (s-dot) of P in F"),
    "acc_t": Signature(("point", "frame"), "scalar", _fixed("m/s^2"),
                       "acc_t(P, F): tangential acceleration (s-double-dot) of P in F"),
    "acc_n": Signature(("point", "frame"), "scalar", _fixed("m/s^2"),
                       "acc_n(P, F): normal acceleration s-dot^2/rho of P in F"),
    "rho": Signature(("point", "frame"), "scalar", _fixed("m"),
                     "rho(P, F): radius of curvature of P's path in F"),
    "tangent": Signature(("point", "frame"), "vector", lambda dims: dimensionless(),
                         "tangent(P, F): unit tangent of P's path in F"),
    "normal": Signature(("point", "frame"), "vector", lambda dims: dimensionless(),
                        "normal(P, F): unit normal of P's path in F, toward the centre of curvature"),
    "coincident": Signature(("point", "frame"), "point", lambda dims: _length(),
                            "coincident(P, A): the point fixed in frame A that is at P now"),
    "ic": Signature(("frame", "frame"), "point", lambda dims: _length(),
                    "ic(A, F): instantaneous centre of zero velocity of body A in F "
                    "(usable inside pos)"),
    # dynamics (see spec/dynamics.py): loads, momenta and energies of bodies
    "force": Signature(("load",), "vector", _fixed("N"),
                       "force(R): the force of a load (a reaction, friction, spring, applied force)"),
    "impulse": Signature(("load",), "vector", _fixed("N*s"),
                         "impulse(R): the impulse of a reaction during an impact"),
    "before": Signature(("vector",), "vector", lambda dims: dims[0],
                        "before(v): vector v with the rates just before the impact "
                        "(analysis: impulse)"),
    "moment": Signature(("load", "point"), "vector", _fixed("N*m"),
                        "moment(R, P): the moment of a load about point P"),
    "momentum": Signature(("body", "frame"), "vector", _fixed("kg*m/s"),
                          "momentum(B, F): linear momentum of body B in frame F"),
    "angmom": Signature(("body", "point", "frame"), "vector", _fixed("kg*m^2/s"),
                        "angmom(B, P, F): angular momentum of body B about point P in frame F"),
    "ke": Signature(("body", "frame"), "scalar", _fixed("J"),
                    "ke(B, F): kinetic energy of body B in frame F"),
    "pe": Signature(("body or spring",), "scalar", _fixed("J"),
                    "pe(X): potential energy of body X in gravity (zero at the inertial point) "
                    "or of spring X"),
    "power": Signature(("load", "frame"), "scalar", _fixed("W"),
                       "power(R, F): power of a load, with velocities in frame F"),
    "eom": Signature(("coordinate",), "scalar", lambda dims: dims[0] * _per_time(2),
                     "eom(q): q'' from the equations of motion"),
    "omega_n": Signature(("coordinate",), "scalar", _fixed("rad/s"),
                         "omega_n(q): natural frequency of the motion linearised about the "
                         "instant's configuration (an equilibrium)"),
    "mode_frequency": Signature(("scalar",), "scalar", _fixed("rad/s"),
                                "mode_frequency(n): the n-th natural frequency (1 the lowest) "
                                "of the motion linearised about the equilibrium"),
    "mode_shape": Signature(("scalar", "coordinate", "coordinate"), "scalar",
                            lambda dims: dims[1] / dims[2],
                            "mode_shape(n, q, r): the amplitude ratio of q to r in mode n"),
    "zeta": Signature(("coordinate",), "scalar", lambda dims: dimensionless(),
                      "zeta(q): damping ratio of the motion linearised about the equilibrium"),
}
