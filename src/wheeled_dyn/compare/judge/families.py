r""""Agrees only if": the smallest combination of the model's special parameter families
(products of inertia zero, a centre of mass on an axis, disc wheels ...) the document did not
declare under which a differing element agrees.

The engine evaluates both sides on a small grid of each combination's parameter sets (a
callback, :data:`Agreeing`: which elements agree there); this module only searches: the first
single family that suffices (weakest first), else a greedy minimal combination. An element
that no family makes agree but that is a constant factor of the truth under the weakest family
that gives one says so ("factor: ... (if ...)"); two velocity products of one row of h that are
each other's truth under a family are a swap "equal only if" it.

A family *explains* a difference only where it takes it away: an element agrees under it when
its difference there, relative to its row's scale, is at most :data:`EXPLAINED` of what it is on
the main grid (or the truth's round-off), and does not on a grid of the same size under the
declared families alone. A product of inertia left out vanishes to round-off where the
products are zero; an element 1 + 10⁻⁶ times the truth stays 10⁻⁶ off, and falls within the
tolerance on a small grid only where its row's other terms are larger there; a term that
differs only near one state (a narrow bump) agrees on any small grid: no family is their
cause.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

import numpy as np

from ..grid.samples import SpecialCase
from ..records import Diagnosis, DiagnosisKind as K, Verdict, diagnosis, first_of, has_kind
from .diagnose import agrees, value_diagnoses
from .draft import ElementDraft

#: Which elements agree on a combination's grid: ``("ok", key, index, relative difference)``,
#: ``("factor", key, index, diagnosis)``, ``("swap", a, b)`` (h indices).
Agreeing = Callable[[tuple[SpecialCase, ...]], set]

#: The largest fraction of an element's relative difference on the main grid that a family
#: may leave for the element to agree under it (module text).
EXPLAINED = 1e-3


def _relative(D: np.ndarray, T: np.ndarray, scale: float) -> float:
    r""":math:`\max|D - T| / s` over the finite samples (inf where none is, or ``s`` is 0)."""
    with np.errstate(all="ignore"):
        diff = np.abs(D - T)
    diff = diff[np.isfinite(diff)]
    if not diff.size or not scale > 0:
        return float("inf")
    return float(diff.max()) / scale


def items(elements: Iterable[tuple[str, tuple[int, ...], np.ndarray, np.ndarray, float]]) -> set:
    r"""The :data:`Agreeing` items of ``(key, index, D, T, scale)`` on one grid."""
    ok: set = set()
    h_values = {}
    for key, index, D, T, scale in elements:
        if agrees(D, T, scale):
            ok.add(("ok", key, index, _relative(D, T, scale)))
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
        d.diagnoses, K.DIMENSION, K.SIGN, K.FACTOR, K.SWAP, K.SMALL_ANGLE, K.UNDECIDED,
        K.DECLARED)


class _Grids:
    r"""The family grids of one search: each combination's :data:`Agreeing` items, asked once,
    and whether an item holds there (an element agreeing only where the family explains its
    difference: :func:`_limit`)."""

    def __init__(self, cases: Sequence[SpecialCase], agreeing: Agreeing,
                 todo: Sequence[ElementDraft]) -> None:
        self.cases, self._agreeing = tuple(cases), agreeing
        self._memo: dict[tuple[str, ...], set] = {}
        self._explained: dict[tuple[str, ...], dict] = {}
        self._limits = {(r.key, r.index): _limit(r) for r in todo}

    def on(self, combo: tuple[SpecialCase, ...]) -> set:
        key = tuple(c.name for c in combo)
        if key not in self._memo:
            self._memo[key] = self._agreeing(combo)
            self._explained[key] = {x[1:3]: x[3] for x in self._memo[key] if x[0] == "ok"}
        return self._memo[key]

    def holds(self, item, combo: tuple[SpecialCase, ...]) -> bool:
        if item[0] != "ok":
            return item in self.on(combo)
        return self._within(item, combo) and not self._within(item, ())

    def _within(self, item, combo: tuple[SpecialCase, ...]) -> bool:
        r"""Whether the element of ``item`` agrees on ``combo``'s grid within its limit; on
        ``()``, the grid of the declared families alone, of the same size (the control: an
        element agreeing there too is one these small grids do not see differ, a difference
        near one state, and no family is its cause)."""
        self.on(combo)
        rel = self._explained[tuple(c.name for c in combo)].get(item[1:3])
        return rel is not None and rel <= self._limits[item[1:3]]

    def minimal(self, item) -> list[SpecialCase]:
        r"""The first single family under which ``item`` holds, else a greedy minimal
        combination."""
        for case in self.cases:
            if self.holds(item, (case,)):
                return [case]
        needed = list(self.cases)
        for case in self.cases:
            trial = tuple(c for c in needed if c is not case)
            if self.holds(item, trial):
                needed = list(trial)
        return needed


def search(cases: Sequence[SpecialCase], drafts: Sequence[ElementDraft],
           agreeing: Agreeing) -> None:
    r"""Mark the drafts that agree under undeclared ``cases`` (module text), in place."""
    todo = [r for r in drafts if _searchable(r)]
    if not cases or not todo:
        return
    grids = _Grids(cases, agreeing, todo)
    swapped = {id(r) for r in _swaps(grids, drafts)}      # drafts compare by their arrays
    for r in todo:
        if id(r) not in swapped:
            _condition(grids, r)


def _swaps(grids: _Grids, drafts: Sequence[ElementDraft]) -> list[ElementDraft]:
    r"""Two differing velocity products of a row of h, each the other's truth under a family:
    each marked a swap "equal only if" it; the drafts marked."""
    by_index = {(r.key, r.index): r for r in drafts}
    marked: list[ElementDraft] = []
    for item in sorted((x for x in grids.on(grids.cases) if x[0] == "swap"), key=str):
        _, a, b = item
        ra, rb = by_index.get(("h", a)), by_index.get(("h", b))
        if ra is None or rb is None or has_kind(ra.diagnoses, K.SWAP) \
                or ra.verdict != Verdict.DIFFERS:
            continue
        text = " and ".join(c.description for c in grids.minimal(item))
        pa, pb = ra.element.split(":")[1], rb.element.split(":")[1]
        ra.diagnoses.append(diagnosis(K.SWAP, f"the document's {pa} term is the true {pb} "
                                      f"term (equal only if {text})", written=pa, fits=pb,
                                      condition=text))
        rb.diagnoses.append(diagnosis(K.SWAP, f"written as {pa} in the document (equal only "
                                      f"if {text})", written=pa, fits=pb, condition=text))
        marked += [ra, rb]
    return marked


def _condition(grids: _Grids, r: ElementDraft) -> None:
    r"""The draft ``r`` "agrees only if" the smallest combination under which it agrees, or,
    where none does, a factor of the truth under the weakest family that gives one."""
    if not grids.holds(("ok", r.key, r.index), grids.cases):
        for case in grids.cases:    # no family makes it agree: a factor under the weakest
            hit = next((x[3] for x in grids.on((case,))
                        if x[0] == "factor" and x[1:3] == (r.key, r.index)), None)
            if hit is not None:
                r.diagnoses.insert(0, diagnosis(
                    K.FACTOR, f"{hit.detail} (if {case.description})",
                    factor=hit.factor, condition=case.description))
                return
        return
    needed = grids.minimal(("ok", r.key, r.index))
    text = " and ".join(c.description for c in needed) if needed else "always"
    r.verdict = Verdict.AGREES_IF
    named = [x for x in r.diagnoses if x.kind in (K.MISSING, K.EXTRA)]
    rest = [x for x in r.diagnoses if x.kind not in (K.MISSING, K.EXTRA)]
    r.diagnoses = [Diagnosis(K.CONDITION, f"agrees only if {text}", text,
                             condition=text)] + rest + named


def _limit(d: ElementDraft) -> float:
    r"""The relative difference a family may leave in the draft ``d`` (:data:`EXPLAINED` of
    its main grid's, or the truth's round-off in its row, whichever is larger)."""
    main = _relative(d.D, d.T, d.scale)
    return max(EXPLAINED * main, d.round_off / d.scale if d.scale > 0 else 0.0)


def condition(d: ElementDraft) -> str:
    r"""The condition of an "agrees only if" draft ("" when it has none)."""
    hit = first_of(d.diagnoses, K.CONDITION)
    return "" if hit is None else hit.condition


__all__ = ["Agreeing", "condition", "items", "search"]
