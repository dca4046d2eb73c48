r"""Other lengths for a built model: random draws of its geometry, and the model they give.

:func:`draw_geometry` draws every length a parameter set varies (:mod:`.geometry`): each drawn
dimension, each list of equal lengths and each free constant is multiplied by its own factor,
log-uniform in :math:`[1/F, F]` (:data:`FACTOR`), so a zero stays zero and a length keeps its
sign. A *uniform* link (a family of the comparison: a disc stays a disc, a rod a rod) is
scaled as a whole: one factor :math:`s` for its shape (its radii and lengths, and every list
of equal lengths that includes one of them, so links tied by such a list share it) and its
inertia about its link frame, and a random mass factor :math:`\mu`,

.. math::

    m \to \mu m,\qquad c \to s\,c,\qquad I_G \to \mu s^2 I_G ,

which keeps :math:`I = m r^2/2`, :math:`\tfrac25 m r^2`, :math:`m l^2/12` of a uniform disc,
ball or rod of the drawn radius or length.

:func:`apply_geometry` makes the model of a draw from the model it was drawn on: Pinocchio's
joint placements (for a moving joint of parent link frame :math:`(R_p, p_p)` in its parent
joint, :math:`{}^{\lambda}M_j = (R_p, p_p)\,(R_o, t)`: a new origin :math:`t'` moves the
translation by :math:`R_p(t' - t)`); for a fixed joint the same move of everything it carries
inside its rigid body (frames, the joints hanging from them, the links' inertias); a planar
model's axle height (its wheel radius) and half track (the wheel joints moved along the axle
about their midpoint); the radii of the rolling contacts and the constants. A rigid body whose
links moved or that has a uniform link is put together again from its links' own inertias
(:attr:`~.geometry.GeometryTable.inertials`), each scaled as drawn. The visual model is not
changed (parameter sets are not drawn).
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType

import numpy as np
import pinocchio as pin

from .wheeled_model import WheeledModel
from .geometry import ConstantKind, Dimension, GeometryTable

#: Largest factor of a drawn length (and smallest: 1/FACTOR).
FACTOR = 1.6
#: Range of the random mass factor of a uniform link.
MASS_FACTORS = (0.5, 2.0)


@dataclass(frozen=True)
class GeometryDraw:
    r"""The lengths of one parameter set: ``values`` of the dimensions and free constants;
    ``links`` the (size, mass) factors of the links whose rigid body is put together again
    from its links (the uniform links and the other links of their bodies, size 1)."""

    values: Mapping[str, float]
    links: Mapping[str, tuple[float, float]]
    #: the links drawn uniform (their URDF inertia read as the uniform body's where it is
    #: that to its printed digits: :mod:`.uniform_reading`)
    uniform: frozenset[str] = frozenset()


class _Classes:
    r"""Union-find over the draw groups and the uniform links."""

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


def _factor(rng: np.random.Generator, spread: float = FACTOR) -> float:
    return float(math.exp(rng.uniform(-math.log(spread), math.log(spread))))


def _groups(table: GeometryTable, uniform: set[str]) -> tuple[dict[str, list[str]], _Classes]:
    r"""The draw groups (a list of equal lengths, a free constant, a length drawn alone: name
    → its dimensions) and their classes: groups that touch a ``uniform`` link's shape share
    its factor."""
    classes = _Classes()
    groups: dict[str, list[str]] = {}
    tied: set[str] = set()
    for name, c in table.constants.items():
        if c.kind is ConstantKind.SAME:
            tied.update(d for _, d in c.members)            # drawn with it, or kept
            if c.drawn:
                groups[name] = [d for _, d in c.members]
        elif c.kind in (ConstantKind.FREE, ConstantKind.TRACK) and c.drawn:
            groups[name] = []
    for name, d in table.dimensions.items():
        if d.drawn and name not in tied:
            groups[name] = [name]
    for group, dims in groups.items():
        for link in {table.dimensions[d].shape_of for d in dims} & uniform:
            classes.union(("group", group), ("link", link))
    return groups, classes


def bodies_of(wm: WheeledModel) -> dict[int, list[str]]:
    r"""The links of each rigid body (Pinocchio joint id → link names, in frame order)."""
    out: dict[int, list[str]] = {}
    for frame in wm.model.frames:
        if frame.type == pin.FrameType.BODY:
            out.setdefault(frame.parentJoint, []).append(frame.name)
    return out


def draw_geometry(wm: WheeledModel, rng: np.random.Generator,
                  uniform: Collection[str] = (), spread: float = FACTOR) -> GeometryDraw:
    r"""Random lengths for ``wm`` (module docstring, each factor in :math:`[1/s, s]` for the
    ``spread`` s); ``uniform``: the links scaled as a whole (with a random mass factor each;
    the two drive wheels of a planar model share theirs)."""
    table = wm.lengths
    if table is None:
        return GeometryDraw(MappingProxyType({}), MappingProxyType({}))
    uniform = set(uniform)
    groups, classes = _groups(table, uniform)
    factors: dict[object, float] = {}

    def factor(key: object) -> float:
        root = classes.find(key)
        if root not in factors:
            factors[root] = _factor(rng, spread)
        return factors[root]

    values: dict[str, float] = {}
    for group, dims in groups.items():
        f = factor(("group", group))
        c = table.constants.get(group)
        if c is not None and c.kind in (ConstantKind.FREE, ConstantKind.TRACK):
            values[group] = c.value * f
        for d in dims:
            values[d] = table.dimensions[d].value * f
    links: dict[str, tuple[float, float]] = {}
    wheels = {w.link for w in wm.wheels}
    masses: dict[str, float] = {}            # the drive wheels share one factor, in any order
    for body, names in bodies_of(wm).items():
        if not uniform & set(names):
            continue
        for link in names:
            size = factor(("link", link)) if link in uniform else 1.0
            key = "wheels" if link in wheels else link
            if key not in masses:
                masses[key] = float(rng.uniform(*MASS_FACTORS))
            links[link] = (size, masses[key])
    return GeometryDraw(MappingProxyType(values), MappingProxyType(links), frozenset(uniform))


def uniform_scales(wm: WheeledModel, uniform: Collection[str]
                   ) -> dict[str, tuple[str, float, tuple[str, ...]]]:
    r"""For each ``uniform`` link: a name whose length its size factor multiplies (a drawn
    group of its class: a constant's or a length's name), that length's value in ``wm``, and
    every name of the class (they scale alike); links whose class has none are left out. The
    closed forms write the link's size as that length over its value."""
    table = wm.lengths
    if table is None:
        return {}
    uniform = set(uniform)
    groups, classes = _groups(table, uniform)
    out: dict[str, tuple[str, float, tuple[str, ...]]] = {}
    for link in sorted(uniform):
        root = classes.find(("link", link))
        members = [g for g in groups if classes.find(("group", g)) == root]
        names = tuple(dict.fromkeys([*members, *(d for g in members for d in groups[g])]))
        for group in members:
            value = table.constants[group].value if group in table.constants else \
                table.dimensions[groups[group][0]].value
            if value:
                out[link] = (group, value, names)
                break
    return out


def apply_geometry(wm: WheeledModel, draw: GeometryDraw) -> WheeledModel:
    r"""The model ``wm`` with the lengths of ``draw`` (module docstring): names not in the
    draw keep their values. Raises :class:`~wheeled_dyn.errors.ParameterError` where a contact
    becomes invalid (a ball as large as its bowl's vertex radius)."""
    table = wm.lengths
    if table is None or (not draw.values and not draw.links):
        return wm
    model = pin.Model(wm.model)
    old = {k: d.value for k, d in table.dimensions.items()}
    new = {k: float(draw.values.get(k, v)) for k, v in old.items()}
    moved = _move_origins(model, old, new)
    geometry = table.constant_values(new, {k: v for k, v in draw.values.items()
                                           if k in table.constants})
    wheels = wm.wheels
    if wheels:
        wheels = tuple(_planar(wm, model, geometry["R"], geometry["L"]))
    for body, links in bodies_of(wm).items():
        if body in moved or set(links) & set(draw.links):
            _compose(model, body, links, table, draw.links, draw.uniform)
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
        size = draw.links.get(w.link, (1.0, 1.0))[0]
        spec = replace(w.spec, radius=new[f"radius({w.link})"],
                       tyre_radius=new.get(f"tyre_radius({w.link})", w.spec.tyre_radius))
        rolling.append(replace(w, spec=spec, centre=w.centre * size))
    dims = {k: replace(d, value=new[k]) for k, d in table.dimensions.items()}
    consts = {k: replace(c, value=geometry[k]) for k, c in table.constants.items()}
    lengths = replace(table, dimensions=MappingProxyType(dims),
                      constants=MappingProxyType(consts))
    return replace(wm, model=model, wheels=wheels, contact=contact,
                   rolling_wheels=tuple(rolling), geometry=geometry, lengths=lengths)


def _compose(model: pin.Model, body: int, links: list[str], table: GeometryTable,
             factors: Mapping[str, tuple[float, float]],
             uniform: frozenset[str] = frozenset()) -> None:
    r"""Body ``body``'s inertia as the sum of its links' own inertias at their (moved) frames,
    each scaled by its (size, mass) factors: :math:`\mu m`, :math:`s c`, :math:`\mu s^2 I_G`."""
    total = pin.Inertia.Zero()
    for link in links:
        if link not in table.inertials or table.inertials[link][0] <= 0:
            continue                  # no mass (a ROS base_footprint): nothing to add
        # a link drawn uniform: the uniform body's, where the URDF prints that (rounded)
        read = table.uniform[link][0] if link in uniform and link in table.uniform else \
            table.inertials[link]
        own = pin.Inertia.FromDynamicParameters(np.asarray(read))
        size, mass = factors.get(link, (1.0, 1.0))
        own = pin.Inertia(own.mass * mass, own.lever * size, own.inertia * mass * size**2)
        frame = model.frames[model.getFrameId(link, pin.FrameType.BODY)]
        total += frame.placement.act(own)
    model.inertias[body] = total


def _move_origins(model: pin.Model, old: Mapping[str, float], new: Mapping[str, float]
                  ) -> set[int]:
    r"""Each joint whose origin changed: a moving joint's placement moved by :math:`R_p(t' -
    t)`; a fixed joint's subtree inside its body moved by as much. The bodies whose links
    moved."""
    moved: set[int] = set()
    for name in [k for k in old if k.startswith("origin_x(")]:
        joint = name[len("origin_x("):-1]
        t_old = np.array([old[f"origin_{a}({joint})"] for a in "xyz"])
        t_new = np.array([new[f"origin_{a}({joint})"] for a in "xyz"])
        if np.array_equal(t_new, t_old):
            continue
        moving = model.existJointName(joint)
        kind = pin.FrameType.JOINT if moving else pin.FrameType.FIXED_JOINT
        fid = model.getFrameId(joint, kind)
        frame = model.frames[fid]
        delta = model.frames[frame.parentFrame].placement.rotation @ (t_new - t_old)
        if moving:
            jid = model.getJointId(joint)
            jp = model.jointPlacements[jid]
            model.jointPlacements[jid] = pin.SE3(jp.rotation, jp.translation + delta)
        else:
            _shift_subtree(model, fid, delta)
            moved.add(frame.parentJoint)
    return moved


def _shift_subtree(model: pin.Model, root: int, delta: np.ndarray) -> None:
    r"""Move frame ``root`` and every frame and joint hanging from it inside its body by
    ``delta`` (in the body's joint frame)."""
    body = model.frames[root].parentJoint
    inside = {root}
    for fid, frame in enumerate(model.frames):
        if fid != root and frame.parentJoint == body and frame.type != pin.FrameType.JOINT:
            chain = fid
            while chain not in inside and model.frames[chain].parentJoint == body and \
                    model.frames[chain].parentFrame != chain:
                chain = model.frames[chain].parentFrame
            if chain in inside:
                inside.add(fid)
    for fid in inside:
        frame = model.frames[fid]
        frame.placement = pin.SE3(frame.placement.rotation, frame.placement.translation + delta)
    for jid in range(body + 1, model.njoints):
        joint_frame = model.frames[model.getFrameId(model.names[jid], pin.FrameType.JOINT)]
        if model.parents[jid] == body and joint_frame.parentFrame in inside:
            jp = model.jointPlacements[jid]
            model.jointPlacements[jid] = pin.SE3(jp.rotation, jp.translation + delta)


def _planar(wm: WheeledModel, model: pin.Model, R: float, L: float) -> list:
    r"""A planar model's axle at height ``R`` and its wheels ``L`` from the axle midpoint."""
    lift = np.array([0.0, 0.0, R - wm.geometry["R"]])
    if wm.spec.pitch:
        phi = model.getJointId("phi")
        jp = model.jointPlacements[phi]
        model.jointPlacements[phi] = pin.SE3(jp.rotation, jp.translation + lift)
    else:
        _shift_body(model, model.getJointId("psi"), lift)
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


__all__ = ["FACTOR", "Dimension", "GeometryDraw", "apply_geometry", "bodies_of",
           "draw_geometry", "uniform_scales"]
