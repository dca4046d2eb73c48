r"""Matrices: the cells of a ``bmatrix``/``pmatrix`` value, transposed by ``^T``.

A matrix is a whole value (``A = { latex = '\begin{bmatrix} ... \end{bmatrix}' }``);
:func:`split_latex_matrix` gives its cells as LaTeX text, each read by the reader
(:mod:`.reader`) as one element. A printed name before it (``\mathbf{A} =``), a transpose
after it (:data:`TRANSPOSE`) and its equation number are read here.
"""

from __future__ import annotations

import re
from typing import Any

from pylatexenc.latexwalker import (LatexCommentNode, LatexEnvironmentNode, LatexMacroNode,
                                    LatexSpecialsNode)

from .nodes import TAG, LatexError, content, drop_equation_number, parse_nodes

MATRICES: frozenset[str] = frozenset({"bmatrix", "pmatrix", "matrix", "Bmatrix"})
#: A transposed matrix: ``\end{bmatrix}^T`` (``^{T}``, ``^\top``, ``^{\mathsf{T}}``, ...).
_T_MARK = r"(?:T|\\top|\\intercal|\\(?:mathsf|mathrm|mathit|mathbf)\s*\{\s*T\s*\})"
TRANSPOSE = re.compile(rf"\^\s*(?:{_T_MARK}|\{{\s*{_T_MARK}\s*\}})\s*")


#: A ``matrix`` in delimiters, as ``sympy.latex`` prints one: ``\left[\begin{matrix} …
#: \end{matrix}\right]`` (the delimiters dropped: a bmatrix or pmatrix).
_OPEN = re.compile(r"\\left\s*(?:\[|\(|\\\{)\s*(?=\\begin\s*\{\s*matrix\s*\})")
_CLOSE = re.compile(r"(\\end\s*\{\s*matrix\s*\})\s*\\right\s*(?:\]|\)|\\\})")


def split_latex_matrix(source: str) -> list[list[str]]:
    r"""The cells (LaTeX text) of the one ``bmatrix``/``pmatrix`` in ``source``, row by row.
    Text before the matrix ending in ``=`` (its printed name, ``\mathbf{A} =``) is skipped;
    a matrix followed by a transpose (:data:`TRANSPOSE`: ``^T``, ``^{T}``, ``^\top``,
    ``^{\mathsf{T}}``) gives its columns as rows (a printed row vector ``[a & b]^T`` is the
    column ``[[a], [b]]``); ``\tag{...}`` and a final ``\quad (35)`` are dropped; a
    ``matrix`` in ``\left[ … \right]`` (SymPy's printing) is read as a bmatrix."""
    source = _CLOSE.sub(r"\1", _OPEN.sub("", source))
    nodes = drop_equation_number([n for n in content(parse_nodes(source)) if not (
        isinstance(n, LatexMacroNode) and n.macroname == TAG)])
    envs = [k for k, n in enumerate(nodes) if isinstance(n, LatexEnvironmentNode)]
    prefix = source[nodes[0].pos:nodes[envs[0]].pos].strip() if envs else ""
    tail = "".join(source[n.pos:n.pos + n.len] for n in nodes[envs[0] + 1:]) if envs else ""
    transposed = bool(tail) and TRANSPOSE.fullmatch(tail) is not None
    if (len(envs) != 1 or (tail and not transposed)
            or nodes[envs[0]].environmentname not in MATRICES
            or (prefix and not prefix.endswith("="))):
        raise LatexError(source, "expected one \\begin{bmatrix} ... \\end{bmatrix} "
                                 "(or pmatrix), optionally after 'A =', optionally "
                                 "transposed (^T)")
    rows: list[list[str]] = [[]]
    cell: list[Any] = []

    def close_cell() -> None:
        text = source[cell[0].pos:cell[-1].pos + cell[-1].len].strip() if cell else ""
        rows[-1].append(text)
        cell.clear()

    for node in nodes[envs[0]].nodelist:
        if isinstance(node, LatexSpecialsNode) and node.specials_chars == "&":
            close_cell()
        elif isinstance(node, LatexMacroNode) and node.macroname == "\\":
            close_cell()
            rows.append([])
        elif node is not None and not isinstance(node, LatexCommentNode):
            cell.append(node)
    close_cell()
    if rows[-1] == [""] and len(rows) > 1:
        rows.pop()                              # a trailing \\ ends the last row
    if any(c == "" for row in rows for c in row):
        raise LatexError(source, "empty matrix cell")
    if transposed:
        if len({len(row) for row in rows}) != 1:
            raise LatexError(source, "a transposed matrix needs rows of one length, got "
                                     + ", ".join(str(len(row)) for row in rows))
        rows = [list(column) for column in zip(*rows)]
    return rows
