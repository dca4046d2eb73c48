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
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..models.builder import WheeledModel

_EZ_CROSS = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
_LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def contact_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray | None = None,
                     data: pin.Data | None = None) -> tuple[np.ndarray, np.ndarray | None]:
    r""":math:`J_c(q)` (2·wheels × nv) and, if ``v`` is given, :math:`\dot J_c(q, v)`."""
    model = wm.model
    data = data or model.createData()
    if v is None:
        pin.computeJointJacobians(model, data, q)
    else:
        pin.computeJointJacobiansTimeVariation(model, data, q, v)
        pin.computeJointJacobians(model, data, q)
    rows, drows = [], []
    for wheel in wm.wheels:
        J = pin.getJointJacobian(model, data, wheel.joint_id, _LWA)
        rows.append((J[:3] + wheel.radius * _EZ_CROSS @ J[3:])[:2])
        if v is not None:
            dJ = pin.getJointJacobianTimeVariation(model, data, wheel.joint_id, _LWA)
            drows.append((dJ[:3] + wheel.radius * _EZ_CROSS @ dJ[3:])[:2])
    return np.vstack(rows), (np.vstack(drows) if v is not None else None)


def contact_points(wm: WheeledModel, q: np.ndarray) -> np.ndarray:
    r"""World positions of the contact points (one row per wheel)."""
    data = wm.model.createData()
    pin.forwardKinematics(wm.model, data, q)
    return np.array([data.oMi[w.joint_id].translation - [0.0, 0.0, w.radius] for w in wm.wheels])


def contact_velocities(wm: WheeledModel, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    r"""Velocity (world frame, 3 components) of each wheel's material point at its contact,
    computed from the frame velocity of the wheel (independently of :func:`contact_jacobian`)."""
    data = wm.model.createData()
    pin.forwardKinematics(wm.model, data, q, v)
    out = []
    for w in wm.wheels:
        vel = pin.getVelocity(wm.model, data, w.joint_id, _LWA)
        out.append(vel.linear + np.cross(vel.angular, [0.0, 0.0, -w.radius]))
    return np.array(out)
