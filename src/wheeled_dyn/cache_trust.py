r"""Whether the disk cache may be used, and with which key: the reuse switch, private folders,
the owner and mode checks made before anything is read, the signing key, the warnings.

A remembered result or generated code only saves time (docs/cache.md). The cache is read only
from folders no other user can write, and only entries signed with a key no other user can
read are taken:

- **The switch.** ``WHEELED_DYN_REUSE=0`` (or :func:`without_reuse`, the commands'
  ``--no-cache``) turns the disk cache off: nothing remembered is read (no result, no code,
  no closed form), nothing is written. ``WHEELED_DYN_REUSE=forms`` keeps the printed and
  compiled forms, closed forms and URDF outlines but no results: every comparison is made
  again (the tests and the benchmarks run so).
- **Private folders.** The cache root (``$WHEELED_DYN_CACHE``, else ``~/.cache/wheeled_dyn``)
  and its folders are created ``0700`` whatever the umask. Before an entry is read or written,
  the root and the entry's folder must be directories owned by the user running the check and
  writable by no one else, and every folder above the root must be owned by that user or by
  root and writable by no one else unless its sticky bit is set (``/tmp``) — the rules of
  ssh's StrictModes and of pip's cache. A folder that fails is not used: one warning line
  naming it and why, then the run goes on without the cache.
- **The key.** ``<root>/signing-key``: :data:`KEY_BYTES` random bytes, created ``0600``
  (written whole, then linked into place, so no reader sees half a key). A key file not owned
  by the user, readable or writable by anyone else, or of the wrong size turns the cache off
  the same way (:mod:`.disk_cache` signs each entry with it).
- **Best effort.** A cache that cannot be created or written (read-only, missing, full) makes
  the run slower, never fail: one warning naming the folder, once per process.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import stat
import tempfile
import warnings
from collections.abc import Iterator
from pathlib import Path

from .errors import CacheWarning

#: Environment variable naming the cache directory.
CACHE_ENV: str = "WHEELED_DYN_CACHE"
#: Environment variable: "0" turns every use of the disk cache off.
REUSE_ENV: str = "WHEELED_DYN_REUSE"
#: The signing key's file name in the cache root, and its size in bytes.
KEY_NAME, KEY_BYTES = "signing-key", 32
#: Mode of the folders the cache creates.
FOLDER_MODE = 0o700

_switched_off = 0                        # depth of :func:`without_reuse` blocks
_warned: set[str] = set()                # warnings given in this process
_keys: dict[str, bytes] = {}             # signing key by cache root (read once per process)


def cache_root(root: str | Path | None = None) -> Path:
    r"""The cache directory (not created here): ``root``, else ``$WHEELED_DYN_CACHE``, else
    ``~/.cache/wheeled_dyn`` (without a home folder: ``wheeled_dyn-<uid>`` in the temporary
    folder, which the checks below then judge like any other)."""
    if root is None:
        root = os.environ.get(CACHE_ENV)
    if not root:
        try:
            return Path.home() / ".cache" / "wheeled_dyn"
        except (RuntimeError, KeyError):
            return Path(tempfile.gettempdir()) / f"wheeled_dyn-{_uid()}"
    return Path(root)


#: Values of ``$WHEELED_DYN_REUSE`` that turn the disk cache off, and the one that keeps
#: everything but results.
OFF_VALUES, FORMS_ONLY = ("0", "false", "no", "off"), "forms"


def _setting() -> str:
    return os.environ.get(REUSE_ENV, "1").strip().lower()


def reuse_enabled() -> bool:
    r"""Whether the disk cache may be used: ``$WHEELED_DYN_REUSE`` is not ``0`` and no
    :func:`without_reuse` block is running."""
    return _switched_off == 0 and _setting() not in OFF_VALUES


def results_reused() -> bool:
    r"""Whether comparison results may be reused: the cache is on and
    ``$WHEELED_DYN_REUSE`` is not ``forms``."""
    return reuse_enabled() and _setting() != FORMS_ONLY


@contextlib.contextmanager
def without_reuse(off: bool = True) -> Iterator[None]:
    r"""A block that runs with the disk cache off (as ``WHEELED_DYN_REUSE=0``); processes
    forked inside it inherit that. ``off=False`` changes nothing (for callers that pass a
    flag through)."""
    global _switched_off
    _switched_off += bool(off)
    try:
        yield
    finally:
        _switched_off -= bool(off)


def warn_once(key: str, message: str) -> None:
    r"""Warn ``message`` (a :class:`~wheeled_dyn.errors.CacheWarning`) once per process for
    ``key``."""
    if key not in _warned:
        _warned.add(key)
        warnings.warn(CacheWarning(message), stacklevel=3)


def _uid() -> int | None:
    r"""The user the checks are made for; None where the system has no POSIX owners (there
    the file system's own permissions are all there is)."""
    return os.geteuid() if hasattr(os, "geteuid") else None


def _why_untrusted(folder: Path, own: bool) -> str | None:
    r"""Why ``folder`` may not be trusted, or None. ``own``: it must be the user's and
    writable by no one else; else (a folder above) the user's or root's, and writable by
    others only with the sticky bit."""
    try:
        st = os.stat(folder)
    except OSError as exc:
        return f"cannot be examined ({exc.strerror})"
    if not stat.S_ISDIR(st.st_mode):
        return "is not a folder"
    if _uid() is None:
        return None
    owners = (_uid(),) if own else (_uid(), 0)
    if st.st_uid not in owners:
        return f"belongs to another user (uid {st.st_uid})"
    shared = st.st_mode & (stat.S_IWGRP | stat.S_IWOTH)
    if shared and (own or not st.st_mode & stat.S_ISVTX):
        return f"can be written by other users (mode {stat.S_IMODE(st.st_mode):04o})"
    return None


def _make_private(folder: Path) -> None:
    r"""Create ``folder`` and any missing folder above it, each ``0700`` whatever the umask."""
    missing = []
    p = folder
    while not os.path.lexists(p):
        missing.append(p)
        if p.parent == p:
            break
        p = p.parent
    for p in reversed(missing):
        try:
            os.mkdir(p, FOLDER_MODE)
        except FileExistsError:          # made meanwhile by another process: checked below
            continue
        os.chmod(p, FOLDER_MODE)


def _created(folder: Path, root: Path, then: str) -> bool:
    r"""``folder`` exists or is made private now; where it cannot be made, one warning (once
    per ``root``) naming it and what ``then`` happens, and False."""
    if os.path.lexists(folder):
        return True
    try:
        _make_private(folder)
    except OSError as exc:
        warn_once(f"write {root}", f"the cache folder {folder} cannot be created "
                  f"({exc.strerror}); {then}")
        return False
    return True


def trusted_root(root: str | Path | None = None, create: bool = False) -> Path | None:
    r"""The cache root if the cache may be used (the switch is on, the root and every folder
    above it pass the checks of the module docstring), else None after one warning. With
    ``create``, a missing root is created private first."""
    if not reuse_enabled():
        return None
    path = cache_root(root)
    if create and not _created(path, path, "running without it (only slower)"):
        return None
    if not os.path.isdir(path):
        if create:
            warn_once(f"write {path}", f"the cache folder {path} is not a folder; running "
                      "without it (only slower)")
        return None
    real = Path(os.path.realpath(path))
    why = _why_untrusted(real, own=True)
    above = real.parent
    while why is None and above != above.parent:
        if (reason := _why_untrusted(above, own=False)) is not None:
            why = f"is inside {above}, which {reason}"
        above = above.parent
    if why is not None:
        warn_once(f"trust {real}", f"the cache folder {path} {why}: not used (make it "
                  f"yours and private: chown $USER and chmod 700 {path}; or set {CACHE_ENV} "
                  "to a private folder)")
        return None
    return path


def trusted_folder(root: Path, kind: str, create: bool = False) -> Path | None:
    r"""The folder ``<root>/<kind>`` if it may be used (created private with ``create``),
    else None (with one warning when it exists and fails the checks)."""
    folder = root / kind
    if create and not _created(folder, root, "results are not kept (only slower)"):
        return None
    if not os.path.lexists(folder):
        return None
    if (why := _why_untrusted(folder, own=True)) is not None or os.path.islink(folder):
        warn_once(f"trust {folder}", f"the cache folder {folder} {why or 'is a link'}: not "
                  f"used (remove it, or set {CACHE_ENV} to a private folder)")
        return None
    return folder


def signing_key(root: Path, create: bool = False) -> bytes | None:
    r"""The cache's signing key (:data:`KEY_NAME` in ``root``), read once per process;
    created with ``create`` when missing. None when there is none, or when the file is not
    private (then with one warning: the cache is not used)."""
    name = str(root)
    if name in _keys:
        return _keys[name]
    path = root / KEY_NAME
    if create and not os.path.lexists(path):
        _new_key(root, path)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
                     | getattr(os, "O_NOFOLLOW", 0))
    except FileNotFoundError:
        return None
    except OSError as exc:
        warn_once(f"trust {path}", f"the cache's key {path} cannot be read ({exc.strerror}): "
                  "the cache is not used")
        return None
    try:
        st = os.fstat(fd)
        key = os.read(fd, KEY_BYTES + 1) if stat.S_ISREG(st.st_mode) else b""
    except OSError as exc:
        warn_once(f"trust {path}", f"the cache's key {path} cannot be read ({exc.strerror}): "
                  "the cache is not used")
        return None
    finally:
        os.close(fd)
    if not stat.S_ISREG(st.st_mode):
        warn_once(f"trust {path}", f"the cache's key {path} is not a regular file: the cache "
                  "is not used (remove it to start anew)")
        return None
    if _uid() is not None and (st.st_uid != _uid() or st.st_mode & 0o077):
        warn_once(f"trust {path}", f"the cache's key {path} is not private to this user "
                  f"(owner uid {st.st_uid}, mode {stat.S_IMODE(st.st_mode):04o}): the cache "
                  "is not used (delete the file to start anew)")
        return None
    if len(key) != KEY_BYTES:               # damaged: a new key (every entry is then a miss)
        if not create:
            return None
        _new_key(root, path, replace=True)
        return signing_key(root)
    _keys[name] = key
    return key


def _new_key(root: Path, path: Path, replace: bool = False) -> None:
    r"""Write a new key to a private temporary file and link it to ``path`` (the first
    process to do so wins; the others read its key), or rename it over ``path`` with
    ``replace`` (a damaged key)."""
    tmp = root / f".{KEY_NAME}.{os.getpid()}.{secrets.token_hex(4)}"
    try:
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        try:
            os.fchmod(fd, 0o600)
            os.write(fd, secrets.token_bytes(KEY_BYTES))
        finally:
            os.close(fd)
        if replace:
            os.replace(tmp, path)
        else:
            os.link(tmp, path)
    except FileExistsError:
        pass
    except OSError as exc:
        warn_once(f"write {root}", f"the cache folder {root} cannot be written "
                  f"({exc.strerror}); running without it (only slower)")
    finally:
        with contextlib.suppress(OSError):
            os.unlink(tmp)


def forget_keys() -> None:
    r"""Read the keys again on next use, and warn again (for tests that change the folders)."""
    _keys.clear()
    _warned.clear()


__all__ = ["CACHE_ENV", "FOLDER_MODE", "FORMS_ONLY", "KEY_NAME", "OFF_VALUES", "REUSE_ENV",
           "cache_root", "forget_keys", "results_reused", "reuse_enabled", "signing_key",
           "trusted_folder", "trusted_root", "warn_once", "without_reuse"]
