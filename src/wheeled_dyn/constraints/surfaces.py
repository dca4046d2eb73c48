r"""A ball on a fixed surface of revolution: where it touches, the normal there, and how fast
that normal turns.

The surface turns about the vertical axis through a point :math:`o`; its meridian is the height
:math:`z = o_z + f(\rho)` over the horizontal distance :math:`\rho` from the axis, with
:math:`f(0) = 0` and :math:`f'(0) = 0` (a smooth vertex at :math:`o`). The ball, of radius
:math:`r`, is on the upper side (inside a bowl such as the paraboloid
:math:`f = \rho^2/(2a)`). In the meridian plane, with :math:`e_\rho` the horizontal unit vector
from the axis towards the point and :math:`e_\varphi = e_z\times e_\rho`, the unit normal at the
surface point of radius :math:`\rho`, pointing to the ball's side, and the unit tangent of the
meridian are

.. math::

    n = \frac{-f'\,e_\rho + e_z}{\sqrt{1 + f'^2}},\qquad
    t_1 = \frac{e_\rho + f'\,e_z}{\sqrt{1 + f'^2}},\qquad t_2 = e_\varphi .

**Contact point.** The centre lies on the offset surface :math:`c = p + r\,n(p)`, so the
contact :math:`p` is in the meridian plane of :math:`c`, and its radius :math:`\rho_p` solves

.. math::

    g(\rho_p) \equiv \rho_p - r\,\frac{f'(\rho_p)}{\sqrt{1 + f'(\rho_p)^2}} = \rho_c ,\qquad
    g'(\rho) = 1 - r\,\kappa_1(\rho),

with :math:`\rho_c` the centre's distance from the axis. As :math:`|f'|/\sqrt{1+f'^2} < 1`, the
root lies in :math:`[\max(0, \rho_c - r), \rho_c + r]` (where :math:`g - \rho_c` changes sign,
:math:`g(0) = 0`); it is unique when :math:`r\,\kappa_1 < 1` everywhere, i.e. the ball is
smaller than the smallest radius of curvature of the meridian on its side (the paraboloid:
:math:`r < a`, checked by :class:`~wheeled_dyn.models.contact.SphereContact`). It is found by
Brent's method. Only the horizontal position of :math:`c` enters: :math:`n` is a function of
:math:`(c_x, c_y)` alone.

**Curvatures.** The principal curvatures, positive for a bowl (the surface bends towards the
ball), are those of the meridian and of the parallel,

.. math::

    \kappa_1 = \frac{f''}{(1 + f'^2)^{3/2}},\qquad
    \kappa_2 = \frac{f'}{\rho\,\sqrt{1 + f'^2}}\ \xrightarrow[\rho\to 0]{}\ f''(0),

and the shape operator (Weingarten map, :math:`dn = W\,dp` along the surface) is
:math:`W = -\kappa_1\,t_1t_1^T - \kappa_2\,t_2t_2^T` on the tangent plane. (A ball on the
outside of a sphere of radius :math:`R_1` has :math:`W = P/R_1`, :math:`P = 1 - nn^T`.) The
meridian supplies :math:`f'/\rho` itself, so that :math:`\kappa_2` is exact on the axis.

**Rate of the normal.** Differentiating :math:`c = p + r\,n(p)` along the surface gives
:math:`\dot c = (1 + rW)\,\dot p`, hence

.. math::

    \dot n = W\,(1 + rW)^{-1}\,\dot c_T
    = -\frac{\kappa_1}{1 - r\kappa_1}\,(e_\rho\!\cdot\dot c)\,(e_\rho + f' e_z)
      -\frac{\kappa_2}{1 - r\kappa_2}\,(e_\varphi\!\cdot\dot c)\,e_\varphi ,

where :math:`\dot c_T = \sqrt{1+f'^2}\,(e_\rho\cdot\dot c)\,t_1 + (e_\varphi\cdot\dot c)\,e_\varphi`
is the tangent vector with the same horizontal part as :math:`\dot c` (equal to :math:`\dot c`
when the centre moves on its offset surface). This is the exact derivative of
:math:`n(c_x, c_y)` for any :math:`\dot c`: from :math:`n(\rho_p, \varphi)`,
:math:`\dot n = -\kappa_1\dot\rho_p(e_\rho + f'e_z) - \kappa_2\rho_p\dot\varphi\,e_\varphi`
with :math:`\dot\rho_c = (1 - r\kappa_1)\dot\rho_p` and :math:`\rho_c = (1 - r\kappa_2)\rho_p`.
For the sphere :math:`W(1 + rW)^{-1} = P/(R_1 + r)`, the rule of :mod:`.sphere_contact`. On the
axis the two curvatures agree and :math:`W` is isotropic, so the arbitrary choice of
:math:`e_\rho` there does not matter.

A new meridian is a class with the four methods of :class:`Meridian`; a new surface key maps
to it in :func:`meridian_of`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from ..models.contact import SphereContact

_EX = np.array([1.0, 0.0, 0.0])
_EZ = np.array([0.0, 0.0, 1.0])
#: Below this distance from the axis (relative to the ball radius) the centre is on the axis.
AXIS_TOL = 1e-14


class Meridian(Protocol):
    r"""The derivatives of the height :math:`f(\rho)` of a surface of revolution above its
    vertex, with :math:`f(0) = f'(0) = 0` (the contact needs its slope and curvature)."""

    def df(self, rho: float) -> float: ...

    def d2f(self, rho: float) -> float: ...

    def df_by_rho(self, rho: float) -> float:
        r""":math:`f'(\rho)/\rho`, continued by :math:`f''(0)` at :math:`\rho = 0`."""
        ...


@dataclass(frozen=True)
class Paraboloid:
    r"""The paraboloid :math:`f(\rho) = \rho^2/(2a)`, :math:`a` its radius of curvature at the
    vertex (``vertex_radius``); its curvatures :math:`\kappa_1 = a^2/(a^2+\rho^2)^{3/2}`,
    :math:`\kappa_2 = 1/\sqrt{a^2+\rho^2}` are largest, :math:`1/a`, at the vertex."""

    vertex_radius: float

    def df(self, rho: float) -> float:
        return rho / self.vertex_radius

    def d2f(self, rho: float) -> float:
        return 1.0 / self.vertex_radius

    def df_by_rho(self, rho: float) -> float:
        return 1.0 / self.vertex_radius


def meridian_of(spec: SphereContact) -> Meridian | None:
    r"""The meridian of the contact's surface, or None for the plane and the sphere."""
    if spec.surface == "paraboloid":
        return Paraboloid(float(spec.vertex_radius))
    return None


@dataclass(frozen=True)
class Foot:
    r"""Where a ball touches a surface of revolution: the contact's distance ``rho`` from the
    axis, the unit vectors ``e_rho``, ``e_phi`` of the centre's meridian plane, the slope
    :math:`f'` there, the unit normal ``normal`` (towards the ball) and the principal
    curvatures ``kappa1`` (meridian), ``kappa2`` (parallel)."""

    rho: float
    e_rho: np.ndarray
    e_phi: np.ndarray
    slope: float
    normal: np.ndarray
    kappa1: float
    kappa2: float


def foot(meridian: Meridian, vertex: np.ndarray, centre: np.ndarray, radius: float) -> Foot:
    r"""The contact of a ball of radius ``radius`` centred at ``centre`` with the surface of
    revolution of ``meridian`` whose vertex is ``vertex`` (see the module docstring)."""
    d = np.asarray(centre, dtype=float)[:2] - np.asarray(vertex, dtype=float)[:2]
    rho_c = math.hypot(d[0], d[1])
    if rho_c <= AXIS_TOL * radius:
        e_rho, rho = _EX, 0.0
    else:
        e_rho = np.array([d[0] / rho_c, d[1] / rho_c, 0.0])

        def residual(rho: float) -> float:
            s = meridian.df(rho)
            return rho - radius * s / math.sqrt(1.0 + s * s) - rho_c

        from scipy.optimize import brentq    # only for surfaces of revolution (0.3 s import)
        rho = brentq(residual, max(0.0, rho_c - radius), rho_c + radius,
                     xtol=1e-15 * (rho_c + radius))
    s = meridian.df(rho)
    w = math.sqrt(1.0 + s * s)
    return Foot(rho=rho, e_rho=e_rho, e_phi=np.cross(_EZ, e_rho), slope=s,
                normal=(_EZ - s * e_rho) / w, kappa1=meridian.d2f(rho) / w**3,
                kappa2=meridian.df_by_rho(rho) / w)


def normal_rate(ft: Foot, radius: float, centre_velocity: np.ndarray) -> np.ndarray:
    r""":math:`\dot n = W(1 + rW)^{-1}\dot c_T` at the contact ``ft`` of a ball of radius
    ``radius`` whose centre moves at ``centre_velocity`` (see the module docstring)."""
    radial = ft.e_rho @ centre_velocity
    around = ft.e_phi @ centre_velocity
    return (-ft.kappa1 / (1.0 - radius * ft.kappa1) * radial * (ft.e_rho + ft.slope * _EZ)
            - ft.kappa2 / (1.0 - radius * ft.kappa2) * around * ft.e_phi)
