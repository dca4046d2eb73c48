r"""Seed 002's body of revolution with its centre of mass off the centre of the sphere that
bounds it (``offset_sphere_plane``: Routh's sphere), rolling without slip on the plane — its
first integrals and the spin that keeps it upright, reproduced from the tool's own dynamics.

With :math:`G` the centre of mass, :math:`P` the contact point, :math:`r = G - P`,
:math:`e_3` the axis of symmetry, :math:`I_1` (diameters) and :math:`I_3` (axis) the central
moments and :math:`\omega` the angular velocity, the free motion keeps, besides the energy,

.. math::

    J = (I_G\,\omega)\cdot r \quad\text{(Jellett)},\qquad
    \Lambda = \omega_3\,\sqrt{I_1 I_3 + m I_1\,\lVert r\times e_3\rVert^2
                              + m I_3\,(r\cdot e_3)^2}\quad\text{(Routh)},

with :math:`\omega_3 = \omega\cdot e_3`. Spinning upright at rate :math:`n` about the vertical
with the centre of mass a height :math:`l > 0` above the sphere's centre (radius :math:`R`,
:math:`h = R + l` the height of :math:`G`), the linearised rolling equations in the tilt
:math:`z = x + i y` of the axis are

.. math::

    (I_1 + m h^2)\,\ddot z - i\,n\,(I_3 + m h R)\,\dot z - m g l\,z = 0 ,

so the upright spin is (neutrally) stable iff :math:`n^2 (I_3 + m h R)^2 > 4 (I_1 + m h^2)\,m g l`
— for :math:`l = 0` no condition (the uniform ball), for :math:`l < 0` always (bottom heavy).
The tests compute J and Λ along a simulation, and the threshold by linearising the reduced
equations numerically; neither uses these formulas to move the body.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from rolling_checks import stability_threshold
from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model, simulate

#: Largest relative drift of a conserved quantity over the simulation (DOP853, rtol 1e-10).
INTEGRAL_TOL = 1e-7
#: A quantity that is not conserved must vary by more than this (relative).
VARIES = 1e-3
#: Central finite-difference step of the numerical linearisation.
FD_STEP = 1e-6
#: Real parts below this, relative to the spin, count as zero (neutral stability).
NEUTRAL_TOL = 1e-6
#: Relative accuracy of the threshold found by bisection.
THRESHOLD_TOL = 1e-3

NAME = "offset_sphere_plane"
#: The body turned upside down (roll = pi about its x axis): centre of mass above the centre.
INVERTED_ROLL = np.pi


def _body(wm):
    inertia = wm.model.inertias[wm.joint_id_of_link("ball")]
    I_G = np.array(inertia.inertia)           # about the centre of mass, body axes
    return inertia.mass, np.array(inertia.lever), I_G


def _integrals(wm, cmap, q, nu):
    r"""(J, Λ, energy-free check quantities) at the state (q, nu): Jellett's J, Routh's Λ and
    the wrong Routh variant with I_1 and I_3 exchanged in the brackets."""
    m, lever, I_G = _body(wm)
    I1, I3 = I_G[0, 0], I_G[2, 2]
    _, _, v = cmap.reduce_at(q, nu)
    data = wm.model.createData()
    pin.forwardKinematics(wm.model, data, q, v)
    pin.updateFramePlacements(wm.model, data)
    fid = wm.contact.frame_id
    rot, centre = data.oMf[fid].rotation, data.oMf[fid].translation
    omega = pin.getFrameVelocity(wm.model, data, fid, pin.LOCAL_WORLD_ALIGNED).angular
    r = centre + rot @ lever - (centre - np.array([0.0, 0.0, wm.contact.radius]))
    e3 = rot[:, 2]
    w3, perp2, par2 = omega @ e3, np.cross(r, e3) @ np.cross(r, e3), (r @ e3) ** 2
    jellett = (rot @ I_G @ rot.T @ omega) @ r
    routh = w3 * np.sqrt(I1 * I3 + m * I1 * perp2 + m * I3 * par2)
    swapped = w3 * np.sqrt(I1 * I3 + m * I3 * perp2 + m * I1 * par2)
    return np.array([jellett, routh, swapped])


def test_jellett_and_routh_integrals_are_kept():
    r"""A wobbling, rolling run (tilt swinging over more than a radian): J and Λ stay constant
    to the integrator's accuracy; the variant with I_1, I_3 exchanged does not, nor does the
    axial spin ω_3 alone (so the motion exercises the integrals)."""
    wm = load_model(NAME)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    q0 = np.array([0.0, 0.0, wm.contact.radius, 0.3, 0.4, 2.6])
    traj = simulate(cmap, q0, np.array([0.5, -0.4, 9.0]), 2.0, rate=50)
    values = np.array([_integrals(wm, cmap, q, nu) for q, nu in zip(traj.q, traj.nu)])
    drift = np.ptp(values, axis=0) / np.abs(values).max(axis=0)
    assert drift[0] < INTEGRAL_TOL and drift[1] < INTEGRAL_TOL, drift
    assert drift[2] > VARIES, drift
    assert traj.relative_energy_drift() < INTEGRAL_TOL
    assert np.ptp(traj.nu[:, 2]) > VARIES * np.abs(traj.nu[:, 2]).max()
    assert np.ptp(traj.q[:, 5]) > 1.0              # the tilt really changes


def _tilt_dynamics(cmap):
    r"""f(pitch, roll, nu) of the reduced equations in body rates; the position on the plane and
    the heading do not enter (the plane and gravity are invariant under them)."""
    radius = cmap.wm.contact.radius

    def f(x):
        q = np.array([0.0, 0.0, radius, 0.0, x[0], x[1]])
        terms, _, v = cmap.reduce_at(q, x[2:])
        return np.concatenate([v[4:6], np.linalg.solve(terms.A, -terms.h - terms.Q)])
    return f


def _max_growth(f, x):
    J = np.array([(f(x + FD_STEP * e) - f(x - FD_STEP * e)) / (2 * FD_STEP)
                  for e in np.eye(len(x))]).T
    return np.linalg.eigvals(J).real.max()


def _closed_form_threshold(wm):
    m, lever, I_G = _body(wm)
    g = float(-wm.model.gravity.linear[2])
    R, l = wm.contact.radius, -lever[2]            # upside down: G is -lever_z above the centre
    h = R + l
    return 2 * np.sqrt((I_G[0, 0] + m * h**2) * m * g * l) / (I_G[2, 2] + m * h * R)


def test_upright_spin_threshold_of_the_inverted_body():
    r"""The body upside down (centre of mass above the sphere's centre), spinning about the
    vertical: the numerically linearised true equations are unstable below the spin n_crit and
    neutrally stable above; n_crit equals the closed form above to THRESHOLD_TOL. Upright
    (centre of mass below), the body is stable without spin."""
    wm = load_model(NAME)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    f = _tilt_dynamics(cmap)
    n_cf = _closed_form_threshold(wm)
    assert n_cf > 1.0

    def growth(n0, roll=INVERTED_ROLL):
        x = np.array([0.0, roll, 0.0, 0.0, n0])
        assert np.abs(f(x)).max() < 1e-9 * max(n0, 1.0)     # a steady motion
        return _max_growth(f, x)

    assert growth(0.0, roll=0.0) < NEUTRAL_TOL             # bottom heavy: stable at rest
    assert growth(0.8 * n_cf) > 0.1
    assert growth(1.2 * n_cf) < NEUTRAL_TOL * n_cf
    n_crit = stability_threshold(growth, n_cf, NEUTRAL_TOL, THRESHOLD_TOL)
    assert abs(n_crit / n_cf - 1) < THRESHOLD_TOL, (n_crit, n_cf)


@pytest.mark.parametrize("factor,stable", [(1.3, True), (0.7, False)])
def test_inverted_spin_probe(factor, stable):
    r"""Simulation on both sides of the threshold: released 0.01 rad off upside-down with a spin
    factor × n_crit about its axis, the body stays within a small tilt above the threshold and
    falls over below it."""
    wm = load_model(NAME)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    n0 = factor * _closed_form_threshold(wm)
    q0 = np.array([0.0, 0.0, wm.contact.radius, 0.0, 0.0, INVERTED_ROLL - 0.01])
    # body rates: upside down the body's z axis points down, so a spin +n0 about the world
    # vertical is -n0 about the body's z
    traj = simulate(cmap, q0, np.array([0.0, 0.0, -n0]), 3.0, rate=50)
    tilt = np.abs(np.cos(traj.q[:, 4]) * np.cos(traj.q[:, 5]) + 1.0)   # 1 + e3.z, 0 upside down
    if stable:
        assert tilt.max() < 0.05, tilt.max()
    else:
        assert tilt.max() > 0.5, tilt.max()
    assert traj.relative_energy_drift() < 1e-5
