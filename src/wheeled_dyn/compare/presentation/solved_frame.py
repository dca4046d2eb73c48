r"""The frame a row solved for an acceleration is compared in: row :math:`k` of the true
:math:`A^{-1}` (its adjugate over its determinant) times the true equations, written in
closed form where it is short enough to read. Nothing here decides a verdict."""

from __future__ import annotations

import sympy as sp

from ...expression_size import ops_over

#: Most operations of the true A whose inverse is written as a solved row's frame.
SOLVED_LIMIT = 200
#: Most operations of a truth in a solved row's frame, before it is cancelled.
SOLVED_TRUTH_LIMIT = 2000


def solved_truth(expr: sp.Expr) -> sp.Expr | None:
    r"""``cancel(expr)``: the truth an element of a solved row is compared with, or None where
    it has more than :data:`SOLVED_TRUTH_LIMIT` operations (a 3×3 inverse times a long row:
    12–17 s for a 3×3 form's elements under a profiler, and no one reads it)."""
    return None if ops_over(expr, SOLVED_TRUTH_LIMIT) else sp.cancel(expr)


def solved_weights(truth: dict[str, sp.Expr], n: int) -> list[tuple[sp.Expr, ...]] | None:
    r"""The rows of :math:`A^{-1}` of the true A in ``truth`` (its adjugate over its
    determinant), or None where an element has no closed form, n is above 3, or A has more
    than :data:`SOLVED_LIMIT` operations."""
    labels = [[f"A[{i + 1},{j + 1}]" for j in range(n)] for i in range(n)]
    if n > 3 or any(x not in truth for row in labels for x in row):
        return None
    A = sp.Matrix([[truth[x] for x in row] for row in labels])
    if ops_over(A, SOLVED_LIMIT):
        return None
    det = sp.cancel(A.det())
    if det == 0:
        return None
    adj = A.adjugate()
    return [tuple(adj[i, j] / det for j in range(n)) for i in range(n)]


__all__ = ["SOLVED_LIMIT", "SOLVED_TRUTH_LIMIT", "solved_truth", "solved_weights"]
