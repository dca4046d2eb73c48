r"""The reproduced table's rows and equations: each element matched between the two documents
and against the truth, set beside the printed table's verdict with the reason where they part
ways; each equation's difference derived − reference beside the printed one."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from ....derivations.table import ComparisonTable, TableEntry
from ...grid.samples import special_cases
from ...judge.diagnose import agrees
from ...records import DerivationResult, Diagnosis, DiagnosisKind, first_of
from .records import EquationDifference, TableRow
from .text import num, same, show


def _engine_text(result: DerivationResult, label: str) -> str:
    for r in result.records:
        if r.element == label:
            return r.verdict.value + (": " + "; ".join(d.text for d in r.diagnoses)
                                      if r.diagnoses else "")
    return "not compared"


@dataclass(frozen=True)
class Context:
    table: ComparisonTable
    numbers: Mapping[str, tuple[np.ndarray, np.ndarray]]
    h: Mapping[str, np.ndarray]
    scale: np.ndarray
    raw: Mapping[str, Mapping[str, sp.Matrix]]
    cells: Mapping[str, Mapping[str, sp.Matrix]]
    factors: Mapping[str, list[float]]
    results: Mapping[str, DerivationResult]
    assumed: tuple[str, ...]
    rng: np.random.Generator

    def subst(self, expr: sp.Expr) -> sp.Expr:
        return sp.sympify(expr).xreplace(dict(self.table.substitution))

    def factor(self, which: str, i: int) -> sp.Expr:
        return sp.nsimplify(self.factors[which][i])


def _within(diagnoses: Sequence[Diagnosis], model: str, assumed: Sequence[str]) -> bool:
    r"""An "agrees only if ..." diagnosis whose conditions are all among ``assumed``
    (descriptions of the model's special cases, as the engine quotes them)."""
    hit = first_of(diagnoses, DiagnosisKind.CONDITION)
    if hit is None:
        return False
    text = hit.condition
    return all(c.description not in text or c.description in assumed
               for c in special_cases(model))


def _h_both_wrong(ctx: Context, i: int) -> list[str]:
    r"""h coefficients of row ``i`` that the engine finds wrong in both documents, beyond the
    table's assumptions."""
    wrong = None
    for result in ctx.results.values():
        bad = {r.element for r in result.records if r.key == "h" and r.index[0] == i
               and r.verdict != "agrees"
               and not (r.verdict == "agrees_if"
                        and _within(r.diagnoses, ctx.table.model, ctx.assumed))}
        wrong = bad if wrong is None else wrong & bad
    return sorted(wrong or ())


def table_row(entry: TableEntry, ctx: Context) -> TableRow:
    key, i, j = entry.matrix, entry.row - 1, entry.col - 1
    idx = 0 if key == "A" else 1
    D, R, T = (ctx.numbers[k][idx][:, i, j] for k in ("derived", "reference", "truth"))
    tol = ctx.scale[i]
    match = agrees(D, R, tol)
    same_h = agrees(ctx.h["derived"][:, i], ctx.h["reference"][:, i], tol)
    machine = "match" if match else ("factorization" if key == "C" and same_h else "mismatch")
    right = {"derived": agrees(D, T, tol), "reference": agrees(R, T, tol)}
    truth = ("both" if all(right.values()) else "derived" if right["derived"] else
             "reference" if right["reference"] else "neither")
    d_printed = ctx.subst(ctx.raw["derived"][key][i, j])
    r_printed = ctx.subst(ctx.raw["reference"][key][i, j])
    d_expr = d_printed / ctx.factor("derived", i)
    r_expr = r_printed / ctx.factor("reference", i)
    label = f"{key}[{entry.row},{entry.col}]"
    engine = {w: _engine_text(ctx.results[w], label) for w in ("derived", "reference")}
    listed = entry.name in ctx.table.mismatched
    gens = (*ctx.table.velocities, *ctx.table.accelerations)
    parts, kinds = [], []

    if machine == "match":
        f_d, f_r = ctx.factors["derived"][i], ctx.factors["reference"][i]
        if f_d != f_r and not same(d_printed, r_printed, ctx.rng):
            parts.append(f"equal once row {entry.row} is divided by its factor (derived "
                         f"{num(f_d)}, reference {num(f_r)}); the printed cells differ by "
                         f"the factor {num(f_r / f_d)}"
                         + (" (in sign only)" if f_r == -f_d else ""))
        else:
            parts.append("equal after the substitution")
    else:
        parts.append(f"derived − reference = {show(d_expr - r_expr, gens)}")
        if machine == "factorization":
            parts.append(f"but C q̇ of row {entry.row} is the same in both: only the "
                         "factorisation of C differs, not the equations")
    verdict = {True: "agrees with the truth", False: "differs from the truth"}
    parts.append(f"under the table's assumptions the derived {verdict[right['derived']]} "
                 f"(engine, general parameters: {engine['derived']}), the reference "
                 f"{verdict[right['reference']]} (engine: {engine['reference']})")
    if machine == "mismatch" and not listed:
        kinds.append("missed by the table")
        parts.append("the table does not list it")
    elif machine != "mismatch" and listed:
        kinds.append("factorisation only" if machine == "factorization" else "not a mismatch")
        parts.append("the table lists it as mismatched, but the equations agree here")
    elif listed:
        parts.append("the table lists it: agreed")
    if machine == "match" and truth == "neither":
        kinds.append("both documents wrong")
        hidden = _h_both_wrong(ctx, i)
        parts.append("the two documents agree with each other here, so a table comparing them "
                     "cannot see it, but both differ from the truth"
                     + (f" (the engine finds {', '.join(hidden)} wrong in both)" if hidden else ""))
    cell_parts, cell_kinds = _cell_checks(entry, ctx, (d_printed, r_printed), T, tol)
    return TableRow(element=entry.name, derived=show(d_printed, gens),
                    reference=show(r_printed, gens), machine=machine,
                    table="mismatched" if listed else "match", truth=truth,
                    derived_engine=engine["derived"], reference_engine=engine["reference"],
                    disagreement="; ".join(dict.fromkeys(kinds + cell_kinds)),
                    explanation="; ".join(parts + cell_parts))


def _cell_checks(entry: TableEntry, ctx: Context, docs, T, tol):
    r"""Are the table's derived and reference cells the documents as printed? When they are
    not, is the cell the truth?"""
    notes, kinds = [], []
    key, i, j = entry.matrix, entry.row - 1, entry.col - 1
    for column, cell, doc in (("derived", entry.derived, docs[0]),
                              ("reference", entry.reference, docs[1])):
        printed = ctx.raw[column][key][i, j]
        if same(ctx.subst(cell), doc, ctx.rng):
            if not same(cell, printed, ctx.rng):
                notes.append(f"the table's {column} cell {sp.sstr(cell)} is not the document as "
                             f"printed, {sp.sstr(printed)}, but equal to it after the "
                             "substitution")
            continue
        values = ctx.numbers[f"{column} cell"][0 if key == "A" else 1][:, i, j]
        kinds.append("cells differ from the documents")
        notes.append(f"the table's {column} cell {sp.sstr(cell)} is not the {column} document as "
                     f"printed, {sp.sstr(printed)}, even after the substitution; the cell "
                     + ("agrees with the truth" if agrees(values, T, tol) else
                        "differs from the truth too") + " under the table's assumptions")
    return notes, kinds


def step_notes(table: ComparisonTable, rng) -> list[str]:
    r"""Printed steps of the "equivalent form" column that do not equal the derived cell after
    the substitution."""
    out = []
    subst = dict(table.substitution)
    for e in table.entries:
        target = e.derived.xreplace(subst)
        for k, step in enumerate(e.equivalent, start=1):
            if not same(step, target, rng):
                out.append(f"{e.name}: step {k} of the table's equivalent form, {sp.sstr(step)}, "
                           f"is not the derived cell after the substitution, {show(target)}")
    return out


def equation_differences(ctx: Context, rows: Sequence[TableRow]) -> list[EquationDifference]:
    table = ctx.table
    acc, vel = sp.Matrix(table.accelerations), sp.Matrix(table.velocities)
    gens = (*table.velocities, *table.accelerations)

    def lhs(M: Mapping[str, sp.Matrix], i: int) -> sp.Expr:
        return ctx.subst((M["A"] * acc)[i] + (M["C"] * vel)[i])

    out = []
    for i in range(len(table.positions)):
        label = f"equation {i + 1}"
        fd, fr = ctx.factor("derived", i), ctx.factor("reference", i)
        machine = lhs(ctx.raw["derived"], i) / fd - lhs(ctx.raw["reference"], i) / fr
        from_cells = lhs(ctx.cells["derived"], i) / fd - lhs(ctx.cells["reference"], i) / fr
        printed = table.differences.get(label)
        mine = [r for r in rows if r.element[1] == str(i + 1)]
        if printed is None:
            relation, why = "not printed", "the table gives no difference for this equation"
        elif same(printed, machine, ctx.rng):
            relation, why = "equal", "the table's difference is derived − reference"
        elif same(printed, -machine, ctx.rng):
            relation, why = "opposite sign", ("the table gives reference − derived here, "
                                              "derived − reference in the other equations")
        elif same(printed, from_cells, ctx.rng) or same(printed, -from_cells, ctx.rng):
            relation = "differs"
            why = ("the table's difference follows its own cells, which are not the documents "
                   "as printed at " + ", ".join(r.element for r in mine
                                                if "cells differ" in r.disagreement)
                   + f"; from its cells: {show(from_cells, gens)}")
        else:
            relation = "differs"
            why = ("neither derived − reference nor its negative; from the table's cells: "
                   + show(from_cells, gens))
        hidden = [r.element for r in mine if r.truth == "neither" and r.machine == "match"]
        neither = [r.element for r in mine if r.truth == "neither" and r.machine != "match"]
        if hidden:
            why += (f"; both documents differ from the truth at {', '.join(hidden)} in the same "
                    "way, which no difference between them shows")
        if neither:
            why += f"; neither document is right at {', '.join(neither)}"
        out.append(EquationDifference(i + 1, show(machine, gens),
                                      "" if printed is None else show(printed, gens),
                                      relation, why))
    return out
