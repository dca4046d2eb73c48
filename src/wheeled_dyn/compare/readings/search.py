r"""The engine's evaluation of one derivation, with what the convention search needs
(:mod:`.conventions`): the document at sign-flipped states, and how many of its equations
are combinations of the true ones and how many elements agree in a set of arrays, on a
subset of the samples — an equation made right counting more than every element (a form
solved for the accelerations has no element that agrees under any reading; its inputs
exchanged or a position's sign reversed make its equations right).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from ..sides.evaluation import Evaluation
from ..judge.diagnose import AGREE_TOL
from ..judge.equivalence import Side, combination_rows, decide_row
from ..judge.precision import largest_terms, row_sizes as row_sizes_of
from ..records import Verdict
from .relative_angles import Sum, document_state, sum_arrays
from .signs import flip_arrays
from .row_factors import (apply_row_factors, decided_factor, explaining, row_factors,
                          row_scales, row_sizes, row_votes)
from ..grid.arrays import Arrays

#: Samples the convention search scores each reading on (spread over the parameter sets).
SEARCH_SAMPLES = 400
#: Of those, the samples each reading's equations are decided on (:meth:`_few`).
EQUATION_SAMPLES = 64


class SearchEvaluation(Evaluation):
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

    def _truth_parts(self) -> tuple[np.ndarray, np.ndarray | None]:
        r"""What :meth:`score` needs of the truth on the search's samples at every reading:
        its rows' sizes and its H weighted as the velocity products' coefficients."""
        if not hasattr(self, "_parts"):
            n = self.q.shape[1]
            _, truth, _ = self._subset()
            H = None if truth.H is None else truth.H * _product_weights(n)
            self._parts = (row_sizes(truth, n), H)
        return self._parts

    def doc_at(self, s: Sequence[int], offsets: Sequence[int] = (),
               sums: Sequence[Sum] = ()) -> Arrays:
        r"""The document's arrays at :math:`(S(p - \pi o), S\nu)` on the search's samples,
        :math:`o_k = 1` for the positions ``offsets`` (rows not yet divided by factors): the
        document read with :math:`p_k \to s_kp_k + \pi o_k` against the truth at :math:`p`;
        with ``sums``, at :math:`(L^{-1}p, L^{-1}\nu)` and as equations of :math:`p`
        (:mod:`.relative_angles`)."""
        rows, _, _ = self._subset()
        values = {p: np.asarray(v)[rows] if np.ndim(v) else v for p, v in self.values.items()}
        if sums:
            q, nu = document_state(self.q[rows], self.nu[rows], sums)
            return sum_arrays(self.funcs.evaluate(q, nu, values), sums)
        S = np.asarray(s, float)
        shift = np.zeros(self.q.shape[1])
        shift[list(offsets)] = np.pi
        return self.funcs.evaluate((self.q[rows] - shift) * S, self.nu[rows] * S, values)

    def weight(self) -> int:
        r"""What one equation right counts in :meth:`score`: more than every element."""
        if not hasattr(self, "_weight"):
            self._weight = self.elements(self.doc_at((1,) * self.q.shape[1])) + 1
        return self._weight

    def most(self) -> int:
        r"""The score of a reading under which everything agrees."""
        return self.weight() - 1 + self.weight() * self.q.shape[1]

    def _few(self) -> np.ndarray:
        r"""The samples of the search's (:data:`EQUATION_SAMPLES`, spread) its equations are
        decided on: a reading is only ranked here, the one found is judged on every one."""
        rows, _, _ = self._subset()
        return np.unique(np.linspace(0, len(rows) - 1, min(EQUATION_SAMPLES, len(rows)))
                         .astype(int))

    def _combinations(self, doc: Arrays
                      ) -> tuple[Side, Side, np.ndarray, np.ndarray, np.ndarray] | None:
        r"""Both sides on the samples the equations are decided on (:meth:`_few`; the
        document's B left out: a reading of the inputs gives it), :math:`W = A_{doc}A^{-1}`,
        the true rows' sizes there and their largest terms (the round-off's), or None where
        the document gives no A."""
        _, truth, B_true = self._subset()
        if doc.A is None or truth.A is None:
            return None
        at = self._few()

        def n_of(a: Arrays) -> np.ndarray | None:
            parts = [x[at] for x in (a.h, a.Q) if x is not None]
            return sum(parts[1:], parts[0]) if parts else None
        mine = Side(doc.A[at], n_of(doc), None)
        true = Side(truth.A[at], n_of(truth), None if B_true is None else B_true[at])
        return mine, true, combination_rows(mine.A, true.A), \
            row_sizes_of(true.A, (true.n, true.B)), largest_terms(true.A, true.n)

    def _right(self, B: np.ndarray | None,
               found: tuple[Side, Side, np.ndarray, np.ndarray, np.ndarray] | None) -> int:
        r"""Equations that are combinations of the true ones, as
        :func:`~..judge.equivalence.decide_row` decides them, of the document ``found``
        (:meth:`_combinations`) with its inputs' coefficients ``B``."""
        if found is None:
            return 0
        mine, true, W, sizes, largest = found
        mine = replace(mine, B=None if B is None or true.B is None else B[self._few()])
        if not hasattr(self, "_decided"):
            self._decided: dict[tuple[object, ...], bool] = {}
        right = 0
        for i in range(W.shape[1]):
            # the truth is the search's own, so the row's parts decide it: many readings
            # differ in other rows' inputs only
            key = (i, *(b"" if x is None else (x[:, i] + 0.0).tobytes()
                        for x in (mine.A, mine.n, mine.B)))
            if key not in self._decided:
                self._decided[key] = decide_row(i, mine, true, W, sizes=sizes,
                                                largest=largest).verdict == Verdict.AGREES
            right += self._decided[key]
        return right

    def equations_right(self, doc: Arrays) -> int:
        r"""How many equations of ``doc`` (on the search's samples) are combinations of the
        true ones."""
        return self._right(doc.B, self._combinations(doc))

    def score(self, doc: Arrays) -> int:
        r"""Equations of ``doc`` (on the search's samples) that are combinations of the true
        ones (:meth:`weight` each), and elements that agree with the truth, after its own
        row factors (:meth:`agreeing`)."""
        return self.weight() * self.equations_right(doc) + \
            self.agreeing(doc)

    def agreeing(self, doc: Arrays) -> int:
        r"""Elements of ``doc`` (on the search's samples) that agree with the truth, after
        its own row factors (applied to ``doc``)."""
        n = self.q.shape[1]
        _, truth, B_true = self._subset()
        truth_sizes, truth_H = self._truth_parts()
        factors = row_factors(doc, truth, B_true, n)
        apply_row_factors(doc, factors)
        scales = row_scales(doc, truth, n, truth_sizes)
        count = 0
        for name in ("A", "C", "Q"):
            D = getattr(doc, name)
            if D is not None:
                count += _agreeing(D, truth.need(name), scales)
        if B_true is not None and doc.B is not None:
            count += _agreeing(doc.B, B_true, scales)
        if doc.H is not None:            # the velocity products j <= k (2 H_ijk for j < k)
            upper = np.triu(np.ones((n, n), dtype=bool))
            count += _agreeing(doc.H * _product_weights(n), _needed(truth_H), scales, upper)
        return count

    def elements(self, doc: Arrays) -> int:
        r"""How many elements :meth:`score` counts at most (each that agrees counts one)."""
        n = self.q.shape[1]
        count = sum(int(np.prod(getattr(doc, k).shape[1:])) for k in ("A", "C", "Q")
                    if getattr(doc, k) is not None)
        if self.B_true is not None and doc.B is not None:
            count += int(np.prod(doc.B.shape[1:]))
        if doc.H is not None:
            count += doc.H.shape[1] * n * (n + 1) // 2
        return count

    def score_readings(self, base: Arrays, s: Sequence[int],
                       readings: Sequence[tuple[Sequence[int], Sequence[int]]]) -> list[int]:
        r""":meth:`score` of ``flip_arrays(base, s, t, order)`` for each ``(t, order)`` of
        ``readings``: the document at one sign pattern :math:`s` of its positions, its inputs
        read in several ways. The readings differ in B only and every part of the score is a
        row's, so the votes of A and Q, and per row and factor the number of agreeing A, C, Q
        and H elements and the row's scale, are found once; per reading only B's votes, the
        rows' factors and B's agreement (the row factors are powers of two: dividing by one
        is exact, and so is a row's largest magnitude divided by it)."""
        n = self.q.shape[1]
        _, truth, B_true = self._subset()
        doc = flip_arrays(base, s, (), ())
        if doc.B is None or B_true is None:
            return [self.score(flip_arrays(base, s, t, order)) for t, order in readings]
        votes_a, every = row_votes(Arrays(A=doc.A, Q=doc.Q), truth, None, n)
        fixed = (votes_a, every[:, votes_a.shape[1]:])
        rows = _RowParts(doc, truth, *self._truth_parts(), n)
        combinations = self._combinations(doc)
        out = []
        for t, order in readings:
            B = doc.B[:, :, list(order)] if len(order) else doc.B
            B = B * np.asarray(t, float)[None, None, :] if len(t) else B
            variant = Arrays(A=doc.A, Q=doc.Q, B=B)
            votes_a, votes_all = row_votes(variant, truth, B_true, n, fixed)
            total = 0
            for i in range(n):
                f = decided_factor(votes_a[i], votes_all[i],
                                   explaining(variant, truth, B_true, i))
                count, scale = rows.part(i, f)
                Bi = B[:, i:i + 1] if f is None else B[:, i:i + 1] / f
                total += count + _agreeing(Bi, B_true[:, i:i + 1], np.array([scale]))
            out.append(total + self.weight() * self._right(B, combinations))
        return out


class _RowParts:
    r"""Per row i and factor f of a document's arrays (samples × rows × ...): the number of
    its A, C, Q and H elements that agree with the truth once the row is divided by f, and
    the row's scale then (:meth:`SearchEvaluation.score`'s, row by row)."""

    def __init__(self, doc: Arrays, truth: Arrays, truth_sizes: np.ndarray,
                 truth_H: np.ndarray | None, n: int) -> None:
        self.doc, self.truth, self.truth_H, self.n = doc, truth, truth_H, n
        self.sizes, self.truth_sizes = row_sizes(doc, n), truth_sizes
        self._parts: dict[tuple[int, float | None], tuple[int, float]] = {}

    def part(self, i: int, f: float | None) -> tuple[int, float]:
        if (i, f) not in self._parts:
            size = self.sizes[i] if f is None else self.sizes[i] / abs(f)
            scale = float(np.maximum(size, self.truth_sizes[i]))      # NaN as row_scales:
            scale = scale if scale > 0 else 1.0                          # a scale of 1
            one = np.array([scale])
            count = 0
            for name in ("A", "C", "Q"):
                D = getattr(self.doc, name)
                if D is not None:
                    D = D[:, i:i + 1] if f is None else D[:, i:i + 1] / f
                    count += _agreeing(D, self.truth.need(name)[:, i:i + 1], one)
            if self.doc.H is not None:
                H = self.doc.H[:, i:i + 1] if f is None else self.doc.H[:, i:i + 1] / f
                upper = np.triu(np.ones((self.n, self.n), dtype=bool))
                count += _agreeing(H * _product_weights(self.n),
                                   _needed(self.truth_H)[:, i:i + 1], one, upper)
            self._parts[(i, f)] = (count, scale)
        return self._parts[(i, f)]


def _product_weights(n: int) -> np.ndarray:
    r"""The weights of H's entries as coefficients of h's velocity products: 1 for
    :math:`\nu_j^2`, 2 for :math:`\nu_j\nu_k` (:math:`j \ne k`)."""
    return np.where(np.eye(n, dtype=bool), 1.0, 2.0)


def _needed(truth_H: np.ndarray | None) -> np.ndarray:
    r"""The truth's weighted H, which a document that gives h is compared with."""
    if truth_H is None:
        raise ValueError("the truth's H is needed where the document gives h")
    return truth_H


def _agreeing(D: np.ndarray, T: np.ndarray, scales: np.ndarray,
              mask: np.ndarray | None = None) -> int:
    r"""How many elements of ``D`` (samples × rows × ...) are finite at every sample and
    agree with ``T`` (:func:`~.diagnose.agrees` with their row's scale), all at once;
    ``mask`` keeps some of each row's entries."""
    with np.errstate(invalid="ignore"):
        error = np.abs(D - T).max(axis=0, initial=0.0)
        ok = np.isfinite(D).all(axis=0) & (
            error <= AGREE_TOL * scales.reshape((-1,) + (1,) * (error.ndim - 1)))
    if mask is not None:
        ok = ok & mask
    return int(ok.sum())


__all__ = ["SEARCH_SAMPLES", "SearchEvaluation"]
