r"""Trajectories as meshcat animations.

A trajectory is a strictly increasing sequence of times :math:`t_0 < \dots < t_{N-1}` and the
configurations :math:`q_i` at those times, as a simulation returns them (any step, even
variable). An animation needs key frames at a fixed rate, so the trajectory is resampled at
:math:`\tau_k = t_0 + k\,s/f` (:math:`f` frames per second of wall-clock time, :math:`s` the
playback speed), :math:`k = 0 \dots \lfloor (t_{N-1} - t_0) f / s \rfloor`, with the
configuration between two samples interpolated on the configuration manifold,

.. math::

    q(\tau) = \mathrm{integrate}\big(q_i,\ u\,\mathrm{difference}(q_i, q_{i+1})\big),
    \qquad u = \frac{\tau - t_i}{t_{i+1} - t_i} \quad (\texttt{pin.interpolate}),

which is linear interpolation for the 1-DoF joints of a wheeled model and correct for any other
joint. Each frame records the pose of every moving node (:class:`~.scene.ScenePoses`) as a
position track and a quaternion track; three.js interpolates between frames when playing.
"""

from __future__ import annotations

from collections.abc import Sequence

import meshcat
import meshcat.animation
import numpy as np
import pinocchio as pin

from ..errors import StateError
from .scene import ScenePoses, as_configuration


def as_trajectory(model: pin.Model, times: Sequence[float] | np.ndarray,
                  qs: Sequence[Sequence[float]] | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""``times`` (N,) and ``qs`` (N × nq) as float arrays; raises :class:`StateError` unless the
    times are finite and strictly increasing and there is one configuration per time."""
    t = np.asarray(times, dtype=float)
    if t.ndim != 1 or t.size == 0:
        raise StateError("times", f"array of shape {t.shape}", "a non-empty 1-D sequence")
    if not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
        raise StateError("times", t[:8].tolist(), "finite, strictly increasing times")
    q = np.asarray(qs, dtype=float)
    if q.ndim != 2 or q.shape != (t.size, model.nq):
        raise StateError("qs", f"array of shape {q.shape}",
                         f"shape ({t.size}, {model.nq}): one configuration per time")
    for row in q:
        as_configuration(model, row)
    return t, q


def resample(model: pin.Model, times: Sequence[float] | np.ndarray,
             qs: Sequence[Sequence[float]] | np.ndarray, fps: float = 30.0,
             speed: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    r"""Trajectory times and configurations at the frames of an animation played at ``fps``
    frames per second and ``speed`` × real time (see the module docstring). Returns the frame
    times :math:`\tau_k` (trajectory time, not wall-clock) and the configurations (K × nq)."""
    if not (np.isfinite(fps) and fps > 0):
        raise StateError("fps", fps, "a positive number of frames per second")
    if not (np.isfinite(speed) and speed > 0):
        raise StateError("speed", speed, "a positive playback speed")
    t, q = as_trajectory(model, times, qs)
    n_frames = int(np.floor((t[-1] - t[0]) * fps / speed + 1e-9)) + 1
    tau = t[0] + np.arange(n_frames) * speed / fps
    out = np.empty((n_frames, model.nq))
    idx = np.clip(np.searchsorted(t, tau, side="right") - 1, 0, max(t.size - 2, 0))
    for k, (tk, i) in enumerate(zip(tau, idx)):
        if t.size == 1:
            out[k] = q[0]
            continue
        u = float(np.clip((tk - t[i]) / (t[i + 1] - t[i]), 0.0, 1.0))
        out[k] = pin.interpolate(model, q[i], q[i + 1], u)
    return tau, out


def build_animation(poses: ScenePoses, root: meshcat.Visualizer,
                    times: Sequence[float] | np.ndarray,
                    qs: Sequence[Sequence[float]] | np.ndarray, fps: float = 30.0,
                    speed: float = 1.0) -> meshcat.animation.Animation:
    r"""A ``meshcat.animation.Animation`` of the trajectory: one key frame per resampled
    configuration for every moving node of ``poses`` (paths relative to ``root``)."""
    _, frames = resample(poses.model, times, qs, fps, speed)
    anim = meshcat.animation.Animation(default_framerate=fps)
    for k, q in enumerate(frames):
        with anim.at_frame(root, k) as frame:
            for path, T in poses.poses(q).items():
                frame[path].set_transform(T)
    return anim


def duration(anim: meshcat.animation.Animation) -> float:
    r"""Length of an animation in seconds of wall-clock time (its last key frame / its rate)."""
    longest = 0.0
    for clip in anim.clips.values():
        for track in clip.tracks.values():
            if track.frames:
                longest = max(longest, track.frames[-1] / clip.fps)
    return longest
