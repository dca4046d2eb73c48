r"""Velocity products a document declared linearised keeps: compared with the true ones in
full.

A file declaring ``linearised_about`` is judged against the truth linearised at the point,
where every velocity product is of second order and vanishes; the document's own are
evaluated there too. A document that writes velocity products anyway (its equations are not
linear: the nonlinear equations, declared linearised) says what they are, and a wrong one
— a centripetal term's sign, a Coriolis term dropped beside the others kept — vanishes at
the point as the right one does: the declaration would turn the difference into "agrees".
So where the document writes a velocity product whose coefficient is a function of the
positions (its nonlinear equations; a coefficient that is a number is compared by the
linearisation itself, with the truth's zero), the file is judged again without the
linearisation, and each velocity product :math:`h_i:\dot q_j\dot q_k` that differs from the
true one in full (one the document leaves out beside those it keeps included) differs in the
result too: its record is the full comparison's, its equation differs, and a cause says
why. Where they all agree, nothing changes: the declaration holds for the rest.
"""

from __future__ import annotations

from dataclasses import replace
from types import MappingProxyType

import sympy as sp

from ...derivations.schema import Derivation
from ..grid.assumptions import declared
from ..records import Cause, CauseKind, DerivationResult, DiagnosisKind, Verdict, diagnosis


def kept_products(engine, d: Derivation, j) -> tuple[DerivationResult, Cause] | None:
    r"""``j``'s result (``d`` judged as declared) with the velocity products the document
    keeps that differ from the true ones in full, and the cause saying so; None where ``d``
    declares no linearisation, writes no velocity product, or every one agrees in full."""
    raw = dict(d.assumes or {})
    h = j.funcs.exprs.get("h")
    if not raw.get("linearised_about") or h is None or not any(
            sp.sympify(e).free_symbols & set(d.positions) for e in h):
        return None           # no product, or only numbers times products: as linearised
    full_assumes = {k: v for k, v in raw.items() if k not in ("linearised_about", "potential")}
    full = engine.judge(replace(d, assumes=MappingProxyType(full_assumes))).result
    wrong = {r.element: r for r in full.records if r.key == "h" and r.verdict == Verdict.DIFFERS}
    if not wrong:
        return None
    result = j.result
    records = tuple(wrong.get(r.element, r) for r in result.records)
    rows = sorted({r.index[0] for r in wrong.values()})
    named = ", ".join(wrong)
    equations = list(result.equations)
    for i in rows:
        if i < len(equations):
            e = equations[i]
            said = diagnosis(DiagnosisKind.NOT_EQUIVALENT, (
                "its velocity products, which the declared linearisation drops, differ from "
                "the true ones: " + ", ".join(x for x in wrong if wrong[x].index[0] == i)),
                prefix="")
            equations[i] = replace(e, verdict=Verdict.DIFFERS, diagnoses=(*e.diagnoses, said))
    point = ", ".join(f"{k} = {v:g}" for k, v in declared(d).linearised_about)
    cause = Cause(CauseKind.NOT_EQUIVALENT, (), (
        f"the file declares its equations linearised about {point}, but they keep velocity "
        f"products, and compared with the true ones in full these differ: {named} (each "
        "vanishes at the point, right or wrong; the document's nonlinear equations are "
        "wrong there)"))
    return replace(result, records=records, equations=tuple(equations)), cause


__all__ = ["kept_products"]
