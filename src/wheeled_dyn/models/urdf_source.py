r"""Reading a URDF: validation, inventory of links and joints, wheel radii.

The file is parsed once as XML (so a malformed file is reported with its line and column), then
inspected with :mod:`yourdfpy` (links, joints, geometry), whose outline of the file is kept in
the disk cache (:mod:`wheeled_dyn.disk_cache`) so that a file read before is not inspected
again. Pinocchio later builds its model from
the same text after one rewrite: ``continuous`` joints become ``revolute`` joints without
limits, so that every wheel angle is one coordinate (Pinocchio would otherwise use the pair
(cos θ, sin θ), which has no Christoffel symbols).
"""

from __future__ import annotations

import hashlib
import importlib.util
import io
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from ..disk_cache import cache_root, load, store
from ..errors import InputFileError, ModelError, UnknownNameError
from .conventions import TENSOR_ENTRIES, inertia_tensor, inertial_rotation, right_angles
from .urdf_checks import check_urdf_tree
from .urdf_values import check_urdf_values

#: Limits written for ``continuous`` joints turned ``revolute`` (radians): wheels never reach them.
UNBOUNDED_LIMIT = 1.0e6
#: Version of :class:`UrdfOutline`: entries of another version are not read.
OUTLINE_VERSION = "2"


@dataclass(frozen=True)
class JointInfo:
    r"""A joint of a URDF as yourdfpy reads it: name, type, parent and child links."""

    name: str
    type: str
    parent: str
    child: str


@dataclass(frozen=True)
class UrdfOutline:
    r"""What the builder needs of a URDF beyond Pinocchio's model: its links, its joints and
    each link's first cylinder (collision, then visual geometry) as (link, radius, length,
    centre, axis), its centre and axis in the link's frame."""

    links: tuple[str, ...]
    joints: tuple[JointInfo, ...]
    cylinders: tuple[tuple[str, float, float, tuple[float, ...], tuple[float, ...]], ...]


def _outline(path: Path, text: str) -> UrdfOutline:
    r"""The outline of a URDF text, read with :mod:`yourdfpy` (which also rejects what it
    cannot read, as :class:`InputFileError` naming ``path``) and kept in the disk cache
    (``urdf/``), keyed by the text, yourdfpy's version and this code: a file read before is
    not parsed again, and yourdfpy is then not even imported."""
    key = hashlib.sha256(f"{_reader_digest()}\0{text}".encode()).hexdigest()
    entry = cache_root() / "urdf" / f"{key}.pickle"
    cached = load(entry, UrdfOutline)
    if cached is not None:
        return cached
    import yourdfpy
    try:
        robot = yourdfpy.URDF.load(io.BytesIO(text.encode("utf-8")), build_scene_graph=False,
                                   load_meshes=False, load_collision_meshes=False).robot
    except Exception as exc:  # yourdfpy raises assorted types for invalid content
        raise InputFileError(path, f"invalid URDF: {exc}") from None
    cylinders = []
    for link in robot.links:
        shapes = [s for group in (link.collisions, link.visuals) for s in group
                  if s.geometry is not None and s.geometry.cylinder is not None]
        if shapes:
            cyl = shapes[0].geometry.cylinder
            origin = np.eye(4) if shapes[0].origin is None else np.asarray(shapes[0].origin)
            cylinders.append((link.name, float(cyl.radius), float(cyl.length),
                              tuple(float(x) for x in origin[:3, 3]),
                              tuple(float(x) for x in origin[:3, 2])))
    outline = UrdfOutline(tuple(link.name for link in robot.links),
                          tuple(JointInfo(j.name, j.type, j.parent, j.child)
                                for j in robot.joints), tuple(cylinders))
    store(entry, outline)               # best effort: a cache that cannot be written is slower
    return outline


@lru_cache(maxsize=1)
def _reader_digest() -> str:
    r"""What an outline depends on besides the text: :data:`OUTLINE_VERSION`, yourdfpy's
    reader (its ``urdf.py``, found without importing yourdfpy) and this module's code."""
    h = hashlib.sha256(f"{OUTLINE_VERSION}\0".encode())
    spec = importlib.util.find_spec("yourdfpy")   # a dependency: None only if uninstalled
    h.update(b"-" if spec is None or spec.origin is None
             else Path(spec.origin).with_name("urdf.py").read_bytes())
    h.update(Path(__file__).read_bytes())
    return h.hexdigest()


@dataclass(frozen=True)
class UrdfSource:
    r"""A URDF file that parsed, with its text and its :class:`UrdfOutline`."""

    path: Path
    text: str
    outline: UrdfOutline

    @property
    def link_names(self) -> tuple[str, ...]:
        return self.outline.links

    @property
    def joint_names(self) -> tuple[str, ...]:
        return tuple(j.name for j in self.outline.joints)

    def link(self, name: str) -> str:
        r"""``name`` if it is a link of the file, else :class:`UnknownNameError`."""
        if name not in self.outline.links:
            raise UnknownNameError("link", name, self.link_names, where=str(self.path))
        return name

    def joint_to(self, child_link: str) -> JointInfo:
        """The joint whose child is ``child_link``."""
        self.link(child_link)
        for joint in self.outline.joints:
            if joint.child == child_link:
                return joint
        raise ModelError(self.path.stem, child_link, "this link is the root: it has no joint")

    def root_link(self) -> str:
        children = {j.child for j in self.outline.joints}
        roots = [n for n in self.link_names if n not in children]
        if len(roots) != 1:
            raise InputFileError(self.path, f"expected one root link, found {roots}")
        return roots[0]

    def cylinder(self, link_name: str) -> tuple[float, float] | None:
        r"""(radius, length) of the first cylinder among the link's collision, then visual,
        geometries; None if it has none."""
        self.link(link_name)
        return next(((r, length) for name, r, length, _, _ in self.outline.cylinders
                     if name == link_name), None)

    def cylinder_placement(self, link_name: str) -> tuple[np.ndarray, np.ndarray] | None:
        r"""(centre, axis) of the cylinder :meth:`cylinder` reads, in the link's frame; None
        if it has none."""
        self.link(link_name)
        return next(((np.array(c), np.array(a)) for name, _, _, c, a in self.outline.cylinders
                     if name == link_name), None)

    def pinocchio_text(self) -> str:
        r"""The URDF text with ``continuous`` joints rewritten as unlimited ``revolute`` ones,
        and the ``<inertial>`` orientations within a rounding of right angles made right
        angles (:func:`~.conventions.right_angles`): where all three are, the tensor is
        written in the link's axes, turned exactly (:func:`_turned_exactly`)."""
        root = ET.fromstring(self.text)
        for inertial in root.iterfind("link/inertial"):
            origin = inertial.find("origin")
            if origin is not None and origin.get("rpy") is not None:
                rpy = np.array([float(x) for x in origin.get("rpy", "").split()])
                origin.set("rpy", " ".join(repr(float(x)) for x in right_angles(rpy)))
                _turned_exactly(inertial, origin, inertial_rotation(rpy))
        for joint in root.findall("joint"):
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


def _turned_exactly(inertial: ET.Element, origin: ET.Element, R: np.ndarray) -> None:
    r"""Where ``R`` is a signed permutation (an ``<inertial>`` turned by right angles), its
    ``<inertia>`` written as :math:`R I R^T` in the link's axes and its ``rpy`` as zeros: the
    same tensor, exact (a signed permutation only moves and negates its entries)."""
    tensor = inertial.find("inertia")
    if tensor is None or not np.array_equal(R, np.rint(R)):
        return
    turned = R @ inertia_tensor(tensor) @ R.T
    for key, (r, c) in TENSOR_ENTRIES.items():
        tensor.set(key, repr(float(turned[r, c])))
    origin.set("rpy", "0 0 0")


def check_link_names(path: Path, names: tuple[str, ...], where: str) -> None:
    r"""Every one of ``names`` is a link of the URDF at ``path`` (read once before: it parses);
    else :class:`UnknownNameError` naming ``where`` (an option, a key) and the links."""
    links = [el.get("name", "") for el in ET.parse(path).getroot().findall("link")]
    for name in names:
        if name not in links:
            raise UnknownNameError("link", name, links, where=f"{path}: {where}")


def _not_xacro(path: Path, text: str, root: ET.Element) -> None:
    r"""An :class:`InputFileError` for a xacro source given as a URDF (a ``<xacro:...>``
    element, or ``${...}`` or ``$(...)`` in an attribute): read as it stands, its macros were
    left out and a robot of one link was built without a word."""
    macro = next((el for el in root.iter() if isinstance(el.tag, str) and el.tag.startswith(
        "{http://www.ros.org/wiki/xacro}")), None)
    if macro is not None:
        what, fragment = f"<xacro:{macro.tag.split('}')[1]}>", "<xacro:"
    else:
        found = next((v for el in root.iter() for v in el.attrib.values()
                      if "${" in v or "$(" in v), None)
        if found is None:
            return
        what, fragment = f'"{found}"', found
    at = text.find(fragment)
    raise InputFileError(path, f"a xacro source ({what}), not a URDF: expand it first "
                               "(xacro robot.urdf.xacro > robot.urdf)",
                         line=None if at < 0 else text.count("\n", 0, at) + 1)


def read_urdf(path: str | Path, locked: tuple[str, ...] = (),
              accept_inertia: tuple[str, ...] = ()) -> UrdfSource:
    r"""Read and check a URDF file.

    Raises :class:`InputFileError` if the file is missing, is not well-formed XML (with line and
    column), has no ``<robot>`` root, fails the tree checks of :mod:`.urdf_checks` or the checks
    of its numbers and joints of :mod:`.urdf_values`, or is rejected by yourdfpy (with its
    reason); :class:`ModelError` for bad inertial data
    (``locked`` joints count as fixed there, the links of ``accept_inertia`` are not checked).
    """
    path = Path(path)
    if not path.is_file():
        raise InputFileError(path, "is a folder, FIFO or device, not a URDF file"
                             if path.exists() else "no such URDF file")
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
    _not_xacro(path, text, root)
    check_urdf_tree(path, text, root, tuple(locked), tuple(accept_inertia))
    check_urdf_values(path, text, root)
    source = UrdfSource(path=path, text=text, outline=_outline(path, text))
    for joint in source.outline.joints:
        if joint.parent not in source.link_names or joint.child not in source.link_names:
            raise InputFileError(path, f"joint {joint.name!r} connects unknown links "
                                       f"{joint.parent!r} -> {joint.child!r}")
    return source
