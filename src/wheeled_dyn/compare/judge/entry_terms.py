r"""An entry of the equations read back before solving or combining (:mod:`.unsolved`,
:mod:`.source_entry`) that differs, named (:func:`entry_part`): as a body's own inertia (a
point mass, a parallel-axis term: :func:`~.own_inertia.own_reading`, as the elements of a
form not solved are), by its numbers, as a symbol for another, or by terms against the
truth's entry in the document's symbols (its closed form, where the symbolic engine gives
it: :func:`entry_reading`).

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

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from ...expression_size import expand_trig_small
from ..records import Diagnosis, DiagnosisKind as K
from .diagnose import nice_number, plausible_factor, value_diagnoses
from .fitting import fit_factor, symbol_values
from .own_inertia import (OwnInertia, formula_phrase, formula_reading, own_reading,
                          parallel_phrase, same_parts, term_values)
from .part_swap import part_swap
from .swap_fit import difference_reading


def _terms(expr: sp.Expr, trig: bool = False) -> dict[sp.Expr, sp.Expr]:
    r"""Coefficient (a number) of each monomial of ``expr`` (with sines and cosines of sums
    expanded: ``trig``)."""
    out: dict[sp.Expr, sp.Expr] = {}
    for term in sp.Add.make_args(sp.expand(expand_trig_small(expr) if trig else expr)):
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


def _said(found: sp.Expr | None) -> str:
    return f"truth − document = {sp.sstr(found)}" if found is not None else "differs"


@dataclass(frozen=True)
class Part:
    r"""One entry of the equations read back before solving that differs: its ``text``,
    ``found`` truth − document in the document's symbols (or None), and its ``kind``."""

    text: str
    found: sp.Expr | None
    kind: K


def entry_part(where: str, T: np.ndarray, D: np.ndarray, scale: float,
               bases: Sequence[tuple[sp.Expr, np.ndarray]],
               own: OwnInertia | None = None,
               truths: Mapping[str, sp.Expr] | None = None,
               groups: Sequence[Sequence[sp.Symbol]] = ()) -> Part:
    r"""The entry ``where`` read back, ``T`` the truth's values and ``D`` the document's: a
    body's own inertia where truth − document is one of ``own``'s
    (:func:`~.own_inertia.own_reading`: a point mass, also where that makes the whole entry
    a factor of the truth, as a uniform rod's does; a parallel-axis term); the whole entry's
    sign, factor, absence or excess where the numbers say one
    (:func:`~.diagnose.value_diagnoses`); one of two symbols written where the other fits in
    a product (:func:`~.swap_fit.swap_reading`); a part of one of the truth's terms in
    ``truths`` where a body's own moment fits (:func:`~.own_inertia.formula_reading`: the
    document has m_w where 2J_w/R² fits); a term missing, of the wrong sign or factor,
    or too much, against the truth's entry in ``truths`` (closed forms in the document's
    symbols, :func:`entry_reading`); one symbol of ``groups`` written for another in a part
    of the truth's entry (:func:`~.part_swap.part_swap`: a product the expansion spread);
    else truth − document, with no claim of what it is."""
    found, swap = difference_reading(T - D, bases)
    found = found if found is not None or swap is None else swap[0]
    hit = own_reading(T - D, own) if own is not None else None
    if hit is not None:                     # before the whole entry's factor (a uniform rod's)
        kind, name, times = hit
        times_said = "" if times == 1 else f" × {sp.sstr(times)}"
        said = f"the moment of inertia {name} about its own centre of mass{times_said} is " \
            "missing, a point mass" if kind == K.POINT_MASS else \
            f"{parallel_phrase(name, same_parts(name, own.parallel if own else {}))} " \
            "is missing: the inertia about the centre of mass where the one about the " \
            "joint's axis fits"
        return Part(f"{where}: {said} ({_said(found)})", found, kind)
    whole = value_diagnoses(D, T, scale)
    if whole:
        said = f" ({_said(found)})" if found is not None else ""
        return Part(f"{where}: {whole[0].detail}{said}", found, whole[0].kind)
    truth = None if truths is None else truths.get(where)
    formula = None if own is None or truth is None else formula_reading(
        T - D, term_values(truth, bases), own.moments, own.lengths, own.sets)
    if formula is not None:              # a part of one of the truth's terms: what it has
        said = f" ({_said(found)})" if found is not None else ""
        symbols = fit_factor(formula.fit_values, bases)     # the moment in the file's symbols
        return Part(f"{where}: the document has {formula_phrase(formula, symbols=symbols)}"
                    f"{said}", found, K.SWAP)
    if swap is not None:
        return Part(f"{where}: {swap[1]} ({_said(swap[0])})", swap[0], K.SWAP)
    read = None if truth is None or found is None else entry_reading(found, truth)
    if read is not None:
        return Part(f"{where}: {read[1]} ({_said(found)})", found, read[0])
    spread = None if truth is None or not groups else part_swap(
        truth, T - D, symbol_values(bases), groups, document=False)
    if spread is not None:
        found = sp.factor(spread.fixed - spread.part)
        return Part(f"{where}: {spread.text} ({_said(found)})", found, K.SWAP)
    # no claim of a term missing: truth − document may be terms too much, or some of each
    return Part(f"{where} {_said(found)}", found, K.RESIDUAL)


def read_back_diagnosis(head: str, parts: Sequence[Part]) -> Diagnosis:
    r"""``parts`` as one diagnosis, of the first part's kind (the one its cause names; the
    others are said in its text). Its terms are each part's truth − document, as the
    document lacks them; a part the document has too much (:attr:`K.EXTRA`) as it writes
    it, document − truth (a record's terms say what is missing or extra, as
    :mod:`.named` gives them)."""
    text = "; ".join(p.text for p in parts)
    return Diagnosis(parts[0].kind, f"{head}{text}", text,
                     terms=tuple(sp.sstr(-p.found if p.kind == K.EXTRA else p.found)
                                 for p in parts if p.found is not None))


__all__ = ["Part", "entry_part", "entry_reading", "read_back_diagnosis"]
