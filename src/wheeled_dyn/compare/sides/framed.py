r"""The truth brought into a document row's frame: for weights :math:`f_i` per sample
(S × n, which combination of the true equations the document's row :math:`i` is), the row
:math:`f_i\,[A \mid C \mid Q \mid h \mid B \mid H \mid \Gamma]` of the truth, shaped as one row of
the document's arrays, and the row's scale."""

from __future__ import annotations

import numpy as np

from ..grid.arrays import Arrays


def framed(w: np.ndarray, truth: Arrays, B_true: np.ndarray | None, full: bool = True
           ) -> Arrays:
    r"""The truth brought into the frame: one row (S × 1 × ...) of A, C, Q, h, B (as
    ``Arrays.B``), K and H (on the truth's ``H_rows``); with ``full`` also h and
    :math:`\Gamma` (not needed to score a frame)."""
    out = Arrays(H_rows=truth.H_rows)
    with np.errstate(all="ignore"):
        for name in ("A", "C", "K"):
            M = getattr(truth, name)
            if M is not None:
                setattr(out, name, np.einsum("sl,slj->sj", w, M)[:, None, :])
        for name in ("Q", "h") if full else ("Q",):
            M = getattr(truth, name)
            if M is not None:
                setattr(out, name, np.einsum("sl,sl->s", w, M)[:, None])
        if B_true is not None:
            out.B = np.einsum("sl,slj->sj", w, B_true)[:, None, :]
        if truth.H is not None:
            rows = truth.H_rows if truth.H_rows is not None else np.arange(len(w))
            out.H = np.einsum("sl,sljk->sjk", w[rows], truth.H)[:, None, :, :]
        if truth.Gamma is not None and full:
            rows = truth.H_rows if truth.H_rows is not None else np.arange(len(w))
            out.Gamma = np.einsum("sl,sljk->sjk", w[rows], truth.Gamma)[:, None, :, :]
    return out


def row_of(doc: Arrays, i: int) -> Arrays:
    r"""Row ``i`` of the document's arrays, shaped as :func:`framed`'s."""
    out = Arrays(H_rows=doc.H_rows)
    for name in ("A", "C", "Q", "h", "B", "H", "Gamma", "K"):
        M = getattr(doc, name)
        if M is not None:
            setattr(out, name, M[:, i:i + 1])
    return out


def row_scale(doc_row: Arrays, true_row: Arrays, doc_size: float | None = None) -> float:
    r"""The row's scale: the largest magnitude of its A, C, Q and H entries on either side
    among the entries finite at every sample (1 for a row of zeros). An entry that overflows
    somewhere never sets it, not even where it is finite: a term of 1e299 there would make
    every other element of its row agree whatever it is. ``doc_size``: the document's side's
    :func:`side_size`, where it was found before (a row scored in many frames)."""
    s = max(side_size(doc_row) if doc_size is None else doc_size, side_size(true_row))
    return s if s > 0 else 1.0


def side_size(row: Arrays) -> float:
    r"""One side's part of :func:`row_scale` (0 for a row of zeros)."""
    s = 0.0
    for name in ("A", "C", "Q", "H"):
        M = getattr(row, name)
        if M is not None and M.size:
            entries = np.abs(M).reshape(M.shape[0], -1)
            finite = np.isfinite(entries).all(axis=0)
            if finite.any():
                s = max(s, float(entries[:, finite].max()))
    return s


__all__ = ["framed", "row_of", "row_scale", "side_size"]
