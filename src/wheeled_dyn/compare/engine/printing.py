r"""What the reports print of each element: the document's expression (text and LaTeX, as
printed, velocities dotted), the same in the model's parameters, and — where the symbolic
engine has closed forms — the truth and truth − document in the row's frame
(:mod:`..presentation.closed_form`). Nothing here decides a verdict."""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from ...derivations.schema import Derivation
from ...models.registry import load_model
from ..grid.assumptions import Assumptions
from ..grid.samples import uniform_links
from ..judge.draft import ElementDraft
from ..presentation import closed_form
from ..presentation.printing import printed
from ..readings.describe import FrameText
from ..sides.elements import element_expr, latex_names


def print_drafts(d: Derivation, drafts: Sequence[ElementDraft], cs, texts: Sequence[FrameText],
                 assumed: Assumptions, exprs) -> None:
    r"""Fill the printed forms of every draft (module text), in place; ``exprs``: the
    document's read-off matrices (its compiled functions'), C as the file prints it."""
    as_printed = {**{k: exprs[k] for k in ("A", "Q", "B", "h")}, "C": d.C}
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
    uniform = frozenset(uniform_links(load_model(d.model), assumed.families))
    closed_form.annotate(d, list(drafts), cs, frames, families, uniform)


__all__ = ["print_drafts"]
