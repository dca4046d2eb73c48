r"""Simulation of a model on its reduced equations (rolling eliminated).

For a quasi-velocity set (rolling eliminated, or no rolling), the state is the model
configuration :math:`q` (all of it: x0, y0, heading, wheel angles...) and the document
velocities :math:`\nu`:

.. math::

    \dot q = S(q)\,\nu,\qquad A_\nu(q)\,\dot\nu = B_\nu u - h_\nu(q,\nu) - Q_\nu(q).

For a holonomic set without rolling constraints (a fixed-base body, or a holonomic map such as
a gear coupling or a disk rolling on a line) the state is the document's positions and their
velocities, :math:`\dot q_{doc} = \nu`, and the model configuration is :math:`g(q_{doc})`;

integrated by :func:`scipy.integrate.solve_ivp` (DOP853). The energy
:math:`E = \tfrac12\nu^TA_\nu\nu + U(q)` is returned along the trajectory; with zero input it
must stay constant (the rolling constraints do no work).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from ..constraints.batch import reduced_mass_batch
from ..constraints.linalg import spd_solve
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
    positions: np.ndarray | None = None      # document positions (N × n), holonomic sets

    def relative_energy_drift(self) -> float:
        scale = max(abs(self.energy[0]), np.abs(self.energy - self.energy[0]).max(), 1e-12)
        return float(np.abs(self.energy - self.energy[0]).max() / scale)


def energy(cmap: CoordinateMap, q: np.ndarray, nu: np.ndarray,
           q_doc: np.ndarray | None = None) -> float:
    r""":math:`\tfrac12\nu^TA_\nu\nu + U(q)` (``q_doc``: the document positions, needed for
    holonomic sets)."""
    terms, _, _ = cmap.reduce_at(q, nu, q_doc)
    return float(0.5 * nu @ terms.A @ nu
                 + cmap.wm.potential_energy(cmap.wm.model.createData(), q))


def energies(cmap: CoordinateMap, q: np.ndarray, nu: np.ndarray,
             q_doc: np.ndarray | None = None) -> np.ndarray:
    r""":func:`energy` at N samples at once (``q``: N model configurations, ``nu``: N × n
    document velocities, ``q_doc`` the document positions of holonomic sets): :math:`A_\nu`
    from the batched reduction (:func:`~wheeled_dyn.constraints.batch.reduced_mass_batch`)."""
    A = reduced_mass_batch(cmap, q, q_doc)
    data = cmap.wm.model.createData()
    potential = np.array([cmap.wm.potential_energy(data, x) for x in q])
    return 0.5 * np.einsum("ni,nij,nj->n", nu, A, nu) + potential


def simulate(cmap: CoordinateMap, q0: np.ndarray, nu0: np.ndarray, duration: float,
             rate: float = 1000.0, u: Input | None = None, rtol: float = RTOL,
             atol: float = ATOL) -> Trajectory:
    r"""Integrate from ``q0`` (the model configuration for a quasi-velocity set, the document
    positions for a holonomic one) and document velocities ``nu0`` for ``duration`` seconds,
    sampled at ``rate`` Hz. ``u(t, q, nu)`` gives the motor inputs (default zero; ``q`` is the
    model configuration). Sets that keep rolling constraints with multipliers cannot be
    integrated this way."""
    cs = cmap.cs
    holonomic = cs.kind == "holonomic"
    if cs.rolling == "multipliers" or (holonomic and cs.rolling != "none"):
        raise StateError(None, cs.name, "a quasi-velocity coordinate set with rolling "
                                        "eliminated (e.g. 'seed001', 'heading', 'wheels'), or a "
                                        "set without rolling constraints")
    nq, n = (cmap.n if holonomic else cmap.wm.model.nq), cmap.n
    n_inputs = len(cmap.wm.input_names)
    zero_u = np.zeros(n_inputs)
    control = u or (lambda t, q, nu: zero_u)

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        if holonomic:
            q_doc, nu = y[:nq], y[nq:]
            q = cmap.model_configuration(q_doc)
            A, hQ, B, _ = cmap.dynamics_at(q, nu, q_doc)
            qdot = nu
        else:
            q, nu = y[:nq], y[nq:]
            A, hQ, B, S = cmap.dynamics_at(q, nu)
            qdot = S @ nu
        force = B @ control(t, q, nu) - hQ
        return np.concatenate([qdot, spd_solve(A, force)])

    y0 = np.concatenate([np.asarray(q0, float).reshape(-1), np.asarray(nu0, float).reshape(-1)])
    if y0.shape != (nq + n,) or not np.all(np.isfinite(y0)):
        raise StateError(None, y0.tolist(), f"{nq + n} finite numbers (initial state)")
    t_eval = np.linspace(0.0, duration, int(round(duration * rate)) + 1)
    sol = solve_ivp(rhs, (0.0, duration), y0, method="DOP853", t_eval=t_eval, rtol=rtol, atol=atol)
    if not sol.success:
        raise StateError(None, float(sol.t[-1]), f"integration to {duration} s ({sol.message})")
    positions = None
    if holonomic:
        positions, nus = sol.y[:nq].T, sol.y[nq:].T
        qs = np.array([cmap.model_configuration(p) for p in positions])
    else:
        qs, nus = sol.y[:nq].T, sol.y[nq:].T
    us = np.array([control(t, q, nu) for t, q, nu in zip(sol.t, qs, nus)]).reshape(len(sol.t),
                                                                                n_inputs)
    es = energies(cmap, qs, nus, positions) if u is None else np.full(len(sol.t), np.nan)
    return Trajectory(sol.t, qs, nus, us, es, cmap.cs.velocities, cmap.wm.coordinate_names,
                      positions)
