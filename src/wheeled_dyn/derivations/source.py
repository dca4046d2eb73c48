r"""Reading a TOML file and finding lines in it, so that every error names file:line.

``tomllib`` reports syntax errors as ``"Invalid value (at line 3, column 7)"``; those become
:class:`~wheeled_dyn.errors.InputFileError` with ``line`` and ``column``. For errors of content
(an unknown name in ``A[2,3]``) the parsed data has no positions, so :class:`SourceText`
searches the text: the table header, then the key, then the element's text after the key.
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

from ..errors import InputFileError, WheeledDynError

_TOML_POSITION = re.compile(r"\(at line (\d+), column (\d+)\)")
#: A table header starts in column 0 (as written in every shipped file and the documentation):
#: ``[name]`` or ``[[name]]``, a dotted key without commas.
_TABLE_HEADER = re.compile(r"^\[\[?\s*([A-Za-z0-9_.\-\" ]+?)\s*\]\]?\s*(#.*)?$")


#: The key a line starts with (``key =``, ``"key" =``, ``'key' =``), for :class:`SourceText`'s
#: index.
_KEY_AT_START = re.compile(r"""^\s*(?:"([^"]*)"|'([^']*)'|([^\s="']+))\s*=""")


@dataclass(frozen=True)
class SourceText:
    r"""The text of a file, for locating keys and fragments (1-based line numbers). The
    headers and keys are indexed once (:attr:`_index`), so that locating every key of a file of
    many thousands is linear in its size."""

    path: Path
    text: str

    @cached_property
    def lines(self) -> list[str]:
        return self.text.splitlines()

    @cached_property
    def _index(self) -> tuple[dict[str, int], dict[tuple[str | None, str], int]]:
        r"""(table -> line of its first header, (table or None, key) -> first line of the key
        in that table, or anywhere)."""
        headers: dict[str, int] = {}
        keys: dict[tuple[str | None, str], int] = {}
        current: str | None = None
        for number, line in enumerate(self.lines, start=1):
            header = _TABLE_HEADER.match(line)
            if header:
                current = header.group(1).strip()
                headers.setdefault(current, number)
                continue
            found = _KEY_AT_START.match(line)
            if found:
                key = next(g for g in found.groups() if g is not None)
                keys.setdefault((current, key), number)
                keys.setdefault((None, key), number)
        return headers, keys

    def _key_line(self, table: str | None, key: str) -> int | None:
        return self._index[1].get((table, key))

    def line_of(self, table: str | None, key: str | None = None,
                fragment: str | None = None) -> int | None:
        r"""Line of ``key`` in ``[table]`` (``table=None``: top level or anywhere), or of the
        first occurrence of ``fragment`` from that key on, up to the next table header. None
        if not found."""
        lines = self.lines
        if key is None:
            return None if table is None else self._index[0].get(table)
        start = self._key_line(table, key)
        if start is None or fragment is None:
            return start
        squeezed = "".join(fragment.split())
        for number in range(start, len(lines) + 1):
            line = lines[number - 1]
            if number > start and _TABLE_HEADER.match(line):
                break
            if fragment in line or (squeezed and squeezed in "".join(line.split())):
                return number
        return start


#: Largest file read as a derivation file or comparison table (the shipped ones are < 20 kB).
MAX_FILE_BYTES = 4 * 1024 * 1024


def read_small_text(p: Path) -> str:
    r"""The UTF-8 text of a regular file of at most :data:`MAX_FILE_BYTES` (without the
    byte-order mark a Windows editor may write first). A missing file, a
    folder, a FIFO or a device (reading those could block or never end), a larger file, or
    text that is not UTF-8 raises :class:`InputFileError`."""
    import os
    import stat
    try:
        info = os.stat(p)
    except FileNotFoundError:
        raise InputFileError(p, "file not found") from None
    except OSError as exc:
        raise InputFileError(p, f"cannot read the file ({exc.strerror})") from None
    if stat.S_ISDIR(info.st_mode):
        raise InputFileError(p, "is a folder, expected a file")
    if not stat.S_ISREG(info.st_mode):
        kind = ("a FIFO" if stat.S_ISFIFO(info.st_mode) else "a socket"
                if stat.S_ISSOCK(info.st_mode) else "a device")
        raise InputFileError(p, f"is {kind}, not a regular file")
    if info.st_size > MAX_FILE_BYTES:
        raise InputFileError(p, f"file of {info.st_size} bytes; at most {MAX_FILE_BYTES} "
                                "(4 MiB) are read")
    try:
        with open(p, "rb") as fh:
            raw = fh.read(MAX_FILE_BYTES + 1)
        return raw[:MAX_FILE_BYTES].decode("utf-8-sig")    # a Windows editor's BOM dropped
    except UnicodeDecodeError as exc:
        raise InputFileError(p, f"not UTF-8 text (byte {exc.start})") from None
    except OSError as exc:
        raise InputFileError(p, f"cannot read the file ({exc.strerror})") from None


def key_line(path: str | Path, table: str | None, key: str) -> int | None:
    r"""The line of ``key`` in ``[table]`` of the file ``path`` (:meth:`SourceText.line_of`),
    or None where the file cannot be read: for an error found after the file was parsed."""
    try:
        return SourceText(Path(path), read_small_text(Path(path))).line_of(table, key)
    except (OSError, WheeledDynError):
        return None


def read_toml(path: str | Path) -> tuple[dict[str, Any], SourceText]:
    r"""Parse a TOML file. A missing or unreadable file, or a syntax error, raises
    :class:`InputFileError` (with the line and column tomllib reports)."""
    p = Path(path)
    text = read_small_text(p)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message = str(exc)
        found = _TOML_POSITION.search(message)
        line = column = None
        if found:
            line, column = int(found.group(1)), int(found.group(2))
            message = _TOML_POSITION.sub("", message).strip()
        elif "end of document" in message:
            line = len(text.splitlines()) or 1
        raise InputFileError(p, f"malformed TOML: {message}", line=line, column=column) from exc
    except RecursionError:
        raise InputFileError(p, "malformed TOML: arrays or tables nested too deeply") from None
    return data, SourceText(p, text)


def array_item_line(path: str | Path, table: str | None, key: str, index: int) -> int | None:
    r"""The line of item ``index`` (from 0) of the array ``key`` in ``[table]`` of the file
    ``path`` where the array is written one string a line after its opening bracket (as
    ``equations = [`` is); else the key's line (:func:`key_line`); None where neither is
    found: for an error found in one item after the file was parsed."""
    start = key_line(path, table, key)
    if start is None:
        return None
    try:
        lines = read_small_text(Path(path)).splitlines()
    except (OSError, WheeledDynError):
        return start
    if not lines[start - 1].rstrip().endswith("["):
        return start
    items = [n for n in range(start + 1, len(lines) + 1)
             if lines[n - 1].lstrip().startswith(('"', "'"))]
    ends = next((n for n in range(start + 1, len(lines) + 1)
                 if lines[n - 1].strip().startswith("]")), len(lines) + 1)
    items = [n for n in items if n < ends]
    return items[index] if index < len(items) else start

