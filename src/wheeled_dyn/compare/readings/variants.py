r"""The combinations a row that is not right may be explained in besides
:math:`A_{doc,i}A^{-1}` (:mod:`.frames`): the true rows' weights fitted with one inertia
column of the row left out, replaced by the velocity and gravity terms or by an input's
column — an error in that column then stands alone —, or with every inertia column left out
(an error in two of them), and which of them are as good as a constant factor (their
weights the same numbers at every sample).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from ..grid.arrays import Arrays
from .frames import (CONSTANT_SPREAD, TERMS, FrameKind, FrameRule, combination_weights,
                     constant_weights)


def combination_variants(grids: Sequence[tuple[Arrays, Arrays, np.ndarray | None]], i: int,
                         simple: tuple[np.ndarray, Callable[[np.ndarray], bool]] | None = None
                         ) -> list[FrameRule]:
    r"""Row ``i``'s combinations with one inertia column replaced (tried for an equation that
    is not right where the simpler rules leave many elements differing). Their weights are
    fitted to the row with one inertia column left out, so weights that are simple
    expressions there say little of the form; but where they are the same constants at every
    sample of every grid (eq1 − eq2 with an error in its first inertia column), a combination
    of the true rows reproduces the rest of the row with numbers, not functions, fitted — as
    good as a constant factor (``identified``); so too where each weight is a simple
    expression of the document's names on the first grid's samples ``simple[0]``
    (``simple[1]`` of the weights there says whether it is: the cart's equation less
    3 cos θ/(4l) × the pole's, with the pole's inertia wrong)."""
    doc0, truth0, B0 = grids[0]
    n = truth0.need("A").shape[1]
    m = 0 if doc0.B is None or B0 is None else doc0.B.shape[2]
    rules = [FrameRule(FrameKind.COMBINATION, variant=(j, c))
             for j in range(n) for c in range(-1, m)]
    if 1 + m >= n:                       # every inertia column left out (frames.TERMS)
        rules.append(FrameRule(FrameKind.COMBINATION, variant=TERMS))
    at = None if simple is None else _at(grids[0], simple[0])
    return [replace(rule, identified=True) if _constant(i, rule, grids) or (
        simple is not None and at is not None and _simple(i, rule, at, simple[1])) else rule
        for rule in rules]


def _at(grid: tuple[Arrays, Arrays, np.ndarray | None], rows: np.ndarray
        ) -> tuple[Arrays, Arrays, np.ndarray | None]:
    r"""The document's and the truth's arrays of ``grid`` at the samples ``rows``."""
    doc, truth, B_true = grid

    def some(a: np.ndarray | None) -> np.ndarray | None:
        return None if a is None else a[rows]
    return (Arrays(A=some(doc.A), Q=some(doc.Q), B=some(doc.B), h=some(doc.h)),
            Arrays(A=some(truth.A), Q=some(truth.Q), h=some(truth.h)), some(B_true))


def _simple(i: int, rule: FrameRule, grid: tuple[Arrays, Arrays, np.ndarray | None],
            simple: Callable[[np.ndarray], bool]) -> bool:
    r"""Whether every weight of ``rule`` for row ``i`` on ``grid`` (a few samples) is zero or
    a ``simple`` expression, two of them at least not zero (one alone is a factor's rule)."""
    doc, truth, B_true = grid
    w = combination_weights(i, rule, doc, truth, doc.B, B_true)
    if not np.isfinite(w).all():
        return False
    size = float(np.abs(w).max(initial=0.0))
    present = [k for k in range(w.shape[1]) if np.abs(w[:, k]).max() > CONSTANT_SPREAD * size]
    return len(present) > 1 and all(simple(w[:, k]) for k in present)


def _constant(i: int, rule: FrameRule, grids: Sequence[tuple[Arrays, Arrays,
                                                               np.ndarray | None]]) -> bool:
    r"""Whether the weights of ``rule`` for row ``i`` are the same constants at every sample of
    every grid, two of them or more not zero (one alone is a constant factor's rule); tried
    on :data:`CONSTANT_SCREEN` samples of the first grid before all (most are not)."""
    S = len(grids[0][1].need("A"))
    screened = _at(grids[0], np.linspace(0, S - 1, min(S, CONSTANT_SCREEN)).astype(int))
    if S > CONSTANT_SCREEN and not _same_numbers(i, rule, [screened]):
        return False
    return _same_numbers(i, rule, grids)


#: Samples a combination's weights are first tried on for being constants (:func:`_constant`).
CONSTANT_SCREEN = 32


def _same_numbers(i: int, rule: FrameRule, grids: Sequence[tuple[Arrays, Arrays,
                                                                 np.ndarray | None]]) -> bool:
    r"""The test of :func:`_constant` on ``grids``."""
    first = None
    for doc, truth, B_true in grids:
        w = combination_weights(i, rule, doc, truth, doc.B, B_true)
        if not constant_weights(w):
            return False
        size = float(np.abs(w).max())
        first = w[0] if first is None else first
        if np.abs(w[0] - first).max() > CONSTANT_SPREAD * size:
            return False
    return first is not None and int((np.abs(first) > CONSTANT_SPREAD * size).sum()) > 1


__all__ = ["CONSTANT_SCREEN", "combination_variants"]
