r"""``wheeled-dyn compare ... --watch``: check a derivation again each time it, or anything its
verdict depends on, is saved.

A person fixing a derivation saves the file and wants the verdict at once. :func:`watch` polls
the stamps (times of change, size, inode) of every file the result depends on
(:func:`watched_files`: the derivation files, the step files beside them, the model file and
its URDF; no extra dependency, works on every file system) every :data:`WATCH_INTERVAL` seconds and calls the
check again when one changed. The caller keeps one
:class:`~wheeled_dyn.compare.ComparisonEngine` while the model's files stay the same, so the
truth (Pinocchio on the sampled states and parameter sets, the closed forms) is computed once
and only the document side is redone; when the model file or the URDF changes, the truth is
computed again (a new engine, and the model is read again: :mod:`wheeled_dyn.models.registry`
keeps models per content of their files). An error in a saved file (a half-written line, an
unknown symbol) is printed as one line and the watch goes on; Ctrl-C ends it with exit code
130, as every command.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from ..errors import WheeledDynError
from ..paths import file_stamp, resolved

#: Seconds between two looks at the files' stamps.
WATCH_INTERVAL: float = 0.25
#: Exit code of a watch ended by Ctrl-C (as every command interrupted: 128 + SIGINT).
INTERRUPTED = 130


def stamps(files: Sequence[Path]) -> dict[Path, tuple | None]:
    r"""The :func:`~wheeled_dyn.paths.file_stamp` of each file, None for a file that is
    missing (being replaced)."""
    return {Path(f): file_stamp(f) for f in files}


def watched_files(files: Sequence[Path], model: str) -> list[Path]:
    r"""The files a check of derivation ``files`` on ``model`` depends on (sorted): the files,
    the step files beside them, the model file and the model's URDF. A model that cannot be
    read now (a half-saved model file) contributes its model file only."""
    from ..models.model_file import is_model_path
    from ..models.registry import model_files, model_key
    out = set()
    for f in files:
        path = resolved(f)
        out.update([path, *path.parent.glob("*_steps.toml")])
    try:
        out.update(model_files(model))
    except WheeledDynError:
        if is_model_path(str(model)):
            out.add(Path(model_key(model)))
    return sorted(out)


def watch(files: Sequence[Path] | Callable[[], Sequence[Path]], check: Callable[[], None],
          interval: float = WATCH_INTERVAL, max_checks: int | None = None,
          say: Callable[[str], None] | None = None) -> int:
    r"""Call ``check()`` each time one of ``files`` changes (``files`` a list, or a function
    giving the list now: it is asked at every look, so a step file or a URDF that comes or
    goes is followed), until Ctrl-C (exit code :data:`INTERRUPTED`) or, for tests,
    ``max_checks`` checks after the first (exit code 0). A
    :class:`~wheeled_dyn.errors.WheeledDynError` raised by ``check`` is printed, not
    raised."""
    def say_(text: str) -> None:
        print(text)
        sys.stdout.flush()

    say = say or say_
    listed: Callable[[], Sequence[Path]] = files if callable(files) else (lambda: files)
    seen = stamps(listed())
    done = 0
    say(f"watching {', '.join(Path(f).name for f in seen)} (checked again when saved; "
        "Ctrl-C to stop)")
    try:
        while max_checks is None or done < max_checks:
            time.sleep(interval)
            now = stamps(listed())
            if now == seen or None in now.values():
                continue
            seen = now                    # as before the check: a save during it is seen next
            done += 1
            t0 = time.perf_counter()
            try:
                check()
            except WheeledDynError as exc:
                say(f"wheeled-dyn: error: {exc}")
            say(f"checked again in {time.perf_counter() - t0:.2f} s; watching (Ctrl-C to stop)")
    except KeyboardInterrupt:
        say("stopped watching")
        return INTERRUPTED
    return 0


__all__ = ["INTERRUPTED", "WATCH_INTERVAL", "stamps", "watch", "watched_files"]
