r"""A symbol written for another inside one product, fitted from truth − document at the
samples: :math:`M\,(x - y)` (:func:`fit_swap`), with :math:`M` a monomial in the bases of
:mod:`.fitting`."""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
import sympy as sp

from .fitting import EXPONENTS, _independent, _try, fit_factor, fit_sum


def _product(M: sp.Expr, x: sp.Expr, y: sp.Expr) -> sp.Expr:
    r""":math:`M\,(x - y)` as one expression (a number kept in front: ``2*(l1 - lc1)``)."""
    return sp.Mul(M, x - y, evaluate=False) if M.is_Number else M * (x - y)


def fit_swap(target: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]
             ) -> sp.Expr | None:
    r""":math:`M\,(x - y)` of :func:`swap_pair` as one expression, or None."""
    pair = swap_pair(target, bases)
    return None if pair is None else _product(*pair)


def difference_reading(residual: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]
                       ) -> tuple[sp.Expr | None, tuple[sp.Expr, str] | None]:
    r"""Truth − document ``residual`` in the document's names: (a monomial or a sum of two
    that fits it, or None; :func:`swap_reading` of it, or None) — the swap searched once."""
    found = fit_factor(residual, bases) if np.abs(residual).min() > 0 else None
    found = found if found is not None else fit_sum(residual, bases)
    return found, swap_reading(residual, bases, found)


def swap_reading(target: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]],
                 found: sp.Expr | None) -> tuple[sp.Expr, str] | None:
    r"""Truth − document ``target`` read as one of two symbols written where the other fits,
    where no plainer fit was ``found`` (none, or a sum of two terms:
    :math:`m_2l_1^2 - m_2l_{c1}^2` says what :math:`m_2(l_1^2 - l_{c1}^2)` says):
    (:math:`M(x - y)`, ``"x and y, one written where the other fits"``) — which of the two
    the author wrote, the sign of :math:`M` in the source would tell, and the numbers do
    not; None otherwise (:func:`swap_pair`)."""
    if found is not None and len(sp.Add.make_args(sp.expand(found))) != 2:
        return None
    pair = swap_pair(target, bases)
    if pair is None:
        return None
    M, x, y = pair
    a, b = (sp.sstr(e.base) if e.is_Pow and e.exp == 2 else sp.sstr(e) for e in (x, y))
    return _product(M, x, y), f"{a} and {b}, one written where the other fits"


def swap_pair(target: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]
              ) -> tuple[sp.Expr, sp.Expr, sp.Expr] | None:
    r"""``(M, x, y)``: a monomial :math:`M` in ``bases`` times the difference of two of them,
    :math:`M\,(x - y)`, or of two symbols' squares, :math:`M\,(x^2 - y^2)`, equal to
    ``target`` at every sample: truth − document where the document writes :math:`y` for
    :math:`x` in one product (:math:`g m_2 (L_1 - a_1)\sin\theta_1`: the centre's distance for
    the link's length; :math:`g l m(\sin\theta - \cos\theta)`: a cos for a sin). Each pair
    is screened by least squares on :math:`\log|\text{target}/(x - y)|` (integer exponents of
    the bases), and what fits there is checked exactly (:data:`RATIO_TOL`) at every sample."""
    if not bases or not np.isfinite(target).all() or np.abs(target).min() <= 0:
        return None
    full = _independent([(e, np.broadcast_to(np.asarray(v, float), target.shape))
                         for e, v in bases], len(target))
    X = np.column_stack([np.log(np.abs(v)) for _, v in full] + [np.ones(len(target))])
    pairs = [(x, y, vx, vy) for (x, vx), (y, vy) in itertools.combinations(full, 2)]
    pairs += [(x ** 2, y ** 2, vx ** 2, vy ** 2) for x, y, vx, vy in pairs
              if isinstance(x, sp.Symbol) and isinstance(y, sp.Symbol)]
    # equal somewhere: no ratio (and no swap to tell)
    pairs = [p for p in pairs if np.abs(p[2] - p[3]).min() > 1e-12 * np.abs(p[2]).max()]
    if not pairs:
        return None
    # every pair's least squares at once: X has independent columns, so its pseudo-inverse
    # gives what lstsq gives, one product for all pairs
    ratios = target[None, :] / np.stack([vx - vy for _, _, vx, vy in pairs])
    exponents = (np.log(np.abs(ratios)) @ np.linalg.pinv(X).T)[:, :-1]
    rounded = np.rint(exponents).astype(int)
    fits = (np.abs(exponents - rounded).max(axis=1, initial=0.0) < 1e-6) & \
        (np.abs(rounded).max(axis=1, initial=0) <= max(EXPONENTS))
    for k in np.flatnonzero(fits):
        x, y = pairs[k][:2]
        found = _try(ratios[k], full, rounded[k])
        if found is not None:             # the monomial's sign on it: g*m2*(L1 - a1)*sin(th1)
            if found.could_extract_minus_sign():
                found, (x, y) = -found, (y, x)
            return found, x, y
    return None


__all__ = ["difference_reading", "fit_swap", "swap_pair", "swap_reading"]
