r"""Equations that are combinations of the true ones: a Newton–Euler derivation's moment
balance about the centre of mass, with the joint's reaction eliminated by the force balance,
is Lagrange's equation of that coordinate minus a multiple of another's.

Row :math:`i` of such a document is :math:`\sum_k W_{ik}` × true row :math:`k`, with
:math:`W(q, p)` invertible: the two systems have the same solutions. Per sample,
:math:`W = A_{doc}A^{-1}`, and it must then carry every other part of the equations too:

.. math::

    h_{doc} = W h,\qquad Q_{doc} = W Q,\qquad B_{doc} = W B .

When it does at every sample of a grid of many parameter sets and :math:`W` is not diagonal
(a diagonal :math:`W` is a row divided by a function, :mod:`.row_functions`), each entry is
fitted as a constant, a monomial in the document's symbols, positions, sines and cosines, or a
short sum of such products (:func:`~..judge.fitting.fit_factor`, :func:`~..judge.fitting.fit_sum`).
The engine then compares the document's equations with the combination undone,
:math:`W^{-1}` × its rows, and keeps that reading when more elements agree
(:meth:`~.engine.ComparisonEngine._compare`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..grid.arrays import Arrays
from ..judge.fitting import fit_factor, fit_sum
from .row_functions import document_names, with_row_functions

#: Relative agreement of :math:`W h`, :math:`W Q`, :math:`W B` with the document's.
COMBINATION_TOL = 1e-8


def combination(doc: Arrays, truth: Arrays, B_true: np.ndarray | None) -> np.ndarray | None:
    r""":math:`W` per sample (samples × n × n) with the document's A, h, Q (and B) equal to
    :math:`W` times the truth's, when one exists and is not diagonal; else None."""
    A_doc, A_true = doc.A, truth.A
    h_doc, h_true, Q_doc, Q_true = doc.h, truth.h, doc.Q, truth.Q
    if A_doc is None or A_true is None or h_doc is None or h_true is None or Q_doc is None \
            or Q_true is None:
        return None
    parts = [(h_doc, h_true), (Q_doc, Q_true)]
    arrays = [A_doc, A_true, h_doc, h_true, Q_doc, Q_true]
    if not all(np.isfinite(a).all() for a in arrays):
        return None
    try:
        W = np.swapaxes(np.linalg.solve(np.swapaxes(A_true, 1, 2), np.swapaxes(A_doc, 1, 2)),
                        1, 2)                                        # W A = A_doc
    except np.linalg.LinAlgError:
        return None
    if doc.B is not None and B_true is not None:
        parts.append((doc.B, B_true))
    for D, T in parts:
        predicted = W @ T if T.ndim == 3 else np.einsum("nij,nj->ni", W, T)
        scale = max(float(np.abs(D).max()), float(np.abs(predicted).max()), 1e-300)
        if np.abs(predicted - D).max() > COMBINATION_TOL * scale:
            return None
    off = W.copy()
    idx = np.arange(W.shape[1])
    off[:, idx, idx] = 0.0
    if np.abs(off).max() <= COMBINATION_TOL * np.abs(W).max():
        return None                                  # rows scaled only: row_functions'
    return W


def fit_combination(W: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]
                    ) -> sp.Matrix | None:
    r"""The entries of :math:`W` (samples × n × n) as expressions of the ``bases``: zero, a
    monomial, or a short sum; None when one fits none of them."""
    n = W.shape[1]
    out = sp.zeros(n, n)
    scale = float(np.abs(W).max())
    for i in range(n):
        for k in range(n):
            entry = W[:, i, k]
            if np.abs(entry).max() <= COMBINATION_TOL * scale:
                continue
            found = fit_factor(entry, bases)
            if found is None:
                found = fit_sum(entry, bases)
            if found is None:
                return None
            out[i, k] = found
    return out


def separated(d: Derivation, W: sp.Matrix) -> Derivation | None:
    r"""``d`` with its equations (or matrices) multiplied by :math:`W^{-1}`: the true rows,
    if ``d``'s rows are :math:`W` times them; None for a file with lost elements or declared
    row scalings (not combined here)."""
    if d.row_scale is not None:
        return None
    M = W.inv().applyfunc(sp.cancel)
    if d.equations is not None:
        rows = [eq.lhs - eq.rhs for eq in d.equations]
        if any(r.has(sp.nan) for r in rows):
            return None
        return replace(d, equations=tuple(
            sp.Eq(sp.Add(*(M[i, k] * rows[k] for k in range(d.n) if M[i, k] != 0)), 0)
            for i in range(d.n)))
    mats = (d.A, d.C, d.Q, d.B)
    if any(m is not None and m.has(sp.nan) for m in mats):
        return None
    A, C, Q, B = (None if m is None else sp.ImmutableMatrix(M * m) for m in mats)
    return replace(d, A=A, C=C, Q=Q, B=B)


def as_text(W: sp.Matrix) -> tuple[tuple[str, ...], ...]:
    r""":math:`W` as rows of SymPy text (a result's ``row_combination``)."""
    return tuple(tuple(sp.sstr(W[i, k]) for k in range(W.cols)) for i in range(W.rows))


def undone(d: Derivation, texts: Sequence[Sequence[str]]) -> Derivation:
    r"""``d`` with the combination a result found (:func:`as_text`; none: ``d`` itself)
    undone, as it was compared."""
    if not texts:
        return d
    names = document_names(d)
    W = sp.Matrix([[sp.sympify(t, locals=names) for t in row] for row in texts])
    return separated(d, W) or d


def as_compared(d: Derivation, result) -> Derivation:
    r"""``d`` read as its comparison ``result`` read it: the functions its rows were divided
    by (:mod:`.row_functions`) and the combination of the true equations they are undone
    (for its own energies' consistency, its own simulation)."""
    return undone(with_row_functions(d, result.row_functions), result.row_combination)


def describe(W: sp.Matrix) -> str:
    r"""``"equation 2 = H*cos(theta)*eq1/2 - eq2 (eq k: the true equation k)"``."""
    eq = [sp.Symbol(f"eq{k + 1}") for k in range(W.cols)]
    parts = [f"equation {i + 1} = {sp.sstr(sum(W[i, k] * eq[k] for k in range(W.cols)))}"
             for i in range(W.rows) if any(W[i, k] != 0 for k in range(W.cols) if k != i)]
    return ", ".join(parts) + " (eq k: the true equation k)"


__all__ = ["COMBINATION_TOL", "as_compared", "as_text", "combination", "describe",
           "fit_combination", "separated", "undone"]
