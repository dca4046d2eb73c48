r"""The meshcat viewer without a browser: its server's lifetime and ports, the poses it sends,
trajectories resampled into animations, and the exported HTML file."""

from __future__ import annotations

import base64
import os
import re
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
import umsgpack

from test_viewer_models import RADIUS, cart_circle, cart_model
from wheeled_dyn.errors import StateError
from wheeled_dyn.viewer import (ScenePoses, Viewer, ViewerError, close_all, fallback_visual_model,
                                resample, show_trajectory, start_server, stop_server)

#: Seconds a server may take to disappear once its Python is gone.
GONE_WITHIN = 10.0
TOL = 1e-12


def _alive(pid: int) -> bool:
    r"""True if process ``pid`` runs (a zombie waiting to be reaped counts as gone)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except FileNotFoundError:
        return False
    except OSError:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return False
        return True
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


def _wait_gone(pid: int, timeout: float = GONE_WITHIN) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if not _alive(pid):
            return True
        time.sleep(0.1)
    return False


def _serves(url: str) -> bool:
    try:
        with urllib.request.urlopen(url, timeout=5) as answer:
            return answer.status == 200 and b"MeshCat" in answer.read()
    except (urllib.error.URLError, ConnectionError):
        return False


def _decoded_commands(html: str) -> list[dict]:
    blobs = re.findall(r'data:application/octet-binary;base64,([A-Za-z0-9+/=]+)"', html)
    return [umsgpack.unpackb(base64.b64decode(b)) for b in blobs]


@pytest.fixture
def cart():
    return cart_model()


# -- the server ---------------------------------------------------------------------------------
def test_close_ends_the_server_process(cart) -> None:
    viewer = Viewer.for_wheeled(cart)
    proc = viewer.server_proc
    assert viewer.vis.window.server_proc is proc
    assert proc.poll() is None and _serves(viewer.url), viewer.url
    viewer.close()
    assert proc.poll() is not None, "server still running after close()"
    assert not _serves(viewer.url), f"{viewer.url} still answers after close()"
    viewer.close()                                   # idempotent
    with pytest.raises(ViewerError, match="closed viewer"):
        viewer.display(np.zeros(cart.model.nq))


def test_context_manager_ends_the_server(cart) -> None:
    with Viewer.for_wheeled(cart) as viewer:
        proc = viewer.server_proc
    assert proc.poll() is not None


def test_two_viewers_at_once_get_different_ports(cart) -> None:
    with Viewer.for_wheeled(cart) as a, Viewer.for_wheeled(cart) as b:
        assert a.port != b.port, (a.url, b.url)
        assert _serves(a.url) and _serves(b.url)


def test_a_port_in_use_moves_to_the_next_free_one(cart) -> None:
    blocker = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    blocker.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)   # as tornado binds
    for port in range(7000, 7100):
        try:
            blocker.bind(("127.0.0.1", port))
            break
        except OSError:
            continue
    else:
        pytest.skip("no free port in 7000-7099 to occupy")
    blocker.listen(1)
    try:
        with Viewer.for_wheeled(cart) as viewer:
            assert viewer.port != port, f"viewer took port {port}, which was held"
            assert viewer.port >= 7000
            assert _serves(viewer.url)
    finally:
        blocker.close()


def _python(code: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def test_the_server_ends_when_python_is_killed() -> None:
    child = _python("import time\nfrom wheeled_dyn.viewer import start_server\n"
                    "s = start_server()\nprint(s.proc.pid, flush=True)\ntime.sleep(120)\n")
    try:
        pid = int(child.stdout.readline())
        assert _alive(pid)
        child.send_signal(signal.SIGKILL)
        child.wait(timeout=10)
        assert _wait_gone(pid), f"server {pid} outlived its killed Python"
    finally:
        if child.poll() is None:
            child.kill()
            child.wait(timeout=10)


def test_the_server_ends_at_exit_without_close() -> None:
    child = _python("import sys\nsys.path.insert(0, %r)\n"
                    "from test_viewer_models import cart_model\n"
                    "from wheeled_dyn.viewer import Viewer\n"
                    "v = Viewer.for_wheeled(cart_model())\n"
                    "print(v.server_proc.pid, flush=True)\n" % str(Path(__file__).parent))
    try:
        out, err = child.communicate(timeout=60)
    finally:
        if child.poll() is None:
            child.kill()
            child.wait(timeout=10)
    assert child.returncode == 0, err
    pid = int(out.split()[0])
    assert _wait_gone(pid, timeout=2.0), f"server {pid} outlived Python's normal exit"


def test_stop_server_is_idempotent() -> None:
    server = start_server()
    stop_server(server)
    stop_server(server)
    stop_server(None)
    assert not server.running


# -- what is sent --------------------------------------------------------------------------------
def test_poses_follow_pinocchio(cart) -> None:
    geom = fallback_visual_model(cart.model, cart.wheels)
    poses = ScenePoses(cart.model, geom, frame_joints=range(1, cart.model.njoints))
    data = cart.model.createData()
    rng = np.random.default_rng(3)
    for _ in range(5):
        q = rng.uniform(-2, 2, cart.model.nq)
        got = poses.poses(q)
        com = pin.centerOfMass(cart.model, data, q)
        np.testing.assert_allclose(got["com"][:3, 3], com, atol=TOL)
        for jid in range(1, cart.model.njoints):
            np.testing.assert_allclose(got[f"frames/{cart.model.names[jid]}"],
                                       data.oMi[jid].homogeneous, atol=TOL)
        wheel = got["visuals/wheel_left_wheel"]
        np.testing.assert_allclose(wheel[2, 3], RADIUS, atol=TOL)   # axle height on the ground


def test_a_bad_configuration_is_a_state_error(cart) -> None:
    poses = ScenePoses(cart.model, fallback_visual_model(cart.model, cart.wheels))
    with pytest.raises(StateError, match="5 numbers"):
        poses.poses(np.zeros(4))
    with pytest.raises(StateError, match="finite"):
        poses.poses(np.full(5, np.nan))


def test_resample_interpolates_at_the_frame_rate(cart) -> None:
    t = np.array([0.0, 0.5, 2.0])
    qs = np.array([np.zeros(5), np.full(5, 1.0), np.full(5, 4.0)])
    tau, frames = resample(cart.model, t, qs, fps=10)
    assert len(tau) == 21
    np.testing.assert_allclose(tau, np.arange(21) / 10, atol=TOL)
    expected = np.interp(tau, t, qs[:, 0])
    np.testing.assert_allclose(frames, np.repeat(expected[:, None], 5, axis=1), atol=1e-12)
    tau2, _ = resample(cart.model, t, qs, fps=10, speed=2.0)
    assert len(tau2) == 11 and tau2[-1] == pytest.approx(2.0)


def test_bad_trajectories_are_state_errors(cart) -> None:
    q = np.zeros((3, 5))
    with pytest.raises(StateError, match="strictly increasing"):
        resample(cart.model, [0.0, 1.0, 1.0], q)
    with pytest.raises(StateError, match="one configuration per time"):
        resample(cart.model, [0.0, 1.0], q)
    with pytest.raises(StateError, match="frames per second"):
        resample(cart.model, [0.0, 1.0, 2.0], q, fps=0)


def test_animation_has_a_key_frame_per_frame_for_every_moving_node(cart) -> None:
    t, qs = cart_circle(duration=1.0)
    with Viewer.for_wheeled(cart) as viewer:
        anim = viewer.animation(t, qs, fps=20)
        paths = {p.lower() for p in anim.clips}
        expected = {f"{viewer.root.path.lower()}/{p}" for p in viewer.poses.paths}
        assert paths == expected
        last = viewer.poses.poses(qs[-1])
        for path, clip in anim.clips.items():
            assert set(clip.tracks) == {"position", "quaternion"}
            assert clip.tracks["position"].frames == list(range(21))
            rel = path.lower()[len(viewer.root.path.lower()) + 1:]
            np.testing.assert_allclose(clip.tracks["position"].values[-1], last[rel][:3, 3],
                                       atol=1e-9)


def test_for_wheeled_skips_the_x0_y0_triads(cart) -> None:
    with Viewer.for_wheeled(cart) as viewer:
        assert viewer.poses.frame_paths == ("frames/psi", "frames/wheel_left",
                                            "frames/wheel_right")


def test_export_html_is_one_self_contained_file_with_the_animation(cart, tmp_path) -> None:
    t, qs = cart_circle(duration=1.0)
    with Viewer.for_wheeled(cart) as viewer:
        out = viewer.export_html(tmp_path / "sub" / "cart.html", t, qs, fps=10)
        root = viewer.root.path.lower()
    html = out.read_text(encoding="utf-8")
    assert "<script src" not in html and "viewer.connect" not in html
    commands = _decoded_commands(html)
    kinds = [c["type"] for c in commands]
    assert kinds.count("set_animation") == 1
    animation = next(c for c in commands if c["type"] == "set_animation")
    animated = {a["path"] for a in animation["animations"]}
    assert f"{root}/visuals/psi_body" in animated and f"{root}/com" in animated
    objects = {c["path"] for c in commands if c["type"] == "set_object"}
    assert f"{root}/visuals/psi_body/shape" in objects
    assert not animated & objects, "an animated node also holds an object"


def test_export_html_needs_times_and_qs_together(cart, tmp_path) -> None:
    with Viewer.for_wheeled(cart) as viewer, pytest.raises(ViewerError, match="both"):
        viewer.export_html(tmp_path / "x.html", times=[0.0, 1.0])


def test_show_trajectory_to_a_file_and_live(cart, tmp_path) -> None:
    t, qs = cart_circle(duration=0.5)
    path = show_trajectory(cart, t, qs, export=tmp_path / "run.html")
    assert Path(path).is_file() and Path(path).stat().st_size > 100_000
    url = show_trajectory(cart, t, qs)
    try:
        assert url.startswith("http://127.0.0.1:") and _serves(url)
    finally:
        close_all()
    assert not _serves(url)


def test_play_keeps_to_the_clock(cart) -> None:
    t, qs = cart_circle(duration=2.0)
    with Viewer.for_wheeled(cart) as viewer:
        start = time.perf_counter()
        viewer.play(t, qs, speed=8.0)
        elapsed = time.perf_counter() - start
    assert 2.0 / 8.0 - 0.05 < elapsed < 5.0, f"played 2 s at 8x in {elapsed:.2f} s"


def test_unknown_frame_joints_are_a_model_error(cart) -> None:
    from wheeled_dyn.errors import ModelError

    with pytest.raises(ModelError, match=r"joint ids \[99\]"):
        Viewer(cart.model, frames=[99])
