r"""The inertial parameters a derivation file may name, per rigid body, with their reference
points.

Pinocchio merges links joined by ``fixed`` (and locked) joints into one rigid body, the body
of the moving joint that carries them: a ``base_footprint`` root, its ``base_link`` and a torso
fixed on top are one body; the dynamics sees only that body's mass distribution, never how it
is shared between its links. So each rigid body has one name, the link that *carries* it:

- the child link of its moving joint (``disk`` for the joint ``theta``, also carrying the
  point mass ``mass`` fixed to it);
- for a planar (wheeled) model, the body link of the model file (``base_link``, also carrying
  ``base_footprint`` and the torso);
- for a fixed or free base, the URDF's root link.

Its parameters describe the whole rigid body and are expressed in the carrying link's frame.
Two families exist, related by the parallel-axis theorem:

- Khalil's standard parameters, about the link frame's **origin**: ``M(link)``,
  ``MX MY MZ(link)`` (first moments :math:`M c`), ``XX XY XZ YY YZ ZZ(link)`` (inertia tensor
  entries :math:`J_O`);
- the physical ones, about the **centre of mass**: ``M(link)``, ``CX CY CZ(link)`` (the centre
  of mass :math:`c` in the link frame), ``IXX IXY IXZ IYY IYZ IZZ(link)`` (inertia tensor
  entries :math:`J_G` about the centre of mass, in the link's axes; ``IXY`` is the tensor entry
  :math:`-\int x y\,dm`, as URDF's ``ixy``), with

.. math::
    MX = M\,CX,\qquad XX = IXX + M\,(CY^2 + CZ^2),\qquad XY = IXY - M\,CX\,CY,\ \dots

A link merged into another body (its joint is fixed or locked) has no parameters of its own
here: naming it is an error (:class:`MergedLinkError`) that names the body it belongs to, so
``MZ(base_footprint)`` can never silently mean a moment of the whole robot about the ground.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from ..errors import UnknownNameError

#: Khalil's standard parameters (about the link origin), in the order of
#: ``Inertia.toDynamicParameters()``.
STANDARD: tuple[str, ...] = ("M", "MX", "MY", "MZ", "XX", "XY", "YY", "XZ", "YZ", "ZZ")
#: The physical parameters (about the centre of mass); ``M`` is shared with :data:`STANDARD`.
PHYSICAL: tuple[str, ...] = ("M", "CX", "CY", "CZ", "IXX", "IXY", "IXZ", "IYY", "IYZ", "IZZ")
#: Every function name a derivation file may apply to a link.
FUNCTIONS: tuple[str, ...] = STANDARD + tuple(n for n in PHYSICAL if n not in STANDARD)
#: Merged links named in a listing (the rest are counted).
LISTED_MEMBERS = 8


class MergedLinkError(UnknownNameError):
    r"""A parameter names a link that is merged into another link's rigid body. Attributes as
    :class:`UnknownNameError` plus ``link``, ``carrier`` (the link naming the body) and
    ``members`` (the body's links)."""

    def __init__(self, link: str, carrier: str, members: tuple[str, ...],
                 where: str | None = None) -> None:
        self.link = link
        self.carrier = carrier
        self.members = tuple(members)
        super().__init__("link", link, None, where=where)
        joined = ", ".join(self.members)
        self.args = (f"{where + ': ' if where else ''}link {link!r} has no parameters of its "
                     f"own: it is fixed to the rigid body named {carrier!r} ({joined}), which "
                     f"the dynamics sees only as a whole; name that body, e.g. "
                     f"M({carrier}), CZ({carrier}) (about {carrier}'s origin or centre of "
                     f"mass, in {carrier}'s axes)",)


@dataclass(frozen=True)
class RigidBody:
    r"""One rigid body of a built model: the link naming it, every link merged into it and
    the joint that moves it."""

    carrier: str
    members: tuple[str, ...]
    joint: str


def rigid_bodies(wm) -> tuple[RigidBody, ...]:
    r"""The model's rigid bodies that carry mass (see the module docstring)."""
    model = wm.model
    planar_body = wm.spec.body if wm.base == "planar" else ""
    members: dict[int, list[str]] = {}
    carriers: dict[int, str] = {}
    for f in model.frames:
        if f.type != pin.FrameType.BODY or f.parentJoint == 0:
            continue
        members.setdefault(f.parentJoint, []).append(f.name)
        above = model.frames[f.parentFrame]
        if above.type == pin.FrameType.JOINT or above.type == pin.FrameType.OP_FRAME:
            carriers.setdefault(f.parentJoint, f.name)
    if planar_body:
        carriers[wm.body_joint_id] = planar_body
    out = []
    for jid, links in members.items():
        if model.inertias[jid].mass <= 0 or jid not in carriers:
            continue
        out.append(RigidBody(carriers[jid], tuple(links), model.names[jid]))
    return tuple(out)


def body_inertia(wm, body: RigidBody) -> pin.Inertia:
    r"""The rigid body's inertia expressed in its carrying link's frame."""
    model = wm.model
    frame = model.frames[model.getFrameId(body.carrier, pin.FrameType.BODY)]
    return frame.placement.actInv(model.inertias[frame.parentJoint])


def parameter_values(wm) -> dict[str, float]:
    r"""Both families of every rigid body, keyed ``"MZ(link)"``, ``"IXX(link)"`` ..."""
    out: dict[str, float] = {}
    for body in rigid_bodies(wm):
        inertia = body_inertia(wm, body)
        for key, value in zip(STANDARD, inertia.toDynamicParameters()):
            out[f"{key}({body.carrier})"] = float(value)
        J, c = np.asarray(inertia.inertia), np.asarray(inertia.lever)
        physical = (inertia.mass, *c, J[0, 0], J[0, 1], J[0, 2], J[1, 1], J[1, 2], J[2, 2])
        for key, value in zip(PHYSICAL, physical):
            out[f"{key}({body.carrier})"] = float(value)
    return out


def merged_links(wm) -> dict[str, RigidBody]:
    r"""Every link that is not a carrying link, with the rigid body it is part of (links of
    massless bodies are absent: they have no parameters either)."""
    return {link: body for body in rigid_bodies(wm) for link in body.members
            if link != body.carrier}


def check_link(wm, link: str, where: str | None = None) -> RigidBody:
    r"""The rigid body named by ``link``; :class:`MergedLinkError` for a merged link,
    :class:`UnknownNameError` (with the valid names) for any other name."""
    bodies = {b.carrier: b for b in rigid_bodies(wm)}
    if link in bodies:
        return bodies[link]
    merged = merged_links(wm)
    if link in merged:
        body = merged[link]
        raise MergedLinkError(link, body.carrier, body.members, where)
    raise UnknownNameError("link with mass", link, bodies, where=where)


def parameter_listing(wm, values: Mapping[str, float] | None = None) -> list[str]:
    r"""Lines listing, per rigid body, the names a derivation file may use and what they refer
    to (the reference point and axes), with the model's values."""
    values = parameter_values(wm) if values is None else values
    lines = []
    for body in rigid_bodies(wm):
        c = body.carrier
        merged = [m for m in body.members if m != c]
        shown = ", ".join(merged[:LISTED_MEMBERS]) + (
            f" and {len(merged) - LISTED_MEMBERS} more" if len(merged) > LISTED_MEMBERS else "")
        lines.append(f"  {c}: the rigid body moved by joint {body.joint}"
                     + (f" ({c} with {shown} fixed to it)" if merged else ""))
        lines.append(f"    about {c}'s origin, in its axes (Khalil): " + ", ".join(
            f"{k}({c})={values[f'{k}({c})']:.6g}" for k in STANDARD))
        lines.append(f"    about the centre of mass, in {c}'s axes:    " + ", ".join(
            f"{k}({c})={values[f'{k}({c})']:.6g}" for k in PHYSICAL))
    merged_all = merged_links(wm)
    for link, body in list(merged_all.items())[:LISTED_MEMBERS]:
        lines.append(f"  {link}: merged into {body.carrier} (name that body; {link} has no "
                     "parameters of its own)")
    if len(merged_all) > LISTED_MEMBERS:
        lines.append(f"  ... and {len(merged_all) - LISTED_MEMBERS} more merged links")
    return lines
