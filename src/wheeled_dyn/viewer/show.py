r"""One call from a trajectory to a picture: :func:`show_trajectory`.

For scenarios and the command line: give a wheeled model (attributes ``model``,
``visual_model``, ``wheels``, ``name``), the times and configurations of a trajectory, and get
either a self-contained HTML file that plays offline (``export=path``) or a live viewer URL
(the server then keeps running until Python ends or :func:`close_all` is called).
"""

from __future__ import annotations

import webbrowser
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .viewer import Viewer

_LIVE: list[Viewer] = []


def show_trajectory(wheeled_model: Any, times: Sequence[float] | np.ndarray,
                    qs: Sequence[Sequence[float]] | np.ndarray, export: Path | str | None = None,
                    open_browser: bool = False, fps: float = 30.0, speed: float = 1.0,
                    repetitions: int = 1, **options: Any) -> str:
    r"""Animate a trajectory of ``wheeled_model``.

    With ``export`` a path, write the animation there as one self-contained HTML file, stop the
    server, and return the file's path (as a string). Without it, leave a live viewer playing the
    animation and return its URL; the viewer is kept alive until :func:`close_all` or the end of
    the Python process. ``open_browser`` opens the file or URL in the default browser.
    ``options`` go to :meth:`Viewer.for_wheeled` (``frames``, ``com``, ``ground``,
    ``azimuth``, ``elevation``).
    """
    viewer = Viewer.for_wheeled(wheeled_model, **options)
    if export is not None:
        with viewer:
            path = viewer.export_html(export, times, qs, fps=fps, speed=speed,
                                      repetitions=repetitions)
        target = str(path.resolve())
        if open_browser:
            webbrowser.open(path.resolve().as_uri(), new=2)
        return target
    try:
        viewer.animate(times, qs, fps=fps, speed=speed, repetitions=repetitions)
    except BaseException:
        viewer.close()
        raise
    _LIVE.append(viewer)
    if open_browser:
        webbrowser.open(viewer.url, new=2)
    return viewer.url


def close_all() -> None:
    r"""Close the live viewers left open by :func:`show_trajectory`."""
    while _LIVE:
        _LIVE.pop().close()
