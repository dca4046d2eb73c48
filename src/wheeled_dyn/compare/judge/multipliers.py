r"""The multipliers' terms of a form that keeps the rolling constraints,
:math:`A\ddot q + n = Bu + G^T\lambda` (:func:`~.equivalence.decide`): the true multipliers'
coefficients recombined for the document, whose multipliers may be any invertible mixing of
the true ones, and the document's own scaled to a largest coefficient of 1 (a multiplier is
an unknown: :math:`\lambda_k \to c\lambda_k` is the same document).
"""

from __future__ import annotations

import itertools

import numpy as np

from .diagnose import AGREE_TOL, FLOOR

#: Samples a subset of the equations is first fitted on (spread over the grid), and the
#: residual there above which it is not fitted on every sample: the fit is per sample, so a
#: subset that fails there by far fails on all (ten times AGREE_TOL: a margin for the screen's
#: scale, whose floor is taken from the document's whole grid but not from the fit's; the
#: four groups' reports and the multiplier tests are unchanged by the screening).
SCREEN_SAMPLES, SCREEN_TOL = 64, 10 * AGREE_TOL


def multiplier_terms(doc_L: np.ndarray, true_L: np.ndarray, W: np.ndarray) -> np.ndarray:
    r"""The true multipliers' coefficients recombined for the document (S × n × m_doc):
    :math:`G^T M` with :math:`M` the least-squares solution of :math:`W G^T M = G_{doc}^T`
    per sample. The multipliers are unknowns of the equations, so a document may name any
    invertible combination of the true ones (:math:`\lambda = M\lambda_{doc}`); its equation
    :math:`i` is then a combination of the true ones only if its coefficients of
    :math:`\lambda_{doc}` are row :math:`i` of :math:`W G^T M`. :math:`M` is fitted on every
    equation; where they do not all fit, on all but one, else all but two (as many as
    multipliers left at least): of the subsets that fit, the one whose mixing is nearest the
    one the document's constraint rows give (:math:`G_{doc} = PG`, :math:`M = P^T`) — a wrong
    equation does not make the right ones differ, nor a right one take the blame. Where not
    every equation fits and the document's multiplier terms are exactly the truth's mixed so
    (:math:`G^T P^T`), that mixing is taken: more equations wrong than can be left out (three
    of five) left every subset a wrong one's weights. NaN where a side is not finite."""
    if doc_L.shape == true_L.shape and not np.any(doc_L):
        return true_L.copy()        # no multipliers at all: none to mix, the terms must vanish
    out = np.full(doc_L.shape, np.nan)
    ok = (np.isfinite(W).all(axis=(1, 2)) & np.isfinite(true_L).all(axis=(1, 2))
          & np.isfinite(doc_L).all(axis=(1, 2)))
    if not ok.any():
        return out
    mixed, D = W[ok] @ true_L[ok], doc_L[ok]
    # as many equations left as independent multipliers (a robot's two wheels: four rows of
    # G of rank three; its four columns counted, two wrong equations of five were never left
    # out, and the three right ones were said to be no combination)
    n, m = D.shape[1], int(np.linalg.matrix_rank(true_L[ok][:10]).max())

    screen = np.unique(np.linspace(0, len(D) - 1, min(SCREEN_SAMPLES, len(D))).astype(int))

    def fit(left_out: tuple[int, ...], at: np.ndarray | None = None
            ) -> tuple[float, np.ndarray]:
        rows = [i for i in range(n) if i not in left_out]
        X, Y = (mixed[:, rows], D[:, rows]) if at is None else (mixed[at][:, rows],
                                                                 D[at][:, rows])
        M = np.linalg.pinv(X) @ Y
        fitted = X @ M
        scale = np.maximum(np.abs(Y).max(axis=2), np.abs(fitted).max(axis=2))
        floor = FLOOR * max(float(scale.max(initial=0.0)), float(np.abs(D[:, rows]).max()))
        off = np.abs(Y - fitted).max(axis=2) / np.maximum(np.maximum(scale, floor), 1e-300)
        return float(off.max(initial=0.0)), M

    # the mixing the document's own constraint rows give (G_doc = P G: M = Pᵀ)
    reference = np.linalg.pinv(true_L[ok]) @ D

    def distance(M: np.ndarray) -> float:
        # among the subsets that fit, the one closest to it (leaving out either of two may fit)
        return float(np.nanmean(np.abs(M - reference)))

    best = fit(())
    if best[0] > AGREE_TOL and float(np.abs(true_L[ok] @ reference - D).max(initial=0.0)) <= \
            AGREE_TOL * max(float(np.abs(D).max(initial=0.0)), 1e-300):
        # the document's multiplier terms are the truth's mixed as its constraint rows mix
        # them: that mixing, not one fitted on the equations' weights, where those do not all
        # fit (more equations wrong than can be left out: a right one was blamed for the
        # wrong ones' weights)
        best = (0.0, reference)
    for size in (1, 2):
        if best[0] <= AGREE_TOL or n - size < m:
            break
        # a subset that does not fit on the screening samples fits on none (a per-sample fit)
        fits = [f for f in (fit(c) for c in itertools.combinations(range(n), size)
                            if fit(c, screen)[0] <= SCREEN_TOL) if f[0] <= AGREE_TOL]
        if fits:
            best = min(fits, key=lambda f: distance(f[1]))
    M = best[1]
    out[ok] = true_L[ok] @ M
    return out


def multiplier_floor(doc_L: np.ndarray, mixed: np.ndarray) -> np.ndarray:
    r"""The least scale of a row's multiplier terms at each sample: :data:`FLOOR` of the
    largest finite coefficient of either side over every row and sample. The multipliers'
    coefficients are measured at their own size (a multiplier is an unknown, scaled at will:
    :func:`unit_multipliers`), not at the row's inertia's, which in other units could hide a
    wrong coefficient; the floor keeps the round-off of a row with no multiplier term from
    deciding."""
    with np.errstate(all="ignore"):
        size = max(float(np.abs(np.where(np.isfinite(x), x, 0.0)).max(initial=0.0))
                   for x in (doc_L, mixed))
    return np.full(len(doc_L), FLOOR * size)


def unit_multipliers(L: np.ndarray) -> np.ndarray:
    r"""The document's multipliers' coefficients (S × n × m) with each multiplier's column
    scaled to a largest finite magnitude of 1: :math:`\lambda_k` is an unknown of the
    equations, so :math:`\lambda_k \to c\lambda_k` is the same document (a constraint row
    written 1e8 times larger gave its multiplier's terms a round-off of 6e-7 of the row)."""
    size = np.abs(np.where(np.isfinite(L), L, 0.0)).max(axis=(0, 1))
    return L / np.where(size > 0, size, 1.0)


__all__ = ["multiplier_floor", "multiplier_terms", "unit_multipliers"]
