r"""Where an equation of a document is lost at special states (the engine's: a position at
:math:`0, \pm\pi/2, \pi`, and the states its search found): :math:`W = A_{doc}A^{-1}`
singular there, for the equivalence decision (:func:`.equivalence.decide`)."""

from __future__ import annotations

import numpy as np

from .equivalence import (NULL_SHARE, SINGULAR_TOL, _null_rows, combination_rows,
                          relative_det)


def vanishing_at(doc_A: np.ndarray, true_A: np.ndarray, typical: np.ndarray | None = None
                 ) -> tuple[int, ...] | None:
    r"""At special states (the engine's: a position at :math:`0, \pm\pi/2, \pi`, and the
    states its search found), the equations involved where :math:`W` is singular, else
    None: its rows dependent (relative determinant), or a row :math:`w_i` vanishing — below
    :data:`SINGULAR_TOL` of ``typical`` (per state and row, its usual norm), where given (an
    equation times :math:`(\cos\theta - \tfrac12)^2` is lost at :math:`\pi/3`; its rows
    each scaled to 1, the determinant does not see that). States where the truth's own
    :math:`A` is near singular (a singular position of the coordinates: its rows dependent,
    or one vanishing, as a gimbal's first row :math:`J\cos^2 b` at :math:`b = \pi/2`, where
    the true equation is lost too) are left out — but where the document's rows (each scaled
    by its usual norm) are of lower rank there than the truth's, the equations its null
    vectors beyond the truth's involve are lost (its second equation times :math:`\cos^2 b`
    at the gimbal lock, or two rows that become one there)."""
    rd, rt = relative_det(doc_A), relative_det(true_A)
    ok = np.isfinite(rd) & np.isfinite(rt)
    if not ok.any():
        return None
    doc, true = _unit_rows(doc_A, ok), _unit_rows(true_A, ok)
    rank_d, rank_t = _rank(doc, ok), _rank(true, ok)
    singular = (rt < SINGULAR_TOL ** 0.5 * float(np.median(rt[ok]))) | (rank_t < rank_t.max())
    more = np.flatnonzero(ok & singular & (rank_d < rank_t))
    if len(more):             # the document loses more equations there than the truth does
        return _lost_rows(doc[int(more[0])], true[int(more[0])])
    ok &= ~singular
    hit = np.flatnonzero(ok & (rd <= SINGULAR_TOL * rt))
    if len(hit):
        W = combination_rows(doc_A[hit[:1]], true_A[hit[:1]])
        return _null_rows(W[0])
    if typical is None or not ok.any():
        return None
    W = combination_rows(doc_A[ok], true_A[ok])
    with np.errstate(all="ignore"):
        small = np.linalg.norm(W, axis=2) <= SINGULAR_TOL * typical[ok]
    states = np.flatnonzero(small.any(axis=1))
    return tuple(int(i) for i in np.flatnonzero(small[states[0]])) if len(states) else None


def _unit_rows(A: np.ndarray, ok: np.ndarray) -> np.ndarray:
    r""":math:`A` with each row divided by its median norm over the states ``ok`` (the rows of
    an equation of forces and one of torques compared alike)."""
    with np.errstate(all="ignore"):
        norms = np.median(np.linalg.norm(A[ok], axis=2), axis=0)
        return A / np.where(norms > 0, norms, 1.0)[None, :, None]


def _left_null(A: np.ndarray) -> np.ndarray:
    r"""An orthonormal basis (columns) of :math:`\{y: y^TA = 0\}` to
    :math:`\sqrt{\text{SINGULAR\_TOL}}` (``A`` row-scaled)."""
    U, s, _ = np.linalg.svd(A)
    return U[:, s <= SINGULAR_TOL ** 0.5]


def _lost_rows(doc: np.ndarray, true: np.ndarray) -> tuple[int, ...]:
    r"""The equations the document loses at a state where it has more dependent rows than
    the truth (both row-scaled): those a null vector of its rows involves that is none of
    the truth's (the truth's own lost row is not blamed)."""
    N, T = _left_null(doc), _left_null(true)
    R = N - T @ (T.T @ N)                 # the document's null vectors beyond the truth's
    y = np.abs(R[:, int(np.argmax(np.linalg.norm(R, axis=0)))])
    return tuple(int(k) for k in np.flatnonzero(y >= NULL_SHARE * y.max()))


def _rank(A: np.ndarray, ok: np.ndarray) -> np.ndarray:
    r"""The numerical rank of each of the (row-scaled) matrices ``A`` at the states ``ok``
    (singular values above :math:`\sqrt{\text{SINGULAR\_TOL}}`), 0 elsewhere."""
    out = np.zeros(len(A), dtype=int)
    if ok.any():
        out[ok] = (np.linalg.svd(A[ok], compute_uv=False) > SINGULAR_TOL ** 0.5).sum(axis=1)
    return out


__all__ = ["vanishing_at"]
