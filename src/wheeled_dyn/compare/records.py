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
from enum import StrEnum
from pathlib import Path


class Verdict(StrEnum):
    r"""Verdict of an element or of an equation. ``UNDECIDED``: the comparison cannot decide
    (values not finite at some samples, and no finite sample differs); never counted as
    agreeing. ``FACTORIZATION``: a C element that differs while :math:`C\dot q` agrees."""

    AGREES = "agrees"
    AGREES_IF = "agrees_if"
    FACTORIZATION = "factorization"
    DIFFERS = "differs"
    UNDECIDED = "undecided"


#: Verdicts of an element, in report order.
VERDICTS: tuple[str, ...] = tuple(v.value for v in Verdict)


class CauseKind(StrEnum):
    r"""Kinds of causes (what the reports group and explain)."""

    CONVENTION = "convention"          # a sign or scaling of a coordinate, velocity, input or row
    QUASI_COORDINATE_CHRISTOFFEL = "quasi_coordinate_christoffel"   # SᵀAṠ missing
    CONSTRAINT_IN_LAGRANGIAN = "constraint_in_lagrangian"
    C_INCONSISTENT_WITH_A = "c_inconsistent_with_a"
    CLAIMED_RELATION = "claimed_relation"
    UPSTREAM_STEP = "upstream_step"
    SIGN = "sign"                      # one additive term with the wrong sign
    POWER = "power"                    # a symbol to the wrong power (G for G², R for R²)
    FACTOR = "factor"                  # a constant factor
    SWAP = "swap"                      # one variable or symbol written for another
    SWAPPED_INPUTS = "swapped_inputs"  # input columns exchanged
    DIMENSION = "dimension"            # a term with inconsistent units
    MISSING_PHYSICS = "missing_physics"  # an effect the document leaves out and does not state
    POINT_MASS = "point_mass"          # a rigid body treated as a point mass
    ASSUMPTION = "assumption"          # holds only under a condition the document did not state
    ENERGY = "energy"                  # the model as printed does not conserve energy
    NOT_POSITIVE_DEFINITE = "not_positive_definite"
    NOT_EQUIVALENT = "not_equivalent"  # equations lost, repeated, or scaled by a vanishing factor
    UNDECIDED = "undecided"            # values not finite: no verdict
    FILE_ERROR = "file_error"          # the derivation file contradicts the model or itself


#: Kinds of causes (their values, in order).
CAUSE_KINDS: tuple[str, ...] = tuple(k.value for k in CauseKind)


class Step(StrEnum):
    r"""Steps of a derivation a record can belong to."""

    EQUATIONS_OF_MOTION = "equations of motion"
    VELOCITY = "velocity"
    ANGULAR_VELOCITY = "angular velocity"
    ACCELERATION = "acceleration"
    ANGULAR_ACCELERATION = "angular acceleration"
    KINETIC_ENERGY = "kinetic energy"
    POTENTIAL_ENERGY = "potential energy"
    CONSTRAINT = "constraint"
    CLAIM = "claim"
    GENERALIZED_FORCE = "generalized force"
    NEWTON_EULER = "newton-euler"
    LINEARISED_EQUATIONS = "linearised equations"
    FREQUENCY = "frequency"
    CRITICAL_SPEED = "critical speed"
    STABILITY = "stability"
    STEADY_MOTION = "steady motion"
    ORIENTATION = "orientation"
    GRAVITY = "gravity"


#: Steps (their values, in order).
STEPS: tuple[str, ...] = tuple(s.value for s in Step)


class DiagnosisKind(StrEnum):
    r"""What a diagnosis says, as data: the causes and the reports read this, never the text.

    Whole-element findings (``term`` empty) or one additive term's (``term`` set):
    ``SIGN``, ``FACTOR`` (``factor``), ``POWER``/``SWAP`` (``written`` where ``fits`` fits),
    ``MISSING``/``EXTRA`` (the document has 0 / the truth is 0; with ``terms``: the terms
    named one by one), ``POINT_MASS`` (a body's own inertia about its centre is missing),
    ``DIMENSION``; ``CONDITION`` (agrees only if ``condition``), ``FACTORIZATION`` (C differs,
    C q̇ agrees), ``UNDECIDED`` (values not finite), ``RESIDUAL`` (truth − document, as
    text), ``COINCIDENCE`` (numerically equal only because an inconsistent term vanishes
    here), ``NOT_EQUIVALENT`` (an equation that is no combination of the true ones),
    ``SINGULAR`` (equations lost, repeated, or scaled by a factor that vanishes somewhere:
    :math:`W` singular), ``NOTE`` (words only)."""

    SIGN = "sign"
    FACTOR = "factor"
    POWER = "power"
    SWAP = "swap"
    MISSING = "missing"
    EXTRA = "extra"
    POINT_MASS = "point_mass"
    DIMENSION = "dimension"
    CONDITION = "condition"
    FACTORIZATION = "factorization"
    UNDECIDED = "undecided"
    RESIDUAL = "residual"
    COINCIDENCE = "coincidence"
    NOT_EQUIVALENT = "not_equivalent"
    SINGULAR = "singular"
    NOTE = "note"


#: Diagnoses that name one term's error precisely (an element carrying one is left to its
#: single-term cause rather than to a method cause).
SPECIFIC_KINDS = frozenset({DiagnosisKind.SIGN, DiagnosisKind.FACTOR, DiagnosisKind.SWAP,
                            DiagnosisKind.POWER, DiagnosisKind.DIMENSION})


@dataclass(frozen=True)
class Diagnosis:
    r"""One finding about an element, as a record. ``text`` is the sentence the reports show
    (``"sign: the term m*g*l has the wrong sign"``); ``detail`` the part after its kind, which
    groups equal findings into one cause; the other fields carry the finding's data in the
    document's symbols (SymPy text): ``term`` the document's term concerned (empty: the
    whole element), ``factor`` the document / truth ratio, ``written``/``fits`` the symbol
    (or power, or velocity product) the document wrote and the one that fits, ``condition``
    the special values an element needs, ``terms`` terms named one by one (missing or extra),
    ``rows`` 0-based equations concerned, ``product`` the velocity or acceleration product
    whose coefficient an earlier step's finding is about (``"dx*dpsi"``)."""

    kind: DiagnosisKind
    text: str
    detail: str = ""
    term: str = ""
    factor: str = ""
    written: str = ""
    fits: str = ""
    condition: str = ""
    terms: tuple[str, ...] = ()
    rows: tuple[int, ...] = ()
    product: str = ""

    def __str__(self) -> str:
        return self.text

    def as_dict(self) -> dict[str, object]:
        out: dict[str, object] = {"kind": self.kind.value, "text": self.text}
        for name in ("term", "factor", "written", "fits", "condition", "product"):
            if getattr(self, name):
                out[name] = getattr(self, name)
        if self.terms:
            out["terms"] = list(self.terms)
        return out


def diagnosis(kind: DiagnosisKind, detail: str, prefix: str | None = None, **data) -> Diagnosis:
    r"""A :class:`Diagnosis` whose text is ``"<prefix>: <detail>"`` (the prefix defaults to the
    kind's value; ``prefix=""``: the detail alone)."""
    head = kind.value if prefix is None else prefix
    return Diagnosis(kind, f"{head}: {detail}" if head else detail, detail, **data)


def in_product(product: str, inner: Diagnosis) -> Diagnosis:
    r"""``inner`` about the coefficient of the velocity or acceleration ``product`` of an
    earlier step: ``"term dx*dpsi: missing: the document has 0"``."""
    from dataclasses import replace
    return replace(inner, text=f"term {product}: {inner.text}", product=product)


def has_kind(diagnoses, *kinds: DiagnosisKind) -> bool:
    r"""Whether any of ``diagnoses`` is of one of ``kinds``."""
    return any(d.kind in kinds for d in diagnoses)


def first_of(diagnoses, *kinds: DiagnosisKind) -> Diagnosis | None:
    r"""The first of ``diagnoses`` of one of ``kinds``, or None."""
    return next((d for d in diagnoses if d.kind in kinds), None)


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

    @property
    def equivalent(self) -> bool | None:
        r"""Whether the document's equations have the truth's solutions (every equation
        agrees, W invertible); None when no equation was decided (a file of steps) or one is
        undecided."""
        if not self.equations or any(e.verdict == Verdict.UNDECIDED for e in self.equations):
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
                "equations": [e.as_dict() for e in self.equations],
                "equivalent": self.equivalent,
                "truth_in_document": self.truth_in_document,
                "energy": self.energy.as_dict() if self.energy else None,
                "asymmetric": list(self.asymmetric), "constraints": list(self.constraints),
                "reconstructed": dict(self.reconstructed), "samples": self.samples,
                "parameter_sets": self.parameter_sets, "notes": list(self.notes),
                "latex_input": {k: {"latex": a, "read_as": b}
                                for k, (a, b) in self.latex_input.items()},
                "records": [r.as_dict() for r in self.records]}
