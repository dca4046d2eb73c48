r"""The meshcat server process: started on a free port, never outliving Python.

``meshcat.Visualizer()`` starts its server (``meshcat.servers.zmqserver``) as a subprocess in a
new session, reads its two address lines from a pipe and registers an ``atexit`` kill. Three
things are not enough for us there: the server's stderr is a pipe nobody reads (a chatty server
would eventually block on it), a Python process that is killed (SIGKILL, a crashed test worker)
leaves the server running forever, and a hung start blocks forever. So this module starts the
same server with a small bootstrap that

- binds the ZeroMQ port (from 6000) and the HTTP port (from 7000), each moving to the next free
  port when one is taken (meshcat's own ``find_available_port``: a port held by any other
  process raises ``OSError`` on ``listen`` and the next one is tried);
- prints the two addresses, then sends its own stdout to ``/dev/null``;
- watches its parent: when the Python process that started it is gone (its parent pid changes)
  it exits at once.

:func:`start_server` returns a :class:`ServerProcess`; :func:`stop_server` terminates it (then
kills it if it does not end within a timeout). The :class:`~wheeled_dyn.viewer.Viewer` ends it on
``close()``, on garbage collection and at interpreter exit.
"""

from __future__ import annotations

import os
import queue
import subprocess
import sys
import tempfile
import threading
from dataclasses import dataclass

from ..errors import WheeledDynError

#: Seconds to wait for the server to print its addresses.
START_TIMEOUT = 30.0
#: Seconds to wait for the server to end after SIGTERM before SIGKILL.
STOP_TIMEOUT = 5.0
#: Seconds between two checks of the parent process by the server's watchdog.
WATCHDOG_PERIOD = 0.5

_BOOTSTRAP = r"""
import os, sys, threading, time
parent = int(sys.argv[1])
period = float(sys.argv[2])
def watchdog():
    while True:
        if os.getppid() != parent:
            os._exit(0)
        time.sleep(period)
threading.Thread(target=watchdog, daemon=True).start()
from meshcat.servers.zmqserver import ZMQWebSocketBridge
bridge = ZMQWebSocketBridge()
print("zmq_url=" + bridge.zmq_url, flush=True)
print("web_url=" + bridge.web_url, flush=True)
devnull = os.open(os.devnull, os.O_WRONLY)
os.dup2(devnull, 1)
sys.stdout = open(os.devnull, "w")
try:
    bridge.run()
except KeyboardInterrupt:
    pass
"""


class ViewerError(WheeledDynError):
    r"""The viewer cannot do what was asked: its server did not start or stopped answering.

    Attributes: ``reason``, ``log`` (the server's stderr, possibly empty).
    """

    def __init__(self, reason: str, log: str = "") -> None:
        self.reason = reason
        self.log = log
        tail = f"\nserver log:\n{log.strip()}" if log.strip() else ""
        super().__init__(f"meshcat viewer: {reason}{tail}")


@dataclass
class ServerProcess:
    r"""A running meshcat server: its process, ZeroMQ address and web address."""

    proc: subprocess.Popen
    zmq_url: str
    web_url: str

    @property
    def port(self) -> int:
        r"""The HTTP port the browser connects to."""
        return int(self.web_url.rsplit(":", 1)[1].split("/", 1)[0])

    @property
    def running(self) -> bool:
        return self.proc.poll() is None


def _read_log(log) -> str:
    try:
        log.seek(0)
        return log.read().decode("utf-8", "replace")
    except (OSError, ValueError):
        return ""


def start_server(timeout: float = START_TIMEOUT) -> ServerProcess:
    r"""Start a meshcat server on the first free ports from 6000 (ZeroMQ) and 7000 (HTTP).

    The server needs no display. It ends by itself when this Python process ends, however it
    ends; call :func:`stop_server` to end it earlier. Raises :class:`ViewerError` if it does not
    print its addresses within ``timeout`` seconds.
    """
    log = tempfile.TemporaryFile()
    env = dict(os.environ)
    import meshcat

    meshcat_root = os.path.dirname(os.path.dirname(os.path.abspath(meshcat.__file__)))
    env["PYTHONPATH"] = os.pathsep.join(p for p in (meshcat_root, env.get("PYTHONPATH")) if p)
    args = [sys.executable, "-u", "-c", _BOOTSTRAP, str(os.getpid()), str(WATCHDOG_PERIOD)]
    proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=log,
                            env=env, start_new_session=True)
    lines: queue.Queue[str | None] = queue.Queue()

    def reader() -> None:
        for raw in proc.stdout or ():
            lines.put(raw.decode("utf-8", "replace").strip())
        lines.put(None)

    threading.Thread(target=reader, daemon=True, name="meshcat-server-stdout").start()
    urls: dict[str, str] = {}
    try:
        while len(urls) < 2:
            line = lines.get(timeout=timeout)
            if line is None:
                proc.wait(timeout=STOP_TIMEOUT)
                raise ViewerError(f"the server exited with code {proc.returncode} before "
                                  "printing its addresses", _read_log(log))
            key, sep, value = line.partition("=")
            if sep and key in ("zmq_url", "web_url"):
                urls[key] = value
    except queue.Empty:
        _stop(proc)
        raise ViewerError(f"the server printed no address within {timeout} s",
                          _read_log(log)) from None
    except BaseException:
        _stop(proc)
        raise
    return ServerProcess(proc, urls["zmq_url"], urls["web_url"])


def _stop(proc: subprocess.Popen, timeout: float = STOP_TIMEOUT) -> None:
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=timeout)
    if proc.stdout is not None:
        proc.stdout.close()


def stop_server(server: ServerProcess | subprocess.Popen | None,
                timeout: float = STOP_TIMEOUT) -> None:
    r"""End a server: SIGTERM, wait up to ``timeout`` seconds, then SIGKILL. Idempotent; accepts
    a :class:`ServerProcess`, a bare ``Popen`` (e.g. ``vis.window.server_proc``) or None."""
    if server is None:
        return
    _stop(server.proc if isinstance(server, ServerProcess) else server, timeout)
