"""The closed-form simulation (simulate/fast.py) against the Pinocchio-backed one and the
numeric reduction; energy conservation over 10 s."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import SEED
from wheeled_dyn import (CoordinateMap, builtin_coordinate_set, load_model,
                         random_wip_parameters, simulate)
from wheeled_dyn.errors import OptionalDependencyError, StateError
from wheeled_dyn.simulate.fast import compile_rhs, fast_model, simulate_fast

#: Agreement of the compiled right-hand side with the numeric reduction (relative).
RHS_TOL = 1e-9
#: Agreement of the two trajectories (absolute, positions in m and rad, velocities in m/s,
#: rad/s) over TRAJECTORY_SECONDS; both integrate to 1e-9..1e-10 relative tolerance.
TRAJECTORY_TOL = 1e-6
TRAJECTORY_SECONDS = 1.5
#: Largest relative energy drift of a zero-input simulation over ENERGY_SECONDS.
ENERGY_DRIFT_TOL = 1e-6
ENERGY_SECONDS = 10.0
N_STATES = 5


def _tilted(wm, phi=0.3):
    q0 = np.zeros(wm.nv)
    q0[wm.index("phi")] = phi
    return q0


def _wip(seed=SEED):
    return load_model("wip", random_wip_parameters(np.random.default_rng(seed)))


@pytest.mark.parametrize("coords", ["seed001", "wheels"])
def test_rhs_equals_the_numeric_reduction(coords):
    """q' = S nu and nu' = A^-1 (B u - h - Q) at random full configurations, velocities and
    inputs, from the compiled closed forms and from CoordinateMap."""
    rng = np.random.default_rng(SEED)
    wm = _wip(SEED + 1)
    cs = builtin_coordinate_set(wm, coords)
    fm = fast_model(wm, cs)
    cmap = CoordinateMap(wm, cs)
    for s in range(N_STATES):
        q = rng.uniform(-np.pi, np.pi, wm.nv)
        nu = rng.normal(size=cmap.n)
        u = rng.normal(size=2)
        terms, S, v = cmap.reduce_at(q, nu)
        want = np.concatenate([v, np.linalg.solve(terms.A, terms.B @ u - terms.h - terms.Q)])
        got = np.array(fm.rhs([*q, *nu], list(u)))
        err = np.abs(got - want).max() / max(1.0, np.abs(want).max())
        assert err < RHS_TOL, f"state {s}: {err:.2e}\n{got}\n{want}"


@pytest.mark.parametrize("u", [None, "torques"])
def test_fast_and_pinocchio_trajectories_agree(u):
    wm = _wip(SEED + 2)
    cs = builtin_coordinate_set(wm, "seed001")
    q0, nu0 = _tilted(wm), np.array([0.4, 0.8, -0.2])
    control = None if u is None else (lambda t, q, nu: np.array([0.5 * np.sin(t), -0.3]))
    slow = simulate(CoordinateMap(wm, cs), q0, nu0, TRAJECTORY_SECONDS, rate=200.0, u=control)
    fast = simulate_fast(wm, cs, q0, nu0, TRAJECTORY_SECONDS, rate=200.0, u=control)
    assert np.array_equal(slow.t, fast.t)
    dq = np.abs(slow.q - fast.q).max()
    dnu = np.abs(slow.nu - fast.nu).max()
    assert dq < TRAJECTORY_TOL and dnu < TRAJECTORY_TOL, (dq, dnu)
    assert np.abs(slow.u - fast.u).max() == 0.0
    assert fast.velocities == cs.velocities and fast.coordinate_names == wm.coordinate_names
    if u is None:
        scale = abs(slow.energy[0])
        assert np.abs(slow.energy - fast.energy).max() < TRAJECTORY_TOL * scale


def test_energy_drift_over_ten_seconds():
    """A random WIP falling from a tilt while turning, zero input: the rolling constraints do
    no work, the energy stays constant."""
    wm = _wip(SEED + 3)
    cs = builtin_coordinate_set(wm, "seed001")
    traj = simulate_fast(wm, cs, _tilted(wm, 0.3), np.array([0.2, 0.5, 0.0]), ENERGY_SECONDS)
    assert len(traj.t) == int(ENERGY_SECONDS * 1000) + 1
    assert np.ptp(traj.q[:, wm.index("phi")]) > 1.0, "the body did not fall"
    drift = traj.relative_energy_drift()
    assert drift < ENERGY_DRIFT_TOL, drift


def test_tiago_base_rolls_like_pinocchio():
    try:
        wm = load_model("tiago_base")
    except OptionalDependencyError as exc:
        pytest.skip(str(exc))
    cs = builtin_coordinate_set(wm, "heading")
    q0, nu0 = np.zeros(wm.nv), np.array([0.3, 0.7])
    torque = lambda t, q, nu: np.array([0.2, 0.1])  # noqa: E731
    slow = simulate(CoordinateMap(wm, cs), q0, nu0, 1.0, rate=100.0, u=torque)
    fast = simulate_fast(wm, cs, q0, nu0, 1.0, rate=100.0, u=torque)
    assert np.abs(slow.q - fast.q).max() < TRAJECTORY_TOL
    assert np.abs(slow.nu - fast.nu).max() < TRAJECTORY_TOL


def test_compiled_ldlt_solves_a_dense_system():
    """The unrolled LDL^T of compile_rhs on a 4x4 SPD system with no zero entries."""
    import sympy as sp
    rng = np.random.default_rng(SEED + 4)
    X = rng.normal(size=(4, 4))
    A = X @ X.T + 4 * np.eye(4)
    b = rng.normal(size=4)
    nu = sp.symbols("n0:4")
    fn = compile_rhs(sp.zeros(0, 4), sp.Matrix(A), sp.Matrix(b), (), nu)
    assert np.allclose(fn([0.0] * 4, []), np.linalg.solve(A, b), rtol=1e-12, atol=1e-12)


def test_errors():
    wm = load_model("wip")
    with pytest.raises(StateError):
        simulate_fast(wm, builtin_coordinate_set(wm, "full"), np.zeros(6), np.zeros(6), 1.0)
    cs = builtin_coordinate_set(wm, "seed001")
    with pytest.raises(StateError):
        simulate_fast(wm, cs, np.zeros(5), np.zeros(3), 1.0)
    with pytest.raises(StateError):
        simulate_fast(wm, cs, np.full(6, np.nan), np.zeros(3), 1.0)
