r"""Fitting a quantity known at samples with a short expression in a document's names.

The candidate *bases* are the document's symbols (parameters), its positions and their sines
and cosines, and the sines and cosines it writes of combinations of its positions
(:math:`\cos(q_1 + q_2)`), with their values at the samples (:func:`bases`). A quantity is fitted as a
monomial

.. math::

    c = c_0 \prod_k x_k^{e_k},\qquad e_k \in \{-2, \dots, 2\},

first by least squares on :math:`\log|c|` (exponents rounded to integers), else by a search
over products of at most :data:`MAX_FACTORS` bases (:func:`fit_factor`), :math:`c_0` a simple
rational; or as one product, or a sum of two, of at most :data:`SUM_DEGREE` bases with simple
rational coefficients (:func:`fit_sum`: :math:`I_g + m a^2`). A fit is accepted only if it
reproduces every sample to :data:`RATIO_TOL`; on a grid of many parameter sets (a quantity of
the parameters alone is told apart only by their variety).
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Mapping, Sequence
from typing import NamedTuple

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..sides.document import compound_trig, written_divisors

#: Relative agreement of a fit with every sample.
RATIO_TOL = 1e-8
#: A base's logarithm whose part independent of those before it is below this fraction of
#: its norm is dependent on them (:func:`_independent`).
INDEPENDENT_TOL = 1e-8
#: Most bases in one product of the search.
MAX_FACTORS = 2
#: Exponents tried for each base.
EXPONENTS = (-2, -1, 1, 2)
#: Largest denominator and numerator of the constant c0 (a fit that needs 7870917/10 has
#: found a coincidence, not a term).
MAX_DENOMINATOR, MAX_NUMERATOR = 12, 1000
#: Most bases in a term of a sum a row was divided by; the fraction of the target's square
#: a fit's residual may leave to be checked exactly; most fits checked.
SUM_DEGREE, SCREEN_TOL, MAX_CANDIDATES = 3, 1e-12, 20


def bases(d: Derivation, q: np.ndarray, values: Mapping[sp.Symbol, np.ndarray]
           ) -> list[tuple[sp.Expr, np.ndarray]]:
    r"""The candidate bases with their sample values (one of each set of equal columns)."""
    out: list[tuple[sp.Expr, np.ndarray]] = []
    n = len(q)
    unknown = {spec.symbol for spec in d.symbols.values() if spec.is_input}
    for s, v in values.items():
        if s not in unknown:                 # inputs are no parameters; free ones are
            out.append((s, np.broadcast_to(np.asarray(v, dtype=float), (n,))))
    for a, p in enumerate(d.positions):
        out += [(p, q[:, a]), (sp.cos(p), np.cos(q[:, a])), (sp.sin(p), np.sin(q[:, a]))]
    out += _compound_trig(d, q)
    out += _divisors(d, q, values)
    unique: list[tuple[sp.Expr, np.ndarray]] = []
    positions = set(d.positions)
    for expr, v in out:
        if np.abs(v).min() == 0 or not np.isfinite(v).all():
            continue                   # a name the grid holds constant is a number there
        if expr.free_symbols & positions and np.ptp(v) <= 1e-12 * np.abs(v).max():
            continue                   # so is a function of positions held at a point
        if any(np.allclose(v, w, rtol=1e-12, atol=0) for _, w in unique):
            continue
        unique.append((expr, v))
    return unique


def _compound_trig(d: Derivation, q: np.ndarray) -> list[tuple[sp.Expr, np.ndarray]]:
    r"""The sines and cosines the document writes of a combination of its positions
    (:func:`~..sides.document.compound_trig`), with their values at the samples."""
    from ...compiled import numpy_function
    out = []
    for f in compound_trig(d):
        if isinstance(f, (sp.sin, sp.cos)):
            value = numpy_function(d.positions, f)(*q.T)
            out.append((f, np.broadcast_to(np.asarray(value, float), (len(q),))))
    return out


def _divisors(d: Derivation, q: np.ndarray, values: Mapping[sp.Symbol, np.ndarray]
              ) -> list[tuple[sp.Expr, np.ndarray]]:
    r"""The sums the document divides by (:func:`~..sides.document.written_divisors`) whose
    names the samples give, with their values there."""
    from ...compiled import numpy_function
    args = [*d.positions, *values]
    out = []
    for x in written_divisors(d):
        if not x.free_symbols <= set(args):
            continue
        with np.errstate(all="ignore"):
            value = numpy_function(args, x)(*q.T, *(np.asarray(v, float)
                                                    for v in values.values()))
        out.append((x, np.broadcast_to(np.asarray(value, float), (len(q),))))
    return out


def _constant(ratio: np.ndarray, product: np.ndarray) -> sp.Rational | None:
    c = ratio / product
    c0 = float(c[0])
    if not np.isfinite(c0) or c0 == 0 or np.abs(c - c0).max() > RATIO_TOL * abs(c0):
        return None
    rational = sp.Rational(c0).limit_denominator(MAX_DENOMINATOR)
    if abs(rational.p) > MAX_NUMERATOR:
        return None
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


def _search(ratio: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]
            ) -> list[tuple[tuple[int, ...], tuple[int, ...]]]:
    r"""The products of at most :data:`MAX_FACTORS` bases with exponents of
    :data:`EXPONENTS` whose logarithm differs from :math:`\log|\text{ratio}|` by a constant
    (all at once on the logarithms): (bases, exponents) to be checked exactly. Each product is
    first tried on :data:`SEARCH_SCREEN` of the samples (a spread over some samples is at
    most the spread over all), on all of them only where it passes there."""
    if not bases:
        return []
    L = _logarithms(bases, len(ratio))
    y = np.log(np.abs(ratio))
    rows = np.unique(np.linspace(0, len(y) - 1, min(len(y), SEARCH_SCREEN)).astype(int))
    out: list[tuple[tuple[int, ...], tuple[int, ...]]] = []
    for p in EXPONENTS:
        spread = np.ptp(y[:, None] - p * L, axis=0)
        out += [((int(a),), (p,)) for a in np.flatnonzero(spread <= RATIO_TOL)]
    if MAX_FACTORS >= 2 and L.shape[1] > 1:
        a, b = _pairs(L.shape[1])
        e = np.array(EXPONENTS, dtype=float)[:, None, None, None]
        ys, La, Lb = y[rows][:, None], L[rows][:, a], L[rows][:, b]
        passed = np.ptp(ys - e * La - e[None, :, 0] * Lb, axis=2) <= RATIO_TOL
        for i, j in zip(*np.nonzero(passed.any(axis=2))):     # (p, q) in EXPONENTS' order
            p, q = EXPONENTS[i], EXPONENTS[j]
            near = np.flatnonzero(passed[i, j])
            if near.size:
                spread = np.ptp(y[:, None] - p * L[:, a[near]] - q * L[:, b[near]], axis=0)
                out += [((int(a[k]), int(b[k])), (p, q))
                        for k in near[spread <= RATIO_TOL]]
    return out


#: Samples a product of two bases is screened on in :func:`_search` (spread over them).
SEARCH_SCREEN = 4


def _logarithms(bases: Sequence[tuple[sp.Expr, np.ndarray]], n: int) -> np.ndarray:
    r"""The logarithms of the bases' magnitudes (samples × bases), made once for the same
    list of bases (a document's frames fit many ratios on one list)."""
    if _LOGS[0] is bases and _LOGS[1] == n:
        return _LOGS[2]
    L = np.column_stack([np.log(np.abs(v)) for _, v in bases])
    _LOGS[:] = [bases, n, L]
    return L


#: The last bases :func:`_logarithms` was given, their number of samples, and its answer.
_LOGS: list = [None, 0, None]


def _independent(bases: Sequence[tuple[sp.Expr, np.ndarray]], n: int
                 ) -> list[tuple[sp.Expr, np.ndarray]]:
    r"""The bases whose logarithms are independent of those before them and of a constant
    (:math:`\log|\sin 2\alpha| = \log 2 + \log|\sin\alpha| + \log|\cos\alpha|`: with
    both, least squares splits an exponent between them and no integer one is found)."""
    if _LAST[0] is bases and _LAST[1] == n:      # the same bases, fitted again and again
        return _LAST[2]
    kept: list[tuple[sp.Expr, np.ndarray]] = []
    Q = np.empty((n, len(bases) + 1))             # orthonormal: the constant, then the kept
    Q[:, 0], k = 1.0 / np.sqrt(n), 1              # (Gram-Schmidt, twice for round-off)
    for b, v in bases:
        x = np.log(np.abs(np.broadcast_to(np.asarray(v, float), (n,))))
        if not np.isfinite(x).all():
            continue
        r = x - Q[:, :k] @ (Q[:, :k].T @ x)
        r -= Q[:, :k] @ (Q[:, :k].T @ r)
        norm = float(np.linalg.norm(r))
        if norm > INDEPENDENT_TOL * max(float(np.linalg.norm(x)), 1e-300):
            kept.append((b, v))
            Q[:, k], k = r / norm, k + 1
    _LAST[:] = [bases, n, kept]
    return kept


#: The last bases :func:`_independent` was given, their number of samples, and its answer.
_LAST: list = [None, 0, []]


def _monomial(ratio: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]
              ) -> sp.Expr | None:
    r"""A monomial in ``bases`` equal to ``ratio``, by least squares on the logarithms
    (integer exponents), checked exactly."""
    if not bases:
        return None
    X = np.column_stack([np.log(np.abs(v)) for _, v in bases] + [np.ones(len(ratio))])
    e = np.linalg.lstsq(X, np.log(np.abs(ratio)), rcond=None)[0][:-1]
    rounded = np.rint(e).astype(int)
    if np.abs(e - rounded).max() < 1e-6 and np.abs(rounded).max() <= max(EXPONENTS):
        return _try(ratio, bases, rounded)
    return None


def fit_factor(ratio: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]) -> sp.Expr | None:
    r"""A monomial in ``bases`` equal to ``ratio`` at every sample (module docstring): by least
    squares on all the bases' logarithms, a constant, the search, and last by least squares
    on the bases independent of the others (:func:`_independent`)."""
    if not np.isfinite(ratio).all() or np.abs(ratio).min() <= 0:
        return None
    found = _monomial(ratio, bases)
    if found is not None:
        return found
    found = _constant(ratio, np.ones_like(ratio))
    if found is not None:
        return found
    for group, powers in _search(ratio, bases):
        found = _try(ratio, [bases[g] for g in group], powers)
        if found is not None:
            return found
    independent = _independent(bases, len(ratio))
    return _monomial(ratio, independent) if len(independent) < len(bases) else None


@functools.lru_cache(maxsize=8)
def _pairs(n: int) -> tuple[np.ndarray, np.ndarray]:
    r"""The index pairs :math:`i < j` of ``n`` columns (``numpy.triu_indices(n, 1)``, made
    once per size: the same bases recur from row to row and file to file)."""
    i, j = np.triu_indices(n, 1)
    i.flags.writeable = j.flags.writeable = False
    return i, j


def _products(bases: Sequence[np.ndarray], degree: int
              ) -> tuple[list[tuple[int, ...]], np.ndarray]:
    r"""Every product of at most ``degree`` of the bases' values (repetitions allowed): the
    bases' indices of each, and their values (samples × products), multiplied left to right
    as the indices go."""
    groups = [g for k in range(1, degree + 1)
              for g in itertools.combinations_with_replacement(range(len(bases)), k)]
    V = np.column_stack(bases)
    values = np.empty((V.shape[0], len(groups)))
    start = 0
    for k in range(1, degree + 1):
        index = np.array([g for g in groups if len(g) == k]).reshape(-1, k)
        block = V[:, index[:, 0]]
        for m in range(1, k):
            block = block * V[:, index[:, m]]
        values[:, start:start + len(index)] = block
        start += len(index)
    return groups, values


class _Screen(NamedTuple):
    r"""What :func:`fit_sum` screens with, for one list of bases on one set of samples: the
    bases' values (kept, so that they are the same arrays while this is kept), the samples,
    the products' indices, their unit columns and Gram matrix."""

    values: tuple[np.ndarray, ...]
    rows: np.ndarray
    groups: list[tuple[int, ...]]
    Xn: np.ndarray
    G: np.ndarray


def _screen(full: Sequence[np.ndarray], rows: np.ndarray) -> _Screen:
    r"""The :class:`_Screen` of the bases' values ``full`` at the samples ``rows``; the last
    one made is made again only for other arrays or samples (a derivation's rows are fitted
    with the same bases, and the Gram matrix of their products is most of a fit's work)."""
    last = _SCREEN[0]
    if last is not None and len(last.values) == len(full) and np.array_equal(
            last.rows, rows) and all(a is b for a, b in zip(last.values, full)):
        return last
    groups, X = _products([v[rows] for v in full], SUM_DEGREE)
    norms = np.linalg.norm(X, axis=0)
    Xn = X / np.where(norms > 0, norms, 1.0)           # unit columns: a well-scaled Gram
    _SCREEN[0] = made = _Screen(tuple(full), rows, groups, Xn, Xn.T @ Xn)
    return made


#: The last :class:`_Screen` made.
_SCREEN: list[_Screen | None] = [None]


def _pair_gram(screen: _Screen) -> tuple[np.ndarray, ...]:
    r"""The index pairs of the screen's products, their Gram entries and :math:`1 - g^2`,
    made once per screen (the last one is kept)."""
    if _PAIR_GRAM[0] is not screen:
        i, j = _pairs(len(screen.groups))
        g = screen.G[i, j]
        _PAIR_GRAM[:] = [screen, (i, j, g, 1.0 - g * g)]
    return _PAIR_GRAM[1]


_PAIR_GRAM: list = [None, ()]


def _exact_sum(columns: Sequence[np.ndarray], y: np.ndarray, terms: Sequence[sp.Expr]
               ) -> sp.Expr | None:
    r"""The sum of ``terms`` (their values: ``columns``) with simple rational coefficients
    equal to ``y`` at every sample, or None."""
    sub = np.column_stack(columns)
    coef = np.linalg.lstsq(sub, y, rcond=None)[0]
    exact = [sp.Rational(c).limit_denominator(MAX_DENOMINATOR) for c in coef]
    if any(c == 0 for c in exact):
        return None
    if np.abs(sub @ np.array([float(c) for c in exact]) - y).max() > RATIO_TOL * np.abs(y).max():
        return None
    return sp.Add(*(c * t for c, t in zip(exact, terms)))


#: Most bases :func:`fit_sum` searches (its products of three grow as the cube).
SUM_BASES = 16
#: Most samples the search screens on (evenly spaced; every sample checks what it finds).
SCREEN_SAMPLES = 400


def fit_sum(target: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]) -> sp.Expr | None:
    r"""One product, or a sum of two, of at most :data:`SUM_DEGREE` bases with simple rational
    coefficients equal to ``target`` at every sample (the quantity a row was divided by when
    it is a sum, :math:`I_g + m a^2`). Every pair is tried at once through the Gram matrix
    (the residual of each 2 × 2 least-squares fit) on at most :data:`SCREEN_SAMPLES` distinct
    samples, and the few that fit there are checked exactly at every sample. The sums the
    document divides by are left out (they are fitted whole, by :func:`fit_factor`). Not
    searched with more than :data:`SUM_BASES` bases: then among those without a sine or
    cosine, where they are few enough (a three-link arm's row divided by
    :math:`I_3 + m_3 l_{c3}^2`)."""
    if any(b[0].is_Add for b in bases):          # the sums the document divides by: whole
        return fit_sum(target, [b for b in bases if not b[0].is_Add])
    if len(bases) > SUM_BASES:
        plain = [b for b in bases if not b[0].has(sp.sin, sp.cos)]
        return fit_sum(target, plain) if 0 < len(plain) < len(bases) else None
    if not bases or not np.isfinite(target).all():
        return None
    full = [v if isinstance(v, np.ndarray) and v.dtype == float and v.shape == np.shape(
        target) else np.broadcast_to(np.asarray(v, float), np.shape(target)) for _, v in bases]
    step = max(1, len(target) // SCREEN_SAMPLES)
    rows = np.arange(0, len(target), step)
    rows = rows[np.unique(np.column_stack([*(v[rows] for v in full), target[rows]]), axis=0,
                          return_index=True)[1]]
    screen = _screen(full, rows)
    groups, Xn, y = screen.groups, screen.Xn, target[rows]

    def fit(ks: Sequence[int]) -> sp.Expr | None:
        columns = [np.prod([full[i] for i in groups[k]], axis=0) for k in ks]
        terms = [sp.Mul(*(bases[i][0] for i in groups[k])) for k in ks]
        return _exact_sum(columns, target, terms)

    c, yy = Xn.T @ y, float(y @ y)
    floor = SCREEN_TOL * yy
    for k in np.flatnonzero(yy - c ** 2 <= floor)[:MAX_CANDIDATES]:
        found = fit((int(k),))
        if found is not None:
            return found
    i, j, g, det = _pair_gram(screen)
    ci, cj = c[i], c[j]
    with np.errstate(all="ignore"):                    # |y|² less its projection on (i, j)
        residual = yy - (ci * ci + cj * cj - 2.0 * g * ci * cj) / det
    fits = np.flatnonzero((residual <= floor) & (det > SCREEN_TOL))
    for k in fits[np.argsort(residual[fits])][:MAX_CANDIDATES]:
        found = fit((int(i[k]), int(j[k])))
        if found is not None:
            return found
    return None


def symbol_values(bases: Sequence[tuple[sp.Expr, np.ndarray]]) -> dict[sp.Expr, np.ndarray]:
    r"""The symbols among ``bases`` with their values."""
    return {e: v for e, v in bases if e.is_Symbol}


def evaluated(expr: sp.Expr, values: Mapping[sp.Expr, np.ndarray], shape: tuple[int, ...]
              ) -> np.ndarray | None:
    r"""``expr`` at the samples of ``values`` (:func:`symbol_values`), broadcast to ``shape``;
    None where one of its symbols has no values there."""
    from ...compiled import numpy_function
    names = sorted(expr.free_symbols, key=str)
    if not set(names) <= set(values):
        return None
    with np.errstate(all="ignore"):
        v = np.asarray(numpy_function(names, expr)(*(values[s] for s in names)), dtype=float)
    return np.broadcast_to(v, shape)


__all__ = ["MAX_DENOMINATOR", "RATIO_TOL", "SUM_DEGREE", "bases", "evaluated", "fit_factor",
           "fit_sum", "symbol_values"]
