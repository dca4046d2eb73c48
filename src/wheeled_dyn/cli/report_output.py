r"""What the commands print and write: the summary of each result, the shipped comparison
tables reproduced (reused from the results cache), the optional simulations, and the report
files."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:       # the heavy modules load in the functions (a quick --help and list)
    from ..compare.engine import ComparisonEngine
    from ..compare.records import DerivationResult


def summary_heading(r: DerivationResult) -> str:
    r"""``file — document eqs (1)-(3): title``; the parts the file does not give left out
    (``notes.toml — my notes, 26 Nov: title``, ``notes.toml: title``)."""
    document = str(r.source.get("document", "")).strip()
    equations = str(r.source.get("equations", "")).strip()
    where = " ".join(p for p in (document, f"eqs {equations}" if equations else "") if p)
    return f"{r.path.name} — {where}: {r.title}" if where else f"{r.path.name}: {r.title}"


#: Longest summary line printed whole (an energy residual unsimplified ran to 10 000
#: characters); a longer one is cut, the reports holding it whole.
SUMMARY_WIDTH = 600


def print_summary(results: Sequence[DerivationResult]) -> None:
    from ..report.markdown import summary_lines
    for r in results:
        print(summary_heading(r))
        for line in summary_lines(r):
            if len(line) > SUMMARY_WIDTH:
                line = (f"{line[:SUMMARY_WIDTH // 2]}… ({len(line)} characters: the reports "
                        "hold it whole)")
            print(f"    {line}")


def reused_tables(engine: ComparisonEngine, group: str) -> tuple[list[str], list[str], dict]:
    r""":func:`_table_sections`, reused from the results cache while no file of the group and
    nothing else it depends on changed."""
    from ..derivations import builtin_tables, load_comparison_table
    from ..derivations.builtin import builtin_derivations
    from ..compare.runtime.result_cache import result_key, reused
    tables = builtin_tables(group)
    if not tables:
        return [], [], {}
    model = load_comparison_table(tables[0]).model
    folder = tables[0].parent
    grid = ("tables", engine.samples, engine.param_sets, engine.seed)
    return reused(lambda: result_key(tables[0], model, grid, [*folder.glob("*.toml"),
                                                              *builtin_derivations(group)]),
                  tuple, lambda: tuple(_table_sections(engine, group)))


def _table_sections(engine: ComparisonEngine, group: str) -> tuple[list[str], list[str], dict]:
    r"""The shipped hand-made comparison tables of ``group``, reproduced by the machine."""
    import html as H

    from ..derivations import builtin_tables
    from ..derivations.table import load_comparison_table
    from ..compare.other_documents.tables import reproduce_table
    md, out_html, data = [], [], []
    for path in builtin_tables(group):
        rep = reproduce_table(load_comparison_table(path), engine)
        md.append(rep.markdown().replace("\n# ", "\n## ").replace("\n## Resulting", "\n### Resulting")
                  .replace("\n## Notes", "\n### Notes").replace("# Comparison", "## Comparison", 1))
        rows = "".join(
            f"<tr><td>{H.escape(r.element)}</td><td><code>{H.escape(r.derived)}</code></td>"
            f"<td><code>{H.escape(r.reference)}</code></td><td>{H.escape(r.machine)}"
            f"{' <b>≠ table</b>' if r.disagreement else ''}</td><td>{H.escape(r.table)}</td>"
            f"<td>{H.escape(r.truth)}</td><td>{H.escape(r.explanation)}</td></tr>" for r in rep.rows)
        notes = "".join(f"<li>{H.escape(n)}</li>" for n in rep.notes)
        out_html.append(
            f"<section><h2>Comparison table reproduced: {H.escape(path.name)}</h2>"
            f"<p>mismatched, table: {H.escape(', '.join(rep.table_mismatched))}; machine: "
            f"{H.escape(', '.join(rep.machine_mismatched))}</p><table><tr><th>element</th>"
            f"<th>derived</th><th>reference</th><th>machine</th><th>table</th>"
            f"<th>right (vs truth)</th><th>explanation</th></tr>{rows}</table><ul>{notes}</ul>"
            f"</section>")
        data.append({"table": path.name, "table_mismatched": list(rep.table_mismatched),
                     "machine_mismatched": list(rep.machine_mismatched),
                     "rows": [r.__dict__ for r in rep.rows], "notes": list(rep.notes)})
    return md, out_html, ({"tables": data} if data else {})


def plot_sections(results: Sequence[DerivationResult]) -> tuple[list[str], list[str], dict[str, bytes]]:
    r"""The optional section: each derivation simulated beside the truth (zero input)."""
    import base64

    from ..derivations import load_derivation
    from ..errors import WheeledDynError
    from .simulate_cmd import default_start
    from ..simulate.documented import side_by_side
    from ..simulate.plots import plot_side_by_side
    from ..compare.readings.row_combinations import as_compared
    md, html, files = ["## Simulations: truth and document from the same start", ""], [
        "<section><h2>Simulations: truth and document from the same start</h2>"], {}
    for r in results:
        if r.form == "linearised":              # published linear equations: nothing to run
            continue
        d = as_compared(load_derivation(r.path), r)
        try:
            factors = tuple(None if c is None else float(eval_fraction(c)) for c in r.row_factors)
            s = side_by_side(d, default_start(d), 4.0, row_factors=factors)
        except WheeledDynError as exc:
            md.append(f"- {r.path.name}: not simulated ({exc})")
            continue
        png = plot_side_by_side(s)
        name = f"{r.path.stem}_simulation.png"
        files[name] = png
        md.append(f"![{r.title}]({name})")
        html.append(f"<h3>{r.title}</h3><img alt='{name}' src='data:image/png;base64,"
                    f"{base64.b64encode(png).decode()}'>")
    html.append("</section>")
    return md, html, files


def eval_fraction(text: str) -> float:
    num, _, den = text.partition("/")
    return float(num) / float(den or 1)


def write_report(results, title: str, out: Path, plots: bool = False,
           sections: tuple[list[str], list[str], dict] = ([], [], {}),
           html_sections: dict[Path, str] | None = None) -> None:
    from ..report import render, write_reports
    md, html, js = sections
    files: dict[str, bytes] = {}
    if plots:
        pmd, phtml, files = plot_sections(results)
        md, html = [*md, *pmd], [*html, *phtml]
    paths = write_reports({**render(results, title, md, html, js, html_sections), **files},
                          out)
    print("reports: " + ", ".join(str(p) for p in paths))
