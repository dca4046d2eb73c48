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

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import pinocchio as pin
import sympy as sp

from ..errors import ModelError, UnknownNameError
from .exact import exact_translation
from .trigpoly import TrigRing

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


#: Largest denominator :func:`exact_number` accepts in a fraction or under a square root.
EXACT_MAX_DENOMINATOR: int = 1000


def _fraction(x: float, tolerance: float) -> Fraction | None:
    f = Fraction(x).limit_denominator(EXACT_MAX_DENOMINATOR)
    return f if abs(float(f) - x) <= tolerance * max(1.0, abs(x)) else None


def exact_number(x: float, tolerance: float = 1e-12) -> sp.Expr:
    r"""A float as a SymPy number, exact where that is no harder to read.

    Integers (``0``, ``±1`` ...) become Integers; a fraction :math:`p/q` or a square root
    :math:`\pm\sqrt{p/q}` (:math:`q \le` :data:`EXACT_MAX_DENOMINATOR`, e.g. :math:`1/5`,
    :math:`\sqrt{2}/2`) within ``tolerance`` (relative) is used if its text is at most one
    character longer than the float's shortest decimal text; else the float is kept as a
    ``Float``. This is what ``sympy.nsimplify(x, tolerance, rational=False)`` finds for such
    values, without its integer-relation search (slow on the random floats of a URDF).
    """
    x = float(x)
    if not math.isfinite(x):
        raise ModelError("<pinocchio>", None, f"non-finite number {x!r} in the model")
    if abs(x - round(x)) <= tolerance * max(1.0, abs(x)):
        return sp.Integer(round(x))
    limit = len(repr(x)) + 1
    f = _fraction(x, tolerance)
    if f is not None:
        r = sp.Rational(f.numerator, f.denominator)
        if len(str(r)) <= limit:
            return r
    f2 = _fraction(x * x, tolerance)
    if f2 is not None:
        r = sp.sqrt(sp.Rational(f2.numerator, f2.denominator)) * (1 if x > 0 else -1)
        if len(str(r)) <= limit and abs(float(r) - x) <= tolerance * max(1.0, abs(x)):
            return r
    return sp.Float(x)


def exact_matrix(a: np.ndarray, tolerance: float = 1e-12) -> sp.Matrix:
    """A NumPy array (1-D as a column) as a SymPy Matrix of :func:`exact_number` entries."""
    a = np.atleast_1d(np.asarray(a, dtype=float))
    if a.ndim == 1:
        a = a.reshape(-1, 1)
    return sp.Matrix(a.shape[0], a.shape[1], lambda i, j: exact_number(float(a[i, j]), tolerance))


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


@dataclass(frozen=True)
class RingKinematics:
    r"""The same kinematics as ring elements of ``ring`` (canonical trigonometric form):
    ``frames[j]`` maps ``"R", "p", "R_rel", "p_rel", "omega", "v"`` to nested lists (3×3 as
    rows); ``extra`` holds the elements of the ``extra_exprs`` given."""

    ring: TrigRing
    frames: dict[int, dict[str, list]]
    extra: list


def _mat(M: list[list], N: list[list], ring: TrigRing) -> list[list]:
    return [[ring.reduce(sum((M[i][k] * N[k][j] for k in range(3)), ring.ring.zero))
             for j in range(3)] for i in range(3)]


def _matvec(M: list[list], v: list, ring: TrigRing) -> list:
    return [ring.reduce(sum((M[i][k] * v[k] for k in range(3)), ring.ring.zero))
            for i in range(3)]


def _cross(a: list, b: list) -> list:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def resolve_translations(model: pin.Model, translations: Mapping | None
                         ) -> dict[int, tuple[sp.Expr, ...]]:
    """``{joint index: 3 SymPy expressions}`` from a mapping keyed by joint index or name.
    Raises :class:`UnknownNameError` for a key that is no joint and :class:`ModelError` for a
    value that is not three entries."""
    names = list(model.names)
    out: dict[int, tuple[sp.Expr, ...]] = {}
    for key, value in (translations or {}).items():
        j = names.index(key) if isinstance(key, str) and key in names[1:] else key
        if not (isinstance(j, (int, np.integer)) and 1 <= int(j) < model.njoints):
            raise UnknownNameError("joint", str(key), names[1:], where="symbolic translations")
        vals = tuple(sp.sympify(x) for x in value)
        if len(vals) != 3:
            raise ModelError(getattr(model, "name", "") or "<pinocchio>", names[int(j)],
                             f"a translation needs 3 entries, got {len(vals)}")
        out[int(j)] = vals
    return out


def kinematics_in_ring(model: pin.Model, q: Sequence[sp.Symbol], qd: Sequence[sp.Symbol],
                       extra_exprs: Sequence[sp.Expr] = (),
                       extra_symbols: Sequence[sp.Symbol] = (),
                       translations: Mapping | None = None) -> RingKinematics:
    r"""Placements and frame velocities of joints ``1 .. njoints-1`` computed in one
    :class:`~.trigpoly.TrigRing` (which also holds ``extra_exprs``, e.g. inertial parameters,
    and has ``q``, ``qd`` and ``extra_symbols`` among its generators).

    ``q[k]``/``qd[k]`` are the symbols of the k-th velocity index (``model.joints[j].idx_v``).
    ``translations``: ``{joint index or name: (x, y, z)}`` replacing the translation of
    ``model.jointPlacements[j]`` by expressions (symbolic geometry: an axle height ``R``, a
    half track ``L``); the rotation stays the model's.
    Raises :class:`ModelError` for joints that are not 1-DoF revolute/prismatic.
    """
    if len(q) != model.nv or len(qd) != model.nv:
        raise ModelError(getattr(model, "name", "") or "<pinocchio>", None,
                         f"{len(q)} coordinates and {len(qd)} velocities given for nv={model.nv}")
    moved = resolve_translations(model, translations)
    joints = []
    flat: list[sp.Expr] = list(extra_exprs)
    for j in range(1, model.njoints):
        kind, a = joint_kind(model, j)
        k = model.joints[j].idx_v
        place = model.jointPlacements[j]
        Rp = exact_matrix(place.rotation)
        pp = sp.Matrix(moved[j]) if j in moved else exact_translation(place.translation)
        Rq = rodrigues(a, q[k]) if kind == "revolute" else sp.eye(3)
        joints.append((j, kind, k))
        flat += list(a) + list(Rp) + list(pp) + list(Rq)
    ring, el = TrigRing.from_exprs(flat, extra=tuple(q) + tuple(qd) + tuple(extra_symbols))
    extra, el = el[:len(extra_exprs)], el[len(extra_exprs):]
    zero = ring.ring.zero
    zv = [zero] * 3
    eye = [[ring.ring.one if i == j else zero for j in range(3)] for i in range(3)]
    frames: dict[int, dict[str, list]] = {0: {"R": eye, "p": zv, "omega": zv, "v": zv}}
    for n_j, (j, kind, k) in enumerate(joints):
        chunk = el[n_j * 24:(n_j + 1) * 24]
        a, Rp, pp, Rq = chunk[:3], chunk[3:12], chunk[12:15], chunk[15:24]
        Rp = [Rp[0:3], Rp[3:6], Rp[6:9]]
        Rq = [Rq[0:3], Rq[3:6], Rq[6:9]]
        qk, vk = ring.gen(q[k]), ring.gen(qd[k])
        if kind == "revolute":
            Rx, px = _mat(Rp, Rq, ring), list(pp)
        else:
            Rpa = _matvec(Rp, a, ring)
            Rx, px = Rp, [pp[i] + Rpa[i] * qk for i in range(3)]
        par = frames[model.parents[j]]
        Rt = [[Rx[c][r] for c in range(3)] for r in range(3)]
        omega = _matvec(Rt, par["omega"], ring)
        lin = [par["v"][i] + w for i, w in enumerate(_cross(par["omega"], px))]
        v = _matvec(Rt, lin, ring)
        if kind == "revolute":
            omega = [omega[i] + a[i] * vk for i in range(3)]
        else:
            v = [v[i] + a[i] * vk for i in range(3)]
        Rpx = _matvec(par["R"], px, ring)
        frames[j] = {"R": _mat(par["R"], Rx, ring), "p": [par["p"][i] + Rpx[i] for i in range(3)],
                     "R_rel": Rx, "p_rel": px, "omega": omega, "v": v, "axis": a}
    del frames[0]
    return RingKinematics(ring=ring, frames=frames, extra=extra)


def joint_kinematics(model: pin.Model, rk: RingKinematics) -> tuple[JointKinematics, ...]:
    """SymPy records of :func:`kinematics_in_ring`'s frames."""
    to = rk.ring.to_expr
    out = []
    for j, f in rk.frames.items():
        kind, _ = joint_kind(model, j)

        def m3(rows):
            return sp.Matrix(3, 3, lambda r, c: to(rows[r][c]))

        def v3(vec):
            return sp.Matrix([to(x) for x in vec])

        out.append(JointKinematics(j, model.names[j], model.parents[j], kind, v3(f["axis"]),
                                   m3(f["R"]), v3(f["p"]), m3(f["R_rel"]), v3(f["p_rel"]),
                                   v3(f["omega"]), v3(f["v"])))
    return tuple(out)


def forward_kinematics(model: pin.Model, q: Sequence[sp.Symbol],
                       qd: Sequence[sp.Symbol], translations: Mapping | None = None
                       ) -> tuple[JointKinematics, ...]:
    r"""Symbolic placements and frame velocities of joints ``1 .. njoints-1`` (expanded,
    canonical trigonometric form). ``q[k]``/``qd[k]`` are the symbols of velocity index ``k``;
    ``translations`` as in :func:`kinematics_in_ring`.
    Raises :class:`ModelError` for joints that are not 1-DoF revolute/prismatic."""
    return joint_kinematics(model, kinematics_in_ring(model, q, qd, translations=translations))


def velocity_jacobian(kin: JointKinematics, qd: Sequence[sp.Symbol]) -> sp.Matrix:
    r"""The 6×n body Jacobian :math:`J_j = \partial [v_j; \omega_j] / \partial \dot q` (joint
    frame, linear part first, as Pinocchio's ``LOCAL`` Jacobian)."""
    return sp.Matrix.vstack(kin.v, kin.omega).jacobian(list(qd))
