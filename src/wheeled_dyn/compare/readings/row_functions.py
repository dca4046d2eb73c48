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

import functools
import itertools
from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..sides.evaluate import Arrays

#: Relative agreement of the fitted factor with every sample's ratio.
RATIO_TOL = 1e-8
#: A ratio counts as one constant when its relative spread is below this.
CONSTANT_SPREAD = 1e-9
#: Most bases in one product of the search.
MAX_FACTORS = 2
#: Exponents tried for each base.
EXPONENTS = (-2, -1, 1, 2)
#: Largest denominator of the constant c0.
MAX_DENOMINATOR = 12
#: Most bases in a term of a sum a row was divided by; the fraction of the target's square
#: a fit's residual may leave to be checked exactly; most fits checked.
SUM_DEGREE, SCREEN_TOL, MAX_CANDIDATES = 3, 1e-12, 20
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


def bases(d: Derivation, q: np.ndarray, values: Mapping[sp.Symbol, np.ndarray]
           ) -> list[tuple[sp.Expr, np.ndarray]]:
    r"""The candidate bases with their sample values (one of each set of equal columns)."""
    out: list[tuple[sp.Expr, np.ndarray]] = []
    n = len(q)
    unknown = {spec.symbol for spec in d.symbols.values() if spec.free or spec.is_input}
    for s, v in values.items():
        if s not in unknown:                 # a balance's forces, inputs: not parameters
            out.append((s, np.broadcast_to(np.asarray(v, dtype=float), (n,))))
    for a, p in enumerate(d.positions):
        out += [(p, q[:, a]), (sp.cos(p), np.cos(q[:, a])), (sp.sin(p), np.sin(q[:, a]))]
    unique: list[tuple[sp.Expr, np.ndarray]] = []
    for expr, v in out:
        if np.abs(v).min() == 0 or not np.isfinite(v).all():
            continue
        if any(np.allclose(v, w, rtol=1e-12, atol=0) for _, w in unique):
            continue
        unique.append((expr, v))
    return unique


def _constant(ratio: np.ndarray, product: np.ndarray) -> sp.Rational | None:
    c = ratio / product
    c0 = float(c[0])
    if not np.isfinite(c0) or c0 == 0 or np.abs(c - c0).max() > RATIO_TOL * abs(c0):
        return None
    rational = sp.Rational(c0).limit_denominator(MAX_DENOMINATOR)
    return rational if abs(float(rational) - c0) <= RATIO_TOL * abs(c0) else None


def _try(ratio: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]],
         exponents: Sequence[int]) -> sp.Expr | None:
    product = np.ones_like(ratio)
    for (_, v), e in zip(bases, exponents):
        product = product * v ** e
    c0 = _constant(ratio, product)
    if c0 is None:
        return None
    return c0 * sp.Mul(*(b ** e for (b, _), e in zip(bases, exponents) if e))


def fit_factor(ratio: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]) -> sp.Expr | None:
    r"""A monomial in ``bases`` equal to ``ratio`` at every sample (module docstring)."""
    if bases:
        X = np.column_stack([np.log(np.abs(v)) for _, v in bases] + [np.ones(len(ratio))])
        e = np.linalg.lstsq(X, np.log(np.abs(ratio)), rcond=None)[0][:-1]
        rounded = np.rint(e).astype(int)
        if np.abs(e - rounded).max() < 1e-6 and np.abs(rounded).max() <= max(EXPONENTS):
            found = _try(ratio, bases, rounded)
            if found is not None:
                return found
    for size in range(1, MAX_FACTORS + 1):
        for group in itertools.combinations(range(len(bases)), size):
            for powers in itertools.product(EXPONENTS, repeat=size):
                found = _try(ratio, [bases[g] for g in group], powers)
                if found is not None:
                    return found
    return None


def _products(bases: Sequence[tuple[sp.Expr, np.ndarray]], degree: int
              ) -> tuple[list[tuple[int, ...]], np.ndarray]:
    r"""Every product of at most ``degree`` of the bases (repetitions allowed): the bases'
    indices of each, and their values (samples × products)."""
    groups = [g for k in range(1, degree + 1)
              for g in itertools.combinations_with_replacement(range(len(bases)), k)]
    values = np.column_stack([np.prod([bases[i][1] for i in g], axis=0) for g in groups])
    return groups, values


def _exact_sum(X: np.ndarray, y: np.ndarray, chosen: Sequence[int],
               terms: Sequence[sp.Expr]) -> sp.Expr | None:
    r"""The sum of the ``chosen`` columns (``terms``) with simple rational coefficients equal
    to ``y``, or None."""
    sub = X[:, list(chosen)]
    coef = np.linalg.lstsq(sub, y, rcond=None)[0]
    exact = [sp.Rational(c).limit_denominator(MAX_DENOMINATOR) for c in coef]
    if any(c == 0 for c in exact):
        return None
    if np.abs(sub @ np.array([float(c) for c in exact]) - y).max() > RATIO_TOL * np.abs(y).max():
        return None
    return sp.Add(*(c * t for c, t in zip(exact, terms)))


@functools.lru_cache(maxsize=8)
def _pairs(n: int) -> tuple[np.ndarray, np.ndarray]:
    r"""The index pairs :math:`i < j` of ``n`` columns (``numpy.triu_indices(n, 1)``, made
    once per size: the same bases recur from row to row and file to file)."""
    i, j = np.triu_indices(n, 1)
    i.flags.writeable = j.flags.writeable = False
    return i, j


def fit_sum(target: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]) -> sp.Expr | None:
    r"""One product, or a sum of two, of at most :data:`SUM_DEGREE` bases with simple rational
    coefficients equal to ``target`` at every sample (the quantity a row was divided by when
    it is a sum, :math:`I_g + m a^2`). Every pair is tried at once through the Gram matrix
    (the residual of each 2 × 2 least-squares fit), and the few that fit are checked
    exactly."""
    if not bases:
        return None
    groups, X = _products(bases, SUM_DEGREE)

    def term(k: int) -> sp.Expr:
        return sp.Mul(*(bases[i][0] for i in groups[k]))

    X = np.unique(np.column_stack([X, target]), axis=0)
    X, y = X[:, :-1], X[:, -1]
    norms = np.linalg.norm(X, axis=0)
    Xn = X / np.where(norms > 0, norms, 1.0)           # unit columns: a well-scaled Gram
    G, c, yy = Xn.T @ Xn, Xn.T @ y, float(y @ y)
    floor = SCREEN_TOL * yy
    for k in np.flatnonzero(yy - c ** 2 <= floor)[:MAX_CANDIDATES]:
        found = _exact_sum(X, y, (int(k),), (term(k),))
        if found is not None:
            return found
    i, j = _pairs(len(groups))
    det = 1.0 - G[i, j] ** 2
    with np.errstate(all="ignore"):
        a = (c[i] - c[j] * G[i, j]) / det
        b = (c[j] - c[i] * G[i, j]) / det
        residual = yy - a * c[i] - b * c[j]
    fits = np.flatnonzero((residual <= floor) & (det > SCREEN_TOL))
    for k in fits[np.argsort(residual[fits])][:MAX_CANDIDATES]:
        found = _exact_sum(X, y, (int(i[k]), int(j[k])), (term(i[k]), term(j[k])))
        if found is not None:
            return found
    return None


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


__all__ = ["bases", "candidate_rows", "document_names", "describe_factors", "fit_factor", "fit_sum", "state_row_factors",
           "with_row_factors",
           "with_row_functions"]
