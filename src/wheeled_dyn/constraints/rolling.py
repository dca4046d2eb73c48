r"""Rolling without slip of the drive wheels on the flat ground :math:`z = 0`.

A wheel of radius :math:`R` whose axle stays horizontal touches the ground at
:math:`p = c - R\,e_z` below its centre :math:`c`. The material point of the wheel there must
not move horizontally:

.. math::

    v_p = v_c + \omega \times (p - c) = v_c + R\, e_z\times\omega ,\qquad
    J_c(q) = P\,\big(J_{c,\text{lin}} + R\,[e_z]_\times J_{\omega}\big),\qquad J_c v = 0,

with :math:`P` keeping the world x and y rows (the vertical row vanishes identically for a
body riding on the ground plane) and the Jacobians of the wheel joint in the
``LOCAL_WORLD_ALIGNED`` frame. Its time derivative uses Pinocchio's Jacobian time variation in
the same frame: :math:`\dot J_c = P(\dot J_{c,\text{lin}} + R\,[e_z]_\times \dot J_\omega)`.
Two wheels on one axle give four rows of rank three (their lateral rows coincide): the
reduction handles the redundancy by least squares, which is exact because the system is
consistent.

The functions here serve every rolling contact of a model: the wheels' rows, then those of a
rolling ball (:mod:`.sphere_contact`, three rows) when the model declares one, then three per
tilting wheel (:mod:`.wheel_contact`). A model with
neither has no rows (:math:`J_c` is 0 × nv).
"""

from __future__ import annotations

from functools import lru_cache
from typing import overload

import numpy as np
import pinocchio as pin

from ..models.builder import WheeledModel
from .sphere_contact import ball_contact_point, ball_contact_velocity, ball_jacobian

_EZ_CROSS = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
_LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


@overload
def contact_jacobian(wm: WheeledModel, q: np.ndarray, v: None = None,
                     data: pin.Data | None = None) -> tuple[np.ndarray, None]: ...


@overload
def contact_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray,
                     data: pin.Data | None = None) -> tuple[np.ndarray, np.ndarray]: ...


@overload
def contact_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray | None = None,
                     data: pin.Data | None = None
                     ) -> tuple[np.ndarray, np.ndarray | None]: ...


def contact_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray | None = None,
                     data: pin.Data | None = None) -> tuple[np.ndarray, np.ndarray | None]:
    r""":math:`J_c(q)` (2·wheels [+ 3 for a ball] × nv) and, if ``v`` is given,
    :math:`\dot J_c(q, v)`."""
    model = wm.model
    data = data or model.createData()
    if v is None:
        pin.computeJointJacobians(model, data, q)
    else:
        pin.computeJointJacobiansTimeVariation(model, data, q, v)   # fills data.J too
    rows, drows = [np.zeros((0, model.nv))], [np.zeros((0, model.nv))]
    for wheel in wm.wheels:
        J = pin.getJointJacobian(model, data, wheel.joint_id, _LWA)
        rows.append((J[:3] + wheel.radius * _EZ_CROSS @ J[3:])[:2])
        if v is not None:
            dJ = pin.getJointJacobianTimeVariation(model, data, wheel.joint_id, _LWA)
            drows.append((dJ[:3] + wheel.radius * _EZ_CROSS @ dJ[3:])[:2])
    if wm.contact is not None:
        Jb, dJb = ball_jacobian(wm, q, v, data)
        rows.append(Jb)
        if dJb is not None:                    # v given
            drows.append(dJb)
    if wm.rolling_wheels:                      # tilting wheels: 3 rows each (.wheel_contact)
        from .wheel_contact import wheel_jacobian
        Jw, dJw = wheel_jacobian(wm, q, v, data)
        rows.append(Jw)
        if dJw is not None:                    # v given
            drows.append(dJw)
    return np.vstack(rows), (np.vstack(drows) if v is not None else None)


@lru_cache(maxsize=None)
def _rolling_select(radius: float) -> np.ndarray:
    r"""The rows x and y of :math:`[I_3\;\; R[e_z]_\times]`: a wheel joint's 6-row Jacobian
    (or its acceleration) to its rolling rows (:math:`J_x - R J_{\omega_y}`,
    :math:`J_y + R J_{\omega_x}`)."""
    return np.array([[1.0, 0.0, 0.0, 0.0, -radius, 0.0], [0.0, 1.0, 0.0, radius, 0.0, 0.0]])


def planar_rows(wm: WheeledModel, data: pin.Data) -> np.ndarray:
    r""":math:`J_c` of the drive wheels (2·wheels × nv) from the joint Jacobians already in
    ``data`` (left there by ``crba`` in the world convention, or ``computeJointJacobians``):
    per wheel the world x and y rows of :math:`J_{lin} + R [e_z]_\times J_\omega`."""
    model = wm.model
    out = np.empty((2 * len(wm.wheels), model.nv))
    for k, wheel in enumerate(wm.wheels):
        np.matmul(_rolling_select(wheel.radius),
                  pin.getJointJacobian(model, data, wheel.joint_id, _LWA), out=out[2 * k:2 * k + 2])
    return out


def planar_drift(wm: WheeledModel, data: pin.Data, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    r""":math:`\dot J_c v` of the drive wheels: with :math:`\ddot q = 0` the classical
    acceleration of each wheel joint's origin and its angular acceleration are
    :math:`\dot J v` (``forwardKinematics(q, v, 0)``), taken through the same rows."""
    model = wm.model
    pin.forwardKinematics(model, data, q, v, np.zeros(model.nv))
    out = np.empty(2 * len(wm.wheels))
    for k, wheel in enumerate(wm.wheels):
        a = pin.getClassicalAcceleration(model, data, wheel.joint_id, _LWA).vector
        np.matmul(_rolling_select(wheel.radius), a, out=out[2 * k:2 * k + 2])
    return out


def contact_points(wm: WheeledModel, q: np.ndarray) -> np.ndarray:
    r"""World positions of the contact points (one row per wheel)."""
    data = wm.model.createData()
    pin.forwardKinematics(wm.model, data, q)
    points = [data.oMi[w.joint_id].translation - [0.0, 0.0, w.radius] for w in wm.wheels]
    if wm.contact is not None:
        points.append(ball_contact_point(wm, q))
    if wm.rolling_wheels:
        from .wheel_contact import wheel_contact_points
        points.extend(wheel_contact_points(wm, q))
    return np.array(points).reshape(-1, 3)


def contact_velocities(wm: WheeledModel, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    r"""Velocity (world frame, 3 components) of each wheel's material point at its contact,
    computed from the frame velocity of the wheel (independently of :func:`contact_jacobian`)."""
    data = wm.model.createData()
    pin.forwardKinematics(wm.model, data, q, v)
    out = []
    for w in wm.wheels:
        vel = pin.getVelocity(wm.model, data, w.joint_id, _LWA)
        out.append(vel.linear + np.cross(vel.angular, [0.0, 0.0, -w.radius]))
    if wm.contact is not None:
        out.append(ball_contact_velocity(wm, q, v))
    if wm.rolling_wheels:
        from .wheel_contact import wheel_contact_velocities
        out.extend(wheel_contact_velocities(wm, q, v))
    return np.array(out).reshape(-1, 3)
