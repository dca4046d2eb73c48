r"""A wheeled model from any URDF: the body on a ground-plane base, the wheels as revolute joints.

Given a URDF, the link that carries the axle (the *body*) and the two drive wheels, the builder
makes a Pinocchio model whose joints, all with one degree of freedom (so that q and v have the
same size and Christoffel symbols exist), are

.. math::

    q = (x_0,\ y_0,\ \psi,\ [\varphi],\ \text{the URDF's own joints}\ \dots)

- :math:`x_0, y_0` (prismatic along the world x and y): the point on the ground plane
  :math:`z = 0` below the axle midpoint;
- :math:`\psi` (revolute about the world z, up): the heading, the body's forward direction;
- :math:`\varphi` (optional, revolute about the axle, oriented from the left wheel to the right
  wheel): the pitch of the body; the axle midpoint is at height :math:`R` (wheel radius);
- then the URDF's tree as written, hanging from the body, with ``continuous`` joints as
  unlimited revolute joints (each wheel angle is one coordinate, measured relative to the body).

Joints listed in ``lock`` are frozen at zero (their bodies' inertia is merged into their parents).
The body's *up* direction (in its link frame, at zero pitch) is declared; *forward* is
up × axle. The wheel radius comes from the wheel link's cylinder geometry unless given.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..errors import ModelError, UnknownNameError
from .urdf_source import UrdfSource, read_urdf

#: Largest |cos| between the axle and the up direction for the axle to count as horizontal.
HORIZONTAL_TOL = 1e-9
#: Largest relative difference between the two wheel radii.
RADIUS_TOL = 1e-9

_AXES = {"X": np.array([1.0, 0, 0]), "Y": np.array([0, 1.0, 0]), "Z": np.array([0, 0, 1.0])}


@dataclass(frozen=True)
class ModelSpec:
    r"""What to build: a URDF, its body and wheels, conventions. See the module docstring."""

    name: str
    urdf: Path
    body: str
    wheels: tuple[str, str]                      # (left wheel link, right wheel link)
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)
    pitch: bool = True
    lock: tuple[str, ...] = ()
    aliases: Mapping[str, str] = field(default_factory=dict)   # joint name -> coordinate name
    inputs: tuple[str, str] = ("tau_l", "tau_r")
    radius: float | None = None
    package_dirs: tuple[str, ...] = ()
    description: str = ""


@dataclass(frozen=True)
class Wheel:
    r"""A drive wheel of a built model."""

    link: str
    side: str            # "left" or "right"
    joint_name: str
    joint_id: int
    v_index: int
    radius: float
    width: float


@dataclass(frozen=True)
class WheeledModel:
    r"""A Pinocchio model of a wheeled body with its conventions.

    ``coordinate_names[i]`` names ``q[i]`` (and ``v[i]``); ``wheels`` are the drive wheels;
    ``input_names`` the wheel motor torques (acting about each wheel joint axis, reaction on
    the wheel's parent); ``geometry`` holds ``R`` (wheel radius) and ``L`` (half the distance
    between the wheel centres).
    """

    name: str
    spec: ModelSpec
    model: pin.Model
    visual_model: pin.GeometryModel | None
    wheels: tuple[Wheel, ...]
    coordinate_names: tuple[str, ...]
    input_names: tuple[str, ...]
    geometry: Mapping[str, float]
    body_joint_id: int

    @property
    def nv(self) -> int:
        return self.model.nv

    def index(self, coordinate: str) -> int:
        try:
            return self.coordinate_names.index(coordinate)
        except ValueError:
            raise UnknownNameError("coordinate", coordinate, self.coordinate_names,
                                   where=f"model {self.name}") from None

    def joint_id_of_link(self, link: str) -> int:
        r"""The joint that moves ``link`` (its body frame's parent joint)."""
        if not self.model.existFrame(link):
            names = [f.name for f in self.model.frames if f.type == pin.FrameType.BODY]
            raise UnknownNameError("link", link, names, where=f"model {self.name}")
        return self.model.frames[self.model.getFrameId(link)].parentJoint

    def input_matrix(self) -> np.ndarray:
        r"""B (nv × number of motors): motor k acts on its wheel joint, :math:`B_{ik}=\delta_{i,w_k}`."""
        B = np.zeros((self.nv, len(self.wheels)))
        for k, wheel in enumerate(self.wheels):
            B[wheel.v_index, k] = 1.0
        return B

    def with_model(self, model: pin.Model) -> "WheeledModel":
        r"""The same conventions on another Pinocchio model of identical structure (e.g. other
        inertial parameters)."""
        return WheeledModel(self.name, self.spec, model, self.visual_model, self.wheels,
                            self.coordinate_names, self.input_names, self.geometry,
                            self.body_joint_id)


def _joint_axis(jmodel: pin.JointModel) -> np.ndarray:
    short = jmodel.shortname()
    if short in ("JointModelRX", "JointModelRY", "JointModelRZ"):
        return _AXES[short[-1]]
    if short == "JointModelRevoluteUnaligned":
        return np.asarray(jmodel.axis, dtype=float)
    raise ValueError(short)


def _urdf_models(source: UrdfSource, spec: ModelSpec) -> tuple[pin.Model, pin.GeometryModel]:
    text = source.pinocchio_text()
    model = pin.buildModelFromXML(text)
    geom = pin.buildGeomFromUrdfString(model, text, pin.GeometryType.VISUAL,
                                       package_dirs=list(spec.package_dirs))
    if spec.lock:
        ids = []
        for name in spec.lock:
            if not model.existJointName(name):
                raise UnknownNameError("joint", name, list(model.names)[1:], where=str(source.path))
            ids.append(model.getJointId(name))
        model, geom = pin.buildReducedModel(model, geom, ids, pin.neutral(model))
    return model, geom


def _wheel_geometry(source: UrdfSource, spec: ModelSpec, model: pin.Model, data: pin.Data,
                    link: str) -> tuple[np.ndarray, np.ndarray, float, float, str]:
    """Centre, spin axis (in the URDF root frame), radius, width and joint name of a wheel."""
    joint = source.joint_to(link)
    if joint.type not in ("continuous", "revolute"):
        raise ModelError(spec.name, link, f"wheel joint {joint.name!r} is {joint.type!r}, "
                                          "expected continuous or revolute")
    jid = model.getJointId(joint.name)
    centre = data.oMi[jid].translation.copy()
    axis = data.oMi[jid].rotation @ _joint_axis(model.joints[jid])
    cylinder = source.cylinder(link)
    if spec.radius is not None:
        radius = float(spec.radius)
        width = cylinder[1] if cylinder else 0.05
    elif cylinder is None:
        raise ModelError(spec.name, link, "wheel has no cylinder geometry to read its radius "
                                          "from; give the radius explicitly")
    else:
        radius, width = cylinder
    if not radius > 0:
        raise ModelError(spec.name, link, f"wheel radius {radius} is not positive")
    return centre, axis, radius, width, joint.name


def build_wheeled_model(spec: ModelSpec) -> WheeledModel:
    r"""Build the wheeled model described by ``spec`` (see the module docstring)."""
    source = read_urdf(spec.urdf)
    body_link = source.link(spec.body).name
    for w in spec.wheels:
        source.link(w)
    urdf_model, urdf_geom = _urdf_models(source, spec)
    data = urdf_model.createData()
    pin.forwardKinematics(urdf_model, data, pin.neutral(urdf_model))
    pin.updateFramePlacements(urdf_model, data)

    (cl, al, rl, wl, jl), (cr, ar, rr, wr, jr) = (
        _wheel_geometry(source, spec, urdf_model, data, link) for link in spec.wheels)
    if abs(rl - rr) > RADIUS_TOL * max(rl, rr):
        raise ModelError(spec.name, None, f"wheel radii differ: {rl} and {rr}")
    axle = cr - cl
    half_track = 0.5 * float(np.linalg.norm(axle))
    if half_track <= 0:
        raise ModelError(spec.name, None, "the two wheel centres coincide")
    axle /= 2 * half_track
    body_rot = data.oMf[urdf_model.getFrameId(body_link)].rotation
    up = body_rot @ np.asarray(spec.up, dtype=float)
    up /= np.linalg.norm(up)
    for link, axis in ((spec.wheels[0], al), (spec.wheels[1], ar)):
        if np.linalg.norm(np.cross(axis, axle)) > 1e-6:
            raise ModelError(spec.name, link, "wheel spin axis is not along the axle")
    if abs(float(up @ axle)) > HORIZONTAL_TOL:
        raise ModelError(spec.name, body_link, "the axle is not horizontal for the declared "
                                               f"up direction {spec.up}")
    forward = np.cross(up, axle)
    left = np.cross(up, forward)
    R_HJ = np.vstack([forward, left, up])        # root-frame vectors -> heading frame
    centre = 0.5 * (cl + cr)

    base = pin.Model()
    base.name = spec.name
    parent = 0
    for name, jmodel in (("x0", pin.JointModelPX()), ("y0", pin.JointModelPY()),
                         ("psi", pin.JointModelRZ())):
        parent = base.addJoint(parent, jmodel, pin.SE3.Identity(), name)
        base.appendBodyToJoint(parent, pin.Inertia.Zero(), pin.SE3.Identity())
        base.addJointFrame(parent, -1)
    # the mount frame has the URDF root's axes, at the axle midpoint, axle height above ground
    mount_in_heading = pin.SE3(R_HJ, np.array([0.0, 0.0, rl]))
    names = ["x0", "y0", "psi"]
    if spec.pitch:
        parent = base.addJoint(parent, pin.JointModelRevoluteUnaligned(axle), mount_in_heading,
                               "phi")
        base.appendBodyToJoint(parent, pin.Inertia.Zero(), pin.SE3.Identity())
        names.append("phi")
        mount_in_heading = pin.SE3.Identity()
    frame = base.addFrame(pin.Frame("mount", parent, 0, mount_in_heading, pin.FrameType.OP_FRAME))
    model, geom = pin.appendModel(base, urdf_model, pin.GeometryModel(), urdf_geom, frame,
                                  pin.SE3(np.eye(3), -centre))
    model.name = spec.name
    model.gravity = pin.Motion(np.array([0.0, 0.0, -9.81]), np.zeros(3))

    coordinate_names = list(names)
    for jid in range(len(names) + 1, model.njoints):
        coordinate_names.append(spec.aliases.get(model.names[jid], model.names[jid]))
    for jid in range(1, model.njoints):
        if model.joints[jid].nq != 1 or model.joints[jid].nv != 1:
            raise ModelError(spec.name, model.names[jid],
                             f"joint type {model.joints[jid].shortname()} has more than one "
                             "coordinate; lock it or replace it")
    wheels = []
    for link, side, jname, width in ((spec.wheels[0], "left", jl, wl),
                                     (spec.wheels[1], "right", jr, wr)):
        jid = model.getJointId(jname)
        wheels.append(Wheel(link, side, jname, jid, model.joints[jid].idx_v, rl, width))
    body_jid = model.frames[model.getFrameId(body_link)].parentJoint
    return WheeledModel(spec.name, spec, model, geom, tuple(wheels), tuple(coordinate_names),
                        tuple(spec.inputs), {"R": rl, "L": half_track}, body_jid)


def coordinate_vector(wm: WheeledModel, values: Mapping[str, float] | Sequence[float]) -> np.ndarray:
    r"""A model vector from a mapping name → value (missing entries are 0) or a sequence."""
    if isinstance(values, Mapping):
        out = np.zeros(wm.nv)
        for key, val in values.items():
            out[wm.index(key)] = float(val)
        return out
    return np.asarray(values, dtype=float).reshape(wm.nv)
