r"""Checks every rolling body's reduction must pass, shared by the rolling tests.

:func:`stability_threshold`: the spin at which a body's largest growth rate falls to zero, by
bisection about its closed form.

:func:`assert_contact_at_rest`: the material point at the contact does not move for the
velocities the reduction gives (:math:`v = S\nu`), and :math:`J_c v = 0`.

:func:`assert_power_identity`: with the body's link given a random, non-uniform inertia (so
that :math:`A_\nu` varies along the motion), the reduced terms in the body rates satisfy

.. math::

    \nu^T h_\nu = \tfrac12\,\nu^T \dot A_\nu\,\nu ,

:math:`\dot A_\nu` by central differences along :math:`v = S\nu` on the manifold.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin

from conftest import N_STATES
from wheeled_dyn import CoordinateMap, builtin_coordinate_set
from wheeled_dyn.constraints import contact_jacobian, contact_velocities

#: Step and relative tolerance of the central differences.
FD_STEP = 1e-6
FD_TOL = 1e-6
#: h must be larger than this somewhere, or the identity would be 0 = 0.
NONTRIVIAL = 1e-6
#: Tolerance of identities exact to rounding.
EXACT_TOL = 1e-9
#: The ball's centre moves at least this fast (m/s), or "at rest" would be trivial.
MOVING = 1e-3


def assert_contact_at_rest(wm, coordinates: str, random_state: Callable,
                           rng: np.random.Generator, moving: bool = False) -> None:
    r"""At :data:`N_STATES` states ``random_state(wm, rng)`` with random velocities in the
    coordinate set ``coordinates``: one contact, its material point at rest, :math:`J_c v = 0`
    (and, with ``moving``, the body's origin moving: the identity is not 0 = 0)."""
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, coordinates))
    for _ in range(N_STATES):
        q = random_state(wm, rng)
        _, _, v = cmap.reduce_at(q, rng.normal(size=cmap.n))
        vc = contact_velocities(wm, q, v)
        assert vc.shape == (1, 3)
        assert np.abs(vc).max() < EXACT_TOL * (1 + np.abs(v).max()), vc
        assert np.abs(contact_jacobian(wm, q)[0] @ v).max() < EXACT_TOL * (1 + np.abs(v).max())
        if moving:
            assert np.abs(v[:3]).max() > MOVING


def assert_power_identity(base, link: str, random_state: Callable, rng: np.random.Generator,
                          coordinates: str = "body_rates") -> None:
    r"""The power identity (module docstring) at :data:`N_STATES` states ``random_state(wm,
    rng)`` of ``base`` with ``link``'s inertia replaced by a random one."""
    model = pin.Model(base.model)
    model.inertias[base.joint_id_of_link(link)] = pin.Inertia.FromLogCholeskyParameters(
        pin.LogCholeskyParameters(rng.normal(size=10) * 0.3))
    wm = base.with_model(model)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, coordinates))
    for _ in range(N_STATES):
        q, nu = random_state(wm, rng), rng.normal(size=cmap.n)
        terms, _, v = cmap.reduce_at(q, nu)
        plus = cmap.terms_at(pin.integrate(wm.model, q, v * FD_STEP), nu).A
        minus = cmap.terms_at(pin.integrate(wm.model, q, -v * FD_STEP), nu).A
        Adot = (plus - minus) / (2 * FD_STEP)
        lhs, rhs = nu @ terms.h, 0.5 * nu @ Adot @ nu
        assert abs(lhs - rhs) < FD_TOL * (1 + abs(lhs) + np.abs(Adot).max()), (lhs, rhs)
        assert np.abs(terms.h).max() > NONTRIVIAL


def stability_threshold(growth: Callable[[float], float], expected: float, neutral: float,
                        tolerance: float) -> float:
    r"""The spin in [0.5, 1.5] × ``expected`` above which ``growth(spin)`` (the largest growth
    rate of the linearised motion) stays below ``neutral`` × ``expected``, by bisection to
    ``tolerance`` / 10 relative."""
    lo, hi = 0.5 * expected, 1.5 * expected
    while hi - lo > 0.1 * tolerance * expected:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if growth(mid) < neutral * expected else (mid, hi)
    return 0.5 * (lo + hi)


def ball_centre_dynamics(cmap) -> Callable[[np.ndarray], np.ndarray]:
    r"""f(c, omega) of a uniform ball's reduced equations in world rates, its orientation held
    at zero (the uniform ball's equations do not depend on it): the state is the centre c and
    the angular velocity omega."""
    def f(x):
        q = np.concatenate([x[:3], np.zeros(3)])
        terms, S, _ = cmap.reduce_at(q, x[3:])
        return np.concatenate([S[:3] @ x[3:], np.linalg.solve(terms.A, -terms.h - terms.Q)])
    return f
