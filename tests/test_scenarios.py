"""Scenarios: the controllers do what they claim, and the free fall keeps its energy."""

from __future__ import annotations

import numpy as np

from wheeled_dyn.simulate.scenarios import run_scenario, wip_linearisation
from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model, WipParameters

#: Largest pitch while balancing (rad), and how close the turn rate gets to its reference.
BALANCE_PITCH_MAX = 0.2
TURN_RATE_TOL = 0.05
#: Distance (m) of the base from the circle of radius 1 m about (0, 1) once at speed.
CIRCLE_RADIUS_TOL = 0.15
ENERGY_DRIFT_TOL = 1e-6


def test_fall_keeps_energy():
    traj = run_scenario("fall", 3.0).trajectory
    assert traj.relative_energy_drift() < ENERGY_DRIFT_TOL


def test_balance_stays_upright_and_turns():
    s = run_scenario("balance", 6.0)
    phi = s.trajectory.q[:, s.model.index("phi")]
    assert np.abs(phi).max() < BALANCE_PITCH_MAX
    assert abs(s.trajectory.nu[-1, 1] - 0.6) < TURN_RATE_TOL


def test_circle_stays_on_its_circle():
    s = run_scenario("circle", 1.0 + 2 * np.pi / 0.4)
    xy = s.trajectory.q[:, :2]
    radius = np.linalg.norm(xy - [0.0, 1.0], axis=1)[len(xy) // 2:]
    assert np.abs(radius - 1.0).max() < CIRCLE_RADIUS_TOL
    assert np.allclose(s.trajectory.nu[-1], [0.4, 0.4], atol=1e-3)


def test_linearisation_matches_the_pendulum_closed_form():
    r"""Upright WIP, no armature: the pitch row of the linearised dynamics. From the closed
    form (tests/test_reduction.py), with D = A11 A33 - A13**2 at phi = 0:
    d(phidot)/d(phi) = A11 m_S g d / D."""
    p = WipParameters(I_a=0.0)
    wm = load_model("wip", p)
    A, _ = wip_linearisation(CoordinateMap(wm, builtin_coordinate_set(wm, "seed001")))
    a11 = p.m_S + 2 * p.m_C + 2 * p.Iw3 / p.R**2
    a13 = -p.m_S * p.d
    a33 = p.I3 + p.m_S * p.d**2
    expected = a11 * p.m_S * p.g * p.d / (a11 * a33 - a13**2)
    assert abs(A[3, 0] - expected) < 1e-5 * expected


def test_ball_scenarios_keep_energy():
    for name in ("roll", "roll_down"):
        traj = run_scenario(name, 1.0).trajectory
        assert traj.relative_energy_drift() < ENERGY_DRIFT_TOL, name
