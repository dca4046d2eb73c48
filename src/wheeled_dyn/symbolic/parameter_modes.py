r"""The parameter modes of the closed forms: what :func:`~.model.symbolic_model` is given for
a wheeled model (inertial parameters, gravity, joint translations, armature, wheel radii,
geometry) in each of :data:`PARAMETER_MODES`.

- ``"physical"`` (a model with a physical-parameter record: the WIP): Khalil's standard
  parameters of ``body`` and the wheels from
  :func:`~wheeled_dyn.models.wip_parameters.standard_parameters` of the real symbols
  ``m_S, m_C, d, I1, ...``, the armature ``I_a`` on both wheel joints, gravity ``g``; the axle
  at height ``R`` (the pitch joint's translation :math:`(0, 0, R)`, also the wheel radius) and
  the wheels at :math:`(0, 0, \mp L)` on the axle, each checked against the model's numbers
  within :data:`PLACEMENT_TOL`;
- ``"numbers"``: every number from the Pinocchio model, exact
  (:func:`~.kinematics.exact_number`, :func:`~.exact.exact_length`);
- ``"standard"``: the symbols :math:`(M, MX, MY, MZ, XX, XY, XZ, YY, YZ, ZZ)_j` named after
  the link carrying joint :math:`j`'s body when its frame is the joint frame (else after the
  joint) for every joint that carries mass, numbers for the rest; the drawn lengths as
  symbols (:mod:`.lengths`).
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np
import pinocchio as pin
import sympy as sp

from ..errors import ModelError, UnknownNameError
from ..models.geometry import identifier
from ..models.wheeled_model import WheeledModel
from .exact import exact_length
from .kinematics import exact_number
from .lengths import (axle_symbols, gravity_symbol, length_symbols, planar_translations,
                      translations)
from .parameters import PARAMETER_NAMES, numeric_parameters

#: Parameter modes of :func:`~.wheeled.wheeled_symbolic`.
PARAMETER_MODES: tuple[str, ...] = ("physical", "numbers", "standard")
#: Largest distance between a model's joint placement and the symbolic one at its numbers.
PLACEMENT_TOL: float = 1e-12


def physical_symbols() -> dict[str, sp.Symbol]:
    r"""``{name: Symbol(name, real=True)}`` for every field of
    :class:`~wheeled_dyn.models.wip_parameters.WipParameters` (``m_S, m_C, R, L, d, g, ...``)."""
    from ..models.wip_parameters import WipParameters
    return {f.name: sp.Symbol(f.name, real=True) for f in fields(WipParameters)}


#: LaTeX of the physical symbols (seed 001's notation).
PHYSICAL_LATEX: dict[str, str] = {
    "m_S": "m_S", "m_C": "m_C", "I1": "I_1", "I2": "I_2", "I3": "I_3", "Ixy": "I_{xy}",
    "Ixz": "I_{xz}", "Iyz": "I_{yz}", "Iw2": "I_{w2}", "Iw3": "I_{w3}", "d_x": "d_x",
    "d_z": "d_z", "I_a": "I_a"}


def physical_latex() -> dict[sp.Symbol, str]:
    """``{symbol: LaTeX}`` for :func:`~.printing.to_latex`'s ``names``."""
    P = physical_symbols()
    return {P[k]: v for k, v in PHYSICAL_LATEX.items() if k in P}


def has_physical_record(wm: WheeledModel) -> bool:
    from ..models.registry import MODELS
    from ..models.wip_parameters import WipParameters
    entry = MODELS.get(wm.name)
    return entry is not None and entry.parameters is WipParameters


def _link_at_joint(wm: WheeledModel, link: str) -> int:
    """The joint of ``link``, checking that the link frame is the joint frame."""
    model = wm.model
    if not model.existFrame(link):
        raise UnknownNameError("link", link, [f.name for f in model.frames],
                               where=f"model {wm.name}")
    frame = model.frames[model.getFrameId(link)]
    if not frame.placement.isIdentity(PLACEMENT_TOL):
        raise ModelError(wm.name, link, "the link frame is not its joint frame: the physical "
                                        "parameters are given in the link frame")
    return frame.parentJoint


def _physical_setup(wm: WheeledModel) -> dict:
    r"""Arguments of :func:`~.model.symbolic_model` for the WIP in physical symbols."""
    from ..models.wip_parameters import standard_parameters
    if not has_physical_record(wm):
        raise ModelError(wm.name, None, "no physical-parameter record: use parameters="
                                        "'numbers' or 'standard'")
    P = physical_symbols()
    std = standard_parameters(P)
    model = wm.model
    params: dict[int, list] = {j: [0] * 10 for j in range(1, model.njoints)}
    body = _link_at_joint(wm, "body")
    if body != wm.body_joint_id:
        raise ModelError(wm.name, "body", "the body link is not on the pitch joint")
    params[body] = [std["body"][k] for k in PARAMETER_NAMES]
    translations = {body: (0, 0, P["R"])}
    armature = [0] * model.nv
    for wheel, sign in zip(wm.wheels, (-1, 1)):
        j = _link_at_joint(wm, wheel.link)
        params[j] = [std[wheel.link][k] for k in PARAMETER_NAMES]
        translations[j] = (0, 0, sign * P["L"])
        armature[wheel.v_index] = P["I_a"]
    numbers = {P["R"]: wm.geometry["R"], P["L"]: wm.geometry["L"]}
    for j, t in translations.items():
        want = np.array([float(sp.sympify(x).xreplace(numbers)) for x in t])
        if np.abs(model.jointPlacements[j].translation - want).max() > PLACEMENT_TOL:
            raise ModelError(wm.name, model.names[j], "the joint placement is not the WIP's "
                             f"(0, 0, R) / (0, 0, -+L): {model.jointPlacements[j].translation}")
    return dict(params=params, gravity=P["g"], translations=translations, armature=armature,
                radius=[P["R"]] * len(wm.wheels), geometry={"R": P["R"], "L": P["L"]})


def standard_names(wm: WheeledModel) -> dict[int, str]:
    r"""The name of each joint body's standard parameters (in the joint frame): the link that
    carries the rigid body (:mod:`~wheeled_dyn.models.link_parameters`) when its frame is the
    joint frame, so that ``XX_link`` is what a derivation's ``XX(link)`` names; else the
    joint's name (a merged link such as ``base_footprint`` never names the whole body)."""
    from ..models.link_parameters import rigid_bodies
    model = wm.model
    names = {j: model.names[j] for j in range(1, model.njoints)}
    for body in rigid_bodies(wm):
        frame = model.frames[model.getFrameId(body.carrier, pin.FrameType.BODY)]
        if frame.placement.isIdentity(PLACEMENT_TOL):
            names[frame.parentJoint] = body.carrier
    return names


def carrier_parameters(wm: WheeledModel) -> dict[str, dict[str, sp.Expr]]:
    r"""A derivation's Khalil parameters of a carrying link whose frame is not its joint frame
    (a ROS ``base_link`` above the ``base_footprint`` a planar base moves), in the closed
    forms' symbols of the body, named after the joint (:func:`standard_names`). With the
    link frame at :math:`(R, p)` in the joint frame, the body's first moments
    :math:`MS_j = R\,MS_l + M p` and inertia about the joint-frame origin

    .. math::
        J_j = R J_l R^T + 2 (p\cdot s) I - s p^T - p s^T + M (|p|^2 I - p p^T),
        \qquad s = R\,MS_l,

    solved for the link's :math:`MS_l, J_l`. Only where :math:`(R, p)` are exact numbers the
    parameter sets do not draw (no fixed joint between them has a drawn origin)."""
    from ..models.link_parameters import rigid_bodies
    from .exact import exact_rotation, exact_translation
    model, names = wm.model, standard_names(wm)
    drawn = {k for k, v in length_symbols(wm).items() if not sp.sympify(v).is_Number}
    out: dict[str, dict[str, sp.Expr]] = {}
    for body in rigid_bodies(wm):
        fid = model.getFrameId(body.carrier, pin.FrameType.BODY)
        frame, jid = model.frames[fid], model.frames[fid].parentJoint
        if names[jid] == body.carrier or _drawn_between(model, fid, drawn):
            continue
        rotation = np.asarray(frame.placement.rotation, dtype=float)
        signs = np.rint(rotation)     # a turn by right angles is exact at once (the table of
        R = sp.Matrix(signs.astype(int)) if np.abs(rotation - signs).max() <= PLACEMENT_TOL \
            else exact_rotation(rotation)         # special values takes 0.25 s to make)
        p = exact_translation(frame.placement.translation)
        M, *rest = (sp.Symbol(f"{k}_{names[jid]}", real=True) for k in PARAMETER_NAMES)
        s = sp.Matrix(rest[:3]) - M * p
        xx, xy, yy, xz, yz, zz = rest[3:]
        J = sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
        J = J - (2 * p.dot(s) * sp.eye(3) - s * p.T - p * s.T
                 + M * (p.dot(p) * sp.eye(3) - p * p.T))
        MS, J = R.T * s, R.T * J * R
        out[body.carrier] = dict(zip(PARAMETER_NAMES, (M, *MS, J[0, 0], J[0, 1], J[1, 1],
                                                       J[0, 2], J[1, 2], J[2, 2])))
    return out


def _drawn_between(model: pin.Model, fid: int, drawn: set[str]) -> bool:
    r"""Whether a fixed joint between frame ``fid`` and its joint has a drawn origin."""
    frame = model.frames[fid]
    while frame.type in (pin.FrameType.BODY, pin.FrameType.FIXED_JOINT) and \
            frame.parentFrame != 0:
        if frame.type == pin.FrameType.FIXED_JOINT and \
                any(f"origin_{a}({frame.name})" in drawn for a in "xyz"):
            return True
        frame = model.frames[frame.parentFrame]
    return False


def drawn_symbols(wm: WheeledModel, mode: str, axle: bool = False) -> dict[str, sp.Expr]:
    r"""The lengths the closed forms of ``mode`` write as symbols, by name (empty where they
    hold numbers): in standard parameters, a model without wheels' and a planar wheeled
    model's with ``axle`` (:func:`_numeric_setup`)."""
    if mode != "standard" or wm.lengths is None or (wm.wheels and not
                                                     (axle and axle_symbols(wm))):
        return {}
    return length_symbols(wm)


def _numeric_setup(wm: WheeledModel, mode: str, axle: bool = False) -> dict:
    r"""Standard or numeric parameters; with ``mode == "standard"`` gravity's magnitude as the
    symbol ``g`` (the parameter sets draw it) and the drawn lengths as symbols (a planar
    wheeled model's ``R`` and ``L`` only with ``axle``: the tree's closed forms, where the
    rolling rows stay polynomial in them)."""
    model = wm.model
    nums = numeric_parameters(model)
    names = standard_names(wm)
    params: dict[int, list] = {}
    for j, pi in nums.items():
        if mode == "standard" and any(abs(x) > 0 for x in pi):
            params[j] = [sp.Symbol(f"{k}_{names[j]}", real=True) for k in PARAMETER_NAMES]
        else:
            params[j] = [exact_number(x) for x in pi]
    geometry = {k: exact_length(v) for k, v in wm.named_lengths().items()}
    moved, radius = None, [exact_length(w.radius) for w in wm.wheels]
    planar = axle and axle_symbols(wm)
    lengths = drawn_symbols(wm, mode, axle)
    if lengths:
        geometry.update({identifier(k): v for k, v in lengths.items()})
        geometry.update({k: v for k, v in lengths.items() if k in wm.geometry})
        moved = translations(wm, lengths)
        if planar:                  # the axle and wheels through R and L, the rest by name
            moved = {**(moved or {}), **(planar_translations(wm, lengths) or {})} or None
            radius = [lengths.get("R", r) for r in radius]
    return dict(params=params, gravity=gravity_symbol(wm) if mode == "standard" else None,
                translations=moved, armature=None, radius=radius, geometry=geometry)


def parameter_setup(wm: WheeledModel, parameters: str, axle: bool = False) -> dict:
    if parameters not in PARAMETER_MODES:
        raise UnknownNameError("parameter mode", parameters, PARAMETER_MODES)
    if parameters == "physical":
        return _physical_setup(wm)
    return _numeric_setup(wm, parameters, axle)
