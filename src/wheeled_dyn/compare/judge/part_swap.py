r"""One symbol written for another in a part of an expression: in one printed product that the
multiplying out spread over several terms, or merged with others —
:math:`-k_1(\theta_2 - \theta_1 - r_2)` where :math:`-k_2(\theta_2 - \theta_1 - r_2)` fits,
whose :math:`k_1\theta_1` joins :math:`k_1(\theta_1 - r_1)`'s into :math:`2k_1\theta_1`.
Neither a symbol read as another everywhere in the element nor in one term of it says that.

With the terms :math:`m` of an expression :math:`E` holding a symbol :math:`a`, and truth −
document :math:`r` at the samples, the part of :math:`E` in which :math:`a` stands for
:math:`b` (a symbol of its group: equal units) is the fractions :math:`c_m \in (0, 1]` with

.. math::

    r = \sum_m c_m\,\big(m[a \to b] - m\big)        \quad(E \text{ the document's: } a
    \text{ written, } b \text{ fits}),

    r = \sum_m c_m\,\big(m - m[a \to b]\big)        \quad(E \text{ the truth's: } a
    \text{ fits, } b \text{ written}),

found by least squares and kept only where each :math:`c_m` is a fraction :math:`p/q`,
:math:`q \le` :data:`MAX_DENOMINATOR`, and the sum so written equals :math:`r` at every sample
(to :data:`~.fitting.RATIO_TOL`). An explanation only: the element's verdict is its numbers'.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import sympy as sp

from ...expression_size import ops_over
from .fitting import RATIO_TOL, evaluated

#: Largest denominator of a fraction of a term taken as the part written with the other symbol
#: (a product merged with another's: half of :math:`2k_1\theta_1`).
MAX_DENOMINATOR = 6
#: Most terms holding the symbol, and largest expression (operations), searched.
MAX_TERMS, MAX_OPS = 16, 400


@dataclass(frozen=True)
class PartSwap:
    r"""``written`` where ``fits`` belongs in ``part`` (as the document has it, factorised),
    which reads ``fixed`` with ``fits`` in its place; ``whole`` the terms ``part`` is a part
    of, where it is less than them (the document's :math:`2k_2` of which one :math:`k_2` is
    :math:`k_1`'s; said where the part is the symbol alone)."""

    written: sp.Symbol
    fits: sp.Symbol
    part: sp.Expr
    fixed: sp.Expr
    whole: sp.Expr | None = None

    @property
    def text(self) -> str:
        r"""``"k1 where k2 fits in k1*(r2 + th1 - th2)"``, ``"k2 (of its 2*k2) where k1
        fits"``."""
        if self.part == self.written:
            of = f" (of its {sp.sstr(self.whole)})" if self.whole is not None else ""
            return f"{self.written}{of} where {self.fits} fits"
        return f"{self.written} where {self.fits} fits in {sp.sstr(self.part)}"


def part_swap(expr: sp.Expr, residual: np.ndarray, values: Mapping[sp.Symbol, np.ndarray],
              groups: Sequence[Sequence[sp.Symbol]], document: bool = True) -> PartSwap | None:
    r"""The part of ``expr`` (the document's element, ``document``, else the truth's entry) in
    which one symbol stands for another of its group, that truth − document ``residual`` says
    (module text); ``values`` the symbols' values at its samples. None where none does."""
    if expr is None or ops_over(expr, MAX_OPS) or not np.isfinite(residual).all() \
            or np.abs(residual).max(initial=0.0) == 0:
        return None
    terms = sp.Add.make_args(sp.expand(expr))
    members = {s: g for g in groups for s in g}
    for a in sorted(expr.free_symbols & set(members), key=sp.default_sort_key):
        holding = [m for m in terms if a in m.free_symbols]
        if not 0 < len(holding) <= MAX_TERMS:
            continue
        for b in members[a]:
            if b == a or b not in values:
                continue
            found = _fractions(holding, a, b, residual, values, document)
            if found is not None:
                part = sp.Add(*(c * m for c, m in zip(found, holding)))
                whole = sp.Add(*(m for c, m in zip(found, holding) if c != 0))
                fixed = part.xreplace({a: b})
                written, fits = (a, b) if document else (b, a)
                shown, other = (part, fixed) if document else (fixed, part)
                merged = None if all(c in (0, 1) for c in found) else \
                    sp.factor(whole if document else whole.xreplace({a: b}))
                return PartSwap(written, fits, sp.factor(shown), sp.factor(other), merged)
    return None


def _fractions(holding: Sequence[sp.Expr], a: sp.Symbol, b: sp.Symbol, residual: np.ndarray,
               values: Mapping[sp.Symbol, np.ndarray], document: bool
               ) -> list[sp.Rational] | None:
    r"""The fractions :math:`c_m` of the terms ``holding`` (module text), or None."""
    columns = []
    for m in holding:
        before = evaluated(m, values, residual.shape)
        after = evaluated(m.xreplace({a: b}), values, residual.shape)
        if before is None or after is None:
            return None
        columns.append(after - before if document else before - after)
    X = np.column_stack(columns)
    if not np.isfinite(X).all() or np.linalg.matrix_rank(X) < len(columns):
        return None                           # which terms, the numbers cannot tell
    c = np.linalg.lstsq(X, residual, rcond=None)[0]
    if not np.isfinite(c).all():
        return None
    fractions = [Fraction(float(x)).limit_denominator(MAX_DENOMINATOR) for x in c]
    if any(f < 0 or f > 1 for f in fractions) or not any(fractions):
        return None
    fit = X @ np.array([float(f) for f in fractions])
    if np.abs(fit - residual).max() > RATIO_TOL * np.abs(residual).max():
        return None
    return [sp.Rational(f.numerator, f.denominator) for f in fractions]


__all__ = ["MAX_DENOMINATOR", "PartSwap", "part_swap"]
