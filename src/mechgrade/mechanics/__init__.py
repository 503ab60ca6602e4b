"""The mechanics core: the only package that imports ``sympy.physics``.

``symbols`` (plain symbols of coordinates, rates, parameters), ``interpret`` (the expression
language as ``sympy.physics`` values), ``build`` (frames and points), ``kinematics`` (constraint
equations, givens and objectives at every level), ``derivation`` (the write-up text).
"""

from .writeup import derivation
from .kinematics import Kinematics, derive

__all__ = ["Kinematics", "derivation", "derive"]
