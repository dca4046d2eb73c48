"""`compare` compares the step files feeding a derivation in a forked worker while it compares
the derivation: the same result as one process, a step file's error as the project's own
error, a worker that dies as WorkerError naming the step files."""

from __future__ import annotations

import os
import shutil
import signal
import sys
from pathlib import Path

import pytest

from wheeled_dyn.compare.steps import chain as steps
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import DerivationError, WorkerError

SEED001 = Path(__file__).resolve().parents[1] / "src/wheeled_dyn/data/derivations/seed001"
pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="the worker is forked")


def _copy(tmp_path: Path, planted: str = "") -> Path:
    shutil.copy(SEED001 / "eq25_lagrange.toml", tmp_path)
    text = (SEED001 / "s4_energy_steps.toml").read_text()
    (tmp_path / "s4_energy_steps.toml").write_text(text.replace("[[step]]", "[[step]]" + planted,
                                                                1))
    return tmp_path / "eq25_lagrange.toml"


def _compare(path: Path, parallel: bool):
    steps._STEP_CACHE.clear()
    return ComparisonEngine(samples=40, param_sets=2, parallel_steps=parallel).compare(
        load_derivation(path))


def test_same_result_as_one_process(tmp_path):
    path = _copy(tmp_path)
    one, two = _compare(path, False), _compare(path, True)
    assert one.as_dict() == two.as_dict()
    assert any(r.key == "step" for r in two.records)


def test_error_in_a_step_file_is_the_projects(tmp_path):
    path = _copy(tmp_path, '\ngiven = ["no_such_family"]')
    with pytest.raises(DerivationError, match="no_such_family"):
        _compare(path, True)


def test_a_worker_that_dies_is_named(tmp_path, monkeypatch):
    path = _copy(tmp_path)
    monkeypatch.setattr(steps, "_step_file", lambda *a: os.kill(os.getpid(), signal.SIGKILL))
    with pytest.raises(WorkerError, match="s4_energy_steps.toml"):
        _compare(path, True)


def test_ctrl_c_while_the_workers_are_forked_is_not_lost():
    r"""A Ctrl-C that arrives inside the fork's callbacks (an exception raised there is
    swallowed) is held back and raised once the workers are forked: in a fresh interpreter
    whose at-fork callback sends the interrupt."""
    import subprocess
    import sys
    code = (
        "import os, signal\n"
        "from wheeled_dyn.compare.runtime.workers import Workers\n"
        "def on_interrupt(s, f):\n"
        "    raise KeyboardInterrupt\n"
        "signal.signal(signal.SIGINT, on_interrupt)\n"
        "os.register_at_fork(after_in_parent=lambda: os.kill(os.getpid(), signal.SIGINT))\n"
        "try:\n"
        "    with Workers(1):\n"
        "        pass\n"
        "    print('lost')\n"
        "except KeyboardInterrupt:\n"
        "    print('raised')\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=60)
    assert out.stdout.strip() == "raised", (out.stdout, out.stderr)


#: Longest wait for a worker to end after its parent is killed (s).
ORPHAN_WAIT = 20.0


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc (Linux)")
def test_workers_end_when_their_parent_is_killed():
    r"""A parent killed outright (SIGKILL: nothing of it runs) leaves no worker computing on:
    a probe's ``report`` killed so left two at full load for 25 s."""
    import subprocess
    import time
    code = ("import time\n"
            "from wheeled_dyn.compare.runtime.workers import Workers\n"
            "import multiprocessing\n"
            "with Workers(1) as w:\n"
            "    w.submit(time.sleep, (120,), [])\n"
            "    time.sleep(1.0)\n"
            "    print(*[p.pid for p in multiprocessing.active_children()], flush=True)\n"
            "    time.sleep(120)\n")
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    try:
        pids = [int(x) for x in proc.stdout.readline().split()]
        assert pids
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=10)
        deadline = time.monotonic() + ORPHAN_WAIT
        alive = list(pids)
        while alive and time.monotonic() < deadline:
            time.sleep(0.1)
            alive = [p for p in alive if _running(p)]
        assert not alive
    finally:
        if proc.poll() is None:
            proc.kill()


def _running(pid: int) -> bool:
    r"""Whether process ``pid`` exists and is no zombie (an orphan is reaped by init)."""
    try:
        with open(f"/proc/{pid}/stat") as handle:
            return handle.read().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False
