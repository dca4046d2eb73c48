r"""Printed forms of expressions — SymPy's text (``sstr``) and LaTeX — remembered across runs.

A comparison prints every element it judges four times (the document's text and LaTeX, the
same in the model's parameters) and the truth beside it twice. Printing is a function of
the expression and the names its symbols print with only, and SymPy's printers take a good
part of a comparison's time, so the printed forms are kept in the disk cache
(:class:`~wheeled_dyn.disk_cache.DiskMemo` ``compare/printed-<code>.pickle``, named by
SymPy's version and this file): checking a derivation again prints only what changed.
Nothing a verdict depends on is kept there.

An expression of more than :data:`PRINT_NODES` nodes (a solved form's element with its
determinant written out in every term: megabytes of text; 20 s to print the longest as
text and LaTeX) is not printed: its text says how long it is, and the file's own text is
what the document wrote.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import sympy as sp

from ...disk_cache import DiskMemo
from ...expression_size import free_symbols_of, node_count

#: The remembered ``(text, LaTeX)`` pairs, keyed by the expression and its symbols' names.
PRINTED = DiskMemo("compare", "printed", lambda: [Path(__file__)])
#: Most nodes of an expression printed in full.
PRINT_NODES = 20_000


def printed(expr: sp.Basic, names: Mapping[sp.Symbol, str] | None = None) -> tuple[str, str]:
    r"""``(sympy.sstr(expr), sympy.latex(expr, symbol_names=names))``, remembered
    (:data:`PRINTED`); ``names`` maps symbols to their LaTeX (only those of ``expr`` count).
    Above :data:`PRINT_NODES` nodes, a short text saying so instead."""
    if node_count(expr, PRINT_NODES) > PRINT_NODES:
        said = f"(not printed: more than {PRINT_NODES} nodes)"
        return said, rf"\text{{{said}}}"
    free = free_symbols_of(expr)                # a walk of the tree: once, not per name
    names = {s: t for s, t in (names or {}).items() if s in free}
    key = (expr, tuple(sorted((str(s), t) for s, t in names.items())))
    return PRINTED.get(key, lambda: (sp.sstr(expr), sp.latex(expr, symbol_names=names)))


__all__ = ["PRINTED", "PRINT_NODES", "printed"]
