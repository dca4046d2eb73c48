r"""One finding about an element, as a record (:class:`Diagnosis`), and the few functions
that make and read such records by their kind, never by their text."""

from __future__ import annotations

from dataclasses import dataclass

from .kinds import DiagnosisKind


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
    whose coefficient an earlier step's finding is about (``"dx*dpsi"``), ``position`` the
    coordinate a small-angle approximation is made in."""

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
    position: str = ""

    def __str__(self) -> str:
        return self.text

    def as_dict(self) -> dict[str, object]:
        out: dict[str, object] = {"kind": self.kind.value, "text": self.text}
        for name in ("term", "factor", "written", "fits", "condition", "product", "position"):
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
