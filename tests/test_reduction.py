"""The equations in document coordinates: rolling reduction, projections, multipliers."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from conftest import N_STATES, SEED, random_wip_models
from wheeled_dyn import (CoordinateMap, WipParameters, builtin_coordinate_set, load_model,
                         multipliers, simulate)
from wheeled_dyn.constraints import contact_velocities

#: Tolerance of identities exact to rounding.
EXACT_TOL = 1e-9
#: Step and tolerance of central finite differences.
FD_STEP = 1e-6
FD_TOL = 1e-6
#: Largest relative energy drift of a zero-input simulation (issue: 1e-6 over 5 s).
ENERGY_DRIFT_TOL = 1e-6

QUASI_SETS = [("wip", "seed001"), ("wip", "wheels"), ("tiago", "heading"), ("tiago", "wheels")]


def _maps(model_name, coords):
    models = random_wip_models(2) if model_name == "wip" else [load_model(model_name)]
    return [CoordinateMap(wm, builtin_coordinate_set(wm, coords)) for wm in models]


def _random_state(cmap, rng):
    q = rng.uniform(-np.pi, np.pi, cmap.wm.nv)   # a full model configuration
    return q, rng.normal(size=cmap.n)


@pytest.mark.parametrize("model_name,coords", QUASI_SETS)
def test_contact_points_do_not_move(model_name, coords):
    rng = np.random.default_rng(SEED)
    for cmap in _maps(model_name, coords):
        for _ in range(N_STATES):
            q, nu = _random_state(cmap, rng)
            _, S, v = cmap.reduce_at(q, nu)
            vc = contact_velocities(cmap.wm, q, v)
            assert np.abs(vc).max() < EXACT_TOL * (1 + np.abs(v).max()), vc


@pytest.mark.parametrize("model_name,coords", QUASI_SETS)
def test_reduced_power_identity(model_name, coords):
    r"""nu^T h_nu = 1/2 nu^T (dA_nu/dt) nu, dA_nu/dt by central differences along the motion."""
    rng = np.random.default_rng(SEED)
    for cmap in _maps(model_name, coords):
        for _ in range(N_STATES):
            q, nu = _random_state(cmap, rng)
            terms, S, v = cmap.reduce_at(q, nu)
            plus = pin.integrate(cmap.wm.model, q, v * FD_STEP)
            minus = pin.integrate(cmap.wm.model, q, -v * FD_STEP)
            Adot = (cmap.terms_at(plus, nu).A - cmap.terms_at(minus, nu).A) / (2 * FD_STEP)
            lhs, rhs = nu @ terms.h, 0.5 * nu @ Adot @ nu
            assert abs(lhs - rhs) < FD_TOL * (1 + abs(lhs) + np.abs(Adot).max()), (lhs, rhs)


@pytest.mark.parametrize("model_name,coords", QUASI_SETS[:2])
def test_Sdot_is_the_derivative_of_S(model_name, coords):
    rng = np.random.default_rng(SEED)
    cmap = _maps(model_name, coords)[0]
    q, nu = _random_state(cmap, rng)
    _, S, v = cmap.reduce_at(q, nu)
    plus = pin.integrate(cmap.wm.model, q, v * FD_STEP)
    minus = pin.integrate(cmap.wm.model, q, -v * FD_STEP)
    Sdot_fd = (cmap.velocity_matrix(plus) - cmap.velocity_matrix(minus)) / (2 * FD_STEP)
    # C_nu - S^T C S = S^T A Sdot  =>  compare the Sdot implied by the reduction
    from wheeled_dyn import full_terms
    full = full_terms(cmap.wm, q, v)
    implied = cmap.terms_at(q, nu).C - S.T @ full.C @ S
    assert np.allclose(implied, S.T @ full.A @ Sdot_fd, atol=FD_TOL * (1 + np.abs(implied).max()))


def test_wip_closed_form_in_seed001_coordinates(rng):
    r"""The WIP in (dx, dpsi, dphi), derived by hand for a body symmetric about its mid-plane
    (no products of inertia, d_x = d_z = 0) with motor armature I_a, rolling on flat ground:

    A11 = m_S + 2 m_C + 2 (Iw3 + I_a)/R^2     A13 = -m_S d cos(phi) + 2 I_a / R
    A22 = I2 cos^2 + (I1 + m_S d^2) sin^2 + 2 Iw2 + 2 L^2 (m_C + (Iw3 + I_a)/R^2)
    A33 = I3 + m_S d^2 + 2 I_a,   A12 = A23 = 0,   Q3 = -m_S g d sin(phi)
    h1 = m_S d sin(phi) (dphi^2 + dpsi^2)
    h2 = 2 (I1 + m_S d^2 - I2) sin cos dpsi dphi - m_S d sin(phi) dx dpsi
    h3 = -(I1 + m_S d^2 - I2) sin cos dpsi^2
    B = [[-1/R, -1/R], [L/R, -L/R], [-1, -1]]
    """
    p = WipParameters(m_S=55.0, m_C=4.0, R=0.3, L=0.4, d=0.5, g=9.7, I1=7.0, I2=2.0, I3=6.0,
                      Iw2=0.1, Iw3=0.17, I_a=0.05)
    cmap = CoordinateMap(load_model("wip", p), builtin_coordinate_set(load_model("wip"), "seed001"))
    for _ in range(N_STATES):
        x, psi, phi = rng.uniform(-3, 3, 3)
        dx, dpsi, dphi = nu = rng.normal(size=3)
        t = cmap.terms(np.array([x, psi, phi]), nu)
        s, c = np.sin(phi), np.cos(phi)
        K = p.I1 + p.m_S * p.d**2 - p.I2
        A = np.array([
            [p.m_S + 2 * p.m_C + 2 * (p.Iw3 + p.I_a) / p.R**2, 0, -p.m_S * p.d * c + 2 * p.I_a / p.R],
            [0, p.I2 * c**2 + (p.I1 + p.m_S * p.d**2) * s**2 + 2 * p.Iw2
             + 2 * p.L**2 * (p.m_C + (p.Iw3 + p.I_a) / p.R**2), 0],
            [-p.m_S * p.d * c + 2 * p.I_a / p.R, 0, p.I3 + p.m_S * p.d**2 + 2 * p.I_a]])
        h = np.array([p.m_S * p.d * s * (dphi**2 + dpsi**2),
                      2 * K * s * c * dpsi * dphi - p.m_S * p.d * s * dx * dpsi,
                      -K * s * c * dpsi**2])
        B = np.array([[-1 / p.R, -1 / p.R], [p.L / p.R, -p.L / p.R], [-1, -1]])
        assert np.allclose(t.A, A, atol=EXACT_TOL)
        assert np.allclose(t.h, h, atol=EXACT_TOL)
        assert np.allclose(t.Q, [0, 0, -p.m_S * p.g * p.d * s], atol=EXACT_TOL)
        assert np.allclose(t.B, B, atol=EXACT_TOL)


def test_holonomic_map_gives_christoffel_C_and_constraint_matrix(rng):
    r"""In seed 001 section 5's coordinates (a holonomic map), C equals the Christoffel matrix
    of A_doc(q_doc) by finite differences, and G nu = 0 for rolling motions."""
    wm = random_wip_models(1)[0]
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "absolute_wheels"))
    n = cmap.n
    qd = rng.uniform(-1, 1, n)
    nu = rng.normal(size=n)
    A = lambda x: cmap.terms(x, np.zeros(n)).A
    D = np.empty((n, n, n))
    for k in range(n):
        e = np.zeros(n)
        e[k] = FD_STEP
        D[:, :, k] = (A(qd + e) - A(qd - e)) / (2 * FD_STEP)
    c = 0.5 * (D + D.transpose(0, 2, 1) - D.transpose(2, 0, 1))
    t = cmap.terms(qd, nu)
    assert np.allclose(t.C, np.einsum("ijk,k->ij", c, nu), atol=FD_TOL * (1 + np.abs(t.C).max()))
    # a rolling motion: wheels turn, the axle midpoint moves along the heading
    R, L = wm.geometry["R"], wm.geometry["L"]
    x0, y0, th_l, th_r, phi = qd
    psi = R * (th_r - th_l) / (2 * L)
    dl, dr, dphi = rng.normal(size=3)
    speed = R * (dl + dr) / 2
    rolling = np.array([speed * np.cos(psi), speed * np.sin(psi), dl, dr, dphi])
    G = cmap.terms(qd, rolling).G
    assert np.abs(G @ rolling).max() < EXACT_TOL


def test_multipliers_agree_with_reduced_accelerations(rng):
    wm = random_wip_models(1)[0]
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "seed001"))
    q = rng.uniform(-1, 1, wm.nv)
    nu = rng.normal(size=3)
    u = rng.normal(size=2)
    terms, S, v = cmap.reduce_at(q, nu)
    nudot = np.linalg.solve(terms.A, terms.B @ u - terms.h - terms.Q)
    lam, vdot = multipliers(wm, q, v, u)
    # the reduced acceleration, lifted: vdot = S nudot + Sdot nu
    plus = pin.integrate(wm.model, q, v * FD_STEP)
    minus = pin.integrate(wm.model, q, -v * FD_STEP)
    Sdot = (cmap.velocity_matrix(plus) - cmap.velocity_matrix(minus)) / (2 * FD_STEP)
    assert np.allclose(vdot, S @ nudot + Sdot @ nu, atol=FD_TOL * (1 + np.abs(vdot).max()))
    # Newton: the horizontal ground forces on the wheels accelerate the centre of mass
    data = wm.model.createData()
    pin.centerOfMass(wm.model, data, q, v, vdot)
    mass = sum(inertia.mass for inertia in wm.model.inertias)
    total = lam.reshape(-1, 2).sum(axis=0)
    assert np.allclose(total, mass * data.acom[0][:2], atol=FD_TOL * (1 + np.abs(total).max()))


def test_zero_input_simulation_keeps_energy():
    wm = random_wip_models(1)[0]
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "seed001"))
    q0 = cmap.model_configuration(np.array([0.0, 0.0, 0.3]))
    traj = simulate(cmap, q0, np.array([0.5, 0.8, 0.0]), duration=5.0, rate=200.0)
    assert traj.relative_energy_drift() < ENERGY_DRIFT_TOL
    assert np.ptp(traj.q[:, wm.index("phi")]) > 0.1      # it did move


@pytest.mark.parametrize("coords", ["seed001", "wheels", "absolute_wheels", "full"])
def test_batch_equals_single_state(coords):
    wm = random_wip_models(1)[0]
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, coords))
    rng = np.random.default_rng(SEED)
    q, nu = rng.uniform(-2, 2, (7, cmap.n)), rng.normal(size=(7, cmap.n))
    batch = cmap.terms_batch(q, nu)
    for i in range(len(q)):
        single = cmap.terms(q[i], nu[i])
        for key in ("A", "C", "Q", "B", "h", "G"):
            a, b = getattr(batch, key), getattr(single, key)
            if b is None:
                assert a is None
            else:
                assert np.allclose(a[i], b, atol=EXACT_TOL), key


@pytest.mark.parametrize("model,cset", [*QUASI_SETS, ("wip", "absolute_wheels"),
                                         ("sphere_sphere", "body_rates"),
                                         ("rolling_coin", None)])
def test_dynamics_at_equals_the_reduced_terms(model, cset):
    r"""The simulation's right-hand side (:meth:`CoordinateMap.dynamics_at`: A, h + Q, B from
    ``nonLinearEffects`` and the vector S-dot nu) equals the reduced terms of
    :meth:`CoordinateMap.reduce_at` (the Coriolis matrix and S-dot as matrices)."""
    rng = np.random.default_rng(SEED)
    wm = load_model(model)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, cset))
    holonomic = cmap.cs.kind == "holonomic"
    for _ in range(N_STATES):
        q_doc = rng.uniform(-1.0, 1.0, cmap.n)
        nu = rng.normal(size=cmap.n)
        if holonomic:
            q = cmap.model_configuration(q_doc)
        else:                     # any configuration: both sides are the same algebra
            q = rng.uniform(-1.0, 1.0, wm.model.nq)
            q_doc = None
        terms, S, _ = cmap.reduce_at(q, nu, q_doc)
        A, hQ, B, S2 = cmap.dynamics_at(q, nu, q_doc)
        scale = 1.0 + np.abs(terms.A).max() + np.abs(terms.h).max() + np.abs(terms.Q).max()
        assert np.abs(A - terms.A).max() < EXACT_TOL * scale
        assert np.abs(hQ - terms.h - terms.Q).max() < EXACT_TOL * scale
        assert np.abs(B - terms.B).max(initial=0.0) < EXACT_TOL * scale
        assert np.abs(S - S2).max() < EXACT_TOL


def test_singular_samples_are_drawn_again():
    r"""ZYX angles are singular at pitch = +-pi/2: the body-rate map's condition number grows
    there without bound, and the comparison's samples avoid it (rounding there is amplified
    by the cube of the condition number)."""
    from wheeled_dyn.compare.grid.samples import MAX_CONDITION, random_states, regular_states
    wm = load_model("free_body")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    pitch = wm.index("pitch")
    q = np.zeros((3, cmap.n))
    q[:, pitch] = [0.0, np.pi / 2 - 1e-3, np.pi / 2 - 1e-6]
    cond = cmap.conditioning(q)
    assert cond[0] < 10 and cond[1] > 1e2 and cond[2] > 1e5
    rng = np.random.default_rng(SEED)
    drawn, _ = random_states(cmap.n, 2000, rng)
    drawn[:20, pitch] = np.pi / 2                     # planted singular samples
    regular = regular_states(cmap, drawn, rng)
    assert cmap.conditioning(regular).max() <= MAX_CONDITION
    kept = cmap.conditioning(drawn) <= MAX_CONDITION
    assert np.array_equal(regular[kept], drawn[kept])  # the regular ones are left as drawn


def test_pseudo_inverse_by_normal_equations_or_svd():
    r"""The normal equations' M+ where M has full column rank, the SVD's where it has not: one
    matrix or a stack, the same as NumPy's pinv either way."""
    from wheeled_dyn.constraints.linalg import pseudo_inverse
    rng = np.random.default_rng(SEED)
    full = rng.normal(size=(4, 7, 6))
    deficient = full.copy()
    deficient[:, :, 5] = deficient[:, :, 4]                 # two equal columns: rank 5
    for stack in (full, deficient, np.concatenate([full, deficient])):
        assert np.allclose(pseudo_inverse(stack), np.linalg.pinv(stack), atol=EXACT_TOL)
        for M in stack:
            assert np.allclose(pseudo_inverse(M), np.linalg.pinv(M), atol=EXACT_TOL)


@pytest.mark.parametrize("by_reference", [True, False])
def test_batch_across_blocks_equals_single_state(monkeypatch, by_reference):
    r"""More states than one block of the stacked algebra (:data:`~wheeled_dyn.constraints.
    batch.BLOCK`), the states on both sides of a block's edge against the one-state terms;
    also as with a Pinocchio binding that returns copies of ``data.J`` (read after each
    call instead of through views)."""
    from wheeled_dyn.constraints import batch
    if not by_reference:
        plain = batch._context
        monkeypatch.setattr(batch, "_context",
                            lambda cmap: plain(cmap)._replace(by_reference=False))
    wm = random_wip_models(1)[0]
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "seed001"))
    rng = np.random.default_rng(SEED)
    N = batch.BLOCK + 9
    q, nu = rng.uniform(-2, 2, (N, cmap.n)), rng.normal(size=(N, cmap.n))
    terms = cmap.terms_batch(q, nu)
    for i in (0, batch.BLOCK - 1, batch.BLOCK, N - 1):
        single = cmap.terms(q[i], nu[i])
        for key in ("A", "C", "Q", "B", "h"):
            assert np.allclose(getattr(terms, key)[i], getattr(single, key), atol=EXACT_TOL), \
                (key, i)
