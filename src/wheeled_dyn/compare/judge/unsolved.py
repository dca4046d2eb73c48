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
            found = None if np.abs(residual).min() <= 0 else fit_factor(residual, bases)
            found = found if found is not None else fit_sum(residual, bases)
            what = f"truth − document = {sp.sstr(found)}" if found is not None else "differs"
            parts.append(f"A[{i + 1},{j + 1}] {what}")
            if found is not None:
                terms.append(sp.sstr(found))
    if not parts:
        return None
    return Diagnosis(K.MISSING, "the inertia matrix the document inverted (read back from its "
                     "inputs' coefficients, M = B B_doc⁻¹ A_doc) differs from the truth's: "
                     + "; ".join(parts), "; ".join(parts), terms=tuple(terms))


__all__ = ["implied_inertia", "inertia_diagnoses", "solved_rows"]
