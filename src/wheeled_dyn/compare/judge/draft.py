r"""The working record of one element while it is judged: mutable, with its numbers on both
sides, frozen into an :class:`~..records.ElementRecord` at the end."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from ..records import Diagnosis, ElementRecord, Step, Verdict


@dataclass
class ElementDraft:
    r"""One element being judged: its label, ``key`` (A, C, Q, B, h), 0-based ``index``,
    verdict and diagnoses so far, what the reports print, and its values: ``D`` the
    document's, ``T`` the truth's in the row's frame, on the same samples; ``expr`` the
    document's expression (None where it has none)."""

    element: str
    key: str
    index: tuple[int, ...]
    verdict: Verdict
    diagnoses: list[Diagnosis]
    D: np.ndarray
    T: np.ndarray
    scale: float
    expr: sp.Expr | None = None
    document: str = ""
    document_latex: str = ""
    document_model: str = ""
    model_latex: str = ""
    truth: str | None = None
    truth_latex: str = ""
    residual: str | None = None
    residual_latex: str = ""
    equation: str = ""
    step: Step = Step.EQUATIONS_OF_MOTION
    notes: list[str] = field(default_factory=list)
    #: the truth's own round-off in the element's row (:func:`~.precision.row_round_off`): a
    #: difference no larger is not decided
    round_off: float = 0.0

    @property
    def row(self) -> int:
        return self.index[0]

    def freeze(self) -> ElementRecord:
        with np.errstate(all="ignore"):
            finite = np.isfinite(self.D) & np.isfinite(self.T)
            error = float(np.abs(self.D - self.T)[finite].max(initial=0.0)) if finite.any() \
                else float("nan")
        return ElementRecord(
            element=self.element, key=self.key, index=self.index, verdict=self.verdict,
            diagnoses=tuple(self.diagnoses), document=self.document,
            document_model=self.document_model, truth=self.truth, residual=self.residual,
            max_error=error, scale=float(self.scale), document_latex=self.document_latex,
            model_latex=self.model_latex, truth_latex=self.truth_latex,
            truth_sample=float(self.T[0]) if len(self.T) else float("nan"),
            document_sample=float(self.D[0]) if len(self.D) else float("nan"),
            step=self.step, equation=self.equation, residual_latex=self.residual_latex)


__all__ = ["ElementDraft"]
