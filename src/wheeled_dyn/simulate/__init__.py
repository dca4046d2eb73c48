r"""Simulation of wheeled models on their reduced equations."""

from .reduced import Trajectory, energy, simulate

__all__ = ["Trajectory", "energy", "simulate"]
