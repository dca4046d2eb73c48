r"""The truth in the document's own symbols, and each differing equation corrected.

The symbolic engine gives the true elements in the model's parameters :math:`p` (Khalil's
standard parameters of the links, ``XX_link`` ...). The derivation file declares what each of
its symbols is in them, :math:`s_k = f_k(p)` (``m = M(rod)``, ``lc1 = CX(link1)``,
``I1 = IYY(link1)``). Where these declarations determine the parameters the truth depends on,
they are solved for them, :math:`p = g(s)` — one parameter at a time, each from a declaration
linear in it (``MX = m lc``, then ``YY = I + m lc²``), so the answer is unique — and the truth
reads in the document's symbols, :math:`T(g(s))`. Parameters the document's assumed families
set to zero (a centre of mass on the link's line: ``urdf_structure`` keeps the URDF's zeros)
are zero first.

Each differing equation is then given corrected: the true row in the document's frame (the
factor or combination the row was found to be), written with the document's accelerations,
velocities and inputs, :math:`\sum_j T_{ij}\ddot q_j + \sum_{j\le k} T_{i,jk}\nu_j\nu_k + T_{Q,i}
= \sum_j T_{B,ij}u_j`, as text and LaTeX ready to paste back. Nothing here decides.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import sympy as sp

from ...derivations.schema import Derivation
from ...disk_cache import DiskMemo
from ...models.registry import load_model, model_parameters
from ...symbolic import simplify
from ...symbolic.simplify import simplify_expr
from . import proportions
from .proportions import completed, equalities

#: A document expression in the model's parameters (None where it has none).
ToModel = Callable[[sp.Expr], sp.Expr | None]

#: Most declarations solved (each a SymPy solve in one unknown).
MAX_STEPS = 40
#: Rows with more operations than this are not written out corrected.
CORRECTED_LIMIT = 400


def _linear_in(eq: sp.Expr, x: sp.Symbol) -> bool:
    num = sp.numer(sp.together(eq))
    try:
        return sp.Poly(num, x).degree() == 1
    except sp.PolynomialError:
        return False


def parameter_solution(declared: Sequence[tuple[sp.Symbol, sp.Expr]],
                       document: set[sp.Symbol], unknowns: set[sp.Symbol],
                       relations: Mapping[sp.Symbol, sp.Expr]) -> dict[sp.Symbol, sp.Expr]:
    r""":math:`p = g(s)` for as many of the ``unknowns`` as the declarations :math:`s = f(p)`
    determine (module text); the others are left out (they stay model parameters)."""
    eqs = [s - v.xreplace(dict(relations)) for s, v in declared]
    eqs = [e for e in eqs if e.free_symbols - document]
    solution: dict[sp.Symbol, sp.Expr] = {}
    todo = set(unknowns)
    for _ in range(MAX_STEPS):
        step = next(((eq, x) for eq in eqs for x in sorted(eq.free_symbols & todo, key=str)
                     if _linear_in(eq, x)), None)
        if step is None:
            break
        eq, x = step
        found = sp.solve(eq, x, dict=True)
        eqs = [e for e in eqs if e is not eq]
        if len(found) != 1:
            continue
        value = sp.simplify(found[0][x])
        solution = {k: v.xreplace({x: value}) for k, v in solution.items()}
        solution[x] = value
        todo.discard(x)
        todo |= {y for y in value.free_symbols if y not in document and y not in solution}
        eqs = [e.xreplace({x: value}) for e in eqs]
        eqs = [e for e in eqs if sp.simplify(e) != 0]
    return solution


#: The truths in documents' symbols, remembered across runs (the disk cache's
#: ``compare/in-document-<code>.pickle``), keyed by everything they are computed from.
IN_DOCUMENT = DiskMemo("compare", "in-document", lambda: [
    Path(__file__), Path(proportions.__file__), Path(simplify.__file__)])


def _declarations(d: Derivation, to_model: ToModel) -> list[tuple[sp.Symbol, sp.Expr]]:
    out = []
    for spec in d.symbols.values():
        if spec.value is None or spec.is_input or spec.free:
            continue
        value = to_model(spec.symbol)
        if value is not None:
            out.append((spec.symbol, sp.sympify(value)))
    return out


@dataclass(frozen=True)
class InDocument:
    r"""The truth in a document's symbols: ``truth``, the true elements (labels as the
    engine's); ``unsolved``, each document symbol the solution does not give back as itself
    (a declared number, or a declaration no parameter was solved from) as what it is in the
    parameters left, so that the document's side is read in the same symbols as the truth."""

    truth: dict[str, sp.Expr]
    unsolved: dict[sp.Symbol, sp.Expr]


def in_document(d: Derivation, truth: Mapping[str, sp.Expr], to_model: ToModel,
                assumed: Mapping[sp.Symbol, sp.Expr], families: Sequence[str] = (),
                standard: bool = False) -> InDocument | None:
    r"""The true elements in the document's symbols where its declarations (``to_model``: a
    document expression in the model's parameters) determine the parameters (module text;
    the others stay model parameters), or None where they determine none of them.
    ``assumed``: the substitution the document's families make (a
    physical record's families, or the uniform links of a model in Khalil's parameters);
    with ``standard`` (a model in Khalil's parameters) the relations of
    :mod:`.proportions` under ``families`` too. Remembered: :data:`IN_DOCUMENT`."""
    wm = load_model(d.model)
    relations = {**(equalities(wm, families) if standard else {}), **assumed}
    relations = {k: sp.sympify(v).xreplace(relations) for k, v in relations.items()}
    declared = _declarations(d, to_model)
    values = tuple(sorted(model_parameters(wm).items())) if standard else ()
    key = (tuple(sorted(truth.items(), key=lambda kv: kv[0])), tuple(declared),
           tuple(sorted(relations.items(), key=str)), tuple(families), values,
           tuple(d.positions), tuple(d.velocities), d.model,
           tuple(sorted((spec.symbol for spec in d.symbols.values()), key=str)))
    return IN_DOCUMENT.get(key, lambda: _in_document(d, wm, truth, declared, relations,
                                                     standard, families))


def _in_document(d: Derivation, wm, truth: Mapping[str, sp.Expr],
                 declared: Sequence[tuple[sp.Symbol, sp.Expr]],
                 relations: Mapping[sp.Symbol, sp.Expr], standard: bool,
                 families: Sequence[str]) -> InDocument | None:
    motion = {*d.positions, *d.velocities}
    exprs = {k: sp.sympify(v).xreplace(relations) for k, v in truth.items()}
    names = {str(x): x for x in motion}
    document = {spec.symbol for spec in d.symbols.values()}
    exprs, declared, relations = _apart(exprs, declared, relations, document, motion)
    unknowns = {u for e in exprs.values() for u in e.free_symbols if u.name not in names}
    solution = parameter_solution(declared, document, unknowns, relations)
    if not solution:
        return None
    if standard:
        solution.update(completed(wm, families, solution))
    out = {}
    for k, e in exprs.items():
        e = e.xreplace(solution)
        e = e.xreplace({s: names[s.name] for s in e.free_symbols
                        if s.name in names and s not in motion})
        pars = sorted(e.free_symbols - motion, key=str)
        out[k] = simplify_expr(e, pars) if e.free_symbols else sp.nsimplify(e)
    unsolved = {}
    for symbol, value in declared:
        back = sp.simplify(value.xreplace(relations).xreplace(solution))
        if back != symbol:
            unsolved[symbol] = back
    return InDocument(out, unsolved)


def _apart(exprs: dict[str, sp.Expr], declared: Sequence[tuple[sp.Symbol, sp.Expr]],
           relations: Mapping[sp.Symbol, sp.Expr], document: set[sp.Symbol],
           motion: set[sp.Symbol]) -> tuple[dict[str, sp.Expr],
                                              list[tuple[sp.Symbol, sp.Expr]],
                                              dict[sp.Symbol, sp.Expr]]:
    r"""The truth, the declarations' values and the relations with each model parameter that
    has the name of a document symbol renamed ``<name>_model``: a document's ``L`` for the
    model's ``d`` beside a ``D = 2 L`` of the model's ``L`` are two quantities, never one
    (the truth was printed with one for the other)."""
    taken = {s.name for s in document}
    found = {u for e in (*exprs.values(), *(v for _, v in declared), *relations,
                         *relations.values()) for u in sp.sympify(e).free_symbols
             if u.name in taken and u not in motion}
    if not found:
        return exprs, list(declared), dict(relations)
    fresh = {u: sp.Symbol(f"{u.name}_model", **u.assumptions0) for u in found}
    return ({k: e.xreplace(fresh) for k, e in exprs.items()},
            [(s, sp.sympify(v).xreplace(fresh)) for s, v in declared],
            {sp.sympify(k).xreplace(fresh): sp.sympify(v).xreplace(fresh)
             for k, v in relations.items()})


@dataclass(frozen=True)
class CorrectedRow:
    r"""An equation as it should read: its left side as ``terms`` (coefficient, then the
    acceleration, the velocity product or 1 it multiplies, in the document's order) and its
    right side ``rhs`` (the inputs)."""

    terms: tuple[tuple[sp.Expr, sp.Expr], ...]
    rhs: sp.Expr


def corrected_row(d: Derivation, truth: Mapping[str, sp.Expr],
                  weights: Sequence[sp.Expr]) -> CorrectedRow | None:
    r"""An equation as it should read in the document's frame (``weights``: the true rows it
    combines, in the document's symbols): each coefficient :math:`\sum_k w_k T_{k\cdot}` of
    the truth's already simplified elements (simplified again only where several rows are
    combined), or None where an element is not known or the row is longer than
    :data:`CORRECTED_LIMIT` operations."""
    used = [(k, w) for k, w in enumerate(weights) if w != 0]
    n, v = d.n, d.velocities
    keys: list[tuple[str, sp.Expr]] = [(f"A[{{k}},{j + 1}]", d.accelerations[j])
                                       for j in range(n)]
    keys += [(f"h[{{k}}]:{v[j]}*{v[m]}", v[j] * v[m]) for j in range(n) for m in range(j, n)]
    keys += [("Q[{k}]", sp.Integer(1))]
    terms = []
    for label, key in keys:
        parts = [(w, truth.get(label.format(k=k + 1))) for k, w in used]
        if any(t is None for _, t in parts):
            return None
        c = sp.Add(*(w * t for w, t in parts))
        c = simplify_expr(c) if len(parts) > 1 else sp.factor_terms(c)
        if c != 0:
            terms.append((c, key))
    rhs = sp.expand(sp.Add(*(w * _inputs(d, k, truth) for k, w in used)))
    if sum(sp.count_ops(c) for c, _ in terms) + sp.count_ops(rhs) > CORRECTED_LIMIT:
        return None
    return CorrectedRow(tuple(terms), rhs)


def written(row: CorrectedRow, names: Mapping[sp.Symbol, str]) -> tuple[str, str]:
    r"""Text and LaTeX of a corrected ``row`` (``names``: the LaTeX of the velocities and
    accelerations)."""
    text = _joined(row.terms, sp.sstr, "*")
    latex = _joined(row.terms, lambda e: sp.latex(e, symbol_names=dict(names)), " ")
    return (f"{text} = {sp.sstr(row.rhs)}",
            f"{latex} = {sp.latex(row.rhs, symbol_names=dict(names))}")


def _joined(terms: Sequence[tuple[sp.Expr, sp.Expr]], show: Callable[[sp.Expr], str],
            times: str) -> str:
    r"""``c_1 k_1 + c_2 k_2 - ...`` in the order given (``times`` between a coefficient and
    its acceleration or product: ``" "`` for LaTeX), each coefficient in parentheses where it is
    a sum."""
    out = ""
    for c, k in terms:
        negative = c.could_extract_minus_sign()
        c = -c if negative else c
        left, right = (r"\left(", r"\right)") if times == " " else ("(", ")")
        shown = f"{left}{show(c)}{right}" if isinstance(c, sp.Add) else show(c)
        body = shown if k == 1 else show(k) if c == 1 else f"{shown}{times}{show(k)}"
        out += (" - " if negative else " + ") + body if out else ("-" if negative else "") + body
    return out or "0"


def _inputs(d: Derivation, k: int, truth: Mapping[str, sp.Expr]) -> sp.Expr:
    r"""Row ``k``'s input terms in the document's inputs: :math:`\sum_j B_{kj}\tau_j(u)`."""
    if not d.inputs:
        return sp.Integer(0)
    names = load_model(d.model).input_names
    out = sp.Integer(0)
    for j, name in enumerate(names):
        b = truth.get(f"B[{k + 1},{j + 1}]")
        tau = d.inputs.get(name)
        if b is not None and tau is not None:
            out += b * sp.sympify(tau)
    return out


__all__ = ["CORRECTED_LIMIT", "CorrectedRow", "InDocument", "corrected_row", "in_document", "parameter_solution", "written"]
