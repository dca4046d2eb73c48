"""transform(): A_nu = S^T A S, C_nu = S^T C S + S^T A Sdot, Q_nu = S^T Q, B_nu = S^T B against
Pinocchio's matrices transformed numerically; rolling reduction of a WIP-like model; the power
identity; substitution to document coordinates; errors."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
import sympy as sp
from test_symbolic_model import SEED, arm3, assert_close, pinocchio_terms, wip_like

from wheeled_dyn.errors import ModelError
from wheeled_dyn.symbolic import (
    is_zero, lambdify_terms, parameter_vector, symbolic_model, time_derivative, transform)

N_STATES = 4
#: Wheel radius and track width used to evaluate the rolling reduction.
R_VALUE, L_VALUE = 0.1, 0.5


@pytest.fixture(scope="module")
def wip():
    model = wip_like(np.random.default_rng(SEED + 10))
    return model, symbolic_model(model)


def test_constant_invertible_S_matches_numeric_transform(wip):
    """A constant invertible S of the kind documents use (a rotated planar frame, pitch
    measured from the vertical with a sign, mean and differential wheel angles) transforms
    exactly like Pinocchio's numbers (C_nu = S^T C S, Sdot = 0)."""
    model, sym = wip
    rng = np.random.default_rng(SEED + 11)
    half = sp.Rational(1, 2)
    S = sp.Matrix([[sp.Rational(3, 5), -sp.Rational(4, 5), 0, 0, 0, 0],
                   [sp.Rational(4, 5), sp.Rational(3, 5), 0, 0, 0, 0],
                   [0, 0, 1, 0, 0, 0],
                   [0, 0, 0, -1, 0, 0],
                   [0, 0, 0, 1, 1, half],
                   [0, 0, 0, 1, 1, -half]])
    Sn = np.array(S, dtype=float)
    assert abs(np.linalg.det(Sn)) > 0.5
    nu = sp.symbols("n1:7")
    B = sp.zeros(6, 2)
    B[4, 0] = B[5, 1] = 1
    red = transform(sym, S, sp.zeros(6, 6), nu, B=B)
    f = lambdify_terms(red)
    p = parameter_vector(red, model)
    for s in range(N_STATES):
        q = rng.uniform(-np.pi, np.pi, 6)
        n = rng.normal(size=6)
        want = pinocchio_terms(model, q, Sn @ n)
        ctx = f"at state {s}"
        assert_close("A_nu", f.A(q, n, p), Sn.T @ want["A"] @ Sn, ctx)
        assert_close("C_nu", f.C(q, n, p), Sn.T @ want["C"] @ Sn, ctx)
        assert_close("Q_nu", f.Q(q, n, p), Sn.T @ want["Q"], ctx)
        assert_close("h_nu", f.h(q, n, p), Sn.T @ want["h"], ctx)
        assert_close("B_nu", f.B(q, n, p), Sn.T @ np.array(B, dtype=float), ctx)


def test_transform_of_a_model_with_float_geometry():
    """Random placements (float coefficients): a constant S on a 3-link arm."""
    rng = np.random.default_rng(SEED + 13)
    model = arm3(rng)
    sym = symbolic_model(model)
    S = sp.Matrix([[1, 0], [1, 1], [0, -1]])
    Sn = np.array(S, dtype=float)
    red = transform(sym, S, sp.zeros(3, 2), sp.symbols("a b"), simplify=False)
    f = lambdify_terms(red, names=["A", "Q", "h"])
    p = parameter_vector(red, model)
    for s in range(N_STATES):
        q = rng.uniform(-np.pi, np.pi, 3)
        n = rng.normal(size=2)
        want = pinocchio_terms(model, q, Sn @ n)
        ctx = f"at state {s}"
        assert_close("A_nu", f.A(q, n, p), Sn.T @ want["A"] @ Sn, ctx)
        assert_close("Q_nu", f.Q(q, n, p), Sn.T @ want["Q"], ctx)
        assert_close("h_nu", f.h(q, n, p), Sn.T @ want["h"], ctx)


def rolling_S(sym):
    r"""Quasi-velocities (v, w, dphi) of a WIP-like model rolling without slip: x' = v cos psi,
    y' = v sin psi, wheel rates relative to the pitching body."""
    x, y, psi, phi, thl, thr = sym.q
    R, L = sp.symbols("R L", positive=True)
    S = sp.Matrix([[sp.cos(psi), 0, 0], [sp.sin(psi), 0, 0], [0, 1, 0], [0, 0, 1],
                   [1 / R, -L / (2 * R), -1], [1 / R, L / (2 * R), -1]])
    return S, (R, L)


def test_rolling_reduction_matches_pinocchio(wip):
    """q-dependent S: h_nu = S^T (rnea(q, S nu, Sdot nu) - g) includes the S^T A Sdot term;
    with theta = -phi as document coordinate (subs)."""
    model, sym = wip
    S, (R, L) = rolling_S(sym)
    Sd = time_derivative(S, sym.q, sym.qd)
    nu = sp.symbols("v w dtheta")
    theta = sp.Symbol("theta")
    phi = sym.q[3]
    B = sp.zeros(6, 2)
    B[4, 0] = B[5, 1] = 1
    red = transform(sym, S, Sd, nu, subs={phi: -theta}, B=B)
    assert red.q == sym.q[:3] + (theta,) + sym.q[4:]
    assert {R, L} <= set(red.parameters)
    assert phi not in set().union(*[M.free_symbols for M in red.terms().values()])
    f = lambdify_terms(red)
    p = parameter_vector(red, model, {"R": R_VALUE, "L": L_VALUE})
    vals = [R_VALUE, L_VALUE]
    Sf = sp.lambdify([sym.q, [R, L]], S)
    Sdf = sp.lambdify([sym.q, sym.qd, [R, L]], Sd)
    rng = np.random.default_rng(SEED + 12)
    for s in range(N_STATES):
        q = rng.uniform(-np.pi, np.pi, 6)
        n = rng.normal(size=3)
        Sn = np.array(Sf(q, vals), dtype=float)
        Sdn = np.array(Sdf(q, Sn @ n, vals), dtype=float)
        d = model.createData()
        M = pin.crba(model, d, q)
        M = np.triu(M) + np.triu(M, 1).T
        g = pin.computeGeneralizedGravity(model, d, q)
        h = pin.rnea(model, d, q, Sn @ n, Sdn @ n) - g
        qdoc = q.copy()
        qdoc[3] = -q[3]
        ctx = f"at state {s}"
        assert_close("A_nu", f.A(qdoc, n, p), Sn.T @ M @ Sn, ctx)
        assert_close("Q_nu", f.Q(qdoc, n, p), Sn.T @ g, ctx)
        assert_close("h_nu", f.h(qdoc, n, p), Sn.T @ h, ctx)
        assert_close("C_nu nu", f.C(qdoc, n, p) @ n, Sn.T @ h, ctx)
        assert_close("B_nu", f.B(qdoc, n, p), Sn.T @ np.array(B, dtype=float), ctx)


def test_power_identity_of_the_reduced_model(wip):
    r"""nu^T h_nu = 1/2 nu^T Adot_nu nu symbolically (ideal rolling constraints do no work),
    with Adot_nu = sum_k dA_nu/dq_k qdot_k and qdot = S nu."""
    _, sym = wip
    S, _ = rolling_S(sym)
    nu = sp.symbols("v w dphi_")
    red = transform(sym, S, time_derivative(S, sym.q, sym.qd), nu)
    qdot = S * sp.Matrix(nu)
    Adot = time_derivative(red.A, sym.q, list(qdot))
    n = sp.Matrix(nu)
    assert is_zero((n.T * red.h)[0] - (n.T * Adot * n)[0] / 2)


def test_identity_S_returns_the_model(wip):
    _, sym = wip
    red = transform(sym, sp.eye(sym.n), sp.zeros(sym.n, sym.n), sym.qd)
    for name in ("A", "Q", "h"):
        diff = red.terms()[name] - sym.terms()[name]
        assert all(is_zero(e) for e in diff), name
    assert all(is_zero(e) for e in red.C - sym.C())


def test_without_simplify_same_values(wip):
    model, sym = wip
    S, (R, L) = rolling_S(sym)
    Sd = time_derivative(S, sym.q, sym.qd)
    nu = sp.symbols("v w dphi_")
    a = transform(sym, S, Sd, nu, simplify=True)
    b = transform(sym, S, Sd, nu, simplify=False)
    for name in ("A", "C", "Q", "h"):
        assert all(is_zero(e) for e in a.terms()[name] - b.terms()[name]), name


def test_same_name_sign_flip(wip):
    """subs {phi: -phi} (a document measuring the pitch the other way, same name) is applied
    simultaneously: Q_phi changes sign, A_phi,phi does not."""
    _, sym = wip
    phi = sym.q[3]
    red = transform(sym, sp.eye(6), sp.zeros(6, 6), sym.qd, subs={phi: -phi})
    assert red.q == sym.q
    assert is_zero(red.Q[3] - sym.Q[3].xreplace({phi: -phi}))
    assert is_zero(red.A[3, 3] - sym.A[3, 3])
    assert is_zero(red.A[0, 3] - sym.A[0, 3].xreplace({phi: -phi}))


def test_shape_errors(wip):
    _, sym = wip
    nu = sp.symbols("a b")
    with pytest.raises(ModelError):
        transform(sym, sp.zeros(6, 3), sp.zeros(6, 3), nu)
    with pytest.raises(ModelError):
        transform(sym, sp.zeros(6, 2), sp.zeros(5, 2), nu)
    with pytest.raises(ModelError):
        transform(sym, sp.zeros(6, 2), sp.zeros(6, 2), nu, B=sp.zeros(4, 1))
