r"""The evidence of one derivation in the HTML report: its matrices side by side (document in
the model's parameters or as printed | truth, differing cells marked and linked), an entry per
element that differs or holds only conditionally, grouped by step, and the agreeing elements
folded."""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from ..compare.records import DerivationResult, DiagnosisKind, ElementRecord
from . import summary as S
from .html_text import esc, math_box, mathml, num_text
from .markdown import VERDICT_TEXT
from ..sympy_text import parse
from .symbols import Notation, difference_latex, product_latex, text_latex


#: Marks of a matrix cell by verdict (besides its colour).
MARK = {"agrees": "", "agrees_if": "?", "factorization": "≈", "differs": "≠", "undecided": "!"}


def _divided(text: str, factor: str | None, names: Notation) -> str:
    r"""LaTeX of the expression ``text`` divided by a detected row ``factor``."""
    if not factor:
        return text_latex(text, names)
    expr = parse(text)
    if expr is None:
        return ""
    return sp.latex(0) if expr == 0 else text_latex(sp.sstr(expr / sp.nsimplify(factor)), names)


def _truth_latex(r: ElementRecord, names: Notation) -> str:
    return text_latex(r.truth, names, r.truth_latex) if r.truth else ""


def _closed(result: DerivationResult, key: str) -> bool:
    return any(r.truth for r in result.records if r.key == key)


def _matrix(result: DerivationResult, key: str, names: Notation, document: bool) -> str:
    r"""One matrix of one side. With closed-form truths in the model's parameters the document
    is shown in them too; without, or with the truth in the document's symbols, as printed, and
    both sides show their numbers at the reference state (after dividing out a row factor)."""
    recs = {r.index: r for r in result.records if r.key == key}
    if not recs:
        return ""
    closed = _closed(result, key) and not result.truth_in_document
    n = max(i[0] for i in recs) + 1
    cols = 1 if key == "Q" else max(i[1] for i in recs) + 1
    factors = [result.row_factors[i] if i < len(result.row_factors) else None for i in range(n)]
    marked = document and any(factors)      # a column of its own for the rows' "÷ c" marks
    rows = []
    for i in range(n):
        factor = factors[i]
        cells = []
        for j in range(cols):
            r = recs.get((i,) if key == "Q" else (i, j))
            if r is None:
                cells.append("<td class='lost' title='not compared (lost in the extracted text "
                             "or not given)'>lost</td>")
                continue
            if document and closed:
                body = mathml(_divided(r.document_model or r.document, factor, names)) or \
                    mathml(r.model_latex or r.document_latex)
            elif document:
                latex = text_latex(r.document, names, r.document_latex)
                number = "" if not r.document or (expr := parse(r.document)) is None or \
                    expr.is_number else f'<div class="num">{num_text(r.document_sample)}</div>'
                body = (mathml(latex) or "0") + number
            else:
                latex = _truth_latex(r, names)
                body = mathml(latex) if latex else f'<div class="num">{num_text(r.truth_sample)}</div>'
            mark = f'<span class="mark">{MARK[r.verdict]}</span>' if MARK[r.verdict] else ""
            if r.verdict != "agrees":
                body = f"<a href='#{S.element_anchor(result, r.element)}'>{body}</a>"
            tip = esc(VERDICT_TEXT[r.verdict] + (f"; {r.diagnoses[0]}" if r.diagnoses else ""))
            cells.append(f'<td class="v-{r.verdict}" title="{tip}">{body}{mark}</td>')
        side = (f"<th class='div'>÷ {esc(factor)}</th>" if factor else "<td class='div'></td>") \
            if marked else ""
        rows.append(f"<tr>{side}{''.join(cells)}</tr>")
    if document:
        label = ("document, in the model's parameters" if closed else
                 "document as printed; below each, its number at the reference state")
    else:
        label = ("truth, in the document's symbols" if result.truth_in_document else
                 "truth" if closed else "truth: numbers at the reference state")
    return (f'<div><b>{key}</b> <span class="note">({label})</span>'
            f'<table class="mat">{"".join(rows)}</table></div>')


def matrices(result: DerivationResult, names: Notation) -> str:
    r"""The document's matrices beside the truth's: A, C, Q, B, and a linearised document's
    stiffness K (its Q is judged at the point, K carries its slopes)."""
    out = []
    for key in ("A", "C", "Q", "K", "B"):
        doc = _matrix(result, key, names, True)
        if doc:
            out.append(f'<div class="pair"><div class="pane">{doc}</div><div class="pane">'
                       f"{_matrix(result, key, names, False)}</div></div>")
    return "".join(out)


def element_title(r: ElementRecord, names: Notation) -> str:
    r"""An element's name; a velocity product of h with its velocities as math."""
    if r.key == "h" and ":" in r.element:
        row, product = r.element.split(":", 1)
        return (f"{esc(row)}, coefficient of " + mathml(product_latex(product, names)))
    return esc(r.element)


def _difference(r: ElementRecord, names: Notation) -> str:
    return difference_latex(r.residual, names, r.residual_latex)


def _card(result: DerivationResult, r: ElementRecord, names: Notation) -> str:
    factor = result.row_factors[r.index[0]] if r.index and r.index[0] < len(result.row_factors) \
        else None
    diags = [d.text for d in r.diagnoses if d.kind != DiagnosisKind.RESIDUAL]
    doc_latex = text_latex(r.document, names, r.document_latex)
    model = _divided(r.document_model, factor, names) if r.document_model else ""
    truth = _truth_latex(r, names)
    rows = [("document, as printed", math_box(doc_latex, "0"))]
    if model and model != doc_latex:
        rows.append(("in the model's parameters" + (f", ÷ {factor}" if factor else ""),
                     math_box(model)))
    if truth:
        rows.append(("truth", math_box(truth)))
    else:
        rows.append(("truth (number)", f"<div>{num_text(r.truth_sample, 6)} at the reference state; "
                     f"document {num_text(r.document_sample, 6)}; largest error {r.max_error:.3g}</div>"))
    diff = _difference(r, names)
    if diff:
        rows.append(("truth − document", math_box(diff)))
    grid = "".join(f"<span>{esc(a)}</span>{b}" for a, b in rows)
    return (f'<div class="card v-{r.verdict}" id="{S.element_anchor(result, r.element)}">'
            f"<h4>{element_title(r, names)}{esc(f' {r.equation}' if r.equation and r.equation not in r.element else '')}"
            f" — {esc(VERDICT_TEXT[r.verdict])}</h4>"
            + "".join(f'<div class="diag">{esc(d)}</div>' for d in diags)
            + f'<div class="rows">{grid}</div></div>')


def cards(result: DerivationResult, shown: Sequence[ElementRecord], names: Notation) -> str:
    r"""The entries of the shown elements, the equations of motion first, then each earlier
    step of the derivation (velocities, energies, claims ...) under its own heading."""
    steps: dict[str, list[ElementRecord]] = {}
    for r in shown:
        steps.setdefault(r.step, []).append(r)
    order = sorted(steps, key=lambda s: s != "equations of motion")
    out = []
    for step in order:
        if step != "equations of motion" or len(steps) > 1:
            out.append(f'<h4 class="step">{esc(step[:1].upper() + step[1:])}</h4>')
        out += [_card(result, r, names) for r in steps[step]]
    return "".join(out)


def agreeing(result: DerivationResult, names: Notation) -> str:
    agree = [r for r in result.records if r.verdict == "agrees"]
    if not agree:
        return ""
    rows = "".join(f"<tr><td>{element_title(r, names)}</td><td>"
                   f"{math_box(text_latex(r.document, names, r.document_latex), '0')}</td>"
                   f"<td>{math_box(_truth_latex(r, names), 'agrees (numbers)')}</td></tr>"
                   for r in agree)
    return (f"<details><summary>{len(agree)} agreeing elements</summary>"
            '<table class="agree"><colgroup><col class="c1"><col><col></colgroup>'
            f"<tr><th>element</th><th>document</th><th>truth</th></tr>{rows}</table></details>")
