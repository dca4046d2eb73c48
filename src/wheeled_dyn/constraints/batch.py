r"""The reduction of :mod:`.reduction` for many states at once.

Pinocchio is called per state (``crba`` in the world convention, which leaves the joint
Jacobians and placements in ``data``, ``computeCoriolisMatrix``, which leaves their time
variation there too, and ``computeGeneralizedGravity``), each result written into a row of a
stack, and ``data.J``, ``data.dJ`` and the wheel joints' positions are copied from views of
``data`` (cheaper than ``getJointJacobian`` per wheel). Everything else — the rolling rows,
the coordinate map's expressions, the pseudo-inverse of :math:`[J_c; T]`, :math:`\dot S` and
the projections :math:`S^TAS`, :math:`S^TCS + S^TA\dot S`, :math:`S^TQ`, :math:`S^TB` — is
done on stacked arrays, :data:`BLOCK` states at a time (the temporaries stay in the cache and
the allocator reuses their memory, where stacks of thousands of states cost fresh pages at
every call). The result is a :class:`~wheeled_dyn.dynamics.terms.Terms` whose arrays have a
leading axis of length N.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import NamedTuple

import numpy as np
import pinocchio as pin
import sympy as sp

from ..compiled import numpy_function
from ..dynamics.terms import Terms
from ..models.springs import spring_force_batch
from .linalg import pseudo_inverse
from .sphere_contact import ball_jacobian
from .wheel_contact import wheel_jacobian

#: States per block of the stacked algebra.
BLOCK = 256


def lambdify_batch(matrix: sp.Matrix, args: Sequence) -> Callable[..., np.ndarray]:
    r"""A function of stacked arguments returning an array (N, rows, cols) of ``matrix``;
    the constant entries (no symbol at all) are evaluated once and broadcast."""
    rows, cols = matrix.shape
    template = np.zeros((rows, cols))
    varying = []
    for i, row in enumerate(matrix.tolist()):
        for j, e in enumerate(row):
            f = numpy_function(args, e)
            if e.free_symbols:
                varying.append((i, j, f))
            else:
                template[i, j] = f(*[0.0] * len(args))

    def evaluate(n: int, *values) -> np.ndarray:
        out = np.empty((n, rows, cols))
        out[:] = template
        for i, j, f in varying:
            out[:, i, j] = f(*values)
        return out

    return evaluate


class _Wheels(NamedTuple):
    r"""The drive wheels' joints, radii and the velocity columns of each wheel's Jacobian
    (``support``, wheels × nv, 1 on its joint's supporting joints, 0 elsewhere)."""

    ids: tuple[int, ...]
    radius: np.ndarray
    support: np.ndarray


def _wheels(wm) -> _Wheels:
    r"""The :class:`_Wheels` of model ``wm`` (its drive wheels, :mod:`.rolling`)."""
    model = wm.model
    ids = tuple(wheel.joint_id for wheel in wm.wheels)
    support = np.zeros((len(ids), model.nv))
    for k, jid in enumerate(ids):
        for j in model.supports[jid]:
            joint = model.joints[j]
            support[k, joint.idx_v:joint.idx_v + joint.nv] = 1.0
    return _Wheels(ids, np.array([w.radius for w in wm.wheels]), support)


def _skew(c: np.ndarray) -> np.ndarray:
    r""":math:`[c]_\times` (… × 3 × 3) for vectors ``c`` (… × 3)."""
    out = np.zeros((*c.shape, 3))
    out[..., 0, 1], out[..., 0, 2], out[..., 1, 2] = -c[..., 2], c[..., 1], -c[..., 0]
    out[..., 1, 0], out[..., 2, 0], out[..., 2, 1] = c[..., 2], -c[..., 1], c[..., 0]
    return out


def _rolling_rows(w: _Wheels, J: np.ndarray, p: np.ndarray, v: np.ndarray | None = None,
                  dJ: np.ndarray | None = None) -> np.ndarray:
    r"""Rows of :math:`J_c` (N × 2·wheels × nv), or with ``v`` and ``dJ`` of :math:`\dot J_c`,
    from the joint Jacobians in the world frame ``J`` (N × 6 × nv: velocity of the point at
    the world origin, angular velocity), their time variation ``dJ`` and the wheel joints'
    positions ``p`` (N × wheels × 3). Per wheel, with :math:`c = p - R e_z` the contact point,
    :math:`(\cdot)_k` the columns of the wheel's supporting joints and
    :math:`\dot c = \dot p = (J_{lin} - [p]_\times J_\omega)_k v`,

    .. math::

        J_{c,k} = P(J_{lin} - [c]_\times J_\omega)_k,\qquad
        \dot J_{c,k} = P(\dot J_{lin} - [c]_\times\dot J_\omega - [\dot c]_\times J_\omega)_k:

    :math:`P(J + R[e_z]_\times J_\omega)` of Pinocchio's ``LOCAL_WORLD_ALIGNED`` Jacobians of
    the wheel joints (:mod:`.rolling`) and its time derivative."""
    N, k, nv = J.shape[0], len(w.ids), J.shape[-1]
    c = p.copy()
    c[:, :, 2] -= w.radius
    if dJ is None:
        lin, X, W = J, _skew(c)[:, :, :2], J[:, 3:]
    else:
        assert v is not None, "the rows of the rate of J_c need the velocities v"
        Jv = np.swapaxes(J @ (v[:, :, None] * w.support.T), 1, 2)[..., None]  # N × k × 6 × 1
        c_dot = Jv[:, :, :3] - _skew(p) @ Jv[:, :, 3:]
        lin, X = dJ, np.concatenate([_skew(c), _skew(c_dot[..., 0])], axis=-1)[:, :, :2]
        W = np.concatenate([dJ[:, 3:], J[:, 3:]], axis=1)
    rows = lin[:, None, :2] - (X.reshape(N, 2 * k, X.shape[-1]) @ W).reshape(N, k, 2, nv)
    return (rows * w.support[:, None]).reshape(N, 2 * k, nv)


class _Context(NamedTuple):
    r"""What a call needs once for all its blocks: the wheels, views of ``data.J`` and
    ``data.dJ`` and of the wheel joints' translations ``data.oMi[j].translation`` (Pinocchio's
    bindings return them by reference, so every algorithm call refreshes them;
    ``by_reference`` False: a binding that returns copies, read again after each call)."""

    wheels: _Wheels
    J: np.ndarray
    dJ: np.ndarray
    centres: tuple[np.ndarray, ...]
    by_reference: bool

    def positions(self, data) -> tuple[np.ndarray, ...]:
        r"""The wheel joints' translations read again (a binding that returns copies)."""
        return tuple(data.oMi[j].translation for j in self.wheels.ids[:len(self.centres)])


def _context(cmap) -> _Context:
    r"""The :class:`_Context` of a call on ``cmap`` (its ``data``, model and coordinate set)."""
    data, wheels = cmap._data, _wheels(cmap.wm)
    need_J = cmap.cs.rolling in ("eliminate", "multipliers")
    views = [data.J, data.dJ, *(data.oMi[j].translation for j in wheels.ids if need_J)]
    again = [data.J, data.dJ, *(data.oMi[j].translation for j in wheels.ids if need_J)]
    by_reference = all(np.shares_memory(a, b) for a, b in zip(views, again))
    return _Context(wheels, views[0], views[1], tuple(views[2:]), by_reference)


def _blocks(N: int) -> list[slice]:
    r"""Slices of at most :data:`BLOCK` states covering ``range(N)`` (one, empty, if N = 0)."""
    return [slice(i, min(i + BLOCK, N)) for i in range(0, N, BLOCK)] or [slice(0, 0)]


def reduce_batch(cmap, q: np.ndarray, nu: np.ndarray, q_doc: np.ndarray | None = None) -> Terms:
    r"""Terms in document velocities at N model configurations ``q`` (N × nq) and velocities
    ``nu`` (N × n); ``q_doc`` (N × n) is needed for holonomic sets."""
    return reduce_batch_multi(cmap, q, [nu], q_doc)[0]


class _Configuration(NamedTuple):
    r"""What depends on the configurations only: A, Q, J_c, the velocity basis S, with
    rolling eliminated :math:`[J_c; T]^+` (its first ``w`` columns: J_c's), and the joint
    Jacobians in the world frame and the wheel joints' positions (N × wheels × 3)."""

    A: np.ndarray
    Q: np.ndarray | None
    J: np.ndarray | None
    S: np.ndarray
    Mp: np.ndarray | None
    world: np.ndarray
    positions: np.ndarray


def _configuration(cmap, ctx: _Context, q: np.ndarray, q_doc: np.ndarray | None,
                   with_gravity: bool = True) -> _Configuration:
    r"""Pinocchio per state: ``crba`` (WORLD convention; the Python binding returns A
    symmetric) and ``computeGeneralizedGravity``; then :math:`J_c` and :math:`S` on stacks."""
    wm, cs = cmap.wm, cmap.cs
    model, data = wm.model, cmap._data
    N, nv, p = q.shape[0], model.nv, cmap._p
    need_J, centres = cs.rolling in ("eliminate", "multipliers"), ctx.centres
    by_reference, J_view = ctx.by_reference, ctx.J
    A, Q = np.empty((N, nv, nv)), np.empty((N, nv))
    Jw, pos = np.empty((N, 6, nv)), np.empty((N, len(centres), 3))
    crba, gravity, world = pin.crba, pin.computeGeneralizedGravity, pin.Convention.WORLD
    for qi, Ai, Qi, Ji, Pi in zip(q, A, Q, Jw, pos):
        Ai[...] = crba(model, data, qi, world)
        if centres:
            Ji[...] = J_view if by_reference else data.J
            Pi[...] = centres if by_reference else ctx.positions(data)
        if with_gravity:
            Qi[...] = gravity(model, data, qi)
    if wm.springs and with_gravity:
        Q += spring_force_batch(wm.springs, q, nv)
    J = _rolling_rows(ctx.wheels, Jw, pos) if need_J else None
    if need_J and wm.contact is not None:
        ball = np.stack([ball_jacobian(wm, q[i], None, data)[0] for i in range(N)])
        J = np.concatenate([J, ball], axis=1)
    if need_J and wm.rolling_wheels:
        tilt = np.stack([wheel_jacobian(wm, q[i], None, data)[0] for i in range(N)])
        J = np.concatenate([J, tilt], axis=1)
    Mp = None
    if cs.kind == "holonomic":
        assert q_doc is not None, "a holonomic set's S is a function of its own positions"
        S = cmap._S_batch(N, *q_doc.T, *p)
    else:
        T = cmap._T_batch(N, *q.T, *p)
        if cs.rolling == "eliminate":
            assert J is not None, "rolling eliminated: J_c was computed (need_J)"
            Mp = pseudo_inverse(np.concatenate([J, T], axis=1))
            S = cmap.basis(Mp, J.shape[1])
        else:
            S = np.linalg.inv(T)
    return _Configuration(A, Q if with_gravity else None, J, S, Mp, Jw, pos)


def _project(A: np.ndarray, S: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""(:math:`S^TAS`, symmetrised against rounding; :math:`AS`)."""
    AS = A @ S
    A_nu = np.swapaxes(S, 1, 2) @ AS
    return 0.5 * (A_nu + np.swapaxes(A_nu, 1, 2)), AS


def reduced_mass_batch(cmap, q: np.ndarray, q_doc: np.ndarray | None = None) -> np.ndarray:
    r""":math:`A_\nu = S^TAS` at N configurations (no velocities: the kinetic energies of
    a trajectory's samples need nothing else)."""
    ctx = _context(cmap)
    parts = [_configuration(cmap, ctx, q[b], None if q_doc is None else q_doc[b], False)
             for b in _blocks(q.shape[0])]
    return np.concatenate([_project(c.A, c.S)[0] for c in parts])


def reduce_batch_multi(cmap, q: np.ndarray, nus: list[np.ndarray],
                       q_doc: np.ndarray | None = None) -> list[Terms]:
    r"""As :func:`reduce_batch` for several velocity arrays at the same configurations: what
    depends on q only (A, Q, J_c, S) is computed once."""
    ctx = _context(cmap)
    parts = [_reduce_block(cmap, ctx, q[b], [nu[b] for nu in nus],
                           None if q_doc is None else q_doc[b]) for b in _blocks(q.shape[0])]
    if len(parts) == 1:
        return parts[0]
    out = []
    for terms in zip(*parts):
        first, G = terms[0], None if terms[0].G is None else np.concatenate([t.G for t in terms])
        A, C, Q, B, h = (np.concatenate([getattr(t, k) for t in terms]) for k in "ACQBh")
        out.append(Terms(first.velocities, first.inputs, A, C, Q, B, h, G))
    return out


def _reduce_block(cmap, ctx: _Context, q: np.ndarray, nus: list[np.ndarray],
                  q_doc: np.ndarray | None) -> list[Terms]:
    r""":func:`reduce_batch_multi` on one block of states. Per state and velocity array,
    ``computeCoriolisMatrix`` (which leaves the Jacobians' time variation in ``data``); then,
    on stacks, with :math:`A` symmetric,

    .. math::

        \dot S = -\begin{bmatrix}J_c\\T\end{bmatrix}^{+}
        \Big(\begin{bmatrix}\dot J_c\\ \dot T\end{bmatrix} S\Big),\qquad
        C_\nu = S^T(CS) + (AS)^T\dot S .
    """
    wm, cs = cmap.wm, cmap.cs
    model, data = wm.model, cmap._data
    N, nv, p = q.shape[0], model.nv, cmap._p
    A, Q, J, S, Mp, Jw, pos = _configuration(cmap, ctx, q, q_doc)
    St = np.swapaxes(S, 1, 2)
    A_nu, AS = _project(A, S)
    SA = np.swapaxes(AS, 1, 2)
    assert Q is not None, "_configuration with gravity gives Q"
    Q_nu = (St @ Q[:, :, None])[:, :, 0]
    B_nu = St @ cmap._B
    G = J @ S if cs.rolling == "multipliers" else None
    need_dJ = cs.kind == "quasi" and cs.rolling == "eliminate"
    rolling, dJ_view, by_reference = need_dJ and bool(ctx.centres), ctx.dJ, ctx.by_reference
    coriolis = pin.computeCoriolisMatrix
    out = []
    for nu in nus:
        v = (S @ nu[:, :, None])[:, :, 0]
        C, dJw = np.empty((N, nv, nv)), np.empty((N, 6, nv))
        for qi, vi, Ci, Di in zip(q, v, C, dJw):
            Ci[...] = coriolis(model, data, qi, vi)
            if rolling:
                Di[...] = dJ_view if by_reference else data.dJ
        if cs.kind == "holonomic":
            assert q_doc is not None, "a holonomic set's S is a function of its own positions"
            Sdot = cmap._Sdot_batch(N, *q_doc.T, *nu.T, *p)
        else:
            Tdot = cmap._Tdot_batch(N, *q.T, *v.T, *p)
            if need_dJ:
                dJ = _rolling_rows(ctx.wheels, Jw, pos, v, dJw)
                if wm.contact is not None:
                    ball = np.stack([ball_jacobian(wm, q[i], v[i], data)[1] for i in range(N)])
                    dJ = np.concatenate([dJ, ball], axis=1)
                if wm.rolling_wheels:
                    tilt = np.stack([wheel_jacobian(wm, q[i], v[i], data)[1] for i in range(N)])
                    dJ = np.concatenate([dJ, tilt], axis=1)
                Sdot = -(Mp @ (np.concatenate([dJ, Tdot], axis=1) @ S))
            else:
                Sdot = -(S @ (Tdot @ S))
        C_nu = St @ (C @ S) + SA @ Sdot
        out.append(Terms(cs.velocities, wm.input_names, A_nu, C_nu, Q_nu, B_nu,
                         (C_nu @ nu[:, :, None])[:, :, 0], G))
    return out
