r"""The comparison engine: documents' derivations against the truth, term by term.

The package is also callable: ``wheeled_dyn.compare(model, A=..., C=..., ...)`` is
:func:`wheeled_dyn.api.compare` (a derivation built from SymPy objects, compared).
"""

from .._lazy import attach, callable_package

__getattr__, __dir__, __all__ = attach(__name__, {
    "ComparisonEngine": ".engine",
    "Cause": ".records",
    "Convention": ".records",
    "ConventionSummary": ".records",
    "DerivationResult": ".records",
    "ElementRecord": ".records",
    "EnergyCheck": ".records",
})
callable_package(__name__, ".api:compare")
