r"""Closed forms from the URDF: symbolic :math:`A(q)`, :math:`C(q,\dot q)`, :math:`Q(q)` of a
Pinocchio tree of 1-DoF joints in Khalil's standard inertial parameters, their reduction to
quasi-velocities, simplification, printing, numeric evaluation and an on-disk cache.

Depends only on ``pinocchio`` (the model) and ``sympy``.
"""

from .kinematics import JointKinematics, exact_number, forward_kinematics
from .lagrange import LagrangeTerms, energy_terms, lagrange_terms
from .model import SymbolicModel, symbolic_model
from .numeric import NumericTerms, lambdify_terms, parameter_vector
from .parameters import PARAMETER_NAMES, inertial_symbols, numeric_parameters
from .simplify import canonical_trig, is_zero, polish_trig, simplify_expr, simplify_matrix
from .transform import ReducedSymbolic, time_derivative, transform
from .trigpoly import TrigRing

__all__ = [
    "JointKinematics", "LagrangeTerms", "NumericTerms", "PARAMETER_NAMES", "ReducedSymbolic",
    "SymbolicModel",
    "TrigRing", "canonical_trig", "energy_terms", "exact_number", "forward_kinematics",
    "inertial_symbols", "is_zero", "lagrange_terms", "lambdify_terms", "numeric_parameters",
    "parameter_vector", "polish_trig", "simplify_expr", "simplify_matrix", "symbolic_model",
    "time_derivative", "transform",
]
