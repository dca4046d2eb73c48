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
is named in the document's symbols (:func:`~.unsolved.entry_part`: a point mass, a sign, a factor, a
symbol for another) only where exactly one entry so explains every sample; an entry that is a
factor f of the truth's is said with its equal, every other entry of its equation 1/f × the
truth's (the row's common factor goes into its weight). This only explains: the equations'
verdicts are decided by their equivalence.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace

import numpy as np
import sympy as sp

from ..records import Diagnosis
from .diagnose import AGREE_TOL, nice_number
from .equivalence import SINGULAR_TOL, relative_det
from .named import own_moments
from .unsolved import entry_part, read_back_diagnosis, term_columns, whole_factor

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
               f"h[{{r}}]:{j},{m}" for j in range(n) for m in range(j, n))]
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


def _explains(T: np.ndarray, D: np.ndarray, r: int, c: int, delta: np.ndarray) -> bool:
    r"""Whether :math:`V = T + \delta e_re_c^T` gives the document's rows as :math:`WV` with
    :math:`W` invertible at every sample, and :math:`\delta` is not zero throughout."""
    if not np.isfinite(delta).all() or not np.abs(delta).max() > AGREE_TOL * np.abs(
            T[:, :, c]).max(initial=0.0):
        return False
    V = T.copy()
    V[:, r, c] += delta
    W = D @ np.linalg.pinv(V)
    scale = max(float(np.abs(D).max()), 1e-300)
    return bool(np.abs(W @ V - D).max() <= AGREE_TOL * scale
                and (relative_det(W) > SINGULAR_TOL).all())


def source_entry(sides, bases: Sequence[tuple[sp.Expr, np.ndarray]],
                 velocities: Sequence[sp.Symbol] = (),
                 truths: Mapping[str, sp.Expr] | None = None) -> Diagnosis | None:
    r"""The one wrong entry of the equations the document solved or combined (module text),
    named; None where no entry, or more than one, explains every sample. ``sides``: both
    sides on a grid (:class:`~..sides.both.Sides`), ``bases`` the names' values on it,
    ``truths`` the truth's entries in the document's symbols (or None)."""
    doc, truth = sides.doc, sides.truth
    rows = truth.H_rows if truth.H_rows is not None else np.arange(len(truth.need("A")))
    true = _columns(truth, sides.B_true, rows, velocities)
    mine = _columns(doc, doc.B, rows, velocities)
    if true is None or mine is None or true[0].shape != mine[0].shape:
        return None
    (T, names), D = true, mine[0]
    fits = []
    for r in range(T.shape[1]):
        deltas = _entry_values(T, D, r)
        if deltas is None:
            continue
        fits += [(r, c, deltas[:, c]) for c in range(T.shape[2])
                 if _explains(T, D, r, c, deltas[:, c])]
    if len(fits) != 1:
        return None
    r, c, delta = fits[0]
    sets = [ps.values for ps in sides.grid.sets]
    moments = own_moments(sets, len(truth.need("A")) // max(len(sets), 1))
    at = [(e, v[rows]) for e, v in bases]
    moments = {k: v[rows] for k, v in moments.items()}
    truth_entry = T[:, r, c]
    scale = float(np.abs(T[:, :, c]).max())
    part = entry_part(names[c].format(r=r + 1), truth_entry, truth_entry + delta, scale, at,
                      moments, truths)
    factor = whole_factor(truth_entry, truth_entry + delta)
    if factor is not None:          # a row's common factor goes into its weight: the same
        part = replace(part, text=f"{part.text} — or, the same equations: every other entry "
                       f"of equation {r + 1} is {nice_number(1.0 / factor)} × the truth's")
    return read_back_diagnosis("read back before it was solved or combined (the equations "
                               "whose combinations its rows are), one entry differs: ", [part])


__all__ = ["source_entry"]
