r"""The terms of :math:`A(q)\ddot q + C(q,\dot q)\dot q + Q(q) = B u` of a model, by Pinocchio.

- :math:`A` = ``crba`` (symmetrised; includes the motor armature on the wheel joints);
- :math:`C` = ``computeCoriolisMatrix``. Every joint of a wheeled model has one degree of
  freedom and the base is fixed to the world, so this is the Christoffel-consistent matrix
  :math:`C_{ij} = \sum_k c_{i,jk}\dot q_k` (checked against :mod:`.christoffel` in the tests);
- :math:`Q = \partial U/\partial q` = ``computeGeneralizedGravity`` plus the joint springs'
  :math:`k(q_j - q_{j,0})` (:mod:`~wheeled_dyn.models.springs`);
- :math:`B`: each wheel motor acts on its wheel joint (reaction on the body is implied by the
  joint being relative);
- :math:`h = C\dot q` (unique, whatever C).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..errors import StateError
from ..models.builder import WheeledModel


@dataclass(frozen=True)
class Terms:
    r"""A, C, Q, B and h at one state, in the coordinates named by ``velocities``
    (``G`` is the constraint matrix when constraints are kept with multipliers)."""

    velocities: tuple[str, ...]
    inputs: tuple[str, ...]
    A: np.ndarray
    C: np.ndarray
    Q: np.ndarray
    B: np.ndarray
    h: np.ndarray
    G: np.ndarray | None = None

    def as_dict(self) -> dict[str, object]:
        out = {"coordinates": list(self.velocities), "inputs": list(self.inputs),
               "A": self.A.tolist(), "C": self.C.tolist(), "Q": self.Q.tolist(),
               "B": self.B.tolist(), "h": self.h.tolist()}
        if self.G is not None:
            out["G"] = self.G.tolist()
        return out


def check_vector(name: str, value: np.ndarray, size: int, labels: tuple[str, ...] = ()) -> np.ndarray:
    r"""``value`` as a float vector of length ``size``; :class:`StateError` on a wrong length or
    a NaN/infinite entry (named by ``labels`` when given)."""
    arr = np.asarray(value, dtype=float).reshape(-1)
    if arr.shape != (size,):
        raise StateError(name, arr.tolist(), f"{size} numbers")
    bad = np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        label = labels[bad[0]] if labels else f"{name}[{bad[0]}]"
        raise StateError(label, float(arr[bad[0]]), "a finite number")
    return arr


def full_terms(wm: WheeledModel, q: np.ndarray, v: np.ndarray, data: pin.Data | None = None) -> Terms:
    r"""A, C, Q, B, h of the whole model (no constraint) at :math:`(q, v)`."""
    names = wm.coordinate_names
    q = check_vector("q", q, wm.model.nq, names)
    v = check_vector("v", v, wm.model.nv, tuple("d" + n for n in names))
    model = wm.model
    data = data or model.createData()
    A = pin.crba(model, data, q)
    A = np.triu(A) + np.triu(A, 1).T
    C = pin.computeCoriolisMatrix(model, data, q, v).copy()
    Q = wm.potential_force(data, q)
    return Terms(tuple("d" + n for n in names), wm.input_names, A, C, Q, wm.input_matrix(), C @ v)
