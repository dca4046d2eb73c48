r"""Shapes drawn by the viewer: stand-in bodies, joint triads, the centre-of-mass ball, the ground.

A model without meshes still deserves a picture. :func:`fallback_visual_model` gives every
body that has mass a box with the *same principal moments of inertia* as the body (its
equivalent uniform box), and every wheel a cylinder of the wheel's radius and width about the
wheel's spin axis. For a uniform box of mass :math:`m` and sides :math:`a, b, c`,

.. math::

    I_a = \tfrac{m}{12}(b^2 + c^2),\quad I_b = \tfrac{m}{12}(a^2 + c^2),\quad
    I_c = \tfrac{m}{12}(a^2 + b^2)
    \quad\Longrightarrow\quad
    a^2 = \tfrac{6}{m}(I_b + I_c - I_a)\ \text{(and cyclically)},

with :math:`I_a, I_b, I_c` the eigenvalues of the rotational inertia about the centre of mass
and the box's axes along its eigenvectors. A sliver (a side whose square comes out below
:data:`MIN_SIDE`\ ²) is drawn :data:`MIN_SIDE` thick so that it stays visible.

The other builders return meshcat objects: a triad (x red, y green, z blue line segments), a
ball, and a square grid of lines in the plane z = 0.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import coal
import meshcat.geometry as mg
import numpy as np
import pinocchio as pin

#: Smallest side of a stand-in box, in metres.
MIN_SIDE = 0.01
#: RGBA colour of stand-in bodies.
BODY_COLOR = np.array([0.55, 0.62, 0.75, 1.0])
#: RGBA colour of stand-in wheels.
WHEEL_COLOR = np.array([0.15, 0.15, 0.15, 1.0])
#: Colour (0xRRGGBB) of the centre-of-mass ball.
COM_COLOR = 0xE8590C
#: Colour (0xRRGGBB) of the ground grid lines.
GROUND_COLOR = 0x8899AA


class WheelLike(Protocol):
    r"""What the viewer needs to know about a wheel."""

    joint_id: int
    radius: float
    width: float


def joint_axis(model: pin.Model, joint_id: int) -> np.ndarray:
    r"""The unit rotation axis of a 1-DoF revolute joint, in the joint's frame (its motion
    subspace's angular part). Raises ``ValueError`` for a joint that does not rotate."""
    data = model.createData()
    pin.forwardKinematics(model, data, pin.neutral(model))
    S = np.asarray(data.joints[joint_id].S, dtype=float).reshape(6, -1)
    if S.shape[1] != 1 or np.linalg.norm(S[3:, 0]) == 0.0:
        raise ValueError(f"joint {model.names[joint_id]!r} is not a 1-DoF revolute joint")
    return S[3:, 0] / np.linalg.norm(S[3:, 0])


def rotation_z_to(axis: np.ndarray) -> np.ndarray:
    r"""A rotation matrix taking the z axis onto ``axis`` (coal cylinders are along z)."""
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    return pin.Quaternion.FromTwoVectors(np.array([0.0, 0.0, 1.0]), axis).toRotationMatrix()


def equivalent_box(inertia: pin.Inertia) -> tuple[np.ndarray, np.ndarray]:
    r"""Sides (3,) and axes (3×3 rotation, columns = box axes in the body frame) of the uniform
    box with the mass and principal moments of ``inertia`` (see the module docstring)."""
    m = float(inertia.mass)
    moments, axes = np.linalg.eigh(np.asarray(inertia.inertia, dtype=float))
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    total = moments.sum()
    squares = 6.0 / m * (total - 2.0 * moments)      # a² = 6/m (I_b + I_c - I_a)
    sides = np.sqrt(np.clip(squares, MIN_SIDE ** 2, None))
    return sides, axes


def fallback_visual_model(model: pin.Model, wheels: Sequence[WheelLike] = ()) -> pin.GeometryModel:
    r"""A visual model of simple shapes: an equivalent-inertia box for each body with mass that
    is not a wheel, a cylinder for each wheel (see the module docstring)."""
    geom = pin.GeometryModel()
    wheel_ids = {int(w.joint_id) for w in wheels}
    for w in wheels:
        jid = int(w.joint_id)
        R = rotation_z_to(joint_axis(model, jid))
        obj = pin.GeometryObject(f"{model.names[jid]}_wheel", jid, pin.SE3(R, np.zeros(3)),
                                 coal.Cylinder(float(w.radius), float(w.width)))
        obj.meshColor = WHEEL_COLOR.copy()
        geom.addGeometryObject(obj)
    for jid in range(1, model.njoints):
        inertia = model.inertias[jid]
        if jid in wheel_ids or not inertia.mass > 0:
            continue
        sides, axes = equivalent_box(inertia)
        obj = pin.GeometryObject(f"{model.names[jid]}_body", jid,
                                 pin.SE3(axes, np.asarray(inertia.lever, dtype=float).copy()),
                                 coal.Box(*sides))
        obj.meshColor = BODY_COLOR.copy()
        geom.addGeometryObject(obj)
    return geom


_TRIAD_POSITIONS = np.array([[0, 0, 0], [1, 0, 0], [0, 0, 0], [0, 1, 0], [0, 0, 0], [0, 0, 1]],
                            dtype=np.float32).T
_TRIAD_COLORS = np.array([[1, 0, 0], [1, 0, 0], [0, 1, 0], [0, 1, 0], [0, 0, 1], [0, 0, 1]],
                         dtype=np.float32).T


def triad(length: float) -> mg.LineSegments:
    r"""Three line segments of ``length`` along x (red), y (green), z (blue), drawn on top."""
    return mg.LineSegments(mg.PointsGeometry(position=length * _TRIAD_POSITIONS,
                                             color=_TRIAD_COLORS),
                           mg.LineBasicMaterial(vertexColors=True, linewidth=2,
                                                depthTest=False))


def ball(radius: float, color: int = COM_COLOR) -> mg.Mesh:
    r"""A sphere of ``radius``, drawn on top of everything else (the centre of mass is usually
    inside a body)."""
    return mg.Mesh(mg.Sphere(radius), mg.MeshLambertMaterial(color=color, depthTest=False,
                                                             transparent=True, opacity=0.9))


def ground_grid(half_size: float, step: float, color: int = GROUND_COLOR) -> mg.LineSegments:
    r"""Lines every ``step`` metres in the plane z = 0, from -``half_size`` to +``half_size``."""
    n = max(1, int(round(half_size / step)))
    ticks = np.arange(-n, n + 1) * step
    h = n * step
    pts: list[Any] = []
    for t in ticks:
        pts += [(t, -h, 0.0), (t, h, 0.0), (-h, t, 0.0), (h, t, 0.0)]
    return mg.LineSegments(mg.PointsGeometry(position=np.array(pts, dtype=np.float32).T),
                           mg.LineBasicMaterial(color=color))
