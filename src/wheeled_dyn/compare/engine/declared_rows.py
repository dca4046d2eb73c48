r"""The rows a file declares scaled (``[rows] scale``) that the equations contradict: read as
declared (declarations bind), each such equation differs, and what it is instead is said.

- :func:`printed_factors`: the number each equation as printed is its true one times;
- :func:`bind_declared`: an equation right as printed but not as declared differs, with a
  ``DECLARED`` diagnosis naming what it is (another row's equation, times a factor);
- :func:`declared_only`, :func:`declared_apart`: its elements differ only as declared, or as
  printed too (named where the document's error is);
- :func:`apart_causes`: the ``file_error`` cause of a row whose elements contradict its
  declared scale, naming the elements that agree as declared.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import replace

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..judge.diagnose import nice_number
from ..judge.draft import ElementDraft
from ..judge.equivalence import EquationDecision, SystemDecision
from ..readings.frames import Frame
from ..records import Cause, CauseKind, Diagnosis, DiagnosisKind, Verdict, diagnosis


def printed_factors(decision: SystemDecision, rows: Collection[int]) -> dict[int, sp.Expr | None]:
    r"""Per row of ``rows``, the number its equation as printed is the true one times (its
    weights :math:`w_i` a constant times :math:`e_i`), or None where it is another
    combination of the true ones."""
    out: dict[int, sp.Expr | None] = {}
    for i in rows:
        found = _one_row(decision.equations[i].w)
        out[i] = found[0] if found is not None and found[1] == i else None
    return out


def _one_row(w: np.ndarray) -> tuple[sp.Expr | None, int] | None:
    r"""(the number or None where it varies, the true equation j) where the weights ``w``
    (samples × n) are a factor times :math:`e_j`: an equation printed as row j's, scaled."""
    j = int(np.argmax(np.abs(w).max(axis=0)))
    own, others = w[:, j], np.delete(w, j, axis=1)
    if not np.isfinite(w).all() or np.abs(own).min() <= 0 or \
            (others.size and np.abs(others).max() > 1e-9 * np.abs(own).max()):
        return None
    factor = float(np.median(own))
    return (sp.nsimplify(nice_number(factor)) if np.ptp(own) <= 1e-9 * abs(factor)
            else None), j


def bind_declared(d: Derivation, decision: SystemDecision, wrong: Collection[int]
                  ) -> SystemDecision:
    r"""``decision`` with each equation of ``wrong`` (right as printed, its declared row scale
    contradicted: :func:`choose_frames`) differing, as the file declares it to be read: a
    ``DECLARED`` diagnosis says what the equation is instead."""
    if not wrong or d.row_scale is None:
        return decision
    equations = list(decision.equations)
    for i, factor in printed_factors(decision, wrong).items():
        e = equations[i]
        other = None if factor is not None else _one_row(e.w)
        actual = f"the true one times {sp.sstr(factor)}" if factor is not None else \
            "another combination of the true ones" if other is None else \
            (f"true equation {other[1] + 1} times "
             f"{'a factor' if other[0] is None else sp.sstr(other[0])} ([rows] scale declares "
             "equation i a factor times the true equation i, of position i: equations "
             "printed in another order are transcribed in the order of the positions)")
        text = (f"the file declares equation {i + 1} as the true one times "
                f"{sp.sstr(d.row_scale[i])}, but as printed it is {actual}: read as declared "
                "it differs (the equation as printed is right: the declaration is probably "
                "wrong)")
        equations[i] = EquationDecision(Verdict.DIFFERS, (
            *e.diagnoses, diagnosis(DiagnosisKind.DECLARED, text, prefix="")), e.max_error, e.w)
    return replace(decision, equations=tuple(equations))


def declared_only(d: Derivation, drafts: Sequence[ElementDraft], wrong: Collection[int]
                  ) -> None:
    r"""The elements of each row of ``wrong`` (right as printed, its declared scale
    contradicted) that differ: they differ only as the file declares the row to be read, so
    they say that, in place, and no term of theirs is diagnosed (a term "lc2 where lc2**2
    fits" in a row the file declares lc2 × the true one is the declaration's doing)."""
    if d.row_scale is None:
        return
    for r in drafts:
        if r.row in wrong and r.verdict != Verdict.AGREES:
            r.verdict = Verdict.DIFFERS
            r.diagnoses = [_as_declared(d, r.row, "the equation as printed is right")]


def _as_declared(d: Derivation, row: int, printed: str) -> Diagnosis:
    r"""An element of ``row`` that differs only as the file declares the row to be read."""
    assert d.row_scale is not None, "a declared row scale"
    return diagnosis(DiagnosisKind.DECLARED, f"differs only as the file declares equation "
                     f"{row + 1} to be read (the true one times {sp.sstr(d.row_scale[row])}); "
                     f"{printed}", prefix="")


def declared_apart(d: Derivation, drafts: Sequence[ElementDraft],
                   printed: Sequence[ElementDraft]) -> None:
    r"""The elements of the rows whose elements contradict their declared scale
    (:func:`_printed`), judged as declared (``drafts``) and as printed (``printed``): an
    element right as printed differs only as declared (said so, no term of it diagnosed);
    one that differs as printed too keeps its verdict and is named as printed, where the
    document's error is (a term's sign, not "−1/2 × the truth"). In place."""
    if d.row_scale is None:
        return
    found = {(r.key, r.index): r for r in printed}
    for r in drafts:
        other = found.get((r.key, r.index))
        if other is None or r.verdict == Verdict.AGREES:
            continue
        r.verdict = Verdict.DIFFERS
        if other.verdict == Verdict.AGREES:
            r.diagnoses = [_as_declared(d, r.row, "as printed it agrees")]
        else:
            r.diagnoses = list(other.diagnoses)


def apart_causes(d: Derivation, apart: Mapping[int, Frame], drafts: Sequence[ElementDraft]
                 ) -> list[Cause]:
    r"""Per row whose elements contradict its declared scale (:func:`_printed`), a
    ``file_error`` cause claiming the elements that differ only as declared."""
    out = []
    for i, frame in apart.items():
        if d.row_scale is None:
            break
        row = [r for r in drafts if r.row == i]
        only = tuple(r.element for r in row if r.diagnoses
                     and r.diagnoses[0].kind == DiagnosisKind.DECLARED)
        kept = [r.element for r in row if r.verdict == Verdict.AGREES   # as declared, and
                and np.abs(r.D).max(initial=0.0) > 0]                     # not 0 both ways
        own = [r.element for r in row if r.verdict != Verdict.AGREES and r.element not in only]
        factor = "the true one" if frame.constant in (None, 1.0) else \
            f"{sp.sstr(sp.nsimplify(nice_number(frame.constant)))} × the true one"
        but = [f"{', '.join(kept)}, as declared"] * bool(kept) + \
            [f"{', '.join(own)}, named on their own"] * bool(own)
        out.append(Cause(CauseKind.FILE_ERROR, only, (
            f"the file declares equation {i + 1} as the true one times "
            f"{sp.sstr(d.row_scale[i])}, but its elements are {factor} as printed"
            + (f" but for {'; '.join(but)}" if but else "") + ": read as declared the "
            "others differ (the declaration is probably wrong, or the row was multiplied by "
            "it in part only)")))
    return out


__all__ = ["apart_causes", "bind_declared", "declared_apart", "declared_only",
           "printed_factors"]
