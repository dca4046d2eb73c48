r""""Agrees only if": the smallest combination of the model's special parameter families
(products of inertia zero, a centre of mass on an axis, disc wheels ...) the document did not
declare under which a differing element agrees.

The engine evaluates both sides on a small grid of each combination's parameter sets (a
callback, :data:`Agreeing`: which elements agree there); this module only searches: the first
single family that suffices (weakest first), else a greedy minimal combination. An element
that no family makes agree but that is a constant factor of the truth under the weakest family
that gives one says so ("factor: ... (if ...)"); two velocity products of one row of h that are
each other's truth under a family are a swap "equal only if" it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

import numpy as np

from ..grid.samples import SpecialCase
from ..records import Diagnosis, DiagnosisKind as K, Verdict, diagnosis, first_of, has_kind
from .diagnose import agrees, value_diagnoses
from .draft import ElementDraft

#: Which elements agree on a combination's grid: ``("ok", key, index)``,
#: ``("factor", key, index, diagnosis)``, ``("swap", a, b)`` (h indices).
Agreeing = Callable[[tuple[SpecialCase, ...]], set]


def items(elements: Iterable[tuple[str, tuple[int, ...], np.ndarray, np.ndarray, float]]) -> set:
    r"""The :data:`Agreeing` items of ``(key, index, D, T, scale)`` on one grid."""
    ok: set = set()
    h_values = {}
    for key, index, D, T, scale in elements:
        if agrees(D, T, scale):
            ok.add(("ok", key, index))
        else:                                # a constant factor that holds only here
            found = value_diagnoses(D, T, scale)
            if found and found[0].kind == K.FACTOR:
                ok.add(("factor", key, index, found[0]))
        if key == "h":
            h_values[index] = (D, T, scale)
    for a, (Da, Ta, sa) in h_values.items():
        for b, (Db, Tb, _) in h_values.items():
            if a != b and a[0] == b[0] and agrees(Da, Tb, sa) and not agrees(Da, Ta, sa) \
                    and not agrees(Da, 0 * Da, sa):
                ok.add(("swap", a, b))
    return ok


def _searchable(d: ElementDraft) -> bool:
    return d.verdict == Verdict.DIFFERS and not has_kind(
        d.diagnoses, K.DIMENSION, K.SIGN, K.FACTOR, K.SWAP, K.SMALL_ANGLE, K.UNDECIDED)


def search(cases: Sequence[SpecialCase], drafts: Sequence[ElementDraft],
           agreeing: Agreeing) -> None:
    r"""Mark the drafts that agree under undeclared ``cases`` (module text), in place."""
    todo = [r for r in drafts if _searchable(r)]
    if not cases or not todo:
        return
    memo: dict[tuple[str, ...], set] = {}

    def on(combo: tuple[SpecialCase, ...]) -> set:
        key = tuple(c.name for c in combo)
        if key not in memo:
            memo[key] = agreeing(combo)
        return memo[key]

    everything = on(tuple(cases))

    def minimal(item) -> list[SpecialCase]:
        for case in cases:
            if item in on((case,)):
                return [case]
        needed = list(cases)
        for case in cases:
            trial = tuple(c for c in needed if c is not case)
            if item in on(trial):
                needed = list(trial)
        return needed

    by_index = {(r.key, r.index): r for r in drafts}
    for item in sorted((x for x in everything if x[0] == "swap"), key=str):
        _, a, b = item
        ra, rb = by_index.get(("h", a)), by_index.get(("h", b))
        if ra is None or rb is None or has_kind(ra.diagnoses, K.SWAP) \
                or ra.verdict != Verdict.DIFFERS:
            continue
        text = " and ".join(c.description for c in minimal(item))
        pa, pb = ra.element.split(":")[1], rb.element.split(":")[1]
        ra.diagnoses.append(diagnosis(K.SWAP, f"the document's {pa} term is the true {pb} "
                                      f"term (equal only if {text})", written=pa, fits=pb,
                                      condition=text))
        rb.diagnoses.append(diagnosis(K.SWAP, f"written as {pa} in the document (equal only "
                                      f"if {text})", written=pa, fits=pb, condition=text))
        todo = [r for r in todo if r is not ra and r is not rb]
    for r in todo:
        if ("ok", r.key, r.index) not in everything:
            for case in cases:      # no family makes it agree: a factor under the weakest
                hit = next((x[3] for x in on((case,))
                            if x[0] == "factor" and x[1:3] == (r.key, r.index)), None)
                if hit is not None:
                    r.diagnoses.insert(0, diagnosis(
                        K.FACTOR, f"{hit.detail} (if {case.description})",
                        factor=hit.factor, condition=case.description))
                    break
            continue
        needed = minimal(("ok", r.key, r.index))
        text = " and ".join(c.description for c in needed) if needed else "always"
        r.verdict = Verdict.AGREES_IF
        named = [x for x in r.diagnoses if x.kind in (K.MISSING, K.EXTRA)]
        rest = [x for x in r.diagnoses if x.kind not in (K.MISSING, K.EXTRA)]
        r.diagnoses = [Diagnosis(K.CONDITION, f"agrees only if {text}", text,
                                 condition=text)] + rest + named


def condition(d: ElementDraft) -> str:
    r"""The condition of an "agrees only if" draft ("" when it has none)."""
    hit = first_of(d.diagnoses, K.CONDITION)
    return "" if hit is None else hit.condition


__all__ = ["Agreeing", "condition", "items", "search"]
