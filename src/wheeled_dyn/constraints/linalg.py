r"""Small dense linear algebra of the reductions, fast on the small matrices of one state.

- :func:`spd_solve`: :math:`K^{-1}R` for a symmetric positive definite :math:`K` (a mass
  matrix, normal equations) by LAPACK's Cholesky solver;
- :func:`pseudo_inverse`: :math:`M^+ = (M^TM)^{-1}M^T` of one matrix or a stack, checked
  (:math:`M^+M = I`) and replaced by the SVD's where :math:`M` loses column rank.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

#: Largest entry of :math:`M^+M - I` for the normal equations' pseudo-inverse to stand.
PSEUDO_INVERSE_TOL = 1e-9


def spd_solve(K: np.ndarray, R: np.ndarray) -> np.ndarray:
    r""":math:`X = K^{-1}R` for a symmetric positive definite ``K`` (a mass matrix, the
    normal equations :math:`M^TM`) by LAPACK's Cholesky solver ``dposv`` (SciPy, imported on
    first use): on the small matrices of a simulation step a third of the time of
    ``numpy.linalg.solve``. Where ``K`` is not positive definite, NumPy's LU solve (which
    raises ``LinAlgError`` when ``K`` is singular)."""
    global _dposv
    if _dposv is None:
        from scipy.linalg.lapack import dposv
        _dposv = dposv
    _, x, info = _dposv(K, R)
    return x if info == 0 else np.linalg.solve(K, R)


_dposv: Callable[..., tuple] | None = None


def pseudo_inverse(M: np.ndarray) -> np.ndarray:
    r""":math:`M^+` of one matrix or a stack: :math:`(M^TM)^{-1}M^T` where :math:`M` has full
    column rank (a fraction of an SVD's time), the SVD's pseudo-inverse where it has not
    (:math:`M^+M \ne I` there, or :math:`M^TM` singular). One matrix is solved by NumPy, not
    :func:`spd_solve`: a comparison needs no SciPy, whose linear algebra takes 0.25–0.35 s to
    import (4 µs more a call, where a simulation step calls it)."""
    if M.ndim == 2:
        try:
            Mp = np.linalg.solve(M.T @ M, M.T)
        except np.linalg.LinAlgError:
            return np.linalg.pinv(M)
        ok = np.abs(Mp @ M - np.eye(M.shape[1])).max() <= PSEUDO_INVERSE_TOL
        return Mp if ok else np.linalg.pinv(M)
    Mt = np.swapaxes(M, 1, 2)
    try:
        with np.errstate(all="ignore"):
            Mp = np.linalg.solve(Mt @ M, Mt)
            residual = Mp @ M                       # M^+ M - I, in place
            residual -= np.eye(M.shape[2])
            np.abs(residual, out=residual)
            bad = ~(residual.max(axis=(1, 2)) <= PSEUDO_INVERSE_TOL)
    except np.linalg.LinAlgError:
        Mp, bad = np.empty_like(Mt), np.ones(len(M), dtype=bool)
    if bad.any():
        Mp[bad] = np.linalg.pinv(M[bad])
    return Mp


__all__ = ["PSEUDO_INVERSE_TOL", "pseudo_inverse", "spd_solve"]
