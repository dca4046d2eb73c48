r"""Closed forms for the reports: the document's elements in the model's own parameters, and
(when the symbolic engine provides them) the true expressions and simplified residuals.

For the WIP, Khalil's standard parameters are functions of the physical ones
(:func:`~wheeled_dyn.models.wip_parameters.standard_parameters` applied to SymPy symbols), so a
document written with XX1, MY1 ... reads, after the parameter map, in m_S, d, I1 ... — the
"equivalent form" column of seed 001's own table.
"""

from __future__ import annotations

from collections.abc import Callable

import sympy as sp
from sympy.core.function import AppliedUndef

from ..derivations.schema import Derivation
from ..models.registry import model_entry
from ..models.wip_parameters import WipParameters, standard_parameters

def _physical_symbols() -> dict[str, sp.Symbol]:
    from dataclasses import fields
    return {f.name: sp.Symbol(f.name, real=True) for f in fields(WipParameters)}


def document_in_model(d: Derivation) -> Callable[[sp.Expr | None], tuple[str, str]]:
    r"""A function: document expression → (text, LaTeX) in the model's parameters."""
    mapping = {s.symbol: s.value for s in d.symbols.values() if s.value is not None}
    physical = model_entry(d.model).parameters is WipParameters
    std = standard_parameters(_physical_symbols()) if physical else None
    names = _physical_symbols()

    dots = {}
    for q, v in zip(d.positions, d.velocities):
        dots[v] = rf"\dot{{{sp.latex(q)}}}"

    def convert(expr: sp.Expr | None) -> tuple[str, str]:
        if expr is None:
            return "", ""
        out = sp.sympify(expr).xreplace(mapping)
        if std is not None:
            calls = {}
            for call in out.atoms(AppliedUndef):
                link = str(call.args[0])
                if link in std and call.func.__name__ in std[link]:
                    calls[call] = std[link][call.func.__name__]
            out = out.xreplace(calls)
            out = out.xreplace({s: names.get(s.name, s) for s in out.free_symbols})
        return sp.sstr(out), sp.latex(out, symbol_names=dots)

    return convert


def annotate(d: Derivation, records: list[dict], coordinates: str) -> None:
    r"""Fill ``truth`` and ``residual`` of the records where closed forms are available
    (symbolic engine). Without them the records keep the numeric verdict."""
    try:
        from ..symbolic import true_expressions  # provided by the symbolic engine
    except ImportError:
        return
    truth = true_expressions(d.model, coordinates)
    if truth is None:
        return
    mapped = document_in_model(d)
    for r in records:
        expr = truth.get(r["element"])
        if expr is None:
            continue
        r["truth"] = sp.sstr(expr)
        if r["verdict"] != "agrees":
            doc = sp.sympify(r["document_model"]) if r["document_model"] else sp.Integer(0)  # noqa
            res = sp.trigsimp(sp.expand(expr - doc))
            r["residual"] = sp.sstr(res)
