r"""The comparison engine: documents' derivations against the truth, term by term."""

from .engine import ComparisonEngine
from .result import (
           Cause,
           Convention,
           ConventionSummary,
           DerivationResult,
           ElementRecord,
           EnergyCheck,
)

__all__ = ["Cause", "ComparisonEngine", "Convention", "ConventionSummary", "DerivationResult",
           "ElementRecord", "EnergyCheck"]
