r"""Output places checked before any computing, and files written whole or not at all.

:func:`check_output_folder` and :func:`check_output_file` are called by the commands before
they start computing: a place that cannot be written (a file where a folder is expected, a
folder where a file is expected, a name longer than the file system allows, a read-only place)
raises :class:`~wheeled_dyn.errors.InputFileError` at once instead of after minutes of work.
The check writes and removes a probe file in the nearest existing folder (``os.access`` says
yes to root even on a read-only file system), and creates nothing.

:func:`write_atomic` and :func:`write_files_atomic` write to a temporary name (``.NAME.XXXX``)
in the target folder and rename it over the final name (``os.replace`` is atomic): a failure
(a full disk, Ctrl-C) leaves the previous file or none, never half of one, and removes the
temporary files on every path out. The files get the mode ``open()`` would give them
(:data:`FILE_MODE` less the umask: 0644 under the usual umask 022, 0600 under 077).
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path

from .errors import InputFileError

#: Longest name of one path component, in bytes (POSIX file systems: 255).
NAME_MAX = 255
#: Mode of the files written, before the umask (as ``open()`` creates files: 0666).
FILE_MODE = 0o666


def _check_names(p: Path) -> None:
    for part in p.parts:
        size = len(os.fsencode(part))
        if size > NAME_MAX:
            raise InputFileError(p, f"a name of {size} bytes ({part[:24]}...); file names are "
                                    f"at most {NAME_MAX} bytes")


def _probe(folder: Path, target: Path) -> None:
    r"""Raise unless a file can be created (and removed) in the existing ``folder``."""
    try:
        fd, tmp = tempfile.mkstemp(prefix=".wheeled_dyn_probe.", dir=folder)
    except OSError as exc:
        raise InputFileError(target, f"cannot write in {folder} ({exc.strerror})") from None
    os.close(fd)
    os.unlink(tmp)


def _nearest_existing(p: Path) -> tuple[Path, Path]:
    r"""The nearest existing ancestor of ``p`` (``p`` itself if it exists) and the first
    missing component below it."""
    current, missing = p, p
    while not current.exists():
        missing = current
        if current.parent == current:
            break
        current = current.parent
    return current, missing


def check_output_folder(path: str | Path) -> Path:
    r"""Check that ``path`` is, or can be created as, a writable folder. Returns it."""
    p = Path(path)
    _check_names(p)
    existing, _ = _nearest_existing(p)
    if not existing.is_dir():
        what = "is a file" if existing == p else f"cannot be created: {existing} is a file"
        raise InputFileError(p, f"{what}, expected a folder")
    _probe(existing, p)
    return p


def check_output_file(path: str | Path, suffix: str | None = None) -> Path:
    r"""Check that ``path`` names a file that can be written (its folder existing or
    creatable, writable; the path not a folder). ``suffix`` (e.g. ``".html"``), if given, is
    required. Returns the path."""
    text = os.fspath(path)
    p = Path(text)
    _check_names(p)
    if text.endswith(os.sep) or p.is_dir():
        raise InputFileError(p, "is a folder, expected a file name"
                                + (f" ending in {suffix}" if suffix else ""))
    if suffix and p.suffix.lower() != suffix:
        raise InputFileError(p, f"expected a file name ending in {suffix}")
    existing, _ = _nearest_existing(p.parent)
    if not existing.is_dir():
        raise InputFileError(p, f"cannot be created: {existing} is a file, not a folder")
    _probe(existing, p)
    return p


def current_umask() -> int:
    r"""The process's umask: from ``/proc/self/status`` where Linux gives it, else by setting
    it and setting it back (POSIX has no getter)."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def write_files_atomic(files: Mapping[str, str | bytes], folder: str | Path) -> list[Path]:
    r"""Write ``files`` (name → text or bytes) into ``folder`` (created if needed), all or
    none: every file is staged under a temporary name first, and the renames happen only when
    all are written; on a failure the folders made for them are removed too (a full disk left
    an empty report folder). Returns the final paths."""
    out = Path(folder)
    made = [p for p in (out, *out.parents) if not p.exists()]       # the deepest first
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        _remove([], made)
        raise InputFileError(out, f"cannot create the folder: {exc.strerror}") from None
    staged: list[tuple[Path, Path]] = []
    mode = FILE_MODE & ~current_umask()      # as open() would create it
    try:
        for file, data in files.items():
            fd, tmp = tempfile.mkstemp(prefix=f".{file}.", dir=out)
            staged.append((Path(tmp), out / file))
            with os.fdopen(fd, "wb") as fh:
                fh.write(data if isinstance(data, bytes) else data.encode("utf-8"))
            os.chmod(tmp, mode)
        for _, final in staged:                   # nothing replaced where one cannot be
            if final.is_dir():
                raise IsADirectoryError(21, "Is a directory", str(final))
        for staged_file, final in staged:
            os.replace(staged_file, final)
    except OSError as exc:
        _remove(staged, made)
        finals = {str(tmp): final for tmp, final in staged}
        # a write that fails names no file (a full disk): the one being written
        name = exc.filename if isinstance(exc.filename, str) else \
            staged[-1][1] if staged else out
        name = finals.get(str(name), name)
        raise InputFileError(out, f"cannot write {Path(name).name} ({exc.strerror})") from None
    except BaseException:
        _remove(staged, made)
        raise
    return [final for _, final in staged]


def write_atomic(path: str | Path, data: str | bytes) -> Path:
    r"""Write one file whole or not at all (its folder created if needed). Returns the path."""
    p = Path(path)
    return write_files_atomic({p.name: data}, p.parent)[0]


def _remove(staged: list[tuple[Path, Path]], made: Sequence[Path] = ()) -> None:
    r"""The ``staged`` temporary files, and the folders ``made`` for them (the deepest first;
    each only where left empty)."""
    for tmp, _ in staged:
        try:
            tmp.unlink(missing_ok=True)
        except OSError:
            pass
    for folder in made:
        try:
            folder.rmdir()
        except OSError:
            pass
