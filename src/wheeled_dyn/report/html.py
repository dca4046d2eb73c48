r"""The comparison as one self-contained HTML file: no network request, MathML with a math font.

Layout (one screen to the verdict, then the evidence):

1. a summary table — derivation, source equations, verdict counts, its causes one line each —
   each row linking to its section; then a table of contents;
2. per derivation, in the document's own order (:func:`.summary.ordered`): its causes, the
   "assumes:" line, the conventions, the matrices side by side (document in the model's
   parameters | truth, differing cells marked), then only the elements that differ or hold
   conditionally — document as printed, document in the model's parameters, truth and the
   simplified difference, as MathML — and the agreeing elements folded in a ``<details>``;
3. nothing wider than the window: document and truth side by side where both fit, else one
   below the other, each as wide as the page (a matrix wider than that scrolls inside its own
   box, as long formulas do); one column below 700 px.

Formulas are MathML made by ``latex2mathml`` from SymPy's LaTeX with the document's names
(:mod:`.symbols`); Chromium renders MathML offline, brackets stretch with the font
``DejaVu Math TeX Gyre`` (Debian fonts-dejavu-extra).
"""

from __future__ import annotations

import functools
import html
import re
from collections.abc import Mapping, Sequence
from pathlib import Path

import latex2mathml.converter as latex2mathml
import sympy as sp
from latex2mathml.converter import convert

from ..compare.records import DerivationResult, DiagnosisKind, ElementRecord
from ..disk_cache import DiskMemo
from . import summary as S
from .corrected import corrected_html
from .markdown import VERDICT_TEXT, check_lines
from .symbols import (
    Notation,
    derivation_notation,
    difference_latex,
    parse,
    product_latex,
    text_latex,
)

#: Short verdict words (summary counts, matrix cells).
SHORT = {"agrees": "agree", "agrees_if": "only if", "factorization": "factorisation",
         "differs": "differ", "undecided": "undecided"}
#: Numbers smaller than this are rounding noise of the truth (shown as ≈0).
ROUNDING = 1e-12
#: Causes shown per derivation in the summary table (the rest in its section).
SUMMARY_CAUSES = 3
#: Marks of a matrix cell by verdict (besides its colour).
MARK = {"agrees": "", "agrees_if": "?", "factorization": "≈", "differs": "≠", "undecided": "!"}

CSS = """
*{box-sizing:border-box}
body{font-family:"DejaVu Sans",sans-serif;margin:0 auto;padding:.8em 1.2em;max-width:1240px;
color:#222;line-height:1.4;font-size:15px}
math{font-family:"DejaVu Math TeX Gyre",math}
h1{font-size:1.35em;margin:.2em 0 .3em}h2{font-size:1.2em;border-top:2px solid #888;
padding-top:.5em;margin-top:1.6em}h3{font-size:1.02em;margin:1em 0 .4em}
a{color:#1a4fa0}code{font-size:.9em;overflow-wrap:anywhere;white-space:pre-wrap}
table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:.25em .45em;
vertical-align:top;text-align:left}th{background:#eee}
.lede{margin:.2em 0 .6em;color:#444}
.sumtab{width:100%;table-layout:fixed;font-size:.93em}
.sumtab td{overflow-wrap:anywhere}.sumtab ul{margin:0;padding-left:1.1em}
.sumtab li{white-space:nowrap;overflow:hidden;text-overflow:ellipsis;list-style-position:inside}
.sumtab ul{padding-left:0}
.sumtab col.c1{width:24%}.sumtab col.c2{width:11%}.sumtab col.c3{width:15%}
.pill{display:inline-block;padding:0 .35em;margin:.05em .1em;border-radius:.3em;
border:1px solid #bbb;white-space:nowrap;font-size:.92em}
.v-agrees{background:#d9f2d9}.v-agrees_if{background:#fff3c4}.v-factorization{background:#dde8ff}
.v-differs{background:#f9d0d0}.v-undecided{background:#e0e0e0}.pill.zero{color:#666}
.toc{columns:2 24em;margin:.3em 0}.toc li{break-inside:avoid}
.causes{background:#f6f6f6;padding:.4em .8em;border-left:4px solid #b33}
.causes.grouped{border-left-color:#c90}.causes ul{margin:.2em 0;padding-left:1.2em}
.meta,.assumes,.conv{margin:.35em 0}.fix{margin:.4em 0}.fix .m{overflow-x:auto}.fix pre{white-space:pre-wrap;font-size:.85em}.note{color:#555;font-size:.92em}
.m{overflow-x:auto;overflow-y:hidden;max-width:100%;padding:.1em 0}
.pair{display:flex;flex-wrap:wrap;gap:1em;margin:.4em 0}
.pane{flex:1 1 auto;min-width:0;max-width:100%;overflow-x:auto;border:1px solid #ddd;
padding:.3em;font-size:.9em}
.pane table.mat td{text-align:center;vertical-align:middle;min-width:2.5em;position:relative}
.mat td.v-differs,.mat td.v-agrees_if,.mat td.v-factorization{outline:2px solid #a33;
outline-offset:-2px}.mat td.v-agrees_if{outline-color:#b80}.mat td.v-factorization{outline-color:#36c}
.mark{font-size:.75em;font-weight:bold;color:#a33;vertical-align:super;margin-left:.2em}
.mat a{text-decoration:none;color:inherit}.mat .div{border:0;background:none;
white-space:nowrap;font-weight:normal;color:#555;min-width:0}.mat td.lost{color:#999;font-size:.8em}
.num{font-family:"DejaVu Sans Mono",monospace;font-size:.85em;color:#333}
.card{border:1px solid #ccc;border-left:6px solid #ccc;margin:.6em 0;padding:.3em .6em}
.card.v-differs{border-left-color:#c44}.card.v-agrees_if{border-left-color:#d9a400}
.card.v-factorization{border-left-color:#36c}.card.v-undecided{border-left-color:#888}
.card{background:#fff}.card h4{margin:.2em 0;font-size:1em}
h4.step{margin:1em 0 .2em;font-size:1em;color:#444}
.card .diag{font-size:.92em;margin:.1em 0 .3em}
.rows{display:grid;grid-template-columns:11em minmax(0,1fr);gap:.15em .8em;align-items:center}
.rows>span{color:#555;font-size:.9em}
details{margin:.6em 0}summary{cursor:pointer;font-weight:bold}
.agree{width:100%;table-layout:fixed}.agree td{overflow:hidden}
.agree col.c1{width:9em}
.wide{max-width:100%;overflow-x:auto}
.wide table{font-size:.85em}
@media (max-width:700px){body{padding:.5em;font-size:14px}.pane{flex-basis:100%}
.rows{grid-template-columns:1fr}.sumtab col.c2,.sumtab td:nth-child(2),.sumtab th:nth-child(2)
{display:none}.sumtab col.c1{width:34%}.sumtab col.c3{width:22%}.toc{columns:1}
.sumtab li{white-space:normal}}
"""


def _num(x: float, digits: int = 4) -> str:
    r"""A number at the reference state; rounding noise (below :data:`ROUNDING`) as ≈0."""
    return "≈0" if abs(x) < ROUNDING else f"{x:.{digits}g}"


#: The MathML of LaTeX texts, remembered across runs (the disk cache's
#: ``report/mathml-<code>.pickle``, named by SymPy's version, this file and latex2mathml's
#: converter: MathML made by other code is not read).
MATHML = DiskMemo("report", "mathml", lambda: [Path(__file__), Path(latex2mathml.__file__)])


@functools.lru_cache(maxsize=8192)
def _mathml(latex: str) -> str:
    r"""The MathML of ``latex`` (:data:`MATHML`); code for LaTeX latex2mathml cannot read."""
    return MATHML.get(latex, lambda: _converted(latex)) if latex else ""


def _converted(latex: str) -> str:
    try:
        return convert(latex)
    except Exception:          # an expression latex2mathml cannot read is shown as text
        return f"<code>{html.escape(latex)}</code>"


def _math_box(latex: str, empty: str = "—") -> str:
    return f'<div class="m">{_mathml(latex)}</div>' if latex else f'<div class="m">{empty}</div>'


def _e(text: object) -> str:
    return html.escape(str(text))


def _counts(result: DerivationResult) -> str:
    r"""The verdict counts as pills; a count of 0 is neutral ("0 differ" is not red)."""
    c = result.counts()
    return "".join(f'<span class="pill {f"v-{v}" if n else "zero"}">{n} {SHORT[v]}</span>'
                   for v, n in c.items() if n or v in ("agrees", "differs"))


# -- the top of the report --------------------------------------------------------------------
def summary_table(results: Sequence[DerivationResult]) -> str:
    r"""The one-screen summary: one row per derivation, linking to its section; at most
    :data:`SUMMARY_CAUSES` causes, one line each (the full sentence on hover)."""
    rows = []
    for r in results:
        names = derivation_notation(r.path)
        lines = [c.one_line(names.label) for c in S.cause_lines(r)]
        items = "".join(f'<li title="{_e(t)}">{_e(t)}</li>' for t in lines[:SUMMARY_CAUSES])
        more = len(lines) - SUMMARY_CAUSES
        extra = f"<br><a href='#{S.anchor(r)}'>+{more} more</a>" if more > 0 else ""
        factors = S.row_factor_line(r)
        if factors:
            extra += f"<br><span class='note' title='{_e(factors)}'>{_e(factors.split('×')[0])}× (undeclared)</span>"
        rows.append(f"<tr><td><a href='#{S.anchor(r)}'>{_e(r.title)}</a></td>"
                    f"<td>{_e(S.equations(r))}</td><td>{_counts(r)}{extra}</td>"
                    f"<td><ul>{items or '<li>no difference found</li>'}</ul></td></tr>")
    return ('<table class="sumtab" id="summary"><colgroup><col class="c1"><col class="c2">'
            '<col class="c3"><col></colgroup><tr><th>derivation</th><th>source</th>'
            "<th>verdicts</th><th>causes</th></tr>" + "".join(rows) + "</table>")


def _extra_titles(extra_html: Sequence[str]) -> list[str]:
    out = []
    for text in extra_html:
        m = re.search(r"<h2>(.*?)</h2>", text, re.S)
        out.append(re.sub(r"<[^>]+>", "", m.group(1)) if m else "more")
    return out


def contents(results: Sequence[DerivationResult], extra_titles: Sequence[str]) -> str:
    r"""The table of contents."""
    items = [f"<li><a href='#{S.anchor(r)}'>{_e(S.equations(r))} — {_e(r.title)}</a></li>"
             for r in results]
    items += [f"<li><a href='#extra-{k + 1}'>{_e(t)}</a></li>" for k, t in enumerate(extra_titles)]
    return f'<nav id="contents"><h2>Contents</h2><ol class="toc">{"".join(items)}</ol></nav>'


# -- one derivation ---------------------------------------------------------------------------
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
    is shown in them too; without, or with the truth in the document's symbols, as printed, and both sides show their numbers
    at the reference state (the document's after dividing out a row factor)."""
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
                body = _mathml(_divided(r.document_model or r.document, factor, names)) or \
                    _mathml(r.model_latex or r.document_latex)
            elif document:
                latex = text_latex(r.document, names, r.document_latex)
                number = "" if not r.document or parse(r.document) is None or \
                    parse(r.document).is_number else f'<div class="num">{_num(r.document_sample)}</div>'
                body = (_mathml(latex) or "0") + number
            else:
                latex = _truth_latex(r, names)
                body = _mathml(latex) if latex else f'<div class="num">{_num(r.truth_sample)}</div>'
            mark = f'<span class="mark">{MARK[r.verdict]}</span>' if MARK[r.verdict] else ""
            if r.verdict != "agrees":
                body = f"<a href='#{S.element_anchor(result, r.element)}'>{body}</a>"
            tip = _e(VERDICT_TEXT[r.verdict] + (f"; {r.diagnoses[0]}" if r.diagnoses else ""))
            cells.append(f'<td class="v-{r.verdict}" title="{tip}">{body}{mark}</td>')
        side = (f"<th class='div'>÷ {_e(factor)}</th>" if factor else "<td class='div'></td>") \
            if marked else ""
        rows.append(f"<tr>{side}{''.join(cells)}</tr>")
    if document:
        label = ("document, in the model's parameters" if closed else
                 "document as printed; below each, its number at the reference state")
    else:
        label = "truth" if closed else "truth: numbers at the reference state"
    return (f'<div><b>{key}</b> <span class="note">({label})</span>'
            f'<table class="mat">{"".join(rows)}</table></div>')


def _matrices(result: DerivationResult, names: Notation) -> str:
    out = []
    for key in ("A", "C", "Q", "B"):
        doc = _matrix(result, key, names, True)
        if doc:
            out.append(f'<div class="pair"><div class="pane">{doc}</div><div class="pane">'
                       f"{_matrix(result, key, names, False)}</div></div>")
    return "".join(out)


def element_title(r: ElementRecord, names: Notation) -> str:
    r"""An element's name; a velocity product of h with its velocities as math."""
    if r.key == "h" and ":" in r.element:
        row, product = r.element.split(":", 1)
        return (f"{_e(row)}, coefficient of " + _mathml(product_latex(product, names)))
    return _e(r.element)


def _difference(r: ElementRecord, names: Notation) -> str:
    return difference_latex(r.residual, names, r.residual_latex)


def _card(result: DerivationResult, r: ElementRecord, names: Notation) -> str:
    factor = result.row_factors[r.index[0]] if r.index and r.index[0] < len(result.row_factors) \
        else None
    diags = [d.text for d in r.diagnoses if d.kind != DiagnosisKind.RESIDUAL]
    doc_latex = text_latex(r.document, names, r.document_latex)
    model = _divided(r.document_model, factor, names) if r.document_model else ""
    truth = _truth_latex(r, names)
    rows = [("document, as printed", _math_box(doc_latex, "0"))]
    if model and model != doc_latex:
        rows.append(("in the model's parameters" + (f", ÷ {factor}" if factor else ""),
                     _math_box(model)))
    if truth:
        rows.append(("truth", _math_box(truth)))
    else:
        rows.append(("truth (number)", f"<div>{_num(r.truth_sample, 6)} at the reference state; "
                     f"document {_num(r.document_sample, 6)}; largest error {r.max_error:.3g}</div>"))
    diff = _difference(r, names)
    if diff:
        rows.append(("truth − document", _math_box(diff)))
    grid = "".join(f"<span>{_e(a)}</span>{b}" for a, b in rows)
    return (f'<div class="card v-{r.verdict}" id="{S.element_anchor(result, r.element)}">'
            f"<h4>{element_title(r, names)}{_e(f' {r.equation}' if r.equation and r.equation not in r.element else '')}"
            f" — {_e(VERDICT_TEXT[r.verdict])}</h4>"
            + "".join(f'<div class="diag">{_e(d)}</div>' for d in diags)
            + f'<div class="rows">{grid}</div></div>')


def _cards(result: DerivationResult, shown: Sequence[ElementRecord], names: Notation) -> str:
    r"""The entries of the shown elements, the equations of motion first, then each earlier
    step of the derivation (velocities, energies, claims ...) under its own heading."""
    steps: dict[str, list[ElementRecord]] = {}
    for r in shown:
        steps.setdefault(r.step, []).append(r)
    order = sorted(steps, key=lambda s: s != "equations of motion")
    out = []
    for step in order:
        if step != "equations of motion" or len(steps) > 1:
            out.append(f'<h4 class="step">{_e(step[:1].upper() + step[1:])}</h4>')
        out += [_card(result, r, names) for r in steps[step]]
    return "".join(out)


def _agreeing(result: DerivationResult, names: Notation) -> str:
    agree = [r for r in result.records if r.verdict == "agrees"]
    if not agree:
        return ""
    rows = "".join(f"<tr><td>{element_title(r, names)}</td><td>"
                   f"{_math_box(text_latex(r.document, names, r.document_latex), '0')}</td>"
                   f"<td>{_math_box(_truth_latex(r, names), 'agrees (numbers)')}</td></tr>"
                   for r in agree)
    return (f"<details><summary>{len(agree)} agreeing elements</summary>"
            '<table class="agree"><colgroup><col class="c1"><col><col></colgroup>'
            f"<tr><th>element</th><th>document</th><th>truth</th></tr>{rows}</table></details>")


def _causes(result: DerivationResult, names: Notation) -> str:
    r"""The causes the result names, the other findings grouped by diagnosis, the causes in
    earlier steps."""
    lines = S.cause_lines(result)
    if not lines:
        return '<div class="causes"><b>Causes:</b> none — every element agrees.</div>'

    def items(group):
        return "".join(f"<li>{_e(c.one_line(names.label))}"
                       + (f"<div class='m'>{_mathml(c.latex)}</div>" if c.latex else "") + "</li>"
                       for c in group)
    root = [c for c in lines if c.computed and c.kind != "upstream_step"]
    grouped = [c for c in lines if not c.computed]
    upstream = [c for c in lines if c.computed and c.kind == "upstream_step"]
    out = f"<b>Causes</b><ul>{items(root)}</ul>" if root else ""
    if grouped:
        head = "Other findings, grouped by diagnosis" if root else \
            "Findings, grouped by diagnosis"
        note = "" if root else (' <span class="note">(no root cause was computed for these '
                                "elements; they are grouped by their diagnosis)</span>")
        out += f"<b>{head}</b>{note}<ul>{items(grouped)}</ul>"
    if upstream:
        out += f"<b>Found in earlier steps</b><ul>{items(upstream)}</ul>"
    return f'<div class="causes{"" if root else " grouped"}">{out}</div>'


def _conventions(result: DerivationResult) -> str:
    factors = S.row_factor_line(result)
    parts = []
    equations = S.equations_line(result)
    out = f'<p class="eqs"><b>Equations:</b> {_e(equations)}</p>' if equations else ""
    if S.conventions_line(result):
        parts.append(_e(S.conventions_line(result)))
    if factors:
        parts.append(_e(factors))
    if not parts:
        return out
    return out + '<p class="conv"><b>Conventions:</b> ' + "; ".join(parts) + "</p>"


def _grid_text(result: DerivationResult) -> str:
    r"""What the numbers were decided on: the random grid, or the model's linearisation."""
    if result.form == "linearised":
        return "the model's own linearisation (each number to its printed digits)"
    return f"{result.samples} states × {result.parameter_sets} random parameter sets"


def derivation_html(result: DerivationResult, names: Notation | None = None) -> str:
    r"""One derivation's section."""
    names = names or derivation_notation(result.path)
    src = result.source
    shown = [r for r in result.records if r.verdict in S.SHOWN_VERDICTS]
    recon = ""
    if result.reconstructed:
        recon = ('<p class="note"><b>Reconstructed from garbled text:</b> ' + "; ".join(
            _e(f"{k}: {v}") for k, v in result.reconstructed.items()) + "</p>")
    if result.latex_input:
        recon += ('<details class="latex-input"><summary>Read from LaTeX ('
                  f"{len(result.latex_input)})</summary><table>"
                  + "".join(f"<tr><td>{_e(k)}</td><td><code>{_e(a)}</code></td>"
                            f"<td>parsed as <code>{_e(b)}</code></td></tr>"
                            for k, (a, b) in result.latex_input.items())
                  + "</table></details>")
    checks = "".join(f"<li>{_e(line)}</li>" for line in check_lines(result))
    return (f'<section id="{S.anchor(result)}"><h2>{_e(S.equations(result))} — {_e(result.title)}</h2>'
            f"{_causes(result, names)}"
            f'<p class="assumes"><b>Assumes:</b> {_e(S.assumes_line(result, dict(names.assumed)))}</p>'
            f"{_conventions(result)}"
            f'<p class="meta note"><code>{_e(result.path.name)}</code> — '
            f"{_e(' '.join(str(src.get(k, '')).strip() for k in ('document', 'section') if src.get(k)))}; model "
            f"<code>{_e(result.model)}</code>, coordinates <code>{_e(result.coordinates)}</code> "
            f"(velocities {_mathml(', '.join(names.latex(v) for v in result.velocities))}); "
            f"{_grid_text(result)} "
            f"{_counts(result)}</p>{recon}"
            f"<h3>Matrices: document | truth</h3>"
            f'<p class="note">Marked cells: ≠ differs, ? agrees only for special values, '
            f"≈ only the factorisation of C differs; click one for its entry below.</p>"
            f"{_matrices(result, names)}"
            f"{corrected_html(result, _mathml)}"
            f"<h3>What differs or holds only conditionally ({len(shown)})</h3>"
            + (_cards(result, shown, names) or "<p>Nothing: every element agrees.</p>")
            + _agreeing(result, names)
            + (f"<details><summary>Checks of the document on its own</summary><ul>{checks}</ul>"
               "</details>" if checks else "")
            + "</section>")


def report_html(results: Sequence[DerivationResult], title: str, extra_html: Sequence[str] = (),
                sections: Mapping[Path, str] | None = None) -> str:
    r"""The whole report: summary, contents, derivations in the document's order, extras.
    ``sections``: derivations' :func:`derivation_html` made already (by the processes that
    compared them), by file."""
    results = S.ordered(results)
    sections = sections or {}
    legend = "".join(f'<span class="pill v-{v}">{_e(VERDICT_TEXT[v])}</span>' for v in SHORT)
    titles = _extra_titles(extra_html)
    extras = "".join(f'<div class="wide" id="extra-{k + 1}">{text}</div>'
                     for k, text in enumerate(extra_html))
    grid = "; ".join(sorted({_grid_text(r) for r in results}))
    body = "".join(sections.get(r.path) or derivation_html(r) for r in results)
    return ("<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
            "<meta name='viewport' content='width=device-width, initial-scale=1'>"
            f"<title>{_e(title)}</title><style>{CSS}</style></head><body>"
            f"<h1>{_e(title)}</h1><p class='lede'>{len(results)} derivations, in the documents' "
            f"order; each on {_e(grid)}. Verdicts: {legend}</p>"
            f"{summary_table(results)}{contents(results, titles)}{body}{extras}</body></html>")
