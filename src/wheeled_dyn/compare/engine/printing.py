r"""What the reports print of each element: the document's expression (text and LaTeX, as
printed, velocities dotted), the same in the model's parameters, and — where the symbolic
engine has closed forms — the truth and truth − document in the row's frame
(:mod:`..presentation.closed_form`). Nothing here decides a verdict."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import sympy as sp

from ...derivations.schema import Derivation
from ...models.registry import load_model
from ..grid.assumptions import Assumptions
from ..grid.samples import uniform_links
from ..judge.draft import ElementDraft
from ..presentation import closed_form
from ..presentation.in_document import corrected_row, written
from ..presentation.printing import printed
from ..records import EquationRecord, Verdict
from ..readings.describe import FrameText
from ..sides.elements import element_expr, latex_names


def print_drafts(d: Derivation, drafts: Sequence[ElementDraft], cs, texts: Sequence[FrameText],
                 assumed: Assumptions, exprs) -> Corrections:
    r"""Fill the printed forms of every draft (module text), in place; ``exprs``: the
    document's read-off matrices (its compiled functions'), C as the file prints it. Returns
    what :func:`corrected` needs: the truth in the document's symbols (None where the closed
    forms or the declarations do not give it) and each row's frame."""
    as_printed = {**{k: exprs[k] for k in ("A", "Q", "B", "h", "K")}, "C": d.C}
    names = latex_names(d)
    families = tuple(c.name for c in assumed.families)
    mapped = closed_form.document_in_model(d, families)
    for r in drafts:
        shown = element_expr(as_printed, r.key, r.index, d.velocities)
        r.document, r.document_latex = ("", "") if shown is None else printed(shown, names)
        r.document_model, r.model_latex = mapped(r.expr)
    frames: dict[int, tuple[sp.Expr, ...] | sp.Expr] = {}
    for i, t in enumerate(texts):
        if t.weights is not None:
            frames[i] = t.weights
        elif t.factor is not None:
            frames[i] = t.factor
    solved = {i: (t.solved[0], sp.nsimplify(t.solved[1], rational=True))
              for i, t in enumerate(texts) if t.solved is not None and i not in frames}
    return Corrections(closed_form.annotate(d, list(drafts), cs, frames, *_read(d, assumed),
                                            solved), frames)


def _read(d: Derivation, assumed: Assumptions
          ) -> tuple[tuple[str, ...], frozenset[str],
                     tuple[tuple[tuple[str, float], ...], bool] | None, frozenset[str]]:
    r"""How the closed forms are read under the document's assumptions: (families, uniform
    links, the linearisation, massless links), as :func:`~..presentation.closed_form.annotate`
    takes them."""
    uniform = frozenset(uniform_links(load_model(d.model), assumed.families))
    linearised = None if not assumed.linearised_about else (assumed.linearised_about,
                                                            assumed.equilibrium_potential)
    massless = frozenset(link for c in assumed.families for link in c.massless)
    return tuple(c.name for c in assumed.families), uniform, linearised, massless


def document_truth(d: Derivation, cs, assumed: Assumptions) -> dict[str, sp.Expr] | None:
    r"""The truth's entries (``A[1,2]``, ``Q[2]``, ``h[2]:dq1*dq2``) in the document's own
    symbols, as the reports print them; None where the closed forms or the declarations do
    not give them."""
    found = closed_form.true_forms(d, cs, *_read(d, assumed))
    return found[0] if found is not None and found[3] else None


@dataclass(frozen=True)
class Corrections:
    r"""The truth in a document's symbols (labels as the engine's) and each row's frame: a
    factor of the true row or the weights of the true rows."""

    truth: dict[str, sp.Expr] | None
    frames: dict[int, tuple[sp.Expr, ...] | sp.Expr]


def corrected(d: Derivation, equations: Sequence[EquationRecord], fixes: Corrections
              ) -> list[EquationRecord]:
    r"""The equations, each that differs with its corrected form (text and LaTeX) where the
    truth reads in the document's symbols: :func:`.in_document.corrected_row` in the row's
    frame, collected by acceleration and velocity product."""
    if fixes.truth is None:
        return list(equations)
    names = latex_names(d)
    out = []
    for e in equations:
        frame = fixes.frames.get(e.index)
        if e.verdict is not Verdict.DIFFERS or frame is None:
            out.append(e)
            continue
        weights = frame if isinstance(frame, tuple) else tuple(
            frame if k == e.index else sp.Integer(0) for k in range(d.n))
        row = corrected_row(d, fixes.truth, weights)
        if row is None:
            out.append(e)
            continue
        text, latex = written(row, names)
        out.append(replace(e, corrected=text, corrected_latex=latex))
    return out


__all__ = ["Corrections", "corrected", "print_drafts"]
