r"""The frame an equation is explained in: which combination of the true equations the
document's equation is meant to be, so that each differing term is named where its author
wrote it.

Whether an equation is right is decided by :mod:`..judge.equivalence`, whatever its form. To
*explain* a difference, the document's row :math:`i` is compared element by element with the
truth brought into the document's frame, :math:`T' = f_i\,[A \mid C \mid Q \mid B \mid H]`,
for a row vector :math:`f_i` per sample (a *frame*):

- ``DECLARED``: the factor the file declares for the row (``[rows] scale``), binding;
- ``IDENTITY``: the true equation :math:`i` itself;
- ``CONSTANT`` / ``FUNCTION``: :math:`c\,e_k`, a constant (Kane's :math:`F^* = -(A\ddot q + h)`
  has :math:`-1`) or a function of the state and parameters (the row divided by its diagonal
  inertia, by :math:`m l`), pairing the document's row with the true row :math:`k` (another
  :math:`k`: the equations printed in another order). :math:`c` is the ratio
  :math:`D_{ij}/T_{kj}` most of the row's nonzero elements share, per sample;
- ``COMBINATION``: :math:`w_i = A_{doc,i}A^{-1}` (a row solved for the accelerations has
  :math:`A_{doc,i} = e_i`, and :math:`w_i` is row :math:`i` of :math:`A^{-1}`), or, so that one
  wrong element of :math:`A_{doc,i}` is not absorbed into :math:`w_i`, the :math:`w` that fits
  the row's other inertia elements and its velocity-and-gravity term (or one input column).

The frame of a row is the candidate under which most of the row's elements agree (the fewest
differences: the most parsimonious explanation), the simplest on a tie; a declared factor is
kept as declared (:mod:`.frame_choice`). A frame never changes whether an equation is right: for an equation that is
right the frame is exact and every element agrees; for one that is not, some element differs
under every frame (if all agreed, :math:`f_i = w_i` and the equation would be right).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from enum import IntEnum

import numpy as np

from ..judge.diagnose import plausible_factor
from ..judge.equivalence import SINGULAR_TOL, relative_det
from ..grid.arrays import Arrays

#: Relative agreement of two elements' ratio arrays to share a vote.
RATIO_TOL = 1e-8
#: A ratio counts as one constant when its relative spread is below this.
CONSTANT_SPREAD = 1e-9
def constant_weights(w: np.ndarray) -> bool:
    r"""Whether weights ``w`` (S × n) are the same numbers at every sample (finite, not all
    zero, each within :data:`CONSTANT_SPREAD` of the largest)."""
    size = float(np.abs(w).max(initial=0.0)) if np.isfinite(w).all() else 0.0
    return size > 0.0 and float(np.ptp(w, axis=0).max()) <= CONSTANT_SPREAD * size


#: An element takes part in a vote when its smallest magnitude is above this fraction of the
#: row's largest.
VOTE_FLOOR = 1e-9


class FrameKind(IntEnum):
    r"""Kinds of frame, simplest first (the order breaks ties)."""

    DECLARED = 0
    IDENTITY = 1
    CONSTANT = 2
    FUNCTION = 3
    COMBINATION = 4


@dataclass(frozen=True)
class FrameRule:
    r"""How a frame is found on any grid: ``kind``; ``partner`` the true row paired with the
    document's (``CONSTANT``/``FUNCTION``) and ``value`` the constant (``CONSTANT``: the same
    on every grid; a ``FUNCTION``'s ratio is voted on each); ``variant`` for
    ``COMBINATION``, ``identified`` a function whose ratio is a simple expression in the
    document's names (voted by one element of A alone, it is then as good as a constant),
    ``rank`` the ratio a function takes (0: the one most elements share; 1 the next, the
    first a factor no author writes); ``COMBINATION``: ``None`` for
    :math:`A_{doc,i}A^{-1}`, ``(j, c)`` for the :math:`w` fitting the row with inertia column
    ``j`` replaced by column ``c`` of the rest (``-1``: the velocity-and-gravity term,
    ``k >= 0``: input ``k``), ``(-1, -1)`` for every inertia column left out (:data:`TERMS`)."""

    kind: FrameKind
    partner: int = -1
    variant: tuple[int, int] | None = None
    value: float | None = None
    identified: bool = False
    rank: int = 0


@dataclass(frozen=True)
class Frame:
    r"""A frame found on one grid: its rule, the weights per sample (S × n), and the constant
    when it is one (``CONSTANT``: :math:`c`; else None)."""

    rule: FrameRule
    weights: np.ndarray
    constant: float | None = None


def _ratio_groups(D: np.ndarray, T: np.ndarray, first: int
                  ) -> list[tuple[np.ndarray, int, int, tuple[int, ...]]]:
    r"""Per-sample ratios :math:`D_j/T_j` of the columns of ``D`` and ``T`` (S × k) that are
    finite and nonzero, grouped by equality: (ratio, votes, votes of the first ``first``
    columns — the inertia's —, the columns), most votes first."""
    with np.errstate(all="ignore"):
        size = max(float(np.nanmax(np.abs(T), initial=0.0)), float(np.nanmax(np.abs(D),
                                                                              initial=0.0)))
        groups: list[list] = []
        for j in range(T.shape[1]):
            d, t = D[:, j], T[:, j]
            if not (np.isfinite(d).all() and np.isfinite(t).all()):
                continue
            if np.abs(t).min() <= VOTE_FLOOR * size or np.abs(d).min() <= VOTE_FLOOR * size:
                continue
            r = d / t
            for g in groups:
                if np.abs(r - g[0]).max() <= RATIO_TOL * np.abs(g[0]).max():
                    g[1] += 1
                    g[2] += int(j < first)
                    g[3] += (j,)
                    break
            else:
                groups.append([r, 1, int(j < first), (j,)])
    return sorted(((g[0], g[1], g[2], g[3]) for g in groups), key=lambda g: -g[1])


def _terms_ratio(groups: list, n: int, with_n: bool) -> tuple[np.ndarray, int] | None:
    r"""Where no two elements of A share a ratio (each wrong its own way: a point mass in
    Kane's form, every inertia of the row lacking I2), the constant ratio the velocity and
    gravity terms share (with the inputs' where they share it): the row's. Else None."""
    if not with_n or any(g[2] >= 2 for g in groups):
        return None
    top = next((g for g in groups if n in g[3] and not g[2]), None)
    if top is None or np.ptp(top[0]) > CONSTANT_SPREAD * np.abs(top[0]).max():
        return None
    # one vote against one (one inertia, its terms): the row is taken as the true one or
    # its negative (Kane's) rather than as another multiple, else the inertia's ratio stands
    # (a gravity term twice what fits is named, not the inertia "1/2 × the truth")
    inertias = [g for g in groups if g[2]]
    unit = [bool(np.abs(np.abs(g[0]) - 1.0).max() <= RATIO_TOL) for g in (top, *inertias)]
    return None if top[1] < 2 and len(inertias) < 2 and (not unit[0] or any(unit[1:])) \
        else (top[0], top[1])


def _columns(a: Arrays, B: np.ndarray | None, row: int, with_n: bool) -> np.ndarray:
    r"""Row ``row`` of A, the velocity-and-gravity term :math:`n = h + Q` (``with_n``, per
    sample) and B (where given) side by side (S × k)."""
    parts = [a.need("A")[:, row, :]]
    if with_n:
        n = sum(x[:, row] for x in (a.h, a.Q) if x is not None)
        parts.append(np.asarray(n, float)[:, None])
    if B is not None:
        parts.append(B[:, row, :])
    return np.concatenate(parts, axis=1)


def paired(i: int, k: int, doc: Arrays, truth: Arrays, B_doc: np.ndarray | None,
           B_true: np.ndarray | None, simple: Callable[[np.ndarray], bool] | None = None,
           rank: int = 0) -> tuple[np.ndarray, int] | None:
    r"""The ratio of the document's row ``i`` to the true row ``k`` that most of their nonzero
    elements (A, Q, B) share, per sample, with its votes; only a ratio an element of A shares
    (an equation multiplied through scales its accelerations' coefficients too: a wrong input
    map must not scale a row), and one that varies only with at least two votes or, with one,
    when ``simple`` says it is a simple expression of the document's names (a function fitted
    to one element would absorb it); ``rank`` > 0: the ``rank``-th such ratio after it. None
    when there is none."""
    if doc.A is None or truth.A is None:
        return None
    both, with_n = B_doc is not None and B_true is not None, doc.h is not None or doc.Q is not None
    D = _columns(doc, B_doc if both else None, i, with_n)
    n = doc.A.shape[2]
    groups = _ratio_groups(D, _columns(_matching(truth, doc), B_true if both else None, k,
                                       with_n), n)
    terms = _terms_ratio(groups, n, with_n)      # (one wrong element of A's ratio, 0.81,
    for ratio, votes, inertia, _ in groups:      # made the right terms "differ by 1.234")
        constant = np.ptp(ratio) <= CONSTANT_SPREAD * np.abs(ratio).max()
        if inertia and (constant or votes >= 2 or (simple is not None and simple(ratio))):
            if rank:
                rank -= 1
                continue
            return terms if terms is not None and votes == 1 else (ratio, votes)
    return None if rank else terms


def _matching(truth: Arrays, doc: Arrays) -> Arrays:
    r"""The truth with the parts the document does not give left out (its n = h + Q is the
    document's parts')."""
    return Arrays(A=truth.A, h=truth.h if doc.h is not None else None,
                  Q=truth.Q if doc.Q is not None else None)


def _solve_rows(inverse: np.ndarray, regular: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    r""":math:`w = rhs\,M^{-1}` (:math:`w M = rhs`) per sample (``inverse``: S × n × n, rhs:
    S × n); NaN where M is not ``regular`` (:func:`_matrix`) or ``rhs`` is not finite."""
    out = np.full(rhs.shape, np.nan)
    ok = regular & np.isfinite(rhs).all(axis=1)
    if ok.any():
        out[ok] = np.einsum("sj,sjk->sk", rhs[ok], inverse[ok])
    return out


#: The inverses :func:`combination_weights` solves with (every row with the same ones; the
#: determinants were half the time), by truth and replaced column, with where they are
#: regular: at most :data:`MATRICES_KEPT`, the least recently used given up first; those of
#: fewer than :data:`MATRICES_FROM` samples made again (:mod:`.variants`' screens, cheap).
_MATRICES: OrderedDict[tuple, tuple[tuple, np.ndarray, np.ndarray]] = OrderedDict()
MATRICES_KEPT, MATRICES_FROM = 32, 256


def _matrix(truth: Arrays, B_true: np.ndarray | None, variant: tuple[int, int] | None
            ) -> tuple[np.ndarray, np.ndarray]:
    r"""The inverse of the true :math:`A`, or of :math:`A` with column :math:`j` replaced by
    :math:`h + Q` (:math:`c < 0`) or by input column :math:`c` of ``B_true`` (``variant`` =
    (j, c)), NaN where it is not regular, and where it is: finite,
    :func:`~..judge.equivalence.relative_det` above :data:`~..judge.equivalence.SINGULAR_TOL`. Kept while the arrays it is made of are the
    same objects (held here, so that their identities are not reused)."""
    parts = (truth.A,) if variant is None else (truth.A, truth.h, truth.Q) \
        if variant[1] < 0 else (truth.A, B_true)
    key = (*map(id, parts), variant)
    found = _MATRICES.get(key)
    if found is not None and all(a is b for a, b in zip(found[0], parts)):
        _MATRICES.move_to_end(key)
        return found[1], found[2]
    A_true = truth.need("A")
    if variant is None:
        M = A_true
    else:
        j, c = variant
        M = A_true.copy()
        if c < 0:
            M[:, :, j] = truth.need("h") + (truth.Q if truth.Q is not None else 0.0)
        else:
            assert B_true is not None          # combination_weights checked it
            M[:, :, j] = B_true[:, :, c]
    regular = np.isfinite(M).all(axis=(1, 2))
    regular[regular] = relative_det(M[regular]) > SINGULAR_TOL
    inverse = np.full(M.shape, np.nan)          # every row solves with it: inverted once
    inverse[regular] = np.linalg.inv(M[regular])
    if len(M) >= MATRICES_FROM:
        while len(_MATRICES) >= MATRICES_KEPT:
            _MATRICES.popitem(last=False)
        _MATRICES[key] = (parts, inverse, regular)
    return inverse, regular


#: The variant of a ``COMBINATION`` fitted to the row's velocity, gravity and input columns
#: alone (every inertia column left out: eq1 − eq2 with an error in both d12 and d21).
TERMS = (-1, -1)


def _terms_weights(i: int, doc: Arrays, truth: Arrays, B_doc: np.ndarray | None,
                   B_true: np.ndarray | None) -> np.ndarray:
    r""":math:`w` with :math:`w\,[h + Q\;\; B] = [h_{doc,i} + Q_{doc,i}\;\; B_{doc,i}]` per
    sample by least squares (:data:`TERMS`), NaN where that does not fit or does not
    determine :math:`w` (fewer columns than rows, or not independent)."""
    S, n = truth.need("A").shape[:2]
    out = np.full((S, n), np.nan)
    if doc.h is None or truth.h is None or B_doc is None or B_true is None or \
            1 + B_true.shape[2] < n:
        return out
    zero = np.zeros((S, n))
    M = np.concatenate([(truth.h + (truth.Q if truth.Q is not None else zero))[:, :, None],
                        B_true], axis=2)                                  # S × n × (1 + k)
    rhs = np.concatenate([(doc.h[:, i] + (doc.Q[:, i] if doc.Q is not None else 0.0)
                           )[:, None], B_doc[:, i, :]], axis=1)           # S × (1 + k)
    ok = np.isfinite(M).all(axis=(1, 2)) & np.isfinite(rhs).all(axis=1)
    if not ok.any():
        return out
    u, sv, vt = np.linalg.svd(M[ok], full_matrices=False)   # M = UΣVᵀ: w = rhs VΣ⁻¹Uᵀ
    with np.errstate(all="ignore"):
        w = np.einsum("sk,sjk,sj,snj->sn", rhs[ok], vt, 1.0 / sv, u)
    fit = np.einsum("sn,snk->sk", w, M[ok])
    size = np.maximum(np.abs(rhs[ok]).max(axis=1), 1e-300)
    good = (sv[:, n - 1] > 1e-9 * sv[:, 0]) & \
        (np.abs(fit - rhs[ok]).max(axis=1) <= CONSTANT_SPREAD * 100 * size)
    w[~good] = np.nan
    out[ok] = w
    return out


def combination_weights(i: int, rule: FrameRule, doc: Arrays, truth: Arrays,
                        B_doc: np.ndarray | None, B_true: np.ndarray | None) -> np.ndarray:
    r"""The weights of a ``COMBINATION`` rule (see :class:`FrameRule`)."""
    A_doc = doc.need("A")
    if rule.variant is None:
        return _solve_rows(*_matrix(truth, B_true, None), A_doc[:, i, :])
    if rule.variant == TERMS:
        return _terms_weights(i, doc, truth, B_doc, B_true)
    j, c = rule.variant
    if c < 0:
        if doc.h is None or truth.h is None:
            return np.full(A_doc[:, i, :].shape, np.nan)
        extra_d = doc.h[:, i] + (doc.Q[:, i] if doc.Q is not None else 0.0)
    else:
        if B_doc is None or B_true is None:
            return np.full(A_doc[:, i, :].shape, np.nan)
        extra_d = B_doc[:, i, c]
    rhs = A_doc[:, i, :].copy()
    rhs[:, j] = extra_d
    return _solve_rows(*_matrix(truth, B_true, rule.variant), rhs)


def evaluate_rule(i: int, rule: FrameRule, doc: Arrays, truth: Arrays,
                  B_doc: np.ndarray | None, B_true: np.ndarray | None,
                  declared: np.ndarray | None = None) -> Frame | None:
    r"""The frame of ``rule`` for row ``i`` on this grid (None when it does not exist here:
    no element votes for the pairing). ``declared``: the declared factor per sample."""
    S, n = truth.need("A").shape[:2]
    if rule.kind == FrameKind.DECLARED:
        w = np.zeros((S, n))
        w[:, i] = 1.0 if declared is None else declared
        return Frame(rule, w)
    if rule.kind == FrameKind.IDENTITY:
        w = np.zeros((S, n))
        w[:, i] = 1.0
        return Frame(rule, w, 1.0)
    if rule.kind == FrameKind.CONSTANT and rule.value is not None:
        w = np.zeros((S, n))
        w[:, rule.partner] = rule.value
        return Frame(rule, w, rule.value)
    if rule.kind in (FrameKind.CONSTANT, FrameKind.FUNCTION):
        found = paired(i, rule.partner, doc, truth, B_doc, B_true,
                       (lambda r: True) if rule.identified else None, rule.rank)
        if found is None:
            return None
        ratio = found[0]
        w = np.zeros((S, n))
        w[:, rule.partner] = ratio
        constant = float(np.median(ratio)) if np.ptp(ratio) <= CONSTANT_SPREAD * np.abs(
            ratio).max() else None
        return Frame(rule, w, constant)
    w = combination_weights(i, rule, doc, truth, B_doc, B_true)
    if not np.isfinite(w).all():
        return None
    size = np.abs(w).max(axis=1)
    if size.min() <= VOTE_FLOOR * max(float(size.max()), 1e-300) or size.min() == 0.0:
        return None                  # the row would be no equation at some sample
    return Frame(rule, w)


def candidate_rules(i: int, grids: Sequence[tuple[Arrays, Arrays, np.ndarray | None]],
                    simple: Callable[[np.ndarray], bool] | None = None) -> list[FrameRule]:
    r"""The rules tried for row ``i``: the identity; for each true row the elements vote for
    on some grid ((document, truth, true B) each, the document's B in its ``Arrays.B``), the
    constant they share there, else a function (``identified`` where ``simple`` finds its
    ratio a simple expression of the document's names on the first grid, however many
    elements share it: as good as a constant); the combination :math:`A_{doc,i}A^{-1}` (its
    variants with one inertia column replaced: :mod:`.variants`)."""
    doc0, truth0, B0 = grids[0]
    n = truth0.need("A").shape[1]
    out = [FrameRule(FrameKind.IDENTITY)]
    for k in range(n):
        for g, (doc, truth, B_true) in enumerate(grids):
            found = paired(i, k, doc, truth, doc.B, B_true, simple if g == 0 else None)
            if found is None:
                continue
            ratio, votes = found
            if np.ptp(ratio) <= CONSTANT_SPREAD * np.abs(ratio).max():
                c = float(np.median(ratio))
                # a factor an author writes (−1, 2, 1/2, 1000); 0.9869 is the model's
                # proportions the elements happen to share, no frame
                if not (k == i and abs(c - 1.0) <= RATIO_TOL) and plausible_factor(c):
                    rule = FrameRule(FrameKind.CONSTANT, k, value=c)
                    if not any(r.kind == FrameKind.CONSTANT and r.partner == k and
                               r.value is not None and abs(r.value - c) <= RATIO_TOL * abs(c)
                               for r in out):
                        out.append(rule)
            else:
                identified = votes < 2 or (g == 0 and simple is not None and simple(ratio))
                rule = FrameRule(FrameKind.FUNCTION, k, identified=identified)
                if not any(r.kind == FrameKind.FUNCTION and r.partner == k for r in out):
                    out.append(rule)
    if doc0.A is None:                    # no inertia: no combination to find
        return out
    out.append(_combination(i, grids[0], simple))
    return out


def _combination(i: int, grid: tuple[Arrays, Arrays, np.ndarray | None],
                 simple: Callable[[np.ndarray], bool] | None) -> FrameRule:
    r"""The combination :math:`A_{doc,i}A^{-1}` of row ``i``, ``identified`` where ``simple``
    finds each of its weights on ``grid`` a simple expression of the document's names (a row
    replaced by eq1 − 3 cos θ/(2L) eq2: the weights are the form's, as good as fitted none)."""
    rule = FrameRule(FrameKind.COMBINATION)
    if simple is None:
        return rule
    doc, truth, B_true = grid
    w = combination_weights(i, rule, doc, truth, doc.B, B_true)
    if not np.isfinite(w).all():
        return rule
    size = float(np.abs(w).max(initial=0.0))
    columns = [w[:, k] for k in range(w.shape[1]) if np.abs(w[:, k]).max() > 1e-12 * size]
    if columns and all(simple(c) for c in columns):
        return FrameRule(FrameKind.COMBINATION, identified=True)
    return rule


__all__ = ["CONSTANT_SPREAD", "Frame", "FrameKind", "FrameRule", "RATIO_TOL", "VOTE_FLOOR",
           "TERMS", "candidate_rules", "combination_weights", "constant_weights", "evaluate_rule",
           "paired"]
