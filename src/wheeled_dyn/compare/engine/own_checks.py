r"""What a document is checked for on its own, read in the frames found for its rows: the
power identity (energy) and its inertia matrix's symmetry and definiteness — where every row
is the true one times a factor, divided by it (a solved or combined form has none of them).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..judge.document_checks import asymmetry, energy_check
from ..readings.frames import FrameKind
from ..records import EnergyCheck


def own_checks(d: Derivation, funcs, sides, texts, rules, frames,
               printed: Mapping[int, sp.Expr | None] | None = None
               ) -> tuple[EnergyCheck | None, tuple[str, ...]]:
    r"""(the power identity's check or None, the asymmetric pairs and definiteness as text) of
    the document ``d``; ``sides`` both sides on the main grid, ``texts``, ``rules``,
    ``frames`` each row's frame; ``printed``: per row whose declared scale the equation as
    printed contradicts, the factor it is the true one times (None: a combination), which
    the power identity reads it with (divided by a scale it does not have, a row conserves
    no energy, and that is the declaration's error, said by its own cause)."""
    own = _unscaled(sides.doc, frames, rules)
    asymmetric = () if own is None or own.A is None else asymmetry(
        own, _entry_sizes(own.A), d.n, sides.truth.A, sides.doc.A)
    diagonal = _diagonal_factors(d, texts, rules, printed or {})
    grid = sides.grid
    energy = None if diagonal is None else energy_check(
        funcs, sides.doc, diagonal, grid.flat_q, grid.flat_nu, sides.values, d)
    return energy, asymmetric


def _diagonal_factors(d: Derivation, texts, rules, printed: Mapping[int, sp.Expr | None]
                      ) -> list[sp.Expr] | None:
    r"""Each row's factor of the true equation when every row is the true one times a factor
    (symbolic, identified; a row contradicting its declared scale, the factor it is
    ``printed`` with), else None: the document's own checks (energy) read it so."""
    out: list[sp.Expr] = []
    for i, (t, r) in enumerate(zip(texts, rules)):
        if i in printed:
            factor = printed[i]
            if factor is None:
                return None
            out.append(factor)
        elif r.kind == FrameKind.IDENTITY:
            out.append(sp.Integer(1))
        elif r.kind == FrameKind.DECLARED and d.row_scale is not None:
            out.append(d.row_scale[i])
        elif r.kind in (FrameKind.CONSTANT, FrameKind.FUNCTION) and r.partner == i \
                and t.factor is not None:
            out.append(t.factor)
        else:
            return None
    return out


def _unscaled(doc, frames, rules):
    r"""The document's arrays with each row divided by its factor per sample, when every row
    is the true one times a factor; None otherwise (its A's symmetry and definiteness are
    then not judged: a solved or combined form has neither)."""
    from ..grid.arrays import Arrays
    factors = []
    for i, (f, r) in enumerate(zip(frames, rules)):
        if r.kind not in (FrameKind.IDENTITY, FrameKind.DECLARED, FrameKind.CONSTANT,
                          FrameKind.FUNCTION) or r.partner not in (i, -1):
            return None
        factors.append(f.weights[:, i])
    c = np.stack(factors, axis=1)
    if doc.A is None:
        return doc
    with np.errstate(all="ignore"):
        return Arrays(A=doc.A / c[:, :, None])


def _entry_sizes(A: np.ndarray) -> np.ndarray:
    r"""Each row's largest finite magnitude (1 for a row with none)."""
    finite = np.where(np.isfinite(A), np.abs(A), 0.0)
    size = finite.max(axis=(0, 2))
    return np.where(size > 0, size, 1.0)


__all__ = ["own_checks"]
