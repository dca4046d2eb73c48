r"""A number written where a parameter of the model fits: :math:`9.81` for the gravity
:math:`g`. The comparison draws every parameter of the model, gravity too (a document's
equations must hold for every robot of the model, on any planet: a term that needs :math:`g`
and lacks it is an error), so a document that writes Earth's value differs — it holds for
:math:`g = 9.81` only — and its units say so ("has kg, expected kg·m·s⁻²"). That is its
name here: each number of an element within :data:`GRAVITY_NUMBERS` of a standard value,
read as the document's symbol for the model's :math:`g`, makes the element agree at every
sample. An explanation only: the element still differs.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..records import Diagnosis, DiagnosisKind as K, diagnosis
from .diagnose import agrees

#: The numbers read as Earth's gravity (m/s²): 9.7 to 9.9 (9.8, 9.81, 9.807, 9.80665).
GRAVITY_NUMBERS = (9.7, 9.9)


def gravity_symbol(d: Derivation) -> sp.Symbol | None:
    r"""The document's symbol whose value is the model's gravity ``g``, or None."""
    return next((spec.symbol for spec in d.symbols.values()
                 if isinstance(spec.value, sp.Symbol) and spec.value.name == "g"), None)


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
    low, high = GRAVITY_NUMBERS
    numbers = sorted({x for x in expr.atoms(sp.Number) if low <= abs(float(x)) <= high},
                     key=float)
    for number in numbers:
        value = abs(number)
        trial = expr.xreplace({value: g, -value: -g})
        if trial != expr and agrees(evaluate(trial), T, scale):
            shown = f"{float(value):g}"
            return [diagnosis(K.SWAP, f"the number {shown} is written where {g} fits (the "
                              "comparison draws gravity, as every parameter of the model: "
                              f"the equations hold for {g} = {shown} only{units})",
                              written=shown, fits=str(g))]
    return []


__all__ = ["GRAVITY_NUMBERS", "gravity_symbol", "number_for_gravity"]
