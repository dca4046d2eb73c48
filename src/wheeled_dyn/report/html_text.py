r"""The pieces of text of the HTML report: escaped text, a number at the reference state
(rounding noise as ≈0), and formulas as MathML made by ``latex2mathml`` (remembered across
runs: :data:`MATHML`)."""

from __future__ import annotations

import functools
import html
import importlib.util
from pathlib import Path

from ..disk_cache import DiskMemo


#: Numbers smaller than this are rounding noise of the truth (shown as ≈0).
ROUNDING = 1e-12


def num_text(x: float, digits: int = 4) -> str:
    r"""A number at the reference state; rounding noise (below :data:`ROUNDING`) as ≈0."""
    return "≈0" if abs(x) < ROUNDING else f"{x:.{digits}g}"


#: The MathML of LaTeX texts, remembered across runs (the disk cache's
#: ``report/mathml-<code>.pickle``, named by SymPy's version, this file and latex2mathml's
#: converter: MathML made by other code is not read).
MATHML = DiskMemo("report", "mathml", lambda: [Path(__file__), _converter_file()])


def _converter_file() -> Path:
    r"""latex2mathml's converter, found without importing it: a report whose MathML is all
    remembered does not load it (with the XML and URL modules it imports)."""
    spec = importlib.util.find_spec("latex2mathml")     # the package found, not run
    if spec is None or spec.origin is None:
        raise OSError("latex2mathml is not installed")
    return Path(spec.origin).with_name("converter.py")


#: Longest LaTeX typeset as MathML (characters): a form solved for the accelerations and never
#: simplified can print pages per element (a two-link arm's 13 took 8.6 s to convert, and
#: nobody reads them typeset); such LaTeX is shown as its first characters, said to go on.
MATHML_LIMIT = 20_000


@functools.lru_cache(maxsize=8192)
def mathml(latex: str) -> str:
    r"""The MathML of ``latex`` (:data:`MATHML`); code for LaTeX latex2mathml cannot read, or
    longer than :data:`MATHML_LIMIT`."""
    if len(latex) > MATHML_LIMIT:
        return (f"<code>{html.escape(latex[:MATHML_LIMIT // 10])} … (an expression of "
                f"{len(latex)} characters of LaTeX: not typeset)</code>")
    return MATHML.get(latex, lambda: _converted(latex)) if latex else ""


def _converted(latex: str) -> str:
    from latex2mathml.converter import convert
    try:
        return convert(latex)
    except Exception:          # an expression latex2mathml cannot read is shown as text
        return f"<code>{html.escape(latex)}</code>"


def math_box(latex: str, empty: str = "—") -> str:
    return f'<div class="m">{mathml(latex)}</div>' if latex else f'<div class="m">{empty}</div>'


def esc(text: object) -> str:
    return html.escape(str(text))
