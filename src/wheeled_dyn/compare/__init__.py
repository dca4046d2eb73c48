r"""The comparison engine: documents' derivations against the truth, term by term."""

from .engine import ComparisonEngine, DerivationResult, ElementRecord, EnergyCheck

__all__ = ["ComparisonEngine", "DerivationResult", "ElementRecord", "EnergyCheck"]
