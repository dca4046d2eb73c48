r"""Expressions of a comparison table as text and as identities: a document's expression in
the table's namespace, its shortest printed form (remembered on disk), and whether two
expressions are equal identically (checked at random values of every symbol)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import sympy as sp

from ....compiled import numpy_function
from ....derivations.schema import Derivation
from ....derivations.table import ComparisonTable
from ....disk_cache import DiskMemo


#: Random points of the identity checks of printed expressions, and their tolerance.
CHECK_POINTS, CHECK_TOL = 12, 1e-9


def in_table(expr: sp.Expr, d: Derivation, table: ComparisonTable, notes: list[str]) -> sp.Expr:
    r"""A document expression in the table's namespace: each document symbol becomes the table
    symbol of the same name and model value, or else the one of the same model value."""
    rename = {}
    by_value = {s.value: s.symbol for s in table.symbols.values() if s.value is not None}
    for spec in d.symbols.values():
        if spec.symbol not in expr.free_symbols or spec.value is None:
            continue
        mine = table.symbols.get(spec.name)
        if mine is not None and mine.value == spec.value:
            continue
        if spec.value in by_value:
            rename[spec.symbol] = by_value[spec.value]
        else:
            note = (f"{d.path.name}: symbol {spec.name} = {spec.value_expr_text} has no "
                    f"counterpart in the table; kept as is")
            if note not in notes:
                notes.append(note)
    rename.update(zip(d.velocities, table.velocities))
    rename.update(zip(d.accelerations, table.accelerations))
    rename.update(zip(d.positions, table.positions))
    return sp.sympify(expr).xreplace(rename)


def _simplest(expr: sp.Expr) -> sp.Expr:
    trig = sp.trigsimp(sp.expand(expr))
    powers = [a for a in trig.atoms(sp.Pow) if a.base.func in (sp.sin, sp.cos)]
    candidates = [trig, sp.factor_terms(trig),
                  sp.collect(sp.expand(trig), powers or list(trig.atoms(sp.sin, sp.cos)))]
    return min(candidates, key=lambda e: (sp.count_ops(e), len(sp.sstr(e))))


#: The short texts of :func:`show`, remembered across runs (the disk cache's
#: ``compare/table-text-<code>.pickle``): simplifying a cell again gives the same text.
SHOWN = DiskMemo("compare", "table-text", lambda: [Path(__file__)])


def show(expr: sp.Expr, gens: Sequence[sp.Symbol] = ()) -> str:
    r"""Short text of ``expr``: grouped by the monomials in ``gens`` (velocities,
    accelerations), each coefficient in its simplest form (remembered: :data:`SHOWN`)."""
    expr = sp.sympify(expr)
    return SHOWN.get((expr, tuple(gens)), lambda: _shown(expr, gens))


def _shown(expr: sp.Expr, gens: Sequence[sp.Symbol]) -> str:
    expr = sp.expand(expr)
    gens = [g for g in gens if expr.has(g)]
    if not gens:
        return sp.sstr(_simplest(expr))
    try:
        monomials = sp.Poly(expr, *gens).terms()
    except sp.PolynomialError:
        return sp.sstr(_simplest(expr))
    return sp.sstr(sp.Add(*[_simplest(c) * sp.Mul(*[g**k for g, k in zip(gens, mon)])
                            for mon, c in monomials]))


def same(a: sp.Expr, b: sp.Expr, rng: np.random.Generator) -> bool:
    r"""``a`` equals ``b`` identically (checked at random values of every symbol)."""
    a, b = sp.sympify(a), sp.sympify(b)
    symbols = sorted(a.free_symbols | b.free_symbols, key=str)
    if not symbols:
        return abs(float(a - b)) <= CHECK_TOL * max(1.0, abs(float(a)), abs(float(b)))
    fa, fb = numpy_function(symbols, a), numpy_function(symbols, b)
    for _ in range(CHECK_POINTS):
        x = rng.uniform(0.3, 1.7, len(symbols))
        va, vb = float(fa(*x)), float(fb(*x))
        if abs(va - vb) > CHECK_TOL * max(1.0, abs(va), abs(vb)):
            return False
    return True


def num(c: float) -> str:
    return sp.sstr(sp.nsimplify(c))
