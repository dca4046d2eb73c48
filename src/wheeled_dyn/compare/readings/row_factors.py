r"""Constant row factors a document did not declare: Kane's generalised inertia forces
:math:`F^* = -(A\ddot q + h)` are the true rows times :math:`-1`.

A constant :math:`c_i` with document row i = :math:`c_i` × true row i is found by a vote of the
row's elements (:func:`row_factors`); the convention search (:mod:`.search`) scores its readings
with the rows divided by their factors. Whether an equation is right never depends on it
(:mod:`..judge.equivalence`); the frame an equation is explained in is chosen by
:mod:`.frames`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from ..grid.arrays import Arrays
from ..judge.diagnose import AGREE_TOL, agrees

#: Candidate undeclared row factors, and how far an element's own ratio may be from one.
ROW_FACTORS = (1.0, -1.0, 2.0, -2.0, 0.5, -0.5)
ROW_FACTOR_SPREAD = 0.35


def row_factors(doc: Arrays, truth: Arrays, B_true, n: int) -> list[float | None]:
    r"""A constant :math:`c_i` with document row i = :math:`c_i` × true row i that the file did
    not declare (e.g. −1 for Kane's generalised inertia forces :math:`F^* = -(A\ddot q + h)`).

    Each nonzero element of the row votes for the candidate of :data:`ROW_FACTORS` nearest its
    own least-squares ratio (within :data:`ROW_FACTOR_SPREAD`); a candidate other than 1 needs
    a strict majority among A's entries and among all of the row's (A, Q, B). Voting keeps a
    single wrong coefficient (e.g. 3(m_c + m_s)) from scaling a row."""
    votes_a, votes_all = row_votes(doc, truth, B_true, n)
    return [decided_factor(votes_a[i], votes_all[i], explaining(doc, truth, B_true, i))
            for i in range(n)]


def explaining(doc: Arrays, truth: Arrays, B_true, i: int) -> Callable[[float], bool]:
    r"""Whether dividing row ``i`` by a factor makes one of its elements agree."""
    return lambda f: explains(f, row_pairs(doc, truth, B_true, i))


def row_votes(doc: Arrays, truth: Arrays, B_true, n: int,
              fixed: tuple[np.ndarray, np.ndarray] | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    r"""The votes of :func:`row_factors`: A's entries' (rows × columns) and all of each row's
    (A's, Q's, B's; rows × entries). ``fixed``: the votes of A and of Q, known already (only
    B's are counted then)."""
    if fixed is None:
        votes_a = _votes(doc.A, truth.need("A")) if doc.A is not None else np.empty((n, 0))
        votes_q = _votes(doc.Q[:, :, None], truth.need("Q")[:, :, None]) if doc.Q is not None \
            else np.empty((n, 0))
    else:
        votes_a, votes_q = fixed
    parts = [votes_a, votes_q]
    if doc.B is not None and B_true is not None:
        parts.append(_votes(doc.B, B_true))
    return votes_a, np.concatenate(parts, axis=1)


def decided_factor(votes_a: np.ndarray, votes_all: np.ndarray,
                   explains: Callable[[float], bool]) -> float | None:
    r"""One row's factor from its votes (:func:`row_factors`): A's entries decide, Q and B only
    confirm (a wrong input map must not scale a row); ``explains(f)``: dividing by ``f``
    makes an element of the row agree."""
    row_a, row_all = votes_a[~np.isnan(votes_a)], votes_all[~np.isnan(votes_all)]
    winner = None
    for f in ROW_FACTORS:
        if f == 1.0 or not len(row_a):
            continue
        if np.count_nonzero(row_a == f) * 2 > len(row_a) and \
                np.count_nonzero(row_all == f) * 2 > len(row_all):
            winner = f
    return winner if winner is not None and explains(winner) else None


def row_pairs(doc: Arrays, truth: Arrays, B_true, i: int) -> list[tuple[np.ndarray, np.ndarray]]:
    r"""Row i's (document, truth) sample pairs: A's entries, Q, B's entries."""
    pairs = []
    if doc.A is not None:
        A_true = truth.need("A")
        pairs += [(doc.A[:, i, j], A_true[:, i, j]) for j in range(doc.A.shape[2])]
    if doc.Q is not None:
        pairs.append((doc.Q[:, i], truth.need("Q")[:, i]))
    if doc.B is not None and B_true is not None:
        pairs += [(doc.B[:, i, j], B_true[:, i, j]) for j in range(doc.B.shape[2])]
    return pairs


def _votes(D: np.ndarray, T: np.ndarray) -> np.ndarray:
    r"""The votes (:func:`row_factors`) of the entries of ``D`` against ``T`` (samples ×
    rows × entries): the candidate of :data:`ROW_FACTORS` nearest each entry's ratio
    :math:`D\cdot T / T\cdot T`, or ``inf`` (a vote for none) when none is within
    :data:`ROW_FACTOR_SPREAD`; NaN (no vote) for an entry not finite or with a zero side.
    Rows × entries."""
    with np.errstate(all="ignore"):
        finite = np.isfinite(D).all(axis=0) & np.isfinite(T).all(axis=0)
        tt, dd = np.einsum("nij,nij->ij", T, T), np.einsum("nij,nij->ij", D, D)
        c = np.einsum("nij,nij->ij", D, T) / tt
        best = _CANDIDATES[np.argmin(np.abs(c[..., None] - _CANDIDATES), axis=-1)]
        out = np.where(np.abs(c - best) <= ROW_FACTOR_SPREAD * np.abs(best), best, np.inf)
    return np.where(finite & (tt > 0) & (dd > 0), out, np.nan)


_CANDIDATES = np.array(ROW_FACTORS)


def explains(factor: float, pairs: Sequence[tuple[np.ndarray, np.ndarray]]) -> bool:
    r"""A row factor is only taken when dividing by it makes at least one nonzero element
    of the row agree exactly (near-ratios of elements that differ anyway explain nothing)."""
    finite = [(D, T) for D, T in pairs if np.isfinite(D).all() and np.isfinite(T).all()]
    if not finite:
        return False
    scale = max(max(float(np.abs(D).max()), float(np.abs(T).max())) for D, T in finite)
    return any(float(np.abs(T).max()) > AGREE_TOL * scale and agrees(D / factor, T, scale)
               for D, T in finite)


def apply_row_factors(doc: Arrays, factors) -> None:
    for i, c in enumerate(factors):
        if c is None:
            continue
        for name in ("A", "C", "Q", "B", "h", "H"):
            M = getattr(doc, name)
            if M is not None:
                M[:, i] = M[:, i] / c


def row_scales(doc: Arrays, truth: Arrays, n: int, truth_sizes: np.ndarray | None = None
               ) -> np.ndarray:
    r"""Each row's scale: the largest magnitude in its A, C, Q and H, document or truth (1
    for a row of zeros); ``truth_sizes``: :func:`row_sizes` of ``truth``, known already."""
    s = np.maximum(row_sizes(doc, n), row_sizes(truth, n) if truth_sizes is None
                   else truth_sizes)
    return np.where(s > 0, s, 1.0)


def row_sizes(arrays: Arrays, n: int) -> np.ndarray:
    r"""The largest magnitude in each row of ``arrays``' A, C, Q and H (0 where none)."""
    s = np.zeros(n)
    for name in ("A", "C", "Q", "H"):
        M = getattr(arrays, name)
        if M is not None:
            s = np.maximum(s, np.abs(M.reshape(M.shape[0], n, -1)).max(axis=(0, 2)))
    return s


__all__ = ["ROW_FACTORS", "ROW_FACTOR_SPREAD", "apply_row_factors", "decided_factor",
           "explaining", "explains", "row_factors", "row_pairs", "row_scales", "row_sizes",
           "row_votes"]
