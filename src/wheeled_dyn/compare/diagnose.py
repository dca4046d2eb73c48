r"""Verdict and diagnosis of one element from its values on both sides.

Given the document's values :math:`D_s` and the truth's :math:`T_s` over samples :math:`s`, and
a scale :math:`\sigma` (the size of the row's entries):

- **agrees** when :math:`\max_s |D_s - T_s| \le \epsilon\sigma`;
- otherwise **differs**, with what explains the difference:
  *sign* (:math:`D = -T`), *factor c* (:math:`D = cT`, c fitted by least squares and shown as a
  simple fraction when it is one), *swap* (the document's expression with one coordinate,
  velocity or symbol replaced by another agrees: "φ̇ where ψ̇ fits"), *extra* (the truth is 0),
  *missing* (the document has 0), or a *residual* :math:`T - D`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp

#: Relative tolerance of agreement (the numbers are exact to ~1e-13 relative).
AGREE_TOL = 1e-7


def agrees(D: np.ndarray, T: np.ndarray, scale: float) -> bool:
    return bool(np.max(np.abs(D - T), initial=0.0) <= AGREE_TOL * scale)


def max_error(D: np.ndarray, T: np.ndarray) -> float:
    return float(np.max(np.abs(D - T), initial=0.0))


def nice_number(c: float) -> str:
    r"""``c`` as a simple fraction when it is one (1/2, -2, 3/4 ...), else 4 significant digits."""
    frac = sp.nsimplify(c, tolerance=1e-6, rational=True)
    if frac.q <= 12 and abs(float(frac) - c) <= 1e-6 * max(1.0, abs(c)):
        return str(frac)
    return f"{c:.4g}"


def value_diagnoses(D: np.ndarray, T: np.ndarray, scale: float) -> list[str]:
    r"""Diagnoses from the numbers alone (sign, factor, extra, missing)."""
    tol = AGREE_TOL * scale
    if np.max(np.abs(T), initial=0.0) <= tol:
        return ["extra term: the truth is 0"]
    if np.max(np.abs(D), initial=0.0) <= tol:
        return ["missing: the document has 0"]
    if np.max(np.abs(D + T)) <= tol:
        return ["sign: the document has the opposite sign"]
    c = float(D.ravel() @ T.ravel() / (T.ravel() @ T.ravel()))
    if np.max(np.abs(D - c * T)) <= tol:
        return [f"factor: the document is {nice_number(c)} × the truth"]
    return []


def swap_diagnoses(expr: sp.Expr, candidates: Sequence[Sequence[sp.Symbol]],
                   evaluate: Callable[[sp.Symbol, sp.Symbol], np.ndarray], T: np.ndarray,
                   scale: float) -> list[str]:
    r"""Replace one symbol of ``expr`` by another of the same group (velocities with velocities,
    positions with positions, symbols of equal units with each other); report the replacements
    that make it agree. ``evaluate(a, b)`` gives the element's values with ``a`` read as ``b``."""
    found = []
    present = expr.free_symbols
    for group in candidates:
        for a in group:
            if a not in present:
                continue
            for b in group:
                if b == a:
                    continue
                if agrees(evaluate(a, b), T, scale):
                    found.append(f"swap: {sp.sstr(a)} where {sp.sstr(b)} fits")
    return found
