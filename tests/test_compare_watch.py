"""``wheeled-dyn compare ... --watch``: a saved file is checked again (a broken save is reported
and the watch goes on), Ctrl-C ends it with exit code 0; every wait is bounded."""

from __future__ import annotations

import os
import queue
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

from wheeled_dyn.cli.watch import watch
from wheeled_dyn.derivations.builtin import builtin_derivations
from wheeled_dyn.errors import InputFileError

#: Longest wait for one expected line of output (s): start-up plus one comparison.
LINE_TIMEOUT = 120.0
#: Small grid: the test is about watching, not about the verdicts.
GRID = ["--samples", "40", "--param-sets", "2"]


def _eq25() -> Path:
    return next(p for p in builtin_derivations("seed001") if p.name == "eq25_lagrange.toml")


def _reader(stream, q: queue.Queue) -> None:
    for line in iter(stream.readline, ""):
        q.put(line)
    q.put(None)


def _wait_for(q: queue.Queue, text: str, seen: list[str]) -> str:
    deadline = time.monotonic() + LINE_TIMEOUT
    while time.monotonic() < deadline:
        try:
            line = q.get(timeout=max(0.1, deadline - time.monotonic()))
        except queue.Empty:
            break
        if line is None:
            break
        seen.append(line)
        if text in line:
            return line
    raise AssertionError(f"no line with {text!r} within {LINE_TIMEOUT} s; output:\n"
                         + "".join(seen))


def test_watch_rechecks_saved_file_and_stops_on_ctrl_c(tmp_path):
    doc = tmp_path / "eq25.toml"
    shutil.copy(_eq25(), doc)
    original = doc.read_text(encoding="utf-8")
    proc = subprocess.Popen(
        [sys.executable, "-m", "wheeled_dyn.cli.main", "compare", "wip", str(doc), "--watch",
         "--out", str(tmp_path / "out"), *GRID],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1,
        env={**os.environ, "PYTHONUNBUFFERED": "1"})
    q: queue.Queue = queue.Queue()
    threading.Thread(target=_reader, args=(proc.stdout, q), daemon=True).start()
    seen: list[str] = []
    try:
        _wait_for(q, "watching", seen)
        time.sleep(0.05)
        doc.write_text(original.replace("[coordinates]", "[coordinates\n"), encoding="utf-8")
        _wait_for(q, "error:", seen)                       # a broken save: reported
        _wait_for(q, "checked again", seen)
        time.sleep(0.05)
        doc.write_text(original.replace('title = "', 'title = "EDITED ', 1), encoding="utf-8")
        _wait_for(q, "EDITED", seen)                       # the new content was compared
        _wait_for(q, "checked again", seen)
        proc.send_signal(signal.SIGINT)
        _wait_for(q, "stopped watching", seen)
        assert proc.wait(timeout=LINE_TIMEOUT) == 0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=10)


def test_watch_calls_check_once_per_save(tmp_path):
    f = tmp_path / "a.toml"
    f.write_text("x = 1\n")
    calls: list[int] = []
    lines: list[str] = []

    def check():
        calls.append(1)
        if len(calls) == 1:
            raise InputFileError(f, "broken on purpose")

    def save_twice():
        for k in range(2):
            time.sleep(0.3)
            f.write_text(f"x = {k + 2}\n")
            os.utime(f, ns=(time.time_ns(), time.time_ns() + k + 1))
            time.sleep(0.3)

    t = threading.Thread(target=save_twice)
    t.start()
    assert watch([f], check, interval=0.05, max_checks=2, say=lines.append) == 0
    t.join(timeout=10)
    assert len(calls) == 2
    assert any("broken on purpose" in line for line in lines)
