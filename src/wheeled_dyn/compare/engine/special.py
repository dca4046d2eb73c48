r"""The states at which a document's equation may be lost, for the equivalence decision
(:func:`~..judge.equivalence.decide`): where its equations are combinations of the true ones
with weights that vary, :math:`W(q) = A_{doc}A^{-1}` may be singular at states the samples
miss.

- **Special positions**: a position at :math:`0, \pm\pi/2, \pi` (:func:`~..grid.grid.
  special_states`): an equation times :math:`\sin\theta` is lost at :math:`\theta = 0`.
- **Searched states**: a factor that touches zero without changing sign
  (:math:`(\cos\theta - \tfrac12)^2`, :math:`(r - 1)^2`) leaves :math:`\det W` of one sign at
  every sample. Per parameter set, where a row's norm of :math:`A_{doc}` (a row that vanishes
  with :math:`w_i = A_{doc,i}A^{-1}`) or the ratio
  :math:`\rho = \mathrm{rd}(A_{doc}) / \mathrm{rd}(A)` of relative determinants
  (:func:`~..judge.equivalence.relative_det`: rows that become dependent) comes below
  :data:`SCREEN` of its median over the samples, the sample with the smallest is the start
  of a bounded search (positions within their ranges) for the smallest logarithm of it, on
  the document's side alone; the state found is judged with the special ones
  (:func:`~..judge.lost_at.vanishing_at`: the truth's A computed there, a state where
  the coordinates are singular left out). A factor that does not vanish
  (:math:`2 + \cos\theta`) stays within one order of its median and costs nothing.
- **The model's own numbers** (:func:`own_numbers`): the parameter sets are drawn, so a
  factor of the parameters (:math:`M - 5m`) that vanishes for the robot of the file would
  pass; the states of the first set are judged with its URDF's numbers too.
"""

from __future__ import annotations

import numpy as np

from ..grid.grid import SPECIAL_STATES_PER_SET, special_states
from ..judge import equivalence
from ..sides.both import Sides
from ..sides.document import DocumentFunctions
from ..sides.truth import special_truth_A

#: A parameter set's smallest row norm of the document's A, or ratio of relative determinants
#: (document / truth), below this fraction of its median over the set, is searched for a zero.
SCREEN = 1e-2
#: Relative determinant taken as zero inside the logarithm searched (below any decision).
LOG_FLOOR = 1e-300


def _values(sides: Sides, funcs: DocumentFunctions, owner: np.ndarray) -> dict:
    return {s: np.asarray([sides.per_set[k][s] for k in owner]) for s in funcs.params}


def _row_norms(A: np.ndarray) -> np.ndarray:
    with np.errstate(all="ignore"):
        return np.linalg.norm(A, axis=2)


def _median_rows(W: np.ndarray) -> np.ndarray:
    r"""Each row's median norm over the samples where :math:`W` is finite (NaN where none)."""
    norms = _row_norms(W)
    finite = np.isfinite(norms).all(axis=1)
    return np.median(norms[finite], axis=0) if finite.any() else np.full(W.shape[1], np.nan)


def _searches(doc_A: np.ndarray, true_A: np.ndarray) -> list[tuple[int, int | None]]:
    r"""(start sample, row or None) of each search on one parameter set's samples: the
    sample where the ratio of relative determinants is least (rows that become dependent),
    and for each row the sample where its norm is least (a row that vanishes), where that
    is below :data:`SCREEN` of the median."""
    with np.errstate(all="ignore"):
        ratio = equivalence.relative_det(doc_A) / equivalence.relative_det(true_A)
    out: list[tuple[int, int | None]] = []
    for values, row in ((ratio, None), *((_row_norms(doc_A)[:, i], i)
                                         for i in range(doc_A.shape[1]))):
        ok = np.isfinite(values)
        if not ok.any():
            continue
        j = int(np.flatnonzero(ok)[np.argmin(values[ok])])
        if values[j] < SCREEN * float(np.median(values[ok])):
            out.append((j, row))
    return out


def searched_states(funcs: DocumentFunctions, sides: Sides, doc_A: np.ndarray,
                    true_A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""``(q, set index)`` of the searched states (module text)."""
    grid = sides.grid
    K, N, n = grid.q.shape
    starts = [(k, j, row) for k in range(K)
              for j, row in _searches(doc_A[k * N:(k + 1) * N], true_A[k * N:(k + 1) * N])]
    if not starts:
        return np.empty((0, n)), np.empty(0, dtype=int)
    from scipy.optimize import minimize     # 0.5 s to import: only where a search is made
    bounds = np.array(grid.ranges, dtype=float)
    qs = []
    for k, j, row in starts:
        values = _values(sides, funcs, np.array([k]))

        def size(x: np.ndarray, row: int | None = row, values: dict = values) -> float:
            A = funcs.evaluate(x[None], np.zeros((1, n)), values, ("A",)).need("A")
            v = equivalence.relative_det(A)[0] if row is None else _row_norms(A)[0, row]
            return float(np.log(v + LOG_FLOOR)) if np.isfinite(v) else 0.0
        found = minimize(size, grid.q[k, j], method="L-BFGS-B", bounds=bounds)
        qs.append(np.clip(found.x, bounds[:, 0], bounds[:, 1]))
    return np.array(qs), np.array([k for k, _, _ in starts])


def own_numbers(funcs: DocumentFunctions, sides: Sides) -> tuple[np.ndarray, np.ndarray]:
    r"""The document's and the truth's A with the model's own numbers (its URDF's, or its
    parameter record's), at the first parameter set's first
    :data:`~..grid.grid.SPECIAL_STATES_PER_SET` states: an equation times a factor of the
    parameters that vanishes there (:math:`M - 5m` of a cart-pole of 2 kg and 0.4 kg) is lost
    for the very robot of the file, though not for the parameter sets drawn."""
    from ...models.registry import load_model, model_entry
    from ..grid.samples import ParameterSet, namespace_values
    from ..sides.document import document_symbol_values
    from ..sides.truth import truth_for
    d, grid = funcs.d, sides.grid
    record = model_entry(d.model).parameters
    physical = None if record is None else record()
    wm = load_model(d.model, physical)
    own = ParameterSet(wm, namespace_values(wm, physical), physical)
    q = grid.q[0, :SPECIAL_STATES_PER_SET]
    values = document_symbol_values(d, own, np.random.default_rng(0))
    at = funcs.evaluate(q, np.zeros_like(q), {s: np.full(len(q), values[s])
                                               for s in funcs.params}, ("A",))
    truth = truth_for(grid.cmap, [own], q[None], np.zeros((1, *q.shape)))
    grid.cmap.bind(grid.sets[-1].model)          # as the grid's truth left it
    return at.need("A"), truth.need("A")


def special_sides(funcs: DocumentFunctions, sides: Sides, doc_A: np.ndarray,
                  true_A: np.ndarray, W: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    r"""The document's and the truth's A with the model's own numbers and at the special and
    searched states (module text), and there the typical norm of each row of :math:`W` (its
    median over the state's parameter set, from the samples' ``W``; over all sets for the
    model's own numbers)."""
    q, owner = special_states(sides.grid)
    found_q, found_owner = searched_states(funcs, sides, doc_A, true_A)
    q, owner = np.concatenate([q, found_q]), np.concatenate([owner, found_owner]).astype(int)
    typical = np.array([_median_rows(part) for part in np.array_split(W, len(sides.grid.sets))])
    own_doc, own_true = own_numbers(funcs, sides)
    docs, truths = [own_doc], [own_true]
    usual = [np.broadcast_to(_median_rows(W), own_doc.shape[:2])]
    if len(q):
        at = funcs.evaluate(q, np.zeros_like(q), _values(sides, funcs, owner), ("A",))
        docs.append(at.need("A"))
        truths.append(special_truth_A(sides.grid, q, owner))
        usual.append(typical[owner])
    return np.concatenate(docs), np.concatenate(truths), np.concatenate(usual)


__all__ = ["SCREEN", "searched_states", "special_sides"]
