r"""The equations that differ, as they should read: the corrected equations of a derivation
(:attr:`~wheeled_dyn.compare.records.EquationRecord.corrected`) in the document's symbols and
frame, for the HTML report (rendered, with the LaTeX to copy) and the Markdown one (the LaTeX in
a ``$$`` block and the text form)."""

from __future__ import annotations

from html import escape

from ..compare.records import DerivationResult, EquationRecord
from .html_text import mathml


def _fixed(result: DerivationResult) -> list[EquationRecord]:
    return [e for e in result.equations if e.corrected_latex]


def corrected_html(result: DerivationResult) -> str:
    r"""A block with each corrected equation rendered as MathML, empty without one."""
    fixed = _fixed(result)
    if not fixed:
        return ""
    items = "".join(
        f'<div class="fix"><b>{escape(e.label)}</b> ({escape(e.frame)}) should read'
        f'<div class="m">{mathml(e.corrected_latex)}</div>'
        f"<details class=\"paste\"><summary>LaTeX and text to paste back</summary>"
        f"<pre>{escape(e.corrected_latex)}</pre><pre>{escape(e.corrected)}</pre></details></div>"
        for e in fixed)
    return ('<div class="corrected"><h3>Corrected, in the document\'s symbols</h3>'
            f"{items}</div>")


def corrected_markdown(result: DerivationResult) -> list[str]:
    r"""Markdown lines with each corrected equation, none without one."""
    fixed = _fixed(result)
    if not fixed:
        return []
    lines = ["**Corrected, in the document's symbols:**", ""]
    for e in fixed:
        lines += [f"- {e.label} ({e.frame}) should read", "", "  $$", f"  {e.corrected_latex}",
                  "  $$", "", f"  `{e.corrected}`", ""]
    return lines


__all__ = ["corrected_html", "corrected_markdown"]
