r"""Other lengths for a built model: random draws of its geometry, and the model they give.

:func:`draw_geometry` draws every length a parameter set varies (:mod:`.geometry`): each drawn
dimension, each list of equal lengths and each free constant is multiplied by its own factor,
log-uniform in :math:`[1/F, F]` (:data:`FACTOR`), so a zero stays zero and a length keeps its
sign. A *uniform* body (a family of the comparison: a disc stays a disc, a rod a rod) is scaled
as a whole: one factor :math:`s` for all its lengths — its own radii and shapes, the origins of
the joints it carries, its fixed joints — and for every list of equal lengths that touches it
(so bodies tied by such a list share it):

.. math::

    c \to s\,c,\qquad I_G \to s^2 I_G \qquad(\text{mass kept: the caller draws it}),

which keeps :math:`I = m r^2/2`, :math:`2/5\,m r^2`, :math:`m l^2/12` of a uniform disc, ball
or rod.

:func:`apply_geometry` makes the model of a draw from the model it was drawn on: Pinocchio's
joint placements (for a moving joint of parent link frame :math:`(R_p, p_p)` in its parent
joint, :math:`{}^{\lambda}M_j = (R_p, p_p)\,(R_o, t)`: a new origin :math:`t'` moves the
translation by :math:`R_p(t' - t)`), the frames and inertias of the uniform bodies, a planar
model's axle height (its wheel radius) and half track (the wheel joints moved along the axle
about their midpoint), the radii of the rolling contacts, and the constants. The visual model is
not changed (parameter sets are not drawn).
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType

import numpy as np
import pinocchio as pin

from .builder import WheeledModel
from .geometry import ConstantKind, Dimension, GeometryTable

#: Largest factor of a drawn length (and smallest: 1/FACTOR).
FACTOR = 1.6


@dataclass(frozen=True)
class GeometryDraw:
    r"""The lengths of one parameter set: ``values`` of the dimensions and free constants,
    ``bodies`` the factor of each uniform body (Pinocchio joint id)."""

    values: Mapping[str, float]
    bodies: Mapping[int, float]


class _Classes:
    r"""Union-find over the draw groups and the uniform bodies."""

    def __init__(self) -> None:
        self.parent: dict[object, object] = {}

    def find(self, x: object) -> object:
        self.parent.setdefault(x, x)
        while self.parent[x] != x:
            self.parent[x] = self.parent[self.parent[x]]
            x = self.parent[x]
        return x

    def union(self, a: object, b: object) -> None:
        self.parent[self.find(a)] = self.find(b)


def _factor(rng: np.random.Generator) -> float:
    return float(math.exp(rng.uniform(-math.log(FACTOR), math.log(FACTOR))))


def _groups(wm: WheeledModel, table: GeometryTable, uniform: set[int]
            ) -> tuple[dict[str, list[str]], _Classes]:
    r"""The draw groups (a list of equal lengths, a free constant, a length drawn alone: name
    → its dimensions) and their classes: groups that touch a ``uniform`` body share its
    factor."""
    classes = _Classes()
    groups: dict[str, list[str]] = {}
    of_dim: set[str] = set()
    for name, c in table.constants.items():
        if c.kind is ConstantKind.SAME:
            of_dim.update(d for _, d in c.members)          # drawn with it, or kept
            if c.drawn:
                groups[name] = [d for _, d in c.members]
        elif c.kind in (ConstantKind.FREE, ConstantKind.TRACK) and c.drawn:
            groups[name] = []
    for name, d in table.dimensions.items():
        if d.drawn and name not in of_dim:
            groups[name] = [name]
    track_body = wm.model.parents[wm.wheels[0].joint_id] if wm.wheels else None
    for group, dims in groups.items():
        c = table.constants.get(group)
        bodies = {track_body} if c is not None and c.kind is ConstantKind.TRACK else \
            {table.dimensions[d].body for d in dims}
        for body in bodies & uniform:
            classes.union(("group", group), ("body", body))
    return groups, classes


def draw_geometry(wm: WheeledModel, rng: np.random.Generator,
                  uniform: Collection[int] = ()) -> GeometryDraw:
    r"""Random lengths for ``wm`` (module docstring); ``uniform``: the bodies (Pinocchio joint
    ids) scaled as a whole."""
    table = wm.lengths
    if table is None:
        return GeometryDraw(MappingProxyType({}), MappingProxyType({}))
    uniform = set(uniform)
    groups, classes = _groups(wm, table, uniform)
    tied_kept = {d for c in table.constants.values() if c.kind is ConstantKind.SAME
                 and any(table.dimensions[m].kept for _, m in c.members) for _, d in c.members}
    factors: dict[object, float] = {}

    def factor(key: object) -> float:
        root = classes.find(key)
        if root not in factors:
            factors[root] = _factor(rng)
        return factors[root]

    values: dict[str, float] = {}
    for group, dims in groups.items():
        f = factor(("group", group))
        c = table.constants.get(group)
        if c is not None and c.kind in (ConstantKind.FREE, ConstantKind.TRACK):
            values[group] = c.value * f
        for d in dims:
            values[d] = table.dimensions[d].value * f
    bodies = {b: factor(("body", b)) for b in sorted(uniform)}
    for name, d in table.dimensions.items():
        if name not in values and d.body in bodies and not d.kept and name not in tied_kept:
            values[name] = d.value * bodies[d.body]        # a fixed joint of a uniform body
    return GeometryDraw(MappingProxyType(values), MappingProxyType(bodies))


def uniform_scales(wm: WheeledModel, uniform: Collection[int]
                   ) -> dict[int, tuple[str, float, tuple[str, ...]]]:
    r"""For each ``uniform`` body: a name whose length its scale factor multiplies (a drawn
    group of its class: a constant's or a length's name), that length's value in ``wm``, and
    every name of the class (they scale alike); bodies whose class has none are left out. The
    closed forms write the body's scale as that length over its value."""
    table = wm.lengths
    if table is None:
        return {}
    uniform = set(uniform)
    groups, classes = _groups(wm, table, uniform)
    out: dict[int, tuple[str, float, tuple[str, ...]]] = {}
    for body in sorted(uniform):
        root = classes.find(("body", body))
        members = [g for g in groups if classes.find(("group", g)) == root]
        names = tuple(dict.fromkeys([*members, *(d for g in members for d in groups[g]),
                                     *(k for k, d in table.dimensions.items()
                                       if d.body == body and not d.kept)]))
        for group in members:
            value = table.constants[group].value if group in table.constants else \
                table.dimensions[groups[group][0]].value
            if value:
                out[body] = (group, value, names)
                break
    return out


def apply_geometry(wm: WheeledModel, draw: GeometryDraw) -> WheeledModel:
    r"""The model ``wm`` with the lengths of ``draw`` (module docstring): names not in the
    draw keep their values. Raises :class:`~wheeled_dyn.errors.ParameterError` where a contact
    becomes invalid (a ball as large as its bowl's vertex radius)."""
    table = wm.lengths
    if table is None or (not draw.values and not draw.bodies):
        return wm
    model = pin.Model(wm.model)
    old = {k: d.value for k, d in table.dimensions.items()}
    new = {k: float(draw.values.get(k, v)) for k, v in old.items()}
    bodies = dict(draw.bodies)
    for body, s in bodies.items():
        _scale_body(model, body, s)
    _move_origins(wm, model, old, new, bodies)
    geometry = table.constant_values(new, {k: v for k, v in draw.values.items()
                                           if k in table.constants})
    wheels = wm.wheels
    if wheels:
        wheels = _planar(wm, model, bodies, geometry["R"], geometry["L"])
    contact = wm.contact
    if contact is not None:
        link = contact.spec.link
        sc = contact.spec
        contact = replace(contact, spec=replace(
            sc, radius=new[f"radius({link})"],
            polar_radius=new.get(f"polar_radius({link})", sc.polar_radius),
            surface_radius=new.get(f"surface_radius({link})", sc.surface_radius),
            vertex_radius=new.get(f"vertex_radius({link})", sc.vertex_radius)))
    rolling = []
    for w in wm.rolling_wheels:
        s = bodies.get(model.frames[w.frame_id].parentJoint, 1.0)
        spec = replace(w.spec, radius=new[f"radius({w.link})"],
                       tyre_radius=new.get(f"tyre_radius({w.link})", w.spec.tyre_radius))
        rolling.append(replace(w, spec=spec, centre=w.centre * s))
    dims = {k: replace(d, value=new[k]) for k, d in table.dimensions.items()}
    consts = {k: replace(c, value=geometry[k]) for k, c in table.constants.items()}
    lengths = GeometryTable(MappingProxyType(dims), MappingProxyType(consts))
    return replace(wm, model=model, wheels=tuple(wheels), contact=contact,
                   rolling_wheels=tuple(rolling), geometry=geometry, lengths=lengths)


def _scale_body(model: pin.Model, body: int, s: float) -> None:
    r"""Scale body ``body`` about its joint frame by ``s``: its frames, the placements of the
    joints it carries, its centre of mass and central inertia (:math:`s^2`; mass kept)."""
    inertia = model.inertias[body]
    model.inertias[body] = pin.Inertia(inertia.mass, inertia.lever * s, inertia.inertia * s**2)
    for frame in model.frames:
        if frame.parentJoint == body and frame.type != pin.FrameType.JOINT:
            frame.placement = pin.SE3(frame.placement.rotation, frame.placement.translation * s)
    for child in range(body + 1, model.njoints):
        if model.parents[child] == body:
            jp = model.jointPlacements[child]
            model.jointPlacements[child] = pin.SE3(jp.rotation, jp.translation * s)


def _move_origins(wm: WheeledModel, model: pin.Model, old: Mapping[str, float],
                  new: Mapping[str, float], bodies: Mapping[int, float]) -> None:
    r"""Each moving joint whose origin changed other than by its body's scaling: its placement
    moved by :math:`R_p(t' - s\,t)`."""
    for name in [k for k in old if k.startswith("origin_x(")]:
        joint = name[len("origin_x("):-1]
        if not model.existJointName(joint):
            continue                            # fixed or locked: scaled with its body only
        jid = model.getJointId(joint)
        t_old = np.array([old[f"origin_{a}({joint})"] for a in "xyz"])
        t_new = np.array([new[f"origin_{a}({joint})"] for a in "xyz"])
        s = bodies.get(model.parents[jid], 1.0)
        if np.array_equal(t_new, s * t_old):
            continue
        frame = model.frames[model.getFrameId(joint, pin.FrameType.JOINT)]
        parent = model.frames[frame.parentFrame]
        rotation = parent.placement.rotation
        jp = model.jointPlacements[jid]
        model.jointPlacements[jid] = pin.SE3(jp.rotation, jp.translation
                                             + rotation @ (t_new - s * t_old))


def _planar(wm: WheeledModel, model: pin.Model, bodies: Mapping[int, float], R: float,
            L: float) -> list:
    r"""A planar model's axle at height ``R`` and its wheels ``L`` from the axle midpoint."""
    psi = model.getJointId("psi")
    s_psi = bodies.get(psi, 1.0)
    R_old = wm.geometry["R"]
    if wm.spec.pitch:
        phi = model.getJointId("phi")
        jp = model.jointPlacements[phi]
        model.jointPlacements[phi] = pin.SE3(jp.rotation, jp.translation
                                             + np.array([0.0, 0.0, R - s_psi * R_old]))
    else:
        _shift_body(model, psi, np.array([0.0, 0.0, R - s_psi * R_old]))
    ids = [w.joint_id for w in wm.wheels]
    T = [model.jointPlacements[j].translation.copy() for j in ids]
    mid = 0.5 * (T[0] + T[1])
    half = 0.5 * float(np.linalg.norm(T[1] - T[0]))
    for j, t in zip(ids, T):
        jp = model.jointPlacements[j]
        model.jointPlacements[j] = pin.SE3(jp.rotation, mid + (L / half) * (t - mid))
    return [replace(w, radius=R) for w in wm.wheels]


def _shift_body(model: pin.Model, body: int, delta: np.ndarray) -> None:
    r"""Move everything body ``body`` carries (frames, joints, inertia) by ``delta`` in its
    joint frame."""
    if not np.any(delta):
        return
    model.inertias[body] = pin.SE3(np.eye(3), delta).act(model.inertias[body])
    for frame in model.frames:
        if frame.parentJoint == body and frame.type != pin.FrameType.JOINT:
            frame.placement = pin.SE3(frame.placement.rotation, frame.placement.translation
                                      + delta)
    for child in range(body + 1, model.njoints):
        if model.parents[child] == body:
            jp = model.jointPlacements[child]
            model.jointPlacements[child] = pin.SE3(jp.rotation, jp.translation + delta)


__all__ = ["FACTOR", "Dimension", "GeometryDraw", "apply_geometry", "draw_geometry",
           "uniform_scales"]
