r"""The engine's evaluation of one derivation, with what the convention search needs
(:mod:`.conventions`): the document at sign-flipped states, and how many elements agree in a
set of arrays, on a subset of the samples.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from . import causes
from .diagnose import agrees
from .elements import apply_row_factors, element_values, row_factors, row_scales
from .evaluate import Arrays

#: Samples the convention search scores each reading on (spread over the parameter sets).
SEARCH_SAMPLES = 400


class SearchEvaluation(causes.Evaluation):
    r"""The engine's evaluation, with what the convention search needs: the document at
    sign-flipped states and the number of elements agreeing in a set of arrays."""

    def _subset(self) -> tuple[np.ndarray, Arrays, np.ndarray | None]:
        r"""The samples the search scores on: those where the truth has H (the first
        :data:`~.evaluate.H_SAMPLES` states of every parameter set), at most
        :data:`SEARCH_SAMPLES`; the truth and its B there."""
        if not hasattr(self, "_sub"):
            rows = self.truth.H_rows if self.truth.H_rows is not None \
                else np.arange(len(self.q))
            keep = np.arange(len(rows))
            if len(rows) > SEARCH_SAMPLES:
                keep = np.linspace(0, len(rows) - 1, SEARCH_SAMPLES).astype(int)
            rows = rows[keep]
            sub = Arrays(**{k: (None if getattr(self.truth, k) is None
                                else getattr(self.truth, k)[rows]) for k in "ACQBhG"})
            sub.H = None if self.truth.H is None else self.truth.H[keep]
            B = None if self.B_true is None else self.B_true[rows]
            self._sub = (rows, sub, B)
        return self._sub

    def doc_at(self, s: Sequence[int]) -> Arrays:
        r"""The document's arrays at :math:`(Sp, S\nu)` on the search's samples (rows not
        yet divided by factors)."""
        rows, _, _ = self._subset()
        S = np.asarray(s, float)
        values = {p: np.asarray(v)[rows] if np.ndim(v) else v for p, v in self.values.items()}
        return self.funcs.evaluate(self.q[rows] * S, self.nu[rows] * S, values)

    def score(self, doc: Arrays) -> int:
        r"""Elements of ``doc`` (on the search's samples) that agree with the truth, after
        its own row factors."""
        n = self.q.shape[1]
        _, truth, B_true = self._subset()
        factors = row_factors(doc, truth, B_true, n)
        apply_row_factors(doc, factors)
        scales = row_scales(doc, truth, n)
        return sum(bool(np.isfinite(D).all()) and agrees(D, T, scales[index[0]])
                   for _, D, T, index, _ in element_values(self.funcs, doc, truth, B_true, n,
                                                      expressions=False))


__all__ = ["SEARCH_SAMPLES", "SearchEvaluation"]
