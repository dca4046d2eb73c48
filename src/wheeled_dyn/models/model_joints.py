r"""The joints of a built model: a revolute joint's axis, a joint's origin moved along its
axis, the coordinate names and gravity of a finished model, springs bound to their joints,
and a declared direction as a unit vector.

Moving joint :math:`j`'s origin by :math:`d` along its axis :math:`a` is an exact change of
frame (a rotation about an axis commutes with a translation along it):

.. math::

    {}^{p}M_{j'} = {}^{p}M_{j}\,(I, d\,a),\qquad X_{j'} = (I, -d\,a)\,X_j

for everything :math:`X` the joint carries (inertia, frames, child joints, geometry).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from ..errors import ModelError, UnknownNameError
from .springs import SPRING_JOINTS, BoundSpring
from .wheeled_model import ModelSpec

#: Shortest direction vector (``up``, a wheel axis) taken as a direction.
DIRECTION_TOL = 1e-9
#: Standard gravity of built models (m/s²); parameter sets may change it.
GRAVITY = 9.81

_AXES = {"X": np.array([1.0, 0, 0]), "Y": np.array([0, 1.0, 0]), "Z": np.array([0, 0, 1.0])}


def joint_axis(jmodel: pin.JointModel) -> np.ndarray:
    r"""The axis of a revolute joint in its own frame (``ValueError`` naming the joint type
    for any other joint)."""
    short = jmodel.shortname()
    if short in ("JointModelRX", "JointModelRY", "JointModelRZ"):
        return _AXES[short[-1]]
    if short == "JointModelRevoluteUnaligned":
        inner = jmodel.extract() if hasattr(jmodel, "extract") else jmodel
        return np.asarray(inner.axis, dtype=float)
    raise ValueError(short)



def unit_direction(spec: ModelSpec, what: str, value: Sequence[float], item: str
                   ) -> np.ndarray:
    r"""``value`` as a unit vector; :class:`ModelError` for three numbers that are not finite
    or of length below :data:`DIRECTION_TOL`."""
    v = np.asarray(value, dtype=float).reshape(-1)
    norm = float(np.linalg.norm(v)) if v.shape == (3,) and np.all(np.isfinite(v)) else 0.0
    if not norm > DIRECTION_TOL:
        raise ModelError(spec.name, item, f"{what} direction {tuple(value)}: expected three "
                                          "finite numbers, not all zero")
    return v / norm



def move_joint_to(model: pin.Model, geom: pin.GeometryModel, jid: int, frame: pin.Frame
                  ) -> None:
    r"""Move joint ``jid``'s origin along its axis to the origin of ``frame`` (on the axis):
    with :math:`d` the offset along the axis, :math:`{}^{j}M_{j'} = (I, d\,a)`, and everything
    the joint carries re-expressed in the new joint frame by :math:`(I, -d\,a)`."""
    if frame.parentJoint != jid:
        return
    axis = joint_axis(model.joints[jid])
    d = float(frame.placement.translation @ axis)
    if d == 0.0:
        return
    shift, back = pin.SE3(np.eye(3), d * axis), pin.SE3(np.eye(3), -d * axis)
    model.jointPlacements[jid] = model.jointPlacements[jid] * shift
    model.inertias[jid] = back.act(model.inertias[jid])
    for f in model.frames:
        if f.parentJoint == jid and f.type != pin.FrameType.JOINT:
            f.placement = back * f.placement
    for child in range(jid + 1, model.njoints):
        if model.parents[child] == jid:
            model.jointPlacements[child] = back * model.jointPlacements[child]
    for obj in geom.geometryObjects:
        if obj.parentJoint == jid:
            obj.placement = back * obj.placement



#: Pinocchio's joint models of more than one coordinate, by the URDF joint type they come
#: from.
URDF_TYPES = {"JointModelFreeFlyer": "floating", "JointModelPlanar": "planar",
              "JointModelSpherical": "spherical", "JointModelSphericalZYX": "spherical"}


def finish_coordinates(spec: ModelSpec, model: pin.Model, base_names: Sequence[str]
                       ) -> tuple[str, ...]:
    r"""Name the model, set gravity, check every joint has one coordinate; the coordinate
    names (the base's, then the URDF joints' under their aliases)."""
    model.name = spec.name
    model.gravity = pin.Motion(np.array([0.0, 0.0, -GRAVITY]), np.zeros(3))
    names = list(base_names)
    for jid in range(len(base_names) + 1, model.njoints):
        names.append(spec.aliases.get(model.names[jid], model.names[jid]))
    for jid in range(1, model.njoints):
        joint = model.joints[jid]
        if joint.nq != 1 or joint.nv != 1:
            kind = joint.shortname()
            urdf = URDF_TYPES.get(kind)
            said = f"URDF joint type {urdf!r} (Pinocchio's {kind})" if urdf else \
                f"joint type {kind}"
            raise ModelError(spec.name, model.names[jid],
                             f"{said} has {joint.nv} velocities: a model's joints have one "
                             "each (revolute, continuous, prismatic); lock it or replace it")
    if len(set(names)) != len(names):
        raise ModelError(spec.name, None, f"coordinate names repeat: {names}")
    for name in names:          # a coordinate's name is no other's velocity or acceleration
        for prefix in ("d", "dd"):
            if name.startswith(prefix) and name[len(prefix):] in names:
                joint = next((j for j, a in spec.aliases.items() if a == name), None)
                raise ModelError(spec.name, joint, f"coordinate name {name!r} is the name of "
                                 f"the {'velocity' if prefix == 'd' else 'acceleration'} of "
                                 f"coordinate {name[len(prefix):]!r} (a velocity is named d "
                                 "and an acceleration dd before its coordinate's name): "
                                 "give the joint another alias")
    return tuple(names)



def bind_springs(spec: ModelSpec, model: pin.Model, coordinate_names: Sequence[str]
                  ) -> tuple[BoundSpring, ...]:
    r"""Each spring of ``spec`` on its joint, named by its URDF joint name or its coordinate
    name; the joint must be prismatic or revolute, and carry one spring at most."""
    out: list[BoundSpring] = []
    for s in spec.springs:
        if s.joint in coordinate_names:
            jid = 1 + list(coordinate_names).index(s.joint)
        elif model.existJointName(s.joint):
            jid = model.getJointId(s.joint)
        else:
            raise UnknownNameError("joint", s.joint, list(coordinate_names),
                                   where=f"model {spec.name}, spring {s.name}")
        if model.joints[jid].shortname() not in SPRING_JOINTS:
            raise ModelError(spec.name, s.joint, f"spring {s.name}: joint type "
                             f"{model.joints[jid].shortname()}; expected prismatic or revolute")
        if any(b.v_index == model.joints[jid].idx_v or b.spec.name == s.name for b in out):
            raise ModelError(spec.name, s.joint, f"spring {s.name}: a second spring on this "
                                                 "joint, or a repeated spring name")
        out.append(BoundSpring(s, model.joints[jid].idx_q, model.joints[jid].idx_v,
                               float(s.stiffness)))
    return tuple(out)


#: The wheel torques' names of a wheeled model where its file names none.
WHEEL_INPUTS = ("tau_l", "tau_r")


def actuated_inputs(spec: ModelSpec, model: pin.Model, coordinate_names: Sequence[str],
                    wheel_inputs: Sequence[str] = ()) -> tuple[tuple[int, ...], tuple[str, ...]]:
    r"""The velocity indices of the joints ``spec.actuated`` names (one degree of freedom
    each, no wheel's) and the names of all the model's inputs, B's columns in order: the
    wheels' torques first (``wheel_inputs``: a wheeled model's two), then one per actuated
    joint (``tau_<its coordinate>`` where the file names none). The file's ``inputs`` name
    them all, or, beside wheels, the actuated joints' only; another count is an error
    naming what was expected."""
    wheel_joints = set(wheel_joint_names(spec, model))
    actuated = []
    for joint in spec.actuated:
        if not model.existJointName(joint):
            raise UnknownNameError("joint", joint, list(model.names)[1:],
                                   where=f"model {spec.name}")
        jmodel = model.joints[model.getJointId(joint)]
        if joint in wheel_joints or jmodel.nv != 1:
            raise ModelError(spec.name, joint, "an actuated joint must be a joint of one "
                             "degree of freedom that is no drive wheel's (the wheels' "
                             "torques are inputs already)" if joint in wheel_joints else
                             f"an actuated joint must have one degree of freedom, not "
                             f"{jmodel.nv}")
        actuated.append(jmodel.idx_v)
    own = tuple("tau_" + coordinate_names[i] for i in actuated)
    given = tuple(spec.inputs) if spec.inputs is not None else None
    if given is None:
        return tuple(actuated), (*wheel_inputs, *own)
    if len(given) == len(wheel_inputs) + len(actuated):
        return tuple(actuated), given
    if wheel_inputs and actuated and len(given) == len(actuated):
        return tuple(actuated), (*wheel_inputs, *given)
    expected = " and ".join([*(["two wheel motors"] if wheel_inputs else []),
                             *([f"{len(actuated)} actuated joints"]
                               if actuated or not wheel_inputs else [])])
    raise ModelError(spec.name, None, f"{len(given)} input names for {expected}" + (
        " (name the wheels' two first, then one per actuated joint; or the actuated "
        "joints' only)" if wheel_inputs and actuated else ""))


def wheel_joint_names(spec: ModelSpec, model: pin.Model) -> list[str]:
    r"""The joints that move the drive wheels' links ``spec.wheels`` (those the model has)."""
    out = []
    for link in spec.wheels:
        if model.existFrame(link, pin.FrameType.BODY):
            jid = model.frames[model.getFrameId(link, pin.FrameType.BODY)].parentJoint
            out.append(model.names[jid])
    return out
