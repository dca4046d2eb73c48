r"""Numbers on both sides: the truth and the document over K parameter sets × N states.

Truth, in the document's coordinates (:class:`~wheeled_dyn.constraints.CoordinateMap`):
:math:`A, C, Q, h` and the unique symmetric coefficient tensor of :math:`h`,
:math:`H_{i,jk} = \tfrac12(C(e_k)_{ij} + C(e_j)_{ik})`, and :math:`B` in the document's inputs:
if the model's inputs are :math:`\tau = f(u_{doc})`, :math:`B_{doc} = B\,\partial f/\partial u`.

Document: each element of its A, C, Q, B (matrix form) or of the read-off A, h, Q, B (equation
form) is compiled with ``sympy.lambdify`` in its coordinates, velocities and symbols; every
symbol takes the value its declaration gives in the model namespace, at each parameter set.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp
from sympy.core.function import AppliedUndef

from ..constraints.reduction import CoordinateMap
from ..coordinates import CoordinateSet, builtin_coordinate_set, parse_coordinate_set
from ..derivations.schema import Derivation
from ..errors import DerivationError
from .samples import ParameterSet

#: Range of the random values of a document's free symbols (present on both sides).
FREE_RANGE = (0.5, 2.0)


@dataclass
class Arrays:
    r"""Matrices over the samples (leading axis S = K·N); None where not given."""

    A: np.ndarray | None = None
    C: np.ndarray | None = None
    Q: np.ndarray | None = None
    B: np.ndarray | None = None
    h: np.ndarray | None = None
    H: np.ndarray | None = None
    G: np.ndarray | None = None


def model_value(expr: sp.Expr, values: Mapping[str, float]) -> float:
    r"""A model-namespace expression (physical names, ``XX(link)`` calls) at ``values``."""
    calls = {}
    for call in expr.atoms(AppliedUndef):
        key = f"{call.func.__name__}({call.args[0]})"
        if key not in values:
            from ..errors import UnknownNameError
            raise UnknownNameError("model parameter", key,
                                   [k for k in values if "(" in k])
        calls[call] = sp.Float(values[key])
    expr = expr.xreplace(calls)
    missing = [s.name for s in expr.free_symbols if s.name not in values]
    if missing:
        from ..errors import UnknownNameError
        raise UnknownNameError("model parameter", missing[0], values)
    return float(expr.xreplace({s: values[s.name] for s in expr.free_symbols}))


def derivation_coordinate_set(d: Derivation, ps: ParameterSet) -> CoordinateSet:
    r"""The document's coordinate set, built-in or inline; document symbols in inline
    expressions are replaced by their model values' names (R, L ...)."""
    wm = ps.model
    spec = d.coordinates
    if spec.use:
        cs = builtin_coordinate_set(wm, spec.use)
        if tuple(cs.velocities) != tuple(str(v) for v in d.velocities):
            raise DerivationError(d.path, "coordinates", f"built-in set {spec.use!r} has "
                                  f"velocities {cs.velocities}, the file {d.velocities}")
        return cs
    to_model = {s.symbol: s.value for s in d.symbols.values() if s.value is not None}
    raw = {"kind": spec.kind, "rolling": spec.rolling, "positions": list(spec.positions),
           "velocities": list(spec.velocities),
           "configuration": {k: str(sp.sympify(v).xreplace(to_model))
                             for k, v in spec.configuration.items()}}
    if spec.velocity_map:
        raw["velocity_map"] = {k: str(sp.sympify(v).xreplace(to_model))
                               for k, v in spec.velocity_map.items()}
    return parse_coordinate_set(raw, "inline", wm.coordinate_names, tuple(wm.geometry),
                                where=str(d.path))


def document_symbol_values(d: Derivation, ps: ParameterSet, rng: np.random.Generator) -> dict[sp.Symbol, float]:
    r"""Each non-input document symbol's number at this parameter set."""
    out = {}
    for spec in d.symbols.values():
        if spec.is_input:
            continue
        if spec.value is not None:
            out[spec.symbol] = model_value(spec.value, ps.values)
        else:
            out[spec.symbol] = rng.uniform(*FREE_RANGE)
    return out


def truth_arrays(cmaps: Sequence[CoordinateMap], q: np.ndarray, nu: np.ndarray,
                 input_maps: Sequence[np.ndarray] | None) -> Arrays:
    r"""Truth for each parameter set's bound map ``cmaps[k]`` at states ``q[k], nu[k]``
    (K × N × n); ``input_maps[k]`` is :math:`\partial\tau/\partial u_{doc}` (or None)."""
    parts: dict[str, list[np.ndarray]] = {k: [] for k in "ACQBhHG"}
    for k, cmap in enumerate(cmaps):
        t = cmap.terms_batch(q[k], nu[k])
        n = cmap.n
        gamma = np.stack([cmap.terms_batch(q[k], np.tile(np.eye(n)[j], (len(q[k]), 1))).C
                          for j in range(n)], axis=3)
        parts["A"].append(t.A)
        parts["C"].append(t.C)
        parts["Q"].append(t.Q)
        parts["h"].append(t.h)
        parts["H"].append(0.5 * (gamma + gamma.transpose(0, 1, 3, 2)))
        parts["B"].append(t.B if input_maps is None else t.B @ input_maps[k])
        if t.G is not None:
            parts["G"].append(t.G)
    return Arrays(**{k: (np.concatenate(v) if v else None) for k, v in parts.items()})


class DocumentFunctions:
    r"""The document's elements compiled once; evaluated at any samples."""

    def __init__(self, d: Derivation, A, C, Q, B, h, G) -> None:
        self.d = d
        self.params = tuple(s.symbol for s in d.symbols.values() if not s.is_input)
        self.args = [*d.positions, *d.velocities, *self.params]
        self.exprs = {"A": A, "C": C, "Q": Q, "B": B, "h": h, "G": G}
        if h is not None:
            H = [[[sp.diff(h[i], a, b) / 2 for b in d.velocities] for a in d.velocities]
                 for i in range(d.n)]
            self.exprs["H"] = sp.Array(H)
        else:
            self.exprs["H"] = None
        self._fns = {}
        for key, M in self.exprs.items():
            if M is None:
                continue
            arr = sp.Array(M) if not isinstance(M, sp.Array) else M
            self._fns[key] = (arr.shape, [sp.lambdify(self.args, e, "numpy")
                                          for e in sp.flatten(arr.tolist())])

    def element_function(self, key: str, index: tuple[int, ...]):
        r"""The compiled function of one element (for ``h``: of :math:`H_{i,jk}`)."""
        if key == "h":
            key = "H"
        shape, fns = self._fns[key]
        index = tuple(index) + (0,) * (len(shape) - len(index))
        flat = int(np.ravel_multi_index(index, shape))
        return fns[flat]

    def evaluate(self, q: np.ndarray, nu: np.ndarray, values: Mapping[sp.Symbol, np.ndarray],
                 substitute: Mapping[sp.Symbol, sp.Symbol] | None = None) -> Arrays:
        r"""Arrays over samples: positions ``q`` (S × n), velocities ``nu``, symbol values
        (arrays of length S)."""
        S = len(q)
        argv = [*q.T, *nu.T, *(values[p] for p in self.params)]
        out = Arrays()
        for key, (shape, fns) in self._fns.items():
            flat = np.empty((S, len(fns)))
            for j, fn in enumerate(fns):
                flat[:, j] = fn(*argv)
            setattr(out, key, flat.reshape((S, *shape)) if len(shape) > 1 or key in "QhB"
                    else flat.reshape((S, *shape)))
        if out.Q is not None and out.Q.ndim == 3:
            out.Q = out.Q[..., 0]
        if out.h is not None and out.h.ndim == 3:
            out.h = out.h[..., 0]
        return out

    def element(self, key: str, index: tuple[int, ...]) -> sp.Expr:
        M = self.exprs[key]
        if key in ("Q", "h") and len(index) == 1:
            return M[index[0], 0] if isinstance(M, sp.MatrixBase) else M[index[0]]
        return M[index]
