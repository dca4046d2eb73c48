r"""Symbolic forward kinematics of a Pinocchio tree of 1-DoF joints.

For joint :math:`j` with parent :math:`\lambda(j)`, Pinocchio places the joint frame as

.. math::
   {}^{\lambda}T_j(q_j) = \underbrace{\texttt{model.jointPlacements[j]}}_{(R_P,\ p_P)}
   \cdot T_{\mathrm{joint}}(q_j),

with :math:`T_{\mathrm{joint}} = (\mathrm{Rot}(a, q_j),\ 0)` for a revolute joint about the unit
axis :math:`a` (Rodrigues: :math:`\mathrm{Rot}(a,q) = I + \sin q\,[a]_\times + (1-\cos q)
[a]_\times^2`) and :math:`(I,\ a q_j)` for a prismatic one. With
:math:`{}^{\lambda}T_j = (R_x, p_x)` the velocities of the joint-frame origin, expressed in the
joint frame, follow the usual recursion (Khalil's eq. (16) of seed 001):

.. math::
   \omega_j = R_x^T \omega_{\lambda} + \sigma^R_j\, a\, \dot q_j, \qquad
   v_j = R_x^T (v_{\lambda} + \omega_{\lambda} \times p_x) + \sigma^P_j\, a\, \dot q_j,

and the world placement is :math:`{}^0T_j = {}^0T_{\lambda}\,{}^{\lambda}T_j`. Numbers read from
the model are made exact where they are simple (:func:`exact_number`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import sympy as sp

from ..errors import ModelError

#: Joint kinds accepted, by Pinocchio short name: (kind, fixed axis or None for "unaligned").
SUPPORTED_JOINTS: dict[str, tuple[str, tuple[int, int, int] | None]] = {
    "JointModelRX": ("revolute", (1, 0, 0)),
    "JointModelRY": ("revolute", (0, 1, 0)),
    "JointModelRZ": ("revolute", (0, 0, 1)),
    "JointModelPX": ("prismatic", (1, 0, 0)),
    "JointModelPY": ("prismatic", (0, 1, 0)),
    "JointModelPZ": ("prismatic", (0, 0, 1)),
    "JointModelRevoluteUnaligned": ("revolute", None),
    "JointModelPrismaticUnaligned": ("prismatic", None),
}


def exact_number(x: float, tolerance: float = 1e-12) -> sp.Expr:
    r"""A float as a SymPy number, exact where that is no harder to read.

    ``0``, ``±1`` and integers become Integers; otherwise ``sympy.nsimplify(x, tolerance,
    rational=False)`` is tried (it finds :math:`\sqrt{2}/2`, :math:`\pi/2`, :math:`1/5` ...) and
    kept only if its text is at most one character longer than the float's shortest decimal
    text; else the float is kept as a ``Float``.
    """
    x = float(x)
    if not np.isfinite(x):
        raise ModelError("<pinocchio>", None, f"non-finite number {x!r} in the model")
    r = round(x)
    if abs(x - r) <= tolerance * max(1.0, abs(x)):
        return sp.Integer(r)
    try:
        cand = sp.nsimplify(x, tolerance=tolerance, rational=False)
    except (ValueError, TypeError):  # pragma: no cover - nsimplify is robust for finite floats
        cand = None
    if cand is not None and cand.is_number and len(str(cand)) <= len(repr(x)) + 1 \
            and abs(float(cand) - x) <= tolerance * max(1.0, abs(x)):
        return cand
    return sp.Float(x)


def exact_matrix(a: np.ndarray, tolerance: float = 1e-12) -> sp.Matrix:
    """A NumPy array (1-D as a column) as a SymPy Matrix of :func:`exact_number` entries."""
    a = np.atleast_1d(np.asarray(a, dtype=float))
    if a.ndim == 1:
        a = a.reshape(-1, 1)
    return sp.Matrix(a.shape[0], a.shape[1], lambda i, j: exact_number(a[i, j], tolerance))


def skew(u: Sequence) -> sp.Matrix:
    r"""The cross-product matrix :math:`[u]_\times` with :math:`[u]_\times w = u \times w`."""
    return sp.Matrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])


def joint_kind(model: pin.Model, j: int) -> tuple[str, sp.Matrix]:
    """``("revolute" | "prismatic", axis)`` of joint ``j``; :class:`ModelError` otherwise."""
    jm = model.joints[j]
    short = jm.shortname()
    if short not in SUPPORTED_JOINTS or jm.nq != 1 or jm.nv != 1:
        raise ModelError(
            getattr(model, "name", "") or "<pinocchio>", model.names[j],
            f"joint type {short} (nq={jm.nq}, nv={jm.nv}) is not supported by the symbolic "
            f"core; supported: {', '.join(sorted(SUPPORTED_JOINTS))}")
    kind, axis = SUPPORTED_JOINTS[short]
    if axis is None:
        a = np.asarray(jm.extract().axis, dtype=float)
        a = a / np.linalg.norm(a)
        return kind, exact_matrix(a)
    return kind, sp.Matrix(axis)


def rodrigues(axis: sp.Matrix, q: sp.Expr) -> sp.Matrix:
    r""":math:`\mathrm{Rot}(a, q) = I + \sin q\,[a]_\times + (1-\cos q)[a]_\times^2`, with the
    simple forms for the coordinate axes."""
    a = [sp.sympify(x) for x in axis]
    if a == [1, 0, 0]:
        return sp.Matrix([[1, 0, 0], [0, sp.cos(q), -sp.sin(q)], [0, sp.sin(q), sp.cos(q)]])
    if a == [0, 1, 0]:
        return sp.Matrix([[sp.cos(q), 0, sp.sin(q)], [0, 1, 0], [-sp.sin(q), 0, sp.cos(q)]])
    if a == [0, 0, 1]:
        return sp.Matrix([[sp.cos(q), -sp.sin(q), 0], [sp.sin(q), sp.cos(q), 0], [0, 0, 1]])
    k = skew(a)
    return (sp.eye(3) + sp.sin(q) * k + (1 - sp.cos(q)) * k * k).applyfunc(sp.expand)


@dataclass(frozen=True)
class JointKinematics:
    r"""Kinematics of one joint frame :math:`j`.

    ``R``, ``p``: world placement :math:`{}^0T_j`; ``R_rel``, ``p_rel``: placement in the parent
    joint frame; ``omega``, ``v``: angular and linear velocity of the frame origin expressed in
    frame :math:`j` (3×1, linear in :math:`\dot q`); ``axis``: joint axis in frame :math:`j`.
    """

    index: int
    name: str
    parent: int
    kind: str
    axis: sp.Matrix
    R: sp.Matrix
    p: sp.Matrix
    R_rel: sp.Matrix
    p_rel: sp.Matrix
    omega: sp.Matrix
    v: sp.Matrix


def _expand(m: sp.Matrix) -> sp.Matrix:
    return m.applyfunc(sp.expand)


def forward_kinematics(model: pin.Model, q: Sequence[sp.Symbol],
                       qd: Sequence[sp.Symbol]) -> tuple[JointKinematics, ...]:
    r"""Symbolic placements and frame velocities of joints ``1 .. njoints-1``.

    ``q[k]``/``qd[k]`` are the symbols of the k-th velocity index (``model.joints[j].idx_v``).
    Raises :class:`ModelError` for joints that are not 1-DoF revolute/prismatic.
    """
    if len(q) != model.nv or len(qd) != model.nv:
        raise ModelError(getattr(model, "name", "") or "<pinocchio>", None,
                         f"{len(q)} coordinates and {len(qd)} velocities given for nv={model.nv}")
    zero = sp.zeros(3, 1)
    world: dict[int, tuple[sp.Matrix, sp.Matrix, sp.Matrix, sp.Matrix]] = {
        0: (sp.eye(3), zero, zero, zero)}
    out: list[JointKinematics] = []
    for j in range(1, model.njoints):
        kind, a = joint_kind(model, j)
        k = model.joints[j].idx_v
        parent = model.parents[j]
        place = model.jointPlacements[j]
        Rp, pp = exact_matrix(place.rotation), exact_matrix(place.translation)
        if kind == "revolute":
            Rx, px = _expand(Rp * rodrigues(a, q[k])), pp
        else:
            Rx, px = Rp, _expand(pp + Rp * a * q[k])
        R0, p0, w0, v0 = world[parent]
        Rt = Rx.T
        omega = _expand(Rt * w0 + (a * qd[k] if kind == "revolute" else zero))
        v = _expand(Rt * (v0 + w0.cross(px)) + (a * qd[k] if kind == "prismatic" else zero))
        R, p = _expand(R0 * Rx), _expand(p0 + R0 * px)
        world[j] = (R, p, omega, v)
        out.append(JointKinematics(j, model.names[j], parent, kind, a, R, p, Rx, px, omega, v))
    return tuple(out)


def velocity_jacobian(kin: JointKinematics, qd: Sequence[sp.Symbol]) -> sp.Matrix:
    r"""The 6×n body Jacobian :math:`J_j = \partial [v_j; \omega_j] / \partial \dot q` (joint
    frame, linear part first, as Pinocchio's ``LOCAL`` Jacobian)."""
    return sp.Matrix.vstack(kin.v, kin.omega).jacobian(list(qd))
