r"""Physical parameters of the two-wheeled inverted pendulum, named as in seed 001.

Body (link ``body``, seed 001's frame 1: x forward, y up, z along the axle to the right):
mass :math:`m_S`; centre of mass at :math:`(d_x, d, d_z)` from the axle midpoint (seed 001 has
:math:`d_x = d_z = 0`); central inertia tensor

.. math::

    I_G = \begin{bmatrix} I_1 & I_{xy} & I_{xz}\\ I_{xy} & I_2 & I_{yz}\\ I_{xz} & I_{yz} & I_3
    \end{bmatrix}

(tensor entries, so a product is :math:`-\int xy\,dm`). Each wheel (``wheel_left``,
``wheel_right``): mass :math:`m_C`, radius :math:`R`, centre at :math:`z = \mp L` (:math:`L` is
half the track), inertia :math:`\mathrm{diag}(I_{w2}, I_{w2}, I_{w3})` about its centre (a
diameter, a diameter, the axle). Each wheel motor adds the armature :math:`I_a = \eta^2 I_m` on
its joint. Gravity :math:`g`.

Khalil's standard parameters of a link about its frame origin follow by the parallel-axis rule:
:math:`MS = m\,c`, :math:`J_O = I_G + m(\lVert c\rVert^2 \mathbb 1 - c c^T)`, with
:math:`XX = J_{O,xx}, XY = J_{O,xy}, \dots` The same function serves numbers and SymPy symbols.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, fields
from typing import Any, ClassVar

import numpy as np

from ..errors import ParameterError

#: Standard-parameter names in Pinocchio's ``toDynamicParameters`` order.
STANDARD_NAMES: tuple[str, ...] = ("M", "MX", "MY", "MZ", "XX", "XY", "YY", "XZ", "YZ", "ZZ")
#: Relative slack allowed in the triangle inequalities of an inertia tensor.
TRIANGLE_TOL = 1e-12


@dataclass(frozen=True)
class WipParameters:
    r"""Physical parameters of the WIP (SI units). Validated on construction."""

    m_S: float = 60.0
    m_C: float = 5.0
    R: float = 0.25
    L: float = 0.35
    d: float = 0.45
    g: float = 9.81
    I1: float = 6.25
    I2: float = 1.7
    I3: float = 5.45
    Ixy: float = 0.0
    Ixz: float = 0.0
    Iyz: float = 0.0
    Iw2: float = 0.0808
    Iw3: float = 0.15625
    d_x: float = 0.0
    d_z: float = 0.0
    I_a: float = 0.0

    #: The masses and inertias of the record by what scales them with its density (the body,
    #: the two wheels alike, the motors' armature), and the links of each: a robot of another
    #: density is another robot of this model (its lengths and gravity kept).
    DENSITY_OF: ClassVar[Mapping[str, str]] = {
        **dict.fromkeys(("m_S", "I1", "I2", "I3", "Ixy", "Ixz", "Iyz"), "body"),
        **dict.fromkeys(("m_C", "Iw2", "Iw3"), "wheels"), "I_a": "armature"}
    LINK_GROUPS: ClassVar[Mapping[str, str]] = {"body": "body", "wheel_left": "wheels",
                                                "wheel_right": "wheels"}
    #: The record's lengths (each drawn by its own factor where parameter sets draw lengths
    #: more widely than its own ranges).
    LENGTHS: ClassVar[tuple[str, ...]] = ("R", "L", "d", "d_x", "d_z")

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if not isinstance(value, (int, float)) or not math.isfinite(value):
                raise ParameterError(f.name, value, "a finite number")
        for name in ("m_S", "m_C", "R", "L"):
            if getattr(self, name) <= 0:
                raise ParameterError(name, getattr(self, name), "a positive number")
        for name in ("g", "I_a"):
            if getattr(self, name) < 0:
                raise ParameterError(name, getattr(self, name), "a number >= 0")
        check_inertia("body central inertia (I1, I2, I3, Ixy, Ixz, Iyz)", self.body_inertia())
        check_inertia("wheel inertia (Iw2, Iw2, Iw3)", np.diag([self.Iw2, self.Iw2, self.Iw3]))

    def body_inertia(self) -> np.ndarray:
        return np.array([[self.I1, self.Ixy, self.Ixz], [self.Ixy, self.I2, self.Iyz],
                         [self.Ixz, self.Iyz, self.I3]], dtype=float)

    def as_dict(self) -> dict[str, float]:
        return asdict(self)

    def replace(self, **changes: float) -> "WipParameters":
        unknown = set(changes) - {f.name for f in fields(self)}
        if unknown:
            from ..errors import UnknownNameError
            raise UnknownNameError("parameter", sorted(unknown)[0], [f.name for f in fields(self)])
        return WipParameters(**{**asdict(self), **changes})


def check_inertia(name: str, inertia: np.ndarray) -> None:
    r"""Raise :class:`ParameterError` unless the tensor is symmetric positive definite with
    principal moments obeying :math:`I_a \le I_b + I_c`."""
    eig = np.linalg.eigvalsh(0.5 * (inertia + inertia.T))
    if eig[0] <= 0:
        raise ParameterError(name, inertia.tolist(), "a positive definite inertia tensor")
    if eig[2] > (eig[0] + eig[1]) * (1 + TRIANGLE_TOL):
        raise ParameterError(name, inertia.tolist(),
                             "principal moments with I_max <= I_a + I_b (triangle inequality)")


def standard_parameters(p: Mapping[str, Any]) -> dict[str, dict[str, Any]]:
    r"""Khalil's standard parameters of ``body``, ``wheel_left`` and ``wheel_right`` in their
    link frames, from the physical parameters ``p`` (numbers or SymPy symbols, keyed as the
    fields of :class:`WipParameters`; ``Any``: the same formulas serve both)."""
    m, cx, cy, cz = p["m_S"], p["d_x"], p["d"], p["d_z"]
    c = (cx, cy, cz)
    r2 = cx * cx + cy * cy + cz * cz
    IG = ((p["I1"], p["Ixy"], p["Ixz"]), (p["Ixy"], p["I2"], p["Iyz"]),
          (p["Ixz"], p["Iyz"], p["I3"]))
    J = [[IG[i][j] + m * ((r2 if i == j else 0) - c[i] * c[j]) for j in range(3)]
         for i in range(3)]
    body = {"M": m, "MX": m * cx, "MY": m * cy, "MZ": m * cz, "XX": J[0][0], "XY": J[0][1],
            "YY": J[1][1], "XZ": J[0][2], "YZ": J[1][2], "ZZ": J[2][2]}
    wheel = {"M": p["m_C"], "MX": 0, "MY": 0, "MZ": 0, "XX": p["Iw2"], "XY": 0, "YY": p["Iw2"],
             "XZ": 0, "YZ": 0, "ZZ": p["Iw3"]}
    return {"body": body, "wheel_left": dict(wheel), "wheel_right": dict(wheel)}


def random_wip_parameters(rng: np.random.Generator) -> WipParameters:
    r"""A random, physically consistent parameter set with every product of inertia and every
    centre-of-mass offset nonzero (for structural checks).

    The body's central inertia is built from positive second moments :math:`(a, b, c)` as
    :math:`Q\,\mathrm{diag}(b+c, a+c, a+b)\,Q^T` with a random rotation :math:`Q`, so the triangle
    inequality holds by construction; likewise the wheel's. :math:`Q` comes from a quaternion
    of four standard normal draws, normalised (uniform on the rotations).
    """
    import pinocchio as pin

    m_S = rng.uniform(20.0, 100.0)
    a, b, c = rng.uniform(0.005, 0.1, size=3) * m_S
    x, y, z, w = rng.normal(size=4)          # a uniformly random rotation: a normalised
    Q = pin.Quaternion(w, x, y, z).normalized().toRotationMatrix()   # Gaussian quaternion
    IG = Q @ np.diag([b + c, a + c, a + b]) @ Q.T
    m_C = rng.uniform(1.0, 10.0)
    R = rng.uniform(0.1, 0.4)
    s, t = rng.uniform(0.1, 0.5) * m_C * R**2, rng.uniform(0.001, 0.05) * m_C * R**2
    return WipParameters(
        m_S=m_S, m_C=m_C, R=R, L=rng.uniform(0.2, 0.5), d=rng.uniform(0.2, 0.8),
        g=rng.uniform(5.0, 15.0), I1=IG[0, 0], I2=IG[1, 1], I3=IG[2, 2], Ixy=IG[0, 1],
        Ixz=IG[0, 2], Iyz=IG[1, 2], Iw2=s + t, Iw3=2 * s, d_x=rng.uniform(-0.1, 0.1),
        d_z=rng.uniform(-0.1, 0.1), I_a=rng.uniform(0.0, 0.5))
