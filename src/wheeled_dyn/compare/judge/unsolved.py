r"""Equations solved for the accelerations, read back before solving.

A document that writes :math:`\ddot q = M_{doc}^{-1}(B u - n_{doc})` (simulation code does),
or solves part of its equations, hides its inertia matrix in every element; an error in it (a
dropped inertia, a symbol for another in :math:`M_{doc}`) changes all of them. When the inputs
act on every coordinate (B square and invertible), the document's own inertia matrix, in the
true equations' frame, is read back from its inputs' coefficients: its equations
:math:`A_{doc}\ddot q + n_{doc} = B_{doc}u` are :math:`BB_{doc}^{-1}` times a system whose
inputs enter as the truth's, with the inertia matrix

.. math:: M_{doc} = B\,B_{doc}^{-1}A_{doc}

and compared with the truth's A element by element; a differing element is named in the
document's symbols (:mod:`.fitting`: "A[1,1] lacks I1"). This only explains: the equations'
verdicts are decided by their equivalence.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ..records import Diagnosis, DiagnosisKind as K
from .diagnose import AGREE_TOL
from .fitting import fit_factor, fit_sum


def _fit(residual: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]) -> sp.Expr | None:
    r"""Truth − document as a monomial, or a sum of two, in the document's names, or None."""
    found = None if np.abs(residual).min() <= 0 else fit_factor(residual, bases)
    return found if found is not None else fit_sum(residual, bases)


def _said(found: sp.Expr | None) -> str:
    return f"truth − document = {sp.sstr(found)}" if found is not None else "differs"


def solved_rows(doc_A: np.ndarray) -> dict[int, tuple[int, float]]:
    r"""The rows of the document's A with one constant nonzero entry: row → (the acceleration
    it is solved for, that entry)."""
    out = {}
    for i in range(doc_A.shape[1]):
        row = doc_A[:, i, :]
        size = np.abs(row).max(axis=0)
        nonzero = np.flatnonzero(size > 1e-12 * max(float(size.max(initial=0.0)), 1e-300))
        if len(nonzero) == 1 and np.ptp(row[:, nonzero[0]]) <= 1e-12 * size[nonzero[0]]:
            out[i] = (int(nonzero[0]), float(row[0, nonzero[0]]))
    return out


def implied_inertia(doc_B: np.ndarray, true_B: np.ndarray) -> np.ndarray | None:
    r""":math:`M_{doc} = B B_{doc}^{-1}` per sample, or None (B not square, or singular)."""
    if doc_B.shape[1] != doc_B.shape[2] or true_B.shape != doc_B.shape:
        return None
    if not (np.isfinite(doc_B).all() and np.isfinite(true_B).all()):
        return None
    if (np.abs(np.linalg.det(doc_B)) <= 1e-12 * np.abs(doc_B).max(axis=(1, 2)) ** doc_B.shape[1]
            ).any():
        return None
    return true_B @ np.linalg.inv(doc_B)


def inertia_diagnoses(doc_A: np.ndarray, doc_B: np.ndarray | None, true_A: np.ndarray,
                      true_B: np.ndarray | None,
                      bases: Sequence[tuple[sp.Expr, np.ndarray]]) -> Diagnosis | None:
    r"""The elements of the document's own inertia matrix (read back from its inputs,
    module text) that differ from the truth's, named; None when all agree or it cannot be
    read back."""
    n = doc_A.shape[1]
    if doc_B is None or true_B is None or not np.isfinite(doc_A).all():
        return None
    M = implied_inertia(doc_B, true_B)
    if M is None:
        return None
    M = M @ doc_A
    scale = float(np.abs(true_A).max())
    parts, terms = [], []
    for i in range(n):
        for j in range(n):
            residual = true_A[:, i, j] - M[:, i, j]
            if np.abs(residual).max() <= AGREE_TOL * scale:
                continue
            found = _fit(residual, bases)
            parts.append(f"A[{i + 1},{j + 1}] {_said(found)}")
            if found is not None:
                terms.append(sp.sstr(found))
    if not parts:
        return None
    return Diagnosis(K.MISSING, "the inertia matrix the document inverted (read back from its "
                     "inputs' coefficients, M = B B_doc⁻¹ A_doc) differs from the truth's: "
                     + "; ".join(parts), "; ".join(parts), terms=tuple(terms))


#: Most differing entries of the equations read back before solving for them to be named
#: (one term wrong in the source equations changes one or two; an inertia matrix the document
#: inverted wrong changes every one, and the true one does not undo it).
MAX_UNSOLVED = 3




def _undo(true_A: np.ndarray, doc_A: np.ndarray) -> np.ndarray | None:
    r""":math:`A A_{doc}^{-1}` per sample (the document's rows back to the true equations'
    frame), or None where the document's A is singular somewhere."""
    try:
        return true_A @ np.linalg.inv(doc_A)
    except np.linalg.LinAlgError:
        return None


def unsolved_terms(doc, truth, true_B: np.ndarray | None, velocities: Sequence[sp.Symbol],
                   bases: Sequence[tuple[sp.Expr, np.ndarray]]) -> Diagnosis | None:
    r"""A document solved for its accelerations (or its rows combined), read back before it
    was: its rows times :math:`AA_{doc}^{-1}` (``doc``, ``truth``: arrays on the same
    samples, A, Q, B and the products' tensor H on ``H_rows``). Where that undoes it — its
    inputs' coefficients are then the truth's — the few terms of the velocity products,
    gravity terms and inputs of the equations it solved that differ are named in its
    symbols (a sign in one h term changed all three solved rows, and none was named); where
    its inputs' coefficients differ too or more than :data:`MAX_UNSOLVED` entries do, the
    inertia it inverted is not the truth's and nothing is said here."""
    if doc.A is None or truth.A is None or not np.isfinite(doc.A).all():
        return None
    T = _undo(truth.A, doc.A)
    if T is None:
        return None
    n = doc.A.shape[1]
    parts: list[tuple[str, sp.Expr | None]] = []           # (where, truth − document)
    if doc.B is not None and true_B is not None:
        B = np.einsum("ski,sij->skj", T, doc.B)
        if np.abs(true_B - B).max() > AGREE_TOL * max(float(np.abs(true_B).max()), 1e-300):
            return None
    if doc.Q is not None and truth.Q is not None:
        Q = np.einsum("ski,si->sk", T, doc.Q)
        scale = float(np.abs(truth.Q).max())
        parts += [(f"Q[{k + 1}]", _fit(truth.Q[:, k] - Q[:, k], bases)) for k in range(n)
                  if np.abs(truth.Q[:, k] - Q[:, k]).max() > AGREE_TOL * scale]
    rows = truth.H_rows
    if doc.H is not None and truth.H is not None and rows is not None:
        H = np.einsum("ski,sijl->skjl", T[rows], doc.H)
        scale = float(np.abs(truth.H).max())
        at = [(e, v[rows]) for e, v in bases]
        for k in range(n):
            for j in range(n):
                for m in range(j, n):
                    off = (truth.H[:, k, j, m] - H[:, k, j, m]) * (1 if j == m else 2)
                    if np.abs(off).max() > AGREE_TOL * scale:
                        product = f"{velocities[j]}*{velocities[m]}"
                        parts.append((f"h[{k + 1}]:{product}", _fit(off, at)))
    if not parts or len(parts) > MAX_UNSOLVED:
        return None
    text = "; ".join(f"{where} {_said(found)}" for where, found in parts)
    return Diagnosis(K.MISSING, "read back before it was solved (its rows times A A_doc⁻¹: "
                     f"its inputs' coefficients are then the truth's), the equations differ: "
                     f"{text}", text, terms=tuple(sp.sstr(found) for _, found in parts
                                                 if found is not None))


__all__ = ["MAX_UNSOLVED", "implied_inertia", "inertia_diagnoses", "solved_rows",
           "unsolved_terms"]
