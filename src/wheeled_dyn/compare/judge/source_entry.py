r"""The one entry of the equations a document solved or combined that is wrong, found where
its inertia cannot be read back from its inputs (:mod:`.unsolved`: fewer inputs than
coordinates, and a column of :math:`[B\;Q\;H]` that alone carries a row — the cart-pole's
gravity term carries its pole's).

Each equation of the document, as a row of coefficients of the accelerations, inputs, gravity
term and velocity products, :math:`D = [A_{doc}\;B_{doc}\;Q_{doc}\;H_{doc}]`, is a combination
of the equations it was derived from, :math:`D = W V`. If those are the truth's,
:math:`T = [A\;B\;Q\;H]`, but for one entry :math:`(r, c)`, :math:`V = T + \delta\,e_re_c^T`,
then projected away from the other true rows (:math:`P_\perp`, the complement of the span of
:math:`T`'s rows but :math:`r`), every row of :math:`D` is a multiple of
:math:`P_\perp(T_r + \delta e_c)`: the projected :math:`D` has rank one, its direction
:math:`d = \alpha P_\perp T_r + \alpha\delta P_\perp e_c` gives :math:`\delta` per sample by
least squares, and :math:`D = (DV^+)V` with :math:`W = DV^+` invertible confirms it. The entry
is named in the document's symbols (:func:`~.entry_terms.entry_part`: a point mass, a sign, a
factor, a symbol for another) only where exactly one entry so explains every sample; an entry
that is a factor f of the truth's is said with its equal, every other entry of its equation
1/f × the truth's (the row's common factor goes into its weight).

Where no one entry does, a symmetric pair of the inertia's, :math:`V = T + \delta(e_re_c^T +
e_ce_r^T)` — the coupling an author derives once and writes in both equations — is tried:
the columns but :math:`r, c` give :math:`W` by least squares (:math:`D_j = WT_j`), then
:math:`D_c - WT_c = \delta W_r` and :math:`D_r - WT_r = \delta W_c` give :math:`\delta` per
sample, confirmed as above. This only explains: the equations' verdicts are decided by their
equivalence.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np
import sympy as sp

from ..records import Diagnosis
from .diagnose import AGREE_TOL, nice_number
from .equivalence import SINGULAR_TOL, relative_det
from .own_inertia import grid_inertia
from .entry_terms import entry_part, read_back_diagnosis
from .unsolved import term_columns, whole_factor

#: A projected document of rank one: its second singular value at most this times its first.
RANK_ONE_TOL = 1e-7


def _columns(arrays, B: np.ndarray | None, rows: np.ndarray, velocities: Sequence[sp.Symbol]
             ) -> tuple[np.ndarray, list[str]] | None:
    r"""Each equation's coefficients of the accelerations, then of the inputs, the gravity
    term and the velocity products (:func:`~.unsolved.term_columns`) on the samples ``rows``
    (samples × n × columns) and the columns' labels as the reports write entries; None where
    one of them is not given or not finite."""
    terms = term_columns(arrays, B, rows)
    if arrays.A is None or B is None or terms is None:
        return None
    out = np.concatenate([arrays.A[rows], terms], axis=2)
    if not np.isfinite(out).all():
        return None
    n = arrays.A.shape[1]
    names = [*(f"A[{{r}},{j + 1}]" for j in range(n)),
             *(f"B[{{r}},{c + 1}]" for c in range(B.shape[2])), "Q[{r}]",
             *(f"h[{{r}}]:{velocities[j]}*{velocities[m]}" if velocities else
               f"h[{{r}}]:{j},{m}" for j in range(n) for m in range(j, n)),
             *((f"K[{{r}},{j + 1}]" for j in range(n)) if arrays.K is not None else ())]
    return out, names


def _entry_values(T: np.ndarray, D: np.ndarray, r: int) -> np.ndarray | None:
    r""":math:`\delta` per sample and column (samples × columns) for a wrong entry in row
    ``r`` of the source equations (module text), NaN where a column cannot carry it; None
    where the document's rows, projected away from the truth's others, are not of rank one
    (the source differs in more than row ``r``)."""
    S, n, m = T.shape
    others = np.delete(T, r, axis=1)                          # S × (n−1) × m
    P = np.broadcast_to(np.eye(m), (S, m, m)) - np.linalg.pinv(others) @ others
    Dp = D @ P                                                # rows of D, projected
    sv = np.linalg.svd(Dp, compute_uv=False)
    if not (sv[:, 0] > 0).all() or (sv[:, 1:2] > RANK_ONE_TOL * sv[:, :1]).any():
        return None
    big = np.argmax(np.linalg.norm(Dp, axis=2), axis=1)
    d = Dp[np.arange(S), big]                                 # S × m: the direction
    u = np.einsum("sij,sj->si", P, T[:, r, :])                # P⊥ T_r (P symmetric)
    uu, ud = np.einsum("si,si->s", u, u), np.einsum("si,si->s", u, d)
    vv, uv, vd = (np.einsum("sii->si", P), P @ u[:, :, None], P @ d[:, :, None])
    uv, vd = uv[..., 0], vd[..., 0]                           # (P e_c)·u, (P e_c)·d
    det = uu[:, None] * vv - uv ** 2
    with np.errstate(all="ignore"):
        alpha = (vv * ud[:, None] - uv * vd) / det
        beta = (uu[:, None] * vd - uv * ud[:, None]) / det
        return np.where(np.abs(det) > 1e-12 * uu[:, None] * vv, beta / alpha, np.nan)


def _pair_values(T: np.ndarray, D: np.ndarray, r: int, c: int) -> np.ndarray | None:
    r""":math:`\delta` per sample for the symmetric pair of inertia entries :math:`(r, c)` and
    :math:`(c, r)` of the source equations (module text); None where the other columns do not
    give :math:`W` (too few, or the document's rows are no combination of the truth's there)."""
    keep = [j for j in range(T.shape[2]) if j not in (r, c)]
    if len(keep) < T.shape[1]:
        return None
    Tk, Dk = T[:, :, keep], D[:, :, keep]
    W = Dk @ np.linalg.pinv(Tk)
    if np.abs(W @ Tk - Dk).max() > AGREE_TOL * max(float(np.abs(D).max()), 1e-300):
        return None
    y = np.concatenate([D[:, :, c] - np.einsum("sij,sj->si", W, T[:, :, c]),
                        D[:, :, r] - np.einsum("sij,sj->si", W, T[:, :, r])], axis=1)
    x = np.concatenate([W[:, :, r], W[:, :, c]], axis=1)
    with np.errstate(all="ignore"):
        return np.einsum("si,si->s", x, y) / np.einsum("si,si->s", x, x)


def _explains(T: np.ndarray, D: np.ndarray, entries: Sequence[tuple[int, int]],
              delta: np.ndarray) -> np.ndarray | None:
    r""":math:`W` per sample where :math:`V = T + \delta\sum e_re_c^T` over the ``entries``
    gives the document's rows as :math:`WV` with :math:`W` invertible at every sample, and
    :math:`\delta` is not zero throughout; else None."""
    c = entries[0][1]
    if not np.isfinite(delta).all() or not np.abs(delta).max() > AGREE_TOL * np.abs(
            T[:, :, c]).max(initial=0.0):
        return None
    V = T.copy()
    for r, c in entries:
        V[:, r, c] += delta
    W = D @ np.linalg.pinv(V)
    scale = max(float(np.abs(D).max()), 1e-300)
    ok = np.abs(W @ V - D).max() <= AGREE_TOL * scale and (relative_det(W) > SINGULAR_TOL).all()
    return W if ok else None


@dataclass(frozen=True)
class SourceEntry:
    r"""The wrong entry named (:func:`source_entry`) and the document's rows that are
    combinations of several source equations (a row of :math:`W` not a multiple of a unit
    row: eq1 − (d₁₂/d₂₂)·eq2, solved; not a row only scaled or divided)."""

    diagnosis: Diagnosis
    combined: frozenset[int]
    #: :math:`W` (the document's rows as combinations of the source's) on the ``samples``
    weights: np.ndarray
    samples: np.ndarray

    def other_frames(self, frames: Sequence[np.ndarray | None]) -> frozenset[int]:
        r"""The combined rows whose frame's weights (per row, samples × n on the grid, or
        None) are not the combination :math:`W` says: a frame fitted to the row has taken
        the wrong entry into its weights (eq1 − (3M cos θ/(4lm))·eq2 for the author's
        eq1 − (3 cos θ/(4l))·eq2 with M for m in the coupling), and its elements' names are
        not the author's."""
        out = set()
        for i in self.combined:
            frame = frames[i]
            w = None if frame is None else frame[self.samples]
            mine = self.weights[:, i, :]
            scale = max(float(np.abs(mine).max()), 1e-300)
            if w is None or w.shape != mine.shape or not np.abs(w - mine).max() <= \
                    AGREE_TOL * scale:
                out.add(i)
        return frozenset(out)


def _combined_rows(W: np.ndarray) -> frozenset[int]:
    r"""The rows of :math:`W` (S × n × n) with more than one entry nonzero somewhere."""
    size = np.abs(W).max(axis=0)
    big = size > 1e-9 * size.max(axis=1, keepdims=True)
    return frozenset(int(i) for i in np.flatnonzero(big.sum(axis=1) > 1))


def _fits(sides, velocities: Sequence[sp.Symbol]):
    r"""The entries (or else the symmetric pairs of the inertia's) of the source equations
    that, wrong, give the document at every sample (module text): ``(fits, pair, T,
    labels, samples)`` with each fit ``(r, c, δ, W)``; None where a side lacks a part."""
    doc, truth = sides.doc, sides.truth
    rows = truth.H_rows if truth.H_rows is not None else np.arange(len(truth.need("A")))
    true = _columns(truth, sides.B_true, rows, velocities)
    mine = _columns(doc, doc.B, rows, velocities)
    if true is None or mine is None or true[0].shape != mine[0].shape:
        return None
    (T, names), D = true, mine[0]
    n = T.shape[1]
    fits = []
    for r in range(n):
        deltas = _entry_values(T, D, r)
        if deltas is None:
            continue
        fits += [(r, c, deltas[:, c], W) for c in range(T.shape[2])
                 if (W := _explains(T, D, [(r, c)], deltas[:, c])) is not None]
    pair = False
    if not fits:                       # a symmetric pair of the inertia's (module text)
        fits = [(r, c, delta, W) for r in range(n) for c in range(r + 1, n)
                if (delta := _pair_values(T, D, r, c)) is not None
                and (W := _explains(T, D, [(r, c), (c, r)], delta)) is not None]
        pair = True
    return fits, pair, T, names, rows


def one_wrong_entry(sides, velocities: Sequence[sp.Symbol] = ()) -> bool:
    r"""Whether exactly one entry of the source equations, or one symmetric pair of the
    inertia's, wrong gives the document at every sample (module text): one term's error,
    which a reading of the positions that also makes it right must not be said for."""
    found = _fits(sides, velocities)
    return found is not None and len(found[0]) == 1


def source_entry(sides, bases: Sequence[tuple[sp.Expr, np.ndarray]],
                 velocities: Sequence[sp.Symbol] = (),
                 truths: Mapping[str, sp.Expr] | None
                 | Callable[[], Mapping[str, sp.Expr] | None] = None,
                 lengths: Sequence[tuple[sp.Expr, np.ndarray]] = (),
                 groups: Sequence[Sequence[sp.Symbol]] = ()) -> SourceEntry | None:
    r"""The one wrong entry of the equations the document solved or combined (module text),
    named, with the rows it combined; None where no entry, or more than one, explains every
    sample. ``sides``: both sides on a grid (:class:`~..sides.both.Sides`), ``bases`` the
    names' values on it, ``truths`` the truth's entries in the document's symbols (or
    None; or a function giving them, called only where an entry is found), ``lengths`` the
    bases of the document's lengths (:func:`~.own_inertia.length_bases`), ``groups`` the
    symbols of one kind (:func:`~.entry_terms.entry_part`)."""
    found = _fits(sides, velocities)
    if found is None or len(found[0]) != 1:
        return None
    fits, pair, T, names, rows = found
    truth = sides.truth
    r, c, delta, W = fits[0]
    truths = truths() if callable(truths) else truths
    own = grid_inertia([ps.values for ps in sides.grid.sets], len(truth.need("A")),
                       lengths).at(rows)
    at = [(e, v[rows]) for e, v in bases]
    truth_entry = T[:, r, c]
    scale = float(np.abs(T[:, :, c]).max())
    part = entry_part(names[c].format(r=r + 1), truth_entry, truth_entry + delta, scale, at,
                      own, truths, groups)
    if pair:
        part = replace(part, text=f"{part.text} — and in A[{c + 1},{r + 1}], the same "
                       "symmetric entry")
    factor = None if pair else whole_factor(truth_entry, truth_entry + delta)
    if factor is not None:          # a row's common factor goes into its weight: the same
        part = replace(part, text=f"{part.text} — or, the same equations: every other entry "
                       f"of equation {r + 1} is {nice_number(1.0 / factor)} × the truth's")
    return SourceEntry(read_back_diagnosis(
        "read back before it was solved or combined (the equations whose combinations its "
        "rows are), one entry differs: ", [part]), _combined_rows(W), W, rows)


__all__ = ["SourceEntry", "one_wrong_entry", "source_entry"]
