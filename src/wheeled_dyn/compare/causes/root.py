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

from ...compiled import numpy_function
from ...sympy_text import parse
from ..judge.diagnose import AGREE_TOL, agrees
from ..sides.evaluation import Evaluation
from ..records import (SPECIFIC_KINDS, Cause, CauseKind, DiagnosisKind as K, ElementRecord, Step,
                       Verdict, first_of)

#: Share of samples at which A must have rank n − m to call the constraints substituted.
RANK_SHARE = 0.99
#: Relative size below which an eigenvalue of A counts as zero.
RANK_TOL = 1e-9
#: Verdicts of records a cause can explain (never an element whose equation is right only in
#: its factorisation: those get no cause).
EXPLAINED_VERDICTS = (Verdict.DIFFERS, Verdict.AGREES_IF, Verdict.UNDECIDED)


def christoffel_tensor(A: sp.MatrixBase, positions: Sequence[sp.Symbol]) -> list:
    r"""The Christoffel symbols of the first kind of ``A``,
    :math:`H_{ijk} = \tfrac12(\partial_k A_{ij} + \partial_j A_{ik} - \partial_i A_{jk})`
    (nested lists ``[i][j][k]``, symmetric in j, k), so that
    :math:`h^{chr}_i = \sum_{jk} H_{ijk}\nu_j\nu_k`."""
    n = len(positions)
    dA = [A.diff(p) for p in positions]
    return [[[(dA[k][i, j] + dA[j][i, k] - dA[i][j, k]) / 2 for k in range(n)]
             for j in range(n)] for i in range(n)]


def christoffel_h(A: sp.MatrixBase, positions: Sequence[sp.Symbol],
                  velocities: Sequence[sp.Symbol]) -> sp.Matrix:
    r""":math:`h^{chr}` of the module text: the Christoffel terms of ``A`` with velocity
    :math:`k` taken as the rate of position :math:`k`."""
    n = len(positions)
    H = christoffel_tensor(A, positions)
    return sp.Matrix([sp.Add(*[H[i][j][k] * velocities[j] * velocities[k]
                               for j in range(n) for k in range(n) if H[i][j][k] != 0])
                      for i in range(n)])


def _product(element: str) -> tuple[int, str] | None:
    r"""``h[2]:dx*dpsi`` → (1, ``dx*dpsi``)."""
    if not element.startswith("h[") or ":" not in element:
        return None
    head, prod = element.split(":", 1)
    return int(head[2:-1]) - 1, prod


def _own_christoffel(ev: Evaluation, d) -> dict[tuple[int, int, int], bool] | None:
    r"""For each product :math:`(i, j, k)` of the document's h, whether it equals
    :math:`h^{chr}` of the document's own A (None when A or h is missing or lost)."""
    A, h = ev.funcs.exprs.get("A"), ev.funcs.exprs.get("h")
    if A is None or h is None or ev.doc.H is None or sp.Matrix(A).has(sp.nan):
        return None
    scale = [1 if c is None else sp.nsimplify(1 / c) for c in ev.row_factor]
    H = sp.Array([[[scale[i] * x for x in row] for row in plane]
                  for i, plane in enumerate(christoffel_tensor(sp.Matrix(A), d.positions))])
    flat = sp.flatten(H.tolist())
    fn = numpy_function(ev.funcs.args, flat)
    rows = ev.truth.H_rows if ev.truth.H_rows is not None else np.arange(len(ev.q))
    argv = [*ev.q[rows].T, *ev.nu[rows].T, *(np.asarray(ev.values[p])[rows]
                                            for p in ev.funcs.params)]
    vals = np.stack([np.broadcast_to(np.asarray(v, float), (len(rows),)) for v in fn(*argv)],
                    axis=1).reshape(len(rows), *H.shape)
    n = d.n
    out = {}
    for i in range(n):
        if sp.Matrix(h).row(i).has(sp.nan):
            continue
        for j in range(n):
            for k in range(j, n):
                D = ev.doc.H[:, i, j, k]
                if np.isfinite(D).all():
                    out[(i, j, k)] = agrees(D, vals[:, i, j, k], ev.scales[i])
    return out


def _specific(r) -> bool:
    r"""A diagnosis naming one term's error precisely: the element is left to its
    single-term cause rather than to a method cause."""
    return any(x.kind in SPECIFIC_KINDS for x in r.diagnoses)


def covered_products(records: Sequence, velocities: Sequence[sp.Symbol]) -> dict[str, str]:
    r"""h products explained by a single-term error of a C element of their row: a product
    :math:`\nu_j\nu_k` of row i containing the velocity of the column of a differing
    ``C[i, c]`` that has a specific diagnosis (``C[3,2]`` with φ̇ written for ψ̇ explains
    ``h[3]:dpsi*dpsi`` and ``h[3]:dpsi*dphi``). Maps the h element to the C element."""
    out: dict[str, str] = {}
    for c in records:
        if c.key != "C" or c.verdict not in EXPLAINED_VERDICTS or not _specific(c):
            continue
        i, col = c.index
        for r in records:
            if r.key != "h" or r.index[0] != i or r.verdict not in EXPLAINED_VERDICTS:
                continue
            own = [x for x in r.diagnoses if x.kind in SPECIFIC_KINDS and x.kind != K.SWAP]
            if not own and col in r.index[1:]:
                out.setdefault(r.element, c.element)
    return out


def method_causes(ev: Evaluation, d, records: Sequence) -> list[Cause]:
    r"""Quasi-coordinate Christoffel and C-inconsistent-with-A causes (module text); elements
    with a precise single-term diagnosis, and h products such a C element explains
    (:func:`covered_products`), are left to the single-term causes."""
    own = _own_christoffel(ev, d)
    if own is None:
        return []
    names = [str(v) for v in d.velocities]
    covered = covered_products(records, d.velocities)
    by_product = {tuple(r.index): r for r in records if r.key == "h" and not _specific(r)
                  and r.element not in covered}
    quasi: list[ElementRecord] = []
    inconsistent: list[ElementRecord] = []
    for index, same in own.items():
        r = by_product.get(index)
        if r is None or r.verdict != Verdict.DIFFERS:
            continue
        (quasi if same else inconsistent).append(r)
    # a C said not to come from the document's own A: only where the document gives a C
    # (equations written out, Kane's method, never took one from A's Christoffel terms)
    if d.C is None:
        inconsistent = []

    def c_elements(rows: set[int]) -> tuple[str, ...]:
        r"""The differing C elements of ``rows`` without a precise diagnosis of their own."""
        return tuple(r.element for r in records if r.key == "C" and r.index[0] in rows
                     and r.verdict == Verdict.DIFFERS and not _specific(r))

    out = []
    # with coordinates (not quasi-velocities) an h term equal to A's Christoffel term but not
    # to the truth follows from A, whose own records say what differs: no cause of its own
    if quasi and ev.kind == "quasi":
        out.append(Cause(
            kind=CauseKind.QUASI_COORDINATE_CHRISTOFFEL,
            elements=tuple(r.element for r in quasi) + c_elements({q.index[0] for q in quasi}),
            explanation=("the document's C is the Christoffel matrix of its own A taken as if "
                         f"its velocities ({', '.join(names)}) were rates of coordinates; at least "
                         "one is a quasi-velocity (q̇ = S ν), so the SᵀAṠ (Boltzmann–Hamel) terms "
                         "are missing" + (" (truth − document below)"
                                          if any(r.residual for r in quasi) else "")),
            latex=_missing_terms_latex(quasi, d)))
    if inconsistent:
        rows = {q.index[0] for q in inconsistent}
        out.append(Cause(
            kind=CauseKind.C_INCONSISTENT_WITH_A,
            elements=tuple(r.element for r in inconsistent) + c_elements(rows),
            explanation=("these velocity products of C q̇ are not the Christoffel terms of the "
                         "document's own A (nor the truth's): C was not derived from this A "
                         f"(rows {', '.join(str(i + 1) for i in sorted(rows))})")))
    return out


def velocity_latex(d) -> dict[sp.Symbol, str]:
    r"""LaTeX of the document's velocities as it writes them: the rate of a position
    (``dpsi`` of ``psi``) dotted, :math:`\dot\psi`; a quasi-velocity that is no position's
    rate (``u``, ``n``, ``wx``) by its own name."""
    positions = {str(p): p for p in d.positions}
    out = {}
    for v in d.velocities:
        p = positions.get(str(v)[1:]) if str(v).startswith("d") else None
        out[v] = rf"\dot{{{sp.latex(p)}}}" if p is not None else sp.latex(v)
    return out


def _missing_terms_latex(records: Sequence, d) -> str:
    r"""The truth − document terms of h records, as equations per row in LaTeX
    (:math:`\Delta h_1 = m_S d\sin\varphi\,\dot\psi^2`), velocities dotted."""
    by_row: dict[int, sp.Expr] = {}
    for r in records:
        p = _product(r.element)
        if p is None or not r.residual:
            continue
        coeff = parse(r.residual)
        if coeff is None:
            return ""
        velocity = {str(v): v for v in d.velocities}
        product = sp.Mul(*(velocity[name] for name in p[1].split("*") if name in velocity))
        by_row[p[0]] = by_row.get(p[0], sp.Integer(0)) + coeff * product
    names = velocity_latex(d)
    return r",\qquad ".join(rf"\Delta h_{{{i + 1}}} = " + sp.latex(
        e.xreplace({s: v for v in d.velocities for s in e.free_symbols if s.name == str(v)}),
        symbol_names=names) for i, e in sorted(by_row.items()))


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
    (K.EXTRA, CauseKind.MISSING_PHYSICS, "a term the truth does not have"),
)


def _one_swap(r, hit) -> str:
    r"""The two halves of a swapped velocity product in h — ``h[3]:dpsi*dpsi`` "written as
    dphi*dphi in the document" and ``h[3]:dphi*dphi`` "the document's dphi*dphi term is the
    true dpsi*dpsi term" — as one sentence, so they make one cause."""
    p = _product(r.element)
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
        for dkind, kind, sentence in TERM_KINDS:
            hit = first_of(r.diagnoses, dkind)
            if hit is not None:
                detail = hit.detail or sentence
                detail = _one_swap(r, hit) if dkind == K.SWAP else detail
                if dkind == K.SMALL_ANGLE:            # one cause per coordinate
                    detail = (f"the document takes {hit.position} as small (sin({hit.position})"
                              f" ≈ {hit.position}, cos({hit.position}) ≈ 1) but declares no "
                              "linearisation (linearised_about): compared with the exact "
                              "equations")
                key = (kind, sentence if kind == CauseKind.MISSING_PHYSICS else detail)
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
    return [Cause(kind=kind, elements=tuple(elements), explanation=text)
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


__all__ = ["christoffel_h", "christoffel_tensor", "claim_causes", "constraint_cause",
           "covered_products", "document_causes", "method_causes", "root_causes",
           "term_causes"]
