"""The mechanics core: the only package that imports ``sympy.physics``."""

from .model import Kinematics, derivation, derive

__all__ = ["Kinematics", "derive", "derivation"]
