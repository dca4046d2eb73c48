r"""A ball rolling without slip: what a model spec declares (the constraint itself is
:mod:`wheeled_dyn.constraints.sphere_contact`).

A ball of radius :math:`r` whose centre is the origin of link ``link`` touches a fixed surface:

- ``surface = "plane"``: the ground :math:`z = 0`, the ball above it;
- ``surface = "sphere"``: a fixed sphere of radius :math:`R_1` centred at ``centre``, the ball on
  its outside; the contact point is on the line of centres;
- ``surface = "paraboloid"``: the bowl :math:`z = o_z + \rho^2/(2a)` about the vertical axis
  through ``centre`` :math:`= o` (:math:`\rho` the horizontal distance from that axis), the ball
  inside it. :math:`a` (``vertex_radius``) is the radius of curvature at the vertex, the
  smallest of the surface: the ball touches the bowl at one point only if :math:`r < a` (a
  larger ball would rest on a circle around the vertex), so that is required. The geometry of
  the contact (any surface of revolution) is :mod:`wheeled_dyn.constraints.surfaces`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import ParameterError

SURFACES = ("plane", "sphere", "paraboloid")


@dataclass(frozen=True)
class SphereContact:
    r"""A ball on a fixed surface (see the module docstring). Validated on construction."""

    link: str
    radius: float
    surface: str = "plane"
    surface_radius: float = 0.0
    centre: tuple[float, float, float] = (0.0, 0.0, 0.0)
    vertex_radius: float = 0.0

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
        if self.surface == "paraboloid":
            self._check_paraboloid()
        elif self.vertex_radius:
            raise ParameterError("vertex_radius", self.vertex_radius,
                                 "no value: it belongs to surface = 'paraboloid'")

    def _check_paraboloid(self) -> None:
        a = self.vertex_radius
        if not (isinstance(a, (int, float)) and math.isfinite(a) and a > 0):
            raise ParameterError("paraboloid vertex_radius (radius of curvature at the vertex)",
                                 a, "a positive number")
        if self.surface_radius:
            raise ParameterError("surface_radius", self.surface_radius,
                                 "no value for surface = 'paraboloid' (its size is vertex_radius)")
        if not self.radius < a:
            raise ParameterError("ball radius", self.radius,
                                 f"less than the paraboloid's vertex_radius a = {a} (its "
                                 "radius of curvature at the vertex): a ball with r >= a does "
                                 "not touch the bowl at a single point")


@dataclass(frozen=True)
class BallContact:
    r"""A :class:`SphereContact` bound to a built model: ``frame_id`` is the ball link's frame
    (its origin is the ball's centre)."""

    spec: SphereContact
    frame_id: int

    @property
    def radius(self) -> float:
        return float(self.spec.radius)
