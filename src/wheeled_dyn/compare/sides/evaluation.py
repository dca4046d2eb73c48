r"""The numbers one comparison was decided on: the engine's working state, handed to the
readings and the causes."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from ..grid.arrays import Arrays
from .document import DocumentFunctions


@dataclass
class Evaluation:
    r"""The numbers one comparison was decided on (the engine's working state): the document's
    compiled functions and arrays (as printed), the truth, the truth's
    B in the document's inputs, the row scales, the flat samples and symbol values, the row
    factors, and the kind of the coordinate set (``holonomic`` or ``quasi``)."""

    funcs: DocumentFunctions
    doc: Arrays
    truth: Arrays
    B_true: np.ndarray | None
    scales: np.ndarray
    q: np.ndarray
    nu: np.ndarray
    values: Mapping[sp.Symbol, np.ndarray]
    row_factor: Sequence[float | None]
    kind: str


__all__ = ["Evaluation"]
