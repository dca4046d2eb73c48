r"""A better reading of a file's sign conventions: a cause, never a verdict.

The file's maps (coordinates, velocities, inputs) are how the document is read, and the
verdicts under them are the verdicts (declarations are binding). When the equations are not
right as declared, the signs of the positions and inputs and the order of the inputs are
searched (:mod:`..readings.signs`), and where most equations stay wrong an angle read from the
opposite direction (θ → θ + π, π − θ: measured from the upright where the map measures it
hanging) or from another link (q₂ → q₂ ± q₁: :mod:`..readings.relative_angles`); a reading
under which more elements agree is reported as a cause — "under
τ → −τ, 30 elements agree instead of 19 (every equation is right): the file's torque signs
are probably reversed" — with the verdicts left as declared.

Only a file that says its document's convention is unknown (``convention = "unknown"``) is
compared under the reading found, and the report says so first.
"""

from __future__ import annotations

import sympy as sp

from ...expression_size import atoms_of
from ...derivations.schema import Derivation
from ..judge.source_entry import one_wrong_entry
from ..readings import signs
from ..readings.search import SearchEvaluation
from ..records import Cause, CauseKind, Convention, ConventionSummary, DerivationResult, Verdict


def search_evaluation(j) -> SearchEvaluation:
    r"""The convention search's view of a judged derivation ``j`` (its numbers)."""
    ev = j.evaluation
    return SearchEvaluation(funcs=ev.funcs, doc=ev.doc, truth=ev.truth, B_true=ev.B_true,
                            scales=ev.scales, q=ev.q, nu=ev.nu, values=ev.values,
                            row_factor=ev.row_factor, kind=ev.kind)


def _search(j, complete_gain: int = signs.MIN_GAIN_ORDER) -> tuple | None:
    r"""The best reading of the judged derivation ``j``'s file, or None (``complete_gain``:
    :func:`~..readings.signs.best_reading`'s)."""
    search = search_evaluation(j)
    d = j.funcs.d
    return signs.best_reading(d, search.doc_at, search.score, search.score_readings,
                              search.most(), complete_gain, _trig_positions(j.funcs),
                              lambda score: score // search.weight() <= d.n // 2,
                              search.weight())


def _trig_positions(funcs) -> tuple[int, ...]:
    r"""The positions (indices) the document takes sines, cosines or tangents of: those a
    reading from the opposite direction (:math:`+\pi`) can change."""
    positions = list(funcs.d.positions)
    inside: set = set()
    for e in funcs.exprs.values():
        if isinstance(e, sp.Basic):
            for f in atoms_of(e, sp.sin, sp.cos, sp.tan):
                inside |= f.free_symbols
    return tuple(k for k, p in enumerate(positions) if p in inside)


def _right(result: DerivationResult) -> int:
    return sum(1 for e in result.equations if e.verdict == Verdict.AGREES)


def unknown_convention(engine, d: Derivation) -> tuple[Derivation, Cause] | None:
    r"""For a file declaring its convention unknown: ``d`` read under the best reading, with
    the cause saying so; None for any other file or when no reading is better."""
    if d.convention != "unknown":
        return None
    j = engine.judge(d)
    # the file asks for its convention: a reading under which every element agrees is it,
    # though one input's sign shows in one element only (the arm's τ₁ in B[1,1] alone)
    best = None if j.result.equivalent else _search(j, complete_gain=1)
    if best is None:
        return None
    reading = best[0]
    flipped = signs.flipped(d, *reading)
    text = signs.describe(d, *reading)
    return flipped, Cause(CauseKind.CONVENTION, (), (
        f"the file declares its document's sign convention unknown: compared as {text} "
        f"({signs.maps_text(flipped)}) instead of the file's {signs.maps_text(d)}, the reading "
        "under which most equations are right and most elements agree"))


def convention_finding(engine, d: Derivation, j) -> tuple[Cause, ConventionSummary] | None:
    r"""A reading under which more elements agree than as declared: the cause and the
    summary (module text); the verdicts stay as declared. A reading of the positions is no
    cause where one wrong entry of the equations (or one symmetric pair of the inertia's)
    gives the document as well (:func:`~..judge.source_entry.one_wrong_entry`): a pole's
    gravity sign solved for the accelerations reads as π − θ, its coupling's sign as −θ."""
    best = _search(j)
    if best is None:
        return None
    reading = best[0]
    if signs.moves_position(reading) and one_wrong_entry(j.sides, d.velocities):
        return None          # one term's error (a gravity sign): said as that, not as a reading
    flipped = signs.flipped(d, *reading)
    better = engine.judge(flipped).result
    declared = j.result
    if better.counts()["agrees"] <= declared.counts()["agrees"]:
        return None
    text = signs.describe(d, *reading)
    now = {r.element for r in better.records if r.verdict == Verdict.AGREES}
    elements = tuple(sorted(r.element for r in declared.records
                            if r.verdict != Verdict.AGREES and r.element in now))
    n = len(declared.equations)
    finding = (f"read as {signs.maps_text(flipped)} instead of the file's "
               f"{signs.maps_text(d)} ({text}), {better.counts()['agrees']} elements agree "
               f"instead of {declared.counts()['agrees']} and {_right(better)} of {n} "
               f"equations are right instead of {_right(declared)}")
    kind = CauseKind.SWAPPED_INPUTS if signs.is_permutation_only(reading) else \
        CauseKind.CONVENTION
    what = "inputs are probably exchanged" if kind == CauseKind.SWAPPED_INPUTS else \
        "angles are probably measured from the opposite direction" if reading[3] else \
        "angles are probably measured from another link (absolute where the map takes them " \
        "relative to the link before, or the reverse)" if reading[4] else \
        "declared signs of these are probably reversed"
    cause = Cause(kind, elements, f"{finding}: the file's {what}; the verdicts are under the "
                  "file's declaration (declare the maps the document uses, or "
                  "convention = \"unknown\")")
    summary = ConventionSummary(
        declared=Convention("as declared: " + signs.maps_text(d), declared.counts()),
        best=Convention(f"{text} ({signs.maps_text(flipped)})", better.counts()),
        finding=finding)
    return cause, summary


__all__ = ["convention_finding", "search_evaluation", "unknown_convention"]
