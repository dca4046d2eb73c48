r"""The truth of a derivation's earlier steps, computed with Pinocchio from the model.

A document state is positions :math:`q_d`, velocities :math:`\nu` and accelerations
:math:`\dot\nu` in the document's coordinate set (:class:`~wheeled_dyn.constraints.CoordinateMap`).
The model's state follows from the set's velocity matrix :math:`S`:

.. math::

    q = g(q_d),\qquad v = S\nu,\qquad \dot v = S\dot\nu + \dot S\nu ,

with, for quasi-velocities :math:`\nu = T(q)v` and rolling eliminated,
:math:`\dot S\nu = -\begin{bmatrix}J_c\\T\end{bmatrix}^{+}\begin{bmatrix}\dot J_c v\\ \dot T v
\end{bmatrix}`; when the set keeps the rolling constraints (multipliers), :math:`\nu` and
:math:`\dot\nu` are first made admissible (:math:`J_c v = 0`, :math:`J_c\dot v + \dot J_c v = 0`,
least-norm corrections).

Then ``pin.forwardKinematics(q, v, a)`` gives, for a point :math:`p` of a link (components in
the link frame; origin :math:`O`, angular velocity :math:`\omega`, spatial angular acceleration
:math:`\dot\omega`, classical acceleration of the origin :math:`a_O` from
``getFrameClassicalAcceleration``):

.. math::

    v_p = v_O + \omega\times p,\qquad a_p = a_O + \dot\omega\times p + \omega\times(\omega\times p),

rotated into the frame the document writes them in (world; the heading frame, the ``psi``
joint's frame, turning with :math:`\psi` only; or a link frame). The heading frame is also a body
(``"heading"``): its angular velocity is :math:`\dot\psi` about the vertical, its origin the
point on the ground below the axle midpoint. Kinetic energy per link
:math:`\tfrac12 v_J^T I_J v_J` (spatial velocity and inertia of its joint), in total
``pin.computeKineticEnergy``; potential :math:`-m\,g^T c` per link, in total
``pin.computePotentialEnergy`` plus the springs'; generalized forces from the reduced terms
:math:`A_\nu\dot\nu + h_\nu` of the coordinate map.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from ...constraints.reduction import CoordinateMap
from ...constraints.rolling import contact_jacobian
from ...derivations.steps import Step
from ...errors import UnknownNameError
from ...models.builder import WheeledModel

_LOCAL = pin.ReferenceFrame.LOCAL


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    r""":math:`a\times b` of two 3-vectors (faster than NumPy's on single vectors)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]])
_AXIS = {"x": 0, "y": 1, "z": 2}
#: The name of the heading frame (the ``psi`` joint's frame of a wheeled model) as a body.
HEADING = "heading"


def heading_frame(wm: WheeledModel) -> int:
    r"""Frame id of the heading frame (the ``psi`` joint's), else :class:`UnknownNameError`."""
    if "psi" not in wm.coordinate_names:
        raise UnknownNameError("frame", HEADING, ["world", "a link"],
                               where=f"model {wm.name} (it has no heading)")
    return wm.model.getFrameId("psi", pin.FrameType.JOINT)


class Motion:
    r"""The model at one document state: ``q, v, a`` and Pinocchio's data after
    ``forwardKinematics``; ``S`` the velocity matrix."""

    def __init__(self, cmap: CoordinateMap, data: pin.Data, q_doc: np.ndarray, nu: np.ndarray,
                 nudot: np.ndarray, admissible: bool = True) -> None:
        wm = cmap.wm
        self.cmap, self.wm, self.data = cmap, wm, data
        q = cmap.model_configuration(q_doc)
        cs = cmap.cs
        if cs.kind == "holonomic":
            S = np.asarray(cmap._S(q_doc, cmap._p), dtype=float)
            if cs.rolling == "multipliers" and admissible:
                J, _ = contact_jacobian(wm, q, data=data)
                G = J @ S
                P = np.eye(len(nu)) - np.linalg.pinv(G) @ G
                nu = P @ nu
            v = S @ nu
            Sdot_nu = np.asarray(cmap._Sdot(q_doc, nu, cmap._p), dtype=float) @ nu
            if cs.rolling == "multipliers" and admissible:
                J, dJ = contact_jacobian(wm, q, v, data=data)
                G = J @ S
                nudot = nudot - np.linalg.pinv(G) @ (G @ nudot + J @ Sdot_nu + dJ @ v)
            a = S @ nudot + Sdot_nu
        else:
            T = np.asarray(cmap._T(q, cmap._p), dtype=float)
            if cs.rolling == "eliminate":
                J, _ = contact_jacobian(wm, q, data=data)
                Mp = np.linalg.pinv(np.vstack([J, T]))
                S = cmap.basis(Mp, J.shape[0])
                v = S @ nu
                _, dJ = contact_jacobian(wm, q, v, data=data)
                Tdot = np.asarray(cmap._Tdot(q, v, cmap._p), dtype=float)
                a = S @ nudot - Mp @ np.concatenate([dJ @ v, Tdot @ v])
            else:
                S = np.linalg.inv(T)
                v = S @ nu
                Tdot = np.asarray(cmap._Tdot(q, v, cmap._p), dtype=float)
                a = S @ (nudot - Tdot @ v)
        self.q_doc, self.nu, self.nudot = q_doc, nu, nudot
        self.q, self.v, self.a, self.S = q, v, a, S
        pin.forwardKinematics(wm.model, data, q, v, a)
        pin.updateFramePlacements(wm.model, data)

    # -- frames ---------------------------------------------------------------------------
    def frame_id(self, link: str) -> int:
        model = self.wm.model
        if link == HEADING:
            return heading_frame(self.wm)
        if not model.existFrame(link):
            raise UnknownNameError("link", link, [f.name for f in model.frames
                                                  if f.type == pin.FrameType.BODY],
                                   where=f"model {self.wm.name}")
        return model.getFrameId(link)

    def rotation(self, frame: str) -> np.ndarray:
        r"""World rotation of ``frame`` (world, heading, or a link)."""
        if frame == "world":
            return np.eye(3)
        if frame == "heading":
            if "psi" not in self.wm.coordinate_names:
                raise UnknownNameError("frame", frame, ["world", "a link"],
                                       where=f"model {self.wm.name} (it has no heading)")
            return self.data.oMi[self.wm.model.getJointId("psi")].rotation
        return self.data.oMf[self.frame_id(frame)].rotation

    def point_in_link(self, link: str, point) -> np.ndarray:
        r"""A point of ``link`` in its frame: origin, centre of mass, contact, or given."""
        fid = self.frame_id(link)
        frame = self.wm.model.frames[fid]
        if isinstance(point, np.ndarray):
            return point
        if link == HEADING and point != "origin":
            raise UnknownNameError("point", str(point), ["origin", "[x, y, z]"],
                                   where="body heading")
        if point == "origin":
            return np.zeros(3)
        if point == "com":
            lever = self.wm.model.inertias[frame.parentJoint].lever
            return frame.placement.actInv(lever)
        wheel = next((w for w in self.wm.wheels if w.link == link), None)
        if wheel is None:
            raise UnknownNameError("wheel", link, [w.link for w in self.wm.wheels],
                                   where="point = \"contact\"")
        centre = self.data.oMi[wheel.joint_id].translation
        return self.data.oMf[fid].actInv(centre - np.array([0.0, 0.0, wheel.radius]))

    def vector(self, kind: str, link: str, point, frame: str) -> np.ndarray:
        r"""The ``kind`` vector of ``link`` (at ``point``) in ``frame``'s axes."""
        model, data = self.wm.model, self.data
        fid = self.frame_id(link)
        vel = pin.getFrameVelocity(model, data, fid, _LOCAL)
        w = vel.angular
        if kind == "angular velocity":
            local = w
        elif kind == "angular acceleration":
            local = pin.getFrameAcceleration(model, data, fid, _LOCAL).angular
        else:
            p = self.point_in_link(link, point)
            if kind == "velocity":
                local = vel.linear + _cross(w, p)
            else:
                acc = pin.getFrameClassicalAcceleration(model, data, fid, _LOCAL)
                dw = pin.getFrameAcceleration(model, data, fid, _LOCAL).angular
                local = acc.linear + _cross(dw, p) + _cross(w, _cross(w, p))
        world = data.oMf[fid].rotation @ local
        return self.rotation(frame).T @ world

    def orientation(self, body: str, frame: str, axes: Sequence[str],
                    body_axes: Sequence[str]) -> np.ndarray:
        r"""The matrix whose column j is ``body``'s axis ``body_axes[j]`` along ``frame``'s
        ``axes``: :math:`{}^fA_b` as a document writes it."""
        R = self.rotation(frame).T @ self.rotation(body)
        unit = {"x": 0, "y": 1, "z": 2}
        cols = []
        for a in body_axes:
            v = np.zeros(3)
            v[unit[a.lstrip("-")]] = -1.0 if a.startswith("-") else 1.0
            cols.append(along(R @ v, axes))
        return np.column_stack(cols)

    # -- energies ---------------------------------------------------------------------------
    def _joints(self, links: Sequence[str]) -> list[int]:
        return sorted({self.wm.model.frames[self.frame_id(link)].parentJoint for link in links})

    def kinetic_energy(self, links: Sequence[str]) -> float:
        model, data = self.wm.model, self.data
        if not links:
            return float(pin.computeKineticEnergy(model, data, self.q, self.v))
        return float(sum(0.5 * model.inertias[j].vtiv(data.v[j]) for j in self._joints(links)))

    def potential_energy(self, links: Sequence[str]) -> float:
        model, data = self.wm.model, self.data
        if not links:
            return self.wm.potential_energy(data, self.q)
        g = model.gravity.linear
        return float(sum(-model.inertias[j].mass * g @ data.oMi[j].act(model.inertias[j].lever)
                         for j in self._joints(links)))

    def inertial_terms(self) -> np.ndarray:
        r""":math:`A_\nu\dot\nu + h_\nu` in the document's velocities."""
        terms = self.cmap.terms_at(self.q, self.nu, self.q_doc)
        return terms.A @ self.nudot + terms.h


def along(vector: np.ndarray, axes: Sequence[str]) -> np.ndarray:
    r"""Components of ``vector`` along the document's axes (``"-y"``: minus the y axis)."""
    return np.array([(-1.0 if a.startswith("-") else 1.0) * vector[_AXIS[a.lstrip("-")]]
                     for a in axes])


def step_body(step: Step) -> str:
    r"""The link a vector, orientation or balance step is about (the file's parser requires
    one); a ``ValueError`` for a step without one."""
    if step.body is None:
        raise ValueError(f"step {step.equation} ({step.kind}) names no body")
    return step.body


def check_links(wm: WheeledModel, links: Sequence[str]) -> None:
    r"""Every name is a link (BODY frame) of the model or the heading frame (a model with a
    ``psi`` joint), else :class:`UnknownNameError`."""
    names = [f.name for f in wm.model.frames if f.type == pin.FrameType.BODY]
    for link in links:
        if link == HEADING:
            heading_frame(wm)
        elif link not in names:
            raise UnknownNameError("link", link, names, where=f"model {wm.name}")
