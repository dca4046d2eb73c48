r"""The reduction of :mod:`.wheel_reduction` for many states at once.

Pinocchio is called per state in two passes: joint Jacobians and frame placements (for
:math:`J_c` and :math:`S`), then, with :math:`v = S\nu` known, the Jacobians' time variation,
``crba``, ``computeCoriolisMatrix`` and ``computeGeneralizedGravity``. The contact geometry of
:mod:`.wheel_contact` (:math:`d`, :math:`\rho`, :math:`\dot\rho`, the rows and their
derivatives), the solves for :math:`S` and :math:`\dot S` and the projections are done on
stacked arrays. The numbers are those of :meth:`.wheel_reduction.RollingReduction.terms`.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..dynamics.terms import Terms
from ..errors import StateError
from ..models.springs import spring_force_batch
from .wheel_contact import FLAT_TOL
from .wheel_reduction import (PARAMETRISATION_TOL, RollingReduction,
                              normalised_determinant)

_LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def _cross_columns(x: np.ndarray, M: np.ndarray) -> np.ndarray:
    r""":math:`[x]_\times M` for stacks: ``x`` (N × 3), ``M`` (N × 3 × nv)."""
    X = np.zeros((x.shape[0], 3, 3))
    X[:, 0, 1], X[:, 0, 2], X[:, 1, 2] = -x[:, 2], x[:, 1], -x[:, 0]
    X[:, 1, 0], X[:, 2, 0], X[:, 2, 1] = x[:, 2], -x[:, 1], x[:, 0]
    return X @ M


def terms_batch(red: RollingReduction, q: np.ndarray, nu: np.ndarray) -> Terms:
    r"""Reduced terms at N states (``q``: N × nq on the ground, ``nu``: N × n); arrays with a
    leading axis N."""
    wm = red.wm
    model, data = wm.model, red._data
    q = np.atleast_2d(np.asarray(q, dtype=float))
    nu = np.atleast_2d(np.asarray(nu, dtype=float))
    N, nv, n, m = q.shape[0], model.nv, red.n, red.m
    if nu.shape != (N, n) or q.shape[1] != model.nq or not (np.all(np.isfinite(q))
                                                             and np.all(np.isfinite(nu))):
        raise StateError("states", (q.shape, nu.shape), f"N x {model.nq} configurations and "
                         f"N x {n} velocities, finite")
    wheels = wm.rolling_wheels
    k = len(wheels)
    J6 = np.empty((N, k, 6, nv))
    dJ6 = np.empty((N, k, 6, nv))
    rot = np.empty((N, k, 3, 3))
    org = np.empty((N, k, 3))
    jac, place, get_frame = pin.computeJointJacobians, pin.updateFramePlacement, pin.getFrameJacobian
    for i in range(N):
        jac(model, data, q[i])
        for j, wc in enumerate(wheels):
            H = place(model, data, wc.frame_id).homogeneous
            rot[i, j], org[i, j] = H[:3, :3], H[:3, 3]
            J6[i, j] = get_frame(model, data, wc.frame_id, _LWA)
    # contact geometry, per wheel, on stacks
    geo = []
    rows = np.empty((N, m, nv))
    for j, wc in enumerate(wheels):
        a = rot[:, j] @ wc.axis
        c = org[:, j] + rot[:, j] @ wc.centre
        u = -a[:, 2, None] * a
        u[:, 2] += 1.0
        s = np.linalg.norm(u, axis=1)
        if s.min() < FLAT_TOL:
            raise StateError(f"q ({wc.link})", float(s.min()), "configurations where the "
                             "wheel is not lying flat")
        d = -u / s[:, None]
        p = c + wc.radius * d
        p[:, 2] -= wc.tyre_radius
        rho = p - org[:, j]
        rows[:, 3 * j:3 * j + 3] = J6[:, j, :3] - _cross_columns(rho, J6[:, j, 3:])
        geo.append((a, c - org[:, j], s, d, rho))
    K = np.concatenate([rows, np.broadcast_to(red.T, (N, n, nv))], axis=1)
    bad = ~(normalised_determinant(K) > PARAMETRISATION_TOL)
    if bad.any():
        raise StateError("independent velocities", red.independent, "velocities that "
                         "parametrise the rolling motions at every state (state "
                         f"{int(np.argmax(bad))}: [J_c; T] is singular)")
    S = np.linalg.solve(K, np.broadcast_to(red._rhs, (N, nv, n)))
    v = np.einsum("nij,nj->ni", S, nu)
    A = np.empty((N, nv, nv))
    C = np.empty((N, nv, nv))
    Q = np.empty((N, nv))
    variation, get_var = pin.computeJointJacobiansTimeVariation, pin.getFrameJacobianTimeVariation
    crba, coriolis, gravity = pin.crba, pin.computeCoriolisMatrix, pin.computeGeneralizedGravity
    for i in range(N):
        variation(model, data, q[i], v[i])
        for j, wc in enumerate(wheels):
            dJ6[i, j] = get_var(model, data, wc.frame_id, _LWA)
        A[i] = crba(model, data, q[i])
        C[i] = coriolis(model, data, q[i], v[i])
        Q[i] = gravity(model, data, q[i])
    if wm.springs:
        Q += spring_force_batch(wm.springs, q, nv)
    drows = np.empty((N, m, nv))
    for j, wc in enumerate(wheels):
        a, offset, s, d, rho = geo[j]
        Jw = J6[:, j, 3:]
        w = np.einsum("nij,nj->ni", Jw, v)
        adot = np.cross(w, a)
        udot = -(adot[:, 2, None] * a + a[:, 2, None] * adot)
        ddot = -(udot - d * np.einsum("ni,ni->n", d, udot)[:, None]) / s[:, None]
        rhodot = np.cross(w, offset) + wc.radius * ddot
        drows[:, 3 * j:3 * j + 3] = (dJ6[:, j, :3] - _cross_columns(rho, dJ6[:, j, 3:])
                                     - _cross_columns(rhodot, Jw))
    rhs = np.concatenate([drows @ S, np.zeros((N, n, n))], axis=1)
    Sdot = -np.linalg.solve(K, rhs)
    lower = np.tril_indices(nv, -1)
    A[:, lower[0], lower[1]] = A[:, lower[1], lower[0]]      # crba fills the upper triangle
    St = np.swapaxes(S, 1, 2)
    A_nu = St @ A @ S
    A_nu = 0.5 * (A_nu + np.swapaxes(A_nu, 1, 2))
    C_nu = St @ C @ S + St @ A @ Sdot
    return Terms(red.velocities, wm.input_names, A_nu, C_nu, np.einsum("nji,nj->ni", S, Q),
                 St @ red.B, np.einsum("nij,nj->ni", C_nu, nu))
