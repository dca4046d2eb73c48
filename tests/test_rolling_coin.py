r"""The rolling disk (``rolling_coin``): results reproduced from the tool's own dynamics.

Closed forms (uniform thin disk of mass m, radius R; I_a = m R^2/2 about the axle, I_d =
m R^2/4 about a diameter; lean phi, heading rate Omega, total spin about the axle
omega_2 = theta-dot + Omega sin(phi)). Euler's equations about the centre with the rolling
condition (as in Neimark & Fufaev, *Dynamics of Nonholonomic Systems*, AMS 1972, ch. II, and
O'Reilly, "The dynamics of rolling disks and sliding disks", Nonlinear Dyn. 10 (1996) 287-305;
re-derived here to fix this model's signs) give

- steady circular motion (phi, Omega, omega_2 constant):
  I_d Omega^2 sin(phi) cos(phi) - (I_a + m R^2) Omega omega_2 cos(phi) = m g R sin(phi),
  with the ground's force (m Omega R omega_2 towards the centre of the turn, m g up);
- about upright straight rolling at spin omega_0, the lean obeys
  (I_d + m R^2) phi'' + [(I_a + m R^2) I_a omega_0^2 / I_d - m g R] phi = 0, so it is stable for
  omega_0^2 > m g R I_d / (I_a (I_a + m R^2)) = g / (3 R) for the thin disk (v^2 > g R / 3).

The tool's side never uses these formulas: the steady spin is the root of the reduced lean
acceleration; the stability threshold is the root of the lean stiffness of the linearised
reduced equations (rolling_linear.py, central differences); both are also probed by simulation.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from scipy.optimize import brentq

from conftest import SEED
from wheeled_dyn.constraints.rolling_linear import linearise, state_matrix
from wheeled_dyn.constraints.wheel_contact import wheel_contact_velocities, wheel_heights
from wheeled_dyn.constraints.wheel_reduction import RollingReduction
from wheeled_dyn.models.registry import load_model

#: Identities exact to rounding.
EXACT_TOL = 1e-10
#: Roots found by brentq.
ROOT_XTOL = 1e-13
#: Agreement of tool-derived results with closed forms (relative).
CLOSED_FORM_TOL = 1e-9
#: Central differences for the power identity.
FD_STEP = 1e-6
FD_TOL = 1e-7
#: Simulation: largest relative energy drift, and largest contact height before projection (m).
ENERGY_TOL = 1e-8
DRIFT_TOL = 1e-9
#: A steady motion kept in simulation: largest change of lean (rad) over the run.
STEADY_TOL = 1e-6
#: Lean perturbation (rad) and the lean beyond which the disk counts as falling.
PERTURBATION = 0.01
FALLEN = 0.2


def _coin():
    wm = load_model("rolling_coin")
    red = RollingReduction(wm, ("psi", "phi", "theta"), ("z",))
    inertia = wm.model.inertias[wm.joint_id_of_link("coin")]
    m, R, g = inertia.mass, wm.geometry["R"], -wm.model.gravity.linear[2]
    return wm, red, m, R, g, float(inertia.inertia[1, 1]), float(inertia.inertia[0, 0])


def _config(red, phi):
    q = np.zeros(red.wm.nv)
    q[4] = phi
    return red.on_ground(q)


@pytest.mark.parametrize("phi, omega", [(0.3, -2.0), (-0.5, 3.0), (0.1, -6.0)])
def test_steady_circular_motion(phi, omega):
    wm, red, m, R, g, Ia, Id = _coin()
    q = _config(red, phi)
    spin = brentq(lambda th: red.acceleration(q, np.array([omega, 0.0, th]))[1], -500, 500,
                  xtol=ROOT_XTOL)
    nu = np.array([omega, 0.0, spin])
    assert np.abs(red.acceleration(q, nu)).max() < EXACT_TOL
    w2 = spin + omega * np.sin(phi)
    closed = ((Id * omega ** 2 * np.sin(phi) * np.cos(phi) - m * g * R * np.sin(phi))
              / ((Ia + m * R ** 2) * omega * np.cos(phi)))
    assert abs(w2 - closed) < CLOSED_FORM_TOL * abs(closed)
    lam, _ = red.multipliers(q, nu)
    lateral = np.array([-np.sin(q[3]), np.cos(q[3]), 0.0])
    assert abs(lam @ lateral - m * omega * R * w2) < CLOSED_FORM_TOL * m * g
    assert abs(lam[2] - m * g) < CLOSED_FORM_TOL * m * g
    traj = red.simulate(q, nu, 1.0, rate=50)
    assert np.abs(traj.q[:, 4] - phi).max() < STEADY_TOL
    # the centre runs on a circle of radius R omega_2 / Omega
    centre = traj.q[:, :2]
    radius = R * w2 / omega
    mid = centre[0] + radius * np.array([-np.sin(q[3]), np.cos(q[3])])
    assert np.abs(np.linalg.norm(centre - mid, axis=1) - abs(radius)).max() < STEADY_TOL * R


def _lean_stiffness(red, spin):
    r"""k with eigenvalues 0, 0, +-sqrt(-k) of the linearised upright rolling: -tr(A^2)/2."""
    lin = linearise(red, np.zeros(red.wm.nv), ("phi",), np.array([0.0, 0.0, spin]))
    A = state_matrix(lin, (1,))
    return float(-np.trace(A @ A) / 2), A


def test_upright_rolling_stability_threshold():
    wm, red, m, R, g, Ia, Id = _coin()
    for spin in (2.0, 5.0, 9.0):
        k, A = _lean_stiffness(red, spin)
        closed = ((Ia + m * R ** 2) * Ia * spin ** 2 / Id - m * g * R) / (Id + m * R ** 2)
        assert abs(k - closed) < CLOSED_FORM_TOL * max(abs(closed), m * g * R / Id)
    critical = brentq(lambda s: _lean_stiffness(red, s)[0], 0.5, 20.0, xtol=ROOT_XTOL)
    assert abs(critical - np.sqrt(g / (3 * R))) < CLOSED_FORM_TOL * critical
    assert abs(critical ** 2 - m * g * R * Id / (Ia * (Ia + m * R ** 2))) < (
        CLOSED_FORM_TOL * critical ** 2)
    # probed by simulation on both sides: a small lean stays small above, grows below
    for factor, falls in ((1.6, False), (0.5, True)):
        q = _config(red, PERTURBATION)
        traj = red.simulate(q, np.array([0.0, 0.0, factor * critical]), 3.0, rate=20)
        assert bool(np.abs(traj.q[:, 4]).max() > FALLEN) == falls, factor


def test_identities_and_energy():
    wm, red, m, R, g, Ia, Id = _coin()
    rng = np.random.default_rng(SEED)
    for _ in range(3):
        q = _config(red, rng.uniform(-0.6, 0.6))
        q[[0, 1, 3, 5]] = rng.uniform(-1, 1, 4)
        nu = rng.normal(size=3) * [1.0, 1.0, 6.0]
        t = red.terms(q, nu)
        v = red.velocity_matrix(q) @ nu
        assert np.abs(wheel_contact_velocities(wm, q, v)).max() < EXACT_TOL
        Ap = red.terms(pin.integrate(wm.model, q, FD_STEP * v), nu).A
        Am = red.terms(pin.integrate(wm.model, q, -FD_STEP * v), nu).A
        half_dA = 0.5 * nu @ ((Ap - Am) / (2 * FD_STEP)) @ nu
        assert abs(nu @ t.h - half_dA) < FD_TOL * max(1.0, abs(half_dA))
        assert np.all(np.linalg.eigvalsh(t.A) > 0)
    q = _config(red, 0.2)
    traj = red.simulate(q, np.array([1.0, 0.5, 8.0]), 2.0, rate=50)
    assert traj.relative_energy_drift() < ENERGY_TOL
    assert traj.drift < DRIFT_TOL
    assert np.abs([wheel_heights(wm, x)[0] for x in traj.q]).max() < EXACT_TOL
