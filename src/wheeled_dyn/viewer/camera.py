r"""Framing the camera on a set of points.

meshcat's camera is the object ``/Cameras/default/rotated/<object>`` (a three.js perspective
camera, vertical field of view 75°, near 0.01, far 100), below a group ``rotated`` that turns
three.js's y-up into meshcat's z-up (rotation of +90° about x). Its orbit controls always look
at the world origin. Pinocchio's camera helpers call methods meshcat 0.3.2 does not have, so the
view is set with plain transforms and properties:

- the points' bounding box centre :math:`c` is moved to the origin (the scene root gets the
  translation :math:`-c`, see :class:`~wheeled_dyn.viewer.Viewer`);
- ``/Cameras/default`` gets a uniform scale :math:`d`, the viewing distance, so that the near and
  far planes scale with the scene;
- the camera's position, in the ``rotated`` frame and before that scale, is the unit vector of
  the chosen azimuth :math:`\alpha` (from the x axis, about z) and elevation :math:`\epsilon`,
  :math:`(\cos\epsilon\cos\alpha,\ \sin\epsilon,\ -\cos\epsilon\sin\alpha)`
  (world :math:`(x, y, z)` is rotated :math:`(x, z, -y)`).

The distance makes a sphere of radius :math:`r` (half the bounding box diagonal, times
:data:`MARGIN`) fit the vertical field of view: :math:`d = r / \sin(\mathrm{fov}/2)`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: meshcat's default vertical field of view, in degrees.
FIELD_OF_VIEW = 75.0
#: Factor on the bounding radius, room around the framed points.
MARGIN = 1.15
#: Smallest framing radius, in metres.
MIN_RADIUS = 0.1
#: Path of the camera rig and of the camera object.
CAMERA_RIG = "/Cameras/default"
CAMERA_OBJECT = "/Cameras/default/rotated/<object>"


@dataclass(frozen=True)
class View:
    r"""A camera view: the world point looked at, the distance, azimuth and elevation (degrees)."""

    centre: tuple[float, float, float]
    distance: float
    azimuth: float = 35.0
    elevation: float = 25.0

    def rig_transform(self) -> np.ndarray:
        r"""The 4×4 transform of ``/Cameras/default``: a uniform scale by the distance."""
        T = np.eye(4)
        T[:3, :3] *= self.distance
        return T

    def camera_position(self) -> list[float]:
        r"""The camera object's position in the ``rotated`` frame, before the rig's scale."""
        a, e = np.radians(self.azimuth), np.radians(self.elevation)
        return [float(np.cos(e) * np.cos(a)), float(np.sin(e)), float(-np.cos(e) * np.sin(a))]

    def eye(self) -> np.ndarray:
        r"""The camera position in world coordinates."""
        a, e = np.radians(self.azimuth), np.radians(self.elevation)
        direction = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
        return np.asarray(self.centre) + self.distance * direction


def frame_points(points: np.ndarray, azimuth: float = 35.0, elevation: float = 25.0,
                 margin: float = MARGIN, fov: float = FIELD_OF_VIEW) -> View:
    r"""The :class:`View` that keeps every point (k×3) in sight, see the module docstring."""
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre = 0.5 * (lo + hi)
    radius = max(MIN_RADIUS, 0.5 * float(np.linalg.norm(hi - lo))) * margin
    distance = radius / np.sin(np.radians(fov) / 2)
    return View((float(centre[0]), float(centre[1]), float(centre[2])), float(distance), azimuth,
                elevation)


def apply_view(vis, view: View) -> None:
    r"""Send ``view`` to a ``meshcat.Visualizer`` (see the module docstring)."""
    vis[CAMERA_RIG].set_transform(view.rig_transform())
    vis[CAMERA_OBJECT].set_property("position", view.camera_position())
