r"""Reading a URDF: validation, inventory of links and joints, wheel radii.

The file is parsed once as XML (so a malformed file is reported with its line and column), then
inspected with :mod:`yourdfpy` (links, joints, geometry). Pinocchio later builds its model from
the same text after one rewrite: ``continuous`` joints become ``revolute`` joints without
limits, so that every wheel angle is one coordinate (Pinocchio would otherwise use the pair
(cos θ, sin θ), which has no Christoffel symbols).
"""

from __future__ import annotations

import io
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import yourdfpy

from ..errors import InputFileError, ModelError, UnknownNameError
from .urdf_checks import check_urdf_tree

#: Limits written for ``continuous`` joints turned ``revolute`` (radians): wheels never reach them.
UNBOUNDED_LIMIT = 1.0e6


@dataclass(frozen=True)
class UrdfSource:
    r"""A URDF file that parsed, with its text and its yourdfpy description."""

    path: Path
    text: str

    @cached_property
    def robot(self) -> yourdfpy.URDF:
        return yourdfpy.URDF.load(io.BytesIO(self.text.encode("utf-8")), build_scene_graph=False,
                                  load_meshes=False, load_collision_meshes=False)

    @property
    def link_names(self) -> tuple[str, ...]:
        return tuple(link.name for link in self.robot.robot.links)

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(j.name for j in self.robot.robot.joints)

    def link(self, name: str) -> yourdfpy.Link:
        for link in self.robot.robot.links:
            if link.name == name:
                return link
        raise UnknownNameError("link", name, self.link_names, where=str(self.path))

    def joint_to(self, child_link: str) -> yourdfpy.Joint:
        """The joint whose child is ``child_link``."""
        self.link(child_link)
        for joint in self.robot.robot.joints:
            if joint.child == child_link:
                return joint
        raise ModelError(self.path.stem, child_link, "this link is the root: it has no joint")

    def root_link(self) -> str:
        children = {j.child for j in self.robot.robot.joints}
        roots = [n for n in self.link_names if n not in children]
        if len(roots) != 1:
            raise InputFileError(self.path, f"expected one root link, found {roots}")
        return roots[0]

    def cylinder(self, link_name: str) -> tuple[float, float] | None:
        r"""(radius, length) of the first cylinder among the link's collision, then visual,
        geometries; None if it has none."""
        link = self.link(link_name)
        for shapes in (link.collisions, link.visuals):
            for shape in shapes:
                cyl = shape.geometry.cylinder if shape.geometry is not None else None
                if cyl is not None:
                    return float(cyl.radius), float(cyl.length)
        return None

    def pinocchio_text(self) -> str:
        r"""The URDF text with ``continuous`` joints rewritten as unlimited ``revolute`` ones."""
        root = ET.fromstring(self.text)
        for joint in root.iter("joint"):
            if joint.get("type") == "continuous":
                joint.set("type", "revolute")
                limit = joint.find("limit")
                if limit is None:
                    limit = ET.SubElement(joint, "limit")
                limit.set("lower", str(-UNBOUNDED_LIMIT))
                limit.set("upper", str(UNBOUNDED_LIMIT))
                limit.set("effort", limit.get("effort", "1e6"))
                limit.set("velocity", limit.get("velocity", "1e6"))
        return ET.tostring(root, encoding="unicode")


def read_urdf(path: str | Path, locked: tuple[str, ...] = (),
              accept_inertia: tuple[str, ...] = ()) -> UrdfSource:
    r"""Read and check a URDF file.

    Raises :class:`InputFileError` if the file is missing, is not well-formed XML (with line and
    column), has no ``<robot>`` root, fails the tree checks of :mod:`.urdf_checks` or is
    rejected by yourdfpy (with its reason); :class:`ModelError` for bad inertial data
    (``locked`` joints count as fixed there, the links of ``accept_inertia`` are not checked).
    """
    path = Path(path)
    if not path.is_file():
        raise InputFileError(path, "no such URDF file")
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputFileError(path, f"cannot read the URDF: {exc}") from None
    try:
        root = ET.fromstring(text)
    except ET.ParseError as exc:
        line, column = exc.position
        raise InputFileError(path, f"malformed XML: {exc.msg if hasattr(exc, 'msg') else exc}",
                             line=line, column=column + 1) from None
    if root.tag != "robot":
        raise InputFileError(path, f"root element is <{root.tag}>, expected <robot>", line=1)
    check_urdf_tree(path, text, root, tuple(locked), tuple(accept_inertia))
    source = UrdfSource(path=path, text=text)
    try:
        _ = source.robot
    except Exception as exc:  # yourdfpy raises assorted types for invalid content
        raise InputFileError(path, f"invalid URDF: {exc}") from None
    for joint in source.robot.robot.joints:
        if joint.parent not in source.link_names or joint.child not in source.link_names:
            raise InputFileError(path, f"joint {joint.name!r} connects unknown links "
                                       f"{joint.parent!r} -> {joint.child!r}")
    return source
