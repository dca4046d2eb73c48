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

A body that is not a ball: given ``polar_radius`` :math:`c`, the body is the spheroid (ellipsoid
of revolution)

.. math::

    \frac{x^2 + y^2}{a^2} + \frac{z^2}{c^2} = 1

in the link frame (centre at the link origin, axis of revolution the link's z), with
:math:`a` = ``radius`` its equatorial radius: oblate for :math:`c < a`, prolate for
:math:`c > a`, the ball again for :math:`c = a`. It rolls on the ground plane only
(``surface = "plane"``); its constraint is :mod:`wheeled_dyn.constraints.spheroid_contact`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import ParameterError
from .urdf_values import MAX_MODEL_NUMBER, MAX_MODEL_TEXT

SURFACES = ("plane", "sphere", "paraboloid")


def _positive(x: object) -> bool:
    r"""A finite positive number (not a bool) of at most
    :data:`~.urdf_values.MAX_MODEL_NUMBER`."""
    return (isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)
            and 0 < x <= MAX_MODEL_NUMBER)


@dataclass(frozen=True)
class SphereContact:
    r"""A ball on a fixed surface, or (``polar_radius`` given) a spheroid on the ground (see
    the module docstring). Validated on construction."""

    link: str
    radius: float
    surface: str = "plane"
    surface_radius: float = 0.0
    centre: tuple[float, float, float] = (0.0, 0.0, 0.0)
    vertex_radius: float = 0.0
    polar_radius: float | None = None

    @property
    def spheroid(self) -> bool:
        r"""Whether the body is the spheroid of ``radius`` (equatorial) and ``polar_radius``
        rather than a ball (see the module docstring)."""
        return self.polar_radius is not None

    def __post_init__(self) -> None:
        if self.surface not in SURFACES:
            raise ParameterError("contact surface", self.surface, f"one of {SURFACES}")
        if not _positive(self.radius):
            name = "spheroid equatorial radius (radius)" if self.spheroid else "ball radius"
            raise ParameterError(name, self.radius,
                                 f"a positive number of at most {MAX_MODEL_TEXT}")
        if self.spheroid:
            self._check_spheroid()
        if self.surface == "sphere" and not self.surface_radius > 0:
            raise ParameterError("fixed sphere radius", self.surface_radius, "a positive number")
        if len(self.centre) != 3:
            raise ParameterError("fixed sphere centre", self.centre, "three coordinates")
        if self.surface == "paraboloid":
            self._check_paraboloid()
        elif self.vertex_radius:
            raise ParameterError("vertex_radius", self.vertex_radius,
                                 "no value: it belongs to surface = 'paraboloid'")

    def _check_spheroid(self) -> None:
        if not _positive(self.polar_radius):
            raise ParameterError("spheroid polar radius (polar_radius)", self.polar_radius,
                                 "a positive number")
        if self.surface != "plane":
            raise ParameterError("polar_radius", self.polar_radius,
                                 f"no value for surface = {self.surface!r}: a spheroid rolls on "
                                 "surface = 'plane' only")

    def _check_paraboloid(self) -> None:
        a = self.vertex_radius
        if not _positive(a):
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
        r"""The ball's radius (a spheroid's equatorial radius :math:`a`)."""
        return float(self.spec.radius)

    @property
    def polar_radius(self) -> float | None:
        r"""A spheroid's polar radius :math:`c` (None for a ball)."""
        return None if self.spec.polar_radius is None else float(self.spec.polar_radius)
