r"""The elements of one document row against the truth in the row's frame: A, C, Q, B per
element and h per velocity product (the coefficient :math:`H_{i,jk}` weighted 1 for
:math:`\nu_j^2` and 2 for :math:`\nu_j\nu_k`), each judged by :func:`.element.judge`.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from typing import Any

import numpy as np
import sympy as sp

from ..grid.arrays import Arrays
from ..records import Verdict
from ..sides.elements import element_expr, element_label
from .draft import ElementDraft


def row_values(doc_row: Arrays, true_row: Arrays, i: int, exprs: Mapping[str, Any],
               velocities: Sequence[sp.Symbol]
               ) -> Iterator[tuple[str, tuple[int, ...], np.ndarray, np.ndarray, sp.Expr | None]]:
    r"""``(key, index, D, T, expression)`` of every element of row ``i`` (``doc_row`` and
    ``true_row`` shaped as :func:`~..sides.framed.row_of`'s)."""
    n = len(velocities)
    for key in ("A", "C", "K"):
        D, T = getattr(doc_row, key), getattr(true_row, key)
        if D is not None and T is not None:
            for j in range(n):
                yield key, (i, j), D[:, 0, j], T[:, 0, j], element_expr(exprs, key, (i, j),
                                                                          velocities)
    if doc_row.Q is not None and true_row.Q is not None:
        yield "Q", (i,), doc_row.Q[:, 0], true_row.Q[:, 0], element_expr(exprs, "Q", (i,),
                                                                         velocities)
    if doc_row.B is not None and true_row.B is not None:
        for j in range(doc_row.B.shape[2]):
            yield "B", (i, j), doc_row.B[:, 0, j], true_row.B[:, 0, j], element_expr(
                exprs, "B", (i, j), velocities)
    if doc_row.H is not None and true_row.H is not None:
        for j in range(n):
            for k in range(j, n):
                w = 1.0 if j == k else 2.0
                yield ("h", (i, j, k), w * doc_row.H[:, 0, j, k], w * true_row.H[:, 0, j, k],
                       element_expr(exprs, "h", (i, j, k), velocities))


def drafts_of_row(doc_row: Arrays, true_row: Arrays, i: int, exprs: Mapping[str, Any],
                  velocities: Sequence[sp.Symbol], scale: float, lost: set[str],
                  equation: str) -> list[ElementDraft]:
    r"""Unjudged drafts of row ``i``'s elements; elements the extracted text lost (labels in
    ``lost``, or NaN in their expression) are left out."""
    out = []
    for key, index, D, T, expr in row_values(doc_row, true_row, i, exprs, velocities):
        label = element_label(key, index, velocities)
        whole = exprs.get(key)
        if label in lost or (expr is not None and sp.sympify(expr).has(sp.nan)) or (
                key == "h" and whole is not None and sp.sympify(whole[i]).has(sp.nan)):
            continue
        out.append(ElementDraft(element=label, key=key, index=index, verdict=Verdict.DIFFERS,
                                diagnoses=[], D=np.asarray(D, float), T=np.asarray(T, float),
                                scale=scale, expr=expr, equation=equation))
    return out


__all__ = ["drafts_of_row", "row_values"]
