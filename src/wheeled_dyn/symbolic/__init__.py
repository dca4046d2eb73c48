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

from .._lazy import attach

__getattr__, __dir__, __all__ = attach(__name__, {
    "cache_dir": ".cache",
    "cached_symbolic_model": ".cache",
    "clear_cache": ".cache",
    "model_fingerprint": ".cache",
    "JointKinematics": ".kinematics",
    "exact_number": ".kinematics",
    "forward_kinematics": ".kinematics",
    "LagrangeTerms": ".lagrange",
    "energy_terms": ".lagrange",
    "lagrange_terms": ".lagrange",
    "SymbolicModel": ".model",
    "symbolic_model": ".model",
    "NumericTerms": ".numeric",
    "lambdify_terms": ".numeric",
    "parameter_vector": ".numeric",
    "PARAMETER_NAMES": ".parameters",
    "inertial_symbols": ".parameters",
    "numeric_parameters": ".parameters",
    "from_srepr": ".printing",
    "to_latex": ".printing",
    "to_mathml": ".printing",
    "to_srepr": ".printing",
    "to_text": ".printing",
    "velocity_dots": ".printing",
    "canonical_trig": ".simplify",
    "is_zero": ".simplify",
    "polish_trig": ".simplify",
    "simplify_expr": ".simplify",
    "simplify_matrix": ".simplify",
    "ReducedSymbolic": ".transform",
    "time_derivative": ".transform",
    "transform": ".transform",
    "TrigRing": ".trigpoly",
    "PARAMETER_MODES": ".parameter_modes",
    "contact_rows": ".basis",
    "element_expressions": ".elements",
    "physical_symbols": ".parameter_modes",
    "true_expressions": ".wheeled",
    "lengths_are_symbols": ".wheeled",
    "velocity_products": ".elements",
    "wheeled_symbolic": ".wheeled",
})
