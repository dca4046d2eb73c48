r"""The :class:`Viewer`: a Pinocchio model drawn by meshcat in a browser.

.. code-block:: python

    with Viewer(model, visual_model) as viewer:          # starts a meshcat server
        print(viewer.url)                                 # open it in a browser
        viewer.display(q)                                 # one configuration
        viewer.play(times, qs)                            # a trajectory, in real time
        viewer.export_html("run.html", times, qs)         # one file that plays offline

The scene shows the model's visual geometry (meshes through Pinocchio's meshcat loader, or
stand-in boxes and wheel cylinders from :func:`~.shapes.fallback_visual_model` when there is no
visual model), a small triad at each drawn joint frame, a ball at the centre of mass
:math:`c(q)` (``pin.centerOfMass``) and optionally a grid on the ground plane z = 0. The camera
is framed on the model, or on a whole trajectory before it is played (:mod:`.camera`).

The server process (:mod:`.server`) is ended by :meth:`Viewer.close`, by leaving the ``with``
block, when the viewer is garbage collected, at interpreter exit, and by itself if Python is
killed. A viewer never waits for a browser: nothing here calls ``vis.wait()``.
"""

from __future__ import annotations

import functools
import time
import warnings
import weakref
import webbrowser
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, ParamSpec, TypeVar

import meshcat
import meshcat.animation
import numpy as np
import pinocchio as pin
import zmq
from meshcat.visualizer import ViewerWindow
from pinocchio.visualize import MeshcatVisualizer

from ..errors import ModelError
from . import camera, shapes
from .animation import as_trajectory, build_animation, resample
from .scene import SHAPE, ScenePoses, as_configuration, node_name
from .server import ServerProcess, ViewerError, start_server, stop_server

#: Milliseconds the viewer waits for the server to acknowledge one command.
COMMAND_TIMEOUT_MS = 60_000

P = ParamSpec("P")
R = TypeVar("R")


def _answering(method: Callable[P, R]) -> Callable[P, R]:
    """Turn a server that stopped answering into a :class:`ViewerError`."""
    @functools.wraps(method)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        self = args[0]
        if self.closed:  # type: ignore[attr-defined]
            raise ViewerError(f"{method.__name__}() on a closed viewer")
        try:
            return method(*args, **kwargs)
        except zmq.error.Again:
            raise ViewerError(f"the server did not answer within {COMMAND_TIMEOUT_MS} ms "
                              f"(in {method.__name__})") from None
    return wrapper


class _GeometryLoader(MeshcatVisualizer):
    """Pinocchio's meshcat loader, putting each object at ``<group>/<name>/shape``."""

    def getViewerNodeName(self, geometry_object: pin.GeometryObject, geometry_type: Any) -> str:
        return f"{self.viewerVisualGroupName}/{node_name(geometry_object.name)}/{SHAPE}"


def _shutdown(window: ViewerWindow, server: ServerProcess) -> None:
    window.zmq_socket.close(linger=0)
    stop_server(server)


def _grid_step(half_size: float) -> float:
    for step in (0.05, 0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0):
        if half_size / step <= 20:
            return step
    return 20.0


class Viewer:
    r"""A meshcat scene of a Pinocchio model, served to browsers at :attr:`url`.

    ``visual_model`` None (or empty) draws stand-in shapes; ``wheels`` (objects with
    ``joint_id``, ``radius``, ``width``) are then drawn as cylinders. ``frames`` selects the joint
    frames drawn as triads: True for all joints, False for none, or joint ids. ``com`` draws the
    centre-of-mass ball, ``ground`` the grid on z = 0. ``q`` is the configuration shown first
    (neutral by default). ``azimuth`` and ``elevation`` (degrees) orient the camera.
    """

    def __init__(self, model: pin.Model, visual_model: pin.GeometryModel | None = None, *,
                 wheels: Sequence[shapes.WheelLike] = (), name: str | None = None,
                 frames: bool | Sequence[int] = True, com: bool = True, ground: bool = True,
                 q: Sequence[float] | np.ndarray | None = None, azimuth: float = 35.0,
                 elevation: float = 25.0, open_browser: bool = False) -> None:
        if not isinstance(model, pin.Model):
            raise ModelError(str(name), None, f"expected a pinocchio.Model, got {type(model)}")
        self.model = model
        self.name = name or model.name or "model"
        self.azimuth, self.elevation = float(azimuth), float(elevation)
        self.ground = bool(ground)
        if visual_model is None or visual_model.ngeoms == 0:
            visual_model = shapes.fallback_visual_model(model, wheels)
        self.visual_model = visual_model
        if frames is True:
            frame_joints: Sequence[int] = range(1, model.njoints)
        elif frames is False:
            frame_joints = ()
        else:
            frame_joints = [int(j) for j in frames]
            bad = [j for j in frame_joints if not 0 < j < model.njoints]
            if bad:
                raise ModelError(self.name, None,
                                 f"joint ids {bad} are not in 1..{model.njoints - 1}")
        self.poses = ScenePoses(model, visual_model, frame_joints, com)
        self.closed = True
        self._server = start_server()
        window = ViewerWindow.__new__(ViewerWindow)
        window.server_proc, window.zmq_url = self._server.proc, self._server.zmq_url
        window.web_url = self._server.web_url
        window.connect_zmq()
        for option in (zmq.RCVTIMEO, zmq.SNDTIMEO):
            window.zmq_socket.setsockopt(option, COMMAND_TIMEOUT_MS)
        window.zmq_socket.setsockopt(zmq.LINGER, 0)
        self._finalizer = weakref.finalize(self, _shutdown, window, self._server)
        self.closed = False
        self.vis = meshcat.Visualizer(window=window)
        self.root = self.vis[node_name(self.name)]
        try:
            self._build_scene(q)
        except BaseException:
            self.close()
            raise
        if open_browser:
            webbrowser.open(self.url, new=2)

    @classmethod
    def for_wheeled(cls, wheeled: Any, **options: Any) -> "Viewer":
        r"""A viewer of a wheeled model (attributes ``model``, ``visual_model``, ``wheels``,
        ``name``). Its first two joints (x0, y0: prismatic, no body) get no triad unless
        ``frames`` says otherwise."""
        options.setdefault("frames", range(3, wheeled.model.njoints))
        options.setdefault("name", getattr(wheeled, "name", None))
        return cls(wheeled.model, getattr(wheeled, "visual_model", None),
                   wheels=tuple(getattr(wheeled, "wheels", ())), **options)

    # -- properties ---------------------------------------------------------------------------
    @property
    def url(self) -> str:
        r"""The address to open in a browser, e.g. ``http://127.0.0.1:7000/static/``."""
        return self._server.web_url

    @property
    def port(self) -> int:
        r"""The HTTP port of :attr:`url`."""
        return self._server.port

    @property
    def server_proc(self):
        r"""The meshcat server's ``subprocess.Popen`` (also ``vis.window.server_proc``)."""
        return self._server.proc

    # -- scene --------------------------------------------------------------------------------
    @_answering
    def _build_scene(self, q: Sequence[float] | np.ndarray | None) -> None:
        for path in ("/Grid", "/Axes"):            # meshcat's own grid and axes: ours follow
            self.vis[path].set_property("visible", False)      # the framing shift instead
        loader = _GeometryLoader(self.model, None, self.visual_model)
        loader.viewer = self.vis
        loader.viewerVisualGroupName = f"{self.root.path.lower()}/visuals"
        with warnings.catch_warnings():
            warnings.simplefilter("default")
            for g in self.visual_model.geometryObjects:
                loader.loadViewerGeometryObject(g, pin.GeometryType.VISUAL)
                scale = np.asarray(g.meshScale, dtype=float)
                if not np.allclose(scale, 1.0):
                    self.root[f"visuals/{node_name(g.name)}/{SHAPE}"].set_transform(
                        np.diag([*scale, 1.0]))
        size = self.poses.size()
        for path in self.poses.frame_paths:
            self.root[f"{path}/{SHAPE}"].set_object(shapes.triad(min(0.1, 0.06 * size)))
        if self.poses.com:
            self.root[f"{self.poses.com_path}/{SHAPE}"].set_object(
                shapes.ball(min(0.05, max(0.01, 0.03 * size))))
        self.root["world"].set_object(shapes.triad(min(0.3, 0.2 * size)))
        q = pin.neutral(self.model) if q is None else as_configuration(self.model, q)
        self.display(q)
        self.frame([q])

    @_answering
    def display(self, q: Sequence[float] | np.ndarray) -> None:
        r"""Show configuration ``q`` (length ``model.nq``)."""
        for path, T in self.poses.poses(q).items():
            self.root[path].set_transform(T)

    @_answering
    def frame(self, qs: Sequence[Sequence[float] | np.ndarray] | np.ndarray) -> camera.View:
        r"""Aim the camera so that the model stays in view at every configuration of ``qs``,
        resize the ground grid to match, and return the view."""
        pts = np.vstack([self.poses.points(q) for q in qs])
        view = camera.frame_points(pts, self.azimuth, self.elevation)
        shift = np.eye(4)
        shift[:3, 3] = -np.asarray(view.centre)
        self.root.set_transform(shift)
        camera.apply_view(self.vis, view)
        if self.ground:
            reach = np.max(np.abs(pts[:, :2])) + 0.5 * view.distance
            step = _grid_step(reach)
            self.root["ground"].set_object(shapes.ground_grid(np.ceil(reach / step) * step, step))
        return view

    # -- trajectories -------------------------------------------------------------------------
    @_answering
    def play(self, times: Sequence[float] | np.ndarray, qs: Sequence[Sequence[float]] | np.ndarray,
             speed: float = 1.0, fps: float = 30.0) -> None:
        r"""Show a trajectory live at ``speed`` × real time (blocks for its duration / speed).
        Frames that fall behind the clock are skipped; the last one is always shown."""
        _, frames = resample(self.model, times, qs, fps, speed)
        self.frame(frames)
        start = time.perf_counter()
        for k, q in enumerate(frames):
            deadline = start + k / fps
            now = time.perf_counter()
            if k + 1 < len(frames) and now > deadline + 1.0 / fps:
                continue
            if now < deadline:
                time.sleep(deadline - now)
            self.display(q)

    def animation(self, times: Sequence[float] | np.ndarray,
                  qs: Sequence[Sequence[float]] | np.ndarray, fps: float = 30.0,
                  speed: float = 1.0) -> meshcat.animation.Animation:
        r"""The trajectory as a ``meshcat.animation.Animation`` (nothing is sent to the browser;
        see :meth:`animate`)."""
        as_trajectory(self.model, times, qs)
        return build_animation(self.poses, self.root, times, qs, fps, speed)

    @_answering
    def animate(self, times: Sequence[float] | np.ndarray,
                qs: Sequence[Sequence[float]] | np.ndarray, fps: float = 30.0,
                speed: float = 1.0, play: bool = True,
                repetitions: int = 1) -> meshcat.animation.Animation:
        r"""Frame the camera on the trajectory and hand its animation to the browser, which plays
        it (``play``) ``repetitions`` times and offers play/pause and a time slider."""
        t, q = as_trajectory(self.model, times, qs)
        anim = self.animation(t, q, fps, speed)
        self.display(q[0])
        self.frame(q)
        self.vis.set_animation(anim, play=play, repetitions=int(repetitions))
        return anim

    @_answering
    def static_html(self) -> str:
        r"""The current scene (and its animation, if any) as one self-contained HTML page."""
        return self.vis.static_html()

    def export_html(self, path: str | Path, times: Sequence[float] | np.ndarray | None = None,
                    qs: Sequence[Sequence[float]] | np.ndarray | None = None, fps: float = 30.0,
                    speed: float = 1.0, repetitions: int = 1) -> Path:
        r"""Write ONE self-contained HTML file (meshcat's JavaScript, the meshes and the
        animation inlined) that plays offline; with ``times`` and ``qs`` the trajectory is
        animated first (:meth:`animate`). Returns the path written."""
        if (times is None) != (qs is None):
            raise ViewerError("export_html needs both times and qs, or neither")
        if times is not None and qs is not None:
            self.animate(times, qs, fps, speed, play=True, repetitions=repetitions)
        from ..output import write_atomic      # whole or not at all (a full disk, Ctrl-C)
        return write_atomic(path, self.static_html())

    # -- lifetime -----------------------------------------------------------------------------
    def close(self) -> None:
        r"""End the meshcat server (terminate, wait, kill if needed). Idempotent."""
        self.closed = True
        self._finalizer()

    def __enter__(self) -> "Viewer":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        state = "closed" if self.closed else self.url
        return f"<Viewer {self.name!r} ({self.model.nq} coordinates) at {state}>"
