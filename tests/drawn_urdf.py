"""A URDF written out with the numbers of a drawn parameter set, and the spec that builds it.

The independent side of the identity "the truth on drawn geometry = a model built from a URDF
with the same numbers": the model's URDF text with each joint origin, each first sphere or
cylinder and each rigid body's inertia replaced by the parameter set's, read again by Pinocchio's
URDF parser through the builder (``build_wheeled_model``). Nothing of the parameter set's
Pinocchio model is copied but numbers a user would write in a URDF: origins, radii, lengths,
masses, centres of mass and inertia tensors per link.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

import numpy as np
import pinocchio as pin

from wheeled_dyn.models.builder import ModelSpec, WheeledModel, build_wheeled_model


def _first_links(wm: WheeledModel) -> dict[int, str]:
    """The link carrying each rigid body's inertia in the written URDF: the first link frame
    on that body (the child link of its moving joint, or a planar model's root link)."""
    out: dict[int, str] = {}
    for frame in wm.model.frames:
        if frame.type == pin.FrameType.BODY and frame.parentJoint not in out:
            out[frame.parentJoint] = frame.name
    return out


def _fmt(values) -> str:
    return " ".join(repr(float(x)) for x in values)


def drawn_urdf_text(base: WheeledModel, drawn: WheeledModel) -> str:
    """The URDF of ``base`` with the lengths and inertias of ``drawn`` (the same model with a
    parameter set's numbers)."""
    root = ET.fromstring(base.spec.urdf.read_text())
    dims = drawn.dimensions
    for joint in root.iter("joint"):
        name = joint.get("name")
        origin = joint.find("origin")
        if origin is None:
            origin = ET.SubElement(joint, "origin", xyz="0 0 0", rpy="0 0 0")
        xyz = [float(x) for x in origin.get("xyz", "0 0 0").split()]
        keys = [f"origin_{a}({name})" for a in "xyz"]
        if all(k in dims for k in keys):
            xyz = [dims[k] for k in keys]
        elif base.wheels and name in {w.joint_name for w in base.wheels}:
            jid = base.model.getJointId(name)     # a planar model's wheel: moved along the axle
            parent = base.model.frames[base.model.frames[
                base.model.getFrameId(name, pin.FrameType.JOINT)].parentFrame].placement
            delta = drawn.model.jointPlacements[jid].translation - \
                base.model.jointPlacements[jid].translation
            xyz = list(np.asarray(xyz) + parent.rotation.T @ delta)
        origin.set("xyz", _fmt(xyz))
    first = _first_links(drawn)
    for link in root.iter("link"):
        name = link.get("name")
        for key, attribute in (("radius", "radius"), ("length", "length")):
            dim = f"{key}({name})"
            shape = _first_shape(link)
            if dim in dims and shape is not None and shape.get(attribute) is not None:
                shape.set(attribute, repr(float(dims[dim])))
        for inertial in link.findall("inertial"):
            link.remove(inertial)
        jid = drawn.model.frames[drawn.model.getFrameId(name, pin.FrameType.BODY)].parentJoint
        if first.get(jid) == name and drawn.model.inertias[jid].mass > 0:
            frame = drawn.model.frames[drawn.model.getFrameId(name, pin.FrameType.BODY)]
            inertia = frame.placement.actInv(drawn.model.inertias[jid])
            I = inertia.inertia
            inertial = ET.SubElement(link, "inertial")
            ET.SubElement(inertial, "origin", xyz=_fmt(inertia.lever), rpy="0 0 0")
            ET.SubElement(inertial, "mass", value=repr(float(inertia.mass)))
            entries = {f"i{'xyz'[a]}{'xyz'[b]}": repr(float(I[a, b]))
                       for a, b in ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))}
            ET.SubElement(inertial, "inertia", **entries)
    return ET.tostring(root, encoding="unicode")


def _first_shape(link: ET.Element) -> ET.Element | None:
    """The link's first sphere or cylinder (collision, then visual), as the model reads it."""
    for group in ("collision", "visual"):
        for item in link.findall(group):
            geometry = item.find("geometry")
            if geometry is None:
                continue
            for kind in ("cylinder", "sphere"):
                if geometry.find(kind) is not None:
                    return geometry.find(kind)
    return None


def drawn_spec(base: WheeledModel, drawn: WheeledModel, urdf: Path) -> ModelSpec:
    """The spec of ``base`` reading ``urdf``, with the contact radii, the wheel radius and the
    free constants of ``drawn``."""
    spec = base.spec
    contact = spec.contact
    if contact is not None:
        contact = drawn.contact.spec
    rolling = tuple(w.spec for w in drawn.rolling_wheels)
    geometry = {k: (drawn.geometry[k] if isinstance(v, float) else v)
                for k, v in spec.geometry.items()}
    radius = drawn.wheels[0].radius if drawn.wheels else spec.radius
    return replace(spec, urdf=urdf, contact=contact, rolling_wheels=rolling or spec.rolling_wheels,
                   geometry=geometry, radius=radius, coordinate_sets=spec.coordinate_sets)


def rebuilt(base: WheeledModel, drawn: WheeledModel, folder: Path) -> WheeledModel:
    """The model built from the URDF written with ``drawn``'s numbers (its gravity and springs
    copied: a URDF has neither)."""
    path = folder / f"{base.name}_drawn.urdf"
    path.write_text(drawn_urdf_text(base, drawn))
    wm = build_wheeled_model(drawn_spec(base, drawn, path))
    wm.model.gravity = drawn.model.gravity
    wm.model.armature[:] = drawn.model.armature
    return replace(wm, springs=drawn.springs)
