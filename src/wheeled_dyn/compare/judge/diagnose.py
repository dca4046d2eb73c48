r"""Verdict and diagnosis of one element from its values on both sides.

Given the document's values :math:`D_s` and the truth's :math:`T_s` over samples :math:`s`, and
a scale :math:`\sigma` (the size of the row's entries):

- **agrees** when :math:`\max_s |D_s - T_s| \le \epsilon\sigma`;
- otherwise **differs**, with what explains the difference:
  *sign* (:math:`D = -T`), *factor c* (:math:`D = cT`, c fitted by least squares and shown as a
  simple fraction when it is one), *swap* (the document's expression with one coordinate,
  velocity or symbol replaced by another agrees: "φ̇ where ψ̇ fits"), *extra* (the truth is 0),
  *missing* (the document has 0), or a *residual* :math:`T - D`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import functools
import math
from fractions import Fraction

import numpy as np
import sympy as sp

from ..records import Diagnosis, DiagnosisKind as K, diagnosis

#: Relative tolerance of agreement (the numbers are exact to ~1e-13 relative).
AGREE_TOL = 1e-7
#: A sample's residual scale in the equivalence decision is at least this fraction of the
#: largest over the samples (of the row's column, or of the multipliers' fit).
FLOOR = 1e-6


def agrees(D: np.ndarray, T: np.ndarray, scale: float) -> bool:
    return bool(np.max(np.abs(D - T), initial=0.0) <= AGREE_TOL * scale)


def max_error(D: np.ndarray, T: np.ndarray) -> float:
    return float(np.max(np.abs(D - T), initial=0.0))


#: Relative distance within which a factor is the simple fraction it is near.
FRACTION_TOL = 1e-9


def nice_number(c: float) -> str:
    r"""``c`` as a simple fraction when it is one (1/2, -2, 3/4 ...), else 4 significant
    digits, more where 4 would print a simple fraction it is not (0.9999997, not "1": a
    wheel axis tilted by a rounded angle scales an element by that)."""
    frac = sp.nsimplify(c, tolerance=FRACTION_TOL, rational=True)
    if frac.q <= 12 and abs(float(frac) - c) <= FRACTION_TOL * max(1.0, abs(c)):
        return str(frac)
    for digits in range(4, 17):
        text = f"{c:.{digits}g}"
        near = sp.nsimplify(float(text), rational=True)
        if near.q > 12 or float(near) != float(text) or abs(c) > 1e3:
            return text
    return repr(c)


#: Significant digits (and denominators) of a factor an author can have written or a simple
#: ratio gives: a term "c × what fits" is said only for such a c (:func:`plausible_factor`).
FACTOR_DIGITS = 1000


def small_fraction(x: float, tol: float, largest_q: int = 12) -> Fraction | None:
    r"""``x`` as a fraction of denominator at most ``largest_q`` within ``tol`` of it
    (relative), else None."""
    frac = Fraction(x).limit_denominator(largest_q)
    return frac if abs(float(frac) - x) <= tol * abs(x) else None


def plausible_factor(c: float) -> bool:
    r"""Whether ``c`` is a factor a term can be wrong by: :math:`(p/q)\,10^k\,\pi^j` with
    :math:`|p| \le` :data:`FACTOR_DIGITS`, :math:`q \le 12`, :math:`|k| \le 9`,
    :math:`j \in \{-1, 0, 1\}` (a typed 0.999 for 1, 2 for 1, 3/4, 1000 for a unit, 180/π);
    not a coincidence of the numbers (1.179e7 where a CAD export's rounding is all a term
    has, 0.8083 where a family fixes a ratio)."""
    if not np.isfinite(c) or c == 0:
        return False
    for base in (c, c / np.pi, c * np.pi):
        for k in range(-9, 10):
            x = base / 10.0 ** k
            if not 1.0 <= abs(x) <= FACTOR_DIGITS:
                continue
            frac = small_fraction(x, FRACTION_TOL)
            if frac is not None and abs(frac.numerator) <= FACTOR_DIGITS:
                return True
    return False


#: Denominators above which a fraction of a document's term is printed as the decimal it was
#: written as (the parser reads 0.241704332108682 as 120852166054341/500000000000000).
DECIMAL_DENOMINATOR = 10 ** 6


def term_text(term: sp.Expr) -> str:
    r"""``term`` as text, its fractions of large denominators as the decimals they were."""
    big = {r: sp.Float(r, 15) for r in term.atoms(sp.Rational) if r.q > DECIMAL_DENOMINATOR}
    return sp.sstr(term.xreplace(big) if big else term)


def value_diagnoses(D: np.ndarray, T: np.ndarray, scale: float) -> list[Diagnosis]:
    r"""Diagnoses from the numbers alone (sign, factor, extra, missing)."""
    tol = AGREE_TOL * scale
    if np.max(np.abs(T), initial=0.0) <= tol:
        return [diagnosis(K.EXTRA, "the truth is 0", prefix="extra term")]
    if np.max(np.abs(D), initial=0.0) <= tol:
        return [diagnosis(K.MISSING, "the document has 0")]
    if np.max(np.abs(D + T)) <= tol:
        return [diagnosis(K.SIGN, "the document has the opposite sign", factor="-1")]
    c = float(D.ravel() @ T.ravel() / (T.ravel() @ T.ravel()))
    off = float(np.max(np.abs(D - c * T)))
    near = small_fraction(c, NEAR_FRACTION) if np.isfinite(c) and c else None
    if off > NEAR_FRACTION * scale or near == 1 or (near is None and off > tol):
        return []                         # 0.9999998: no factor (a family's difference)
    if near == -1:                        # -0.99999: a sign, beside a CAD export's 1e-6
        return [diagnosis(K.SIGN, "the document has the opposite sign", factor="-1")]
    if near is not None:
        c = float(near)
    elif not plausible_factor(c):         # 1.0003: a term, not a factor an author writes
        return []
    return [diagnosis(K.FACTOR, f"the document is {nice_number(c)} × the truth",
                      factor=nice_number(c))]


#: A whole element's factor within this (relative) of a simple fraction, the element within
#: this of its scale from that multiple of the truth, is that fraction (-0.99999 is -1 where
#: a CAD export's products of inertia are 1e-6 of the element; only the explanation).
NEAR_FRACTION = 1e-5


def swap_diagnoses(expr: sp.Expr, candidates: Sequence[Sequence[sp.Symbol]],
                   evaluate: Callable[[sp.Symbol, sp.Symbol], np.ndarray], T: np.ndarray,
                   scale: float, screen: Callable[[sp.Symbol, sp.Symbol], bool] | None = None
                   ) -> list[Diagnosis]:
    r"""Replace one symbol of ``expr`` by another of the same group (velocities with velocities,
    positions with positions, symbols of equal units with each other); report the replacements
    that make it agree. ``evaluate(a, b)`` gives the element's values with ``a`` read as ``b``;
    ``screen(a, b)``, where given, False rules the replacement out without evaluating it (it
    disagrees already on some of the samples)."""
    found = []
    present = expr.free_symbols
    for group in candidates:
        for a in group:
            if a not in present:
                continue
            for b in group:
                if b == a or (screen is not None and not screen(a, b)):
                    continue
                if agrees(evaluate(a, b), T, scale):
                    found.append(diagnosis(K.SWAP, f"{sp.sstr(a)} where {sp.sstr(b)} fits",
                                           written=sp.sstr(a), fits=sp.sstr(b)))
    return found


@functools.lru_cache(maxsize=4096)
def expanded_terms(expr: sp.Expr) -> tuple[sp.Expr, ...]:
    r"""The additive terms of ``sympy.expand(expr)``, once per expression (the power, term,
    product and small-angle trials of a differing element each read them)."""
    return sp.Add.make_args(sp.expand(expr))


#: Largest number of additive terms of an element searched for one wrong term.
MAX_TERMS = 16


def power_diagnoses(expr: sp.Expr, params: Sequence[sp.Symbol],
                    evaluate: Callable[[sp.Expr], np.ndarray], T: np.ndarray,
                    scale: float,
                    powered: Callable[[sp.Symbol, float], np.ndarray] | None = None,
                    at_zero: Callable[[sp.Symbol], np.ndarray] | None = None
                    ) -> list[Diagnosis]:
    r"""A parameter :math:`s` written to the power :math:`e` where :math:`e'` fits
    (:math:`e' \in \{-e, e \pm 1, 2e\}`, e.g. G where G² fits, R⁻² where R² fits):
    ``expr`` with :math:`s \to s^{e'/e}` agrees. ``evaluate(e)`` gives an expression's values
    at the samples; ``powered(s, k)``, where given, the values of ``expr`` itself with the
    values of :math:`s` raised to the power k (the same numbers, without compiling a trial
    expression); ``at_zero(s)``, where given, its values with those of :math:`s` set to 0 (not
    finite where a term divides by it)."""
    if powered is None:
        def powered(s: sp.Symbol, k: float) -> np.ndarray:
            return evaluate(expr.xreplace({s: s ** sp.nsimplify(k)}))
    found = []
    factors = [f for term in expanded_terms(expr) for f in sp.Mul.make_args(term)]
    for s in sorted(expr.free_symbols & set(params), key=str):
        e = next((f.as_base_exp()[1] for f in factors if f.as_base_exp()[0] == s), sp.Integer(0))
        if e == 0 or not e.is_Rational:
            continue
        if e > 0 and _agrees_without(expr, s, evaluate, at_zero, T, scale):
            continue         # its terms left out agree: they are extra (a small length to a
            #                  higher power only makes them vanish), not to another power
        for new in dict.fromkeys((-e, e - 1, e + 1, 2 * e)):
            if new != 0 and agrees(powered(s, new / e), T, scale):
                found.append(diagnosis(K.POWER, f"{sp.sstr(s ** e)} where {sp.sstr(s ** new)} "
                                       "fits", written=sp.sstr(s ** e), fits=sp.sstr(s ** new)))
    return found


def _agrees_without(expr: sp.Expr, s: sp.Symbol, evaluate: Callable[[sp.Expr], np.ndarray],
                    at_zero: Callable[[sp.Symbol], np.ndarray] | None, T: np.ndarray,
                    scale: float) -> bool:
    r"""Whether ``expr`` with :math:`s = 0` (its terms in :math:`s` left out) agrees with
    ``T``: never where a term divides by :math:`s` (not finite)."""
    if at_zero is not None:
        values = at_zero(s)
        return bool(np.isfinite(values).all()) and agrees(values, T, scale)
    dropped = expr.xreplace({s: sp.S.Zero})
    return not dropped.has(sp.zoo, sp.oo, -sp.oo, sp.nan) and agrees(evaluate(dropped), T, scale)


def term_diagnoses(expr: sp.Expr, evaluate: Callable[[sp.Expr], np.ndarray], D: np.ndarray,
                   T: np.ndarray, scale: float) -> list[Diagnosis]:
    r"""One additive term :math:`t` of the element wrong, the rest right: with the wrong sign
    (:math:`D - 2t = T`) or a constant factor :math:`c` (:math:`D + (1/c - 1)\,t = T`, the
    document's term is :math:`c` × the one that fits). The terms tried: those expanded, those
    as printed (:math:`k_1(\theta_1 - r_1)` whole), and the sum of the expanded terms that
    hold one symbol (the spring's two terms with :math:`k_1`)."""
    expanded = expanded_terms(expr)
    if not 1 < len(expanded) <= MAX_TERMS:
        return []
    values: dict[sp.Expr, np.ndarray] = {}

    def value(t: sp.Expr) -> np.ndarray:
        if t not in values:
            values[t] = np.broadcast_to(np.asarray(evaluate(t), float), D.shape)
        return values[t]
    printed = list(dict.fromkeys((*expanded, *sp.Add.make_args(expr))))
    # (the term, or the terms of a sum factored only where it is named; its values)
    trials: list[tuple[sp.Expr | tuple[sp.Expr, ...], np.ndarray]] = [
        (t, value(t)) for t in printed]
    sums = {frozenset(sp.Add.make_args(sp.expand(t))) for t in printed}
    for sym in sorted(expr.free_symbols, key=sp.default_sort_key):
        holding = tuple(t for t in expanded if t.has(sym))
        if 1 < len(holding) < len(expanded) and frozenset(holding) not in sums:
            sums.add(frozenset(holding))           # its values the sum of its terms' values
            trials.append((holding, sum((value(t) for t in holding), np.zeros(D.shape))))

    def text(x: sp.Expr | tuple[sp.Expr, ...]) -> str:
        return term_text(sp.factor_terms(sp.Add(*x)) if isinstance(x, tuple) else x)
    found = []
    for term, tv in trials:
        tt = float(tv @ tv)
        if math.sqrt(tt) <= AGREE_TOL * scale * math.sqrt(len(tv)):   # no square of scale:
            continue                                                   # it overflowed at 1e154
        if agrees(D - 2 * tv, T, scale):
            found.append(diagnosis(K.SIGN, f"the term {text(term)} has the wrong sign",
                                   term=text(term), factor="-1"))
            continue
        k = float((T - D) @ tv / tt)                  # T = D + k t, the document's term is
        if abs(1 + k) > 1e-12 and agrees(D + k * tv, T, scale) and \
                plausible_factor(1 / (1 + k)):                     # 1/(1+k) × what fits
            c = nice_number(1 / (1 + k))
            found.append(diagnosis(K.FACTOR, f"the term {text(term)} is {c} × what fits",
                                   term=text(term), factor=c))
    return found or _term_powers(expanded, value, D, T, scale)


#: Samples a term's trial power is screened on before it is checked on all.
POWER_SCREEN = 256


def _term_powers(terms: Sequence[sp.Expr], value: Callable[[sp.Expr], np.ndarray],
                 D: np.ndarray, T: np.ndarray, scale: float) -> list[Diagnosis]:
    r"""One term :math:`t` with a symbol :math:`s` to the power :math:`e` where :math:`e'`
    fits (:math:`e' \in \{-e, e \pm 1, 2e\}`), the rest right: :math:`D - t +
    t\,s^{e'-e} = T` (a length where its square fits in one term, the others holding it
    rightly)."""
    screen = np.linspace(0, len(D) - 1, min(len(D), POWER_SCREEN)).astype(int)
    for t in terms:
        for base, e in (f.as_base_exp() for f in sp.Mul.make_args(t)):
            if not (base.is_Symbol and e.is_Rational and e != 0):
                continue
            tv, sv = value(t), value(base)
            if agrees(D - tv, T, scale):
                return []    # the term left out agrees: it is extra, not to another power
            for new in dict.fromkeys((-e, e - 1, e + 1, 2 * e)):
                with np.errstate(all="ignore"):
                    seen = D[screen] - tv[screen] + tv[screen] * sv[screen] ** float(new - e)
                    if new == 0 or not agrees(seen, T[screen], scale):
                        continue             # screened on a few samples: most trials end here
                    trial = D - tv + tv * sv ** float(new - e)
                if agrees(trial, T, scale):
                    return [diagnosis(K.POWER, f"{sp.sstr(base ** e)} where "
                                      f"{sp.sstr(base ** new)} fits in the term {sp.sstr(t)}",
                                      written=sp.sstr(base ** e), fits=sp.sstr(base ** new),
                                      term=sp.sstr(t))]
    return []


_TRIG_SWAP = {sp.sin: sp.cos, sp.cos: sp.sin}


def _argument_trials(expr: sp.Expr) -> list[tuple[sp.Expr, sp.Expr]]:
    r"""(written, trial) for the arguments of ``expr``'s sines, cosines and tangents: a tangent
    read as the sine of its argument, and an argument that is a sum with one of its terms'
    sign flipped or the term left out (cos(θ₁ + θ₂) where cos(θ₁ − θ₂) fits; cos(q₁ + q₂)
    where cos q₂ does)."""
    out = [(f, sp.sin(f.args[0])) for f in sorted(expr.atoms(sp.tan), key=sp.default_sort_key)]
    for f in sorted(expr.atoms(sp.sin, sp.cos, sp.tan), key=sp.default_sort_key):
        a = f.args[0]
        if not isinstance(a, sp.Add):
            continue
        for t in sp.Add.make_args(a):
            out += [(f, f.func(a - 2 * t)), (f, f.func(a - t))]
    return out


def _swap(written: sp.Expr, fits: sp.Expr, both: bool) -> Diagnosis:
    r"""The diagnosis of :func:`trig_swap_diagnoses` for ``written`` where ``fits`` fits,
    or, ``both``, the sine and cosine of one argument exchanged (made only for a reading
    that agrees: printing every trial's was much of the search's time)."""
    if both:
        return diagnosis(K.SWAP, f"{sp.sstr(written)} and {sp.sstr(fits)} exchanged (sin "
                         "written for cos and cos for sin)", written=sp.sstr(written),
                         fits=sp.sstr(fits))
    return diagnosis(K.SWAP, f"{sp.sstr(written)} where {sp.sstr(fits)} fits",
                     written=sp.sstr(written), fits=sp.sstr(fits))


def trig_swap_diagnoses(expr: sp.Expr, evaluate_many: Callable[[list], list[np.ndarray]],
                        T: np.ndarray, scale: float) -> list[Diagnosis]:
    r"""A sin written for a cos (or the reverse): everywhere it occurs, both exchanged for one
    argument, or — when neither fits — in one printed (else expanded) additive term only; a
    tangent for a sine, and a wrong argument (:func:`_argument_trials`) everywhere it occurs.
    ``evaluate_many`` evaluates a list of expressions at the samples in one compiled call."""
    atoms = sorted(expr.atoms(sp.sin, sp.cos), key=sp.default_sort_key)
    if not atoms and not expr.has(sp.tan):
        return []
    args = sorted({f.args[0] for f in atoms}, key=sp.default_sort_key)
    # (what is written, what fits, whether both of one argument are exchanged; the trial)
    whole = [((f, _TRIG_SWAP[f.func](*f.args), False),
              expr.xreplace({f: _TRIG_SWAP[f.func](*f.args)})) for f in atoms]
    whole += [((sp.sin(a), sp.cos(a), True),
               expr.xreplace({sp.sin(a): sp.cos(a), sp.cos(a): sp.sin(a)}))
              for a in args if expr.has(sp.sin(a)) and expr.has(sp.cos(a))]
    whole += [((f, o, False), expr.xreplace({f: o})) for f, o in _argument_trials(expr)]
    values = evaluate_many([e for _, e in whole])
    fitting = [what for (what, _), v in zip(whole, values) if agrees(v, T, scale)]
    if fitting:                # one function for another first, then both exchanged
        return [_swap(*what) for what in [w for w in fitting if not w[2]] or fitting]
    for terms in (sp.Add.make_args(expr), expanded_terms(expr)):
        if len(terms) > MAX_TERMS:
            continue
        trials = [(k, f, _TRIG_SWAP[f.func](*f.args)) for k, term in enumerate(terms)
                  for f in sorted(term.atoms(sp.sin, sp.cos), key=sp.default_sort_key)]
        if not trials:
            continue
        values = evaluate_many([*terms, *(terms[k].xreplace({f: o}) for k, f, o in trials)])
        total = sum(values[:len(terms)])
        found = [diagnosis(K.SWAP, f"{sp.sstr(f)} where {sp.sstr(o)} fits in the term "
                           f"{sp.sstr(terms[k])}", written=sp.sstr(f), fits=sp.sstr(o),
                           term=sp.sstr(terms[k]))
                 for (k, f, o), v in zip(trials, values[len(terms):])
                 if agrees(total - values[k] + v, T, scale)]
        if found:
            return found
    return []

