r"""Rows divided by a function of the state: :math:`\theta'' + 2\dot r\dot\theta/r = 0` is
the equation :math:`m r^2\ddot\theta + 2 m r\dot r\dot\theta = 0` divided by :math:`m r^2`.

A document may divide an equation by any quantity that does not vanish — the coefficient of its
acceleration, :math:`\cos\theta`, a mass — and the result is as right as the equation. Row
:math:`i` of such a document is :math:`c(p, q)` times the true row, with :math:`c` a function of
the parameters :math:`p` and positions :math:`q`. On the samples, every element of A in the row
that is not zero gives the same ratio :math:`\rho = D_{ij}/T_{ij}` per sample; when that ratio is
not one constant, it is fitted as a monomial

.. math::

    c = c_0 \prod_k x_k^{e_k},\qquad x_k \in \{\text{the document's symbols},\ q_a,\
    \cos q_a,\ \sin q_a\},\quad e_k \in \{-2, \dots, 2\},

first by least squares on :math:`\log|\rho|` (exponents rounded to integers), else by a search
over products of at most :data:`MAX_FACTORS` of them; :math:`c_0` must be a simple rational.
Failing that, :math:`1/\rho` is fitted as one such product or a sum of two with rational
coefficients (:func:`fit_sum`: a row divided by the coefficient of its acceleration,
:math:`I_g + m a^2`). A
factor is accepted only if it reproduces every sample's ratio to :data:`RATIO_TOL`; the engine
then compares the file with that factor declared as its row's ``scale`` and keeps the reading
only if more elements agree (:meth:`~.engine.ComparisonEngine._compare`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..grid.arrays import Arrays
from ..judge.fitting import RATIO_TOL, bases, fit_factor, fit_sum

#: A ratio counts as one constant when its relative spread is below this.
CONSTANT_SPREAD = 1e-9
#: An element of A takes part when its size is above this fraction of the row's largest.
ELEMENT_FLOOR = 1e-6


def _ratio(doc: Arrays, truth: Arrays, i: int) -> np.ndarray | None:
    r"""The common ratio :math:`D_{ij}/T_{ij}` of row ``i``'s elements of A per sample, or None
    when the elements do not share one (or the row has none)."""
    if doc.A is None or truth.A is None:
        return None
    D, T = doc.A[:, i, :], truth.A[:, i, :]
    if not (np.isfinite(D).all() and np.isfinite(T).all()):
        return None
    size = max(float(np.abs(T).max()), 1e-300)
    cols = [j for j in range(T.shape[1])
            if np.abs(T[:, j]).min() > ELEMENT_FLOOR * size and np.abs(D[:, j]).min() > 0]
    if not cols:
        return None
    ratios = [D[:, j] / T[:, j] for j in cols]
    first = ratios[0]
    if any(np.abs(r - first).max() > RATIO_TOL * np.abs(first).max() for r in ratios[1:]):
        return None
    if np.ptp(first) <= CONSTANT_SPREAD * np.abs(first).max():
        return None                                   # a constant: the row factors' business
    return first


def candidate_rows(doc: Arrays, truth: Arrays, constant: Sequence[float | None]) -> list[int]:
    r"""The rows without a constant factor whose elements of A share one ratio to the truth
    per sample that is not constant: rows a function may have divided."""
    return [i for i in range(truth.A.shape[1] if truth.A is not None else 0)
            if (i >= len(constant) or constant[i] is None) and _ratio(doc, truth, i) is not None]


def state_row_factors(d: Derivation, doc: Arrays, truth: Arrays, q: np.ndarray,
                      values: Mapping[sp.Symbol, np.ndarray], rows: Sequence[int]
                      ) -> dict[int, sp.Expr]:
    r"""``{row: c}`` for the ``rows`` that are :math:`c` × the true row, :math:`c` a function
    of the state or of the parameters found on these samples (a grid of many parameter sets:
    a function of the parameters alone is told apart only by their variety)."""
    out: dict[int, sp.Expr] = {}
    candidates = bases(d, q, values)
    for i in rows:
        ratio = _ratio(doc, truth, i)
        if ratio is None:
            continue
        found = fit_factor(ratio, candidates)
        if found is None:
            divisor = fit_sum(1.0 / ratio, candidates)
            found = None if divisor is None else 1 / divisor
        if found is not None:
            out[i] = found
    return out


def with_row_factors(d: Derivation, factors: Mapping[int, sp.Expr]) -> Derivation:
    r"""``d`` with each found factor multiplied into its row's ``scale``."""
    from dataclasses import replace
    scale = list(d.row_scale) if d.row_scale is not None else [sp.Integer(1)] * d.n
    for i, c in factors.items():
        scale[i] = scale[i] * c
    return replace(d, row_scale=tuple(scale))


def with_row_functions(d: Derivation, texts: Sequence[str | None]) -> Derivation:
    r"""``d`` with the factors a result found (:attr:`~.result.DerivationResult.
    row_functions`, SymPy text in ``d``'s symbols) multiplied into its rows' scales."""
    if not any(texts):
        return d
    names = document_names(d)
    return with_row_factors(d, {i: sp.sympify(t, locals=names)
                                for i, t in enumerate(texts) if t})


def document_names(d: Derivation) -> dict[str, sp.Symbol]:
    r"""The document's symbols and positions by name (to read back a function found)."""
    return {str(s.symbol): s.symbol for s in d.symbols.values()} | \
        {str(p): p for p in d.positions}


def describe_factors(d: Derivation, factors: Mapping[int, sp.Expr]) -> str:
    r"""``"equation 1 is the true one divided by m*r**2"`` (or ``"times ..."`` when the
    factor is not the inverse of a product or a sum)."""
    parts = []
    for i, c in sorted(factors.items()):
        inverse = sp.factor_terms(1 / c)
        if sp.fraction(inverse)[1].is_number:
            parts.append(f"equation {i + 1} is the true one divided by {sp.sstr(inverse)}")
        else:
            parts.append(f"equation {i + 1} is the true one times {sp.sstr(c)}")
    return ", ".join(parts)


__all__ = ["candidate_rows", "document_names", "describe_factors", "state_row_factors",
           "with_row_factors", "with_row_functions"]
