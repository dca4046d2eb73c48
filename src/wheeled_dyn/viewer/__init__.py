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

# meshcat 0.3.2 imports a module pyzmq deprecates; every viewer module that imports meshcat
# is imported after this package, so the filter is in place before meshcat is loaded.
warnings.filterwarnings("ignore", message="zmq.eventloop.ioloop is deprecated",
                        category=DeprecationWarning)

from .._lazy import attach  # noqa: E402

__getattr__, __dir__, __all__ = attach(__name__, {
    "build_animation": ".animation", "resample": ".animation",
    "View": ".camera", "frame_points": ".camera",
    "ScenePoses": ".scene",
    "ServerProcess": ".server", "ViewerError": ".server", "start_server": ".server",
    "stop_server": ".server",
    "equivalent_box": ".shapes", "fallback_visual_model": ".shapes",
    "close_all": ".show", "show_trajectory": ".show",
    "Viewer": ".viewer",
})
