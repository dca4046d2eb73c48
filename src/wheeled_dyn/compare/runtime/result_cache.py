r"""Results of comparisons kept in the disk cache (``results/``), so that running a check or a
report again recomputes only what changed.

A derivation file's :class:`~.result.DerivationResult` is reused when nothing it depends on
changed. Its key is a SHA-256 over:

- the package's own files (code and shipped data), and the versions of NumPy, SymPy and
  Pinocchio;
- the derivation file's text and the step files beside it (``*_steps.toml``);
- its model's model file and URDF texts;
- the grid: samples, parameter sets and seed.

The reproduced comparison tables of a group are keyed the same way, by every file of the
group. Setting ``WHEELED_DYN_REUSE=0`` turns reuse off (the tests do, except where they test
it).
"""

from __future__ import annotations

import hashlib
import importlib.metadata
import os
from collections.abc import Callable, Iterable
from functools import lru_cache
from pathlib import Path

from ...disk_cache import cache_root, load, store

#: Environment variable: "0" turns the reuse of results off.
REUSE_ENV = "WHEELED_DYN_REUSE"
_PACKAGE = Path(__file__).resolve().parents[1]


def reuse_enabled() -> bool:
    return os.environ.get(REUSE_ENV, "1") != "0"


@lru_cache(maxsize=1)
def package_digest() -> str:
    r"""SHA-256 of the package's files and of the numerical libraries' versions."""
    h = hashlib.sha256()
    for name in ("numpy", "sympy", "pin"):
        try:
            h.update(importlib.metadata.version(name).encode())
        except importlib.metadata.PackageNotFoundError:
            h.update(b"-")
    for path in sorted(_PACKAGE.rglob("*")):
        if path.is_file() and path.suffix in (".py", ".toml", ".json", ".tex"):
            h.update(str(path.relative_to(_PACKAGE)).encode())
            h.update(path.read_bytes())
    return h.hexdigest()


def _texts(paths: Iterable[Path]) -> list[bytes]:
    out = []
    for p in sorted(set(paths)):
        out.append(str(p).encode())
        out.append(p.read_bytes() if p.is_file() else b"(missing)")
    return out


def _model_files(model: str) -> list[Path]:
    from ...models.model_file import is_model_path
    from ...models.registry import model_entry, model_key
    key = model_key(model)
    files = [Path(key)] if is_model_path(key) else []
    spec = model_entry(model).spec()
    return [*files, Path(spec.urdf)]


def result_key(path: Path, model: str, grid: tuple, extra: Iterable[Path] = ()) -> str:
    r"""The key of the result of derivation ``path`` (on model ``model``) on ``grid``."""
    path = Path(path).resolve()
    h = hashlib.sha256(package_digest().encode())
    for item in _texts([path, *path.parent.glob("*_steps.toml"), *_model_files(model), *extra]):
        h.update(item)
    h.update(repr(grid).encode())
    return h.hexdigest()


def reused(key: str, kind: type, compute: Callable[[], object]) -> object:
    r"""The entry ``key`` of the results cache, or ``compute()`` stored under it."""
    if not reuse_enabled():
        return compute()
    entry = cache_root() / "results" / f"{key}.pickle"
    found = load(entry, kind)
    if found is not None:
        return found
    value = compute()
    try:
        store(entry, value)
    except (OSError, TypeError, AttributeError):   # unwritable, or a value that cannot pickle
        pass
    return value


__all__ = ["REUSE_ENV", "package_digest", "result_key", "reuse_enabled", "reused"]
