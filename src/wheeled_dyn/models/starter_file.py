r"""The text of a starting model file (:mod:`.starter`): the URDF, the base and its wheels,
``pitch`` false where casters keep the body level, the moving joints that are neither the
wheels' nor locked (a swivel caster's) and how to lock them, the candidate wheels, links,
joints and lengths by the names a derivation may use — every suggestion marked ``CHECK``."""

from __future__ import annotations

import os
from pathlib import Path

from ..paths import resolved
from .starter import UrdfInventory, free_joints, inspect_urdf
from .urdf_packages import package_reference


def _q(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def starter_text(inv: UrdfInventory, out: Path | None) -> str:
    r"""The text of a starting model file for ``inv`` (written next to ``out`` if given)."""
    urdf = resolved(inv.path)
    rel = os.path.relpath(urdf, (resolved(out).parent if out else Path.cwd()))
    name = "".join(c if c.isalnum() or c == "_" else "_" for c in (inv.robot or inv.path.stem))
    lines = [f"# Starting model file for {inv.robot or inv.path.stem}, written by "
             f"'wheeled-dyn model {inv.path.name}'.",
             "# Check every line marked CHECK before trusting results; format: "
             "docs/model-format.md.",
             f"name = {_q(name)}",
             f"summary = {_q(f'{inv.robot or inv.path.stem} from {inv.path.name}')}",
             "", "[urdf]"]
    package = package_reference(urdf)
    if package is None:
        lines += [f"path = {_q(Path(rel).as_posix())}   # relative to this file", ""]
    else:
        lines += [f"package = {_q(package[0])}"]
        lines += [f"path = {_q(package[1])}   # inside the package"] if package[1] else []
        lines += [""]
    if inv.bad_inertia:
        lines += ["[checks]",
                  "# CHECK: these links' inertias are accepted as written (--accept-inertia) "
                  "even if they fail",
                  "# the URDF checks. Fix the URDF, or keep them if they are small parts "
                  "of a larger body.",
                  "accept_inertia = [" + ", ".join(_q(n) for n in inv.bad_inertia) + "]", ""]
    if inv.pair is None:
        moving = [j for j in inv.joints if j[1] in ("continuous", "revolute")]
        lines += ["[base]", f"# The root link {inv.root!r} is the world, so this is no "
                  "wheeled model:" if inv.world_root else "# No pair of wheels found, so "
                  "this is no wheeled model:"]
        lines += [f"#   {joint}: {reason}" for joint, reason in inv.rejected] or \
            ["#   the URDF has no revolute or continuous joint"]
        if any(j[1] == "continuous" for j in moving) and not inv.world_root:
            lines += ["# CHECK: a fixed base holds the root link in the air: the continuous "
                      "joints above spin",
                      "# on a stand. For a wheeled robot, give each wheel link a cylinder "
                      "about its joint's axis."]
        lines += ['type = "fixed"         # CHECK: fixed (root link fixed to the world) or free',
                  f"body = {_q(inv.root)}", ""]
        lines += _actuated_lines(inv)
    else:
        left, right = inv.pair
        up = "[" + ", ".join(f"{x:.1f}" for x in inv.up) + "]"
        lines += ["[base]",
                  'type = "planar"        # a wheeled body on the ground plane (fixed, free: '
                  'see the format)',
                  f"body = {_q(inv.body)}    # the link carrying the axle; the links fixed to "
                  "it move with it",
                  f"up = {up}   # the body's up direction in its link frame "
                  "(perpendicular to the axle)",
                  *_pitch_lines(inv), "", "[wheels]"]
        lines += [f"# {note}" for note in inv.notes]
        lines += [f"links = [{_q(left.link)}, {_q(right.link)}]   # left, right",
                  f"radius = {left.radius:.6g}    # CHECK: the rolling radius; read from "
                  f"{left.link}'s {left.geometry} cylinder", ""]
        lines += _free_joint_lines(inv)
        lines += ["[joints.aliases]          # the wheel angles' coordinate names",
                  f"{_q(left.joint)} = \"theta_l\"", f"{_q(right.joint)} = \"theta_r\"", ""]
        if inv.path_joints:
            lines += ["[joints.locked]",
                      "# The joints between the body and the wheels, locked (a planar base "
                      "needs the axle on one rigid",
                      "# body). CHECK the values (rad or m): the axle must stay horizontal.",
                      *(f"{_q(j)} = 0.0" for j in inv.path_joints),
                      ""]
    lines += ["# Candidate wheels (link, joint, radius m, position in the root frame m):"]
    lines += [f"#   {c.link:28} {c.joint:20} r={c.radius:<8g} "
              f"({', '.join(f'{x:.4g}' for x in c.position)})" for c in inv.candidates] \
        or ["#   none"]
    lines += [f"# Links ({len(inv.links)}): name, mass kg, cylinder"]
    lines += [f"#   {n:32} {m:<10.6g} {note}".rstrip() for n, m, note in inv.links]
    lines += [f"# Joints ({len(inv.joints)}): name, type, parent -> child, axis"]
    lines += [f"#   {n:32} {t:10} {p} -> {c}  {a}".rstrip() for n, t, p, c, a in inv.joints]
    lines += _length_lines(inv)
    return "\n".join(lines) + "\n"


def _actuated_lines(inv: UrdfInventory) -> list[str]:
    r"""A ``[joints]`` table whose ``actuated`` and ``inputs`` (B's columns: the joints with
    motors, and the names of their torques or forces) are commented out, for a base without
    wheels: every moving joint, to keep the ones driven."""
    moving = [j[0] for j in inv.joints if j[1] in ("continuous", "revolute", "prismatic")]
    if not moving:
        return []
    return ["[joints]",
            "# CHECK: the joints driven by a motor (B's columns) and their inputs' names; "
            "uncomment, keeping",
            "# the driven ones (none: a model without inputs, B has no columns):",
            "# actuated = [" + ", ".join(_q(j) for j in moving) + "]",
            "# inputs = [" + ", ".join(_q(f"tau_{j}") for j in moving) + "]", ""]


def _pitch_lines(inv: UrdfInventory) -> list[str]:
    r"""``pitch``: false where casters keep the body level (:func:`.starter_urdf.caster_links`:
    a caster ball, a swivel caster, other wheels), true otherwise (a balancing robot)."""
    if inv.casters:
        return ["pitch = false          # CHECK: false: casters keep the body level "
                f"({', '.join(inv.casters)}); true if it pitches about the axle (a pendulum)"]
    return ["pitch = true           # CHECK: true if the body pitches about the axle "
            "(a pendulum), false if casters keep it level"]


def _free_joint_lines(inv: UrdfInventory) -> list[str]:
    r"""A ``[joints]`` table naming the moving joints of a wheeled model that are neither its
    wheels' nor locked (a swivel caster's): the model does not roll them, and a derivation
    that leaves them out holds them at 0 with their links' mass on the body."""
    free = free_joints(inv.joints, inv.pair, inv.path_joints)
    if not free:
        return []
    names = ", ".join(_q(j) for j in free)
    return ["[joints]",
            f"# CHECK: {', '.join(free)} move freely (a caster, an arm?): the model does not roll",
            "# them. A derivation that leaves them out holds them at 0, its truth carrying "
            "their links' mass",
            "# ('agrees only if ... carry no mass'). To make them part of the body, lock them:",
            f"# lock = [{names}]", ""]


def _length_lines(inv: UrdfInventory) -> list[str]:
    r"""The URDF's lengths by the names derivation files use (``l1 = "origin_x(elbow)"``) and
    a commented ``[geometry]`` to tie the ones the body has equal by design."""
    from .geometry import urdf_length_names
    names = urdf_length_names(inv.path.read_text(encoding="utf-8"))
    axle: list[str] = []
    if inv.pair is not None:        # a planar model names the axle's lengths R and L
        parent = {child: (joint, up) for joint, _, up, child, _ in inv.joints}
        for wheel in inv.pair:
            link = wheel.link
            while link in parent:
                joint, link = parent[link]
                axle.append(f"({joint})")
        wheels = {f"radius({w.link})" for w in inv.pair}
        names = [x for x in names if x[0] not in wheels and not x[0].endswith(tuple(axle))]
    lines = [f"# Lengths ({len(names)}), by the names a derivation's [symbols] may use "
             "(random parameter sets draw them):"]
    if inv.pair is not None:
        lines += ["#   R, L: the wheels' radius and half the track (the axle's lengths)"]
    lines += [f"#   {n:40} {v:<10.6g} {what}" for n, v, what in names] or ["#   none"]
    groups: list[list[tuple[str, float]]] = []
    for n, v, _ in names:
        group = next((g for g in groups if abs(abs(g[0][1]) - abs(v)) <= 1e-9 * abs(v)), None)
        if group is None:
            groups.append([(n, v)])
        else:
            group.append((n, v))
    equal = [g for g in groups if len(g) > 1]
    lines += ["# Lengths the body has equal by design are drawn as one when [geometry] lists "
              "them (docs/model-format.md).",
              "# CHECK these, equal in the URDF (uncomment the ones that are one length, name "
              "them as you like):" if equal else "# None are equal in this URDF."]
    if equal:
        lines += ["# [geometry]"]
    for k, g in enumerate(equal):
        first = g[0][1]
        items = ", ".join(_q(n if v * first > 0 else f"-{n}") for n, v in g)
        lines += [f"# length_{k + 1} = [{items}]    # {abs(first):g} m"]
    return lines


def write_starter(urdf: str | Path, out: str | Path | None,
                  inventory: UrdfInventory | None = None) -> str:
    r"""Inspect ``urdf`` (unless its ``inventory`` is given) and return the starting model
    file's text; write it to ``out`` (atomic: a temporary file renamed; missing folders
    created) when given."""
    from ..output import write_atomic
    out_path = Path(out) if out is not None else None
    text = starter_text(inventory or inspect_urdf(urdf), out_path)
    if out_path is not None:
        write_atomic(out_path, text)
    return text
