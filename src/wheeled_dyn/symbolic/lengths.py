r"""A model's lengths in its closed forms: the drawn ones as symbols.

The random parameter sets of a comparison draw every length of a model
(:mod:`wheeled_dyn.models.geometry`), so the closed forms the reports print write them as
symbols too: a drawn length as one symbol per group of equal lengths (``origin_y(spin_rl)`` →
``W/2``, ``radius(coin)`` → ``R``), the others by their identifiers (``origin_x(elbow)`` →
``origin_x_elbow``), a kept one as its exact number (:func:`length_symbols`); and the joint
placements through them (:func:`translations`; a planar wheeled model's axle and wheels
through ``R`` and ``L``, :func:`planar_translations`).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pinocchio as pin
import sympy as sp

from ..models.wheeled_model import WheeledModel
from .exact import exact_length, exact_rotation, exact_translation


def length_symbols(wm: WheeledModel) -> dict[str, sp.Expr]:
    r"""The model's lengths and constants as its closed forms write them
    (:func:`~wheeled_dyn.models.geometry.symbols`: a drawn length a symbol, a kept one its
    exact number)."""
    from ..models.geometry import symbols
    return symbols(wm.lengths, exact_length) if wm.lengths is not None else {}


def translations(wm: WheeledModel, lengths: Mapping[str, sp.Expr]) -> dict | None:
    r"""The joint placements' translations in the drawn lengths: for a moving joint of parent
    link frame :math:`(R_p, p_p)` in its parent joint, :math:`p_p + R_p\,t` with :math:`t` its
    origin (symbols where drawn) and :math:`p_p` through the origins of the fixed joints
    between (:func:`_frame_translation`: a link clamped at a drawn distance moves the joint
    after it); None where every one is a number."""
    model = wm.model
    out = {}
    for j in range(1, model.njoints):
        name = model.names[j]
        t = [lengths.get(f"origin_{a}({name})") for a in "xyz"]
        fid = model.getFrameId(name, pin.FrameType.JOINT)
        if any(x is None for x in t) or fid >= len(model.frames):
            continue                  # a joint the model adds (a planar base's): no origin
        frame = model.frames[fid]
        parent = model.frames[frame.parentFrame].placement
        p = _frame_translation(model, frame.parentFrame, lengths)
        if all(sp.sympify(x).is_Number for x in (*t, *p)):
            continue
        placed = p + exact_rotation(parent.rotation) * sp.Matrix(t)
        if not _places(placed, model.jointPlacements[j].translation, wm, lengths):
            rest = model.jointPlacements[j].translation - parent.rotation @ np.array(
                [wm.dimensions[f"origin_{a}({name})"] for a in "xyz"])
            placed = exact_translation(rest) + exact_rotation(parent.rotation) * sp.Matrix(t)
        out[j] = tuple(placed)
    return out or None


def _places(placed: sp.Matrix, translation: np.ndarray, wm: WheeledModel,
            lengths: Mapping[str, sp.Expr]) -> bool:
    r"""Whether ``placed`` at the model's own lengths is Pinocchio's ``translation``."""
    at = {v: wm.dimensions[k] for k, v in lengths.items()
          if isinstance(v, sp.Symbol) and k in wm.dimensions}
    try:
        value = np.array([float(sp.sympify(x).xreplace(at)) for x in placed])
    except TypeError:                 # a symbol without a value (a length named otherwise)
        return False
    return bool(np.abs(value - translation).max() <= 1e-9 * max(1.0, np.abs(translation).max()))


def _frame_translation(model: pin.Model, fid: int, lengths: Mapping[str, sp.Expr]
                       ) -> sp.Matrix:
    r"""The translation of frame ``fid`` in its parent joint's frame, through the origins of
    the fixed joints from that joint to it (:math:`p_f = p_{parent} + R_{parent}\,t_f`, the
    drawn ones as symbols); the exact number where a fixed joint's origin is not among
    ``lengths`` (:func:`translations` checks the sum against Pinocchio's placement)."""
    frame = model.frames[fid]
    here = exact_translation(frame.placement.translation)
    if frame.type not in (pin.FrameType.BODY, pin.FrameType.FIXED_JOINT) or \
            frame.parentFrame == fid or model.frames[frame.parentFrame].parentJoint != \
            frame.parentJoint:
        return here
    if frame.type == pin.FrameType.BODY:
        up = model.frames[frame.parentFrame]
        same = np.allclose(up.placement.translation, frame.placement.translation)
        return _frame_translation(model, frame.parentFrame, lengths) if same else here
    t = [lengths.get(f"origin_{a}({frame.name})") for a in "xyz"]
    if any(x is None for x in t):
        return here
    parent = model.frames[frame.parentFrame].placement
    p = _frame_translation(model, frame.parentFrame, lengths)
    return p + exact_rotation(parent.rotation) * sp.Matrix(t)


def planar_translations(wm: WheeledModel, lengths: Mapping[str, sp.Expr]) -> dict | None:
    r"""A planar wheeled model's placements in its drawn ``R`` and ``L``, as the parameter sets
    draw them (:func:`~wheeled_dyn.models.geometry_apply.apply_geometry`): the pitch joint (or,
    without one, the wheels hanging from the yaw body) lifted by :math:`R - R_0`, each wheel at
    :math:`m + (L/L_0)(t - m)` from the axle midpoint :math:`m` of its URDF placement
    :math:`t`. None where neither is drawn."""
    R, L = (sp.sympify(lengths.get(k, 0)) for k in ("R", "L"))
    if len(wm.wheels) != 2 or (R.is_Number and L.is_Number):
        return None
    model = wm.model
    lift = sp.Matrix([0, 0, R - exact_length(wm.geometry["R"])])
    out: dict[int, tuple] = {}
    if wm.spec.pitch:
        j = model.getJointId("phi")
        out[j] = tuple(exact_translation(model.jointPlacements[j].translation) + lift)
        lift = sp.zeros(3, 1)
    T = [exact_translation(model.jointPlacements[w.joint_id].translation) for w in wm.wheels]
    mid = (T[0] + T[1]) / 2
    half = exact_length(0.5 * float(np.linalg.norm(np.array(T[1] - T[0], dtype=float))))
    for w, t in zip(wm.wheels, T):
        out[w.joint_id] = tuple(mid + (L / half) * (t - mid) + lift)
    return out


def gravity_symbol(wm: WheeledModel) -> sp.Symbol | None:
    r"""Gravity's magnitude as the closed forms in Khalil's parameters write it: the symbol
    ``g`` (the parameter sets draw it), None for a model without gravity."""
    return sp.Symbol("g", real=True) if np.any(wm.model.gravity.linear) else None


def axle_symbols(wm: WheeledModel) -> bool:
    r"""Whether the tree's closed forms write the model's axle through its drawn ``R`` and
    ``L`` (:func:`planar_translations`): a planar model on its two wheels."""
    return wm.spec.base == "planar" and len(wm.wheels) == 2
