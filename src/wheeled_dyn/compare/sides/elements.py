r"""Element by element: both sides' numbers per element, and labels.

- :func:`element_values` every element of A, C, Q, B and every velocity product of h with the
  document's and the true values and the document's expression; :func:`element_label` its
  name as documents write it (``A[2,1]``, ``h[1]:dpsi*dpsi``);
- :func:`element_expr` the expression of one element (for h, the coefficient of a velocity
  product), :func:`latex_names` the velocities dotted, :func:`swap_groups` the symbols one may
  have been written for another (velocities, positions, symbols of equal units).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import sympy as sp

from ...derivations.namespace import GEOMETRY_NAMES, KHALIL_NAMES, PHYSICAL_NAMES
from ...derivations.schema import Derivation
from ..grid.arrays import Arrays
from ..sides.document import DocumentFunctions, expanded, large_coefficients



def latex_names(d: Derivation) -> dict[sp.Symbol, str]:
    r"""LaTeX of velocities and accelerations as dotted coordinates (:math:`\dot\psi`)."""
    out = {}
    for q, v, a in zip(d.positions, d.velocities, d.accelerations):
        base = sp.latex(q)
        out[v] = rf"\dot{{{base}}}"
        out[a] = rf"\ddot{{{base}}}"
    return out


def element_label(key: str, index: tuple[int, ...], velocities: Sequence[sp.Symbol]) -> str:
    if key in ("Q",):
        return f"Q[{index[0] + 1}]"
    if key == "h":
        i, j, k = index
        return f"h[{i + 1}]:{velocities[j]}*{velocities[k]}"
    return f"{key}[{index[0] + 1},{index[1] + 1}]"


def element_expr(exprs: Mapping[str, Any], key: str, index: tuple[int, ...],
                  velocities: Sequence[sp.Symbol]) -> sp.Expr | None:
    r"""The expression of one element (for h: the coefficient of a velocity product)."""
    M = exprs.get(key if key != "h" else "h")
    if M is None:
        return None
    if key == "Q":
        return M[index[0]]
    if key == "h":
        i, j, k = index
        large = large_coefficients(M[i], velocities)
        if large is not None:
            return large.get((min(j, k), max(j, k)), sp.Integer(0))
        h = expanded(M[i])
        if j == k:
            return h.coeff(velocities[j], 2)
        return h.coeff(velocities[j], 1).coeff(velocities[k], 1)
    return M[index]


def element_values(funcs: DocumentFunctions, doc: Arrays, truth: Arrays, B_true, n: int):
    r"""(key, document values, true values, index, document expression) of every element."""
    ex = funcs.exprs
    if doc.A is not None:
        yield from _matrix_values("A", doc.A, truth.need("A"), ex["A"], n, n)
    if doc.C is not None:
        yield from _matrix_values("C", doc.C, truth.need("C"), ex["C"], n, n)
    if doc.Q is not None:
        Q_true = truth.need("Q")
        for i in range(n):
            yield "Q", doc.Q[:, i], Q_true[:, i], (i,), ex["Q"][i]
    if doc.B is not None and B_true is not None:
        yield from _matrix_values("B", doc.B, B_true, ex["B"], n, doc.B.shape[2])
    if doc.H is not None:
        yield from _h_values(funcs, doc.H, truth.need("H"), n)


def _matrix_values(key: str, D: np.ndarray, T: np.ndarray, exprs: sp.Matrix, rows: int,
                   cols: int):
    r"""The elements of matrix ``key`` (samples × rows × cols), row by row."""
    for i in range(rows):
        for j in range(cols):
            yield key, D[:, i, j], T[:, i, j], (i, j), exprs[i, j]


def _h_values(funcs: DocumentFunctions, H_doc: np.ndarray, H_true: np.ndarray, n: int):
    r"""The velocity products of h: the coefficient of :math:`\dot q_j\dot q_k` (j ≤ k) in
    row i, twice the symmetric H's element where j ≠ k."""
    for i in range(n):
        for j in range(n):
            for k in range(j, n):
                w = 1.0 if j == k else 2.0
                yield ("h", w * H_doc[:, i, j, k], w * H_true[:, i, j, k], (i, j, k),
                       element_expr(funcs.exprs, "h", (i, j, k), funcs.d.velocities))


#: The kinds of a link's parameters a symbol without units may be one of (its value one call:
#: ``m = "M(pole)"``): symbols of one kind may have been written for each other.
PARAMETER_KINDS = {"M": "mass", **{k: "first moment" for k in ("MX", "MY", "MZ")},
                   **{k: "moment of inertia" for k in (*KHALIL_NAMES[4:], *PHYSICAL_NAMES[3:])},
                   **{k: "length" for k in (*PHYSICAL_NAMES[:3], *GEOMETRY_NAMES)}}


#: The units of each kind of link parameter, as a file writes them (a symbol with its units
#: declared groups with one whose value names a parameter of that kind).
KIND_UNITS = {"mass": "kg", "first moment": "kg*m", "moment of inertia": "kg*m**2",
              "length": "m"}


def _kind(spec) -> str | None:
    r"""A symbol's group for swaps: its units, else the units of the kind of the one link
    parameter its value calls, times a number or not (``M(cart)`` and ``M(pole)`` both
    masses: M written where m fits; ``-CZ(link1)`` and ``-CZ(link2)`` both lengths, as a
    file that declares no units maps a hanging arm's lc1 and lc2)."""
    if spec.units:
        return spec.units.replace(" ", "")
    from sympy.core.function import AppliedUndef
    value = spec.value
    if isinstance(value, sp.Mul):
        value = value.as_coeff_Mul()[1]
    if isinstance(value, AppliedUndef) and len(value.args) == 1:
        kind = PARAMETER_KINDS.get(value.func.__name__)
        return KIND_UNITS.get(kind, kind) if kind is not None else None
    return None


def swap_groups(d: Derivation, values: Mapping[sp.Symbol, Any] | None = None
                ) -> list[list[sp.Symbol]]:
    r"""The document's symbols that one may be written for another: its velocities, its
    positions, and its symbols of one kind (:func:`_kind`) — but for a symbol 0 at every
    sample of ``values`` (the grid's, where given): a term in it vanishes whatever it is
    written for (b where a fits, b the centre of mass's offset a family keeps at 0, reads as
    any term missing in a)."""
    by_kind: dict[str, list[sp.Symbol]] = {}
    for spec in d.symbols.values():
        kind = None if spec.is_input else _kind(spec)
        held = None if values is None else values.get(spec.symbol)
        if held is not None and not np.any(np.asarray(held)):
            continue
        if kind is not None:
            by_kind.setdefault(kind, []).append(spec.symbol)
    return [list(d.velocities), list(d.positions), *[g for g in by_kind.values() if len(g) > 1]]


__all__ = ["element_expr", "element_label", "element_values", "expanded", "latex_names",
           "swap_groups"]
