r"""The comparison as Markdown with math GitHub renders (``$...$``)."""

from __future__ import annotations

from collections.abc import Sequence

from ..compare.result import DerivationResult, ElementRecord

VERDICT_TEXT = {"agrees": "agrees", "agrees_if": "agrees only for special values",
                "factorization": "C differs, C q̇ agrees", "differs": "differs",
                "undecided": "cannot decide (values not finite)"}


def _math(latex: str) -> str:
    bar = "\\vert "
    return "$" + latex.replace("|", bar) + "$" if latex else ""


def summary_lines(result: DerivationResult) -> list[str]:
    r"""The summary of one derivation, as short lines (also printed by the CLI)."""
    c = result.counts()
    lines = [f"{c['agrees']} agree, {c['agrees_if']} agree only for special parameter values, "
             f"{c['factorization']} differ in factorisation only, {c['differs']} differ"]
    typos = result.typos()
    if typos:
        lines.append("typos: " + "; ".join(f"{r.element} ({r.diagnoses[0]})" for r in typos))
    missing = result.missing()
    if missing:
        lines.append("missing or extra physics: " + ", ".join(r.element for r in missing))
    factors = [f"row {i + 1} × {c}" for i, c in enumerate(result.row_factors) if c]
    if factors:
        lines.append("rows scaled by a constant the file does not declare: " + ", ".join(factors))
    if result.energy is not None:
        lines.append("conserves energy (power identity holds)" if result.energy.conserves else
                     f"does not conserve energy: ν·h − ½ ν·Ȧν = {result.energy.residual}")
    lines += list(result.asymmetric) + list(result.constraints) + list(result.notes)
    return lines


def _row(r: ElementRecord) -> str:
    diag = "; ".join(r.diagnoses)
    verdict = VERDICT_TEXT[r.verdict] + (f": {diag}" if diag else "")
    truth = _math(r.truth_latex) if r.truth_latex else f"(numeric; max error {r.max_error:.3g})"
    return (f"| {r.element} | {_math(r.document_latex)} | {_math(r.model_latex)} | {truth} | "
            f"{verdict.replace('|', '/')} |")


def derivation_markdown(result: DerivationResult) -> str:
    src = result.source
    lines = [f"## {result.title}", "",
             f"`{result.path.name}` — {src.get('document', '')} {src.get('section', '')} "
             f"eqs {src.get('equations', '')}; model `{result.model}`, coordinates "
             f"`{result.coordinates}` ({', '.join(result.velocities)}); "
             f"{result.samples} states × {result.parameter_sets} random parameter sets.", ""]
    lines += [f"- {line}" for line in summary_lines(result)]
    if result.reconstructed:
        lines += ["", "Reconstructed from garbled text: " + "; ".join(
            f"{k}: {v}" for k, v in result.reconstructed.items())]
    lines += ["", "| element | document | document after the parameter map | truth | verdict |",
              "|---|---|---|---|---|"]
    lines += [_row(r) for r in result.records]
    return "\n".join(lines) + "\n"


def report_markdown(results: Sequence[DerivationResult], title: str,
                    extra: Sequence[str] = ()) -> str:
    parts = [f"# {title}", "", "Verdicts: *agrees* (over every random state and parameter set), "
             "*agrees only for special values* (named), *C differs, C q̇ agrees* (the equations "
             "are right; only the factorisation of C differs), *differs* (with its diagnosis).", ""]
    parts += [derivation_markdown(r) for r in results]
    parts += list(extra)
    return "\n".join(parts)
