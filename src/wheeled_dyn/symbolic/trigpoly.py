r"""Trigonometric polynomials as elements of a sparse polynomial ring.

Every entry of :math:`A, Q, c_{i,jk}, h` of a tree of 1-DoF joints is a polynomial in the
parameters, the velocities, the prismatic coordinates and :math:`s_x = \sin x`,
:math:`c_x = \cos x` of the angles :math:`x`. :class:`TrigRing` maps such expressions into one
SymPy ``PolyRing`` (sparse, fast arithmetic) where

* the reduction :math:`s_x^{e} \to s_x^{e \bmod 2}(1-c_x^2)^{\lfloor e/2 \rfloor}` gives a
  canonical form (two expressions are equal as functions iff their reductions are equal);
* the derivative along a coordinate :math:`q` is
  :math:`\partial_q P = \partial_q P|_{\text{explicit}} + \sum_x \frac{\partial x}{\partial q}
  \left(c_x\,\partial_{s_x} P - s_x\,\partial_{c_x} P\right)` (angles :math:`x` linear in
  :math:`q`).

Anything else that is not a number (denominators like :math:`1/R`) becomes a ring generator
of its own; numbers are coefficients: exact rationals, algebraic numbers such as
:math:`\sqrt{2}/2` (an algebraic field), or, as soon as one float occurs, floats (``RR``).
:meth:`TrigRing.from_exprs` raises :class:`NotPolynomial` when that is impossible (a sine inside
a denominator, say); callers fall back to ``trigsimp``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from fractions import Fraction
from math import comb

import sympy as sp
from sympy.polys.constructor import construct_domain
from sympy.polys.polyutils import parallel_dict_from_expr
from sympy.polys.rings import PolyElement, PolyRing


#: Relative error within which :func:`simple_number` accepts a fraction for a float.
SIMPLE_NUMBER_RTOL: float = 1e-13


def simple_number(x: float, max_denominator: int = 1000) -> sp.Expr:
    """``x`` as a SymPy Rational if a fraction with denominator up to ``max_denominator``
    matches it within :data:`SIMPLE_NUMBER_RTOL` and reads no longer than the float (plus one
    character), else as a Float."""
    f = Fraction(x).limit_denominator(max_denominator)
    if abs(f - Fraction(x)) <= SIMPLE_NUMBER_RTOL * abs(x):
        r = sp.Rational(f.numerator, f.denominator)
        if len(str(r)) <= len(repr(x)) + 1:
            return r
    return sp.Float(x)


class NotPolynomial(ValueError):
    """An expression is not a polynomial in sines, cosines and other generators."""


class TrigRing:
    r"""A ``PolyRing`` over the generators of some expressions, sines and cosines replaced by
    generator pairs :math:`(s_x, c_x)`. Build with :meth:`from_exprs`."""

    def __init__(self, ring: PolyRing, pairs: dict[sp.Expr, tuple[int, int]],
                 back: dict[sp.Expr, sp.Expr]) -> None:
        self.ring = ring
        self.pairs = pairs  # angle -> (index of s, index of c) among ring.gens
        self._back = back
        self._index = {g: i for i, g in enumerate(ring.symbols)}
        self._symbols = tuple(g.xreplace(back) for g in ring.symbols)

    @classmethod
    def from_exprs(cls, exprs: Sequence[sp.Expr], extra: Iterable[sp.Symbol] = ()
                   ) -> tuple[TrigRing, list[PolyElement]]:
        """The ring of ``exprs`` (plus the symbols ``extra`` as generators) and the elements."""
        exprs = [sp.sympify(e) for e in exprs]
        split = {a: sp.expand_trig(a) for e in exprs for a in e.atoms(sp.sin, sp.cos)
                 if not a.args[0].is_Symbol}  # sin(a + b), cos(2a) -> products
        if split:
            exprs = [e.xreplace(split) for e in exprs]
        angles = sorted({a.args[0] for e in exprs for a in e.atoms(sp.sin, sp.cos)},
                        key=sp.default_sort_key)
        fwd, back, dummies = {}, {}, []
        for x in angles:
            s, c = sp.Dummy("s"), sp.Dummy("c")
            fwd[sp.sin(x)], fwd[sp.cos(x)] = s, c
            back[s], back[c] = sp.sin(x), sp.cos(x)
            dummies += [s, c]
        mapped = [e.xreplace(fwd) for e in exprs]
        extra = list(extra) + dummies
        if not extra and not any(e.free_symbols for e in mapped):
            extra = [sp.Dummy("one")]  # a ring needs at least one generator
        try:
            reps, gens = parallel_dict_from_expr(mapped + extra)
            numeric = [g for g in gens if not g.free_symbols]  # sqrt(2), pi: coefficients
            if numeric:
                gens = tuple(g for g in gens if g.free_symbols)
                reps, gens = parallel_dict_from_expr(mapped + extra, gens=gens)
        except (sp.PolynomialError, sp.GeneratorsNeeded) as exc:
            raise NotPolynomial(str(exc)) from exc
        trig = set(dummies)
        for g in gens:
            if g not in trig and g.free_symbols & trig:
                raise NotPolynomial(f"sine or cosine inside the generator {g}")
        reps = reps[:len(mapped)]
        coeffs = [c for r in reps for c in r.values()] or [sp.Integer(0)]
        if any(c.has(sp.Float) for c in coeffs):  # floats: all arithmetic in floats (RR)
            coeffs = [sp.Float(c) for c in coeffs]
        domain, converted = construct_domain(coeffs, field=True, extension=True)
        ring = PolyRing(gens, domain)
        it = iter(converted)
        elems = [ring.from_dict({mon: next(it) for mon in r}) for r in reps]
        idx = {g: i for i, g in enumerate(gens)}
        pairs = {x: (idx[fwd[sp.sin(x)]], idx[fwd[sp.cos(x)]]) for x in angles}
        self = cls(ring, pairs, back)
        return self, [self.reduce(e) for e in elems]

    def gen(self, symbol: sp.Symbol) -> PolyElement:
        """The ring element of a generator symbol (given in ``extra`` or met in the exprs)."""
        return self.ring.gens[self._index[symbol]]

    def reduce(self, p: PolyElement) -> PolyElement:
        r"""Canonical form: each :math:`s_x^e,\ e\ge2` rewritten with :math:`1 - c_x^2`."""
        if not self.pairs or not any(m[i] >= 2 for m in p for i, _ in self.pairs.values()):
            return p
        out: dict[tuple[int, ...], object] = {}
        zero = self.ring.domain.zero
        for monom, coeff in p.items():
            terms = [(monom, coeff)]
            for i_s, i_c in self.pairs.values():
                new = []
                for mon, cf in terms:
                    e = mon[i_s]
                    if e < 2:
                        new.append((mon, cf))
                        continue
                    n = e // 2
                    for k in range(n + 1):  # (1 - c^2)^n
                        m2 = list(mon)
                        m2[i_s], m2[i_c] = e % 2, mon[i_c] + 2 * k
                        new.append((tuple(m2), cf * comb(n, k) * (-1) ** k))
                terms = new
            for mon, cf in terms:
                out[mon] = out.get(mon, zero) + cf
        return self.ring.from_dict({m: c for m, c in out.items() if c})

    def diff(self, p: PolyElement, q: sp.Symbol) -> PolyElement:
        r""":math:`\partial P / \partial q`, canonical (angles must be linear in ``q``)."""
        out = self.ring.zero
        if q in self._index:
            out += p.diff(self.gen(q))
        gens = self.ring.gens
        for x, (i_s, i_c) in self.pairs.items():
            dx = sp.diff(x, q)
            if dx == 0:
                continue
            if dx.free_symbols:
                raise NotPolynomial(f"angle {x} is not linear in {q}")
            term = gens[i_c] * p.diff(gens[i_s]) - gens[i_s] * p.diff(gens[i_c])
            out += term * self.ring.domain.convert(dx)
        return self.reduce(out)

    def to_expr(self, p: PolyElement) -> sp.Expr:
        """Back to a SymPy expression (sines and cosines restored, expanded)."""
        return p.as_expr().xreplace(self._back)

    def terms(self, p: PolyElement) -> list[tuple[tuple[int, ...], sp.Expr]]:
        """``[(monomial exponents, SymPy coefficient)]`` of ``p``; over the reals, a float
        coefficient that is a simple fraction (``1.0``, ``0.5``, ``0.04000000000000001``)
        comes back exact (:func:`simple_number`)."""
        dom = self.ring.domain
        if dom.is_RealField:
            return [(m, simple_number(float(c))) for m, c in p.items()]
        return [(m, dom.to_sympy(c)) for m, c in p.items()]

    def symbols(self) -> tuple[sp.Expr, ...]:
        """The generators as SymPy expressions, sines and cosines restored."""
        return self._symbols

    def is_trig(self, i: int) -> bool:
        """Whether generator ``i`` stands for a sine or a cosine."""
        return self.ring.symbols[i] in self._back
