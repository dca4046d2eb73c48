r"""Names of a package imported on first use (PEP 562).

A package ``__init__`` that lists its public names with the module defining each::

    from .._lazy import attach
    __getattr__, __dir__, __all__ = attach(__name__, {"CoordinateMap": ".reduction", ...})

imports nothing until a name is used, so that importing one sub-module (say the package's
``commands``, which the command line reads for every call) does not load Pinocchio, SymPy,
yourdfpy or matplotlib.
"""

from __future__ import annotations

import importlib
import sys
import types
from collections.abc import Callable, Mapping
from typing import Any


class _LazyPackage(types.ModuleType):
    r"""A package whose exported names win over sub-modules of the same name: importing
    ``package.transform`` (a module) does not replace the exported function ``transform``."""

    _exports: dict[str, str] = {}

    def __setattr__(self, name: str, value: Any) -> None:
        if (isinstance(value, types.ModuleType) and name in self._exports
                and value.__name__ == f"{self.__name__}.{name}"):
            return
        super().__setattr__(name, value)


class _CallablePackage(_LazyPackage):
    r"""A package that can be called: ``wd.compare(model, A=...)`` runs the function named by
    ``_call`` (``"module:function"``, relative to the package's parent), while
    ``wheeled_dyn.compare`` stays the package of the comparison engine."""

    _call: str = ""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        where, name = self._call.split(":")
        parent = self.__name__.rpartition(".")[0]
        return getattr(importlib.import_module(where, parent), name)(*args, **kwargs)


def callable_package(package: str, target: str) -> None:
    r"""Make the (attached) ``package`` callable: calling it calls ``target``
    (``".api:compare"``, relative to the package's parent)."""
    module = sys.modules[package]
    module.__class__ = _CallablePackage
    object.__setattr__(module, "_call", target)


def attach(package: str, exports: Mapping[str, str]
           ) -> tuple[Callable[[str], Any], Callable[[], list[str]], list[str]]:
    r"""``(__getattr__, __dir__, __all__)`` for ``package``: ``exports`` maps each public
    name to the module (relative to ``package``) that defines it. A name is looked up once,
    then stored in the package namespace."""
    table = dict(exports)
    module = sys.modules[package]
    module.__class__ = _LazyPackage
    object.__setattr__(module, "_exports", table)

    def __getattr__(name: str) -> Any:
        where = table.get(name)
        if where is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(where, package), name)
        types.ModuleType.__setattr__(module, name, value)
        return value

    def __dir__() -> list[str]:
        return sorted(set(vars(module)) | set(table))

    return __getattr__, __dir__, sorted(table)
