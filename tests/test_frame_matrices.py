r"""The combination frames' weights (:func:`wheeled_dyn.compare.readings.frames.combination_weights`)
against a direct solution, per row, with the matrices the rows share remembered: the weights
follow the truth's arrays when they are replaced (a grid's truth read under an assumption is
new arrays), a singular sample is NaN whichever row asked first, and the main grid's
matrices are kept while the small screens' come and go."""

from __future__ import annotations

import numpy as np
import pytest

from wheeled_dyn.compare.grid.arrays import Arrays
from wheeled_dyn.compare.readings import frames
from wheeled_dyn.compare.readings.frames import (MATRICES_FROM, FrameKind, FrameRule,
                                                 combination_weights)

#: Agreement of two solutions of the same small systems (condition numbers below 1e3 here).
TOL = 1e-10
#: Samples: enough for the matrices to be remembered.
S, N = MATRICES_FROM, 3


def _spd(rng: np.random.Generator) -> np.ndarray:
    X = rng.normal(size=(S, N, N))
    return X @ np.swapaxes(X, 1, 2) + N * np.eye(N)


def _sides(seed: int) -> tuple[Arrays, Arrays, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    truth = Arrays(A=_spd(rng), h=rng.normal(size=(S, N)), Q=rng.normal(size=(S, N)))
    doc = Arrays(A=rng.normal(size=(S, N, N)), h=rng.normal(size=(S, N)),
                 Q=rng.normal(size=(S, N)))
    return doc, truth, rng.normal(size=(S, N, 2)), rng.normal(size=(S, N, 2))


@pytest.mark.parametrize("i", range(N))
def test_weights_solve_each_row(i: int) -> None:
    doc, truth, B_doc, B_true = _sides(1)
    w = combination_weights(i, FrameRule(FrameKind.COMBINATION), doc, truth, B_doc, B_true)
    direct = np.linalg.solve(np.swapaxes(truth.A, 1, 2), doc.A[:, i, :][:, :, None])[..., 0]
    assert np.abs(w - direct).max() <= TOL * np.abs(direct).max()


@pytest.mark.parametrize("variant", [(0, -1), (2, -1), (1, 0), (2, 1)])
def test_variant_weights_fit_their_matrix(variant: tuple[int, int]) -> None:
    r""":math:`w M = rhs` with column j of A replaced by h + Q (c < 0) or by input column c,
    and the document's row likewise, for every row in turn (the rows share M)."""
    doc, truth, B_doc, B_true = _sides(2)
    j, c = variant
    for i in range(N):
        rule = FrameRule(FrameKind.COMBINATION, variant=variant)
        w = combination_weights(i, rule, doc, truth, B_doc, B_true)
        M = truth.A.copy()
        M[:, :, j] = truth.h + truth.Q if c < 0 else B_true[:, :, c]
        rhs = doc.A[:, i, :].copy()
        rhs[:, j] = doc.h[:, i] + doc.Q[:, i] if c < 0 else B_doc[:, i, c]
        assert np.abs(np.einsum("sk,skl->sl", w, M) - rhs).max() <= TOL * np.abs(rhs).max()


def test_weights_follow_replaced_truth() -> None:
    r"""The same rule asked again after the truth's A (and h) are replaced by new arrays gives
    the new truth's weights, not the remembered matrix's."""
    doc, truth, B_doc, B_true = _sides(3)
    rule = FrameRule(FrameKind.COMBINATION)
    first = combination_weights(0, rule, doc, truth, B_doc, B_true)
    truth.A = 2.0 * truth.A
    again = combination_weights(0, rule, doc, truth, B_doc, B_true)
    assert np.abs(again - first / 2.0).max() <= TOL * np.abs(first).max()
    variant = FrameRule(FrameKind.COMBINATION, variant=(1, -1))
    before = combination_weights(2, variant, doc, truth, B_doc, B_true)
    truth.h = truth.h + 1.0
    after = combination_weights(2, variant, doc, truth, B_doc, B_true)
    assert np.abs(after - before).max() > 1e-3


def test_singular_samples_are_nan_for_every_row() -> None:
    doc, truth, B_doc, B_true = _sides(4)
    truth.A = truth.A.copy()
    truth.A[5] = 0.0                      # singular at sample 5
    truth.A[7, 0, 0] = np.inf             # not finite at sample 7
    rule = FrameRule(FrameKind.COMBINATION)
    for i in range(N):
        w = combination_weights(i, rule, doc, truth, B_doc, B_true)
        assert np.isnan(w[5]).all() and np.isnan(w[7]).all()
        assert np.isfinite(np.delete(w, [5, 7], axis=0)).all()


def test_main_matrices_kept_between_screens(monkeypatch: pytest.MonkeyPatch) -> None:
    r"""Every variant of the main grid asked again after a round of small screens (fewer
    samples than :data:`MATRICES_FROM`, new arrays each) is found, not made again: its
    determinants are taken once."""
    doc, truth, B_doc, B_true = _sides(5)
    made: list[int] = []
    real = frames.relative_det
    monkeypatch.setattr(frames, "relative_det", lambda M: made.append(len(M)) or real(M))
    variants = [None, *((j, c) for j in range(N) for c in (-1, 0, 1))]
    rules = [FrameRule(FrameKind.COMBINATION, variant=v) for v in variants]
    for i in range(N):
        for rule in rules:
            combination_weights(i, rule, doc, truth, B_doc, B_true)
            for k in range(3):             # three screens on 32 samples each
                part = slice(32 * k, 32 * (k + 1))
                small = Arrays(A=truth.A[part].copy(), h=truth.h[part].copy(),
                               Q=truth.Q[part].copy())
                combination_weights(i, rule, Arrays(A=doc.A[part], h=doc.h[part],
                                                    Q=doc.Q[part]),
                                    small, B_doc[part], B_true[part].copy())
    assert sum(m == S for m in made) == len(variants)
