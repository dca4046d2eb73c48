r"""Equations of motion of a body on tilting rolling wheels, in chosen independent velocities.

The wheels' rows (:mod:`.wheel_contact`) give :math:`J_c(q)\,v = 0`, three per wheel. With
the independent velocities :math:`\nu = T v` a selection of model velocities (a bicycle's roll,
steer and rear-wheel rates), :math:`S` solves

.. math::

    \begin{bmatrix}J_c\\T\end{bmatrix} S = \begin{bmatrix}0\\ \mathbb 1\end{bmatrix},\qquad
    \dot S\nu = -\begin{bmatrix}J_c\\T\end{bmatrix}^{-1}\begin{bmatrix}\dot J_c v\\0\end{bmatrix}
    \quad (v = S\nu),

and the reduced equations are

.. math::

    A_\nu\dot\nu + C_\nu\nu + Q_\nu = B_\nu u,\qquad A_\nu = S^TAS,\quad
    C_\nu = S^TCS + S^TA\dot S,\quad Q_\nu = S^TQ,\quad B_\nu = S^TB,

with :math:`h_\nu = C_\nu\nu = S^T\,\mathrm{rnea}(q, v, \dot S\nu) - Q_\nu` computed by one
RNEA. Contact forces come from the full equations with multipliers (:meth:`multipliers`).

The holonomic part (contacts on the ground, :math:`g(q) = 0`) is kept by projection: the
simulation integrates :math:`\dot q = S\nu`, and at each sample solves :math:`g(q) = 0` for the
``heights`` coordinates (:func:`.wheel_contact.solve_contact`); the largest :math:`|g|` before
projection is reported as the drift.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..dynamics.terms import Terms, check_vector
from ..errors import StateError
from ..models.builder import WheeledModel
from ..models.springs import spring_force
from .wheel_contact import (WheelRows, solve_contact, wheel_heights, wheel_jacobian,
                            wheel_rows, wheel_rows_rate)

#: Smallest |det [J_c; T]| / (product of its row norms) (Hadamard's ratio, in [0, 1]) for the
#: chosen velocities to parametrise the rolling motions.
PARAMETRISATION_TOL = 1e-10
#: Default integration tolerances (relative, absolute).
RTOL, ATOL = 1e-10, 1e-12

Input = Callable[[float, np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class RollingTrajectory:
    r"""Samples of a simulation: times ``t``, configurations ``q`` (projected on
    :math:`g = 0`), independent velocities ``nu``, energy (NaN with inputs), and ``drift``: the
    largest contact height :math:`|g|` reached before each projection (m)."""

    t: np.ndarray
    q: np.ndarray
    nu: np.ndarray
    energy: np.ndarray
    drift: float

    def relative_energy_drift(self) -> float:
        scale = max(abs(self.energy[0]), np.abs(self.energy - self.energy[0]).max(), 1e-12)
        return float(np.abs(self.energy - self.energy[0]).max() / scale)


def normalised_determinant(K: np.ndarray) -> np.ndarray:
    r""":math:`|\det K| / \prod_i \lVert K_{i\cdot}\rVert` (stacks allowed): 1 for orthogonal
    rows, 0 for dependent ones, whatever the rows' scales."""
    return np.abs(np.linalg.det(K)) / np.prod(np.linalg.norm(K, axis=-1), axis=-1)


class RollingReduction:
    r"""The reduced equations of a model with tilting rolling wheels (module docstring).

    ``independent``: coordinate names whose rates are the independent velocities; ``heights``:
    coordinates solved for to keep the contacts on the ground (one per wheel)."""

    def __init__(self, wm: WheeledModel, independent: Sequence[str],
                 heights: Sequence[str]) -> None:
        if not wm.rolling_wheels:
            raise StateError("model", wm.name, "a model with rolling wheels (spec.rolling_wheels)")
        self.wm = wm
        self.independent = tuple(independent)
        self.heights = tuple(heights)
        self.index = [wm.index(n) for n in self.independent]
        for n in self.heights:
            wm.index(n)
        self.n = len(self.index)
        self.velocities = tuple("d" + n for n in self.independent)
        nv = wm.nv
        self.T = np.zeros((self.n, nv))
        self.T[np.arange(self.n), self.index] = 1.0
        self.m = 3 * len(wm.rolling_wheels)
        if self.m + self.n != nv:
            raise StateError("independent velocities", self.independent,
                             f"{nv - self.m} names ({nv} velocities, {self.m} contact rows)")
        self.B = wm.input_matrix()
        self._data = wm.model.createData()
        self._rhs = np.vstack([np.zeros((self.m, self.n)), np.eye(self.n)])

    # -- kinematics -------------------------------------------------------------------------
    def _solve(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, WheelRows]:
        rows = wheel_rows(self.wm, q, self._data)
        K = np.vstack([rows.J, self.T])
        if not normalised_determinant(K) > PARAMETRISATION_TOL:
            raise StateError("independent velocities", self.independent,
                             "velocities that parametrise the rolling motions at this "
                             "configuration ([J_c; T] is singular)")
        return K, np.linalg.solve(K, self._rhs), rows

    def velocity_matrix(self, q: np.ndarray) -> np.ndarray:
        r""":math:`S(q)`: model velocities :math:`v = S\nu` that keep the contacts rolling."""
        return self._solve(q)[1]

    def kinematics(self, q: np.ndarray, nu: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        r"""(S, v, :math:`\dot S`, :math:`\dot S\nu`) at ``(q, nu)``."""
        K, S, rows = self._solve(q)
        v = S @ nu
        dJ = wheel_rows_rate(self.wm, q, v, rows, self._data)
        Sdot = -np.linalg.solve(K, np.vstack([dJ @ S, np.zeros((self.n, self.n))]))
        return S, v, Sdot, Sdot @ nu

    # -- dynamics ---------------------------------------------------------------------------
    def terms(self, q: np.ndarray, nu: np.ndarray) -> Terms:
        r""":math:`A_\nu, C_\nu, Q_\nu, B_\nu, h_\nu` at ``(q, nu)``."""
        nu = check_vector("velocity", nu, self.n, self.velocities)
        model, data = self.wm.model, self._data
        S, v, Sdot, _ = self.kinematics(q, nu)
        A = pin.crba(model, data, q)
        A = np.triu(A) + np.triu(A, 1).T
        C = pin.computeCoriolisMatrix(model, data, q, v)
        Q = self.wm.potential_force(data, q)
        A_nu = S.T @ A @ S
        C_nu = S.T @ C @ S + S.T @ A @ Sdot
        return Terms(self.velocities, self.wm.input_names, 0.5 * (A_nu + A_nu.T), C_nu,
                     S.T @ Q, S.T @ self.B, C_nu @ nu)

    def mass_and_force(self, q: np.ndarray, nu: np.ndarray, u: np.ndarray | None = None
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        r"""(:math:`A_\nu`, :math:`B_\nu u - h_\nu - Q_\nu`, :math:`v`), by CRBA and one RNEA."""
        model, data = self.wm.model, self._data
        S, v, _, sdot_nu = self.kinematics(q, nu)
        A = pin.crba(model, data, q)
        A = np.triu(A) + np.triu(A, 1).T
        force = -S.T @ pin.rnea(model, data, q, v, sdot_nu)
        if self.wm.springs:
            force -= S.T @ spring_force(self.wm.springs, q, model.nv)
        if u is not None and len(u):
            force = force + S.T @ (self.B @ u)
        return S.T @ A @ S, force, v

    def acceleration(self, q: np.ndarray, nu: np.ndarray, u: np.ndarray | None = None) -> np.ndarray:
        r""":math:`\dot\nu` of the reduced equations."""
        A_nu, force, _ = self.mass_and_force(q, nu, u)
        return np.linalg.solve(A_nu, force)

    def multipliers(self, q: np.ndarray, nu: np.ndarray, u: np.ndarray | None = None
                    ) -> tuple[np.ndarray, np.ndarray]:
        r"""Contact forces :math:`\lambda` (per wheel the world x, y, z force of the ground on
        the wheel) and :math:`\dot v`, from
        :math:`A\dot v + h + Q = Bu + J_c^T\lambda,\ J_c\dot v = -\dot J_c v`."""
        model, data = self.wm.model, self._data
        v = self.velocity_matrix(q) @ nu
        J, dJ = wheel_jacobian(self.wm, q, v, data=data)
        A = pin.crba(model, data, q)
        A = np.triu(A) + np.triu(A, 1).T
        nle = self.wm.nonlinear_effects(data, q, v)
        m = self.m
        K = np.block([[A, -J.T], [J, np.zeros((m, m))]])
        tau = self.B @ u if u is not None and len(u) else np.zeros(model.nv)
        sol = np.linalg.solve(K, np.concatenate([tau - nle, -dJ @ v]))
        return sol[model.nv:], sol[:model.nv]

    def energy(self, q: np.ndarray, nu: np.ndarray) -> float:
        r"""Kinetic plus potential energy."""
        model, data = self.wm.model, self._data
        v = self.velocity_matrix(q) @ nu
        return float(pin.computeKineticEnergy(model, data, q, v)
                     + self.wm.potential_energy(data, q))

    # -- states -----------------------------------------------------------------------------
    def on_ground(self, q: np.ndarray) -> np.ndarray:
        r"""``q`` with the ``heights`` coordinates solved so that every contact touches."""
        return solve_contact(self.wm, q, self.heights)

    def simulate(self, q0: np.ndarray, nu0: np.ndarray, duration: float, rate: float = 200.0,
                 u: Input | None = None, rtol: float = RTOL, atol: float = ATOL,
                 project: bool = True) -> RollingTrajectory:
        r"""Integrate :math:`\dot q = S\nu`, :math:`\dot\nu` from ``(q0, nu0)`` (``q0`` is put
        on the ground first) for ``duration`` s, sampled at ``rate`` Hz; with ``project`` the
        configuration is put back on :math:`g = 0` at every sample."""
        wm = self.wm
        nq = wm.model.nq
        q = self.on_ground(np.asarray(q0, dtype=float))
        nu = check_vector("velocity", nu0, self.n, self.velocities)
        zero = np.zeros(len(wm.input_names))
        control = u or (lambda t, q, nu: zero)

        def rhs(t: float, y: np.ndarray) -> np.ndarray:
            qq, nn = y[:nq], y[nq:]
            A_nu, force, v = self.mass_and_force(qq, nn, control(t, qq, nn))
            if not (np.all(np.isfinite(A_nu)) and np.all(np.isfinite(force))):
                raise StateError(None, float(t), "a state where the reduced equations are "
                                 "finite (the motion reached a singular configuration)")
            return np.concatenate([v, np.linalg.solve(A_nu, force)])

        times = np.linspace(0.0, duration, int(round(duration * rate)) + 1)
        qs, nus, drift = [q], [nu], 0.0
        from scipy.integrate import solve_ivp        # simulations only (0.3 s import)
        for t0, t1 in zip(times[:-1], times[1:]):
            sol = solve_ivp(rhs, (t0, t1), np.concatenate([q, nu]), method="DOP853",
                            rtol=rtol, atol=atol)
            if not sol.success or not np.all(np.isfinite(sol.y[:, -1])):
                raise StateError(None, float(t0), f"integration to {duration} s ({sol.message})")
            q, nu = sol.y[:nq, -1], sol.y[nq:, -1]
            drift = max(drift, float(np.abs(wheel_heights(wm, q)).max()))
            if project:
                q = self.on_ground(q)
            qs.append(q)
            nus.append(nu)
        q_path, nu_path = np.array(qs), np.array(nus)
        energy = (np.array([self.energy(a, b) for a, b in zip(q_path, nu_path)]) if u is None
                  else np.full(len(times), np.nan))
        return RollingTrajectory(times, q_path, nu_path, energy, drift)
