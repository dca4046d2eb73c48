r"""The comparison as Markdown with math GitHub renders (``$...$``), in the structure of the HTML
report: the summary table first, then per derivation (in the document's own order) its causes,
"assumes:" line, conventions, a table of only the elements that differ or hold conditionally
(document, truth, simplified difference) and the agreeing elements named in one line."""

from __future__ import annotations

from collections.abc import Sequence

from ..compare.records import DerivationResult, DiagnosisKind, ElementRecord
from . import summary as S
from .corrected import corrected_markdown
from .symbols import derivation_notation, difference_latex, product_latex, text_latex

VERDICT_TEXT = {"agrees": "agrees", "agrees_if": "agrees only for special values",
                "factorization": "factorisation of C only", "differs": "differs",
                "undecided": "cannot decide"}
#: Causes named per derivation in the summary table (all of them in its section).
SUMMARY_CAUSES = 3
#: Formulas longer than this (characters of LaTeX) are left to the HTML report.
LONG_LATEX = 200


def _math(latex: str) -> str:
    if not latex:
        return ""
    if len(latex) > LONG_LATEX:
        return "(long: see the HTML report)"
    return "$" + latex.replace("|", "\\vert ") + "$"


def check_lines(result: DerivationResult) -> list[str]:
    r"""The checks of the document on its own: energy, symmetry, constraints, notes."""
    lines = []
    if result.energy is not None:
        lines.append("conserves energy (power identity holds)" if result.energy.conserves else
                     f"does not conserve energy: ν·h − ½ ν·Ȧν = {result.energy.residual}")
    return lines + list(result.asymmetric) + list(result.constraints) + list(result.notes)


def summary_lines(result: DerivationResult) -> list[str]:
    r"""The summary of one derivation, as short lines (also printed by the CLI)."""
    c = result.counts()
    lines = [f"{c['agrees']} agree, {c['agrees_if']} agree only for special parameter values, "
             f"{c['factorization']} differ in factorisation only, {c['differs']} differ"
             + (f", {c['undecided']} undecided" if c.get("undecided") else "")
             + (f"; {S.system_word(result)}" if S.system_word(result) else "")]
    lines += [line.one_line() for line in S.cause_lines(result)]
    factors = S.row_factor_line(result)
    if factors:
        lines.append(factors)
    return lines + [f"model: {r}" for r in result.model_readings] + check_lines(result)


def _counts(result: DerivationResult) -> str:
    short = {"agrees": "agree", "agrees_if": "only if", "factorization": "factorisation",
             "differs": "differ", "undecided": "undecided"}
    counts = ", ".join(f"{n} {short[v]}" for v, n in result.counts().items()
                       if n or v in ("agrees", "differs"))
    return f"{counts}; **{S.system_word(result)}**" if S.system_word(result) else counts


def _cell(text: str) -> str:
    return text.replace("|", "/").replace("\n", " ")


def summary_markdown(results: Sequence[DerivationResult]) -> list[str]:
    r"""The summary table (one row per derivation, linking to its section)."""
    lines = ["## Summary", "", "| derivation | source | verdicts | causes |", "|---|---|---|---|"]
    for r in results:
        label = derivation_notation(r.path).label
        causes = [c.one_line(label) for c in S.cause_lines(r)] or ["no difference found"]
        if len(causes) > SUMMARY_CAUSES:
            causes = causes[:SUMMARY_CAUSES] + [f"+{len(causes) - SUMMARY_CAUSES} more"]
        lines.append(f"| [{_cell(r.title)}](#{S.anchor(r)}) | {_cell(S.equations(r))} | "
                     f"{_counts(r)} | {_cell('<br>'.join(causes))} |")
    return lines


def _label(r: ElementRecord, names) -> str:
    if r.key == "h" and ":" in r.element:
        row, product = r.element.split(":", 1)
        return f"{row} · {_math(product_latex(product, names))}"
    if r.step != "equations of motion":
        return _cell(f"{r.step}: {r.element}")
    return r.element


def _row(result: DerivationResult, r: ElementRecord, names) -> str:
    diag = "; ".join(d.text for d in r.diagnoses if d.kind != DiagnosisKind.RESIDUAL)
    verdict = VERDICT_TEXT[r.verdict] + (f": {diag}" if diag else "")
    truth = text_latex(r.truth, names, r.truth_latex) if r.truth else ""
    truth = _math(truth) if truth else (f"{r.truth_sample:.4g} at the reference state "
                                        f"(largest error {r.max_error:.3g})")
    return (f"| {_label(r, names)} | {_cell(verdict)} | "
            f"{_math(text_latex(r.document, names, r.document_latex)) or '0'} | {truth} | "
            f"{_math(difference_latex(r.residual, names, r.residual_latex))} |")


def _readings(result: DerivationResult) -> list[str]:
    r"""What the model reads otherwise than its URDF writes, a list under the assumptions."""
    if not result.model_readings:
        return []
    return ["**The model reads its URDF so:**", ""] + [
        f"- {r}" for r in result.model_readings] + [""]


def derivation_markdown(result: DerivationResult) -> str:
    r"""One derivation's section."""
    names = derivation_notation(result.path)
    src = result.source
    lines = [f'<a id="{S.anchor(result)}"></a>', "",
             f"## {S.equations(result)} — {result.title}", ""]
    causes = S.cause_lines(result)
    root = [c for c in causes if c.computed and c.kind != "upstream_step"]
    grouped = [c for c in causes if not c.computed]
    upstream = [c for c in causes if c.computed and c.kind == "upstream_step"]

    def items(group):
        return [f"- {c.one_line(names.label)}" + (f" {_math(c.latex)}" if c.latex else "")
                for c in group]
    if root:
        lines += ["**Causes:**", ""] + items(root) + [""]
    if grouped:
        head = "Other findings, grouped by diagnosis" if root else \
            "Findings, grouped by diagnosis (no root cause computed)"
        lines += [f"**{head}:**", ""] + items(grouped) + [""]
    if upstream:
        lines += ["**Found in earlier steps:**", ""] + items(upstream) + [""]
    if not causes:
        lines += ["**Causes:** none, every element agrees.", ""]
    lines += [f"**Assumes:** {S.assumes_line(result, dict(names.assumed))}", ""]
    lines += _readings(result)
    if S.equations_line(result):
        lines += [f"**Equations:** {S.equations_line(result)}.", ""]
    if S.conventions_line(result):
        lines += [f"**Conventions:** {S.conventions_line(result)}.", ""]
    factors = S.row_factor_line(result)
    if factors:
        lines += [f"**Rows:** {factors}.", ""]
    lines += corrected_markdown(result)
    lines += [f"`{result.path.name}` — {src.get('document', '')} {src.get('section', '')}; model "
              f"`{result.model}`, coordinates `{result.coordinates}`; {result.samples} states × "
              f"{result.parameter_sets} random parameter sets; {_counts(result)}.", ""]
    shown = [r for r in result.records if r.verdict in S.SHOWN_VERDICTS and r.verdict != "agrees_if"]
    if shown:
        lines += [f"What differs ({len(shown)}):", "",
                  "| element | verdict | document | truth | truth − document |",
                  "|---|---|---|---|---|"]
        lines += [_row(result, r, names) for r in shown]
        lines.append("")
    conditional = [r for r in result.records if r.verdict == "agrees_if"]
    if conditional:
        lines += [f"What holds only conditionally ({len(conditional)}):", "",
                  "| element | condition | truth − document |", "|---|---|---|"]
        lines += [f"| {_label(r, names)} | {_cell(S.condition(r))} | "
                  f"{_math(difference_latex(r.residual, names, r.residual_latex))} |"
                  for r in conditional]
        lines.append("")
    agree = [r.element for r in result.records if r.verdict == "agrees"]
    if agree:
        lines += [f"Agreeing ({len(agree)}): " + ", ".join(agree), ""]
    checks = check_lines(result)
    if checks:
        lines += ["Checks of the document on its own:", ""] + [f"- {c}" for c in checks] + [""]
    if result.reconstructed:
        lines += ["Reconstructed from garbled text: " + "; ".join(
            f"{k}: {v}" for k, v in result.reconstructed.items()), ""]
    if result.latex_input:
        lines += ["Read from LaTeX:", ""] + [
            f"- {k}: `{a}` parsed as `{b}`" for k, (a, b) in result.latex_input.items()] + [""]
    return "\n".join(lines) + "\n"


def report_markdown(results: Sequence[DerivationResult], title: str,
                    extra: Sequence[str] = ()) -> str:
    r"""The whole report: summary, derivations in the document's order, extras."""
    results = S.ordered(results)
    parts = [f"# {title}", "", "Verdicts: *agrees* (over every random state and parameter set), "
             "*agrees only for special values* (named), *factorisation of C only* (a C element "
             "whose difference is only how C is factored: the h = C q̇ terms it makes agree, or "
             "differ only where another element is wrong, said there), *differs* (with its "
             "diagnosis).",
             ""]
    parts += summary_markdown(results) + [""]
    parts += [derivation_markdown(r) for r in results]
    parts += list(extra)
    return "\n".join(parts)
