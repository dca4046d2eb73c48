r"""The truth's numbers on a grid, in the document's coordinates.

With the document's coordinate map (:class:`~wheeled_dyn.constraints.CoordinateMap`) bound to
each parameter set: :math:`A, C, Q, h`, the unique symmetric coefficient tensor of :math:`h`,
:math:`H_{i,jk} = \tfrac12(C(e_k)_{ij} + C(e_j)_{ik})` (on the first :data:`H_SAMPLES` states
of each set), and :math:`B` in the document's inputs: if the model's inputs are
:math:`\tau = f(u_{doc})`, :math:`B_{doc} = B\,\partial f/\partial u` (:func:`input_map`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...constraints.reduction import CoordinateMap
from ...derivations.schema import Derivation
from ...errors import StateError
from ..grid.arrays import Arrays
from ..grid.grid import Grid

#: States per parameter set on which the coefficient tensor H of h is compared (h itself, A,
#: C, Q, B are compared on all of them).
H_SAMPLES = 200


def truth_arrays(cmaps: Sequence[CoordinateMap], q: np.ndarray, nu: np.ndarray,
                 input_maps: Sequence[np.ndarray] | None) -> Arrays:
    r"""Truth for each parameter set's bound map ``cmaps[k]`` at states ``q[k], nu[k]``
    (K × N × n); ``input_maps[k]`` is :math:`\partial\tau/\partial u_{doc}` (or None).
    :math:`H` comes from :math:`C_\nu(e_j)`, which is linear in :math:`\nu`, on the first
    :data:`H_SAMPLES` states of each set (rows listed in ``H_rows``)."""
    from ...constraints.batch import reduce_batch_multi
    parts: dict[str, list[np.ndarray]] = {k: [] for k in ("A", "C", "Q", "B", "h", "H", "G",
                                                          "Gamma")}
    rows: list[np.ndarray] = []
    for k, cmap in enumerate(cmaps):
        n, N = cmap.n, len(q[k])
        qm = cmap._config_batch(N, *q[k].T, *cmap._p)[:, :, 0]
        m = min(N, H_SAMPLES)
        units = [np.tile(np.eye(n)[j], (m, 1)) for j in range(n)]
        if m == N:
            t, *basis = reduce_batch_multi(cmap, qm, [nu[k], *units], q[k])
        else:
            (t,) = reduce_batch_multi(cmap, qm, [nu[k]], q[k])
            basis = reduce_batch_multi(cmap, qm[:m], units, q[k][:m])
        rows.append(k * N + np.arange(m))
        gamma = np.stack([b.C for b in basis], axis=3)
        parts["A"].append(t.A)
        parts["C"].append(t.C)
        parts["Q"].append(t.Q)
        parts["h"].append(t.h)
        parts["H"].append(0.5 * (gamma + gamma.transpose(0, 1, 3, 2)))
        parts["Gamma"].append(gamma)
        parts["B"].append(t.B if input_maps is None else t.B @ input_maps[k])
        if t.G is not None and t.G.shape[1]:    # a model without rolling constraints: none
            parts["G"].append(t.G)
    out = Arrays(**{k: (np.concatenate(v) if v else None) for k, v in parts.items()})
    out.H_rows = np.concatenate(rows)
    return out


def truth_for(cmap: CoordinateMap, sets, q: np.ndarray, nu: np.ndarray) -> Arrays:
    r"""The truth at every parameter set's states (B in the model's inputs)."""
    parts = []
    for k, ps in enumerate(sets):
        cmap.bind(ps.model)
        parts.append(truth_arrays([cmap], q[k:k + 1], nu[k:k + 1], None))
    out = Arrays()
    for name in ("A", "C", "Q", "B", "h", "H", "G", "Gamma"):
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


#: Step of the central differences of the truth's stiffness (in the document's positions), and
#: the most distinct states per parameter set it is computed at (else at every state).
STIFFNESS_STEP, STIFFNESS_STATES = 1e-3, 32


def stiffness(cmap: CoordinateMap, sets, q: np.ndarray) -> np.ndarray:
    r""":math:`K = \partial Q/\partial q` of the truth at the states ``q`` (K × N × n) of the
    parameter ``sets`` (S × n × n), by Richardson-extrapolated central differences
    (:math:`[8(Q(q+\delta) - Q(q-\delta)) - (Q(q+2\delta) - Q(q-2\delta))]/12\delta`, error of
    order :math:`\delta^4`), at each distinct state once."""
    K_sets, N, n = q.shape
    out = np.empty((K_sets, N, n, n))
    h = STIFFNESS_STEP
    steps = [(2 * h, -1.0), (h, 8.0), (-h, -8.0), (-2 * h, 1.0)]
    for k, ps in enumerate(sets):
        states, where = np.unique(q[k], axis=0, return_inverse=True)
        if len(states) > STIFFNESS_STATES:
            states, where = q[k], np.arange(N)
        moved = np.concatenate([states + dh * np.eye(n)[j] for j in range(n)
                                for dh, _ in steps])
        Q = truth_for(cmap, [ps], moved[None], np.zeros_like(moved)[None]).need("Q")
        Q = Q.reshape(n, len(steps), len(states), n)
        weights = np.array([w for _, w in steps])
        deriv = np.einsum("c,jcsi->sij", weights, Q) / (12 * h)
        out[k] = deriv[np.ravel(where)]
    return out.reshape(K_sets * N, n, n)


def special_truth_A(grid: Grid, q: np.ndarray, owner: np.ndarray) -> np.ndarray:
    r"""The truth's A at states ``q`` of the parameter sets ``owner`` (S × n × n); NaN at a
    state where the model has none (a rolling disk lying flat at a lean of ±π/2, one of the
    special positions: its contact point is not defined there)."""
    n = grid.q.shape[2]
    out = np.full((len(q), n, n), np.nan)
    for k, ps in enumerate(grid.sets):
        rows = np.flatnonzero(owner == k)
        try:
            if len(rows):
                out[rows] = truth_for(grid.cmap, [ps], q[rows][None],
                                      np.zeros((1, len(rows), n))).A
        except StateError:                # one state at a time: those that have a truth
            for r in rows:
                try:
                    out[r] = truth_for(grid.cmap, [ps], q[r:r + 1][None],
                                       np.zeros((1, 1, n))).need("A")[0]
                except StateError:
                    pass
    return out


__all__ = ["H_SAMPLES", "STIFFNESS_STATES", "STIFFNESS_STEP", "input_map", "special_truth_A",
           "stiffness", "truth_arrays", "truth_for"]
