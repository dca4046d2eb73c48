r"""How a comparison draws a wheeled model's two drive wheels, from what the document names.

The random parameter sets draw the wheels alike, each its URDF inertia scaled
(:func:`~.samples.parameter_sets`): what is zero there (a product of inertia, the centre of
mass off the axle) stays zero, and a CAD export's rounding (TIAGo's wheels are axisymmetric to
2e-5: :mod:`~wheeled_dyn.models.round_wheels`) leaves a derivation taking them round a
difference of about 1e-7 of a row, the comparisons' tolerance. From the symbols the file's
equations write (a symbol declared and not written names nothing):

- **it names their asymmetry** — a wheel parameter other than its mass, its moment about the
  axle, its centre of mass along the axle and one moment about a diameter (a product of
  inertia, the centre of mass off the axle, both diametral moments, a ratio of them): the
  wheels are drawn alike but free (:data:`~.samples.FREE_WHEELS`: a random inertia and centre
  of mass, the same for both in their joints' frames), so its terms in them are compared;
  drawn as the URDF's, a term in a product that is zero there vanished in every set;
- **it names none**, and the URDF's wheels are within
  :data:`~wheeled_dyn.models.round_wheels.ROUND_TOL` of axisymmetric, not exactly: they are
  drawn axisymmetric (:data:`IMPLIED_ROUND_WHEELS`);
- otherwise as the URDF has them.

A file may declare ``round_wheels`` itself; then it is binding, and naming their asymmetry
besides is a file error said first (:func:`round_contradiction`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from sympy.core.function import AppliedUndef

from ...derivations.schema import Derivation
from ..records import Cause, CauseKind
from .samples import FREE_WHEELS, ROUND_WHEELS, SpecialCase
from .wheel_draws import wheel_axles

#: The implied family, said as such among the assumptions.
IMPLIED_ROUND_WHEELS = replace(ROUND_WHEELS, description=(
    "the drive wheels are axisymmetric about their axles, as the model's are to its URDF's "
    "rounding (implied: the document names nothing of their asymmetry)"))
#: A frame axis within this of the axle is along it (the axle in the link's frame).
ALONG = 1e-9
_AXES = "XYZ"
_NAMED: dict[tuple, tuple[str, ...]] = {}


def _axle_index(wm, link: str) -> int | None:
    r"""The axis (0, 1, 2) of ``link``'s frame along its wheel's axle, or None where the
    axle is along none of them (then every parameter but the mass mixes the two)."""
    import pinocchio as pin
    model = wm.model
    frame = model.frames[model.getFrameId(link, pin.FrameType.BODY)]
    jid = frame.parentJoint
    axle = frame.placement.rotation.T @ wheel_axles(wm)[jid]
    k = int(np.argmax(np.abs(axle)))
    return k if abs(abs(axle[k]) - 1.0) <= ALONG else None


def _written(d: Derivation) -> set:
    r"""The symbols ``d``'s equations write (its matrices, equations and constraints)."""
    found: set = set()
    for part in (d.A, d.C, d.Q, d.B, d.G, *(d.equations or ()), *(d.constraints or ())):
        if part is not None:
            found |= part.free_symbols
    return found


def asymmetry_named(d: Derivation, wm) -> tuple[str, ...]:
    r"""The calls of the symbols ``d``'s equations write that name the drive wheels'
    asymmetry (module text; a symbol declared and not written names nothing)."""
    written = _written(d)
    values = tuple((s.symbol, s.value) for s in d.symbols.values()
                   if s.value is not None and not s.is_input and s.symbol in written)
    from ...models.registry import model_version
    key = (d.model, model_version(d.model), values)
    if key in _NAMED:
        return _NAMED[key]
    axles = {w.link: _axle_index(wm, w.link) for w in wm.wheels}
    named, diametral = [], set()
    for _, value in values:
        for call in value.atoms(AppliedUndef):
            link, name = str(call.args[0]) if call.args else "", call.func.__name__
            if link not in axles:
                continue
            a = axles[link]
            if name == "M":
                continue
            axis = _AXES[a] if a is not None else None
            if axis is not None and name in (f"I{axis}{axis}", f"{axis}{axis}", f"C{axis}",
                                             f"M{axis}"):
                continue                     # the moment about the axle, the COM along it
            if axis is not None and len(name) in (2, 3) and name[-1] == name[-2] \
                    and name[-1] in _AXES:   # a moment about a diameter: one of them
                diametral.add(name[-1])
                if len(diametral) == 1:
                    continue
            named.append(str(call))
    _NAMED[key] = tuple(dict.fromkeys(named))
    return _NAMED[key]


def implied_wheel_families(d: Derivation, families: tuple[SpecialCase, ...]
                           ) -> tuple[SpecialCase, ...]:
    r"""The family the comparison of ``d`` draws its model's wheels in, not declared (module
    text): :data:`~.samples.FREE_WHEELS`, :data:`IMPLIED_ROUND_WHEELS`, or none."""
    from ...models.registry import model_entry
    from ...models.round_wheels import ROUND_TOL
    if model_entry(d.model).parameters is not None or any(
            c.name in (ROUND_WHEELS.name, FREE_WHEELS.name) for c in families):
        return ()
    wm, worst = _wheels(d.model)
    if len(wm.wheels) != 2:
        return ()
    if asymmetry_named(d, wm):
        return (FREE_WHEELS,)
    return (IMPLIED_ROUND_WHEELS,) if 0.0 < worst <= ROUND_TOL else ()


_WHEELS: dict[tuple, tuple] = {}


def _wheels(model: str) -> tuple:
    r"""The model (as built) and its drive wheels' largest asymmetry, once per version of its
    files (:func:`declared <.assumptions.declared>` asks for every judgement)."""
    from ...models.registry import load_model, model_version
    from ...models.round_wheels import asymmetry
    key = (model, model_version(model))
    if key not in _WHEELS:
        wm = load_model(model)
        axles = wheel_axles(wm)
        _WHEELS[key] = (wm, max((asymmetry(wm.model.inertias[w.joint_id], axles[w.joint_id],
                                           w.radius) for w in wm.wheels), default=0.0))
    return _WHEELS[key]


def round_contradiction(d: Derivation, families: tuple[SpecialCase, ...]) -> tuple[Cause, ...]:
    r"""A ``file_error`` cause where the file declares ``round_wheels`` and names the wheels'
    asymmetry: its terms in those parameters are the round wheel's, never the URDF's."""
    from ...models.registry import model_entry
    if model_entry(d.model).parameters is not None or not any(
            c.name == ROUND_WHEELS.name for c in families):
        return ()
    named = asymmetry_named(d, _wheels(d.model)[0])
    if not named:
        return ()
    return (Cause(CauseKind.FILE_ERROR, (), (
        f"the file declares round_wheels, but its symbols name the wheels' asymmetry "
        f"({', '.join(named)}): under the family those are a round wheel's (its moments about "
        "its diameters equal, no products of inertia, its centre of mass on the axle), and "
        "the document's terms in them are compared as such (declare the family only where "
        "the equations take the wheels round)")),)


__all__ = ["IMPLIED_ROUND_WHEELS", "asymmetry_named", "implied_wheel_families",
           "round_contradiction"]
