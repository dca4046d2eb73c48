r"""Forked worker processes for the comparisons: ``report`` splits its derivations over them,
``compare`` compares the step files that feed a derivation in one while the parent compares
the derivation itself.

:class:`Workers` forks its processes when it starts (nothing is imported twice, and what the
parent computed before is there already). A worker's error is raised in the parent when its
result is collected (the project's errors survive pickling, :mod:`wheeled_dyn.errors`); a
worker that dies (a crash in compiled code) raises
:class:`~wheeled_dyn.errors.WorkerError` naming the files its unfinished jobs were comparing,
instead of waiting forever. Workers leave Ctrl-C to the parent, which ends them; a Ctrl-C
that comes while they are forked is held back until they are, then raised in the parent.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import threading
import time
from collections.abc import Callable, Sequence
from multiprocessing.pool import AsyncResult
from types import TracebackType

#: Seconds between two looks at the workers while waiting for their results.
POLL = 0.2
#: Signals held back while the processes are forked.
HELD_SIGNALS = {signal.SIGINT, *([signal.SIGALRM] if hasattr(signal, "SIGALRM") else [])}

#: In a worker: the queue (inherited from the parent) on which it announces its process id
#: and each derivation done.
_PROGRESS = None


def can_fork() -> bool:
    r"""Whether :class:`Workers` can start here: the platform forks, and this process is not
    itself a worker (those may not have children)."""
    return ("fork" in multiprocessing.get_all_start_methods()
            and not multiprocessing.current_process().daemon)


def tick() -> None:
    r"""In a worker: one more derivation done (the parent's progress bar moves)."""
    if _PROGRESS is not None:
        _PROGRESS.put(1)


def stage(name: str, stage: str) -> None:
    r"""In a worker: the comparison of file ``name`` starts ``stage`` (the parent shows it)."""
    if _PROGRESS is not None:
        _PROGRESS.put(("stage", name, stage))


def _start_worker(parent: int) -> None:
    r"""Workers leave Ctrl-C to the parent, which ends them (no traceback from each), end
    with their parent however it ends (killed, it cannot end them), and announce their
    process id (so that the parent notices one that dies)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _end_with_parent(parent)
    if _PROGRESS is not None:
        _PROGRESS.put(("pid", os.getpid()))


#: Seconds between two looks of a worker at its parent (is it still there?).
PARENT_POLL = 0.5


def _end_with_parent(parent: int) -> None:
    r"""A thread that ends this worker once its parent has ended (its parent process id is
    then another's: it was killed, and could not end its workers). Not the kernel's
    parent-death signal: that follows the thread that forked, and the pool forks a worker it
    replaces from a thread of its own that ends before the workers do."""
    def look() -> None:
        while os.getppid() == parent:
            time.sleep(PARENT_POLL)
        os._exit(1)
    threading.Thread(target=look, daemon=True, name="parent-watch").start()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        pass
    return True


class Workers:
    r"""``count`` forked processes (a context manager: leaving it ends them). :meth:`submit`
    a module-level function and its arguments, do something else, then :meth:`wait` for the
    results."""

    def __init__(self, count: int) -> None:
        global _PROGRESS
        ctx = multiprocessing.get_context("fork")
        self._queue = _PROGRESS = ctx.SimpleQueue()     # set before the fork: inherited
        # Ctrl-C is held back while the processes are forked: one arriving inside the fork's
        # callbacks (logging's lock release) would be swallowed there and the command would
        # run on; held back, it is raised here once they are forked (the workers, which
        # inherit it blocked, ignore it anyway). SIGALRM too: the command line raises a
        # Ctrl-C it held back during an import from a SIGALRM (cli.main._on_interrupt), which
        # could otherwise fire inside those callbacks
        held = hasattr(signal, "pthread_sigmask")
        before = signal.pthread_sigmask(signal.SIG_BLOCK, HELD_SIGNALS) if held else None
        self._pool = ctx.Pool(count, initializer=_start_worker, initargs=(os.getpid(),))
        try:
            if before is not None:           # held: the mask as it was
                signal.pthread_sigmask(signal.SIG_SETMASK, before)
        except BaseException:
            self._pool.terminate()
            self._queue.close()
            _PROGRESS = None
            raise
        self._jobs: list[tuple[AsyncResult, tuple[str, ...]]] = []
        self._pids: set[int] = set()

    def __enter__(self) -> Workers:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        global _PROGRESS
        self._pool.terminate()
        self._queue.close()
        _PROGRESS = None

    def submit(self, fn: Callable, args: tuple, files: Sequence[str]) -> None:
        r"""Run ``fn(*args)`` in a worker; ``files`` are named should the worker die."""
        self._jobs.append((self._pool.apply_async(fn, args), tuple(files)))

    def wait(self, progress: Callable[[int], object] | None = None,
             on_stage: Callable[[str, str], object] | None = None) -> list:
        r"""The results of the submitted jobs, in their order; ``progress(1)`` for each
        derivation a worker reports done, ``on_stage(file, stage)`` for each stage of a
        comparison a worker reports started."""
        while waiting := [job for job, _ in self._jobs if not job.ready()]:
            waiting[0].wait(POLL)
            while not self._queue.empty():
                message = self._queue.get()
                if isinstance(message, tuple) and message[0] == "pid":
                    self._pids.add(message[1])
                elif isinstance(message, tuple):
                    if on_stage is not None:
                        on_stage(message[1], message[2])
                elif progress is not None:
                    progress(message)
            for job, _ in self._jobs:
                if job.ready() and not job.successful():
                    job.get()                            # raises the worker's error
            if any(not _alive(pid) for pid in self._pids):
                from ...errors import WorkerError
                files = sorted({f for job, names in self._jobs if not job.ready()
                                for f in names})
                raise WorkerError("a comparison process ended abruptly", files)
        return [job.get() for job, _ in self._jobs]


__all__ = ["Workers", "can_fork", "stage", "tick"]
