r"""Root causes: the few reasons that explain a derivation's differing elements.

The element records say *what* differs; this module says *why*, as
:class:`~wheeled_dyn.compare.records.Cause` records, most important first:

**Method errors** (found from the document's own matrices, with the truth as witness)

- *quasi-coordinate Christoffel*: the document's :math:`h = C\nu` equals the Christoffel terms
  of its own :math:`A`,

  .. math:: h^{chr}_i = \sum_{jk} \tfrac12\big(\partial_k A_{ij} + \partial_j A_{ik}
            - \partial_i A_{jk}\big)\,\nu_j\nu_k,

  taken as if each velocity :math:`\nu_k` were the rate of the position :math:`p_k`, while the
  truth differs: with quasi-velocities :math:`\dot q = S\nu` the equations have
  :math:`C_\nu = S^TCS + S^TA\dot S`, and the :math:`S^TA\dot S` (Boltzmann–Hamel) terms are the
  difference, given in closed form where the truth has one.
- *C not consistent with the document's own A*: products :math:`\nu_j\nu_k` of :math:`h` that
  are neither :math:`h^{chr}` nor the truth (no truth is needed to see the first; the second
  keeps a correct quasi-velocity document, whose :math:`h` is *not* :math:`h^{chr}`, unflagged).
- *constraint substituted into the Lagrangian*: a document that keeps :math:`m` constraint rows
  with multipliers has an :math:`A` of rank :math:`n - m`: its kinetic energy was written with
  the constraints substituted (a function of :math:`n - m` velocities). Where the truth's
  constraint rows are known, the sentence says whether :math:`N^TA_{doc}N = N^TA N` on the
  admissible velocities :math:`N` (the energy is right on the constrained motion).
- *claimed relation*: a relation the document states between coordinates (a ``claim`` step)
  that the model's kinematics contradict, with the true one.

**Single-term errors and physics**: one cause per diagnosis kind (sign, factor, power, swap,
dimension, missing or extra physics, a condition the document did not state), naming every
element it explains; C-level and h-level flags of the same row are one cause.

**The document on its own**: energy not conserved, A not positive definite.

An element is explained by at most one cause (the first in this order).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...sympy_text import parse
from ..judge.diagnose import AGREE_TOL
from ..sides.evaluation import Evaluation
from ..records import Cause, CauseKind, DiagnosisKind as K, Step, Verdict, first_of
from .methods import (EXPLAINED_VERDICTS, covered_products, method_causes, product_of,
                      terms_said, velocity_latex)

#: Share of samples at which A must have rank n − m to call the constraints substituted.
RANK_SHARE = 0.99
#: Relative size below which an eigenvalue of A counts as zero.
RANK_TOL = 1e-9


def constraint_cause(ev: Evaluation, records: Sequence) -> list[Cause]:
    r"""The constraint substituted into the Lagrangian (module text)."""
    A, G = ev.doc.A, ev.doc.G
    if A is None or G is None or not np.isfinite(A).all():
        return []
    n, m = A.shape[1], G.shape[1]
    sv = np.linalg.svd(A, compute_uv=False)         # rank is blind to row factors
    rank = (sv > RANK_TOL * np.maximum(sv[:, :1], 1e-300)).sum(axis=1)
    if np.mean(rank == n - m) < RANK_SHARE:
        return []
    differing = tuple(r.element for r in records if r.key == "A"
                      and r.verdict in EXPLAINED_VERDICTS)
    if not differing:
        return []
    witness = ""
    if ev.truth.G is not None and ev.truth.A is not None:
        _, s, vt = np.linalg.svd(ev.truth.G)
        r_true = int(np.median((s > RANK_TOL * np.maximum(s[:, :1], 1e-300)).sum(axis=1)))
        N = np.swapaxes(vt[:, r_true:, :], 1, 2)                       # admissible velocities
        on_doc = np.swapaxes(N, 1, 2) @ A @ N
        on_true = np.swapaxes(N, 1, 2) @ ev.truth.A @ N
        scale = float(max(np.abs(on_true).max(), 1e-300))
        same = bool(np.abs(on_doc - on_true).max() <= AGREE_TOL * 10 * scale)
        witness = ("; on the admissible motions it equals the true kinetic energy" if same else
                   "; even on the admissible motions it differs from the true kinetic energy")
    return [Cause(
        kind=CauseKind.CONSTRAINT_IN_LAGRANGIAN, elements=differing,
        explanation=(f"A has rank {n - m} of {n}: the kinetic energy was written with the "
                     f"{m} constraint{'s' if m > 1 else ''} substituted (a function of "
                     f"{n - m} velocities) and then used with multipliers{witness}; with "
                     "multipliers, Lagrange's equations need the unconstrained kinetic energy"))]


def claim_causes(records: Sequence) -> list[Cause]:
    r"""Claims (relations the document states) that the model contradicts."""
    out = []
    for r in records:
        if r.step == Step.CLAIM and r.verdict == Verdict.DIFFERS:
            why = next((x.text for x in r.diagnoses if x.kind != K.RESIDUAL),
                       "the model's kinematics contradict it")
            out.append(Cause(kind=CauseKind.CLAIMED_RELATION, elements=(r.element,),
                             explanation=f"{r.element}: {why}", step=r.step,
                             equation=r.equation))
    return out


#: Single-term diagnoses, in the order their causes are listed: (diagnosis kind, cause kind,
#: sentence).
TERM_KINDS = (
    (K.COMMON_DIVISOR, CauseKind.UPSTREAM_STEP, "the equations were solved with a wrong "
     "determinant (one divisor common to every solved equation)"),
    (K.DIMENSION, CauseKind.DIMENSION, "a term with inconsistent units"),
    (K.POINT_MASS, CauseKind.POINT_MASS, "a body's own inertia about its centre of mass is "
     "missing (a point mass)"),
    (K.PARALLEL_AXIS, CauseKind.PARALLEL_AXIS, "a body's inertia about its centre of mass "
     "written where the one about the joint's axis fits (the parallel-axis term is missing)"),
    (K.SIGN, CauseKind.SIGN, "the document has the opposite sign"),
    (K.POWER, CauseKind.POWER, "a symbol to the wrong power"),
    (K.FACTOR, CauseKind.FACTOR, "a constant factor"),
    (K.SWAP, CauseKind.SWAP, "one symbol written for another"),
    (K.SMALL_ANGLE, CauseKind.SMALL_ANGLE, "a small-angle approximation"),
    (K.MISSING, CauseKind.MISSING_PHYSICS, "a term the document leaves out"),
    (K.EXTRA, CauseKind.EXTRA_TERM, "a term the truth does not have"),
)


def _term_kinds(diagnoses: Sequence) -> tuple:
    r""":data:`TERM_KINDS`, with a symbol written for another before a term's factor where the
    element says the swap first (a factor that is the ratio of two of the model's parameters:
    :func:`~..judge.element.judge`), and any term's diagnosis before the units where the
    element says it first (a term not divided as the rest of its row: its units follow; a
    dropped inertia beside a length written as a number); a factor that holds only under a
    family the document did not state (3 × the truth if a wheel is uniform) after the terms
    the element names missing or too much (:math:`m_w R^2`)."""
    kinds = [x.kind for x in diagnoses]
    order = list(TERM_KINDS)
    factor = first_of(diagnoses, K.FACTOR)
    if factor is not None and factor.condition and any(
            x.kind in (K.MISSING, K.EXTRA) and x.terms for x in diagnoses):
        # a factor that holds only under a family the document did not state (3 × the truth
        # if the wheel is uniform) after the exact terms missing or too much (m_w R²)
        order.remove(next(t for t in order if t[0] == K.FACTOR))
        order.append(next(t for t in TERM_KINDS if t[0] == K.FACTOR))
    if K.SWAP in kinds and K.FACTOR in kinds and kinds.index(K.SWAP) < kinds.index(K.FACTOR):
        swap = next(t for t in order if t[0] == K.SWAP)
        order.remove(swap)
        order.insert(next(i for i, t in enumerate(order) if t[0] == K.FACTOR), swap)
    if K.DIMENSION in kinds:
        term_kinds = {t[0] for t in TERM_KINDS}
        said = next((k for k in kinds if k in term_kinds), K.DIMENSION)
        if said != K.DIMENSION:
            units = next(t for t in order if t[0] == K.DIMENSION)
            order.remove(units)
            order.insert(next(i for i, t in enumerate(order) if t[0] == said) + 1, units)
    return tuple(order)


def _one_swap(r, hit) -> str:
    r"""The two halves of a swapped velocity product in h — ``h[3]:dpsi*dpsi`` "written as
    dphi*dphi in the document" and ``h[3]:dphi*dphi`` "the document's dphi*dphi term is the
    true dpsi*dpsi term" — as one sentence, so they make one cause."""
    p = product_of(r.element)
    if p is None or not hit.written or hit.fits != p[1]:
        return hit.detail
    rest = f" (equal only if {hit.condition})" if hit.condition else ""
    return f"the document's {hit.written} term is the true {p[1]} term{rest}"


def term_causes(records: Sequence, explained: set[str],
                velocities: Sequence[sp.Symbol] = ()) -> list[Cause]:
    r"""One cause per single-term diagnosis (``dimension``, ``sign``, ``power``, ``factor``,
    ``swap``, ``missing``/``extra``) and per unstated condition (``agrees_if``), each naming
    the elements it explains; the exact diagnosis of each element stays on its record."""
    groups: dict[tuple[CauseKind, str], list[str]] = {}
    for r in records:
        if r.element in explained or r.verdict not in EXPLAINED_VERDICTS \
                or r.step != Step.EQUATIONS_OF_MOTION:
            continue
        if r.verdict == Verdict.AGREES_IF:
            cond = first_of(r.diagnoses, K.CONDITION)
            text = "holds only if " + (cond.condition if cond is not None else "")
            groups.setdefault((CauseKind.ASSUMPTION, text), []).append(r.element)
            continue
        for dkind, kind, sentence in _term_kinds(r.diagnoses):
            hit = first_of(r.diagnoses, dkind)
            if hit is not None:
                detail = hit.detail or sentence
                detail = _one_swap(r, hit) if dkind == K.SWAP else detail
                if dkind == K.SMALL_ANGLE:            # one cause per coordinate
                    detail = (f"the document takes {hit.position} as small (sin({hit.position})"
                              f" ≈ {hit.position}, cos({hit.position}) ≈ 1) but declares no "
                              "linearisation (linearised_about): compared with the exact "
                              "equations")
                key = (kind, sentence if kind in (CauseKind.MISSING_PHYSICS,
                                                  CauseKind.EXTRA_TERM) else detail)
                groups.setdefault(key, []).append(r.element)
                break
    covered = covered_products(records, velocities)
    for elements in groups.values():
        for h, c in covered.items():
            if c in elements and h not in explained and h not in elements:
                elements.append(h)
    taken = {h for elements in groups.values() for h in elements if h in covered}
    for elements in groups.values():
        elements[:] = [e for e in elements if e not in covered or e in taken
                       and covered[e] in elements]
    by_element = {r.element: r for r in records}
    return [Cause(kind=kind, elements=tuple(elements), explanation=text + (
                terms_said([by_element[e] for e in elements if e in by_element],
                           (K.MISSING,) if kind == CauseKind.MISSING_PHYSICS else (K.EXTRA,))
                if kind in (CauseKind.MISSING_PHYSICS, CauseKind.EXTRA_TERM) else ""))
            for (kind, text), elements in groups.items() if elements]


def document_causes(energy, asymmetric: Sequence[str], d=None) -> list[Cause]:
    r"""What the document fails on its own: energy (the power :math:`\nu^Th -
    \tfrac12\nu^T\dot A\nu` as math when it reads), positive definiteness."""
    out = []
    if energy is not None and not energy.conserves:
        latex = _power_latex(energy.residual, d)
        out.append(Cause(kind=CauseKind.ENERGY, elements=(), latex=latex,
                         explanation=("the model as printed does not conserve energy: its "
                                      "gyroscopic terms do work, ν·h − ½ ν·Ȧν ≠ 0"
                                      + (" (below)" if latex else f": {energy.residual}"))))
    pd = [x for x in asymmetric if "positive definite" in x]
    if pd:
        out.append(Cause(kind=CauseKind.NOT_POSITIVE_DEFINITE, elements=(), explanation=pd[0]))
    return out


def _power_latex(residual: str, d) -> str:
    r""":math:`\nu^Th - \tfrac12\nu^T\dot A\nu = \dots` in LaTeX, velocities dotted, or
    ``""``."""
    if d is None:
        return ""
    expr = parse(residual)
    if expr is None:
        return ""
    own = {str(v): v for v in (*d.positions, *d.velocities)}
    expr = expr.xreplace({s: own[s.name] for s in expr.free_symbols if s.name in own})
    return r"\nu^T h - \tfrac{1}{2}\nu^T \dot A \nu = " + sp.latex(
        expr, symbol_names=velocity_latex(d))


def root_causes(ev: Evaluation | None, d, records: Sequence, energy, asymmetric: Sequence[str],
                first: Sequence[Cause] = ()) -> tuple[Cause, ...]:
    r"""Every cause of one derivation, in the module's order; ``first``: causes found before
    (a convention). Each element is explained by the first cause that names it."""
    found: list[Cause] = list(first)
    if ev is not None:
        found += method_causes(ev, d, records)
        found += constraint_cause(ev, records)
    out: list[Cause] = []
    explained: set[str] = set()
    for c in found:
        fresh = tuple(e for e in c.elements if e not in explained)
        if c.elements and not fresh:
            continue
        explained.update(fresh)
        out.append(c if fresh == c.elements else Cause(c.kind, fresh, c.explanation, c.latex,
                                                       c.step, c.equation))
    out += term_causes(records, explained, d.velocities)
    out += document_causes(energy, asymmetric, d)
    return tuple(out)


__all__ = ["claim_causes", "constraint_cause", "document_causes", "root_causes",
           "term_causes"]
