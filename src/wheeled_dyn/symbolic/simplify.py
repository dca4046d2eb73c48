r"""Fast trigonometric simplification, collected by parameter.

The entries of :math:`A, C, Q` built from 1-DoF joints are polynomials in the parameters, the
prismatic coordinates and :math:`\sin q_k, \cos q_k`. Such a polynomial has a *canonical* form
modulo the ideal :math:`\langle s_k^2 + c_k^2 - 1\rangle` (:mod:`.trigpoly`): every
:math:`s_k^{e},\ e \ge 2` is rewritten as :math:`s_k^{e \bmod 2}(1 - c_k^2)^{\lfloor e/2\rfloor}`.
Two such expressions are equal as functions iff their canonical forms are equal, so
:func:`canonical_trig` is an exact zero test, and a cheap one (sparse polynomial arithmetic, no
pattern search).

:func:`simplify_expr` groups the terms by monomials in the parameter symbols
(:math:`\sum_\pi \pi\, f_\pi(q)`, the layout of Khalil's closed forms) and writes each
coefficient :math:`f_\pi` in the shortest of a few forms (:func:`polish_trig`, e.g.
:math:`1 - \cos^2\phi \to \sin^2\phi`,
:math:`\cos\phi\cos\theta - \sin\phi\sin\theta \to \cos(\phi+\theta)`). Float coefficients
that are pure round-off (:math:`|c| \le \texttt{chop}\cdot \max |c|` within one entry) are
dropped.
"""

from __future__ import annotations

import importlib
from functools import lru_cache
from collections.abc import Iterable, Sequence

import sympy as sp

from .trigpoly import NotPolynomial, TrigRing

_fu = importlib.import_module("sympy.simplify.fu")  # the module, not the function ``fu``

#: Relative size below which a float coefficient is treated as round-off and dropped.
DEFAULT_CHOP: float = 1e-13
#: Largest ``count_ops`` of a coefficient that :func:`polish_trig` rewrites.
TRIG_POLISH_MAX_OPS: int = 60
#: Largest number of terms of a coefficient that :func:`polish_trig` rewrites (``TR10i`` looks
#: at pairs of terms).
TRIG_POLISH_MAX_TERMS: int = 8
#: Entries with more parameter groups than this are left in canonical form (not polished).
POLISH_MAX_GROUPS: int = 60


def _chop(terms: list[tuple[tuple[int, ...], sp.Expr]], chop: float) -> list:
    if chop <= 0:
        return terms
    if not any(v.is_Float for _, v in terms):
        return terms
    limit = chop * max(abs(complex(v)) for _, v in terms)
    return [(m, v) for m, v in terms if v != 0 and not (v.is_Float and abs(float(v)) <= limit)]


def _monomial(gens: Sequence[sp.Expr], mon: Iterable[int]) -> sp.Expr:
    return sp.Mul(*[g ** k for g, k in zip(gens, mon) if k])


def canonical_trig(expr: sp.Expr, chop: float = DEFAULT_CHOP) -> sp.Expr:
    r"""Expanded canonical form of ``expr`` modulo :math:`\sin^2 + \cos^2 = 1` (sines to the
    first power at most); falls back to ``trigsimp`` for non-polynomial expressions."""
    expr = sp.sympify(expr)
    try:
        ring, (p,) = TrigRing.from_exprs([expr])
    except NotPolynomial:
        return _trigsimp(expr)
    gens = ring.symbols()
    return sp.Add(*[cf * _monomial(gens, m) for m, cf in _chop(ring.terms(p), chop)])


#: Operations of the largest expression :func:`_trigsimp` simplifies: a spherical pendulum's
#: terms under a map of atan2 and asin kept ``trigsimp`` busy for more than 11 minutes (with
#: this bound alone, 39 s, one run: such maps get no closed forms,
#: :func:`~.wheeled.trig_polynomial_map`).
TRIGSIMP_OPS = 200


def _trigsimp(expr: sp.Expr) -> sp.Expr:
    r"""``sympy.trigsimp(expr)`` where ``expr`` has at most :data:`TRIGSIMP_OPS` operations,
    else ``expr`` as it is (the forms are for reading: a longer one is not read either)."""
    return sp.trigsimp(expr) if sp.count_ops(expr) <= TRIGSIMP_OPS else expr


def _has_trig_products(expr: sp.Expr) -> bool:
    """Whether a term holds a power or a product of sines/cosines of one angle (where the
    products-to-sums rewrite can shorten)."""
    for term in sp.Add.make_args(expr):
        args: list[sp.Expr] = []
        for f in sp.Mul.make_args(term):
            base, e = f.as_base_exp()
            if isinstance(base, (sp.sin, sp.cos)):
                if e != 1:
                    return True
                args.append(base.args[0])
        if len(args) != len(set(args)):
            return True
    return False


@lru_cache(maxsize=8192)
def polish_trig(expr: sp.Expr) -> sp.Expr:
    r"""The shortest (``count_ops``) of a few cheap rewritings of a trigonometric polynomial:
    itself, :math:`\cos^2 \to 1-\sin^2`, sums of products to functions of sums (``fu.TR10i``),
    products to sums (``fu.TR8``, e.g. :math:`2\sin\phi\cos\phi \to \sin 2\phi`) and both.
    About 5 times faster than ``trigsimp`` on the coefficients met here, and as short."""
    if expr.is_number or not expr.has(sp.sin, sp.cos) or expr.has(sp.Float) \
            or len(sp.Add.make_args(expr)) > TRIG_POLISH_MAX_TERMS \
            or sp.count_ops(expr) > TRIG_POLISH_MAX_OPS:
        return expr  # float coefficients (random geometry) rarely combine; not worth it
    cands = [expr, sp.expand(_fu.TR6(expr)), _fu.TR10i(expr)]
    if _has_trig_products(expr):
        t8 = _fu.TR8(expr)
        cands += [t8, _fu.TR10i(t8)]
    return min(cands, key=lambda e: (sp.count_ops(e), len(sp.Add.make_args(e)),
                                     sp.default_sort_key(e)))


def collect_terms(ring: TrigRing, p, parameters: Iterable[sp.Symbol] | None = None,
                  chop: float = DEFAULT_CHOP, trig: bool = True) -> sp.Expr:
    r"""A ring element as :math:`\sum_\pi \pi\, f_\pi` over monomials :math:`\pi` in
    ``parameters`` (default: every generator that is a plain symbol and no angle). With
    ``trig``, each :math:`f_\pi` is polished (:func:`polish_trig`) unless the entry has more
    than :data:`POLISH_MAX_GROUPS` of them (too long to read anyway)."""
    gens = ring.symbols()
    if parameters is None:
        inside = set().union(set(), *[x.free_symbols for x in ring.pairs])
        pset = {g for i, g in enumerate(gens)
                if g.is_Symbol and not ring.is_trig(i) and g not in inside}
    else:
        pset = set(parameters)
    # 1/R, sqrt(m) ... count as parameters when their symbols all are
    is_par = [g in pset or (not g.is_Symbol and bool(g.free_symbols)
                            and g.free_symbols <= pset) for g in gens]
    groups: dict[tuple[int, ...], list] = {}
    for mon, cf in _chop(ring.terms(p), chop):
        pkey = tuple(k if isp else 0 for k, isp in zip(mon, is_par))
        rest = tuple(0 if isp else k for k, isp in zip(mon, is_par))
        groups.setdefault(pkey, []).append(cf * _monomial(gens, rest))
    trig = trig and len(groups) <= POLISH_MAX_GROUPS
    out = []
    for pkey in sorted(groups, key=lambda k: (sum(k), k)):
        coef = sp.Add(*groups[pkey])
        out.append(_monomial(gens, pkey) * (polish_trig(coef) if trig else coef))
    return sp.Add(*out)


def simplify_expr(expr: sp.Expr, parameters: Iterable[sp.Symbol] | None = None,
                  chop: float = DEFAULT_CHOP, trig: bool = True) -> sp.Expr:
    r"""Canonical trigonometric form of ``expr`` collected by parameter monomials.

    ``parameters``: the symbols to collect on (default: every free symbol that does not occur
    inside a sine or cosine). ``trig=False`` skips the :func:`polish_trig` step (the result is
    then canonical: equal functions give identical expressions).
    """
    expr = sp.sympify(expr)
    try:
        ring, (p,) = TrigRing.from_exprs([expr])
    except NotPolynomial:
        # trigsimp factors: with the floats of a rounded URDF angle (cos(1.57)) in a quotient
        # it ran for minutes; such an expression is left as it is
        return expr if expr.has(sp.Float) else _trigsimp(expr)
    return collect_terms(ring, p, parameters, chop=chop, trig=trig)


def simplify_matrix(M: sp.MatrixBase, parameters: Iterable[sp.Symbol] | None = None,
                    chop: float = DEFAULT_CHOP, trig: bool = True) -> sp.Matrix:
    """:func:`simplify_expr` on every entry (identical entries, e.g. the two halves of a
    symmetric matrix, are simplified once)."""
    pars = None if parameters is None else tuple(parameters)
    done: dict[sp.Expr, sp.Expr] = {}

    def one(e: sp.Expr) -> sp.Expr:
        if e not in done:
            done[e] = simplify_expr(e, pars, chop=chop, trig=trig)
        return done[e]

    return sp.Matrix(M).applyfunc(one)


def is_zero(expr: sp.Expr, atol: float = 0.0) -> bool:
    """Exact zero test through the canonical form; with ``atol > 0`` float coefficients up to
    ``atol`` in magnitude count as zero (round-off)."""
    expr = sp.sympify(expr)
    try:
        ring, (p,) = TrigRing.from_exprs([expr])
    except NotPolynomial:
        return sp.simplify(expr) == 0
    return all(abs(complex(v)) <= atol for _, v in ring.terms(p))
