r"""Element by element: both sides' numbers per element, labels, and undeclared row factors.

- :func:`truth_for` the truth over K parameter sets, :func:`input_map` its B in the document's
  inputs (:math:`B\,\partial\tau/\partial u_{doc}`);
- :func:`element_values` every element of A, C, Q, B and every velocity product of h with the
  document's and the true values and the document's expression; :func:`element_label` its
  name as documents write it (``A[2,1]``, ``h[1]:dpsi*dpsi``);
- :func:`row_factors` constants :math:`c_i` the document multiplied a row by without saying so
  (Kane's generalised inertia forces :math:`F^* = -(A\ddot q + h)`), found by a vote of the
  row's elements, and :func:`apply_row_factors`; :func:`row_scales`, the size of each row's
  entries, the scale agreement is measured against.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import numpy as np
import sympy as sp

from ...constraints.reduction import CoordinateMap
from ...derivations.schema import Derivation
from ..judge.diagnose import AGREE_TOL, agrees
from .evaluate import Arrays, DocumentFunctions, truth_arrays

#: Candidate undeclared row factors, and how far an element's own ratio may be from one.
ROW_FACTORS = (1.0, -1.0, 2.0, -2.0, 0.5, -0.5)
ROW_FACTOR_SPREAD = 0.35


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


def truth_for(cmap: CoordinateMap, sets, q, nu) -> Arrays:
    r"""The truth at every parameter set (B in the model's inputs)."""
    parts = []
    for k, ps in enumerate(sets):
        cmap.bind(ps.model)
        parts.append(truth_arrays([cmap], q[k:k + 1], nu[k:k + 1], None))
    out = Arrays()
    for name in ("A", "C", "Q", "B", "h", "H", "G"):
        vals = [getattr(p, name) for p in parts]
        setattr(out, name, None if vals[0] is None else np.concatenate(vals))
    n_states = q.shape[1]
    out.H_rows = np.concatenate([k * n_states + p.H_rows for k, p in enumerate(parts)])
    return out


def input_map(d: Derivation, truth: Arrays, per_set, n_states: int, notes: list[str]):
    r"""The truth's B in the document's inputs: :math:`B\,\partial\tau/\partial u_{doc}`."""
    if not d.input_symbols or not d.inputs:
        if d.input_symbols:
            notes.append("the file maps no model input to the document's inputs: B not compared")
        return None
    from ...models.registry import load_model
    names = load_model(d.model).input_names
    f = sp.Matrix([d.inputs.get(name, 0) for name in names])
    P = f.jacobian(sp.Matrix(d.input_symbols))
    Ps = np.stack([np.array(P.xreplace(v), dtype=float) for v in per_set])
    Ps = np.repeat(Ps, n_states, axis=0)
    return truth.B @ Ps


def element_expr(exprs: Mapping[str, object], key: str, index: tuple[int, ...],
                  velocities: Sequence[sp.Symbol]) -> sp.Expr | None:
    r"""The expression of one element (for h: the coefficient of a velocity product)."""
    M = exprs.get(key if key != "h" else "h")
    if M is None:
        return None
    if key == "Q":
        return M[index[0]]
    if key == "h":
        i, j, k = index
        h = expanded(M[i])
        if j == k:
            return h.coeff(velocities[j], 2)
        return h.coeff(velocities[j], 1).coeff(velocities[k], 1)
    return M[index]


_EXPANDED: dict[sp.Expr, sp.Expr] = {}


def expanded(expr: sp.Expr) -> sp.Expr:
    if expr not in _EXPANDED:
        _EXPANDED[expr] = sp.expand(expr)
    return _EXPANDED[expr]


def element_values(funcs: DocumentFunctions, doc: Arrays, truth: Arrays, B_true, n: int):
    r"""(key, document values, true values, index, document expression) of every element."""
    ex, vel = funcs.exprs, funcs.d.velocities
    if doc.A is not None:
        for i in range(n):
            for j in range(n):
                yield "A", doc.A[:, i, j], truth.A[:, i, j], (i, j), ex["A"][i, j]
    if doc.C is not None:
        for i in range(n):
            for j in range(n):
                yield "C", doc.C[:, i, j], truth.C[:, i, j], (i, j), ex["C"][i, j]
    if doc.Q is not None:
        for i in range(n):
            yield "Q", doc.Q[:, i], truth.Q[:, i], (i,), ex["Q"][i]
    if doc.B is not None and B_true is not None:
        for i in range(n):
            for j in range(doc.B.shape[2]):
                yield "B", doc.B[:, i, j], B_true[:, i, j], (i, j), ex["B"][i, j]
    if doc.H is not None:
        for i in range(n):
            for j in range(n):
                for k in range(j, n):
                    w = 1.0 if j == k else 2.0
                    yield ("h", w * doc.H[:, i, j, k], w * truth.H[:, i, j, k], (i, j, k),
                           element_expr(ex, "h", (i, j, k), vel))


def row_factors(doc: Arrays, truth: Arrays, B_true, n: int) -> list[float | None]:
    r"""A constant :math:`c_i` with document row i = :math:`c_i` × true row i that the file did
    not declare (e.g. −1 for Kane's generalised inertia forces :math:`F^* = -(A\ddot q + h)`).

    Each nonzero element of the row votes for the candidate of :data:`ROW_FACTORS` nearest its
    own least-squares ratio (within :data:`ROW_FACTOR_SPREAD`); a candidate other than 1 needs
    a strict majority among A's entries and among all of the row's (A, Q, B). Voting keeps a
    single wrong coefficient (e.g. 3(m_c + m_s)) from scaling a row."""
    votes_a, votes_all = row_votes(doc, truth, B_true, n)
    return [decided_factor(votes_a[i], votes_all[i],
                           lambda f, i=i: explains(f, row_pairs(doc, truth, B_true, i)))
            for i in range(n)]


def row_votes(doc: Arrays, truth: Arrays, B_true, n: int,
              fixed: tuple[np.ndarray, np.ndarray] | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    r"""The votes of :func:`row_factors`: A's entries' (rows × columns) and all of each row's
    (A's, Q's, B's; rows × entries). ``fixed``: the votes of A and of Q, known already (only
    B's are counted then)."""
    if fixed is None:
        votes_a = _votes(doc.A, truth.A) if doc.A is not None else np.empty((n, 0))
        votes_q = _votes(doc.Q[:, :, None], truth.Q[:, :, None]) if doc.Q is not None \
            else np.empty((n, 0))
    else:
        votes_a, votes_q = fixed
    parts = [votes_a, votes_q]
    if doc.B is not None and B_true is not None:
        parts.append(_votes(doc.B, B_true))
    return votes_a, np.concatenate(parts, axis=1)


def decided_factor(votes_a: np.ndarray, votes_all: np.ndarray,
                   explains: Callable[[float], bool]) -> float | None:
    r"""One row's factor from its votes (:func:`row_factors`): A's entries decide, Q and B only
    confirm (a wrong input map must not scale a row); ``explains(f)``: dividing by ``f``
    makes an element of the row agree."""
    row_a, row_all = votes_a[~np.isnan(votes_a)], votes_all[~np.isnan(votes_all)]
    winner = None
    for f in ROW_FACTORS:
        if f == 1.0 or not len(row_a):
            continue
        if np.count_nonzero(row_a == f) * 2 > len(row_a) and \
                np.count_nonzero(row_all == f) * 2 > len(row_all):
            winner = f
    return winner if winner is not None and explains(winner) else None


def row_pairs(doc: Arrays, truth: Arrays, B_true, i: int) -> list[tuple[np.ndarray, np.ndarray]]:
    r"""Row i's (document, truth) sample pairs: A's entries, Q, B's entries."""
    pairs = []
    if doc.A is not None:
        pairs += [(doc.A[:, i, j], truth.A[:, i, j]) for j in range(doc.A.shape[2])]
    if doc.Q is not None:
        pairs.append((doc.Q[:, i], truth.Q[:, i]))
    if doc.B is not None and B_true is not None:
        pairs += [(doc.B[:, i, j], B_true[:, i, j]) for j in range(doc.B.shape[2])]
    return pairs


_CANDIDATES = np.array(ROW_FACTORS)


def _votes(D: np.ndarray, T: np.ndarray) -> np.ndarray:
    r"""The votes (:func:`row_factors`) of the entries of ``D`` against ``T`` (samples ×
    rows × entries): the candidate of :data:`ROW_FACTORS` nearest each entry's ratio
    :math:`D\cdot T / T\cdot T`, or ``inf`` (a vote for none) when none is within
    :data:`ROW_FACTOR_SPREAD`; NaN (no vote) for an entry not finite or with a zero side.
    Rows × entries."""
    with np.errstate(all="ignore"):
        finite = np.isfinite(D).all(axis=0) & np.isfinite(T).all(axis=0)
        tt, dd = np.einsum("nij,nij->ij", T, T), np.einsum("nij,nij->ij", D, D)
        c = np.einsum("nij,nij->ij", D, T) / tt
        best = _CANDIDATES[np.argmin(np.abs(c[..., None] - _CANDIDATES), axis=-1)]
        out = np.where(np.abs(c - best) <= ROW_FACTOR_SPREAD * np.abs(best), best, np.inf)
    return np.where(finite & (tt > 0) & (dd > 0), out, np.nan)


def explains(factor: float, pairs: Sequence[tuple[np.ndarray, np.ndarray]]) -> bool:
    r"""A row factor is only taken when dividing by it makes at least one nonzero element
    of the row agree exactly (near-ratios of elements that differ anyway explain nothing)."""
    finite = [(D, T) for D, T in pairs if np.isfinite(D).all() and np.isfinite(T).all()]
    if not finite:
        return False
    scale = max(max(float(np.abs(D).max()), float(np.abs(T).max())) for D, T in finite)
    return any(float(np.abs(T).max()) > AGREE_TOL * scale and agrees(D / factor, T, scale)
               for D, T in finite)


def apply_row_factors(doc: Arrays, factors) -> None:
    for i, c in enumerate(factors):
        if c is None:
            continue
        for name in ("A", "C", "Q", "B", "h", "H"):
            M = getattr(doc, name)
            if M is not None:
                M[:, i] = M[:, i] / c


def row_scales(doc: Arrays, truth: Arrays, n: int, truth_sizes: np.ndarray | None = None
               ) -> np.ndarray:
    r"""Each row's scale: the largest magnitude in its A, C, Q and H, document or truth (1
    for a row of zeros); ``truth_sizes``: :func:`row_sizes` of ``truth``, known already."""
    s = np.maximum(row_sizes(doc, n), row_sizes(truth, n) if truth_sizes is None
                   else truth_sizes)
    return np.where(s > 0, s, 1.0)


def row_sizes(arrays: Arrays, n: int) -> np.ndarray:
    r"""The largest magnitude in each row of ``arrays``' A, C, Q and H (0 where none)."""
    s = np.zeros(n)
    for name in ("A", "C", "Q", "H"):
        M = getattr(arrays, name)
        if M is not None:
            s = np.maximum(s, np.abs(M.reshape(M.shape[0], n, -1)).max(axis=(0, 2)))
    return s


def swap_groups(d: Derivation) -> list[list[sp.Symbol]]:
    by_units: dict[str, list[sp.Symbol]] = {}
    for spec in d.symbols.values():
        if not spec.is_input and spec.units:
            by_units.setdefault(spec.units.replace(" ", ""), []).append(spec.symbol)
    return [list(d.velocities), list(d.positions), *[g for g in by_units.values() if len(g) > 1]]


__all__ = ["ROW_FACTORS", "ROW_FACTOR_SPREAD", "apply_row_factors", "decided_factor",
           "element_expr", "element_label", "element_values", "expanded", "explains", "input_map",
           "latex_names", "row_factors", "row_pairs", "row_scales", "row_sizes", "row_votes",
           "swap_groups",
           "truth_for"]
