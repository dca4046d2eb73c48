r"""Rolling without slip of a spheroid (an ellipsoid of revolution) on the ground plane.

The body's surface is, in its link frame (origin at the centre, axis of revolution the link's
z axis),

.. math::

    \frac{x^2 + y^2}{a^2} + \frac{z^2}{c^2} = 1 ,\qquad\text{i.e.}\qquad
    x^T A^{-1} x = 1,\quad A = \operatorname{diag}(a^2, a^2, c^2),

:math:`a` the equatorial radius, :math:`c` the polar radius
(:class:`~wheeled_dyn.models.contact.SphereContact` with ``polar_radius``). The link frame has
the rotation :math:`R` (body axes to world) and the origin :math:`o`. The ground is
:math:`z = 0`, the body above it.

**Contact point.** With :math:`u = R^T(-e_z)` the world's downward direction in body axes, the
lowest point of the body maximises :math:`u^T x` on the surface; the condition
:math:`u = \lambda A^{-1}x` of a stationary point gives

.. math::

    p = \frac{A\,u}{s},\qquad s = \sqrt{u^T A\,u}
      = \sqrt{a^2 - (a^2 - c^2)\,(e_3\cdot e_z)^2}

(body axes; :math:`e_3 = R\,e_z` the axis in world axes), the point whose outward normal
:math:`A^{-1}p \propto u` points straight down. Its depth below the centre is
:math:`u^T p = s` (:math:`s > 0` for every orientation: :math:`A` is positive definite, so the
contact is defined everywhere). The holonomic condition that the body touches the ground is

.. math::

    g(q) = o_z - s = 0 ,

so the touching configurations have the centre at the height :math:`s` of the given orientation
(:func:`spheroid_height`, :func:`place_on_ground`).

**Rows** (three, world x, y, z): the velocity of the body's *material* point at the contact,
with :math:`\rho = R\,p` (world axes, from :math:`o`),

.. math::

    v_p = v_o + \omega\times\rho,\qquad J_c = J_{o,\text{lin}} - [\rho]_\times J_\omega ,

Jacobians of the link frame in ``LOCAL_WORLD_ALIGNED`` (origin velocity and angular velocity
in world axes; the convention of :mod:`.wheel_contact`). The x and y rows are the no-slip
conditions; the z row is :math:`\dot g`: from :math:`ds = u^T A\,du/s = p^T du`,

.. math::

    \dot g = \dot o_z - p^T\dot u = \dot o_z - \omega_B\cdot(p\times u)
           = e_z\cdot(v_o + \omega\times\rho),

since :math:`e_z\cdot(\omega\times R p) = -u\cdot(\omega_B\times p)` with
:math:`\omega_B = R^T\omega` (the contact point moves over the body along the tangent plane,
so only the material velocity enters).

**Time derivative.** The contact point moves over the body as the body turns:

.. math::

    \dot u = \dot R^T(-e_z) = -[\omega_B]_\times u = u\times\omega_B ,\qquad
    \dot p = \Big(\frac{A}{s} - \frac{A u\,u^T A}{s^3}\Big)\dot u
           = \frac{A\,\dot u - p\,(p^T\dot u)}{s},

so :math:`\dot\rho = \dot R\,p + R\,\dot p = \omega\times\rho + R\,\dot p` and

.. math::

    \dot J_c = \dot J_{o,\text{lin}} - [\rho]_\times\dot J_\omega - [\dot\rho]_\times J_\omega ,

with Pinocchio's Jacobian time variation in the same frame. For :math:`a = c = r`,
:math:`p = r\,u`, :math:`\rho = -r\,e_z` and :math:`\dot\rho = 0`: the rows of a ball on the
plane, :math:`J_{o,\text{lin}} + r\,[e_z]_\times J_\omega` (:mod:`.sphere_contact`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import overload

import numpy as np
import pinocchio as pin

from ..errors import ModelError
from ..models.builder import WheeledModel
from ..models.contact import BallContact

_LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def _cross(x: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -x[2], x[1]], [x[2], 0.0, -x[0]], [-x[1], x[0], 0.0]])


def ball_contact(wm: WheeledModel) -> BallContact:
    r"""The model's rolling ball or spheroid; a :class:`~wheeled_dyn.errors.ModelError` for a
    model without one."""
    if wm.contact is None:
        raise ModelError(wm.name, None, "has no rolling ball or spheroid to take the contact of")
    return wm.contact


def _radii(contact: BallContact, model: str) -> tuple[float, float]:
    r"""The equatorial and polar radii :math:`a, c` of a spheroid contact."""
    c = contact.polar_radius
    if c is None:
        raise ModelError(model, None, "its contact is a ball, not a spheroid (no polar_radius)")
    return contact.radius, c


def lowest_point(a: float, c: float, u: np.ndarray) -> tuple[np.ndarray, float]:
    r"""The point :math:`p = A u/s` (body axes) of the spheroid of equatorial radius ``a`` and
    polar radius ``c`` whose outward normal is the unit vector ``u`` (body axes), and its
    depth :math:`s = \sqrt{u^TAu}` along ``u`` below the centre."""
    diag = np.array([a * a, a * a, c * c])
    Au = diag * np.asarray(u, dtype=float)
    s = float(np.sqrt(u @ Au))
    return Au / s, s


def lowest_point_rate(a: float, c: float, u: np.ndarray, udot: np.ndarray) -> np.ndarray:
    r""":math:`\dot p = (A\dot u - p\,(p^T\dot u))/s`: the rate of :func:`lowest_point` when
    ``u`` changes at ``udot`` (body axes)."""
    diag = np.array([a * a, a * a, c * c])
    p, s = lowest_point(a, c, u)
    udot = np.asarray(udot, dtype=float)
    return (diag * udot - p * (p @ udot)) / s


@dataclass(frozen=True)
class SpheroidPoint:
    r"""Geometry of the contact (see the module docstring): the link's ``origin`` and
    ``rotation``, the downward direction ``u`` and the contact point ``p`` in body axes, the
    depth ``s``, :math:`\rho = R\,p` and the contact point ``point`` (world)."""

    origin: np.ndarray
    rotation: np.ndarray
    u: np.ndarray
    p: np.ndarray
    s: float
    rho: np.ndarray
    point: np.ndarray


def spheroid_point(wm: WheeledModel, data: pin.Data) -> SpheroidPoint:
    r"""The contact geometry of the model's spheroid from ``data`` (joint placements up to
    date)."""
    contact = ball_contact(wm)
    H = pin.updateFramePlacement(wm.model, data, contact.frame_id).homogeneous
    R, o = H[:3, :3].copy(), H[:3, 3].copy()
    u = -R[2]
    p, s = lowest_point(*_radii(contact, wm.name), u)
    rho = R @ p
    return SpheroidPoint(o, R, u, p, s, rho, o + rho)


@overload
def spheroid_jacobian(wm: WheeledModel, q: np.ndarray, v: None = None,
                      data: pin.Data | None = None) -> tuple[np.ndarray, None]: ...


@overload
def spheroid_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray,
                      data: pin.Data | None = None) -> tuple[np.ndarray, np.ndarray]: ...


@overload
def spheroid_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray | None = None,
                      data: pin.Data | None = None
                      ) -> tuple[np.ndarray, np.ndarray | None]: ...


def spheroid_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray | None = None,
                      data: pin.Data | None = None) -> tuple[np.ndarray, np.ndarray | None]:
    r""":math:`J_c(q)` (3 × nv: world x, y, z of the material contact point's velocity) and,
    if ``v`` is given, :math:`\dot J_c(q, v)` (see the module docstring)."""
    model = wm.model
    data = data or model.createData()
    contact = ball_contact(wm)
    fid = contact.frame_id
    if v is None:
        pin.computeJointJacobians(model, data, q)
    else:
        pin.computeJointJacobiansTimeVariation(model, data, q, v)   # fills data.J too
    g = spheroid_point(wm, data)
    J = pin.getFrameJacobian(model, data, fid, _LWA)
    Jw = J[3:]
    Jc = J[:3] - _cross(g.rho) @ Jw
    if v is None:
        return Jc, None
    dJ = pin.getFrameJacobianTimeVariation(model, data, fid, _LWA)
    omega = Jw @ v
    udot = np.cross(g.u, g.rotation.T @ omega)
    pdot = lowest_point_rate(*_radii(contact, wm.name), g.u, udot)
    rhodot = np.cross(omega, g.rho) + g.rotation @ pdot
    return Jc, dJ[:3] - _cross(g.rho) @ dJ[3:] - _cross(rhodot) @ Jw


def spheroid_contact_point(wm: WheeledModel, q: np.ndarray) -> np.ndarray:
    r"""World position of the contact point: the lowest point of the body."""
    data = wm.model.createData()
    pin.framesForwardKinematics(wm.model, data, q)
    return spheroid_point(wm, data).point


def spheroid_height(wm: WheeledModel, q: np.ndarray) -> float:
    r"""The holonomic condition :math:`g(q) = o_z - s`: the height of the body's lowest point
    above the ground (0 when it touches, negative when it sinks in)."""
    return float(spheroid_contact_point(wm, q)[2])


def spheroid_contact_velocity(wm: WheeledModel, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    r"""Velocity (world axes) of the body's material point at the contact, from the frame
    velocity of the link (independently of :func:`spheroid_jacobian`)."""
    data = wm.model.createData()
    pin.forwardKinematics(wm.model, data, q, v)
    pin.updateFramePlacements(wm.model, data)
    g = spheroid_point(wm, data)
    vel = pin.getFrameVelocity(wm.model, data, ball_contact(wm).frame_id, _LWA)
    return vel.linear + np.cross(vel.angular, g.rho)


def place_on_ground(wm: WheeledModel, q: np.ndarray) -> np.ndarray:
    r"""``q`` with the free base's height ``z0`` changed so that the body touches the ground
    (:math:`g(q) = 0`; the orientation and the horizontal position are kept). A vertical
    translation of the base moves the body rigidly, so one step is exact."""
    if "z0" not in wm.coordinate_names:
        raise ModelError(wm.name, None, "placing the spheroid on the ground moves the free "
                                        "base's height z0; this model has none")
    q = np.array(q, dtype=float)
    q[wm.index("z0")] -= spheroid_height(wm, q)
    return q
