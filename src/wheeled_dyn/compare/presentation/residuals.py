r"""Truth − document as the reports print it: expanded with the trigonometric identities
where it is short (:math:`\sin^2 + \cos^2 = 1` used where that shortens it), put over one
denominator for a solved row, the round-off of decimals against the document's fractions
dropped, remembered across runs."""

from __future__ import annotations

from pathlib import Path

import sympy as sp

from ...disk_cache import DiskMemo
from ...expression_size import expand_trig_small

#: Residuals up to this many operations are expanded with trigonometric identities for display
#: (larger ones, e.g. in seed 001 section 5's wheel-angle coordinates, are shown as they are).
TRIG_EXPAND_LIMIT = 40
#: Models without a physical record: residuals in Khalil's parameters longer than this many
#: operations, or with roots of them (a document's mass or length read as an algebraic function
#: of the link's parameters), are not shown; the truth is.
STANDARD_RESIDUAL_LIMIT = 60
#: Most operations of a solved row's truth − document put over one denominator (a longer one
#: is not shown: it is not read, and the polynomial arithmetic took 49 s an element of a
#: two-link arm's solved form).
SOLVED_RESIDUAL_LIMIT = 250


#: Relative size below which a term of a residual with decimals is round-off: a decimal of
#: the truth (a rotation by a rounded angle) less the document's same number as a fraction.
CHOP_TOL = 1e-9


def _chopped(expr: sp.Expr) -> sp.Expr:
    r"""``expr`` (expanded) without the terms whose numeric coefficient is below
    :data:`CHOP_TOL` of its largest: :math:`0.0978\ldots\,x - \tfrac{978\ldots}{10^{16}}\,x`
    leaves round-off, and a residual of 2 kB hid the one term that differs (the numbers
    evaluated first: :math:`0.9588\ldots\,x - 2\sin\tfrac12\,x` is round-off too)."""
    terms = sp.Add.make_args(expr)
    sizes = [abs(float(t.as_coeff_Mul()[0])) for t in terms]
    largest = max(sizes, default=0.0)
    return sp.Add(*(t for t, c in zip(terms, sizes) if c > CHOP_TOL * largest))


def _pythagorean(expr: sp.Expr) -> sp.Expr:
    r"""``expr`` (expanded) with :math:`\cos^2 a = 1 - \sin^2 a` or :math:`\sin^2 a = 1 -
    \cos^2 a` used for each argument where that makes it shorter
    (:math:`I\cos^2\theta - I` as :math:`-I\sin^2\theta`), no other identity: the terms
    stay the document's monomials."""
    args = sorted({f.args[0] for f in expr.atoms(sp.sin, sp.cos)}, key=sp.default_sort_key)
    for a in args:
        trials = [sp.expand(expr.xreplace({sp.cos(a) ** 2: 1 - sp.sin(a) ** 2})),
                  sp.expand(expr.xreplace({sp.sin(a) ** 2: 1 - sp.cos(a) ** 2}))]
        best = min(trials, key=sp.count_ops)
        expr = best if sp.count_ops(best) < sp.count_ops(expr) else expr
    return expr


#: The texts of :func:`residual_text`, remembered across runs (the disk cache's
#: ``compare/residual-<code>.pickle``): a function of the two expressions only.
RESIDUALS = DiskMemo("compare", "residual", lambda: [Path(__file__)])


def residual_text(truth: sp.Expr, doc: sp.Expr, physical: bool, solved: bool = False
                  ) -> str | None:
    r"""The text of truth − document, expanded with trigonometric identities when it has at
    most :data:`TRIG_EXPAND_LIMIT` operations (``solved``: a solved row's, a quotient, put
    over one denominator and factored first); None where it is not shown (a model without a
    physical record: longer than :data:`STANDARD_RESIDUAL_LIMIT`, or with roots of Khalil's
    parameters). Remembered: :data:`RESIDUALS`."""
    return RESIDUALS.get((truth, doc, physical, solved),
                         lambda: _residual_text(truth, doc, physical, solved))


def _residual_text(truth: sp.Expr, doc: sp.Expr, physical: bool, solved: bool = False
                   ) -> str | None:
    residual = truth - doc
    if residual.has(sp.Float):                # a rotation's decimals against the document's
        residual = _chopped(sp.expand(sp.expand(residual).evalf(15)))   # or sin(1/2)'s
    if solved:                                # a quotient: over one denominator, if short
        if sp.count_ops(residual) > SOLVED_RESIDUAL_LIMIT:
            return None
        residual = sp.factor(sp.cancel(residual))
    elif sp.count_ops(residual) <= TRIG_EXPAND_LIMIT:
        residual = sp.expand(expand_trig_small(residual))
        residual = _pythagorean(residual)
    if not physical and (sp.count_ops(residual) > STANDARD_RESIDUAL_LIMIT or any(
            not p.exp.is_Integer for p in residual.atoms(sp.Pow))):
        return None                           # roots of Khalil's parameters: not shown
    return sp.sstr(residual)


__all__ = ["CHOP_TOL", "RESIDUALS", "SOLVED_RESIDUAL_LIMIT", "STANDARD_RESIDUAL_LIMIT",
           "TRIG_EXPAND_LIMIT", "residual_text"]
