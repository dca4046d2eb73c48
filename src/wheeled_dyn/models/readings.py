r"""What a model reads otherwise than its URDF writes it, said in words
(``WheeledModel.readings``): every comparison made with the model lists these (a result's
``model_readings``, under the assumptions in the reports), so a difference they make is never
silent.

- An ``<inertial>`` orientation within :data:`~.conventions.RIGHT_ANGLE_TOL` of right angles
  is read as them (:func:`~.conventions.right_angles`): ``rpy="1.5708 0 0"`` as
  :math:`(\pi/2, 0, 0)`.
- A planar model's wheel whose spin axis is off the axle by a rounding (``rpy="-1.57 0 0"``:
  8e-4 rad) is turned onto it (:func:`wheel_turn`, from the planar builder).
- A joint's ``<dynamics damping friction>`` is not part of the equations: the truth is
  :math:`A\ddot q + C\dot q + Q = \Gamma`, with no joint damping or friction; a derivation
  that writes :math:`b\dot\theta` has a term the truth does not.
- A root link that is a frame only (``base_footprint``) off the ground the wheels' radius
  puts under a planar model's axle (:func:`ground_reading`).
- A joint's ``<origin rpy>`` right angles to a rounding (``1.5708``) are taken as right
  angles in the comparisons' parameter sets (:func:`joint_origin_readings`).
- A joint's ``<axis>`` not of unit length (``"0 0 2"``) is read as its direction
  (:func:`axis_readings`).
- A ``<transmission>`` is not applied: the model's inputs are its joints' torques (a
  mechanical reduction between motor and joint is the document's to state).
- A planar model's drive wheels axisymmetric about their axles to a CAD export's rounding
  are drawn axisymmetric in the comparisons' random parameter sets where a derivation writes
  nothing of their asymmetry (:mod:`.round_wheels`).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np

from .conventions import RIGHT_ANGLE_TOL, right_angles
from .rounded_angles import is_rounding

#: Smallest turn of a wheel's axis (rad) that a model's readings mention: below it the turn
#: changes no number by more than round-off of the comparisons' tolerances (a URDF's
#: π/2 written to 13 digits leaves its wheels 5e-12 rad off).
TURN_NOTED = 1e-9


def _angles(values: np.ndarray) -> str:
    r"""Angles as multiples of :math:`\pi/2` where they are (``π/2, 0, -π``), else numbers."""
    out = []
    for v in values:
        k = int(round(float(v) / (np.pi / 2)))
        if abs(float(v) - k * np.pi / 2) > 1e-15:
            out.append(f"{float(v):g}")
        else:
            out.append({0: "0", 1: "π/2", -1: "-π/2", 2: "π", -2: "-π"}.get(k, f"{k}π/2"))
    return ", ".join(out)


def inertial_readings(root: ET.Element) -> list[str]:
    r"""The links whose ``<inertial>`` orientation is read as right angles it is near."""
    out = []
    for link in root.iterfind("link"):
        origin = link.find("inertial/origin")
        if origin is None or origin.get("rpy") is None:
            continue
        written = origin.get("rpy", "")
        rpy = np.array([float(x) for x in written.split()])
        read = right_angles(rpy)
        if np.any(read != rpy):
            out.append(f"link {link.get('name')}: its inertial origin rpy=\"{written}\" is read as "
                       f"({_angles(read)}), the right angles within {RIGHT_ANGLE_TOL:g} rad of "
                       "it (as written, its inertia would have products of inertia of the "
                       "rounding's order)")
    return out


def joint_origin_readings(root: ET.Element) -> list[str]:
    r"""The joints whose ``<origin rpy>`` has an angle within :data:`RIGHT_ANGLE_TOL` of a
    multiple of :math:`\pi/2` and not on it (beyond :data:`TURN_NOTED`): one line. The
    comparisons' parameter sets take a joint's turn that is right angles to that rounding as
    right angles (:func:`~.conventions.right_angled_joints`); ``matrices`` keeps it as
    written. A joint whose angle near a right angle is no rounding of it (``1.569``:
    :mod:`.rounded_angles`) keeps that angle as written (its roundings made right angles),
    and that is said."""
    near: list[str] = []
    kept: list[str] = []
    for joint in root.iterfind("joint"):
        origin = joint.find("origin")
        if origin is None or origin.get("rpy") is None:
            continue
        texts = origin.get("rpy", "").split()
        rpy = np.array([float(x) for x in texts])
        off = np.abs(rpy - right_angles(rpy))
        close = (off > TURN_NOTED) & (off <= RIGHT_ANGLE_TOL)
        if np.any(close):
            rounded = all(is_rounding(t) for t, c in zip(texts, close) if c)
            (near if rounded else kept).append(joint.get("name", ""))
    out = [f"joint{'s' if len(near) > 1 else ''} {_listed(near)}: origin rpy within "
           f"{RIGHT_ANGLE_TOL:g} rad of right angles in one or more of its angles (1.5708 "
           "for π/2): the comparisons' parameter sets turn a joint by the right angles its "
           "rounding stands for, its other angles as written, as a derivation does (the "
           "model's own matrices keep the numbers as written)"] if near else []
    return out + ([f"joint{'s' if len(kept) > 1 else ''} {_listed(kept)}: an origin rpy angle "
                   "near a right angle that is no rounding of it (1.569 or 1.5700, which are "
                   "not π/2 to the digits they print): that angle kept as written, its other "
                   "angles that are roundings made the right angles"] if kept else [])


#: Relative distance of an axis's length from 1 beyond which the readings say it is scaled.
AXIS_LENGTH_TOL = 1e-9


def axis_readings(root: ET.Element, locked: tuple[str, ...] = ()) -> list[str]:
    r"""The moving joints whose ``<axis xyz>`` is not of unit length (``"0 0 2"``): read as its
    direction, as URDF readers do (Pinocchio, ROS), one line naming them; a zero axis is an
    error of the URDF checks, before this."""
    scaled = []
    for joint in root.iterfind("joint"):
        axis = joint.find("axis")
        if joint.get("type") == "fixed" or joint.get("name") in locked or axis is None:
            continue
        try:
            length = float(np.linalg.norm([float(x) for x in axis.get("xyz", "").split()]))
        except ValueError:
            continue
        if length > 0 and abs(length - 1.0) > AXIS_LENGTH_TOL:
            scaled.append(f"{joint.get('name', '')} ({axis.get('xyz')})")
    if not scaled:
        return []
    return [f"joint{'s' if len(scaled) > 1 else ''} {_listed(scaled)}: an axis not of unit "
            "length, read as its direction (the joint's coordinate is the angle or distance "
            "along the unit axis, as URDF readers take it)"]


def _listed(names: list[str]) -> str:
    return ", ".join(names) if len(names) <= 4 else f"{', '.join(names[:3])} and {len(names) - 3} more"


def _damped(joint: ET.Element) -> bool:
    dynamics = joint.find("dynamics")
    return dynamics is not None and any(float(dynamics.get(k) or 0) != 0.0
                                        for k in ("damping", "friction"))


def joint_readings(root: ET.Element, locked: tuple[str, ...] = ()) -> list[str]:
    r"""The moving joints (not fixed, not ``locked``) whose ``<dynamics>`` has damping or
    friction, and the transmissions of moving joints: one line each."""
    moving = {j.get("name", ""): j for j in root.iterfind("joint")
              if j.get("type") != "fixed" and j.get("name") not in locked}
    damped = [name for name, j in moving.items() if _damped(j)]
    out = []
    if damped:
        their = "their" if len(damped) > 1 else "its"
        out.append(f"joint{'s' if len(damped) > 1 else ''} {_listed(damped)}: the damping and "
                   f"friction of {their} dynamics element are not part of the equations (the "
                   "truth has none: a derivation's damping or friction terms are terms it "
                   "does not have)")
    driven = [t.get("name", "") for t in root.iterfind("transmission")
              if any(j.get("name") in moving for j in t.iterfind("joint"))]
    if driven:
        out.append(f"transmission{'s' if len(driven) > 1 else ''} {_listed(driven)}: not "
                   "applied; the model's inputs are its joints' torques (a reduction between "
                   "motor and joint is the document's to state)")
    return out


def urdf_readings(text: str, locked: tuple[str, ...] = ()) -> tuple[str, ...]:
    r"""What the model reads otherwise than the URDF ``text`` writes (module text), its
    ``locked`` joints part of their links' bodies: inertias, then joints and transmissions."""
    root = ET.fromstring(text)
    return (*inertial_readings(root), *joint_origin_readings(root), *axis_readings(root, locked),
            *joint_readings(root, locked))


#: Height (relative to the wheels' radius) of a frame-only root link above or below the
#: ground beyond which the readings say so.
GROUND_TOL = 1e-3


def ground_reading(text: str, root: str, height: float, radius: float) -> tuple[str, ...]:
    r"""Where the root link is a frame only (no inertia, no geometry: a ROS
    ``base_footprint``, which REP 120 puts on the ground) and lies ``height`` above the ground
    the wheels' ``radius`` puts under their axle: that it is not on it (the wheels' radius
    and the root's height do not agree: R is the radius)."""
    link = next((el for el in ET.fromstring(text).iterfind("link") if el.get("name") == root),
                None)
    if link is None or len(link) or abs(height) <= GROUND_TOL * radius:
        return ()
    where = "above" if height > 0 else "below"
    return (f"link {root} (a frame only, the root) is {abs(height):.3g} m {where} the ground "
            f"the wheels' radius {radius:g} puts under their axle: the model's R is that "
            "radius (if the root is meant on the ground, its joints' origins and the wheels' "
            "radius do not agree)",)


def wheel_turn(joint: str, angle: float) -> str:
    r"""The reading of a planar model's wheel joint turned by ``angle`` onto the axle."""
    return (f"joint {joint}: its axis is turned by {angle:.2g} rad onto the axle (a planar "
            "model's wheels turn about their axle; URDFs round π/2)")


__all__ = ["AXIS_LENGTH_TOL", "TURN_NOTED", "axis_readings", "ground_reading", "inertial_readings",
           "joint_readings", "urdf_readings", "wheel_turn"]
