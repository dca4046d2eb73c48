r"""The states at which the constraint rows a document states may lose a constraint, for
:mod:`.constraint_factors`: rows that span the model's rolling constraints at every sample
may not at a state the samples miss.

A constraint is lost at a state where the stated rows :math:`G_{doc}(q)` state fewer
independent constraints than the model's rows there (ranks of the rows each scaled to a
largest entry of 1, :func:`~..judge.document_checks.row_rank`). The states tried:

- the special positions (each position at :math:`0, \pm\pi/2, \pi`);
- the zeros of a row's factor in the positions (:func:`factor_zeros`, where it changes sign
  between two samples of a set: a square's base is its factor; a row times
  :math:`\cos\theta` is zero at :math:`\theta = \pi/2`; whether the constraint is lost there
  depends on the other rows: :math:`\cos\theta\,g` and :math:`\sin\theta\,g` together state
  :math:`g` everywhere);
- the least independence of the stated rows (:func:`weakest`: the ratio of the r-th to the
  largest singular value of the rows each scaled by its median norm, r the model's number of
  constraints), searched from the sample where it is least when that is below
  :data:`WEAK_SCREEN` of its median: rows mixed with weights singular where
  :math:`\cos\theta = 1/3`, or touching singular there; two rows stating one constraint
  with factors that vanish together (:math:`\cos\theta\,g` and :math:`\sin\varphi\,g`).

Each search is a bounded one (L-BFGS-B, the positions within their ranges) on a logarithm,
per parameter set, from the sample where the quantity is least.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..grid.grid import special_states
from ..judge.document_checks import row_rank, unit_rows
from ..sides.both import Sides
from ..sides.document import DocumentFunctions

#: A quantity at most this fraction of its median over a set's samples is searched for zero
#: (a factor's; the stated rows' independence, which two factors shrink together only near
#: where both vanish: a looser screen).
SCREEN, WEAK_SCREEN = 1e-2, 0.25
#: A factor at most this fraction of its median magnitude is zero at a state.
ZERO = 1e-12
#: Inside the logarithms searched, the floor (below any decision).
LOG_FLOOR = 1e-300
#: Halvings of the segment a factor's zero is sought on (to the double's precision).
BISECTIONS = 60
#: The stated rows' independence at a searched state below this fraction of the model's rows'
#: there: a constraint lost (a search ends near, not at, the state; the decision is a ratio).
LOST = 1e-6


def parameters(funcs: DocumentFunctions, sides: Sides, owner: np.ndarray) -> list[np.ndarray]:
    r"""The document's parameters (``funcs.params``) at states of the sets ``owner``."""
    return [np.array([sides.per_set[k][p] for k in owner]) for p in funcs.params]


class StatedRows:
    r"""The rows ``G`` (SymPy, in the document's names) and the model's, at any states."""

    def __init__(self, funcs: DocumentFunctions, sides: Sides, G: sp.Matrix) -> None:
        self.funcs, self.sides, self.G = funcs, sides, G
        self.fn = funcs.compiled(tuple(G))

    def values(self, owner: np.ndarray) -> list[np.ndarray]:
        r"""The document's parameters at the states of the sets ``owner``."""
        return parameters(self.funcs, self.sides, owner)

    def stated(self, q: np.ndarray, owner: np.ndarray) -> np.ndarray:
        r"""The stated rows at the states ``q`` of the sets ``owner`` (S × m × n)."""
        with np.errstate(all="ignore"):
            flat = [np.broadcast_to(np.asarray(v, float), (len(q),)) for v in
                    self.fn(*q.T, *np.zeros_like(q).T, *self.values(owner))]
        return np.stack(flat, axis=1).reshape(len(q), self.G.rows, self.G.cols)

    def model(self, q: np.ndarray, owner: np.ndarray) -> np.ndarray:
        r"""The model's rows at the states ``q`` of the sets ``owner``."""
        from ..sides.truth import truth_for
        grid = self.sides.grid
        out = np.full((len(q),) + self.sides.truth.need("G").shape[1:], np.nan)
        for k, ps in enumerate(grid.sets):
            at = np.flatnonzero(owner == k)
            if len(at):
                out[at] = truth_for(grid.cmap, [ps], q[at][None],
                                    np.zeros((1, len(at), q.shape[1]))).G
        grid.cmap.bind(grid.sets[-1].model)          # as the grid's truth left it
        return out

    def fewer(self, q: np.ndarray, owner: np.ndarray) -> int | None:
        r"""The first of the states where the stated rows state fewer independent constraints
        than the model's, or None."""
        if not len(q):
            return None
        D, T = self.stated(q, owner), self.model(q, owner)
        ok = np.isfinite(D).all(axis=(1, 2)) & np.isfinite(T).all(axis=(1, 2))
        short = np.flatnonzero(ok)[row_rank(unit_rows(D[ok])) < row_rank(unit_rows(T[ok]))]
        return int(short[0]) if len(short) else None


def _search(sides: Sides, size, start: np.ndarray) -> np.ndarray:
    from scipy.optimize import minimize     # 0.5 s to import: only where a search is made
    bounds = np.array(sides.grid.ranges, dtype=float)
    found = minimize(lambda x: float(size(x)), start, method="L-BFGS-B", bounds=bounds)
    return np.clip(found.x, bounds[:, 0], bounds[:, 1])


def factor_zeros(funcs: DocumentFunctions, sides: Sides, factor: sp.Expr
                 ) -> tuple[np.ndarray, np.ndarray]:
    r"""``(q, set index)`` of states where ``factor`` (of the positions and parameters) is
    zero: special states where it is, and per set where it changes sign, the zero between
    the two samples of opposite signs nearest it (bisection on the segment joining them: the
    positions' ranges hold it)."""
    grid = sides.grid
    K, N, n = grid.q.shape
    fn = funcs.compiled(factor)
    sq, sowner = special_states(grid)
    qs, owners = [], []
    for k in range(K):
        q = np.concatenate([grid.q[k], sq[sowner == k]])
        values = parameters(funcs, sides, np.array([k]))

        def f(x: np.ndarray) -> np.ndarray:
            with np.errstate(all="ignore"):
                return np.broadcast_to(np.asarray(fn(*x.T, *np.zeros_like(x).T,
                                                     *(p[0] for p in values)), float),
                                       (len(x),))
        v = f(q)
        ok = np.isfinite(v)
        if not ok.any():
            continue
        typical = float(np.median(np.abs(v[ok])))
        zero = np.flatnonzero(ok & (np.abs(v) <= ZERO * typical))
        qs += [q[j] for j in zero[:4]]
        owners += [k] * len(zero[:4])
        plus, minus = np.flatnonzero(ok & (v > 0)), np.flatnonzero(ok & (v < 0))
        if not (len(plus) and len(minus)):
            continue
        a, b = q[plus[np.argmin(v[plus])]], q[minus[np.argmax(v[minus])]]
        lo, hi = 0.0, 1.0                       # f(a) > 0 > f(b)
        for _ in range(BISECTIONS):
            mid = 0.5 * (lo + hi)
            if f((a + mid * (b - a))[None])[0] > 0:
                lo = mid
            else:
                hi = mid
        qs.append(a + 0.5 * (lo + hi) * (b - a))
        owners.append(k)
    return (np.array(qs), np.array(owners, dtype=int)) if qs else \
        (np.empty((0, n)), np.empty(0, dtype=int))


def _independence(D: np.ndarray, scale: np.ndarray, r: int) -> np.ndarray:
    r"""Per sample, the r-th singular value of the rows ``D`` each divided by its constant
    ``scale``, against the largest (rows that shrink count: cos θ·g and sin φ·g together
    state g nowhere where both vanish; rows each scaled to 1 per sample would not show it)."""
    with np.errstate(all="ignore"):
        sv = np.linalg.svd(D / scale[None, :, None], compute_uv=False)
    if sv.shape[1] < r:
        return np.zeros(len(D))
    return sv[:, r - 1] / np.maximum(sv[:, 0], LOG_FLOOR)


def weakest(rows: StatedRows) -> tuple[np.ndarray, np.ndarray] | None:
    r"""``(q, set index)`` of a state where the stated rows state fewer constraints than the
    model's, found per set by a bounded search for the least independence of the stated rows
    (:func:`_independence`, each row scaled by its median norm over the set) from the sample
    where it is least, where that is below :data:`WEAK_SCREEN` of its median: lost where it is
    below :data:`LOST` of the model's rows' independence there (scaled alike); else None."""
    sides = rows.sides
    grid = sides.grid
    K, N, n = grid.q.shape
    for k in range(K):
        owner = np.full(N, k)
        D, T = rows.stated(grid.q[k], owner), sides.truth.need("G")[k * N:(k + 1) * N]
        ok = np.isfinite(D).all(axis=(1, 2)) & np.isfinite(T).all(axis=(1, 2))
        if not ok.any():
            continue
        r = int(row_rank(unit_rows(T[ok])).max())
        d_scale = np.maximum(np.median(np.linalg.norm(D[ok], axis=2), axis=0), LOG_FLOOR)
        t_scale = np.maximum(np.median(np.linalg.norm(T[ok], axis=2), axis=0), LOG_FLOOR)
        m = _independence(np.where(ok[:, None, None], D, 0.0), d_scale, r)
        j = int(np.flatnonzero(ok)[np.argmin(m[ok])])
        if m[j] >= WEAK_SCREEN * float(np.median(m[ok])):
            continue

        def size(x: np.ndarray, k: int = k) -> float:
            v = _independence(rows.stated(x[None], np.array([k])), d_scale, r)[0]
            return float(np.log(v + LOG_FLOOR)) if np.isfinite(v) else 0.0
        x = _search(sides, size, grid.q[k, j])[None]
        at = np.array([k])
        stated = _independence(rows.stated(x, at), d_scale, r)[0]
        model = _independence(rows.model(x, at), t_scale, r)[0]
        if np.isfinite(stated) and np.isfinite(model) and stated <= LOST * model:
            return x, at
    return None


__all__ = ["BISECTIONS", "LOG_FLOOR", "LOST", "SCREEN", "WEAK_SCREEN", "ZERO", "StatedRows",
           "factor_zeros", "parameters", "weakest"]
