r"""Khalil's standard inertial parameters of each joint's body, in the joint frame.

Per joint :math:`j` ten numbers, in the order of Pinocchio's ``Inertia.toDynamicParameters()``:

.. math::
   \pi_j = [M_j,\ MX_j,\ MY_j,\ MZ_j,\ XX_j,\ XY_j,\ YY_j,\ XZ_j,\ YZ_j,\ ZZ_j],

with :math:`MS_j = [MX_j, MY_j, MZ_j]^T = M_j\,c_j` the first moments and
:math:`J_{O,j} = \begin{bmatrix}XX&XY&XZ\\XY&YY&YZ\\XZ&YZ&ZZ\end{bmatrix}_j` the inertia tensor
about the joint-frame origin (not the centre of mass). The kinetic energy of body :math:`j`
(seed 001, eq. (17)) is

.. math::
   E_j = \tfrac12\left(\omega^T J_O \omega + M v^T v + 2\,MS^T (v \times \omega)\right)
       = \tfrac12 \begin{bmatrix} v \\ \omega \end{bmatrix}^T
         \underbrace{\begin{bmatrix} M I_3 & -[MS]_\times \\ [MS]_\times & J_O \end{bmatrix}}_{
         \mathcal{I}_j}
         \begin{bmatrix} v \\ \omega \end{bmatrix}.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import pinocchio as pin
import sympy as sp

from ..errors import ParameterError, UnknownNameError
from .kinematics import skew

#: Names of the ten standard parameters, in Pinocchio's ``toDynamicParameters()`` order.
PARAMETER_NAMES: tuple[str, ...] = ("M", "MX", "MY", "MZ", "XX", "XY", "YY", "XZ", "YZ", "ZZ")


def inertial_symbols(suffix: str) -> tuple[sp.Symbol, ...]:
    """The ten symbols ``M_<suffix>, MX_<suffix>, ..., ZZ_<suffix>`` (no assumptions)."""
    return tuple(sp.Symbol(f"{n}_{suffix}") for n in PARAMETER_NAMES)


def numeric_parameters(model: pin.Model) -> dict[int, tuple[float, ...]]:
    """The model's own parameters: ``{j: model.inertias[j].toDynamicParameters()}`` for every
    joint ``j >= 1``."""
    return {j: tuple(float(x) for x in model.inertias[j].toDynamicParameters())
            for j in range(1, model.njoints)}


def named_parameters(model: pin.Model) -> dict[str, float]:
    """The model's own parameters by the names of their symbols in the closed forms of
    :mod:`.tree`: ``{"M_<joint>": m, "MX_<joint>": ..., ..., "ZZ_<joint>": ...}``."""
    return {f"{k}_{model.names[j]}": x for j, pi in numeric_parameters(model).items()
            for k, x in zip(PARAMETER_NAMES, pi)}


def resolve_parameters(model: pin.Model, params: Mapping[int, Sequence] | None
                       ) -> dict[int, tuple[sp.Expr, ...]]:
    """Ten SymPy expressions per joint: ``params[j]`` where given, else the default symbols
    named after the joint (:func:`inertial_symbols`).

    Keys may be joint indices or joint names. Raises :class:`UnknownNameError` for a key that
    is no joint and :class:`ParameterError` for a sequence that is not of length ten.
    """
    names = list(model.names)
    given: dict[int, Sequence] = {}
    for key, value in (params or {}).items():
        if isinstance(key, str):
            if key not in names[1:]:
                raise UnknownNameError("joint", key, names[1:], where="symbolic parameters")
            key = names.index(key)
        if not (isinstance(key, (int, np.integer)) and 1 <= int(key) < model.njoints):
            raise UnknownNameError("joint", str(key), names[1:], where="symbolic parameters")
        given[int(key)] = value
    out: dict[int, tuple[sp.Expr, ...]] = {}
    for j in range(1, model.njoints):
        if j in given:
            vals = tuple(sp.sympify(x) for x in given[j])
            if len(vals) != len(PARAMETER_NAMES):
                raise ParameterError(f"params[{names[j]}]", given[j],
                                     f"10 values in the order {', '.join(PARAMETER_NAMES)}")
            out[j] = vals
        else:
            out[j] = inertial_symbols(names[j])
    return out


def spatial_inertia(pi: Sequence[sp.Expr]) -> sp.Matrix:
    r"""The 6×6 matrix :math:`\mathcal{I}` of the module docstring, acting on
    :math:`[v; \omega]`, from the ten standard parameters."""
    m, mx, my, mz, xx, xy, yy, xz, yz, zz = pi
    ms = skew([mx, my, mz])
    jo = sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    return sp.Matrix(sp.BlockMatrix([[m * sp.eye(3), -ms], [ms, jo]]))


def _cross(a: Sequence, b: Sequence) -> list:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _dot(a: Sequence, b: Sequence):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def kinetic_energy_body(pi: Sequence, v: Sequence, omega: Sequence):
    r""":math:`E = \tfrac12(\omega^T J_O \omega + M v^T v + 2 MS^T (v \times \omega))` (eq. 17).

    Plain arithmetic on the entries, so it works on SymPy expressions and on ring elements
    alike (the result is then twice the energy divided by two: no Rational needed)."""
    m, mx, my, mz, xx, xy, yy, xz, yz, zz = pi
    w = omega
    jw = [xx * w[0] + xy * w[1] + xz * w[2],
          xy * w[0] + yy * w[1] + yz * w[2],
          xz * w[0] + yz * w[1] + zz * w[2]]
    twice = _dot(w, jw) + m * _dot(v, v) + 2 * _dot([mx, my, mz], _cross(v, w))
    return twice / 2


def potential_energy_body(pi: Sequence, R: Sequence[Sequence], p: Sequence,
                          gravity: Sequence):
    r""":math:`U = -g^T (M p + R\, MS)` with :math:`(R, p)` the world placement (eq. 17);
    ``R`` is indexed ``R[row][col]``."""
    m, mx, my, mz = pi[:4]
    ms = (mx, my, mz)
    world = [m * p[r] + R[r][0] * ms[0] + R[r][1] * ms[1] + R[r][2] * ms[2] for r in range(3)]
    return -_dot(gravity, world)
