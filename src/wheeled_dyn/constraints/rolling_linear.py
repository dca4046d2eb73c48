r"""Linearised equations of a rolling body about a steady motion, from its reduced dynamics.

The reduced equations of :class:`~.wheel_reduction.RollingReduction` read
:math:`A_\nu(q)\,\dot\nu = F(q, \nu)` with :math:`F = B_\nu u - h_\nu - Q_\nu`. Let
:math:`p` be some position coordinates (a bicycle's roll and steer; the others are cyclic or
follow from the contact conditions, which :meth:`~.wheel_reduction.RollingReduction.on_ground`
solves at every evaluation), and :math:`\nu` the independent velocities. About
:math:`(p_0, \nu_0)` with :math:`\dot\nu_0 = 0`,

.. math::

    M\,\delta\dot\nu + D\,\delta\nu + K\,\delta p = 0,\qquad
    M = A_\nu(p_0),\quad D = -\frac{\partial F}{\partial\nu},\quad
    K = -\frac{\partial F}{\partial p}

(the term :math:`\partial A_\nu/\partial p\,\dot\nu_0` vanishes). The derivatives are central
differences refined by one Richardson step (error :math:`O(h^4)`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .wheel_reduction import RollingReduction

#: Step of the central differences (radians or metres, and per second for velocities).
STEP = 1e-3


@dataclass(frozen=True)
class LinearModel:
    r""":math:`M\,\delta\dot\nu + D\,\delta\nu + K\,\delta p = 0` (module docstring): ``M``
    and ``D`` are n × n, ``K`` n × len(positions); ``residual`` is :math:`\dot\nu_0` (zero at
    a steady motion)."""

    positions: tuple[str, ...]
    velocities: tuple[str, ...]
    M: np.ndarray
    D: np.ndarray
    K: np.ndarray
    residual: np.ndarray


def _richardson(f, x0: np.ndarray, h: float) -> np.ndarray:
    r"""Jacobian of ``f`` at ``x0``: :math:`(4D_{h/2} - D_h)/3` of central differences."""
    cols = []
    for i in range(len(x0)):
        e = np.zeros(len(x0))
        e[i] = 1.0

        def central(step: float) -> np.ndarray:
            return (f(x0 + step * e) - f(x0 - step * e)) / (2 * step)

        cols.append((4 * central(h / 2) - central(h)) / 3)
    return np.array(cols).T


def linearise(red: RollingReduction, q0: np.ndarray, positions: Sequence[str],
              nu0: np.ndarray, u: np.ndarray | None = None, step: float = STEP) -> LinearModel:
    r"""The linearised equations about ``(q0, nu0)`` in ``positions`` (coordinate names) and
    the reduction's independent velocities."""
    wm = red.wm
    idx = [wm.index(n) for n in positions]
    q0 = red.on_ground(np.asarray(q0, dtype=float))
    nu0 = np.asarray(nu0, dtype=float)

    def config(p: np.ndarray) -> np.ndarray:
        q = q0.copy()
        q[idx] = p
        return red.on_ground(q)

    def force(q: np.ndarray, nu: np.ndarray) -> np.ndarray:
        return red.mass_and_force(q, nu, u)[1]

    M, F0, _ = red.mass_and_force(q0, nu0, u)
    K = -_richardson(lambda p: force(config(p), nu0), q0[idx], step)
    D = -_richardson(lambda nu: force(q0, nu), nu0, step)
    return LinearModel(tuple(positions), red.velocities, M, D, K, np.linalg.solve(M, F0))


def state_matrix(lin: LinearModel, rate_of: Sequence[int]) -> np.ndarray:
    r"""The first-order matrix of :math:`x = (\delta p, \delta\nu)` when
    :math:`\dot p_i = \nu_{\text{rate\_of}[i]}`:

    .. math::

        \dot x = \begin{bmatrix} 0 & E\\ -M^{-1}K & -M^{-1}D\end{bmatrix} x ,

    :math:`E` selecting the velocities that are the positions' rates."""
    k, n = lin.K.shape[1], lin.M.shape[0]
    E = np.zeros((k, n))
    E[np.arange(k), list(rate_of)] = 1.0
    top = np.hstack([np.zeros((k, k)), E])
    bottom = np.hstack([-np.linalg.solve(lin.M, lin.K), -np.linalg.solve(lin.M, lin.D)])
    return np.vstack([top, bottom])


@dataclass(frozen=True)
class SpeedForm:
    r"""Linearised equations of a vehicle about straight running at speed :math:`v`, in the
    form of Meijaard et al. (2007):
    :math:`M\ddot p + v\,C_1\dot p + (g K_0 + v^2 K_2)\,p = f`."""

    M: np.ndarray
    C1: np.ndarray
    K0: np.ndarray
    K2: np.ndarray
    g: float

    def state_matrix(self, speed: float) -> np.ndarray:
        r""":math:`\dot x = A(v)\,x`, :math:`x = (p, \dot p)`."""
        k = self.M.shape[0]
        Minv = np.linalg.inv(self.M)
        K = self.g * self.K0 + speed ** 2 * self.K2
        return np.block([[np.zeros((k, k)), np.eye(k)], [-Minv @ K, -speed * Minv @ self.C1]])

    def eigenvalues(self, speeds: np.ndarray) -> np.ndarray:
        r"""Eigenvalues (N × 2k, each row sorted by real part) at N speeds, in one batched
        call."""
        speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
        k = self.M.shape[0]
        Minv = np.linalg.inv(self.M)
        A = np.zeros((len(speeds), 2 * k, 2 * k))
        A[:, :k, k:] = np.eye(k)
        A[:, k:, :k] = -(self.g * Minv @ self.K0)[None] - speeds[:, None, None] ** 2 * (
            Minv @ self.K2)[None]
        A[:, k:, k:] = -speeds[:, None, None] * (Minv @ self.C1)[None]
        ev = np.linalg.eigvals(A)
        return np.take_along_axis(ev, np.argsort(ev.real + 1e-9 * ev.imag, axis=1), axis=1)


def speed_form(red: RollingReduction, q0: np.ndarray, positions: Sequence[str],
               unit: np.ndarray, rates: Sequence[int], g: float) -> tuple[SpeedForm, LinearModel,
                                                                            LinearModel]:
    r"""The :class:`SpeedForm` of the true reduced dynamics from two linearisations, at rest
    and at the independent velocities ``unit`` of unit forward speed (the reduced forces are
    quadratic in :math:`\nu`, so :math:`K(v) = K(0) + v^2 (K(1) - K(0))` and
    :math:`D(v) = v\,D(1)` exactly). ``rates[i]`` is the velocity that is ``positions[i]``'s
    rate. Also returns the two linear models (their other rows and columns carry the couplings
    to the remaining velocities, zero for a symmetric vehicle)."""
    rest = linearise(red, q0, positions, np.zeros_like(unit))
    moving = linearise(red, q0, positions, unit)
    sel = list(rates)
    form = SpeedForm(rest.M[np.ix_(sel, sel)], moving.D[np.ix_(sel, sel)], rest.K[sel] / g,
                     moving.K[sel] - rest.K[sel], g)
    return form, rest, moving
