r"""The comparison engine: documents' derivations against the truth, term by term."""

from .._lazy import attach

__getattr__, __dir__, __all__ = attach(__name__, {
    "ComparisonEngine": ".engine",
    "Cause": ".result",
    "Convention": ".result",
    "ConventionSummary": ".result",
    "DerivationResult": ".result",
    "ElementRecord": ".result",
    "EnergyCheck": ".result",
})
