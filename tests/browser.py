r"""Driving headless Chromium from tests: screenshots of a page, as numpy arrays.

Two ways to take a screenshot:

- :func:`screenshot` runs ``chromium --headless --screenshot`` with a *virtual time budget*:
  the page's clock (timers, ``requestAnimationFrame``, ``performance.now``) advances by the budget
  as fast as the page allows, fetches pause it, then the picture is taken. Deterministic for a
  self-contained page (an exported meshcat HTML file: everything is inlined); two budgets show
  an animation at two times.
- :func:`screenshot_when_ready` speaks the DevTools protocol over ``--remote-debugging-pipe``
  (JSON messages ending in NUL on file descriptors 3 and 4) and takes the picture once a
  JavaScript expression has been truthy and unchanged for ``settle`` seconds of real time. For a
  page fed over a websocket (a live meshcat viewer), where virtual time runs ahead of the data.

Every Chromium process gets a fresh profile directory and a hard timeout after which it is
killed. The flags are those checked on these machines (``/work/shared/DESIGN.md``).
"""

from __future__ import annotations

import base64
import fcntl
import json
import os
import select
import shutil
import signal
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

INSTALL_HINT = "chromium not installed: apt-get install chromium fonts-dejavu-extra"

FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
         "--disable-quic", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--hide-scrollbars", "--mute-audio")

#: Seconds after which a Chromium process is killed.
TIMEOUT = 90.0


class BrowserError(RuntimeError):
    """Chromium failed, timed out, or the page never became ready."""


def find_chromium() -> str | None:
    r"""The Chromium executable (``/usr/bin/chromium`` or ``chromium`` / ``chromium-browser``
    on PATH), or None."""
    if os.access("/usr/bin/chromium", os.X_OK):
        return "/usr/bin/chromium"
    for name in ("chromium", "chromium-browser"):
        found = shutil.which(name)
        if found:
            return found
    return None


def _command(profile: str, size: tuple[int, int]) -> list[str]:
    exe = find_chromium()
    if exe is None:
        raise BrowserError(INSTALL_HINT)
    return [exe, *FLAGS, f"--user-data-dir={profile}", f"--window-size={size[0]},{size[1]}"]


def _signal_group(proc: subprocess.Popen, sig: int) -> None:
    try:
        os.killpg(proc.pid, sig)     # its own session: the group holds only its helpers
    except ProcessLookupError:
        pass


def _end(proc: subprocess.Popen) -> None:
    r"""End a Chromium started in its own session, and its helper processes with it."""
    if proc.poll() is None:
        _signal_group(proc, signal.SIGTERM)
        try:
            proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            _signal_group(proc, signal.SIGKILL)
            proc.wait(timeout=5)
    _signal_group(proc, signal.SIGKILL)        # helpers still writing to the profile


def screenshot(url: str, out: str | Path, virtual_time_ms: int = 2000,
               size: tuple[int, int] = (800, 600), timeout: float = TIMEOUT) -> Path:
    r"""Screenshot ``url`` after ``virtual_time_ms`` of virtual time into the PNG ``out``."""
    out = Path(out)
    out.unlink(missing_ok=True)
    with tempfile.TemporaryDirectory(prefix="wd-chromium-",
                                     ignore_cleanup_errors=True) as profile:
        cmd = _command(profile, size) + [f"--screenshot={out}",
                                         f"--virtual-time-budget={int(virtual_time_ms)}", url]
        proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, start_new_session=True)
        try:
            log, _ = proc.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            _end(proc)
            raise BrowserError(f"chromium took more than {timeout} s on {url}") from None
        finally:
            _end(proc)
    if proc.returncode != 0 or not out.is_file():
        tail = log.decode("utf-8", "replace")[-2000:]
        raise BrowserError(f"chromium exited with {proc.returncode}, no {out}:\n{tail}")
    return out


class _DevTools:
    """A DevTools-protocol connection over Chromium's debugging pipe."""

    def __init__(self, proc: subprocess.Popen, write_fd: int, read_fd: int, deadline: float):
        self.proc, self.write_fd, self.read_fd, self.deadline = proc, write_fd, read_fd, deadline
        self.buffer = b""
        self.next_id = 0

    def _message(self) -> dict:
        while b"\0" not in self.buffer:
            left = self.deadline - time.monotonic()
            if left <= 0:
                raise BrowserError("chromium did not answer before the deadline")
            ready, _, _ = select.select([self.read_fd], [], [], min(left, 1.0))
            if ready:
                chunk = os.read(self.read_fd, 1 << 20)
                if not chunk:
                    raise BrowserError(f"chromium closed its pipe (exit {self.proc.poll()})")
                self.buffer += chunk
        raw, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(raw)

    def call(self, method: str, session: str | None = None, **params) -> dict:
        self.next_id += 1
        msg: dict = {"id": self.next_id, "method": method, "params": params}
        if session:
            msg["sessionId"] = session
        os.write(self.write_fd, json.dumps(msg).encode() + b"\0")
        while True:
            answer = self._message()
            if answer.get("id") == self.next_id:
                if "error" in answer:
                    raise BrowserError(f"{method}: {answer['error']}")
                return answer.get("result", {})

    def evaluate(self, session: str, expression: str, await_promise: bool = False):
        result = self.call("Runtime.evaluate", session, expression=expression,
                           returnByValue=True, awaitPromise=await_promise)
        if "exceptionDetails" in result:
            raise BrowserError(f"{expression!r} raised {result['exceptionDetails']}")
        return result.get("result", {}).get("value")


def screenshot_when_ready(url: str, out: str | Path, ready_js: str, settle: float = 1.0,
                          size: tuple[int, int] = (800, 600), timeout: float = TIMEOUT) -> Path:
    r"""Load ``url``, wait until ``ready_js`` evaluates to a truthy value that stays the same
    for ``settle`` seconds, let two frames render, and save a PNG screenshot to ``out``."""
    out = Path(out)
    deadline = time.monotonic() + timeout
    to_chrome = os.pipe()
    from_chrome = os.pipe()

    def wire_fds() -> None:       # in the child: Chromium reads fd 3 and writes fd 4
        r = fcntl.fcntl(to_chrome[0], fcntl.F_DUPFD, 10)
        w = fcntl.fcntl(from_chrome[1], fcntl.F_DUPFD, 10)
        os.dup2(r, 3)
        os.dup2(w, 4)

    with tempfile.TemporaryDirectory(prefix="wd-chromium-",
                                     ignore_cleanup_errors=True) as profile:
        cmd = _command(profile, size) + ["--remote-debugging-pipe", "about:blank"]
        proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, pass_fds=(3, 4),
                                preexec_fn=wire_fds, start_new_session=True)
        os.close(to_chrome[0])
        os.close(from_chrome[1])
        try:
            tools = _DevTools(proc, to_chrome[1], from_chrome[0], deadline)
            target = tools.call("Target.createTarget", url="about:blank")["targetId"]
            session = tools.call("Target.attachToTarget", targetId=target,
                                 flatten=True)["sessionId"]
            tools.call("Emulation.setDeviceMetricsOverride", session, width=size[0],
                       height=size[1], deviceScaleFactor=1, mobile=False)
            tools.call("Page.navigate", session, url=url)
            last, since = None, time.monotonic()
            while True:
                value = tools.evaluate(session, ready_js)
                now = time.monotonic()
                if value != last:
                    last, since = value, now
                elif value and now - since >= settle:
                    break
                if now > deadline:
                    raise BrowserError(f"{url}: {ready_js!r} still {value!r} after {timeout} s")
                time.sleep(0.2)
            tools.evaluate(session, "new Promise(r => requestAnimationFrame(() => "
                                    "requestAnimationFrame(() => r(true))))", await_promise=True)
            shot = tools.call("Page.captureScreenshot", session, format="png")
            out.write_bytes(base64.b64decode(shot["data"]))
            try:
                tools.call("Browser.close")
            except BrowserError:
                pass                 # the browser may close its pipe before answering
        finally:
            os.close(to_chrome[1])
            os.close(from_chrome[0])
            _end(proc)
    return out


def read_png(path: str | Path) -> np.ndarray:
    r"""An RGB image (H × W × 3, integers 0–255) from a PNG file."""
    import matplotlib.image

    img = np.asarray(matplotlib.image.imread(str(path)))
    if img.dtype != np.uint8:
        img = np.round(img * 255.0).astype(np.uint8)
    return img[..., :3].astype(np.int16)


def changed_pixels(a: np.ndarray, b: np.ndarray, tolerance: int = 24) -> int:
    r"""Pixels whose colour differs by more than ``tolerance`` (max over channels) between two
    images of the same size."""
    if a.shape != b.shape:
        raise ValueError(f"image sizes differ: {a.shape} and {b.shape}")
    return int(np.count_nonzero(np.max(np.abs(a - b), axis=-1) > tolerance))
