r"""Simulation of a wheeled model on its reduced equations (rolling eliminated).

The state is the model configuration :math:`q` (all of it: x0, y0, heading, wheel angles...)
and the document velocities :math:`\nu`:

.. math::

    \dot q = S(q)\,\nu,\qquad A_\nu(q)\,\dot\nu = B_\nu u - h_\nu(q,\nu) - Q_\nu(q),

integrated by :func:`scipy.integrate.solve_ivp` (DOP853). The energy
:math:`E = \tfrac12\nu^TA_\nu\nu + U(q)` is returned along the trajectory; with zero input it
must stay constant (the rolling constraints do no work).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
from scipy.integrate import solve_ivp

from ..constraints.reduction import CoordinateMap
from ..errors import StateError

#: Default integration tolerances (relative, absolute).
RTOL, ATOL = 1e-10, 1e-12

Input = Callable[[float, np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class Trajectory:
    r"""Samples of a simulation: times ``t`` (N), model configurations ``q`` (N × nq),
    document velocities ``nu`` (N × n), inputs ``u`` (N × motors), energy (N)."""

    t: np.ndarray
    q: np.ndarray
    nu: np.ndarray
    u: np.ndarray
    energy: np.ndarray
    velocities: tuple[str, ...]
    coordinate_names: tuple[str, ...]

    def relative_energy_drift(self) -> float:
        scale = max(abs(self.energy[0]), np.abs(self.energy - self.energy[0]).max(), 1e-12)
        return float(np.abs(self.energy - self.energy[0]).max() / scale)


def energy(cmap: CoordinateMap, q: np.ndarray, nu: np.ndarray) -> float:
    r""":math:`\tfrac12\nu^TA_\nu\nu + U(q)`."""
    terms, _, _ = cmap.reduce_at(q, nu)
    return float(0.5 * nu @ terms.A @ nu
                 + pin.computePotentialEnergy(cmap.wm.model, cmap.wm.model.createData(), q))


def simulate(cmap: CoordinateMap, q0: np.ndarray, nu0: np.ndarray, duration: float,
             rate: float = 1000.0, u: Input | None = None, rtol: float = RTOL,
             atol: float = ATOL) -> Trajectory:
    r"""Integrate from model configuration ``q0`` and document velocities ``nu0`` for
    ``duration`` seconds, sampled at ``rate`` Hz. ``u(t, q, nu)`` gives the motor torques
    (default zero). The coordinate set must be of kind ``quasi`` with rolling eliminated."""
    if cmap.cs.kind != "quasi" or cmap.cs.rolling != "eliminate":
        raise StateError(None, cmap.cs.name, "a quasi-velocity coordinate set with rolling "
                                             "eliminated (e.g. 'seed001', 'heading', 'wheels')")
    nq, n = cmap.wm.model.nq, cmap.n
    n_inputs = len(cmap.wm.input_names)
    zero_u = np.zeros(n_inputs)
    control = u or (lambda t, q, nu: zero_u)

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        q, nu = y[:nq], y[nq:]
        terms, S, _ = cmap.reduce_at(q, nu)
        force = terms.B @ control(t, q, nu) - terms.h - terms.Q
        return np.concatenate([S @ nu, np.linalg.solve(terms.A, force)])

    y0 = np.concatenate([np.asarray(q0, float), np.asarray(nu0, float)])
    if not np.all(np.isfinite(y0)):
        raise StateError(None, y0.tolist(), "finite initial state")
    t_eval = np.linspace(0.0, duration, int(round(duration * rate)) + 1)
    sol = solve_ivp(rhs, (0.0, duration), y0, method="DOP853", t_eval=t_eval, rtol=rtol, atol=atol)
    if not sol.success:
        raise StateError(None, float(sol.t[-1]), f"integration to {duration} s ({sol.message})")
    qs, nus = sol.y[:nq].T, sol.y[nq:].T
    us = np.array([control(t, q, nu) for t, q, nu in zip(sol.t, qs, nus)])
    es = np.array([energy(cmap, q, nu) for q, nu in zip(qs, nus)]) if u is None else \
        np.full(len(sol.t), np.nan)
    return Trajectory(sol.t, qs, nus, us, es, cmap.cs.velocities, cmap.wm.coordinate_names)
