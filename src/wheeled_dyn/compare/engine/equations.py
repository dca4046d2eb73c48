r"""The document's equations as records, consistent with their elements.

The verdict of an equation is its equivalence decision (:mod:`..judge.equivalence`); where it
differs on the general grid but is a combination of the true equations on the grid of the
special parameter families the document did not declare, it *agrees only if* they hold (the
conditions its elements need). The elements of a row are then made to say the same: in an
equation that agrees every element agrees in its frame (C elements that differ only in their
factorisation excepted), so a tolerance on one element cannot contradict the equation; an
equation that differs where no element does says so itself.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..judge.draft import ElementDraft
from ..readings.describe import FrameText
from ..records import (Diagnosis, DiagnosisKind as K, EquationRecord, Verdict, diagnosis,
                       first_of)
from ..sides.both import Sides
from .assumed_values import assumed_text, nonzero_assumed


def units_notes(drafts: Sequence[ElementDraft],
                point: Sequence[tuple[str, float]] = ()) -> list[str]:
    r"""A note of the terms whose units disagree in elements that agree (numerically, their
    equation right): a symbol's declared units are wrong (an inertia declared in kg), not its
    equation — or, in a document linearised about a ``point`` where a position is not 0, the
    numbers of the point written in it carry units the text does not show (r = 0.2 m written
    as 1/5)."""
    said: dict[str, list[str]] = {}
    for r in drafts:
        if r.verdict == Verdict.AGREES:
            for x in r.diagnoses:
                if x.kind == K.DIMENSION:
                    said.setdefault(x.detail or x.text, []).append(r.element)
    values = ", ".join(f"{k} = {v:g}" for k, v in point if v)
    why = (f"the numbers of the linearisation point ({values}) written in it carry units the "
           "text does not show, or a symbol's declared units are wrong") if values else \
        "a symbol's declared units are probably wrong, or a number stands for a quantity " \
        "with units"
    return [f"units as declared: {text} — {', '.join(elements)} (the elements agree: {why})"
            for text, elements in said.items()]


def _lost(d: Derivation, i: int) -> list[str]:
    return [e for e in d.missing if e.split("[")[1].split(",")[0].split("]")[0] == str(i + 1)]


def _family_condition(row: Sequence[ElementDraft]) -> str:
    conditions = [c.condition for r in row if r.verdict == Verdict.AGREES_IF
                  for c in r.diagnoses if c.kind == K.CONDITION and c.condition]
    return " and ".join(dict.fromkeys(conditions))


def _reconcile(verdict: Verdict, row: Sequence[ElementDraft], error: float = float("nan")
               ) -> list[Diagnosis]:
    r"""Make the row's elements say what the equation says (module text); the equation's
    extra diagnoses (``error``: its largest residual relative to its terms)."""
    if verdict == Verdict.AGREES:
        for r in row:
            if r.verdict in (Verdict.AGREES, Verdict.FACTORIZATION):
                continue
            if r.key == "C":
                r.verdict = Verdict.FACTORIZATION
                r.diagnoses = [Diagnosis(K.FACTORIZATION, f"C q̇ agrees in row {r.row + 1}: "
                                         "only the factorisation of C differs, not the "
                                         "equations")]
            elif r.verdict != Verdict.UNDECIDED:
                r.verdict = Verdict.AGREES   # its terms' units kept: a symbol's declared
                r.diagnoses = [diagnosis(K.NOTE, "within the equation's tolerance (its "  # (kg
                                         "equation agrees)", prefix=""),  # for an inertia)
                               *(x for x in r.diagnoses if x.kind == K.DIMENSION)]
        return []
    if verdict == Verdict.DIFFERS and not any(
            r.verdict in (Verdict.DIFFERS, Verdict.AGREES_IF) and r.key != "C" for r in row):
        size = f" (at most {error:.2g} of their size)" if np.isfinite(error) else ""
        return [diagnosis(K.NOTE, "no single element of it differs in its frame: the "
                          f"difference is spread over its terms{size}", prefix="")]
    return []


def equation_records(d: Derivation, decision, drafts: Sequence[ElementDraft],
                     texts: Sequence[FrameText], label: str, grids: Sequence[Sides],
                     funcs, rules, solved: Diagnosis | None = None,
                     owed: frozenset[int] = frozenset()) -> list[EquationRecord]:
    r"""One :class:`~..records.EquationRecord` per equation (module text); none where the
    document gives no A. ``solved``: for a document solved for its accelerations, what its
    own inertia matrix lacks (:mod:`..judge.unsolved`), said on each equation that differs.
    ``owed``: the equations that agree only with the file's nonzero ``[assume]`` values
    (:mod:`.assumed_values`): they *agree only if* those hold."""
    if decision is None:
        return []
    on_families = None
    if len(grids) > 1 and any(e.verdict in (Verdict.DIFFERS, Verdict.UNDECIDED)
                              for e in decision.equations):
        from .deciding import decide
        on_families = decide(d, funcs, grids[1])
    out = []
    names = _named_by(d, funcs.exprs.get("A"))
    for i, e in enumerate(decision.equations):
        row = [r for r in drafts if r.row == i]
        verdict, diags = e.verdict, list(e.diagnoses)
        lost = _lost(d, i)
        if lost and verdict != Verdict.DIFFERS:
            verdict = Verdict.UNDECIDED
            diags = [diagnosis(K.UNDECIDED, f"{', '.join(lost)} lost in the extracted text: "
                               "the equation is not decided")]
        singular = first_of(diags, K.SINGULAR, K.DECLARED) is not None  # no family mends
        # a family is named where an element needs one and none differs without one (an
        # element that differs with a sign is no family's: its equation differs too)
        text = _family_condition(row)
        differing = any(r.verdict == Verdict.DIFFERS and r.key != "C" for r in row)
        # (undecided by a residual near the tolerance, not by values that are not finite
        # or lost text: a CAD export's products of inertia of 1e-7 of a row, a family's)
        near = verdict == Verdict.UNDECIDED and not lost and bool(np.isfinite(e.max_error))
        if (verdict == Verdict.DIFFERS or near) and not singular and on_families is not None \
                and on_families.equations[i].verdict == Verdict.AGREES and text \
                and not differing:
            verdict = Verdict.AGREES_IF
            diags = [Diagnosis(K.CONDITION, f"agrees only if {text}", text, condition=text)]
        if i in owed and verdict != Verdict.UNDECIDED:
            text = assumed_text(nonzero_assumed(d))
            verdict = Verdict.AGREES_IF
            diags = [Diagnosis(K.CONDITION, f"agrees only if {text}", text, condition=text)]
        diags += _reconcile(verdict, row, e.max_error)
        if solved is not None and verdict == Verdict.DIFFERS:
            diags.append(solved)
        own = names[i]
        out.append(EquationRecord(index=i, label=f"equation {i + 1} ({own})",
                                  verdict=verdict, diagnoses=tuple(diags),
                                  frame=texts[i].text or "the true equation",
                                  max_error=e.max_error, equation=label))
    return out


def _named_by(d: Derivation, A) -> list[sp.Symbol]:
    r"""The coordinate each equation is named by: the one it is solved for, its row of the
    document's A that coordinate's unit row (``ddq2 = …`` printed first is q2's, whatever
    the order of the positions); the others the coordinates left, in the order of the
    positions (``ddq1 = (τ1 − d12 ddq2 − …)/d11`` after it is q1's). By the velocities where
    they are no positions' rates."""
    own = list(d.velocities if d.coordinates.kind == "quasi" else d.positions)
    n = len(own)
    names: list[sp.Symbol | None] = [None] * n
    if A is not None and A.rows == n and A.cols == n:
        for i in range(n):
            ones = [j for j in range(n) if A[i, j] != 0]
            if len(ones) == 1 and A[i, ones[0]] == 1 and own[ones[0]] not in names:
                names[i] = own[ones[0]]
    left = [x for x in own if x not in names]
    for i in range(n):
        if names[i] is None:
            names[i] = own[i] if own[i] in left else left[0]
            left.remove(names[i])
    return [x for x in names if x is not None]


def state_rates(d: Derivation) -> tuple[tuple[str, ...], bool | None]:
    r"""A state-space form's rows that state a position's rate (:mod:`...derivations.state_space`):
    the wrong ones as the reports say them (``"state row 1 (the rate of x) is 2*dx where the
    state's velocity dx fits"``), and whether every row is its position's velocity (None: the
    file has none, or one holds a place the text lost and none is wrong)."""
    rates = () if d.state_space is None else d.state_space.rates
    if not rates:
        return (), None
    wrong = tuple(f"{r.label} is {r.written} where the state's velocity {r.velocity} fits"
                  for r in rates if r.agrees is False)
    agree = False if wrong else (None if any(r.agrees is None for r in rates) else True)
    return wrong, agree


__all__ = ["equation_records", "state_rates"]
