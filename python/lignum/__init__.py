"""Lignum from Python: Lie group time integrators for constrained
multibody systems (generalized-alpha, Newmark, BDF) on numpy arrays.

Models are built from bodies, joints, spring-dampers and drivers
(:class:`Multibody`, :class:`PlanarMultibody` for planar mechanisms,
integrated without Python in the inner loop) or
written as Python functions (:class:`PythonModel`). :class:`Integrator`
is Lignum's integrator object; :func:`solve_ivp` runs it in one call.
See doc/python.md."""
from ._core import GROUND, flag_name
from ._errors import LignumError, LignumWarning
from .integrator import Integrator
from .ivp import Result, solve_ivp
from .model import Multibody, PlanarMultibody, PythonModel, harmonic, polynomial, quaternion

__version__ = "0.1.0"
__all__ = ["GROUND", "Integrator", "LignumError", "LignumWarning", "Multibody",
           "PlanarMultibody", "PythonModel",
           "Result", "flag_name", "harmonic", "polynomial", "quaternion", "solve_ivp"]
