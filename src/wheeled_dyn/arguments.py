r"""Checks of the arguments of the public API's functions (``wheeled_dyn.<name>``).

The functions the package exports are called from notebooks and scripts with whatever the
user has at hand. :func:`checked` wraps each one so that an argument of the wrong type or
value raises :class:`~wheeled_dyn.errors.ArgumentError` (picklable, naming the function, the
argument and what was expected) before any computing, instead of an ``AttributeError`` from
deep inside, or a Pinocchio ``ValueError`` about an Eigen matrix. The check of each argument
follows from its annotation (:data:`CHECKS`; an annotation it does not know is an error when
the function is wrapped, so a new export cannot slip through unchecked):

- a model, a Pinocchio model or data, a coordinate map, a random generator, a mapping, a
  function: an instance of that;
- a number (``float``): a finite real number; ``duration``, ``rate``, ``rtol``, ``atol``
  positive;
- a count (``int``): an integer, at least 1; a flag (``bool``): True or False;
- a vector (``np.ndarray``): finite real numbers, and for ``q``, ``v``, ``u`` as many as the
  model has coordinates (velocities, inputs);
- keyword arguments of a state (``**state: float``): finite real numbers, else
  :class:`~wheeled_dyn.errors.StateError` naming the entry.

The functions inside the package call each other unwrapped (no cost there).
"""

from __future__ import annotations

import functools
import inspect
import math
import numbers
import os
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from .errors import ArgumentError, StateError

#: Arguments (``float``) that must be positive.
POSITIVE = frozenset({"duration", "rate", "rtol", "atol"})


def _instance(kind: Callable[[], type], what: str) -> Callable[[str, str, Any, dict], None]:
    def check(fn: str, name: str, value: Any, bound: dict) -> None:
        if not isinstance(value, kind()):
            raise ArgumentError(fn, name, value, what)
    return check


def _finite(value: Any) -> bool:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    try:
        return math.isfinite(float(value))
    except OverflowError:                     # an int of 400 digits
        return False


def _number(fn: str, name: str, value: Any, bound: dict) -> None:
    if not _finite(value):
        raise ArgumentError(fn, name, value, "a finite real number")
    if name in POSITIVE and not float(value) > 0:
        raise ArgumentError(fn, name, value, "a positive number")


def _count(fn: str, name: str, value: Any, bound: dict) -> None:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or int(value) < 1:
        raise ArgumentError(fn, name, value, "an integer, at least 1")


def _size(name: str, bound: dict) -> int | None:
    r"""How many numbers vector ``name`` must hold, from the model among the arguments."""
    from .models.builder import WheeledModel
    for other in bound.values():
        if isinstance(other, WheeledModel):
            sizes = {"q": other.model.nq, "v": other.nv, "u": len(other.input_names)}
            return sizes.get(name)
        if type(other).__name__ == "Model" and hasattr(other, "nq"):   # a Pinocchio model
            return {"q": other.nq, "v": other.nv}.get(name)
    return None


def _vector(fn: str, name: str, value: Any, bound: dict) -> None:
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ArgumentError(fn, name, value, "a vector of real numbers") from None
    if array.ndim > 1 or not np.all(np.isfinite(array)):
        raise ArgumentError(fn, name, value, "a vector of finite real numbers")
    size = _size(name, bound)
    if size is not None and array.size != size:
        raise ArgumentError(fn, name, value, f"{size} numbers (one per model "
                            f"{'input' if name == 'u' else 'coordinate'})")


def _text(fn: str, name: str, value: Any, bound: dict) -> None:
    if not isinstance(value, str):
        raise ArgumentError(fn, name, value, "a name (str)")


def _flag(fn: str, name: str, value: Any, bound: dict) -> None:
    if not isinstance(value, bool):
        raise ArgumentError(fn, name, value, "True or False")


def _callable(fn: str, name: str, value: Any, bound: dict) -> None:
    if not callable(value):
        raise ArgumentError(fn, name, value, "a function")


def _model_or_name(fn: str, name: str, value: Any, bound: dict) -> None:
    from .models.builder import WheeledModel
    if not isinstance(value, (WheeledModel, str, os.PathLike)):
        raise ArgumentError(fn, name, value, "a model (wheeled_dyn.load_model) or a model "
                            "name or model file path")


def _wheeled_model() -> type:
    from .models.builder import WheeledModel
    return WheeledModel


def _pin(name: str) -> Callable[[], type]:
    def kind() -> type:
        import pinocchio as pin
        return getattr(pin, name)
    return kind


def _parameters() -> type:
    from .models.wip_parameters import WipParameters
    return WipParameters


def _coordinate_map() -> type:
    from .constraints import CoordinateMap
    return CoordinateMap


#: The check of an argument by its annotation (its first alternative other than None).
CHECKS: dict[str, Callable[[str, str, Any, dict], None]] = {
    "WheeledModel | str": _model_or_name,
    "WheeledModel": _instance(_wheeled_model, "a model (wheeled_dyn.load_model)"),
    "pin.Model": _instance(_pin("Model"), "a Pinocchio model"),
    "pin.Data": _instance(_pin("Data"), "a Pinocchio data object"),
    "CoordinateMap": _instance(_coordinate_map, "a CoordinateMap"),
    "WipParameters": _instance(_parameters, "a WipParameters record"),
    "str | Path": _model_or_name,
    "np.random.Generator": _instance(lambda: np.random.Generator,
                                     "a NumPy random generator (numpy.random.default_rng)"),
    "Mapping": _instance(lambda: Mapping, "a mapping (dict)"),
    "Callable": _callable,
    "Input": _callable,
    "np.ndarray": _vector,
    "float": _number,
    "int": _count,
    "str": _text,
    "bool": _flag,
    "Any": lambda fn, name, value, bound: None,
}


def _check_of(fn: Callable, parameter: inspect.Parameter) -> Callable | None:
    annotation = parameter.annotation
    if annotation is inspect.Parameter.empty:
        return None
    text = annotation if isinstance(annotation, str) else getattr(annotation, "__name__", "")
    for key, check in CHECKS.items():           # the longest keys first where they overlap
        if text == key or text.startswith(key + " |") or text.startswith(key + "["):
            return check
    raise TypeError(f"wheeled_dyn.arguments: no check for {fn.__name__}({parameter.name}: "
                    f"{text})")


def checked(fn: Callable) -> Callable:
    r"""``fn`` with its arguments checked first (see the module docstring); the same name,
    docstring and signature."""
    signature = inspect.signature(fn)
    checks = {p.name: (_check_of(fn, p), p.default is None or "None" in str(p.annotation))
              for p in signature.parameters.values()}
    name = fn.__name__

    @functools.wraps(fn)
    def run(*args: Any, **kwargs: Any) -> Any:
        try:
            bound = signature.bind(*args, **kwargs)
        except TypeError as exc:
            raise ArgumentError(name, "(arguments)", f"{len(args)} positional, "
                                f"{sorted(kwargs)} by keyword", str(exc)) from None
        values = bound.arguments
        for key, value in values.items():
            check, optional = checks[key]
            if check is None or (value is None and optional):
                continue
            if signature.parameters[key].kind is inspect.Parameter.VAR_KEYWORD:
                for entry, item in value.items():       # a state's entries, by name
                    if not _finite(item):
                        raise StateError(entry, item, "a finite real number")
            else:
                check(name, key, value, values)
        return fn(*args, **kwargs)

    return run


__all__ = ["CHECKS", "POSITIVE", "checked"]
