r"""What a comparison says about one derivation, as frozen, picklable records.

The data flow of :mod:`wheeled_dyn.compare` is one way:

.. code-block:: text

    derivation → evaluation (truth and document on the same samples) → element records
               → causes (the few reasons that explain the records) → DerivationResult

- :class:`ElementRecord`: one element of A, C, Q, B, G or one velocity product of
  :math:`h = C\dot q`, or one component of an earlier step of the derivation (a velocity, an
  energy, a constraint, a claim), with its verdict and diagnoses.
- :class:`Cause`: one reason, named by its ``kind`` (:data:`CAUSE_KINDS`), the elements it
  explains and one sentence in the document's own symbols. A cause is reported once, however
  many elements (C-level and h-level) it explains.
- :class:`ConventionSummary`: the verdict counts under the convention the file declares and
  under the best one found (sign flips and scalings of coordinates, velocities and inputs,
  permutations of inputs, row scalings, half vs full track).
- :class:`DerivationResult`: everything the reports (Markdown, HTML, JSON) show of one
  derivation. ``as_dict`` is the JSON contract documented in ``docs/report-schema.json``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

#: Verdicts of an element. ``undecided``: the comparison cannot decide (the document's or the
#: truth's values are not finite at some samples); never counted as agreeing.
VERDICTS: tuple[str, ...] = ("agrees", "agrees_if", "factorization", "differs", "undecided")

#: Kinds of causes.
CAUSE_KINDS: tuple[str, ...] = (
    "convention",                    # a sign or scaling of a coordinate, velocity, input or row
    "quasi_coordinate_christoffel",  # Christoffel formula applied to quasi-velocities (SᵀAṠ missing)
    "constraint_in_lagrangian",      # nonholonomic constraint substituted into the Lagrangian
    "c_inconsistent_with_a",         # the document's C is not the Christoffel matrix of its own A
    "claimed_relation",              # a relation the document states is wrong
    "upstream_step",                 # an earlier step (velocity, energy ...) explains the difference
    "sign",                          # one additive term with the wrong sign
    "power",                         # a symbol to the wrong power (G for G², R for R²)
    "factor",                        # a constant factor
    "swap",                          # one variable or symbol written for another
    "swapped_inputs",                # input columns exchanged
    "dimension",                     # a term with inconsistent units
    "missing_physics",               # an effect the document leaves out and does not state
    "assumption",                    # holds only under a condition the document did not state
    "energy",                        # the model as printed does not conserve energy
    "not_positive_definite",         # the document's A is singular or indefinite
    "file_error",                    # the derivation file contradicts the model (e.g. its map)
)

#: Steps of a derivation a record can belong to.
STEPS: tuple[str, ...] = ("equations of motion", "velocity", "angular velocity", "acceleration",
                          "angular acceleration", "kinetic energy", "potential energy",
                          "constraint", "claim", "generalized force", "newton-euler",
                          "linearised equations", "frequency", "critical speed", "stability",
                          "steady motion", "orientation", "gravity")


@dataclass(frozen=True)
class ElementRecord:
    r"""One element's comparison. ``element`` is labelled as documents do (1-based):
    ``A[2,1]``, ``C[3,2]``, ``Q[3]``, ``B[1,2]``, ``h[1]:dpsi*dpsi``. ``step`` is the step of
    the derivation it belongs to (:data:`STEPS`), ``equation`` the document's label of the
    equation it comes from, as printed (``"(25)"``), or ``""``."""

    element: str
    key: str
    index: tuple[int, ...]
    verdict: str
    diagnoses: tuple[str, ...]
    document: str
    document_model: str
    truth: str | None
    residual: str | None
    max_error: float
    scale: float
    document_latex: str = ""
    model_latex: str = ""
    truth_latex: str = ""
    truth_sample: float = float("nan")      # the truth at the first sample (reference state)
    document_sample: float = float("nan")
    step: str = "equations of motion"
    equation: str = ""
    residual_latex: str = ""

    def as_dict(self) -> dict[str, object]:
        return {"element": self.element, "verdict": self.verdict, "diagnoses": list(self.diagnoses),
                "step": self.step, "equation": self.equation,
                "document": self.document, "document_model": self.document_model,
                "truth": self.truth, "residual": self.residual, "max_error": self.max_error,
                "scale": self.scale, "truth_at_reference": self.truth_sample,
                "document_at_reference": self.document_sample}


@dataclass(frozen=True)
class EnergyCheck:
    r"""The power identity of the document on its own."""

    conserves: bool
    max_power: float
    residual: str

    def as_dict(self) -> dict[str, object]:
        return {"conserves": self.conserves, "max_power": self.max_power, "residual": self.residual}


@dataclass(frozen=True)
class Cause:
    r"""One reason behind differences: ``kind`` (:data:`CAUSE_KINDS`), the labels of the
    ``elements`` it explains, one sentence in the document's symbols, optional math
    (``latex``: e.g. the missing terms in closed form), the ``step`` and document ``equation``
    where it enters."""

    kind: str
    elements: tuple[str, ...]
    explanation: str
    latex: str = ""
    step: str = "equations of motion"
    equation: str = ""

    def as_dict(self) -> dict[str, object]:
        return {"kind": self.kind, "elements": list(self.elements),
                "explanation": self.explanation, "latex": self.latex, "step": self.step,
                "equation": self.equation}


@dataclass(frozen=True)
class Convention:
    r"""A reading of the document: ``description`` ("as declared", or e.g. "x → −x, u → −u"),
    and the verdict counts under it."""

    description: str
    counts: Mapping[str, int]

    def as_dict(self) -> dict[str, object]:
        return {"description": self.description, "counts": dict(self.counts)}


@dataclass(frozen=True)
class ConventionSummary:
    r"""The declared convention and the best one found (None when the declared one is best);
    ``finding``: a sentence when the declared convention is worse than an available one."""

    declared: Convention
    best: Convention | None = None
    finding: str = ""

    def as_dict(self) -> dict[str, object]:
        return {"declared": self.declared.as_dict(),
                "best": None if self.best is None else self.best.as_dict(),
                "finding": self.finding}


@dataclass(frozen=True)
class DerivationResult:
    r"""Everything the reports show of one derivation. ``assumes``: what the document assumes
    (stated once, in words); ``causes``: the reasons, most important first; ``order``: where
    the derivation stands in its document (sort key of the reports)."""

    path: Path
    title: str
    model: str
    source: Mapping[str, str]
    coordinates: str
    velocities: tuple[str, ...]
    form: str
    records: tuple[ElementRecord, ...]
    row_factors: tuple[str | None, ...]
    energy: EnergyCheck | None
    asymmetric: tuple[str, ...]
    constraints: tuple[str, ...]
    reconstructed: Mapping[str, str]
    samples: int
    parameter_sets: int
    notes: tuple[str, ...] = field(default=())
    assumes: tuple[str, ...] = field(default=())
    causes: tuple[Cause, ...] = field(default=())
    conventions: ConventionSummary | None = None
    order: tuple = field(default=())
    #: values the file gives as LaTeX: item → (the LaTeX as written, the text it was read as)
    latex_input: Mapping[str, tuple[str, str]] = field(default_factory=dict)
    #: per equation, the function of the state or parameters the document multiplied it by,
    #: found by the comparison (:mod:`.row_functions`; SymPy text), None where none
    row_functions: tuple[str | None, ...] = field(default=())
    #: the combination of the true equations the document's are, found by the comparison
    #: (:mod:`.row_combinations`; rows of SymPy text), () where none
    row_combination: tuple[tuple[str, ...], ...] = field(default=())

    def counts(self) -> dict[str, int]:
        out = {v: 0 for v in VERDICTS}
        for r in self.records:
            out[r.verdict] += 1
        return out

    def typos(self) -> list[ElementRecord]:
        keys = ("sign:", "factor:", "swap:", "dimension")
        return [r for r in self.records if r.verdict == "differs"
                and any(d.startswith(keys) for d in r.diagnoses)]

    def missing(self) -> list[ElementRecord]:
        typo = {id(r) for r in self.typos()}
        return [r for r in self.records if r.verdict == "differs" and id(r) not in typo]

    def _repr_pretty_(self, printer, cycle: bool) -> None:
        r"""In IPython, as text: the file and its verdict counts (the HTML form shows the rest)."""
        counts = ", ".join(f"{n} {v}" for v, n in self.counts().items() if n)
        printer.text(f"<DerivationResult {self.path.name}: {counts or 'no records'}>")

    def _repr_html_(self) -> str:
        r"""In a notebook: the report's section of this result (causes first, then document
        | truth side by side; :func:`wheeled_dyn.report.notebook.result_html`)."""
        from ..report.notebook import result_html       # the renderer imports this module
        return result_html(self)

    def as_dict(self) -> dict[str, object]:
        return {"path": str(self.path), "title": self.title, "model": self.model,
                "source": dict(self.source), "coordinates": self.coordinates,
                "velocities": list(self.velocities), "form": self.form,
                "assumes": list(self.assumes),
                "conventions": None if self.conventions is None else self.conventions.as_dict(),
                "causes": [c.as_dict() for c in self.causes],
                "counts": self.counts(), "row_factors": list(self.row_factors),
                "row_functions": list(self.row_functions),
                "row_combination": [list(r) for r in self.row_combination],
                "energy": self.energy.as_dict() if self.energy else None,
                "asymmetric": list(self.asymmetric), "constraints": list(self.constraints),
                "reconstructed": dict(self.reconstructed), "samples": self.samples,
                "parameter_sets": self.parameter_sets, "notes": list(self.notes),
                "latex_input": {k: {"latex": a, "read_as": b}
                                for k, (a, b) in self.latex_input.items()},
                "records": [r.as_dict() for r in self.records]}
