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

import re
from collections.abc import Mapping, Sequence
from pathlib import Path

from ..compare.records import DerivationResult
from . import summary as S
from .corrected import corrected_html
from .html_elements import agreeing, cards, matrices
from .html_text import esc, mathml
from .markdown import VERDICT_TEXT, check_lines
from .symbols import Notation, derivation_notation


#: Short verdict words (summary counts, matrix cells).
SHORT = {"agrees": "agree", "agrees_if": "only if", "factorization": "factorisation",
         "differs": "differ", "undecided": "undecided"}


#: Causes shown per derivation in the summary table (the rest in its section).
SUMMARY_CAUSES = 3


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
.meta,.assumes,.conv{margin:.35em 0}.fix{margin:.4em 0}.fix .m{overflow-x:auto}
.fix pre{white-space:pre-wrap;font-size:.85em}.note{color:#555;font-size:.92em}
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


def _counts(result: DerivationResult) -> str:
    r"""The verdict counts as pills; a count of 0 is neutral ("0 differ" is not red), but where
    no element differs and the equations are not equivalent (a factor that vanishes, an
    equation lost, the constraints) that pill says so."""
    c = result.counts()
    whole = S.system_word(result)

    def pill(v: str, n: int) -> str:
        if v == "differs" and not n and whole:
            decided = result.equivalent is not None
            return (f'<span class="pill {"v-differs" if decided else "v-undecided"}" '
                    f'title="{esc(whole)}">{"not equivalent" if decided else "not decided"}'
                    '</span>')
        return f'<span class="pill {f"v-{v}" if n else "zero"}">{n} {SHORT[v]}</span>'
    return "".join(pill(v, n) for v, n in c.items() if n or v in ("agrees", "differs"))


# -- the top of the report --------------------------------------------------------------------
def summary_table(results: Sequence[DerivationResult]) -> str:
    r"""The one-screen summary: one row per derivation, linking to its section; at most
    :data:`SUMMARY_CAUSES` causes, one line each (the full sentence on hover)."""
    rows = []
    for r in results:
        names = derivation_notation(r.path)
        lines = [c.one_line(names.label) for c in S.cause_lines(r)]
        items = "".join(f'<li title="{esc(t)}">{esc(t)}</li>' for t in lines[:SUMMARY_CAUSES])
        more = len(lines) - SUMMARY_CAUSES
        extra = f"<br><a href='#{S.anchor(r)}'>+{more} more</a>" if more > 0 else ""
        factors = S.row_factor_line(r)
        if factors:
            extra += f"<br><span class='note' title='{esc(factors)}'>{esc(factors.split('×')[0])}× (undeclared)</span>"
        rows.append(f"<tr><td><a href='#{S.anchor(r)}'>{esc(r.title)}</a></td>"
                    f"<td>{esc(S.equations(r))}</td><td>{_counts(r)}{extra}</td>"
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
    items = [f"<li><a href='#{S.anchor(r)}'>{esc(S.equations(r))} — {esc(r.title)}</a></li>"
             for r in results]
    items += [f"<li><a href='#extra-{k + 1}'>{esc(t)}</a></li>" for k, t in enumerate(extra_titles)]
    return f'<nav id="contents"><h2>Contents</h2><ol class="toc">{"".join(items)}</ol></nav>'


def _causes(result: DerivationResult, names: Notation) -> str:
    r"""The causes the result names, the other findings grouped by diagnosis, the causes in
    earlier steps."""
    lines = S.cause_lines(result)
    if not lines:
        return '<div class="causes"><b>Causes:</b> none — every element agrees.</div>'

    def items(group):
        return "".join(f"<li>{esc(c.one_line(names.label))}"
                       + (f"<div class='m'>{mathml(c.latex)}</div>" if c.latex else "") + "</li>"
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
    out = f'<p class="eqs"><b>Equations:</b> {esc(equations)}</p>' if equations else ""
    if S.conventions_line(result):
        parts.append(esc(S.conventions_line(result)))
    if factors:
        parts.append(esc(factors))
    if not parts:
        return out
    return out + '<p class="conv"><b>Conventions:</b> ' + "; ".join(parts) + "</p>"


def _grid_text(result: DerivationResult) -> str:
    r"""What the numbers were decided on: the random grid, or the model's linearisation."""
    if result.form == "linearised":
        return "the model's own linearisation (each number to its printed digits)"
    return f"{result.samples} states × {result.parameter_sets} random parameter sets"


def _readings(result: DerivationResult) -> str:
    r"""What the model reads otherwise than its URDF writes, a list under the assumptions."""
    if not result.model_readings:
        return ""
    return ('<div class="assumes"><b>The model reads its URDF so:</b><ul>'
            + "".join(f"<li>{esc(r)}</li>" for r in result.model_readings) + "</ul></div>")


def derivation_html(result: DerivationResult, names: Notation | None = None) -> str:
    r"""One derivation's section."""
    names = names or derivation_notation(result.path)
    src = result.source
    shown = [r for r in result.records if r.verdict in S.SHOWN_VERDICTS]
    recon = ""
    if result.reconstructed:
        recon = ('<p class="note"><b>Reconstructed from garbled text:</b> ' + "; ".join(
            esc(f"{k}: {v}") for k, v in result.reconstructed.items()) + "</p>")
    if result.latex_input:
        recon += ('<details class="latex-input"><summary>Read from LaTeX ('
                  f"{len(result.latex_input)})</summary><table>"
                  + "".join(f"<tr><td>{esc(k)}</td><td><code>{esc(a)}</code></td>"
                            f"<td>parsed as <code>{esc(b)}</code></td></tr>"
                            for k, (a, b) in result.latex_input.items())
                  + "</table></details>")
    checks = "".join(f"<li>{esc(line)}</li>" for line in check_lines(result))
    return (f'<section id="{S.anchor(result)}"><h2>{esc(S.equations(result))} — {esc(result.title)}</h2>'
            f"{_causes(result, names)}"
            f'<p class="assumes"><b>Assumes:</b> {esc(S.assumes_line(result, dict(names.assumed)))}</p>'
            f"{_readings(result)}"
            f"{_conventions(result)}"
            f'<p class="meta note"><code>{esc(result.path.name)}</code> — '
            f"{esc(' '.join(str(src.get(k, '')).strip() for k in ('document', 'section') if src.get(k)))}; model "
            f"<code>{esc(result.model)}</code>, coordinates <code>{esc(result.coordinates)}</code> "
            f"(velocities {mathml(', '.join(names.latex(v) for v in result.velocities))}); "
            f"{_grid_text(result)} "
            f"{_counts(result)}</p>{recon}"
            f"<h3>Matrices: document | truth</h3>"
            f'<p class="note">Marked cells: ≠ differs, ? agrees only for special values, '
            f"≈ only the factorisation of C differs; click one for its entry below.</p>"
            f"{matrices(result, names)}"
            f"{corrected_html(result)}"
            f"<h3>What differs or holds only conditionally ({len(shown)})</h3>"
            + (cards(result, shown, names) or "<p>Nothing: every element agrees.</p>")
            + agreeing(result, names)
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
    legend = "".join(f'<span class="pill v-{v}">{esc(VERDICT_TEXT[v])}</span>' for v in SHORT)
    titles = _extra_titles(extra_html)
    extras = "".join(f'<div class="wide" id="extra-{k + 1}">{text}</div>'
                     for k, text in enumerate(extra_html))
    grid = "; ".join(sorted({_grid_text(r) for r in results}))
    body = "".join(sections.get(r.path) or derivation_html(r) for r in results)
    return ("<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
            "<meta name='viewport' content='width=device-width, initial-scale=1'>"
            f"<title>{esc(title)}</title><style>{CSS}</style></head><body>"
            f"<h1>{esc(title)}</h1><p class='lede'>{len(results)} derivations, in the documents' "
            f"order; each on {esc(grid)}. Verdicts: {legend}</p>"
            f"{summary_table(results)}{contents(results, titles)}{body}{extras}</body></html>")
