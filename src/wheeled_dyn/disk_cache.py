r"""Where the toolkit keeps what it computed once and can reuse: ``$WHEELED_DYN_CACHE`` if set,
else ``~/.cache/wheeled_dyn``, one folder per kind of entry (``symbolic/`` closed forms,
``urdf/`` outlines of URDF files). Entries are pickles written atomically (a temporary file in
the same folder, renamed), so a reader never sees half an entry; an entry that cannot be read
is treated as missing.

A :class:`DiskMemo` is a dictionary of printed forms (compiled code, text, LaTeX, MathML,
simplified display text) kept there between runs: printing the same expression again gives
the same text, so a check made again does not print it again. Its file is named by SymPy's version and the code that
prints, so text printed by other code is never served.
"""

from __future__ import annotations

import atexit
import hashlib
import os
import pickle
import tempfile
import warnings
from collections.abc import Callable, Hashable, Iterable
from pathlib import Path

#: Environment variable naming the cache directory.
CACHE_ENV: str = "WHEELED_DYN_CACHE"


def cache_root(root: str | Path | None = None) -> Path:
    r"""The cache directory (not created here)."""
    if root is None:
        root = os.environ.get(CACHE_ENV) or Path.home() / ".cache" / "wheeled_dyn"
    return Path(root)


def store(path: Path, obj: object) -> None:
    r"""Pickle ``obj`` to ``path`` atomically (a temporary file in the same folder, renamed)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".pickle")
    try:
        with os.fdopen(fd, "wb") as fh:
            pickle.dump(obj, fh, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def load(path: Path, kind: type, warn: bool = False) -> object | None:
    r"""The entry at ``path`` if it is a readable pickle of a ``kind``, else None; with
    ``warn``, an entry that exists but cannot be used says so (it is then made again)."""
    try:
        with path.open("rb") as fh:
            obj = pickle.load(fh)
    except FileNotFoundError:
        return None
    except (OSError, EOFError, pickle.UnpicklingError, AttributeError, ImportError,
            TypeError, ValueError) as exc:
        if warn:
            warnings.warn(f"cache entry {path} is unreadable ({exc}); made again", stacklevel=3)
        return None
    if isinstance(obj, kind):
        return obj
    if warn:
        warnings.warn(f"cache entry {path} holds {type(obj).__name__}; made again",
                      stacklevel=3)
    return None


class DiskMemo:
    r"""Values computed from keys (an expression, its printed text ...), remembered in
    memory and in the file ``<cache>/<kind>/<name>-<digest>.pickle``, the digest over SymPy's
    version and the bytes of the ``code`` files that compute the values (:meth:`path`).

    :meth:`save` writes the entries made in this process, merged with what the file holds
    then, keeping the newest :data:`MEMO_LIMIT` (the commands save when they write their
    reports, and every process at its exit). Best effort: two processes writing at once
    keep the last one's merge (the other's new entries are computed again next time), and a
    file that cannot be read or written is only slower.
    """

    def __init__(self, kind: str, name: str, code: Callable[[], Iterable[Path]]) -> None:
        self.kind, self.name, self._code = kind, name, code
        self._entries: dict | None = None
        self._new = False
        if not _MEMOS:                        # a program using the API saves on exit
            atexit.register(save_memos)
        _MEMOS.append(self)

    def path(self) -> Path:
        import sympy
        h = hashlib.sha256(sympy.__version__.encode())
        for code in sorted(self._code()):
            h.update(code.read_bytes())
        return cache_root() / self.kind / f"{self.name}-{h.hexdigest()[:16]}.pickle"

    def entries(self) -> dict:
        r"""The remembered entries (read from the file on first use)."""
        if self._entries is None:
            self._entries = load(self.path(), dict) or {}
        return self._entries

    def get(self, key: Hashable, compute: Callable[[], object]) -> object:
        r"""The value remembered under ``key``, else ``compute()``, remembered. Entries are
        kept under a digest of the key's pickle (a SymPy expression pickles to the same bytes
        in every process, and the file then holds no expressions to rebuild when read); a
        key that cannot be pickled is computed every time."""
        try:
            digest = hashlib.sha1(pickle.dumps(key, protocol=4)).digest()
        except (pickle.PicklingError, TypeError, AttributeError, RecursionError):
            return compute()
        store_ = self.entries()
        if digest not in store_:
            store_[digest] = compute()
            self._new = True
        return store_[digest]

    def forget(self) -> None:
        r"""Drop what is in memory (the next use reads the file again)."""
        self._entries, self._new = None, False

    def save(self) -> None:
        r"""Write the entries to the file when this process added any."""
        if not self._new or self._entries is None:
            return
        path = self.path()
        entries = {**(load(path, dict) or {}), **self._entries}
        try:
            store(path, dict(list(entries.items())[-MEMO_LIMIT:]))
            for old in path.parent.glob(f"{self.name}-*.pickle"):
                if old != path:               # made by other code: never read again
                    old.unlink(missing_ok=True)
        except (OSError, pickle.PicklingError, TypeError, AttributeError):
            pass
        self._new = False


#: Entries a :class:`DiskMemo` file keeps (the newest).
MEMO_LIMIT = 20000
_MEMOS: list[DiskMemo] = []


def save_memos() -> None:
    r""":meth:`DiskMemo.save` for every memo of the process."""
    for memo in _MEMOS:
        memo.save()


__all__ = ["CACHE_ENV", "DiskMemo", "cache_root", "load", "save_memos", "store"]
