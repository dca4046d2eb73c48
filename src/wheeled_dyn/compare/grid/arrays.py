r"""Matrices over samples: the record both sides of a comparison are evaluated into."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class Arrays:
    r"""Matrices over the samples (leading axis S = K·N); None where not given."""

    A: np.ndarray | None = None
    C: np.ndarray | None = None
    Q: np.ndarray | None = None
    B: np.ndarray | None = None
    h: np.ndarray | None = None
    H: np.ndarray | None = None
    G: np.ndarray | None = None
    #: :math:`\Gamma_{i,jk}`, the coefficient of :math:`\nu_k` in :math:`C_{ij}` (C as given,
    #: not symmetrised), on the samples ``H_rows``
    Gamma: np.ndarray | None = None
    #: :math:`K_{ij} = \partial(h + Q)_i/\partial q_j` at the state a linearised document is
    #: linearised about (its stiffness); None for other documents
    K: np.ndarray | None = None
    H_rows: np.ndarray | None = None       # samples where H was computed (None: all)

    def need(self, name: str) -> np.ndarray:
        r"""Matrix ``name``, which the caller knows is there (the truth's A, C, Q, h and H; a
        matrix the document gives); a ``ValueError`` naming it where it is not."""
        value = getattr(self, name)
        if value is None:
            raise ValueError(f"{name} is needed here and was not evaluated")
        return value


__all__ = ["Arrays"]
