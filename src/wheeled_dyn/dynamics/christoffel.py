r"""Christoffel symbols, exactly, from Pinocchio's derivatives of the inverse dynamics.

With zero velocity and gravity, :math:`\mathrm{RNEA}(q, 0, e_j) = A(q) e_j`, so column j of
``computeRNEADerivatives``' :math:`\partial\tau/\partial q` is :math:`\partial (A e_j)/\partial
q`: the tensor :math:`\partial A_{ij}/\partial q_k`, exact to rounding. Then

.. math::

    c_{i,jk} = \tfrac12\left(\frac{\partial A_{ij}}{\partial q_k} + \frac{\partial A_{ik}}
    {\partial q_j} - \frac{\partial A_{jk}}{\partial q_i}\right),\qquad
    C_{ij} = \sum_k c_{i,jk}\,\dot q_k .

In any velocities :math:`\nu` (quasi-velocities included) the Coriolis/centrifugal vector is a
quadratic form :math:`h_i = \sum_{j,k} H_{i,jk}\nu_j\nu_k`; its symmetric coefficient tensor
:math:`H_{i,jk} = H_{i,kj}` is unique, unlike the matrix C.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin


def mass_matrix_derivative(model: pin.Model, q: np.ndarray, data: pin.Data | None = None) -> np.ndarray:
    r"""The tensor :math:`D_{ijk} = \partial A_{ij}/\partial q_k` (nv × nv × nv), exact.

    Works for models whose joints have ``nq == nv`` (so that :math:`\partial/\partial q` is the
    ordinary derivative), which every wheeled model of the toolkit satisfies."""
    nv = model.nv
    if model.nq != nv:
        raise ValueError("mass_matrix_derivative needs nq == nv")
    no_gravity = pin.Model(model)
    no_gravity.gravity = pin.Motion.Zero()
    data = no_gravity.createData()
    zero = np.zeros(nv)
    D = np.empty((nv, nv, nv))
    for j in range(nv):
        a = np.zeros(nv)
        a[j] = 1.0
        dtau_dq, _, _ = pin.computeRNEADerivatives(no_gravity, data, q, zero, a)
        D[:, j, :] = dtau_dq
    return D


def christoffel_tensor(model: pin.Model, q: np.ndarray) -> np.ndarray:
    r"""Christoffel symbols of the first kind, ``c[i, j, k]`` = :math:`c_{i,jk}`."""
    D = mass_matrix_derivative(model, q)
    # D[i,j,k] = dA_ij/dq_k ; D.transpose(0,2,1)[i,j,k] = dA_ik/dq_j ; D.transpose(2,0,1)[i,j,k] = dA_jk/dq_i
    return 0.5 * (D + D.transpose(0, 2, 1) - D.transpose(2, 0, 1))


def coriolis_from_christoffel(c: np.ndarray, qdot: np.ndarray) -> np.ndarray:
    r""":math:`C_{ij} = \sum_k c_{i,jk}\dot q_k`."""
    return np.einsum("ijk,k->ij", c, qdot)


def h_coefficients(coriolis: Callable[[np.ndarray], np.ndarray], n: int) -> np.ndarray:
    r"""The unique symmetric tensor H of :math:`h = C(\nu)\nu`, from a function returning the
    matrix :math:`C(\nu)` that is linear in :math:`\nu`: with :math:`\Gamma_{i,jk} =
    C(e_k)_{ij}`, :math:`H_{i,jk} = \tfrac12(\Gamma_{i,jk} + \Gamma_{i,kj})`."""
    gamma = np.stack([coriolis(np.eye(n)[k]) for k in range(n)], axis=2)
    return 0.5 * (gamma + gamma.transpose(0, 2, 1))
