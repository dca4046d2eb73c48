r"""Equations solved for the accelerations by Cramer's rule with a wrong determinant: every
element of every solved row is the truth's in that frame times one function of the state and
parameters.

A document that writes :math:`\ddot q = \operatorname{adj}(M)\,f / \Delta` with
:math:`\Delta \ne \det M` (a term of the determinant dropped, a sign) has every solved
element :math:`k = \det M / \Delta` times the truth, the same :math:`k` at each sample for
all of them, and no single term of any element is wrong: the step of solving is. Where the
differing elements of at least two solved rows share one such :math:`k` (at every sample,
to the comparison's tolerance), and :math:`k` is no constant (a constant is a row's factor,
read by the frames), this names it on each (:data:`~..records.DiagnosisKind.COMMON_DIVISOR`).
An explanation only: the equations' verdicts are decided by their equivalence.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..records import Diagnosis, DiagnosisKind as K, Verdict, diagnosis
from .diagnose import AGREE_TOL
from .draft import ElementDraft

#: Least share of its largest a truth's value must have at every sample for the ratio of an
#: element to it to be read there.
NONZERO = 1e-9


def common_divisor(drafts: Sequence[ElementDraft], rows: set[int],
                   h_rows: np.ndarray | None = None) -> Diagnosis | None:
    r"""The diagnosis of module text for the differing elements of ``rows`` (the rows the
    frames show solved), or None where their ratios to the truth are not one function. The
    elements of h are on the samples ``h_rows`` of the others' (where those are fewer): each
    ratio is compared with the one function there."""
    differing = [d for d in drafts if d.row in rows and d.verdict == Verdict.DIFFERS]
    if len({d.row for d in differing}) < 2:
        return None
    ratios = []
    for d in differing:
        D, T = np.asarray(d.D, float), np.asarray(d.T, float)
        if D.shape != T.shape or D.ndim != 1 or not (np.isfinite(D).all()
                                                      and np.isfinite(T).all()):
            return None
        if not (np.abs(T) > NONZERO * max(float(np.abs(T).max(initial=0.0)), 1e-300)).all():
            return None                 # the truth is 0 somewhere: no ratio to read there
        ratios.append(D / T)
    size = max(len(r) for r in ratios)
    full = [r for r in ratios if len(r) == size]
    k = np.median(np.stack(full), axis=0)
    for r in ratios:
        at = k if len(r) == size else k[h_rows] if h_rows is not None and \
            len(h_rows) == len(r) else None
        if at is None or np.abs(r - at).max() > AGREE_TOL * np.abs(at).max():
            return None
    if np.ptp(k) <= AGREE_TOL * np.abs(k).max():
        return None                     # a constant: a factor of the rows
    if not _all_divided(drafts, rows, k, h_rows):
        return None
    solved = ", ".join(str(i + 1) for i in sorted({d.row for d in differing}))
    return divisor_diagnosis(k, f"every differing element of the solved equations {solved} "
                                "is the truth's")


def _all_divided(drafts: Sequence[ElementDraft], rows: set[int], k: np.ndarray,
                 h_rows: np.ndarray | None) -> bool:
    r"""Whether every element of the solved rows but the accelerations' coefficients (A: the
    solved form's identity, divided by nothing) is the truth's times :math:`k`, those that
    agree too: a wrong divisor divides them all, so one column wrong (a stiffness written
    wrong before solving: :math:`k` a function of the parameters at a linearisation point)
    is no divisor's."""
    for d in drafts:
        if d.row not in rows or d.key == "A":
            continue
        D, T = np.asarray(d.D, float), np.asarray(d.T, float)
        at = k if len(T) == len(k) else k[h_rows] if h_rows is not None and \
            len(h_rows) == len(T) else None
        if at is None or D.shape != T.shape:
            return False
        if np.abs(D - at * T).max(initial=0.0) > AGREE_TOL * max(d.scale, 1e-300) * \
                max(1.0, float(np.abs(at).max())):
            return False
    return True


def function_factor(M: np.ndarray, A: np.ndarray) -> np.ndarray | None:
    r"""The function :math:`k` (one value per sample) with ``M`` = :math:`k` ``A`` entry by
    entry (samples × n × n: an inertia matrix read back, and the truth's), where it is no
    constant; else None."""
    scale = np.abs(A).max(axis=(1, 2), keepdims=True)
    big = np.abs(A) > NONZERO * np.maximum(scale, 1e-300)
    if not (np.isfinite(M).all() and np.isfinite(A).all()) or not big.any(axis=(1, 2)).all():
        return None
    with np.errstate(all="ignore"):
        ratio = np.where(big, M / np.where(big, A, 1.0), np.nan)
    k = np.nanmedian(ratio.reshape(len(M), -1), axis=1)
    if np.abs(M - k[:, None, None] * A).max() > AGREE_TOL * float(np.abs(M).max()):
        return None
    return None if np.ptp(k) <= AGREE_TOL * np.abs(k).max() else k


def divisor_diagnosis(k: np.ndarray, what: str) -> Diagnosis:
    r"""The :data:`~..records.DiagnosisKind.COMMON_DIVISOR` diagnosis: ``what`` is the truth's
    times the function ``k``."""
    return diagnosis(
        K.COMMON_DIVISOR, f"{what} times one function of the state, the same for all (its "
        f"value from {float(k.min()):.3g} to {float(k.max()):.3g} over the samples): the "
        "divisor the solved equations share — the determinant of the inertia matrix they were "
        "solved with — differs from the true one; no term of the elements is wrong by itself",
        prefix="common divisor")


__all__ = ["NONZERO", "common_divisor", "divisor_diagnosis", "function_factor"]
