"""The rolling contact of a tilting wheel (constraints/wheel_contact.py, wheel_reduction.py).

Each property is checked against an independent computation: the contact point against the
lowest of many sampled rim/tyre points; J_c v against the frame velocity of the wheel; the z
row against the derivative of the contact height; J_c-dot against central finite differences
of J_c on the manifold (pin.integrate); the solved heights against the closed form
z = R cos(phi) + r; the reduction of wheel_reduction.py against the generic CoordinateMap
(quasi-velocities, rolling eliminated) and its batch version; the power identity; contact
forces from both multiplier routines.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from conftest import N_STATES, SEED
from wheeled_dyn.constraints.reduction import CoordinateMap, multipliers
from wheeled_dyn.constraints.wheel_contact import (solve_contact, wheel_contact_points,
                                                   wheel_contact_velocities, wheel_heights,
                                                   wheel_jacobian)
from wheeled_dyn.constraints.wheel_reduction import RollingReduction
from wheeled_dyn.coordinates.spec import parse_coordinate_set
from wheeled_dyn.errors import ModelError, ParameterError, StateError
from wheeled_dyn.models.builder import ModelSpec, build_wheeled_model
from wheeled_dyn.models.registry import load_model
from wheeled_dyn.models.rolling_wheel import WheelContact
from wheeled_dyn.paths import urdf_dir

#: Identities exact to rounding.
EXACT_TOL = 1e-10
#: Central finite differences: step and tolerance (relative to the largest entry).
FD_STEP = 1e-6
FD_TOL = 1e-7
#: Rim samples for the lowest-point check, and its tolerance (sampling error ~ R (pi/n)^2).
RIM_SAMPLES = 20000
RIM_TOL = 1e-7

TORUS = WheelContact("coin", 0.3, axis=(0.2, 0.9, -0.3), centre=(0.01, -0.02, 0.03),
                     tyre_radius=0.04)


def _coin_variant(contact: WheelContact, name: str = "coin_variant"):
    return build_wheeled_model(ModelSpec(name=name, urdf=urdf_dir() / "rolling_coin.urdf",
                                         base="fixed", body="coin", rolling_wheels=(contact,)))


def _models():
    return {"coin": load_model("rolling_coin"), "torus": _coin_variant(TORUS)}


def _state(wm, rng, solve=True):
    q = rng.uniform(-1.2, 1.2, wm.nv)
    q[4] = rng.uniform(-1.0, 1.0)          # lean away from flat
    if solve:
        q = solve_contact(wm, q, ("z",))
    return q


@pytest.mark.parametrize("which", ["coin", "torus"])
def test_contact_point_is_the_lowest_point(which):
    wm = _models()[which]
    rng = np.random.default_rng(SEED)
    wc = wm.rolling_wheels[0]
    data = wm.model.createData()
    angle = np.linspace(0, 2 * np.pi, RIM_SAMPLES, endpoint=False)
    for _ in range(N_STATES):
        q = _state(wm, rng, solve=False)
        pin.framesForwardKinematics(wm.model, data, q)
        M = data.oMf[wc.frame_id]
        a = M.rotation @ wc.axis
        e1 = np.cross(a, [1.0, 0.3, 0.2])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(a, e1)
        rim = (M.translation + M.rotation @ wc.centre)[None] + wc.radius * (
            np.cos(angle)[:, None] * e1 + np.sin(angle)[:, None] * e2)
        lowest = rim[np.argmin(rim[:, 2])] - [0.0, 0.0, wc.tyre_radius]
        p = wheel_contact_points(wm, q)[0]
        assert np.abs(p - lowest).max() < RIM_TOL * 10 + wc.radius * (np.pi / RIM_SAMPLES) * 2
        assert abs(p[2] - lowest[2]) < RIM_TOL


@pytest.mark.parametrize("which", ["coin", "torus"])
def test_rows_are_material_velocity_and_height_rate(which):
    wm = _models()[which]
    rng = np.random.default_rng(SEED + 1)
    for _ in range(N_STATES):
        q = _state(wm, rng, solve=False)
        v = rng.normal(size=wm.nv)
        J, _ = wheel_jacobian(wm, q)
        assert np.abs(J @ v - wheel_contact_velocities(wm, q, v)[0]).max() < EXACT_TOL
        gp = wheel_heights(wm, pin.integrate(wm.model, q, FD_STEP * v))
        gm = wheel_heights(wm, pin.integrate(wm.model, q, -FD_STEP * v))
        assert abs((gp - gm)[0] / (2 * FD_STEP) - (J @ v)[2]) < FD_TOL * max(1.0, np.abs(v).max())


@pytest.mark.parametrize("which", ["coin", "torus"])
def test_jacobian_derivative_matches_finite_differences(which):
    wm = _models()[which]
    rng = np.random.default_rng(SEED + 2)
    for _ in range(N_STATES):
        q = _state(wm, rng, solve=False)
        v = rng.normal(size=wm.nv)
        _, dJ = wheel_jacobian(wm, q, v)
        Jp, _ = wheel_jacobian(wm, pin.integrate(wm.model, q, FD_STEP * v))
        Jm, _ = wheel_jacobian(wm, pin.integrate(wm.model, q, -FD_STEP * v))
        fd = (Jp - Jm) / (2 * FD_STEP)
        assert np.abs(fd - dJ).max() < FD_TOL * max(1.0, np.abs(dJ).max())


@pytest.mark.parametrize("tyre", [0.0, 0.05])
def test_solved_height_is_the_closed_form(tyre):
    wm = _coin_variant(WheelContact("coin", 0.3, tyre_radius=tyre))
    rng = np.random.default_rng(SEED + 3)
    for _ in range(N_STATES):
        q = _state(wm, rng)
        assert abs(wheel_heights(wm, q)[0]) < EXACT_TOL
        assert abs(q[2] - (0.3 * np.cos(q[4]) + tyre)) < EXACT_TOL


def test_reduction_agrees_with_the_coordinate_map():
    wm = load_model("rolling_coin")
    red = RollingReduction(wm, ("psi", "phi", "theta"), ("z",))
    cs = parse_coordinate_set(
        {"kind": "quasi", "positions": ["psi", "phi", "theta"],
         "configuration": {"psi": "psi", "phi": "phi", "theta": "theta", "z": "R*cos(phi)"},
         "velocity_map": {"dpsi": "dpsi", "dphi": "dphi", "dtheta": "dtheta"}},
        "coin", wm.coordinate_names, list(wm.geometry))
    cmap = CoordinateMap(wm, cs)
    rng = np.random.default_rng(SEED + 4)
    docs, nus = rng.uniform(-1, 1, (N_STATES, 3)), rng.normal(size=(N_STATES, 3))
    batch = cmap.terms_batch(docs, nus)
    for i, (doc, nu) in enumerate(zip(docs, nus)):
        q = cmap.model_configuration(doc)
        ours, theirs = red.terms(q, nu), cmap.terms_at(q, nu)
        for name in ("A", "C", "Q", "h"):
            a, b = getattr(ours, name), getattr(theirs, name)
            assert np.abs(a - b).max() < EXACT_TOL, name
            assert np.abs(getattr(batch, name)[i] - b).max() < EXACT_TOL, name
        v = red.velocity_matrix(q) @ nu
        assert np.abs(wheel_contact_velocities(wm, q, v)).max() < EXACT_TOL
        lam, vdot = red.multipliers(q, nu)
        lam2, vdot2 = multipliers(wm, q, v, np.zeros(0))
        assert np.abs(lam - lam2).max() < EXACT_TOL and np.abs(vdot - vdot2).max() < EXACT_TOL
        # the reduced acceleration is the constrained one
        nudot = red.acceleration(q, nu)
        assert np.abs(nudot - vdot[[3, 4, 5]]).max() < EXACT_TOL * max(1, np.abs(nudot).max())


def test_power_identity_on_a_torus():
    wm = _coin_variant(TORUS)
    red = RollingReduction(wm, ("psi", "phi", "theta"), ("z",))
    rng = np.random.default_rng(SEED + 5)
    for _ in range(N_STATES):
        q = _state(wm, rng)
        nu = rng.normal(size=3)
        t = red.terms(q, nu)
        v = red.velocity_matrix(q) @ nu
        Ap = red.terms(pin.integrate(wm.model, q, FD_STEP * v), nu).A
        Am = red.terms(pin.integrate(wm.model, q, -FD_STEP * v), nu).A
        half_dA = 0.5 * nu @ ((Ap - Am) / (2 * FD_STEP)) @ nu
        assert abs(nu @ t.h - half_dA) < FD_TOL * max(1.0, abs(half_dA))


def test_bad_input_is_reported():
    with pytest.raises(ParameterError, match="wheel radius of coin"):
        WheelContact("coin", -0.3)
    with pytest.raises(ParameterError, match="axis"):
        WheelContact("coin", 0.3, axis=(0.0, 0.0, 0.0))
    wm = load_model("rolling_coin")
    q = np.zeros(wm.nv)
    q[4] = np.pi / 2                          # lying flat
    with pytest.raises(StateError, match="flat"):
        wheel_jacobian(wm, q)
    with pytest.raises(StateError, match="one per"):
        solve_contact(wm, np.zeros(wm.nv), ("z", "phi"))
    with pytest.raises(ModelError, match="planar"):
        build_wheeled_model(ModelSpec(name="bad", urdf=urdf_dir() / "rolling_coin.urdf",
                                      body="coin", wheels=("coin", "coin"),
                                      rolling_wheels=(WheelContact("coin", 0.3),)))


# -- wheels on different bodies: Upkie with its legs free --------------------------------------

#: Independent velocities of Upkie: body pitch, the four leg joints, the left wheel.
UPKIE_VELOCITIES = ("pitch", "left_hip", "left_knee", "right_hip", "right_knee", "left_wheel")
#: Short zero-input run (s): the legs fold under gravity.
UPKIE_RUN = 0.2


def _upkie(rng, symmetric=False):
    pytest.importorskip("upkie_description", reason="model upkie needs upkie-description")
    wm = load_model("upkie")
    red = RollingReduction(wm, UPKIE_VELOCITIES, ("z0", "roll"))
    q = np.zeros(wm.nv)
    q[2] = 0.5
    q[[0, 1, 3]] = rng.uniform(-1, 1, 3)
    q[4] = rng.uniform(-0.3, 0.3)
    legs = rng.uniform(-0.6, 0.6, 2)
    q[[6, 7]] = legs
    q[[9, 10]] = -legs if symmetric else rng.uniform(-0.6, 0.6, 2)   # mirrored joint frames
    q[[8, 11]] = rng.uniform(-3, 3, 2)
    return wm, red, red.on_ground(q)


def test_upkie_rolling_identities():
    rng = np.random.default_rng(SEED + 6)
    for _ in range(N_STATES):
        wm, red, q = _upkie(rng)
        assert np.abs(wheel_heights(wm, q)).max() < EXACT_TOL
        nu = rng.normal(size=red.n)
        S, v, _, _ = red.kinematics(q, nu)
        assert np.abs(wheel_contact_velocities(wm, q, v)).max() < EXACT_TOL
        _, dJ = wheel_jacobian(wm, q, v)
        Jp, _ = wheel_jacobian(wm, pin.integrate(wm.model, q, FD_STEP * v))
        Jm, _ = wheel_jacobian(wm, pin.integrate(wm.model, q, -FD_STEP * v))
        assert np.abs((Jp - Jm) / (2 * FD_STEP) - dJ).max() < FD_TOL * max(1, np.abs(dJ).max())
        t = red.terms(q, nu)
        Ap = red.terms(pin.integrate(wm.model, q, FD_STEP * v), nu).A
        Am = red.terms(pin.integrate(wm.model, q, -FD_STEP * v), nu).A
        half_dA = 0.5 * nu @ ((Ap - Am) / (2 * FD_STEP)) @ nu
        assert abs(nu @ t.h - half_dA) < FD_TOL * max(1.0, abs(half_dA))
        lam, vdot = red.multipliers(q, nu)
        nudot = red.acceleration(q, nu)
        assert np.abs(vdot[red.index] - nudot).max() < EXACT_TOL * max(1, np.abs(nudot).max())
    traj = red.simulate(q, nu * 0.1, UPKIE_RUN, rate=50)
    assert traj.relative_energy_drift() < 1e-8
    assert traj.drift < 1e-9


def test_upkie_coaxial_wheels_lose_a_row():
    r"""With both legs alike the wheels are coaxial: their lateral no-slip rows coincide (rank
    5, the body may turn); otherwise the six rows are independent (rank 6, no turning without
    slip), and six independent velocities no longer parametrise the coaxial case."""
    rng = np.random.default_rng(SEED + 7)
    wm, red, q = _upkie(rng, symmetric=True)
    J, _ = wheel_jacobian(wm, q)
    assert np.linalg.matrix_rank(J, tol=1e-9) == 5
    with pytest.raises(StateError, match="parametrise"):
        red.terms(q, np.zeros(red.n))
    wm, red, q = _upkie(rng)
    assert np.linalg.matrix_rank(wheel_jacobian(wm, q)[0], tol=1e-9) == 6


@pytest.mark.parametrize("name", ["bicycle", "upkie", "rolling_coin"])
def test_batch_equals_single(name):
    from wheeled_dyn.constraints.wheel_batch import terms_batch
    rng = np.random.default_rng(SEED + 8)
    if name == "upkie":
        states = [_upkie(rng)[2] for _ in range(N_STATES)]
        wm, red, _ = _upkie(rng)
    else:
        wm = load_model(name)
        red = (RollingReduction(wm, ("roll", "steer", "rear_wheel"), ("z", "pitch"))
               if name == "bicycle" else RollingReduction(wm, ("psi", "phi", "theta"), ("z",)))
        states = []
        for _ in range(N_STATES):
            q = np.zeros(wm.nv)
            q[2] = 0.3
            q[4] = rng.uniform(-0.3, 0.3)
            q[[0, 1, 3]] = rng.uniform(-1, 1, 3)
            q[5 if name == "rolling_coin" else 7] = rng.uniform(-0.5, 0.5)
            states.append(red.on_ground(q))
    qs, nus = np.array(states), rng.normal(size=(N_STATES, red.n))
    batch = terms_batch(red, qs, nus)
    for i in range(N_STATES):
        single = red.terms(qs[i], nus[i])
        for key in ("A", "C", "Q", "B", "h"):
            diff = np.abs(getattr(batch, key)[i] - getattr(single, key))
            assert diff.max(initial=0.0) < EXACT_TOL, key
