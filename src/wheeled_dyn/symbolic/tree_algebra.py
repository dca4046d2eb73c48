r"""The algebra of the tree's closed forms (:mod:`.tree`): intermediate variables and 3- and
6-vectors of SymPy expressions as lists.

- :class:`Namer` names every quantity that is not a number, a symbol or a number times a
  symbol (``<prefix><n>``, real), and gives an expression met before (or its negative) its
  earlier name, so a tree's closed forms stay linear in its size;
- :class:`Body` holds a body's standard parameters :math:`(m, h = mc, I_O)` in one frame and
  applies its spatial inertia to a motion :math:`(\omega, v)`:
  :math:`(I\omega + h\times v,\ m v + \omega\times h)`;
- :func:`motion_cross` is the spatial motion cross product
  :math:`(\omega_1, v_1)\times(\omega_2, v_2) = (\omega_1\times\omega_2,\
  \omega_1\times v_2 + v_1\times\omega_2)`; :func:`mv`, :func:`mtv` apply :math:`R` and
  :math:`R^T`; :func:`sym3` unpacks Pinocchio's inertia order ``xx, xy, yy, xz, yz, zz``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import sympy as sp

Vec = list  # three (or six) SymPy expressions


class Namer:
    r"""Records intermediate variables ``<prefix><n>``; numbers, symbols and their negatives
    are kept as they are, an expression met before gets its earlier name."""

    def __init__(self) -> None:
        self.assignments: list[tuple[sp.Symbol, sp.Expr]] = []
        self.seen: dict[sp.Expr, sp.Expr] = {}
        self.count = 0

    def __call__(self, e: sp.Expr, prefix: str) -> sp.Expr:
        e = sp.expand(e) if e.is_Add or e.is_Mul else e
        if e.is_Number or e.is_Symbol or (e.is_Mul and len(e.args) == 2 and e.args[0].is_Number
                                          and e.args[1].is_Symbol):
            return e
        if e in self.seen:
            return self.seen[e]
        neg = -e
        if neg in self.seen:
            return -self.seen[neg]
        self.count += 1
        w = sp.Symbol(f"{prefix}{self.count}", real=True)
        self.assignments.append((w, e))
        self.seen[e] = w
        return w

    def vec(self, v: Vec, prefix: str) -> Vec:
        r"""Each entry of ``v`` named."""
        return [self(x, prefix) for x in v]


def cross(a: Vec, b: Vec) -> Vec:
    r""":math:`a \times b`."""
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a: Vec, b: Vec) -> sp.Expr:
    r""":math:`a \cdot b`."""
    return sp.Add(*[x * y for x, y in zip(a, b)])


def mv(R: sp.Matrix, v: Vec) -> Vec:
    r""":math:`R v`."""
    return [sp.Add(*[R[i, k] * v[k] for k in range(3)]) for i in range(3)]


def mtv(R: sp.Matrix, v: Vec) -> Vec:
    r""":math:`R^T v`."""
    return [sp.Add(*[R[k, i] * v[k] for k in range(3)]) for i in range(3)]


def sym3(I6: Vec) -> list[list[sp.Expr]]:
    r"""The symmetric 3×3 matrix of ``xx, xy, yy, xz, yz, zz``."""
    xx, xy, yy, xz, yz, zz = I6
    return [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]


@dataclass
class Body:
    r"""A body's standard parameters in one frame: mass, first moment :math:`h = mc`,
    inertia about the frame origin."""

    m: sp.Expr
    h: Vec
    I: Vec  # xx, xy, yy, xz, yz, zz (Pinocchio's order)

    def apply(self, motion: Vec) -> Vec:
        r"""The momentum :math:`K m` of the motion ``(ω, v)``: ``(n, f)`` with
        :math:`n = I\omega + h\times v`, :math:`f = m v + \omega\times h`."""
        w, v = motion[:3], motion[3:]
        M = sym3(self.I)
        n = [sp.Add(*[M[i][k] * w[k] for k in range(3)]) for i in range(3)]
        hv = cross(self.h, v)
        wh = cross(w, self.h)
        return [n[i] + hv[i] for i in range(3)] + [self.m * v[i] + wh[i] for i in range(3)]


def motion_cross(a: Vec, b: Vec) -> Vec:
    r"""The spatial motion cross product (module docstring)."""
    w1, v1, w2, v2 = a[:3], a[3:], b[:3], b[3:]
    x, y, z = cross(w1, w2), cross(w1, v2), cross(v1, w2)
    return x + [y[i] + z[i] for i in range(3)]


class TooLarge(Exception):
    r"""An expression grew past the limit of :func:`inliner` (internal: callers give up)."""


def inliner(assignments: Sequence[tuple[sp.Symbol, sp.Expr]], expand: bool = False,
            limit: int | None = None) -> Callable[[sp.Expr], sp.Expr]:
    r"""A function replacing every intermediate variable :math:`w_k = f_k(\dots)` of
    ``assignments`` in an expression by its definition, each definition written out once (a
    shared memo). With ``expand`` each one and the result are expanded, and an expression of
    more than ``limit`` terms raises :class:`TooLarge`."""
    definitions = dict(assignments)
    memo: dict[sp.Symbol, sp.Expr] = {}

    def done(e: sp.Expr, what: str) -> sp.Expr:
        if not expand:
            return e
        out = sp.expand(e)
        if limit is not None and len(sp.Add.make_args(out)) > limit:
            raise TooLarge(what)
        return out

    def full(e: sp.Expr, what: str = "element") -> sp.Expr:
        subs = {}
        for s in e.free_symbols:
            if s in definitions:
                if s not in memo:
                    memo[s] = full(definitions[s], str(s))      # expanded once, checked
                subs[s] = memo[s]
        return done(e.xreplace(subs) if subs else e, what)

    return full
