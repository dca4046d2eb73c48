r"""The visual geometry of a URDF, as Pinocchio reads it for the viewer.

The dynamics do not use meshes (a link's inertia is in its ``<inertial>``), so a mesh file
that cannot be found must not stop a check: it is left out of the visual geometry with one
:class:`~wheeled_dyn.errors.ModelWarning` naming the mesh, its link and the URDF, and the
model is built without it. Any other failure to read the geometry is a
:class:`~wheeled_dyn.errors.ModelError` naming the URDF.
"""

from __future__ import annotations

import re
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from pathlib import Path

import pinocchio as pin

from ..errors import ModelError, ModelWarning
from .urdf_source import UrdfSource

#: How Pinocchio says a mesh file is missing.
_MISSING_MESH = re.compile(r"Mesh (.+) could not be found")


def visual_geometry(source: UrdfSource, name: str, package_dirs: Sequence[str],
                    model: pin.Model, text: str) -> pin.GeometryModel:
    r"""The URDF's visual geometry. A mesh file that cannot be found is left out with one
    :class:`~wheeled_dyn.errors.ModelWarning` naming it, its link and the URDF (the dynamics
    do not need meshes: only the viewer shows them)."""
    dropped: set[str] = set()
    for mesh in _absent_files(text):    # Pinocchio tries to load these and fails otherwise
        dropped.add(mesh)
        text = _dropped(text, mesh, name, source)
    while True:
        try:
            return pin.buildGeomFromUrdfString(model, text, pin.GeometryType.VISUAL,
                                               package_dirs=list(package_dirs))
        except ValueError as exc:
            found = _MISSING_MESH.search(str(exc))
            if found is None or found.group(1) in dropped:
                raise ModelError(name, None, f"{source.path}: the visual geometry "
                                 f"cannot be read ({' '.join(str(exc).split())})") from None
            mesh = found.group(1)
            dropped.add(mesh)
            text = _dropped(text, mesh, name, source)


def _dropped(text: str, mesh: str, name: str, source: UrdfSource) -> str:
    r"""``text`` without the visuals of ``mesh``, with one warning naming it."""
    text, links = _without_mesh(text, mesh)
    warnings.warn(ModelWarning(
        f"model {name}: mesh {mesh!r} (link {', '.join(links) or '?'}, "
        f"{source.path}) not found; the model is built without it (the dynamics do "
        "not use meshes; the viewer does not show it)"), stacklevel=3)
    return text


def _absent_files(text: str) -> list[str]:
    r"""The visual meshes given as absolute paths or ``file://`` addresses that are not
    there (``package://`` and relative ones Pinocchio resolves, and says when it cannot)."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError:
        return []                         # the URDF's own reader says what is wrong
    out = []
    for mesh in root.iterfind("link/visual/geometry/mesh"):
        filename = mesh.get("filename", "")
        path = filename[len("file://"):] if filename.startswith("file://") else filename
        if path.startswith("/") and not Path(path).is_file() and filename not in out:
            out.append(filename)
    return out


def _without_mesh(text: str, mesh: str) -> tuple[str, list[str]]:
    r"""``text`` without the ``<visual>`` elements whose mesh is ``mesh``, and their links."""
    root = ET.fromstring(text)
    links = []
    for link in root.findall("link"):
        for visual in list(link.findall("visual")):
            found = visual.find("geometry/mesh")
            if found is not None and found.get("filename") == mesh:
                link.remove(visual)
                links.append(link.get("name", "?"))
    return ET.tostring(root, encoding="unicode"), links


__all__ = ["visual_geometry"]
