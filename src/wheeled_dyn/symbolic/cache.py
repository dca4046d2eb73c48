r"""On-disk cache of :class:`~.model.SymbolicModel` results.

The key is a SHA-256 of everything the result depends on: each joint's type, axis, parent, name
and placement (floats in exact hexadecimal), the armature and gravity, the resolved standard
parameters (numbers or SymPy ``srepr``), the coordinate names, the ``simplify`` flag, the SymPy
version and the source text of this package (so a code change invalidates old entries). Values
are pickles of the SymPy objects, signed and written atomically by
:mod:`wheeled_dyn.disk_cache` (an entry is taken only with its signature for its own name, the
key; anything unreadable is derived again). The directory is ``$WHEELED_DYN_CACHE`` if set,
else ``~/.cache/wheeled_dyn``; entries live under ``symbolic/``. With reuse off
(``WHEELED_DYN_REUSE=0``) nothing is read or written.
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping, Sequence
from functools import lru_cache
from pathlib import Path

import numpy as np
import pinocchio as pin
import sympy as sp

from ..disk_cache import CACHE_ENV, cache_root, load, store
from .kinematics import joint_kind, resolve_translations
from .model import SymbolicModel, symbolic_model
from .parameters import resolve_parameters

def cache_dir(root: str | Path | None = None) -> Path:
    """The directory of cached symbolic models (not created here)."""
    return cache_root(root) / "symbolic"


@lru_cache(maxsize=1)
def _code_digest() -> str:
    h = hashlib.sha256()
    for path in sorted(Path(__file__).parent.glob("*.py")):
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()


def _floats(a) -> str:
    return ",".join(float(x).hex() for x in np.asarray(a, dtype=float).reshape(-1))


def model_fingerprint(model: pin.Model, params: Mapping[int, Sequence] | None = None,
                      coordinate_names: Sequence[str] | None = None, gravity=None,
                      simplify: bool = True, translations: Mapping | None = None,
                      armature: Sequence | None = None, real: bool = False) -> str:
    """Hex SHA-256 of the inputs of :func:`~.model.symbolic_model` (see module docstring).
    Raises :class:`~wheeled_dyn.errors.ModelError` for unsupported joints."""
    h = hashlib.sha256()

    def put(*items: object) -> None:
        for item in items:
            h.update(str(item).encode())
            h.update(b"\x00")

    put("wheeled_dyn.symbolic", sp.__version__, _code_digest(), model.nv, simplify)
    for j in range(1, model.njoints):
        kind, axis = joint_kind(model, j)
        place = model.jointPlacements[j]
        put(model.names[j], model.joints[j].shortname(), kind, sp.srepr(axis),
            model.parents[j], model.joints[j].idx_v,
            _floats(place.rotation), _floats(place.translation))
    put(_floats(model.armature), _floats(model.gravity.linear))
    put(sp.srepr(gravity) if isinstance(gravity, sp.Basic) else repr(gravity))
    for j, pi in sorted(resolve_parameters(model, params).items()):
        put(j, *[float(x).hex() if x.is_Float else sp.srepr(x) for x in pi])
    put(repr(None if coordinate_names is None else list(coordinate_names)))
    if translations or armature is not None or real:  # keys of older entries stay valid
        for j, t in sorted(resolve_translations(model, translations).items()):
            put("translation", j, *[sp.srepr(x) for x in t])
        put("armature", *(() if armature is None else [sp.srepr(sp.sympify(a))
                                                        for a in armature]))
        put("real", real)
    return h.hexdigest()


def cached_symbolic_model(model: pin.Model, params: Mapping[int, Sequence] | None = None,
                          coordinate_names: Sequence[str] | None = None, gravity=None,
                          simplify: bool = True, root: str | Path | None = None,
                          refresh: bool = False, translations: Mapping | None = None,
                          armature: Sequence | None = None, real: bool = False
                          ) -> SymbolicModel:
    """:func:`~.model.symbolic_model`, read from the cache when an entry for the same inputs
    exists (unless ``refresh``), else derived and stored. An unreadable entry is a miss: it
    is derived again and replaced."""
    key = model_fingerprint(model, params, coordinate_names, gravity, simplify,
                            translations, armature, real)
    path = cache_dir(root) / f"{key}.pickle"
    if not refresh and (found := load(path, SymbolicModel)) is not None:
        return found
    sym = symbolic_model(model, params, coordinate_names, gravity, simplify, translations,
                         armature, real)
    store(path, sym)
    return sym


def clear_cache(root: str | Path | None = None) -> int:
    """Delete every cached symbolic model; returns how many files were removed."""
    d = cache_dir(root)
    removed = 0
    if d.is_dir():
        for path in d.glob("*.pickle"):
            path.unlink(missing_ok=True)
            removed += 1
    return removed


__all__ = ["CACHE_ENV", "cache_dir", "cached_symbolic_model", "clear_cache", "model_fingerprint"]
