"""``wheeled-dyn compare ... --watch``: a saved file is checked again (a broken save is reported
and the watch goes on), Ctrl-C ends it with exit code 130 (as every command); a change of the
model's URDF is a change too: the truth is computed again, during the watch and after it
(the stale-watch sequence of issue 25); every wait is bounded."""

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

from shipped_copies import own_wip_model
from wheeled_dyn.cli import compare_cmd as commands
from wheeled_dyn.cli.watch import INTERRUPTED, watch, watched_files
from wheeled_dyn.disk_cache import CACHE_ENV, REUSE_ENV
from wheeled_dyn.report.markdown import summary_lines
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


def _start_watch(doc: Path, out: Path) -> tuple[subprocess.Popen, queue.Queue]:
    r"""``compare wip DOC --watch --out OUT`` started, and the queue its output lines reach."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "wheeled_dyn.cli.main", "compare", "wip", str(doc), "--watch",
         "--out", str(out), *GRID],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1,
        env={**os.environ, "PYTHONUNBUFFERED": "1"})
    q: queue.Queue = queue.Queue()
    threading.Thread(target=_reader, args=(proc.stdout, q), daemon=True).start()
    return proc, q


def test_watch_rechecks_saved_file_and_stops_on_ctrl_c(tmp_path):
    doc = tmp_path / "eq25.toml"
    shutil.copy(_eq25(), doc)
    original = doc.read_text(encoding="utf-8")
    proc, q = _start_watch(doc, tmp_path / "out")
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
        assert proc.wait(timeout=LINE_TIMEOUT) == INTERRUPTED == 130
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=10)


def test_a_file_that_becomes_a_folder_is_an_error_not_an_empty_report(tmp_path):
    r"""The watched file replaced by an empty folder: the error a fresh ``compare`` gives
    ("folder without derivation files"), and the last report stays; the watch wrote an
    empty report over it, with no error."""
    doc = tmp_path / "eq25.toml"
    shutil.copy(_eq25(), doc)
    out = tmp_path / "out"
    proc, q = _start_watch(doc, out)
    seen: list[str] = []
    try:
        _wait_for(q, "watching", seen)
        report = (out / "report.md").read_text()
        doc.unlink()
        doc.mkdir()
        line = _wait_for(q, "error:", seen)
        assert "folder without derivation files" in line, seen
        _wait_for(q, "checked again", seen)
        assert (out / "report.md").read_text() == report
    finally:
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


#: The left wheel's joint as the shipped URDF has it, and turned 90° about the body's x axis
#: (its axis turned with it, so that it still spins about the axle): the wheel's symmetry
#: axis is then vertical, its inertia about the axle Iw2 instead of Iw3 — another body.
JOINT = """    <origin xyz="0 0 -0.35" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>"""
TURNED = """    <origin xyz="0 0 -0.35" rpy="1.5707963267948966 0 0"/>
    <axis xyz="0 1 0"/>"""
#: Grid of the stale-watch sequence (small: the test is about which truth is used).
SAMPLES, PARAM_SETS = 40, 2


def _own_model(folder: Path) -> tuple[Path, Path, Path]:
    r"""A copy of the wip model (model file, URDF) and of eq. (25) naming it, in ``folder``."""
    model, urdf = own_wip_model(folder)
    doc = folder / "eq25.toml"
    doc.write_text(_eq25().read_text().replace('model = "wip"', f'model = "{model.name}"'))
    return model, urdf, doc


def _counts_line(model: Path, doc: Path) -> str:
    r"""The counts line of a comparison made from scratch here (no result reused)."""
    (result,) = commands.run_comparison([doc], SAMPLES, PARAM_SETS, model=str(model))
    return summary_lines(result)[0]


def _replace(path: Path, text: str) -> None:
    r"""Save ``text`` to ``path`` as an editor does: a new file renamed over it."""
    tmp = path.with_name(path.name + ".saving")
    tmp.write_text(text)
    os.replace(tmp, path)


def test_a_urdf_saved_during_the_watch_is_the_truth_during_and_after(tmp_path):
    model, urdf, doc = _own_model(tmp_path)
    assert JOINT in urdf.read_text()
    original, turned = urdf.read_text(), urdf.read_text().replace(JOINT, TURNED)
    before = _counts_line(model, doc)
    _replace(urdf, turned)
    after = _counts_line(model, doc)
    _replace(urdf, original)
    assert before != after, "the turned joint must change the verdicts"
    assert watched_files([doc], str(model)) == sorted([doc, model, urdf])
    env = {**os.environ, "PYTHONUNBUFFERED": "1", CACHE_ENV: str(tmp_path / "cache"),
           REUSE_ENV: "1"}                                 # results remembered, as users run
    grid = ["--samples", str(SAMPLES), "--param-sets", str(PARAM_SETS),
            "--out", str(tmp_path / "out")]
    command = [sys.executable, "-m", "wheeled_dyn.cli.main", "compare", str(model), str(doc)]
    proc = subprocess.Popen([*command, "--watch", *grid], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, bufsize=1, env=env)
    q: queue.Queue = queue.Queue()
    threading.Thread(target=_reader, args=(proc.stdout, q), daemon=True).start()
    seen: list[str] = []
    try:
        assert _wait_for(q, " agree, ", seen).strip() == before
        _wait_for(q, "watching", seen)
        time.sleep(0.05)
        _replace(urdf, turned)                              # the URDF alone is saved
        assert _wait_for(q, " agree, ", seen).strip() == after
        _wait_for(q, "checked again", seen)
        time.sleep(0.05)
        _replace(doc, doc.read_text() + "\n# saved\n")      # then the derivation
        assert _wait_for(q, " agree, ", seen).strip() == after
        _wait_for(q, "checked again", seen)
        proc.send_signal(signal.SIGINT)
        assert proc.wait(timeout=LINE_TIMEOUT) == 130
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=10)
    for urdf_text, expected in ((turned, after), (original, before)):    # after the watch
        _replace(urdf, urdf_text)
        out = subprocess.run([*command, *grid], capture_output=True, text=True, env=env,
                             timeout=LINE_TIMEOUT)
        assert out.returncode == 0, out.stderr
        assert expected in out.stdout, out.stdout
