r"""Round wheels implied: a comparison draws a wheeled model's drive wheels axisymmetric
(:data:`~.samples.ROUND_WHEELS`) where the URDF's are so to its rounding and the document
writes nothing of their asymmetry.

A CAD export's wheel is axisymmetric only to its rounding (TIAGo's to 2e-5:
:mod:`~wheeled_dyn.models.round_wheels`), which leaves a derivation taking it round a
difference of about 1e-7 of a row — the comparisons' tolerance, so each verdict would be the
draw's. The family is implied where

- the model's wheels are within :data:`~wheeled_dyn.models.round_wheels.ROUND_TOL` of
  axisymmetric, and not exactly (then drawing them so changes nothing), and
- no symbol of the document vanishes under it, or comes to equal another: a document that
  writes a wheel's centre of mass off its axle (``e = CX(right_wheel)``), a product of its
  inertia, or its two moments about diameters apart (``D1 = IXX(wheel)``, ``D2 =
  IZZ(wheel)``) models the asymmetry, and its terms in them are compared against the URDF's
  wheel (a sign error there would vanish with them).

A document may declare ``round_wheels`` itself; then it is binding, as every family
(:mod:`~..judge.consistency` says what it makes vanish).
"""

from __future__ import annotations

from dataclasses import replace
from itertools import combinations

from ...derivations.schema import Derivation
from ...errors import UnknownNameError
from .samples import ROUND_WHEELS, wheel_axles
from .values import model_value

#: The implied family, said as such among the assumptions.
IMPLIED_ROUND_WHEELS = replace(ROUND_WHEELS, description=(
    "the drive wheels are axisymmetric about their axles, as the model's are to its URDF's "
    "rounding (implied: the document writes nothing of their asymmetry)"))
#: A symbol's value at most this fraction of its own is zero; two values this close are equal.
ZERO = 1e-12

_IMPLIED: dict[tuple, bool] = {}


def implied_round_wheels(d: Derivation) -> bool:
    r"""Whether ``d`` is compared with its model's wheels drawn axisymmetric, not declaring
    it (module text)."""
    from ...models.registry import load_model, model_entry, model_parameters, model_version
    from ...models.round_wheels import ROUND_TOL, asymmetry, made_round
    if model_entry(d.model).parameters is not None:
        return False                        # a physical record: its own ranges
    values = tuple((s.symbol, s.value) for s in d.symbols.values()
                   if s.value is not None and not s.is_input)
    key = (d.model, model_version(d.model), values)
    if key in _IMPLIED:
        return _IMPLIED[key]
    wm = load_model(d.model)
    axles = wheel_axles(wm)
    worst = max((asymmetry(wm.model.inertias[j], a, w.radius)
                 for (j, a), w in zip(axles.items(), wm.wheels)), default=0.0)
    found = len(axles) == 2 and 0.0 < worst <= ROUND_TOL
    if found:
        import pinocchio as pin
        model = pin.Model(wm.model)
        for jid, axis in axles.items():
            model.inertias[jid] = made_round(model.inertias[jid], axis)
        found = not _written_asymmetry(values, model_parameters(wm),
                                       model_parameters(wm.with_model(model)))
    _IMPLIED[key] = found
    return found


def _written_asymmetry(values, own: dict[str, float], rounded: dict[str, float]) -> bool:
    r"""Whether a symbol of ``values`` (symbol, model expression) vanishes with the wheels
    rounded, or comes to equal another (``own``, ``rounded``: the model's namespace values
    as its URDF has them and with its wheels axisymmetric)."""
    try:
        before = [model_value(v, own) for _, v in values]
        after = [model_value(v, rounded) for _, v in values]
    except (UnknownNameError, TypeError, ValueError):
        return True              # the file's own error, said where its symbols are read
    if any(abs(b) > 0 and abs(a) <= ZERO * abs(b) for b, a in zip(before, after)):
        return True
    for (b1, a1), (b2, a2) in combinations(zip(before, after), 2):
        size = max(abs(b1), abs(b2))
        if abs(b1 - b2) > ZERO * size and abs(a1 - a2) <= ZERO * size:
            return True
    return False


__all__ = ["IMPLIED_ROUND_WHEELS", "ZERO", "implied_round_wheels"]
