r"""The Whipple bicycle at the benchmark parameters (Meijaard, Papadopoulos, Ruina, Schwab 2007,
Proc. R. Soc. A 463:1955-1982), from the tool's own dynamics.

The model (urdf/bicycle.urdf, Table 1) is nine joints with two knife-edge wheel contacts
(six rows). Its reduced equations in the roll, steer and rear-wheel rates are linearised about
upright straight running by central differences with one Richardson step
(constraints/rolling_linear.py); the linear model's roll and steer block gives M, C1, K0, K2
(two linearisations: at rest and at 1 m/s, exact because the reduced forces are quadratic in
the velocities). These are compared with the published matrices of the transcribed document
(data/linearised/meijaard2007_benchmark.toml); the eigenvalues of a fresh linearisation at each
speed of Table 2 with the table; the weave and capsize speeds, found by root finding on the
spectral abscissa of fresh linearisations, with the published speeds. The nonlinear model is
simulated on both sides of the weave speed, and its reduction's identities are checked.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from scipy.optimize import brentq

from conftest import SEED
from wheeled_dyn.derivations.linear_document import load_linear_document
from wheeled_dyn.constraints.rolling_linear import linearise, speed_form
from wheeled_dyn.constraints.wheel_contact import wheel_contact_velocities, wheel_heights
from wheeled_dyn.constraints.wheel_reduction import RollingReduction
from wheeled_dyn.errors import InputFileError
from wheeled_dyn.models.registry import load_model

#: Agreement with the published matrices, relative to each matrix's largest entry (the
#: published digits are 14 decimals; the linearisation's error is ~1e-14 relative).
MATRIX_TOL = 1e-12
#: Agreement of each published eigenvalue (14 decimals) with the nearest computed one.
EIGEN_TOL = 1e-11
#: Weave and capsize speeds (m/s): root finding to 1e-14, linearisation error ~1e-13.
SPEED_TOL = 1e-11
#: Identities exact to rounding; central differences.
EXACT_TOL = 1e-10
FD_STEP = 1e-6
FD_TOL = 1e-7
#: Simulation: relative energy drift, contact height before projection (m).
ENERGY_TOL = 1e-8
DRIFT_TOL = 1e-9
#: Roll-rate perturbation (rad/s) and duration (s) of the weave probes.
KICK = 0.02
PROBE_TIME = 2.0

REAR_RADIUS = 0.3


def _bicycle():
    wm = load_model("bicycle")
    red = RollingReduction(wm, ("roll", "steer", "rear_wheel"), ("z", "pitch"))
    q0 = red.on_ground(np.zeros(wm.nv))
    return wm, red, q0


def _speed_nu(speed):
    return np.array([0.0, 0.0, speed / REAR_RADIUS])


def _eigenvalues(red, q0, speed):
    lin = linearise(red, q0, ("roll", "steer"), _speed_nu(speed))
    M, D, K = lin.M[:2, :2], lin.D[:2, :2], lin.K[:2]
    A = np.block([[np.zeros((2, 2)), np.eye(2)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, D)]])
    return np.linalg.eigvals(A)


def test_upright_configuration():
    wm, red, q0 = _bicycle()
    # the rear hub at rR above the ground, the rear frame level: both contacts touch
    assert abs(q0[wm.index("z")] - REAR_RADIUS) < EXACT_TOL
    assert abs(q0[wm.index("pitch")]) < EXACT_TOL
    assert np.abs(wheel_heights(wm, q0)).max() < EXACT_TOL


def test_matrices_against_the_published_ones():
    doc = load_linear_document()
    assert doc.model == "bicycle" and doc.positions == ("roll", "steer")
    wm, red, q0 = _bicycle()
    form, rest, moving = speed_form(red, q0, doc.positions, _speed_nu(1.0), (0, 1), doc.form.g)
    for name in ("M", "C1", "K0", "K2"):
        ours, printed = getattr(form, name), getattr(doc.form, name)
        assert np.abs(ours - printed).max() < MATRIX_TOL * np.abs(printed).max(), name
    # the rear-wheel rate decouples from roll and steer at first order (lateral symmetry)
    scale = np.abs(rest.M).max()
    for block in (rest.M[2, :2], rest.M[:2, 2], moving.D[2, :2], moving.D[:2, 2], rest.K[2],
                  moving.K[2]):
        assert np.abs(block).max() < MATRIX_TOL * scale
    # the roll and steer torques enter as the generalized forces of phi and delta
    B = red.terms(q0, _speed_nu(4.0)).B
    assert np.abs(B[:2] - np.eye(2)).max() < EXACT_TOL and np.abs(B[2]).max() < EXACT_TOL
    # and the steady straight running is an equilibrium
    assert np.abs(moving.residual).max() < EXACT_TOL


def test_eigenvalues_against_table_2():
    doc = load_linear_document()
    wm, red, q0 = _bicycle()
    assert sorted(doc.eigenvalues) == [float(v) for v in range(11)]
    for speed, printed in doc.eigenvalues.items():
        ours = _eigenvalues(red, q0, speed)
        for value in printed:
            assert np.abs(ours - value).min() < EIGEN_TOL, (speed, value)
        # and the other way round: every computed eigenvalue is printed
        for value in ours:
            assert np.abs(printed - value).min() < EIGEN_TOL, (speed, value)


def test_weave_and_capsize_speeds():
    doc = load_linear_document()
    wm, red, q0 = _bicycle()

    def abscissa(speed):
        return float(_eigenvalues(red, q0, speed).real.max())

    weave = brentq(abscissa, 4.0, 5.0, xtol=1e-14)
    capsize = brentq(abscissa, 5.5, 7.0, xtol=1e-14)
    assert abs(weave - doc.claims["weave_speed"]) < SPEED_TOL
    assert abs(capsize - doc.claims["capsize_speed"]) < SPEED_TOL
    # the sweep of the speed form agrees with fresh linearisations
    form, _, _ = speed_form(red, q0, doc.positions, _speed_nu(1.0), (0, 1), doc.form.g)
    speeds = np.linspace(0.0, 10.0, 100)
    sweep = form.eigenvalues(speeds)
    stable = sweep.real.max(axis=1) < 0
    assert np.all(stable == ((speeds > weave) & (speeds < capsize)))
    for i in (0, 37, 99):
        fresh = _eigenvalues(red, q0, speeds[i])
        assert max(np.abs(fresh - s).min() for s in sweep[i]) < EIGEN_TOL


@pytest.mark.parametrize("speed, grows", [(5.0, False), (3.0, True)])
def test_nonlinear_simulation_across_the_weave_speed(speed, grows):
    wm, red, q0 = _bicycle()
    nu0 = _speed_nu(speed) + np.array([KICK, 0.0, 0.0])
    traj = red.simulate(q0, nu0, PROBE_TIME, rate=10)
    roll = np.abs(traj.q[:, wm.index("roll")])
    late = roll[len(roll) // 2:].max()
    early = roll[: len(roll) // 2].max()
    assert bool(late > early) == grows
    assert traj.relative_energy_drift() < ENERGY_TOL
    assert traj.drift < DRIFT_TOL


def test_reduction_identities():
    wm, red, q0 = _bicycle()
    rng = np.random.default_rng(SEED)
    for _ in range(3):
        q = q0.copy()
        q[[0, 1, 3, 6, 8]] = rng.uniform(-1, 1, 5)
        q[wm.index("roll")] = rng.uniform(-0.4, 0.4)
        q[wm.index("steer")] = rng.uniform(-0.6, 0.6)
        q = red.on_ground(q)
        nu = rng.normal(size=3) * [0.5, 0.5, 15.0]
        v = red.velocity_matrix(q) @ nu
        assert np.abs(wheel_contact_velocities(wm, q, v)).max() < EXACT_TOL
        t = red.terms(q, nu)
        Ap = red.terms(pin.integrate(wm.model, q, FD_STEP * v), nu).A
        Am = red.terms(pin.integrate(wm.model, q, -FD_STEP * v), nu).A
        half_dA = 0.5 * nu @ ((Ap - Am) / (2 * FD_STEP)) @ nu
        assert abs(nu @ t.h - half_dA) < FD_TOL * max(1.0, abs(half_dA))
        lam, vdot = red.multipliers(q, nu)
        nudot = red.acceleration(q, nu)
        assert np.abs(vdot[red.index] - nudot).max() < EXACT_TOL * max(1.0, np.abs(nudot).max())
        # the ground carries the weight on average (vertical forces sum to m g + dynamic part)
        assert lam[2] > 0 and lam[5] > 0


def test_bad_document_is_reported(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('model = "bicycle"\n[coordinates]\npositions = ["roll", "steer"]\n'
                   '[form]\nM = [[1.0, 0.0], [0.0, 1.0]]\n')
    with pytest.raises(InputFileError, match="C1"):
        load_linear_document(bad)
