r"""A starting model file from a URDF: ``wheeled-dyn model robot.urdf [--out robot.toml]``.

The URDF is checked (:mod:`.urdf_checks`, :mod:`.urdf_values`; a link inertia that fails is
an error unless ``--accept-inertia`` names it) and inspected with yourdfpy at its zero
configuration. *Candidate wheels* are links with a cylinder (collision first, then visual)
whose axis is parallel to the axis of the revolute or continuous joint that turns them (the
first moving joint above the link, through fixed joints) and whose joint carries no other
moving joint (wheels end their chains); for each such joint the largest cylinder counts (a
tyre rather than a hub). The suggested pair has equal radii, lies on one axle, lowest and farthest apart;
*left* is the one whose name says so, or else the one on the root link's +y side (x forward,
z up, the ROS convention); the suggested up direction is perpendicular to the axle. The
suggested body is the root link; the joints between it and the wheels are locked at 0 (a
planar base needs the axle on one rigid body). Every suggestion is marked
``CHECK`` in the written file (:mod:`.starter_file`), with the reason it was made.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .conventions import ANGLE_TOL, TYRE_OFF_AXIS_TOL
from .starter_urdf import caster_links, read_checked

#: Largest relative difference of two wheel radii to pair them.
PAIR_RADIUS_TOL = 1e-6
#: The root link's name by which a URDF says it is fixed to the world (ROS and Gazebo read a
#: massless root link named so as the world itself: the robot's joints move it relative to the
#: ground, and no wheel of it carries a planar base).
WORLD_LINK = "world"
#: A wheel radius (m) above which the starter notes that the URDF may not be in metres (the
#: largest wheels on robots and vehicles are about a metre across; a file exported from CAD in
#: millimetres gives radii of tens of metres).
PLAUSIBLE_RADIUS = 2.0


@dataclass(frozen=True)
class WheelCandidate:
    r"""A link that looks like a wheel: its cylinder turns about its joint's axis."""

    link: str
    joint: str
    radius: float
    width: float
    position: tuple[float, float, float]      # link origin in the root frame, zero configuration
    geometry: str                             # "collision" or "visual"
    axis: tuple[float, float, float] = (0.0, 1.0, 0.0)   # spin axis in the root frame


@dataclass(frozen=True)
class UrdfInventory:
    r"""What :func:`inspect_urdf` found."""

    path: Path
    robot: str
    root: str
    links: tuple[tuple[str, float, str], ...]          # (name, mass, cylinder note)
    joints: tuple[tuple[str, str, str, str, str], ...]  # (name, type, parent, child, axis)
    candidates: tuple[WheelCandidate, ...]
    pair: tuple[WheelCandidate, WheelCandidate] | None
    path_joints: tuple[str, ...]                        # moving joints body -> wheels
    bad_inertia: tuple[str, ...] = ()                   # links accepted (--accept-inertia)
    rejected: tuple[tuple[str, str], ...] = ()          # (moving joint, why not a wheel)
    body: str = ""                                      # the link carrying the axle
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)    # in the body's link axes
    notes: tuple[str, ...] = ()                         # how left, right, up were decided
    casters: tuple[str, ...] = ()                       # links keeping the body level
    world_root: bool = False                            # the root is the world (WORLD_LINK)


def _cylinders(link) -> Iterator[tuple[float, float, np.ndarray, str, np.ndarray]]:
    r"""The link's cylinders, collision ones first: (radius, length, axis, kind, centre), the
    axis and centre in the link's frame."""
    for kind, shapes in (("collision", link.collisions), ("visual", link.visuals)):
        for shape in shapes:
            cyl = shape.geometry.cylinder if shape.geometry is not None else None
            if cyl is not None:
                origin = shape.origin if shape.origin is not None else np.eye(4)
                yield (float(cyl.radius), float(cyl.length), np.asarray(origin)[:3, 2], kind,
                       np.asarray(origin)[:3, 3])


def _cylinder(link) -> tuple[float, float, np.ndarray, str, np.ndarray] | None:
    return next(_cylinders(link), None)


def _carriers(robot, parent_joint) -> set[str]:
    r"""The moving joints that carry another moving joint (a wheel ends its chain)."""
    carriers = set()
    for j in robot.joints:
        if j.type == "fixed":
            continue
        link = j.parent
        while link in parent_joint:
            above = parent_joint[link]
            if above.type != "fixed":
                carriers.add(above.name)
            link = above.parent
    return carriers


def _candidate(urdf, link, cyl, parent_joint, carriers, root: str, why: dict[str, str]
               ) -> WheelCandidate | None:
    r"""``link`` as a wheel, or None (with the reason in ``why`` under its joint's name)."""
    joint = parent_joint[link.name]
    while joint.type == "fixed" and joint.parent in parent_joint:
        joint = parent_joint[joint.parent]
    if joint.type not in ("revolute", "continuous"):
        return None
    if joint.name in carriers:
        why.setdefault(joint.name, f"turns {link.name}'s cylinder but carries other moving "
                                   "joints (a wheel ends its chain)")
        return None
    cyl_axis = urdf.get_transform(link.name, joint.child)[:3, :3] @ cyl[2]
    axis = np.asarray(joint.axis if joint.axis is not None else (1.0, 0.0, 0.0), dtype=float)
    sine = float(np.linalg.norm(np.cross(cyl_axis, axis / np.linalg.norm(axis))))
    angle = float(np.arcsin(min(1.0, sine)))
    if angle > ANGLE_TOL:
        why.setdefault(joint.name, f"{link.name}'s {cyl[3]} cylinder axis is {angle:.3g} rad "
                                   f"from the joint axis (at most {ANGLE_TOL} rad for a wheel)")
        return None
    axis = axis / np.linalg.norm(axis)
    to_child = urdf.get_transform(link.name, joint.child)
    centre = to_child[:3, :3] @ cyl[4] + to_child[:3, 3]     # the tyre's, in the joint's frame
    along = (centre @ axis) * axis
    off = float(np.linalg.norm(centre - along))
    if off > TYRE_OFF_AXIS_TOL * cyl[0]:
        why.setdefault(joint.name, f"{link.name}'s {cyl[3]} cylinder is centred {off:.3g} m "
                                   "off the joint axis (a wheel is round about its axle)")
        return None
    child = urdf.get_transform(joint.child, root)
    pos = tuple(float(x) for x in child[:3, :3] @ along + child[:3, 3])   # the tyre's plane
    spin = child[:3, :3] @ axis
    return WheelCandidate(link.name, joint.name, cyl[0], cyl[1], pos,  # type: ignore[arg-type]
                          cyl[3], tuple(float(x) for x in spin))  # type: ignore[arg-type]


def _path_joints(pair, parent_joint) -> tuple[str, ...]:
    r"""The moving joints between the body and the wheels' spin joints."""
    out: list[str] = []
    for cand in pair or ():
        link = cand.link
        while link in parent_joint:
            joint = parent_joint[link]
            if joint.type != "fixed" and joint.name != cand.joint and joint.name not in out:
                out.insert(0, joint.name)
            link = joint.parent
    return tuple(out)


def inspect_urdf(path: str | Path, accept_inertia: tuple[str, ...] = ()) -> UrdfInventory:
    r"""Links, joints and candidate wheels of a URDF (see the module docstring); the links of
    ``accept_inertia`` may have an inertia that fails the checks."""
    source, urdf, accept = read_checked(path, tuple(accept_inertia))
    robot = urdf.robot
    root = source.root_link()
    parent_joint = {j.child: j for j in robot.joints}
    carriers = _carriers(robot, parent_joint)
    links: list[tuple[str, float, str]] = []
    candidates: dict[str, WheelCandidate] = {}
    why: dict[str, str] = {}
    for link in robot.links:
        mass = float(link.inertial.mass) if link.inertial is not None and \
            link.inertial.mass is not None else 0.0
        cyl = _cylinder(link)
        links.append((link.name, mass, f"cylinder r={cyl[0]:g} m, length {cyl[1]:g} m "
                      f"({cyl[3]})" if cyl else ""))
        if cyl is None or link.name not in parent_joint:
            continue
        cand = next((c for c in (_candidate(urdf, link, shape, parent_joint, carriers, root,
                                            why) for shape in _cylinders(link)) if c), None)
        if cand is not None:            # a visual cylinder about the axis (the collision
            why.pop(cand.joint, None)   # one turned wrong): the wheel is read from it
        best = candidates.get(cand.joint) if cand is not None else None
        if cand is not None and (best is None or cand.radius > best.radius):
            candidates[cand.joint] = cand
    for j in robot.joints:
        if j.type in ("revolute", "continuous") and j.name not in candidates:
            why.setdefault(j.name, "turns no link with a cylinder (collision or visual "
                                   "geometry) that could be a wheel")
    ordered = sorted(candidates.values(), key=lambda c: (c.position[2], c.link))
    pair = _pair(ordered)
    if pair is None and len(ordered) >= 2:
        why["(pairing)"] = ("no two candidate wheels have equal radii (within "
                            f"{PAIR_RADIUS_TOL:g} relative) at distinct places")
    elif pair is None and ordered:
        why["(pairing)"] = f"only one candidate wheel ({ordered[0].link})"
    world_root = root == WORLD_LINK and next(m for n, m, _ in links if n == root) == 0.0
    if world_root and pair is not None:
        why["(root)"] = (f"the root link {root!r} is the world (a URDF fixed to the world "
                         "names its massless root so): the robot is a fixed base; "
                         f"{pair[0].link} and {pair[1].link} spin on their joints (a "
                         "derivation that rolls them ties their angles to the travel in its "
                         "coordinate map)")
        pair = None
    path_joints = _path_joints(pair, parent_joint)
    joints = tuple((j.name, j.type, j.parent, j.child,
                    " ".join(f"{x:g}" for x in (j.axis if j.axis is not None and j.type
                                                 != "fixed" else ())))   # none of its own
                   for j in robot.joints)
    body, up = root, (0.0, 0.0, 1.0)
    notes: tuple[str, ...] = ()
    if pair is not None:
        body = _body(pair, parent_joint, path_joints, root)
        pair, up, notes = _sides(pair, urdf.get_transform(body, root)[:3, :3], body)
        notes += _units_note(pair)
    notes += _extent_note(urdf, robot, root)
    free = free_joints(joints, pair, path_joints)
    casters = caster_links(urdf, pair, free, urdf.get_transform(body, root)[:3, :3]
                           @ np.asarray(up), root) if pair else ()
    return UrdfInventory(Path(path), robot.name, root, tuple(links), joints, tuple(ordered),
                         pair, path_joints, accept,
                         tuple(sorted(why.items())) if pair is None else (), body, up, notes,
                         casters, world_root)


def _units_note(pair: tuple[WheelCandidate, WheelCandidate]) -> tuple[str, ...]:
    r"""A CHECK note where the wheels are larger than :data:`PLAUSIBLE_RADIUS`: URDF lengths
    are metres (REP 103), and a file in millimetres is 1000 times too large (its masses and
    inertias are read as written)."""
    left, right = pair
    if left.radius <= PLAUSIBLE_RADIUS:
        return ()
    track = float(np.linalg.norm(np.subtract(left.position, right.position)))
    return (f"CHECK units: a wheel radius of {left.radius:g} m and a track of {track:g} m; "
            "URDF lengths are metres (REP 103): a file exported in millimetres is 1000 times "
            "too large",)


#: A distance (m) of a link's centre of mass from the root link above which the starter
#: notes that the URDF may not be in metres (a robot a person brings is a few metres at most;
#: a CAD export in millimetres puts a torso hundreds of metres up).
PLAUSIBLE_EXTENT = 20.0


def _extent_note(urdf, robot, root: str) -> tuple[str, ...]:
    r"""A CHECK note where a link's centre of mass, at every joint 0, is farther than
    :data:`PLAUSIBLE_EXTENT` from the root link's origin (the farthest named)."""
    far, where = 0.0, ""
    for link in robot.links:
        if link.inertial is None or link.inertial.origin is None:
            continue
        try:
            at = urdf.get_transform(link.name, root) @ np.asarray(link.inertial.origin)
        except (ValueError, KeyError):
            continue
        distance = float(np.linalg.norm(at[:3, 3]))
        if np.isfinite(distance) and distance > far:
            far, where = distance, link.name
    if far <= PLAUSIBLE_EXTENT:
        return ()
    return (f"CHECK units: link {where}'s centre of mass is {far:g} m from the root link "
            f"{root}; URDF lengths are metres (REP 103): a file exported in millimetres is "
            "1000 times too large",)


def _body(pair, parent_joint, path_joints, root: str) -> str:
    r"""The link carrying the axle: the link both wheel joints hang from (a ``base_link`` under
    a ``base_footprint`` root), or the root when joints lie between (they are locked)."""
    parents = {parent_joint[c.link].parent if parent_joint[c.link].name == c.joint else None
               for c in pair}
    if len(parents) == 1 and None not in parents and not path_joints:
        return str(parents.pop())
    return root


def _sides(pair, R_body: np.ndarray, body: str):
    r"""(left, right), the up direction and notes, from the geometry: in the body's axes, up
    is +z (REP 103) unless the axle is along z (then +y, as seed 001 writes its body), forward
    is +x, and left is the wheel for which up × (left → right) points forward. Where the axle
    lies along x, forward is unknown and the link names decide (else the list order)."""
    a, b = pair
    axle = R_body.T @ np.subtract(b.position, a.position)
    axle /= np.linalg.norm(axle)
    up = np.array([0.0, 1.0, 0.0]) if abs(axle[2]) >= np.cos(ANGLE_TOL) else np.eye(3)[2]
    notes = []
    along = float(np.cross(up, axle)[0])
    if abs(along) < np.cos(ANGLE_TOL):
        notes.append(f"CHECK left and right: the axle is not perpendicular to +x of {body}, so "
                     "the link names decided (REP 103: x forward, y left, z up)")
        for left, right in (pair, pair[::-1]):
            if _side(left.link) == "left" or _side(right.link) == "right":
                return (left, right), tuple(up), tuple(notes)
        return pair, tuple(up), tuple(notes)
    left, right = (a, b) if along > 0 else (b, a)
    notes.append(f"left and right from the geometry: forward = +x of {body} (REP 103), up = "
                 f"{'+z' if up[2] else '+y'} of {body}, {left.link} on the left")
    if _side(left.link) == "right" or _side(right.link) == "left":
        notes.append(f"CHECK: the names say otherwise ({left.link} is on the left side of "
                     f"{body}'s +x); the geometry decided")
    return (left, right), tuple(up), tuple(notes)


def _pair(cands: list[WheelCandidate]) -> tuple[WheelCandidate, WheelCandidate] | None:
    r"""The drive wheels: two candidates of equal radius on one axle (each spin axis along the
    line between their centres: a skid-steer's diagonal pair is not one), the lowest, the
    farthest apart; two not on one axle only where no such pair exists."""
    best, best_key = None, None
    for i, a in enumerate(cands):
        for b in cands[i + 1:]:
            if abs(a.radius - b.radius) > PAIR_RADIUS_TOL * max(a.radius, b.radius):
                continue
            line = np.subtract(b.position, a.position)
            gap = float(np.linalg.norm(line))
            if gap <= 0:
                continue
            coaxial = all(np.linalg.norm(np.cross(line / gap, w.axis)) <= np.sin(ANGLE_TOL)
                          for w in (a, b))
            key = (not coaxial, round(a.position[2] + b.position[2], 6), -round(gap, 9))
            if best_key is None or key < best_key:
                best, best_key = (a, b), key
    return best


def _side(name: str) -> str | None:
    low = name.lower()
    for side, marks in (("left", ("left", "_l_", "_l")), ("right", ("right", "_r_", "_r"))):
        if any(m in low and (m != "_l" and m != "_r" or low.endswith(m)) for m in marks):
            return side
    return None


def free_joints(joints, pair, path_joints) -> tuple[str, ...]:
    r"""The moving ``joints`` that are neither the drive wheels' (``pair``) nor locked (a
    caster's)."""
    own = {w.joint for w in pair or ()} | set(path_joints)
    return tuple(j[0] for j in joints if j[1] in ("continuous", "revolute", "prismatic")
                 and j[0] not in own)
