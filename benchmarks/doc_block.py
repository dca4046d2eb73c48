r"""Each benchmark script keeps its own block of ``docs/benchmarks.md`` true.

A block is everything between the script's two markers::

    <!-- bench_core.py: begin (rewritten by the script; do not edit) -->
    ...
    <!-- bench_core.py: end -->

:func:`recorded` wraps a script's run: what it prints goes to the terminal as before and, when
the run finishes without an exception, replaces the script's block with that output and the
date of the run (the file written whole: a temporary file renamed). Text outside the markers
(what the figures mean, earlier runs) is the writers'.
"""

from __future__ import annotations

import contextlib
import datetime
import io
import os
import platform
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

#: The page the blocks are in.
DOC = Path(__file__).resolve().parents[1] / "docs" / "benchmarks.md"


def markers(script: str) -> tuple[str, str]:
    r"""The begin and end markers of the block of ``script`` (a file name, ``bench_core.py``)."""
    return (f"<!-- {script}: begin (rewritten by the script; do not edit) -->",
            f"<!-- {script}: end -->")


def block(script: str, output: str, date: str, machine: str) -> str:
    r"""The block of ``script``: its markers around the date, the machine and the output."""
    begin, end = markers(script)
    return (f"{begin}\nLast run {date} ({machine}):\n\n```\n{output.strip(chr(10))}\n```\n{end}")


def replace_block(text: str, script: str, output: str, date: str, machine: str) -> str:
    r"""``text`` with the block of ``script`` rewritten; ValueError when ``text`` does not
    hold the script's two markers, once each and in order."""
    begin, end = markers(script)
    start, stop = text.find(begin), text.find(end)
    if text.count(begin) != 1 or text.count(end) != 1 or stop < start:
        raise ValueError(f"{DOC.name} has no block for {script} (markers {begin!r} ... {end!r})")
    return text[:start] + block(script, output, date, machine) + text[stop + len(end):]


def machine() -> str:
    r"""Where the figures were measured: cores and Python."""
    return f"{os.cpu_count()} cores, Python {platform.python_version()}"


class _Tee(io.TextIOBase):
    def __init__(self, out) -> None:
        self.out, self.kept = out, io.StringIO()

    def write(self, text: str) -> int:
        self.kept.write(text)
        return self.out.write(text)

    def flush(self) -> None:
        self.out.flush()


@contextlib.contextmanager
def recorded(script_file: str, doc: Path | None = None) -> Iterator[None]:
    r"""Run the body with its printed output kept; on a normal exit, the block of
    ``script_file`` in ``doc`` (default :data:`DOC`) is rewritten with it and today's date."""
    doc = doc or DOC
    tee = _Tee(sys.stdout)
    before, sys.stdout = sys.stdout, tee
    try:
        yield
    finally:
        sys.stdout = before
    name = Path(script_file).name
    text = replace_block(doc.read_text(encoding="utf-8"), name, tee.kept.getvalue(),
                         datetime.date.today().isoformat(), machine())
    with tempfile.NamedTemporaryFile("w", encoding="utf-8", dir=doc.parent, delete=False,
                                     suffix=".tmp") as tmp:
        tmp.write(text)
    os.replace(tmp.name, doc)
    print(f"{doc.name}: block of {name} rewritten", file=sys.stderr)
