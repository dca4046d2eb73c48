r"""A comparison result in a notebook: its report section, with the report's style kept to it.

:meth:`DerivationResult._repr_html_ <wheeled_dyn.compare.records.DerivationResult._repr_html_>`
returns :func:`result_html`: the section :func:`~.html.derivation_html` writes for the report
(causes first, then the matrices, document | truth side by side, then what differs), preceded
by the report's CSS with every selector put under one class, so that the notebook's own page
keeps its look (the report's ``body`` rule becomes the box's).
"""

from __future__ import annotations

import re

from ..compare.records import DerivationResult
from .html import CSS, derivation_html

#: The class of the box a result is shown in.
SCOPE = "wheeled-dyn-result"


def _scoped_selector(selector: str, scope: str) -> str:
    selector = selector.strip()
    if selector in ("body", "html"):
        return f".{scope}"
    return f".{scope} {selector}"


def scoped_css(css: str, scope: str = SCOPE) -> str:
    r"""``css`` with each rule's selectors put under ``.scope`` (``a{..}`` → ``.scope a{..}``,
    ``body{..}`` → ``.scope{..}``), inside ``@media`` blocks too."""
    out: list[str] = []
    i = 0
    text = css.strip()
    while i < len(text):
        brace = text.find("{", i)
        if brace < 0:
            break
        head = text[i:brace].strip()
        if head.startswith("@"):                       # a block of rules: scope its inside
            depth, j = 1, brace + 1
            while depth:
                depth += {"{": 1, "}": -1}.get(text[j], 0)
                j += 1
            out.append(f"{head}{{{scoped_css(text[brace + 1:j - 1], scope)}}}")
        else:
            j = text.index("}", brace) + 1
            selectors = ",".join(_scoped_selector(s, scope) for s in head.split(","))
            out.append(f"{selectors}{text[brace:j]}")
        i = j
    return re.sub(r"\s*\n\s*", " ", "".join(out))


def result_html(result: DerivationResult) -> str:
    r"""The report's section of ``result`` in a box of class :data:`SCOPE`, with its style."""
    return (f'<div class="{SCOPE}"><style>{scoped_css(CSS)}</style>'
            f"{derivation_html(result)}</div>")


__all__ = ["SCOPE", "result_html", "scoped_css"]
