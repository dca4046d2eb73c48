r"""A number written where a parameter of the model fits: :math:`9.81` for the gravity
:math:`g` (or a simple fraction of it: 9.81/2 for g/2). The comparison draws every parameter
of the model, gravity too (a document's equations must hold for every robot of the model,
on any planet: a term that needs :math:`g` and lacks it is an error), so a document that
writes Earth's value differs — it holds for
:math:`g = 9.81` only — and its units say so where the file declares them ("has kg, expected
kg·m·s⁻²"). That is its
name here: each number of an element within :data:`GRAVITY_NUMBERS` of a standard value,
read as the document's symbol for the model's :math:`g`, makes the element agree at every
sample. An explanation only: the element still differs.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp

from ...expression_size import atoms_of
from ...derivations.schema import Derivation
from ..records import Diagnosis, DiagnosisKind as K, diagnosis
from .diagnose import agrees, small_fraction

#: The numbers read as Earth's gravity (m/s²): 9.7 to 9.9 (9.8, 9.81, 9.807, 9.80665).
GRAVITY_NUMBERS = (9.7, 9.9)


def gravity_symbol(d: Derivation) -> sp.Symbol | None:
    r"""The document's symbol whose value is the model's gravity ``g``, or None."""
    return next((spec.symbol for spec in d.symbols.values()
                 if isinstance(spec.value, sp.Symbol) and spec.value.name == "g"), None)


#: Earth's gravity as documents write it, each number of an element is tried as a simple
#: fraction of (9.81/2 for g/2).
EARTH = (9.81, 9.8, 9.80665, 9.807)


def _gravity_parts(expr: sp.Expr) -> list[tuple[sp.Number, sp.Rational]]:
    r"""Each positive number of ``expr`` (its value) that is a simple fraction (denominator
    at most 12) of one of :data:`EARTH`'s values or within :data:`GRAVITY_NUMBERS`, with that
    fraction (1 for the latter)."""
    low, high = GRAVITY_NUMBERS
    out = []
    for x in sorted({abs(a) for a in atoms_of(expr, sp.Number) if a != 0}, key=float):
        if low <= float(x) <= high:
            out.append((x, sp.Integer(1)))
            continue
        for earth in EARTH:
            part = small_fraction(float(x) / earth, 1e-12)
            if part is not None and abs(part.numerator) <= 12:    # not 981 as 100 g
                out.append((x, sp.Rational(part.numerator, part.denominator)))
                break
    return out


def number_for_gravity(expr: sp.Expr, d: Derivation,
                       evaluate: Callable[[sp.Expr], np.ndarray], T: np.ndarray,
                       scale: float, problems: Sequence[str] = ()) -> list[Diagnosis]:
    r"""The diagnosis of an element ``expr`` (evaluated by ``evaluate`` at every sample) that
    agrees with the truth ``T`` once a number near Earth's gravity in it is read as the
    document's symbol for :math:`g`, its units' ``problems`` said in it; [] otherwise."""
    units = f"; its units: {'; '.join(problems)}" if problems else ""
    g = gravity_symbol(d)
    if g is None:
        return []
    for value, part in _gravity_parts(expr):
        trial = expr.xreplace({value: part * g, -value: -part * g})
        if trial != expr and agrees(evaluate(trial), T, scale):
            shown, fits = f"{float(value):g}", sp.sstr(part * g)
            return [diagnosis(K.SWAP, f"the number {shown} is written where {fits} fits (the "
                              "comparison draws gravity, as every parameter of the model: "
                              f"the equations hold for {g} = {float(value / part):g} only"
                              f"{units})", written=shown, fits=fits)]
    return []


__all__ = ["EARTH", "GRAVITY_NUMBERS", "gravity_symbol", "number_for_gravity"]
