r"""Printed forms of expressions — SymPy's text (``sstr``) and LaTeX — remembered across runs.

A comparison prints every element it judges four times (the document's text and LaTeX, the
same in the model's parameters) and the truth beside it twice. Printing is a function of
the expression and the names its symbols print with only, and SymPy's printers take a good
part of a comparison's time, so the printed forms are kept in the disk cache
(:class:`~wheeled_dyn.disk_cache.DiskMemo` ``compare/printed-<code>.pickle``, named by
SymPy's version and this file): checking a derivation again prints only what changed.
Nothing a verdict depends on is kept there.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import sympy as sp

from ...disk_cache import DiskMemo

#: The remembered ``(text, LaTeX)`` pairs, keyed by the expression and its symbols' names.
PRINTED = DiskMemo("compare", "printed", lambda: [Path(__file__)])


def printed(expr: sp.Basic, names: Mapping[sp.Symbol, str] | None = None) -> tuple[str, str]:
    r"""``(sympy.sstr(expr), sympy.latex(expr, symbol_names=names))``, remembered
    (:data:`PRINTED`); ``names`` maps symbols to their LaTeX (only those of ``expr`` count)."""
    free = expr.free_symbols                    # a walk of the tree: once, not per name
    names = {s: t for s, t in (names or {}).items() if s in free}
    key = (expr, tuple(sorted((str(s), t) for s, t in names.items())))
    return PRINTED.get(key, lambda: (sp.sstr(expr), sp.latex(expr, symbol_names=names)))


__all__ = ["PRINTED", "printed"]
