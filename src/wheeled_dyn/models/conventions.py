r"""What each coordinate and input of a built model means, for its URDF: one table.

A planar (wheeled) model is built in a *heading frame* (:mod:`.builder`): at :math:`q = 0` the
world axes are the body's forward, left and up directions, so every claim below is read off
the built Pinocchio model at :math:`q = 0`, in words and as a vector in the body link's axes:

- ``x0, y0``: the point on the ground below the axle midpoint, along the world x and y;
- ``psi``: the heading, about the world up axis; positive turns forward toward left;
- ``phi``: the pitch, about the axle oriented from the left wheel to the right wheel (world
  :math:`-y` at :math:`q = 0`): positive moves the body's top *backward*. For a body whose
  link axes are REP 103's (x forward, y left, z up) this is :math:`-`\ the REP 103 pitch about
  +y;
- a wheel angle: about its joint's axis as the URDF writes it, relative to the body; rolling
  forward (body level) makes it increase when that axis points left, decrease when it points
  right;
- a wheel torque: about the same joint axis on the wheel, the reaction on the body; from rest,
  upright, a positive torque accelerates the robot forward when the axis points left.

Fixed and free bases list each joint's axis in the link that carries it, and each motor along
its joint. ``tests/test_conventions.py`` checks every claim against the terms ``matrices``
computes (the acceleration from rest, the centre of mass at a pitch, the wheel rates of a
rolling motion), for the WIP and for a REP 103 robot; ``docs/derivation-format.md`` shows
the WIP's table as :func:`convention_table` prints it (tested).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import Enum

import numpy as np

from ..errors import ModelError

#: Largest angle (rad) between two directions that count as the same, wherever axes are
#: compared (a wheel's cylinder and its joint axis, an axle and the body's y, left and right):
#: URDFs round π/2 as 1.5708 (3.7e-6 rad off) or 1.57 (8e-4 rad off).
ANGLE_TOL = 1e-2
#: Largest distance of a tyre's centre (its cylinder's) from the wheel's spin axis, relative
#: to the radius: a rolling wheel is round about its axle (URDFs round their numbers).
TYRE_OFF_AXIS_TOL = 1e-3
#: Largest distance (rad) of an inertia's orientation angle from a multiple of π/2 for it to
#: be read as that multiple (:func:`right_angles`): URDFs round π/2 as 1.5708 or 1.57 and π as
#: 3.1416 or 3.14 (1.6e-3 rad off).
RIGHT_ANGLE_TOL = 2e-3


def right_angles(rpy: np.ndarray) -> np.ndarray:
    r"""An ``<inertial>``'s ``rpy`` with each angle within :data:`RIGHT_ANGLE_TOL` of a
    multiple of :math:`\pi/2` made that multiple: the author turned the inertia by a right
    angle, and the rounding would leave it products of inertia of that angle's order (a
    wheel's tensor turned by 1.5708 about x: :math:`3.7\cdot10^{-6}(I_{yy} - I_{zz})`),
    which a derivation that takes its axes as principal does not have."""
    rpy = np.asarray(rpy, dtype=float)
    nearest = np.round(rpy / (np.pi / 2)) * (np.pi / 2)
    return np.where(np.abs(rpy - nearest) <= RIGHT_ANGLE_TOL, nearest, rpy)


def base_joints(wm) -> frozenset[int]:
    r"""The joints the model's base puts under the URDF's (a planar base's x0, y0, psi and
    phi, a free base's six; a fixed base has none) and the URDF's root joints on them: their
    turns are the model's own, exact."""
    from .wheeled_model import FREE_BASE
    spec, model = wm.spec, wm.model
    count = 3 + int(spec.pitch) if spec.base == "planar" else \
        len(FREE_BASE) if spec.base == "free" else 0
    base = set(range(1, 1 + count))
    return frozenset(base | {j for j in range(1, model.njoints) if model.parents[j] in base})


def right_angled_joints(model, skip: frozenset[int] = frozenset(),
                        kept: Mapping[str, tuple[float, ...]] | None = None) -> int:
    r"""Each joint's placement (but the ``skip`` ones') whose rotation is within
    :data:`RIGHT_ANGLE_TOL` per entry of a signed permutation made that permutation, in place
    (a URDF's ``rpy="0 1.5708 -1.5708"``: an arm's joint origin turned by right angles, which
    a derivation takes as exact); else, where its roll, pitch and yaw include angles within
    :data:`RIGHT_ANGLE_TOL` of a multiple of π/2, those made that multiple, the others kept
    (``rpy="1.5708 0 0.3"``: a quarter turn and 0.3 rad). The joints named in ``kept`` print an
    angle near a right angle that is no rounding of it (:mod:`.rounded_angles`): turned by the
    roll, pitch and yaw ``kept`` gives them (that angle as written, their roundings made right
    angles: ``rpy="1.5708 0 1.569"`` is π/2, 0, 1.569). Returns how many were changed."""
    import pinocchio as pin
    changed = 0
    for jid in range(1, model.njoints):
        if jid in skip:
            continue
        placement = model.jointPlacements[jid]
        if kept and model.names[jid] in kept:
            R = np.asarray(placement.rotation)
            meant = np.asarray(pin.rpy.rpyToMatrix(*kept[model.names[jid]]))
            if ROUNDING < float(np.abs(meant - R).max()) <= 2 * RIGHT_ANGLE_TOL:
                model.jointPlacements[jid] = pin.SE3(meant, placement.translation)
                changed += 1
            continue
        R = np.asarray(placement.rotation)
        P = np.rint(R)
        off = float(np.abs(R - P).max())
        if 0.0 < off <= RIGHT_ANGLE_TOL and np.array_equal(P.T @ P, np.eye(3)):
            model.jointPlacements[jid] = pin.SE3(P, placement.translation)
            changed += 1
        elif off > RIGHT_ANGLE_TOL:
            turned = _mixed_right_angles(R)
            if turned is not None:
                model.jointPlacements[jid] = pin.SE3(turned, placement.translation)
                changed += 1
    return changed


#: Least distance of an angle from a multiple of π/2 that is a rounding (closer, it is one).
ROUNDING = 1e-12


def _mixed_right_angles(R: np.ndarray) -> np.ndarray | None:
    r"""The rotation of roll, pitch and yaw of ``R`` with those within
    :data:`RIGHT_ANGLE_TOL` of a multiple of π/2 (and not within :data:`ROUNDING`) made that
    multiple, where there are some and the rotation moves by no more than the rounding; else
    None."""
    import pinocchio as pin
    rpy = np.asarray(pin.rpy.matrixToRpy(R), dtype=float)
    snapped = right_angles(rpy)
    if not np.any(np.abs(snapped - rpy) > ROUNDING):
        return None
    turned = np.asarray(pin.rpy.rpyToMatrix(*snapped))
    return turned if float(np.abs(turned - R).max()) <= 2 * RIGHT_ANGLE_TOL else None


#: The attributes of an ``<inertia>`` as (row, column) of its tensor.
TENSOR_ENTRIES = {"ixx": (0, 0), "ixy": (0, 1), "ixz": (0, 2), "iyy": (1, 1), "iyz": (1, 2),
                  "izz": (2, 2)}


def inertia_tensor(element) -> np.ndarray:
    r"""The symmetric tensor an ``<inertia>`` element writes (zeros where it or an entry is
    missing)."""
    I = np.zeros((3, 3))
    for key, (r, c) in TENSOR_ENTRIES.items():
        I[r, c] = I[c, r] = 0.0 if element is None else float(element.get(key, "0"))
    return I


def inertial_rotation(rpy: np.ndarray) -> np.ndarray:
    r"""The rotation of an ``<inertial>``'s axes, :math:`R(\text{rpy})` with the angles read
    by :func:`right_angles`; where all three are right angles, exactly the signed permutation
    it is (``rpyToMatrix(π/2, 0, 0)`` has entries of 6e-17, which leave a wheel's tensor
    products of inertia of 1e-20 and its closed forms terms like
    :math:`3.5\cdot10^{-16} I_m/R`)."""
    import pinocchio as pin
    R = pin.rpy.rpyToMatrix(right_angles(rpy))
    signs = np.rint(R)
    return signs if np.abs(R - signs).max() <= 1e-12 else R


class Positive(Enum):
    r"""What a positive value (or rate, or input) of a coordinate does."""

    ALONG_WORLD_X = "moves the robot along the world x axis"
    ALONG_WORLD_Y = "moves the robot along the world y axis"
    TURNS_LEFT = "turns the robot's forward direction toward its left (counterclockwise seen " \
                 "from above)"
    TOP_BACKWARD = "tilts the body's top backward"
    TOP_FORWARD = "tilts the body's top forward"
    INCREASES_ROLLING_FORWARD = "increases when the robot rolls forward (body level)"
    DECREASES_ROLLING_FORWARD = "decreases when the robot rolls forward (body level)"
    DRIVES_FORWARD = "from rest, upright, accelerates the robot forward"
    DRIVES_BACKWARD = "from rest, upright, accelerates the robot backward"
    ABOUT_AXIS = "turns the child link about the axis (right-hand rule)"
    ALONG_AXIS = "moves the child link along the axis"


@dataclass(frozen=True)
class Convention:
    r"""One row: a coordinate or an input, its axis (words, and the vector in ``frame``'s
    axes), what a positive value does, and a note (e.g. its relation to REP 103)."""

    name: str
    kind: str                                  # "coordinate" or "input"
    axis: str
    vector: tuple[float, float, float] | None
    frame: str
    positive: Positive
    note: str = ""


@dataclass(frozen=True)
class ConventionTable:
    r"""The table of a model (see the module docstring)."""

    model: str
    body: str
    rows: tuple[Convention, ...]

    def row(self, name: str) -> Convention:
        return next(r for r in self.rows if r.name == name)

    def lines(self) -> list[str]:
        r"""The table as printed by ``wheeled-dyn model`` and ``matrices``."""
        width = max(len(r.name) for r in self.rows) if self.rows else 4
        out = [f"conventions of model {self.model} (body {self.body or '-'}):"]
        for r in self.rows:
            text = f"  {r.kind:10} {r.name:{width}}  {r.axis}; positive {r.positive.value}"
            out.append(text + (f"; {r.note}" if r.note else ""))
        return out


def _words(vector: np.ndarray, frame: str) -> str:
    r"""``"+y of base_link"`` for a unit vector within :data:`ANGLE_TOL` of an axis; the
    components otherwise."""
    for i, axis in enumerate("xyz"):
        if abs(abs(vector[i]) - 1.0) <= ANGLE_TOL ** 2 / 2:
            return f"{'+' if vector[i] > 0 else '-'}{axis} of {frame}"
    return "(" + ", ".join(f"{x:.3g}" for x in vector) + f") in {frame}'s axes"


def _vec(v: np.ndarray) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def convention_table(wm) -> ConventionTable:
    r"""The table of a built model (:class:`~.wheeled_model.WheeledModel`)."""
    import pinocchio as pin
    model = wm.model
    data = model.createData()
    pin.forwardKinematics(model, data, pin.neutral(model))
    pin.updateFramePlacements(model, data)
    if wm.base != "planar":
        return _joint_table(wm)
    body = wm.spec.body
    R_body = data.oMf[model.getFrameId(body, pin.FrameType.BODY)].rotation
    in_body = lambda world: R_body.T @ np.asarray(world, dtype=float)   # noqa: E731
    forward, left, up = np.eye(3)
    rows = [Convention("x0", "coordinate", "along the world x axis (the robot's forward "
                       "direction at psi = 0)", None, "world", Positive.ALONG_WORLD_X),
            Convention("y0", "coordinate", "along the world y axis", None, "world",
                       Positive.ALONG_WORLD_Y),
            Convention("psi", "coordinate", "about the world up axis", None, "world",
                       Positive.TURNS_LEFT)]
    if "phi" in wm.coordinate_names:
        axis = in_body(-left)
        note = ""
        if abs(in_body(left) @ np.array([0.0, 1.0, 0.0]) - 1.0) <= ANGLE_TOL ** 2 / 2:
            note = f"phi = -(REP 103 pitch about +y of {body})"
        rows.append(Convention("phi", "coordinate", f"about the axle from the left wheel to "
                               f"the right wheel, {_words(axis, body)}", _vec(axis), body,
                               Positive.TOP_BACKWARD, note))
    for wheel in wm.wheels:
        jid = wheel.joint_id
        world = data.oMi[jid].rotation @ _axis(model.joints[jid])[0]
        axis = in_body(world)
        points_left = float(world @ left) > 0
        name = wm.coordinate_names[wheel.v_index]
        where = (f"about joint {wheel.joint_name}'s axis, {_words(axis, body)} "
                 f"(toward the {'left' if points_left else 'right'})")
        rows.append(Convention(name, "coordinate", f"{wheel.side} wheel {wheel.link}, "
                               f"relative to the body, {where}", _vec(axis), body,
                               Positive.INCREASES_ROLLING_FORWARD if points_left
                               else Positive.DECREASES_ROLLING_FORWARD))
    for wheel, name in zip(wm.wheels, wm.input_names):
        conv = next(r for r in rows if r.name == wm.coordinate_names[wheel.v_index])
        rows.append(Convention(name, "input", f"torque on {wheel.link} about the axis of "
                               f"{conv.name} ({_words(np.array(conv.vector), body)}), reaction "
                               "on the body", conv.vector, body,
                               Positive.DRIVES_FORWARD
                               if conv.positive is Positive.INCREASES_ROLLING_FORWARD
                               else Positive.DRIVES_BACKWARD))
    for name in wm.coordinate_names:
        if name not in {r.name for r in rows}:
            rows.append(_joint_row(wm, name))
    rows += _actuated_rows(wm, {r.name: r for r in rows}, len(wm.wheels))
    return ConventionTable(wm.name, body, tuple(rows))


def _actuated_rows(wm, coordinates: dict[str, Convention], first: int) -> list[Convention]:
    r"""The inputs of the ``actuated`` joints (B's columns from ``first``): each along its
    joint's coordinate, the reaction on the joint's parent."""
    joints = [coordinates[wm.coordinate_names[vi]] for vi in wm.actuated]
    return [Convention(wm.input_names[first + k], "input", f"force or torque {c.axis}, "
                       "reaction on the parent", c.vector, c.frame, c.positive)
            for k, c in enumerate(joints)]


def _axis(jmodel) -> tuple[np.ndarray | None, bool]:
    r"""A 1-DoF joint's axis in its joint frame and whether it is prismatic (None for other
    joints)."""
    short = jmodel.shortname()
    prismatic = short.startswith("JointModelP")
    if short[-2:] in ("RX", "RY", "RZ", "PX", "PY", "PZ"):
        return np.eye(3)["XYZ".index(short[-1])], prismatic
    if short.endswith("Unaligned"):
        inner = jmodel.extract() if hasattr(jmodel, "extract") else jmodel
        return np.asarray(inner.axis, dtype=float), prismatic
    return None, prismatic


def _joint_row(wm, name: str) -> Convention:
    r"""A URDF joint's coordinate: about (along) its axis, in its joint frame."""
    model = wm.model
    jid = 1 + wm.coordinate_names.index(name)
    axis, prismatic = _axis(model.joints[jid])
    joint = model.names[jid]
    if axis is None:
        return Convention(name, "coordinate", f"joint {joint} ({model.joints[jid].shortname()})",
                          None, joint, Positive.ABOUT_AXIS)
    words = (f"{'along' if prismatic else 'about'} joint {joint}'s axis "
             f"({', '.join(f'{x:g}' for x in axis)} in its joint frame)")
    return Convention(name, "coordinate", words, _vec(axis), joint,
                      Positive.ALONG_AXIS if prismatic else Positive.ABOUT_AXIS)


def _joint_table(wm) -> ConventionTable:
    rows = [_joint_row(wm, name) for name in wm.coordinate_names]
    rows += _actuated_rows(wm, {r.name: r for r in rows}, 0)
    return ConventionTable(wm.name, wm.spec.body, tuple(rows))


def check_sides(spec, body_rot: np.ndarray, forward: np.ndarray) -> None:
    r"""Check that a :class:`~.wheeled_model.ModelSpec` ``spec`` lists its wheels (left, right) as
    the geometry says (``body_rot`` the body's rotation and ``forward`` = up × (left → right),
    both in the URDF root's frame): a swapped list mirrors the model (forward reversed, every
    input's sign flipped). Forward is the spec's ``forward`` (in the body link's axes) when given, else the
    body's +x when it is horizontal (REP 103: x forward, y left, z up); a body whose x is not
    horizontal, without ``forward``, is not checked."""
    declared = spec.forward is not None
    ref = np.asarray(spec.forward if declared else (1.0, 0.0, 0.0), dtype=float)
    if not np.linalg.norm(ref) > 0:
        raise ModelError(spec.name, spec.body, f"forward direction {spec.forward} is zero")
    ref = body_rot @ (ref / np.linalg.norm(ref))
    along = float(ref @ forward)
    if declared and along < np.cos(ANGLE_TOL) and along > -np.cos(ANGLE_TOL):
        raise ModelError(spec.name, spec.body, f"the declared forward direction "
                         f"{spec.forward} is not perpendicular to the axle and the up direction")
    if along < -np.cos(ANGLE_TOL):
        axis = "the declared forward" if declared else f"+x of {spec.body} (REP 103)"
        raise ModelError(spec.name, f"{spec.wheels[0]}, {spec.wheels[1]}",
                         f"wheels listed against the geometry: with {spec.wheels[0]!r} as "
                         f"left and {spec.wheels[1]!r} as right, forward would be opposite "
                         f"to {axis}, a mirrored model with every input's sign flipped; list "
                         f"them as [{spec.wheels[1]!r}, {spec.wheels[0]!r}], or declare the "
                         "body's forward direction ([base] forward = [...], in its link axes)")
