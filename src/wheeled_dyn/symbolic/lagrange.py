r"""Lagrange's equations from the energies, in closed form (seed 001, §4.3).

For a kinetic energy quadratic in the velocities, :math:`E = \tfrac12\dot q^T A(q)\dot q`, and a
potential energy :math:`U(q)`, Lagrange's equations
:math:`\frac{d}{dt}\frac{\partial L}{\partial \dot q} - \frac{\partial L}{\partial q} = \Gamma`
with :math:`L = E - U` read :math:`A\ddot q + C\dot q + Q = \Gamma` with

.. math::
   A_{ij} = \frac{\partial^2 E}{\partial \dot q_i \partial \dot q_j}, \qquad
   Q_i = \frac{\partial U}{\partial q_i}, \qquad
   C_{ij} = \sum_k c_{i,jk}\,\dot q_k, \qquad
   c_{i,jk} = \tfrac12\left(\frac{\partial A_{ij}}{\partial q_k}
      + \frac{\partial A_{ik}}{\partial q_j} - \frac{\partial A_{jk}}{\partial q_i}\right),

and :math:`h = C\dot q`, :math:`\dot A = \sum_k \partial_k A\,\dot q_k`. Everything is computed
on :class:`~.trigpoly.TrigRing` elements (canonical trigonometric form), so it is exact and
fast; :func:`lagrange_terms` is independent of where the energies come from.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp
from sympy.polys.rings import PolyElement

from .trigpoly import TrigRing


@dataclass(frozen=True)
class LagrangeTerms:
    r"""Ring elements of :math:`A` (``A[i][j]``), :math:`\partial A/\partial q_k`
    (``dA[k][i][j]``), :math:`c_{i,jk}` (``c[i][j][k]``), :math:`h`, :math:`\dot A`,
    :math:`Q`, :math:`E`, :math:`U`; all in canonical form of ``ring``."""

    ring: TrigRing
    A: list[list[PolyElement]]
    dA: list[list[list[PolyElement]]]
    c: list[list[list[PolyElement]]]
    h: list[PolyElement]
    Adot: list[list[PolyElement]]
    Q: list[PolyElement]
    E: PolyElement
    U: PolyElement


def lagrange_terms(ring: TrigRing, E: PolyElement, U: PolyElement,
                   q: Sequence[sp.Symbol], qd: Sequence[sp.Symbol]) -> LagrangeTerms:
    r"""All closed-form terms from the energies :math:`E(q,\dot q)` (quadratic form in
    :math:`\dot q`) and :math:`U(q)`, given as elements of ``ring`` whose generators include
    the velocity symbols ``qd``."""
    n = len(q)
    zero = ring.ring.zero
    qdp = [ring.gen(x) for x in qd]
    dE = [E.diff(v) for v in qdp]
    A = [[zero] * n for _ in range(n)]
    for i in range(n):
        for j in range(i, n):
            A[i][j] = A[j][i] = ring.reduce(dE[i].diff(qdp[j]))
    dA = [[[zero] * n for _ in range(n)] for _ in range(n)]
    for k, qk in enumerate(q):
        for i in range(n):
            for j in range(i, n):
                dA[k][i][j] = dA[k][j][i] = ring.diff(A[i][j], qk)
    half = ring.ring.domain.convert(sp.Rational(1, 2))
    c = [[[zero] * n for _ in range(n)] for _ in range(n)]
    for i in range(n):
        for j in range(n):
            for k in range(j, n):
                c[i][j][k] = c[i][k][j] = (dA[k][i][j] + dA[j][i][k] - dA[i][j][k]) * half
    h = []
    for i in range(n):
        hi = zero
        for j in range(n):
            hi += sum((c[i][j][k] * qdp[k] for k in range(n)), zero) * qdp[j]
        h.append(ring.reduce(hi))
    Adot = [[sum((dA[k][i][j] * qdp[k] for k in range(n)), zero) for j in range(n)]
            for i in range(n)]
    Q = [ring.diff(U, qi) for qi in q]
    return LagrangeTerms(ring=ring, A=A, dA=dA, c=c, h=h, Adot=Adot, Q=Q,
                         E=ring.reduce(E), U=ring.reduce(U))


def energy_terms(E: sp.Expr, U: sp.Expr, q: Sequence[sp.Symbol], qd: Sequence[sp.Symbol]
                 ) -> LagrangeTerms:
    """:func:`lagrange_terms` of SymPy expressions (e.g. a document's own energies)."""
    ring, (Ep, Up) = TrigRing.from_exprs([E, U], extra=tuple(q) + tuple(qd))
    return lagrange_terms(ring, Ep, Up, q, qd)
