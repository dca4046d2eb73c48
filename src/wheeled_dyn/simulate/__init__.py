r"""Simulation of wheeled models on their reduced equations."""

from .._lazy import attach

__getattr__, __dir__, __all__ = attach(__name__, {
    "simulate_fast": ".fast",
    "Trajectory": ".reduced",
    "energy": ".reduced",
    "simulate": ".reduced",
})
