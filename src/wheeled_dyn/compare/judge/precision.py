r"""How far a comparison can see into a combination of the true equations: a row
:math:`w\,[A\;n\;B]` is compared to a tolerance relative to its largest part, so where its
parts :math:`|w_l|\,\|T_l\|` differ in size by more than the tolerance's inverse, a difference
in the smaller one — even as large as it — is not seen (:func:`combination_span`;
:func:`~.equivalence.decide_row` leaves such a row undecided).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .diagnose import AGREE_TOL

#: A combination whose smallest present part is below this share of its largest at every
#: sample cannot be checked in that part: the relative tolerance is AGREE_TOL of the largest.
PRECISION_SHARE = AGREE_TOL
#: Parts below this share of the largest are absent (a weight zero but for round-off).
ABSENT_SHARE = 1e-13


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


__all__ = ["ABSENT_SHARE", "PRECISION_SHARE", "combination_span", "row_sizes"]
