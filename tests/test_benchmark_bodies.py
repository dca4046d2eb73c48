"""Closed-form results of seed 000's benchmark bodies, checked on the true equations.

Each test linearises or simulates the model's own equations (Pinocchio, in the model's or a
built-in coordinate set) and compares with the textbook's closed form: the rod pendulum's
natural frequency (4.4), the rod on a driven flywheel (4.17), spin stability of a free body
(7.1/7.2), gyroscopic precession (7.7). Inertial parameters are drawn at random (seeded) around
the URDFs' where the closed form holds for any of them.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from conftest import SEED
from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model, simulate

#: Step of the central differences of a state derivative.
FD_STEP = 1e-6
#: Relative agreement of a linearisation by central differences with a closed form.
LINEARISATION_TOL = 1e-6
#: Real parts smaller than this (relative to the largest eigenvalue) count as zero.
NEUTRAL_TOL = 1e-6
#: Random parameter sets per closed-form test.
N_SETS = 4
#: Relative agreement of a growth rate measured in a simulation with the linearisation's.
GROWTH_TOL = 0.05
#: The fast-top approximation's error is of order eps = I_perp M g L / (I_s omega_s)^2; the
#: measured mean precession rate must be within this multiple of eps of M g L / (I_s omega_s).
FAST_TOP_FACTOR = 1.0
#: Nutation periods over which the mean precession rate is measured.
NUTATION_PERIODS = 20


def _jacobian(f, x: np.ndarray, step: float = FD_STEP) -> np.ndarray:
    r"""Central differences of ``f`` at ``x`` (columns: directions)."""
    cols = [(f(x + step * e) - f(x - step * e)) / (2 * step) for e in np.eye(len(x))]
    return np.array(cols).T


def _state_derivative(cmap: CoordinateMap):
    r"""f(q_doc, nu) = (nu, A^-1 (-h - Q)) of a holonomic set without inputs."""
    n = cmap.n

    def f(x):
        q_doc, nu = x[:n], x[n:]
        terms, _, _ = cmap.reduce_at(cmap.model_configuration(q_doc), nu, q_doc)
        return np.concatenate([nu, np.linalg.solve(terms.A, -terms.h - terms.Q)])
    return f


def _gravity(wm) -> float:
    return float(-wm.model.gravity.linear[2])


def _set_gravity(model: pin.Model, g: float) -> None:
    model.gravity = pin.Motion(np.array([0.0, 0.0, -g]), np.zeros(3))


# -- 4.4 rod pendulum ---------------------------------------------------------------------
def _rod(m: float, length: float) -> pin.Inertia:
    r"""A uniform slender rod hanging along -z from its end (inertia about its centre)."""
    I = m * length**2 / 12
    return pin.Inertia(m, np.array([0.0, 0.0, -length / 2]), np.diag([I, I, 0.0]))


def test_rod_pendulum_natural_frequency():
    r"""4.4: the linearised true equations at the hanging state have eigenvalues
    :math:`\pm i\sqrt{3g/(2l)}`, for random rods and gravities."""
    rng = np.random.default_rng(SEED)
    base = load_model("rod_pendulum")
    jid = base.joint_id_of_link("rod")
    for k in range(N_SETS):
        m, length, g = rng.uniform(0.2, 5.0), rng.uniform(0.2, 2.0), rng.uniform(5.0, 15.0)
        model = pin.Model(base.model)
        model.inertias[jid] = _rod(m, length)
        _set_gravity(model, g)
        wm = base.with_model(model)
        cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "full"))
        eig = np.linalg.eigvals(_jacobian(_state_derivative(cmap), np.zeros(2)))
        omega_n = np.sqrt(3 * g / (2 * length))
        assert np.abs(eig.real).max() <= NEUTRAL_TOL * omega_n, eig
        assert np.abs(np.abs(eig.imag) - omega_n).max() <= LINEARISATION_TOL * omega_n, \
            (k, eig, omega_n)


def test_rod_pendulum_urdf_numbers():
    r"""The shipped rod (1 m, g = 9.81) swings at sqrt(3 g / 2) rad/s."""
    wm = load_model("rod_pendulum")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "full"))
    eig = np.linalg.eigvals(_jacobian(_state_derivative(cmap), np.zeros(2)))
    assert np.abs(np.abs(eig.imag) - np.sqrt(1.5 * 9.81)).max() < LINEARISATION_TOL * 4


# -- 4.17 rod on a driven flywheel ----------------------------------------------------------
def _driven_theta(cmap: CoordinateMap, omega: float):
    r"""f(theta, theta') of the rod with the flywheel held at phi' = omega (phi'' = 0): the
    theta-row of the true equations, :math:`A_{\theta\theta}\ddot\theta + h_\theta + Q_\theta
    = 0`."""
    wm = cmap.wm
    i_phi, i_th = wm.index("phi"), wm.index("theta")

    def f(x):
        q = np.zeros(2)
        q[i_th] = x[0]
        v = np.zeros(2)
        v[i_phi], v[i_th] = omega, x[1]
        terms, _, _ = cmap.reduce_at(q, v, q)
        return np.array([x[1], -(terms.h[i_th] + terms.Q[i_th]) / terms.A[i_th, i_th]])
    return f


def _flywheel_models(rng):
    base = load_model("flywheel_rod")
    jid = base.joint_id_of_link("rod")
    out = [(base, 0.5)]
    for _ in range(N_SETS - 1):
        m, length, g = rng.uniform(0.2, 3.0), rng.uniform(0.2, 1.5), rng.uniform(5.0, 15.0)
        model = pin.Model(base.model)
        model.inertias[jid] = _rod(m, length)
        _set_gravity(model, g)
        out.append((base.with_model(model), length))
    return out


def test_flywheel_rod_critical_speed():
    r"""4.17: with the flywheel driven at omega, the hanging rod is stable (eigenvalues on the
    imaginary axis) below omega_crit = sqrt(3 g / (2 L)) and unstable above; the boundary
    found by bisection on the linearisation is omega_crit."""
    rng = np.random.default_rng(SEED)
    for wm, length in _flywheel_models(rng):
        cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "full"))
        crit = np.sqrt(3 * _gravity(wm) / (2 * length))

        def growth(omega):
            eig = np.linalg.eigvals(_jacobian(_driven_theta(cmap, omega), np.zeros(2)))
            return eig.real.max()

        assert abs(growth(0.9 * crit)) <= NEUTRAL_TOL * crit
        assert growth(1.1 * crit) > 0.1 * crit
        lo, hi = 0.5 * crit, 1.5 * crit
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if growth(mid) <= NEUTRAL_TOL * crit else (lo, mid)
        assert abs(0.5 * (lo + hi) / crit - 1) < 1e-3, (lo, hi, crit)


def test_flywheel_rod_new_equilibrium():
    r"""4.17 above omega_crit: cos(theta_0) = 3 g / (2 L omega^2) is an equilibrium of the
    true driven equations, and a stable one."""
    rng = np.random.default_rng(SEED + 1)
    for wm, length in _flywheel_models(rng):
        cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "full"))
        g = _gravity(wm)
        omega = np.sqrt(3 * g / (2 * length)) * rng.uniform(1.2, 3.0)
        theta0 = np.arccos(3 * g / (2 * length * omega**2))
        f = _driven_theta(cmap, omega)
        x0 = np.array([theta0, 0.0])
        scale = omega**2
        assert abs(f(x0)[1]) <= 1e-9 * scale, f(x0)
        assert abs(f(np.array([0.5 * theta0, 0.0]))[1]) > 1e-3 * scale   # not everywhere
        eig = np.linalg.eigvals(_jacobian(f, x0))
        assert np.abs(eig.real).max() <= NEUTRAL_TOL * omega and np.abs(eig.imag).min() > 0


def test_flywheel_rod_driven_simulation_stays_near_new_equilibrium():
    r"""4.17, simulated: the motor holds phi' = omega (computed torque from the true
    equations); started 0.05 rad off theta_0 the rod oscillates about theta_0 (mean within
    0.01 rad) and phi' stays omega."""
    wm = load_model("flywheel_rod")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "full"))
    length, g = 0.5, _gravity(wm)
    omega = 2.0 * np.sqrt(3 * g / (2 * length))
    theta0 = np.arccos(3 * g / (2 * length * omega**2))
    i_phi, i_th = wm.index("phi"), wm.index("theta")

    def motor(t, q, nu):
        terms, _, _ = cmap.reduce_at(q, nu, q)
        thdd = -(terms.h[i_th] + terms.Q[i_th]) / terms.A[i_th, i_th]
        return np.array([terms.A[i_phi, i_th] * thdd + terms.h[i_phi] + terms.Q[i_phi]])

    q0, nu0 = np.zeros(2), np.zeros(2)
    q0[i_th], nu0[i_phi] = theta0 + 0.05, omega
    traj = simulate(cmap, q0, nu0, 3.0, rate=200, u=motor, rtol=1e-9, atol=1e-11)
    theta = traj.positions[:, i_th]
    assert abs(theta.mean() - theta0) < 0.01, (theta.mean(), theta0)
    assert np.abs(theta - theta0).max() < 0.08
    assert np.abs(traj.nu[:, i_phi] - omega).max() < 1e-6 * omega


# -- 7.1 / 7.2 free body ------------------------------------------------------------------------
def _random_block(rng, base):
    r"""The free block with random principal moments (triangle inequality kept) about its
    centre of mass at the link origin, principal axes along the link axes."""
    a, b, c = rng.uniform(0.005, 0.1, 3)                  # second moments
    moments = np.array([b + c, a + c, a + b])
    model = pin.Model(base.model)
    jid = base.joint_id_of_link("block")
    model.inertias[jid] = pin.Inertia(rng.uniform(0.5, 3.0), np.zeros(3), np.diag(moments))
    return base.with_model(model), moments


def _euler_rates(cmap: CoordinateMap):
    r"""nu' = A^-1(-h - Q) of the body_rates set (dx0, dy0, dz0, wx, wy, wz) at q = 0."""
    q = np.zeros(cmap.wm.nv)

    def f(nu):
        terms, _, _ = cmap.reduce_at(q, nu)
        return np.linalg.solve(terms.A, -terms.h - terms.Q)
    return f


def _spin_growth_rate(moments: np.ndarray, k: int, spin: float) -> float:
    r"""sqrt(max(-K, 0)) with 7.2 (c)'s K = (I1 - I3)(I1 - I2) Omega^2 / (I2 I3), axis k as 1."""
    i1, i2, i3 = moments[k], moments[(k + 1) % 3], moments[(k + 2) % 3]
    K = (i1 - i3) * (i1 - i2) * spin**2 / (i2 * i3)
    return float(np.sqrt(max(-K, 0.0)))


def test_free_body_spin_stability():
    r"""7.1/7.2: spinning about the axis of the largest or smallest moment is neutrally stable
    (eigenvalues of the linearised Euler equations on the imaginary axis, at +-sqrt(K)), about
    the intermediate axis unstable with growth rate sqrt(-K), K of 7.2 (c)."""
    rng = np.random.default_rng(SEED)
    base = load_model("free_body")
    for _ in range(N_SETS):
        wm, moments = _random_block(rng, base)
        cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
        f = _euler_rates(cmap)
        order = np.argsort(moments)
        spin = rng.uniform(1.0, 20.0)
        for rank, k in enumerate(order):
            nu = np.zeros(6)
            nu[3 + k] = spin
            eig = np.linalg.eigvals(_jacobian(f, nu)[3:, 3:])
            expected = _spin_growth_rate(moments, k, spin)
            if rank == 1:                                   # intermediate axis
                assert expected > 0
                assert abs(eig.real.max() / expected - 1) < LINEARISATION_TOL, (eig, expected)
            else:
                i1, i2, i3 = moments[k], moments[(k + 1) % 3], moments[(k + 2) % 3]
                freq = np.sqrt((i1 - i3) * (i1 - i2) / (i2 * i3)) * spin
                assert np.abs(eig.real).max() <= NEUTRAL_TOL * spin, eig
                assert abs(np.abs(eig.imag).max() / freq - 1) < LINEARISATION_TOL, (eig, freq)


def test_free_body_intermediate_axis_growth_in_simulation():
    r"""7.2, simulated: a small perturbation of a spin about the intermediate axis (x, I1 of
    the URDF's block) grows at the rate sqrt(-K) of the linearisation; about the largest
    axis (y) it stays small. (The spin about y starts with roll = pi/2, which makes y vertical:
    spinning about a horizontal y would drive the pitch to the ZYX angles' singularity.)"""
    wm = load_model("free_body")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    moments = np.array([0.0044833, 0.0062833, 0.00195])
    spin, kick = 6.0, 1e-6
    rate = _spin_growth_rate(moments, 0, spin)
    traj = simulate(cmap, np.zeros(6), np.array([0, 0, 0, spin, kick, 0.0]), 4.0 / rate,
                    rate=200 * rate, rtol=1e-11, atol=1e-14)
    off = np.hypot(traj.nu[:, 4], traj.nu[:, 5])
    t = traj.t
    late = (t > 1.5 / rate) & (off < 1e-2 * spin)       # past the transient, still linear
    slope = np.polyfit(t[late], np.log(off[late]), 1)[0]
    assert abs(slope / rate - 1) < GROWTH_TOL, (slope, rate)
    upright = np.zeros(6)
    upright[wm.index("roll")] = np.pi / 2
    traj = simulate(cmap, upright, np.array([0, 0, 0, kick, spin, 0.0]), 4.0 / rate,
                    rate=200 * rate, rtol=1e-11, atol=1e-14)
    assert np.hypot(traj.nu[:, 3], traj.nu[:, 5]).max() < 10 * kick


# -- 7.7 gyroscope -------------------------------------------------------------------------------
def _precession(wm, cmap, spin: float, duration: float) -> float:
    r"""Mean precession rate (least-squares slope of psi) after release with the axle
    horizontal, spin ``spin`` and no precession."""
    q0, nu0 = np.zeros(3), np.zeros(3)
    nu0[wm.index("phi")] = spin
    traj = simulate(cmap, q0, nu0, duration, rate=400, rtol=1e-9, atol=1e-11)
    return float(np.polyfit(traj.t, traj.positions[:, wm.index("psi")], 1)[0])


def test_gyroscope_precession_rate():
    r"""7.7: the axle precesses at Omega = M g L / (I_s omega_s) to within the fast-top
    approximation's error eps = I_perp M g L / (I_s omega_s)^2, and the error shrinks as the
    spin grows."""
    wm = load_model("gyroscope")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "full"))
    rotor = wm.model.inertias[wm.joint_id_of_link("rotor")]
    M, L = rotor.mass, float(np.linalg.norm(rotor.lever))
    I_s = float(rotor.inertia[1, 1])                        # about the axle (y), at the centre
    I_perp = float(rotor.inertia[0, 0]) + M * L**2          # about a transverse axis at O
    g = _gravity(wm)
    errors = []
    for spin in (150.0, 600.0):
        omega = M * g * L / (I_s * spin)
        eps = I_perp * M * g * L / (I_s * spin) ** 2
        nutation_period = 2 * np.pi * I_perp / (I_s * spin)
        measured = _precession(wm, cmap, spin, NUTATION_PERIODS * nutation_period)
        errors.append(abs(measured / omega - 1))
        assert errors[-1] < FAST_TOP_FACTOR * eps, (spin, measured, omega, eps)
    assert errors[1] < errors[0]
