r"""Whether a document's equations are right, decided without reading their form.

A document's equations of motion are right when they have the same solutions as the true ones,
whatever the form they are written in: as matrices, written out, solved for the accelerations,
one equation divided by its inertia or replaced by a combination of the others, scaled,
reordered, Kane's :math:`F_r + F_r^* = 0`. With the truth :math:`A\ddot q + n = B u`
(:math:`n = h + Q`, the velocity and gravity terms) in the document's coordinates, equation
:math:`i` of the document, :math:`A_{doc,i}\ddot q + n_{doc,i} = B_{doc,i} u`, is right iff it
is a combination of the true equations:

.. math::

    w_i = A_{doc,i}\,A^{-1},\qquad n_{doc,i} = w_i\,n,\qquad B_{doc,i} = w_i\,B

at every sample (:math:`A_{doc,i} = w_i A` holds by construction). The document is right iff
every equation is and :math:`W = (w_i) = A_{doc}A^{-1}` is invertible everywhere: no equation
lost or repeated, none multiplied by a factor that vanishes somewhere (:math:`\sin\theta`,
where the equation reads :math:`0 = 0`).

:math:`W` is singular where :math:`\det A_{doc}` is (:math:`A` is positive definite). It is
found singular

- at every sample: relative to its rows' sizes, :math:`|\det A_{doc}|` is
  :data:`SINGULAR_TOL` or less of the truth's; the equations whose coefficients the null
  vector of :math:`W^T` carries are not independent;
- somewhere: :math:`\det W` takes both signs among the samples of one parameter set (it is
  continuous in the positions, so it vanishes between them), or it vanishes at one of the
  special positions the engine adds (each position at :math:`0, \pm\pi/2, \pi`).

Tolerances are relative, per sample: a residual counts when it exceeds :data:`~.diagnose.
AGREE_TOL` of the largest quantity the row sums at that sample (the document's terms, the sums
:math:`\sum_l |w_{il}|\,|n_l|`, the row's inertia; the multipliers' terms at their own size),
floored at :data:`FLOOR` of the row's largest over all samples; a residual within the truth's
own round-off is undecided (:mod:`.precision`). Values that are not finite never decide and
never enter a scale: an equation that differs at a finite sample differs; one that agrees
wherever it is finite but is not finite somewhere is undecided.

These are pure functions of numbers; the engine supplies both sides on the same grid.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from ..records import Diagnosis, DiagnosisKind, Verdict, diagnosis
from .diagnose import AGREE_TOL, FLOOR
from .multipliers import multiplier_floor, multiplier_terms, unit_multipliers
from .precision import (combination_span, largest_terms, round_off, round_off_diagnosis,
                        row_sizes, within_round_off)

#: :math:`|\det A_{doc}|` relative to its rows' sizes, below this fraction of the truth's:
#: W singular at that sample.
SINGULAR_TOL = 1e-9
#: A component of the null vector of :math:`W^T` above this fraction of its largest names
#: its equation as one of the dependent ones.
NULL_SHARE = 0.2


@dataclass(frozen=True)
class Side:
    r"""One side's equations on the samples (leading axis S): ``A`` (S × n × n), ``n`` the
    velocity and gravity terms (S × n; None where the document gives neither h nor Q),
    ``B`` (S × n × m, in the document's inputs; None where not compared)."""

    A: np.ndarray
    n: np.ndarray | None
    B: np.ndarray | None
    #: the multipliers' coefficients :math:`G^T` of a form that keeps the rolling constraints
    #: (S × n × m: :math:`A\ddot q + n = B u + G^T\lambda`), None where it eliminates them
    L: np.ndarray | None = None


@dataclass(frozen=True)
class EquationDecision:
    r"""The decision on one equation: its verdict, why (typed diagnoses), its largest
    residual relative to the row's size, and :math:`w_i` per sample (S × n; NaN where it
    could not be computed)."""

    verdict: Verdict
    diagnoses: tuple[Diagnosis, ...]
    max_error: float
    w: np.ndarray
    #: undecided for precision: the parts of its combination differ in size beyond the
    #: tolerance, or it differs within the truth's own round-off
    beyond_precision: bool = False


@dataclass(frozen=True)
class SystemDecision:
    r"""Every equation's :class:`EquationDecision` and :math:`W` per sample (S × n × n)."""

    equations: tuple[EquationDecision, ...]
    W: np.ndarray
    #: per equation, whether its weights were told by the document's terms beyond A
    #: (:func:`weights_told`); where they were not, they were given (its own row, or times
    #: its declared scale) and its A compared with them; empty: every equation's were told
    told: tuple[bool, ...] = ()

    def told_row(self, i: int) -> bool:
        return not self.told or self.told[i]

    @property
    def equivalent(self) -> bool:
        return all(e.verdict == Verdict.AGREES for e in self.equations)


def relative_det(A: np.ndarray) -> np.ndarray:
    r""":math:`|\det A|` divided by the product of its rows' norms (Hadamard's bound: 1 for
    orthogonal rows, 0 when singular), per sample; NaN where A is not finite."""
    out = np.full(len(A), np.nan)
    finite = np.isfinite(A).all(axis=(1, 2))
    if finite.any():
        norms = np.linalg.norm(A[finite], axis=2).prod(axis=1)
        with np.errstate(all="ignore"):
            out[finite] = np.abs(np.linalg.det(A[finite])) / np.where(norms > 0, norms, 1.0)
    return out


def combination_rows(doc_A: np.ndarray, true_A: np.ndarray) -> np.ndarray:
    r""":math:`W = A_{doc}A^{-1}` per sample (S × n × n): NaN in a row :math:`w_i` where the
    document's row is not finite (an element lost in the extracted text, an overflow), in
    every row where the truth's A is not."""
    W = np.full(doc_A.shape, np.nan)
    finite = np.isfinite(true_A).all(axis=(1, 2))
    if finite.any():
        # W A = A_doc  ⇔  Aᵀ Wᵀ = A_docᵀ
        W[finite] = np.swapaxes(np.linalg.solve(np.swapaxes(true_A[finite], 1, 2),
                                                np.swapaxes(doc_A[finite], 1, 2)), 1, 2)
    return W


def row_residual(doc: np.ndarray, true: np.ndarray, w: np.ndarray, least: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""For one row: (relative residual per sample, finite mask, the scale per sample it is
    relative to) of ``doc`` (S × k) against :math:`w\,` ``true`` (S × n × k), the scale at
    least ``least`` (the row's inertia; for the multipliers' terms, their own floor) and at
    least :data:`FLOOR` of its largest."""
    with np.errstate(all="ignore"):
        predicted = np.einsum("sl,slk->sk", w, true)
        sums = np.einsum("sl,slk->sk", np.abs(w), np.abs(true))
        finite = (np.isfinite(doc).all(axis=1) & np.isfinite(predicted).all(axis=1)
                  & np.isfinite(sums).all(axis=1) & np.isfinite(least))
        scale = np.maximum(np.maximum(np.abs(doc).max(axis=1, initial=0.0),
                                      sums.max(axis=1, initial=0.0)), least)
        scale = np.where(finite, scale, 0.0)
        floor = FLOOR * float(scale.max(initial=0.0))
        error = np.abs(doc - predicted).max(axis=1, initial=0.0)
        scale = np.maximum(np.maximum(scale, floor), 1e-300)
        relative = np.where(finite, error / scale, 0.0)
    return relative, finite, scale


def weights_told(doc: Side, truth: Side) -> tuple[bool, ...]:
    r"""Per equation, whether the document's terms beyond A tell its weights :math:`w_i`:
    it states (finite somewhere) its element of a part (n, B, the multipliers'
    coefficients) that is not zero in the truth, so :math:`w_i` is checked on it. An
    equation stating none (A alone, its other terms lost or only terms the truth has none
    of) is :math:`w_i A` for some :math:`w_i` whatever it is, and nothing would be checked:
    its A is then compared as the mass matrix's row, as printed or scaled as declared."""
    n = truth.A.shape[1]
    size = float(np.abs(np.where(np.isfinite(truth.A), truth.A, 0.0)).max(initial=0.0))
    told = np.zeros(n, dtype=bool)
    for D, T in ((doc.n, truth.n), (doc.B, truth.B), (doc.L, truth.L)):
        if D is None or T is None:
            continue
        with np.errstate(all="ignore"):
            if np.isfinite(T).all() and np.abs(T).max(initial=0.0) <= AGREE_TOL * size:
                continue                      # the truth has none of it: nothing to check
        told |= np.isfinite(D.reshape(len(D), n, -1)).any(axis=(0, 2))
    return tuple(bool(x) for x in told)


def decide_row(i: int, doc: Side, truth: Side, W: np.ndarray,
               multipliers: np.ndarray | None = None,
               least_multiplier: np.ndarray | None = None,
               with_A: bool = False, sizes: np.ndarray | None = None,
               largest: np.ndarray | None = None) -> EquationDecision:
    r"""The verdict on equation ``i`` (module text), :math:`W` known; ``multipliers``: the
    true multipliers' coefficients recombined for the document (:func:`multiplier_terms`),
    where both sides keep the constraints; ``with_A``: :math:`W` was given, not found from
    :math:`A_{doc}`, and the inertia row is compared too; ``sizes``: the true rows' sizes
    (:func:`~.precision.row_sizes`, made once for every row), ``largest`` their
    :func:`~.precision.largest_terms` (likewise)."""
    w = W[:, i, :]
    inertia = np.abs(doc.A[:, i, :]).max(axis=1)
    rho = round_off(w, truth.A, truth.n, largest)
    residuals, masks, scales = [], [], []
    parts = ((doc.n, truth.n), (doc.B, truth.B), (doc.L, multipliers))
    for D, T in ((doc.A, truth.A), *parts) if with_A else parts:
        if D is None or T is None:
            continue
        D2 = D[:, i:i + 1] if D.ndim == 2 else D[:, i, :]
        T3 = T[:, :, None] if T.ndim == 2 else T
        least = inertia if D is not doc.L else least_multiplier if \
            least_multiplier is not None else multiplier_floor(D, T)
        rel, finite, scale = row_residual(D2, T3, w, least)
        residuals.append(rel)
        masks.append(finite)
        scales.append(None if D is doc.L else scale)  # the multipliers': geometry, exact
    finite = np.logical_and.reduce(masks) if masks else np.isfinite(w).all(axis=1)
    finite &= np.isfinite(w).all(axis=1)
    worst = max((float(r[finite].max(initial=0.0)) for r in residuals), default=0.0)
    total = len(finite)
    if worst > AGREE_TOL and within_round_off(residuals, scales, rho, finite):
        return EquationDecision(Verdict.UNDECIDED, (round_off_diagnosis(i, worst),), worst, w,
                                True)
    if worst > AGREE_TOL and with_A:
        return EquationDecision(Verdict.DIFFERS, (diagnosis(
            DiagnosisKind.NOT_EQUIVALENT, f"equation {i + 1} is not the true one (it states "
            "no velocity, gravity, input or multiplier terms that tell how it combines the "
            "true ones, so its A is compared as the mass matrix's row, as printed or scaled "
            f"as declared: off by {worst:.2g} of the row's size at the worst of {total} "
            "samples)",
            prefix="differs", rows=(i,)),), worst, w)
    if worst > AGREE_TOL:
        return EquationDecision(Verdict.DIFFERS, (diagnosis(
            DiagnosisKind.NOT_EQUIVALENT, f"equation {i + 1} is no combination of the true "
            f"equations (W = A_doc A⁻¹ does not carry its velocity, gravity, input or "
            f"multiplier terms; "
            f"off by {worst:.2g} of the row's size at the worst of {total} samples)",
            prefix="differs", rows=(i,)),), worst, w)
    if not finite.all():
        return EquationDecision(Verdict.UNDECIDED, (diagnosis(
            DiagnosisKind.UNDECIDED, f"values not finite at {int((~finite).sum())} of {total} "
            "samples; it agrees wherever they are finite"),), worst, w)
    sizes = row_sizes(truth.A, (truth.n, truth.B)) if sizes is None else sizes
    span = combination_span(w, sizes, finite)
    if span is not None:
        return EquationDecision(Verdict.UNDECIDED, (diagnosis(
            DiagnosisKind.UNDECIDED, f"equation {i + 1} agrees as a combination of the true "
            f"equations whose parts differ in size by a factor {span:.2g} (W = A_doc A⁻¹): "
            "a difference in its smaller part, even as large as that part, would be below "
            "the comparison's tolerance, so it cannot be decided (write the equations so "
            "that no one is a multiple of another to that precision)"),), worst, w, True)
    return EquationDecision(Verdict.AGREES, (), worst, w)


def _null_rows(W: np.ndarray) -> tuple[int, ...]:
    r"""The equations a null vector of :math:`W^T` (the most singular sample's) involves."""
    _, _, vt = np.linalg.svd(np.swapaxes(W, 0, 1))
    y = np.abs(vt[-1])
    return tuple(int(k) for k in np.flatnonzero(y >= NULL_SHARE * y.max()))


def singular_everywhere(doc_A: np.ndarray, true_A: np.ndarray, W: np.ndarray
                        ) -> tuple[int, ...] | None:
    r"""The dependent equations when :math:`W` is singular at every sample (module text),
    else None."""
    rd, rt = relative_det(doc_A), relative_det(true_A)
    ok = np.isfinite(rd) & np.isfinite(rt) & np.isfinite(W).all(axis=(1, 2))
    if not ok.any() or not (rd[ok] <= SINGULAR_TOL * rt[ok]).all():
        return None
    k = int(np.flatnonzero(ok)[0])
    return _null_rows(W[k])


def sign_changes(W: np.ndarray, sets: int, across: bool = False
                 ) -> tuple[tuple[int, ...], bool] | None:
    r"""Where :math:`\det W` takes both signs among the samples of one parameter set (with
    ``across``, among all samples): the equations involved and whether it passes through a
    pole rather than a zero, else None. ``sets``: the number of parameter sets, the samples
    being grouped by set (K × N in order). Across sets it is the same test: the truth's
    :math:`\det A` never changes sign (A is positive definite), so :math:`\det W` has the
    sign of :math:`\det A_{doc}`; the parameter sets are drawn in ranges of masses, inertias
    and lengths that hold every robot between two of them, taken for robots of the model too
    (where a length between made the coordinates singular, the truth would be singular there:
    not seen in the shipped models or the tests), so a factor :math:`m_1 - 2m_2` negative for
    one set and positive for another vanishes for one of them. Between random samples a zero
    and a pole look alike by sign; they differ by magnitude: the samples nearest a zero make
    :math:`|\det W|` small against its median, those nearest a pole large. At a zero the
    equations are those the null vector of :math:`W^T` involves; at a pole (an equation
    divided by a factor that vanishes) those whose weights :math:`w_i` grow there against
    their median."""
    det = np.full(len(W), np.nan)
    finite = np.isfinite(W).all(axis=(1, 2))
    det[finite] = np.linalg.det(W[finite])
    groups = [np.arange(len(W))] if across else np.array_split(np.arange(len(W)), sets)
    for group in groups:
        d = det[group]
        d = d[np.isfinite(d)]
        if not (len(d) and (d > 0).any() and (d < 0).any()):
            continue
        size = np.abs(d)
        middle = float(np.median(size))
        low, high = float(size.min()), float(size.max())
        if middle > 0 and low > 0 and high / middle > middle / low:        # a pole
            members = group[np.isfinite(det[group])]
            k = int(np.argmax(np.abs(det[members])))
            norms = np.linalg.norm(W[members], axis=2)
            growth = norms[k] / np.maximum(np.median(norms, axis=0), 1e-300)
            rows = tuple(int(i) for i in np.flatnonzero(growth >= NULL_SHARE * growth.max())
                         if growth[i] > 1.0)
            if rows:
                return rows, True
        k = group[np.nanargmin(np.abs(det[group]))]    # a zero (or a pole no row shows)
        return _null_rows(W[k]), False
    return None


def decide(doc: Side, truth: Side, sets: int,
           special: tuple[np.ndarray, np.ndarray, np.ndarray | None] | None = None,
           given: np.ndarray | None = None) -> SystemDecision:
    r"""Every equation's verdict (module text). ``sets``: parameter sets the samples are
    grouped in; ``special``: the document's and the truth's A at the special states (or
    None); ``given``: the rows of :math:`W` for the equations whose terms do not tell
    theirs (:func:`weights_told`), each then compared with its inertia terms too (None: every
    equation's weights found from A, as for a document of matrices or equations)."""
    n = truth.A.shape[1]
    W = combination_rows(doc.A, truth.A)
    told = weights_told(doc, truth) if given is not None else (True,) * n
    for i in range(n):
        if given is not None and not told[i]:
            W[:, i, :] = given[:, i, :]           # given: the equation's own row, or scaled
    if doc.L is not None:
        doc = replace(doc, L=unit_multipliers(doc.L))
    multipliers = None if doc.L is None or truth.L is None else \
        multiplier_terms(doc.L, truth.L, W)
    floor = None if multipliers is None or doc.L is None else \
        multiplier_floor(doc.L, multipliers)            # every row's, made once
    sizes = row_sizes(truth.A, (truth.n, truth.B))
    largest = largest_terms(truth.A, truth.n)
    decisions = [decide_row(i, doc, truth, W, multipliers, floor, not told[i], sizes, largest)
                 for i in range(n)]
    told = () if all(told) else told
    lost = singular_everywhere(doc.A, truth.A, W)
    where = "at every sample" if lost is not None else ""
    rows = lost
    pole = False
    if rows is None:
        changes = sign_changes(W, sets)
        where = "somewhere: det W changes sign between states of one parameter set"
        if changes is None and sets > 1:
            changes = sign_changes(W, sets, across=True)
            where = ("for some robot of the model: det W changes sign between parameter "
                     "sets, and the robots between them are robots of the model too")
        if changes is not None:
            rows, pole = changes
        where = where if rows is not None else ""
    if rows is None and special is not None:
        from .lost_at import vanishing_at        # it reads this module's measures
        rows = vanishing_at(*special)
        where = ("with the model's own numbers, at a special position (a coordinate at 0, "
                 "±π/2 or π) or at a state searched where its weights are least"
                 ) if rows is not None else ""
    if rows is not None and not pole and _precision_only(W, decisions):
        rows = None         # nearly dependent only to the precision that left one undecided
    if rows is not None:
        wrong = [k for k in rows if decisions[k].verdict == Verdict.DIFFERS]
        rows = tuple(wrong) or rows     # an equation that is no combination explains it
        names = ", ".join(str(k + 1) for k in rows)
        which = f"equations {names} are" if len(rows) > 1 else f"equation {names} is"
        text = (f"{which} not defined everywhere ({where[0].lower() + where[1:]}): "
                "W = A_doc A⁻¹ is unbounded there (an equation divided by a factor that "
                "vanishes: where it does, the equation is not defined)") if pole else (
            f"{which} not independent {where}: W = A_doc A⁻¹ is singular there (an "
            "equation lost, repeated, or multiplied by a factor that vanishes)")
        return mark_lost(SystemDecision(tuple(decisions), W, told), rows, text)
    return SystemDecision(tuple(decisions), W, told)


def _precision_only(W: np.ndarray, decisions: Sequence[EquationDecision]) -> bool:
    r"""Whether :math:`W` looks singular only through the equations left undecided for the
    precision of their combinations: without them, the other rows of :math:`W` are
    independent at every sample (eq1 + 1e12·eq2 beside eq2; eq2 written twice beside it is
    still lost)."""
    beyond = [k for k, e in enumerate(decisions) if e.beyond_precision]
    if not beyond:
        return False
    rest = np.delete(W, beyond, axis=1)
    if rest.shape[1] == 0:
        return True
    rest = rest[np.isfinite(rest).all(axis=(1, 2))]
    sv = np.linalg.svd(rest, compute_uv=False)
    return bool(len(sv) and (sv[:, -1] > SINGULAR_TOL * sv[:, 0]).all())


def mark_lost(decision: SystemDecision, rows: tuple[int, ...], text: str) -> SystemDecision:
    r"""``decision`` with the equations ``rows`` not equivalent, for the reason ``text`` (W
    singular or unbounded somewhere)."""
    decisions = list(decision.equations)
    for k in rows:
        e = decisions[k]
        extra = diagnosis(DiagnosisKind.SINGULAR, text, prefix="not equivalent",
                          rows=tuple(rows))
        decisions[k] = EquationDecision(Verdict.DIFFERS, (*e.diagnoses, extra), e.max_error,
                                        e.w)
    return replace(decision, equations=tuple(decisions))


__all__ = ["EquationDecision", "FLOOR", "NULL_SHARE", "SINGULAR_TOL", "Side", "SystemDecision",
           "combination_rows", "decide", "decide_row", "mark_lost", "multiplier_terms",
           "relative_det", "row_residual", "sign_changes", "singular_everywhere",
           "weights_told"]
