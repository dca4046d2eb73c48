r"""The reduction of :mod:`.reduction` for many states at once.

Pinocchio is called per state (``crba`` in the world convention, which leaves the joint
Jacobians in ``data``, ``computeCoriolisMatrix``, which leaves their time variation there too,
and ``computeGeneralizedGravity``); everything else — the coordinate
map's expressions, the pseudo-inverse of :math:`[J_c; T]`, :math:`\dot S` and the projections
:math:`S^TAS`, :math:`S^TCS + S^TA\dot S`, :math:`S^TQ`, :math:`S^TB` — is done on stacked
arrays. The result is a :class:`~wheeled_dyn.dynamics.terms.Terms` whose arrays have a leading
axis of length N.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import pinocchio as pin
import sympy as sp

from ..dynamics.terms import Terms
from ..models.springs import spring_force_batch
from .linalg import pseudo_inverse
from .rolling import _LWA
from .sphere_contact import ball_jacobian
from .wheel_contact import wheel_jacobian


def lambdify_batch(matrix: sp.Matrix, args: Sequence) -> callable:
    r"""A function of stacked arguments returning an array (N, rows, cols) of ``matrix``;
    constant entries are broadcast."""
    entries = [[sp.lambdify(args, e, "numpy") for e in row] for row in matrix.tolist()]
    rows, cols = matrix.shape

    def evaluate(n: int, *values) -> np.ndarray:
        out = np.empty((n, rows, cols))
        for i in range(rows):
            for j in range(cols):
                out[:, i, j] = entries[i][j](*values)
        return out

    return evaluate


def _rolling_rows(wm, raw: np.ndarray) -> np.ndarray:
    r"""Rows of :math:`J_c` (N × 2·wheels × nv) from the wheels' stacked 6-row Jacobians
    ``raw`` (N × wheels × 6 × nv): :math:`P(J_{lin} + R[e_z]_\times J_\omega)`."""
    radius = np.array([w.radius for w in wm.wheels])[None, :, None]
    lin, ang = raw[:, :, :3], raw[:, :, 3:]
    x = lin[:, :, 0] - radius * ang[:, :, 1]
    y = lin[:, :, 1] + radius * ang[:, :, 0]
    return np.stack([x, y], axis=2).reshape(raw.shape[0], -1, raw.shape[-1])


def reduce_batch(cmap, q: np.ndarray, nu: np.ndarray, q_doc: np.ndarray | None = None) -> Terms:
    r"""Terms in document velocities at N model configurations ``q`` (N × nq) and velocities
    ``nu`` (N × n); ``q_doc`` (N × n) is needed for holonomic sets."""
    return reduce_batch_multi(cmap, q, [nu], q_doc)[0]


class _Configuration(NamedTuple):
    r"""What depends on the configurations only: A (symmetric), Q, J_c, the velocity basis S
    and, with rolling eliminated, :math:`[J_c; T]^+` (its first ``w`` columns: J_c's)."""

    A: np.ndarray
    Q: np.ndarray | None
    J: np.ndarray | None
    S: np.ndarray
    Mp: np.ndarray | None
    raw: np.ndarray


def _configuration(cmap, q: np.ndarray, q_doc: np.ndarray | None,
                   with_gravity: bool = True) -> _Configuration:
    wm, cs = cmap.wm, cmap.cs
    model, data = wm.model, cmap._data
    N = q.shape[0]
    p = cmap._p
    need_J = cs.rolling in ("eliminate", "multipliers")
    A = np.empty((N, model.nv, model.nv))
    Q = np.empty((N, model.nv)) if with_gravity else None
    ids = [wheel.joint_id for wheel in wm.wheels]
    raw = np.empty((N, len(ids), 6, model.nv))
    crba, gravity, world = pin.crba, pin.computeGeneralizedGravity, pin.Convention.WORLD
    get_jacobian = pin.getJointJacobian
    wheels = tuple(enumerate(ids)) if need_J else ()
    for i, qi in enumerate(q):                      # rows as views: no indexing per call
        A[i] = crba(model, data, qi, world)         # fills the joint Jacobians data.J too
        if with_gravity:
            Q[i] = gravity(model, data, qi)
        rows = raw[i]
        for k, jid in wheels:
            rows[k] = get_jacobian(model, data, jid, _LWA)
    if wm.springs and with_gravity:
        Q += spring_force_batch(wm.springs, q, model.nv)
    J = _rolling_rows(wm, raw) if need_J else None
    if need_J and wm.contact is not None:
        ball = np.stack([ball_jacobian(wm, q[i], None, data)[0] for i in range(N)])
        J = np.concatenate([J, ball], axis=1)
    if need_J and wm.rolling_wheels:
        tilt = np.stack([wheel_jacobian(wm, q[i], None, data)[0] for i in range(N)])
        J = np.concatenate([J, tilt], axis=1)
    A = np.triu(A) + np.swapaxes(np.triu(A, 1), 1, 2)
    Mp = None
    if cs.kind == "holonomic":
        S = cmap._S_batch(N, *q_doc.T, *p)
    else:
        T = cmap._T_batch(N, *q.T, *p)
        if cs.rolling == "eliminate":
            Mp = pseudo_inverse(np.concatenate([J, T], axis=1))
            S = Mp[:, :, J.shape[1]:]
        else:
            S = np.linalg.inv(T)
    return _Configuration(A, Q, J, S, Mp, raw)


def _project(A: np.ndarray, S: np.ndarray) -> np.ndarray:
    A_nu = np.swapaxes(S, 1, 2) @ A @ S
    return 0.5 * (A_nu + np.swapaxes(A_nu, 1, 2))


def reduced_mass_batch(cmap, q: np.ndarray, q_doc: np.ndarray | None = None) -> np.ndarray:
    r""":math:`A_\nu = S^TAS` at N configurations (no velocities: the kinetic energies of
    a trajectory's samples need nothing else)."""
    c = _configuration(cmap, q, q_doc, with_gravity=False)
    return _project(c.A, c.S)


def reduce_batch_multi(cmap, q: np.ndarray, nus: list[np.ndarray],
                       q_doc: np.ndarray | None = None) -> list[Terms]:
    r"""As :func:`reduce_batch` for several velocity arrays at the same configurations: what
    depends on q only (A, Q, J_c, S) is computed once."""
    wm, cs = cmap.wm, cmap.cs
    model, data = wm.model, cmap._data
    N = q.shape[0]
    p = cmap._p
    A, Q, J, S, Mp, raw = _configuration(cmap, q, q_doc)
    ids = [wheel.joint_id for wheel in wm.wheels]
    St = np.swapaxes(S, 1, 2)
    A_nu = _project(A, S)
    Q_nu = np.einsum("nji,nj->ni", S, Q)
    B_nu = St @ cmap._B
    G = J @ S if cs.rolling == "multipliers" else None
    need_dJ = cs.kind == "quasi" and cs.rolling == "eliminate"
    coriolis, get_variation = pin.computeCoriolisMatrix, pin.getJointJacobianTimeVariation
    out = []
    for nu in nus:
        v = np.einsum("nij,nj->ni", S, nu)
        C = np.empty_like(A)
        wheels = tuple(enumerate(ids)) if need_dJ else ()
        for i, (qi, vi) in enumerate(zip(q, v)):
            C[i] = coriolis(model, data, qi, vi)     # fills data.J and data.dJ too
            rows = raw[i]
            for k, jid in wheels:
                rows[k] = get_variation(model, data, jid, _LWA)
        if cs.kind == "holonomic":
            Sdot = cmap._Sdot_batch(N, *q_doc.T, *nu.T, *p)
        else:
            Tdot = cmap._Tdot_batch(N, *q.T, *v.T, *p)
            if need_dJ:
                dJ = _rolling_rows(wm, raw)
                if wm.contact is not None:
                    ball = np.stack([ball_jacobian(wm, q[i], v[i], data)[1] for i in range(N)])
                    dJ = np.concatenate([dJ, ball], axis=1)
                if wm.rolling_wheels:
                    tilt = np.stack([wheel_jacobian(wm, q[i], v[i], data)[1] for i in range(N)])
                    dJ = np.concatenate([dJ, tilt], axis=1)
                Sdot = -Mp @ np.concatenate([dJ, Tdot], axis=1) @ S
            else:
                Sdot = -S @ Tdot @ S
        C_nu = St @ C @ S + St @ A @ Sdot
        out.append(Terms(cs.velocities, wm.input_names, A_nu, C_nu, Q_nu, B_nu,
                         np.einsum("nij,nj->ni", C_nu, nu), G))
    return out
