r"""Closed forms from the URDF: symbolic :math:`A(q)`, :math:`C(q,\dot q)`, :math:`Q(q)` of a
Pinocchio tree of 1-DoF joints in Khalil's standard inertial parameters, their reduction to
quasi-velocities, simplification, printing, numeric evaluation and an on-disk cache.

Depends only on ``pinocchio`` (the model) and ``sympy``. Typical use::

    sym = cached_symbolic_model(model)            # or symbolic_model(model)
    sym.A, sym.C(), sym.Q, sym.h(), sym.christoffel()
    red = transform(sym, S, Sdot, nu, subs={phi: -theta})
    to_latex(red.A); lambdify_terms(red)("h", q, nu, parameter_vector(red, model))

For a wheeled model in a coordinate set, rolling included, in physical symbols::

    red = wheeled_symbolic(load_model("wip"), builtin_coordinate_set(wm, "seed001"))
    true_expressions("wip", cs)["h[1]:dpsi*dpsi"]     # labelled elements, cached
"""

from .cache import cache_dir, cached_symbolic_model, clear_cache, model_fingerprint
from .kinematics import JointKinematics, exact_number, forward_kinematics
from .lagrange import LagrangeTerms, energy_terms, lagrange_terms
from .model import SymbolicModel, symbolic_model
from .numeric import NumericTerms, lambdify_terms, parameter_vector
from .parameters import PARAMETER_NAMES, inertial_symbols, numeric_parameters
from .printing import from_srepr, to_latex, to_mathml, to_srepr, to_text, velocity_dots
from .simplify import canonical_trig, is_zero, polish_trig, simplify_expr, simplify_matrix
from .transform import ReducedSymbolic, time_derivative, transform
from .trigpoly import TrigRing
from .wheeled import (PARAMETER_MODES, contact_rows, element_expressions, physical_symbols,
                      true_expressions, velocity_products, wheeled_symbolic)

__all__ = [
    "JointKinematics", "LagrangeTerms", "NumericTerms", "PARAMETER_NAMES", "ReducedSymbolic",
    "SymbolicModel", "TrigRing", "cache_dir", "cached_symbolic_model", "canonical_trig",
    "clear_cache", "energy_terms", "exact_number", "forward_kinematics", "from_srepr",
    "PARAMETER_MODES", "contact_rows", "element_expressions", "physical_symbols",
    "true_expressions", "velocity_products", "wheeled_symbolic",
    "inertial_symbols", "is_zero", "lagrange_terms", "lambdify_terms", "model_fingerprint",
    "numeric_parameters", "parameter_vector", "polish_trig", "simplify_expr",
    "simplify_matrix", "symbolic_model", "time_derivative", "to_latex", "to_mathml",
    "to_srepr", "to_text", "transform", "velocity_dots",
]
