r"""Angles measured from another link: a document's position read as a sum of the file's.

A double pendulum derived in absolute angles (each link's from the vertical) while the file's
map takes the model's relative joint angles (the second link's from the first), or the
reverse, differs from the truth in nearly every element for one reason. With the file's
positions :math:`p = Lp'` and :math:`L = I + c\,e_ke_j^T` (:math:`c = \pm1`: the document's
:math:`p'_k` is the file's :math:`p_k - c\,p_j`), the document's equations in :math:`p'` are
those of :math:`p` once multiplied by :math:`L^{-T}` (generalised forces transform with the
Jacobian :math:`\partial p/\partial p' = L`), its accelerations :math:`\ddot p' = L^{-1}\ddot
p`:

.. math::

    A = L^{-T}A'L^{-1},\quad C = L^{-T}C'L^{-1},\quad h = L^{-T}h',\quad Q = L^{-T}Q',\quad
    B = L^{-T}B',

with the document evaluated at :math:`p' = L^{-1}p,\ \nu' = L^{-1}\nu` — the sign readings of
:mod:`.signs` are the case :math:`L = \mathrm{diag}(s)`. Whether an equation is a combination
of the true ones does not change under :math:`L^{-T}` (an invertible combination); the
elements are scored in the file's positions, where the truth is.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ..grid.arrays import Arrays

#: A position read as a sum: ``(k, j, c)`` for :math:`p_k \to p_k + c\,p_j` in the file's map.
Sum = tuple[int, int, int]


def sum_matrix(n: int, sums: Sequence[Sum]) -> np.ndarray:
    r""":math:`L` of the module text (n × n): the file's positions from the document's."""
    L = np.eye(n)
    for k, j, c in sums:
        L[k, j] += c
    return L


def document_state(q: np.ndarray, nu: np.ndarray, sums: Sequence[Sum]
                   ) -> tuple[np.ndarray, np.ndarray]:
    r"""The document's positions and velocities :math:`(L^{-1}p, L^{-1}\nu)` at the file's
    (samples × n each)."""
    inverse = np.linalg.inv(sum_matrix(q.shape[1], sums))
    return q @ inverse.T, nu @ inverse.T


def sum_arrays(doc: Arrays, sums: Sequence[Sum]) -> Arrays:
    r"""The document's arrays (evaluated at :func:`document_state`) as equations of the
    file's positions: the module's formulas."""
    n = next(x.shape[1] for x in (doc.A, doc.Q, doc.h, doc.C, doc.B) if x is not None)
    Li = np.linalg.inv(sum_matrix(n, sums))
    with np.errstate(all="ignore"):      # a term not finite somewhere stays so: undecided
        return _combined(doc, Li)


def _combined(doc: Arrays, Li: np.ndarray) -> Arrays:
    out = Arrays(H_rows=doc.H_rows)
    Lt = Li.T
    if doc.A is not None:
        out.A = Lt @ doc.A @ Li
    if doc.C is not None:
        out.C = Lt @ doc.C @ Li
    if doc.Q is not None:
        out.Q = doc.Q @ Li
    if doc.B is not None:
        out.B = Lt @ doc.B
    if doc.h is not None:
        out.h = doc.h @ Li
    if doc.H is not None:                  # H'_abc = Li_ia H_ijk Li_jb Li_kc, one axis at a time
        H = np.tensordot(doc.H, Li, axes=([1], [0]))        # (s, j, k, a)
        H = np.tensordot(H, Li, axes=([1], [0]))             # (s, k, a, b)
        H = np.tensordot(H, Li, axes=([1], [0]))             # (s, a, b, c)
        out.H = H
    if doc.G is not None:
        out.G = doc.G @ Li
    return out


def rates_of_positions(positions: Sequence[sp.Symbol], velocities: Sequence[sp.Symbol],
                       configuration: dict, velocity_map: dict) -> bool:
    r"""Whether each of a file's velocities is the rate of its position: with the model
    coordinates :math:`c = F(p)` its ``configuration`` gives, the ``velocity_map``
    :math:`\nu_k = G_k(c, \dot c)` is :math:`\dot p_k` once :math:`\dot c = (\partial F/
    \partial p)\,\nu` (wheel angles and a pitch with rolling eliminated: their rates, though
    x and y are not functions of them); False where a velocity takes the rate of a coordinate
    the configuration does not give (:math:`v = \cos\psi\,\dot x_0 + \dots`: a
    quasi-velocity). Read so, a position read as a sum, :math:`p = Lp'`, has the velocities
    :math:`\nu' = L^{-1}\nu` (:func:`sum_velocity_map`)."""
    plain = {str(x): sp.Symbol(str(x)) for x in (*positions, *velocities)}

    def bare(e) -> sp.Expr:
        e = sp.sympify(e)
        return e.xreplace({x: sp.Symbol(str(x)) for x in e.free_symbols})
    config = {name: bare(e) for name, e in configuration.items()}
    rates = {"d" + name: sum((sp.diff(e, plain[str(p)]) * plain[str(v)]
                              for p, v in zip(positions, velocities)), sp.Integer(0))
             for name, e in config.items()}
    for v in velocities:
        G = bare(velocity_map.get(str(v), sp.nan))
        if G.has(sp.nan):
            return False
        free = {str(x) for x in G.free_symbols}
        if any(n.startswith("d") and n not in rates and n not in plain for n in free):
            return False                  # the rate of a coordinate no position gives
        got = G.xreplace({sp.Symbol(n): rates[n] for n in free if n in rates})
        got = got.xreplace({sp.Symbol(n): config[n] for n in free if n in config})
        if sp.expand(got - plain[str(v)]) != 0:      # linear maps: exact (else no rate)
            return False
    return True


def sum_velocity_map(velocities: Sequence[object], velocity_map: dict, n: int,
                     sums: Sequence[Sum]) -> dict:
    r"""The ``velocity_map`` of velocities that are their positions' rates
    (:func:`rates_of_positions`) with the positions read as the ``sums``: :math:`\nu' =
    L^{-1}\nu`, each velocity the same combination of the file's maps."""
    inverse = sp.Matrix(n, n, lambda i, j: sp.Integer(int(i == j)))
    for k, j, c in sums:
        inverse[k, j] += c
    inverse = inverse.inv()
    G = [sp.sympify(velocity_map[str(v)]) for v in velocities]
    return {str(v): sp.Add(*(inverse[k, m] * G[m] for m in range(n) if inverse[k, m] != 0))
            for k, v in enumerate(velocities)}


def describe_sums(positions: Sequence[object], sums: Sequence[Sum]) -> list[str]:
    r"""``["q2 → q2 − q1", "q3 → q3 + q1 + q2"]``: each position read as a sum, in the
    document's symbols."""
    by: dict[int, list[str]] = {}
    for k, j, c in sums:
        by.setdefault(k, []).append(f"{'+' if c > 0 else '−'} {positions[j]}")
    return [f"{positions[k]} → {positions[k]} " + " ".join(terms) for k, terms in by.items()]


__all__ = ["Sum", "describe_sums", "document_state", "rates_of_positions", "sum_arrays",
           "sum_matrix", "sum_velocity_map"]
