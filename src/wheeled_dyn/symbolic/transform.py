r"""Change of velocity coordinates and reduction by constraints, in closed form.

With :math:`\dot q = S(q)\,\nu` (quasi-velocities :math:`\nu`; :math:`S` spanning the null space
of rolling constraints, or an invertible change of coordinates) and therefore
:math:`\ddot q = S\dot\nu + \dot S\nu`, projecting :math:`A\ddot q + C\dot q + Q = B u` on
:math:`S^T` gives

.. math::
   A_\nu \dot\nu + C_\nu \nu + Q_\nu = B_\nu u, \qquad
   A_\nu = S^T A S,\quad C_\nu = S^T C(q, S\nu)\, S + S^T A \dot S,\quad
   Q_\nu = S^T Q,\quad B_\nu = S^T B,

and :math:`h_\nu = C_\nu \nu`. :math:`C_\nu` is not Christoffel-consistent in :math:`\nu`
unless :math:`\nu = \dot q'` for some coordinates :math:`q'` (Boltzmann–Hamel); :math:`h_\nu`
is unique. After the products, ``subs`` maps the model coordinates (and any other symbol) to the
document's, and every entry is brought to the canonical form of :mod:`.simplify`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import sympy as sp

from ..errors import ModelError
from .model import SymbolicModel
from .simplify import collect_terms, simplify_expr
from .trigpoly import NotPolynomial, TrigRing


@dataclass(frozen=True, eq=False)
class ReducedSymbolic:
    r"""Closed forms in quasi-velocities: ``A``, ``C``, ``Q``, ``h`` (:math:`C_\nu\nu`) and
    ``B`` (None if no input matrix was given); ``q``: the coordinates they depend on (document
    coordinates after ``subs``); ``nu``: the quasi-velocity symbols; ``parameters``: every other
    free symbol (the model's parameters first); ``params``: the model's standard parameters per
    joint (after ``subs``); ``S``, ``Sdot``: as given, after ``subs``; ``G``: the constraint
    matrix :math:`J_c S` when constraints are kept with multipliers (else None)."""

    q: tuple[sp.Symbol, ...]
    nu: tuple[sp.Symbol, ...]
    parameters: tuple[sp.Symbol, ...]
    params: Mapping[int, tuple[sp.Expr, ...]]
    A: sp.Matrix
    C: sp.Matrix
    Q: sp.Matrix
    h: sp.Matrix
    B: sp.Matrix | None
    S: sp.Matrix
    Sdot: sp.Matrix
    G: sp.Matrix | None = None

    @property
    def velocities(self) -> tuple[sp.Symbol, ...]:
        """Same as ``nu`` (the name shared with :class:`~.model.SymbolicModel`)."""
        return self.nu

    def terms(self) -> dict[str, sp.Matrix]:
        """``{"A", "C", "Q", "h"}`` and ``"B"``, ``"G"`` when present."""
        out = {"A": self.A, "C": self.C, "Q": self.Q, "h": self.h}
        if self.B is not None:
            out["B"] = self.B
        if self.G is not None:
            out["G"] = self.G
        return out


def time_derivative(M: sp.MatrixBase, q: Sequence[sp.Symbol], qdot: Sequence[sp.Expr]
                    ) -> sp.Matrix:
    r""":math:`\dot M = \sum_k \partial M/\partial q_k\,\dot q_k` (e.g. :math:`\dot S`)."""
    M = sp.Matrix(M)
    out = sp.zeros(*M.shape)
    for qk, vk in zip(q, qdot):
        out += M.diff(qk) * vk
    return out.applyfunc(sp.expand)


def _products(flat: list[sp.Expr], n: int, m: int, k: int | None, nu: Sequence[sp.Symbol],
              extra: Sequence[sp.Symbol]) -> tuple[TrigRing | None, list]:
    r"""Entries of :math:`A_\nu, C_\nu, Q_\nu, h_\nu, B_\nu` (row-major, in this order)
    from ``flat`` = A (n×n), c (n×n×n), Q, S (n×m), Sdot (n×m), B (n×k); computed in a
    trigonometric ring when possible (ring returned), else on SymPy expressions (None)."""
    try:
        ring, el = TrigRing.from_exprs(flat, extra=tuple(extra) + tuple(nu))
        zero = ring.ring.zero
        nup = [ring.gen(x) for x in nu]
    except NotPolynomial:
        ring, zero, el, nup = None, sp.Integer(0), [sp.sympify(e) for e in flat], list(nu)
    A = [el[i * n:(i + 1) * n] for i in range(n)]
    el = el[n * n:]
    cp = [[el[(i * n + j) * n:(i * n + j + 1) * n] for j in range(n)] for i in range(n)]
    el = el[n ** 3:]
    Q, el = el[:n], el[n:]
    Sp = [el[i * m:(i + 1) * m] for i in range(n)]
    el = el[n * m:]
    Sdp = [el[i * m:(i + 1) * m] for i in range(n)]
    Bp = el[n * m:]

    def total(items):
        return sum(items, zero)

    def mul(X, Y, inner):
        return [[total(X[i][a] * Y[a][j] for a in range(inner)) for j in range(len(Y[0]))]
                for i in range(len(X))]

    St = [[Sp[j][i] for j in range(n)] for i in range(m)]
    Snu = [total(Sp[a][b] * nup[b] for b in range(m)) for a in range(n)]
    Cq = [[total(cp[i][j][a] * Snu[a] for a in range(n)) for j in range(n)] for i in range(n)]
    Anu = mul(St, mul(A, Sp, n), n)
    Cnu = mul(St, mul(Cq, Sp, n), n)
    ASd = mul(St, mul(A, Sdp, n), n)
    Cnu = [[Cnu[i][j] + ASd[i][j] for j in range(m)] for i in range(m)]
    hnu = [total(Cnu[i][j] * nup[j] for j in range(m)) for i in range(m)]
    Qnu = [total(St[i][a] * Q[a] for a in range(n)) for i in range(m)]
    out = [x for row in Anu for x in row] + [x for row in Cnu for x in row] + Qnu + hnu
    if k is not None:
        Bm = [Bp[i * k:(i + 1) * k] for i in range(n)]
        out += [x for row in mul(St, Bm, n) for x in row]
    if ring is not None:
        out = [ring.reduce(x) for x in out]
    return ring, out


def _replace(e: sp.Expr, subs: Mapping) -> sp.Expr:
    if not subs:
        return e
    if all(isinstance(key, sp.Symbol) for key in subs):
        return sp.sympify(e).xreplace(subs)
    return sp.sympify(e).subs(subs, simultaneous=True)


def transform(sym: SymbolicModel, S: sp.MatrixBase, Sdot: sp.MatrixBase,
              nu: Sequence[sp.Symbol], subs: Mapping[sp.Expr, sp.Expr] | None = None,
              B: sp.MatrixBase | None = None, coordinates: Sequence[sp.Symbol] | None = None,
              simplify: bool = True) -> ReducedSymbolic:
    r"""The equations of ``sym`` in quasi-velocities ``nu`` with :math:`\dot q = S\nu`.

    ``S`` (n×m) and ``Sdot`` are functions of the model coordinates ``sym.q`` (and of
    parameters); the model velocities in ``Sdot`` are replaced by :math:`S\nu`. ``subs`` maps
    model coordinates to document coordinates (and may rename parameters); it is applied
    simultaneously to every factor before the products, which is the same as applying it to
    the results. ``B``: the model's input matrix (n×k), optional. ``coordinates``: the
    coordinates of the result (default: the free symbols of the images of ``sym.q`` under
    ``subs``, in order). ``simplify``: polish the collected canonical forms for reading.
    Raises :class:`ModelError` on shape mismatches.
    """
    S, Sdot = sp.Matrix(S), sp.Matrix(Sdot)
    n, nu = sym.n, tuple(nu)
    m = len(nu)
    if S.shape != (n, m) or Sdot.shape != S.shape:
        raise ModelError("<symbolic>", None, f"S is {S.shape}, Sdot {Sdot.shape}: expected "
                         f"({n}, {m}) for {n} model velocities and {m} quasi-velocities")
    if B is not None:
        B = sp.Matrix(B)
        if B.shape[0] != n:
            raise ModelError("<symbolic>", None, f"B has {B.shape[0]} rows, expected {n}")
    subs = dict(subs or {})
    Sd = Sdot.xreplace(dict(zip(sym.qd, S * sp.Matrix(nu))))
    c = sym.christoffel_symbols
    flat = list(sym.A_canonical) + [c[i][j][k] for i in range(n) for j in range(n)
                                    for k in range(n)] + list(sym.Q) + list(S) + list(Sd)
    if B is not None:
        flat += list(B)
    done: dict[sp.Expr, sp.Expr] = {}
    flat = [done.setdefault(e, _replace(e, subs)) if e not in done else done[e] for e in flat]

    if coordinates is None:
        coords: dict[sp.Symbol, None] = {}
        for qi in sym.q:
            for s in sorted(_replace(qi, subs).free_symbols, key=sp.default_sort_key):
                if s not in sym.parameters and s not in nu:
                    coords.setdefault(s, None)
        coordinates = tuple(coords)
    coordinates = tuple(coordinates)

    k = None if B is None else B.shape[1]
    ring, out = _products(flat, n, m, k, nu, coordinates)
    if ring is not None:
        used = {i for x in out for mon in x.itermonoms() for i, e in enumerate(mon) if e}
        gens = ring.symbols()
        free = set().union(*[gens[i].free_symbols for i in used])
    else:
        free = set().union(*[x.free_symbols for x in out])
    pars = [p for p in sym.parameters if p in free]
    extra = free - set(pars) - set(coordinates) - set(nu)
    parameters = tuple(pars) + tuple(sorted(extra, key=sp.default_sort_key))
    by = parameters + nu
    if ring is not None:
        exprs = [collect_terms(ring, x, by, trig=simplify) for x in out]
    elif simplify:
        exprs = [simplify_expr(x, by) for x in out]
    else:
        exprs = [sp.expand(x) for x in out]
    Anu = sp.Matrix(m, m, exprs[:m * m])
    Cnu = sp.Matrix(m, m, exprs[m * m:2 * m * m])
    Qnu = sp.Matrix(exprs[2 * m * m:2 * m * m + m])
    hnu = sp.Matrix(exprs[2 * m * m + m:2 * m * m + 2 * m])
    Bnu = None if k is None else sp.Matrix(m, k, exprs[2 * m * m + 2 * m:])
    params = {j: tuple(_replace(x, subs) for x in pi) for j, pi in sym.params.items()}
    return ReducedSymbolic(q=coordinates, nu=nu, parameters=parameters, params=params,
                           A=Anu, C=Cnu, Q=Qnu, h=hnu, B=Bnu,
                           S=S.applyfunc(lambda e: _replace(e, subs)),
                           Sdot=Sd.applyfunc(lambda e: _replace(e, subs)))
