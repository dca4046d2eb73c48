r"""How far a comparison can see. Into a combination of the true equations: a row
:math:`w\,[A\;n\;B]` is compared to a tolerance relative to its largest part, so where its
parts :math:`|w_l|\,\|T_l\|` differ in size by more than the tolerance's inverse, a difference
in the smaller one — even as large as it — is not seen (:func:`combination_span`;
:func:`~.equivalence.decide_row` leaves such a row undecided). Into the truth itself: Pinocchio
computes every body's terms in one frame, so each true row carries the round-off of the
largest, :math:`\rho_s = c\,\epsilon \max_l \max(\|A_l\|, |n_l|)` at sample :math:`s`, and
the row :math:`w\,T` carries :math:`\rho_s \sum_l |w_l|` (:func:`round_off`): a difference no
larger than that is not seen either (a link of 10⁷ m beside one of 0.8 m: the elbow's
equation carried 0.04 of round-off, 2e-7 of its size, and a right file differed).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..records import Diagnosis, DiagnosisKind, diagnosis
from .diagnose import AGREE_TOL

#: A combination whose smallest present part is below this share of its largest at every
#: sample cannot be checked in that part: the relative tolerance is AGREE_TOL of the largest.
PRECISION_SHARE = AGREE_TOL
#: Parts below this share of the largest are absent (a weight zero but for round-off).
ABSENT_SHARE = 1e-13
#: The truth's round-off, in machine epsilons of the largest of its rows' inertia, velocity
#: and gravity terms at a sample (c above; measured: 0.5 in the case that motivated it).
ROUND_OFF_EPS = 32


def row_sizes(A: np.ndarray, others: Sequence[np.ndarray | None]) -> np.ndarray:
    r""":math:`\|T_l\|` per sample and true row (S × n): the largest magnitude of row l of
    ``A`` and of the ``others`` (n: S × n, B: S × n × k)."""
    sizes = np.abs(A).max(axis=2)
    for T in others:
        if T is not None:
            sizes = np.maximum(sizes, np.abs(T if T.ndim == 3 else T[:, :, None]).max(axis=2))
    return sizes


def combination_span(w: np.ndarray, sizes: np.ndarray, finite: np.ndarray) -> float | None:
    r"""The ratio of the largest to the smallest present part :math:`|w_{il}|\,\|T_l\|` of
    a row's combination :math:`w` (S × n; :math:`\|T_l\|` in ``sizes``, :func:`row_sizes`)
    at the sample where that ratio is least, where it exceeds
    1/:data:`PRECISION_SHARE` even there (eq1 + 10¹⁰ eq2 with a term of eq1 missing agreed:
    the term is 1e-10 of the row); else None."""
    if not finite.any():
        return None
    with np.errstate(all="ignore"):
        parts = (np.abs(w) * sizes)[finite]
        largest = parts.max(axis=1)
        present = parts > ABSENT_SHARE * largest[:, None]
        least = np.where(present, parts, np.inf).min(axis=1) / np.maximum(largest, 1e-300)
    share = float(least.max())
    return 1.0 / share if 0.0 < share < PRECISION_SHARE else None


def largest_terms(A: np.ndarray, n: np.ndarray | None) -> np.ndarray:
    r"""Per sample, the largest magnitude of the true inertia, velocity and gravity terms
    (S): what the truth's round-off is relative to (module text)."""
    return row_sizes(A, (n,)).max(axis=1)


def round_off(w: np.ndarray, A: np.ndarray | None, n: np.ndarray | None,
              largest: np.ndarray | None = None) -> np.ndarray:
    r"""The truth's round-off in the row :math:`w\,T` per sample (module text): ``w`` the
    row's weights (S × n), ``A`` (S × n × n) and ``n`` (S × n) the true terms, or their
    :func:`largest_terms` made once. NaN where they are not finite; 0 without A (nothing
    computed by Pinocchio to round)."""
    if largest is None and A is None:
        return np.zeros(len(w))
    if largest is None:
        assert A is not None
        largest = largest_terms(A, n)
    with np.errstate(all="ignore"):
        return ROUND_OFF_EPS * float(np.finfo(float).eps) * largest * np.abs(w).sum(axis=1)


def row_round_off(w: np.ndarray, largest: np.ndarray) -> float:
    r"""The largest finite :func:`round_off` of the row of weights ``w`` over the samples (0
    where none is finite), the truth's :func:`largest_terms` given: an element of the row
    that differs by no more is not decided."""
    rho = round_off(w, None, None, largest)
    rho = rho[np.isfinite(rho)]
    return float(rho.max(initial=0.0))


def within_round_off(residuals: Sequence[np.ndarray], scales: Sequence[np.ndarray | None],
                     rho: np.ndarray, finite: np.ndarray) -> bool:
    r"""Whether every part's residual (relative to its ``scales``, per sample) is within the
    truth's round-off ``rho`` (:func:`round_off`) at every ``finite`` sample where it is over
    the tolerance; a part without a scale (the multipliers' terms, exact geometry) must be
    within the tolerance."""
    with np.errstate(all="ignore"):
        return all(bool((r[finite] <= np.maximum(AGREE_TOL, 0.0 if s is None else
                                                  np.nan_to_num(rho / s)[finite])).all())
                   for r, s in zip(residuals, scales))


def round_off_diagnosis(i: int, worst: float) -> Diagnosis:
    r"""Why equation ``i`` (0-based) is undecided: its difference from a combination of the
    true equations, ``worst`` of the row's size at most, is within the truth's round-off."""
    return diagnosis(
        DiagnosisKind.UNDECIDED, f"equation {i + 1} differs from a combination of the true "
        f"equations by at most {worst:.2g} of the row's size, within the truth's own "
        "round-off there (Pinocchio computes every body's terms in one frame, so this row "
        "carries the round-off of the model's largest terms): it cannot be decided")


__all__ = ["ABSENT_SHARE", "PRECISION_SHARE", "ROUND_OFF_EPS", "combination_span", "largest_terms",
           "round_off", "row_round_off", "round_off_diagnosis", "row_sizes",
           "within_round_off"]
