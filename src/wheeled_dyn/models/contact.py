r"""A ball rolling without slip: what a model spec declares (the constraint itself is
:mod:`wheeled_dyn.constraints.sphere_contact`).

A ball of radius :math:`r` whose centre is the origin of link ``link`` touches a fixed surface:

- ``surface = "plane"``: the ground :math:`z = 0`, the ball above it;
- ``surface = "sphere"``: a fixed sphere of radius :math:`R_1` centred at ``centre``, the ball on
  its outside; the contact point is on the line of centres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import ParameterError

SURFACES = ("plane", "sphere")


@dataclass(frozen=True)
class SphereContact:
    r"""A ball on a fixed surface (see the module docstring). Validated on construction."""

    link: str
    radius: float
    surface: str = "plane"
    surface_radius: float = 0.0
    centre: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        if self.surface not in SURFACES:
            raise ParameterError("contact surface", self.surface, f"one of {SURFACES}")
        if not (isinstance(self.radius, (int, float)) and math.isfinite(self.radius)
                and self.radius > 0):
            raise ParameterError("ball radius", self.radius, "a positive number")
        if self.surface == "sphere" and not self.surface_radius > 0:
            raise ParameterError("fixed sphere radius", self.surface_radius, "a positive number")
        if len(self.centre) != 3:
            raise ParameterError("fixed sphere centre", self.centre, "three coordinates")


@dataclass(frozen=True)
class BallContact:
    r"""A :class:`SphereContact` bound to a built model: ``frame_id`` is the ball link's frame
    (its origin is the ball's centre)."""

    spec: SphereContact
    frame_id: int

    @property
    def radius(self) -> float:
        return float(self.spec.radius)
