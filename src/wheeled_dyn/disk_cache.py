r"""Where the toolkit keeps what it computed once and can reuse: ``$WHEELED_DYN_CACHE`` if set,
else ``~/.cache/wheeled_dyn``, one folder per kind of entry (``results/`` comparisons,
``symbolic/`` closed forms, ``urdf/`` outlines of URDF files, ``compiled/``, ``compare/``,
``report/`` printed forms). The rules (docs/cache.md) are those of a cache that only saves
time:

- an entry ``<root>/<kind>/<file>`` is written atomically (a private temporary file in the
  same folder, renamed), so a reader never sees half an entry;
- it is signed: :data:`MAGIC`, then HMAC-SHA256 under the cache's private key
  (:func:`~wheeled_dyn.cache_trust.signing_key`) of its name ``<kind>/<file>`` and its bytes,
  then the pickle. The signature is checked before anything is unpickled, so an entry that
  was altered, planted, written by other code or copied under another entry's name is never
  loaded;
- reading is best effort: a missing entry, one over :data:`MAX_ENTRY_BYTES`, one whose
  signature does not match, and any exception while it is read or unpickled, are a miss;
- writing is best effort: a folder that cannot be written (read-only, missing, full) gives
  one :class:`~wheeled_dyn.errors.CacheWarning` naming it, once per process, and the run goes
  on;
- only folders of the user running the check are used, and nothing is read or written when
  reuse is off (:mod:`wheeled_dyn.cache_trust`).

A :class:`DiskMemo` is a dictionary of printed forms (compiled code, text, LaTeX, MathML,
simplified display text) kept there between runs: printing the same expression again gives
the same text, so a check made again does not print it again. Its file is named by SymPy's
version and the code that prints, so text printed by other code is never served.
"""

from __future__ import annotations

import atexit
import hashlib
import hmac
import os
import pickle
import stat
import tempfile
from collections.abc import Callable, Hashable, Iterable
from pathlib import Path
from typing import TypeVar

from .cache_trust import (CACHE_ENV, REUSE_ENV, cache_root, reuse_enabled, signing_key,
                          trusted_folder, trusted_root, warn_once, without_reuse)

T = TypeVar("T")

#: First bytes of every entry (the format's version).
MAGIC = b"wdcache2"
#: Largest entry read (bytes): a bigger file is a miss, never loaded.
MAX_ENTRY_BYTES = 64 * 2 ** 20
_SIGNATURE = hashlib.sha256().digest_size


def _place(path: Path) -> tuple[Path, str, str]:
    r"""The root, the kind (folder) and the name ``<kind>/<file>`` of entry ``path``."""
    path = Path(path)
    return path.parent.parent, path.parent.name, f"{path.parent.name}/{path.name}"


def _signature(key: bytes, name: str, payload: bytes) -> bytes:
    return hmac.new(key, name.encode() + b"\0" + payload, hashlib.sha256).digest()


def store(path: Path, obj: object) -> bool:
    r"""Pickle ``obj``, signed, to the entry ``path`` = ``<root>/<kind>/<file>``, atomically.
    Best effort: True if it was written; False when reuse is off, the folder is not the
    user's, or it cannot be written (then one warning naming it, once per process), or
    ``obj`` cannot be pickled."""
    root, kind, name = _place(path)
    if (trusted_root(root, create=True) is None
            or trusted_folder(root, kind, create=True) is None
            or (key := signing_key(root, create=True)) is None):
        return False
    try:
        payload = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    except Exception:                     # a value that cannot be pickled: not kept
        return False
    tmp = None
    try:
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".pickle")
        with os.fdopen(fd, "wb") as fh:
            fh.write(MAGIC + _signature(key, name, payload) + payload)
        os.replace(tmp, path)
        tmp = None
    except OSError as exc:
        if tmp is not None and path.is_dir():        # the folder is fine: one entry is not
            warn_once(f"entry {path}", f"the cache entry {path} is a folder, not a file: "
                      "that result is not kept (only slower); remove it")
        else:
            warn_once(f"write {root}", f"the cache folder {path.parent} cannot be written "
                      f"({exc.strerror or exc}); results are not kept (only slower)")
        return False
    finally:
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass
    return True


def load(path: Path, kind: type[T]) -> T | None:
    r"""The entry at ``path`` if reuse is on, its folder is the user's, it is a regular file
    (not a link, a FIFO, a folder), its signature is the cache key's for its own name, and it
    unpickles to a ``kind``; else None (a miss, whatever went wrong)."""
    root, folder, name = _place(path)
    if (trusted_root(root) is None or trusted_folder(root, folder) is None
            or (key := signing_key(root)) is None):
        return None
    try:
        # never blocks (a FIFO planted as an entry), never follows a link
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
                     | getattr(os, "O_NOFOLLOW", 0))
        with os.fdopen(fd, "rb") as fh:
            st = os.fstat(fh.fileno())
            if not stat.S_ISREG(st.st_mode) or st.st_size > MAX_ENTRY_BYTES:
                return None
            data = fh.read(MAX_ENTRY_BYTES + 1)
        head = len(MAGIC) + _SIGNATURE
        if len(data) > MAX_ENTRY_BYTES or data[:len(MAGIC)] != MAGIC:
            return None
        payload = data[head:]
        if not hmac.compare_digest(data[len(MAGIC):head], _signature(key, name, payload)):
            return None
        obj = pickle.loads(payload)
    except Exception:                     # anything at all: a miss, computed again
        return None
    return obj if isinstance(obj, kind) else None


class DiskMemo:
    r"""Values computed from keys (an expression, its printed text ...), remembered in
    memory and in the file ``<cache>/<kind>/<name>-<digest>.pickle``, the digest over SymPy's
    version and the bytes of the ``code`` files that compute the values (:meth:`path`).

    :meth:`save` writes the entries made in this process, merged with what the file holds
    then, keeping the newest (those this process used counted new) within :data:`MEMO_LIMIT`
    entries and :data:`MEMO_BYTES` (the commands save when they write their reports, and
    every process at its exit). Best effort: two processes writing at once
    keep the last one's merge (the other's new entries are computed again next time), and a
    file that cannot be read or written is only slower.
    """

    def __init__(self, kind: str, name: str, code: Callable[[], Iterable[Path]]) -> None:
        self.kind, self.name, self._code = kind, name, code
        self._entries: dict | None = None     # read from the file, and made here
        self._first_path: Path | None = None  # the file they were read from
        self._made: dict = {}                 # made in this process, to be saved
        self._used: set = set()               # read from the file and used here
        self._unkept: dict = {}               # made here with reuse off: never saved
        if not _MEMOS:                        # a program using the API saves on exit
            atexit.register(save_memos)
        _MEMOS.append(self)

    def path(self) -> Path:
        r"""The file of this memo: its name with a digest of SymPy's version and the code it
        remembers the output of (read from the source files now; an unreadable one raises
        OSError)."""
        import sympy
        h = hashlib.sha256(sympy.__version__.encode())
        for code in sorted(self._code()):
            h.update(code.read_bytes())
        return cache_root() / self.kind / f"{self.name}-{h.hexdigest()[:16]}.pickle"

    def entries(self) -> dict:
        r"""The remembered entries (read from the file on first use); with reuse off, only
        those made in this process while it was off (never saved)."""
        if not reuse_enabled():
            return self._unkept
        if self._entries is None:
            try:
                self._first_path = self.path()
            except OSError:                   # the code's files cannot be read: remember
                return self._unkept           # nothing beyond this process
            self._entries = {**(load(self._first_path, dict) or {}), **self._made}
        return self._entries

    def get(self, key: Hashable, compute: Callable[[], T]) -> T:
        r"""The value remembered under ``key``, else ``compute()``, remembered. Entries are
        kept under the SHA-256 of the key's bytes (:func:`key_bytes`) (the file
        then holds no expressions to rebuild when read); a key that cannot be pickled is
        computed every time."""
        try:
            digest = hashlib.sha256(key_bytes(key)).digest()
        except Exception:
            return compute()
        found = self.entries()
        if digest not in found:
            found[digest] = compute()
            if found is not self._unkept:
                self._made[digest] = found[digest]
        elif found is not self._unkept:
            self._used.add(digest)
        return found[digest]

    def forget(self) -> None:
        r"""Drop what is in memory (the next use reads the file again)."""
        self._entries, self._made, self._unkept, self._used = None, {}, {}, set()
        self._first_path = None

    def save(self) -> None:
        r"""Write the entries to the file when this process made any (best effort)."""
        if not self._made or not reuse_enabled():
            return
        try:
            path = self.path()
        except OSError:                       # the code's files went away: keep nothing
            return
        if path != self._first_path:          # the code changed while this process ran: its
            return                            # entries are not the new code's
        entries = {**(load(path, dict) or {}), **(self._entries or {})}
        used = {k: entries[k] for k in self._used if k in entries}      # used here: newer
        entries = {**{k: v for k, v in entries.items() if k not in used}, **used,
                   **self._made}
        if store(path, _newest(entries)):
            self._made, self._used = {}, set()
            for old in path.parent.glob(f"{self.name}-*.pickle"):
                if old != path:               # made by other code: never read again
                    try:
                        old.unlink()
                    except OSError:
                        pass


#: The structure of expressions met in keys in this process (at most
#: :data:`STRUCTURE_LIMIT`): the same expression is looked up in several memos.
_STRUCTURE: dict = {}
STRUCTURE_LIMIT = 100_000


def _node(expr: object) -> object:
    r"""The structure of one SymPy node: its class and, recursively, its hashable content
    (what SymPy's ``==`` compares: the arguments in SymPy's canonical order, a symbol's name
    and assumptions, a number's digits and precision). A class SymPy did not define (an
    undefined function ``f``, a subclass of ours) is named with its keyword arguments
    (assumptions) where SymPy keeps them, else by its ``srepr``."""
    import sympy as sp
    if not isinstance(expr, sp.Basic):
        if isinstance(expr, tuple):
            return tuple(_node(e) for e in expr)
        return expr
    found = _STRUCTURE.get(expr)
    if found is not None:
        return found
    cls = type(expr)
    module = cls.__module__ or ""
    if module.startswith("sympy."):
        head: object = f"{module}.{cls.__qualname__}"
    elif hasattr(cls, "_kwargs"):                    # an undefined function f(x)
        head = ("function", cls.__name__, tuple(sorted(cls._kwargs.items())))
    else:
        head = ("srepr", sp.srepr(expr))
    node = (head, tuple(_node(e) for e in expr._hashable_content()))
    if len(_STRUCTURE) >= STRUCTURE_LIMIT:
        _STRUCTURE.clear()
    _STRUCTURE[expr] = node
    return node


def canonical(key: object) -> object:
    r"""``key`` with each SymPy object replaced by its structure (:func:`_node`; in tuples,
    lists, frozensets and dictionaries, recursively). A pickle records which parts of an
    expression are one object in memory, and that depends on how the process built it
    (computed, or read back from the disk cache's closed forms), so equal expressions pickled
    to different bytes in different runs and a remembered form was never found again. The
    structure holds what SymPy's ``==`` compares and nothing else: equal expressions give
    equal keys in every process, unequal ones different keys (a
    :class:`~sympy.core.symbol.Dummy`'s index differs per process: a miss). It is read from
    the expression's own arguments, which SymPy keeps in its canonical order (``srepr``,
    used before, sorted the terms again at every node and took a tenth of a report's time)."""
    import sympy as sp
    if isinstance(key, sp.Basic):
        return ("sympy-structure", _node(key))
    if isinstance(key, sp.MatrixBase):
        return ("sympy-matrix", type(key).__name__, key.shape, tuple(_node(e) for e in key))
    if isinstance(key, (tuple, list)):
        return type(key).__name__, tuple(canonical(k) for k in key)
    if isinstance(key, frozenset):
        return "frozenset", tuple(sorted((canonical(k) for k in key), key=repr))
    if isinstance(key, dict):
        return "dict", tuple((canonical(k), canonical(v)) for k, v in key.items())
    return key


def key_bytes(key: object) -> bytes:
    r"""The bytes a :class:`DiskMemo` digests for ``key``: the pickle of its
    :func:`canonical` form, equal for equal keys in every process."""
    return pickle.dumps(canonical(key), protocol=4)


#: Entries a :class:`DiskMemo` file keeps (the newest, those used last counted new), and
#: the most bytes it holds (every command reads the whole file: 20 000 compiled functions'
#: sources were 33 MB, a quarter of a second read at every start).
MEMO_LIMIT, MEMO_BYTES = 20000, 4 * 2 ** 20


def _newest(entries: dict) -> dict:
    r"""The last :data:`MEMO_LIMIT` of ``entries`` (in insertion order), fewer (the oldest
    half dropped at a time) until they pickle to at most :data:`MEMO_BYTES`."""
    items = list(entries.items())[-MEMO_LIMIT:]
    while len(items) > 1 and len(pickle.dumps(dict(items), protocol=pickle.HIGHEST_PROTOCOL)) \
            > MEMO_BYTES:
        items = items[len(items) // 2:]
    return dict(items)
_MEMOS: list[DiskMemo] = []


def save_memos() -> None:
    r""":meth:`DiskMemo.save` for every memo of the process."""
    for memo in _MEMOS:
        memo.save()


__all__ = ["CACHE_ENV", "MAGIC", "canonical", "key_bytes", "MAX_ENTRY_BYTES", "REUSE_ENV", "DiskMemo", "cache_root", "load",
           "reuse_enabled", "save_memos", "store", "without_reuse"]
