r"""The elements of reduced terms labelled as the comparison engine labels them.

:math:`A_\nu, C_\nu, B, G` element by element (``"A[i,j]"``, 1-based), :math:`Q_\nu` by row,
and the velocity products of :math:`h = C_\nu\nu`: each row is a quadratic form

.. math::
    h_i = \sum_{j \le k} c_{ijk}\,\nu_j\nu_k,

listed as ``"h[i]:a*b"`` with the coefficient :math:`c_{ijk}` (the whole coefficient of the
product for :math:`j < k`; zero products included). :func:`coordinate_set_key` names what of a
coordinate set the closed forms depend on (for cache keys).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import sympy as sp

from ..coordinates.spec import CoordinateSet
from ..errors import ModelError
from .simplify import simplify_expr
from .transform import ReducedSymbolic

if TYPE_CHECKING:
    from .tree_wheeled import ReducedTree


def velocity_products(h: sp.Expr, nu: Sequence[sp.Symbol]) -> dict[tuple[int, int], sp.Expr]:
    r"""``{(j, k): coefficient of}`` :math:`\nu_j\nu_k` (``j <= k``; for ``j < k`` the whole
    coefficient of the product) in a quadratic form ``h`` of the velocities ``nu``."""
    out: dict[tuple[int, int], sp.Expr] = {}
    expanded = sp.expand(h)
    if expanded == 0:
        return out
    poly = sp.Poly(expanded, *nu)
    for mon, coef in poly.terms():
        idx = [i for i, e in enumerate(mon) for _ in range(e)]
        if len(idx) != 2:
            raise ModelError("<symbolic>", None, f"h is not quadratic in {nu}: {mon}")
        out[(idx[0], idx[1])] = out.get((idx[0], idx[1]), 0) + coef
    return out


def element_expressions(red: ReducedSymbolic | ReducedTree, inputs: Sequence[str] = ()) -> dict[str, sp.Expr]:
    r"""The elements of ``red`` labelled as the comparison engine labels them (1-based):
    ``"A[i,j]"``, ``"C[i,j]"``, ``"Q[i]"``, ``"B[i,j]"``, ``"G[i,j]"`` and ``"h[i]:a*b"`` (the
    coefficient of the velocity product ``a*b``, ``a`` not after ``b`` in the velocity
    order; products with a zero coefficient are listed as 0). Each is collected by parameter
    (:func:`~.simplify.simplify_expr`)."""
    nu, m = red.nu, len(red.nu)
    pars = tuple(red.parameters)
    out: dict[str, sp.Expr] = {}
    for key in ("A", "C", "B", "G"):
        M = getattr(red, key, None)
        if M is None:
            continue
        for i in range(M.shape[0]):
            for j in range(M.shape[1]):
                out[f"{key}[{i + 1},{j + 1}]"] = M[i, j]
    for i in range(m):
        out[f"Q[{i + 1}]"] = red.Q[i]
    for i in range(m):
        coeffs = velocity_products(red.h[i], nu)
        for j in range(m):
            for k in range(j, m):
                c = coeffs.get((j, k), sp.Integer(0))
                out[f"h[{i + 1}]:{nu[j]}*{nu[k]}"] = simplify_expr(c, pars) if c != 0 else c
    return out


def coordinate_set_key(cs: CoordinateSet) -> str:
    """A text that changes with anything of ``cs`` the closed forms depend on (not its name or
    description)."""
    def text(e):
        return sp.srepr(sp.sympify(e))
    parts = [cs.kind, cs.rolling, repr(cs.positions), repr(cs.velocities), repr(cs.parameters),
             repr(sorted((k, text(v)) for k, v in cs.configuration.items())),
             repr(None if cs.velocity_map is None else
                  sorted((k, text(v)) for k, v in cs.velocity_map.items()))]
    return "\x00".join(parts)
