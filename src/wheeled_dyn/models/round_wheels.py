r"""Drive wheels as round bodies. A derivation takes a wheel as axisymmetric about its axle:
one moment :math:`J` about the axle, one :math:`D` about every diameter, its centre of mass on
the axle. A CAD export's wheel is so only to its rounding — TIAGo's moments about its two
diameters are 3e-6 of them apart, its products of inertia 1e-5 of them —, which leaves the
reduced equations a difference of about 1e-7 of a row: the size of the comparisons' tolerance,
so each verdict would be the draw's.

The comparisons' random parameter sets draw the two wheels alike, each its URDF inertia scaled
(:func:`~wheeled_dyn.compare.grid.samples.parameter_sets`); wheels within :data:`ROUND_TOL` of
axisymmetric are drawn axisymmetric (:func:`made_round`: about the centre,
:math:`J\,nn^T + D\,(I - nn^T)` with :math:`n` the axle and :math:`D` the mean of the
moments about the diameters; the centre of mass put on the axle) where the derivation writes
nothing of their asymmetry (:mod:`wheeled_dyn.compare.grid.round_wheels`; where it does, they
are drawn free), and the model's
readings say so (:func:`round_reading`). Wheels further from it are drawn as the URDF has
them (a derivation taking them round differs, "agrees only if round_wheels"). The model's own
matrices (``wheeled-dyn matrices``) are the URDF's, unrounded.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin

#: Largest asymmetry of a wheel's inertia drawn axisymmetric: the spread of its moments about
#: its diameters and its products of inertia between the axle and its plane, relative to those
#: moments, and its centre of mass's distance from the axle relative to its radius.
ROUND_TOL = 1e-4


def _parts(inertia: pin.Inertia, axis: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    r"""(:math:`J`, the moments about the two diameters, the products between the axle and
    the plane) of the inertia about the centre, :math:`n` = ``axis`` (unit)."""
    I = np.asarray(inertia.inertia)
    J = float(axis @ I @ axis)
    plane = np.linalg.svd(np.eye(3) - np.outer(axis, axis))[0][:, :2]
    moments = np.linalg.eigvalsh(plane.T @ I @ plane)
    return J, moments, I @ axis - J * axis


def asymmetry(inertia: pin.Inertia, axis: np.ndarray, radius: float) -> float:
    r"""How far a wheel's inertia (in its joint's frame, the axle ``axis``) is from
    axisymmetric: the largest of :math:`|D_1 - D_2|/\bar D`, :math:`|I n - J n|/\bar D` and the
    centre's distance from the axle over ``radius``; 0 for a massless wheel."""
    if inertia.mass <= 0:
        return 0.0
    n = np.asarray(axis, float) / np.linalg.norm(axis)
    _, moments, products = _parts(inertia, n)
    mean = float(moments.mean())
    lever = np.asarray(inertia.lever)
    off = float(np.linalg.norm(lever - (lever @ n) * n)) / radius
    if mean <= 0:
        return off
    return max(float(moments[1] - moments[0]) / mean, float(np.linalg.norm(products)) / mean,
               off)


def made_round(inertia: pin.Inertia, axis: np.ndarray) -> pin.Inertia:
    r"""The axisymmetric inertia nearest ``inertia`` about the axle ``axis`` (module text)."""
    n = np.asarray(axis, float) / np.linalg.norm(axis)
    J, moments, _ = _parts(inertia, n)
    outer = np.outer(n, n)
    lever = np.asarray(inertia.lever)
    return pin.Inertia(inertia.mass, (lever @ n) * n,
                       J * outer + float(moments.mean()) * (np.eye(3) - outer))


def round_reading(links: Sequence[str], asymmetries: Sequence[float]) -> tuple[str, ...]:
    r"""The model's reading of its drive wheels ``links`` when they are round to their
    rounding only (every one of ``asymmetries`` within :data:`ROUND_TOL`, one not zero)."""
    worst = max(asymmetries, default=0.0)
    if not 0.0 < worst <= ROUND_TOL:
        return ()
    return (f"wheels {', '.join(links)}: axisymmetric about their axles to {worst:.1g} (their "
            "moments about their diameters, their products of inertia, their centres of mass "
            "off the axle: a CAD export's rounding); the comparisons' random parameter sets "
            "draw them axisymmetric where a derivation writes nothing of their asymmetry",)


__all__ = ["ROUND_TOL", "asymmetry", "made_round", "round_reading"]
