r"""Rolling without slip of a tilting wheel (thin disk or torus) on the ground plane.

A wheel on link :math:`W` has its centre :math:`c` and unit spin axis :math:`a` (world axes)
from the link's placement. The ground is :math:`z = 0` with normal :math:`e_z`. The point of
the centre circle nearest the ground is in the direction, in the wheel plane,

.. math::

    d = -\frac{u}{s},\qquad u = e_z - (a\cdot e_z)\,a,\qquad s = \lVert u\rVert
      = \sqrt{1 - a_z^2}

(undefined when the wheel lies flat, :math:`s = 0`). The contact point is

.. math::

    p = c + R\,d - r\,e_z

(:math:`r` = tyre radius, 0 for a thin disk: the tyre's cross-section lies in the plane of
:math:`a` and :math:`d`, which contains :math:`e_z`). Its height is the holonomic condition

.. math::

    g(q) = p_z = c_z - R\,s - r = 0 .

Rows (three per wheel, world x, y, z): the velocity of the wheel's *material* point at
:math:`p`, with :math:`o` the link frame's origin and :math:`\rho = p - o`,

.. math::

    v_p = v_o + \omega\times\rho,\qquad J_p = J_{o,\text{lin}} - [\rho]_\times J_\omega ,

Jacobians of the link frame in ``LOCAL_WORLD_ALIGNED``. The x and y rows are the no-slip
conditions (nonholonomic); the z row is :math:`\dot g` (the contact point moves over the wheel
along the ground's tangent plane, so only the material velocity enters): the velocity form of
staying on the ground. The time derivative includes the motion of the contact point over the
wheel:

.. math::

    \dot J_p = \dot J_{o,\text{lin}} - [\rho]_\times\dot J_\omega - [\dot\rho]_\times J_\omega,
    \qquad \dot\rho = \omega\times(c - o) + R\,\dot d,\qquad
    \dot d = -\frac{(1 - d d^T)\,\dot u}{s},\quad
    \dot u = -(\dot a_z\,a + a_z\,\dot a),\quad \dot a = \omega\times a .

Configurations satisfying :math:`g(q) = 0` are found by Newton's method on chosen coordinates
(:func:`solve_contact`), with the z rows as the Jacobian of :math:`g`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import overload

import numpy as np
import pinocchio as pin

from ..errors import StateError
from ..models.builder import WheeledModel

_LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
_EZ = np.array([0.0, 0.0, 1.0])
#: Rows of the contact Jacobian per wheel (world x, y, z).
ROWS = 3
#: Smallest sine of the angle between the spin axis and the vertical (a wheel flatter than
#: this has no defined lowest rim point).
FLAT_TOL = 1e-8
#: Largest |g| (m) accepted as on the ground by :func:`solve_contact`.
CONTACT_TOL = 1e-12
#: Newton iterations of :func:`solve_contact`.
MAX_NEWTON = 50


def _cross(x: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -x[2], x[1]], [x[2], 0.0, -x[0]], [-x[1], x[0], 0.0]])


@dataclass(frozen=True)
class WheelPoint:
    r"""Geometry of one wheel's contact (world axes): link origin ``origin``, centre, spin
    axis, the unit direction ``d`` from the centre to the lowest rim point, its normaliser
    :math:`s`, the contact point and :math:`\rho = p - o`."""

    origin: np.ndarray
    centre: np.ndarray
    axis: np.ndarray
    d: np.ndarray
    s: float
    point: np.ndarray
    rho: np.ndarray


def wheel_point(wm: WheeledModel, k: int, data: pin.Data) -> WheelPoint:
    r"""Contact geometry of wheel ``k`` from ``data`` (joint placements up to date)."""
    wc = wm.rolling_wheels[k]
    H = pin.updateFramePlacement(wm.model, data, wc.frame_id).homogeneous
    R, o = H[:3, :3], H[:3, 3]
    a = R @ wc.axis
    c = o + R @ wc.centre
    u = _EZ - a[2] * a
    s = float(np.linalg.norm(u))
    if s < FLAT_TOL:
        raise StateError(f"q ({wc.link})", round(s, 12), "a configuration where the wheel is "
                         "not lying flat (spin axis not vertical)")
    d = -u / s
    p = c + wc.radius * d - wc.tyre_radius * _EZ
    return WheelPoint(o, c, a, d, s, p, p - o)


def _cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])


@dataclass(frozen=True)
class WheelRows:
    r""":math:`J_c` at one configuration with what :math:`\dot J_c` needs: per wheel its
    geometry and the angular rows :math:`J_\omega` of its frame."""

    J: np.ndarray
    points: tuple[WheelPoint, ...]
    angular: tuple[np.ndarray, ...]


def wheel_rows(wm: WheeledModel, q: np.ndarray, data: pin.Data) -> WheelRows:
    r""":math:`J_c(q)` and the geometry behind it (one kinematics pass)."""
    model = wm.model
    pin.computeJointJacobians(model, data, q)
    rows, points, angular = [np.zeros((0, model.nv))], [], []
    for k, wc in enumerate(wm.rolling_wheels):
        g = wheel_point(wm, k, data)
        J = pin.getFrameJacobian(model, data, wc.frame_id, _LWA)
        rows.append(J[:3] - _cross(g.rho) @ J[3:])
        points.append(g)
        angular.append(J[3:])
    return WheelRows(np.vstack(rows), tuple(points), tuple(angular))


def wheel_rows_rate(wm: WheeledModel, q: np.ndarray, v: np.ndarray, rows: WheelRows,
                    data: pin.Data) -> np.ndarray:
    r""":math:`\dot J_c(q, v)` given :func:`wheel_rows` at the same ``q``."""
    model = wm.model
    pin.computeJointJacobiansTimeVariation(model, data, q, v)
    out = [np.zeros((0, model.nv))]
    for wc, g, Jw in zip(wm.rolling_wheels, rows.points, rows.angular):
        dJ = pin.getFrameJacobianTimeVariation(model, data, wc.frame_id, _LWA)
        w = Jw @ v
        adot = _cross3(w, g.axis)
        udot = -(adot[2] * g.axis + g.axis[2] * adot)
        ddot = -(udot - g.d * (g.d @ udot)) / g.s
        rhodot = _cross3(w, g.centre - g.origin) + wc.radius * ddot
        out.append(dJ[:3] - _cross(g.rho) @ dJ[3:] - _cross(rhodot) @ Jw)
    return np.vstack(out)


@overload
def wheel_jacobian(wm: WheeledModel, q: np.ndarray, v: None = None,
                   data: pin.Data | None = None) -> tuple[np.ndarray, None]: ...


@overload
def wheel_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray,
                   data: pin.Data | None = None) -> tuple[np.ndarray, np.ndarray]: ...


@overload
def wheel_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray | None = None,
                   data: pin.Data | None = None
                   ) -> tuple[np.ndarray, np.ndarray | None]: ...


def wheel_jacobian(wm: WheeledModel, q: np.ndarray, v: np.ndarray | None = None,
                   data: pin.Data | None = None) -> tuple[np.ndarray, np.ndarray | None]:
    r""":math:`J_c(q)` (3 per wheel × nv: world x, y, z of the material contact point's
    velocity) and, if ``v`` is given, :math:`\dot J_c(q, v)`."""
    data = data or wm.model.createData()
    rows = wheel_rows(wm, q, data)
    return rows.J, (wheel_rows_rate(wm, q, v, rows, data) if v is not None else None)


def wheel_contact_points(wm: WheeledModel, q: np.ndarray) -> np.ndarray:
    r"""World positions of the wheels' contact points (one row per wheel)."""
    data = wm.model.createData()
    pin.framesForwardKinematics(wm.model, data, q)
    return np.array([wheel_point(wm, k, data).point
                     for k in range(len(wm.rolling_wheels))]).reshape(-1, 3)


def wheel_heights(wm: WheeledModel, q: np.ndarray, data: pin.Data | None = None) -> np.ndarray:
    r"""The holonomic conditions :math:`g(q)`: the height of each contact point."""
    data = data or wm.model.createData()
    pin.framesForwardKinematics(wm.model, data, q)
    return np.array([wheel_point(wm, k, data).point[2] for k in range(len(wm.rolling_wheels))])


#: Largest |g| over the wheel's radius (rim and tyre) of a configuration on the ground.
GROUND_TOL = 1e-6


def off_ground(wm: WheeledModel, q: np.ndarray, data: pin.Data) -> np.ndarray:
    r"""Per configuration (rows of ``q``, N × nq), whether a tilting wheel is off the ground
    plane or lies flat: :math:`|g(q)| > ` :data:`GROUND_TOL` :math:`(R + r)`, or
    :math:`s <` :data:`FLAT_TOL` (no lowest rim point). A coordinate map that writes the
    centre's height as :math:`R\cos\varphi` sinks a disk leaning beyond a right angle (its
    rim's lowest point is then :math:`R|\cos\varphi|` below the centre): no motion of the
    model is there."""
    wheels = wm.rolling_wheels
    out = np.zeros(len(q), dtype=bool)
    if not wheels:
        return out
    rot, org = np.empty((len(q), len(wheels), 3, 3)), np.empty((len(q), len(wheels), 3))
    for i, qi in enumerate(q):
        pin.framesForwardKinematics(wm.model, data, qi)
        for j, wc in enumerate(wheels):
            H = data.oMf[wc.frame_id].homogeneous
            rot[i, j], org[i, j] = H[:3, :3], H[:3, 3]
    for j, wc in enumerate(wheels):
        a = rot[:, j] @ wc.axis
        c_z = org[:, j, 2] + rot[:, j, 2] @ wc.centre
        s = np.sqrt(np.maximum(1.0 - a[:, 2] ** 2, 0.0))
        g = c_z - wc.radius * s - wc.tyre_radius
        out |= (s < FLAT_TOL) | ~(np.abs(g) <= GROUND_TOL * (wc.radius + wc.tyre_radius))
    return out


def wheel_contact_velocities(wm: WheeledModel, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    r"""Velocity (world axes) of each wheel's material point at its contact, from the frame
    velocity of the wheel link (independently of :func:`wheel_jacobian`)."""
    data = wm.model.createData()
    pin.forwardKinematics(wm.model, data, q, v)
    pin.updateFramePlacements(wm.model, data)
    out = []
    for k, wc in enumerate(wm.rolling_wheels):
        g = wheel_point(wm, k, data)
        vel = pin.getFrameVelocity(wm.model, data, wc.frame_id, _LWA)
        out.append(vel.linear + np.cross(vel.angular, g.rho))
    return np.array(out).reshape(-1, 3)


def solve_contact(wm: WheeledModel, q: np.ndarray, free: Sequence[str],
                  tol: float = CONTACT_TOL) -> np.ndarray:
    r"""A configuration with every wheel on the ground, :math:`g(q) = 0`, changing only the
    coordinates named in ``free`` (as many as wheels; e.g. the base height and pitch), by
    Newton's method from ``q``. :class:`StateError` if it does not converge."""
    model = wm.model
    idx = [wm.index(n) for n in free]
    nw = len(wm.rolling_wheels)
    if len(idx) != nw:
        raise StateError("free coordinates", tuple(free), f"{nw} coordinate names (one per "
                         "rolling wheel)")
    q = np.array(q, dtype=float)
    data = model.createData()
    g = wheel_heights(wm, q, data)
    for _ in range(MAX_NEWTON):
        if np.all(np.isfinite(g)) and np.abs(g).max() <= tol:
            return q
        J, _ = wheel_jacobian(wm, q, data=data)
        Jn = J[2::ROWS][:, idx]
        step = np.zeros(model.nv)
        step[idx] = np.linalg.lstsq(Jn, -g, rcond=None)[0]
        q = pin.integrate(model, q, step)
        g = wheel_heights(wm, q, data)
    if np.all(np.isfinite(g)) and np.abs(g).max() <= 1e3 * tol:
        return q
    raise StateError("q", float(np.abs(g).max()), f"a configuration where the wheels touch the "
                     f"ground by changing {tuple(free)} (Newton did not converge)")
