r"""Scenarios to watch: simulations of the true reduced equations with simple controllers.

- ``fall``: the WIP released from a 0.3 rad tilt while turning, no input;
- ``balance``: the WIP balancing under LQR on its linearised reduced model about the upright,
  driving forward at 0.5 m/s from t = 1 s and turning at 0.6 rad/s from t = 3 s;
- ``circle``: TIAGo's base (upper body locked) driving a circle of radius 1 m at 0.4 m/s under
  a computed-torque velocity controller;
- ``roll``: a uniform ball rolling and spinning on the ground; ``roll_down``: a spinning ball
  rolling down a fixed sphere (seed 002).

The linearisation is by central differences of the reduced dynamics
:math:`\dot x = f(x, u)`, :math:`x = (\varphi, \dot x, \dot\psi, \dot\varphi)`; the LQR gain
comes from :func:`scipy.linalg.solve_continuous_are`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_continuous_are

from ..constraints.reduction import CoordinateMap
from ..coordinates import builtin_coordinate_set
from ..errors import UnknownNameError
from ..models.builder import WheeledModel
from ..models.registry import load_model
from .reduced import Trajectory, simulate

#: Step of the central differences of the linearisation.
LINEARISE_STEP = 1e-6


@dataclass(frozen=True)
class Scenario:
    name: str
    description: str
    model: WheeledModel
    trajectory: Trajectory


def wip_linearisation(cmap: CoordinateMap) -> tuple[np.ndarray, np.ndarray]:
    r"""(A_lin, B_lin) of :math:`x = (\varphi, \dot x, \dot\psi, \dot\varphi)` about the upright
    at rest."""
    wm = cmap.wm
    iphi = wm.index("phi")

    def f(x, u):
        q = np.zeros(wm.nv)
        q[iphi] = x[0]
        terms = cmap.terms_at(q, x[1:])
        return np.concatenate([[x[3]], np.linalg.solve(terms.A, terms.B @ u - terms.h - terms.Q)])

    x0, u0 = np.zeros(4), np.zeros(2)
    A = np.column_stack([(f(x0 + e, u0) - f(x0 - e, u0)) / (2 * LINEARISE_STEP)
                         for e in np.eye(4) * LINEARISE_STEP])
    B = np.column_stack([(f(x0, u0 + e) - f(x0, u0 - e)) / (2 * LINEARISE_STEP)
                         for e in np.eye(2) * LINEARISE_STEP])
    return A, B


def lqr_gain(A: np.ndarray, B: np.ndarray, Q: np.ndarray, R: np.ndarray) -> np.ndarray:
    P = solve_continuous_are(A, B, Q, R)
    return np.linalg.solve(R, B.T @ P)


def _fall(duration: float) -> Scenario:
    wm = load_model("wip")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "seed001"))
    q0 = cmap.model_configuration(np.array([0.0, 0.0, 0.3]))
    traj = simulate(cmap, q0, np.array([0.0, 0.8, 0.0]), duration, rate=60.0)
    return Scenario("fall", "the WIP released from a 0.3 rad tilt while turning, no input",
                    wm, traj)


def _balance(duration: float) -> Scenario:
    wm = load_model("wip")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "seed001"))
    A, B = wip_linearisation(cmap)
    K = lqr_gain(A, B, np.diag([100.0, 10.0, 10.0, 1.0]), np.eye(2))
    iphi = wm.index("phi")

    def control(t, q, nu):
        ref = np.array([0.0, 0.5 if t > 1.0 else 0.0, 0.6 if t > 3.0 else 0.0, 0.0])
        x = np.array([q[iphi], *nu])
        return -K @ (x - ref)

    q0 = cmap.model_configuration(np.array([0.0, 0.0, 0.1]))
    traj = simulate(cmap, q0, np.zeros(3), duration, rate=60.0, u=control, rtol=1e-8, atol=1e-10)
    return Scenario("balance", "the WIP balancing under LQR, driving forward then turning",
                    wm, traj)


def _circle(duration: float) -> Scenario:
    wm = load_model("tiago_base")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "heading"))
    speed, radius, gain = 0.4, 1.0, 5.0

    def control(t, q, nu):
        terms = cmap.terms_at(q, nu)
        want = np.array([speed, speed / radius]) * min(1.0, t)
        force = terms.A @ (gain * (want - nu)) + terms.h + terms.Q
        return np.linalg.lstsq(terms.B, force, rcond=None)[0]

    q0 = np.zeros(wm.nv)
    traj = simulate(cmap, q0, np.zeros(cmap.n), duration, rate=60.0, u=control, rtol=1e-8, atol=1e-10)
    return Scenario("circle", "TIAGo's base driving a circle of radius 1 m at 0.4 m/s", wm, traj)


def _roll(duration: float) -> Scenario:
    wm = load_model("sphere_plane")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "world_rates"))
    q0 = np.array([0.0, 0.0, wm.geometry["r"], 0.0, 0.0, 0.0])
    traj = simulate(cmap, q0, np.array([2.0, -1.0, 3.0]), duration, rate=60.0)
    return Scenario("roll", "a uniform ball rolling and spinning on the ground (seed 002)", wm, traj)


def _roll_down(duration: float) -> Scenario:
    wm = load_model("sphere_sphere")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    rho, tilt = wm.geometry["r"] + wm.geometry["R1"], 0.3
    q0 = np.array([rho * np.sin(tilt), 0.0, rho * np.cos(tilt), 0.2, 0.1, -0.3])
    traj = simulate(cmap, q0, np.array([1.0, -2.0, 30.0]), duration, rate=60.0)
    return Scenario("roll_down", "a spinning ball rolling down a fixed sphere of radius "
                    f"{wm.geometry['R1']} m (seed 002; the sphere itself is not drawn)", wm, traj)


SCENARIOS = {"fall": (_fall, "wip", 5.0), "balance": (_balance, "wip", 8.0),
             "circle": (_circle, "tiago_base", 16.0), "roll": (_roll, "sphere_plane", 2.0),
             "roll_down": (_roll_down, "sphere_sphere", 1.5)}


def default_scenario(model: str) -> str:
    for name, (_, m, _) in SCENARIOS.items():
        if m == model:
            return name
    raise UnknownNameError("scenario for model", model, [m for _, m, _ in SCENARIOS.values()])


def run_scenario(name: str, duration: float | None = None) -> Scenario:
    r"""Run a named scenario (see the module docstring)."""
    if name not in SCENARIOS:
        raise UnknownNameError("scenario", name, SCENARIOS)
    fn, _, default = SCENARIOS[name]
    return fn(duration if duration is not None else default)
