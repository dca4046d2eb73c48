r"""Which frame rule a row is explained in (:mod:`.frames`): each candidate scored by the
number of the row's elements that agree under it beyond the weights it fits
(:func:`freedom`), summed over the grids; the simplest on a tie; a declared factor kept; for
an equation that is right, the simplest rule under which every element agrees. A row that
scores as well in the constant most rows are read in (:func:`consensus`: Kane's −1) is read
in it (:func:`with_consensus`)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..grid.arrays import Arrays
from ..judge.diagnose import AGREE_TOL
from ..judge.unsolved import solved_for
from ..sides.framed import framed, row_of, row_scale, side_size
from .frames import FrameKind, FrameRule, evaluate_rule


def _agreeing(D: np.ndarray | None, T: np.ndarray | None, tol: float,
              mask: np.ndarray | None = None) -> int:
    if D is None or T is None:
        return 0
    with np.errstate(invalid="ignore"):
        ok = (np.isfinite(D).all(axis=0) & np.isfinite(T).all(axis=0)
              & (np.abs(D - T).max(axis=0, initial=0.0) <= tol))
    return int((ok & mask).sum() if mask is not None else ok.sum())


def score(doc_row: Arrays, true_row: Arrays, doc_size: float | None = None) -> int:
    r"""The number of the row's A, Q, B elements and velocity products of H that agree
    (``doc_size``: the document's side of :func:`~..sides.framed.row_scale`, made once)."""
    tol = AGREE_TOL * row_scale(doc_row, true_row, doc_size)
    count = _agreeing(doc_row.A, true_row.A, tol) + _agreeing(doc_row.Q, true_row.Q, tol)
    count += _agreeing(doc_row.B, true_row.B, tol) + _agreeing(doc_row.K, true_row.K, tol)
    if doc_row.H is not None and true_row.H is not None:
        n = doc_row.H.shape[2]
        count += _agreeing(doc_row.H, true_row.H, tol,
                           np.triu(np.ones((n, n), dtype=bool))[None, :, :])
    return count


#: Free weights a frame fits per sample (its degrees of freedom): a frame that fits more
#: must explain that many more elements to be preferred (a combination of n rows fits any n
#: elements of the row).
def freedom(rule: FrameRule, n: int, solved: bool = False) -> int:
    r"""0 for the identity, a declared factor and a constant (one number for every sample: it
    is taken only where an element of A shares it exactly), 1 for a function (a number per
    sample), n for a combination — 0 for :math:`A_{doc,i}A^{-1}` where the row is ``solved``
    for its acceleration (:math:`A_{doc,i} = e_i`: the form says which combination it is,
    row :math:`i` of :math:`A^{-1}`; nothing is fitted)."""
    if rule.kind in (FrameKind.IDENTITY, FrameKind.DECLARED, FrameKind.CONSTANT) or \
            rule.identified:
        return 0
    if rule.kind == FrameKind.FUNCTION:
        return 1
    return 0 if solved and rule.variant is None else n


def solved_row(doc: Arrays, i: int) -> bool:
    r"""Whether the document's row ``i`` is solved for an acceleration: its inertia row is
    :math:`c\,e_k` at every sample, c constant, k its own row or another's
    (:func:`~..judge.unsolved.solved_for` (:math:`\ddot\theta = \dots`
    printed first for positions (x, θ), as simulation code orders them; False for a document
    that gives no A)."""
    return doc.A is not None and solved_for(doc.A[:, i, :]) is not None


def elements_of(doc_row: Arrays) -> int:
    r"""The number of A, Q, B elements and velocity products of H in one row."""
    count = 0
    for name in ("A", "Q", "B", "K"):
        M = getattr(doc_row, name)
        if M is not None:
            count += int(np.prod(M.shape[2:])) if M.ndim > 2 else 1
    if doc_row.H is not None:
        n = doc_row.H.shape[2]
        count += n * (n + 1) // 2
    return count


def choose(i: int, rules: Sequence[FrameRule], grids: Sequence[tuple[Arrays, Arrays,
           np.ndarray | None]], declared: bool, right: bool = False,
           totals: dict[FrameRule, int] | None = None) -> FrameRule:
    r"""The rule of row ``i`` (module text), scored over ``grids`` ((document, truth, true B in
    the document's inputs) each, the document's B in its ``Arrays.B``). For an equation that
    is ``right``: the simplest rule under which every element agrees on the first grid. Else
    the rule under which most elements agree beyond the weights it fits
    (:func:`freedom`), summed over the grids, the simplest on a tie; a ``declared`` factor is
    kept. ``totals``: the scores of rules scored before on the same grids (not ``right``),
    filled with those scored here."""
    if declared:
        return FrameRule(FrameKind.DECLARED)
    n = grids[0][1].need("A").shape[1]
    rows = [(row, side_size(row), elements_of(row), solved_row(doc, i))
            for row, doc in ((row_of(doc, i), doc) for doc, _, _ in grids)]
    best: tuple[int, int, FrameRule] | None = None
    for order, rule in enumerate(rules):
        floor = None if best is None else best[0]
        if right or totals is None:
            total = _total(i, rule, grids, rows, right, n, floor)
        elif rule in totals:
            total = totals[rule]
        else:
            total = _total(i, rule, grids, rows, right, n, floor)
            if total is not None:
                totals[rule] = total
        if total is None:
            continue                     # it cannot score more than the best so far
        if total == _RIGHT:
            return rule
        if total > -10 ** 9 and (best is None or total > best[0]):
            best = (total, -order, rule)
    return best[2] if best is not None else FrameRule(FrameKind.IDENTITY)


#: :func:`_total`'s answer for a rule under which every element of a right row agrees.
_RIGHT = 10 ** 12


def _total(i: int, rule: FrameRule, grids: Sequence[tuple[Arrays, Arrays, np.ndarray | None]],
           rows: Sequence[tuple[Arrays, float, int, bool]], right: bool, n: int,
           floor: int | None = None) -> int | None:
    r"""The score of ``rule`` for row ``i`` (:func:`choose`), summed over the grids; -10⁹
    where it has no frame; :data:`_RIGHT` where ``right`` and every element agrees; None as
    soon as it cannot exceed ``floor`` (the best score so far: every element of the grids
    left agreeing would not lift it above), so that the rest is not scored. ``rows``: per
    grid, the document's row, its side of the row's scale, its number of elements and
    whether it is solved for an acceleration."""
    total = 0
    for g, ((doc, truth, B_true), (row, size, count, solved)) in enumerate(zip(grids, rows)):
        if right and g:
            break
        frame = evaluate_rule(i, rule, doc, truth, doc.B, B_true)
        if frame is None:
            return -10 ** 9
        got = score(row, framed(frame.weights, truth, B_true, full=False), size)
        if right:
            return _RIGHT if got == count else -10 ** 9
        fitted = freedom(rule, n, solved)
        total += got - fitted
        left = len(grids) - g - 1
        if floor is not None and left and total + left * (count - fitted) <= floor:
            return None
    return total


def consensus(rules: Sequence[FrameRule], without: int | None = None) -> float | None:
    r"""The constant factor more than half of the rows are read in, each paired with its own
    true row (Kane's :math:`F_r + F_r^* = 0`: every row −1 × the true one), or None; with
    ``without``, of the rows but that one (a two-row document's other row)."""
    kept = [(i, r) for i, r in enumerate(rules) if i != without]
    values = [round(r.value, 9) for i, r in kept       # 1 − 2e-16 is 1
              if r.kind == FrameKind.CONSTANT and r.partner == i and r.value is not None]
    if not values:
        return None
    best = max(set(values), key=values.count)
    return best if 2 * values.count(best) > len(kept) else None


def with_consensus(i: int, rule: FrameRule, value: float,
                   grids: Sequence[tuple[Arrays, Arrays, np.ndarray | None]]) -> FrameRule:
    r"""Row ``i``'s ``rule``, or the constant ``value`` the other rows are read in where it
    explains as many of the row's elements (a tie: one term's sign in a two-element row of
    Kane's form agrees as printed with its other element's sign wrong, or in −1 with the
    term's; read as the rest of the document is, the sign is the term's, and the inertia the
    document inverts stays positive)."""
    if rule.kind not in (FrameKind.IDENTITY, FrameKind.CONSTANT) or \
            rule.value is not None and round(rule.value, 9) == value:
        return rule
    other = FrameRule(FrameKind.CONSTANT, partner=i, value=value)
    return choose(i, [other, rule], grids, False)


__all__ = ["choose", "consensus", "elements_of", "freedom", "score", "solved_row",
           "with_consensus"]
