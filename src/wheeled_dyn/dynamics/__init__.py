r"""Ground truth by Pinocchio: A, C, Q, B, h of the full model; Christoffel symbols."""

from .christoffel import christoffel_tensor, coriolis_from_christoffel, h_coefficients, mass_matrix_derivative
from .terms import Terms, full_terms

__all__ = ["Terms", "full_terms", "christoffel_tensor", "coriolis_from_christoffel",
           "h_coefficients", "mass_matrix_derivative"]
