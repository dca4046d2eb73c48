r"""``wheeled-dyn compare ... --watch``: check a derivation again each time it is saved.

A person fixing a derivation saves the file and wants the verdict at once. :func:`watch` polls
the files' modification times (no extra dependency, works on every file system) every
:data:`WATCH_INTERVAL` seconds and calls the check again when one changed; the caller keeps one
:class:`~wheeled_dyn.compare.ComparisonEngine`, so the truth (Pinocchio on the sampled states
and parameter sets, the closed forms) is computed once and only the document side is redone.
An error in the saved file (a half-written line, an unknown symbol) is printed as one line and
the watch goes on; Ctrl-C ends it (exit code 0).
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from ..errors import WheeledDynError

#: Seconds between two looks at the files' modification times.
WATCH_INTERVAL: float = 0.25


def stamps(files: Sequence[Path]) -> tuple:
    r"""``(mtime_ns, size)`` of each file, None for a file that is missing (being replaced)."""
    out = []
    for f in files:
        try:
            st = Path(f).stat()
            out.append((st.st_mtime_ns, st.st_size))
        except OSError:
            out.append(None)
    return tuple(out)


def watch(files: Sequence[Path], check: Callable[[], None], interval: float = WATCH_INTERVAL,
          max_checks: int | None = None, say: Callable[[str], None] | None = None) -> int:
    r"""Call ``check()`` each time one of ``files`` changes, until Ctrl-C (or, for tests,
    ``max_checks`` checks after the first); returns the exit code 0. A
    :class:`~wheeled_dyn.errors.WheeledDynError` raised by ``check`` is printed, not raised."""
    def say_(text: str) -> None:
        print(text)
        sys.stdout.flush()

    say = say or say_
    seen = stamps(files)
    done = 0
    say(f"watching {', '.join(Path(f).name for f in files)} (checked again when saved; "
        "Ctrl-C to stop)")
    try:
        while max_checks is None or done < max_checks:
            time.sleep(interval)
            now = stamps(files)
            if now == seen or None in now:
                continue
            seen = now
            done += 1
            t0 = time.perf_counter()
            try:
                check()
            except WheeledDynError as exc:
                say(f"wheeled-dyn: error: {exc}")
            say(f"checked again in {time.perf_counter() - t0:.2f} s; watching (Ctrl-C to stop)")
    except KeyboardInterrupt:
        say("stopped watching")
    return 0
