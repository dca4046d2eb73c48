r"""A ball rolling inside a fixed paraboloid bowl (seed 002's case, ``sphere_paraboloid``).

The contact with a surface of revolution (constraints/surfaces.py) is tested like the sphere's
(tests/test_benchmark_rolling.py): the contact point found from the centre is the surface point
the ball was put on; the contact point does not move under v = S nu; J_c-dot equals the
derivative of J_c along the motion; the reduced equations satisfy the power identity; a
zero-input simulation keeps its energy and keeps the ball on the bowl. The surface geometry is
checked on two spherical meridians against the sphere's rules, and the small oscillations at
the bottom against the closed form omega^2 = g / ((a - r)(1 + A/(M r^2))), by linearising the
tool's reduced equations and by simulation. The bowl is written here in closed form
(z = rho^2/(2a)), independently of the code.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import pytest

from conftest import N_STATES, SEED
from rolling_checks import assert_contact_at_rest, assert_power_identity, ball_centre_dynamics
from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model, multipliers, simulate
from wheeled_dyn.constraints import contact_jacobian, contact_points, contact_velocities
from wheeled_dyn.constraints.surfaces import foot, normal_rate
from wheeled_dyn.errors import ParameterError
from wheeled_dyn.models.contact import SphereContact
from wheeled_dyn.models.benchmarks import BALL_RADIUS, PARABOLOID_VERTEX_RADIUS
from wheeled_dyn.models.listing import shipped_model_files

MODEL = "sphere_paraboloid"
#: Tolerance of identities exact to rounding.
EXACT_TOL = 1e-9
#: Step and tolerance of central finite differences.
FD_STEP = 1e-6
FD_TOL = 1e-6
#: Largest relative energy drift in a zero-input simulation (DOP853 at rtol 1e-10).
ENERGY_TOL = 1e-7
#: Largest distance (m) of the ball from the bowl, beyond its radius, along a simulation (the
#: constraint is imposed on the velocities; the position is integrated; about 2e-12 here).
SURFACE_TOL = 1e-10
#: Relative accuracy of the linearisation's frequency (central differences of the dynamics).
LINEAR_TOL = 1e-6
#: Relative accuracy of the simulated period: amplitude 5 mm in a bowl of a = 0.5 m, so the
#: nonlinear correction is of order (5e-3 / 0.4)^2 ~ 2e-4 at most (3e-5 here).
PERIOD_TOL = 2e-4
#: Amplitude (m) of the simulated small oscillation.
AMPLITUDE = 5e-3
#: Largest distance from the axis (m) of a random contact point.
RHO_MAX = 0.7


# -- the bowl in closed form, independently of the code -------------------------------------------
def _bowl(wm):
    spec = wm.contact.spec
    return float(spec.vertex_radius), np.asarray(spec.centre, dtype=float), float(spec.radius)


def _bowl_point(a, vertex, rho, phi):
    return vertex + np.array([rho * np.cos(phi), rho * np.sin(phi), rho**2 / (2 * a)])


def _bowl_normal(a, vertex, p):
    r"""Upward unit normal: the gradient of z - (x^2 + y^2)/(2a)."""
    d = p - vertex
    g = np.array([-d[0] / a, -d[1] / a, 1.0])
    return g / np.linalg.norm(g)


def _distance_to_bowl(a, vertex, point):
    r"""Distance from ``point`` to the paraboloid: the nearest point lies in the meridian plane,
    at a signed radius s with (s - rho)+ (s/a)(s^2/(2a) - h) = 0, a cubic."""
    d = point - vertex
    rho, h = math.hypot(d[0], d[1]), d[2]
    roots = np.roots([1 / (2 * a**2), 0.0, 1 - h / a, -rho])
    s = roots[np.abs(roots.imag) < 1e-9].real
    return float(np.min(np.hypot(s - rho, s**2 / (2 * a) - h)))


def _random_contact(wm, rng):
    r"""(contact point, centre) with the ball touching the bowl at a random point."""
    a, vertex, r = _bowl(wm)
    p = _bowl_point(a, vertex, rng.uniform(0.0, RHO_MAX), rng.uniform(-np.pi, np.pi))
    return p, p + r * _bowl_normal(a, vertex, p)


def _random_ball_state(wm, rng):
    q = np.zeros(wm.nv)
    q[:3], q[3:6] = _random_contact(wm, rng)[1], rng.uniform(-1.2, 1.2, 3)
    return q


def _ball_constants(wm):
    inertia = wm.model.inertias[wm.joint_id_of_link("ball")]
    return inertia.mass, float(inertia.inertia[0, 0]), float(-wm.model.gravity.linear[2])


# -- the contact ---------------------------------------------------------------------------------
def test_contact_point_is_where_the_ball_was_put():
    rng = np.random.default_rng(SEED)
    wm = load_model(MODEL)
    a, vertex, r = _bowl(wm)
    assert (wm.geometry["a"], wm.geometry["r"]) == (a, r) == (PARABOLOID_VERTEX_RADIUS, BALL_RADIUS)
    for _ in range(N_STATES):
        p, centre = _random_contact(wm, rng)
        q = np.concatenate([centre, rng.uniform(-1.2, 1.2, 3)])
        found = contact_points(wm, q)[0]
        assert np.abs(found - p).max() < EXACT_TOL, (found, p)
        assert abs(np.linalg.norm(found - centre) - r) < EXACT_TOL
        d = found - vertex
        assert abs(d[2] - (d[0] ** 2 + d[1] ** 2) / (2 * a)) < EXACT_TOL
        assert abs(_distance_to_bowl(a, vertex, centre) - r) < EXACT_TOL


@pytest.mark.parametrize("coords", ["body_rates", "world_rates"])
def test_contact_point_does_not_move(coords):
    assert_contact_at_rest(load_model(MODEL), coords, _random_ball_state,
                           np.random.default_rng(SEED), moving=True)


def test_contact_jacobian_derivative():
    r"""J_c-dot(q, v) = d/dt J_c(q) along v, by central differences on the manifold, for
    velocities that keep the contact and for arbitrary ones."""
    rng = np.random.default_rng(SEED)
    wm = load_model(MODEL)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    for _ in range(N_STATES):
        q = _random_ball_state(wm, rng)
        for v in (rng.normal(size=wm.nv), cmap.reduce_at(q, rng.normal(size=3))[2]):
            J, dJ = contact_jacobian(wm, q, v)
            plus = contact_jacobian(wm, pin.integrate(wm.model, q, v * FD_STEP))[0]
            minus = contact_jacobian(wm, pin.integrate(wm.model, q, -v * FD_STEP))[0]
            fd = (plus - minus) / (2 * FD_STEP)
            assert np.abs(fd - dJ).max() < FD_TOL * (1 + np.abs(dJ).max())


def test_reduced_power_identity():
    r"""nu^T h_nu = 1/2 nu^T (dA_nu/dt) nu in the body rates, with a random (non-uniform)
    ball inertia so that A_nu varies along the motion (tests/rolling_checks.py)."""
    assert_power_identity(load_model(MODEL), "ball", _random_ball_state,
                          np.random.default_rng(SEED))


def test_zero_input_keeps_energy_and_the_bowl():
    r"""Rolling and spinning around the bowl with zero input: the energy stays constant, the
    ball stays on the bowl (its centre at distance r from it, by the closed-form bowl) and its
    contact point at rest; the ball really goes up and down the bowl."""
    rng = np.random.default_rng(SEED)
    wm = load_model(MODEL)
    a, vertex, r = _bowl(wm)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    p = _bowl_point(a, vertex, 0.3, 0.4)
    q0 = np.concatenate([p + r * _bowl_normal(a, vertex, p), rng.uniform(-1.2, 1.2, 3)])
    traj = simulate(cmap, q0, np.array([1.5, -0.5, 4.0]), 2.0, rate=50)
    assert traj.relative_energy_drift() < ENERGY_TOL, traj.relative_energy_drift()
    gaps = np.array([_distance_to_bowl(a, vertex, q[:3]) - r for q in traj.q])
    assert np.abs(gaps).max() < SURFACE_TOL, np.abs(gaps).max()
    for q, nu in zip(traj.q[::10], traj.nu[::10]):
        _, S, v = cmap.reduce_at(q, nu)
        assert np.abs(contact_velocities(wm, q, v)).max() < EXACT_TOL * (1 + np.abs(v).max())
    heights = traj.q[:, 2]
    assert heights.max() - heights.min() > 0.01


def test_contact_force_at_the_bottom():
    r"""Multipliers from the full equations (J_c and J_c-dot): the ball at the bottom of the
    bowl, its centre moving at speed V, is pushed up by M (g + V^2/(a - r)) (its centre turns
    on a circle of radius a - r) and, rolling without spin, not sideways."""
    rng = np.random.default_rng(SEED)
    wm = load_model(MODEL)
    a, _, r = _bowl(wm)
    M, _, g = _ball_constants(wm)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "world_rates"))
    q = cmap.model_configuration(np.zeros(3))
    for _ in range(N_STATES):
        wx, wy = rng.normal(size=2) * 3.0
        _, S, v = cmap.reduce_at(q, np.array([wx, wy, 0.0]))
        speed = np.linalg.norm(v[:3])
        lam, _ = multipliers(wm, q, v, np.zeros(0))
        assert speed > 0.1
        assert np.abs(lam[:2]).max() < EXACT_TOL * M * g
        assert abs(lam[2] - M * (g + speed**2 / (a - r))) < EXACT_TOL * M * g, lam


# -- the surface geometry on spherical meridians -------------------------------------------------
@dataclass(frozen=True)
class _SphericalBowl:
    r"""Lower cap of a sphere of radius R, vertex at the origin: f = R - sqrt(R^2 - rho^2)."""

    R: float

    def f(self, rho: float) -> float:
        return self.R - math.sqrt(self.R**2 - rho**2)

    def df(self, rho: float) -> float:
        return rho / math.sqrt(self.R**2 - rho**2)

    def d2f(self, rho: float) -> float:
        return self.R**2 / (self.R**2 - rho**2) ** 1.5

    def df_by_rho(self, rho: float) -> float:
        return 1 / math.sqrt(self.R**2 - rho**2)


@dataclass(frozen=True)
class _SphericalDome:
    r"""Upper cap of a sphere of radius R, vertex at the origin: f = sqrt(R^2 - rho^2) - R."""

    R: float

    def f(self, rho: float) -> float:
        return math.sqrt(self.R**2 - rho**2) - self.R

    def df(self, rho: float) -> float:
        return -rho / math.sqrt(self.R**2 - rho**2)

    def d2f(self, rho: float) -> float:
        return -self.R**2 / (self.R**2 - rho**2) ** 1.5

    def df_by_rho(self, rho: float) -> float:
        return -1 / math.sqrt(self.R**2 - rho**2)


@pytest.mark.parametrize("inside", [True, False], ids=["bowl", "dome"])
def test_spherical_meridian_gives_the_sphere_rules(inside):
    r"""A spherical meridian, through the general surface-of-revolution code: the normal is
    along the line of centres and n-dot = -P c-dot/(R - r) inside a spherical bowl, and
    P c-dot/(R1 + r) on top of a sphere (the rule of constraints/sphere_contact.py), for a
    centre moving on its offset sphere (P = 1 - n n^T)."""
    rng = np.random.default_rng(SEED)
    R, r = (1.0, 0.109) if inside else (0.3, 0.109)
    meridian = _SphericalBowl(R) if inside else _SphericalDome(R)
    sphere_centre = np.array([0.0, 0.0, R if inside else -R])
    dist = R - r if inside else R + r
    for _ in range(N_STATES):
        tilt, phi = rng.uniform(0.0, 0.3), rng.uniform(-np.pi, np.pi)
        e = np.array([np.sin(tilt) * np.cos(phi), np.sin(tilt) * np.sin(phi), np.cos(tilt)])
        centre = sphere_centre + dist * (-e if inside else e)
        n = (sphere_centre - centre) / dist if inside else (centre - sphere_centre) / dist
        ft = foot(meridian, np.zeros(3), centre, r)
        assert np.abs(ft.normal - n).max() < EXACT_TOL
        cdot = rng.normal(size=3)
        cdot -= n * (n @ cdot)
        expected = (-cdot if inside else cdot) / dist
        err = np.abs(normal_rate(ft, r, cdot) - expected).max()
        assert err < EXACT_TOL * (1 + np.abs(cdot).max()), err


# -- small oscillations at the bottom: closed form -----------------------------------------------
def _small_oscillation_frequency(wm):
    r"""omega = sqrt(g / ((a - r)(1 + A/(M r^2)))): near the bottom the centre moves on its
    offset surface, z_c = r + rho_c^2/(2(a - r)) (the offset of a concave surface bends more),
    and rolling gives the kinetic energy 1/2 (M + A/r^2) |c-dot|^2 (no spin)."""
    a, _, r = _bowl(wm)
    M, A, g = _ball_constants(wm)
    return math.sqrt(g / ((a - r) * (1 + A / (M * r**2))))


def test_small_oscillation_frequency_by_linearisation():
    wm = load_model(MODEL)
    M, A, _ = _ball_constants(wm)
    assert abs(A / (M * wm.geometry["r"] ** 2) - 0.4) < 1e-6        # the uniform ball
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "world_rates"))
    f = ball_centre_dynamics(cmap)
    bottom = np.concatenate([cmap.model_configuration(np.zeros(3))[:3], np.zeros(3)])
    assert np.abs(f(bottom)).max() < EXACT_TOL                        # an equilibrium
    J = np.array([(f(bottom + FD_STEP * e) - f(bottom - FD_STEP * e)) / (2 * FD_STEP)
                  for e in np.eye(6)]).T
    eig = np.linalg.eigvals(J)
    omega = _small_oscillation_frequency(wm)
    assert np.abs(eig.real).max() < LINEAR_TOL * omega                # neutrally stable
    oscillating = np.sort(np.abs(eig.imag))[-4:]                      # x and y, +- i omega
    assert np.abs(oscillating / omega - 1).max() < LINEAR_TOL, (oscillating, omega)


def test_small_oscillation_period_by_simulation():
    r"""Released from rest AMPLITUDE from the axis, the ball rolls to and fro through the bottom
    with the period 2 pi / omega of the closed form (measured between zero crossings)."""
    wm = load_model(MODEL)
    a, vertex, r = _bowl(wm)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "world_rates"))
    omega = _small_oscillation_frequency(wm)
    period = 2 * np.pi / omega
    p = _bowl_point(a, vertex, AMPLITUDE, 0.0)
    q0 = np.concatenate([p + r * _bowl_normal(a, vertex, p), np.zeros(3)])
    traj = simulate(cmap, q0, np.zeros(3), 2.2 * period, rate=400)
    x = traj.q[:, 0] - vertex[0]
    k = np.nonzero(np.sign(x[:-1]) != np.sign(x[1:]))[0]
    crossings = traj.t[k] - x[k] * (traj.t[k + 1] - traj.t[k]) / (x[k + 1] - x[k])
    assert len(crossings) == 4, crossings
    measured = (crossings[-1] - crossings[0]) / 1.5
    assert abs(measured / period - 1) < PERIOD_TOL, (measured, period)
    assert np.abs(traj.q[:, 1]).max() < EXACT_TOL                     # a plane motion
    assert traj.relative_energy_drift() < ENERGY_TOL


# -- bad input -----------------------------------------------------------------------------------
@pytest.mark.parametrize("radius,vertex_radius,words", [
    (0.6, 0.5, ("ball radius", "vertex_radius", "less than")),
    (0.5, 0.5, ("ball radius", "vertex_radius", "less than")),
    (0.1, 0.0, ("vertex_radius", "positive")),
    (0.1, -0.5, ("vertex_radius", "positive")),
    (0.1, float("nan"), ("vertex_radius", "positive")),
])
def test_bad_bowl_is_refused(radius, vertex_radius, words):
    with pytest.raises(ParameterError) as err:
        SphereContact("ball", radius, "paraboloid", vertex_radius=vertex_radius)
    assert all(w in str(err.value) for w in words), str(err.value)


def test_bad_bowl_in_a_model_file(tmp_path):
    r"""The model file's [contact] with a ball larger than the bowl's vertex radius of
    curvature, or a vertex_radius on another surface, is refused with the quantity named."""
    text = shipped_model_files()[MODEL].path.read_text()
    cases = [(text.replace("vertex_radius = 0.50", "vertex_radius = 0.10"), "ball radius"),
             (text.replace('surface = "paraboloid"', 'surface = "sphere"\nsurface_radius = 0.3'),
              "vertex_radius")]
    for k, (bad, word) in enumerate(cases):
        assert bad != text
        path = tmp_path / f"bad{k}.toml"
        path.write_text(bad.replace('name = "sphere_paraboloid"', f'name = "bad{k}"'))
        with pytest.raises(ParameterError, match=word):
            load_model(str(path))


# -- seed 002, (3.8): the force function of gravity in the paraboloid -----------------------------
def test_paraboloid_force_function_3_8(tmp_path):
    r"""s3_8_paraboloid.toml: its configuration map puts the ball on the bowl (checked here with
    an independent distance, not the map's formula), so its printed force function (3.8),
    U = -V, is compared with the true potential of a ball that touches the paraboloid: it agrees;
    with the ball's centre offset on the other side of the surface (+R p/sqrt for -R p/sqrt,
    the convex side) it differs."""
    from wheeled_dyn.compare.steps.records import compare_steps
    from wheeled_dyn.constraints.reduction import CoordinateMap as Map
    from wheeled_dyn.compare.grid.grid import derivation_coordinate_set
    from wheeled_dyn.compare.grid.samples import ParameterSet, namespace_values
    from wheeled_dyn.derivations import builtin_derivations, load_derivation
    folder = builtin_derivations("seed002")[0].parent
    path = folder / "s3_8_paraboloid.toml"
    d = load_derivation(path)
    wm = load_model(d.model)
    a, vertex, _ = _bowl(wm)
    cmap = Map(wm, derivation_coordinate_set(d, ParameterSet(wm, namespace_values(wm, None))))
    rng = np.random.default_rng(SEED)
    for _ in range(N_STATES):
        q_doc = np.array([rng.uniform(0.0, 0.4), rng.uniform(-np.pi, np.pi), 0.3])
        centre = cmap.model_configuration(q_doc)[:3]
        assert abs(_distance_to_bowl(a, vertex, centre) - BALL_RADIUS) < EXACT_TOL
    (r,) = compare_steps(d, SEED)
    assert r.verdict == "agrees", r.texts
    printed = 'value = "-M*g*(u1**2/(2*p) + R*p/sqrt(p**2 + u1**2))"'
    assert path.read_text().count(printed) == 1
    text = path.read_text().replace(printed,
                                    'value = "-M*g*(u1**2/(2*p) - R*p/sqrt(p**2 + u1**2))"')
    planted = tmp_path / "s3_8_paraboloid.toml"
    planted.write_text(text)
    assert compare_steps(load_derivation(planted), SEED)[0].verdict == "differs"
    # read as a potential V instead of the force function U = -V, the printed value differs
    planted.write_text(path.read_text().replace('quantity = "force function"\n', ""))
    (r,) = compare_steps(load_derivation(planted), SEED)
    assert r.verdict == "differs" and r.texts[0].startswith("sign"), r.texts
