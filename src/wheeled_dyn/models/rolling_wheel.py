r"""A wheel rolling without slip on the ground plane, on any link: what a model spec declares
(the constraint itself is :mod:`wheeled_dyn.constraints.wheel_contact`).

A wheel is a body of revolution about the spin ``axis`` (a direction in the link frame) through
its ``centre`` (a point in the link frame):

- a thin disk of radius :math:`R` (``tyre_radius = 0``): a knife edge, touching the ground at
  the lowest point of its rim;
- a torus: the centre circle of radius :math:`R` carries a tyre of circular cross-section of
  radius :math:`r` (``tyre_radius``); it touches the ground a distance :math:`r` below the
  lowest point of the centre circle.

Unlike the wheels of a ``planar`` model (:mod:`.builder`), the axle may tilt and the wheel may
be anywhere in the tree (a bicycle's fork, a leg's shank). The model's base is ``fixed`` or
``free``; the ground is the plane :math:`z = 0` of the world (z up).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from .urdf_values import MAX_MODEL_NUMBER, MAX_MODEL_TEXT


@dataclass(frozen=True)
class WheelContact:
    r"""A thin disk or torus wheel on link ``link`` (see the module docstring). Validated on
    construction."""

    link: str
    radius: float
    axis: tuple[float, float, float] = (0.0, 1.0, 0.0)
    centre: tuple[float, float, float] = (0.0, 0.0, 0.0)
    tyre_radius: float = 0.0

    def __post_init__(self) -> None:
        for name, value, positive in (("wheel radius", self.radius, True),
                                      ("tyre radius", self.tyre_radius, False)):
            ok = (isinstance(value, (int, float)) and math.isfinite(value)
                  and value <= MAX_MODEL_NUMBER)
            if not ok or (value <= 0 if positive else value < 0):
                raise ParameterError(f"{name} of {self.link}", value,
                                     ("a positive number" if positive else "a number >= 0")
                                     + f" of at most {MAX_MODEL_TEXT}")
        for name, vec in (("axis", self.axis), ("centre", self.centre)):
            if len(vec) != 3 or not all(math.isfinite(float(x)) for x in vec):
                raise ParameterError(f"wheel {name} of {self.link}", vec, "three finite numbers")
        if float(np.linalg.norm(self.axis)) == 0.0:
            raise ParameterError(f"wheel axis of {self.link}", self.axis, "a non-zero direction")


@dataclass(frozen=True)
class BoundWheelContact:
    r"""A :class:`WheelContact` bound to a built model: ``frame_id`` is the link's body frame,
    ``axis`` the unit spin axis and ``centre`` the wheel centre, both in that frame."""

    spec: WheelContact
    frame_id: int
    axis: np.ndarray
    centre: np.ndarray

    @property
    def radius(self) -> float:
        return float(self.spec.radius)

    @property
    def tyre_radius(self) -> float:
        return float(self.spec.tyre_radius)

    @property
    def link(self) -> str:
        return self.spec.link
