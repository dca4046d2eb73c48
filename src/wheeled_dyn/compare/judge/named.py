r"""Differing terms named in the document's symbols, one by one.

An element that differs and that no single-term diagnosis explains (no sign, factor, power,
swap) has a residual :math:`\Delta = T - D` (the truth in the row's frame minus the document).
On the identification grid (many parameter sets) :math:`\Delta` is fitted

1. as a body's own inertia about its centre of mass (one link's moment about one of its axes,
   or the same moment of two links), times a monomial in the document's names: the document
   treats the body as a point mass (named), or drops its inertia (a wheel's spin inertia
   :math:`2 I_w / r^2`) — ``point_mass``; but where :math:`\Delta` is exactly a link's
   parallel-axis term :math:`M (c_y^2 + c_z^2)` (the mass times its centre's squared distance
   from the axis) and not exactly its own moment, the document wrote the inertia about the
   centre of mass where the one about the joint's axis fits — ``parallel_axis`` (for a
   uniform rod :math:`m l^2/4` is also 3 × its own moment: the exact fit is the one named);
   a part of a moment (:math:`mr^2/4`, half a cylinder's axial :math:`mr^2/2`, left out by a
   slender rod's formula) is a formula's term the document lacks, no point mass;
2. as a monomial, or a sum of two products, in the document's symbols, positions and their
   sines and cosines (:mod:`.fitting`): the terms the document lacks (those of
   :math:`\Delta`) — ``missing`` with the terms named, ``"the document lacks m*l**2/3"``
   (``extra`` where it only has terms too many).

A fit must reproduce :math:`\Delta` at every sample of every set. Nothing here changes a
verdict.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from ..records import Diagnosis, DiagnosisKind as K, Verdict, diagnosis, has_kind
from .diagnose import nice_number, plausible_factor
from .draft import ElementDraft
from .fitting import RATIO_TOL, fit_factor, fit_sum, symbol_values
from .own_inertia import (bodies, formula_phrase, formula_reading, length_bases, parallel_phrase,
                          point_mass_fit, same_parts, set_indices, term_values)
from .part_swap import part_swap
from .swap_fit import difference_reading

#: Diagnoses after which no term is named (the error is named already); a constant factor
#: may still be a point mass's (m l² for the rod's m l²/3), units need not be the difference.
NAMED = (K.SIGN, K.POWER, K.SWAP, K.SMALL_ANGLE, K.EXTRA, K.UNDECIDED, K.POINT_MASS,
         K.PARALLEL_AXIS, K.DECLARED)
#: Most elements of one derivation whose terms are named (each is a search).
MAX_NAMED = 12
#: Largest expressions (operations) whose printed terms are compared with a residual.
MAX_WRITTEN_OPS = 200


def _parallel_axis(r: ElementDraft, name: str, term: sp.Expr | None, also: str = "") -> None:
    r"""Name on ``r`` the parallel-axis term ``name`` (``Pyy(body)``) it lacks, as ``term`` in
    the document's symbols where one fits (``also``: the axes whose terms are the same
    number, named with it); a factor found for the whole element (the term is a constant
    fraction of it only under a family that keeps proportions) goes."""
    written = f" ({sp.sstr(term)} in the document's symbols)" if term is not None else ""
    r.diagnoses[:] = [x for x in r.diagnoses if x.kind != K.FACTOR]
    r.diagnoses.insert(0, diagnosis(
        K.PARALLEL_AXIS, f"{parallel_phrase(name, also)}{written} is missing: the document "
        "takes the "
        "inertia about the centre of mass where the one about the joint's axis fits (the "
        "parallel-axis theorem adds the mass times the centre's squared distance from the "
        "axis)", prefix="missing", terms=(sp.sstr(term),) if term is not None else (),
        fits=name))


def _too_much(term: sp.Expr, written: frozenset, positions: Sequence[sp.Symbol] = ()
              ) -> bool:
    r"""Whether a term of truth − document is one the document has too much: its negative is
    a term the document writes (``written``: its expanded terms). Else by the terms it
    writes of the same kind (the same function of the ``positions``): none — it lacks the
    term, which the truth has (a gravity term dropped from an equation of springs was "too
    much" by its minus sign); all of the term's sign — it lacks one more of them (a Kane
    row, all its terms negated, lacking one); all of the other sign — it has too much
    (:math:`m` written for :math:`m_c + 2m_w`: :math:`2m_w` too much). Of both signs: by
    the term's own. Where none of those holds a parameter of the term, it lacks it (an
    :math:`I_{xz}\cos 2\theta` dropped beside :math:`-m x z\cos 2\theta` was too much)."""
    if -term in written or term in written:
        return -term in written
    kind = term.as_independent(*positions, as_Add=False)[1]
    same = [w for w in written if w.as_independent(*positions, as_Add=False)[1] == kind]
    signs = {w.could_extract_minus_sign() for w in same
             if w.free_symbols & (term.free_symbols - set(positions))}
    if not signs:
        return False
    if len(signs) == 1:
        return signs.pop() != term.could_extract_minus_sign()
    return term.could_extract_minus_sign()


def _plainest(found: sp.Expr | None, bases: Sequence[tuple[sp.Expr, np.ndarray]]
              ) -> sp.Expr | None:
    r"""``found``, a monomial of the document's names, written with the simplest coefficient
    where one of its names is a constant multiple of another on every sample (two wheels'
    moments in a fixed ratio: :math:`2 I_m`, not :math:`9 I_w/8`)."""
    if found is None:
        return None
    values = {e: v for e, v in bases if isinstance(e, sp.Symbol)}
    best = found
    for s in sorted(found.free_symbols & set(values), key=sp.default_sort_key):
        for a, v in values.items():
            ratio = values[s] / v
            if a == s or np.ptp(ratio) > RATIO_TOL * np.abs(ratio).max():
                continue
            k = sp.Rational(float(np.median(ratio))).limit_denominator(12)
            if abs(float(k) - float(np.median(ratio))) > RATIO_TOL * abs(float(k)):
                continue
            trial = found.xreplace({s: k * a})
            c = trial.as_coeff_Mul()[0]
            if sp.Rational(c).q < sp.Rational(best.as_coeff_Mul()[0]).q:
                best = trial
    return best


def _plain_coefficient(found: sp.Expr) -> bool:
    r"""Whether each term's coefficient is one a term is written with, :math:`p/q` with
    :math:`|p|, q \le 24` (not 6397/12: where a family keeps two lengths proportional, any
    sum of their squares is a multiple of either)."""
    for term in sp.Add.make_args(sp.expand(found)):
        c = term.as_coeff_Mul()[0]
        if c.is_Rational and (abs(c.p) > 24 or c.q > 24):
            return False
    return True


def _missing_factor(D: np.ndarray, T: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]],
                    expr: sp.Expr | None = None) -> Diagnosis | None:
    r"""The truth a monomial :math:`f` in the document's names (not a number: a constant factor
    is :func:`.diagnose.value_diagnoses`') times the document: a factor it lacks
    (:math:`L` dropped from :math:`L(\tau_R - \tau_L)/R`), or has too much (:math:`f = 1/L`);
    where :math:`f = (x/y)^k` of two names one written for the other, or the two exchanged, in
    the document's ``expr`` (:func:`_swapped`: R(τR − τL)/L where L(τR − τL)/R fits)."""
    if not D.size or np.abs(D).min() <= 0:
        return None
    f = fit_factor(T / D, bases)
    if f is None or f.is_number:
        return None
    numerator, denominator = sp.fraction(f)
    swapped = _swapped(f, expr)
    if swapped is not None:
        return diagnosis(K.SWAP, f"{swapped[0]} (the document is {sp.sstr(1 / f)} × the "
                         "truth)", written=swapped[1], fits=swapped[2])
    what = f"lacks a factor {sp.sstr(f)}" if denominator == 1 else \
        f"has a factor {sp.sstr(1 / f)} too much" if numerator == 1 else \
        f"lacks a factor {sp.sstr(f)}"
    return diagnosis(K.FACTOR, f"the document {what}: it is {sp.sstr(1 / f)} × the truth",
                     factor=sp.sstr(1 / f))


def _swapped(f: sp.Expr, expr: sp.Expr | None) -> tuple[str, str, str] | None:
    r"""Where the truth is :math:`f = (x/y)^k` times the document's ``expr`` of two names and
    writing :math:`x` for :math:`y` in ``expr`` makes the truth (``"r where l fits"``), or
    exchanging the two does (``"L and R exchanged"``): (the words, written, fits); else None
    — a factor the document lacks (R/L dropped from a term that holds L elsewhere too is no
    L written for R)."""
    if expr is None or sp.count_ops(expr) > MAX_WRITTEN_OPS:
        return None
    numerator, denominator = sp.fraction(f)
    (x, k), (y, j) = (b.as_base_exp() for b in (numerator, denominator))
    if not (isinstance(x, sp.Symbol) and isinstance(y, sp.Symbol) and k == j) or \
            y not in expr.free_symbols:
        return None
    if sp.cancel(expr.xreplace({y: x}) - f * expr) == 0:
        return f"{sp.sstr(y ** k)} where {sp.sstr(x ** k)} fits", sp.sstr(y), sp.sstr(x)
    if x in expr.free_symbols and sp.cancel(expr.xreplace({x: y, y: x}) - f * expr) == 0:
        return f"{sp.sstr(x)} and {sp.sstr(y)} exchanged", sp.sstr(y), sp.sstr(x)
    return None


def _written_term(found: sp.Expr, expr: sp.Expr) -> Diagnosis | None:
    r"""Truth − document ``found`` a rational multiple :math:`c\,t` of one term :math:`t` the
    document writes in ``expr`` (expanded, or as printed): that term has the wrong sign
    (:math:`c = -2`) or is :math:`1/(1 + c)` × what fits (a velocity product's coefficient,
    which the numeric term trials of :mod:`.diagnose` do not see: it is sampled on its own
    grid). None where no term is (:math:`c = -1`, a term too much, is told by
    :func:`_lacks`)."""
    if sp.count_ops(expr) > MAX_WRITTEN_OPS or sp.count_ops(found) > MAX_WRITTEN_OPS:
        return None
    terms = dict.fromkeys((*sp.Add.make_args(sp.expand(expr)), *sp.Add.make_args(expr)))
    for t in terms:
        c = sp.cancel(found / t)
        if not c.is_Rational or c in (0, -1) or not plausible_factor(float(1 / (1 + c))):
            continue
        text = sp.sstr(t)
        if c == -2:
            return diagnosis(K.SIGN, f"the term {text} has the wrong sign", term=text,
                             factor="-1")
        times = nice_number(float(1 / (1 + c)))
        return diagnosis(K.FACTOR, f"the term {text} is {times} × what fits", term=text,
                         factor=times)
    return None


def _lacks(expr: sp.Expr, written: frozenset = frozenset(),
           positions: Sequence[sp.Symbol] = ()) -> str:
    r"""``"lacks a and b"`` / ``"has c too much"`` for the terms of truth − document (a term
    the document writes with the wrong sign or too much is one it has too much: ``m`` for
    ``m_c`` makes −2 d m_w; lacking +2 d m_w is the same sum, told backwards)."""
    terms = sp.Add.make_args(sp.expand(expr))
    lacks = [t for t in terms if not _too_much(t, written, positions)]
    extra = [-t for t in terms if _too_much(t, written, positions)]
    parts = []
    if lacks:
        parts.append("lacks " + " and ".join(sp.sstr(t) for t in lacks))
    if extra:
        parts.append("has " + " and ".join(sp.sstr(t) for t in extra) + " too much")
    return "the document " + "; ".join(parts)


def _own_inertia(r: ElementDraft, hit: tuple[str, sp.Expr], term: sp.Expr | None) -> bool:
    r"""Name the residual of ``r`` found to be ``hit`` = (moment name(s), multiplier) of
    :func:`~.own_inertia.point_mass_fit`, ``term`` it in the document's symbols where found:
    the body as a point mass — or, for a part of a moment (m r²/4 = ½ m r²/2 of a cylinder
    written as a slender rod), the term in the document's symbols a formula for the body's
    inertia left out; whether it was named (a part of a moment with no term in the
    document's symbols is not: which moment a fraction is of, a link's proportions kept in
    every draw cannot tell)."""
    name, c = hit
    if term is not None and term.could_extract_minus_sign():
        term = -term        # a moment is positive (a Kane row: −1 × the truth)
    if c.is_Rational and c < 1:
        if term is None:
            return False
        r.diagnoses.insert(0, diagnosis(
            K.MISSING, f"the document lacks {sp.sstr(term)} ({sp.sstr(c)}*{name} in the "
            "model's parameters), a part of a body's own inertia (a formula for it that "
            "leaves a term out)", prefix="missing", terms=(sp.sstr(term),)))
        return True
    times = "" if c == 1 else f" × {sp.sstr(c)}"
    own = f" ({sp.sstr(term)} in the document's symbols)" if term is not None else ""
    r.diagnoses.insert(0, diagnosis(
        K.POINT_MASS, f"the moment of inertia {name} about its own centre of mass"
        f"{times}{own} is missing: the document treats {bodies(name)} "
        "(or drops its inertia)", prefix="missing",
        terms=(sp.sstr(term) if term is not None else f"{sp.sstr(c)}*{name}",),
        fits=name, factor=sp.sstr(c)))
    return True


def _formula_named(r: ElementDraft, residual: np.ndarray, moments: Mapping[str, np.ndarray],
                   lengths: Sequence[tuple[sp.Expr, np.ndarray]],
                   bases: Sequence[tuple[sp.Expr, np.ndarray]], states: int) -> bool:
    r"""Name a differing inertia element's ``residual`` (truth − document), where it is no
    body's own moment (:func:`point_mass_fit`), as a formula written for one that the
    model's body does not follow (:func:`formula_reading`): a term written where another fits.
    Not where the element agrees if a family holds (a uniform link the URDF draws as one
    follows the formula: the condition says it). Whether it was named."""
    if r.key != "A" or r.expr is None or r.verdict != Verdict.DIFFERS:
        return False
    sets = set_indices(len(residual) // states, states) if states else None
    f = formula_reading(residual, term_values(r.expr, bases), moments, lengths, sets)
    if f is None:
        return False
    of = "" if f.written == f.term else f" (of its {sp.sstr(f.term)})"
    symbols = _plainest(fit_factor(f.fit_values, bases), bases)    # J_b/R**2 for Iyy(ball)/R²
    r.diagnoses.insert(0, diagnosis(
        K.SWAP, f"the document writes {formula_phrase(f, of, symbols)}", prefix="",
        written=sp.sstr(f.written), fits=f.fits,
        term=sp.sstr(f.term)))
    return True


def name_terms(drafts: Sequence[ElementDraft], on_id: Mapping[tuple[str, tuple[int, ...]],
               tuple[np.ndarray, np.ndarray]], bases: Sequence[tuple[sp.Expr, np.ndarray]],
               moments: Mapping[str, np.ndarray], geometric: set[sp.Symbol],
               positions: Sequence[sp.Symbol] = (),
               factors: Mapping[int, np.ndarray] | None = None,
               parallel: Mapping[str, np.ndarray] | None = None, states: int = 0,
               groups: Sequence[Sequence[sp.Symbol]] = ()) -> None:
    r"""Name the differing terms of the drafts (module text), in place. ``on_id``: each
    element's (document, truth in frame) values on the identification grid; ``geometric``
    the document's lengths, the only names a point-mass multiplier may contain (never a
    position: a body's own inertia enters the inertia matrix as a constant times
    lengths); ``factors``: per row, the factor the row is of the true equation (on the same
    grid), divided out of a residual before it is compared with a body's own inertia (an
    equation divided by m l has m l²/3 as l/3); ``parallel`` the links' parallel-axis parts
    (:func:`own_moments`); ``states`` the grid's samples per parameter set (0: no formula
    for a moment is read, :func:`formula_reading`); ``groups`` the symbols of one kind, one
    of which may be written for another in a part of an element (:func:`part_swap`)."""
    lengths = length_bases(bases, geometric, positions)
    named = 0
    for r in drafts:
        if named >= MAX_NAMED:
            break
        if r.verdict not in (Verdict.DIFFERS, Verdict.AGREES_IF) or r.key == "C" \
                or has_kind(r.diagnoses, *NAMED) or (r.key, r.index) not in on_id \
                or any(x.kind == K.FACTOR and x.term for x in r.diagnoses):
            continue                      # named already (one term's factor: that term)
        D, T = on_id[(r.key, r.index)]
        if not (np.isfinite(D).all() and np.isfinite(T).all()):
            continue
        residual = T - D
        named += 1
        if np.abs(residual).max(initial=0.0) <= 1e-7 * max(float(np.abs(T).max(initial=0.0)),
                                                             1e-300):
            continue                          # agrees on these sets (a family's condition)
        own = residual if not factors or r.row not in factors else residual / factors[r.row]
        hit = point_mass_fit(own, moments, lengths) if r.key == "A" else None
        steiner = point_mass_fit(own, parallel, lengths) if r.key == "A" and parallel else None
        if steiner is not None and steiner[1] == 1 and (hit is None or hit[1] != 1):
            _parallel_axis(r, steiner[0], _plainest(fit_factor(residual, bases), bases),
                           same_parts(steiner[0], parallel or {}))
            continue
        if any(x.kind == K.FACTOR and not x.condition for x in r.diagnoses) and \
                (hit is None or hit[1] != 1):
            continue                          # a constant factor says it more plainly (one
            #                                   only if a family holds does not: the terms do)
        term = _plainest(fit_factor(residual, bases), bases) \
            if hit is not None and np.abs(residual).min() > 0 else None
        if hit is not None and hit[1] != 1 and term is not None and ((-term).is_Symbol or \
                term.is_Symbol or _odd_multiple(hit[1])):
            hit = None       # one of the document's symbols (m for 3 Ixx/l²), or a term that
            #                  is a moment only by a uniform body's proportions (m l = 3 Ixx/l)
        if _own_inertia(r, hit, term) if hit is not None else \
                _formula_named(r, own, moments, lengths, bases, states):
            continue
        _name_difference(r, D, T, own, bases, positions, factors, groups)


def _odd_multiple(multiplier: sp.Expr) -> bool:
    r"""A moment's multiplier of lengths with a coefficient no body's own inertia enters with
    (1, or 2 for two alike bodies): :math:`3/l`, where a uniform rod's :math:`I = ml^2/3`
    makes any :math:`ml` "three of its moments over its length"."""
    return not multiplier.is_number and abs(multiplier.as_coeff_Mul()[0]) not in (1, 2)


def _name_difference(r: ElementDraft, D: np.ndarray, T: np.ndarray, own: np.ndarray,
                     bases: Sequence[tuple[sp.Expr, np.ndarray]], positions: Sequence[sp.Symbol],
                     factors: Mapping[int, np.ndarray] | None,
                     groups: Sequence[Sequence[sp.Symbol]]) -> None:
    r"""Name truth − document of ``r`` (``D``, ``T`` on the identification grid; ``own`` it
    over the row's factor) where it is no body's own inertia: a factor missing, a monomial or
    two of the document's names, one symbol written for another in a part of the element
    (:func:`~.part_swap.part_swap`), or a term not divided as its row."""
    residual = T - D
    missing = _missing_factor(D, T, bases, r.expr)
    if missing is not None:
        r.diagnoses.insert(0, missing)
        return
    found = _plainest(fit_factor(residual, bases), bases) \
        if np.abs(residual).min() > 0 else None
    found = found if found is not None and _plain_coefficient(found) else \
        fit_sum(residual, bases)      # not 6397*m*r**2/12: lengths a family keeps
    if found is not None and not _plain_coefficient(found):          # proportional
        found = None
    written_wrong = _written_term(found, r.expr) if r.expr is not None and found is not None \
        else None
    if written_wrong is not None:
        r.diagnoses.insert(0, written_wrong)
        return
    if found is None or len(sp.Add.make_args(sp.expand(found))) > 1:      # not one monomial
        swapped = part_swap(r.expr, residual, symbol_values(bases), groups) \
            if groups and r.expr is not None else None
        if swapped is not None:
            r.diagnoses.insert(0, diagnosis(
                K.SWAP, swapped.text, written=str(swapped.written), fits=str(swapped.fits),
                term=sp.sstr(swapped.part), terms=(sp.sstr(swapped.part),)))
            return
    if found is None:
        f = factors.get(r.row) if factors else None      # a function, not a constant:
        varies = f is not None and np.ptp(f) > 1e-9 * float(np.abs(f).max(initial=0.0))
        before = _undivided(own, bases) if varies else None
        if before is not None:
            r.diagnoses.insert(0, before)
        return
    parts = sp.Add.make_args(sp.expand(found))
    written = frozenset(sp.Add.make_args(sp.expand(r.expr))) if r.expr is not None \
        and sp.count_ops(r.expr) <= 200 else frozenset()
    much = [_too_much(t, written, positions) for t in parts]   # named as written (-t)
    named_terms = tuple(sp.sstr(-t if all(much) else t) for t in parts) \
        if all(much) or not any(much) else ()              # both kinds: its sentence
    r.diagnoses.append(diagnosis(K.EXTRA if all(much) else K.MISSING,
                                 f"{_lacks(found, written, positions)} (truth − document = "
                                 f"{sp.sstr(found)})",
                                 prefix="terms", terms=named_terms))


def _undivided(before: np.ndarray, bases: Sequence[tuple[sp.Expr, np.ndarray]]
               ) -> Diagnosis | None:
    r"""Truth − document of a row the document divided by a function of the state, taken back
    before that division (``before``: the residual over the row's factor), named where it is
    a monomial, a sum of two, or :math:`M(x - y)` — one of two symbols written where the other
    fits (a divisor printed with :math:`l_{c1}^2` for :math:`l_1^2` divides every element by
    it, and only the element it leaves differing shows the error, as a ratio of two
    inertias); None otherwise."""
    found, swap = difference_reading(before, bases)
    head = "before the document divided its equation by its own quantity: "
    if swap is not None:
        return diagnosis(K.SWAP, f"{head}{swap[1]} (truth − document = {sp.sstr(swap[0])})",
                         terms=(sp.sstr(swap[0]),))
    if found is None:
        return None
    return diagnosis(K.MISSING, f"{head}truth − document = {sp.sstr(found)}", prefix="terms",
                     terms=tuple(sp.sstr(t) for t in sp.Add.make_args(sp.expand(found))))


__all__ = ["NAMED", "name_terms"]
