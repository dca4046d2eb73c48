r"""Checks of a URDF's numbers and joint declarations, made before yourdfpy and Pinocchio read it.

urdfdom (Pinocchio's URDF reader) refuses some malformed values with ``Error:`` lines on stderr
and a ``ValueError`` that names nothing ("The XML stream does not contain a valid URDF model"),
and drops others without a word (an ``<inertial>`` whose ``<origin>`` it cannot read: the link
loses its mass); yourdfpy fails with an ``IndexError`` on an unknown joint type and a broadcast
error on an axis of two numbers; a NaN or an infinity read as written makes every result NaN.
These checks raise one :class:`~wheeled_dyn.errors.InputFileError` naming the file, the line
and the link or joint, and what was expected:

- every number of a joint (its ``<origin xyz rpy>``, ``<axis xyz>``, ``<limit>``,
  ``<dynamics>``, ``<mimic>``, ``<safety_controller>``, ``<calibration>``) and of a link (the
  ``<origin>`` of its ``<inertial>``, ``<visual>`` and ``<collision>``, its shapes' sizes) is
  a finite decimal number of magnitude at most :data:`MAX_MODEL_NUMBER`, as many as the
  attribute takes (three for ``xyz``, ``rpy``, a box's ``size``, a mesh's ``scale``);
- a joint's type is one of :data:`JOINT_TYPES`; the axis of a moving one is not zero;
- a ``revolute`` or ``prismatic`` joint has a ``<limit>`` with ``effort`` and ``velocity``
  (the URDF format requires them; a wheel that turns without end is ``continuous``);
- a shape's radius, length and size are not negative (a mesh's scale may be: a mirror).

The mass and inertia of an ``<inertial>`` are checked in :mod:`.urdf_checks`.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

from ..errors import InputFileError

#: Largest magnitude of a number of a model (a URDF's masses, inertias, lengths, limits; a
#: model file's radius, constants, locked values) and of a state entry: the README's "numbers
#: up to 1e100". Products of a few such numbers stay finite; 1e308 overflows at once.
MAX_MODEL_NUMBER = 1e100
#: :data:`MAX_MODEL_NUMBER` as the messages write it.
MAX_MODEL_TEXT = "1e100"
#: The joint types of the URDF format.
JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
#: Joint types that move along or about their axis (a fixed joint's axis is not read: real
#: URDFs write ``0 0 0`` there).
AXIS_TYPES = ("revolute", "continuous", "prismatic", "planar")
#: Joint types that need a ``<limit>`` (the URDF format; urdfdom refuses them without one).
LIMITED_TYPES = ("revolute", "prismatic")
#: A decimal number as urdfdom reads it (no ``nan``, ``inf``, ``1_000``, hexadecimal or digits
#: other than ASCII: Python reads ``１０`` as 10).
NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?", re.ASCII)
#: The numbers of a joint's elements: (element, attribute) -> how many numbers.
JOINT_NUMBERS: dict[tuple[str, str], int] = {
    ("origin", "xyz"): 3, ("origin", "rpy"): 3, ("axis", "xyz"): 3,
    ("limit", "lower"): 1, ("limit", "upper"): 1, ("limit", "effort"): 1,
    ("limit", "velocity"): 1, ("dynamics", "damping"): 1, ("dynamics", "friction"): 1,
    ("mimic", "multiplier"): 1, ("mimic", "offset"): 1,
    ("safety_controller", "soft_lower_limit"): 1, ("safety_controller", "soft_upper_limit"): 1,
    ("safety_controller", "k_position"): 1, ("safety_controller", "k_velocity"): 1,
    ("calibration", "rising"): 1, ("calibration", "falling"): 1}
#: The numbers of a link's shapes: (shape, attribute) -> how many numbers (none negative but
#: a mesh's scale, which mirrors it).
SHAPE_NUMBERS: dict[tuple[str, str], int] = {
    ("box", "size"): 3, ("cylinder", "radius"): 1, ("cylinder", "length"): 1,
    ("sphere", "radius"): 1, ("mesh", "scale"): 3}


def line_of(text: str, tag: str, name: str) -> int | None:
    r"""1-based line of ``<tag ... name="name"`` in ``text``, or None."""
    match = re.search(rf"<{tag}\b[^>]*\bname\s*=\s*[\"']{re.escape(name)}[\"']", text)
    return text.count("\n", 0, match.start()) + 1 if match else None


def line_within(text: str, tag: str, name: str, child: str) -> int | None:
    r"""1-based line of the first ``<child`` inside ``<tag ... name="name"> … </tag>`` in
    ``text`` (a link's ``<mass>``, ``<inertia>``), else the element's own line, or None."""
    match = re.search(rf"<{tag}\b[^>]*\bname\s*=\s*[\"']{re.escape(name)}[\"']", text)
    if match is None:
        return None
    end = text.find(f"</{tag}>", match.end())
    inner = re.compile(rf"<{child}\b").search(text, match.end(), end if end >= 0 else len(text))
    at = inner.start() if inner else match.start()
    return text.count("\n", 0, at) + 1


def _numbers(value: str, count: int) -> list[float] | None:
    r"""The ``count`` finite decimal numbers of ``value`` of magnitude at most
    :data:`MAX_MODEL_NUMBER`, or None."""
    parts = value.split()
    if len(parts) != count or not all(NUMBER.fullmatch(p) for p in parts):
        return None
    numbers = [float(p) for p in parts]
    if not all(math.isfinite(x) and abs(x) <= MAX_MODEL_NUMBER for x in numbers):
        return None
    return numbers


def _expected(count: int) -> str:
    what = "a finite number" if count == 1 else f"{count} finite numbers"
    return f"expected {what} of magnitude at most {MAX_MODEL_TEXT}"


def _check_numbers(path: Path, line: int | None, owner: str, element: ET.Element,
                   label: str, attribute: str, count: int, signed: bool = True) -> None:
    r"""``element``'s ``attribute``, if given, holds ``count`` numbers (see :func:`_numbers`;
    none negative unless ``signed``); else :class:`InputFileError` naming ``owner``."""
    value = element.get(attribute)
    if value is None:
        return
    numbers = _numbers(value, count)
    if numbers is None:
        raise InputFileError(path, f"{owner}: <{label} {attribute}=\"{value}\">: "
                                   f"{_expected(count)}", line=line)
    if not signed and any(x < 0 for x in numbers):
        raise InputFileError(path, f"{owner}: <{label} {attribute}=\"{value}\">: expected "
                                   "sizes that are not negative", line=line)


def _check_joint(path: Path, text: str, joint: ET.Element) -> None:
    r"""One ``<joint>``: its type, its numbers, its axis, its limit (module docstring)."""
    name = joint.get("name", "")
    line = line_of(text, "joint", name)
    owner = f"joint {name!r}"
    jtype = joint.get("type")
    if jtype not in JOINT_TYPES:
        got = "no type" if jtype is None else f"type {jtype!r}"
        raise InputFileError(path, f"{owner} has {got}; expected one of "
                                   + ", ".join(JOINT_TYPES), line=line)
    for (tag, attribute), count in JOINT_NUMBERS.items():
        for element in joint.findall(tag):
            _check_numbers(path, line, owner, element, tag, attribute, count)
    axis = joint.find("axis")
    if jtype in AXIS_TYPES and axis is not None and axis.get("xyz") is not None and \
            not math.hypot(*(float(x) for x in axis.get("xyz", "").split())) > 0:
        raise InputFileError(path, f"{owner}: <axis xyz=\"{axis.get('xyz')}\">: expected a "
                                   "direction: three finite numbers, not all zero", line=line)
    if jtype in LIMITED_TYPES:
        limit = joint.find("limit")
        missing = ["<limit>"] if limit is None else \
            [a for a in ("effort", "velocity") if limit.get(a) is None]
        if missing:
            raise InputFileError(path, f"{owner} is {jtype} without {' and '.join(missing)}: a "
                                       f"{jtype} joint needs <limit lower=... upper=... "
                                       "effort=... velocity=...> (a wheel that turns without "
                                       "end is type=\"continuous\")", line=line)


def _check_link(path: Path, text: str, link: ET.Element) -> None:
    r"""One ``<link>``: the origins of its inertial, visual and collision elements and the
    sizes of its shapes (module docstring)."""
    name = link.get("name", "")
    line = line_of(text, "link", name)
    owner = f"link {name!r}"
    for part in ("inertial", "visual", "collision"):
        for element in link.findall(part):
            for origin in element.findall("origin"):
                for attribute in ("xyz", "rpy"):
                    _check_numbers(path, line, owner, origin, f"{part}><origin", attribute, 3)
            if part == "inertial":
                continue
            for geometry in element.findall("geometry"):
                for (shape, attribute), count in SHAPE_NUMBERS.items():
                    for element_ in geometry.findall(shape):
                        _check_numbers(path, line, owner, element_, f"{part}><{shape}",
                                       attribute, count, signed=shape == "mesh")


def check_urdf_values(path: str | Path, text: str, root: ET.Element) -> None:
    r"""Check the numbers and joint declarations of a parsed URDF (module docstring); the
    first error found is raised."""
    path = Path(path)
    for joint in root.findall("joint"):
        _check_joint(path, text, joint)
    for link in root.findall("link"):
        _check_link(path, text, link)
