r"""The verdict on one element and what explains its difference.

An element of the document, values :math:`D_s`, is compared with the truth in its row's frame,
values :math:`T_s` (:mod:`..readings.frames`), against the row's scale :math:`\sigma`:

- values not finite on either side: a finite sample that differs decides *differs*; else the
  element is *undecided* (never agreeing, never a scale);
- :math:`\max_s|D_s - T_s| \le \epsilon\sigma`: *agrees*, unless its units are inconsistent;
- no more than the truth's own round-off in the row (:mod:`.precision`): *undecided*;
- otherwise *differs*, with the diagnoses, in this order of trial: from the numbers (sign,
  factor, missing, extra: :func:`.diagnose.value_diagnoses`), from its expression (a symbol to
  the wrong power, one additive term with the wrong sign or factor, sin for cos:
  :mod:`.terms`; one symbol written for another, everywhere or inside one product:
  :mod:`.swaps`).

The document's expression is evaluated as printed: the truth is brought into the document's
frame, the document is never divided.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...expression_size import ops_over
from ..records import Diagnosis, DiagnosisKind as K, Verdict, diagnosis, has_kind
from ..sides.document import DocumentFunctions
from .diagnose import agrees, max_error, value_diagnoses
from .draft import ElementDraft
from .numbers import number_for_gravity
from .swaps import product_swaps, symbol_swaps
from .terms import element_term_diagnoses, product_diagnoses, undivided_term_diagnoses

#: Most operations of an element whose expression is read with changes (a power, a term, a
#: sine for a cosine, a symbol inside one product): each trial is compiled, and a form solved
#: for the accelerations and never simplified, tens of thousands of operations per element,
#: took half a minute; the shipped documents' longest has 135. Longer ones are tried only
#: for one symbol read as another everywhere (the arguments permuted, nothing compiled).
TRIAL_OPS = 2000

#: Samples a trial reading of a differing element (one symbol read as another) is first
#: evaluated on, spread over the parameter sets: only one that agrees there is evaluated on
#: every sample (it must agree at all of them), so the verdicts are those of the full grid.
SCREEN_SAMPLES = 64


class Trials:
    r"""The document's elements evaluated with changes, on the engine's samples: ``argv`` the
    arguments of the document's functions (positions, velocities, symbols per sample);
    ``h_rows`` the samples h's velocity products are compared on."""

    def __init__(self, funcs: DocumentFunctions, argv: Sequence[np.ndarray], size: int,
                 h_rows: np.ndarray | None = None) -> None:
        self.funcs, self.argv, self.size, self.h_rows = funcs, list(argv), size, h_rows
        self.position = {a: k for k, a in enumerate(funcs.args)}
        self.screen = np.linspace(0, size - 1, min(SCREEN_SAMPLES, size)).astype(int)
        self.screened = self.at(self.screen)
        self.memo: dict[tuple, object] = {}      # what a trial computes once per judgement

    def at(self, rows: np.ndarray) -> list:
        r"""The arguments at the samples ``rows`` (a number stays a number)."""
        return [x[rows] if np.ndim(x) and len(x) == self.size else x for x in self.argv]

    def swapped(self, key: str, index: tuple[int, ...], a: sp.Symbol, b: sp.Symbol,
                rows: np.ndarray | None = None, both: bool = False) -> np.ndarray:
        r"""The element with symbol ``a`` read as ``b`` (argument arrays permuted), and with
        ``both`` ``b`` as ``a`` too, at every sample or at the samples ``rows``."""
        given = self.argv if rows is None else self.screened if rows is self.screen \
            else self.at(rows)
        trial = list(given)
        trial[self.position[a]] = given[self.position[b]]
        if both:
            trial[self.position[b]] = given[self.position[a]]
        out = np.broadcast_to(self.funcs.element_function(key, index)(*trial),
                              (self.size if rows is None else len(rows),))
        return out.astype(float)

    def evaluate(self, expr: sp.Expr, rows: np.ndarray | None = None) -> np.ndarray:
        r"""``expr`` (in the document's names) at every sample, or at the samples ``rows``."""
        argv = self.argv if rows is None else self.at(rows)
        return np.broadcast_to(np.asarray(self.funcs.compiled(expr)(*argv), float),
                               (self.size if rows is None else len(rows),))

    def evaluator(self, key: str):
        r"""What evaluates an element of ``key`` on the samples its values are on: h's
        velocity products on :attr:`h_rows`, every other element on every sample."""
        if key != "h" or self.h_rows is None:
            return self.evaluate
        rows = self.h_rows
        return lambda expr: self.evaluate(expr, rows)


def _undecided(d: ElementDraft, finite: np.ndarray) -> bool:
    r"""Values not finite somewhere: *differs* where a finite sample differs (say so), else
    *undecided*. True when the element is settled here."""
    if finite.all():
        return False
    side = "the document's" if not np.isfinite(d.D).all() else "the truth's"
    note = (f"{side} values are not finite at {int((~finite).sum())} of {len(finite)} "
            "samples")
    if finite.any() and not agrees(d.D[finite], d.T[finite], d.scale):
        d.verdict = Verdict.DIFFERS
        d.diagnoses.insert(0, diagnosis(K.NOTE, note + "; it differs where they are finite",
                                        prefix=""))
        return True
    d.verdict = Verdict.UNDECIDED
    d.diagnoses.insert(0, diagnosis(K.UNDECIDED, note))
    return True


def _settled(d: ElementDraft, problems: Sequence[str], trials: Trials) -> bool:
    r"""Agreeing (or equal only by coincidence where its units are inconsistent and one of
    its terms vanishes at every sample), or differing by no more than the truth's own
    round-off in its row (undecided): True when the element is settled here, its verdict
    set."""
    if agrees(d.D, d.T, d.scale):
        hidden = bool(problems) and _vanishing_term(d, trials)
        d.verdict = Verdict.DIFFERS if hidden else Verdict.AGREES
        if hidden:
            d.diagnoses.append(diagnosis(
                K.COINCIDENCE, "numerically equal here only because the inconsistent term "
                "vanishes for this model's parameters", prefix=""))
        return True
    error = max_error(d.D, d.T)
    if error <= d.round_off:
        d.verdict = Verdict.UNDECIDED
        d.diagnoses.insert(0, diagnosis(K.UNDECIDED, f"differs from the truth by {error:.2g} "
                                        "at most, within the truth's own round-off in its row "
                                        f"({d.round_off:.2g}: the row carries that of the "
                                        "model's largest terms)"))
        return True
    return False


def _vanishing_term(d: ElementDraft, trials: Trials) -> bool:
    r"""Whether an additive term of the element (multiplied out) is 0 at every sample, within
    the tolerance: a term the drawn parameters hide, which its inconsistent units may show
    (a term in a parameter 0 in every set). Where none is, the element's values agree with
    the truth's on robots drawn at random, and an inconsistency of units is the units'
    (declared wrong, or a number written for a length) — and where the expression is too
    long to read term by term, it is taken to be one."""
    if d.expr is None or ops_over(d.expr, TRIAL_OPS):
        return True
    terms = sp.Add.make_args(sp.expand(d.expr, power_exp=False))
    fixed = set(trials.funcs.d.positions) if trials.funcs.d.assumes.get("linearised_about") \
        else set()              # drawn at the point: a term in a deviation vanishes there
    evaluate = trials.evaluator(d.key)
    return any(agrees(evaluate(t), np.zeros_like(d.D), d.scale) for t in terms
               if not t.free_symbols & fixed)


def judge(d: ElementDraft, problems: Sequence[str], trials: Trials,
          groups: Sequence[Sequence[sp.Symbol]], row_factor: np.ndarray | None = None) -> None:
    r"""Fill the draft's verdict and diagnoses (module text); ``problems`` are its units'
    (:mod:`.units`), ``groups`` the symbols one may have been written for another,
    ``row_factor`` the factor its row is of the true equation per sample, where it is."""
    d.diagnoses += [diagnosis(K.DIMENSION, p) for p in dict.fromkeys(problems)]  # once each
    finite = np.isfinite(d.D) & np.isfinite(d.T)
    if _undecided(d, finite):
        return
    if _settled(d, problems, trials):
        return
    d.verdict = Verdict.DIFFERS
    d.diagnoses += value_diagnoses(d.D, d.T, d.scale)
    expr = d.expr
    if expr is None:
        return
    # a number where gravity fits (its units say so too, where the file declares them)
    found = number_for_gravity(expr, trials.funcs.d, trials.evaluator(d.key), d.T, d.scale,
                               problems)
    if found:
        d.diagnoses[:] = found
        return
    if ops_over(expr, TRIAL_OPS):            # only the symbols read as others: no compiling
        if d.key != "h" and not has_kind(d.diagnoses, K.SIGN, K.FACTOR, K.EXTRA):
            d.diagnoses += symbol_swaps(d, trials, groups)
        return
    if d.key == "h":
        if not d.diagnoses:
            argv = trials.argv if trials.h_rows is None else trials.at(trials.h_rows)
            d.diagnoses += product_diagnoses(expr, trials.funcs, argv, d.D, d.T, d.scale)
        return
    if not has_kind(d.diagnoses, K.SIGN, K.EXTRA, K.MISSING):
        d.diagnoses[:0] = element_term_diagnoses(
            expr, trials.funcs, trials.argv, None, d.D, d.T, d.scale,
            has_kind(d.diagnoses, K.FACTOR))
    if row_factor is not None and not has_kind(d.diagnoses, K.SIGN, K.FACTOR, K.EXTRA,
                                                K.MISSING):
        d.diagnoses[:0] = undivided_term_diagnoses(expr, trials.evaluate, d.D, d.T, d.scale,
                                                   row_factor)
    if not has_kind(d.diagnoses, K.SIGN, K.FACTOR, K.EXTRA):
        d.diagnoses += symbol_swaps(d, trials, groups)
    if not has_kind(d.diagnoses, K.SIGN, K.FACTOR, K.EXTRA, K.SWAP, K.POWER):
        d.diagnoses += product_swaps(expr, trials, groups, d.T, d.scale)
    elif _odd_factor(d.diagnoses) and not has_kind(d.diagnoses, K.SWAP):
        # a term "15/8 × what fits" where the model's proportions make one symbol 15/8 of
        # another: the symbol written for the other says it plainly, and comes first
        d.diagnoses[:0] = product_swaps(expr, trials, groups, d.T, d.scale)


def _odd_factor(diagnoses: Sequence[Diagnosis]) -> bool:
    r"""Whether a term's factor is the only thing said and is no plain number (an integer
    or its inverse, up to 4, or −1): a ratio of two of the model's parameters, maybe."""
    factors = [x.factor for x in diagnoses if x.kind == K.FACTOR and x.term]
    if not factors or has_kind(diagnoses, K.SIGN, K.EXTRA, K.MISSING):
        return False
    try:
        c = abs(sp.Rational(str(factors[0])))
    except (TypeError, ValueError, sp.SympifyError):
        return False
    return not any(c == k or c == sp.Rational(1, k) for k in (1, 2, 3, 4))


def specific(diagnoses: Sequence[Diagnosis]) -> bool:
    r"""A diagnosis naming one term's error precisely (no family search is needed then)."""
    return has_kind(diagnoses, K.DIMENSION, K.SIGN, K.FACTOR, K.SWAP, K.SMALL_ANGLE)


__all__ = ["SCREEN_SAMPLES", "Trials", "judge", "specific"]
