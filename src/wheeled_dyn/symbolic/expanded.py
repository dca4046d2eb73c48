r"""Closed forms of a larger model written out: the intermediate-variable form expanded.

:func:`~.wheeled.wheeled_symbolic` derives the reduced terms in one piece; for a free body in
body rates or a planar base with wheels that takes minutes in SymPy. The intermediate-variable
form :func:`~.tree_wheeled.tree_wheeled` takes under a second for the same models, and where the
model is small (a free block, a balancing robot with a torso: a few hundred terms in all) its
variables can be replaced by their definitions directly,

.. math::
   w_k = f_k(q, \nu, p, w_1 \dots w_{k-1}) \quad\Rightarrow\quad
   A_{ij}(q, p),\ h_{i,jk}(q, p),\ Q_i(q, p) \text{ as polynomials in } p, \sin, \cos,

each intermediate expanded once (a shared memo) and the whole refused as soon as one of them
grows past :data:`MAX_TERMS` terms (a legged robot's tree grows to tens of thousands: no report
prints those). Each element is then collected by parameter (:func:`~.simplify.simplify_matrix`).
"""

from __future__ import annotations

import sympy as sp
from sympy.polys.matrices.exceptions import DMNonInvertibleMatrixError

from ..coordinates.spec import CoordinateSet
from ..models.wheeled_model import WheeledModel
from .simplify import simplify_matrix
from .tree_algebra import TooLarge, inliner
from .tree_wheeled import ReducedTree, tree_wheeled

#: Largest number of terms of one expanded intermediate variable (a free block's largest has
#: a few hundred; a wheel-legged robot's pass ten thousand).
MAX_TERMS = 2000
#: Largest number of degrees of freedom of the model tried at all (its tree is built first).
MAX_DOF = 10


def expanded_tree(wm: WheeledModel, cs: CoordinateSet, parameters: str = "standard",
                  limit: int = MAX_TERMS) -> ReducedTree | None:
    r"""The terms of ``wm`` in ``cs`` with no intermediate variable left (module text), or None
    where the model has more than :data:`MAX_DOF` degrees of freedom, where it rolls on
    something other than upright wheels under a planar base (the tree's contact rows are
    those of :func:`~.tree_wheeled.tree_wheeled`: a sphere or a leaning disk is not one) or
    an intermediate grows past ``limit`` terms, or where the velocity basis has no closed
    form in the drawn lengths (a set with fewer velocities than rolling motions whose
    :math:`MM^T` is singular as a matrix of symbols)."""
    wheels = wm.spec.base == "planar" and bool(wm.wheels)
    if wm.model.nv > MAX_DOF or (cs.rolling != "none" and not wheels):
        return None
    try:
        rt = tree_wheeled(wm, cs, parameters)
    except DMNonInvertibleMatrixError:  # rolling rows singular in the drawn R, L as symbols
        return None
    full = inliner(rt.assignments, expand=True, limit=limit)
    pars = tuple(rt.parameters)

    def done(M: sp.Matrix | None) -> sp.Matrix | None:
        if M is None:
            return None
        return simplify_matrix(M.applyfunc(full), pars)

    try:
        A, C, Q, h, B = (done(M) for M in (rt.A, rt.C, rt.Q, rt.h, rt.B))
    except TooLarge:
        return None
    return ReducedTree(q=rt.q, nu=rt.nu, parameters=pars, assignments=(), A=A, C=C, Q=Q,
                       h=h, B=B)


__all__ = ["MAX_DOF", "MAX_TERMS", "expanded_tree"]
