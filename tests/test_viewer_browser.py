r"""The viewer in a real browser (headless Chromium): the model is drawn, the exported animation
moves.

"Drawn" is measured against the same page with the model's visual geometry hidden (the
triads, the centre-of-mass ball and the ground stay): the pixels that differ are the model's.
This holds whatever meshcat's background gradient and grid look like. Set
``WHEELED_DYN_SCREENSHOTS=<dir>`` to keep the pictures for a look.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from browser import (INSTALL_HINT, changed_pixels, find_chromium, read_png, screenshot,
                     screenshot_when_ready)
from test_viewer_models import cart_circle, cart_model, tiago_models
from wheeled_dyn.viewer import Viewer
from wheeled_dyn.viewer.shapes import COM_COLOR

pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(find_chromium() is None, reason=INSTALL_HINT)]

SIZE = (800, 600)
#: meshcat's page has received every message once this count stops changing.
MESHCAT_READY = "typeof viewer === 'object' ? viewer.num_messages_received : 0"
#: Smallest share of the picture the model must cover.
MIN_MODEL_SHARE = {"tiago": 0.05, "cart": 0.01}
#: Smallest share of the picture that must change between two times of the animation.
MIN_MOTION_SHARE = 0.005
#: Largest difference of the colour ratios G/R, B/R to the ball's for a pixel to count as it.
COM_RATIO_TOL = 0.12
#: Smallest number of pixels of the centre-of-mass ball, framed on the model / on a trajectory.
MIN_COM_PIXELS = 30
MIN_COM_PIXELS_FAR = 8
#: Virtual milliseconds at which the exported animation is pictured.
EARLY_MS, LATE_MS = 100, 1500


def _keep(path: Path) -> None:
    target = os.environ.get("WHEELED_DYN_SCREENSHOTS")
    if target:
        Path(target).mkdir(parents=True, exist_ok=True)
        shutil.copy(path, Path(target) / path.name)


def _shot_shown_and_hidden(viewer: Viewer, tmp_path: Path) -> tuple[np.ndarray, np.ndarray]:
    shown = screenshot_when_ready(viewer.url, tmp_path / f"{viewer.name}_live.png",
                                  MESHCAT_READY, size=SIZE)
    viewer.root["visuals"].set_property("visible", False)
    hidden = screenshot_when_ready(viewer.url, tmp_path / f"{viewer.name}_live_hidden.png",
                                   MESHCAT_READY, size=SIZE)
    _keep(shown)
    _keep(hidden)
    return read_png(shown), read_png(hidden)


def _com_pixels(img: np.ndarray) -> int:
    r"""Pixels of the centre-of-mass ball's hue: shading scales its colour's channels alike, so
    the ratios G/R and B/R of :data:`COM_COLOR` are kept (within :data:`COM_RATIO_TOL`)."""
    red, green, blue = (float((COM_COLOR >> s) & 255) for s in (16, 8, 0))
    r, g, b = (img[..., i].astype(float) for i in range(3))
    lit = r > 0.4 * red
    hue = (np.abs(g / np.maximum(r, 1) - green / red) < COM_RATIO_TOL) & (
        np.abs(b / np.maximum(r, 1) - blue / red) < COM_RATIO_TOL)
    return int(np.count_nonzero(lit & hue))


def test_live_viewer_draws_tiago_meshes(tmp_path: Path) -> None:
    model, visual = tiago_models()
    with Viewer(model, visual, name="tiago") as viewer:
        shown, hidden = _shot_shown_and_hidden(viewer, tmp_path)
    assert shown.shape == (SIZE[1], SIZE[0], 3)
    share = changed_pixels(shown, hidden) / (SIZE[0] * SIZE[1])
    assert share > MIN_MODEL_SHARE["tiago"], f"TIAGo covers only {share:.1%} of the picture"


def test_live_viewer_draws_stand_in_shapes_and_the_centre_of_mass(tmp_path: Path) -> None:
    with Viewer.for_wheeled(cart_model()) as viewer:
        shown, hidden = _shot_shown_and_hidden(viewer, tmp_path)
    share = changed_pixels(shown, hidden) / (SIZE[0] * SIZE[1])
    assert share > MIN_MODEL_SHARE["cart"], f"the cart covers only {share:.1%} of the picture"
    # the ball is drawn on top of the body, so it shows in both pictures
    assert _com_pixels(shown) > MIN_COM_PIXELS and _com_pixels(hidden) > MIN_COM_PIXELS, \
        "no centre-of-mass ball"


def test_exported_animation_plays_offline(tmp_path: Path) -> None:
    times, qs = cart_circle(duration=2.0)
    with Viewer.for_wheeled(cart_model()) as viewer:
        page = viewer.export_html(tmp_path / "cart.html", times, qs)
    # the server is gone: whatever the browser shows comes from the file alone
    early = screenshot(page.as_uri(), tmp_path / "cart_early.png", EARLY_MS, size=SIZE)
    late = screenshot(page.as_uri(), tmp_path / "cart_late.png", LATE_MS, size=SIZE)
    _keep(early)
    _keep(late)
    a, b = read_png(early), read_png(late)
    # framed on the whole trajectory, the ball is a few pixels across (drawn on top of the body)
    assert min(_com_pixels(a), _com_pixels(b)) > MIN_COM_PIXELS_FAR, \
        "the exported page shows no centre of mass"
    share = changed_pixels(a, b) / (SIZE[0] * SIZE[1])
    assert share > MIN_MOTION_SHARE, (f"only {share:.2%} of the picture changed between "
                                      f"{EARLY_MS} and {LATE_MS} ms: the cart did not move")
