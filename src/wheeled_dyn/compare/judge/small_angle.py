r"""A small-angle approximation in equations compared as exact: the document writes
:math:`x` where :math:`\sin x` fits, or drops a factor :math:`\cos x` (:math:`\cos x \approx 1`),
for a position :math:`x`, without declaring a linearisation (``linearised_about``).

An explanation of an element that differs, never a verdict: a trial reading is named only
where it agrees with the truth at every sample, as every other diagnosis
(:mod:`.diagnose`). Trials, in order, for each position :math:`x`:

- the whole element: every :math:`x` outside a trigonometric function read as
  :math:`\sin x`; the element times :math:`\cos x`; both;
- one additive term (as printed, else expanded), the others as written: the same three;
  then two terms read as sines together.

The angles are the positions and the sums and differences of them the document takes sines or
cosines of (:meth:`~..sides.document.DocumentFunctions.angles`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp

from ..records import Diagnosis, DiagnosisKind as K, diagnosis
from .diagnose import MAX_TERMS, agrees, expanded_terms

#: A trial of one expression: (what the document wrote, what fits, the expression it reads,
#: whether that is multiplied by :math:`\cos x`: numerically, so no product is built).
Trial = tuple[str, str, sp.Expr, bool]


def _outside_trig(expr: sp.Expr) -> set[sp.Basic]:
    r"""The symbols of ``expr`` that occur outside :math:`\sin, \cos, \tan`."""
    if isinstance(expr, sp.Symbol):
        return {expr}
    if isinstance(expr, (sp.sin, sp.cos, sp.tan)):
        return set()
    return set().union(*(_outside_trig(a) for a in expr.args))


def bare(expr: sp.Expr, x: sp.Expr, replacement: sp.Expr) -> sp.Expr:
    r"""``expr`` with the occurrences of ``x`` outside :math:`\sin, \cos, \tan` replaced. A
    sum of positions (:math:`q_1 + q_2`) is found however the document grouped it
    (:math:`m g q_1 + m g q_2` too): written in a new variable :math:`X = x` for one of its
    positions, expanded, read, and written back."""
    if not x.free_symbols & _outside_trig(expr):   # nothing of x to read (most elements)
        return expr
    if not isinstance(x, sp.Symbol):
        X = sp.Dummy("X")
        found = next(((s, x.coeff(s)) for s in sorted(x.free_symbols, key=sp.default_sort_key)
                      if x.coeff(s) != 0), None)
        if found is None:                  # no position to first power (q**2): no reading
            return expr
        q, c = found
        moved = sp.expand(expr.subs(q, (X - (x - c * q)) / c))
        read = bare(moved, X, replacement.subs(x, X)).subs(X, x)
        return expr if sp.expand(read - expr) == 0 else read
    inside = {f: sp.Dummy() for f in expr.atoms(sp.sin, sp.cos, sp.tan) if f.has(x)}
    back = {v: k for k, v in inside.items()}
    return expr.xreplace(inside).xreplace({x: replacement}).xreplace(back)


def _trials(expr: sp.Expr, x: sp.Expr) -> list[Trial]:
    r"""The three readings of ``expr`` for angle ``x`` (module text) that change it; none
    multiplying by :math:`\cos x` where ``expr`` divides by it or has :math:`\tan x` (that
    only cancels: a tangent written for a sine is a swap, :mod:`.diagnose`)."""
    sin_read = bare(expr, x, sp.sin(x))
    out: list[Trial] = []
    if sin_read != expr:
        out.append((sp.sstr(x), sp.sstr(sp.sin(x)), sin_read, False))
    divides = expr.has(sp.tan(x)) or any(
        p.base == sp.cos(x) and p.exp.is_negative for p in expr.atoms(sp.Pow))
    if divides:
        return out
    out.append(("1", sp.sstr(sp.cos(x)), expr, True))
    if sin_read != expr:
        out.append((f"{sp.sstr(x)} and 1", f"{sp.sstr(sp.sin(x))} and {sp.sstr(sp.cos(x))}",
                    sin_read, True))
    return out


def _found(x: sp.Symbol, written: str, fits: str, term: str = "") -> Diagnosis:
    where = f" in the term {term}" if term else ""
    return diagnosis(K.SMALL_ANGLE, f"{written} where {fits} fits{where} (small angles: "
                     f"sin({x}) ≈ {x}, cos({x}) ≈ 1; no linearisation is declared)",
                     prefix="small angle", written=written, fits=fits, term=term,
                     position=sp.sstr(x))


class _Values:
    r"""The values of the expressions a set of trials reads, and of :math:`\cos x` for each
    position, each evaluated once (in one compiled call). ``evaluate_many`` gives values of
    the row read in its frame (divided by the row's factor :math:`c`), so the factor
    :math:`\cos x` is its value over that of 1: :math:`(\cos x / c) / (1 / c)`."""

    def __init__(self, evaluate_many: Callable[[list], list[np.ndarray]],
                 exprs: Sequence[sp.Expr], positions: Sequence[sp.Expr]) -> None:
        unique = list(dict.fromkeys([*exprs, sp.S.One, *(sp.cos(x) for x in positions)]))
        self._at = {e: v for e, v in zip(unique, evaluate_many(unique))}

    def __getitem__(self, expr: sp.Expr) -> np.ndarray:
        return self._at[expr]

    def trial(self, x: sp.Expr, t: Trial) -> np.ndarray:
        r"""The value of trial ``t`` of angle ``x``."""
        if not t[3]:
            return self._at[t[2]]
        with np.errstate(all="ignore"):
            return self._at[t[2]] * (self._at[sp.cos(x)] / self._at[sp.S.One])


def small_angle_diagnoses(expr: sp.Expr, positions: Sequence[sp.Symbol],
                          evaluate_many: Callable[[list], list[np.ndarray]], T: np.ndarray,
                          scale: float) -> list[Diagnosis]:
    r"""The small-angle readings of ``expr`` (module text) that agree with ``T``; ``evaluate_many``
    evaluates a list of expressions at the samples in one compiled call; each diagnosis names
    its ``position`` (one cause per position)."""
    if not positions:
        return []
    whole = [(x, t) for x in positions for t in _trials(expr, x)]
    at = _Values(evaluate_many, [t[2] for _, t in whole], positions)
    found = [_found(x, t[0], t[1]) for x, t in whole if agrees(at.trial(x, t), T, scale)]
    if found:
        return found[:1]
    for terms in (sp.Add.make_args(expr), expanded_terms(expr)):
        if len(terms) < 2 or len(terms) > MAX_TERMS:
            continue
        per = [(k, x, t) for k, term in enumerate(terms) for x in positions
               for t in _trials(term, x)]
        at = _Values(evaluate_many, [*terms, *(t[2] for _, _, t in per)], positions)
        values = [at[term] for term in terms]
        total = sum(values)
        found = [_found(x, t[0], t[1], sp.sstr(terms[k])) for k, x, t in per
                 if agrees(total - values[k] + at.trial(x, t), T, scale)]
        if found:
            return found[:1]
        # two terms read so together (m₁a₁gθ + m₂l₁gθ; a bare θ elsewhere in the row kept)
        sines = {(k, x): at.trial(x, t) for k, x, t in per if t[0] == sp.sstr(x)}
        for (k, x), v in sines.items():
            for (j, y), u in sines.items():
                if j > k and y == x and agrees(total - values[k] - values[j] + v + u, T,
                                               scale):
                    return [_found(x, sp.sstr(x), sp.sstr(sp.sin(x)),
                                   f"{sp.sstr(terms[k])} and {sp.sstr(terms[j])}")]
    return []


__all__ = ["bare", "small_angle_diagnoses"]
