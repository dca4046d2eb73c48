r"""Geometry read from a URDF, made exact where it is simple.

A URDF writes angles in decimals (``rpy="1.57079632679 0 0"``), so the rotation Pinocchio builds
has entries like :math:`\cos(1.57079632679) = 4.9\cdot10^{-12}`; placements merged through fixed
joints add rounding of their own. Closed forms built on those numbers carry coefficients such as
``4.97e-11*XZ`` or ``4.10558375634028*MY_l - 4.10558375635007*MY_r``. Here

- a rotation matrix is exact when every entry is within :data:`GEOMETRY_TOLERANCE` of
  :math:`\cos(k\pi/d)` for :math:`d \in` :data:`ANGLE_DENOMINATORS` (0, ±1/2, ±√2/2, ±√3/2, ±1,
  ...) and the exact matrix is orthogonal; otherwise each roll–pitch–yaw angle that is within
  the tolerance of :math:`k\pi/d` is made exact and the matrix rebuilt, if it reproduces the
  model's to the tolerance; otherwise the entries stay floats with |x| below the tolerance set
  to 0;
- a length (translation entry) is the shortest decimal (at most :data:`MAX_DECIMALS` places)
  within the tolerance, as a rational (``0.2022`` → ``1011/5000``), else a float.

The tolerance is absolute (radians, metres, rotation entries): URDF numbers are written to
far fewer digits, and rounding in Pinocchio's parser and in merging fixed joints is below
:math:`10^{-11}`.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import sympy as sp

#: Largest distance (absolute) between a URDF number and the exact value that replaces it.
GEOMETRY_TOLERANCE: float = 1e-9
#: Denominators d of the angles k·π/d recognised as exact.
ANGLE_DENOMINATORS: tuple[int, ...] = (1, 2, 3, 4, 6, 8, 12)
#: Most decimal places of a length made exact.
MAX_DECIMALS: int = 6


@lru_cache(maxsize=1)
def _special_values() -> tuple[tuple[float, sp.Expr], ...]:
    vals: dict[float, sp.Expr] = {}
    for d in ANGLE_DENOMINATORS:
        for k in range(0, 2 * d + 1):
            e = sp.nsimplify(sp.cos(sp.pi * k / d))
            vals.setdefault(round(float(e), 15), e)
    return tuple(sorted(vals.items()))


def exact_entry(x: float, tolerance: float = GEOMETRY_TOLERANCE) -> sp.Expr | None:
    r"""The cosine of a simple angle within ``tolerance`` of ``x`` (0, ±1/2, ±√2/2 ...), or
    None."""
    for value, expr in _special_values():
        if abs(value - x) <= tolerance:
            return expr
    return None


def exact_angle(a: float, tolerance: float = GEOMETRY_TOLERANCE) -> sp.Expr | None:
    r""":math:`k\pi/d` within ``tolerance`` of ``a`` (d in :data:`ANGLE_DENOMINATORS`), or None."""
    for d in ANGLE_DENOMINATORS:
        k = round(a * d / math.pi)
        if abs(a - k * math.pi / d) <= tolerance:
            return sp.pi * sp.Rational(k, d)
    return None


def exact_length(x: float, tolerance: float = GEOMETRY_TOLERANCE) -> sp.Expr:
    r"""The shortest decimal within ``tolerance`` of ``x``, as an exact rational; else a
    float."""
    x = float(x)
    for places in range(MAX_DECIMALS + 1):
        r = round(x, places)
        if abs(r - x) <= tolerance:
            return sp.Rational(round(r * 10 ** places), 10 ** places)
    return sp.Float(x)


def _rpy_matrix(r: sp.Expr, p: sp.Expr, y: sp.Expr) -> sp.Matrix:
    def rot(axis: int, a: sp.Expr) -> sp.Matrix:
        c, s = sp.cos(a), sp.sin(a)
        if axis == 0:
            return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
        if axis == 1:
            return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
        return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    return (rot(2, y) * rot(1, p) * rot(0, r)).applyfunc(sp.nsimplify)


def _orthogonal(M: sp.Matrix) -> bool:
    return (M.T * M - sp.eye(3)).applyfunc(sp.nsimplify).is_zero_matrix


def exact_rotation(R: np.ndarray, tolerance: float = GEOMETRY_TOLERANCE) -> sp.Matrix:
    r"""The rotation ``R`` (3×3) as an exact SymPy matrix where it is one of simple angles
    (see the module docstring); entries stay floats otherwise."""
    R = np.asarray(R, dtype=float)
    entries = [exact_entry(x, tolerance) for x in R.flat]
    if all(e is not None for e in entries):
        M = sp.Matrix(3, 3, entries)
        if _orthogonal(M):
            return M
    import pinocchio as pin
    angles = [exact_angle(a, tolerance) for a in pin.rpy.matrixToRpy(R)]
    if all(a is not None for a in angles):
        M = _rpy_matrix(*angles)
        if np.abs(np.array(M.evalf(), dtype=float) - R).max() <= tolerance:
            return M
    return sp.Matrix(3, 3, [0 if abs(x) <= tolerance else sp.Float(x) for x in R.flat])


def exact_translation(p: np.ndarray, tolerance: float = GEOMETRY_TOLERANCE) -> sp.Matrix:
    """A translation 3-vector of :func:`exact_length` entries."""
    return sp.Matrix([exact_length(x, tolerance) for x in np.asarray(p, dtype=float)])


def exact_model(model, tolerance: float = GEOMETRY_TOLERANCE):
    r"""A copy of the Pinocchio ``model`` whose joint placements are the floats of their exact
    forms (:func:`exact_rotation`, :func:`exact_translation`): a rotation entry
    :math:`4.9\cdot10^{-12}` becomes ``0.0``, so that every later reading of the numbers
    (:func:`~.kinematics.exact_number`) finds the simple values."""
    import pinocchio as pin
    out = pin.Model(model)
    for j in range(1, model.njoints):
        P = model.jointPlacements[j]
        R = np.array(exact_rotation(P.rotation, tolerance).evalf(), dtype=float)
        p = np.array(exact_translation(P.translation, tolerance).evalf(), dtype=float).ravel()
        out.jointPlacements[j] = pin.SE3(R, p)
    return out
