r"""Where an equation of a document is lost at special states (the engine's: a position at
:math:`0, \pm\pi/2, \pi`, and the states its search found): :math:`W = A_{doc}A^{-1}`
singular there, for the equivalence decision (:func:`.equivalence.decide`)."""

from __future__ import annotations

import numpy as np

from .equivalence import SINGULAR_TOL, _null_rows, combination_rows, relative_det


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
    the true equation is lost too) are left out — but where the document's rows vanish there
    in more equations than the truth's, those are lost (its second equation times
    :math:`\cos^2 b` at the gimbal lock)."""
    rd, rt = relative_det(doc_A), relative_det(true_A)
    with np.errstate(all="ignore"):
        rows, own = np.linalg.norm(true_A, axis=2), np.linalg.norm(doc_A, axis=2)
    ok = np.isfinite(rd) & np.isfinite(rt) & np.isfinite(rows).all(axis=1) & \
        np.isfinite(own).all(axis=1)
    if not ok.any():
        return None
    ok &= rt >= SINGULAR_TOL ** 0.5 * float(np.median(rt[ok]))
    if not ok.any():
        return None
    true_gone = rows < SINGULAR_TOL ** 0.5 * np.median(rows[ok], axis=0)
    doc_gone = own < SINGULAR_TOL ** 0.5 * np.median(own[ok], axis=0)
    more = np.flatnonzero(ok & true_gone.any(axis=1)
                          & (doc_gone.sum(axis=1) > true_gone.sum(axis=1)))
    if len(more):             # the document loses more equations there than the truth does
        return tuple(int(i) for i in np.flatnonzero(doc_gone[more[0]] & ~true_gone[more[0]])
                     ) or tuple(int(i) for i in np.flatnonzero(doc_gone[more[0]]))
    ok &= ~true_gone.any(axis=1)
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


__all__ = ["vanishing_at"]
