r"""Showing wheeled bodies moving in a browser, with meshcat.

- :class:`Viewer` — a live meshcat scene of a Pinocchio model: meshes or stand-in shapes,
  joint triads, the centre of mass, the ground; ``display``, ``play``, ``animate``,
  ``export_html`` (one self-contained file that plays offline).
- :func:`show_trajectory` — a wheeled model's trajectory to an HTML file or a live URL.
- :func:`fallback_visual_model` — boxes and wheel cylinders for a model without meshes.
- :func:`start_server` / :func:`stop_server` — the meshcat server process, which never
  outlives Python.
"""

import warnings

with warnings.catch_warnings():     # meshcat 0.3.2 imports a module pyzmq deprecates
    warnings.filterwarnings("ignore", message="zmq.eventloop.ioloop is deprecated",
                            category=DeprecationWarning)
    import meshcat.visualizer  # noqa: F401

from .animation import build_animation, resample
from .camera import View, frame_points
from .scene import ScenePoses
from .server import ServerProcess, ViewerError, start_server, stop_server
from .shapes import equivalent_box, fallback_visual_model
from .show import close_all, show_trajectory
from .viewer import Viewer

__all__ = ["Viewer", "ViewerError", "show_trajectory", "close_all", "fallback_visual_model",
           "equivalent_box", "ScenePoses", "View", "frame_points", "resample", "build_animation",
           "ServerProcess", "start_server", "stop_server"]
