r"""The planar base of a wheeled body: two drive wheels on one axle, checked and placed.

From the wheel centres :math:`c_l, c_r` (on the tyres' mid-planes: :func:`_tyre_plane`; URDF
root frame, neutral configuration) and the declared up direction :math:`u` (body link axes,
rotated to the root frame):

.. math::

    a = \frac{c_r - c_l}{\lVert c_r - c_l\rVert},\quad L = \tfrac12\lVert c_r - c_l\rVert,
    \quad u \leftarrow \frac{u - (u\cdot a)\,a}{\lVert\cdot\rVert},\quad f = u \times a,
    \quad \ell = u \times f,

and the URDF tree hangs from the mount frame :math:`(R_{HJ} = [f;\ \ell;\ u],\ (0, 0, R))` of
the heading joint (or of the pitch joint about :math:`a`), shifted by :math:`-\tfrac12(c_l +
c_r)`: the axle midpoint at height :math:`R` above the point :math:`(x_0, y_0)`. Each wheel's
spin axis must lie along the axle (:data:`~.conventions.ANGLE_TOL`), the axle be horizontal
(:data:`HORIZONTAL_TOL`), the radii agree (:data:`RADIUS_TOL`), and each wheel hang from the
body through fixed or locked joints only.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ..errors import ModelError
from .conventions import ANGLE_TOL, TYRE_OFF_AXIS_TOL, check_sides
from .geometry_constants import planar_lengths
from .model_joints import (WHEEL_INPUTS, actuated_inputs, bind_springs, finish_coordinates,
                           joint_axis, move_joint_to, unit_direction)
from .readings import TURN_NOTED, ground_reading, wheel_turn
from .round_wheels import asymmetry, round_reading
from .urdf_source import JointInfo, UrdfSource
from .wheeled_model import ModelSpec, Wheel, WheeledModel

#: Largest |cos| between the axle and the up direction for the axle to count as horizontal
#: (:data:`~.conventions.ANGLE_TOL`: URDFs round their angles); within it, the up direction is
#: made exactly perpendicular to the axle (the axle, from the wheel centres, is kept).
HORIZONTAL_TOL = ANGLE_TOL
#: Largest distance (m) of a wheel link's origin from its spin joint's axis.
AXIS_TOL = 1e-9
#: Largest relative difference between the two wheel radii.
RADIUS_TOL = 1e-9


def _spin_joint(source: UrdfSource, spec: ModelSpec, link: str) -> JointInfo:
    r"""The first moving joint above the wheel ``link`` (through fixed and locked joints);
    :class:`ModelError` naming the model file's ``[wheels] links`` entry when the link is the
    body, the root or fixed to either (nothing turns it: it cannot be a wheel)."""
    where = f" ({spec.source})" if spec.source is not None else ""
    path = []
    current = link
    while current != source.root_link() and current != spec.body:
        joint = source.joint_to(current)
        if joint.type != "fixed" and joint.name not in spec.lock:
            return joint
        path.append(joint.name)
        current = joint.parent
    what = "the body" if current == spec.body else "the root link"
    how = f"{link} is {what}" if current == link else \
        f"{link} is fixed to {what} {current} through joints {', '.join(path)}"
    raise ModelError(spec.name, link, f"[wheels] links entry {link!r} cannot be a wheel: "
                                      f"{how}, so no continuous or revolute joint turns it"
                                      f"{where}")


def _tyre_plane(source: UrdfSource, spec: ModelSpec, link: str, axis: np.ndarray,
                radius: float) -> np.ndarray:
    r"""Where the tyre's mid-plane crosses the spin axis, from the wheel link's origin, in the
    link's frame: the centre of its cylinder projected on the axis (``axis``, in the link's
    frame), where the cylinder is about the axis — a tyre set off along its axle (a collision
    cylinder at ``xyz="0 0.03 0"``) touches the ground in its own mid-plane, not the link's.
    Zero without a cylinder about the axis; :class:`ModelError` for a cylinder about the
    axis whose centre is off it (by more than :data:`TYRE_OFF_AXIS_TOL` × the radius)."""
    placement = source.cylinder_placement(link)
    if placement is None:
        return np.zeros(3)
    centre, cylinder_axis = placement
    if np.linalg.norm(np.cross(cylinder_axis, axis)) > np.sin(ANGLE_TOL):
        return np.zeros(3)           # a cylinder turned across the axle: no tyre's plane
    along = (centre @ axis) * axis
    off = float(np.linalg.norm(centre - along))
    if off > TYRE_OFF_AXIS_TOL * radius:
        raise ModelError(spec.name, link, f"the wheel's cylinder is centred {off:.3g} m off "
                                          "the spin axis: a rolling wheel is round about its "
                                          "axle (centre the cylinder on the axis)")
    return along


def _wheel_geometry(source: UrdfSource, spec: ModelSpec, model: pin.Model, data: pin.Data,
                    link: str) -> tuple[np.ndarray, np.ndarray, float, float, str, np.ndarray]:
    """Centre (on the tyre's mid-plane: :func:`_tyre_plane`), spin axis (in the URDF root
    frame), radius, width and joint name of a wheel (the joint that spins it: the first
    moving joint above ``link``), and the tyre's plane from the link's origin (link frame)."""
    joint = _spin_joint(source, spec, link)
    if joint.type not in ("continuous", "revolute"):
        raise ModelError(spec.name, link, f"wheel joint {joint.name!r} is {joint.type!r}, "
                                          "expected continuous or revolute")
    jid = model.getJointId(joint.name)
    centre = data.oMf[model.getFrameId(link, pin.FrameType.BODY)].translation.copy()
    axis = data.oMi[jid].rotation @ joint_axis(model.joints[jid])
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
    frame = data.oMf[model.getFrameId(link, pin.FrameType.BODY)]
    plane = _tyre_plane(source, spec, link, frame.rotation.T @ axis, radius)
    return frame.act(plane), axis, radius, width, joint.name, plane



def _along_axle(model: pin.Model, jid: int) -> float:
    r"""Turn wheel joint ``jid`` (and what it carries) about its origin so that its spin axis
    lies exactly along the axle, the heading frame's :math:`y` at the neutral configuration:
    within :data:`~.conventions.ANGLE_TOL` of it (checked before), as a URDF's rounded
    :math:`\pi/2` leaves it (``rpy="-1.57 0 0"``: 8e-4 rad), the wheel of a planar model is
    meant on the axle. With :math:`a` the axis in the world and :math:`t = \pm y`, the
    rotation :math:`\delta` taking :math:`a` to :math:`t` is applied in the parent's frame:
    :math:`{}^{p}R_j \leftarrow {}^{o}R_p^T\,\delta\,{}^{o}R_p\,{}^{p}R_j`. Returns the
    angle of :math:`\delta`."""
    data = model.createData()
    pin.forwardKinematics(model, data, pin.neutral(model))
    axis = data.oMi[jid].rotation @ joint_axis(model.joints[jid])
    target = np.array([0.0, np.sign(axis[1]) or 1.0, 0.0])
    turn = np.cross(axis, target)
    sine, cosine = float(np.linalg.norm(turn)), float(axis @ target)
    if sine == 0.0:
        return 0.0
    delta = pin.exp3(turn / sine * np.arctan2(sine, cosine))
    parent = data.oMi[model.parents[jid]].rotation
    placement = model.jointPlacements[jid]
    model.jointPlacements[jid] = pin.SE3(parent.T @ delta @ parent @ placement.rotation,
                                         placement.translation)
    return float(np.arctan2(sine, cosine))


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



def _off_axle(axis: np.ndarray, other: np.ndarray, axle: np.ndarray, track: float) -> str:
    r"""Why a wheel's spin ``axis`` is not along the unit ``axle`` (the line between the
    wheel centres, ``track`` apart): with the other wheel's axis parallel to it, the centres
    are offset across it (one wheel ahead of or above the other), else the wheel is turned."""
    off = float(np.arcsin(min(1.0, float(np.linalg.norm(np.cross(axis, axle))))))
    if np.linalg.norm(np.cross(axis, other)) <= np.sin(ANGLE_TOL):
        across = track * float(np.linalg.norm(np.cross(axis, axle)))
        return (f"the wheels are not on one axle: their spin axes are parallel, but the line "
                f"between their centres is {off:.3g} rad off them (the centres {across:.3g} m "
                "apart across the spin axis: one wheel ahead of or above the other); a planar "
                "model needs coaxial drive wheels")
    return (f"wheel spin axis is not along the axle (the line between the wheel centres): "
            f"{off:.3g} rad off, more than {ANGLE_TOL} rad")


def build_planar(spec: ModelSpec, source: UrdfSource, urdf_model: pin.Model,
                 urdf_geom: pin.GeometryModel) -> WheeledModel:
    r"""The planar (wheeled) model of ``spec`` on the URDF's model and visual geometry
    (module docstring); :class:`ModelError` for wheels that do not fit a planar base."""
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

    (cl, al, rl, wl, jl, pl), (cr, ar, rr, wr, jr, pr) = (
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
    up = body_rot @ unit_direction(spec, "up", spec.up, body_link)
    for link, axis in ((spec.wheels[0], al), (spec.wheels[1], ar)):
        if np.linalg.norm(np.cross(axis, axle)) > np.sin(ANGLE_TOL):
            raise ModelError(spec.name, link, _off_axle(axis, ar if axis is al else al,
                                                        axle, 2 * half_track))
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
    coordinate_names = finish_coordinates(spec, model, names)
    wheels = []
    for link, side, jname, width, plane in ((spec.wheels[0], "left", jl, wl, pl),
                                            (spec.wheels[1], "right", jr, wr, pr)):
        jid = model.getJointId(jname)
        body = model.frames[model.getFrameId(link, pin.FrameType.BODY)]
        tyre = pin.Frame(link, body.parentJoint, body.parentFrame,
                         body.placement * pin.SE3(np.eye(3), plane), pin.FrameType.OP_FRAME)
        move_joint_to(model, geom, jid, tyre)     # the joint on the tyre's mid-plane
        wheels.append(Wheel(link, side, jname, jid, model.joints[jid].idx_v, rl, width))
    turns = [(wheel.joint_name, _along_axle(model, wheel.joint_id)) for wheel in wheels]
    body_jid = model.frames[model.getFrameId(body_link)].parentJoint
    actuated, inputs = actuated_inputs(spec, model, coordinate_names, WHEEL_INPUTS)
    lengths = planar_lengths(spec, source, model, rl, half_track)
    return WheeledModel(spec.name, spec, model, geom, tuple(wheels), coordinate_names, inputs,
                        lengths.constant_values(lengths.values()), body_jid, actuated,
                        springs=bind_springs(spec, model, coordinate_names), lengths=lengths,
                        readings=ground_reading(source.text, source.root_link(),
                                                rl - float(centre @ up), rl)
                        + tuple(wheel_turn(j, a) for j, a in turns if a > TURN_NOTED)
                        + tuple(f"wheel {link}: its tyre's mid-plane (its cylinder's centre) "
                                f"is {np.linalg.norm(plane):.3g} m from the link's origin along "
                                "the axle: it touches the ground there, and the track is "
                                "measured between the tyres"
                                for link, plane in zip(spec.wheels, (pl, pr))
                                if np.linalg.norm(plane) > AXIS_TOL)
                        + round_reading([w.link for w in wheels], [
                            asymmetry(model.inertias[w.joint_id],
                                      joint_axis(model.joints[w.joint_id]), w.radius)
                            for w in wheels]))

