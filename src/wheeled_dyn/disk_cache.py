r"""Where the toolkit keeps what it computed once and can reuse: ``$WHEELED_DYN_CACHE`` if set,
else ``~/.cache/wheeled_dyn``, one folder per kind of entry (``symbolic/`` closed forms,
``urdf/`` outlines of URDF files). Entries are pickles written atomically (a temporary file in
the same folder, renamed), so a reader never sees half an entry; an entry that cannot be read
is treated as missing.
"""

from __future__ import annotations

import os
import pickle
import tempfile
import warnings
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


__all__ = ["CACHE_ENV", "cache_root", "load", "store"]
