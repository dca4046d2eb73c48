"""Identities of the full model's terms (Pinocchio) on random states and parameter sets."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from conftest import N_STATES, SEED, random_wip_models
from wheeled_dyn import christoffel_tensor, full_terms, load_model
from wheeled_dyn.dynamics import h_coefficients

#: Absolute tolerance of identities that hold to rounding.
EXACT_TOL = 1e-9
#: Step of the central finite differences.
FD_STEP = 1e-6
#: Tolerance of a central-difference derivative (relative to the entries' scale).
FD_TOL = 1e-6


def _states(wm, rng):
    for _ in range(N_STATES):
        yield rng.uniform(-np.pi, np.pi, wm.nv), rng.normal(size=wm.nv)


def _models():
    return random_wip_models() + [load_model("tiago")]


@pytest.mark.parametrize("wm", _models(), ids=lambda m: m.name)
def test_mass_matrix_symmetric_positive_definite(wm):
    rng = np.random.default_rng(SEED)
    for q, v in _states(wm, rng):
        A = full_terms(wm, q, v).A
        assert np.allclose(A, A.T, atol=EXACT_TOL)
        assert np.linalg.eigvalsh(A).min() > 0, f"A not positive definite at q={q}"


@pytest.mark.parametrize("wm", _models(), ids=lambda m: m.name)
def test_coriolis_vector_is_rnea_minus_gravity(wm):
    rng = np.random.default_rng(SEED)
    data = wm.model.createData()
    for q, v in _states(wm, rng):
        t = full_terms(wm, q, v)
        rnea = pin.rnea(wm.model, data, q, v, np.zeros(wm.nv))
        assert np.allclose(t.C @ v, rnea - t.Q, atol=EXACT_TOL * (1 + np.abs(rnea).max()))


@pytest.mark.parametrize("wm", _models()[:2] + _models()[-1:], ids=lambda m: m.name)
def test_christoffel_symmetric_and_equal_to_pinocchio_coriolis(wm):
    rng = np.random.default_rng(SEED)
    for q, v in _states(wm, rng):
        c = christoffel_tensor(wm.model, q)
        assert np.allclose(c, c.transpose(0, 2, 1), atol=EXACT_TOL)
        C = full_terms(wm, q, v).C
        assert np.allclose(np.einsum("ijk,k->ij", c, v), C, atol=EXACT_TOL * (1 + np.abs(C).max()))


@pytest.mark.parametrize("wm", random_wip_models(2), ids=lambda m: m.name)
def test_christoffel_matches_finite_differences_of_A(wm):
    rng = np.random.default_rng(SEED)
    data = wm.model.createData()
    q = rng.uniform(-1, 1, wm.nv)
    c = christoffel_tensor(wm.model, q)
    D = np.empty((wm.nv,) * 3)
    A = lambda x: full_terms(wm, x, np.zeros(wm.nv), data).A
    for k in range(wm.nv):
        dq = np.zeros(wm.nv)
        dq[k] = FD_STEP
        D[:, :, k] = (A(q + dq) - A(q - dq)) / (2 * FD_STEP)
    fd = 0.5 * (D + D.transpose(0, 2, 1) - D.transpose(2, 0, 1))
    assert np.allclose(c, fd, atol=FD_TOL * (1 + np.abs(c).max()))


@pytest.mark.parametrize("wm", _models(), ids=lambda m: m.name)
def test_Adot_minus_2C_is_skew(wm):
    rng = np.random.default_rng(SEED)
    data = wm.model.createData()
    for q, v in _states(wm, rng):
        plus = pin.integrate(wm.model, q, v * FD_STEP)
        minus = pin.integrate(wm.model, q, -v * FD_STEP)
        A = lambda x: full_terms(wm, x, v, data).A
        Adot = (A(plus) - A(minus)) / (2 * FD_STEP)
        N = Adot - 2 * full_terms(wm, q, v).C
        assert np.allclose(N, -N.T, atol=FD_TOL * (1 + np.abs(Adot).max()))


def test_h_coefficients_reproduce_h(rng):
    wm = random_wip_models(1)[0]
    q = rng.uniform(-1, 1, wm.nv)
    H = h_coefficients(lambda e: full_terms(wm, q, e).C, wm.nv)
    assert np.allclose(H, H.transpose(0, 2, 1))
    v = rng.normal(size=wm.nv)
    assert np.allclose(np.einsum("ijk,j,k->i", H, v, v), full_terms(wm, q, v).h, atol=EXACT_TOL)
