r"""Rolling without slip of a ball on the ground plane, on a fixed sphere or in a fixed surface
of revolution (a paraboloid bowl).

A ball of radius :math:`r` has its centre :math:`c` at the origin of its link. It touches

- the plane :math:`z = 0` at :math:`p = c - r\,n` with :math:`n = e_z`;
- a fixed sphere of radius :math:`R_1` and centre :math:`o` (ball outside) on the line of
  centres, :math:`p = c - r\,n` with :math:`n = (c - o)/\lVert c - o\rVert` (the outward normal
  of the fixed sphere at the contact);
- a surface of revolution about the vertical axis through :math:`o` (the ball on its upper
  side, e.g. inside a paraboloid bowl) at :math:`p = c - r\,n`, with :math:`n(c_x, c_y)` the
  surface's normal at the point whose offset by :math:`r` is the centre
  (:mod:`.surfaces`).

The material point of the ball at :math:`p` must not move:

.. math::

    v_p = v_c + \omega\times(p - c) = v_c + r\,n\times\omega ,\qquad
    J_c(q) = J_{c,\text{lin}} + r\,[n]_\times J_\omega ,\qquad J_c v = 0 ,

three rows in world axes, with the Jacobians of the ball's frame in ``LOCAL_WORLD_ALIGNED``
(origin velocity and angular velocity in world axes). The normal row is the velocity form of
the holonomic condition that the ball stays on the surface (:math:`\dot z = 0`,
:math:`\tfrac{d}{dt}\lVert c - o\rVert = 0`, or :math:`c` moving on the offset surface of the
surface of revolution, whose normal is :math:`n`); the two tangential rows are the nonholonomic
no-slip conditions. The time derivative, for :math:`\dot J_c v` in the constrained equations
and :math:`\dot S` in the reduced ones, is

.. math::

    \dot J_c = \dot J_{c,\text{lin}} + r\,[n]_\times\dot J_\omega + r\,[\dot n]_\times J_\omega,
    \qquad \dot n = \frac{(1 - n n^T)\,\dot c}{\lVert c - o\rVert},\quad \dot c = J_{c,\text{lin}}v

(:math:`\dot n = 0` on the plane). In a surface of revolution with shape operator :math:`W`
at the contact, :math:`\dot n = W(1 + rW)^{-1}\dot c_T` (:func:`.surfaces.normal_rate`), which
is the sphere's rule above for :math:`W = (1 - nn^T)/R_1`.

A contact declared with ``polar_radius`` is a spheroid on the plane, not a ball: the three
functions below hand it to :mod:`.spheroid_contact` (same rows: world x, y, z of the material
contact point's velocity).
"""

from __future__ import annotations

from typing import overload

import numpy as np
import pinocchio as pin

from ..models.builder import WheeledModel
from .spheroid_contact import (ball_contact, spheroid_contact_point, spheroid_contact_velocity,
                               spheroid_jacobian)
from .surfaces import Foot, foot, meridian_of, normal_rate

_LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
_EZ = np.array([0.0, 0.0, 1.0])
#: Rows of the contact Jacobian of one ball.
ROWS = 3


def _cross(a: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _revolution_foot(wm: WheeledModel, centre: np.ndarray) -> Foot | None:
    r"""The contact with a surface of revolution (:mod:`.surfaces`), or None for the plane
    and the sphere."""
    spec = ball_contact(wm).spec
    meridian = meridian_of(spec)
    if meridian is None:
        return None
    return foot(meridian, np.asarray(spec.centre, dtype=float), centre, float(spec.radius))


def contact_normal(wm: WheeledModel, centre: np.ndarray) -> np.ndarray:
    r"""The surface normal :math:`n` at the contact of a ball centred at ``centre``."""
    spec = ball_contact(wm).spec
    if spec.surface == "plane":
        return _EZ.copy()
    ft = _revolution_foot(wm, centre)
    if ft is not None:
        return ft.normal
    d = centre - np.asarray(spec.centre, dtype=float)
    return d / np.linalg.norm(d)


@overload
def ball_jacobian(wm: WheeledModel, q: np.ndarray, v: None = None,
                  data: pin.Data | None = None) -> tuple[np.ndarray, None]: ...


@overload
def ball_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray,
                  data: pin.Data | None = None) -> tuple[np.ndarray, np.ndarray]: ...


@overload
def ball_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray | None = None,
                  data: pin.Data | None = None
                  ) -> tuple[np.ndarray, np.ndarray | None]: ...


def ball_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray | None = None,
                  data: pin.Data | None = None) -> tuple[np.ndarray, np.ndarray | None]:
    r""":math:`J_c(q)` (3 × nv) of the ball and, if ``v`` is given, :math:`\dot J_c(q, v)`."""
    contact = ball_contact(wm)
    if contact.spec.spheroid:
        return spheroid_jacobian(wm, q, v, data)
    model = wm.model
    data = data or model.createData()
    fid, r = contact.frame_id, contact.radius
    if v is None:
        pin.computeJointJacobians(model, data, q)
    else:
        pin.computeJointJacobiansTimeVariation(model, data, q, v)   # fills data.J too
    pin.updateFramePlacements(model, data)
    J = pin.getFrameJacobian(model, data, fid, _LWA)
    centre = data.oMf[fid].translation
    ft = _revolution_foot(wm, centre)
    n = contact_normal(wm, centre) if ft is None else ft.normal
    Jc = J[:3] + r * _cross(n) @ J[3:]
    if v is None:
        return Jc, None
    dJ = pin.getFrameJacobianTimeVariation(model, data, fid, _LWA)
    dJc = dJ[:3] + r * _cross(n) @ dJ[3:]
    cdot = J[:3] @ v
    if ft is not None:
        dJc = dJc + r * _cross(normal_rate(ft, r, cdot)) @ J[3:]
    elif contact.spec.surface == "sphere":
        dist = np.linalg.norm(centre - np.asarray(contact.spec.centre, dtype=float))
        ndot = (cdot - n * (n @ cdot)) / dist
        dJc = dJc + r * _cross(ndot) @ J[3:]
    return Jc, dJc


def ball_contact_point(wm: WheeledModel, q: np.ndarray) -> np.ndarray:
    r"""World position of the contact point :math:`p = c - r\,n`."""
    contact = ball_contact(wm)
    if contact.spec.spheroid:
        return spheroid_contact_point(wm, q)
    data = wm.model.createData()
    pin.framesForwardKinematics(wm.model, data, q)
    centre = data.oMf[contact.frame_id].translation
    return centre - contact.radius * contact_normal(wm, centre)


def ball_contact_velocity(wm: WheeledModel, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    r"""Velocity (world axes) of the ball's material point at the contact, from the frame
    velocity of the ball (independently of :func:`ball_jacobian`)."""
    contact = ball_contact(wm)
    if contact.spec.spheroid:
        return spheroid_contact_velocity(wm, q, v)
    data = wm.model.createData()
    pin.forwardKinematics(wm.model, data, q, v)
    pin.updateFramePlacements(wm.model, data)
    fid = contact.frame_id
    vel = pin.getFrameVelocity(wm.model, data, fid, _LWA)
    n = contact_normal(wm, data.oMf[fid].translation)
    return vel.linear + np.cross(vel.angular, -contact.radius * n)
