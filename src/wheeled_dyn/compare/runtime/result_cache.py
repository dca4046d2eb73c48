r"""Results of comparisons kept in the disk cache (``results/``), so that running a check or a
report again recomputes only what changed. A remembered result only saves time: it is served
only for exactly the inputs it was computed from (docs/cache.md).

A derivation file's :class:`~.result.DerivationResult` is reused when nothing it depends on
changed. Its key is a SHA-256 over:

- the package's own files (code and shipped data), and the versions of NumPy, SymPy and
  Pinocchio;
- the path and text of every file it depends on (:func:`dependencies`): the derivation file,
  the step files beside it (``*_steps.toml``), its model's model file and URDF;
- the grid: samples, parameter sets and seed.

An entry holds its key beside the result, and is taken only when that key is the one asked
for and the result is that of the derivation asked for (its path); the disk cache's signature
(:mod:`wheeled_dyn.disk_cache`) covers both. A result is stored only when none of those files
changed while it was computed (the key is made again after, and the derivation file is the
one that was parsed: :func:`note_parsed`), so a file saved during a comparison never gets the
result of its previous text.

The reproduced comparison tables of a group are keyed the same way, by every file of the
group. Setting ``WHEELED_DYN_REUSE=0`` (or the commands' ``--no-cache``) turns every reuse
off; ``WHEELED_DYN_REUSE=forms`` turns off the reuse of results only (the tests run so,
except where they test it).
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterable
from functools import lru_cache
from pathlib import Path
from typing import TypeVar

from ...cache_trust import REUSE_ENV, results_reused, reuse_enabled
from ...disk_cache import cache_root, load, store
from ...paths import PACKAGE_DIR, file_stamp, resolved

T = TypeVar("T")

_PACKAGE = PACKAGE_DIR                  # every file of the package, not only compare/'s
#: The :func:`~wheeled_dyn.paths.file_stamp` of each derivation file when it was
#: parsed (:func:`note_parsed`); forked workers inherit it.
_PARSED: dict[Path, tuple | None] = {}


@lru_cache(maxsize=1)
def package_digest() -> str:
    r"""SHA-256 of the package's files and of the numerical libraries' versions."""
    import importlib.metadata          # here: it loads the email package, needed nowhere else
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


def dependencies(path: Path, model: str, extra: Iterable[Path] = ()) -> list[Path]:
    r"""Every file the result of derivation ``path`` on ``model`` depends on, sorted: the file,
    the step files beside it, the model's model file and URDF, and ``extra``."""
    from ...models.registry import model_files
    path = resolved(path)
    return sorted({path, *path.parent.glob("*_steps.toml"), *model_files(model),
                   *(Path(p) for p in extra)})


def note_parsed(paths: Iterable[Path]) -> None:
    r"""Note the stamps of derivation files about to be parsed: their results are stored only
    if they are still those files when the comparison ends."""
    from ...derivations.builtin import derivation_files
    for p in derivation_files(list(paths)):
        _PARSED[resolved(p)] = file_stamp(p)


def _texts(paths: Iterable[Path]) -> list[bytes]:
    out = []
    for p in sorted(set(paths)):
        out.append(str(p).encode() + b"\0")
        try:
            data = p.read_bytes()
        except OSError:
            data = b"\0(missing)"
        out.append(len(data).to_bytes(8, "little") + data)
    return out


def result_key(path: Path, model: str, grid: tuple, extra: Iterable[Path] = ()) -> str:
    r"""The key of the result of derivation ``path`` (on model ``model``) on ``grid``."""
    h = hashlib.sha256(package_digest().encode())
    for item in _texts(dependencies(path, model, extra)):
        h.update(item)
    h.update(repr(grid).encode())
    return h.hexdigest()


def reused(key: Callable[[], str], kind: type[T], compute: Callable[[], T],
           fits: Callable[[T], bool] = lambda value: True,
           parsed: Path | None = None) -> T:
    r"""The result remembered under ``key()``, else ``compute()``, stored under it.

    A remembered entry is taken only if it holds that key, a ``kind`` and ``fits(value)``.
    The value computed is stored only if ``key()`` is the same after the computation and,
    for a derivation file ``parsed``, the file is the one :func:`note_parsed` saw."""
    if not results_reused():
        return compute()
    before = key()
    entry = cache_root() / "results" / f"{before}.pickle"
    found = load(entry, tuple)
    if (found is not None and len(found) == 2 and found[0] == before
            and isinstance(found[1], kind) and fits(found[1])):
        return found[1]
    value = compute()
    unchanged = parsed is None or _PARSED.get(resolved(parsed), ()) == file_stamp(parsed)
    if unchanged and key() == before:
        store(entry, (before, value))
    return value


__all__ = ["REUSE_ENV", "dependencies", "note_parsed", "package_digest",
           "result_key", "results_reused", "reuse_enabled", "reused"]
