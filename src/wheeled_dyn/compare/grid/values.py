r"""A document symbol's value: its model-namespace expression (physical names, ``XX(link)``
calls) at a parameter set's values."""

from __future__ import annotations

from collections.abc import Mapping

import sympy as sp
from sympy.core.function import AppliedUndef

#: Each model-namespace expression's calls with their names (``XX(link)``), found once.
_CALLS: dict[sp.Expr, tuple[tuple[sp.Expr, str], ...]] = {}


def model_value(expr: sp.Expr, values: Mapping[str, float]) -> float:
    r"""A model-namespace expression (physical names, ``XX(link)`` calls) at ``values``."""
    named = _CALLS.get(expr)
    if named is None:
        named = _CALLS[expr] = tuple((call, f"{call.func.__name__}({call.args[0]})")
                                     for call in expr.atoms(AppliedUndef))
    calls = {}
    for call, key in named:
        if key not in values:
            from ...errors import UnknownNameError
            raise UnknownNameError("model parameter", key,
                                   [k for k in values if "(" in k])
        calls[call] = sp.Float(values[key])
    expr = expr.xreplace(calls)
    missing = [s.name for s in expr.free_symbols if s.name not in values]
    if missing:
        from ...errors import UnknownNameError
        raise UnknownNameError("model parameter", missing[0], values)
    return float(expr.xreplace({s: values[s.name] for s in expr.free_symbols}))


__all__ = ["model_value"]
