r"""The comparison as one self-contained HTML file: no network, MathML with a math font.

Per derivation: a summary first (elements agreeing, typos, missing physics, energy), then the
document's matrices and the true ones side by side, each element coloured by its verdict, then
the seed-style table: element | document | document after the parameter map | truth | verdict.
Formulas are MathML made by ``latex2mathml`` from SymPy's LaTeX; Chromium renders MathML
offline, and brackets stretch with the font ``DejaVu Math TeX Gyre`` (Debian fonts-dejavu-extra).
"""

from __future__ import annotations

import html
from collections.abc import Sequence

from latex2mathml.converter import convert

from ..compare.result import DerivationResult, ElementRecord
from .markdown import VERDICT_TEXT, summary_lines

COLOURS = {"agrees": "#d9f2d9", "agrees_if": "#fff3c4", "factorization": "#dde8ff",
           "differs": "#f9d0d0", "undecided": "#e0e0e0"}

CSS = """
body{font-family:"DejaVu Sans",sans-serif;margin:2em;max-width:90em;color:#222}
math{font-family:"DejaVu Math TeX Gyre",math}
h1{font-size:1.6em}h2{border-top:2px solid #888;padding-top:.6em;margin-top:2em}
table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #bbb;padding:.3em .5em;
vertical-align:middle}th{background:#eee}.summary{background:#f6f6f6;padding:.6em 1em}
.matrices{display:flex;gap:3em;flex-wrap:wrap}.matrix td{text-align:center;min-width:4em}
.legend span{padding:.2em .6em;margin-right:.5em;border:1px solid #bbb}
.diag{font-size:.9em}.num{font-family:monospace}
"""


def _mathml(latex: str) -> str:
    if not latex:
        return ""
    try:
        return convert(latex)
    except Exception:          # an expression latex2mathml cannot read is shown as text
        return f"<code>{html.escape(latex)}</code>"


def _cell(r: ElementRecord | None, content: str) -> str:
    if r is None:
        return "<td></td>"
    tip = html.escape(VERDICT_TEXT[r.verdict] + ("; " + "; ".join(r.diagnoses) if r.diagnoses else ""))
    return f'<td style="background:{COLOURS[r.verdict]}" title="{tip}">{content}</td>'


def _matrix(result: DerivationResult, key: str, document: bool) -> str:
    recs = {r.index: r for r in result.records if r.key == key}
    if not recs:
        return ""
    n = len(result.velocities)
    cols = max(i[1] for i in recs) + 1 if key not in ("Q",) else 1
    rows = []
    for i in range(n):
        cells = []
        for j in range(cols):
            r = recs.get((i,) if key == "Q" else (i, j))
            if r is None:
                cells.append("<td></td>")
            elif document:
                cells.append(_cell(r, _mathml(r.document_latex) or "0"))
            else:
                val = _mathml(r.truth_latex) if r.truth_latex else f'<span class="num">{r.truth_sample:.4g}</span>'
                cells.append(_cell(r, val))
        rows.append("<tr>" + "".join(cells) + "</tr>")
    side = "document" if document else ("truth" if any(r.truth_latex for r in recs.values())
                                       else "truth at the reference sample")
    return (f'<div><b>{key}</b> ({side})<table class="matrix">' + "".join(rows) + "</table></div>")


def _table(result: DerivationResult) -> str:
    head = ("<tr><th>element</th><th>document</th><th>document after the parameter map</th>"
            "<th>truth</th><th>verdict</th></tr>")
    rows = []
    for r in result.records:
        truth = _mathml(r.truth_latex) if r.truth_latex else (f'<span class="num">{r.truth_sample:.6g}</span>'
                                                  f" at the reference sample")
        verdict = html.escape(VERDICT_TEXT[r.verdict])
        diag = "".join(f"<div class='diag'>{html.escape(d)}</div>" for d in r.diagnoses)
        rows.append(f"<tr><td>{html.escape(r.element)}</td><td>{_mathml(r.document_latex)}</td>"
                    f"<td>{_mathml(r.model_latex)}</td><td>{truth}</td>"
                    + _cell(r, verdict + diag) + "</tr>")
    return "<table>" + head + "".join(rows) + "</table>"


def derivation_html(result: DerivationResult) -> str:
    src = result.source
    summary = "".join(f"<li>{html.escape(line)}</li>" for line in summary_lines(result))
    recon = ""
    if result.reconstructed:
        recon = "<p><b>Reconstructed from garbled text:</b> " + "; ".join(
            html.escape(f"{k}: {v}") for k, v in result.reconstructed.items()) + "</p>"
    mats_doc = "".join(_matrix(result, k, True) for k in ("A", "C", "Q", "B"))
    mats_true = "".join(_matrix(result, k, False) for k in ("A", "C", "Q", "B"))
    return (f"<section><h2>{html.escape(result.title)}</h2>"
            f"<p><code>{html.escape(result.path.name)}</code> — "
            f"{html.escape(' '.join(str(src.get(k, '')) for k in ('document', 'section')))} "
            f"eqs {html.escape(str(src.get('equations', '')))}; model <code>{result.model}</code>, "
            f"coordinates <code>{result.coordinates}</code> "
            f"({html.escape(', '.join(result.velocities))}); {result.samples} states × "
            f"{result.parameter_sets} random parameter sets.</p>"
            f'<div class="summary"><ul>{summary}</ul></div>{recon}'
            f'<div class="matrices"><div><h3>Document</h3>{mats_doc}</div>'
            f'<div><h3>Truth</h3>{mats_true}</div></div>'
            f"<h3>Element by element</h3>{_table(result)}</section>")


def report_html(results: Sequence[DerivationResult], title: str, extra_html: Sequence[str] = ()) -> str:
    legend = "".join(f'<span style="background:{c}">{html.escape(VERDICT_TEXT[v])}</span>'
                     for v, c in COLOURS.items())
    body = "".join(derivation_html(r) for r in results) + "".join(extra_html)
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            f"<style>{CSS}</style></head><body><h1>{html.escape(title)}</h1>"
            f'<p class="legend">{legend}</p>{body}</body></html>')
