r"""The bases without wheels: ``fixed`` (the URDF's root link fixed to the world) and ``free``
(the root link on six 1-DoF joints).

A free base's coordinates are :data:`~.wheeled_model.FREE_BASE`, translations along the world
axes then :math:`R = R_z(\text{yaw})\,R_y(\text{pitch})\,R_x(\text{roll})` (ZYX angles),
singular at :math:`\text{pitch} = \pm\pi/2`. Motors are the ``actuated`` joints (a torque or
force along each joint axis); a rolling ball (``contact``) and tilting wheels
(``rolling_wheels``) are bound to their link frames here.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..errors import ModelError
from .contact import BallContact
from .geometry_constants import unwheeled_lengths
from .model_joints import actuated_inputs, bind_springs, finish_coordinates
from .rolling_wheel import BoundWheelContact
from .urdf_source import UrdfSource
from .wheeled_model import FREE_BASE, ModelSpec, WheeledModel


def build_unwheeled(spec: ModelSpec, source: UrdfSource, urdf_model: pin.Model,
                     urdf_geom: pin.GeometryModel) -> WheeledModel:
    r"""A fixed-base or free model (no wheels)."""
    if spec.wheels:
        raise ModelError(spec.name, None, f"wheels need base 'planar'; this base is {spec.base!r}")
    names: tuple[str, ...] = ()            # the base's coordinates (none for a fixed base)
    if spec.base == "fixed":
        model, geom = pin.Model(urdf_model), urdf_geom
    else:
        base = pin.Model()
        parent = 0
        joints = (pin.JointModelPX(), pin.JointModelPY(), pin.JointModelPZ(),
                  pin.JointModelRZ(), pin.JointModelRY(), pin.JointModelRX())
        for name, jmodel in zip(FREE_BASE, joints):
            parent = base.addJoint(parent, jmodel, pin.SE3.Identity(), name)
            base.appendBodyToJoint(parent, pin.Inertia.Zero(), pin.SE3.Identity())
            base.addJointFrame(parent, -1)
        frame = base.addFrame(pin.Frame("mount", parent, 0, pin.SE3.Identity(),
                                        pin.FrameType.OP_FRAME))
        model, geom = pin.appendModel(base, urdf_model, pin.GeometryModel(), urdf_geom, frame,
                                      pin.SE3.Identity())
        names = FREE_BASE
    coordinate_names = finish_coordinates(spec, model, names)
    actuated, inputs = actuated_inputs(spec, model, coordinate_names)
    body_jid = 0
    if spec.body:
        source.link(spec.body)
        body_jid = model.frames[model.getFrameId(spec.body)].parentJoint
    contact = None
    if spec.contact is not None:
        source.link(spec.contact.link)
        contact = BallContact(spec.contact, model.getFrameId(spec.contact.link))
    lengths = unwheeled_lengths(spec, source, model)
    geometry = lengths.constant_values(lengths.values())
    rolling_wheels = []
    for wc in spec.rolling_wheels:
        source.link(wc.link)
        axis = np.asarray(wc.axis, dtype=float)
        frame = model.getFrameId(wc.link, pin.FrameType.BODY)
        rolling_wheels.append(BoundWheelContact(wc, frame, axis / np.linalg.norm(axis),
                                                np.asarray(wc.centre, dtype=float)))
    return WheeledModel(spec.name, spec, model, geom, (), coordinate_names, inputs, geometry,
                        body_jid, tuple(actuated), contact, tuple(rolling_wheels),
                        bind_springs(spec, model, coordinate_names), lengths)
