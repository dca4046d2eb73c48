r"""Method causes: the document's velocity terms taken from its own inertia matrix.

- *quasi-coordinate Christoffel*: the document's :math:`h = C\nu` equals the Christoffel terms
  of its own :math:`A`,

  .. math:: h^{chr}_i = \sum_{jk} \tfrac12\big(\partial_k A_{ij} + \partial_j A_{ik}
            - \partial_i A_{jk}\big)\,\nu_j\nu_k,

  taken as if each velocity :math:`\nu_k` were the rate of the position :math:`p_k` (on the
  products that differ, and on one that is not zero), while the truth differs: with
  quasi-velocities :math:`\dot q = S\nu` the equations have :math:`C_\nu = S^TCS +
  S^TA\dot S`, and the :math:`S^TA\dot S` (Boltzmann–Hamel) terms are the difference;
- *C not consistent with the document's own A*: products of :math:`h` that are neither
  :math:`h^{chr}` nor the truth.

Elements with a precise single-term diagnosis, and the h products a C element with one
explains (:func:`covered_products`), are left to the single-term causes (:mod:`.root`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...compiled import numpy_function
from ...sympy_text import parse
from ..judge.diagnose import agrees
from ..sides.evaluation import Evaluation
from ..records import SPECIFIC_KINDS, Cause, CauseKind, DiagnosisKind as K, ElementRecord, Verdict

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


def product_of(element: str) -> tuple[int, str] | None:
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


def _from_own_christoffel(ev: Evaluation, own: dict[tuple[int, int, int], bool]) -> bool:
    r"""Whether the document took some of its velocity terms from the Christoffel terms of
    its own A: one product that is not zero equals :math:`h^{chr}` (a product it leaves out,
    zero where :math:`h^{chr}` is zero too, is no sign of it: a document whose velocity terms
    are all its own, none :math:`h^{chr}`, left a term out for another reason)."""
    H = ev.doc.H
    return H is not None and any(same and np.abs(H[:, i, j, k]).max(initial=0.0) > 0
                                 for (i, j, k), same in own.items())


def _from_wrong_A(index: Sequence[int], wrong: dict[tuple[int, int], sp.Expr | None],
                  residual: sp.Expr | None, positions: Sequence[sp.Symbol]
                  ) -> list[tuple[int, int]]:
    r"""The elements of A that differ (``wrong``: by element, their truth − document) whose
    difference :math:`\Delta A` gives h product ``index`` = (i, j, k) its whole
    ``residual`` (truth − document) through the Christoffel terms,
    :math:`\tfrac12(\partial_k\Delta A_{ij} + \partial_j\Delta A_{ik} - \partial_i\Delta
    A_{jk})` (twice that for j ≠ k): the product follows from A. Empty where it does not —
    the terms cancel or are zero, a residual is unknown, or the product differs by more (a
    Boltzmann–Hamel term A does not give)."""
    i, j, k = index
    if residual is None:
        return []
    parts = [((i, j), k), ((i, k), j), ((j, k), i)]
    rates: list[sp.Expr] = []
    for (a, b), m in parts:
        e = wrong.get((a, b), wrong.get((b, a), sp.Integer(0)))
        if e is None:
            return []                                   # a difference not known
        x = {str(s): s for s in e.free_symbols}.get(str(positions[m]))
        rates.append(sp.diff(e, x) if x is not None else sp.Integer(0))
    christoffel = (rates[0] + rates[1] - rates[2]) / 2 * (1 if j == k else 2)
    if christoffel == 0:
        return []
    if not _same_function(residual, christoffel):
        return []
    return [e if e in wrong else (e[1], e[0]) for (e, _), rate in zip(parts, rates)
            if rate != 0 and (e in wrong or (e[1], e[0]) in wrong)]


#: Random points two expressions are compared at, and their relative tolerance.
SAME_AT, SAME_TOL = 3, 1e-9


def _same_function(a: sp.Expr, b: sp.Expr) -> bool:
    r"""Whether ``a`` and ``b`` (symbols matched by name) take the same values at
    :data:`SAME_AT` random points (seeded; each name drawn in [0.3, 1.3]): numbers, not
    ``simplify`` (seconds on a trigonometric polynomial)."""
    names = sorted({str(x) for x in (*a.free_symbols, *b.free_symbols)})
    rng = np.random.default_rng(len(names))
    for _ in range(SAME_AT):
        point = dict(zip(names, rng.uniform(0.3, 1.3, len(names))))
        try:
            x, y = (complex(e.xreplace({s: point[str(s)] for s in e.free_symbols}))
                    for e in (a, b))
        except (TypeError, ValueError):
            return False
        if abs(x - y) > SAME_TOL * max(abs(x), abs(y), 1e-300):
            return False
    return True


def specific(r) -> bool:
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
        if c.key != "C" or c.verdict not in EXPLAINED_VERDICTS or not specific(c):
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
    by_product = {tuple(r.index): r for r in records if r.key == "h" and not specific(r)
                  and r.element not in covered}
    quasi: list[ElementRecord] = []
    inconsistent: list[ElementRecord] = []
    from_A = _from_own_christoffel(ev, own)
    for index, same in own.items():
        r = by_product.get(index)
        if r is None or r.verdict != Verdict.DIFFERS:
            continue
        if not same:
            inconsistent.append(r)
        elif from_A:
            quasi.append(r)
    # a C said not to come from the document's own A: only where the document gives a C
    # (equations written out, Kane's method, never took one from A's Christoffel terms)
    if d.C is None:
        inconsistent = []

    def c_elements(rows: set[int]) -> tuple[str, ...]:
        r"""The differing C elements of ``rows`` without a precise diagnosis of their own."""
        return tuple(r.element for r in records if r.key == "C" and r.index[0] in rows
                     and r.verdict == Verdict.DIFFERS and not specific(r))

    out = []
    # with coordinates (not quasi-velocities) an h term equal to A's Christoffel term but not
    # to the truth follows from A, whose own records say what differs: no cause of its own;
    # with quasi-velocities, a product whose whole difference the Christoffel terms of A's
    # own difference give follows from A too (an upstream cause), not from S^T A Ṡ
    wrong_A = {(r.index[0], r.index[1]): parse(r.residual) if r.residual else None
               for r in records if r.key == "A" and r.verdict == Verdict.DIFFERS}
    along = {r.element: _from_wrong_A(r.index, wrong_A, parse(r.residual) if r.residual
                                      else None, d.positions) for r in quasi}
    derived = [r for r in quasi if along[r.element]] if ev.kind == "quasi" else []
    quasi = [r for r in quasi if not along[r.element]]
    if quasi and ev.kind == "quasi":
        out.append(Cause(
            kind=CauseKind.QUASI_COORDINATE_CHRISTOFFEL,
            elements=tuple(r.element for r in quasi) + c_elements({q.index[0] for q in quasi}),
            explanation=("the document's C is the Christoffel matrix of its own A taken as if "
                         f"its velocities ({', '.join(names)}) were rates of coordinates; with "
                         "q̇ = S ν, at least one is a quasi-velocity or S eliminates constraints "
                         "that are not integrable, so the SᵀAṠ (Boltzmann–Hamel) terms are "
                         "missing" + (" (truth − document below)"
                                          if any(r.residual for r in quasi) else "")),
            latex=_missing_terms_latex(quasi, d)))
    if derived:
        sources = sorted({e for r in derived for e in along[r.element]})
        held = ", ".join(f"A[{a + 1},{b + 1}]" for a, b in sources)
        out.append(Cause(
            kind=CauseKind.UPSTREAM_STEP,
            elements=tuple(r.element for r in derived) + c_elements({q.index[0] for q in derived}),
            explanation=("these velocity products are the Christoffel terms of the document's "
                         f"own A along elements of it that differ ({held}): they follow from "
                         "them, whose own records say what differs")))
    if inconsistent:
        rows = {q.index[0] for q in inconsistent}
        out.append(Cause(
            kind=CauseKind.C_INCONSISTENT_WITH_A,
            elements=tuple(r.element for r in inconsistent) + c_elements(rows),
            explanation=("these velocity products of C q̇ are not the Christoffel terms of the "
                         "document's own A (nor the truth's): C was not derived from this A "
                         f"(rows {', '.join(str(i + 1) for i in sorted(rows))})"
                         + terms_said(inconsistent))))
    return out


#: Velocity products whose terms the C-inconsistent cause says (a few dropped or added; more
#: are a method's error, said by the cause alone).
TERMS_SAID = 3


def terms_said(records: Sequence, kinds: tuple = (K.MISSING, K.EXTRA)) -> str:
    r"""The terms the records name as lacking or too much (a centripetal term dropped from a
    C otherwise right: "; h[2]:dtheta*dtheta lacks -m2*r"; one entry read back before the
    equations were solved, said once for every element it reaches), or ``""`` where none
    names one or there are more than :data:`TERMS_SAID` (a cause of missing or extra
    terms, or of a C not derived from A, says them). A record that names none is passed
    over (a C element whose truth carries more than the product named in h: the h element
    says the term). ``kinds``: the diagnoses read (a cause of missing terms reads only the
    terms said missing: an entry read back in another frame may say the same difference as
    a term too much there)."""
    by: dict = {}
    for r in records:
        named = next((x for x in r.diagnoses if x.kind in kinds and x.terms), None)
        if named is not None:
            by.setdefault(named, []).append(r.element)
    if not by or len(by) > TERMS_SAID:
        return ""
    said = [x.detail if len(elements) > 1 else f"{elements[0]} " + (
        "lacks " if x.kind == K.MISSING else "has too much ") + ", ".join(x.terms)
        for x, elements in by.items()]
    return "; " + "; ".join(said)


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
        p = product_of(r.element)
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


__all__ = ["EXPLAINED_VERDICTS", "christoffel_h", "christoffel_tensor", "covered_products",
           "method_causes", "product_of", "specific", "terms_said", "velocity_latex"]
