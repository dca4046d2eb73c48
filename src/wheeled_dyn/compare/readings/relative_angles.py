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


def describe_sums(positions: Sequence[object], sums: Sequence[Sum]) -> list[str]:
    r"""``["q2 → q2 − q1", "q3 → q3 + q1 + q2"]``: each position read as a sum, in the
    document's symbols."""
    by: dict[int, list[str]] = {}
    for k, j, c in sums:
        by.setdefault(k, []).append(f"{'+' if c > 0 else '−'} {positions[j]}")
    return [f"{positions[k]} → {positions[k]} " + " ".join(terms) for k, terms in by.items()]


__all__ = ["Sum", "describe_sums", "document_state", "sum_arrays", "sum_matrix"]
