r"""An entry of the equations read back before solving or combining (:mod:`.unsolved`,
:mod:`.source_entry`) that differs by terms, named against the truth's entry in the
document's symbols (its closed form, where the symbolic engine gives it).

The read-back gives truth − document :math:`r = \sum_k c_k m_k` (monomials :math:`m_k`), the
document's entry only as numbers. With the truth's entry :math:`\sum_k t_k m_k`, written with
its trigonometric functions of sums expanded where :math:`r` is written otherwise, the
document's coefficient of
:math:`m_k` is :math:`t_k - c_k`: 0 — the term is missing; :math:`-t_k` — its sign is wrong;
another multiple of :math:`t_k` — a factor; and :math:`t_k = 0` — the document has a term the
truth does not. Where the truth's entry is not known, nothing is said here (the difference was
called a missing term, also where the document had the term twice).
"""

from __future__ import annotations

import sympy as sp

from ..records import DiagnosisKind as K
from .diagnose import nice_number, plausible_factor


def _terms(expr: sp.Expr, trig: bool = False) -> dict[sp.Expr, sp.Expr]:
    r"""Coefficient (a number) of each monomial of ``expr`` (with sines and cosines of sums
    expanded: ``trig``)."""
    out: dict[sp.Expr, sp.Expr] = {}
    for term in sp.Add.make_args(sp.expand(sp.expand_trig(expr) if trig else expr)):
        c, m = term.as_coeff_Mul()
        out[m] = out.get(m, sp.Integer(0)) + c
    return {m: c for m, c in out.items() if c != 0}


def entry_reading(found: sp.Expr, truth: sp.Expr) -> tuple[K, str] | None:
    r"""(kind, text) of truth − document ``found`` in one entry whose truth is ``truth``
    (module text), for a difference of one or two monomials (the kind of the first); None
    for more."""
    diff, true = _terms(found), _terms(truth)
    if not set(diff) <= set(true):              # cos(q1 + q2) in one, expanded in the other
        diff, true = _terms(found, True), _terms(truth, True)
    if not 0 < len(diff) <= 2:
        return None
    said: list[tuple[K, str]] = []
    for m, c in diff.items():
        t = true.get(m, sp.Integer(0))
        if t == 0:
            said.append((K.EXTRA, f"the document has {sp.sstr(-c * m)} too much"))
        elif c == t:
            said.append((K.MISSING, f"the document lacks {sp.sstr(t * m)}"))
        elif c == 2 * t:
            said.append((K.SIGN, f"the term {sp.sstr(t * m)} has the wrong sign"))
        elif not plausible_factor(float((t - c) / t)):
            return None
        else:
            factor = nice_number(float((t - c) / t))
            said.append((K.FACTOR, f"the term {sp.sstr(t * m)} is {factor} × what fits"))
    return said[0][0], "; ".join(t for _, t in said)


__all__ = ["entry_reading"]
