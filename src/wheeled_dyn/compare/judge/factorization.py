r"""C is not unique, :math:`h = C\dot q` is: a C element that differs is judged by the velocity
products of h it takes part in.

With :math:`\Gamma_{i,jk}` the coefficient of :math:`\nu_k` in :math:`C_{ij}`, the coefficient
of the product :math:`\nu_j\nu_k` in :math:`h_i` is :math:`P_{jk} = \Gamma_{i,jk} +
\Gamma_{i,kj}` (:math:`j \ne k`) and :math:`P_{jj} = \Gamma_{i,jj}`. The element
:math:`C_{ij}` takes part in the products :math:`P_{jk}`, every k. When it differs from the
truth's :math:`C_{ij}` (in the row's frame):

- every product it takes part in agrees: only the factorisation of C differs
  (*factorization*); every one agrees or agrees only under a special family, one of them only
  so: it *agrees only if* that family, as those h terms do;
- a product differs, but for each such product the document's partner element
  :math:`C_{ik}` alone is wrong (putting the truth's :math:`\Gamma_{i,k\cdot}` there makes it
  agree, putting the truth's :math:`\Gamma_{i,j\cdot}` here does not): it is not this
  element's error (*factorization*, naming the partner);
- a product differs, neither element alone makes it agree, and the product's h element names
  its error (a sign, a factor, a term missing, …): the error is that product's, said once
  at its h element; the two elements share it, split otherwise than the truth's C
  (*factorization*, naming the h element) — no cause of their own (a C element written 0
  where the truth's split puts the product is no missing physics);
- otherwise it *differs*.

A product :math:`P_{jj}` is :math:`C_{ij}`'s alone: where it differs, the element differs.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ..records import Diagnosis, DiagnosisKind as K, Verdict, diagnosis, first_of
from .diagnose import agrees
from .draft import ElementDraft


def _product(drafts: dict, i: int, j: int, k: int) -> ElementDraft | None:
    return drafts.get(("h", (i, min(j, k), max(j, k))))


def _innocent(i: int, j: int, k: int, doc: np.ndarray, true: np.ndarray, scale: float) -> bool:
    r"""Product :math:`P_{jk}` of row i is fixed by the partner :math:`C_{ik}` and not by
    :math:`C_{ij}` (``doc``/``true``: :math:`\Gamma_{i,\cdot\cdot}` on the H samples,
    S × n × n)."""
    target = true[:, j, k] + true[:, k, j]
    mine = true[:, j, k] + doc[:, k, j]
    partner = doc[:, j, k] + true[:, k, j]
    return agrees(partner, target, scale) and not agrees(mine, target, scale)


#: Kinds that name a product's error at its h element (a rule of the last kind above).
SAID = (K.SIGN, K.FACTOR, K.POWER, K.SWAP, K.MISSING, K.EXTRA, K.POINT_MASS,
        K.PARALLEL_AXIS, K.SMALL_ANGLE)


def _shared(i: int, j: int, k: int, doc: np.ndarray, true: np.ndarray, scale: float) -> bool:
    r"""Product :math:`P_{jk}` (:math:`k \ne j`) of row i is fixed neither by
    :math:`C_{ij}` alone nor by its partner :math:`C_{ik}` alone (module text), and the
    document splits it between them otherwise than the truth does: with
    :math:`(a, b)` the document's :math:`(\Gamma_{i,jk}, \Gamma_{i,kj})` and :math:`(c, d)`
    the truth's, :math:`ad \ne bc` somewhere. Split alike (an arm's C built from a c whose
    :math:`2h\dot q_1\dot q_2` lost its 2: each half is half the truth's), each element
    carries the error: it differs."""
    target = true[:, j, k] + true[:, k, j]
    if agrees(true[:, j, k] + doc[:, k, j], target, scale) or \
            agrees(doc[:, j, k] + true[:, k, j], target, scale):
        return False
    a, b, c, d = doc[:, j, k], doc[:, k, j], true[:, j, k], true[:, k, j]
    size = max(float(np.abs(x).max(initial=0.0)) for x in (a, b, c, d))
    return not agrees(a * d, b * c, scale * size)


def _still(expr: sp.Expr | None, velocities: Sequence[sp.Symbol]) -> sp.Expr:
    r"""The part of a C element ``expr`` without a velocity (0 for none, or no expression)."""
    if expr is None or not velocities:
        return sp.Integer(0)
    return sp.expand(expr).as_independent(*velocities, as_Add=True)[0]


def factorization(drafts: Sequence[ElementDraft], gammas: dict[int, tuple[np.ndarray,
                  np.ndarray]], velocities: Sequence[sp.Symbol] = ()) -> None:
    r"""Judge the differing C drafts by their products (module text), in place. ``gammas``:
    per row, the document's and the framed truth's :math:`\Gamma_{i,\cdot\cdot}` (absent
    where unknown: then only the first rule applies). A C element with a term free of the
    ``velocities`` (``C = [[1]]``) makes :math:`C\dot q` linear in them, which the products
    do not see: it differs, and says so."""
    by_key = {(r.key, r.index): r for r in drafts}
    for r in drafts:
        if r.key != "C" or r.verdict != Verdict.DIFFERS or first_of(r.diagnoses, K.DIMENSION):
            continue
        still = _still(r.expr, velocities)
        if still != 0:
            text = sp.sstr(still)
            r.diagnoses.insert(0, diagnosis(
                K.EXTRA, f"the term {text} has no velocity: C q̇ has a term linear in the "
                "velocities, which the truth's h has not (its terms are products of two)",
                prefix="extra", terms=(text,)))
            continue
        i, j = r.index
        n = max((x.index[1] for x in drafts if x.key == "C" and x.index[0] == i), default=-1) + 1
        found = [(k, _product(by_key, i, j, k)) for k in range(n)]
        products = [(k, p) for k, p in found if p is not None]
        if len(products) < n:                   # a product not compared
            continue
        verdicts = {p.verdict for _, p in products}
        if verdicts <= {Verdict.AGREES, Verdict.AGREES_IF}:
            special = [p for _, p in products if p.verdict == Verdict.AGREES_IF]
            if special:
                cond = first_of(special[0].diagnoses, K.CONDITION)
                text = cond.condition if cond is not None else ""
                r.verdict = Verdict.AGREES_IF
                r.diagnoses = [Diagnosis(K.CONDITION, f"agrees only if {text}", text,
                                         condition=text)]
                continue
            r.verdict = Verdict.FACTORIZATION
            r.diagnoses = [Diagnosis(K.FACTORIZATION, f"C q̇ agrees in row {i + 1}: only the "
                                     "factorisation of C differs, not the equations")]
            continue
        if i not in gammas:
            continue
        doc, true = gammas[i]
        bad = [k for k, p in products if p.verdict != Verdict.AGREES]
        if j in bad:
            continue
        if all(_innocent(i, j, k, doc, true, r.scale) for k in bad):
            names = ", ".join(f"C[{i + 1},{k + 1}]" for k in bad)
            r.verdict = Verdict.FACTORIZATION
            r.diagnoses = [Diagnosis(K.FACTORIZATION, f"the h terms of row {i + 1} it takes "
                                     f"part in differ only where {names} is wrong: this "
                                     "element's difference is a factorisation of C")]
            continue
        said = {k: p for k, p in products if k in bad and p.verdict == Verdict.DIFFERS
                and any(x.kind in SAID for x in p.diagnoses)}
        if len(said) == len(bad) and all(_shared(i, j, k, doc, true, r.scale) for k in bad):
            names = ", ".join(p.element for p in said.values())
            r.verdict = Verdict.FACTORIZATION
            r.diagnoses = [Diagnosis(K.FACTORIZATION, f"the h terms of row {i + 1} it takes "
                                     f"part in differ only in {names}, said there: it shares "
                                     "them with another element of C, split otherwise than "
                                     "the truth's (a factorisation of C)")]


__all__ = ["factorization"]
