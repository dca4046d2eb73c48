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
        D, T = np.asarray(D, float), np.asarray(T, float)
        own = scale if key == "C" else element_scale(D, T, scale)
        out.append(ElementDraft(element=label, key=key, index=index, verdict=Verdict.DIFFERS,
                                diagnoses=[], D=D, T=T, scale=own, expr=expr,
                                equation=equation))
    return out


#: An element of A, Q, B, K or h is compared relative to its own size, or to this fraction
#: of its row's scale where it is smaller: the truth's rounding in the shipped comparisons
#: reaches 4e-13 of the row's scale in A and 5e-11 in h (C, whose factorisation is not
#: unique, 5e-10: it keeps the row's scale).
ELEMENT_FLOOR = 1e-2


def element_scale(D: np.ndarray, T: np.ndarray, row: float) -> float:
    r"""The scale an element is judged at: the larger of its own largest finite magnitude (on
    either side) and :data:`ELEMENT_FLOOR` of its ``row``'s scale, at most the row's. An
    element is not made to agree by the size of its neighbours: the inertias of an arm with
    lengths in millimetres are 1e-4 of its gravity terms (accelerations of 1 in SI units are
    small there), and a typo in one agreed."""
    values = np.abs(np.concatenate([D.ravel(), T.ravel()]))
    values = values[np.isfinite(values)]
    own = float(values.max()) if values.size else 0.0
    return min(row, max(own, ELEMENT_FLOOR * row))


__all__ = ["drafts_of_row", "row_values"]
