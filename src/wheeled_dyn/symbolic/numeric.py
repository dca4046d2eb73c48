r"""Numeric (NumPy) functions of closed-form terms.

:func:`lambdify_terms` turns the matrices of a :class:`~.model.SymbolicModel` or a
:class:`~.transform.ReducedSymbolic` (anything with ``q``, ``velocities``, ``parameters`` and
``terms()``) into functions :math:`f(q, \dot q, \pi)` of three flat arrays: coordinates,
velocities (model velocities or quasi-velocities :math:`\nu`) and parameter values in the order
of ``parameters``. :func:`parameter_vector` builds :math:`\pi` from a Pinocchio model's own
inertias (Khalil's standard parameters, ``Inertia.toDynamicParameters()``) and a mapping for the
rest (``g``, a wheel radius ...).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np
import pinocchio as pin
import sympy as sp

from ..errors import StateError, UnknownNameError
from .parameters import numeric_parameters


#: Terms returned as 1-D arrays (the others keep their matrix shape, even n×1 or 1×1).
VECTOR_TERMS: frozenset[str] = frozenset({"Q", "h"})


class HasTerms(Protocol):
    """What :func:`lambdify_terms` needs of a symbolic result."""

    q: tuple[sp.Symbol, ...]
    parameters: tuple[sp.Symbol, ...]

    @property
    def velocities(self) -> tuple[sp.Symbol, ...]: ...

    def terms(self) -> dict[str, sp.Matrix]: ...


@dataclass(frozen=True)
class NumericTerms:
    """Compiled terms: ``self(name, q, v, p)`` or ``self.A(q, v, p)`` etc. return arrays
    (``Q`` and ``h`` as 1-D, every other term with its matrix shape)."""

    q: tuple[sp.Symbol, ...]
    velocities: tuple[sp.Symbol, ...]
    parameters: tuple[sp.Symbol, ...]
    functions: Mapping[str, Callable]
    shapes: Mapping[str, tuple[int, int]]

    def __call__(self, name: str, q: Sequence[float], v: Sequence[float] | None = None,
                 p: Sequence[float] | None = None) -> np.ndarray:
        if name not in self.functions:
            raise UnknownNameError("term", name, self.functions)
        qa = self._vector("q", q, len(self.q))
        va = self._vector("v", np.zeros(len(self.velocities)) if v is None else v,
                          len(self.velocities))
        pa = self._vector("p", () if p is None else p, len(self.parameters))
        out = np.asarray(self.functions[name](qa, va, pa), dtype=float)
        out = np.broadcast_to(out, self.shapes[name]).copy() if out.ndim == 0 else out
        rows, cols = self.shapes[name]
        return out.reshape(rows) if name in VECTOR_TERMS else out.reshape(rows, cols)

    def __getattr__(self, name: str) -> Callable[..., np.ndarray]:
        if name.startswith("_") or name not in self.__dict__.get("functions", {}):
            raise AttributeError(name)
        return lambda q, v=None, p=None: self(name, q, v, p)

    @staticmethod
    def _vector(what: str, x, n: int) -> np.ndarray:
        a = np.asarray(x, dtype=float).reshape(-1)
        if a.shape != (n,) or not np.all(np.isfinite(a)):
            raise StateError(what, x, f"{n} finite numbers")
        return a


def lambdify_terms(sym: HasTerms, names: Sequence[str] | None = None,
                   parameters: Sequence[sp.Symbol] | None = None, cse: bool = False
                   ) -> NumericTerms:
    r"""NumPy functions of ``sym.terms()`` (default all: ``A, C, Q, h`` and ``B`` if present),
    each of :math:`(q, v, \pi)` with :math:`\pi` ordered as ``parameters``
    (default ``sym.parameters``). Raises :class:`UnknownNameError` for a free symbol that is
    neither a coordinate, a velocity nor a parameter."""
    terms = sym.terms()
    names = tuple(terms) if names is None else tuple(names)
    pars = tuple(sym.parameters if parameters is None else parameters)
    known = set(sym.q) | set(sym.velocities) | set(pars)
    q = sp.symbols(f"_q0:{len(sym.q)}")
    v = sp.symbols(f"_v0:{len(sym.velocities)}")
    p = sp.symbols(f"_p0:{len(pars)}")
    rename = dict(zip(sym.q, q)) | dict(zip(sym.velocities, v)) | dict(zip(pars, p))
    functions, shapes = {}, {}
    for name in names:
        if name not in terms:
            raise UnknownNameError("term", name, terms)
        M = sp.Matrix(terms[name])
        unknown = M.free_symbols - known
        if unknown:
            raise UnknownNameError("symbol", str(sorted(unknown, key=str)[0]),
                                   [str(s) for s in known], where=f"term {name}")
        functions[name] = sp.lambdify([list(q), list(v), list(p)], M.xreplace(rename),
                                      modules="numpy", cse=cse)
        shapes[name] = M.shape
    return NumericTerms(q=tuple(sym.q), velocities=tuple(sym.velocities), parameters=pars,
                        functions=functions, shapes=shapes)


def parameter_vector(sym: HasTerms, model: pin.Model | None = None,
                     values: Mapping[sp.Symbol | str, float] | None = None) -> np.ndarray:
    """Values of ``sym.parameters``: the inertial symbols of ``sym.params`` and gravity's
    magnitude ``g`` from ``model`` (when given), then ``values`` (by symbol or name; these win). Raises
    :class:`UnknownNameError` for a parameter left without a value."""
    table: dict[str, float] = {}
    if model is not None:
        table["g"] = float(np.linalg.norm(model.gravity.linear))   # the magnitude's symbol
        nums = numeric_parameters(model)
        for j, pis in getattr(sym, "params", {}).items():
            for x, val in zip(pis, nums[j]):
                if isinstance(x, sp.Symbol):
                    table[x.name] = val
    for key, val in (values or {}).items():
        table[key.name if isinstance(key, sp.Symbol) else str(key)] = float(val)
    out = []
    for s in sym.parameters:
        if s.name not in table:
            raise UnknownNameError("parameter value", s.name, table)
        out.append(table[s.name])
    return np.asarray(out, dtype=float)
