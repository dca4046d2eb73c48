r"""Checks of a URDF's tree and inertial data, made before Pinocchio reads the file.

Pinocchio trusts its input: a joint naming a missing link, a link with two parents or a cycle
of joints make it fail with an unhelpful message or crash the process (a cycle: a
segmentation fault). These checks read the XML tree and raise one error per file, naming the
link or joint:

- **structure** (:class:`~wheeled_dyn.errors.InputFileError`): a link or joint without a name or
  named twice; a joint without ``<parent link>``/``<child link>`` or naming a missing link; a
  link that is the child of two joints; a cycle of joints; more than one root link; more
  than :data:`MAX_MOVING_JOINTS` moving joints (:class:`~wheeled_dyn.errors.LimitError`).
- **inertial data** (:class:`~wheeled_dyn.errors.ModelError`): an ``<inertial>`` without
  ``<inertia>`` or one of its six entries; a mass that is not a finite positive number (of at
  most :data:`~.urdf_values.MAX_MODEL_NUMBER`) (a zero mass with a zero inertia is a massless frame, as real URDFs write
  ``base_footprint``, and counts as no ``<inertial>``); an inertia tensor :math:`I` (about the centre of mass) with a non-finite
  entry, with a negative principal moment (not positive semi-definite) or whose principal
  moments violate the triangle inequality :math:`I_a + I_b \ge I_c` (no mass distribution has
  them); a moving joint whose whole subtree carries no mass (its coordinate has no inertia:
  the mass matrix is singular) — a link without ``<inertial>`` is massless; every check is
  made without recursion (a chain of thousands of links is fine);
- **mimic joints** (:func:`check_mimic`, :class:`~wheeled_dyn.errors.InputFileError`): a
  moving joint that follows another is refused (it would be built as an independent
  coordinate, a different body), unless it is locked with its leader at values that satisfy
  the relation.

A point mass (:math:`I = 0`) and a thin rod (one principal moment 0) are accepted: they are
positive semi-definite limits that keep the mass matrix regular when other bodies carry
inertia about the missing axes.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from ..errors import InertiaError, InputFileError, LimitError, ModelError
from .urdf_values import MAX_MODEL_NUMBER, MAX_MODEL_TEXT, NUMBER, line_of as _line_of, \
    line_within

#: Relative tolerance (of the largest principal moment) for PSD and triangle checks.
INERTIA_TOL = 1e-9
#: Absolute tolerance (kg m²) for PSD and triangle checks (rounding in near-zero inertias).
INERTIA_ABS_TOL = 1e-12
#: How to build a model from a URDF whose link inertia is known to be wrong.
ACCEPT_HINT = ("; to build anyway (e.g. a small link merged into a larger body), list the link "
               "in the model file's accept_inertia")
#: Joint types that do not move their child.
FIXED_TYPES = ("fixed",)
#: Most moving joints (neither fixed nor locked) a URDF may have: the symbolic coordinate
#: maps of every comparison and ``matrices`` take time growing as the cube of the number of
#: coordinates (measured: 49 coordinates 2.5 s, 99 coordinates 21 s).
MAX_MOVING_JOINTS = 100
#: Largest relative difference between a locked mimic joint's value and its leader's image.
MIMIC_TOL = 1e-9
#: The entries of an ``<inertia>`` (all required).
INERTIA_KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def _float(value: str | None) -> float:
    r"""A URDF number as urdfdom reads it: a decimal number (:data:`~.urdf_values.NUMBER`),
    else NaN (the error then names it). Python's ``float`` also reads ``1_0`` and full-width
    digits, which urdfdom refuses, dropping the whole ``<inertial>``: the link lost its mass
    without a word."""
    if value is None:
        return 0.0
    if not NUMBER.fullmatch(value.strip()):
        return math.nan
    return float(value)


def _check_inertial(path: Path, text: str, link: ET.Element, accept: tuple[str, ...]) -> float:
    r"""The link's mass (0 without ``<inertial>``); errors for bad mass or inertia."""
    name = link.get("name", "")
    inertial = link.find("inertial")
    if inertial is None:
        return 0.0
    mass_el = inertial.find("mass")
    where = f"{path.name}:{_line_of(text, 'link', name) or '?'}"
    for parent, tag in ((link, "inertial"), (inertial, "mass"), (inertial, "inertia"),
                        (inertial, "origin")):
        count = len(parent.findall(tag))
        if count > 1:               # which one is meant? urdfdom reads the first, silently
            raise ModelError(path.stem, name, f"{count} <{tag}> elements in its "
                             f"{'link' if parent is link else '<inertial>'}: it has one "
                             f"({where})")
    if mass_el is None:
        raise ModelError(path.stem, name, f"<inertial> without <mass> ({where})")
    mass = _float(mass_el.get("value"))
    inertia = inertial.find("inertia")
    if inertia is None:
        raise ModelError(path.stem, name, "<inertial> without <inertia ixx=... ixy=... ixz=... "
                                          f"iyy=... iyz=... izz=...> ({where})")
    absent = [k for k in INERTIA_KEYS if inertia.get(k) is None]
    if absent:
        raise ModelError(path.stem, name, f"<inertia> without {', '.join(absent)} (the six "
                                          f"entries are required) ({where})")
    values = {k: _float(inertia.get(k)) for k in INERTIA_KEYS}
    massless_frame = mass == 0 and all(v == 0 for v in values.values())
    if not (math.isfinite(mass) and 0 < mass <= MAX_MODEL_NUMBER) and not massless_frame:
        at = line_within(text, "link", name, "mass") or "?"
        raise ModelError(path.stem, name, f"mass {mass_el.get('value')!r} is not a finite "
                                          f"positive number of at most {MAX_MODEL_TEXT} "
                                          f"kg ({path.name}:{at})")
    bad = [k for k, v in values.items() if not (math.isfinite(v) and abs(v) <= MAX_MODEL_NUMBER)]
    if bad:
        at = line_within(text, "link", name, "inertia") or "?"
        raise ModelError(path.stem, name, f"inertia entry {bad[0]} = {inertia.get(bad[0])!r} "
                                          "is not a finite number of magnitude at most "
                                          f"{MAX_MODEL_TEXT} ({path.name}:{at})")
    I = np.array([[values["ixx"], values["ixy"], values["ixz"]],
                  [values["ixy"], values["iyy"], values["iyz"]],
                  [values["ixz"], values["iyz"], values["izz"]]])
    moments = np.linalg.eigvalsh(I)
    tol = max(INERTIA_TOL * float(np.abs(moments).max()), INERTIA_ABS_TOL)
    if name in accept:
        negative = [k for k in ("ixx", "iyy", "izz") if values[k] < 0]
        if negative:            # Pinocchio refuses it: accepting cannot let it through
            raise ModelError(path.stem, name, f"inertia entry {negative[0]} = "
                                              f"{inertia.get(negative[0])} is negative: no mass "
                                              "distribution has it and Pinocchio cannot take it"
                                              f", even in accept_inertia ({where})")
        return mass
    if moments[0] < -tol:
        raise InertiaError(path.stem, name, "inertia is not positive semi-definite (principal "
                                            f"moments {', '.join(f'{m:.6g}' for m in moments)}) "
                                            f"({where}){ACCEPT_HINT}")
    if moments[0] + moments[1] < moments[2] - tol:
        raise InertiaError(path.stem, name, "inertia violates the triangle inequality "
                                            f"I_a + I_b >= I_c (principal moments "
                                            f"{', '.join(f'{m:.6g}' for m in moments)}) ({where})"
                                            + ACCEPT_HINT)
    return mass


def _subtree_masses(mass: dict[str, float], parent_of: dict[str, str]) -> dict[str, float]:
    r"""The mass each link carries (its own and everything below it), without recursion (a
    chain of thousands of links is as deep): each link's mass is added to every link above
    it, following the parents (the tree was checked: no cycles)."""
    total = dict(mass)
    depth: dict[str, int] = {}
    for link in mass:                       # depth below the root, iteratively
        path = []
        while link not in depth and link in parent_of:
            path.append(link)
            link = parent_of[link]
        base = depth.get(link, 0)
        for k, item in enumerate(reversed(path), start=1):
            depth[item] = base + k
    for link in sorted(mass, key=lambda n: -depth.get(n, 0)):     # the deepest first
        if link in parent_of:
            total[parent_of[link]] += total[link]
    return total


def check_mimic(path: str | Path, text: str, root: ET.Element, locked: Mapping[str, float],
                lock: tuple[str, ...]) -> None:
    r"""Refuse a ``<mimic>`` joint the model would not honour: a moving joint that the URDF
    makes follow another (``q = multiplier q_leader + offset``) would be built as an
    independent coordinate, a different body. Accepted: a mimic on a fixed joint (nothing
    moves), and a mimic joint that is locked with its leader at values that satisfy the
    relation. Raises :class:`InputFileError` naming the joint and its line."""
    path = Path(path)
    types = {j.get("name"): j.get("type", "") for j in root.findall("joint")}
    for joint in root.findall("joint"):
        mimic = joint.find("mimic")
        name = joint.get("name", "")
        if mimic is None or types.get(name) in FIXED_TYPES:
            continue
        leader = mimic.get("joint", "")
        factor, offset = _float(mimic.get("multiplier", "1")), _float(mimic.get("offset", "0"))
        line = _line_of(text, "joint", name)
        if name in lock and (leader in lock or types.get(leader) in FIXED_TYPES):
            value, lead = locked.get(name, 0.0), locked.get(leader, 0.0)
            if math.isfinite(factor) and math.isfinite(offset) and \
                    abs(value - (factor * lead + offset)) <= MIMIC_TOL * (1 + abs(value)):
                continue
            raise InputFileError(path, f"joint {name!r} mimics {leader!r} (q = {factor:g} "
                                       f"q_{leader} + {offset:g}): its locked value {value:g} "
                                       f"does not follow the leader's {lead:g}", line=line)
        raise InputFileError(path, f"joint {name!r} mimics joint {leader!r} (<mimic>): a "
                                   "mimic joint is not modelled (each joint is an independent "
                                   "coordinate here); lock it and its leader (model file "
                                   "[joints] locked) or remove the <mimic>", line=line)


def _link_elements(path: Path, text: str, root: ET.Element) -> dict[str, ET.Element]:
    r"""The ``<link>`` elements by name; each has a name, and one only."""
    links: dict[str, ET.Element] = {}
    for element in root.findall("link"):
        name = element.get("name")
        if not name:
            raise InputFileError(path, "a <link> has no name")
        if name in links:
            raise InputFileError(path, f"link {name!r} is defined twice",
                                 line=_line_of(text, "link", name))
        links[name] = element
    return links


def _joint_ends(path: Path, text: str, root: ET.Element, links: Mapping[str, ET.Element]
                ) -> tuple[dict[str, tuple[str, str, str]], dict[str, str]]:
    r"""``({joint: (type, parent link, child link)}, {child link: joint})``: every joint named
    once, its two ends defined links, every link the child of one joint at most."""
    joints: dict[str, tuple[str, str, str]] = {}
    parent_of: dict[str, str] = {}          # child link -> joint
    for joint in root.findall("joint"):
        name = joint.get("name")
        if not name:
            raise InputFileError(path, "a <joint> has no name")
        line = _line_of(text, "joint", name)
        if name in joints:
            raise InputFileError(path, f"joint {name!r} is defined twice", line=line)
        ends = []
        for end in ("parent", "child"):
            el = joint.find(end)
            link = el.get("link") if el is not None else None
            if not link:
                raise InputFileError(path, f"joint {name!r} has no <{end} link=...>", line=line)
            if link not in links:
                raise InputFileError(path, f"joint {name!r} names {end} link {link!r}, which "
                                           "is not defined", line=line)
            ends.append(link)
        parent, child = ends
        if child in parent_of:
            raise InputFileError(path, f"joint {name!r}: link {child!r} is already the child "
                                       f"of joint {parent_of[child]!r} (a URDF is a tree)",
                                 line=line)
        parent_of[child] = name
        joints[name] = (joint.get("type", ""), parent, child)
    return joints, parent_of


def _check_no_cycle(path: Path, text: str, joints: Mapping[str, tuple[str, str, str]],
                    parent_of: Mapping[str, str]) -> None:
    r"""No chain of parents returns to its start (every link has one parent at most, so
    following the parents from each link finds any cycle); the error names its joints."""
    for start in parent_of:
        seen = [start]
        link = start
        while link in parent_of:
            link = joints[parent_of[link]][1]
            if link in seen:            # parent -> child order; name the cycle's joints
                cycle = list(reversed(seen[seen.index(link):] + [link]))
                ring = [parent_of[child] for child in cycle[1:]]
                raise InputFileError(path, "the joints form a cycle through links "
                                     + " -> ".join(cycle) + " (joints "
                                     + ", ".join(repr(j) for j in ring) + ")",
                                     line=_line_of(text, "joint", ring[-1]))
            seen.append(link)


def check_urdf_tree(path: str | Path, text: str, root: ET.Element,
                    locked: tuple[str, ...] = (), accept: tuple[str, ...] = ()) -> None:
    r"""Check the tree and inertial data of a parsed URDF (see the module docstring).

    ``locked`` joints count as fixed (their subtree moves with the parent); the inertia tensors
    of the links in ``accept`` are not checked (their mass still is)."""
    path = Path(path)
    links = _link_elements(path, text, root)
    joints, parent_of = _joint_ends(path, text, root, links)
    _check_no_cycle(path, text, joints, parent_of)
    roots = [n for n in links if n not in parent_of]
    if len(roots) != 1:
        raise InputFileError(path, f"expected one root link, found {len(roots)}: {roots}")
    moving = [j for j, (jtype, _, _) in joints.items()
              if jtype not in FIXED_TYPES and j not in locked]
    if len(moving) > MAX_MOVING_JOINTS:
        raise LimitError(f"{path}: moving joints", len(moving), f"at most {MAX_MOVING_JOINTS} "
                         "(lock the others in the model file)", "the time of the coordinate "
                         "maps grows as their cube: 99 coordinates take 21 s")
    mass = {name: _check_inertial(path, text, link, accept) for name, link in links.items()}
    subtree = _subtree_masses(mass, {child: parent for _, parent, child in joints.values()})
    for jname, (jtype, _, child) in joints.items():
        if jtype in FIXED_TYPES or jname in locked:
            continue
        if subtree[child] <= 0:
            raise ModelError(path.stem, child, f"link moved by joint {jname!r} has no mass (no "
                                               "<inertial>, or mass 0), nor has anything it "
                                               "carries: the joint's coordinate would have no "
                                               "inertia; give the link its mass, or lock the "
                                               "joint in the model file ([joints] lock = "
                                               f"[\"{jname}\"]) "
                                               f"({path.name}:{_line_of(text, 'link', child)})")
