r"""One thing written for another: a symbol for another of its kind (everywhere in an element,
or once inside one product: :math:`l_{c1}l_1` where :math:`l_1^2` fits), and in h one velocity
product for another (:math:`\dot\varphi^2` where :math:`\dot\psi^2` fits).

Symbols are exchanged only within a group (velocities with velocities, positions with
positions, symbols of equal units with each other: :func:`~..sides.elements.swap_groups`). A
trial is first evaluated on the screening samples and on every sample only when it agrees
there, so the verdicts are those of the full grid.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...expression_size import ops_over
from ..records import Diagnosis, DiagnosisKind as K, Verdict, diagnosis, has_kind
from .diagnose import MAX_TERMS, agrees, swap_diagnoses
from .draft import ElementDraft


def symbol_swaps(d: ElementDraft, trials, groups: Sequence[Sequence[sp.Symbol]]
                 ) -> list[Diagnosis]:
    r"""One symbol read as another everywhere in the element (``trials``: the engine's
    :class:`~.element.Trials`)."""
    if d.expr is None:
        return []
    screen = trials.screen
    found = swap_diagnoses(
        d.expr, groups, lambda a, b: trials.swapped(d.key, d.index, a, b), d.T, d.scale,
        lambda a, b: agrees(trials.swapped(d.key, d.index, a, b, screen), d.T[screen],
                            d.scale))
    return found or exchanges(d, trials, groups) or definition_swaps(d, trials)


#: Largest element and definition (operations) a definition written for another is tried in.
DEFINITION_OPS = 60


def definition_swaps(d: ElementDraft, trials) -> list[Diagnosis]:
    r"""One of the file's ``[definitions]`` written where another fits (a document's
    :math:`d_2` for its :math:`d_3`): the element is a definition's expression times a factor
    free of its symbols, and the same factor times the other's agrees. Definitions of one
    expression are named together (``M12 or M21``: the file's text is read expanded)."""
    assert d.expr is not None, "an element as printed"
    if ops_over(d.expr, DEFINITION_OPS):
        return []
    alike, values = _definitions(trials, d.key)
    known, found = set(trials.funcs.args), []
    present = d.expr.free_symbols
    usable = list(values)
    for ea, a in alike.items():
        # written for another: the element is ratio*ea with ea's symbols in it, and
        # D*eb/ea is the truth where ea does not vanish (a screen: the symbolic ratio
        # below decides, on the full grid)
        if ea == 0 or not ea.free_symbols <= present or ea not in values:
            continue
        others = [eb for eb in usable if eb != ea and _may_fit(d, values[ea], values[eb])]
        if not others:
            continue
        ratio = sp.cancel(d.expr / ea)
        if ratio == 0 or sp.denom(ratio).free_symbols & ea.free_symbols:
            continue
        for eb in others:
            b = alike[eb]
            if (ratio * eb).free_symbols <= known and agrees(
                    trials.evaluator(d.key)(ratio * eb), d.T, d.scale):
                written, fits = " or ".join(a), " or ".join(b)
                found.append(diagnosis(K.SWAP, f"{written} where {fits} fits",
                                       written=written, fits=fits))
    return found


def _definitions(trials, key: str) -> tuple[dict[sp.Expr, list[str]], dict[sp.Expr, np.ndarray]]:
    r"""The file's definitions short enough to try, expanded, with the names of each, and
    the values of those in the document's symbols on the samples of ``key``'s elements (once
    per judgement)."""
    memo = trials.memo.get(("definitions", key))
    if memo is None:
        alike: dict[sp.Expr, list[str]] = {}
        for name, e in trials.funcs.d.definitions.items():
            if not ops_over(e, DEFINITION_OPS):  # a determinant: no entry written for another
                alike.setdefault(sp.expand(e), []).append(name)
        known = set(trials.funcs.args)
        memo = alike, {e: trials.evaluator(key)(e) for e in alike if e.free_symbols <= known}
        trials.memo[("definitions", key)] = memo
    return memo


#: How much looser than the verdict's tolerance :func:`_may_fit` screens (it may only let
#: through what the exact check then rejects).
SCREEN_SLACK = 10.0


def _may_fit(d: ElementDraft, ea: np.ndarray, eb: np.ndarray) -> bool:
    r"""Whether :math:`D\,e_b/e_a` can be the truth: at the samples where :math:`e_a` is a
    finite non-zero number (all of them, where none is: the exact check decides)."""
    ok = np.isfinite(ea) & (ea != 0) & np.isfinite(eb)
    if not ok.any():
        return True
    with np.errstate(all="ignore"):
        read = d.D[ok] * eb[ok] / ea[ok]
    return agrees(read, d.T[ok], SCREEN_SLACK * d.scale)


def exchanges(d: ElementDraft, trials, groups: Sequence[Sequence[sp.Symbol]]
              ) -> list[Diagnosis]:
    r"""Two symbols of a group the element writes, each where the other fits (:math:`J_{yy}`
    and :math:`J_{zz}` exchanged in :math:`J_{yy}\cos^2\alpha + J_{zz}\sin^2\alpha`): the
    element with both read so agrees."""
    assert d.expr is not None, "an element as printed"
    present, screen, found = d.expr.free_symbols, trials.screen, []
    for group in groups:
        for a, b in itertools.combinations(sorted((s for s in group if s in present),
                                                  key=str), 2):
            if agrees(trials.swapped(d.key, d.index, a, b, screen, True), d.T[screen],
                      d.scale) and agrees(trials.swapped(d.key, d.index, a, b, None, True),
                                          d.T, d.scale):
                found.append(diagnosis(K.SWAP, f"{sp.sstr(a)} and {sp.sstr(b)} exchanged "
                                       "(each written where the other fits)",
                                       written=sp.sstr(a), fits=sp.sstr(b)))
    return found


def _one_factor_trials(expr: sp.Expr, groups: Sequence[Sequence[sp.Symbol]]):
    r"""``(term, written, fits, the term read so)`` (written and fits as expressions, printed
    only for what is found): in one additive term, a symbol :math:`a` read as :math:`b` —
    everywhere in the term (:math:`a^2` becomes :math:`b^2`), or in one factor of a power
    (:math:`a^e` becomes :math:`a^{e-1}b`)."""
    members = {s: g for g in groups for s in g}
    terms = sp.Add.make_args(sp.expand(expr))
    if len(terms) > MAX_TERMS:
        return
    for t in terms:
        factors = sp.Mul.make_args(t)
        present = [f.as_base_exp() for f in factors if f.as_base_exp()[0] in members]
        if len(terms) == 1 and len(present) < 2:
            continue                              # one symbol alone: an ordinary swap
        for base, e in present:
            if not (e.is_Integer and e >= 1):
                continue
            for b in members[base]:
                if b == base:
                    continue
                yield (t, base ** e, b ** e, t.xreplace({base: b}))
                if e > 1:
                    new = t.xreplace({base ** e: base ** (e - 1) * b})
                    yield (t, base ** e, base ** (e - 1) * b, new)


def _exchange_trials(expr: sp.Expr, groups: Sequence[Sequence[sp.Symbol]]):
    r"""``(term, written, fits, the term read so)`` (as :func:`_one_factor_trials`): two
    symbols of one kind exchanged in one additive term (:math:`R^2/L^2` where
    :math:`L^2/R^2` fits)."""
    members = {s: g for g in groups for s in g}
    terms = sp.Add.make_args(sp.expand(expr))
    if len(terms) > MAX_TERMS or len(terms) == 1:
        return                     # one term: the element's own exchange names it
    for t in terms:
        bases = list(dict.fromkeys(f.as_base_exp()[0] for f in sp.Mul.make_args(t)
                                   if f.as_base_exp()[0] in members))
        for a, b in itertools.combinations(bases, 2):
            if b in members[a]:
                new = t.xreplace({a: b, b: a})
                yield (t, t, new, new)


#: Most trials of :func:`product_swaps` per element: a symbol for another, two exchanged.
MAX_PRODUCT_TRIALS, MAX_EXCHANGE_TRIALS = 48, 24


def product_swaps(expr: sp.Expr, trials, groups: Sequence[Sequence[sp.Symbol]], T: np.ndarray,
                  scale: float) -> list[Diagnosis]:
    r"""A symbol written for another inside one product of one additive term (the element
    everywhere else as printed): ``"lc1**2 where l1**2 fits in the term m2*lc1**2"``. The
    trials are screened on a few samples first, the element's value there with one term
    replaced (the terms compiled together, no trial element built), and every trial that
    agrees there is built and evaluated on every sample."""
    found: list[Diagnosis] = []
    candidates = [*itertools.islice(_one_factor_trials(expr, groups), MAX_PRODUCT_TRIALS),
                  *itertools.islice(_exchange_trials(expr, groups), MAX_EXCHANGE_TRIALS)]
    if not candidates:
        return found
    screen = trials.screen
    argv = trials.screened
    unique = list(dict.fromkeys([expr, *(c[0] for c in candidates),
                                 *(c[3] for c in candidates)]))
    with np.errstate(all="ignore"):
        at = {e: np.broadcast_to(np.asarray(v, float), (len(screen),)) for e, v in
              zip(unique, trials.funcs.compiled(tuple(unique))(*argv))}
    for term, written, fits, new in candidates:
        with np.errstate(all="ignore"):
            v = at[expr] - at[term] + at[new]
        if not agrees(v, T[screen], scale):
            continue
        with np.errstate(all="ignore"):
            if agrees(trials.evaluate(expr - term + new), T, scale):
                w, f, t = sp.sstr(written), sp.sstr(fits), sp.sstr(term)
                where = "" if w == t else f" in the term {t}"
                found.append(diagnosis(K.SWAP, f"{w} where {f} fits{where}",
                                       written=w, fits=f, term=t))
    return found


def h_swaps(drafts: Sequence[ElementDraft]) -> None:
    r"""Within a row of h, an extra term equal to a missing one: the document wrote one
    velocity product for another (e.g. φ̇² where ψ̇² fits)."""
    for extra in drafts:
        if extra.key != "h" or extra.verdict != Verdict.DIFFERS \
                or not has_kind(extra.diagnoses, K.EXTRA):
            continue
        for missing in drafts:
            if missing.key != "h" or missing.row != extra.row \
                    or not has_kind(missing.diagnoses, K.MISSING):
                continue
            if agrees(extra.D, missing.T, extra.scale):
                a = extra.element.split(":")[1]
                b = missing.element.split(":")[1]
                extra.diagnoses.append(diagnosis(K.SWAP, f"the document's {a} term is the true "
                                                 f"{b} term", written=a, fits=b))
                missing.diagnoses.append(diagnosis(K.SWAP, f"written as {a} in the document",
                                                   written=a, fits=b))


__all__ = ["h_swaps", "product_swaps", "symbol_swaps"]
