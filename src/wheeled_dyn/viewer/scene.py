r"""Where everything drawn is, for a configuration q: the scene's node paths and their poses.

The scene is a tree of meshcat nodes under one root. Every moving thing is a *group* node that
only ever receives transforms, with its drawable object one level below it (``.../shape``):

.. code-block:: text

    <root>/visuals/<geometry name>          pose oMg(q) of the geometry object
    <root>/visuals/<geometry name>/shape    the mesh or primitive, scaled by its meshScale
    <root>/frames/<joint name>              pose oMi(q) of the joint frame
    <root>/frames/<joint name>/shape        a triad
    <root>/com                              translation to the centre of mass c(q)
    <root>/com/shape                        a ball

Keeping objects off the animated nodes matters for exported HTML: meshcat writes the
animation command *before* the objects, and a ``set_object`` on an animated node would replace
the very object the animation was bound to.

:class:`ScenePoses` computes the poses with Pinocchio (``forwardKinematics``,
``updateGeometryPlacements``, ``centerOfMass``) and the points that must stay in view
(:meth:`ScenePoses.points`) for framing the camera.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
import pinocchio as pin

from ..errors import StateError

#: Name of the child node that holds a drawable object.
SHAPE = "shape"


def node_name(name: str) -> str:
    r"""A meshcat path element for ``name`` (``/`` would start a new path level)."""
    return name.replace("/", "_") or "_"


def as_configuration(model: pin.Model, q: Iterable[float] | np.ndarray) -> np.ndarray:
    r"""``q`` as a float vector of length ``model.nq``; raises :class:`StateError` otherwise."""
    arr = np.asarray(q, dtype=float)
    if arr.shape != (model.nq,):
        raise StateError(None, f"array of shape {arr.shape}",
                         f"a configuration of {model.nq} numbers for model {model.name!r}")
    if not np.all(np.isfinite(arr)):
        raise StateError(None, arr.tolist(), "finite numbers")
    return arr


def _aabb_corners(geometry_object: pin.GeometryObject) -> np.ndarray:
    r"""The 8 corners (8×3) of a geometry's bounding box in its own frame (coal's local AABB,
    meshes included), or its origin alone (1×3) for a geometry without one."""
    geom = geometry_object.geometry
    try:
        geom.computeLocalAABB()
        lo, hi = np.asarray(geom.aabb_local.min_), np.asarray(geom.aabb_local.max_)
    except (AttributeError, RuntimeError):       # a geometry type coal cannot bound
        return np.zeros((1, 3))
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):    # planes, half-spaces
        return np.zeros((1, 3))
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                     for z in (lo[2], hi[2])])


class ScenePoses:
    r"""The poses of the scene's moving nodes (paths relative to the scene root) as functions
    of q, for a Pinocchio model, its visual model and the joints whose frames are drawn."""

    def __init__(self, model: pin.Model, visual_model: pin.GeometryModel,
                 frame_joints: Sequence[int] = (), com: bool = True) -> None:
        self.model = model
        self.visual_model = visual_model
        self.frame_joints = tuple(int(j) for j in frame_joints)
        self.com = com
        self.data = model.createData()
        self.visual_data = pin.GeometryData(visual_model)
        names = [node_name(g.name) for g in visual_model.geometryObjects]
        self.visual_paths = tuple(f"visuals/{n}" for n in names)
        self.frame_paths = tuple(f"frames/{node_name(model.names[j])}" for j in self.frame_joints)
        self.com_path = "com"
        self.corners = tuple(_aabb_corners(g) for g in visual_model.geometryObjects)

    @property
    def paths(self) -> tuple[str, ...]:
        r"""Every moving node, in the order :meth:`poses` gives them."""
        return self.visual_paths + self.frame_paths + ((self.com_path,) if self.com else ())

    def _update(self, q: np.ndarray) -> np.ndarray:
        com = pin.centerOfMass(self.model, self.data, q)       # also runs forwardKinematics
        pin.updateGeometryPlacements(self.model, self.data, self.visual_model, self.visual_data)
        return np.asarray(com, dtype=float).copy()

    def poses(self, q: Iterable[float] | np.ndarray) -> dict[str, np.ndarray]:
        r"""Path → 4×4 homogeneous pose in the world frame, for configuration ``q``."""
        q = as_configuration(self.model, q)
        com = self._update(q)
        out: dict[str, np.ndarray] = {}
        for path, M in zip(self.visual_paths, self.visual_data.oMg):
            out[path] = M.homogeneous.copy()
        for path, jid in zip(self.frame_paths, self.frame_joints):
            out[path] = self.data.oMi[jid].homogeneous.copy()
        if self.com:
            T = np.eye(4)
            T[:3, 3] = com
            out[self.com_path] = T
        return out

    def points(self, q: Iterable[float] | np.ndarray) -> np.ndarray:
        r"""Points (k×3) that should be in view at ``q``: joint origins, the corners of each
        geometry's bounding box (or its origin) and the centre of mass."""
        q = as_configuration(self.model, q)
        com = self._update(q)
        pts = [M.translation for M in self.data.oMi[1:]]
        for M, corners in zip(self.visual_data.oMg, self.corners):
            pts.extend(corners @ M.rotation.T + M.translation)
        pts.append(com)
        return np.array(pts, dtype=float).reshape(-1, 3)

    def size(self) -> float:
        r"""A length scale of the model (metres): the largest extent of :meth:`points` at the
        neutral configuration, at least 0.1."""
        pts = self.points(pin.neutral(self.model))
        return max(0.1, float(np.max(np.ptp(pts, axis=0))))
