r"""wheeled_dyn: check hand-derived equations of motion of wheeled bodies against Pinocchio.

The Python API in four lines::

    import wheeled_dyn as wd
    wip = wd.load_model("wip")                                  # seed 001's pendulum
    terms = wd.matrices(wip, "seed001", phi=0.2, dx=1.0, dpsi=0.5)
    terms.A, terms.C, terms.Q, terms.B, terms.h                 # in (dx, dpsi, dphi)

Names are imported on first use (PEP 562 module ``__getattr__``), so ``import wheeled_dyn``
and the command line's ``--help`` do not load Pinocchio, SymPy or matplotlib. The exported
functions check their arguments first (:mod:`.arguments`): a wrong one raises the project's
:class:`~wheeled_dyn.errors.ArgumentError`.
"""

from __future__ import annotations

import importlib
import inspect
import sys
from typing import Any

from ._lazy import _LazyPackage

__version__ = "0.1.0"

#: Public name → module that defines it (relative to this package).
_EXPORTS: dict[str, str] = {
    "CoordinateMap": ".constraints",
    "contact_jacobian": ".constraints",
    "multipliers": ".constraints",
    "builtin_coordinate_set": ".coordinates",
    "coordinate_set_names": ".coordinates",
    "Terms": ".dynamics",
    "christoffel_tensor": ".dynamics",
    "full_terms": ".dynamics",
    "h_coefficients": ".dynamics",
    "WheeledDynError": ".errors",
    "WheeledModel": ".models",
    "load_model": ".models.registry",
    "model_names": ".models.registry",
    "WipParameters": ".models.wip_parameters",
    "random_wip_parameters": ".models.wip_parameters",
    "standard_parameters": ".models.wip_parameters",
    "Trajectory": ".simulate",
    "simulate": ".simulate",
    "matrices": ".api",
    "compare": "",              # the package wheeled_dyn.compare, callable (api.compare)
}


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'wheeled_dyn' has no attribute {name!r}")
    value = importlib.import_module(f".{name}", __name__) if not module else \
        getattr(importlib.import_module(module, __name__), name)
    if inspect.isfunction(value):           # its arguments checked (.arguments)
        from .arguments import checked
        value = checked(value)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))


# A function named as a sub-package (``simulate``) stays the function when the sub-package is
# imported first (``import wheeled_dyn.simulate.reduced``): the import machinery's setattr
# of the sub-package on this module is ignored for those names.
sys.modules[__name__].__class__ = _LazyPackage
object.__setattr__(sys.modules[__name__], "_exports", {k: v for k, v in _EXPORTS.items() if v})

__all__ = sorted(_EXPORTS)
