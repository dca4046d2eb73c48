r"""Both sides on one grid: the truth in the document's coordinates and inputs, and the
document's compiled elements evaluated at the same samples.

:func:`both_sides` gives a :class:`Sides` record: the grid, the truth (its B in the document's
inputs, :func:`~.truth.input_map`), the document's arrays as printed (:func:`~.document.
document_arrays`, also :math:`\Gamma` of its C on the H samples), the document's symbol values
per parameter set and per sample, and the arguments of its compiled functions.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ...models.registry import load_model
from ..grid.arrays import Arrays
from ..grid.grid import Grid
from .document import DocumentFunctions, document_arrays
from .truth import input_map, stiffness


@dataclass(frozen=True)
class Sides:
    r"""Both sides on ``grid`` (module text); ``notes`` what could not be compared,
    ``readings`` what the model reads otherwise than its URDF writes
    (:mod:`~wheeled_dyn.models.readings`)."""

    grid: Grid
    truth: Arrays
    doc: Arrays
    B_true: np.ndarray | None
    per_set: tuple[dict[sp.Symbol, float], ...]
    values: Mapping[sp.Symbol, np.ndarray]
    argv: tuple[np.ndarray, ...]
    notes: tuple[str, ...]
    readings: tuple[str, ...] = ()

    @property
    def size(self) -> int:
        return len(self.grid.flat_q)


def gamma(funcs: DocumentFunctions, q: np.ndarray, values: Mapping[sp.Symbol, np.ndarray],
          rows: np.ndarray) -> np.ndarray | None:
    r""":math:`\Gamma_{i,jk}` of the document's C (the coefficient of :math:`\nu_k` in
    :math:`C_{ij}`) at the samples ``rows``: C evaluated at the unit velocities."""
    if funcs.exprs.get("C") is None:
        return None
    n = q.shape[1]
    sub = {s: np.asarray(v)[rows] if np.ndim(v) else v for s, v in values.items()}
    parts = []
    for k in range(n):
        unit = np.zeros((len(rows), n))
        unit[:, k] = 1.0
        parts.append(funcs.evaluate(q[rows], unit, sub).need("C"))
    return np.stack(parts, axis=3)


def both_sides(d: Derivation, funcs: DocumentFunctions, grid: Grid, seed: int,
               with_gamma: bool = False) -> Sides:
    r"""Both sides on ``grid`` (module text); ``with_gamma``: also the document's
    :math:`\Gamma` on the truth's H samples."""
    truth = grid.truth
    doc, per_set, values = document_arrays(d, funcs, grid.sets, grid.q, grid.nu, seed,
                                           truth.H_rows)
    if doc.K is not None and truth.K is None:       # a linearised document: its stiffness
        truth.K = stiffness(grid.cmap, grid.sets, grid.q)
    notes: list[str] = []
    B_true = input_map(d, truth, per_set, grid.q.shape[1], notes)
    if with_gamma and truth.H_rows is not None:
        doc.Gamma = gamma(funcs, grid.flat_q, values, truth.H_rows)
    argv = (*grid.flat_q.T, *grid.flat_nu.T, *(values[p] for p in funcs.params))
    return Sides(grid, truth, doc, B_true, tuple(per_set), values, argv, tuple(notes),
                 load_model(d.model).readings + held_readings(grid.cmap))


def held_readings(cmap) -> tuple[str, ...]:
    r"""What the model reads of the coordinates the file's set holds
    (:mod:`~wheeled_dyn.constraints.held`), one sentence each."""
    config = cmap.cs.configuration
    return tuple(f"coordinate {c} held at {config.get(c, 0)}: the file's velocities leave it "
                 "free (its configuration is a constant and no velocity maps its rate), so "
                 "the truth is the model with it held there, as a locked joint or a guide "
                 "holds it" for c in cmap.held)


__all__ = ["Sides", "both_sides", "gamma", "held_readings"]
