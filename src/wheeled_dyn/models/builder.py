r"""A model from any URDF on one of three bases: ``planar`` (wheeled), ``fixed`` or ``free``.

Every joint of a built model has one degree of freedom (so that q and v have the same size and
Christoffel symbols exist). ``ModelSpec.base`` chooses what carries the URDF's root link:

- ``"planar"`` (the default; a wheeled body): given the link that carries the axle (the *body*)
  and the two drive wheels,

  .. math::

      q = (x_0,\ y_0,\ \psi,\ [\varphi],\ \text{the URDF's own joints}\ \dots)

  * :math:`x_0, y_0` (prismatic along the world x and y): the point on the ground plane
    :math:`z = 0` below the axle midpoint;
  * :math:`\psi` (revolute about the world z, up): the heading, the body's forward direction;
  * :math:`\varphi` (optional, revolute about the axle, oriented from the left wheel to the right
    wheel): the pitch of the body; the axle midpoint is at height :math:`R` (wheel radius);
  * then the URDF's tree as written, hanging from the body, with ``continuous`` joints as
    unlimited revolute joints (each wheel angle is one coordinate, measured relative to the body).

  The body's *up* direction (in its link frame, at zero pitch) is declared; *forward* is
  up × axle. The wheel radius comes from the wheel link's cylinder geometry unless given.
- ``"fixed"``: the URDF as written, its root link fixed to the world (world z up, gravity −z);
  no wheels. ``q`` is the URDF's joints.
- ``"free"``: the root link on six 1-DoF joints, ``q = (x0, y0, z0, yaw, pitch, roll, ...)``:
  translations along the world axes, then :math:`R = R_z(\text{yaw})\,R_y(\text{pitch})\,
  R_x(\text{roll})` (ZYX angles). The body's angular velocity in its own frame is

  .. math::

      \omega_B = \begin{bmatrix}\dot\phi - \sin\theta\,\dot\psi\\
      \cos\phi\,\dot\theta + \sin\phi\cos\theta\,\dot\psi\\
      -\sin\phi\,\dot\theta + \cos\phi\cos\theta\,\dot\psi\end{bmatrix}
      \quad(\psi, \theta, \phi = \text{yaw, pitch, roll}),

  singular at :math:`\text{pitch} = \pm\pi/2` (yaw and roll turn about the same axis there:
  keep motions away from it, or use body angular velocities as quasi-velocities, which are
  regular everywhere the angles are).

Joints listed in ``lock`` are frozen, at the values of ``locked`` (0 for a joint not given
there); their bodies' inertia is merged into their parents. A wheel link may hang from its spin
joint through fixed joints (a tyre on a hub on a motor rotor): its link origin is the wheel
centre, which must lie on the spin axis; the joint's origin is moved along its axis to that
centre (an exact change of frame: a rotation about an axis commutes with a translation along
it), so the rolling constraint acts at the tyre. Motors: the wheel joints of a planar model; on the other bases, the joints listed in
``actuated`` (a torque or force along each joint axis, reaction on the parent). ``geometry``
names constants that coordinate sets and derivation files may use (a rolling radius, a gear
ratio); a ball rolling without slip on the ground, on a fixed sphere or inside a paraboloid
bowl, or a spheroid on the ground, is declared by ``contact``
(:class:`~wheeled_dyn.models.contact.SphereContact`); a linear spring along or about a joint by
``springs`` (:mod:`.springs`: :math:`Q` and :math:`U` then include it).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..errors import ModelError, UnknownNameError
from . import geometry as geo
from .contact import BallContact, SphereContact
from .conventions import ANGLE_TOL, check_sides
from .geometry_constants import planar_lengths, unwheeled_lengths
from .rolling_wheel import BoundWheelContact, WheelContact
from .springs import SPRING_JOINTS, BoundSpring, JointSpring, spring_energy, spring_force
from .urdf_checks import check_mimic
from .urdf_source import UrdfSource, read_urdf
from .visual_geometry import visual_geometry

#: Largest |cos| between the axle and the up direction for the axle to count as horizontal
#: (:data:`~.conventions.ANGLE_TOL`: URDFs round their angles); within it, the up direction is
#: made exactly perpendicular to the axle (the axle, from the wheel centres, is kept).
HORIZONTAL_TOL = ANGLE_TOL
#: Largest distance (m) of a wheel link's origin from its spin joint's axis.
AXIS_TOL = 1e-9
#: Largest relative difference between the two wheel radii.
RADIUS_TOL = 1e-9
#: Shortest direction vector (``up``, a wheel axis) taken as a direction.
DIRECTION_TOL = 1e-9
#: Standard gravity of built models (m/s²); parameter sets may change it.
GRAVITY = 9.81

_AXES = {"X": np.array([1.0, 0, 0]), "Y": np.array([0, 1.0, 0]), "Z": np.array([0, 0, 1.0])}


BASES = ("planar", "fixed", "free")
#: Coordinate names of the six joints of a free base (ZYX angles: yaw, pitch, roll).
FREE_BASE = ("x0", "y0", "z0", "yaw", "pitch", "roll")


@dataclass(frozen=True)
class ModelSpec:
    r"""What to build: a URDF, its base, body and wheels, conventions. See the module docstring.

    ``body`` and ``wheels`` (left, right) are required for ``base = "planar"``; the other bases
    take no wheels. ``inputs`` names the motor inputs (default ``tau_l, tau_r`` for the wheels,
    ``tau_<coordinate>`` for each ``actuated`` joint)."""

    name: str
    urdf: Path
    body: str = ""
    wheels: tuple[str, ...] = ()                 # (left wheel link, right wheel link)
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)
    pitch: bool = True
    lock: tuple[str, ...] = ()
    aliases: Mapping[str, str] = field(default_factory=dict)   # joint name -> coordinate name
    inputs: tuple[str, ...] | None = None
    radius: float | None = None
    package_dirs: tuple[str, ...] = ()
    description: str = ""
    base: str = "planar"
    actuated: tuple[str, ...] = ()               # joint names with a motor (fixed/free bases)
    geometry: Mapping[str, object] = field(default_factory=dict)   # [geometry]: see .geometry
    contact: SphereContact | None = None
    rolling_wheels: tuple[WheelContact, ...] = ()   # tilting wheels on any link (fixed/free)
    locked: Mapping[str, float] = field(default_factory=dict)  # values of ``lock`` joints
    accept_inertia: tuple[str, ...] = ()         # links whose URDF inertia is not checked
    coordinate_sets: Mapping[str, Mapping] = field(default_factory=dict)  # declared sets
    default_coordinates: str | None = None       # the default coordinate set's name
    source: Path | None = None                   # the model file, if the spec came from one
    springs: tuple[JointSpring, ...] = ()        # linear springs along or about joints
    forward: tuple[float, float, float] | None = None   # body's forward, link axes (planar)
    fixed_geometry: tuple[str, ...] = ()         # [draw] fixed: names no parameter set draws


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
    r"""A Pinocchio model of a wheeled, fixed-base or free body with its conventions.

    ``coordinate_names[i]`` names ``q[i]`` (and ``v[i]``); ``wheels`` are the drive wheels
    (none for fixed and free bases); ``input_names`` the motor inputs: wheel torques (about each
    wheel joint axis, reaction on the wheel's parent), or one per joint of ``actuated``
    (velocity indices); ``geometry`` holds the named constants (``R`` wheel radius and ``L``
    half the distance between the wheel centres for a planar model, the spec's ``geometry``
    otherwise); ``contact`` the rolling ball, if any; ``lengths`` the named lengths and
    constants (:mod:`.geometry`: ``origin_x(joint)``, ``radius(link)`` ...).
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
    actuated: tuple[int, ...] = ()
    contact: BallContact | None = None
    rolling_wheels: tuple[BoundWheelContact, ...] = ()
    springs: tuple[BoundSpring, ...] = ()
    lengths: geo.GeometryTable | None = None

    @property
    def dimensions(self) -> dict[str, float]:
        r"""The named lengths (:mod:`.geometry`): ``{"origin_x(elbow)": 1.0, ...}``."""
        return {} if self.lengths is None else {k: d.value for k, d in
                                                self.lengths.dimensions.items()}

    def named_lengths(self) -> dict[str, float]:
        r"""The names a coordinate expression may use: the constants (``R``, ``L``, ...) and
        the lengths as identifiers (``radius_coin`` for ``radius(coin)``)."""
        out = {geo.identifier(k): v for k, v in self.dimensions.items()}
        out.update(self.geometry)
        return out

    @property
    def nv(self) -> int:
        return self.model.nv

    @property
    def base(self) -> str:
        return self.spec.base

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
        r"""B (nv × number of motors): motor k acts on its joint, :math:`B_{ik}=\delta_{i,j_k}`
        (wheel joints, or the ``actuated`` joints; nv × 0 for a body without motors)."""
        columns = [w.v_index for w in self.wheels] if self.wheels else list(self.actuated)
        B = np.zeros((self.nv, len(columns)))
        for k, i in enumerate(columns):
            B[i, k] = 1.0
        return B

    def with_model(self, model: pin.Model, springs: tuple[BoundSpring, ...] | None = None
                   ) -> "WheeledModel":
        r"""The same conventions on another Pinocchio model of identical structure (e.g. other
        inertial parameters), and other spring stiffnesses if ``springs`` is given."""
        return replace(self, model=model, springs=self.springs if springs is None else springs)

    def potential_force(self, data: pin.Data, q: np.ndarray) -> np.ndarray:
        r""":math:`Q(q) = \partial U/\partial q`: Pinocchio's generalised gravity plus the
        joint springs' :math:`k (q_j - q_{j,0})` (:mod:`.springs`)."""
        Q = pin.computeGeneralizedGravity(self.model, data, q).copy()
        return Q + spring_force(self.springs, q, self.nv) if self.springs else Q

    def potential_energy(self, data: pin.Data, q: np.ndarray) -> float:
        r""":math:`U(q)`: gravity (Pinocchio) plus the springs' :math:`\tfrac12 k (q_j -
        q_{j,0})^2`."""
        U = float(pin.computePotentialEnergy(self.model, data, q))
        return U + spring_energy(self.springs, q) if self.springs else U

    def nonlinear_effects(self, data: pin.Data, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        r""":math:`C(q, v) v + Q(q)` by ``pin.nonLinearEffects``, springs included."""
        n = pin.nonLinearEffects(self.model, data, q, v).copy()
        return n + spring_force(self.springs, q, self.nv) if self.springs else n


def _joint_axis(jmodel: pin.JointModel) -> np.ndarray:
    short = jmodel.shortname()
    if short in ("JointModelRX", "JointModelRY", "JointModelRZ"):
        return _AXES[short[-1]]
    if short == "JointModelRevoluteUnaligned":
        inner = jmodel.extract() if hasattr(jmodel, "extract") else jmodel
        return np.asarray(inner.axis, dtype=float)
    raise ValueError(short)


def _urdf_models(source: UrdfSource, spec: ModelSpec) -> tuple[pin.Model, pin.GeometryModel]:
    check_mimic(source.path, source.text, ET.fromstring(source.text), spec.locked, spec.lock)
    text = source.pinocchio_text()
    model = pin.buildModelFromXML(text)
    geom = visual_geometry(source, spec.name, spec.package_dirs, model, text)
    for name in spec.locked:
        if name not in spec.lock:
            raise ModelError(spec.name, name, "a value is given for a joint that is not locked")
    if spec.lock:
        ids = []
        q_ref = pin.neutral(model)
        for name in spec.lock:
            if not model.existJointName(name):
                raise UnknownNameError("joint", name, list(model.names)[1:], where=str(source.path))
            jid = model.getJointId(name)
            ids.append(jid)
            value = float(spec.locked.get(name, 0.0))
            if model.joints[jid].nq != 1 or not np.isfinite(value):
                raise ModelError(spec.name, name, f"locked value {value!r}: expected a finite "
                                                  "number for a joint with one coordinate")
            q_ref[model.joints[jid].idx_q] = value
        model, geom = pin.buildReducedModel(model, geom, ids, q_ref)
    return model, geom


def _wheel_geometry(source: UrdfSource, spec: ModelSpec, model: pin.Model, data: pin.Data,
                    link: str) -> tuple[np.ndarray, np.ndarray, float, float, str]:
    """Centre, spin axis (in the URDF root frame), radius, width and joint name of a wheel
    (the joint that spins it: the first moving joint above ``link``)."""
    joint = source.joint_to(link)
    while joint.type == "fixed" or joint.name in spec.lock:
        joint = source.joint_to(joint.parent)
    if joint.type not in ("continuous", "revolute"):
        raise ModelError(spec.name, link, f"wheel joint {joint.name!r} is {joint.type!r}, "
                                          "expected continuous or revolute")
    jid = model.getJointId(joint.name)
    centre = data.oMf[model.getFrameId(link, pin.FrameType.BODY)].translation.copy()
    axis = data.oMi[jid].rotation @ _joint_axis(model.joints[jid])
    offset = centre - data.oMi[jid].translation
    if np.linalg.norm(offset - (offset @ axis) * axis) > AXIS_TOL:
        raise ModelError(spec.name, link, f"the wheel link's origin is not on the spin axis of "
                                          f"joint {joint.name!r}")
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


def _check_on_body(spec: ModelSpec, source: UrdfSource, body: str, wheel: str,
                   wheel_joint: str) -> None:
    r"""The wheel's spin joint hangs from ``body`` through fixed or locked joints only (the
    rolling constraint of a planar base needs the axle on one rigid body)."""
    joint = source.joint_to(wheel)
    while joint.name != wheel_joint:
        joint = source.joint_to(joint.parent)
    link = joint.parent
    while link != body:
        if link == source.root_link():
            raise ModelError(spec.name, wheel, f"the wheel does not hang from the body {body!r}")
        joint = source.joint_to(link)
        if joint.type != "fixed" and joint.name not in spec.lock:
            raise ModelError(spec.name, joint.name, f"this joint moves wheel {wheel!r} relative "
                                                    f"to the body {body!r}: lock it (a planar "
                                                    "base needs the axle on one rigid body), or "
                                                    "use base 'free' with rolling wheels")
        link = joint.parent


def _build_planar(spec: ModelSpec, source: UrdfSource, urdf_model: pin.Model,
                   urdf_geom: pin.GeometryModel) -> WheeledModel:
    if not spec.body:
        raise ModelError(spec.name, None, "a planar (wheeled) model needs its body link")
    if len(spec.wheels) != 2:
        raise ModelError(spec.name, None, f"a planar model needs two drive wheels (left, right), "
                                          f"got {len(spec.wheels)}")
    body_link = source.link(spec.body)
    for w in spec.wheels:
        source.link(w)
    data = urdf_model.createData()
    pin.forwardKinematics(urdf_model, data, pin.neutral(urdf_model))
    pin.updateFramePlacements(urdf_model, data)

    (cl, al, rl, wl, jl), (cr, ar, rr, wr, jr) = (
        _wheel_geometry(source, spec, urdf_model, data, link) for link in spec.wheels)
    for link, jname in ((spec.wheels[0], jl), (spec.wheels[1], jr)):
        _check_on_body(spec, source, body_link, link, jname)
    if abs(rl - rr) > RADIUS_TOL * max(rl, rr):
        raise ModelError(spec.name, None, f"wheel radii differ: {rl} and {rr}")
    axle = cr - cl
    half_track = 0.5 * float(np.linalg.norm(axle))
    if half_track <= 0:
        raise ModelError(spec.name, None, "the two wheel centres coincide")
    axle /= 2 * half_track
    body_rot = data.oMf[urdf_model.getFrameId(body_link)].rotation
    up = body_rot @ _direction(spec, "up", spec.up, body_link)
    for link, axis in ((spec.wheels[0], al), (spec.wheels[1], ar)):
        if np.linalg.norm(np.cross(axis, axle)) > np.sin(ANGLE_TOL):
            raise ModelError(spec.name, link, "wheel spin axis is not along the axle (more "
                                              f"than {ANGLE_TOL} rad off)")
    if abs(float(up @ axle)) > np.sin(HORIZONTAL_TOL):
        raise ModelError(spec.name, body_link, "the axle is not horizontal for the declared "
                                               f"up direction {spec.up} (more than "
                                               f"{HORIZONTAL_TOL} rad off)")
    up = up - (up @ axle) * axle
    up /= np.linalg.norm(up)
    forward = np.cross(up, axle)
    left = np.cross(up, forward)
    check_sides(spec, body_rot, forward)
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
    coordinate_names = _finish(spec, model, names)
    wheels = []
    for link, side, jname, width in ((spec.wheels[0], "left", jl, wl),
                                     (spec.wheels[1], "right", jr, wr)):
        jid = model.getJointId(jname)
        _move_joint_to(model, geom, jid, model.frames[model.getFrameId(link, pin.FrameType.BODY)])
        wheels.append(Wheel(link, side, jname, jid, model.joints[jid].idx_v, rl, width))
    body_jid = model.frames[model.getFrameId(body_link)].parentJoint
    inputs = tuple(spec.inputs) if spec.inputs is not None else ("tau_l", "tau_r")
    if len(inputs) != 2:
        raise ModelError(spec.name, None, f"{len(inputs)} input names for two wheel motors")
    lengths = planar_lengths(spec, source, model, rl, half_track)
    return WheeledModel(spec.name, spec, model, geom, tuple(wheels), coordinate_names, inputs,
                        lengths.constant_values(lengths.values()), body_jid,
                        springs=_bind_springs(spec, model, coordinate_names), lengths=lengths)


def _direction(spec: ModelSpec, what: str, value: Sequence[float], item: str) -> np.ndarray:
    r"""``value`` as a unit vector; :class:`ModelError` for three numbers that are not finite
    or of length below :data:`DIRECTION_TOL`."""
    v = np.asarray(value, dtype=float).reshape(-1)
    norm = float(np.linalg.norm(v)) if v.shape == (3,) and np.all(np.isfinite(v)) else 0.0
    if not norm > DIRECTION_TOL:
        raise ModelError(spec.name, item, f"{what} direction {tuple(value)}: expected three "
                                          "finite numbers, not all zero")
    return v / norm


def _move_joint_to(model: pin.Model, geom: pin.GeometryModel, jid: int, frame: pin.Frame) -> None:
    r"""Move joint ``jid``'s origin along its axis to the origin of ``frame`` (on the axis):
    with :math:`d` the offset along the axis, :math:`{}^{j}M_{j'} = (I, d\,a)`, and everything
    the joint carries re-expressed in the new joint frame by :math:`(I, -d\,a)`."""
    if frame.parentJoint != jid:
        return
    axis = _joint_axis(model.joints[jid])
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


def _finish(spec: ModelSpec, model: pin.Model, base_names: Sequence[str]) -> tuple[str, ...]:
    r"""Name the model, set gravity, check every joint has one coordinate; the coordinate
    names (the base's, then the URDF joints' under their aliases)."""
    model.name = spec.name
    model.gravity = pin.Motion(np.array([0.0, 0.0, -GRAVITY]), np.zeros(3))
    names = list(base_names)
    for jid in range(len(base_names) + 1, model.njoints):
        names.append(spec.aliases.get(model.names[jid], model.names[jid]))
    for jid in range(1, model.njoints):
        if model.joints[jid].nq != 1 or model.joints[jid].nv != 1:
            raise ModelError(spec.name, model.names[jid],
                             f"joint type {model.joints[jid].shortname()} has more than one "
                             "coordinate; lock it or replace it")
    if len(set(names)) != len(names):
        raise ModelError(spec.name, None, f"coordinate names repeat: {names}")
    return tuple(names)


def _build_unwheeled(spec: ModelSpec, source: UrdfSource, urdf_model: pin.Model,
                     urdf_geom: pin.GeometryModel) -> WheeledModel:
    r"""A fixed-base or free model (no wheels)."""
    if spec.wheels:
        raise ModelError(spec.name, None, f"wheels need base 'planar'; this base is {spec.base!r}")
    if spec.base == "fixed":
        model, geom, names = pin.Model(urdf_model), urdf_geom, ()
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
    coordinate_names = _finish(spec, model, names)
    actuated = []
    for joint in spec.actuated:
        if not model.existJointName(joint):
            raise UnknownNameError("joint", joint, list(model.names)[1:], where=f"model {spec.name}")
        actuated.append(model.joints[model.getJointId(joint)].idx_v)
    inputs = (tuple(spec.inputs) if spec.inputs is not None
              else tuple("tau_" + coordinate_names[i] for i in actuated))
    if len(inputs) != len(actuated):
        raise ModelError(spec.name, None, f"{len(inputs)} input names for {len(actuated)} "
                                          "actuated joints")
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
                        _bind_springs(spec, model, coordinate_names), lengths)


def _bind_springs(spec: ModelSpec, model: pin.Model, coordinate_names: Sequence[str]
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


def build_wheeled_model(spec: ModelSpec) -> WheeledModel:
    r"""Build the model described by ``spec`` (see the module docstring)."""
    if spec.base not in BASES:
        raise ModelError(spec.name, None, f"base {spec.base!r}; expected one of {BASES}")
    if spec.rolling_wheels and spec.base == "planar":
        raise ModelError(spec.name, spec.rolling_wheels[0].link, "tilting wheels need base "
                                                                  "'free' or 'fixed', not 'planar'")
    if spec.contact is not None and spec.base == "planar":
        raise ModelError(spec.name, spec.contact.link, "a rolling ball needs base 'free' or "
                                                       "'fixed', not 'planar'")
    source = read_urdf(spec.urdf, tuple(spec.lock), tuple(spec.accept_inertia))
    urdf_model, urdf_geom = _urdf_models(source, spec)
    if spec.base == "planar":
        return _build_planar(spec, source, urdf_model, urdf_geom)
    return _build_unwheeled(spec, source, urdf_model, urdf_geom)




def coordinate_vector(wm: WheeledModel, values: Mapping[str, float] | Sequence[float]) -> np.ndarray:
    r"""A model vector from a mapping name → value (missing entries are 0) or a sequence."""
    if isinstance(values, Mapping):
        out = np.zeros(wm.nv)
        for key, val in values.items():
            out[wm.index(key)] = float(val)
        return out
    return np.asarray(values, dtype=float).reshape(wm.nv)
