r"""The records of a comparison: one element's (:class:`ElementRecord`), one equation's as a
whole (:class:`EquationRecord`), one cause's (:class:`Cause`), the conventions tried
(:class:`ConventionSummary`) and one derivation's (:class:`DerivationResult`), whose
``as_dict`` is the JSON contract documented in ``docs/report-schema.json``."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from .diagnosis import Diagnosis, has_kind
from .kinds import VERDICTS, CauseKind, DiagnosisKind, Step, Verdict


@dataclass(frozen=True)
class ElementRecord:
    r"""One element's comparison. ``element`` is labelled as documents do (1-based):
    ``A[2,1]``, ``C[3,2]``, ``Q[3]``, ``B[1,2]``, ``h[1]:dpsi*dpsi``. ``step`` is the step of
    the derivation it belongs to (:data:`STEPS`), ``equation`` the document's label of the
    equation it comes from, as printed (``"(25)"``), or ``""``."""

    element: str
    key: str
    index: tuple[int, ...]
    verdict: Verdict
    diagnoses: tuple[Diagnosis, ...]
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
    step: Step = Step.EQUATIONS_OF_MOTION
    equation: str = ""
    residual_latex: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "verdict", Verdict(self.verdict))
        object.__setattr__(self, "step", Step(self.step))
        object.__setattr__(self, "diagnoses", tuple(self.diagnoses))
        for d in self.diagnoses:
            if not isinstance(d, Diagnosis):
                raise TypeError(f"{self.element}: a diagnosis is a Diagnosis record, not {d!r}")

    @property
    def texts(self) -> tuple[str, ...]:
        r"""The diagnoses as the reports print them."""
        return tuple(d.text for d in self.diagnoses)

    @property
    def kinds(self) -> tuple[DiagnosisKind, ...]:
        r"""The kinds of the diagnoses, in order."""
        return tuple(d.kind for d in self.diagnoses)

    def as_dict(self) -> dict[str, object]:
        return {"element": self.element, "verdict": self.verdict.value,
                "diagnoses": [d.text for d in self.diagnoses],
                "findings": [d.as_dict() for d in self.diagnoses],
                "step": self.step.value, "equation": self.equation,
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

    kind: CauseKind
    elements: tuple[str, ...]
    explanation: str
    latex: str = ""
    step: Step = Step.EQUATIONS_OF_MOTION
    equation: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", CauseKind(self.kind))
        object.__setattr__(self, "step", Step(self.step))

    def as_dict(self) -> dict[str, object]:
        return {"kind": self.kind.value, "elements": list(self.elements),
                "explanation": self.explanation, "latex": self.latex, "step": self.step.value,
                "equation": self.equation}


@dataclass(frozen=True)
class EquationRecord:
    r"""One of the document's equations as a whole, decided by equivalence: it is right when
    its row :math:`[A_{doc,i} \mid n_{doc,i} \mid B_{doc,i}]` is :math:`w_i[A \mid n \mid B]`
    of the truth at every sample, :math:`w_i = A_{doc,i}A^{-1}`, and the document's system is
    right when every equation is and :math:`W = (w_i)` is invertible (no equation lost or
    repeated). ``index`` is 0-based; ``frame`` says, in words, which combination of the true
    equations the document's is (``"the true equation"``, ``"-1 × the true equation"``,
    ``"divided by m*l"``, ``"solved for the accelerations"`` ...), the frame its elements are
    compared in; ``max_error`` the largest residual relative to the row's size;
    ``corrected``, ``corrected_latex``: an equation that differs as it should read, in the
    document's symbols and frame (empty where the closed forms cannot write it)."""

    index: int
    label: str
    verdict: Verdict
    diagnoses: tuple[Diagnosis, ...]
    frame: str
    max_error: float
    equation: str = ""
    corrected: str = ""
    corrected_latex: str = ""

    @property
    def texts(self) -> tuple[str, ...]:
        r"""The diagnoses as the reports print them."""
        return tuple(d.text for d in self.diagnoses)

    def as_dict(self) -> dict[str, object]:
        return {"equation": self.label, "verdict": self.verdict.value,
                "diagnoses": [d.text for d in self.diagnoses],
                "findings": [d.as_dict() for d in self.diagnoses], "frame": self.frame,
                "max_error": self.max_error, "label": self.equation,
                "corrected": self.corrected, "corrected_latex": self.corrected_latex}


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
    #: the document's equations as a whole, decided by equivalence (:class:`EquationRecord`)
    equations: tuple[EquationRecord, ...] = field(default=())
    #: the truths of the records are written in the document's own symbols (solved from its
    #: declarations); else in the model's parameters
    truth_in_document: bool = False
    #: whether a form that keeps the rolling constraints states them as the model's (its
    #: constraint rows span the true ones: none wrong, none missing); None where neither side
    #: keeps them
    constraints_agree: bool | None = None
    #: what the model reads otherwise than its URDF writes (:mod:`wheeled_dyn.models.readings`)
    model_readings: tuple[str, ...] = field(default=())
    #: a state-space form's rows whose rate of a position is not its velocity, as the reports
    #: say them, and whether every such row is the velocity (None where the file has none)
    state_rates: tuple[str, ...] = field(default=())
    state_rates_agree: bool | None = None

    @property
    def equivalent(self) -> bool | None:
        r"""Whether the document's equations have the truth's solutions (every equation
        agrees, W invertible, the constraints it keeps are the model's); None when no equation
        was decided (a file of steps), or one is undecided and none differs (one equation
        that differs makes the system wrong, whatever the others)."""
        if not self.equations:
            return None
        if self.constraints_agree is False or self.state_rates_agree is False:
            return False                            # whatever the equations: not the motions
        if any(e.verdict == Verdict.DIFFERS for e in self.equations):
            return False
        if any(e.verdict == Verdict.UNDECIDED for e in self.equations):
            return None
        return all(e.verdict == Verdict.AGREES for e in self.equations)

    def counts(self) -> dict[str, int]:
        out = {v: 0 for v in VERDICTS}
        for r in self.records:
            out[r.verdict] += 1
        return out

    def typos(self) -> list[ElementRecord]:
        kinds = (DiagnosisKind.SIGN, DiagnosisKind.FACTOR, DiagnosisKind.SWAP,
                 DiagnosisKind.POWER, DiagnosisKind.DIMENSION)
        return [r for r in self.records if r.verdict == Verdict.DIFFERS
                and has_kind(r.diagnoses, *kinds)]

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
        from ...report.notebook import result_html       # the renderer imports this module
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
                "equations": [e.as_dict() for e in self.equations],
                "equivalent": self.equivalent,
                "constraints_agree": self.constraints_agree,
                "state_rates": list(self.state_rates),
                "state_rates_agree": self.state_rates_agree,
                "truth_in_document": self.truth_in_document,
                "energy": self.energy.as_dict() if self.energy else None,
                "asymmetric": list(self.asymmetric), "constraints": list(self.constraints),
                "reconstructed": dict(self.reconstructed), "samples": self.samples,
                "parameter_sets": self.parameter_sets, "notes": list(self.notes),
                "model_readings": list(self.model_readings),
                "latex_input": {k: {"latex": a, "read_as": b}
                                for k, (a, b) in self.latex_input.items()},
                "records": [r.as_dict() for r in self.records]}
