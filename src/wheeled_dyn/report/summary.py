r"""What every report shows first: the derivations in the document's own order, each with its
verdict counts and its causes in one line each.

Order
    A derivation's place is, in turn: the ``order`` its result carries, an ``order`` its file
    declares in ``[source]`` (a number, as text), the section number (``4.3.3`` → (4, 3, 3)), the
    first equation number (``(3.12)`` → (3, 12)), the file name. So seed 001 reads (1)–(3),
    (4)–(5), (6)–(8), (9)–(11), (12)–(14), (25), (33)–(35), the appendix — as the document does.

Causes
    The result's own root causes (:class:`~wheeled_dyn.compare.records.Cause`), most important
    first; then the elements no cause explains (all of them when none was computed), grouped by
    their first diagnosis — one line per distinct diagnosis, naming the elements — so a reader
    sees a few reasons, not a list of names; then the causes found in earlier steps.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from ..compare.records import (Diagnosis, DiagnosisKind as K, DerivationResult, ElementRecord,
                               Verdict)
from ..derivations.schema import equation_labels

#: Words for the cause kinds of :data:`wheeled_dyn.compare.records.CAUSE_KINDS`.
KIND_TEXT = {
    "convention": "convention", "quasi_coordinate_christoffel": "quasi-coordinate Christoffel",
    "constraint_in_lagrangian": "constraint substituted into the Lagrangian",
    "c_inconsistent_with_a": "C not consistent with the document's own A",
    "claimed_relation": "claimed relation is wrong", "upstream_step": "an earlier step",
    "sign": "sign", "power": "power", "factor": "factor", "swap": "swapped symbol",
    "small_angle": "small-angle approximation",
    "swapped_inputs": "swapped inputs", "dimension": "units", "missing_physics": "missing physics",
    "extra_term": "extra term",
    "assumption": "holds only if", "energy": "energy", "not_positive_definite":
    "A not positive definite", "file_error": "error of the derivation file",
    # kinds of the grouping by diagnosis
    "extra": "extra term", "missing": "missing term", "factorization": "factorisation of C only",
    "differs": "differs", "point_mass": "a point mass",
    "parallel_axis": "parallel-axis term missing", "not_equivalent": "not equivalent",
    "undecided": "undecided",
}
#: Verdicts that are shown as findings (everything but "agrees").
SHOWN_VERDICTS = ("differs", "factorization", "agrees_if", "undecided")
#: Elements named in one summary line before "+N".
NAMED_IN_LINE = 4


@dataclass(frozen=True)
class CauseLine:
    r"""One reason as the reports show it: ``kind`` (a key of :data:`KIND_TEXT`), the
    ``elements`` it explains, a sentence, optional LaTeX; ``computed``: from the result's
    causes (True) or from grouping the elements by diagnosis (False)."""

    kind: str
    elements: tuple[str, ...]
    text: str
    latex: str = ""
    computed: bool = True

    def one_line(self, label: Callable[[str], str] = str) -> str:
        r"""``kind: sentence — A[1,1], A[1,3] +2``; ``label`` writes an element's name."""
        named = ", ".join(label(e) for e in self.elements[:NAMED_IN_LINE])
        more = len(self.elements) - NAMED_IN_LINE
        where = f" — {named}" + (f" +{more}" if more > 0 else "") if self.elements else ""
        kind = KIND_TEXT.get(self.kind, self.kind.replace("_", " "))
        text = self.text if not self.text.lower().startswith(kind.lower()) else self.text[len(kind):].lstrip(": ")
        return f"{kind}: {text}{where}"


def _numbers(text: str) -> tuple[int, ...]:
    m = re.search(r"\d+(?:\.\d+)*", text or "")
    return tuple(int(x) for x in m.group(0).split(".")) if m else ()


def order_key(result: DerivationResult) -> tuple:
    r"""Sort key: the document's own order (see the module text)."""
    src = result.source
    declared = tuple(result.order) if result.order else (
        tuple(float(x) for x in re.findall(r"-?\d+(?:\.\d+)?", str(src.get("order", "")))))
    section = _numbers(str(src.get("section", "")))
    equation = _numbers(str(src.get("equations", "")))
    return (0 if declared else 1, declared, section or (10 ** 6,), equation or (10 ** 6,),
            result.path.name)


def ordered(results: Sequence[DerivationResult]) -> list[DerivationResult]:
    r"""``results`` in the document's own order."""
    return sorted(results, key=order_key)


def anchor(result: DerivationResult) -> str:
    r"""The id of a derivation's section: ``d-`` and the file's stem."""
    return "d-" + re.sub(r"[^A-Za-z0-9_-]", "-", result.path.stem)


def element_anchor(result: DerivationResult, element: str) -> str:
    r"""The id of one element's entry: ``A[2,1]`` → ``d-eq25_lagrange-A-2-1``."""
    return anchor(result) + "-" + "-".join(x for x in re.split(r"[^A-Za-z0-9_]+", element) if x)


def equations(result: DerivationResult) -> str:
    r"""The document and equations, short: ``seed 001 §4.3.3 (25)``."""
    src = result.source
    section = str(src.get("section", "")).strip()
    eq = equation_labels(str(src.get("equations", "")))
    parts = [str(src.get("document", "")).strip(), f"§{section}" if section and
             section[0].isdigit() else section, eq]
    return " ".join(p for p in parts if p)



def _diagnosis_kind(record: ElementRecord, diagnosis: Diagnosis | None) -> str:
    if record.verdict == "agrees_if":
        return "assumption"
    if record.verdict == "factorization":
        return "factorization"
    if record.verdict == "undecided":
        return "undecided"
    if diagnosis is None:
        return "differs"
    return {K.MISSING: "missing", K.EXTRA: "extra", K.DIMENSION: "dimension", K.SIGN: "sign",
            K.FACTOR: "factor", K.SWAP: "swap", K.POWER: "power",
            K.SMALL_ANGLE: "small_angle",
            K.POINT_MASS: "point_mass", K.PARALLEL_AXIS: "parallel_axis"
            }.get(diagnosis.kind, "differs")


def condition(record: ElementRecord) -> str:
    r"""The condition under which an "agrees only if" element agrees (its first such
    diagnosis), or its first diagnosis."""
    first = _first_diagnosis(record)
    if record.verdict == "agrees_if":
        return _group_sentence("assumption", first, record)
    return first.text if first is not None else _no_diagnosis(record)


def _no_diagnosis(record: ElementRecord) -> str:
    return {"differs": "no single-term diagnosis",
            "undecided": "cannot decide"}.get(record.verdict, record.verdict.value)


def _group_sentence(kind: str, diagnosis: Diagnosis | None, record: ElementRecord) -> str:
    if kind == "factorization":
        return ("only the factorisation of C differs; the C q̇ terms they make agree or "
                "differ only where said")
    if diagnosis is None:
        return _no_diagnosis(record)
    if kind == "assumption":
        return diagnosis.condition or diagnosis.detail or diagnosis.text
    if kind == "differs":
        return diagnosis.text
    return diagnosis.detail or diagnosis.text


def _first_diagnosis(record: ElementRecord) -> Diagnosis | None:
    useful = [d for d in record.diagnoses if d.kind != K.RESIDUAL]
    if record.verdict == "agrees_if":
        useful = [d for d in useful if d.kind == K.CONDITION] or useful
    return useful[0] if useful else None


#: Order of the grouped kinds: typos, then physics, factorisation, conditions.
_GROUP_ORDER = ("dimension", "sign", "power", "factor", "swap", "small_angle", "point_mass",
                "parallel_axis", "missing", "extra", "differs",
                "factorization", "assumption", "undecided")


def cause_lines(result: DerivationResult) -> list[CauseLine]:
    r"""The causes of a derivation, most important first (see the module text): the computed
    root causes, then the findings no cause explains grouped by diagnosis, then the causes
    found in earlier steps of the derivation (``upstream_step``)."""
    causes = [CauseLine(c.kind, tuple(c.elements), c.explanation, c.latex) for c in result.causes]
    upstream = [c for c in causes if c.kind == "upstream_step"]
    root = [c for c in causes if c.kind != "upstream_step"]
    explained = {e for c in causes for e in c.elements}
    groups: dict[tuple[str, str], list[str]] = {}
    for r in result.records:
        if r.verdict not in SHOWN_VERDICTS or r.element in explained:
            continue
        first = _first_diagnosis(r)
        kind = _diagnosis_kind(r, first)
        groups.setdefault((kind, _group_sentence(kind, first, r)), []).append(r.element)
    rank = {k: i for i, k in enumerate(_GROUP_ORDER)}
    keys = sorted(groups, key=lambda k: (rank.get(k[0], len(rank)), -len(groups[k])))
    grouped = [CauseLine(k, tuple(groups[(k, s)]), s, computed=False) for k, s in keys]
    return root + grouped + upstream


def equations_line(result: DerivationResult) -> str:
    r"""The equations as a whole, decided by their equivalence to the true ones: whether the
    document's system is right, then each equation's verdict and the frame its elements are
    compared in (``""`` where no equation was decided: a file of steps, a published
    linearisation)."""
    if not result.equations:
        return ""
    whole = {True: "right as a system (the same motions as the true equations)",
             False: "not right as a system", None: "not decided"}[result.equivalent]
    parts = []
    for e in result.equations:
        verdict = VERDICT_WORDS.get(e.verdict.value, e.verdict.value)
        frame = "" if e.frame == "the true equation" else f" ({e.frame})"
        parts.append(f"{e.label} {verdict}{frame}")
    if result.constraints_agree is False:
        parts.append("its constraints are not the model's rolling constraints")
    if result.state_rates_agree is False:
        parts.append("in its state-space form, " + "; ".join(result.state_rates))
    return f"{whole}: " + "; ".join(parts)


def system_word(result: DerivationResult) -> str:
    r"""``"not right as a system"`` where the equations are decided not equivalent to the true
    ones (also when every element agrees: an equation multiplied by a factor that vanishes,
    lost, repeated; its constraints not the model's), ``"not decided as a system"`` where an
    equation is undecided (every element may agree: a combination whose parts differ in size
    beyond the tolerance), else ``""``."""
    if not result.equations:
        return ""
    return {False: "not right as a system", None: "not decided as a system"}.get(
        result.equivalent, "")


#: Words for an equation's verdict.
VERDICT_WORDS = {"agrees": "agrees", "agrees_if": "agrees only for special values",
                 "differs": "differs", "undecided": "undecided"}


def conventions_line(result: DerivationResult) -> str:
    r"""The conventions sentence: the file's reading kept (nothing explains more), or the
    better reading found with the verdict counts under both; ``""`` for a file of steps."""
    conv = result.conventions
    if conv is None:
        return ""
    if conv.best is None:
        return ("as the file declares them (no other sign of its coordinates or inputs, order "
                "of its inputs or of its equations explains more)")

    def counts(c) -> str:
        return ", ".join(f"{n} {v}" for v, n in c.counts.items() if n)

    return (f"{conv.finding}. Under the file's own reading: {counts(conv.declared)}; under "
            f"{conv.best.description}: {counts(conv.best)}")


def row_factor_line(result: DerivationResult) -> str:
    r"""A sentence on the rows the document multiplied by a constant, or ``""``: "the same
    equations" for the rows that are right; a row that differs is said only to be compared
    in that frame (the factor under which most of its elements agree: a position's sign
    reversed makes the row's odd terms agree times −1, not the row)."""
    wrong = {i for i, e in enumerate(result.equations) if e.verdict != Verdict.AGREES}
    shown = [(i + 1, c) for i, c in enumerate(result.row_factors) if c and i in wrong]
    rows = [(i + 1, c) for i, c in enumerate(result.row_factors) if c and i not in wrong]
    framed = "; ".join(f"row {i} is compared with {c} × the equations of motion, the factor "
                       "under which most of its elements agree (the row differs)"
                       for i, c in shown)
    if not rows:
        return framed
    said = _right_rows(rows)
    return f"{said}; {framed}" if framed else said


def _right_rows(rows: list[tuple[int, str]]) -> str:
    factors = {c for _, c in rows}
    which = ", ".join(str(i) for i, _ in rows)
    if len(factors) == 1:
        c = rows[0][1]
        rows_are = f"rows {which} of the document are" if len(rows) > 1 else \
            f"row {which} of the document is"
        return (f"{rows_are} {c} × the equations of motion (a factor the file does not "
                f"declare; the same equations): the truth is compared multiplied by {c}, the "
                "document as printed")
    return ("rows of the document are multiplied by constants the file does not declare ("
            + ", ".join(f"row {i}: {c}" for i, c in rows) + "; the same equations): the "
            "truth is compared multiplied by them, the document as printed")


def assumes_line(result: DerivationResult, file_assumptions: dict[str, str] | None = None) -> str:
    r"""The "assumes:" line: the result's ``assumes``, and the terms the file sets to a value
    (``[assume]``: said always, a value other than 0 as much as 0), or a sentence saying
    none are declared."""
    sets = ("the file sets " + ", ".join(f"{k} = {v}" for k, v in file_assumptions.items())
            + " (terms the model lacks)") if file_assumptions else ""
    if result.assumes:
        return "; ".join((*result.assumes, *([sets] if sets else [])))
    if sets:
        return sets + "; no other assumption is declared"
    return "nothing declared by the file"


def summary_entry(result: DerivationResult) -> dict[str, object]:
    r"""The summary of one derivation for the JSON report (also the order of the report)."""
    return {"id": anchor(result), "path": str(result.path), "title": result.title,
            "equations": equations(result), "counts": result.counts(),
            "causes": [c.one_line() for c in cause_lines(result)],
            "row_factors": row_factor_line(result),
            "causes_computed": bool(result.causes), "assumes": list(result.assumes)}
