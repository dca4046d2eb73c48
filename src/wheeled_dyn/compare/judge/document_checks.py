r"""The document on its own, without the truth: energy, symmetry and definiteness of A, and
what its constraint rows are.

- :func:`energy_check`: the power identity :math:`\nu^T h = \tfrac12\nu^T\dot A\nu`
  (gyroscopic forces do no work), with :math:`\dot A` along the motion: each position's rate
  from :func:`position_rates` (for quasi-velocities, solved from the file's maps); a model that
  fails it does not conserve energy;
- :func:`asymmetry`: pairs :math:`A_{ij} \ne A_{ji}` and samples where A is not positive
  definite;
- :func:`constraint_rows`: whether each row of the document's G is a rolling constraint of the
  model.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import sympy as sp

from ...compiled import numpy_function
from ...disk_cache import DiskMemo
from ...expression_size import expand_trig_small
from ...derivations.schema import Derivation
from .diagnose import AGREE_TOL, agrees
from ..grid.arrays import Arrays
from ..sides.both import Sides
from ..sides.document import DocumentFunctions
from ..records import EnergyCheck

#: Power residuals up to this many operations are factorised for display.
FACTOR_LIMIT = 120


def energy_check(funcs: DocumentFunctions, doc: Arrays, row_factor, q, nu, values, d: Derivation):
    r"""Power identity of the document on its own, its rows divided by the factor each is of
    the true equation (``row_factor``: per row a number or an expression in the document's
    names, None for 1)."""
    A, h = funcs.exprs["A"], funcs.exprs["h"]
    if A is None or h is None or A.has(sp.nan) or h.has(sp.nan):
        return None
    A, h = sp.Matrix(A), sp.Matrix(h)
    for i, c in enumerate(row_factor):   # each row divided by its factor (diag(1/c) A)
        if c is not None:
            s = 1 / sp.nsimplify(c)
            A[i, :], h[i, :] = s * A[i, :], s * h[i, :]
    v = sp.Matrix(d.velocities)
    rates = position_rates(d)
    dA = {p: A.diff(p) for p in d.positions}
    if any(rates[p] is None for p in d.positions if dA[p] != sp.zeros(d.n, d.n)):
        return None                       # A depends on a position whose rate is not known
    Adot = sum((dA[p] * rates[p] for p in d.positions if rates[p] is not None),
               sp.zeros(d.n, d.n))
    power = (v.T * h)[0] - (v.T * Adot * v)[0] / 2
    if not power.free_symbols <= set(funcs.args):
        return None       # the rates hold a model length the map names (length_pole): its
        #                   value is each parameter set's, not a document's symbol
    fn = numpy_function(funcs.args, power)
    fh = numpy_function(funcs.args, (v.T * h)[0])
    argv = [*q.T, *nu.T, *(values[p] for p in funcs.params)]
    # scale: the power's parts, and (when both vanish, e.g. Euler's gyroscopic terms) the
    # kinetic-energy rate scale |A| |nu|^2 |nu|
    kinetic = numpy_function(funcs.args, (v.T * A * v)[0])
    speed = np.linalg.norm(nu, axis=1)
    with np.errstate(all="ignore"):          # an overflowing document: no verdict, below
        P = np.broadcast_to(fn(*argv), (len(q),)).astype(float)
        parts = (np.abs(np.broadcast_to(fh(*argv), (len(q),))).astype(float),
                 np.abs(np.broadcast_to(kinetic(*argv), (len(q),)) * speed).astype(float))
    if not (np.isfinite(P).all() and all(np.isfinite(x).all() for x in parts)):
        return None                           # values not finite: the identity is undecided
    ref = max(float(parts[0].max()), float(parts[1].max()), 1e-300)
    conserves = bool(np.abs(P).max() <= AGREE_TOL * ref * 10)
    residual = "0" if conserves else RESIDUALS.get(("power", power),
                                                   lambda: _residual_text(power))
    return EnergyCheck(conserves, float(np.abs(P).max()), residual)


#: The printed power residuals (:func:`_residual_text`), remembered between runs.
RESIDUALS = DiskMemo("compare", "power", lambda: [Path(__file__)])


def _residual_text(power: sp.Expr) -> str:
    r"""The power residual :math:`\nu^T h - \tfrac12\nu^T\dot A\nu` printed: expanded
    with the trigonometric identities, factorised when it is short."""
    expr = sp.expand(expand_trig_small(power))
    return sp.sstr(sp.factor(expr) if sp.count_ops(expr) <= FACTOR_LIMIT else expr)


def position_rates(d: Derivation) -> dict[sp.Symbol, sp.Expr | None]:
    r"""The rate of each document position along the motion, in the document's velocities.

    Holonomic sets: :math:`\dot q_k` is the k-th velocity. Quasi-velocity sets: with the
    configuration :math:`c = e(p)` (model coordinates of the document's positions) and the
    velocity map :math:`\nu = V(c)\,\dot c`, the rates solve
    :math:`\nu_i = \sum_c V_{ic}\,\sum_k \partial e_c/\partial p_k\,\dot p_k` for the
    velocities whose map involves configured coordinates only. A position no equation fixes
    (the distance x travelled along the heading) gets None. Built-in sets: the velocity
    ``d<position>`` is the position's rate when the set has it (the built-in quasi set's
    heading speed ``dx`` is not the rate of any coordinate the matrices depend on)."""
    spec = d.coordinates
    if spec.kind != "quasi" or spec.use:
        return dict(zip(d.positions, d.velocities))
    rates = sp.symbols(f"rate_0:{d.n}")
    model_rate = {}
    for name, e in spec.configuration.items():
        e = sp.sympify(e).xreplace(d.model_values)
        model_rate[f"d{name}"] = sum((e.diff(p) * r for p, r in zip(d.positions, rates)),
                                     sp.Integer(0))
    eqs = []
    for vel in d.velocities:
        expr = spec.velocity_map.get(str(vel))
        if expr is None:
            continue
        if any(s.name.startswith("d") and s.name not in model_rate
               and s.name not in spec.configuration for s in expr.free_symbols):
            continue                      # involves a model velocity no position fixes
        sub = {s: model_rate[s.name] for s in expr.free_symbols if s.name in model_rate}
        sub.update({s: sp.sympify(spec.configuration[s.name]).xreplace(d.model_values)
                    for s in expr.free_symbols if s.name in spec.configuration})
        eqs.append(expr.xreplace(sub) - vel)
    found = solve_rates(eqs, rates, d) if eqs else {}
    return {p: found.get(r) for p, r in zip(d.positions, rates)}


#: Seed of the generic point at which the rank of the rate equations is read.
RATE_POINT_SEED = 4099
#: Relative size below which a singular value of the rate equations counts as zero.
RATE_RANK_TOL = 1e-9


def solve_rates(eqs: Sequence[sp.Expr], rates: Sequence[sp.Symbol], d: Derivation
                 ) -> dict[sp.Symbol, sp.Expr]:
    r"""The rates the linear equations :math:`M(p)\,r = b` fix, as expressions.

    A rate :math:`r_k` is fixed when :math:`e_k` lies in the row space of :math:`M`, read at
    a generic point (numbers for every symbol). Independent rows and pivot columns found
    there give a square system solved by LU without simplification (``sp.solve`` on
    trigonometric coefficients can run for hours); rates outside the pivots are set to 0."""
    M = sp.Matrix(eqs).jacobian(list(rates))
    b = -sp.Matrix(eqs).xreplace({r: 0 for r in rates})
    symbols = sorted(M.free_symbols | b.free_symbols, key=str)
    rng = np.random.default_rng(RATE_POINT_SEED)
    point = dict(zip(symbols, rng.uniform(0.3, 1.2, len(symbols))))
    try:
        Mn = np.array(M.xreplace(point).evalf(), dtype=float)
    except (TypeError, ValueError):
        return {}
    if not np.all(np.isfinite(Mn)) or not Mn.size:
        return {}
    _, s, vt = np.linalg.svd(Mn)
    rank = int((s > RATE_RANK_TOL * max(s[0], 1e-300)).sum())
    if rank == 0:
        return {}
    null = vt[rank:]
    fixed = [k for k in range(len(rates)) if not null.size or
             np.abs(null[:, k]).max() <= RATE_RANK_TOL]
    rows = independent_rows(Mn, rank)
    cols = independent_rows(Mn[rows].T, rank)
    sol = M.extract(rows, cols).LUsolve(b.extract(rows, [0]))
    value = dict(zip((rates[c] for c in cols), sol))
    return {rates[k]: value.get(rates[k], sp.Integer(0)) for k in fixed}


def independent_rows(Mn: np.ndarray, rank: int) -> list[int]:
    r"""``rank`` linearly independent rows of ``Mn`` (greedy, in order)."""
    chosen: list[int] = []
    for i in range(Mn.shape[0]):
        trial = Mn[chosen + [i]]
        if np.linalg.matrix_rank(trial, tol=RATE_RANK_TOL * max(np.abs(Mn).max(), 1e-300)) \
                > len(chosen):
            chosen.append(i)
        if len(chosen) == rank:
            break
    return chosen


def asymmetry(doc: Arrays, scales, n: int, truth_A: np.ndarray | None = None,
              printed_A: np.ndarray | None = None) -> tuple[str, ...]:
    r"""Pairs A[i,j] ≠ A[j,i], and whether A is positive definite (elements lost in the
    extracted text, NaN, are left out; A with a lost element is not tested for definiteness):
    not where its smallest eigenvalue is negative, or is zero (to :data:`AGREE_TOL` of its
    largest entry) where the truth's ``truth_A`` is not (a rolling disk's A near lying flat
    is nearly singular on both sides: its heading and spin turn about one axis there).
    ``doc``: the document's rows each divided by the factor its frame found; where the
    ``printed_A`` is given, only what holds of it as printed too (a point-mass disk's spin
    row, 2/3 of the true one, read as the true row times 2/3: divided by it, its A was
    "asymmetric", as printed it is not)."""
    if doc.A is None:
        return ()
    out = []
    lost = ~np.isfinite(doc.A).all(axis=0)
    both = [doc.A] if printed_A is None or printed_A.shape != doc.A.shape else \
        [doc.A, printed_A]
    for i in range(n):
        for j in range(i + 1, n):
            if lost[i, j] or lost[j, i]:
                continue
            if not any(agrees(A[:, i, j], A[:, j, i], max(scales[i], scales[j]))
                       for A in both):
                out.append(f"A[{i + 1},{j + 1}] ≠ A[{j + 1},{i + 1}]")
    if lost.any():
        return tuple(out)
    lows = [_lowest(A) for A in both]
    lowest = lows[0]
    singular = _lowest(truth_A) <= AGREE_TOL if truth_A is not None and \
        truth_A.shape == doc.A.shape else np.zeros(len(lowest), dtype=bool)
    bad = np.ones(len(lowest), dtype=bool)
    for low in lows:                      # negative, or zero where the truth's is not
        bad &= (low < -AGREE_TOL) | ((low <= AGREE_TOL) & ~singular)
    if bad.any():
        out.append(f"A is not positive definite at {int(bad.sum())} of {len(lowest)} samples "
                   f"(smallest eigenvalue {lowest[bad].min():.2g} × its largest entry)")
    return tuple(out)


def _lowest(A: np.ndarray) -> np.ndarray:
    r"""The smallest eigenvalue of :math:`(A + A^T)/2` per sample over its largest entry (NaN
    where A is not finite)."""
    sym = 0.5 * (A + np.swapaxes(A, 1, 2))
    out = np.full(len(A), np.nan)
    finite = np.isfinite(sym).all(axis=(1, 2))
    with np.errstate(all="ignore"):
        out[finite] = np.linalg.eigvalsh(sym[finite])[:, 0] / np.maximum(
            np.abs(sym[finite]).max(axis=(1, 2)), 1e-300)
    return out


def constraint_rows(doc: Arrays, truth: Arrays, scales) -> tuple[str, ...]:
    r"""Is each row of the document's G a combination of the true constraint rows?"""
    if doc.G is None:
        return ()
    if truth.G is None:
        return ("the document states constraint rows where the coordinates leave the model "
                "none: not the model's",)
    ok, off = _row_offsets(doc.G, truth.G)
    out = []
    for r in range(doc.G.shape[1]):
        if not ok.any():
            out.append(f"G row {r + 1}: not finite at any sample: not compared")
        elif not np.abs(doc.G[ok, r, :]).any():
            out.append(f"G row {r + 1}: zero (no constraint)")
        else:
            worst = float(off[:, r].max())
            out.append(f"G row {r + 1}: " + (
                "a rolling constraint of the model" if worst <= ROW_TOL else
                f"not a rolling constraint of the model (off by {worst:.2g})"))
    return tuple(out)


def _row_offsets(rows: np.ndarray, true_G: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""The samples where both sides are finite, and there how far each of the document's
    constraint rows is from the true rows' span, relative to its size (each row scaled to 1
    first: a row's scale says nothing)."""
    ok = np.isfinite(rows).all(axis=(1, 2)) & np.isfinite(true_G).all(axis=(1, 2))
    D, T = unit_rows(rows[ok]), unit_rows(true_G[ok])
    proj = np.linalg.pinv(T) @ T                     # projector on the true row space
    off = np.abs(D @ proj - D).max(axis=2) / np.maximum(np.abs(D).max(axis=2), 1e-300)
    return ok, off


#: A constraint row's singular value, relative to the largest at its sample, above which it
#: counts as independent (the rows each scaled to 1 first); a row smaller than ROUND_OFF of
#: the largest on its sample is round-off (a constraint the coordinates satisfy identically).
RANK_TOL, ROUND_OFF = 1e-8, 1e-12
#: A constraint row farther than this from the true rows' span (relative to its size) is
#: not a combination of them.
ROW_TOL = 1e-6


def unit_rows(G: np.ndarray) -> np.ndarray:
    r"""Each constraint row divided by its largest entry (per sample); a row of round-off
    beside the others (below :data:`ROUND_OFF` of the largest on its sample) is 0."""
    size = np.abs(G).max(axis=2, keepdims=True)
    real = size > ROUND_OFF * size.max(axis=1, keepdims=True)
    return np.where(real, G / np.where(real, size, 1.0), 0.0)


def constraint_space(rows: np.ndarray, true_G: np.ndarray, sets: int = 1) -> tuple[str, ...]:
    r"""Why the document's constraint rows (S × m × n: :math:`G_{doc}\dot q = 0`) do not
    restrict the velocities as the model's rolling constraints :math:`G\dot q = 0` do: a row
    that is no combination of the true rows, fewer independent rows than the true ones (a
    constraint missing), rows that are combinations of the true ones :math:`G_{doc} = PG`
    with :math:`\det P` changing sign among the samples of one of the ``sets`` parameter sets
    (a row multiplied by a factor that vanishes: the constraint is lost there). Empty when
    they span the same space at every sample where both are finite."""
    ok, off = _row_offsets(rows, true_G)
    if not ok.any():
        return ()
    D, T = unit_rows(rows[ok]), unit_rows(true_G[ok])
    out = []
    for r in np.flatnonzero(off.max(axis=0) > ROW_TOL):
        out.append(f"its constraint row {r + 1} is no combination of the model's rolling "
                   f"constraints (off by {float(off[:, r].max()):.2g} of its size)")

    short = row_rank(T) - row_rank(D)
    if (short > 0).any():
        k = int(short.max())
        have, want = int(row_rank(D).min()), int(row_rank(T).max())
        out.append(f"it states {have} independent constraint row{'s' if have != 1 else ''} "
                   f"where the model has {want}: {k} rolling constraint"
                   f"{'s' if k > 1 else ''} missing")
    if not out and _vanishing(D, T, ok, sets):
        out.append("its constraint rows are the model's times a factor that vanishes or "
                   "is unbounded somewhere (det P of G_doc = P G changes sign within a "
                   "parameter set): a constraint is lost or undefined there")
    return tuple(out)


def row_rank(M: np.ndarray) -> np.ndarray:
    r"""The rank of each sample's rows of ``M`` (S × m × n), to :data:`RANK_TOL`."""
    sv = np.linalg.svd(M, compute_uv=False)
    return (sv > RANK_TOL * np.maximum(sv[:, :1], 1e-300)).sum(axis=1)


def _distinct(T: np.ndarray, rows: np.ndarray) -> np.ndarray:
    r"""``rows`` of the unit rows ``T`` without those that are another's, or its negative, at
    every sample (a robot's two wheels on one axle state the same sideways constraint)."""
    keep: list[int] = []
    for r in rows:
        if not any(min(np.abs(T[:, r] - T[:, k]).max(), np.abs(T[:, r] + T[:, k]).max())
                   <= ROW_TOL for k in keep):
            keep.append(int(r))
    return np.array(keep, dtype=int)


def _vanishing(D: np.ndarray, T: np.ndarray, ok: np.ndarray, sets: int) -> bool:
    r"""Whether :math:`\det P` (:math:`D = PT'`, :math:`T'` the true rows that are not
    round-off, each stated once: :func:`_distinct`) takes both signs among the finite
    samples ``ok`` of one parameter set. Only where both are as many independent rows at
    every sample: rows that still state a constraint twice have no such P, and one drawn from
    a subset of them changes sign through the poles of that subset."""
    real = _distinct(T, np.flatnonzero(np.abs(T).max(axis=(0, 2)) > 0))
    if len(real) != D.shape[1] or (row_rank(T[:, real, :]) < len(real)).any() or \
            (row_rank(D) < D.shape[1]).any():
        return False
    P = D @ np.linalg.pinv(T[:, real, :])
    det = np.full(len(ok), np.nan)
    det[ok] = np.linalg.det(P)
    for group in np.array_split(det, max(sets, 1)):
        g = group[np.isfinite(group)]
        if (g > 0).any() and (g < 0).any():
            return True
    return False


def constraint_problems(d: Derivation, funcs: DocumentFunctions, sides: Sides
                        ) -> tuple[str, ...] | None:
    r"""Where the truth keeps the rolling constraints in the document's coordinates: what is
    wrong with those the document states (its G, its ``[constraints]`` equations:
    :func:`constraint_space`, named by where the file states them). Where the coordinates
    eliminate them, constraint rows the document states are constraints the model does not
    have (a file's declarations bind: they are not left aside). None where neither side has
    any."""
    doc, truth, argv, size, sets = (sides.doc, sides.truth, sides.argv, sides.size,
                                    len(sides.grid.sets))
    if truth.G is None:
        if doc.G is None or not np.any(np.nan_to_num(doc.G)):
            return None
        if d.coordinates.rolling == "none":
            return ("it states constraint rows, but declares rolling = \"none\", which drops "
                    "the model's rolling constraints: its rows are constraints the model read "
                    "so does not have (declare rolling = \"multipliers\" to keep them)",)
        return ("it states constraint rows, but its coordinates leave the model no rolling "
                "constraint (they eliminate them, or there are none): constraints the model "
                "does not have",)
    stated = []
    if doc.G is not None:
        stated.append(("G" if d.G is not None else "[constraints]", doc.G))
    if d.G is not None and d.constraints is not None:     # both: [constraints] on its own
        M = d.constraint_matrix()
        if M is not None:
            rows = np.stack([np.stack([np.broadcast_to(np.asarray(
                funcs.compiled(M[r, c])(*argv), dtype=float), (size,))
                for c in range(M.cols)], axis=1) for r in range(M.rows)], axis=1)
            stated.append(("[constraints]", rows))
    if not stated:
        return ("it states no constraints (neither G nor [constraints]) though its "
                "coordinates keep them: its equations have no multiplier terms",)
    return tuple(f"{where}: {text}" for where, rows in stated
                 for text in constraint_space(rows, truth.G, sets))


__all__ = ["FACTOR_LIMIT", "RANK_TOL", "ROUND_OFF", "ROW_TOL", "RATE_POINT_SEED", "RATE_RANK_TOL",
           "asymmetry", "constraint_problems", "constraint_rows", "constraint_space",
           "energy_check", "independent_rows", "position_rates", "row_rank", "solve_rates",
           "unit_rows"]
