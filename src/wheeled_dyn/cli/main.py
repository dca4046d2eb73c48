r"""The ``wheeled-dyn`` command: a thin layer over the Python API.

Each sub-command module (``cli/*_cmd.py``) contributes its sub-commands through a function
``add_commands(subparsers)`` listed in :data:`COMMAND_MODULES`; the handler it registers with
``set_defaults(handler=...)`` receives the parsed arguments and returns an exit code. Errors of
the project's own type are printed as one line on stderr with exit code 2, its warnings as one
line each; Ctrl-C ends a command with exit code 130 and one line, no traceback.

A Ctrl-C that arrives while a module is being imported is held back until the import has
finished (see :func:`_on_interrupt`): third-party packages catch ``BaseException`` around
their optional imports (trimesh, loaded by yourdfpy) and would swallow it, and an exception
raised inside a compiled extension's initialisation can abort the process.
"""

from __future__ import annotations

import argparse
import atexit
import gc
import importlib
import os
import signal
import sys
import warnings
from collections.abc import Callable, MutableMapping, Sequence
from types import FrameType
from typing import TYPE_CHECKING, Any, TypeAlias

from ..errors import WheeledDynError, WheeledDynWarning

if TYPE_CHECKING:
    #: What ``signal.signal`` takes and returns.
    _Handler: TypeAlias = Callable[[int, FrameType | None], Any] | int | signal.Handlers | None

#: Modules that define ``add_commands(subparsers)``, in the order they appear in ``--help``.
COMMAND_MODULES: tuple[str, ...] = (
    "wheeled_dyn.cli.models_cmd",
    "wheeled_dyn.cli.compare_cmd",
    "wheeled_dyn.cli.simulate_cmd",
    "wheeled_dyn.cli.symbolic_cmd",
    "wheeled_dyn.cli.viewer_cmd",
)


#: Collections of the middle generation between two of the oldest (the whole heap: SymPy's
#: and Pinocchio's modules and caches) in the command's process (Python's default is 10): at
#: the default, the garbage collector took 0.08 s of ``compare`` of eq. (25) (0.03 s with
#: this), and its pass over the whole heap at exit another 0.15 s (none: see :func:`entry`).
GC_FULL_THRESHOLD = 10_000

#: The thread pools of the linear algebra libraries, one thread each in the command's
#: processes unless the environment says otherwise: ``report`` forks as many workers as the
#: machine has cores, and each worker's own pool of threads competed with the other workers
#: for them (set before NumPy is first imported).
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")

#: Seconds between two looks, after a Ctrl-C held back during an import, at whether the
#: import has finished (the interrupt is then raised).
INTERRUPT_RETRY = 0.02

#: Set by :func:`_on_interrupt` when Ctrl-C comes while a command runs.
_interrupted = False
#: The SIGALRM handler that :func:`_on_interrupt` replaced to look again (None: not replaced).
_previous_alarm: _Handler = None


def _importing(frame: FrameType | None) -> bool:
    r"""Whether ``frame`` runs inside an import (the import system's frames are on its stack)."""
    while frame is not None:
        if frame.f_code.co_filename.startswith("<frozen importlib._bootstrap"):
            return True
        frame = frame.f_back
    return False


def _on_interrupt(signum: int, frame: FrameType | None) -> None:
    r"""SIGINT while a command runs (and the SIGALRM of a held-back one): raise
    :class:`KeyboardInterrupt`, unless a module is being imported; then look again every
    :data:`INTERRUPT_RETRY` seconds and raise it once the import has finished."""
    global _interrupted, _previous_alarm
    if signum == signal.SIGINT:
        _interrupted = True
    if not _interrupted:
        return
    if _importing(frame) and hasattr(signal, "setitimer"):
        if _previous_alarm is None:
            before = signal.signal(signal.SIGALRM, _on_interrupt)
            _previous_alarm = signal.SIG_DFL if before is None else before
        signal.setitimer(signal.ITIMER_REAL, INTERRUPT_RETRY)
        return
    raise KeyboardInterrupt


def _restore_alarm(handler: _Handler) -> None:
    r"""Cancel a pending look at a held-back Ctrl-C and give SIGALRM ``handler`` (its
    handler before :func:`_on_interrupt` took it, when ``None``)."""
    global _previous_alarm
    if _previous_alarm is not None:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, _previous_alarm if handler is None else handler)
        _previous_alarm = None


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="wheeled-dyn",
        description="Check hand-derived equations of motion of wheeled bodies against Pinocchio.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMAND_MODULES:
        importlib.import_module(name).add_commands(sub)
    return parser


def _one_line(show: Callable[..., None]) -> Callable[..., None]:
    r"""``warnings.showwarning`` that prints the project's warnings as one line
    (``wheeled-dyn: warning: ...``) and leaves others to ``show``."""
    def shown(message, category, filename, lineno, file=None, line=None) -> None:
        if issubclass(category, WheeledDynWarning):
            print(f"wheeled-dyn: warning: {message}", file=file or sys.stderr, flush=True)
        else:
            show(message, category, filename, lineno, file, line)
    return shown


def main(argv: Sequence[str] | None = None) -> int:
    r"""Run the command ``argv`` (default: the process's arguments); its exit code. While it
    runs, SIGINT is handled by :func:`_on_interrupt`, and the project's warnings are printed
    as one line each."""
    global _interrupted
    _interrupted = False
    shown, warnings.showwarning = warnings.showwarning, _one_line(warnings.showwarning)
    try:
        previous = signal.signal(signal.SIGINT, _on_interrupt)
    except ValueError:               # not the main thread: signals are not ours to handle
        previous = None
    interrupted = False
    try:
        return _run(argv)
    except KeyboardInterrupt:        # Ctrl-C: the writers have removed their temporary files
        # a second Ctrl-C (or the one the workers' shutdown sees, or a look at a held-back
        # one) must not turn the clean exit into a traceback or a death by signal
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        _restore_alarm(signal.SIG_IGN)
        interrupted = True
        print("wheeled-dyn: interrupted", file=sys.stderr)
        return 130
    finally:
        warnings.showwarning = shown
        if not interrupted:
            _restore_alarm(None)
            if previous is not None:
                signal.signal(signal.SIGINT, previous)


def _run(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    handler = getattr(args, "handler", None)
    if handler is None:
        parser.print_help()
        return 1
    try:
        return int(handler(args) or 0)
    except WheeledDynError as exc:
        print(f"wheeled-dyn: error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:          # output piped into a reader that stopped (e.g. head)
        sys.stderr.close()
        return 0
    except OSError as exc:           # the system refused (a full disk, ...): one line too
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"wheeled-dyn: error: {where}{exc.strerror or exc}", file=sys.stderr)
        return 2


def entry() -> None:
    r"""The ``wheeled-dyn`` command: :func:`main`'s exit code. The linear algebra libraries
    get one thread each (:data:`THREAD_VARIABLES`) where the environment sets none. The
    garbage collector goes over the whole heap every :data:`GC_FULL_THRESHOLD` collections of
    the middle generation, and not once more at exit (everything is frozen first: the
    shutdown frees it without looking for cycles). After Ctrl-C the process ends at once
    with 130 (its files are already cleaned up): the interpreter's own shutdown could
    otherwise meet the interrupt again and end by the signal instead. Any other exit skips the interpreter's shutdown
    (:func:`_exit_now`)."""
    gc.set_threshold(*gc.get_threshold()[:2], GC_FULL_THRESHOLD)
    one_thread_each(os.environ)
    code = main()
    if code == 130:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(130)
    gc.freeze()
    _exit_now(code)


def one_thread_each(environ: MutableMapping[str, str]) -> None:
    r"""Each of :data:`THREAD_VARIABLES` that ``environ`` does not set, set to one thread
    (a value the user set is kept)."""
    for name in THREAD_VARIABLES:
        environ.setdefault(name, "1")


def _exit_now(code: int) -> None:
    r"""End the process with ``code`` once the exit handlers have run (the memos saved, the
    workers joined, temporary folders removed) and the output is flushed, without the
    interpreter's own shutdown: freeing every SymPy and Pinocchio object one by one took
    about a tenth of a second of each command, and nothing of it is seen. Where the exit
    handlers cannot be run first (another Python), the usual ``sys.exit``."""
    run = getattr(atexit, "_run_exitfuncs", None)
    if run is None:
        sys.exit(code)
    run()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):     # closed, or a reader that stopped
            pass
    os._exit(code)


if __name__ == "__main__":  # pragma: no cover
    entry()
