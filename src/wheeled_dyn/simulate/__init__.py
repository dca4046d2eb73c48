r"""Simulation of wheeled models on their reduced equations."""

from .fast import simulate_fast
from .reduced import Trajectory, energy, simulate

__all__ = ["Trajectory", "energy", "simulate", "simulate_fast"]
