r"""A frame in words and, where it is simple, in the document's symbols.

The frame of a row (:mod:`.frames`) is known as numbers per sample; to say it the way an author
would — "equation 2 is the true one divided by m*l", "equation 1 = eq1 - H*cos(theta)*eq2/2",
"solved for the accelerations" — its weights are fitted on the identification grid (many
parameter sets, :mod:`..judge.fitting`) as a constant, a monomial or a short sum in the
document's symbols, positions and their sines and cosines. A frame that fits none of them is
described in words only. The description never decides anything.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from ..judge.diagnose import nice_number
from ..judge.fitting import fit_factor, fit_sum
from ..judge.unsolved import solved_for
from .frames import Frame, FrameKind

#: Relative size below which a weight counts as zero.
ZERO_WEIGHT = 1e-9


@dataclass(frozen=True)
class FrameText:
    r"""A frame described: ``text`` (empty for the true equation itself), ``weights`` the
    symbolic row :math:`f_i` when fitted (else None), ``factor`` the symbolic factor of a
    ``CONSTANT``/``FUNCTION`` frame (else None), ``solved`` ``(k, c)`` for a row solved for
    acceleration k, :math:`A_{doc,i} = c\,e_k` (:func:`~..judge.unsolved.solved_for`)."""

    text: str
    weights: tuple[sp.Expr, ...] | None = None
    factor: sp.Expr | None = None
    solved: tuple[int, float] | None = None


def weight_expression(values: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]
                      ) -> sp.Expr | None:
    r"""One weight as an expression: 0, a constant, a monomial or a short sum (or its
    inverse)."""
    size = float(np.abs(values).max(initial=0.0))
    if not np.isfinite(size):
        return None
    if size == 0.0:
        return sp.Integer(0)
    if np.ptp(values) <= 1e-9 * size:
        return sp.nsimplify(nice_number(float(np.median(values))))
    found = fit_factor(values, bases) or fit_sum(values, bases)
    if found is None and np.abs(values).min() > 0:
        inverse = fit_sum(1.0 / values, bases)
        found = None if inverse is None else 1 / inverse
    if found is not None and found.has(sp.sin, sp.cos):   # 10⁶(sin² + cos²) is 10⁶
        found = sp.trigsimp(found)
    return found


def _quotient(c: sp.Expr) -> str:
    r"""``"divided by m*l"`` or ``"times sin(theta)"``."""
    inverse = sp.factor_terms(1 / c)
    if sp.fraction(inverse)[1].is_number and not inverse.is_number:
        return f"divided by {sp.sstr(inverse)}"
    return f"times {sp.sstr(c)}"


def describe(i: int, frame: Frame, id_weights: np.ndarray | None,
             bases: Sequence[tuple[sp.Expr, np.ndarray]], positions: Sequence[sp.Symbol],
             doc_A: np.ndarray | None = None, declared: sp.Expr | None = None) -> FrameText:
    r"""Row ``i``'s frame in words (module text). ``id_weights``: the frame's weights on the
    identification grid (S × n), fitted there with ``bases``; ``doc_A`` the document's row of
    A on the main grid (to recognise a row solved for the accelerations); ``declared`` the
    file's factor for the row."""
    kind, k = frame.rule.kind, frame.rule.partner
    of = "" if k in (i, -1) else f" of {positions[k]}"
    at = i if k < 0 else k

    def single(c: sp.Expr) -> tuple[sp.Expr, ...]:
        return tuple(c if j == at else sp.Integer(0) for j in range(len(positions)))
    if kind == FrameKind.IDENTITY:
        return FrameText("", (*(sp.Integer(int(j == i)) for j in range(len(positions))),),
                         sp.Integer(1))
    if kind == FrameKind.DECLARED:
        return FrameText(f"the true equation times {sp.sstr(declared)} (declared)",
                         single(declared), factor=declared)
    if kind == FrameKind.CONSTANT and frame.constant is not None:
        c = sp.nsimplify(nice_number(frame.constant))
        text = (f"the true equation{of} with the opposite sign" if c == -1 else
                f"the true equation{of}" if c == 1 else f"{sp.sstr(c)} × the true equation{of}")
        return FrameText(text, single(c), factor=c)
    if id_weights is None:
        return FrameText("a combination of the true equations (its weights found at each "
                         "state, not identified)")
    if kind == FrameKind.FUNCTION:
        c = weight_expression(id_weights[:, k], bases)
        if c is None:
            return FrameText(f"the true equation{of} times a function of the state and "
                             "parameters (not identified)")
        return FrameText(f"the true equation{of} {_quotient(c)}", single(c), factor=c)
    own = np.abs(id_weights[:, i])
    others = np.delete(np.abs(id_weights), i, axis=1)
    if others.size == 0 or others.max() <= ZERO_WEIGHT * max(float(own.max()), 1e-300):
        c = weight_expression(id_weights[:, i], bases)    # a combination of its own row only
        if c is not None:
            return FrameText(f"the true equation {_quotient(c)}", single(c), factor=c)
    entries = [weight_expression(id_weights[:, j], bases) for j in range(id_weights.shape[1])]
    solved = None if doc_A is None else solved_for(doc_A)
    if any(e is None for e in entries):
        text = ("solved for the accelerations (row of A⁻¹ × the true equations)" if solved
                else "a combination of the true equations (its weights found at each state, "
                "not identified)")
        return FrameText(text, solved=solved)
    eq = [sp.Symbol(f"eq{j + 1}") for j in range(len(entries))]
    combo = sp.Add(*(e * s for e, s in zip(entries, eq)))
    text = f"= {sp.sstr(combo)} (eq k: the true equation k)"
    if solved:
        text = "solved for the accelerations, " + text
    return FrameText(text, tuple(entries), solved=solved)


__all__ = ["FrameText", "ZERO_WEIGHT", "describe", "weight_expression"]
