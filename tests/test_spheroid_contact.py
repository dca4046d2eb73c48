r"""A spheroid (ellipsoid of revolution) rolling without slip on the ground (``spheroid_plane``,
constraints/spheroid_contact.py).

The contact is tested like the ball's (tests/test_benchmark_rolling.py), on the shipped oblate
spheroid and on a prolate one built here: the contact point found is the lowest point of the
body (against a brute-force minimum of the height over the surface, written here from the
parametrisation x = (a sin t cos f, a sin t sin f, c cos t)); it does not move under
v = S nu; its z row is the rate of the height of the lowest point; J_c-dot equals the
derivative of J_c along the motion (and the rate of the contact point over the body its
derivative along the rotation); the reduced equations satisfy the power identity; a zero-input
simulation keeps its energy and the body on the ground.

Closed forms independent of the code: with a = c the rows are the ball's; the upright
spheroid spinning about its axis is a steady motion; on its flat side the oblate spheroid
rocks at omega^2 = m g (rho - h)/(I_eq + m h^2), rho = a^2/c the radius of curvature of the
meridian at the pole and h = c the height of the centre of mass (the prolate one standing on
its pole falls away at the rate with the same formula, rho - h < 0). Derivation: the centre of
curvature of the bottom stays at the height rho to second order in the tilt theta, the centre
of mass is rho - h below it on the axis, so its height is h + (rho - h) theta^2/2; rolling
without slip the body turns about the contact point, at distance h from the centre of mass,
so T = (I_eq + m h^2) theta-dot^2/2.
"""

from __future__ import annotations

import math
from dataclasses import replace
from functools import lru_cache

import numpy as np
import pinocchio as pin
import pytest
from scipy.optimize import minimize

from conftest import N_STATES, SEED
from rolling_checks import assert_contact_at_rest, assert_power_identity
from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model, simulate
from wheeled_dyn.constraints import contact_jacobian, contact_points, contact_velocities
from wheeled_dyn.constraints.spheroid_contact import (lowest_point, lowest_point_rate,
                                                      place_on_ground, spheroid_height)
from wheeled_dyn.errors import ParameterError
from wheeled_dyn.models import ModelSpec, build_wheeled_model
from wheeled_dyn.models.benchmarks import BALL_RADIUS, SPHEROID_RADII
from wheeled_dyn.models.contact import SphereContact
from wheeled_dyn.models.listing import shipped_model_files
from wheeled_dyn.paths import urdf_dir

MODEL = "spheroid_plane"
#: The prolate spheroid built here: equatorial and polar radii (m) (the URDF's inertia: the
#: identities do not need the inertia of the shape).
PROLATE_RADII = (0.06, 0.10)
SHAPES = ("oblate", "prolate")
#: Tolerance of identities exact to rounding.
EXACT_TOL = 1e-9
#: Step and tolerance of central finite differences.
FD_STEP = 1e-6
FD_TOL = 1e-6
#: Largest relative energy drift in a zero-input simulation (DOP853 at rtol 1e-10).
ENERGY_TOL = 1e-7
#: Largest height (m) of the lowest point above or below the ground along a simulation (the
#: constraint is imposed on the velocities, the position integrated; about 3e-12 here).
GROUND_TOL = 1e-10
#: Points of the brute-force grid over the surface (polar angle, azimuth).
GRID = (500, 1000)
#: Largest height (m) of the lowest grid point above the contact: the grid spacing is about
#: pi a/500 = 6e-4 m, so the lowest grid point is at most ~ (6e-4)^2/(2 * 0.06) = 3e-6 m up.
GRID_TOL = 1e-5
#: Largest distance (m) of the lowest grid point from the contact point: the height is
#: quadratic about the contact with radii of curvature between c^2/a and a^2/c (a > c), so the
#: lowest grid point is within about the grid's diagonal spacing (9e-4 m) times
#: sqrt(a^3/c^3) = 2.2 (up to 3e-4 m here).
GRID_POINT_TOL = 3e-3
#: Accuracy of the polished (Nelder-Mead) minimum: its height (m), its distance from the
#: contact point (m; the height is quadratic about the minimum).
POLISH_HEIGHT_TOL = 1e-12
POLISH_POINT_TOL = 1e-5
#: Relative accuracy of the linearisation's frequency (central differences of the dynamics).
LINEAR_TOL = 1e-6
#: Relative accuracy of the simulated rocking period: tilt amplitude 5 mrad, so the nonlinear
#: correction is of order (5e-3)^2 (about 1e-5 here).
PERIOD_TOL = 1e-4
#: Tilt amplitude (rad) of the simulated rocking.
AMPLITUDE = 5e-3
#: Largest |pitch|, |roll| (rad) of a random orientation.
ANGLE_MAX = 1.2


# -- models and placement, independently of the code ----------------------------------------
@lru_cache(maxsize=None)
def _built(shape: str):
    if shape == "oblate":
        return load_model(MODEL)
    base = load_model(MODEL).spec
    a, c = PROLATE_RADII
    return build_wheeled_model(replace(base, name="prolate_spheroid", source=None,
                                       contact=SphereContact("spheroid", a, polar_radius=c)))


def _model(shape: str):
    wm = _built(shape)
    return wm.with_model(pin.Model(wm.model))


def _radii(wm) -> tuple[float, float]:
    return float(wm.contact.spec.radius), float(wm.contact.spec.polar_radius)


def _centre_height(a: float, c: float, pitch: float, roll: float) -> float:
    r"""Height of the centre touching the ground: the axis e_3 makes the angle t with the
    vertical, cos t = cos(pitch) cos(roll) (the (3, 3) entry of Rz Ry Rx); the depth of the
    ellipse (a sin, c cos) below its centre along a direction at t from its c axis is
    sqrt(a^2 sin^2 t + c^2 cos^2 t) (its support function)."""
    ct = math.cos(pitch) * math.cos(roll)
    return math.sqrt(a * a * (1 - ct * ct) + c * c * ct * ct)


def _random_state(wm, rng) -> np.ndarray:
    r"""A configuration touching the ground: random place and orientation."""
    a, c = _radii(wm)
    yaw, pitch, roll = rng.uniform(-ANGLE_MAX, ANGLE_MAX, 3)
    return np.array([*rng.uniform(-1, 1, 2), _centre_height(a, c, pitch, roll), yaw, pitch, roll])


def _surface(a: float, c: float, t: np.ndarray, f: np.ndarray) -> np.ndarray:
    r"""Points (..., 3) of the spheroid, body axes."""
    return np.stack([a * np.sin(t) * np.cos(f), a * np.sin(t) * np.sin(f), c * np.cos(t)], -1)


def _placement(wm, q):
    data = wm.model.createData()
    pin.framesForwardKinematics(wm.model, data, q)
    M = data.oMf[wm.contact.frame_id]
    return M.rotation.copy(), M.translation.copy()


def _brute_force_lowest(wm, q) -> tuple[float, np.ndarray, float, np.ndarray]:
    r"""(height, point) of the lowest point over a dense grid of the surface, and polished by
    Nelder-Mead from the best grid point (world)."""
    a, c = _radii(wm)
    R, o = _placement(wm, q)
    t, f = np.meshgrid(np.linspace(0, np.pi, GRID[0]),
                       np.linspace(0, 2 * np.pi, GRID[1], endpoint=False), indexing="ij")
    world = _surface(a, c, t, f) @ R.T + o
    k = np.unravel_index(np.argmin(world[..., 2]), t.shape)

    def height(x):
        return float((R @ _surface(a, c, x[0], x[1]) + o)[2])

    res = minimize(height, [t[k], f[k]], method="Nelder-Mead",
                   options={"xatol": 1e-12, "fatol": 1e-16, "maxiter": 20000})
    return (float(world[k][2]), world[k], float(res.fun),
            R @ _surface(a, c, res.x[0], res.x[1]) + o)


# -- the contact point -------------------------------------------------------------------------
@pytest.mark.parametrize("shape", SHAPES)
def test_contact_point_is_the_lowest_point(shape):
    r"""At random orientations placed on the ground by the closed-form height: the contact point
    is on the spheroid, at z = 0, its outward normal points down, and it is the lowest point
    of the body (brute force over the surface, then polished); the code's placement
    (place_on_ground) and height of the lowest point agree."""
    rng = np.random.default_rng(SEED)
    wm = _model(shape)
    a, c = _radii(wm)
    Ainv = np.diag([1 / a**2, 1 / a**2, 1 / c**2])
    for _ in range(N_STATES):
        q = _random_state(wm, rng)
        R, o = _placement(wm, q)
        p = contact_points(wm, q)[0]
        pb = R.T @ (p - o)
        assert abs(pb @ Ainv @ pb - 1) < EXACT_TOL
        assert abs(p[2]) < EXACT_TOL, p
        normal = R @ Ainv @ pb
        assert np.abs(normal / np.linalg.norm(normal) - [0, 0, -1]).max() < EXACT_TOL
        grid_h, grid_p, best_h, best_p = _brute_force_lowest(wm, q)
        assert -EXACT_TOL < grid_h < GRID_TOL, grid_h
        assert np.linalg.norm(grid_p - p) < GRID_POINT_TOL
        assert abs(best_h) < POLISH_HEIGHT_TOL, best_h
        assert np.linalg.norm(best_p - p) < POLISH_POINT_TOL, (best_p, p)
        assert abs(spheroid_height(wm, q)) < EXACT_TOL
        lifted = q + np.array([0, 0, 0.37, 0, 0, 0])
        assert abs(spheroid_height(wm, lifted) - 0.37) < EXACT_TOL
        assert np.abs(place_on_ground(wm, lifted) - q).max() < EXACT_TOL


@pytest.mark.parametrize("shape", SHAPES)
def test_representative_configuration_touches_the_ground(shape):
    r"""The built-in quasi sets' configuration at random angles puts the centre at the
    closed-form height (brute force: the lowest grid point is on the ground), the upright
    body at z0 = c."""
    rng = np.random.default_rng(SEED)
    wm = _model(shape)
    a, c = _radii(wm)
    for name in ("body_rates", "world_rates"):
        cmap = CoordinateMap(wm, builtin_coordinate_set(wm, name))
        assert abs(cmap.model_configuration(np.zeros(3))[2] - c) < EXACT_TOL
        for _ in range(N_STATES):
            angles = rng.uniform(-ANGLE_MAX, ANGLE_MAX, 3)
            q = cmap.model_configuration(angles)
            assert abs(q[2] - _centre_height(a, c, angles[1], angles[2])) < EXACT_TOL
            grid_h = _brute_force_lowest(wm, q)[0]
            assert -EXACT_TOL < grid_h < GRID_TOL, grid_h


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("coords", ["body_rates", "world_rates"])
def test_contact_point_does_not_move(shape, coords):
    assert_contact_at_rest(_model(shape), coords, _random_state, np.random.default_rng(SEED),
                           moving=True)


# -- the rows and their derivative --------------------------------------------------------------
@pytest.mark.parametrize("shape", SHAPES)
def test_z_row_is_the_rate_of_the_height(shape):
    r"""The z row times any v is the derivative of the height of the lowest point along v
    (central differences on the manifold): the velocity form of touching the ground."""
    rng = np.random.default_rng(SEED)
    wm = _model(shape)
    for _ in range(N_STATES):
        q, v = _random_state(wm, rng), rng.normal(size=wm.nv)
        plus = spheroid_height(wm, pin.integrate(wm.model, q, v * FD_STEP))
        minus = spheroid_height(wm, pin.integrate(wm.model, q, -v * FD_STEP))
        row = contact_jacobian(wm, q)[0][2] @ v
        assert abs((plus - minus) / (2 * FD_STEP) - row) < FD_TOL * (1 + abs(row)), row
        assert abs(row) > 1e-3


@pytest.mark.parametrize("shape", SHAPES)
def test_contact_point_rate_over_the_body(shape):
    r"""p-dot = (A u-dot - p (p.u-dot))/s with u-dot = u x omega_B is the derivative of the
    lowest point p(u) when the body turns at omega_B: u(t) = exp(-t [omega_B]x) u (the world's
    down direction, fixed in the world, seen from the turning body)."""
    rng = np.random.default_rng(SEED)
    a, c = _radii(_model(shape))
    for _ in range(N_STATES):
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        w = rng.normal(size=3)
        p_plus = lowest_point(a, c, pin.exp3(-FD_STEP * w) @ u)[0]
        p_minus = lowest_point(a, c, pin.exp3(FD_STEP * w) @ u)[0]
        rate = lowest_point_rate(a, c, u, np.cross(u, w))
        assert np.abs((p_plus - p_minus) / (2 * FD_STEP) - rate).max() < FD_TOL
        assert np.abs(rate).max() > 1e-3


@pytest.mark.parametrize("shape", SHAPES)
def test_contact_jacobian_derivative(shape):
    r"""J_c-dot(q, v) = d/dt J_c(q) along v, by central differences on the manifold, for
    velocities that keep the contact and for arbitrary ones."""
    rng = np.random.default_rng(SEED)
    wm = _model(shape)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    for _ in range(N_STATES):
        q = _random_state(wm, rng)
        for v in (rng.normal(size=wm.nv), cmap.reduce_at(q, rng.normal(size=3))[2]):
            J, dJ = contact_jacobian(wm, q, v)
            plus = contact_jacobian(wm, pin.integrate(wm.model, q, v * FD_STEP))[0]
            minus = contact_jacobian(wm, pin.integrate(wm.model, q, -v * FD_STEP))[0]
            fd = (plus - minus) / (2 * FD_STEP)
            assert np.abs(fd - dJ).max() < FD_TOL * (1 + np.abs(dJ).max())
            assert np.abs(dJ).max() > 1e-3


@pytest.mark.parametrize("shape", SHAPES)
def test_reduced_power_identity(shape):
    r"""nu^T h_nu = 1/2 nu^T (dA_nu/dt) nu in the body rates, with a random (non-uniform)
    inertia so that A_nu varies along the motion (tests/rolling_checks.py)."""
    assert_power_identity(_model(shape), "spheroid", _random_state, np.random.default_rng(SEED))


@pytest.mark.parametrize("shape", SHAPES)
def test_batch_equals_single(shape):
    r"""The batched terms (constraints/batch.py, which reads the rows of the model's contact)
    equal the single-state ones in every built-in set."""
    rng = np.random.default_rng(SEED)
    wm = _model(shape)
    for name in ("full", "body_rates", "world_rates"):
        cmap = CoordinateMap(wm, builtin_coordinate_set(wm, name))
        q, nu = rng.uniform(-1, 1, (N_STATES, cmap.n)), rng.normal(size=(N_STATES, cmap.n))
        batch = cmap.terms_batch(q, nu)
        for i in range(N_STATES):
            one = cmap.terms(q[i], nu[i])
            for key in ("A", "C", "Q", "B", "h", "G"):
                a, b = getattr(batch, key), getattr(one, key)
                if b is None:
                    assert a is None
                    continue
                assert np.max(np.abs(a[i] - b), initial=0.0) < EXACT_TOL, (name, key)


# -- simulation -------------------------------------------------------------------------------
@pytest.mark.parametrize("shape", SHAPES)
def test_zero_input_keeps_energy_and_the_ground(shape):
    r"""Rolling and wobbling with zero input: the energy stays constant, the lowest point stays
    on the ground (brute force at a few samples) and at rest; the body really tilts and its
    centre really goes up and down."""
    rng = np.random.default_rng(SEED)
    wm = _model(shape)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    q0 = _random_state(wm, rng)
    traj = simulate(cmap, q0, np.array([1.5, -0.5, 4.0]), 2.0, rate=50)
    drift = traj.relative_energy_drift()
    assert drift < ENERGY_TOL, drift
    heights = np.array([spheroid_height(wm, q) for q in traj.q])
    assert np.abs(heights).max() < GROUND_TOL, np.abs(heights).max()
    for q in traj.q[::25]:
        grid_h = _brute_force_lowest(wm, q)[0]
        assert -GROUND_TOL < grid_h < GRID_TOL, grid_h
    for q, nu in zip(traj.q[::10], traj.nu[::10]):
        _, S, v = cmap.reduce_at(q, nu)
        assert np.abs(contact_velocities(wm, q, v)).max() < EXACT_TOL * (1 + np.abs(v).max())
    assert np.ptp(traj.q[:, 2]) > 1e-3
    assert np.ptp(traj.q[:, 5]) > 0.1 or np.ptp(traj.q[:, 4]) > 0.1


# -- closed forms ------------------------------------------------------------------------------
def _ball_rows(wm, q, v):
    r"""J_lin + r [e_z]x J_omega and its time variation, from Pinocchio's frame Jacobians."""
    data = wm.model.createData()
    pin.computeJointJacobiansTimeVariation(wm.model, data, q, v)
    pin.computeJointJacobians(wm.model, data, q)
    pin.updateFramePlacements(wm.model, data)
    fid = wm.model.getFrameId("ball")
    lwa = pin.LOCAL_WORLD_ALIGNED
    J = pin.getFrameJacobian(wm.model, data, fid, lwa)
    dJ = pin.getFrameJacobianTimeVariation(wm.model, data, fid, lwa)
    ez = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    r = BALL_RADIUS
    return J[:3] + r * ez @ J[3:], dJ[:3] + r * ez @ dJ[3:]


def test_equal_radii_give_the_ball():
    r"""A spheroid with a = c = r on the ball's URDF: its rows, their derivative and its contact
    point equal those of the ball contact (sphere_plane) and the formula
    J_lin + r [e_z]x J_omega, at random states."""
    rng = np.random.default_rng(SEED)
    ball = load_model("sphere_plane")
    spec = ModelSpec(name="round_spheroid", urdf=urdf_dir() / "ball.urdf", base="free",
                     body="ball", contact=SphereContact("ball", BALL_RADIUS,
                                                        polar_radius=BALL_RADIUS))
    round_ = build_wheeled_model(spec)
    assert round_.contact.spec.spheroid and not ball.contact.spec.spheroid
    for _ in range(N_STATES):
        q = np.array([*rng.uniform(-1, 1, 2), BALL_RADIUS, *rng.uniform(-ANGLE_MAX, ANGLE_MAX, 3)])
        v = rng.normal(size=6)
        J, dJ = contact_jacobian(round_, q, v)
        Jb, dJb = contact_jacobian(ball, q, v)
        Jf, dJf = _ball_rows(ball, q, v)
        for x, y in ((J, Jb), (J, Jf), (dJ, dJb), (dJ, dJf)):
            assert np.abs(x - y).max() < EXACT_TOL
        assert np.abs(contact_points(round_, q) - contact_points(ball, q)).max() < EXACT_TOL
        assert np.abs(contact_velocities(round_, q, v)
                      - contact_velocities(ball, q, v)).max() < EXACT_TOL


def _body_constants(wm):
    r"""(m, I_eq, I_axial, g): mass, central moments, gravity."""
    inertia = wm.model.inertias[wm.joint_id_of_link("spheroid")]
    I = np.array(inertia.inertia)
    return inertia.mass, float(I[0, 0]), float(I[2, 2]), float(-wm.model.gravity.linear[2])


def _rocking_omega2(wm) -> float:
    r"""omega^2 = m g (rho - h)/(I_eq + m h^2), rho = a^2/c, h = c (module docstring)."""
    a, c = _radii(wm)
    m, I_eq, _, g = _body_constants(wm)
    return m * g * (a * a / c - c) / (I_eq + m * c * c)


def _tilt_dynamics(cmap):
    r"""f(pitch, roll, nu) of the reduced equations in body rates, the body placed on the ground
    by the closed-form height; the position on the plane and the heading do not enter."""
    a, c = _radii(cmap.wm)

    def f(x):
        q = np.array([0.0, 0.0, _centre_height(a, c, x[0], x[1]), 0.0, x[0], x[1]])
        terms, _, v = cmap.reduce_at(q, x[2:])
        return np.concatenate([v[4:6], np.linalg.solve(terms.A, -terms.h - terms.Q)])
    return f


def _linearisation(f, x):
    return np.array([(f(x + FD_STEP * e) - f(x - FD_STEP * e)) / (2 * FD_STEP)
                     for e in np.eye(len(x))]).T


def test_uniform_inertia_is_the_stated_one():
    wm = _model("oblate")
    a, c = SPHEROID_RADII
    assert _radii(wm) == (a, c) and (wm.geometry["a"], wm.geometry["c"]) == (a, c)
    m, I_eq, I_ax, _ = _body_constants(wm)
    assert m == pytest.approx(2.5)
    assert I_ax == pytest.approx(0.4 * m * a * a, rel=1e-12)
    assert I_eq == pytest.approx(0.2 * m * (a * a + c * c), rel=1e-12)


def test_upright_spin_is_a_steady_motion():
    r"""The upright oblate spheroid spinning about its vertical axis: an equilibrium of the
    reduced equations, and in simulation it stays upright, spinning at a constant rate, its
    centre at rest at z0 = c."""
    wm = _model("oblate")
    a, c = _radii(wm)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    n = 7.0
    assert np.abs(_tilt_dynamics(cmap)(np.array([0.0, 0.0, 0.0, 0.0, n]))).max() < EXACT_TOL
    traj = simulate(cmap, np.array([0.0, 0.0, c, 0.0, 0.0, 0.0]), np.array([0.0, 0.0, n]),
                    1.0, rate=50)
    assert np.abs(traj.q[:, [0, 1, 4, 5]]).max() < EXACT_TOL
    assert np.abs(traj.q[:, 2] - c).max() < EXACT_TOL
    assert np.abs(traj.nu - [0.0, 0.0, n]).max() < EXACT_TOL * n
    assert abs(traj.q[-1, 3] - n * traj.t[-1]) < 1e-6            # yaw = n t


def test_rocking_frequency_by_linearisation():
    r"""The oblate spheroid at rest on its flat side: the linearised reduced equations have
    the eigenvalues +-i omega (twice: rocking in two planes) of the closed form; the prolate
    one standing on its pole has +-lambda, lambda^2 = -omega^2 of the same formula."""
    for shape in SHAPES:
        wm = _model(shape)
        cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
        f = _tilt_dynamics(cmap)
        rest = np.zeros(5)
        assert np.abs(f(rest)).max() < EXACT_TOL                      # an equilibrium
        eig = np.linalg.eigvals(_linearisation(f, rest))
        w2 = _rocking_omega2(wm)
        scale = math.sqrt(abs(w2))
        if shape == "oblate":
            assert w2 > 0
            assert np.abs(eig.real).max() < LINEAR_TOL * scale        # neutrally stable
            rocking = np.sort(np.abs(eig.imag))[-4:]
            assert np.abs(rocking / scale - 1).max() < LINEAR_TOL, (rocking, scale)
        else:
            assert w2 < 0
            assert np.abs(eig.imag).max() < LINEAR_TOL * scale
            growth = np.sort(np.abs(eig.real))[-4:]
            assert np.abs(growth / scale - 1).max() < LINEAR_TOL, (growth, scale)


def test_rocking_period_by_simulation():
    r"""Released from rest tilted by AMPLITUDE about the world x axis (roll), the oblate
    spheroid rocks with the period 2 pi/omega of the closed form (between zero crossings of
    the roll), in a plane (no pitch), keeping its energy and the ground."""
    wm = _model("oblate")
    a, c = _radii(wm)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    period = 2 * np.pi / math.sqrt(_rocking_omega2(wm))
    q0 = np.array([0.0, 0.0, _centre_height(a, c, 0.0, AMPLITUDE), 0.0, 0.0, AMPLITUDE])
    traj = simulate(cmap, q0, np.zeros(3), 2.2 * period, rate=400)
    x = traj.q[:, 5]
    k = np.nonzero(np.sign(x[:-1]) != np.sign(x[1:]))[0]
    crossings = traj.t[k] - x[k] * (traj.t[k + 1] - traj.t[k]) / (x[k + 1] - x[k])
    assert len(crossings) == 4, crossings
    measured = (crossings[-1] - crossings[0]) / 1.5
    assert abs(measured / period - 1) < PERIOD_TOL, (measured, period)
    assert np.abs(traj.q[:, [0, 3, 4]]).max() < EXACT_TOL               # a plane motion
    assert np.ptp(traj.q[:, 1]) > 1e-4                                   # it rolls sideways
    assert traj.relative_energy_drift() < ENERGY_TOL
    assert max(abs(spheroid_height(wm, q)) for q in traj.q) < GROUND_TOL


# -- bad input --------------------------------------------------------------------------------
@pytest.mark.parametrize("radius,polar,words", [
    (0.1, 0.0, ("spheroid polar radius", "positive")),
    (0.1, -0.06, ("spheroid polar radius", "positive")),
    (0.1, float("nan"), ("spheroid polar radius", "positive")),
    (0.1, float("inf"), ("spheroid polar radius", "positive")),
    (0.1, "0.06", ("spheroid polar radius", "positive")),
    (0.0, 0.06, ("spheroid equatorial radius", "positive")),
    (-0.1, 0.06, ("spheroid equatorial radius", "positive")),
    (float("inf"), 0.06, ("spheroid equatorial radius", "positive")),
])
def test_bad_semi_axes_are_refused(radius, polar, words):
    with pytest.raises(ParameterError) as err:
        SphereContact("spheroid", radius, polar_radius=polar)
    assert all(w in str(err.value) for w in words), str(err.value)


def test_spheroid_on_another_surface_is_refused():
    with pytest.raises(ParameterError, match="polar_radius.*plane"):
        SphereContact("spheroid", 0.1, "sphere", surface_radius=0.3, polar_radius=0.06)


@pytest.mark.parametrize("value,word", [("0.0", "polar radius"), ("-0.06", "polar radius"),
                                        ('"thin"', "polar radius")])
def test_bad_semi_axes_in_a_model_file(tmp_path, value, word):
    text = shipped_model_files()[MODEL].path.read_text()
    bad = text.replace("polar_radius = 0.06", f"polar_radius = {value}")
    assert bad != text
    path = tmp_path / "bad.toml"
    path.write_text(bad.replace(f'name = "{MODEL}"', 'name = "bad_spheroid"'))
    with pytest.raises(ParameterError, match=word):
        load_model(str(path))
